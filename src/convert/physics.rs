//! A valid table's program that fails its simulation is either a bug in
//! steptable or a machine set up so that no program could run the cycle: a
//! valve that cannot hold its load at a middle stop, a stroke so fast that a
//! sensor passes between two scans, a scan too slow for the strokes. The
//! simulation is the judge: put one setting back to its default, and if the
//! cycle then runs, that setting is the reason, said to the engineer as an
//! input error (E032) rather than reported as a bug.

use super::{Failure, build_program};
use crate::actuator::ActuatorKind;
use crate::diag::{Code, Diagnostic, Location, Severity};
use crate::program::StepProgram;
use crate::settings::Settings;
use crate::simulate::{self, SimReport, plant::Piston};
use crate::stroke::Stroke;
use crate::table::StepTable;

/// A setting put back to its default, and how to say so.
struct Change {
    /// "C3 on its default valve (53closed)".
    said: String,
    settings: Settings,
}

/// The failure to report for `table`'s program failing `report` under
/// `settings`: E032 naming the setting that stops the cycle when one does,
/// an internal error otherwise.
pub fn explain(table: &StepTable, settings: &Settings, report: &SimReport) -> Failure {
    let reason = report.reason();
    let changes = changes(table, settings);
    let runs = |settings: &Settings| {
        let program = build_program(table, settings);
        simulate::simulate(table, &program, &settings.simulation).passed
    };
    let found = changes
        .iter()
        .find(|change| runs(&change.settings))
        .map(|change| change.said.clone())
        .or_else(|| {
            // Several settings together may be to blame.
            let all = all_defaults(settings);
            (changes.len() > 1 && runs(&all))
                .then(|| "every valve, load, stroke and the scan at their defaults".to_string())
        });
    match found {
        Some(said) => Failure::Input(vec![Diagnostic {
            severity: Severity::Error,
            code: Code::E032MachineCannotRun,
            location: Location {
                file: table.file.clone(),
                sheet: None,
                cell: None,
            },
            message: format!(
                "the machine as set up cannot run this cycle: {reason}; it runs with {said}{}",
                why(table, settings)
            ),
        }]),
        None => Failure::Internal(format!(
            "the generated program fails its simulation ({reason}); the table is valid, so this is a bug in steptable: please report it with this file"
        )),
    }
}

/// Every setting that differs from its default, each put back on its own:
/// valves (with their loads) first, then loads, strokes and the scan.
fn changes(table: &StepTable, settings: &Settings) -> Vec<Change> {
    let sim = &settings.simulation;
    let mut changes = Vec::new();
    let mut with = |said: String, edit: &dyn Fn(&mut Settings)| {
        let mut changed = settings.clone();
        edit(&mut changed);
        changes.push(Change {
            said,
            settings: changed,
        });
    };
    for a in &table.actuators {
        let n = a.number;
        let default = ActuatorKind::default_for(a.max_position);
        if sim
            .machine
            .valves
            .per_actuator
            .get(&n)
            .is_some_and(|v| *v != default)
        {
            with(format!("C{n} on its default valve ({default})"), &|s| {
                s.simulation.machine.valves.per_actuator.remove(&n);
                s.simulation.machine.loads.remove(&n);
            });
        }
        if sim.machine.loads.contains_key(&n) {
            with(
                format!("C{n} under the default load (0.05 stroke/s)"),
                &|s| {
                    s.simulation.machine.loads.remove(&n);
                },
            );
        }
        if sim.machine.strokes.per_actuator.contains_key(&n) {
            with(
                format!("C{n} at the default stroke (1 s out, 1 s back)"),
                &|s| {
                    s.simulation.machine.strokes.per_actuator.remove(&n);
                },
            );
        }
    }
    if sim.machine.strokes.default != Stroke::default() {
        with("the default stroke (1 s out, 1 s back)".to_string(), &|s| {
            s.simulation.machine.strokes.default = Stroke::default()
        });
    }
    // A jump's input given later than its step lasts leaves the path
    // untaken; by default the machine gives it as the step starts.
    for name in sim.input_delays.keys() {
        with(
            format!("I:{name} at its default time (without --input-delay {name}=…)"),
            &|s| {
                s.simulation.input_delays.remove(name);
            },
        );
    }
    let default_scan = simulate::SimSettings::default().scan_ms;
    if sim.scan_ms != default_scan {
        with(format!("a {default_scan} ms scan"), &|s| {
            s.simulation.scan_ms = default_scan
        });
    }
    changes
}

/// Middle stops that only luck would make: the PLC sees a sensor at most
/// one scan after the piston reaches it and switches the valve at the end
/// of the scan that saw it, so a middle stop holds on every scan phase
/// only when its sensor stays in view for two scans. A shorter glimpse may
/// pass the simulation's one phase and overrun on the machine (whose scan
/// jitters), so it is refused before the simulation, at the move's cell.
pub fn lucky_middle_stops(table: &StepTable, settings: &Settings) -> Vec<Diagnostic> {
    let sim = &settings.simulation;
    let mut refused = Vec::new();
    if !settings.program.middle_stops {
        // Without middle stops the program does not try to stop there.
        return refused;
    }
    let mut said = std::collections::BTreeSet::new();
    for step in &table.steps {
        for m in &step.moves {
            let Some(actuator) = table.actuator(m.actuator) else {
                continue;
            };
            if m.to == 0 || m.to >= actuator.max_position || !said.insert((m.actuator, m.sign)) {
                continue;
            }
            let stroke = sim.machine.strokes.of(m.actuator);
            let piston = Piston::new(m.actuator, actuator.max_position, stroke, sim.scan_ms);
            let (full_ms, way, flag) = match m.sign {
                crate::cell::Sign::Plus => (stroke.extend_ms, "out", "extend"),
                crate::cell::Sign::Minus => (stroke.retract_ms, "back", "retract"),
            };
            let full_ms = full_ms as f64;
            let in_view = in_view_ms(&piston, sim.window, full_ms);
            if in_view >= 2.0 * sim.scan_ms as f64 {
                continue;
            }
            let n = m.actuator;
            let sensor = crate::program::Signal::Sensor {
                actuator: n,
                position: m.to,
            }
            .symbol();
            refused.push(Diagnostic {
                severity: Severity::Error,
                code: Code::E032MachineCannotRun,
                location: Location {
                    file: table.file.clone(),
                    sheet: table.sheet.clone(),
                    cell: Some(m.cell),
                },
                message: format!(
                    "C{n} stops at its middle position {} in step {}, but its sensor {sensor} is in view for only {} ms of a {full_ms:.0} ms stroke {way}, less than two {} ms scans (one to see it, one to switch the valve): whether it stops there would depend on the scan's timing; give C{n} a slower {flag} stroke (--stroke, or the SETTINGS actuator table) or a shorter scan",
                    m.to,
                    step.number,
                    tenths_below(in_view),
                    sim.scan_ms,
                ),
            });
        }
    }
    refused
}

/// How long a middle sensor sees a piston that crosses the whole stroke
/// in `full_ms`: its window spans twice its half-width.
fn in_view_ms(piston: &Piston, window: f64, full_ms: f64) -> f64 {
    2.0 * piston.window(window) * full_ms
}

/// Watchdog presets no PLC timer of every target holds: FST counts 1/100 s
/// in a 16-bit word (655.35 s at most), and a larger preset would wrap
/// round to a short one there. Refused at the step's first cell.
pub fn watchdogs_beyond_timers(table: &StepTable, program: &StepProgram) -> Vec<Diagnostic> {
    let past_timers = |sheet, cell, need: String, remedy: &str| Diagnostic {
        severity: Severity::Error,
        code: Code::E032MachineCannotRun,
        location: Location {
            file: table.file.clone(),
            sheet,
            cell,
        },
        message: format!(
            "{need}, more than the 655.35 s a PLC timer holds on every target (FST counts 1/100 s in a 16-bit word): {remedy}"
        ),
    };
    let mut refused = Vec::new();
    for (step, ms) in program.watchdogs_beyond_timers() {
        let cell = table.steps.get(step.number.wrapping_sub(1)).and_then(|s| {
            let moves = s.moves.iter().map(|m| m.cell);
            moves.chain(s.dwells.iter().map(|d| d.cell)).next()
        });
        refused.push(past_timers(
            table.sheet.clone(),
            cell,
            format!(
                "step {}'s watchdog would need {:.1} s (twice its longest move, plus its dwell, plus 1 s)",
                step.number,
                ms as f64 / 1000.0
            ),
            "shorten the step's stroke or dwell, or leave the watchdog out of --safety",
        ));
    }
    // Stages that need the same time are said once.
    let mut said = Vec::new();
    for (_, ms) in program.homing_watchdogs_beyond_timers() {
        if said.contains(&ms) {
            continue;
        }
        said.push(ms);
        refused.push(past_timers(
            None,
            None,
            format!(
                "a homing stage's watchdog would need {:.1} s (twice its slowest full retract, plus 1 s)",
                ms as f64 / 1000.0
            ),
            "shorten the stroke, or leave the watchdog out of --safety",
        ));
    }
    refused
}

fn all_defaults(settings: &Settings) -> Settings {
    let mut all = settings.clone();
    let defaults = simulate::SimSettings::default();
    all.simulation.machine = defaults.machine;
    all.simulation.scan_ms = defaults.scan_ms;
    all
}

/// The physics behind a stroke or scan that fails: the shortest time a
/// middle sensor is in view, when it is shorter than one scan.
fn why(table: &StepTable, settings: &Settings) -> String {
    let sim = &settings.simulation;
    let glimpses = table
        .actuators
        .iter()
        .filter(|a| a.max_position > 1)
        .map(|a| {
            let stroke = sim.machine.strokes.of(a.number);
            let piston = Piston::new(a.number, a.max_position, stroke, sim.scan_ms);
            let fastest = stroke.extend_ms.min(stroke.retract_ms) as f64;
            (a.number, in_view_ms(&piston, sim.window, fastest))
        })
        .filter(|(_, ms)| *ms < sim.scan_ms as f64)
        .min_by(|a, b| a.1.total_cmp(&b.1));
    match glimpses {
        Some((n, ms)) => format!(
            " (C{n}'s middle sensor is in view for {} ms of its stroke, less than one {} ms scan: the PLC cannot stop it there)",
            tenths_below(ms),
            sim.scan_ms
        ),
        None => String::new(),
    }
}

/// A time shown to a tenth, rounded down: these messages say a time is
/// *less than* a limit, and 19.96 ms rounded to "20.0" would read as not.
fn tenths_below(ms: f64) -> String {
    format!("{:.1}", (ms * 10.0).floor() / 10.0)
}

#[cfg(test)]
mod tests {
    /// Rounded to the nearest tenth, 19.96 ms would print as the 20 ms it
    /// is said to be less than.
    #[test]
    fn times_said_to_be_below_a_limit_are_rounded_down() {
        assert_eq!(super::tenths_below(19.96), "19.9");
        assert_eq!(super::tenths_below(9.0), "9.0");
        assert_eq!(super::tenths_below(0.04), "0.0");
    }
}
