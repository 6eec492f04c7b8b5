//! Jumps on inputs (`J:7 if I:reject`): the selection divergence of an SFC.
//! While the sequence waits for the step after a jump's step, the jump is
//! tested first: when its step is done and its input has the value, the
//! target step fires in its place (its actions run) and the sequence waits
//! for the step after the target. A jump to the end fires the closing step.

use super::{Action, Literal, ProgramOptions, ProgramStep, Signal, StepKind};
use crate::table::StepTable;

/// One alternative transition of a waiting step.
#[derive(Debug, Clone, PartialEq)]
pub struct StepJump {
    /// The jump as the table writes it (`J:7 if I:reject`).
    pub title: String,
    /// Index into the program's steps of the step that fires instead.
    pub fires: usize,
    /// Its step's completion, the input, the target's own checks.
    pub condition: Vec<Literal>,
    /// The target step's actions (zones set as the target step is in them).
    pub actions: Vec<Action>,
    /// Index into the program's steps of the step then awaited.
    pub next: usize,
}

/// Adds every jump of the table to the step its sequence waits at after
/// the jump's step. `completion(k)` is what must hold for step k (0-based)
/// to be done; `guards(target)` what the target needs besides the step
/// before it being complete (its sensors still off, no halt).
pub(super) fn add_jumps(
    table: &StepTable,
    options: &ProgramOptions,
    steps: &mut [ProgramStep],
    completion: impl Fn(usize) -> Vec<Literal>,
    guards: impl Fn(&ProgramStep) -> Vec<Literal>,
) {
    let count = steps.len();
    for (index, step) in table.steps.iter().enumerate() {
        for jump in &step.jumps {
            // The closing step is there whenever a table ends early.
            let fires = jump.fires(count - 1);
            let target = &steps[fires];
            let mut condition = completion(index);
            condition.push(Literal {
                signal: Signal::MachineInput(jump.input),
                negated: !jump.value,
            });
            condition.extend(guards(target));
            let mut actions: Vec<Action> = target
                .actions
                .iter()
                .copied()
                .filter(|a| !matches!(a.signal(), Signal::InterlockZone(_)))
                .collect();
            // An interlock zone holds while its steps' moves are under way:
            // the jump sets or clears each as its target lies in it or not.
            for (zone, interlock) in options.zones() {
                let Some((first, last)) = interlock.steps else {
                    continue;
                };
                let inside =
                    target.kind == StepKind::Table && (first..=last).contains(&target.number);
                actions.push(if inside {
                    Action::Set(zone)
                } else {
                    Action::Reset(zone)
                });
            }
            let jump = StepJump {
                title: jump.notation(),
                fires,
                condition,
                actions,
                next: (fires + 1) % count,
            };
            steps[index + 1].jumps.push(jump);
        }
    }
}
