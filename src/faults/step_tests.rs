//! The fault table's `step` column means one thing for every kind of
//! finding: the SFC step the machine is in (0 at rest, k while table step
//! k's moves run) when the finding the explanation names first happens.
//! Pinned on the paper's example so that a drift shows.

use super::*;
use crate::program::{self, INITIAL_STEP, ProgramOptions};
use crate::simulate::{Problem, simulate};

fn paper() -> (StepTable, StepProgram) {
    let table = crate::program::tests::paper_table();
    let program = program::build(
        &table,
        &ProgramOptions::default(),
        &crate::actuator::Valves::default(),
        &crate::stroke::Strokes::default(),
    );
    (table, program)
}

fn stuck(actuator: u32, position: u32, stuck_at: bool) -> Fault {
    Fault {
        signal: Signal::Sensor { actuator, position },
        stuck_at,
    }
}

/// A fault's run from power-up, collisions judged against the healthy
/// cycle's positions as the fault analysis judges them.
fn run(fault: Fault) -> crate::simulate::SimReport {
    let (table, program) = paper();
    let healthy = healthy_run(&table, &program, &SimSettings::default());
    let settings = SimSettings {
        faults: vec![fault],
        stop_at_hazard: true,
        known_places: Some(std::sync::Arc::new(healthy.report.places)),
        ..SimSettings::default()
    };
    simulate(&table, &program, &settings)
}

/// The judged outcome and step of one fault from power-up.
fn judged(fault: Fault) -> (Outcome, Option<usize>, String) {
    judge(&run(fault))
}

#[test]
fn a_stall_is_the_step_the_machine_stalls_in() {
    // x11 open: C1+ of step 1 never ends, step 2 never fires.
    let (outcome, step, why) = judged(stuck(1, 1, false));
    assert_eq!((outcome, step), (Outcome::SafeStall, Some(1)), "{why}");
    assert!(why.starts_with("step 2 never fires"), "{why}");
    // x10 open: step 1 never fires, the machine is at rest.
    let (outcome, step, why) = judged(stuck(1, 0, false));
    assert_eq!(
        (outcome, step),
        (Outcome::SafeStall, Some(INITIAL_STEP)),
        "{why}"
    );
}

#[test]
fn an_early_start_is_the_step_it_enters() {
    // x11 short: step 2 starts while C1 still moves.
    let (outcome, step, why) = judged(stuck(1, 1, true));
    assert_eq!((outcome, step), (Outcome::Hazard, Some(2)), "{why}");
    assert!(why.starts_with("step 2 started before step 1"), "{why}");
    // x22 short: step 5 starts early and the positions collide a scan
    // before; the explanation leads with the early start, so does the step.
    let (outcome, step, why) = judged(stuck(2, 2, true));
    assert_eq!((outcome, step), (Outcome::Hazard, Some(5)), "{why}");
    assert!(why.starts_with("step 5 started before step 4"), "{why}");
    assert!(why.contains("collision risk"), "{why}");
}

#[test]
fn a_collision_is_the_step_it_comes_about_in() {
    // The simulator's own collision: x22 short collides during step 4.
    let report = run(stuck(2, 2, true));
    let collision = report
        .problems
        .iter()
        .find(|p| p.kind == ProblemKind::Collision)
        .expect("a collision");
    assert_eq!(collision.step, 4, "{}", collision.message);
    assert!(collision.message.contains("(during step 4)"));
    // A collision alone is judged at its step; after a stall, at the stall's.
    let mut alone = report.clone();
    alone.stalled_at = None;
    alone.problems = vec![Problem {
        step: 3,
        ..collision.clone()
    }];
    assert_eq!(judge(&alone).1, Some(3));
    // x21 open while step 4 moves C2 away from it: the run stalls in
    // step 5 (C2 runs through x21) with a collision there.
    let (table, program) = paper();
    let result = analyse(&table, &program, &SimSettings::default(), 1);
    let x21 = result
        .cases
        .iter()
        .find(|c| c.faults == [stuck(2, 1, false)])
        .expect("x21 open");
    assert_eq!((x21.outcome, x21.step), (Outcome::Hazard, Some(5)));
    assert!(x21.explanation.starts_with("step 6 never fires"));
    assert!(x21.explanation.contains("collision risk"));
}
