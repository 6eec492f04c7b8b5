//! A cycle abandoned (red team 4, findings 6, 8, 9 and 10), through the
//! binary where the engineer reads it: manual mode, or RESET after an
//! EMERGENCY STOP, sends the sequence back to step 0 without finishing the
//! step under way. That is one printed line at its scan, not a problem of
//! the next cycle; `@step0` waits for a cycle's end or for homing done,
//! never for an abandonment; and the messages about a gripper or a drive
//! use the actuator model's words, not a piston's.

use crate::helpers::{run_in, sample, steptable};
use crate::scenario::simulate_file;

fn paper(work: &std::path::Path, args: &[&str]) -> (Option<i32>, String) {
    let mut all = vec!["--modes", "all"];
    all.extend(args);
    simulate_file(
        work,
        &sample("paper_example.xlsx").display().to_string(),
        &all,
    )
}

/// The printed lines containing `text`.
fn lines_with<'a>(table: &'a str, text: &str) -> Vec<&'a str> {
    table.lines().filter(|l| l.contains(text)).collect()
}

/// The time (ms) of the first line containing `text`.
fn time_of(table: &str, text: &str) -> u64 {
    let line = lines_with(table, text)
        .first()
        .copied()
        .unwrap_or_else(|| panic!("no line with {text:?}: {table}"));
    let seconds: f64 = line.split_whitespace().next().unwrap().parse().unwrap();
    (seconds * 1000.0).round() as u64
}

/// Finding 6: after manual mode abandoned step 4 (RESET homing the machine
/// afterwards), and after an EMERGENCY STOP reset, the next cycle starts
/// fresh: no "step 1 started before step 4 finished", a whole cycle runs.
/// The same after jogging home instead of RESET.
#[test]
fn the_cycle_after_an_abandoned_one_is_no_problem() {
    let work = tempfile::tempdir().unwrap();
    let runs: [&[&str]; 3] = [
        &[
            "--press",
            "START@0.5s",
            "--hold",
            "MAN_MODE@step4",
            "--release",
            "MAN_MODE@+2s",
            "--press",
            "RESET@+1s",
            "--press",
            "START@+5s",
        ],
        &[
            "--press",
            "START@0.5s",
            "--press",
            "ESTOP@step4",
            "--press",
            "RESET@+2s",
            "--press",
            "START@+5s",
        ],
        &[
            "--press",
            "START@0.5s",
            "--hold",
            "MAN_MODE@step2",
            "--hold",
            "jog2-@+0.5s",
            "--release",
            "jog2-@+2s",
            "--hold",
            "jog1-@+0.1s",
            "--release",
            "jog1-@+2s",
            "--release",
            "MAN_MODE@+0.5s",
            "--press",
            "START@+1s",
        ],
    ];
    for args in runs {
        let (code, table) = paper(work.path(), args);
        assert_eq!(code, Some(0), "{args:?}: {table}");
        assert!(!table.contains("problem:"), "{args:?}: {table}");
        assert_eq!(
            lines_with(&table, "step 1   ").len(),
            2,
            "{args:?}: {table}"
        );
        assert_eq!(
            lines_with(&table, "end of cycle").len(),
            1,
            "{args:?}: {table}"
        );
    }
}

/// Finding 9: a momentary MAN_MODE (a press of 0.1 s) abandons step 1 and
/// says so at that scan, as a step line; RESET after an EMERGENCY STOP
/// says which step it abandoned, beside "homing starts".
#[test]
fn an_abandoned_cycle_is_one_line_at_its_scan() {
    let work = tempfile::tempdir().unwrap();
    let (code, table) = paper(work.path(), &["--press", "MANUAL@1s"]);
    assert_eq!(code, Some(0), "{table}");
    let said = lines_with(&table, "cycle abandoned");
    assert_eq!(
        said,
        ["    1.00 s  step 0   cycle abandoned in step 1: manual mode (MAN_MODE)"],
        "{table}"
    );
    let (_, table) = paper(
        work.path(),
        &[
            "--press",
            "START@0.5s",
            "--press",
            "ESTOP@step2",
            "--press",
            "RESET@+1s",
        ],
    );
    let said = lines_with(&table, "cycle abandoned");
    assert_eq!(
        said,
        ["    2.50 s  step 0   cycle abandoned in step 2: RESET_PB homes the machine"],
        "{table}"
    );
    assert_eq!(time_of(&table, "homing starts"), 2_500, "{table}");
    // A cycle that ends is no abandoned one.
    let (_, table) = paper(work.path(), &[]);
    assert!(!table.contains("abandoned"), "{table}");
}

/// Finding 8: `START@step0` after RESET waits for homing to be done (the
/// sequence back in step 0, ready) and then runs a whole cycle; RESET
/// itself sending the sequence to step 0 is no `step0`. In manual mode no
/// cycle ends and nothing homes: a `RESET@step0` never happens, and the
/// run says so.
#[test]
fn step0_is_a_cycles_end_or_homing_done_never_an_abandonment() {
    let work = tempfile::tempdir().unwrap();
    let (code, table) = paper(
        work.path(),
        &[
            "--press",
            "START@0.5s",
            "--press",
            "ESTOP@step2",
            "--press",
            "RESET@+1s",
            "--press",
            "START@step0",
        ],
    );
    assert_eq!(code, Some(0), "{table}");
    let homed = time_of(&table, "homing done");
    let start = time_of(&table, "--press START@step0: START pressed");
    assert_eq!(start, homed + 10, "the scan after homing is done: {table}");
    assert_eq!(lines_with(&table, "step 1   ").len(), 2, "{table}");
    assert_eq!(lines_with(&table, "end of cycle").len(), 1, "{table}");
    let (code, table) = paper(
        work.path(),
        &["--press", "MANUAL@step2", "--press", "RESET@step0"],
    );
    assert_eq!(code, Some(0), "{table}");
    assert!(!table.contains("RESET_PB pressed"), "{table}");
    assert!(
        table.contains("never happened: --press RESET@step0"),
        "{table}"
    );
    // The end of a cycle is still step 0.
    let (_, table) = paper(work.path(), &["--press", "STOP@step0"]);
    let end = time_of(&table, "end of cycle");
    assert_eq!(time_of(&table, "--press STOP@step0"), end + 10, "{table}");
}

/// Finding 10: `--load` on an actuator whose kind no load moves says what
/// the actuator is in the actuator model's words: a gripper has no piston,
/// a drive stands; a cylinder's valve holds its piston as before. W006 at
/// the file, the run goes on.
#[test]
fn a_load_that_does_nothing_names_the_actuator_by_its_kind() {
    let rows: [(&str, &[&str], &str); 3] = [
        (
            "pick_and_place.csv",
            &["--valve", "C2=vacuum", "--load", "C2=0.3"],
            "warning[W006]: --load C2=0.3: C2 is a vacuum gripper (valve type vacuum), not a cylinder: it has no piston (a load drifts only a piston on a 53exhaust or 53pressure valve's centre); the load does nothing",
        ),
        (
            "carwash.xlsx",
            &["--load", "C1=0.3"],
            "warning[W006]: --load C1=0.3: C1 is an electric drive (valve type motor), which stands with both contactors off",
        ),
        (
            "paper_example.xlsx",
            &["--load", "C1=0.3"],
            "warning[W006]: --load C1=0.3: C1's valve is 52bi, which holds the piston",
        ),
    ];
    let work = tempfile::tempdir().unwrap();
    for (file, args, said) in rows {
        let path = match file {
            "pick_and_place.csv" => crate::helpers::root().join("tests/fixtures").join(file),
            _ => sample(file),
        };
        let mut line = vec!["simulate".to_string(), path.display().to_string()];
        line.extend(args.iter().map(|a| a.to_string()));
        let (code, out) = run_in(work.path(), &line);
        assert_eq!(code, Some(0), "{file}: {out}");
        assert!(out.contains(said), "{file}: {out}");
        if file != "paper_example.xlsx" {
            assert!(!out.contains("holds the piston"), "{file}: {out}");
        }
    }
}

/// Finding 10, the jogs: a gripper's jog buttons are commented as what
/// they do (vacuum on until jog2-, vacuum off), not as a cylinder's
/// extend and retract while held. (The E042 for a second jog of a
/// `52mono`, naming the kind that has one, is a row of
/// `manual.rs::hostile_jog_events_are_refused`.)
#[test]
fn a_grippers_jogs_are_said_in_its_words() {
    let work = tempfile::tempdir().unwrap();
    let out = work.path().join("out");
    steptable()
        .arg("convert")
        .arg(crate::helpers::root().join("tests/fixtures/pick_and_place.csv"))
        .args(["--valve", "C2=vacuum", "--modes", "manual", "-o"])
        .arg(&out)
        .assert()
        .success();
    let csv = std::fs::read_to_string(out.join("pick_and_place/pick_and_place.io.csv")).unwrap();
    let jog = |name: &str| {
        csv.lines()
            .find(|l| l.split(',').nth(1) == Some(name))
            .unwrap_or_else(|| panic!("{name}: {csv}"))
            .to_string()
    };
    let on = jog("jog2+");
    assert!(
        on.contains("jog push-button: gripper 2, grip, on until its release jog (manual mode)"),
        "{on}"
    );
    let off = jog("jog2-");
    assert!(
        off.contains("jog push-button: gripper 2, release (manual mode)"),
        "{off}"
    );
    assert!(
        jog("jog1+").contains("cylinder 1, extend while held"),
        "{csv}"
    );
}
