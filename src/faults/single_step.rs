//! The one fault the automatic cycle cannot show: a shorted STEP_PB. In
//! automatic it changes nothing, but in single step (STEP_MODE on, at
//! commissioning, with people at the machine) a short reads as one press
//! and fires the step the sequence waits at. Its case is therefore also
//! run in single step — STEP_MODE on, START pressed, the short coming
//! before any press — and judged there.

use crate::program::{Signal, StepProgram};
use crate::simulate::scenario::scenario;
use crate::simulate::{Fault, Operator, ProblemKind, SimSettings};
use crate::table::StepTable;

/// START pressed at 0.5 s, the short at 1 s, the run until 30 s (or until
/// a hazard).
const START_MS: u64 = 500;
const SHORT_MS: u64 = 1_000;
const UNTIL_MS: u64 = 30_000;

/// The short of STEP_PB.
pub(super) const SHORT: Fault = Fault {
    signal: Signal::StepButton,
    stuck_at: true,
};

/// What a shorted STEP_PB does in single step, when the program has the
/// mode and a step fires without a press there: the step concerned and
/// why it is a hazard (at every moment: the short reads as the press
/// whenever it comes).
pub(super) fn step_button_hazard(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
) -> Option<(usize, String)> {
    if !program.signals.inputs.contains(&Signal::StepButton) {
        return None;
    }
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
        faults: vec![SHORT],
        fault_onset_ms: SHORT_MS,
        record_trace: false,
        ..settings.clone()
    };
    let report = scenario(table, program, &run, &script, UNTIL_MS);
    let fired = report
        .problems
        .iter()
        .find(|p| p.kind == ProblemKind::UnexpectedStep)?;
    Some((
        fired.step,
        format!(
            "in single step (STEP_MODE on) {}: the short reads as one press (one step, no more); in automatic the cycle runs as without it",
            fired.message
        ),
    ))
}
