//! The template of earlier steptable versions wrote `1s | 1s` in rows C1
//! to C8 of the actuator table. Such a row for an actuator the table does
//! not move changes nothing, and refusing it would break every old
//! workbook; dropping its cells without a word would break the rule that
//! every filled cell is read or named. So it is W003 at the row's first
//! time cell, naming its cells. Any other value for such an actuator (a
//! valve, a load, another time) is E030, said where the other settings
//! for an actuator the table lacks are.

use crate::diag::{Code, Diagnostics};
use crate::read::Grid;
use crate::settings::Given;
use crate::stroke::Stroke;
use crate::table::StepTable;

/// W003 for each row of the actuator table that gives an actuator the
/// table lacks nothing but the default 1 s stroke. `has` names the
/// table's actuators (`it has C1, C2`).
pub(super) fn placeholder_rows(
    table: &StepTable,
    grid: &Grid,
    given: &Given,
    has: &str,
    diags: &mut Diagnostics,
) {
    for (&n, stroke) in &given.strokes {
        let placeholder = *stroke == Stroke::default()
            && !given.valves.contains_key(&n)
            && !given.loads.contains_key(&n);
        if table.actuator(n).is_some() || !placeholder {
            continue;
        }
        let cells: Vec<_> = ["extend", "retract"]
            .iter()
            .filter_map(|what| given.actuator_cells.get(&(n, *what)))
            .collect();
        let Some(first) = cells.first() else {
            continue;
        };
        let names: Vec<String> = cells
            .iter()
            .filter_map(|at| at.cell.map(|pos| grid.cell_name(pos)))
            .collect();
        diags.warning(
            Code::W003Ignored,
            (*first).clone(),
            format!(
                "the time cells of C{n} ({}) hold 1s, which the template of earlier steptable versions wrote in every row, but the table does not move C{n} ({has}); they were not read: empty them or delete the row",
                names.join(", ")
            ),
        );
    }
}
