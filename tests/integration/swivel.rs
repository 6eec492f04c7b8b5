//! The swivel (semi-rotary) drive (valve type `swivel`): the distributing
//! station's swivel arm C2 on a 5/2 double-solenoid valve, `y2+` to its end
//! stop at 180° (`x21`), `y2-` back to 0° (`x20`, home), 500 ms each way
//! unless told otherwise. Every list, comment and message calls it a
//! swivel drive; a middle position is refused at its cell (E045); its
//! hostile settings and options are refused at theirs.

use predicates::str::contains;

use crate::helpers::{
    Refused, TWO_ACTUATORS, assert_refused, convert_csv, convert_sheets, line_with, read_sheet,
    root, simulate_sheets, squeezed_stdout, step_seconds, steptable,
};

fn station() -> std::path::PathBuf {
    root().join("tests/fixtures/distributing_station.csv")
}

/// The swivel arm and the vacuum cup it carries.
const VALVES: &str = "C2=swivel,C3=vacuum";

fn written(dir: &std::path::Path, suffix: &str) -> String {
    let path = dir.join(format!("distributing_station/distributing_station{suffix}"));
    std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()))
}

#[test]
fn a_swivel_drive_is_named_as_one_in_its_lists_and_programs() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(station())
        .args([
            "--valve",
            VALVES,
            "--modes",
            "all",
            "--formats",
            "io,st",
            "-o",
        ])
        .arg(dir.path())
        .assert()
        .success();
    let io = written(dir.path(), ".io.csv");
    for said in [
        "x20,sensor,2,0,,\"swivel drive 2, at 0° (home)\"",
        "x21,sensor,2,1,,\"swivel drive 2, at 180°\"",
        "\"swivel drive 2, coil + (swivel to 180°)\"",
        "\"swivel drive 2, coil - (swivel back to 0°)\"",
        "\"jog push-button: swivel drive 2, swivel to 180° while held (manual mode)\"",
        // The cylinder beside it is still a cylinder, the cup a gripper.
        "\"cylinder 1, home position 0\"",
        "\"jog push-button: gripper 3, release (manual mode)\"",
    ] {
        assert!(io.contains(said), "{said}:\n{io}");
    }
    assert!(!io.contains("cylinder 2"), "{io}");
    let st = written(dir.path(), ".st");
    for said in [
        "y2+ on: swivel C2 to 180°, C2+1 towards x21",
        "y2- on: swivel C2 back to 0°, C2-0 towards x20",
        "C2 swivels to 180°",
        "C2 swivels back to 0°",
    ] {
        assert!(st.contains(said), "{said}:\n{st}");
    }
    assert!(
        !st.contains("C2 extends") && !st.contains("extend C2"),
        "{st}"
    );
}

#[test]
fn the_station_runs_in_the_swivel_drive_s_own_time() {
    let assert = steptable()
        .arg("simulate")
        .arg(station())
        .args(["--valve", VALVES])
        .assert()
        .success()
        .stdout(contains("passed"));
    let said = squeezed_stdout(&assert);
    // Step 5 swivels the arm home alone: its 500 ms and a scan or two.
    let line = line_with(&said, "5 ");
    let seconds: f64 = line.split(' ').nth(3).expect("a duration").parse().unwrap();
    assert!((0.49..0.56).contains(&seconds), "{said}");
    // The report says the time it gave the drive, in the drive's words.
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(station())
        .args(["--valve", VALVES, "--formats", "report", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let report = written(dir.path(), ".report.html");
    assert!(
        report.contains("valve swivel, swivels to 180° in 500ms, swivels back to 0° in 500ms"),
        "{report}"
    );
}

#[test]
fn the_fault_table_has_both_end_stop_sensors_of_the_swivel_drive() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("faults")
        .arg(station())
        .args(["--valve", VALVES, "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let csv = written(dir.path(), ".faults.csv");
    // A dead end-stop sensor holds the cycle where it waits for it. A
    // shorted one is passed over at the swing out (step 3), which the
    // ejector's stroke beside it outlasts; shorted at home, it ends the
    // cycle while the drive still swings back (step 5): the program is
    // ready for START with the drive not home.
    for row in [
        "x20 open circuit (stuck at 0),x20,0,safe stall,at every moment,,0,step 1 never fires: waiting for x20",
        "x20 short circuit (stuck at 1),x20,1,hazard,at every moment,,5,\"the cycle ended before step 5 finished (C2 had not reached x20)",
        "x21 open circuit (stuck at 0),x21,0,safe stall,at every moment,,3,step 4 never fires: waiting for x21",
        "x21 short circuit (stuck at 1),x21,1,no effect,",
    ] {
        assert!(csv.contains(row), "{row}:\n{csv}");
    }
    assert!(!csv.contains("cylinder 2"), "{csv}");
}

/// The station's table with C2 a swivel drive on the SETTINGS sheet.
const SWIVEL: &[&[&str]] = &[&["actuator", "valve"], &["C2", "swivel"]];

#[test]
fn hostile_swivel_settings_are_refused_at_their_cells() {
    assert_refused(&[
        Refused {
            what: "a middle position asked of a swivel drive",
            table: &[
                &["", "BRANCH 1"],
                &["STEP 1", "C2+1"],
                &["STEP 2", "C2+2"],
                &["STEP 3", "C2-0"],
            ],
            settings: SWIVEL,
            args: &[],
            code_at: "TABLE!B2: error[E045]: \"C2+1\" makes position 1 a middle position of C2, since the table also asks C2 for position 2, but C2 is a swivel drive (valve type swivel), which has positions 0 and 1 only (a swivel drive: C2+1 swivels it to 180°, C2-0 back to 0°",
        },
        Refused {
            what: "a position past 180°",
            table: &[&["", "BRANCH 1"], &["STEP 1", "C2+2"], &["STEP 2", "C2-0"]],
            settings: SWIVEL,
            args: &[],
            code_at: "TABLE!B2: error[E045]: \"C2+2\" asks C2 for position 2",
        },
        Refused {
            what: "the kind given twice",
            table: crate::helpers::TWO_ACTUATORS,
            settings: &[&["actuator", "valve"], &["C2", "swivel"], &["C2", "swivel"]],
            args: &[],
            code_at: "SETTINGS!A3: error[E030]: C2 is given twice in the actuator table",
        },
        Refused {
            what: "contradicting kinds",
            table: crate::helpers::TWO_ACTUATORS,
            settings: &[&["actuator", "valve"], &["C2", "swivel"], &["C2", "52bi"]],
            args: &[],
            code_at: "SETTINGS!A3: error[E030]: C2 is given twice in the actuator table",
        },
        Refused {
            what: "a misspelt kind",
            table: crate::helpers::TWO_ACTUATORS,
            settings: &[&["actuator", "valve"], &["C2", "swivle"]],
            args: &[],
            code_at: "SETTINGS!B2: error[E030]: valve of C2: \"swivle\" is not a valve type",
        },
        Refused {
            what: "the kind in words",
            table: crate::helpers::TWO_ACTUATORS,
            settings: &[&["actuator", "valve"], &["C2", "swivel drive"]],
            args: &[],
            code_at: "SETTINGS!B2: error[E030]: valve of C2: \"swivel drive\" is not a valve type: did you mean swivel?",
        },
        Refused {
            what: "a kind of an actuator the table lacks",
            table: crate::helpers::TWO_ACTUATORS,
            settings: &[&["actuator", "valve"], &["C9", "swivel"]],
            args: &[],
            code_at: "SETTINGS!A2: error[E030]: the actuator table names C9, which the table does not have",
        },
        Refused {
            what: "a coil of the swivel drive kept on through the EMERGENCY STOP",
            table: crate::helpers::TWO_ACTUATORS,
            settings: &[
                &["actuator", "valve"],
                &["C2", "swivel"],
                &["hold on estop", "y2+"],
                &["modes", "estop"],
            ],
            args: &[],
            code_at: "y2+ is a valve coil of swivel drive C2: left on, it swings the arm on to its end stop",
        },
        Refused {
            what: "a name colliding with a generated one",
            table: crate::helpers::TWO_ACTUATORS,
            settings: &[&["actuator", "valve", "name"], &["C2", "swivel", "x21"]],
            args: &[],
            code_at: "SETTINGS!C2: error[E015]: C2 (x21): \"x21\" cannot name an actuator",
        },
    ]);
}

#[test]
fn hostile_swivel_options_are_refused() {
    for (valve, said) in [
        ("C2=swivel,C2=swivel", "C2 is given twice"),
        ("C2=swivel,C2=52bi", "C2 is given twice"),
        ("C2=swivle", "\"swivle\" is not a valve type"),
    ] {
        steptable()
            .arg("check")
            .arg(station())
            .args(["--valve", valve])
            .assert()
            .code(1)
            .stderr(contains(said));
    }
    // A middle position on the command line's swivel drive: E045 at its cell.
    let table = ",BRANCH 1\nSTEP 1,C2+1\nSTEP 2,C2+2\nSTEP 3,C2-0\n";
    let (_dir, out, assert) = convert_csv(table, &["--valve", "C2=swivel"], 1);
    let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(stderr.contains("t.csv:2:2: error[E045]"), "{stderr}");
    assert!(stderr.contains("a swivel drive"), "{stderr}");
    assert!(!out.exists());
}

#[test]
fn the_command_line_s_kind_wins_over_the_sheet_s_and_says_so() {
    // SETTINGS says 52bi, --valve says swivel: the drive is a swivel drive,
    // and the overridden cell is W006 at that cell.
    let settings: &[&[&str]] = &[&["actuator", "valve"], &["C2", "52bi"]];
    let (_dir, out, assert) = convert_sheets(
        crate::helpers::TWO_ACTUATORS,
        settings,
        &["--valve", "C2=swivel"],
        0,
    );
    let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(stderr.contains("SETTINGS!B2: warning[W006]"), "{stderr}");
    let st = std::fs::read_to_string(out.join("h/h.st")).unwrap();
    assert!(st.contains("swivel C2 to 180°"), "{st}");
    // A load on a swivel drive does nothing, and says what holds it.
    let (_dir, _, assert) = convert_sheets(
        crate::helpers::TWO_ACTUATORS,
        SWIVEL,
        &["--load", "C2=0.1"],
        0,
    );
    let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    assert!(
        stderr.contains("warning[W006]: --load C2=0.1: C2's valve is swivel, which holds the arm at its end stop"),
        "{stderr}"
    );
}

/// The template's own SETTINGS sheet, as an engineer fills it who only
/// picks the kinds in the valve column (C1 a swivel drive, C2 a vacuum
/// gripper), with `times` in both time cells of those two rows.
fn template_settings(times: &str) -> Vec<Vec<String>> {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("tpl.xlsx");
    steptable()
        .args(["template", "-o"])
        .arg(&path)
        .assert()
        .success();
    let mut rows = read_sheet(&path, "SETTINGS");
    let header = rows
        .iter()
        .position(|r| r.first().is_some_and(|c| c == "actuator"))
        .expect("the template's actuator table");
    for (row, kind) in [(header + 1, "swivel"), (header + 2, "vacuum")] {
        let cells = &mut rows[row];
        cells.resize(cells.len().max(4), String::new());
        // The template leaves the times empty; the old one wrote 1s.
        assert_eq!(cells[1..3], ["", ""], "{cells:?}");
        cells[1] = times.to_string();
        cells[2] = times.to_string();
        cells[3] = kind.to_string();
    }
    rows
}

/// Finding 8 of the red team on the kinds: an engineer who only picks
/// `swivel` and `vacuum` in the template's valve column gets the kinds' own
/// times (its time cells are empty), without a warning; a workbook of the
/// old template (1s in every row) keeps its 1 s and says so at each cell,
/// with the kind's own time. Broken on purpose (the template writing 1s
/// again) the first half failed on the empty cells; with W007 removed, the
/// second half failed.
#[test]
fn the_template_leaves_a_swivel_drive_and_a_gripper_their_own_times() {
    let run = |times: &str| {
        let rows = template_settings(times);
        let rows: Vec<Vec<&str>> = rows
            .iter()
            .map(|r| r.iter().map(String::as_str).collect())
            .collect();
        let rows: Vec<&[&str]> = rows.iter().map(Vec::as_slice).collect();
        let header = 1 + rows
            .iter()
            .position(|r| r.first() == Some(&"actuator"))
            .unwrap();
        let (said, stderr, code) = simulate_sheets(TWO_ACTUATORS, &rows, &[]);
        (said, stderr, code, header)
    };
    let (said, stderr, code, _) = run("");
    assert_eq!(code, Some(0), "{stderr}");
    assert!(!stderr.contains("warning"), "{stderr}");
    // Swing out, grip, swing back, release: each its own time and a scan.
    for (step, ms) in [(1, 500), (2, 300), (3, 500), (4, 200)] {
        let seconds = step_seconds(&said, step);
        let own = f64::from(ms) / 1000.0;
        assert!(
            (own - 0.011..=own + 0.011).contains(&seconds),
            "step {step}:\n{said}"
        );
    }

    let (said, stderr, code, header) = run("1s");
    assert_eq!(code, Some(0), "{stderr}");
    for (cell, own) in [
        (format!("B{}", header + 1), "swivels to 180° in 500ms"),
        (format!("C{}", header + 1), "swivels back to 0° in 500ms"),
        (format!("B{}", header + 2), "grips in 300ms"),
        (format!("C{}", header + 2), "releases in 200ms"),
    ] {
        let text = format!("SETTINGS!{cell}: warning[W007]");
        let line = stderr.lines().find(|l| l.contains(&text));
        assert!(
            line.is_some_and(|l| l.contains(own) && l.contains("1s is taken as given")),
            "{text} {own}:\n{stderr}"
        );
    }
    for step in 1..=4 {
        let seconds = step_seconds(&said, step);
        assert!((0.96..=1.011).contains(&seconds), "step {step}:\n{said}");
    }
}
