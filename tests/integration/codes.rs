//! Codes that no other test reaches through the binary.

use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;

use crate::helpers::{files_below, steptable};

/// 256 dwells is one more than FST's timers: E026 at the table, nothing
/// written; 255 convert.
#[test]
fn more_than_255_dwells_is_e026() {
    let dir = tempfile::tempdir().unwrap();
    let table = |dwells: usize| {
        let mut rows = String::new();
        for _ in 0..dwells.div_ceil(2) {
            rows.push_str("C1+1\nT=1s\nC1-0\nT=1s\n");
        }
        rows
    };
    let over = dir.path().join("over.csv");
    std::fs::write(&over, table(256)).unwrap();
    steptable()
        .arg("convert")
        .arg(&over)
        .arg("-o")
        .arg(dir.path().join("out"))
        .assert()
        .code(1)
        .stderr(contains("error[E026]"));
    assert!(files_below(&dir.path().join("out")).is_empty());
    let at = dir.path().join("at.csv");
    std::fs::write(&at, table(254)).unwrap();
    steptable().args(["check"]).arg(&at).assert().success();
}

/// STEP labels out of order are read in sheet order, and said (W002).
#[test]
fn a_step_label_out_of_place_is_w002() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("labels.xlsx");
    crate::helpers::write_xlsx(
        &path,
        "Sheet1",
        &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 3", "C1-0"]],
    );
    steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .success()
        .stderr(contains("warning[W002]").and(contains("A3")));
}

/// A sequence synth does not handle is E034 with the reason, exit 1.
#[test]
fn a_sequence_synth_cannot_handle_is_e034() {
    steptable()
        .args(["synth", "--sequence", "A1 A1"])
        .assert()
        .code(1)
        .stderr(contains("error[E034]").and(contains("changes nothing")));
    steptable()
        .arg("synth")
        .arg(crate::helpers::sample("paper_example.xlsx"))
        .assert()
        .code(1)
        .stderr(contains("error[E034]"));
}
