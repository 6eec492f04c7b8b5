//! SETTINGS rows about an event the program does not have (an `on stop`
//! row without the STOP button): W006, and what manual mode still reads;
//! a halt nothing can acknowledge: W012; an interlock whose halt leaves
//! pistons driving that their valve could stop: W013.

use crate::diag::{Code, Diagnostics};
use crate::settings::Settings;
use crate::settings::halt::Row;

/// A SETTINGS row about an event the program does not have does nothing:
/// W006.
pub(super) fn rows_without_their_event(effective: &Settings, diags: &mut Diagnostics) {
    let named = &effective.named;
    let program = &effective.program;
    let no_estop = (
        "the program has no emergency stop (--modes estop)",
        "nothing named here is done",
    );
    let no_halt = (
        "the program never halts without the plausibility or watchdog check, the emergency stop or an interlock (--safety, --modes estop)",
        "the outputs named stay as the sequence left them",
    );
    let no_stop = (
        "the program has no STOP button (--modes stop)",
        "nothing named here is ever done",
    );
    for (row, has, (missing, so)) in [
        (Row::HoldOnEstop, program.modes.estop, no_estop),
        (Row::OnEstop, program.modes.estop, no_estop),
        (Row::OnStop, program.modes.stop, no_stop),
        (Row::OffOnHalt, program.halts(), no_halt),
        (Row::OnHalt, program.halts(), no_halt),
    ] {
        if let Some(list) = named.get(&row)
            && !has
        {
            // Manual mode keeps on what a row holds whether or not its
            // event exists (rt7 F12): "nothing is done" would be false.
            let manual =
                program.modes.manual && matches!(row, Row::HoldOnEstop | Row::OnStop | Row::OnHalt);
            let so = if manual {
                "only manual mode reads it: what it keeps on stays on into manual until its actuator is jogged"
            } else {
                so
            };
            diags.warning(
                Code::W006NoEffect,
                list.at.clone(),
                format!("{}: {missing}; {so}", row.label()),
            );
        }
    }
}

/// A halt without RESET is for good: the safety checks, an interlock and
/// an `on stop` row each stop the machine mid-cycle, and without the
/// `reset` mode no rung ever clears the halt or brings the machine home
/// (START needs every actuator home). The emergency stop brings `reset`
/// with it; these do not, so W012 at what asked for each (its SETTINGS
/// cell, or the file for a command-line option).
pub(super) fn halts_for_good(
    table: &crate::table::StepTable,
    effective: &Settings,
    diags: &mut Diagnostics,
) {
    let program = &effective.program;
    if program.modes.reset {
        return;
    }
    let whole_file = crate::diag::Location {
        file: table.file.clone(),
        sheet: None,
        cell: None,
    };
    let safety = program.safety;
    let checks: Vec<&str> = [
        (safety.watchdog, "the step watchdog"),
        (safety.plausibility, "the plausibility check"),
    ]
    .into_iter()
    .filter_map(|(on, name)| on.then_some(name))
    .collect();
    let mut found = Vec::new();
    if !checks.is_empty() {
        let at = effective.cells.get("safety").cloned();
        found.push((
            at.unwrap_or_else(|| whole_file.clone()),
            format!(
                "{} {} the machine on an alarm",
                checks.join(" and "),
                if checks.len() > 1 { "halt" } else { "halts" }
            ),
        ));
    }
    if !program.interlocks.is_empty()
        && let Some(list) = effective.named.get(&Row::Interlock)
    {
        found.push((
            list.at.clone(),
            "interlock: an input going off halts the machine".to_string(),
        ));
    }
    // A machine with no actuator is home wherever STOP leaves it.
    if program.stops_now()
        && !table.actuators.is_empty()
        && let Some(list) = effective.named.get(&Row::OnStop)
    {
        found.push((
            list.at.clone(),
            "on stop: STOP abandons the cycle where the machine stands".to_string(),
        ));
    }
    for (at, what) in found {
        diags.warning(
            Code::W012HaltForGood,
            at,
            format!(
                "{what}, and the program has no RESET to acknowledge it or bring the machine home: after the first one the machine stands where it stopped, since START needs every actuator home (a PLC restart clears a halt, not a machine away from home); add the reset mode (--modes reset, or `reset` in the SETTINGS modes row)"
            ),
        );
    }
}

/// An interlock "halts the machine where it is", but a halt leaves every
/// coil as the sequence left it unless a halt row says otherwise: a piston
/// under way when the guard opens drives on to its end. A closed-centre
/// valve would stop it with its coils off, so W013 at the `interlock`
/// cell names those actuators and the row that stops them. (A 5/2 valve
/// keeps its position without its coils and a drive's halt cuts it
/// already; an exhausted or pressurised centre lets it drift.)
pub(super) fn guard_leaves_motion(
    table: &crate::table::StepTable,
    effective: &Settings,
    diags: &mut Diagnostics,
) {
    let program = &effective.program;
    let Some(list) = effective.named.get(&Row::Interlock) else {
        return;
    };
    if program.interlocks.is_empty() {
        return;
    }
    let valves = &effective.simulation.machine.valves;
    let halt = &program.halt;
    let stopped = |s: &crate::program::Signal| {
        halt.off_on_halt.contains(s)
            || halt.on_halt.get(s) == Some(&crate::program::StopAction::Off)
    };
    let driving: Vec<String> = table
        .actuators
        .iter()
        .filter(|a| {
            // Only a closed centre holds the piston with its coils off: an
            // exhausted one lets it drift, a pressurised one pushes it out.
            let kind = valves.of(a.number, a.max_position);
            kind == crate::actuator::ActuatorKind::Closed53
                && (crate::program::Coils::of(kind, a.number).signals().iter())
                    .any(|coil| !stopped(coil))
        })
        .map(|a| format!("C{}", a.number))
        .collect();
    if driving.is_empty() {
        return;
    }
    diags.warning(
        Code::W013GuardLeavesMotion,
        list.at.clone(),
        format!(
            "interlock: its halt leaves the coils of {} as the sequence left them, so a piston under way when the input goes off drives on to its end; their closed centres would stop them where they are: name them in `de-energise on halt` (or `on halt | … off`)",
            crate::diag::or_list(&driving).replace(" or ", " and ")
        ),
    );
}
