//! The native programs of the two largest PLC families and OpenPLC v4 in
//! the differential layer: the TIA Portal SCL source (`NAME.scl`, with the
//! tag table `NAME.tags.xlsx` binding its tags to addresses) in the SCL
//! interpreter, the Studio 5000 program (`NAME.L5X`, with `NAME.rockwell.csv`)
//! re-parsed by the `l5x` crate and run in the RLL interpreter, each on the
//! inputs steptable's simulation recorded, with outputs and step equal to
//! the simulation's at every scan; over the matrix of the differential
//! layer (every sample × target × option set, the named station under each
//! designation scheme). OpenPLC v4's build (STruC++, `check-upload-v4`)
//! must accept every `.st` of the same matrix and the synthesised programs.
//! TIA Portal and Studio 5000 themselves were not run: both are Windows
//! software with licences no test can hold.

use std::path::Path;

use crate::differential::{matrix, press_case, replay_accepts, run_all, swap_first_after};
use crate::engines::{Case, rll, scl};
use crate::helpers::steptable;
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "differential_native::scl_runs_in_the_interpreter_as_simulated",
        &[],
        scl_runs_in_the_interpreter_as_simulated,
    ),
    Check::new(
        "differential_native::l5x_reparses_and_runs_in_the_rll_interpreter_as_simulated",
        &[],
        l5x_reparses_and_runs_in_the_rll_interpreter_as_simulated,
    ),
    Check::new(
        "differential_native::a_wrong_scl_file_is_caught",
        &[],
        a_wrong_scl_file_is_caught,
    ),
    Check::new(
        "differential_native::a_wrong_l5x_file_is_caught",
        &[],
        a_wrong_l5x_file_is_caught,
    ),
    Check::new(
        "differential_native::the_scl_interpreter_refuses_unknown_constructs",
        &[],
        scl::unknown_constructs_are_refused,
    ),
    Check::new(
        "differential_native::the_rll_interpreter_refuses_unknown_constructs",
        &[],
        rll::unknown_constructs_are_refused,
    ),
    Check::new(
        "differential_native::openplc_v4_accepts_every_st",
        &[Tool::OpenPlc4],
        openplc_v4_accepts_every_st,
    ),
];

/// Runs a case's `NAME.scl` in the SCL interpreter.
pub fn run_scl(case: &Case) -> Result<crate::engines::Stepped, String> {
    scl::run_stepped(
        &case.file(".scl"),
        &case.file(".tags.xlsx"),
        &case.trace,
        &case.allocation,
    )
}

/// Re-parses a case's `NAME.L5X` with the `l5x` crate (the file and each
/// rung), then runs it in the RLL interpreter.
pub fn run_l5x(case: &Case) -> Result<crate::engines::Stepped, String> {
    let xml = std::fs::read_to_string(case.file(".L5X")).map_err(|e| e.to_string())?;
    reparse_with_l5x_crate(&xml)?;
    let csv = std::fs::read_to_string(case.file(".rockwell.csv")).map_err(|e| e.to_string())?;
    rll::run_stepped(&xml, &csv, &case.trace, &case.allocation)
}

/// The `l5x` crate must read the whole file as an L5X project, and every
/// rung's text as ladder.
fn reparse_with_l5x_crate(xml: &str) -> Result<(), String> {
    l5x::from_str::<l5x::Project>(xml).map_err(|e| format!("l5x crate: {e}"))?;
    let file = rll::read(xml)?;
    for (n, (_, text)) in file.rungs.iter().enumerate() {
        let rung = l5x::rll::parse_rung(text);
        if !rung.is_parsed() {
            return Err(format!("l5x crate: rung {n} does not parse: {text}"));
        }
    }
    if file.target_type != "Program" || file.software_revision.is_empty() {
        return Err(format!(
            "not a program export: {} {}",
            file.target_type, file.software_revision
        ));
    }
    Ok(())
}

fn scl_runs_in_the_interpreter_as_simulated() {
    let dir = tempfile::tempdir().unwrap();
    let cases = matrix(dir.path(), &["--formats", "scl,tia"]);
    run_all(&cases, |c| c.check_stepped("SCL interpreter", run_scl(c)));
    eprintln!("scl: {} .scl files run, traces equal", cases.len());
}

fn l5x_reparses_and_runs_in_the_rll_interpreter_as_simulated() {
    let dir = tempfile::tempdir().unwrap();
    let cases = matrix(dir.path(), &["--formats", "l5x,rockwell"]);
    run_all(&cases, |c| c.check_stepped("RLL interpreter", run_l5x(c)));
    eprintln!(
        "l5x: {} .L5X files re-parsed by the l5x crate and run, traces equal",
        cases.len()
    );
}

/// Writes `text` as the case's file `suffix` (the one the runner reads).
fn replace_file(case: &Case, suffix: &str, text: &str) {
    std::fs::write(case.file(suffix), text).unwrap();
}

/// A swapped coil, and the first dwell's preset (500 ms) in the wrong
/// unit: each must be caught with its scan.
fn a_wrong_scl_file_is_caught() {
    let dir = tempfile::tempdir().unwrap();
    let case = press_case(dir.path());
    let right = std::fs::read_to_string(case.file(".scl")).unwrap();
    case.check_stepped("SCL", run_scl(&case)).unwrap();
    let swapped = swap_first_after(&right, "3: //", "\"y2m\" := TRUE;", "\"y2p\" := TRUE;");
    replace_file(&case, ".scl", &swapped);
    let err = case.check_stepped("SCL", run_scl(&case)).unwrap_err();
    assert!(err.contains("scan ") && err.contains("y2"), "{err}");
    // Seconds where the program means milliseconds: the dwell never ends.
    let seconds = right.replace("#dwell1_pt := T#500ms;", "#dwell1_pt := T#500s;");
    assert_ne!(seconds, right);
    replace_file(&case, ".scl", &seconds);
    let err = case.check_stepped("SCL", run_scl(&case)).unwrap_err();
    assert!(err.contains("scan "), "{err}");
}

fn a_wrong_l5x_file_is_caught() {
    let dir = tempfile::tempdir().unwrap();
    let case = press_case(dir.path());
    let right = std::fs::read_to_string(case.file(".L5X")).unwrap();
    case.check_stepped("RLL", run_l5x(&case)).unwrap();
    let swapped = swap_first_after(&right, "STEP 3:", "OTL(y2m)", "OTL(y2p)");
    replace_file(&case, ".L5X", &swapped);
    let err = case.check_stepped("RLL", run_l5x(&case)).unwrap_err();
    assert!(err.contains("scan ") && err.contains("y2"), "{err}");
    // Hundredths of a second (FST's timer unit) where a Logix TIMER counts
    // milliseconds: the dwell ends ten times too early.
    let hundredths = right.replace("MOV(500,dwell1.PRE)", "MOV(50,dwell1.PRE)");
    assert_ne!(hundredths, right);
    replace_file(&case, ".L5X", &hundredths);
    let err = case.check_stepped("RLL", run_l5x(&case)).unwrap_err();
    assert!(err.contains("scan "), "{err}");
}

/// OpenPLC v4's build (`check-upload-v4`) replayed on one file.
fn openplc_v4_accepts(st: &Path) -> Result<(), String> {
    replay_accepts(&tool(Tool::OpenPlc4), "openplc4: accepted", st)
}

fn openplc_v4_accepts_every_st() {
    let dir = tempfile::tempdir().unwrap();
    let cases = matrix(dir.path(), &["--formats", "st"]);
    run_all(&cases, |c| openplc_v4_accepts(&c.file(".st")));
    let mut synthesised = Vec::new();
    for (k, sequence) in ["A1 A0 B1 B0", "A1 A0 A1 A0 A1 A0 B1 B0 C1 C0"]
        .iter()
        .enumerate()
    {
        let out = dir.path().join(format!("synth{k}"));
        steptable()
            .args(["synth", "--sequence", sequence, "-o"])
            .arg(&out)
            .assert()
            .success();
        synthesised.push(crate::helpers::synthesised(&out, sequence, ".equations.st"));
    }
    let failures: Vec<String> = synthesised
        .iter()
        .filter_map(|st| openplc_v4_accepts(st).err())
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
    eprintln!(
        "openplc v4: {} .st files and {} synthesised programs accepted",
        cases.len(),
        synthesised.len()
    );
}
