//! Operating modes in simulation: STOP, EMERGENCY STOP, RESET and continuous
//! operation, run as scripts of button presses against the paper's example.

use predicates::prelude::PredicateBooleanExt;
use steptable::program::{Modes, Signal, StepProgram};
use steptable::settings::Settings;
use steptable::simulate::scenario::{ScenarioReport, scenario};
use steptable::simulate::{Operator, SimSettings};
use steptable::table::{StepTable, from_rows};

use crate::helpers::Build;

fn paper() -> StepTable {
    Build::paper().table
}

fn program_with(table: &StepTable, modes: &str) -> StepProgram {
    Build {
        table: table.clone(),
        settings: Settings::new(),
    }
    .modes(modes)
    .program()
}

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

fn press(at: u64, button: Operator) -> Vec<(u64, Operator)> {
    vec![(at, button), (at + 100, IDLE)]
}

fn start() -> Operator {
    Operator {
        start: true,
        ..IDLE
    }
}

fn all_home(report: &ScenarioReport, time_ms: u64) -> bool {
    report
        .at(time_ms)
        .expect("sampled")
        .positions
        .iter()
        .all(|p| p.abs() < 0.05)
}

fn coils_on(report: &ScenarioReport, time_ms: u64) -> Vec<Signal> {
    report
        .at(time_ms)
        .expect("sampled")
        .outputs_on
        .iter()
        .copied()
        .filter(|s| matches!(s, Signal::Coil { .. } | Signal::SingleCoil { .. }))
        .collect()
}

/// The last step of the paper's example fires at the end of a cycle.
fn last_step_times(report: &ScenarioReport) -> Vec<u64> {
    report
        .fired
        .iter()
        .filter(|(_, step)| *step == 8)
        .map(|(t, _)| *t)
        .collect()
}

#[test]
fn continuous_operation_repeats_identical_cycles_until_switched_off() {
    let table = paper();
    let program = program_with(&table, "continuous,stop");
    let on = Operator {
        continuous: true,
        ..IDLE
    };
    // CONTINUOUS on alone starts nothing: START does.
    let script = vec![
        (0, on),
        (2_000, Operator { start: true, ..on }),
        (2_100, on),
        (33_000, IDLE),
    ];
    let report = scenario(&table, &program, &SimSettings::default(), &script, 45_000);
    let starts = report.cycle_starts();
    assert!(starts[0] >= 2_000, "no cycle before START: {starts:?}");
    assert!(starts.len() >= 3, "cycles repeat: {starts:?}");
    let periods: Vec<u64> = starts.windows(2).map(|w| w[1] - w[0]).collect();
    // The first cycle starts from rest; every later one starts the scan its
    // predecessor ended, with the last piston just settling on its end stop,
    // and from then on the cycles repeat to the scan.
    assert!(
        periods[1..].iter().all(|p| *p == periods[1]),
        "every cycle takes the same time: {periods:?}"
    );
    assert!(periods[0].abs_diff(periods[1]) <= 10, "{periods:?}");
    let offsets = |from: u64, to: u64| -> Vec<(u64, usize)> {
        report
            .fired
            .iter()
            .filter(|(t, _)| *t >= from && *t < to)
            .map(|(t, s)| (t - from, *s))
            .collect()
    };
    assert_eq!(
        offsets(starts[1], starts[2]),
        offsets(starts[2], starts[3]),
        "the same steps at the same times in every cycle"
    );
    // Switched off at 33 s: the cycle under way ends, no other starts.
    let last = *starts.last().unwrap();
    assert!(last < 33_000, "{starts:?}");
    assert!(all_home(&report, 44_000));
    assert_eq!(
        last_step_times(&report).len(),
        starts.len(),
        "every cycle started was finished"
    );
}

#[test]
fn stop_mid_cycle_finishes_the_cycle_and_halts() {
    let table = paper();
    let program = program_with(&table, "continuous,stop");
    let on = Operator {
        continuous: true,
        ..IDLE
    };
    let mut script = vec![(0, on), (500, Operator { start: true, ..on }), (600, on)];
    // STOP pressed for 0.2 s in the middle of the first cycle.
    script.push((3_000, Operator { stop: true, ..on }));
    script.push((3_200, on));
    let report = scenario(&table, &program, &SimSettings::default(), &script, 20_000);
    assert_eq!(report.cycle_starts().len(), 1, "{:?}", report.fired);
    let ends = last_step_times(&report);
    assert_eq!(ends.len(), 1, "the cycle finished: {:?}", report.fired);
    assert!(ends[0] > 3_200);
    assert!(all_home(&report, 19_000));
    // START again: one more cycle, and continuous operation resumes.
    script.push((20_000, Operator { start: true, ..on }));
    script.push((20_100, on));
    let report = scenario(&table, &program, &SimSettings::default(), &script, 40_000);
    assert!(
        report.cycle_starts().len() >= 3,
        "{:?}",
        report.cycle_starts()
    );
}

#[test]
fn emergency_stop_cuts_every_coil_within_one_scan_and_blocks_start_until_reset() {
    let table = paper();
    let program = program_with(&table, "estop,reset");
    let settings = SimSettings::default();
    let mut script = press(500, start());
    // ESTOP at 1.0 s, while C1 extends (step 1), held for 0.5 s.
    script.push((
        1_000,
        Operator {
            estop: true,
            ..IDLE
        },
    ));
    script.push((1_500, IDLE));
    // START is refused while the emergency stop is latched.
    script.extend(press(3_000, start()));
    // RESET homes everything; then START runs a full cycle again.
    script.extend(press(
        5_000,
        Operator {
            reset: true,
            ..IDLE
        },
    ));
    script.extend(press(9_000, start()));
    let report = scenario(&table, &program, &settings, &script, 20_000);

    assert!(
        !coils_on(&report, 990).is_empty(),
        "C1 was moving before the stop"
    );
    let scan = settings.scan_ms as u64;
    assert_eq!(
        coils_on(&report, 1_000 + scan),
        Vec::<Signal>::new(),
        "every coil off one scan after ESTOP"
    );
    assert!(
        report.fired.iter().all(|(t, _)| *t < 1_000 || *t >= 5_000),
        "nothing fires between ESTOP and RESET: {:?}",
        report.fired
    );
    assert!(report.at(5_000 + 3_000).is_some_and(|s| !s.homing));
    assert!(
        all_home(&report, 8_000),
        "RESET brought every actuator home"
    );
    let starts = report.cycle_starts();
    assert_eq!(starts.len(), 2, "{starts:?}");
    assert!(starts[1] >= 9_000);
    assert_eq!(
        last_step_times(&report).len(),
        1,
        "the cycle after RESET completes"
    );
}

#[test]
fn reset_brings_every_actuator_home_from_any_step() {
    let table = paper();
    let program = program_with(&table, "estop,reset");
    let settings = SimSettings::default();
    // When each step fires in an undisturbed cycle started at 0.5 s.
    let plain = scenario(&table, &program, &settings, &press(500, start()), 10_000);
    for step in 1..=8usize {
        let fired_at = plain
            .fired
            .iter()
            .find(|(_, s)| *s == step)
            .map(|(t, _)| *t)
            .expect("the step fires");
        // Stop half-way through the step's moves, then RESET.
        let stop_at = fired_at + 300;
        let mut script = press(500, start());
        script.push((
            stop_at,
            Operator {
                estop: true,
                ..IDLE
            },
        ));
        script.push((stop_at + 200, IDLE));
        script.extend(press(
            stop_at + 1_000,
            Operator {
                reset: true,
                ..IDLE
            },
        ));
        script.extend(press(stop_at + 8_000, start()));
        let report = scenario(&table, &program, &settings, &script, stop_at + 18_000);
        assert!(
            all_home(&report, stop_at + 7_900),
            "home after RESET from step {step}: {:?}",
            report.at(stop_at + 7_900)
        );
        assert!(report.at(stop_at + 7_900).is_some_and(|s| !s.homing));
        assert_eq!(
            last_step_times(&report)
                .iter()
                .filter(|t| **t > stop_at + 8_000)
                .count(),
            1,
            "a full cycle after homing from step {step}"
        );
    }
}

#[test]
fn default_home_order_is_the_cycles_own_return_order() {
    let table = paper();
    let modes = Modes::parse("reset").unwrap();
    // C2, C3 and C4's last moves are in step 7, C1's in step 8: the cycle
    // returns C2-C4 first, and so does RESET.
    assert_eq!(
        modes.home_stages(&table).unwrap(),
        vec![vec![2, 3, 4], vec![1]]
    );
    let custom = Modes {
        home_order: Some(vec![vec![3, 4], vec![2], vec![1]]),
        ..modes.clone()
    };
    assert_eq!(
        custom.home_stages(&table).unwrap(),
        vec![vec![3, 4], vec![2], vec![1]]
    );
    let missing = Modes {
        home_order: Some(vec![vec![1], vec![2]]),
        ..modes
    };
    assert!(
        missing
            .home_stages(&table)
            .unwrap_err()
            .contains("leaves out C3")
    );
}

/// What an EMERGENCY STOP in the middle of a stroke does, per valve type:
/// every coil goes off, and the valve decides what the piston does then.
#[test]
fn emergency_stop_mid_stroke_shows_what_each_valve_type_does() {
    use steptable::actuator::ActuatorKind;
    let table = from_rows("one.csv", &[["C1+1"], ["C1-0"]]).unwrap();
    let mut seen = Vec::new();
    for valve in ActuatorKind::ALL {
        let mut settings = SimSettings::default();
        settings.machine.valves.per_actuator.insert(1, valve);
        // A light load: a centre valve drifts 1 % of the stroke per second.
        settings.machine.loads.insert(1, 0.01);
        settings.machine.strokes.per_actuator.insert(
            1,
            steptable::stroke::Stroke {
                extend_ms: 2000,
                retract_ms: 2000,
            },
        );
        let program = Build::rows("one.csv", &[["C1+1"], ["C1-0"]])
            .simulation(settings.clone())
            .modes("estop")
            .program();
        // START at 0.5 s; ESTOP at 1.5 s, half-way out; held from then on.
        let mut script = press(500, start());
        script.push((
            1_500,
            Operator {
                estop: true,
                ..IDLE
            },
        ));
        let report = scenario(&table, &program, &settings, &script, 5_000);
        let at_stop = report.at(1_500).unwrap().positions[0];
        let later = report.at(4_900).unwrap().positions[0];
        assert!((0.4..0.6).contains(&at_stop), "{valve}: {at_stop}");
        seen.push((valve, at_stop, later));
    }
    let after = |v: ActuatorKind| seen.iter().find(|(t, ..)| *t == v).unwrap().2;
    // The bistable valve keeps its last position: the stroke goes on to the end.
    assert!(after(ActuatorKind::Bistable52) > 0.99, "{seen:?}");
    // The spring returns the single-solenoid valve: the piston goes home.
    assert!(after(ActuatorKind::Mono52) < 0.01, "{seen:?}");
    // A closed centre locks the air in: the piston stays where it was.
    let closed = seen
        .iter()
        .find(|(t, ..)| *t == ActuatorKind::Closed53)
        .unwrap();
    assert!((closed.2 - closed.1).abs() < 0.01, "{seen:?}");
    // An exhausted centre lets the load pull it home; a pressurised one creeps out.
    assert!(after(ActuatorKind::Exhaust53) < closed.2, "{seen:?}");
    assert!(after(ActuatorKind::Pressure53) > closed.2, "{seen:?}");
}

/// The fault table treats the mode inputs like sensors: a broken STOP or
/// EMERGENCY STOP wire at power-up stops the machine safely, it never
/// starts it. Broken mid-cycle, the EMERGENCY STOP wire does what pressing
/// it does: every output off, and a piston on a bistable valve runs on.
#[test]
fn broken_stop_and_emergency_stop_wires_are_safe_stalls() {
    use steptable::faults::{self, Outcome, Phase};
    let table = paper();
    let program = program_with(&table, "all");
    let fault_table = faults::analyse(&table, &program, &SimSettings::default(), 1);
    let case = |signal: Signal, stuck_at: bool| {
        fault_table
            .cases
            .iter()
            .find(|c| c.faults[0].signal == signal && c.faults[0].stuck_at == stuck_at)
            .expect("every mode input is in the fault table")
    };
    assert_eq!(fault_table.moments[0].phase, Phase::PowerUp);
    let outcome = |signal, stuck_at| case(signal, stuck_at).outcome;
    assert_eq!(outcome(Signal::Stop, false), Outcome::SafeStall);
    assert_eq!(case(Signal::EStop, false).outcomes[0], Outcome::SafeStall);
    let estop = case(Signal::EStop, false);
    assert_eq!(estop.outcome, Outcome::Hazard);
    assert!(
        estop.explanation.contains("C4 at x41") && estop.explanation.contains("collision risk"),
        "C4's bistable valve keeps it going: {}",
        estop.explanation
    );
    assert_eq!(outcome(Signal::Reset, true), Outcome::Hazard);
    // RESET acts on its press: shorted at power-up it never presses.
    assert_eq!(case(Signal::Reset, true).outcomes[0], Outcome::NoEffect);
    for (signal, stuck_at) in [
        (Signal::Stop, true),
        (Signal::EStop, true),
        (Signal::Reset, false),
    ] {
        assert_eq!(outcome(signal, stuck_at), Outcome::NoEffect, "{signal:?}");
    }
    // A CONTINUOUS switch stuck on restarts the machine by itself.
    assert_eq!(outcome(Signal::Continuous, true), Outcome::Hazard);
}

/// `--home-order` through the binary, in every command that takes it: the
/// stages land in the program as given, and an order that leaves out a
/// cylinder is E030 (it once panicked for every value).
#[test]
fn home_order_flag_through_the_binary() {
    let dir = tempfile::tempdir().unwrap();
    let sample = crate::helpers::sample("paper_example.xlsx");
    crate::helpers::steptable()
        .arg("convert")
        .arg(&sample)
        .args([
            "--modes",
            "reset",
            "--home-order",
            "C1, C2&C3, C4",
            "--formats",
            "st",
            "-o",
        ])
        .arg(dir.path())
        .assert()
        .success();
    let st = std::fs::read_to_string(dir.path().join("paper_example/paper_example.st")).unwrap();
    assert!(st.contains("(* homing stage 1: C1 home *)"), "{st}");
    assert!(st.contains("(* homing stage 2: C2, C3 home *)"), "{st}");
    assert!(st.contains("(* homing stage 3: C4 home *)"), "{st}");
    for command in ["check", "simulate", "faults"] {
        let mut cmd = crate::helpers::steptable();
        cmd.arg(command)
            .arg(&sample)
            .args(["--modes", "reset", "--home-order", "C4&C3, C2, C1"]);
        if command == "faults" {
            cmd.arg("-o").arg(dir.path().join("faults"));
        }
        cmd.assert().success();
        crate::helpers::steptable()
            .arg(command)
            .arg(&sample)
            .args(["--modes", "reset", "--home-order", "C2, C1"])
            .assert()
            .code(1)
            .stderr(
                predicates::str::contains("E030").and(predicates::str::contains("leaves out C3")),
            );
    }
}

/// A home order is checked even when the reset mode that uses it is off
/// (a typo must not wait until the engineer adds reset), and a valid one
/// without reset is said to have no effect (W006), not silently dropped.
#[test]
fn a_home_order_without_reset_is_checked_and_said_to_have_no_effect() {
    let sample = crate::helpers::sample("paper_example.xlsx");
    crate::helpers::steptable()
        .args(["check"])
        .arg(&sample)
        .args(["--home-order", "C9"])
        .assert()
        .code(1)
        .stderr(predicates::str::contains(
            "error[E030]: the home order names C9",
        ));
    crate::helpers::steptable()
        .args(["check"])
        .arg(&sample)
        .args(["--home-order", "C4&C3, C2, C1"])
        .assert()
        .success()
        .stderr(predicates::str::contains("warning[W006]").and(predicates::str::contains("reset")));
    crate::helpers::steptable()
        .args(["check"])
        .arg(&sample)
        .args(["--modes", "reset", "--home-order", "C4&C3, C2, C1"])
        .assert()
        .success()
        .stderr(predicates::str::contains("W006").not());
}
