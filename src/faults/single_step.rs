//! The one fault the automatic cycle cannot show: a shorted STEP_PB. In
//! automatic it changes nothing, but in single step (STEP_MODE on, at
//! commissioning, with people at the machine) a short reads as one press
//! and fires the step the sequence waits at. Its case is therefore also
//! run in single step — STEP_MODE on, START pressed, the short coming
//! before any press — and judged there.

use super::{FaultCase, Outcome};
use crate::program::{Signal, StepProgram};
use crate::simulate::scenario::scenario;
use crate::simulate::{Fault, Operator, ProblemKind, SimSettings};
use crate::table::StepTable;

/// START pressed at 0.5 s, the short at 1 s, the run until 30 s (or until
/// a hazard).
const START_MS: u64 = 500;
const SHORT_MS: u64 = 1_000;
const UNTIL_MS: u64 = 30_000;

/// Judges the STEP_PB short-circuit case of `cases` in single step, when
/// the program has the mode: a hazard when a step fires without a press.
pub(super) fn judge_step_button(
    cases: &mut [FaultCase],
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
) {
    let short = Fault {
        signal: Signal::StepButton,
        stuck_at: true,
    };
    let Some(case) = cases.iter_mut().find(|c| c.faults == [short]) else {
        return;
    };
    let stepping = Operator {
        step_mode: true,
        ..Operator::default()
    };
    let script = [
        (0, stepping),
        (
            START_MS,
            Operator {
                start: true,
                ..stepping
            },
        ),
        (START_MS + 100, stepping),
    ];
    let run = SimSettings {
        faults: vec![short],
        fault_onset_ms: SHORT_MS,
        record_trace: false,
        ..settings.clone()
    };
    let report = scenario(table, program, &run, &script, UNTIL_MS);
    let Some(fired) = report
        .problems
        .iter()
        .find(|p| p.kind == ProblemKind::UnexpectedStep)
    else {
        return;
    };
    case.outcome = Outcome::Hazard;
    case.step = Some(fired.step);
    case.explanation = format!(
        "in single step (STEP_MODE on) {}: the short reads as one press (one step, no more); in automatic the cycle runs as without it",
        fired.message
    );
    case.outcomes.fill(Outcome::Hazard);
}
