//! The SETTINGS sheet: any grid of text (lines of tab-separated cells)
//! parses to settings or diagnostics; the settings in force then check and
//! convert a fixed table to a conversion or a failure for the engineer (a
//! valve that cannot hold its load), never a panic or an internal error.
#![no_main]

use libfuzzer_sys::fuzz_target;
use steptable::convert::{Failure, check_bytes, generate};
use steptable::settings::Settings;
use steptable::diag::Diagnostics;
use steptable::read::{Format, Grid};

const TABLE: &[u8] = b"C1+2,C2+1\nC1-1,C2-0\nC1-0;T=1s,\nC3+1,\nC3-0,\n";

fuzz_target!(|bytes: &[u8]| {
    let Ok(text) = std::str::from_utf8(bytes) else {
        return;
    };
    let rows: Vec<Vec<&str>> = text.lines().map(|l| l.split('\t').collect()).collect();
    let grid = Grid::from_text_rows("fuzz.xlsx", Some("SETTINGS"), &rows);
    let mut diags = Diagnostics::new();
    let sheet = steptable::settings::parse(&grid, &mut diags);
    if diags.has_errors() {
        return;
    }
    let settings = Settings::new().with_sheet(&sheet);
    let Ok(checked) = check_bytes("fuzz.csv", Format::Csv, TABLE.to_vec(), &settings) else {
        return;
    };
    if let Err(Failure::Internal(why)) = generate("fuzz", checked) {
        panic!("valid settings gave an internal failure: {why}");
    }
});
