//! The CSV reader (encoding detection, delimiter sniffing, limits) and the
//! table checks behind it: arbitrary bytes give a table or diagnostics.
#![no_main]

use libfuzzer_sys::fuzz_target;
use steptable::convert::check_bytes;
use steptable::settings::Settings;
use steptable::read::Format;

fuzz_target!(|bytes: &[u8]| {
    let _ = check_bytes("fuzz.csv", Format::Csv, bytes.to_vec(), &Settings::new());
});
