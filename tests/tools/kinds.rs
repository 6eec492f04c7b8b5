//! One actuator kind in the engines: a fixture converted with its
//! `--valve` list for every target and set of options, the written
//! programs run in matiec (ST), OpenPLC's upload, awlsim (AWL, both
//! mnemonic sets) and the FST interpreter against the trace steptable
//! simulated, scan by scan.
//! `vacuum.rs` and `swivel.rs` prove their kinds through it.

use std::path::Path;

use crate::differential::{openplc_accepts, run_all};
use crate::engines::{self, Case, fst, matiec};
use crate::shared;

/// Plain, with every safety check, and with every mode and safety check.
const OPTIONS: [&[&str]; 3] = [
    &[],
    &["--safety", "all"],
    &["--modes", "all", "--safety", "all"],
];

/// The cases of `fixture` (under `tests/fixtures/`) with `--valve
/// valves`, for every target and set of options, converted into `dir`
/// with `extra` arguments.
pub fn cases(fixture: &str, valves: &str, dir: &Path, extra: &[&str]) -> Vec<Case> {
    let table = crate::helpers::root().join("tests/fixtures").join(fixture);
    let mut cases = Vec::new();
    for target in ["festo", "iec", "siemens"] {
        for (o, options) in OPTIONS.iter().enumerate() {
            let mut args = vec!["--target", target, "--valve", valves];
            args.extend_from_slice(options);
            args.extend_from_slice(extra);
            let out = dir.join(format!("{target}-{o}"));
            cases.push(engines::prepare(&table, &args, &out));
        }
    }
    cases
}

/// The `.st` of every case run in matiec as simulated and accepted by
/// OpenPLC's upload; `what` names the kind in the printed note.
pub fn in_matiec_and_openplc(what: &str, fixture: &str, valves: &str) {
    let shared = shared();
    let dir = tempfile::tempdir().unwrap();
    let cases = cases(fixture, valves, dir.path(), &["--formats", "st"]);
    run_all(&cases, |c| {
        c.check_stepped(
            "matiec .st",
            matiec::run_stepped(&shared, &c.file(".st"), &c.trace, &c.allocation),
        )?;
        openplc_accepts(&shared, &c.file(".st"))
    });
    eprintln!(
        "{what}: {} .st files run in matiec and accepted by OpenPLC, traces equal",
        cases.len()
    );
}

/// The `.awl` of every case run in awlsim (both mnemonic sets) as simulated.
pub fn in_awlsim(what: &str, fixture: &str, valves: &str) {
    crate::differential::awl_in_awlsim(&format!("{what}: awlsim"), |dir, extra| {
        cases(fixture, valves, dir, extra)
    });
}

/// The `.fst.txt` of every case run in the FST interpreter as simulated
/// (the festo target's, and the others' FST beside their own language).
pub fn in_fst(what: &str, fixture: &str, valves: &str) {
    let dir = tempfile::tempdir().unwrap();
    let cases = cases(fixture, valves, dir.path(), &["--formats", "fst"]);
    run_all(&cases, |c| {
        let text = crate::engines::read_ansi(&c.file(".fst.txt"))?;
        c.check_stepped(
            "FST interpreter",
            fst::run_stepped(&text, &c.trace, &c.festo),
        )
    });
    eprintln!(
        "{what}: {} .fst.txt files run in the FST interpreter, traces equal",
        cases.len()
    );
}
