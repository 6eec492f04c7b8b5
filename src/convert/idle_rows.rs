//! SETTINGS rows about an event the program does not have (an `on stop`
//! row without the STOP button): W006, and what manual mode still reads.

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
