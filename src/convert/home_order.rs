//! The home order as the engineer named it (`C1`, `1A1`, `clamp`), read
//! by the naming authority into the numbers the table check and the
//! program use; what answers to no actuator, or to one twice, is E030.

use crate::diag::{Code, Diagnostics, Location};
use crate::settings::Settings;
use crate::table::StepTable;

/// The longest run of two or more `items` that, joined by `_`, an
/// actuator is called (`gripper`, `arm` → `gripper_arm`): how many, and
/// that name.
fn spaced_name(naming: &crate::symbols::Naming, items: &[String]) -> Option<(usize, String)> {
    (2..=items.len()).rev().find_map(|run| {
        let joined = items[..run].join("_");
        naming.actuator_called(&joined).map(|_| (run, joined))
    })
}

/// The home order in force, its actuators read by the naming authority
/// (`C1`, `1A1`, `clamp`): put in force as numbers for the table check and
/// the program; an item no actuator answers to is E030 on its SETTINGS
/// cell, or on the file naming `--home-order`, with the closest name.
pub(super) fn home_order_by_name(
    table: &StepTable,
    settings: &mut Settings,
    at: Option<&Location>,
    file: &str,
    diags: &mut Diagnostics,
) {
    let Some(order) = settings.home_order.clone() else {
        return;
    };
    let (at, source) = crate::table::home_order_place(at, file);
    let numbers: Vec<u32> = table.actuators.iter().map(|a| a.number).collect();
    let naming = &settings.naming;
    let mut stages = Vec::new();
    let mut known = true;
    let mut spelt: std::collections::BTreeMap<u32, &str> = Default::default();
    for stage in &order {
        let mut actuators = Vec::new();
        let mut items = stage.iter().enumerate();
        while let Some((i, item)) = items.next() {
            // `C1 (clamp)`, as steptable prints it: the name must be C1's.
            let (actuator, name) = crate::program::bracketed(item);
            let called = naming.actuator_called(item);
            if let (None, Some(_), Some(name)) = (called, naming.actuator_called(actuator), name) {
                let like = naming
                    .actuator_like(name, &numbers)
                    .map(|name| format!("; did you mean {name}?"))
                    .unwrap_or_default();
                let name = match name.is_empty() {
                    true => "()",
                    false => name,
                };
                known = false;
                diags.error(
                    Code::E030BadSetting,
                    at.clone(),
                    format!(
                        "the home order names \"{item}\", but {name} is no name of {actuator}; write the actuator alone, or with its own name{like}{source}"
                    ),
                );
                continue;
            }
            match called {
                // The same actuator under two of its names (`C1,1A1`):
                // said with both, which the numbers no longer hold.
                Some(n) if spelt.get(&n).is_some_and(|first| first != item) => {
                    known = false;
                    diags.error(
                        Code::E030BadSetting,
                        at.clone(),
                        format!(
                            "the home order names C{n} twice, as {} and {item}; name each actuator once{source}",
                            spelt[&n]
                        ),
                    );
                }
                Some(n) => {
                    spelt.entry(n).or_insert(item);
                    actuators.push(n);
                }
                None => {
                    known = false;
                    // `gripper arm` parted at its space into two items:
                    // the name it is, said once.
                    if let Some((run, name)) = spaced_name(naming, &stage[i..]) {
                        diags.error(
                            Code::E030BadSetting,
                            at.clone(),
                            format!(
                                "the home order names \"{}\" as {run} actuators, but a space parts the actuators of a stage: write the name as {name}{source}",
                                stage[i..i + run].join(" ")
                            ),
                        );
                        items.nth(run - 2);
                        continue;
                    }
                    let like = naming
                        .actuator_like(item, &numbers)
                        .map(|name| format!("; did you mean {name}?"))
                        .unwrap_or_default();
                    diags.error(
                        Code::E030BadSetting,
                        at.clone(),
                        format!(
                            "the home order names \"{item}\", which is no actuator (C1, its ISO designation 1A1, or its name from the SETTINGS actuator table){like}{source}"
                        ),
                    );
                }
            }
        }
        stages.push(actuators);
    }
    if known {
        settings.program.modes.home_order = Some(stages);
    }
}
