//! Every function, function block and type of the IEC libraries matiec and
//! OpenPLC compile against is refused as a machine signal name (E015): a
//! signal named like one would not compile.

use steptable::names::reserved_name;

use crate::{Check, Tool, shared};

pub const CHECKS: &[Check] = &[Check::new(
    "names::every_iec_library_name_is_reserved",
    &[Tool::Shared],
    every_iec_library_name_is_reserved,
)];

fn every_iec_library_name_is_reserved() {
    let shared = shared();
    let mut names = std::collections::BTreeSet::new();
    for lib in ["tools/matiec/lib", "tools/openplc/lib"] {
        let files = std::fs::read_dir(shared.join(lib)).unwrap().flatten();
        for entry in files.filter(|e| e.path().extension().is_some_and(|x| x == "txt")) {
            let text = std::fs::read_to_string(entry.path()).unwrap_or_default();
            for line in text.lines() {
                let mut words = line.split_whitespace();
                if let (Some("FUNCTION" | "FUNCTION_BLOCK"), Some(name)) =
                    (words.next(), words.next())
                {
                    names.insert(name.trim_end_matches(':').to_ascii_lowercase());
                }
            }
        }
    }
    assert!(names.len() > 1000, "{}", names.len());
    let accepted: Vec<&String> = names
        .iter()
        .filter(|n| reserved_name(n).is_none())
        .collect();
    assert!(accepted.is_empty(), "accepted: {accepted:?}");
}
