//! The simulate and faults commands as a user runs them.

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{sample, steptable};

#[test]
fn simulate_passes_the_paper_and_shows_the_hang_without_middle_stops() {
    steptable()
        .arg("simulate")
        .arg(sample("paper_example.xlsx"))
        .assert()
        .success()
        .stdout(contains("passed: cycle time 7.47 s"))
        .stdout(contains("second START: identical cycle of 7.47 s"));
    steptable()
        .arg("simulate")
        .arg(sample("paper_example.xlsx"))
        .arg("--no-middle-stop")
        .assert()
        .code(1)
        .stdout(contains(
            "FAILED: step 5 never fires: waiting for x22; C2 ran through x22 to x23 in step 4",
        ));
}

#[test]
fn stroke_times_change_the_step_timing() {
    steptable()
        .arg("simulate")
        .arg(sample("drilling_station.xlsx"))
        .args(["--stroke", "C1=2s/0.5s"])
        .assert()
        .success()
        .stdout(contains("1         0.00 s    1.96 s  C1+1"));
    steptable()
        .arg("simulate")
        .arg(sample("drilling_station.xlsx"))
        .args(["--stroke", "C1=fast"])
        .assert()
        .code(1)
        .stderr(contains("\"fast\" is not a stroke time"));
}

#[test]
fn faults_prints_the_table_and_writes_the_csv() {
    let dir = tempfile::tempdir().unwrap();
    let assert = steptable()
        .arg("faults")
        .arg(sample("paper_example.xlsx"))
        .arg("-o")
        .arg(dir.path())
        .assert()
        .success();
    // The columns' padding squeezed to one space.
    let stdout = crate::helpers::squeezed_stdout(&assert);
    for line in [
        "24 fault case(s) at 17 moments of the cycle (80 runs): 1 no effect, 9 safe stall, 14 hazard",
        // Shorted, C1's home sensor ends the cycle as C1 sets off home:
        // the program is ready for START with the machine not home.
        "x10 short circuit (stuck at 1) hazard at every moment 8 the cycle ended before step 8 finished (C1 had not reached x10)",
        "fault outcome appears detected step explanation",
        "x22 open circuit (stuck at 0) hazard from power-up (15 of 17 moments) 4 step 5 never fires: waiting for x22; C2 ran through x22 to x23 in step 4; collision risk: C1 at x11, C2 between x22 and x23, C3 between x30 and x31, C4 at x40 (during step 4)",
        "x11 short circuit (stuck at 1) hazard at every moment 2 step 2 started before step 1 finished (C1 had not reached x11)",
        // Open at power-up, x21 stalls step 4; failing while step 4 moves
        // C2 on from x21 to x22, it lets C2 run back through x21 in step 5.
        "x21 open circuit (stuck at 0) hazard while step 4 moves (3 of 17 moments) 5 step 6 never fires: waiting for x21; C2 ran through x21 to x20 in step 5; collision risk",
    ] {
        assert!(stdout.contains(line), "{line}\n{stdout}");
    }
    let csv =
        std::fs::read_to_string(dir.path().join("paper_example/paper_example.faults.csv")).unwrap();
    assert!(csv.starts_with("fault,signals,stuck_at,outcome,appears,detected,step,explanation\n"));
    assert_eq!(csv.lines().count(), 25);
    steptable()
        .arg("faults")
        .arg(sample("drilling_station.xlsx"))
        .arg("--pairs")
        .arg("-o")
        .arg(dir.path())
        .assert()
        .success()
        // 7 inputs: 14 single faults and 14·12/2 = 84 pairs of different inputs.
        .stdout(contains("98 fault case(s)").and(contains(" + ")));
}

/// Up to K faults at once: a set holding a fault that never reads other
/// than the healthy input (a normally closed STOP stuck at 1) is the
/// smaller set, already in the table, and is left out; `--pairs` is
/// `--faults 2`.
#[test]
fn several_faults_at_once_leave_out_the_sets_a_smaller_one_stands_for() {
    let dir = tempfile::tempdir().unwrap();
    let run = |args: &[&str]| {
        let assert = steptable()
            .arg("faults")
            .arg(sample("carwash.xlsx"))
            .args(args)
            .arg("-o")
            .arg(dir.path())
            .assert()
            .success();
        String::from_utf8_lossy(&assert.get_output().stdout).to_string()
    };
    let pairs = run(&["--faults", "2"]);
    // 13 inputs (its `modes | all` brings single step and manual too:
    // STEP_MODE, STEP_PB, MAN_MODE and the drive's jog1+, jog1-): 26
    // singles and 4·78 = 312 pairs, of which 180 hold one of the nine
    // faults that never read other than healthy (CONT, RESET_PB,
    // STEP_MODE, STEP_PB, MAN_MODE, jog1+, jog1- stuck at 0, STOP or ESTOP
    // stuck at 1): 312 - 132 pairs of the other 17 faults.
    assert!(
        pairs.starts_with(&format!(
            "{}: 158 fault case(s) at 8 moments of the cycle (",
            sample("carwash.xlsx").display()
        )),
        "{pairs}"
    );
    assert!(
        pairs.contains(
            "180 set(s) left out, each holding a fault that never reads other than without it"
        ),
        "{pairs}"
    );
    assert!(
        !pairs.contains("STOP short circuit (stuck at 1) +"),
        "{pairs}"
    );
    assert!(
        pairs.contains("x11 open circuit (stuck at 0) + RESET_PB short circuit (stuck at 1)"),
        "{pairs}"
    );
    assert_eq!(run(&["--pairs"]), pairs);
}

/// `--pairs` grows with the square of the inputs: past 100,000 cases the
/// request is refused before any simulation runs, with the count and the way
/// out (E033, exit 1, nothing written), in either message format.
#[test]
fn fault_pairs_beyond_the_budget_are_refused_with_the_count() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("c120.csv");
    let moves: Vec<String> = (1..=120)
        .map(|i| format!("C{i}+1"))
        .chain((1..=120).map(|i| format!("C{i}-0")))
        .collect();
    std::fs::write(&csv, moves.join("\n")).unwrap();
    let out = dir.path().join("out");
    steptable()
        .arg("faults")
        .arg(&csv)
        .args(["--pairs", "-o"])
        .arg(&out)
        .assert()
        .code(1)
        .stderr(contains(
            "error[E033]: --pairs would simulate 116162 fault cases (241 inputs",
        ))
        .stderr(contains(
            "analyse fewer faults at once (single faults without --pairs)",
        ));
    assert!(!out.exists());
    // Three at once on 12 inputs is within it; on 241, far beyond.
    steptable()
        .arg("faults")
        .arg(&csv)
        .args(["--faults", "3", "-o"])
        .arg(&out)
        .assert()
        .code(1)
        .stderr(contains("error[E033]: --faults 3 would simulate 18547842 fault cases (241 inputs, each stuck at 1 and at 0, up to 3 at once)"));
    assert!(!out.exists());
    let json = steptable()
        .arg("faults")
        .arg(&csv)
        .args(["--pairs", "--message-format", "json", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(json.status.code(), Some(1));
    let first: serde_json::Value =
        serde_json::from_slice(json.stdout.split(|&b| b == b'\n').next().unwrap()).unwrap();
    assert_eq!(first["code"], "E033");
    assert_eq!(first["severity"], "error");
}

/// With stdout closed (a pipe whose reader is gone), `simulate --diagram`
/// and `faults` still write the files they were asked for.
#[cfg(unix)]
#[test]
fn files_are_written_even_when_stdout_is_closed() {
    use std::process::Stdio;
    let dir = tempfile::tempdir().unwrap();
    let bin = assert_cmd::cargo::cargo_bin("steptable");
    for (command, flag, expect) in [
        (
            "simulate",
            "--diagram",
            "paper_example/paper_example.time.svg",
        ),
        ("faults", "-o", "paper_example/paper_example.faults.csv"),
    ] {
        let out = dir.path().join(command);
        let mut child = std::process::Command::new(&bin)
            .arg(command)
            .arg(crate::helpers::sample("paper_example.xlsx"))
            .arg(flag)
            .arg(&out)
            .stdout(Stdio::piped())
            .stderr(Stdio::null())
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        let status = child.wait().unwrap();
        assert!(status.success(), "{command}: {status}");
        assert!(out.join(expect).exists(), "{command}: {expect} missing");
    }
}
