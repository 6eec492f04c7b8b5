//! What steptable found is said in the engineer's notation: where a fault's
//! explanation, the simulation's verdict or `convert`'s findings name an
//! actuator the SETTINGS actuator table names, they say `C1 (clamp)` (and
//! the signal's designation, `1B2` under ISO), not the bare `C1`; in every
//! output that shows them.

use std::path::{Path, PathBuf};

use crate::helpers::{read_sheet, steptable, write_xlsx_sheets};

/// A clamp and a punch with a middle stop it dwells at.
fn station(dir: &Path) -> PathBuf {
    let path = dir.join("named.xlsx");
    let table: &[&[&str]] = &[
        &["", "BRANCH 1"],
        &["STEP 1", "C1+1"],
        &["STEP 2", "C2+1"],
        &["STEP 3", "T=1s"],
        &["STEP 4", "C2+2"],
        &["STEP 5", "C2-0"],
        &["STEP 6", "C1-0"],
    ];
    let settings: &[&[&str]] = &[
        &["actuator", "extend", "retract", "valve", "name"],
        &["C1", "1s", "1s", "", "clamp"],
        &["C2 (punch)"],
    ];
    write_xlsx_sheets(
        &path,
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", table),
            ("SETTINGS", settings),
        ],
    );
    path
}

/// x11 short: step 2 starts while the clamp still moves.
const EARLY: &str = "step 2 started before step 1 finished (C1 (clamp) had not reached x11)";

#[test]
fn the_fault_table_names_the_actuators_in_every_output() {
    let dir = tempfile::tempdir().unwrap();
    let input = station(dir.path());
    let convert = steptable()
        .args([
            "convert",
            "--modes",
            "all",
            "--formats",
            "faults,xlsx,report",
            "-o",
        ])
        .arg(dir.path())
        .arg(&input)
        .assert()
        .success();
    let stdout = String::from_utf8_lossy(&convert.get_output().stdout).to_string();
    let out = dir.path().join("named");
    let csv = std::fs::read_to_string(out.join("named.faults.csv")).unwrap();
    assert!(csv.contains(EARLY), "CSV: {csv}");
    let sheet = read_sheet(&out.join("named.steptable.xlsx"), "FAULTS");
    assert!(
        sheet.iter().any(|r| r.iter().any(|c| c == EARLY)),
        "FAULTS: {sheet:?}"
    );
    let html = std::fs::read_to_string(out.join("named.report.html")).unwrap();
    assert!(html.contains(EARLY), "report");
    // convert's findings name the actuators RESET homes.
    assert!(
        stdout.contains("  RESET homes C2 (punch), then C1 (clamp)\n"),
        "{stdout}"
    );
    let faults = steptable()
        .args(["faults", "-o"])
        .arg(dir.path().join("again"))
        .arg(&input)
        .assert()
        .success();
    let console = String::from_utf8_lossy(&faults.get_output().stdout).to_string();
    assert!(console.contains(EARLY), "{console}");
}

#[test]
fn the_simulation_says_its_verdict_in_the_names() {
    let dir = tempfile::tempdir().unwrap();
    let input = station(dir.path());
    // Without middle stops the punch runs through its middle sensor.
    let run = steptable()
        .args(["simulate", "--no-middle-stop"])
        .arg(&input)
        .assert()
        .code(1);
    let stdout = String::from_utf8_lossy(&run.get_output().stdout).to_string();
    let verdict = stdout.lines().next().unwrap_or_default();
    assert!(
        verdict.contains("FAILED: C2 (punch) ran through x21 to x20 in step 2"),
        "{stdout}"
    );
    assert!(
        stdout
            .lines()
            .any(|l| l.starts_with("  at ") && l.contains(" s: C2 (punch) ran through x21")),
        "{stdout}"
    );
    assert!(!stdout.contains("C2 ran"), "{stdout}");
    // ISO: the sensors by their designations, the actuator by 2A1 (punch).
    let run = steptable()
        .args(["simulate", "--no-middle-stop", "--designations", "iso"])
        .arg(&input)
        .assert()
        .code(1);
    let stdout = String::from_utf8_lossy(&run.get_output().stdout).to_string();
    assert!(
        stdout.contains("2A1 (punch) ran through 2B3 to 2B1"),
        "{stdout}"
    );
}

#[test]
fn the_programs_own_rung_comments_name_signals_by_their_designation() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .args([
            "convert",
            "--designations",
            "iso",
            "--formats",
            "st,awl,fst,l5x",
            "-o",
        ])
        .arg(dir.path())
        .arg(crate::helpers::sample("paper_example.xlsx"))
        .assert()
        .success();
    let out = dir.path().join("paper_example");
    for file in [
        "paper_example.st",
        "paper_example.awl",
        "paper_example.fst.txt",
        "paper_example.L5X",
    ] {
        let text = std::fs::read_to_string(out.join(file)).unwrap();
        assert!(text.contains("middle stop: 2A1 stops at 2B3"), "{file}");
        assert!(!text.contains("C2 stops at x21"), "{file}");
    }
}
