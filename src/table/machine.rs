//! The rules a table keeps on the machine it runs on: valves that can stop
//! at middle positions (E031), a home order that fits the table (E030,
//! W006), and signal names the operating modes take for their buttons.

use super::{Actuator, Step, StepTable};
use crate::actuator::Valves;
use crate::diag::{CellPos, Code, Diagnostics, Location};
use crate::read::Grid;

/// What a table is checked against besides its own rules: the machine it
/// runs on and the program's options.
#[derive(Debug, Clone, Copy)]
pub struct Machine<'a> {
    pub valves: &'a Valves,
    pub home_order: Option<&'a [Vec<u32>]>,
    /// Where the home order was given: its SETTINGS cell, or `None` for
    /// the command line (`--home-order`).
    pub home_order_at: Option<&'a Location>,
    /// Whether the program has the reset mode, which uses the home order.
    pub reset: bool,
    /// The (lower-case) names of the operating-mode buttons the program has
    /// (`stop`, `estop`, …): taken only when their mode is on.
    pub buttons: &'a [String],
    /// A Festo FST file is written: the 9 characters it keeps of a name
    /// may not read as a reserved word or a button either.
    pub fst: bool,
}

/// Checks a built table against the machine it runs on: the valve types,
/// the home order (checked whether or not the reset mode uses it) and the
/// names the operating modes take.
pub fn check_machine(table: &StepTable, machine: &Machine, grid: &Grid, diags: &mut Diagnostics) {
    // A valve given by name (`--valve clamp=vacuum`) is known only now.
    check_positions(&table.actuators, &table.steps, machine.valves, grid, diags);
    check_valves(table, machine.valves, grid, diags);
    check_home_order(table, machine, grid, diags);
    check_button_names(table, machine, grid, diags);
}

/// A machine input or output may be called `stop` unless the program has a
/// STOP button of that name (and likewise for the other buttons): what the
/// buttons add to the one name check ([`crate::names::signal_problem`]),
/// which the table's own build ran without them. Said at the name's first
/// cell, whether a wait, a jump or an output switch.
fn check_button_names(table: &StepTable, machine: &Machine, grid: &Grid, diags: &mut Diagnostics) {
    let buttons = machine.buttons;
    for name in table.inputs.iter().chain(&table.outputs) {
        let name = name.as_str();
        // Said by the table's own build already.
        if crate::names::signal_problem(name, &[], machine.fst).is_some() {
            continue;
        }
        let why = crate::names::signal_problem(name, buttons, machine.fst)
            .or_else(|| alias_problem(name, buttons));
        if let (Some(why), Some(cell)) = (why, first_use(table, name)) {
            diags.error(Code::E015BadName, grid.location(cell), why);
        }
    }
}

/// A signal named as a button's alias (`emergency_stop` beside the ESTOP
/// button): `simulate --press EMERGENCY_STOP@1s` would find two signals of
/// one name. Only the whole name: the alias is no PLC symbol, so FST's
/// 9 characters do not matter.
fn alias_problem(name: &str, buttons: &[String]) -> Option<String> {
    let (button, alias) = buttons.iter().find_map(|b| {
        crate::names::button_alias(b)
            .filter(|a| a.eq_ignore_ascii_case(name))
            .map(|a| (b, a))
    })?;
    Some(format!(
        "\"{name}\" cannot name a machine signal while the program has the operating-mode button {}: scenarios (simulate --press {alias}@…) call that button {alias}; rename the signal, or leave that mode out",
        button.to_ascii_uppercase()
    ))
}

/// The first cell (in step order) that names a machine input or output.
fn first_use(table: &StepTable, name: &str) -> Option<CellPos> {
    table.steps.iter().find_map(|s| {
        let waits = s.waits.iter().filter(|w| w.input.as_str() == name);
        let jumps = s.jumps.iter().filter(|j| j.input.as_str() == name);
        let switches = s.switches.iter().filter(|w| w.output.as_str() == name);
        waits
            .map(|w| w.cell)
            .chain(jumps.map(|j| j.cell))
            .chain(switches.map(|w| w.cell))
            .min()
    })
}

/// Where a message about the home order goes: on its SETTINGS cell, or on
/// the file with the words naming `--home-order` to end the message.
pub fn home_order_place(at: Option<&Location>, file: &str) -> (Location, &'static str) {
    match at {
        Some(at) => (at.clone(), ""),
        None => (
            Location {
                file: file.to_string(),
                sheet: None,
                cell: None,
            },
            " (--home-order)",
        ),
    }
}

/// A home order is checked against the table whether or not it is used,
/// and a home order without the reset mode that uses it is said, so that a
/// forgotten `reset` is not silently a no-op.
fn check_home_order(table: &StepTable, machine: &Machine, grid: &Grid, diags: &mut Diagnostics) {
    let Some(order) = machine.home_order else {
        return;
    };
    let (at, source) = home_order_place(machine.home_order_at, &grid.file);
    if let Err(message) = table.home_stages(Some(order)) {
        diags.error(Code::E030BadSetting, at, format!("{message}{source}"));
    } else if !machine.reset {
        diags.warning(
            Code::W006NoEffect,
            at,
            format!("the home order is used by the reset mode only, which is not on: add reset to the modes, or leave the home order out{source}"),
        );
    }
}

/// A kind that holds only so many positions (a vacuum gripper: released 0,
/// held 1) cannot be asked for more: E045 at the first move past them,
/// whether that move is the highest or one in the middle. Returns the
/// actuators refused.
pub(super) fn check_positions(
    actuators: &[Actuator],
    steps: &[Step],
    valves: &Valves,
    grid: &Grid,
    diags: &mut Diagnostics,
) -> Vec<u32> {
    let mut refused = Vec::new();
    for actuator in actuators {
        let kind = valves.of(actuator.number, actuator.max_position);
        let Some(highest) = kind.highest_position() else {
            continue;
        };
        let asked = |m: &&crate::table::Move| m.actuator == actuator.number;
        let Some(m) = steps
            .iter()
            .flat_map(|s| &s.moves)
            .filter(asked)
            .find(|m| m.to > highest || (m.to > 0 && actuator.max_position > highest))
        else {
            continue;
        };
        let n = actuator.number;
        // Within its positions, the move is refused for the higher one the
        // table asks elsewhere, which makes it a middle position.
        let asks = if m.to > highest {
            format!("asks C{n} for position {}", m.to)
        } else {
            format!(
                "makes position {} a middle position of C{n}, since the table also asks C{n} for position {}",
                m.to, actuator.max_position
            )
        };
        diags.error(
            Code::E045KindCannotHold,
            grid.location(m.cell),
            format!(
                "\"{}\" {asks}, but C{n} is a {} (valve type {kind}), which has positions {} only ({})",
                m.notation(),
                kind.noun(),
                if highest == 1 { "0 and 1".to_string() } else { format!("0 to {highest}") },
                kind.positions_said(n),
            ),
        );
        refused.push(n);
    }
    refused
}

/// A middle position needs a valve with a centre: a 5/2 valve cannot stop a
/// piston between its ends. Names the cell of the first move that asks for it.
fn check_valves(table: &StepTable, valves: &Valves, grid: &Grid, diags: &mut Diagnostics) {
    for actuator in table.actuators.iter().filter(|a| a.has_middle_positions()) {
        let valve = valves.of(actuator.number, actuator.max_position);
        // A kind with fewer positions than asked is said once, by E045.
        if valve.has_centre() || valve.highest_position().is_some() {
            continue;
        }
        let Some(m) = table
            .steps
            .iter()
            .flat_map(|s| &s.moves)
            .find(|m| m.actuator == actuator.number && actuator.is_middle(m.to))
        else {
            continue;
        };
        let centred = crate::actuator::ActuatorKind::centred();
        diags.error(
            Code::E031ValveCannotStop,
            grid.location(m.cell),
            format!(
                "\"{}\" stops C{} at middle position {}, but its valve is {valve}, which cannot stop a piston between its ends (use {})",
                m.notation(),
                actuator.number,
                m.to,
                crate::diag::or_list(&centred)
            ),
        );
    }
}
