//! The workbook readers: arbitrary bytes as `.xlsx`, `.ods` or `.xls` (the
//! first byte picks which) give a table or diagnostics, never a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use steptable::convert::check_bytes;
use steptable::settings::Settings;
use steptable::read::Format;

fuzz_target!(|bytes: &[u8]| {
    let Some((&selector, rest)) = bytes.split_first() else {
        return;
    };
    let (name, format) = match selector % 3 {
        0 => ("fuzz.xlsx", Format::Xlsx),
        1 => ("fuzz.ods", Format::Ods),
        _ => ("fuzz.xls", Format::Xls),
    };
    let _ = check_bytes(name, format, rest.to_vec(), &Settings::new());
});
