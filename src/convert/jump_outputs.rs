//! A jump leaves out steps, and with them the machine outputs they switch:
//! where the sequence arrives by a jump with an output otherwise than it
//! arrives without it (a `Y:vacuum-` or `Y:heater-` left out, so the machine
//! rests with the vacuum on), that is said at the jump's cell (W010). The
//! actuators' positions a jump leaves otherwise are refused (E029); an
//! output may be meant to stay (a reject lamp), so it is a warning.

use std::collections::BTreeMap;

use crate::cell::Name;
use crate::diag::{Code, Diagnostics};
use crate::read::Grid;
use crate::table::{Jump, StepTable};

/// W010 for every jump that leaves a machine output otherwise than the
/// sequence without it.
pub(super) fn outputs_a_jump_leaves(table: &StepTable, grid: &Grid, diags: &mut Diagnostics) {
    let steps = &table.steps;
    if steps.iter().all(|s| s.jumps.is_empty()) {
        return;
    }
    // The outputs after each step of the sequence without jumps, from a
    // start with every output off (after[k]: after step k).
    let mut after: Vec<BTreeMap<Name, bool>> = vec![BTreeMap::new()];
    for step in steps {
        let mut state = after.last().cloned().unwrap_or_default();
        for switch in &step.switches {
            state.insert(switch.output, switch.on);
        }
        after.push(state);
    }
    let count = steps.len();
    for step in steps {
        for jump in &step.jumps {
            let arrives = match jump.target {
                Some(n) if (2..=count).contains(&n) => n - 1,
                Some(_) => continue, // refused (E028)
                None => count,
            };
            let by_jump = &after[step.number];
            let without = &after[arrives];
            for (output, on) in differing(by_jump, without) {
                // The steps between the two paths: those a jump forward
                // leaves out, those a jump back runs again.
                let between = if arrives >= step.number {
                    step.number..arrives
                } else {
                    arrives..step.number
                };
                let switched_in: Vec<String> = steps[between]
                    .iter()
                    .filter(|s| s.switches.iter().any(|w| w.output == output))
                    .map(|s| format!("STEP {}", s.number))
                    .collect();
                diags.warning(
                    Code::W010JumpLeavesOutput,
                    grid.location(jump.cell),
                    message(step.number, jump, output, on, &switched_in),
                );
            }
        }
    }
}

/// The outputs whose state differs between the two, with the state the
/// jump leaves.
fn differing(by_jump: &BTreeMap<Name, bool>, without: &BTreeMap<Name, bool>) -> Vec<(Name, bool)> {
    let names: std::collections::BTreeSet<&Name> = by_jump.keys().chain(without.keys()).collect();
    names
        .into_iter()
        .filter_map(|name| {
            let jump = by_jump.get(name).copied().unwrap_or(false);
            let plain = without.get(name).copied().unwrap_or(false);
            (jump != plain).then_some((*name, jump))
        })
        .collect()
}

fn message(from: usize, jump: &Jump, output: Name, on: bool, switched_in: &[String]) -> String {
    let state = |on: bool| if on { "on" } else { "off" };
    let (where_, so) = match jump.target {
        Some(n) => (format!("in STEP {n}"), format!("STEP {n} and after")),
        None => (
            "at the end of the cycle".to_string(),
            "the machine rests so until a step switches it".to_string(),
        ),
    };
    format!(
        "\"{}\" in STEP {from} leaves Y:{output} {} {where_}, where the sequence arrives without the jump with it {} (switched in {}): {so}; switch it in STEP {from} (Y:{output}{}) if that is not meant",
        jump.notation(),
        state(on),
        state(!on),
        switched_in.join(", "),
        if on { "-" } else { "+" },
    )
}
