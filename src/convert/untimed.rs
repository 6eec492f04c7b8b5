//! The step watchdog does not time a step that waits on a machine input
//! (a part may take as long as it takes to come), and with it goes the
//! supervision of the moves that step makes in any branch: a lost sensor
//! there stalls the machine with no alarm. That choice is said (W009), at
//! the wait's cell, with the way to time the step.

use crate::diag::{Code, Diagnostics};
use crate::read::Grid;
use crate::settings::Settings;
use crate::table::StepTable;

/// W009 for every waiting step with moves the watchdog leaves untimed.
pub(super) fn moves_left_unsupervised(
    table: &StepTable,
    effective: &Settings,
    grid: &Grid,
    diags: &mut Diagnostics,
) {
    let program = &effective.program;
    if !program.safety.watchdog {
        return;
    }
    for step in &table.steps {
        let given = program.supervision.contains_key(&step.number);
        let (Some(wait), false, false) = (step.waits.first(), step.moves.is_empty(), given) else {
            continue;
        };
        let n = step.number;
        let moves: Vec<String> = step.moves.iter().map(|m| m.notation()).collect();
        diags.warning(
            Code::W009Unsupervised,
            grid.location(wait.cell),
            format!(
                "step {n} waits for I:{}, so the step watchdog does not time it, and its {} {} {} not supervised: a sensor lost there stalls the machine with no alarm; give the step a supervision time longer than the wait may take (SETTINGS supervision | {n}=…, or --supervision {n}=…)",
                wait.input,
                if moves.len() == 1 { "move" } else { "moves" },
                moves.join(", "),
                if moves.len() == 1 { "is" } else { "are" },
            ),
        );
    }
}
