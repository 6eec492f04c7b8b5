//! What the Ladder body (`--formats ld`) cannot draw yet, refused before
//! anything is written: a timer. The step program restarts a timer in the
//! scan its step fires (a TON called with IN off, then on); set and reset
//! coils alone cannot do that, so a program with a dwell, the watchdog or a
//! run-on has no Ladder body (E043), rather than one that times a scan late.

use crate::diag::{Code, Diagnostic, Location, Severity};
use crate::program::{Action, Signal, StepProgram};
use crate::settings::Settings;
use crate::table::StepTable;

/// E043 at the first timer of `program`, if the Ladder body was asked for.
pub fn timers_refused(
    table: &StepTable,
    settings: &Settings,
    program: &StepProgram,
) -> Vec<Diagnostic> {
    if !settings.formats.contains(&crate::emit::OutputKind::Ladder) {
        return Vec::new();
    }
    let actions = program.steps.iter().flat_map(|s| {
        let jumps = s.jumps.iter().flat_map(|j| &j.actions);
        s.actions.iter().chain(jumps)
    });
    let started = actions
        .chain(program.rungs.iter().flat_map(|r| &r.actions))
        .find_map(|a| match *a {
            Action::StartTimer(timer, _) => Some(timer),
            _ => None,
        });
    let Some(timer) = started else {
        return Vec::new();
    };
    let whole_file = Location {
        file: table.file.clone(),
        sheet: None,
        cell: None,
    };
    let setting = |label: &str| settings.cells.get(label).cloned();
    let (location, what) = match timer {
        Signal::Dwell(n) => {
            let cell = table
                .steps
                .iter()
                .flat_map(|s| &s.dwells)
                .find(|d| d.number == n)
                .map(|d| d.cell);
            let at = Location {
                file: table.file.clone(),
                sheet: table.sheet.clone(),
                cell,
            };
            (Some(at), "this dwell".to_string())
        }
        Signal::Watchdog => (
            setting("supervision").or_else(|| setting("safety")),
            "the step watchdog (--safety watchdog or a supervision time)".to_string(),
        ),
        Signal::RunOn(_) => (setting("on stop"), "this run-on after STOP".to_string()),
        _ => (None, "a timer".to_string()),
    };
    vec![Diagnostic {
        severity: Severity::Error,
        code: Code::E043LadderTimer,
        location: location.unwrap_or(whole_file),
        message: format!(
            "the Ladder body (--formats ld) has no timers yet, and the program needs {what}: leave ld out of --formats (the ST, SFC and the other programs time it), or the timer out of the table"
        ),
    }]
}
