//! A kind with its own times (a swivel drive's 500 ms swing, a vacuum
//! gripper's build-up and release) has them wherever the engineer gave no
//! time: no `--stroke`, no row in the actuator table, or an empty extend or
//! retract cell in it. A time the engineer wrote is the engineer's, even
//! the old template's placeholder `1s`; that one is kept and said (W007 at
//! the cell, with the kind's own time), since a workbook must not start
//! running differently without a word when steptable is updated.

use crate::diag::{Code, Diagnostics};
use crate::settings::{Given, Settings};
use crate::stroke::Stroke;
use crate::table::StepTable;

/// Puts each kind's own times in force for the halves nobody gave, and
/// warns of a time cell that holds the old template's `1s` for a kind
/// whose own time differs. `sheet` is what the SETTINGS sheet gave.
pub(super) fn kind_times(
    table: &StepTable,
    effective: &mut Settings,
    sheet: Option<&Given>,
    diags: &mut Diagnostics,
) {
    for actuator in &table.actuators {
        let n = actuator.number;
        let machine = &effective.simulation.machine;
        let kind = machine.valves.of(n, actuator.max_position);
        let Some(own) = kind.default_stroke() else {
            continue;
        };
        // The command line's stroke is whole (`C2=1s` is both ways).
        let sheet = sheet.filter(|s| {
            s.strokes.contains_key(&n) && !line_gives_stroke(&effective.given, effective, n)
        });
        let strokes = &mut effective.simulation.machine.strokes.per_actuator;
        let Some(sheet) = sheet else {
            strokes.entry(n).or_insert(own);
            continue;
        };
        let stroke = strokes.entry(n).or_insert(own);
        let halves: [(&str, &mut u32, u32, &str); 2] = [
            (
                "extend",
                &mut stroke.extend_ms,
                own.extend_ms,
                kind.move_words().0,
            ),
            (
                "retract",
                &mut stroke.retract_ms,
                own.retract_ms,
                kind.move_words().1,
            ),
        ];
        for (what, given, own_ms, words) in halves {
            match sheet.actuator_cells.get(&(n, what)) {
                // The cell is empty: the kind's own time.
                None => *given = own_ms,
                Some(at) if *given == Stroke::default().extend_ms && own_ms != *given => {
                    let text = crate::cell::duration_text;
                    diags.warning(
                        Code::W007Assumed,
                        at.clone(),
                        format!(
                            "{what} of C{n}: {} is taken as given, though C{n} is a {} (valve type {kind}), which {words} in {} of its own; the template of earlier steptable versions wrote 1s in every row: empty the cell to take {}",
                            text(*given),
                            kind.noun(),
                            text(own_ms),
                            text(own_ms)
                        ),
                    );
                }
                Some(_) => {}
            }
        }
    }
}

/// Whether the command line gives actuator `n` a stroke, by number or by
/// a name the naming authority reads as `n` (`--stroke arm=1s`).
fn line_gives_stroke(line: &Given, settings: &Settings, n: u32) -> bool {
    line.strokes.contains_key(&n)
        || (line.named_strokes.keys()).any(|name| settings.naming.actuator_called(name) == Some(n))
}
