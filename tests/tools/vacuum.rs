//! The vacuum gripper (`--valve C2=vacuum`) in the engines: a pick and
//! place whose gripper C2 holds the part on its vacuum switch `x21` and
//! reads "released" as that switch off. The written programs must run in
//! matiec (ST), OpenPLC's upload and awlsim (AWL, both mnemonic sets) as
//! steptable simulated them, scan by scan, for every target and with every
//! safety check and mode.

use crate::differential::{openplc_accepts, run_all};
use crate::engines::{self, Case, matiec};
use crate::{Check, Tool, shared};

pub const CHECKS: &[Check] = &[
    Check::new(
        "vacuum::a_vacuum_gripper_runs_in_matiec_and_openplc_as_simulated",
        &[Tool::Shared],
        a_vacuum_gripper_runs_in_matiec_and_openplc_as_simulated,
    ),
    Check::new(
        "vacuum::a_vacuum_gripper_runs_in_awlsim_as_simulated",
        &[Tool::Awlsim],
        a_vacuum_gripper_runs_in_awlsim_as_simulated,
    ),
];

const OPTIONS: [&[&str]; 3] = [
    &[],
    &["--safety", "all"],
    &["--modes", "all", "--safety", "all"],
];

/// The pick and place, gripper C2 on vacuum, for every target and set of
/// options, converted into `dir` with `extra` arguments.
fn cases(dir: &std::path::Path, extra: &[&str]) -> Vec<Case> {
    let table = crate::helpers::root().join("tests/fixtures/pick_and_place.csv");
    let mut cases = Vec::new();
    for target in ["festo", "iec", "siemens"] {
        for (o, options) in OPTIONS.iter().enumerate() {
            let mut args = vec!["--target", target, "--valve", "C2=vacuum"];
            args.extend_from_slice(options);
            args.extend_from_slice(extra);
            let out = dir.join(format!("{target}-{o}"));
            cases.push(engines::prepare(&table, &args, &out));
        }
    }
    cases
}

fn a_vacuum_gripper_runs_in_matiec_and_openplc_as_simulated() {
    let shared = shared();
    let dir = tempfile::tempdir().unwrap();
    let cases = cases(dir.path(), &["--formats", "st"]);
    run_all(&cases, |c| {
        c.check_stepped(
            "matiec .st",
            matiec::run_stepped(&shared, &c.file(".st"), &c.trace, &c.allocation),
        )?;
        openplc_accepts(&shared, &c.file(".st"))
    });
    eprintln!(
        "vacuum: {} .st files run in matiec and accepted by OpenPLC, traces equal",
        cases.len()
    );
}

fn a_vacuum_gripper_runs_in_awlsim_as_simulated() {
    crate::differential::awl_in_awlsim("vacuum: awlsim", cases);
}
