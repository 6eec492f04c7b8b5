//! `convert` says what it found under each input: the verdict and cycle
//! time, the fault table's hazards with the first one's cause, the order
//! RESET homes in, and that a program without modes has no STOP.

use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;

use crate::helpers::{sample, steptable};

#[test]
fn convert_prints_the_verdict_the_hazards_and_the_missing_stop() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .args(["convert", "-o"])
        .arg(dir.path())
        .arg(sample("paper_example.xlsx"))
        .assert()
        .success()
        .stdout(contains("  simulation passed: cycle time "))
        // The paper's x22 open circuit drives C2 through its middle stop.
        .stdout(contains("  fault table: ").and(contains(" hazard(s) among ")))
        .stdout(contains("; first: "))
        .stdout(contains(
            "  note: the program has no STOP or EMERGENCY STOP button (--modes all",
        ))
        .stdout(contains("RESET homes").not());
}

#[test]
fn with_modes_it_says_the_homing_order_and_no_note() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .args(["convert", "--modes", "all", "-o"])
        .arg(dir.path())
        .arg(sample("paper_example.xlsx"))
        .assert()
        .success()
        .stdout(contains("  RESET homes C2, C3 & C4, then C1\n"))
        .stdout(contains("note: the program has no").not());
}

#[test]
fn without_the_fault_table_there_is_no_hazard_line() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .args(["convert", "--formats", "st", "--modes", "estop", "-o"])
        .arg(dir.path())
        .arg(sample("paper_example.xlsx"))
        .assert()
        .success()
        .stdout(contains("  simulation passed: cycle time "))
        .stdout(contains("fault table").not())
        .stdout(contains("  note: the program has no STOP button"));
}
