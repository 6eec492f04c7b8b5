//! RESET's default homing order is the cycle's own return order: a stamping
//! station whose cycle lifts the punch before it opens the clamp must not
//! release the part under the tool when RESET homes it mid-cycle.

use steptable::simulate::scenario::{ScenarioReport, scenario};
use steptable::simulate::{Operator, SimSettings};
use steptable::table::from_rows;

use crate::helpers::{Build, steptable};

/// Clamp C1, punch C2 with a dwell, ejector C3, feeder C4.
const STAMPING: [&str; 9] = [
    "C1+1", "C2+1", "T=2s", "C2-0", "C1-0", "C3+1", "C3-0", "C4+1", "C4-0",
];

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

fn position(report: &ScenarioReport, time_ms: u64, actuator: usize) -> f64 {
    report.at(time_ms).expect("sampled").positions[actuator]
}

#[test]
fn reset_lifts_the_punch_before_it_opens_the_clamp() {
    let rows: Vec<Vec<String>> = STAMPING.iter().map(|c| vec![c.to_string()]).collect();
    let table = from_rows("stamping.csv", &rows).unwrap();
    let build = Build {
        table: table.clone(),
        settings: steptable::settings::Settings::new(),
    }
    .modes("estop,reset");
    let program = build.program();
    let settings = SimSettings::default();
    // START at 0.5 s; C1 clamps (1 s), C2 punches (1 s), then 2 s dwell:
    // at 3.5 s the punch is down in the dwell. ESTOP there, RESET after.
    let script = vec![
        (
            500,
            Operator {
                start: true,
                ..IDLE
            },
        ),
        (600, IDLE),
        (
            3_500,
            Operator {
                estop: true,
                ..IDLE
            },
        ),
        (3_700, IDLE),
        (
            4_000,
            Operator {
                reset: true,
                ..IDLE
            },
        ),
        (4_100, IDLE),
    ];
    let report = scenario(&table, &program, &settings, &script, 10_000);
    assert!(
        position(&report, 3_500, 0) > 0.95 && position(&report, 3_500, 1) > 0.95,
        "clamped and punched before the stop: {:?}",
        report.at(3_500)
    );
    // The first moment after RESET at which the clamp has left its end.
    let opened = report
        .samples
        .iter()
        .find(|s| s.time_ms > 4_000 && s.positions[0] < 0.95)
        .expect("RESET opens the clamp");
    assert!(
        opened.positions[1] < 0.05,
        "the clamp opened at {} ms with the punch at {:.2}",
        opened.time_ms,
        opened.positions[1]
    );
    assert!(position(&report, 9_900, 0) < 0.05 && position(&report, 9_900, 1) < 0.05);
}

/// The order RESET homes in is written into the program as its comment.
#[test]
fn the_programs_say_the_homing_order() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("stamping.csv");
    std::fs::write(&csv, STAMPING.join("\n")).unwrap();
    steptable()
        .args(["convert", "--modes", "all", "--formats", "st", "-o"])
        .arg(dir.path().join("out"))
        .arg(&csv)
        .assert()
        .success();
    let st = std::fs::read_to_string(dir.path().join("out/stamping/stamping.st")).unwrap();
    let stage = |text: &str| st.find(text).unwrap_or_else(|| panic!("{text} in {st}"));
    assert!(stage("homing stage 1: C2 home") < stage("homing stage 2: C1 home"));
}

/// A home order that names an actuator twice says which one.
#[test]
fn a_home_order_naming_an_actuator_twice_says_which() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .args([
            "convert",
            "--modes",
            "all",
            "--home-order",
            "C2&C3&C4, C1, C3",
            "-o",
        ])
        .arg(dir.path().join("out"))
        .arg(crate::helpers::sample("paper_example.csv"))
        .assert()
        .code(1)
        .stderr(predicates::str::contains(
            "error[E030]: the home order names C3 twice",
        ));
    assert!(!dir.path().join("out").exists());
}

/// RESET does not home behind an open guard: a whole-cycle interlock opens
/// mid-cycle (the machine halts), RESET is pressed with it still open, and
/// no homing coil comes on; nor does a step start a move in the scan the
/// guard opens. Closed again, the next RESET homes.
#[test]
fn reset_does_not_home_behind_an_open_guard() {
    use steptable::program::Signal;
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("guarded.xlsx");
    let table: &[&[&str]] = &[&["C1+1"], &["C2+1"], &["C2-0"], &["C1-0"]];
    let settings: &[&[&str]] = &[
        &["interlock", "guard"],
        &["modes", "reset"],
        &["de-energise on halt", "C1, C2"],
    ];
    crate::helpers::write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
    let build = Build::path(&path);
    let program = build.program();
    let mut simulation = build.settings.simulation.clone();
    // The guard opens at 1.8 s (C2 on its way out) and stays open.
    simulation.faults = vec![steptable::simulate::Fault {
        signal: Signal::MachineInput(steptable::cell::Name::new("guard").unwrap()),
        stuck_at: false,
    }];
    simulation.fault_onset_ms = 1_800;
    let press = |at: u64, operator: Operator| [(at, operator), (at + 100, IDLE)];
    let script = [
        press(
            500,
            Operator {
                start: true,
                ..IDLE
            },
        ),
        press(
            3_000,
            Operator {
                reset: true,
                ..IDLE
            },
        ),
    ]
    .concat();
    let report = scenario(&build.table, &program, &simulation, &script, 8_000);
    let homing_coils = [
        Signal::Coil {
            actuator: 1,
            sign: steptable::cell::Sign::Minus,
        },
        Signal::Coil {
            actuator: 2,
            sign: steptable::cell::Sign::Minus,
        },
    ];
    let driven: Vec<u64> = report
        .samples
        .iter()
        .filter(|s| s.time_ms >= 3_000 && s.outputs_on.iter().any(|o| homing_coils.contains(o)))
        .map(|s| s.time_ms)
        .collect();
    assert!(
        driven.is_empty(),
        "homing coils on behind the open guard at {driven:?} ms"
    );
    assert!(
        report
            .samples
            .iter()
            .filter(|s| s.time_ms >= 3_000)
            .all(|s| !s.homing),
        "RESET with the guard open does not start homing"
    );
    // Healthy guard: the same RESET homes.
    simulation.faults.clear();
    let script = [
        press(
            500,
            Operator {
                start: true,
                ..IDLE
            },
        ),
        press(
            1_800,
            Operator {
                reset: true,
                ..IDLE
            },
        ),
    ]
    .concat();
    let report = scenario(&build.table, &program, &simulation, &script, 8_000);
    assert!(
        report.samples.iter().any(|s| s.homing),
        "RESET homes with the guard closed"
    );
}

/// The template workbook tells the engineer the same default: its SETTINGS
/// help for `home order` (cell D20, and the note on B20) is the cycle's own
/// return order, not the reverse of the last moves it once said; and the
/// halt rows name every halt the guide names (an interlock too).
#[test]
fn the_templates_help_says_the_default_home_order() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.xlsx");
    steptable()
        .arg("template")
        .arg("-o")
        .arg(&path)
        .assert()
        .success();
    let settings = crate::helpers::read_sheet(&path, "SETTINGS");
    let help = |label: &str| {
        let row = settings.iter().position(|r| r[0] == label).unwrap();
        (row, settings[row][3].clone())
    };
    let (row, home) = help("home order");
    assert_eq!(row, 19, "D20");
    assert!(
        home.contains("default: the order the cycle itself returns the actuators home (each actuator's last move, earliest first"),
        "{home}"
    );
    assert!(!home.contains("reverse"), "{home}");
    let (_, halt) = help("de-energise on halt");
    assert!(halt.contains("an interlock"), "{halt}");
    for label in ["hold on estop", "on estop"] {
        let (_, text) = help(label);
        assert!(
            text.contains("a valve coil or a drive is refused"),
            "{label}: {text}"
        );
    }
}

/// A machine without actuators (the oven: a horn, a heater, a fan) has
/// nothing to home: RESET after the EMERGENCY STOP leaves it ready, and
/// START runs the next cycle. It used to wait for a homing that never
/// ended, so START was ignored for good.
#[test]
fn reset_on_a_machine_without_actuators_makes_it_ready_at_once() {
    let oven = crate::helpers::sample("oven.xlsx");
    let out = steptable()
        .arg("simulate")
        .arg(&oven)
        .args(["--modes", "stop,estop,reset"])
        .args(["--press", "START@0.5s", "--press", "ESTOP@step1"])
        .args(["--press", "RESET@+1s", "--press", "START@step0"])
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let out = String::from_utf8(out).unwrap();
    assert!(out.contains("homing done"), "{out}");
    let cycles = out.lines().filter(|l| l.contains("step 1 ")).count();
    assert_eq!(cycles, 2, "a second cycle after RESET: {out}");
    let converted = steptable()
        .arg("convert")
        .arg(&oven)
        .args(["--modes", "stop,estop,reset", "--formats", "st", "-o"])
        .arg(tempfile::tempdir().unwrap().path())
        .assert()
        .success()
        .get_output()
        .stdout
        .clone();
    let converted = String::from_utf8(converted).unwrap();
    assert!(
        converted.contains("no actuator to home, the machine is ready at once"),
        "{converted}"
    );
}
