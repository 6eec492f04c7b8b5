//! The ADDRESSES sheet: any grid of text (lines of tab-separated cells) as
//! pins for a fixed table that has sensors, machine inputs and outputs, a
//! dwell and (with the first byte) every mode and safety check, so that the
//! allocation list holds every kind of signal a row can pin (alarm_wd,
//! the mode buttons). On any target and board the pins are used or named:
//! the conversion succeeds or fails for the engineer, never with a panic or
//! an internal error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use steptable::address::Target;
use steptable::convert::{Failure, check_bytes, generate};
use steptable::diag::Diagnostics;
use steptable::program::{Modes, Safety};
use steptable::read::{Format, Grid};
use steptable::settings::Settings;

const TABLE: &[u8] =
    b"C1+2;I:part,C2+1\nC1-1;Y:vac+,C2-0\nC1-0;T=1s;Y:vac-,\nC3+1;J:end if I:reject,\nC3-0,\n";

fuzz_target!(|bytes: &[u8]| {
    let Some((&options, rest)) = bytes.split_first() else {
        return;
    };
    let Ok(text) = std::str::from_utf8(rest) else {
        return;
    };
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split('\t').collect()).collect();
    let grid = Grid::from_text_rows("fuzz.xlsx", Some("ADDRESSES"), &rows);
    let mut diags = Diagnostics::new();
    let pins = steptable::settings::pins::parse(&grid, &mut diags);
    if diags.has_errors() {
        return;
    }
    let mut settings = Settings::new();
    settings.pins = pins;
    settings.target = match options % 4 {
        0 => Target::Festo,
        2 => Target::Siemens,
        _ => Target::Iec,
    };
    // Target 3 is an OpenPLC board: the pins must fit its wired terminals.
    if options % 4 == 3 {
        let boards = &steptable::address::BOARDS;
        settings.board = Some(boards[(options as usize >> 6) % boards.len()]);
    }
    if options & 0x10 != 0 {
        settings.program.safety = Safety::all();
    }
    if options & 0x20 != 0 {
        settings.program.modes = Modes::parse("all").unwrap_or_default();
    }
    let Ok(checked) = check_bytes("fuzz.csv", Format::Csv, TABLE.to_vec(), &settings) else {
        return;
    };
    if let Err(Failure::Internal(why)) = generate("fuzz", checked) {
        panic!("pins that passed the checks gave an internal failure: {why}");
    }
});
