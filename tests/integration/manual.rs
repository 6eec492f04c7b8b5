//! Manual mode (`--modes manual`, in `all`) in simulation: the MAN_MODE
//! selector ends the automatic cycle, each actuator of the paper's example
//! moves while its jog button is held, a forbidden jog (both buttons of one
//! cylinder, any jog under the EMERGENCY STOP) moves nothing, and back in
//! automatic the cycle starts after RESET. The events are those of
//! `tests/fixtures/manual_scenario.txt`, which the engines replay
//! (tests/tools/manual.rs). The hostile inputs of the mode, through the
//! binary, are at the end.

use steptable::program::{Signal, StepProgram};
use steptable::simulate::scenario::{ScenarioReport, events, scenario_events};
use steptable::table::StepTable;

use crate::helpers::{Build, Refused, assert_refused, root, steptable};

/// The fixture's events: `(option, text)`.
pub fn fixture_events() -> Vec<(String, String)> {
    let path = root().join("tests/fixtures/manual_scenario.txt");
    let text = std::fs::read_to_string(path).expect("the manual scenario");
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            let (option, event) = l.split_once(' ').expect("OPTION TEXT");
            (option.to_string(), event.to_string())
        })
        .collect()
}

fn run(build: &Build, written: &[(String, String)]) -> (StepTable, StepProgram, ScenarioReport) {
    let program = build.program();
    let table = &build.table;
    let parsed: Vec<_> = written
        .iter()
        .map(|(o, t)| events::parse(o, t, &program, table, &build.settings.naming))
        .collect::<Result<_, _>>()
        .expect("valid events");
    assert!(events::check(&parsed, 10).is_empty());
    let sim = &build.settings.simulation;
    let (report, _) = scenario_events(table, &program, sim, &parsed, (8_000, 60_000), None);
    (build.table.clone(), program, report)
}

fn coil(actuator: u32, plus: bool) -> Signal {
    Signal::Coil {
        actuator,
        sign: if plus {
            steptable::cell::Sign::Plus
        } else {
            steptable::cell::Sign::Minus
        },
    }
}

/// Whether `signal` is on in every sample from `from` to `to` (ms), or
/// (`on` false) off in every one.
fn always(report: &ScenarioReport, (from, to): (u64, u64), signal: Signal, on: bool) -> bool {
    report
        .samples
        .iter()
        .filter(|s| (from..to).contains(&s.time_ms))
        .all(|s| s.outputs_on.contains(&signal) == on)
}

fn position(report: &ScenarioReport, at: u64, actuator: usize) -> f64 {
    report.at(at).unwrap().positions[actuator - 1]
}

#[test]
fn jogs_move_each_actuator_refuse_forbidden_jogs_and_auto_starts_after_reset() {
    let build = Build::paper().modes("all");
    let (_, _, report) = run(&build, &fixture_events());
    // C1 (52bi) out while jog1+ is held, home while jog1- is.
    assert!(always(&report, (600, 1_900), coil(1, true), true));
    assert!(position(&report, 1_950, 1) > 0.95, "C1 out");
    assert!(always(&report, (2_100, 2_400), coil(1, true), false));
    assert!(position(&report, 3_950, 1) < 0.05, "C1 home");
    // C2 (5/3 closed centre) stops where jog2+ was let go.
    let held = position(&report, 5_300, 2);
    assert!(held > 0.2 && held < 2.8, "C2 between its ends: {held}");
    assert_eq!(held, position(&report, 5_450, 2), "C2 held by the centre");
    assert!(position(&report, 6_950, 2) < 0.05, "C2 home");
    // START in manual: nothing fires until the cycle after RESET.
    assert!(
        report.fired.iter().all(|(t, _)| *t > 17_000),
        "{:?}",
        report.fired
    );
    // Both buttons of C3: neither coil, C3 stays home.
    assert!(always(&report, (7_500, 8_500), coil(3, true), false));
    assert!(always(&report, (7_500, 8_500), coil(3, false), false));
    assert!(position(&report, 8_450, 3) < 0.05);
    // C4 out and back.
    assert!(position(&report, 10_450, 4) > 0.95, "C4 out");
    assert!(position(&report, 12_450, 4) < 0.05, "C4 home");
    // Under the EMERGENCY STOP jog1+ moves nothing.
    assert!(always(&report, (13_500, 14_500), coil(1, true), false));
    assert!(position(&report, 14_450, 1) < 0.05);
    // Step 0 all through manual; the cycle after RESET and START runs to
    // its end and the machine stands home, with no problem found.
    assert!(
        report
            .samples
            .iter()
            .filter(|s| s.time_ms < 17_000)
            .all(|s| s.step == 0)
    );
    let steps: Vec<usize> = report.fired.iter().map(|(_, s)| *s).collect();
    assert_eq!(steps, (1..=9).collect::<Vec<_>>());
    assert!(report.problems.is_empty(), "{:?}", report.problems);
    let last = report.samples.last().unwrap();
    assert!(last.positions.iter().all(|p| p.abs() < 0.05));
}

/// MAN_MODE mid-cycle: the sequence is back at step 0 the scan after and
/// every coil is off; leaving manual away from home, START does nothing.
#[test]
fn entering_manual_ends_the_cycle_and_start_waits_for_home() {
    let build = Build::paper().modes("all");
    let written = [
        ("press", "START@0.5s"),
        ("hold", "MAN_MODE@step3"),
        ("release", "MAN_MODE@+1s"),
        ("press", "START@+1s"),
    ]
    .map(|(o, t)| (o.to_string(), t.to_string()));
    let (_, _, report) = run(&build, &written);
    let (at, _) = report.happened[1];
    let after = report.at(at + 20).unwrap();
    assert_eq!(after.step, 0);
    assert!(after.outputs_on.is_empty(), "{:?}", after.outputs_on);
    // C1 stands out (it was not home), so START after manual is ignored.
    let steps: Vec<usize> = report.fired.iter().map(|(_, s)| *s).collect();
    assert_eq!(steps, [1, 2, 3], "no cycle after manual away from home");
}
