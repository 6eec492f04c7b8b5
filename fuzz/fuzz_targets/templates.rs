//! A user's template: any text in place of one default template (the first
//! byte picks which) renders the paper's table or fails with a template
//! error; it never panics and always ends (minijinja's fuel).
#![no_main]

use libfuzzer_sys::fuzz_target;
use steptable::convert::{Failure, check_bytes, generate};
use steptable::settings::Settings;
use steptable::emit::OutputKind;
use steptable::emit::templates::{DEFAULTS, Templates};
use steptable::read::Format;

const TABLE: &[u8] = b"C1+1,C2+1\nC1-0,C2-0\nC3+1;T=1s,\nC3-0,\n";

fuzz_target!(|bytes: &[u8]| {
    let Some((&selector, source)) = bytes.split_first() else {
        return;
    };
    let Ok(source) = std::str::from_utf8(source) else {
        return;
    };
    let name = DEFAULTS[selector as usize % DEFAULTS.len()].0;
    let Ok(templates) = Templates::from_sources([(name, source)]) else {
        return;
    };
    let mut settings = Settings::new();
    settings.templates = templates;
    // The outputs laid out by templates (the workbook, fault table and
    // diagram are not; leaving them out keeps the fuzzer fast).
    settings.formats.retain(|k| {
        !matches!(
            k,
            OutputKind::Workbook | OutputKind::Faults | OutputKind::Diagram
        )
    });
    let checked = check_bytes("fuzz.csv", Format::Csv, TABLE.to_vec(), &settings)
        .expect("the fixed table is valid");
    match generate("fuzz", checked) {
        Ok(_) | Err(Failure::Template(_)) => {}
        Err(other) => panic!("a template gave another failure: {other:?}"),
    }
});
