//! Step supervision with criteria analysis in the engines: the paper's
//! example converted with `--safety criteria`, x32 open circuit (step 5
//! waits for x32 and x22). The written program raises the timeout alarm
//! and lights x32's missing output, and x32's alone, in matiec (iec),
//! awlsim (siemens) and the FST interpreter (festo), and in the SCL and
//! RLL interpreters (the TIA Portal SCL, the Studio 5000 L5X), scan for
//! scan as simulated. The two stamping-like samples (the press station,
//! the drilling station) stall in step 2 with x21 dead (the gripper lift,
//! the drill feed never seen out) and name x21 missing in the same three
//! engines.

use steptable::convert;
use steptable::program::{Alarm, Signal};
use steptable::simulate::{Fault, Operator};

use crate::differential_native::{run_l5x, run_scl};
use crate::engines::{self, awlsim};
use crate::helpers::sample;
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "supervision::the_missing_condition_is_read_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        the_missing_condition_is_read_in_every_engine,
    ),
    Check::new(
        "supervision::the_press_stations_missing_sensor_is_read_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        the_press_stations_missing_sensor_is_read_in_every_engine,
    ),
    Check::new(
        "supervision::the_drilling_stations_missing_sensor_is_read_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        the_drilling_stations_missing_sensor_is_read_in_every_engine,
    ),
    Check::new(
        "supervision::manual_and_single_step_show_what_is_missing_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        manual_and_single_step_show_what_is_missing_in_every_engine,
    ),
];

/// A sample stalled by a dead sensor: the steps that fire before the
/// stall, how long the run lasts (past the watchdog's time), and whether
/// the native SCL and L5X programs run it too.
struct Stalled {
    stem: &'static str,
    dead: Signal,
    fired: &'static [usize],
    until_ms: u64,
    native: bool,
}

/// Sensor `position` of C`actuator`.
const fn sensor(actuator: u32, position: u32) -> Signal {
    Signal::Sensor { actuator, position }
}

/// START pressed from 0.5 s to 0.6 s.
fn script() -> Vec<(u64, Operator)> {
    let pressed = Operator {
        start: true,
        ..Operator::default()
    };
    vec![
        (0, Operator::default()),
        (500, pressed),
        (600, Operator::default()),
    ]
}

fn the_missing_condition_is_read_in_every_engine() {
    missing_sensor_is_read(&Stalled {
        stem: "paper_example",
        dead: sensor(3, 2),
        fired: &[1, 2, 3, 4],
        until_ms: 12_000,
        native: true,
    });
    eprintln!(
        "supervision: matiec, awlsim, the FST, SCL and RLL interpreters raise the timeout alarm of the paper's example with x32 stuck off and name x32, and only x32, missing, as simulated"
    );
}

/// The press station: step 1 waits for its part, step 2 lowers the
/// gripper and waits for x21 (its supervision time 2.2 s).
fn the_press_stations_missing_sensor_is_read_in_every_engine() {
    missing_sensor_is_read(&Stalled {
        stem: "press_station",
        dead: sensor(2, 1),
        fired: &[1, 2],
        until_ms: 6_000,
        native: false,
    });
    eprintln!(
        "supervision: matiec, awlsim and the FST interpreter raise the timeout alarm of the press station with x21 stuck off and name x21, and only x21, missing, as simulated"
    );
}

/// The drilling station: step 2 feeds the drill and waits for x21 (its
/// supervision time 3 s).
fn the_drilling_stations_missing_sensor_is_read_in_every_engine() {
    missing_sensor_is_read(&Stalled {
        stem: "drilling_station",
        dead: sensor(2, 1),
        fired: &[1, 2],
        until_ms: 7_000,
        native: false,
    });
    eprintln!(
        "supervision: matiec, awlsim and the FST interpreter raise the timeout alarm of the drilling station with x21 stuck off and name x21, and only x21, missing, as simulated"
    );
}

/// `stalled` converted with `--safety criteria`, its sensor dead, runs
/// START in every engine, and in the native programs' interpreters when
/// it says so.
fn missing_sensor_is_read(stalled: &Stalled) {
    let dir = tempfile::tempdir().unwrap();
    let input = sample(&format!("{}.xlsx", stalled.stem));
    let python = awlsim::python(&tool(Tool::Awlsim));
    let dead = stalled.dead;
    // Beside each engine's own file, the native programs of the two largest
    // PLC families: the TIA Portal SCL with its tag table (siemens), the
    // Studio 5000 L5X with its tags (iec), each in its interpreter.
    let runs = [
        ("iec", "st", "st,l5x,rockwell"),
        ("siemens", "awl", "awl,scl,tia"),
        ("festo", "fst", "fst"),
    ];
    for (target, format, native) in runs {
        let formats = if stalled.native { native } else { format };
        let args = ["--target", target, "--safety", "criteria"];
        let scenario = engines::Scenario {
            input: &input,
            out: dir.path().join(format),
            stem: stalled.stem,
            args: &args,
            formats,
            script: script(),
            until_ms: stalled.until_ms,
        };
        let label = format!(
            "{} {} with {} stuck off",
            stalled.stem,
            args.join(" "),
            dead.symbol()
        );
        let (case, report) = engines::record_scenario(&scenario, &label, |simulation| {
            simulation.faults = vec![Fault {
                signal: dead,
                stuck_at: false,
            }]
        });
        let fired = report.fired;
        // The simulation this engine must match: the steps before the
        // stall, then the next waits for the dead sensor until its
        // watchdog runs out.
        let steps: Vec<usize> = fired.iter().map(|(_, s)| *s).collect();
        assert_eq!(steps, stalled.fired, "{}: {fired:?}", case.label);
        let outputs = engines::run_written(&case, format, &python);
        case.check(format, outputs).unwrap();
        match (target, stalled.native) {
            ("siemens", true) => case.check_stepped("scl", run_scl(&case)).unwrap(),
            ("iec", true) => case.check_stepped("l5x", run_l5x(&case)).unwrap(),
            _ => {}
        }
        // The engine's outputs are the trace's: at the end the alarm and
        // the dead sensor's missing output are on, no other missing output.
        let checked = convert::check_path(&input, &engines::settings_for(&args)).unwrap();
        let program = convert::build_program(&checked.table, &checked.settings);
        let signals = &case.trace.signals.outputs;
        let last = &case.trace.scans.last().unwrap().outputs;
        let on: Vec<Signal> = signals
            .iter()
            .zip(last)
            .filter(|(s, on)| **on && matches!(s, Signal::Missing(_) | Signal::Alarm(_)))
            .map(|(s, _)| *s)
            .collect();
        let n = program
            .criteria
            .iter()
            .position(|c| c.signal == dead)
            .unwrap();
        assert_eq!(
            on,
            [Signal::Alarm(Alarm::Timeout), Signal::Missing(n as u16 + 1)],
            "{}",
            case.label
        );
    }
}

/// The criteria beside the commissioning modes (rt7 F14, F15), in matiec,
/// awlsim and the FST interpreter as simulated: the paper's example with
/// x23 dead stalls in step 2, and MAN_MODE turned on at 7 s clears its
/// `miss` output (manual awaits no transition) and keeps the alarm; in
/// single step, one STEP_PB press fires step 1, and the step waiting for
/// the next press runs out of time naming "STEP_MODE off" missing.
fn manual_and_single_step_show_what_is_missing_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let input = sample("paper_example.xlsx");
    let python = awlsim::python(&tool(Tool::Awlsim));
    let press = |operator: Operator| Operator {
        start: true,
        ..operator
    };
    let manual = Operator {
        manual: true,
        ..Operator::default()
    };
    let stepping = Operator {
        step_mode: true,
        ..Operator::default()
    };
    let cases = [
        (
            "manual",
            Some(sensor(2, 3)),
            vec![
                (0, Operator::default()),
                (500, press(Operator::default())),
                (600, Operator::default()),
                (7_000, manual),
            ],
        ),
        (
            "step",
            None,
            vec![
                (0, stepping),
                (500, press(stepping)),
                (600, stepping),
                (
                    1_000,
                    Operator {
                        step: true,
                        ..stepping
                    },
                ),
                (1_100, stepping),
            ],
        ),
    ];
    for (modes, dead, script) in cases {
        for (target, format) in [("iec", "st"), ("siemens", "awl"), ("festo", "fst")] {
            let args = ["--target", target, "--safety", "criteria", "--modes", modes];
            let scenario = engines::Scenario {
                input: &input,
                out: dir.path().join(format!("{modes}-{format}")),
                stem: "paper_example",
                args: &args,
                formats: format,
                script: script.clone(),
                until_ms: 8_000,
            };
            let label = format!("paper_example {}", args.join(" "));
            let (case, _) = engines::record_scenario(&scenario, &label, |simulation| {
                simulation.faults = dead
                    .map(|signal| Fault {
                        signal,
                        stuck_at: false,
                    })
                    .into_iter()
                    .collect()
            });
            let outputs = engines::run_written(&case, format, &python);
            case.check(format, outputs).unwrap();
            let signals = &case.trace.signals.outputs;
            let last = &case.trace.scans.last().unwrap().outputs;
            let misses = signals
                .iter()
                .zip(last)
                .filter(|(s, on)| **on && matches!(s, Signal::Missing(_)))
                .count();
            let alarm = signals
                .iter()
                .zip(last)
                .any(|(s, on)| *on && *s == Signal::Alarm(Alarm::Timeout));
            assert!(alarm, "{}", case.label);
            assert_eq!(misses, usize::from(modes == "step"), "{}", case.label);
        }
    }
    eprintln!(
        "supervision: matiec, awlsim and the FST interpreter clear the missing outputs in manual and name STEP_MODE missing in single step, as simulated"
    );
}
