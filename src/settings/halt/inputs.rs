//! The SETTINGS rows that name inputs rather than outputs: `interlock`
//! (inputs that must stay on, always or in a range of steps) and `start
//! permissive` (inputs a cycle needs to start), each name checked against
//! the table and the program's own signals.

use super::{NamedList, Row};
use crate::diag::{Code, Diagnostics};
use crate::program::Interlock;
use crate::table::StepTable;

/// The SETTINGS row `interlock`: inputs that must stay on, each always or
/// in a range of steps (`guard_closed in steps 3-5`, `door in step 2`).
/// Every item is kept: one input may hold over several ranges (`guard in
/// steps 2-3, guard in steps 5-6`), and over the whole cycle beside a range,
/// each its own interlock. A step the table does not have, a range
/// backwards, or an item written twice is E030 at the cell.
pub fn resolve_interlocks(
    table: &StepTable,
    (buttons, fst): (&[String], bool),
    row: Option<&NamedList>,
    diags: &mut Diagnostics,
) -> Vec<Interlock> {
    let Some(row) = row else {
        return Vec::new();
    };
    let last = table.steps.len();
    let mut items: Vec<(String, Option<(usize, usize)>)> = Vec::new();
    for text in &row.names {
        let lower = text.to_ascii_lowercase();
        let item = match lower.split_once(" in step") {
            None => Some((lower.trim().to_string(), None)),
            Some((name, range)) => {
                let range = range.trim_start_matches('s').trim();
                let numbers: Vec<Option<usize>> = range
                    .split(['-', '\u{2013}'])
                    .map(|n| n.trim().trim_matches('.').parse().ok())
                    .collect();
                let steps = match numbers.as_slice() {
                    [Some(a)] => Some((*a, *a)),
                    [Some(a), Some(b)] => Some((*a, *b)),
                    _ => None,
                };
                // A step two rows answer to (the labels off) is no range.
                let ambiguous = steps.and_then(|(a, b)| {
                    let answer = |n| crate::table::two_rows_answer(&table.steps, n);
                    answer(a).or_else(|| answer(b))
                });
                match steps {
                    Some(_) if ambiguous.is_some() => {
                        diags.error(
                            Code::E030BadSetting,
                            row.at.clone(),
                            format!("interlock: \"{text}\": {}", ambiguous.unwrap_or_default()),
                        );
                        None
                    }
                    Some((a, b)) if (1..=b).contains(&a) && b <= last => {
                        Some((name.trim().to_string(), Some((a, b))))
                    }
                    _ => {
                        diags.error(
                            Code::E030BadSetting,
                            row.at.clone(),
                            format!(
                                "interlock: \"{text}\" has no step range of this table (expected e.g. guard_closed in steps 2-{last}, or guard_closed in step 2; steps 1 to {last})"
                            ),
                        );
                        None
                    }
                }
            }
        };
        let Some(item) = item else { continue };
        if items.contains(&item) {
            diags.error(
                Code::E030BadSetting,
                row.at.clone(),
                format!("interlock: \"{}\" is named twice", text.trim()),
            );
            continue;
        }
        items.push(item);
    }
    let mut distinct: Vec<String> = Vec::new();
    for (name, _) in &items {
        if !distinct.contains(name) {
            distinct.push(name.clone());
        }
    }
    let names = NamedList {
        names: distinct,
        at: row.at.clone(),
    };
    let inputs = resolve_held_inputs(table, (buttons, fst), Row::Interlock, Some(&names), diags);
    items
        .iter()
        .filter_map(|(name, steps)| {
            let input = inputs.iter().find(|i| i.as_str() == name.as_str())?;
            Some(Interlock {
                input: *input,
                steps: *steps,
            })
        })
        .collect()
}

/// The SETTINGS rows `start permissive` and `interlock` (`label`):
/// machine inputs the table does not wait for, that must be on for a cycle
/// to start, or stay on. Each must be a name a machine input may have, and
/// neither an output nor an input the table waits for (that one's value
/// belongs to its step); else E015 (the name) or E030 at the cell.
pub fn resolve_held_inputs(
    table: &StepTable,
    (buttons, fst): (&[String], bool),
    which: Row,
    row: Option<&NamedList>,
    diags: &mut Diagnostics,
) -> Vec<crate::cell::Name> {
    let Some(row) = row else {
        return Vec::new();
    };
    let label = which.label();
    let mut names: Vec<crate::cell::Name> = Vec::new();
    for text in &row.names {
        let lower = text.to_ascii_lowercase();
        // A name an input may not have is E015, as in a table cell (the one
        // name check, the program's buttons included); the rest is E030.
        let (code, why) = match crate::cell::Name::new(&lower) {
            Err(why) => (Code::E015BadName, why),
            Ok(name) => match crate::names::signal_problem(&lower, buttons, fst) {
                Some(why) => (Code::E015BadName, why),
                None if names.contains(&name) => {
                    (Code::E030BadSetting, format!("{lower} is named twice"))
                }
                None => match held_input_problem(table, name) {
                    Some(why) => (Code::E030BadSetting, why),
                    None => {
                        names.push(name);
                        continue;
                    }
                },
            },
        };
        diags.error(code, row.at.clone(), format!("{label}: {why}"));
    }
    names
}

/// Why a valid name cannot be a held input: an output, or an input a step
/// waits for. Names FST cannot tell apart are said by the one check over
/// the table and its settings (crate::symbols::check).
fn held_input_problem(table: &StepTable, name: crate::cell::Name) -> Option<String> {
    if table.outputs.contains(&name) {
        return Some(format!(
            "{name} is a machine output of the table, not an input"
        ));
    }
    if table.inputs.contains(&name) {
        return Some(format!(
            "the table waits for {name} in a step; name an input no step waits for"
        ));
    }
    None
}
