//! The whole pipeline from bytes to every output format: a CSV step table
//! that passes the checks must convert (program, simulation, fault table,
//! every file rendered) without a panic.
#![no_main]

use libfuzzer_sys::fuzz_target;
use steptable::convert::{Settings, check_bytes, generate};
use steptable::read::Format;

fuzz_target!(|bytes: &[u8]| {
    let settings = Settings::new();
    if let Ok(checked) = check_bytes("fuzz.csv", Format::Csv, bytes.to_vec(), &settings) {
        // A valid table always converts; a failed simulation is a result
        // (exit 2 on the command line), not a crash.
        let _ = generate("fuzz", checked);
    }
});
