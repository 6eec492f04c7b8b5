//! Jumps on inputs (`J:7 if I:reject`, `J:end if I:abort`): read, checked
//! at the cell, simulated on every path, faulted, and written in every
//! language. The engines run them in `tests/tools` (the sorting station is a
//! sample, so it is in every differential matrix).

use predicates::str::contains;

use crate::helpers::{files_below, read_sheet, sample, steptable};

fn csv(dir: &std::path::Path, name: &str, rows: &str) -> std::path::PathBuf {
    let path = dir.join(name);
    std::fs::write(&path, rows).unwrap();
    path
}

/// The sorting station runs the plain cycle twice, then one cycle per
/// jump, and says which steps each jump cycle ran.
#[test]
fn every_path_of_the_sorting_station_is_simulated() {
    steptable()
        .args(["simulate"])
        .arg(sample("sorting_station.xlsx"))
        .assert()
        .success()
        .stdout(contains("passed: cycle time 8.32 s"))
        .stdout(contains(
            "cycle 3 (takes J:6 if I:reject after step 3): steps 1, 2, 3, 6, 7, 8, cycle of 6.38 s",
        ))
        .stdout(contains(
            "cycle 4 (takes J:end if I:no_label after step 6): steps 1, 2, 3, 4, 5, 6, cycle of 5.86 s",
        ));
}

/// A jump input that comes too late for its step is a failed proof: the
/// path was never run.
#[test]
fn a_jump_whose_input_comes_after_its_step_fails_the_proof() {
    steptable()
        .args(["simulate", "--input-delay", "reject=3s"])
        .arg(sample("sorting_station.xlsx"))
        .assert()
        .code(1)
        .stdout(contains(
            "cycle 3 was to take J:6 if I:reject after step 3, but step 4 came first",
        ));
}

/// Bad jumps are errors at their cell, all at once, and nothing is written.
#[test]
fn bad_jumps_are_refused_at_their_cell() {
    let dir = tempfile::tempdir().unwrap();
    let table = csv(
        dir.path(),
        "bad.csv",
        "C1+1; J:12 if I:a\nC2+1; J:3 if I:b\nC2-0; J:6 if I:c\nC1-0; J:end if I:d\nC3+1; J:end if I:e\nC3-0; J:1 if I:f\nC1+1\nC1-0; J:2 if I:g\nJ:7 when I:h\n",
    );
    let expected = [
        "bad.csv:1:1: error[E028]: \"J:12 if I:a\" in STEP 1: the table has 9 steps",
        "bad.csv:2:1: error[E028]: \"J:3 if I:b\" in STEP 2: STEP 3 comes after STEP 2 anyway",
        "bad.csv:3:1: error[E029]: \"J:6 if I:c\" in STEP 3: step 6 starts from C1 at 0 (it stands at 1), C3 at 1 (it stands at 0); a jump goes only where every actuator already stands",
        "bad.csv:5:1: error[E029]: \"J:end if I:e\" in STEP 5: the end of the cycle needs every actuator home: C3 at 0 (it stands at 1)",
        "bad.csv:6:1: error[E028]: \"J:1 if I:f\" in STEP 6: STEP 1 starts a cycle on START",
        "bad.csv:8:1: error[E029]: \"J:2 if I:g\" in STEP 8: step 2 starts from C1 at 1 (it stands at 0)",
        "bad.csv:9:1: error[E017]: \"J:7 when I:h\": the jump says no input (if I:…)",
    ];
    let output = steptable()
        .args(["convert"])
        .arg(&table)
        .arg("-o")
        .arg(dir.path().join("out"))
        .assert()
        .code(1)
        .get_output()
        .stderr
        .clone();
    let stderr = String::from_utf8(output).unwrap();
    for line in expected {
        assert!(stderr.contains(line), "{line}\nnot in\n{stderr}");
    }
    // Step 4's jump to the end is right: every actuator is home by then.
    assert!(!stderr.contains(":4:1:"), "{stderr}");
    assert!(files_below(&dir.path().join("out")).is_empty());
    // An actuator that has not moved yet stands home, and the target may
    // need it elsewhere.
    let unseen = csv(
        dir.path(),
        "unseen.csv",
        "C1+1\nC1-0; J:4 if I:x\nC2+1\nC1+1\nC1-0\nC2-0\n",
    );
    steptable()
        .args(["check"])
        .arg(&unseen)
        .assert()
        .code(1)
        .stderr(contains(
            "unseen.csv:2:1: error[E029]: \"J:4 if I:x\" in STEP 2: step 4 starts from C2 at 1 (it stands at 0)",
        ));
    let last = csv(dir.path(), "last.csv", "C1+1\nC1-0; J:1 if I:a\n");
    steptable()
        .args(["check"])
        .arg(&last)
        .assert()
        .code(1)
        .stderr(contains("the cycle ends after STEP 2, the last step"));
}

/// A jump back (a retry) is a loop the sequence may take again and again;
/// each pass is simulated like any step, each jump in its own cycle.
#[test]
fn a_jump_back_retries_steps() {
    let dir = tempfile::tempdir().unwrap();
    let table = csv(
        dir.path(),
        "retry.csv",
        "C1+1\nC2+1\nC2-0; J:2 if I:not_gripped; J:2 if I:retry\nC1-0\n",
    );
    steptable()
        .args(["simulate"])
        .arg(&table)
        .assert()
        .success()
        .stdout(contains(
            "cycle 3 (takes J:2 if I:not_gripped after step 3): steps 1, 2, 3, 2, 3, 4",
        ))
        // Two jumps of one step to one target: each is told apart by its
        // input (the second is not mistaken for the first).
        .stdout(contains(
            "cycle 4 (takes J:2 if I:retry after step 3): steps 1, 2, 3, 2, 3, 4",
        ));
}

/// A jump input stuck on sends every cycle down the jump's path: the
/// fault table calls it a hazard; stuck off, the path is lost.
#[test]
fn a_stuck_jump_input_is_judged() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .args(["convert", "--formats", "faults"])
        .arg(sample("sorting_station.xlsx"))
        .arg("-o")
        .arg(dir.path())
        .assert()
        .success();
    let faults = std::fs::read_to_string(
        dir.path()
            .join("sorting_station/sorting_station.faults.csv"),
    )
    .unwrap();
    let row = |fault: &str| {
        faults
            .lines()
            .find(|l| l.starts_with(fault))
            .unwrap_or_else(|| panic!("{fault}: no row in\n{faults}"))
            .to_string()
    };
    let stuck_on = row("reject short circuit");
    assert!(stuck_on.contains("hazard"), "{stuck_on}");
    assert!(
        stuck_on.contains("the sequence took J:6 if I:reject after step 3 although the machine did not give I:reject=1"),
        "{stuck_on}"
    );
    // The bad part goes down the good chute: the path the jump is for is
    // lost, a hazard.
    let stuck_off = row("reject open circuit");
    assert!(stuck_off.contains("hazard"), "{stuck_off}");
    assert!(
        stuck_off.contains("was to take J:6 if I:reject"),
        "{stuck_off}"
    );
}

/// The PLC PROGRAM sheet lists each jump before its step, with where the
/// sequence goes on.
#[test]
fn the_program_sheet_shows_each_jump_before_its_step() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .args(["convert", "--formats", "xlsx"])
        .arg(sample("sorting_station.xlsx"))
        .arg("-o")
        .arg(dir.path())
        .assert()
        .success();
    let rows = read_sheet(
        &dir.path()
            .join("sorting_station/sorting_station.steptable.xlsx"),
        "PLC PROGRAM",
    );
    let at = |label: &str| {
        rows.iter()
            .position(|r| r.first().is_some_and(|c| c == label))
            .unwrap_or_else(|| panic!("{label}: {rows:?}"))
    };
    // The jump of step 3 sits in step 3 (SFC numbering) and enters step 6.
    let jump = at("STEP 3 (J:6 if I:reject)");
    assert_eq!(jump + 1, at("STEP 3"));
    assert_eq!(
        rows[jump][1],
        "IF x20 AND reject THEN SET y1- RESET y1+ GOTO STEP 6"
    );
    let end = at("STEP 6 (J:end if I:no_label)");
    assert_eq!(rows[end][1], "IF x10 AND no_label THEN GOTO STEP 0");
}

/// Synthesis handles plain sequences of moves: a table with a jump is
/// refused with the step that holds it, not synthesised without the jump.
#[test]
fn synthesis_refuses_a_table_with_a_jump() {
    let dir = tempfile::tempdir().unwrap();
    let table = csv(
        dir.path(),
        "jump.csv",
        "C1+1\nC2+1\nC2-0; J:6 if I:reject\nC3+1\nC3-0\nC1-0\n",
    );
    steptable().args(["check"]).arg(&table).assert().success();
    steptable()
        .args(["synth"])
        .arg(&table)
        .assert()
        .code(1)
        .stderr(contains(
            "error[E034]: STEP 3 (C2-0; J:6 if I:reject) is not one cylinder move",
        ));
}

/// A jump that leaves out the step switching a machine output off (or on)
/// is said at its cell, W010 (red team rt8, finding 8: the machine rested
/// with its vacuum on after the no-part path, without a word). Where both
/// paths arrive with the output alike, nothing is said.
#[test]
fn a_jump_leaving_an_output_otherwise_is_said_at_its_cell() {
    let cases: [(&str, &str, Option<&str>); 5] = [
        (
            "a jump to the end leaving the vacuum on",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,Y:vacuum+; T=200ms\nSTEP 3,C1-0; J:end if I:no_part\nSTEP 4,C1+1\nSTEP 5,C1-0; Y:vacuum-\n",
            Some(
                "t.csv:4:2: warning[W010]: \"J:end if I:no_part\" in STEP 3 leaves Y:vacuum on at the end of the cycle, where the sequence arrives without the jump with it off (switched in STEP 5)",
            ),
        ),
        (
            "a jump forward leaving a lamp off",
            ",BRANCH 1\nSTEP 1,C1+1; J:4 if I:skip\nSTEP 2,C1-0; Y:lamp+\nSTEP 3,C1+1\nSTEP 4,C1-0; Y:lamp-\n",
            Some(
                "t.csv:2:2: warning[W010]: \"J:4 if I:skip\" in STEP 1 leaves Y:lamp off in STEP 4, where the sequence arrives without the jump with it on (switched in STEP 2)",
            ),
        ),
        (
            "a jump to the end leaving out the last step's switch-off",
            ",BRANCH 1\nSTEP 1,C1+1; Y:lamp+\nSTEP 2,C1-0; J:end if I:done\nSTEP 3,C1+1\nSTEP 4,C1-0\nSTEP 5,Y:lamp-\n",
            Some("t.csv:3:2: warning[W010]: \"J:end if I:done\" in STEP 2 leaves Y:lamp on"),
        ),
        (
            "a jump whose paths switch alike",
            ",BRANCH 1\nSTEP 1,C1+1; Y:lamp+\nSTEP 2,C1-0; Y:lamp-; J:end if I:done\nSTEP 3,C2+1\nSTEP 4,C2-0\n",
            None,
        ),
        (
            "a jump back that runs the switching steps again",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,Y:lamp+\nSTEP 3,C1-0; Y:lamp-\nSTEP 4,C1+1; J:2 if I:again\nSTEP 5,C1-0\n",
            None,
        ),
    ];
    for (what, table, said) in cases {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.csv");
        std::fs::write(&path, table).unwrap();
        let out = crate::helpers::steptable()
            .arg("check")
            .arg(&path)
            .output()
            .unwrap();
        assert!(out.status.success(), "{what}: {out:?}");
        let stderr =
            String::from_utf8_lossy(&out.stderr).replace(&format!("{}/", dir.path().display()), "");
        match said {
            Some(line) => assert!(stderr.contains(line), "{what}: {stderr}"),
            None => assert!(!stderr.contains("W010"), "{what}: {stderr}"),
        }
    }
}
