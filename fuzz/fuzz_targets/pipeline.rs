//! The whole pipeline from bytes to every output format: a CSV step table
//! that passes the checks must convert (program, simulation, fault table,
//! every file rendered) without a panic. The first byte picks the target,
//! the safety checks and the operating modes.
#![no_main]

use libfuzzer_sys::fuzz_target;
use steptable::address::Target;
use steptable::program::{Modes, Safety};
use steptable::convert::{check_bytes, generate};
use steptable::settings::Settings;
use steptable::read::Format;

fuzz_target!(|bytes: &[u8]| {
    let Some((&options, csv)) = bytes.split_first() else {
        return;
    };
    let mut settings = Settings::new();
    settings.target = match options % 3 {
        0 => Target::Festo,
        1 => Target::Iec,
        _ => Target::Siemens,
    };
    if options & 0x10 != 0 {
        settings.program.safety = Safety::all();
    }
    if options & 0x20 != 0 {
        settings.program.modes = Modes::parse("all").unwrap_or_default();
    }
    if let Ok(checked) = check_bytes("fuzz.csv", Format::Csv, csv.to_vec(), &settings) {
        // A table that passes the checks must convert: a program that fails
        // its own simulation, or a template that fails, is a bug.
        if let Err(failure) = generate("fuzz", checked) {
            panic!("a valid table did not convert: {failure:?}");
        }
    }
});
