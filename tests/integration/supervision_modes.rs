//! Step supervision beside the commissioning modes (red team rt7, F13–F15):
//! manual mode awaits no transition, so no `miss` output stays on in it;
//! a step that runs out of time waiting for STEP_PB names the press
//! missing; and a step the watchdog does not
//! time (it waits on a machine input) says which moves go unsupervised.

use steptable::program::{Alarm, Literal, Signal, StepProgram};
use steptable::simulate::scenario::{ScenarioReport, scenario};
use steptable::simulate::{Fault, Operator, SimSettings};

use crate::helpers::Build;

/// x23 (C2 at position 3) dead: step 2 never ends.
fn x23_dead() -> SimSettings {
    SimSettings {
        faults: vec![Fault {
            signal: Signal::Sensor {
                actuator: 2,
                position: 3,
            },
            stuck_at: false,
        }],
        ..SimSettings::default()
    }
}

fn run(
    modes: &str,
    simulation: SimSettings,
    script: &[(u64, Operator)],
    until_ms: u64,
) -> (StepProgram, ScenarioReport) {
    let build = Build::paper()
        .modes(modes)
        .safety("criteria".parse().unwrap())
        .simulation(simulation.clone());
    let program = build.program();
    let report = scenario(&build.table, &program, &simulation, script, until_ms);
    (program, report)
}

fn on_at(report: &ScenarioReport, time_ms: u64) -> &[Signal] {
    let sample = report
        .samples
        .iter()
        .rev()
        .find(|s| s.time_ms <= time_ms)
        .expect("a sample by then");
    &sample.outputs_on
}

fn misses(on: &[Signal]) -> usize {
    on.iter()
        .filter(|s| matches!(s, Signal::Missing(_)))
        .count()
}

const ALARM: Signal = Signal::Alarm(Alarm::Timeout);

/// The stall's alarm and x23's `miss` are on; MAN_MODE turned on clears
/// the `miss` output (no transition is awaited in manual) and keeps the
/// alarm, which waits for RESET. It used to keep `miss` on all through
/// manual, against the guide's "no `miss` output is on".
#[test]
fn manual_mode_shows_no_missing_condition() {
    let start = Operator {
        start: true,
        ..Operator::default()
    };
    let manual = Operator {
        manual: true,
        ..Operator::default()
    };
    let script = [
        (0, Operator::default()),
        (500, start),
        (600, Operator::default()),
        (7_000, manual),
    ];
    let (_, report) = run("manual,reset", x23_dead(), &script, 8_000);
    let stalled = on_at(&report, 6_900);
    assert!(stalled.contains(&ALARM), "{stalled:?}");
    assert_eq!(misses(stalled), 1, "{stalled:?}");
    let in_manual = on_at(&report, 8_000);
    assert!(in_manual.contains(&ALARM), "{in_manual:?}");
    assert_eq!(misses(in_manual), 0, "{in_manual:?}");
}

/// Single step: START, one STEP_PB press fires step 1, then no press.
/// Step 1's supervision time runs out while it waits for the press, and
/// the one `miss` output on is "STEP_MODE off" (the step waits for
/// STEP_PB): the alarm names its cause. It used to name nothing (rt7
/// F15). The same alarm catches a STEP_MODE selector stuck on.
#[test]
fn a_step_waiting_for_its_press_names_the_press_missing() {
    let stepping = Operator {
        step_mode: true,
        ..Operator::default()
    };
    let script = [
        (0, stepping),
        (
            500,
            Operator {
                start: true,
                ..stepping
            },
        ),
        (600, stepping),
        (
            1_000,
            Operator {
                step: true,
                ..stepping
            },
        ),
        (1_100, stepping),
    ];
    let (program, report) = run("step", SimSettings::default(), &script, 8_000);
    let fired: Vec<usize> = report.fired.iter().map(|(_, s)| *s).collect();
    assert_eq!(fired, [1], "one press, one step");
    let end = on_at(&report, 8_000);
    assert!(end.contains(&ALARM), "{end:?}");
    let missing: Vec<Literal> = end
        .iter()
        .filter_map(|s| match s {
            Signal::Missing(n) => Some(program.criteria[usize::from(*n) - 1]),
            _ => None,
        })
        .collect();
    assert_eq!(missing, [Literal::not(Signal::StepMode)], "{end:?}");
    // In automatic the criterion is met: a stall names its sensor alone.
    let automatic = [
        (0, Operator::default()),
        (
            500,
            Operator {
                start: true,
                ..Operator::default()
            },
        ),
        (600, Operator::default()),
    ];
    let (_, stalled) = run("step", x23_dead(), &automatic, 8_000);
    assert_eq!(misses(on_at(&stalled, 8_000)), 1);
}

/// A step that waits on a machine input is not timed by the watchdog, nor
/// the moves it makes in any branch: W009 at the wait's cell, naming them.
/// A supervision time for the step, or no watchdog, and nothing is said.
#[test]
fn a_waiting_step_s_unsupervised_moves_are_said() {
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("w.csv");
    std::fs::write(
        &table,
        ",BRANCH 1,BRANCH 2\nSTEP 1,C1+1,I:part\nSTEP 2,C2+1,\nSTEP 3,C1-0,C2-0\n",
    )
    .unwrap();
    let check = |args: &[&str]| {
        let out = crate::helpers::steptable()
            .arg("check")
            .arg(&table)
            .args(args)
            .output()
            .unwrap();
        assert!(out.status.success(), "{out:?}");
        String::from_utf8(out.stderr).unwrap()
    };
    let said = check(&["--safety", "watchdog"]);
    let line = said
        .lines()
        .find(|l| l.contains("W009"))
        .unwrap_or_else(|| panic!("W009: {said}"));
    assert!(line.contains("w.csv:2:3"), "at the wait's cell: {line}");
    assert!(line.contains("step 1 waits for I:part"), "{line}");
    assert!(line.contains("move C1+1 is not supervised"), "{line}");
    assert!(line.contains("--supervision 1="), "{line}");
    assert_eq!(said.matches("W009").count(), 1, "{said}");
    for quiet in [
        &["--safety", "watchdog", "--supervision", "1=20s"][..],
        &["--safety", "edge"][..],
    ] {
        assert!(!check(quiet).contains("W009"), "{quiet:?}");
    }
}
