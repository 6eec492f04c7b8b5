//! The vacuum gripper (valve type `vacuum`): one coil `y2` switches the
//! vacuum on, one vacuum switch `x21` reads 1 once the part is held; the
//! program reads "released" (`C2-0`) as that switch off and has no `x20`.
//! An EMERGENCY STOP keeps the part held; the fault table has the vacuum
//! switch stuck at 0 and at 1; a gripper asked for more than held and
//! released is refused at its cell (E045).

use predicates::str::contains;
use steptable::program::Signal;
use steptable::simulate::Operator;
use steptable::simulate::scenario::scenario;

use crate::helpers::{
    Refused, assert_refused, root, simulate_sheets, squeezed_stdout, step_seconds, steptable,
};

fn pick_and_place() -> std::path::PathBuf {
    root().join("tests/fixtures/pick_and_place.csv")
}

/// The pick and place checked with C2 on `valve`, as `convert` reads it.
fn checked(valve: &str) -> steptable::convert::Checked {
    let mut settings = steptable::settings::Settings::new();
    settings.give(steptable::settings::Given {
        valves: steptable::actuator::parse_valves(&format!("C2={valve}")).unwrap(),
        ..steptable::settings::Given::default()
    });
    steptable::convert::check_path(&pick_and_place(), &settings).expect("a valid table")
}

#[test]
fn a_gripper_has_one_coil_and_its_vacuum_switch_alone() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(pick_and_place())
        .args(["--valve", "C2=vacuum", "--formats", "io,st", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let io =
        std::fs::read_to_string(dir.path().join("pick_and_place/pick_and_place.io.csv")).unwrap();
    assert!(io.contains(",x21,") && !io.contains(",x20,"), "{io}");
    assert!(io.contains(",y2,") && !io.contains("y2+"), "{io}");
    let st = std::fs::read_to_string(dir.path().join("pick_and_place/pick_and_place.st")).unwrap();
    // Released is the vacuum switch off: the step after C2-0 waits for it.
    assert!(st.contains("NOT x21"), "{st}");
    assert!(!st.contains("x20"), "{st}");
}

/// In manual mode the gripper's jogs say what they do: `jog2p` switches the
/// vacuum on and it stays on (holding the part) until `jog2m` releases it,
/// where a cylinder's jog moves it only while held.
#[test]
fn a_gripper_s_jogs_say_the_vacuum_stays_on_until_released() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(pick_and_place())
        .args([
            "--valve",
            "C2=vacuum",
            "--modes",
            "manual",
            "--formats",
            "st",
            "-o",
        ])
        .arg(dir.path())
        .assert()
        .success();
    let st = std::fs::read_to_string(dir.path().join("pick_and_place/pick_and_place.st")).unwrap();
    for said in [
        "jog push-button: gripper 2, grip, on until its release jog (manual mode)",
        "jog push-button: gripper 2, release (manual mode)",
        "jog C2: y2 on when jog2+ is pressed",
        "jog push-button: cylinder 1, extend while held (manual mode)",
    ] {
        assert!(st.contains(said), "{said}: {st}");
    }
    assert!(!st.contains("cylinder 2, extend"), "{st}");
    // The gripper's own times are a default: a CSV has no SETTINGS sheet.
    let made_by = st.lines().next().unwrap_or_default();
    assert!(
        made_by.contains("settings: the command line, defaults for the rest"),
        "{made_by}"
    );
}

#[test]
fn the_pick_and_place_runs_through_its_cycle_in_the_gripper_s_own_times() {
    let assert = steptable()
        .arg("simulate")
        .arg(pick_and_place())
        .args(["--valve", "C2=vacuum"])
        .assert()
        .success()
        .stdout(contains("passed"));
    let said = squeezed_stdout(&assert);
    // The gripper's steps last its build-up (step 2) and its release (step
    // 5: the vacuum switch drops once the vacuum is gone, not when the coil
    // drops), a scan or two more.
    let (grip, release) = (step_seconds(&said, 2), step_seconds(&said, 5));
    assert!((0.29..0.35).contains(&grip), "{said}");
    assert!((0.18..0.25).contains(&release), "{said}");
    let checked = checked("vacuum");
    let stroke = checked.settings.simulation.machine.strokes.of(2);
    assert_eq!((stroke.extend_ms, stroke.retract_ms), (300, 200), "{said}");
    let cylinder = checked.settings.simulation.machine.strokes.of(1);
    assert_eq!(cylinder.extend_ms, 1000);
}

/// The vacuum switch reads 1 once the vacuum has fully built up and 0 once
/// it has fully decayed, not at the 2 % short of the end at which a
/// cylinder's sensor sees its piston: with 1 s given both ways, the grip
/// step lasts the whole second, and so does the step that waits for the
/// release. Broken on purpose (the switch read within the sensor window
/// again) this failed on the grip step.
#[test]
fn the_vacuum_switch_waits_for_the_whole_build_up_and_release() {
    let assert = steptable()
        .arg("simulate")
        .arg(pick_and_place())
        .args(["--valve", "C2=vacuum", "--stroke", "C2=1s"])
        .assert()
        .success()
        .stdout(contains("passed"));
    let said = squeezed_stdout(&assert);
    // One scan (10 ms) at most for the program to see the switch.
    let (grip, release) = (step_seconds(&said, 2), step_seconds(&said, 5));
    assert!((1.0..=1.01).contains(&grip), "{said}");
    assert!((1.0..=1.01).contains(&release), "{said}");
}

#[test]
fn an_emergency_stop_keeps_the_part_held_by_default() {
    let at = |valve: &str, modes: &str| {
        let mut checked = checked(valve);
        checked.settings.program.modes = modes.parse().unwrap();
        let program = steptable::program::build(
            &checked.table,
            &checked.settings.program,
            &checked.settings.simulation.machine.valves,
            &checked.settings.simulation.machine.strokes,
        );
        // START at 0.5 s; C1 down by 1.5 s, the part held by 1.8 s, C1 on
        // its way up when the EMERGENCY STOP comes at 2.2 s.
        let start = Operator {
            start: true,
            ..Operator::default()
        };
        let estop = Operator {
            estop: true,
            ..Operator::default()
        };
        let script = [(500, start), (600, Operator::default()), (2_200, estop)];
        let report = scenario(
            &checked.table,
            &program,
            &checked.settings.simulation,
            &script,
            3_000,
        );
        report.at(2_900).expect("sampled").outputs_on.clone()
    };
    let held = at("vacuum", "estop");
    assert!(
        held.contains(&Signal::SingleCoil { actuator: 2 }),
        "{held:?}"
    );
    assert!(
        !held.contains(&Signal::Coil {
            actuator: 1,
            sign: steptable::cell::Sign::Minus
        }),
        "{held:?}"
    );
    // A 52mono valve on C2 is a cylinder: the EMERGENCY STOP drops its coil.
    let dropped = at("52mono", "estop");
    assert!(
        !dropped.contains(&Signal::SingleCoil { actuator: 2 }),
        "{dropped:?}"
    );
}

#[test]
fn the_fault_table_has_the_vacuum_switch_stuck_at_0_and_at_1() {
    let dir = tempfile::tempdir().unwrap();
    let assert = steptable()
        .arg("faults")
        .arg(pick_and_place())
        .args(["--valve", "C2=vacuum", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let said = squeezed_stdout(&assert);
    let csv = dir.path().join("pick_and_place/pick_and_place.faults.csv");
    let csv = std::fs::read_to_string(csv).unwrap();
    // Stuck at 1 before the grip: the arm lifts before the part is held.
    // Failing open while the part is held: "released" reads at once, and
    // the arm moves on before the part has dropped. Both are hazards.
    assert!(
        csv.contains("x21 short circuit (stuck at 1),x21,1,hazard"),
        "{csv}"
    );
    assert!(
        csv.contains("x21 open circuit (stuck at 0),x21,0,hazard"),
        "{csv}"
    );
    // The gripper has no x20: neither a fault of it nor a place named by it.
    assert!(
        !csv.contains("x20") && !said.contains("x20"),
        "{csv}\n{said}"
    );
    // Its positions are no places: it grips, holds or releases its part.
    assert!(
        !csv.contains("reached NOT") && !csv.contains("between NOT"),
        "{csv}"
    );
    assert!(
        csv.contains("C2 had not released its part (waiting for NOT x21)")
            || csv.contains("C2 had not gripped its part (waiting for x21)"),
        "{csv}"
    );
}

/// A gripper table, its C2 made a gripper on the SETTINGS sheet.
const GRIPPER: &[&[&str]] = &[&["actuator", "valve"], &["C2", "vacuum"]];

#[test]
fn hostile_gripper_settings_are_refused_at_their_cells() {
    assert_refused(&[
        Refused {
            what: "a middle position asked of a gripper",
            table: &[
                &["", "BRANCH 1"],
                &["STEP 1", "C2+1"],
                &["STEP 2", "C2+2"],
                &["STEP 3", "C2-0"],
            ],
            settings: GRIPPER,
            args: &[],
            code_at: "TABLE!B2: error[E045]: \"C2+1\" makes position 1 a middle position of C2, since the table also asks C2 for position 2, but C2 is a gripper (valve type vacuum), which has positions 0 and 1 only",
        },
        Refused {
            what: "a position past held",
            table: &[&["", "BRANCH 1"], &["STEP 1", "C2+2"], &["STEP 2", "C2-0"]],
            settings: GRIPPER,
            args: &[],
            code_at: "TABLE!B2: error[E045]: \"C2+2\" asks C2 for position 2",
        },
        Refused {
            what: "the kind given twice",
            table: crate::helpers::TWO_ACTUATORS,
            settings: &[&["actuator", "valve"], &["C2", "vacuum"], &["C2", "vacuum"]],
            args: &[],
            code_at: "SETTINGS!A3: error[E030]: C2 is given twice in the actuator table",
        },
        Refused {
            what: "contradicting kinds",
            table: crate::helpers::TWO_ACTUATORS,
            settings: &[&["actuator", "valve"], &["C2", "vacuum"], &["C2", "52mono"]],
            args: &[],
            code_at: "SETTINGS!A3: error[E030]: C2 is given twice in the actuator table",
        },
        Refused {
            what: "an unknown kind",
            table: crate::helpers::TWO_ACTUATORS,
            settings: &[&["actuator", "valve"], &["C2", "vacum"]],
            args: &[],
            code_at: "SETTINGS!B2: error[E030]: valve of C2: \"vacum\" is not a valve type",
        },
        Refused {
            what: "a kind of an actuator the table lacks",
            table: crate::helpers::TWO_ACTUATORS,
            settings: &[&["actuator", "valve"], &["C9", "vacuum"]],
            args: &[],
            code_at: "SETTINGS!A2: error[E030]: the actuator table names C9, which the table does not have",
        },
        Refused {
            what: "a wait on the released sensor a gripper does not have",
            table: &[
                &["", "BRANCH 1"],
                &["STEP 1", "C2+1"],
                &["STEP 2", "C2-0"],
                &["STEP 3", "I:x20"],
            ],
            settings: GRIPPER,
            args: &[],
            code_at: "TABLE!B4: error[E015]",
        },
    ]);
}

#[test]
fn hostile_gripper_options_are_refused() {
    // The kind twice, contradicting, misspelt.
    for (valve, said) in [
        ("C2=vacuum,C2=vacuum", "C2 is given twice"),
        ("C2=vacuum,C2=52mono", "C2 is given twice"),
        ("C2=vacum", "\"vacum\" is not a valve type"),
    ] {
        steptable()
            .arg("check")
            .arg(pick_and_place())
            .args(["--valve", valve])
            .assert()
            .code(1)
            .stderr(contains(said));
    }
    steptable()
        .arg("check")
        .arg(pick_and_place())
        .args(["--valve", "C9=vacuum"])
        .assert()
        .code(1)
        .stderr(contains(
            "error[E030]: --valve C9=…: the table has no actuator C9",
        ));
    // A load on the gripper does nothing, and the warning says why in a
    // gripper's words (no piston).
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(pick_and_place())
        .args(["--valve", "C2=vacuum", "--load", "C2=0.2", "--formats", "st", "-o"])
        .arg(dir.path())
        .assert()
        .success()
        .stderr(contains(
            "warning[W006]: --load C2=0.2: C2 is a vacuum gripper (valve type vacuum), not a cylinder: it has no piston",
        ));
}

/// A STOP that acts at once (an `on stop` row naming another output)
/// keeps the gripper's part as the EMERGENCY STOP does, unless the row
/// names the gripper: the milder stop must not drop the part mid-swing.
#[test]
fn a_stop_at_once_keeps_the_part_unless_its_row_names_the_gripper() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("stop.xlsx");
    let table: &[&[&str]] = &[
        &["", "BRANCH 1", "BRANCH 2"],
        &["STEP 1", "C1+1", ""],
        &["STEP 2", "C2+1", ""],
        &["STEP 3", "C1-0", "C3+1"],
        &["STEP 4", "C1+1", ""],
        &["STEP 5", "C2-0", ""],
        &["STEP 6", "C1-0", "C3-0"],
    ];
    let ended = |on_stop: &str| {
        let settings: &[&[&str]] = &[
            &["modes", "all"],
            &["on stop", on_stop],
            &["actuator", "valve"],
            &["C2", "vacuum"],
        ];
        crate::helpers::write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
        let run = steptable()
            .arg("simulate")
            .arg(&path)
            .args(["--press", "STOP@step4"])
            .assert();
        let stdout = String::from_utf8_lossy(&run.get_output().stdout).into_owned();
        stdout.lines().last().unwrap_or_default().to_string()
    };
    let kept = ended("C3 off");
    assert!(kept.contains("on: y2"), "{kept}");
    let dropped = ended("C3 off, C2 off");
    assert!(!dropped.contains("y2"), "{dropped}");
}

/// One row of the actuator table's times for a gripper: its SETTINGS rows,
/// options, what stderr must say (each at its cell) or that it warns of
/// nothing, and the grip and release steps' times it runs in.
struct KindTimes {
    what: &'static str,
    settings: &'static [&'static [&'static str]],
    args: &'static [&'static str],
    said: &'static [&'static str],
    grip_ms: u32,
    release_ms: u32,
}

/// An empty time cell takes the gripper's own time (the template leaves
/// them empty); a row naming only its actuator says nothing; the old
/// template's `1s` is kept and said at its cell (W007, naming the kind's
/// own time); the command line's stroke wins without W007. Broken on
/// purpose (an empty half back to the cylinder's 1 s) the half row ran its
/// release in 1 s and this failed; with the bare rows' W003 back, the
/// first row failed.
#[test]
fn a_gripper_s_time_cells_left_empty_take_its_own_times() {
    const HEAD: &[&str] = &["actuator", "extend", "retract", "valve"];
    let rows = [
        KindTimes {
            what: "the template's rows: only the valve chosen, unused actuators bare",
            settings: &[HEAD, &["C1"], &["C2", "", "", "vacuum"], &["C5"], &["C8"]],
            args: &[],
            said: &[],
            grip_ms: 300,
            release_ms: 200,
        },
        KindTimes {
            what: "half a row: the build-up given, the release empty",
            settings: &[HEAD, &["C2", "2s", "", "vacuum"]],
            args: &[],
            said: &[],
            grip_ms: 2000,
            release_ms: 200,
        },
        KindTimes {
            what: "a bare row repeated, then the actuator's row",
            settings: &[HEAD, &["C2"], &["C2"], &["C2", "", "", "vacuum"]],
            args: &[],
            said: &[],
            grip_ms: 300,
            release_ms: 200,
        },
        KindTimes {
            what: "the old template's 1s / 1s beside a gripper",
            settings: &[HEAD, &["C1", "1s", "1s"], &["C2", "1s", "1s", "vacuum"]],
            args: &[],
            said: &[
                "SETTINGS!B3: warning[W007]: extend of C2: 1s is taken as given, though C2 is a gripper (valve type vacuum), which grips in 300ms of its own",
                "SETTINGS!C3: warning[W007]: retract of C2: 1s is taken as given",
                "empty the cell to take 200ms",
            ],
            grip_ms: 1000,
            release_ms: 1000,
        },
        KindTimes {
            what: "the old template's 1s under a --stroke of the command line",
            settings: &[HEAD, &["C2", "1s", "1s", "vacuum"]],
            args: &["--stroke", "C2=500ms"],
            said: &["SETTINGS!B2: warning[W006]: extend of C2: --stroke on the command line wins"],
            grip_ms: 500,
            release_ms: 500,
        },
    ];
    for row in rows {
        let (said, stderr, code) =
            simulate_sheets(crate::helpers::TWO_ACTUATORS, row.settings, row.args);
        assert_eq!(code, Some(0), "{}: {stderr}", row.what);
        if row.said.is_empty() {
            assert!(!stderr.contains("warning"), "{}: {stderr}", row.what);
        }
        for text in row.said {
            assert!(stderr.contains(text), "{}: {text}\n{stderr}", row.what);
        }
        if !row.said.iter().any(|s| s.contains("W007")) {
            assert!(!stderr.contains("W007"), "{}: {stderr}", row.what);
        }
        // A scan (10 ms) or two for the program to see the switch.
        for (step, ms) in [(2, row.grip_ms), (4, row.release_ms)] {
            let seconds = step_seconds(&said, step);
            let given = f64::from(ms) / 1000.0;
            assert!(
                (given..=given + 0.021).contains(&seconds),
                "{}: step {step}\n{said}",
                row.what
            );
        }
    }
}
