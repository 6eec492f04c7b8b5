//! The SETTINGS sheet's `hold-safe` and `de-energise on halt` rows: which
//! outputs may stay on in a stopped machine, which the program switches
//! off when it halts. The names are read here; what they stand for is
//! decided against the table (`resolve`), where an unknown one is an error
//! at its cell.

use std::collections::{BTreeMap, BTreeSet};

use crate::cell::Sign;
use crate::diag::{Code, Diagnostics, Location};
use crate::program::{HaltPolicy, Interlock, Signal, StopAction};
use crate::table::StepTable;
use crate::valve::{ValveType, Valves};

/// The SETTINGS rows that list outputs or inputs by name.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Row {
    HoldSafe,
    OffOnHalt,
    HoldOnEstop,
    OnStop,
    OnEstop,
    OnHalt,
    StartPermissive,
    Interlock,
}

impl Row {
    pub const ALL: [Row; 8] = [
        Row::HoldSafe,
        Row::OffOnHalt,
        Row::HoldOnEstop,
        Row::OnStop,
        Row::OnEstop,
        Row::OnHalt,
        Row::StartPermissive,
        Row::Interlock,
    ];

    /// The row's label on the sheet.
    pub fn label(self) -> &'static str {
        match self {
            Row::HoldSafe => "hold-safe",
            Row::OffOnHalt => "de-energise on halt",
            Row::HoldOnEstop => "hold on estop",
            Row::OnStop => "on stop",
            Row::OnEstop => "on estop",
            Row::OnHalt => "on halt",
            Row::StartPermissive => "start permissive",
            Row::Interlock => "interlock",
        }
    }

    pub fn from_label(label: &str) -> Option<Row> {
        Row::ALL.into_iter().find(|r| r.label() == label)
    }
}

/// The named rows one source gives, by row.
pub type NamedRows = BTreeMap<Row, NamedList>;

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
        let pmax = table.actuator(actuator).map_or(1, |a| a.max_position);
        if valves.of(actuator, pmax) == ValveType::Mono52 {
            return Some(vec![Signal::SingleCoil { actuator }]);
        }
        return Some(
            [Sign::Plus, Sign::Minus]
                .map(|sign| Signal::Coil { actuator, sign })
                .to_vec(),
        );
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

/// The halt policy the rows give (`hold-safe`, `de-energise on halt`,
/// `hold on estop`, and `on stop`, `on estop`, `on halt` with an action per
/// output); an unknown name, or an output both kept and switched off by
/// one event, is an E030 at its row's cell.
pub fn resolve(
    table: &StepTable,
    valves: &Valves,
    rows: &NamedRows,
    diags: &mut Diagnostics,
) -> HaltPolicy {
    let mut sets: [BTreeSet<Signal>; 3] = Default::default();
    for (set, row) in sets
        .iter_mut()
        .zip([Row::HoldSafe, Row::OffOnHalt, Row::HoldOnEstop])
    {
        let Some(list) = rows.get(&row) else { continue };
        for name in &list.names {
            match outputs_named(table, valves, name) {
                Some(signals) => set.extend(signals),
                None => not_an_output(table, valves, row, list, name, diags),
            }
        }
    }
    let [mut hold_safe, mut off, mut hold_on_estop] = sets;
    let mut actions_of = |row: Row| {
        rows.get(&row)
            .map(|list| stop_actions(table, valves, row, list, diags))
            .unwrap_or_default()
    };
    let on_stop = actions_of(Row::OnStop);
    let (on_estop, on_halt) = (actions_of(Row::OnEstop), actions_of(Row::OnHalt));
    refuse_motion_through_estop(table, valves, rows, &hold_on_estop, &on_estop, diags);
    for (signal, action) in &on_estop {
        if *action == StopAction::Hold {
            hold_on_estop.insert(*signal);
        }
    }
    for (signal, action) in &on_halt {
        match action {
            StopAction::Off => off.insert(*signal),
            StopAction::Hold => hold_safe.insert(*signal),
            StopAction::OffAfter(_) => false,
        };
    }
    let halt_row = rows.get(&Row::OnHalt).or(rows.get(&Row::OffOnHalt));
    if let (Some(row), Some(both)) = (halt_row, hold_safe.intersection(&off).next()) {
        diags.error(
            Code::E030BadSetting,
            row.at.clone(),
            format!(
                "de-energise on halt: {} is also hold-safe; say one or the other",
                both.symbol()
            ),
        );
    }
    // The emergency stop halts: what it keeps on, a halt may not switch
    // off or time out.
    let estop_row = rows.get(&Row::OnEstop).or(rows.get(&Row::HoldOnEstop));
    let runs_on = |actions: &BTreeMap<Signal, StopAction>| -> Vec<Signal> {
        actions
            .iter()
            .filter(|(_, a)| matches!(a, StopAction::OffAfter(_)))
            .map(|(s, _)| *s)
            .collect()
    };
    let ended_on_halt: BTreeSet<Signal> = off.iter().copied().chain(runs_on(&on_halt)).collect();
    let kept_and_ended = hold_on_estop
        .iter()
        .copied()
        .chain(runs_on(&on_estop))
        .find(|s| ended_on_halt.contains(s));
    if let (Some(row), Some(both)) = (estop_row, kept_and_ended) {
        diags.error(
            Code::E030BadSetting,
            row.at.clone(),
            format!(
                "the emergency stop keeps {} on, but a halt switches it off, and the emergency stop halts; say one or the other",
                both.symbol()
            ),
        );
    }
    let policy = HaltPolicy {
        hold_safe,
        off_on_halt: off,
        hold_on_estop,
        on_stop,
        on_estop,
        on_halt,
    };
    let run_on_count = policy.run_ons().len();
    let dwells = table.dwells().count();
    if run_on_count + dwells > crate::table::MAX_DWELLS
        && let Some(row) = [Row::OnStop, Row::OnEstop, Row::OnHalt]
            .into_iter()
            .find_map(|r| rows.get(&r))
    {
        diags.error(
            Code::E030BadSetting,
            row.at.clone(),
            format!(
                "{run_on_count} run-on timers and {dwells} dwells need more than the {} timers a table may use",
                crate::table::MAX_DWELLS
            ),
        );
    }
    policy
}

/// The emergency stop must stop every motion. What it may leave on is what
/// holds a part and moves nothing: a machine output (a vacuum, a clamp the
/// table switches as `Y:clamp`). A valve coil it left on would drive its
/// piston on from wherever it was when the button was pressed (the program
/// cannot know it is at its end), and a drive's contactor would keep the
/// drive running; each is E030 at the row's cell, saying why. A clamp on a
/// 5/2 bistable valve keeps its position with both coils off.
fn refuse_motion_through_estop(
    table: &StepTable,
    valves: &Valves,
    rows: &NamedRows,
    hold_on_estop: &BTreeSet<Signal>,
    on_estop: &BTreeMap<Signal, StopAction>,
    diags: &mut Diagnostics,
) {
    let kept = [Row::HoldOnEstop, Row::OnEstop]
        .into_iter()
        .flat_map(|row| {
            let signals: Vec<Signal> = match row {
                Row::HoldOnEstop => hold_on_estop.iter().copied().collect(),
                _ => on_estop.keys().copied().collect(),
            };
            signals.into_iter().map(move |s| (row, s))
        });
    let mut named = BTreeSet::new();
    for (row, signal) in kept {
        let actuator = match signal {
            Signal::Coil { actuator, .. } | Signal::SingleCoil { actuator } => actuator,
            _ => continue,
        };
        // `hold on estop` lists the same coil the `on estop` row may repeat.
        if !named.insert((row, actuator)) {
            continue;
        }
        let Some(list) = rows.get(&row) else { continue };
        let pmax = table.actuator(actuator).map_or(1, |a| a.max_position);
        let why = if valves.of(actuator, pmax) == ValveType::Motor {
            format!(
                "{} is a contactor of drive C{actuator} (valve type motor): left on, it keeps the drive running through the EMERGENCY STOP; every drive stops",
                signal.symbol()
            )
        } else {
            format!(
                "{} is a valve coil of C{actuator}: left on, it drives the piston on from wherever it stood when the EMERGENCY STOP came; only a machine output that holds a part (a vacuum, a clamp as Y:clamp) may stay on, and a clamp on a 52bi valve keeps its position with both coils off",
                signal.symbol()
            )
        };
        diags.error(
            Code::E030BadSetting,
            list.at.clone(),
            format!("{}: {why}", row.label()),
        );
    }
}

/// E030 for a name that is no output of the table, with the ones it has.
fn not_an_output(
    table: &StepTable,
    valves: &Valves,
    row: Row,
    list: &NamedList,
    name: &str,
    diags: &mut Diagnostics,
) {
    let mut known: Vec<String> = table.outputs.iter().map(|o| o.to_string()).collect();
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
        list.at.clone(),
        format!(
            "{}: \"{name}\" is not an output of this table (expected a machine output, a coil such as y1+, or an actuator: {})",
            row.label(),
            known.join(", ")
        ),
    );
}

/// The `on stop`, `on estop` and `on halt` rows (`row`): `heater off, fan
/// off after 20s, vacuum hold` (also `fan on for 20s`). Each item is an
/// output and what it does when the machine stops so; a run-on lasts 10 ms
/// to 655 s (FST's timers).
fn stop_actions(
    table: &StepTable,
    valves: &Valves,
    row: Row,
    list: &NamedList,
    diags: &mut Diagnostics,
) -> BTreeMap<Signal, StopAction> {
    let label = row.label();
    let mut actions = BTreeMap::new();
    for item in &list.names {
        let (name, rest) = item
            .split_once(char::is_whitespace)
            .map_or((item.as_str(), ""), |(n, r)| (n, r.trim()));
        let lower = rest.to_ascii_lowercase();
        let words: Vec<&str> = lower.split_whitespace().collect();
        let action = match words.as_slice() {
            ["off"] => Some(StopAction::Off),
            ["hold"] => Some(StopAction::Hold),
            ["off", "after", time @ ..] | ["on", "for", time @ ..] => {
                crate::cell::parse_duration_in(&time.concat(), 10..=655_000)
                    .map(StopAction::OffAfter)
            }
            _ => None,
        };
        let Some(action) = action else {
            diags.error(
                Code::E030BadSetting,
                list.at.clone(),
                format!(
                    "{label}: \"{item}\" is not an output and what it does (expected e.g. heater off, fan off after 20s, vacuum hold; a run-on from 10ms to 655s)"
                ),
            );
            continue;
        };
        match outputs_named(table, valves, name) {
            Some(signals) => {
                for signal in signals {
                    if actions.insert(signal, action).is_some() {
                        diags.error(
                            Code::E030BadSetting,
                            list.at.clone(),
                            format!("{label}: {} is named twice", signal.symbol()),
                        );
                    }
                }
            }
            None => not_an_output(table, valves, row, list, name, diags),
        }
    }
    actions
}

/// The SETTINGS row `interlock`: inputs that must stay on, each always or
/// in a range of steps (`guard_closed in steps 3-5`, `door in step 2`); a
/// step the table does not have, or a range backwards, is E030 at the cell.
pub fn resolve_interlocks(
    table: &StepTable,
    buttons: &[String],
    row: Option<&NamedList>,
    diags: &mut Diagnostics,
) -> Vec<Interlock> {
    let Some(row) = row else {
        return Vec::new();
    };
    let last = table.steps.len();
    let mut ranges: Vec<(String, Option<(usize, usize)>)> = Vec::new();
    for text in &row.names {
        let lower = text.to_ascii_lowercase();
        let Some((name, range)) = lower.split_once(" in step") else {
            ranges.push((lower, None));
            continue;
        };
        let range = range.trim_start_matches('s').trim();
        let numbers: Vec<Option<usize>> = range
            .split(['-', '–'])
            .map(|n| n.trim().trim_matches('.').parse().ok())
            .collect();
        let steps = match numbers.as_slice() {
            [Some(a)] => Some((*a, *a)),
            [Some(a), Some(b)] => Some((*a, *b)),
            _ => None,
        };
        match steps {
            Some((a, b)) if (1..=b).contains(&a) && b <= last => {
                ranges.push((name.trim().to_string(), Some((a, b))));
            }
            _ => diags.error(
                Code::E030BadSetting,
                row.at.clone(),
                format!(
                    "interlock: \"{text}\" has no step range of this table (expected e.g. guard_closed in steps 2-{last}, or guard_closed in step 2; steps 1 to {last})"
                ),
            ),
        }
    }
    let names = NamedList {
        names: ranges.iter().map(|(n, _)| n.clone()).collect(),
        at: row.at.clone(),
    };
    resolve_held_inputs(table, buttons, Row::Interlock, Some(&names), diags)
        .into_iter()
        .map(|input| Interlock {
            input,
            steps: ranges
                .iter()
                .find(|(n, _)| n.as_str() == input.as_str())
                .and_then(|(_, steps)| *steps),
        })
        .collect()
}

/// The SETTINGS rows `start permissive` and `interlock` (`label`):
/// machine inputs the table does not wait for, that must be on for a cycle
/// to start, or stay on. Each must be a name a machine input may have, and
/// neither an output nor an input the table waits for (that one's value
/// belongs to its step); else E030 at the cell.
pub fn resolve_held_inputs(
    table: &StepTable,
    buttons: &[String],
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
