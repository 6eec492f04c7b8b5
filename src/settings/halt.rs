//! The SETTINGS sheet's `hold-safe` and `de-energise on halt` rows: which
//! outputs may stay on in a stopped machine, which the program switches
//! off when it halts. The names are read here; what they stand for is
//! decided against the table (`resolve`), where an unknown one is an error
//! at its cell.

use std::collections::{BTreeMap, BTreeSet};

use crate::actuator::{CoilSet, Valves};
use crate::cell::Sign;
use crate::diag::{Code, Diagnostics, Location};
use crate::program::{Coils, HaltPolicy, Signal, StopAction};
use crate::symbols::Naming;
use crate::table::StepTable;

mod inputs;
pub use inputs::{resolve_held_inputs, resolve_interlocks};

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
fn outputs_named(
    table: &StepTable,
    valves: &Valves,
    naming: &Naming,
    name: &str,
) -> Option<Vec<Signal>> {
    let lower = name.to_ascii_lowercase();
    // The engineer's names: `clamp` is C1, `clamp_out` its coil + (under
    // any designation scheme).
    if let Some(n) = naming.actuator_named(name) {
        return outputs_named(table, valves, &Naming::default(), &format!("C{n}"));
    }
    let coils = table.actuators.iter().flat_map(|a| {
        let pmax = a.max_position;
        let actuator = a.number;
        Coils::of(valves.of(actuator, pmax), actuator).signals()
    });
    for coil in coils {
        // Its identifier (`y1p`), ISO designation (`1M1`) or the
        // engineer's name (`clamp_out`); the paper's `y1+` is read below.
        let aliases = naming.aliases(coil, table);
        if aliases.iter().any(|a| a.eq_ignore_ascii_case(lower.trim())) {
            return Some(vec![coil]);
        }
    }
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
        return Some(Coils::of(valves.of(actuator, pmax), actuator).signals());
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
    let single = valves.of(actuator, pmax).coils() == CoilSet::Single;
    match (sign, single) {
        (Some(sign), false) => Some(vec![Signal::Coil { actuator, sign }]),
        (None, true) => Some(vec![Signal::SingleCoil { actuator }]),
        _ => None,
    }
}

/// Where a setting is, for a message that names a second place: the sheet
/// and cell (`SETTINGS!B3`), or the command line.
pub fn place(at: &Location) -> String {
    match (&at.sheet, at.cell) {
        (Some(sheet), Some(cell)) => format!("{sheet}!{}", cell.a1()),
        (None, Some(cell)) => format!("{}:{}", cell.row + 1, cell.col + 1),
        (Some(sheet), None) => sheet.clone(),
        (None, None) => "the command line".to_string(),
    }
}

/// What a row says `output` does, in words: `keeps vacuum on`.
fn verb(action: StopAction, output: &str) -> String {
    match action {
        StopAction::Hold => format!("keeps {output} on"),
        StopAction::Off => format!("switches {output} off"),
        StopAction::OffAfter(ms) => format!(
            "switches {output} off after {}",
            crate::cell::duration_text(ms)
        ),
    }
}

/// What each output does at one event (a halt, the emergency stop), with
/// the row that says so: two rows that say different things of one output
/// are E030 at the later one, naming both cells.
struct EventActions<'r> {
    /// `at a halt`, `at an emergency stop`.
    event: &'static str,
    said: BTreeMap<Signal, (StopAction, Row, &'r NamedList)>,
}

impl<'r> EventActions<'r> {
    fn new(event: &'static str) -> Self {
        EventActions {
            event,
            said: BTreeMap::new(),
        }
    }

    fn say(
        &mut self,
        row: Row,
        list: &'r NamedList,
        actions: &BTreeMap<Signal, StopAction>,
        diags: &mut Diagnostics,
    ) {
        for (signal, action) in actions {
            match self.said.get(signal) {
                Some((other, other_row, other_list)) if *other_row != row && other != action => {
                    diags.error(
                        Code::E030BadSetting,
                        list.at.clone(),
                        format!(
                            "{}: this row {} {}, but {} at {} {}; say one or the other",
                            row.label(),
                            verb(*action, &signal.symbol()),
                            self.event,
                            other_row.label(),
                            place(&other_list.at),
                            verb(*other, "it")
                        ),
                    );
                }
                Some(_) => {}
                None => {
                    self.said.insert(*signal, (*action, row, list));
                }
            }
        }
    }

    /// The outputs given `wanted`.
    fn with(&self, wanted: impl Fn(StopAction) -> bool) -> BTreeSet<Signal> {
        self.said
            .iter()
            .filter(|(_, (action, _, _))| wanted(*action))
            .map(|(signal, _)| *signal)
            .collect()
    }
}

/// The outputs a row of plain names (`hold-safe`, `de-energise on halt`,
/// `hold on estop`) lists, each doing `action`; an unknown name, or an
/// output named twice, is E030 at the row's cell.
fn listed(
    table: &StepTable,
    valves: &Valves,
    naming: &Naming,
    row: Row,
    list: &NamedList,
    action: StopAction,
    diags: &mut Diagnostics,
) -> BTreeMap<Signal, StopAction> {
    let mut actions = BTreeMap::new();
    for name in &list.names {
        match outputs_named(table, valves, naming, name) {
            Some(signals) => {
                for signal in signals {
                    if actions.insert(signal, action).is_some() {
                        twice(row, list, signal, diags);
                    }
                }
            }
            None => not_an_output(table, valves, row, list, name, diags),
        }
    }
    actions
}

/// E030: one row names an output twice (`vacuum, vacuum`; `C1, y1+`).
fn twice(row: Row, list: &NamedList, signal: Signal, diags: &mut Diagnostics) {
    diags.error(
        Code::E030BadSetting,
        list.at.clone(),
        format!("{}: {} is named twice", row.label(), signal.symbol()),
    );
}

/// The halt policy the rows give (`hold-safe`, `de-energise on halt`,
/// `hold on estop`, and `on stop`, `on estop`, `on halt` with an action per
/// output). An unknown name, an output named twice in a row, and two rows
/// that say different things of one output at one event (`hold on estop |
/// vacuum` beside `on estop | vacuum off`; `hold-safe | heater` beside `on
/// halt | heater off`) are E030 at the row's cell, naming the other's.
pub fn resolve(
    table: &StepTable,
    valves: &Valves,
    naming: &Naming,
    rows: &NamedRows,
    diags: &mut Diagnostics,
) -> HaltPolicy {
    let actions_of =
        |row: Row, diags: &mut Diagnostics| -> Option<(&NamedList, BTreeMap<Signal, StopAction>)> {
            let list = rows.get(&row)?;
            let actions = match row {
                Row::HoldSafe | Row::HoldOnEstop => {
                    listed(table, valves, naming, row, list, StopAction::Hold, diags)
                }
                Row::OffOnHalt => listed(table, valves, naming, row, list, StopAction::Off, diags),
                _ => stop_actions(table, valves, naming, row, list, diags),
            };
            Some((list, actions))
        };
    // A halt: hold-safe is `hold`, de-energise on halt is `off`.
    let mut halt = EventActions::new("at a halt");
    let mut on_halt = BTreeMap::new();
    for row in [Row::HoldSafe, Row::OffOnHalt, Row::OnHalt] {
        if let Some((list, actions)) = actions_of(row, diags) {
            halt.say(row, list, &actions, diags);
            refuse_drives_through_halt(table, valves, row, list, &actions, diags);
            if row == Row::OnHalt {
                on_halt = actions;
            }
        }
    }
    let mut estop = EventActions::new("at an emergency stop");
    let mut on_estop = BTreeMap::new();
    let mut held_at_estop = BTreeSet::new();
    for row in [Row::HoldOnEstop, Row::OnEstop] {
        if let Some((list, actions)) = actions_of(row, diags) {
            estop.say(row, list, &actions, diags);
            if row == Row::OnEstop {
                on_estop = actions;
            } else {
                held_at_estop = actions.keys().copied().collect();
            }
        }
    }
    refuse_motion_through_estop(table, valves, rows, &held_at_estop, &on_estop, diags);
    let on_stop = actions_of(Row::OnStop, diags)
        .map(|(list, actions)| {
            refuse_drives_through_halt(table, valves, Row::OnStop, list, &actions, diags);
            actions
        })
        .unwrap_or_default();
    // The emergency stop halts: what it keeps on (or lets run on), a halt
    // may not switch off or time out.
    for (signal, (kept, estop_row, estop_list)) in &estop.said {
        let Some((ended, halt_row, halt_list)) = halt.said.get(signal) else {
            continue;
        };
        if *kept != StopAction::Off && *ended != StopAction::Hold {
            diags.error(
                Code::E030BadSetting,
                estop_list.at.clone(),
                format!(
                    "the emergency stop keeps {} on, but a halt switches it off, and the emergency stop halts ({} at {} {}, {} at {} {}); say one or the other",
                    signal.symbol(),
                    estop_row.label(),
                    place(&estop_list.at),
                    verb(*kept, "it"),
                    halt_row.label(),
                    place(&halt_list.at),
                    verb(*ended, "it"),
                ),
            );
        }
    }
    let mut policy = HaltPolicy {
        hold_safe: halt.with(|a| a == StopAction::Hold),
        off_on_halt: halt.with(|a| a == StopAction::Off),
        hold_on_estop: estop.with(|a| a == StopAction::Hold),
        on_stop,
        on_estop,
        on_halt,
    };
    hold_parts_by_default(table, valves, &mut policy);
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

/// A kind whose output holds a part (a vacuum gripper) keeps it on through
/// an EMERGENCY STOP unless a row says what it does there (`on estop`) or
/// switches it off at every halt: switched off, the part would drop
/// wherever the arm stood. A STOP that acts at once (an `on stop` row
/// naming other outputs) keeps it too, unless that row names it: the
/// milder stop must not drop what the emergency stop keeps. A halt keeps
/// every output as it is already.
fn hold_parts_by_default(table: &StepTable, valves: &Valves, policy: &mut HaltPolicy) {
    for a in &table.actuators {
        let kind = valves.of(a.number, a.max_position);
        if !kind.holds_part() {
            continue;
        }
        for coil in Coils::of(kind, a.number).signals() {
            if policy.off_on_halt.contains(&coil) {
                continue;
            }
            if !policy.on_estop.contains_key(&coil) {
                policy.hold_on_estop.insert(coil);
            }
            if !policy.on_stop.is_empty() {
                policy.on_stop.entry(coil).or_insert(StopAction::Hold);
            }
        }
    }
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
        let kind = valves.of(actuator, pmax);
        // A gripper's vacuum holds the part and moves nothing.
        if kind.holds_part() {
            continue;
        }
        let why = kind.kept_through_estop(&signal.symbol(), actuator);
        diags.error(
            Code::E030BadSetting,
            list.at.clone(),
            format!("{}: {why}", row.label()),
        );
    }
}

/// A halt stops every drive: a watchdog halts because a limit switch is
/// dead, and a contactor a halt row kept on (or let run on) would drive
/// into the end stop for good. So does a STOP that acts at once: it ends
/// the watchdog and the homing that would cut the drive. E030 at the
/// row's cell, once per drive.
fn refuse_drives_through_halt(
    table: &StepTable,
    valves: &Valves,
    row: Row,
    list: &NamedList,
    actions: &BTreeMap<Signal, StopAction>,
    diags: &mut Diagnostics,
) {
    let mut named = BTreeSet::new();
    for (signal, action) in actions {
        let Signal::Coil { actuator, .. } = *signal else {
            continue;
        };
        let pmax = table.actuator(actuator).map_or(1, |a| a.max_position);
        if *action == StopAction::Off
            || !valves.of(actuator, pmax).is_drive()
            || !named.insert(actuator)
        {
            continue;
        }
        let event = if row == Row::OnStop { "STOP" } else { "a halt" };
        diags.error(
            Code::E030BadSetting,
            list.at.clone(),
            format!(
                "{}: {} is a contactor of drive C{actuator} (valve type motor): kept on at {event}, it keeps the drive running, into its end stop when its limit switch is dead (the watchdog and the homing that would cut it are over); {event} stops every drive",
                row.label(),
                signal.symbol(),
            ),
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
        let coils = Coils::of(valves.of(a.number, a.max_position), a.number).signals();
        let symbols: Vec<String> = coils.into_iter().map(Signal::symbol).collect();
        known.push(symbols.join(", "));
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
    naming: &Naming,
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
                // `2 0s` is no time: a space splits its number.
                let ms = match crate::cell::split_number(&time.join(" ")) {
                    true => None,
                    false => crate::cell::parse_duration_in(&time.concat(), 10..=655_000),
                };
                let time = time.concat();
                if ms.is_some() && crate::cell::without_unit(&time) {
                    diags.warning(
                        Code::W007Assumed,
                        list.at.clone(),
                        format!(
                            "{label}: \"{item}\": {}",
                            crate::cell::read_as_seconds(&time)
                        ),
                    );
                }
                ms.map(StopAction::OffAfter)
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
        match outputs_named(table, valves, naming, name) {
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
