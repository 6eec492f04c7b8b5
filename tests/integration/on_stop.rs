//! SETTINGS `on stop`: STOP acts at once, in any state, and each named
//! output goes off, holds, or runs on for a while (Aly 2008's oven).

use predicates::prelude::*;
use predicates::str::contains;
use steptable::cell::Sign;
use steptable::program::{Signal, StopAction};
use steptable::simulate::scenario::scenario;
use steptable::simulate::{Operator, SimSettings};

use crate::helpers::{Build, line_with, sample, squeezed_stdout, steptable, write_xlsx_sheets};

const IDLE: Operator = Operator {
    start: false,
    continuous: false,
    stop: false,
    estop: false,
    reset: false,
    step_mode: false,
    step: false,
    manual: false,
    jogs: steptable::simulate::Jogs::NONE,
};

/// The bundled oven through the binary: its addresses are the paper's
/// Table 3, its STOP stops at once, and neither a broken STOP wire nor a
/// dead START button leaves it heating as a hazard.
#[test]
fn the_oven_converts_with_table_3_and_stops_at_once() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(sample("oven.xlsx"))
        .args(["--formats", "io,st", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let io = std::fs::read_to_string(dir.path().join("oven/oven.io.csv")).unwrap();
    let pinned: Vec<String> = io
        .lines()
        .skip(1)
        .map(|l| l.split(',').take(2).collect::<Vec<_>>().join(" "))
        .collect();
    assert_eq!(
        pinned,
        [
            "I0.0 START",
            "I0.1 STOP",
            "Q0.0 horn",
            "Q0.1 coil",
            "Q0.2 fan"
        ]
    );
    let st = std::fs::read_to_string(dir.path().join("oven/oven.st")).unwrap();
    assert!(
        st.contains(
            "STOP (normally closed): stop at once, every coil and output off but fan off after 20s"
        ),
        "{st}"
    );
    assert!(st.contains("runon1_pt := T#20000ms"), "{st}");
    let stdout = squeezed_stdout(
        &steptable()
            .arg("faults")
            .arg(sample("oven.xlsx"))
            .assert()
            .success(),
    );
    let row = line_with(&stdout, "STOP open circuit");
    assert!(row.contains(" safe stall at every moment "), "{row}");
    let row = line_with(&stdout, "START open circuit");
    assert!(row.contains(" safe stall "), "{row}");
}

/// The oven in simulation: STOP during the horn ends the cycle there (no
/// coil, no fan); STOP while it heats switches the coil off in that scan
/// and the fan 20 s later; the next START runs a full cycle again.
#[test]
fn stop_is_honoured_in_any_state_and_the_fan_runs_on() {
    let build = Build::path(&sample("oven.xlsx"));
    let (table, program) = (&build.table, build.program());
    let start = Operator {
        start: true,
        ..IDLE
    };
    let stop = Operator { stop: true, ..IDLE };
    let script = vec![
        (100, start),
        (200, IDLE),
        (5_000, stop),
        (5_100, IDLE),
        (6_000, start),
        (6_100, IDLE),
        (20_000, stop),
        (20_100, IDLE),
    ];
    let report = scenario(table, &program, &SimSettings::default(), &script, 45_000);
    let on = |t: u64, name: &str| {
        report
            .at(t)
            .expect("sampled")
            .outputs_on
            .iter()
            .any(|s| s.symbol() == name)
    };
    // The horn from START, cut by STOP at 5 s: no coil, no fan.
    assert!(on(4_990, "horn"));
    assert!(!on(5_010, "horn") && !on(5_500, "coil") && !on(5_500, "fan"));
    // The second START: horn 10 s, then coil and fan.
    assert!(on(6_500, "horn") && !on(6_500, "coil"));
    assert!(on(16_500, "coil") && on(16_500, "fan") && !on(16_500, "horn"));
    // STOP at 20 s: coil off at once, fan on until 40 s.
    assert!(!on(20_010, "coil"));
    assert!(on(39_900, "fan"));
    assert!(!on(40_100, "fan"));
    assert_eq!(report.cycle_starts().len(), 2);
}

/// A cylinder machine with `on stop`: STOP mid-travel switches every coil
/// off but the one held (C2 on a closed-centre valve stops where it is), sends the sequence back to STEP 1, and a machine
/// away from home needs RESET before START runs again.
#[test]
fn stop_mid_travel_abandons_the_cycle_until_reset_homes() {
    let mut build =
        Build::rows("t.csv", &[&["C1+1"], &["C2+1"], &["C2-0"], &["C1-0"]]).modes("stop,reset");
    let held = Signal::Coil {
        actuator: 1,
        sign: Sign::Plus,
    };
    build.settings.program.halt.on_stop = [(held, StopAction::Hold)].into();
    // C2's closed-centre valve stops the piston where it is with no coil on.
    build
        .settings
        .simulation
        .machine
        .valves
        .per_actuator
        .insert(2, steptable::actuator::ActuatorKind::Closed53);
    let (table, program) = (&build.table, build.program());
    let script = vec![
        (
            100,
            Operator {
                start: true,
                ..IDLE
            },
        ),
        (200, IDLE),
        // C1 is out after 1 s; C2 travels out from then on.
        (1_600, Operator { stop: true, ..IDLE }),
        (1_700, IDLE),
        (
            3_000,
            Operator {
                start: true,
                ..IDLE
            },
        ),
        (3_100, IDLE),
        (
            5_000,
            Operator {
                reset: true,
                ..IDLE
            },
        ),
        (5_100, IDLE),
        (
            9_000,
            Operator {
                start: true,
                ..IDLE
            },
        ),
        (9_100, IDLE),
    ];
    let report = scenario(table, &program, &build.settings.simulation, &script, 16_000);
    let sample = report.at(1_620).expect("sampled");
    assert_eq!(sample.outputs_on, [held], "only the held coil stays on");
    assert_eq!(sample.step, 0, "back in the initial step");
    let frozen = report.at(2_900).unwrap().positions.clone();
    assert!(
        frozen[1] > 0.1 && frozen[1] < 0.9,
        "C2 stopped mid-way: {frozen:?}"
    );
    // START at 3 s: refused, the machine is not home.
    let starts = report.cycle_starts();
    assert_eq!(
        starts.iter().filter(|t| **t < 9_000).count(),
        1,
        "{starts:?}"
    );
    // RESET homes it; START at 9 s runs a full cycle.
    assert!(
        report
            .at(8_900)
            .unwrap()
            .positions
            .iter()
            .all(|p| p.abs() < 0.05)
    );
    assert_eq!(starts.len(), 2, "{starts:?}");
    assert!(
        report
            .fired
            .iter()
            .any(|(t, step)| *t > 9_000 && *step == 4)
    );
}

/// A row the program cannot use is said at its cell: W006 without STOP,
/// E030 for a malformed item, an unknown output, an output named twice or a
/// run-on out of range; nothing is written.
#[test]
fn on_stop_rows_are_checked_at_their_cell() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("oven.xlsx");
    let table: &[&[&str]] = &[&["Y:heater+; Y:fan+; T=1s"], &["Y:heater-; Y:fan-"]];
    let write = |modes: &str, on_stop: &str| {
        let settings: &[&[&str]] = &[&["modes", modes], &["on stop", on_stop]];
        write_xlsx_sheets(
            &path,
            &[
                ("SEQUENTIAL CONTROL DESCRIPTION", table),
                ("SETTINGS", settings),
            ],
        );
    };
    write("none", "fan off after 20s");
    steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .success()
        .stderr(contains(
            "SETTINGS!B2: warning[W006]: on stop: the program has no STOP button (--modes stop); nothing named here is ever done",
        ));
    // With manual mode the row is not idle: what it holds stays on into
    // manual (red team rt7 F12), and the warning says so.
    let clamp: &[&[&str]] = &[&["C1+1"], &["C1-0"]];
    let settings: &[&[&str]] = &[&["modes", "manual"], &["on stop", "C1 hold"]];
    let held = dir.path().join("held.xlsx");
    write_xlsx_sheets(
        &held,
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", clamp),
            ("SETTINGS", settings),
        ],
    );
    let run = steptable().arg("check").arg(&held).assert().success();
    let stderr = String::from_utf8_lossy(&run.get_output().stderr).into_owned();
    assert!(
        stderr.contains("SETTINGS!B2: warning[W006]: on stop: the program has no STOP button (--modes stop); only manual mode reads it")
            && !stderr.contains("nothing named here"),
        "{stderr}"
    );
    for (row, error) in [
        (
            "fan sometimes",
            "\"fan sometimes\" is not an output and what it does",
        ),
        ("door off", "\"door\" is not an output of this table"),
        ("fan off, fan hold", "fan is named twice"),
        (
            "fan off after 700s",
            "\"fan off after 700s\" is not an output and what it does",
        ),
        (
            "fan off after 5ms",
            "\"fan off after 5ms\" is not an output and what it does",
        ),
    ] {
        write("stop", row);
        let out = dir.path().join("out");
        steptable()
            .arg("convert")
            .arg(&path)
            .arg("-o")
            .arg(&out)
            .assert()
            .failure()
            .stderr(contains(format!(
                "SETTINGS!B2: error[E030]: on stop: {error}"
            )));
        assert!(!out.exists(), "{row}: nothing written");
    }
    write("stop", "heater off, fan on for 1.5s");
    steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .success()
        .stderr(contains("W006").not().and(contains("E030").not()));
}

/// `on estop | fan off after 5s`: the emergency stop switches the heater
/// and the coil off in the scan it is pressed; the fan runs on 5 s.
#[test]
fn the_emergency_stop_lets_the_fan_run_on() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("heated.xlsx");
    let table: &[&[&str]] = &[&["C1+1; Y:heater+; Y:fan+"], &["C1-0; Y:heater-; Y:fan-"]];
    let settings: &[&[&str]] = &[&["modes", "estop"], &["on estop", "fan off after 5s"]];
    write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
    let build = Build::path(&path);
    let program = build.program();
    let script = vec![
        (
            100,
            Operator {
                start: true,
                ..IDLE
            },
        ),
        (200, IDLE),
        (
            600,
            Operator {
                estop: true,
                ..IDLE
            },
        ),
    ];
    let report = scenario(
        &build.table,
        &program,
        &SimSettings::default(),
        &script,
        8_000,
    );
    let on = |t: u64| -> Vec<String> {
        let sample = report.at(t).expect("sampled");
        let mut on: Vec<String> = sample.outputs_on.iter().map(|s| s.symbol()).collect();
        on.sort();
        on
    };
    assert_eq!(on(590), ["fan", "heater", "y1+"]);
    assert_eq!(on(610), ["fan"], "only the fan runs on");
    assert_eq!(on(5_590), ["fan"]);
    assert!(on(5_620).is_empty(), "{:?}", on(5_620));
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(&path)
        .args(["--formats", "st", "-o"])
        .arg(&out)
        .assert()
        .success();
    let st = std::fs::read_to_string(out.join("heated/heated.st")).unwrap();
    assert!(
        st.contains("every coil and output off but fan (off after 5s)"),
        "{st}"
    );
    assert!(
        st.contains("run-on 1: the emergency stop finds fan on: it stays on 5s"),
        "{st}"
    );
}

/// `on halt | heater off, fan off after 5s`: the watchdog halts a machine
/// whose x11 died; the heater goes off at once and the fan 5 s later, so
/// the stall is safe; without the row it keeps both on, a hazard. An
/// output the emergency stop keeps on that a halt switches off is E030.
#[test]
fn a_halt_switches_the_heater_off_and_lets_the_fan_run_on() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("heated.xlsx");
    let table: &[&[&str]] = &[&["C1+1; Y:heater+; Y:fan+"], &["C1-0; Y:heater-; Y:fan-"]];
    let faults = |settings: &[&[&str]]| {
        write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
        let assert = steptable()
            .arg("faults")
            .arg(&path)
            .args(["--safety", "watchdog", "-o"])
            .arg(dir.path().join("out"))
            .assert()
            .success();
        line_with(&squeezed_stdout(&assert), "x11 open circuit")
    };
    let row = faults(&[&["on halt", "heater off, fan off after 5s"]]);
    assert!(row.contains(" safe stall at every moment alarm "), "{row}");
    let row = faults(&[&["scan time", "10ms"]]);
    assert!(
        row.contains("keeps heater, fan on (not hold-safe)"),
        "{row}"
    );
    let settings: &[&[&str]] = &[
        &["modes", "estop"],
        &["on estop", "fan hold"],
        &["on halt", "fan off after 5s"],
    ];
    write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
    steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .failure()
        .stderr(contains(
            "SETTINGS!B2: error[E030]: the emergency stop keeps fan on, but a halt switches it off",
        ));
}

/// Run-on timers share the table's 255 timers with its dwells: exactly 255
/// in all is accepted, one more is E030 at the row that asks for them
/// (cargo mutants survivors in the count).
#[test]
fn run_on_timers_and_dwells_share_the_timers() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("many.xlsx");
    let write = |dwells: usize| {
        let mut rows: Vec<Vec<String>> = vec![vec!["Y:heater+; Y:fan+; T=1s".to_string()]];
        rows.extend((0..dwells - 2).map(|_| vec!["T=1s".to_string()]));
        rows.push(vec!["Y:heater-; Y:fan-; T=1s".to_string()]);
        let table: Vec<Vec<&str>> = rows
            .iter()
            .map(|r| r.iter().map(String::as_str).collect())
            .collect();
        let table: Vec<&[&str]> = table.iter().map(Vec::as_slice).collect();
        let settings: &[&[&str]] = &[
            &["modes", "stop"],
            &["on stop", "heater off after 1s, fan off after 1s"],
        ];
        write_xlsx_sheets(
            &path,
            &[
                ("SEQUENTIAL CONTROL DESCRIPTION", &table),
                ("SETTINGS", settings),
            ],
        );
    };
    write(253);
    steptable().arg("check").arg(&path).assert().success();
    write(254);
    steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .failure()
        .stderr(contains(
            "error[E030]: 2 run-on timers and 254 dwells need more than the 255 timers a table may use",
        ));
}

/// A drive whose contactor `on stop` holds keeps its cut at the limit
/// switch: STOP while C1 runs towards its middle switch x11 lets it run on
/// to x11 and no further (before, the stop request was cleared and the
/// drive ran on to x12).
#[test]
fn a_held_drive_still_stops_at_its_limit_switch() {
    let mut build = Build::rows("t.csv", &[&["C1+1"], &["C1+2"], &["C1-0"]]).modes("stop,reset");
    let held = Signal::Coil {
        actuator: 1,
        sign: Sign::Plus,
    };
    build.settings.program.halt.on_stop = [(held, StopAction::Hold)].into();
    build
        .settings
        .simulation
        .machine
        .valves
        .per_actuator
        .insert(1, steptable::actuator::ActuatorKind::Motor);
    let (table, program) = (&build.table, build.program());
    let script = vec![
        (
            100,
            Operator {
                start: true,
                ..IDLE
            },
        ),
        (200, IDLE),
        // C1 runs 0 → 1 from about 0.1 s; STOP a little after.
        (300, Operator { stop: true, ..IDLE }),
        (400, IDLE),
    ];
    let report = scenario(table, &program, &build.settings.simulation, &script, 6_000);
    let end = &report.samples.last().unwrap();
    assert!(
        (end.positions[0] - 1.0).abs() < 0.1,
        "the held drive stops at its limit switch x11: {:?}",
        end.positions
    );
    assert!(
        end.outputs_on.is_empty(),
        "cut at the switch: {:?}",
        end.outputs_on
    );
}
