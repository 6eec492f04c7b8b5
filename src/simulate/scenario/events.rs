//! The operator's events of a scenario as the command line writes them:
//! `--press STOP@step3`, `--hold STEP_MODE@0s`, `--release STEP_MODE@+4s`,
//! `--stick x21=0@4.0s`. Each is read against the program it runs on:
//! its signal by any name the naming authority gives it (paper symbol,
//! ISO designation, the engineer's name), a button only where its mode is
//! on, a step only where the program has it. Every refusal names the
//! option as written, so the engineer finds it on their command line.

use crate::cell::parse_duration_in;
use crate::program::{Area, Signal, StepProgram};
use crate::symbols::Naming;
use crate::table::StepTable;

/// The latest moment an event may name: a scenario runs every scan, and
/// ten minutes of a machine's life is more than any cycle worth watching.
pub const LATEST_MS: u32 = 600_000;

/// When an event happens.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum When {
    /// At this time of the run (milliseconds from power-up).
    At(u64),
    /// When the program enters this SFC step (0 at rest, k while table
    /// step k's moves run), the first time after the event before it: at
    /// a later scan than that event, never the one it happened in.
    Step(usize),
    /// This long after the event before it (after power-up for the first).
    After(u64),
}

/// What the operator (or a broken wire) does.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Act {
    /// Presses a button and lets go after a press's length (100 ms).
    Press(Signal),
    /// Presses a button (or turns a switch on) and keeps it there.
    Hold(Signal),
    /// Lets go of a held button.
    Release(Signal),
    /// The input reads this value from then on, whatever the machine does.
    Stick(Signal, bool),
}

impl Act {
    pub fn signal(self) -> Signal {
        match self {
            Act::Press(s) | Act::Hold(s) | Act::Release(s) | Act::Stick(s, _) => s,
        }
    }

    /// Whether it presses (or holds) the button `signal`.
    pub fn presses(self, signal: Signal) -> bool {
        matches!(self, Act::Press(s) | Act::Hold(s) if s == signal)
    }

    /// What it does, in words: `STOP pressed`, `x21 stuck at 0`.
    pub fn describe(self) -> String {
        match self {
            Act::Press(s) => format!("{} pressed", s.symbol()),
            Act::Hold(s) => format!("{} held", s.symbol()),
            Act::Release(s) => format!("{} released", s.symbol()),
            Act::Stick(s, v) => format!("{} stuck at {}", s.symbol(), u8::from(v)),
        }
    }
}

/// One event of a scenario, with the option that asked for it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Event {
    pub when: When,
    pub act: Act,
    /// The option as written: `--press STOP@step3`.
    pub written: String,
}

/// The kinds of event option: `press`, `hold`, `release`, `stick`.
pub const OPTIONS: [&str; 4] = ["press", "hold", "release", "stick"];

/// Reads `--OPTION TEXT` (`option` one of [`OPTIONS`]) against `program`.
pub fn parse(
    option: &str,
    text: &str,
    program: &StepProgram,
    table: &StepTable,
    naming: &Naming,
) -> Result<Event, String> {
    let written = format!("--{option} {text}");
    let refuse = |why: String| format!("{written}: {why}");
    let (what, when) = text.rsplit_once('@').ok_or_else(|| {
        refuse("expected SIGNAL@WHEN (`STOP@4.0s`, `STOP@500ms`, `STOP@step3`, `STOP@+2s`)".into())
    })?;
    if what.contains('@') {
        return Err(refuse(
            "more than one @: an option gives one event (`--press STOP@4.0s --press STOP@+2s`)"
                .into(),
        ));
    }
    let when = parse_when(when.trim(), program).map_err(refuse)?;
    let act = match option {
        "stick" => {
            let (name, value) = what.rsplit_once('=').ok_or_else(|| {
                refuse("expected SIGNAL=0 or SIGNAL=1 before the @ (`x21=0@4.0s`)".into())
            })?;
            if name.trim().is_empty() {
                return Err(refuse("no signal named before the =".into()));
            }
            let value = match value.trim() {
                "0" => false,
                "1" => true,
                other => return Err(refuse(format!("\"{other}\" is not 0 or 1"))),
            };
            Act::Stick(
                input(name.trim(), program, table, naming).map_err(refuse)?,
                value,
            )
        }
        _ => {
            let button = button(what.trim(), program, table, naming).map_err(refuse)?;
            match option {
                "hold" => Act::Hold(button),
                "release" => Act::Release(button),
                _ => Act::Press(button),
            }
        }
    };
    Ok(Event { when, act, written })
}

fn parse_when(text: &str, program: &StepProgram) -> Result<When, String> {
    const FORMS: &str = "(`4.0s`, `500ms`, `step3`, `+2s`)";
    if text.is_empty() {
        return Err(format!("nothing after the @: write when {FORMS}"));
    }
    let lower = text.to_ascii_lowercase();
    if let Some(step) = lower.strip_prefix("step") {
        return parse_step(step, program);
    }
    if lower.starts_with("+step") {
        return Err(format!(
            "\"{text}\" is a step with a +: write {} (the next time the program enters it after the event before)",
            &text[1..]
        ));
    }
    if text.starts_with('-') {
        return Err(format!(
            "\"{text}\" is before power-up: times count from 0 s, or from the event before with +"
        ));
    }
    let (relative, time) = match text.strip_prefix('+') {
        Some(t) => (true, t),
        None => (false, text),
    };
    if crate::cell::without_unit(time) {
        return Err(format!("\"{time}\" has no unit: write {time}s or {time}ms"));
    }
    if time.contains(',') {
        // `1,5s` is 1.5 s to a spreadsheet in some languages, and 15 s or
        // an error in others: a command line writes the point.
        return Err(format!(
            "\"{time}\" has a decimal comma: write {}",
            time.replace(',', ".")
        ));
    }
    if time.contains(char::is_whitespace) {
        let joined: String = time.split_whitespace().collect();
        return Err(format!("\"{time}\" has a space in it: write {joined}"));
    }
    let ms = parse_duration_in(time, 0..=LATEST_MS).ok_or_else(|| {
        let finer = crate::cell::plain_time(time)
            && parse_duration_in(time, 0..=u32::MAX).is_none()
            && time.split_once('.').is_some();
        if finer {
            format!("\"{time}\" is finer than a millisecond: times are whole milliseconds (`1.5s`, `1500ms`)")
        } else {
            format!(
                "\"{time}\" is not a time from 0 s to {} s {FORMS}",
                LATEST_MS / 1000
            )
        }
    })? as u64;
    Ok(if relative {
        When::After(ms)
    } else {
        When::At(ms)
    })
}

/// `stepK` (the text after `step`): an SFC step of the program, 0 at rest
/// to its last table step. The closing transition enters step 0, as the
/// printed table says (`step 0   end of cycle`).
fn parse_step(step: &str, program: &StepProgram) -> Result<When, String> {
    let table_step = |s: &&crate::program::ProgramStep| s.kind == crate::program::StepKind::Table;
    let steps = program.steps.iter().filter(table_step);
    let last = steps.map(|s| s.number).max().unwrap_or(0);
    match step.parse::<usize>() {
        Ok(k) if k <= last => Ok(When::Step(k)),
        Ok(k) => Err(format!(
            "the program has no step {k}: its steps are 0 (at rest, entered again at the end of a cycle) to {last}"
        )),
        Err(_) => Err(format!("\"{step}\" is not a step number (`step3`)")),
    }
}

/// The program input called `name` by any of its names.
fn input(
    name: &str,
    program: &StepProgram,
    table: &StepTable,
    naming: &Naming,
) -> Result<Signal, String> {
    if name.is_empty() {
        return Err("no signal named before the @".into());
    }
    let calls = |s: Signal| {
        naming
            .aliases(s, table)
            .iter()
            .chain(&[naming.designation(s, table), alias(s)])
            .any(|a| a.eq_ignore_ascii_case(name))
    };
    if let Some(signal) = program.signals.inputs.iter().copied().find(|s| calls(*s)) {
        return Ok(signal);
    }
    let jog = name.to_ascii_lowercase();
    if jog.starts_with("jog") || jog.contains("_jog_") {
        return Err(format!(
            "the program has no jog button called \"{name}\": {}",
            if program.signals.inputs.contains(&Signal::ManualMode) {
                format!(
                    "each actuator has jogN+ and jogN- (a {} only jogN+: its spring is the way back)",
                    crate::diag::or_list(&crate::actuator::ActuatorKind::one_jog())
                )
            } else {
                manual_off(table)
            }
        ));
    }
    if let Some(button) = BUTTONS.iter().copied().find(|s| calls(*s)) {
        let mode = mode_of(button);
        return Err(if mode == "manual" {
            format!(
                "the program has no {} button: {}",
                button.symbol(),
                manual_off(table)
            )
        } else {
            format!(
                "the program has no {} button: its mode is off (turn it on with --modes {mode})",
                button.symbol(),
            )
        });
    }
    if let Some(n) = naming
        .actuator_called(name)
        .filter(|n| table.actuators.iter().any(|a| a.number == *n))
    {
        let sensors: Vec<String> = program
            .signals
            .inputs
            .iter()
            .filter(|s| matches!(s, Signal::Sensor { actuator, .. } if *actuator == n))
            .map(|s| naming.designation(*s, table))
            .collect();
        return Err(format!(
            "{name} is an actuator: stick one of its sensors instead ({})",
            sensors.join(", ")
        ));
    }
    let outputs = program.steps.iter().flat_map(|s| &s.actions);
    let outputs = outputs.chain(program.rungs.iter().flat_map(|r| &r.actions));
    if let Some(output) = outputs
        .map(|a| a.signal())
        .find(|s| s.area() == Area::Output && calls(*s))
    {
        return Err(format!(
            "{} is an output: only an input (a sensor, a button, a machine input) can be pressed or stuck",
            output.symbol()
        ));
    }
    // In the names the engineer chose (`--designations iso`: 2B3).
    Err(format!(
        "the program has no input called \"{name}\" (its inputs: {})",
        program
            .signals
            .inputs
            .iter()
            .map(|s| naming.designation(*s, table))
            .collect::<Vec<_>>()
            .join(", ")
    ))
}

/// The operator's button called `name`.
fn button(
    name: &str,
    program: &StepProgram,
    table: &StepTable,
    naming: &Naming,
) -> Result<Signal, String> {
    let signal = input(name, program, table, naming)?;
    if BUTTONS.contains(&signal) || matches!(signal, Signal::Jog { .. }) {
        Ok(signal)
    } else {
        Err(format!(
            "{} is not an operator's button: stick it instead (--stick {}=1@…)",
            signal.symbol(),
            signal.symbol()
        ))
    }
}

/// The operator's buttons and switches (and each actuator's jog buttons
/// in manual mode).
pub const BUTTONS: [Signal; 8] = [
    Signal::Start,
    Signal::Stop,
    Signal::EStop,
    Signal::Reset,
    Signal::Continuous,
    Signal::StepMode,
    Signal::StepButton,
    Signal::ManualMode,
];

/// The name an operator calls a button beside its symbol (RESET for
/// RESET_PB): the one list the table's names are checked against too.
fn alias(signal: Signal) -> String {
    crate::names::button_alias(&signal.symbol())
        .unwrap_or("")
        .to_string()
}

/// The `--modes` word that gives the program `button`.
fn mode_of(button: Signal) -> &'static str {
    match button {
        Signal::Stop => "stop",
        Signal::EStop => "estop",
        Signal::Reset => "reset",
        Signal::Continuous => "continuous",
        Signal::ManualMode => "manual",
        _ => "step",
    }
}

/// More jog buttons held at once, in the order the events are written,
/// than [`crate::simulate::Jogs::HANDS`]: the operator is modelled with
/// that many hands (a press lets go by itself).
pub(super) fn too_many_jogs(events: &[Event]) -> Option<String> {
    let mut held: Vec<Signal> = Vec::new();
    for event in events {
        match event.act {
            Act::Hold(jog @ Signal::Jog { .. }) if !held.contains(&jog) => held.push(jog),
            Act::Release(jog) => held.retain(|h| *h != jog),
            _ => {}
        }
        let pressed =
            matches!(event.act, Act::Press(jog @ Signal::Jog { .. }) if !held.contains(&jog));
        if held.len() + usize::from(pressed) > crate::simulate::Jogs::HANDS {
            return Some(format!(
                "{}: at most {} jog buttons can be held at once ({} are)",
                event.written,
                crate::simulate::Jogs::HANDS,
                held.len() + usize::from(pressed)
            ));
        }
    }
    None
}

/// Why a program has no manual mode: a table that moves no actuator has
/// nothing to jog, so the mode is left out even when asked for.
fn manual_off(table: &StepTable) -> String {
    if table.actuators.is_empty() {
        "the table moves no actuator, so manual mode is left out of the program (even with --modes manual)".to_string()
    } else {
        "manual mode is off (turn it on with --modes manual)".to_string()
    }
}
