//! A scenario's run printed as a step table: every event as it happened,
//! every step as it fired with its time and what it does, each alarm as
//! it came on and went off, the problems the run found, and where the
//! machine stood at the end.

use std::fmt::Write;

use super::{Event, ScenarioReport};
use crate::program::{RungKind, Signal, StepKind, StepProgram};
use crate::simulate::ProblemKind;

/// What the table names things by: the naming authority's designation of
/// a signal and of an actuator.
pub struct Names<'a> {
    pub signal: &'a dyn Fn(Signal) -> String,
    pub actuator: &'a dyn Fn(u32) -> String,
    /// A finding's text (in the method's symbols) in the chosen scheme.
    pub explain: &'a dyn Fn(&str) -> String,
}

/// One line of the table, at its time; events sort before a step that
/// fires in the same scan (the scan reads what the event did).
fn lines(
    report: &ScenarioReport,
    events: &[Event],
    program: &StepProgram,
    names: &Names,
) -> Vec<(u64, u8, String)> {
    let mut lines = Vec::new();
    for (t, k) in &report.happened {
        let event = &events[*k];
        let mut said = format!("{}: {}", event.written, describe(event, names));
        if report.still_down.contains(k) {
            said.push_str(
                " while still down: no new press for the program (a press holds its button 0.1 s, two scans at least)",
            );
        } else if let Some(button) = (*t == 0)
            .then(|| event.act.signal())
            .filter(|&b| event.act.presses(b) && program.no_press_at_power_up(b))
        {
            // The program takes the button on its edge, and one held
            // through power-up as none (no start, no homing by itself).
            said.push_str(&format!(
                " at power-up: no press for the program, which takes {} held through power-up as none (press it once the PLC runs, a scan later or more)",
                (names.signal)(button)
            ));
        }
        lines.push((*t, 0, said));
    }
    if let Some(press) = report.auto_start_ms {
        lines.push((press, 0, "START pressed (as in the proof)".to_string()));
    }
    // Each step by the SFC step it enters, the number `@stepK` takes: the
    // closing transition enters step 0.
    for (t, number) in &report.fired {
        let index = program.steps.iter().position(|s| s.number == *number);
        let step = index.map_or(*number, |i| program.step_entered(i));
        let title = match index.map(|i| &program.steps[i]) {
            Some(s) if s.kind == StepKind::Table => s.title.clone(),
            Some(_) => "end of cycle".to_string(),
            None => String::new(),
        };
        lines.push((*t, 1, format!("step {step:<3} {title}")));
    }
    for (t, step, by) in &report.abandoned {
        lines.push((*t, 1, abandoned_line(*step, *by, names)));
    }
    for (t, signal, on) in alarm_changes(report) {
        let what = if on { "on" } else { "off" };
        lines.push((t, 2, format!("{} {what}", (names.signal)(signal))));
    }
    for (t, change) in homing_changes(report) {
        let what = match change {
            Homing::Starts => "homing starts",
            Homing::Done => "homing done",
            Homing::Abandoned => "homing abandoned, the machine not home",
            Homing::Halted => "homing halted: RESET homes on",
        };
        lines.push((t, 2, what.to_string()));
    }
    for p in problems(report) {
        lines.push((
            p.time_ms,
            3,
            format!("problem: {}", (names.explain)(&p.message)),
        ));
    }
    lines.sort_by_key(|(t, order, _)| (*t, *order));
    lines
}

/// The problems the run found but motion while the program homes the
/// machine, which is what RESET asked for. A problem is timed at its
/// scan's start: that scan homes the machine when homing was on before it
/// (the scan that ends homing still moves the last cylinder home) or after
/// it (the scan that reads RESET).
pub fn problems(report: &ScenarioReport) -> impl Iterator<Item = &crate::simulate::Problem> {
    let homed = |t: u64| report.at(t).is_some_and(|s| s.homing);
    let homing = move |t: u64| homed(t) || homed(t + 1);
    report
        .problems
        .iter()
        .filter(move |p| !(is_motion(p.kind) && homing(p.time_ms)))
}

/// `step 0   cycle abandoned in step 2: manual mode (MAN_MODE)`: the
/// sequence sent back to step 0 by a rung, with what did it, printed where
/// a step that fires is.
fn abandoned_line(step: usize, by: RungKind, names: &Names) -> String {
    let why = match by {
        RungKind::Manual => format!("manual mode ({})", (names.signal)(Signal::ManualMode)),
        RungKind::Homing => format!("{} homes the machine", (names.signal)(Signal::Reset)),
        RungKind::StopNow => format!("{} at once", (names.signal)(Signal::Stop)),
        other => other.label().to_lowercase(),
    };
    format!(
        "step {:<3} cycle abandoned in step {step}: {why}",
        crate::program::INITIAL_STEP
    )
}

/// `STOP pressed`, with the signal by its designation when it differs.
fn describe(event: &Event, names: &Names) -> String {
    let signal = event.act.signal();
    let designation = (names.signal)(signal);
    let said = event.act.describe();
    if designation == signal.symbol() {
        said
    } else {
        format!("{said} ({designation})")
    }
}

/// Each sample with the time its scan started (the sample is taken at
/// its end): the time the table prints steps and events at.
fn scans(report: &ScenarioReport) -> impl Iterator<Item = (u64, &super::Sample)> {
    let starts = std::iter::once(0).chain(report.samples.iter().map(|s| s.time_ms));
    starts.zip(&report.samples)
}

fn is_motion(kind: ProblemKind) -> bool {
    matches!(kind, ProblemKind::OutsideStep | ProblemKind::RanThrough)
}

/// When the program started and ended homing the machine, and whether
/// every cylinder was home then.
fn homing_changes(report: &ScenarioReport) -> Vec<(u64, Homing)> {
    let mut was = false;
    let mut changes = Vec::new();
    for (scan, sample) in scans(report) {
        // A halt stops the homing where it is; the RESET that acknowledges
        // it starts the homing again.
        let runs = sample.homing && !sample.halted;
        if runs != was {
            // Within a home sensor's window (a drive coasts onto it).
            let home = sample.positions.iter().all(|p| p.abs() < 0.05);
            let change = match (runs, home) {
                (true, _) => Homing::Starts,
                (false, _) if sample.homing => Homing::Halted,
                (false, true) => Homing::Done,
                (false, false) => Homing::Abandoned,
            };
            changes.push((scan, change));
            was = runs;
        }
    }
    changes
}

/// What the homing did at a scan.
enum Homing {
    Starts,
    Done,
    /// Ended by the EMERGENCY STOP, STOP or manual mode, not home.
    Abandoned,
    /// A halt stopped it: the next RESET starts it again.
    Halted,
}

/// When each alarm output came on and went off.
fn alarm_changes(report: &ScenarioReport) -> Vec<(u64, Signal, bool)> {
    let is_alarm = |s: &Signal| matches!(s, Signal::Alarm(_));
    let mut on: Vec<Signal> = Vec::new();
    let mut changes = Vec::new();
    for (scan, sample) in scans(report) {
        let now: Vec<Signal> = sample.outputs_on.iter().copied().filter(is_alarm).collect();
        for s in now.iter().filter(|s| !on.contains(s)) {
            changes.push((scan, *s, true));
        }
        for s in on.iter().filter(|s| !now.contains(s)) {
            changes.push((scan, *s, false));
        }
        on = now;
    }
    changes
}

/// The table, as printed by `simulate --press …`.
pub fn render(
    report: &ScenarioReport,
    events: &[Event],
    program: &StepProgram,
    actuators: &[u32],
    names: &Names,
) -> String {
    let mut out = String::from("      time  what happened\n");
    for (t, _, line) in lines(report, events, program, names) {
        let _ = writeln!(out, "  {:>6.2} s  {line}", t as f64 / 1000.0);
    }
    if let Some(last) = report.samples.last() {
        let _ = writeln!(
            out,
            "{}",
            where_it_stands(last, actuators, &program.signals, names)
        );
    }
    if let Some(cut) = report.cut_ms {
        let _ = writeln!(
            out,
            "cut at {:.2} s: a scenario runs at most {} scans one by one (quiet ones passed at once do not count)",
            cut as f64 / 1000.0,
            super::SCAN_BUDGET
        );
    }
    for event in events.iter().skip(report.happened.len()) {
        let _ = writeln!(
            out,
            "never happened: {} (the run ended first)",
            event.written
        );
    }
    if let Some(why) = no_start(report, events) {
        let _ = writeln!(out, "{why}");
    }
    out.trim_end().to_string()
}

/// Why no cycle ran when events waited for one: a START event turns off
/// the press at 0.5 s, and the START events written came after the ones
/// waiting.
fn no_start(report: &ScenarioReport, events: &[Event]) -> Option<String> {
    let waiting = report.happened.len() < events.len();
    let start = events.iter().find(|e| e.act.signal() == Signal::Start)?;
    (waiting && report.fired.is_empty() && report.auto_start_ms.is_none()).then(|| {
        format!(
            "no cycle ran: with a START event ({}) the scenario presses START only where it says, not at 0.5 s as the proof does",
            start.written
        )
    })
}

/// `ended at T s in step K; C1 at 1.00, …; on: y1+, spray`: the step, every
/// position and every output still on (but a retract coil holding its
/// cylinder home: a drive's reverse output at home is a motor running
/// into its end stop, and is listed). "At rest" only when it is: step 0,
/// every cylinder home, no homing unfinished and no other output on.
fn where_it_stands(
    last: &super::Sample,
    actuators: &[u32],
    signals: &crate::program::Signals,
    names: &Names,
) -> String {
    let home = last.positions.iter().all(|p| *p == 0.0);
    // A retract coil holding its cylinder home is how a machine rests.
    let holds_home = |s: &&Signal| {
        matches!(s, Signal::Coil { sign: crate::cell::Sign::Minus, actuator }
            if !signals.drives(*actuator)
                && actuators.iter().zip(&last.positions).any(|(n, p)| n == actuator && *p == 0.0))
    };
    let on: Vec<String> = last
        .outputs_on
        .iter()
        .filter(|s| !holds_home(s))
        .map(|s| (names.signal)(*s))
        .collect();
    let step = if last.homing {
        format!("step {}, homing not done", last.step)
    } else if last.halted {
        let reset = signals.inputs.contains(&Signal::Reset);
        let why = if reset { ": RESET before START" } else { "" };
        format!("step {}, halted{why}", last.step)
    } else if last.step == 0 && home && on.is_empty() {
        "step 0 (at rest)".to_string()
    } else {
        format!("step {}", last.step)
    };
    let places: Vec<String> = actuators
        .iter()
        .zip(&last.positions)
        .map(|(n, p)| format!("{} at {p:.2}", (names.actuator)(*n)))
        .collect();
    let mut line = format!("ended at {:.2} s in {step}", last.time_ms as f64 / 1000.0);
    if !places.is_empty() {
        line.push_str(&format!("; {}", places.join(", ")));
    }
    if !on.is_empty() {
        line.push_str(&format!("; on: {}", on.join(", ")));
    }
    line
}
