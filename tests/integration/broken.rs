//! Broken inputs: exit code 1, the cell named in the message, nothing written.

use std::path::{Path, PathBuf};

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{files_below, steptable, write_xlsx};

const SHEET: &str = "SEQUENTIAL CONTROL DESCRIPTION";

/// A Fig. 7 layout: headers on row 3, labels in column A, moves from B4.
fn fig7(dir: &Path, name: &str, steps: &[&[&str]]) -> PathBuf {
    let mut rows: Vec<Vec<&str>> = vec![
        vec![SHEET],
        vec![],
        vec!["", "BRANCH 1", "BRANCH 2", "BRANCH 3"],
    ];
    let labels: Vec<String> = (1..=steps.len()).map(|i| format!("STEP {i}")).collect();
    for (i, step) in steps.iter().enumerate() {
        let mut row = vec![labels[i].as_str()];
        row.extend_from_slice(step);
        rows.push(row);
    }
    let refs: Vec<&[&str]> = rows.iter().map(|r| r.as_slice()).collect();
    let path = dir.join(name);
    write_xlsx(&path, SHEET, &refs);
    path
}

/// Runs convert on `input` and checks the failure: exit 1, every expected
/// text on stderr, and no file below the output folder.
fn assert_rejected(input: &Path, expected: &[&str]) {
    let out = input.parent().unwrap().join("out");
    let mut assert = steptable()
        .arg("convert")
        .arg(input)
        .arg("-o")
        .arg(&out)
        .assert()
        .code(1);
    for text in expected {
        assert = assert.stderr(contains(*text));
    }
    assert.stderr(contains("nothing written"));
    assert!(
        files_below(&out).is_empty(),
        "outputs were written: {:?}",
        files_below(&out)
    );
}

#[test]
fn a_cell_that_is_not_a_move() {
    let dir = tempfile::tempdir().unwrap();
    let input = fig7(dir.path(), "line.xlsx", &[&["C1+1"], &["C2+x"], &["C1-0"]]);
    assert_rejected(
        &input,
        &[
            "line.xlsx: SEQUENTIAL CONTROL DESCRIPTION!B5: error[E010]: \"C2+x\" is not a move (expected C<number>+<position>, e.g. C2+1)",
        ],
    );
}

#[test]
fn an_actuator_that_does_not_return_home() {
    let dir = tempfile::tempdir().unwrap();
    let input = fig7(dir.path(), "home.xlsx", &[&["C1+1", "C2+1"], &["C1-0"]]);
    assert_rejected(
        &input,
        &[
            "SEQUENTIAL CONTROL DESCRIPTION!C4",
            "E022",
            "C2 ends the cycle at position 1",
        ],
    );
}

#[test]
fn a_move_in_the_wrong_direction() {
    let dir = tempfile::tempdir().unwrap();
    let input = fig7(dir.path(), "dir.xlsx", &[&["C1+1"], &["C1+1"], &["C1-0"]]);
    assert_rejected(&input, &["SEQUENTIAL CONTROL DESCRIPTION!B5", "E020"]);
}

#[test]
fn an_actuator_twice_in_one_step() {
    let dir = tempfile::tempdir().unwrap();
    let input = fig7(dir.path(), "twice.xlsx", &[&["C1+1", "C1-0"], &["C1-0"]]);
    assert_rejected(
        &input,
        &[
            "SEQUENTIAL CONTROL DESCRIPTION!C4",
            "E021",
            "already moves in STEP 1 (cell B4)",
        ],
    );
}

#[test]
fn every_error_is_reported_at_once() {
    let dir = tempfile::tempdir().unwrap();
    let input = fig7(
        dir.path(),
        "many.xlsx",
        &[
            &["C1+1", "bogus"],
            &["C1+1", "C2+1"],
            &["", ""],
            &["C1-0", "C0-1"],
        ],
    );
    assert_rejected(
        &input,
        &[
            "!C4: error[E010]",
            "!B5: error[E020]",
            "!B6: error[E023]",
            "!C7: error[E011]",
            "E022",
        ],
    );
}

#[test]
fn an_empty_sheet() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("empty.xlsx");
    write_xlsx(&input, "Sheet1", &[]);
    assert_rejected(&input, &["empty.xlsx", "E003", "no step table found"]);
}

#[test]
fn a_table_without_moves() {
    let dir = tempfile::tempdir().unwrap();
    let input = fig7(dir.path(), "nomoves.xlsx", &[&[""], &[""]]);
    assert_rejected(&input, &["E003", "no moves"]);
}

#[test]
fn a_corrupt_workbook() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("corrupt.xlsx");
    let mut bytes = b"PK\x03\x04".to_vec();
    bytes.extend((0..2000u32).map(|i| (i * 7919 % 251) as u8));
    std::fs::write(&input, bytes).unwrap();
    assert_rejected(
        &input,
        &["corrupt.xlsx", "E002", "not a readable .xlsx workbook"],
    );
}

#[test]
fn a_truncated_real_workbook() {
    let dir = tempfile::tempdir().unwrap();
    let whole = std::fs::read(crate::helpers::sample("paper_example.xlsx")).unwrap();
    let input = dir.path().join("truncated.xlsx");
    std::fs::write(&input, &whole[..whole.len() / 2]).unwrap();
    assert_rejected(&input, &["truncated.xlsx", "E002"]);
}

#[test]
fn a_binary_file_named_csv() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("binary.csv");
    std::fs::write(&input, [0u8, 159, 146, 150, 0, 1, 2, 255]).unwrap();
    assert_rejected(&input, &["binary.csv", "E002", "binary data"]);
}

#[test]
fn csv_errors_name_line_and_column() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("line.csv");
    std::fs::write(
        &input,
        ";BRANCH 1;BRANCH 2\r\nSTEP 1;C1+1;\r\nSTEP 2;C1-0;C2-1\r\n",
    )
    .unwrap();
    assert_rejected(&input, &["line.csv:3:3: error[E020]: \"C2-1\""]);
}

#[test]
fn a_missing_file_and_an_unknown_sheet() {
    let dir = tempfile::tempdir().unwrap();
    assert_rejected(&dir.path().join("nope.xlsx"), &["nope.xlsx", "E001"]);
    let input = fig7(dir.path(), "ok.xlsx", &[&["C1+1"], &["C1-0"]]);
    steptable()
        .arg("check")
        .arg(&input)
        .args(["--sheet", "PLAN"])
        .assert()
        .code(1)
        .stderr(contains("E004").and(contains("no sheet named \"PLAN\"")));
}

#[test]
fn check_prints_a_summary_per_file_and_writes_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let good = fig7(
        dir.path(),
        "good.xlsx",
        &[&["C1+1", "C2+2"], &["C2-1"], &["C1-0", "C2-0"]],
    );
    let bad = fig7(dir.path(), "bad.xlsx", &[&["C1+1"]]);
    steptable()
        .current_dir(dir.path())
        .arg("check")
        .arg("good.xlsx")
        .arg("bad.xlsx")
        .assert()
        .code(1)
        .stdout(contains(
            "good.xlsx: ok: 3 steps, 3 branch(es), 2 actuators, 6 inputs, 4 outputs",
        ))
        .stdout(contains("bad.xlsx: 1 error(s)"));
    let _ = (good, bad);
    assert_eq!(files_below(dir.path()).len(), 2);
}

#[test]
fn an_input_is_never_overwritten() {
    let dir = tempfile::tempdir().unwrap();
    // The second input sits where the first one's workbook would go:
    // DIR/NAME/NAME.steptable.xlsx.
    std::fs::create_dir(dir.path().join("cell")).unwrap();
    let first = fig7(dir.path(), "cell.xlsx", &[&["C1+1"], &["C1-0"]]);
    let input = fig7(
        &dir.path().join("cell"),
        "cell.steptable.xlsx",
        &[&["C1+1"], &["C1-0"]],
    );
    let before = std::fs::read(&input).unwrap();
    steptable()
        .arg("convert")
        .arg(&first)
        .arg(&input)
        .arg("-o")
        .arg(dir.path())
        .assert()
        .code(1)
        .stderr(contains("cell.steptable.xlsx: error[E040]: (converting "))
        .stderr(contains("is an input of this run"));
    assert_eq!(std::fs::read(&input).unwrap(), before);
    assert_eq!(files_below(&dir.path().join("cell")), [input]);
}
