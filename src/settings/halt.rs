//! The SETTINGS sheet's `hold-safe` and `de-energise on halt` rows: which
//! outputs may stay on in a stopped machine, which the program switches
//! off when it halts. The names are read here; what they stand for is
//! decided against the table (`resolve`), where an unknown one is an error
//! at its cell.

use std::collections::BTreeSet;

use crate::cell::Sign;
use crate::diag::{Code, Diagnostics, Location};
use crate::program::{HaltPolicy, Signal};
use crate::table::StepTable;
use crate::valve::{ValveType, Valves};

/// Names as one SETTINGS cell lists them (`vacuum, y1+, C2`), with the
/// cell, for the errors once they are checked against the table.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct NamedList {
    pub names: Vec<String>,
    pub at: Location,
}

impl NamedList {
    pub fn parse(text: &str, at: Location) -> NamedList {
        NamedList {
            names: text
                .split([',', ';'])
                .map(|n| n.trim().to_string())
                .filter(|n| !n.is_empty())
                .collect(),
            at,
        }
    }
}

/// The outputs a name stands for: a machine output of the table
/// (`vacuum`), one coil (`y1+`, `y1-`, `y1` for a single-solenoid valve) or
/// every coil of an actuator (`C1`). A coil its valve does not have (`y1`
/// of a valve with two coils) is no output: the error names the ones it has.
fn outputs_named(table: &StepTable, valves: &Valves, name: &str) -> Option<Vec<Signal>> {
    let lower = name.to_ascii_lowercase();
    if let Some(output) = table
        .outputs
        .iter()
        .find(|o| o.as_str().eq_ignore_ascii_case(name))
    {
        return Some(vec![Signal::MachineOutput(*output)]);
    }
    let has = |actuator: u32| table.actuator(actuator).is_some();
    if let Some(actuator) = crate::cell::parse_actuator(name).filter(|a| has(*a)) {
        return Some(vec![
            Signal::Coil {
                actuator,
                sign: Sign::Plus,
            },
            Signal::Coil {
                actuator,
                sign: Sign::Minus,
            },
            Signal::SingleCoil { actuator },
        ]);
    }
    let coil = lower.strip_prefix('y')?;
    let (number, sign) = match coil.strip_suffix('+') {
        Some(n) => (n, Some(Sign::Plus)),
        None => match coil.strip_suffix('-') {
            Some(n) => (n, Some(Sign::Minus)),
            None => (coil, None),
        },
    };
    let actuator: u32 = number.parse().ok().filter(|a| has(*a))?;
    let pmax = table.actuator(actuator).map_or(1, |a| a.max_position);
    let single = valves.of(actuator, pmax) == ValveType::Mono52;
    match (sign, single) {
        (Some(sign), false) => Some(vec![Signal::Coil { actuator, sign }]),
        (None, true) => Some(vec![Signal::SingleCoil { actuator }]),
        _ => None,
    }
}

/// The halt policy the three rows give (`hold-safe`, `de-energise on
/// halt`, `hold on estop`); an unknown name, or one both hold-safe and to
/// be switched off, is an E030 at its row's cell.
pub fn resolve(
    table: &StepTable,
    valves: &Valves,
    hold_safe: Option<&NamedList>,
    off_on_halt: Option<&NamedList>,
    hold_on_estop: Option<&NamedList>,
    diags: &mut Diagnostics,
) -> HaltPolicy {
    let hold_on_estop_row = hold_on_estop;
    let mut sets: [BTreeSet<Signal>; 3] = Default::default();
    for (set, (label, row)) in sets.iter_mut().zip([
        ("hold-safe", hold_safe),
        ("de-energise on halt", off_on_halt),
        ("hold on estop", hold_on_estop),
    ]) {
        let Some(row) = row else { continue };
        for name in &row.names {
            match outputs_named(table, valves, name) {
                Some(signals) => set.extend(signals),
                None => {
                    let mut known: Vec<String> =
                        table.outputs.iter().map(|o| o.to_string()).collect();
                    for a in &table.actuators {
                        known.push(format!("C{}", a.number));
                        if valves.of(a.number, a.max_position) == ValveType::Mono52 {
                            known.push(format!("y{}", a.number));
                        } else {
                            known.push(format!("y{0}+, y{0}-", a.number));
                        }
                    }
                    diags.error(
                        Code::E030BadSetting,
                        row.at.clone(),
                        format!(
                            "{label}: \"{name}\" is not an output of this table (expected a machine output, a coil such as y1+, or an actuator: {})",
                            known.join(", ")
                        ),
                    );
                }
            }
        }
    }
    let [hold_safe, off, hold_on_estop] = sets;
    if let (Some(row), Some(both)) = (off_on_halt, hold_safe.intersection(&off).next()) {
        diags.error(
            Code::E030BadSetting,
            row.at.clone(),
            format!(
                "de-energise on halt: {} is also hold-safe; say one or the other",
                both.symbol()
            ),
        );
    }
    if let (Some(row), Some(both)) = (hold_on_estop_row, hold_on_estop.intersection(&off).next()) {
        diags.error(
            Code::E030BadSetting,
            row.at.clone(),
            format!(
                "hold on estop: {} is also to be switched off on halt, and the emergency stop halts; say one or the other",
                both.symbol()
            ),
        );
    }
    let off_on_halt = off;
    HaltPolicy {
        hold_safe,
        off_on_halt,
        hold_on_estop,
    }
}

/// The SETTINGS rows `start permissive` and `interlock` (`label`):
/// machine inputs the table does not wait for, that must be on for a cycle
/// to start, or stay on. Each must be a name a machine input may have, and
/// neither an output nor an input the table waits for (that one's value
/// belongs to its step); else E030 at the cell.
pub fn resolve_held_inputs(
    table: &StepTable,
    buttons: &[String],
    label: &str,
    row: Option<&NamedList>,
    diags: &mut Diagnostics,
) -> Vec<crate::cell::Name> {
    let Some(row) = row else {
        return Vec::new();
    };
    let mut names: Vec<crate::cell::Name> = Vec::new();
    for text in &row.names {
        let lower = text.to_ascii_lowercase();
        let mut bad = |why: String| {
            diags.error(
                Code::E030BadSetting,
                row.at.clone(),
                format!("{label}: {why}"),
            )
        };
        let name = match crate::cell::Name::new(&lower) {
            Ok(name) => name,
            Err(why) => {
                bad(why);
                continue;
            }
        };
        let stem = crate::names::fst_stem(&lower);
        if let Some(reason) =
            crate::names::reserved_name(&lower).or_else(|| crate::names::reserved_name(&stem))
        {
            bad(format!(
                "\"{lower}\" cannot name a machine signal: {reason}"
            ));
        } else if buttons.contains(&lower) {
            bad(format!(
                "\"{lower}\" is the program's own operating-mode button"
            ));
        } else if table.outputs.contains(&name) {
            bad(format!(
                "{lower} is a machine output of the table, not an input"
            ));
        } else if table.inputs.contains(&name) {
            bad(format!(
                "the table waits for {lower} in a step; name an input no step waits for"
            ));
        } else if let Some(other) = table
            .inputs
            .iter()
            .chain(&table.outputs)
            .chain(&names)
            .find(|o| **o != name && crate::names::fst_stem(o.as_str()) == stem)
        {
            bad(format!(
                "{lower} and {other} begin with the same 9 characters, which is all Festo FST keeps of a symbol"
            ));
        } else if !names.contains(&name) {
            names.push(name);
        }
    }
    names
}
