//! What each signal is, in words, for the symbol comments of every output
//! ("cylinder 2 (clamp), middle position 1"): decided here once, so that a
//! program text, a tag export and an I/O list describe a signal alike.

use crate::cell::Sign;
use crate::program::{Alarm, Area, Signal, StepProgram};
use crate::table::{Step, StepTable};

/// The comment of `signal` in `program` of `table`; `actuator` names an
/// actuator after the word `cylinder` or `drive` (`1 (clamp)`, `1A1`), and
/// `name` designates a signal.
pub(super) fn comment(
    signal: Signal,
    program: &StepProgram,
    table: &StepTable,
    actuator: &dyn Fn(u32) -> String,
    name: &dyn Fn(Signal) -> String,
) -> String {
    match signal {
        Signal::Sensor { .. }
        | Signal::Coil { .. }
        | Signal::SingleCoil { .. }
        | Signal::Jog { .. }
        | Signal::StopAt { .. } => actuator_comment(signal, program, table, actuator),
        Signal::MachineInput(_)
        | Signal::MachineOutput(_)
        | Signal::Dwell(_)
        | Signal::DwellArmed(_) => table_comment(signal, table),
        Signal::RunOn(_) | Signal::RunOnArmed(_) | Signal::Awaited(_) | Signal::Missing(_) => {
            program_comment(signal, program, name)
        }
        Signal::Start => "START push-button".to_string(),
        Signal::StartMemory => "START in the previous scan (rising edge)".to_string(),
        Signal::Halt => "sequence stopped by a safety check".to_string(),
        Signal::Alarm(Alarm::Sensor) => "alarm: two sensors of one cylinder on at once".to_string(),
        Signal::Alarm(Alarm::Timeout) => "alarm: a step did not finish in time".to_string(),
        Signal::Alarm(Alarm::Interlock) => "alarm: an interlock input went off".to_string(),
        Signal::Watchdog => "step watchdog timer".to_string(),
        Signal::WatchdogArmed => "watchdog is timing a step".to_string(),
        Signal::InterlockZone(n) => format!("the sequence is in the steps of interlock zone {n}"),
        Signal::Continuous => "CONTINUOUS switch (on: repeat cycles)".to_string(),
        Signal::Stop if program.stops_now() => {
            "STOP push-button, normally closed (0: stop at once, outputs as on stop says)"
                .to_string()
        }
        Signal::Stop => {
            "STOP push-button, normally closed (0: finish the cycle, then halt)".to_string()
        }
        Signal::EStop => "EMERGENCY STOP, normally closed (0: every coil off at once)".to_string(),
        Signal::Reset => "RESET push-button (home every actuator)".to_string(),
        Signal::StepMode => {
            "STEP_MODE switch (on: single step, one step per STEP_PB press)".to_string()
        }
        Signal::StepButton => "STEP_PB push-button (single step: fire the next step)".to_string(),
        Signal::ManualMode => {
            "MAN_MODE selector (1 = manual: cycle ended, jog buttons move; 0 = automatic)"
                .to_string()
        }
        Signal::StepPermit => "the sequence may fire a step in this scan".to_string(),
        Signal::StepMemory => "STEP_PB as read in the previous scan".to_string(),
        Signal::ResetMemory => "RESET_PB as read in the previous scan".to_string(),
        Signal::ManualMemory => {
            "MAN_MODE in the previous scan (leaving manual switches the jogs' coils off)"
                .to_string()
        }
        Signal::JogsReleased => {
            "every jog button read released in this manual spell: the jogs may act".to_string()
        }
        Signal::Jogged(n) => {
            format!("C{n} jogged in this manual spell: its held coils follow its jog buttons")
        }
        Signal::CycleRequest => "a cycle was asked for".to_string(),
        Signal::Busy => "a cycle is under way".to_string(),
        Signal::AutoRun => "continuous operation runs".to_string(),
        Signal::Homing => "the homing sequence runs".to_string(),
        Signal::HomeStage(n) => format!("homing stage {n} runs"),
        Signal::Sequence => "the step sequence".to_string(),
    }
}

/// The kind of actuator `a`: as the program keeps it, else its default.
fn kind_of(program: &StepProgram, table: &StepTable, a: u32) -> crate::actuator::ActuatorKind {
    let pmax = table.actuator(a).map(|x| x.max_position).unwrap_or(1);
    program
        .signals
        .kinds
        .get(&a)
        .copied()
        .unwrap_or(crate::actuator::ActuatorKind::default_for(pmax))
}

/// A sensor, coil or stop signal of an actuator.
fn actuator_comment(
    signal: Signal,
    program: &StepProgram,
    table: &StepTable,
    actuator: &dyn Fn(u32) -> String,
) -> String {
    let pmax = |a: u32| table.actuator(a).map(|x| x.max_position).unwrap_or(1);
    match signal {
        Signal::Sensor {
            actuator: a,
            position,
        } => kind_of(program, table, a).sensor_comment(&actuator(a), position, pmax(a)),
        Signal::Coil { actuator: a, sign } if program.signals.is_drive(signal) => format!(
            "drive {}, {} (cut at its limit switch)",
            actuator(a),
            match sign {
                Sign::Plus => "forward (+)",
                Sign::Minus => "reverse (-)",
            }
        ),
        Signal::Coil { actuator: a, sign } => {
            let kind = kind_of(program, table, a);
            let (plus, minus) = kind.coil_words();
            match sign {
                Sign::Plus => format!("{} {}, coil + ({plus})", kind.noun(), actuator(a)),
                Sign::Minus => format!("{} {}, coil - ({minus})", kind.noun(), actuator(a)),
            }
        }
        Signal::SingleCoil { actuator: a } => {
            let kind = program.signals.kinds.get(&a).copied();
            // Only a kind with one coil has a single coil to comment.
            let kind = kind.unwrap_or(crate::actuator::ActuatorKind::Mono52);
            let (on, off) = kind.single_coil_words();
            format!(
                "{} {}, coil (on: {on}; off: {off})",
                kind.noun(),
                actuator(a)
            )
        }
        Signal::StopAt {
            actuator: a,
            position,
        } if program.signals.drives(a) => {
            format!("drive {} stops at position {position}", actuator(a))
        }
        Signal::StopAt {
            actuator: a,
            position,
        } => {
            format!(
                "cylinder {} stops at middle position {position}",
                actuator(a)
            )
        }
        Signal::Jog { actuator: a, sign } => {
            let kind = kind_of(program, table, a);
            let (plus, minus) = kind.coil_words();
            // A coil that holds a part stays on by itself until the
            // release jog; the others move only while their button is held.
            let (plus_tail, minus_tail) = if kind.holds_part() {
                (", on until its release jog", "")
            } else {
                (" while held", " while held")
            };
            let what = match (program.signals.drives(a), sign) {
                (true, Sign::Plus) => format!("drive {}, run forward while held", actuator(a)),
                (true, Sign::Minus) => {
                    format!("drive {}, run in reverse while held", actuator(a))
                }
                (false, Sign::Plus) => {
                    format!("{} {}, {plus}{plus_tail}", kind.noun(), actuator(a))
                }
                (false, Sign::Minus) => {
                    format!("{} {}, {minus}{minus_tail}", kind.noun(), actuator(a))
                }
            };
            format!("jog push-button: {what} (manual mode)")
        }
        // Only the signals of an actuator are described here.
        _ => String::new(),
    }
}

/// A machine input or output, or a dwell, by the steps of the table that
/// use it.
fn table_comment(signal: Signal, table: &StepTable) -> String {
    match signal {
        Signal::MachineInput(input) => {
            let waits = |s: &Step| s.waits.iter().any(|w| w.input == input);
            let jumps = |s: &Step| s.jumps.iter().any(|j| j.input == input);
            let mut uses = vec![format!("machine input {input}")];
            if table.steps.iter().any(waits) {
                uses.push(format!("waited for in {}", steps_where(table, waits)));
            }
            if table.steps.iter().any(jumps) {
                uses.push(format!("jumped on after {}", steps_where(table, jumps)));
            }
            uses.join(", ")
        }
        Signal::MachineOutput(output) => {
            let switched = |s: &Step| s.switches.iter().any(|w| w.output == output);
            format!(
                "machine output {output}, switched in {}",
                steps_where(table, switched)
            )
        }
        Signal::Dwell(n) | Signal::DwellArmed(n) => {
            let what = table
                .steps
                .iter()
                .find_map(|s| {
                    s.dwells.iter().find(|d| d.number == n).map(|d| {
                        format!(
                            "STEP {}, branch {}, {}",
                            s.number,
                            d.branch + 1,
                            crate::cell::dwell_text(d.ms)
                        )
                    })
                })
                .unwrap_or_default();
            if matches!(signal, Signal::Dwell(_)) {
                format!("dwell timer {n} ({what})")
            } else {
                format!("dwell {n} waits for its branch to finish ({what})")
            }
        }
        // Only the signals the table's cells name are described here.
        _ => String::new(),
    }
}

/// A run-on timer or a criterion of the step supervision, by what the
/// program says of it.
fn program_comment(
    signal: Signal,
    program: &StepProgram,
    name: &dyn Fn(Signal) -> String,
) -> String {
    let run_on = |n: u16| program.run_ons.get(usize::from(n).wrapping_sub(1));
    let criterion = |n: u16| program.criteria.get(usize::from(n).wrapping_sub(1));
    // `x21 on`, `x21 off`, by the signal's designation.
    let wanted = |l: &crate::program::Literal| {
        format!(
            "{} {}",
            name(l.signal),
            if l.negated { "off" } else { "on" }
        )
    };
    match signal {
        Signal::RunOn(n) => match run_on(n) {
            Some(r) => format!(
                "run-on timer {n}: {} stays on {} after {}",
                name(r.output),
                crate::cell::duration_text(r.ms),
                r.event.text()
            ),
            None => format!("run-on timer {n} (an output on after STOP)"),
        },
        Signal::RunOnArmed(n) => match run_on(n) {
            Some(r) => format!("{} runs on after {}", name(r.output), r.event.text()),
            None => format!("run-on {n} is timing"),
        },
        Signal::Awaited(n) => match criterion(n) {
            Some(l) => format!("criterion {n}: the awaited transition needs {}", wanted(l)),
            None => format!("criterion {n}"),
        },
        // No "bit k of a word": which bit of which word depends on the
        // target's byte order (the allocation list gives the address).
        Signal::Missing(n) => match criterion(n) {
            Some(l) if l.signal == Signal::StepMode => {
                format!("criterion {n} missing: single step, the step waits for STEP_PB")
            }
            Some(l) => format!(
                "criterion {n} missing: the step ran out of time and {} is not met",
                wanted(l)
            ),
            None => format!("criterion {n} missing"),
        },
        // Only run-ons and criteria are described here.
        _ => String::new(),
    }
}

/// `STEP 2` or `STEPS 2, 5`.
fn steps_where(table: &StepTable, test: impl Fn(&Step) -> bool) -> String {
    let numbers: Vec<String> = table
        .steps
        .iter()
        .filter(|s| test(s))
        .map(|s| s.number.to_string())
        .collect();
    match numbers.len() {
        1 => format!("STEP {}", numbers[0]),
        _ => format!("STEPS {}", numbers.join(", ")),
    }
}

/// The characters of an engineer's actuator name a finding shows.
pub const FINDING_NAME: usize = 40;

/// `text` as a target that holds at most `max` characters takes it: as it
/// is when it fits, else its first `max - 3` characters and `...` (plain
/// dots: STEP 7's files are not all Unicode), the same every run; the bool
/// says it was cut, so that the output can keep the whole text elsewhere
/// (a comment line, a tooltip) and the run can warn. The one cut of every
/// length-limited comment: the symbol table's, a network title, a GRAFCET
/// panel line, an engineer's name in a finding.
pub fn shorten(text: &str, max: usize) -> (String, bool) {
    if text.chars().count() <= max {
        return (text.to_string(), false);
    }
    let mut cut: String = text.chars().take(max.saturating_sub(3)).collect();
    cut.push_str("...");
    (cut, true)
}

/// The `kind` column of the allocation list.
pub(super) fn role(signal: Signal) -> &'static str {
    match signal {
        Signal::Start => "start",
        Signal::Sensor { .. } => "sensor",
        Signal::Coil { .. } | Signal::SingleCoil { .. } => "coil",
        Signal::Alarm(_) => "alarm",
        Signal::Missing(_) => "missing",
        Signal::MachineInput(_) => "input",
        Signal::MachineOutput(_) => "output",
        Signal::Continuous => "continuous",
        Signal::Stop => "stop",
        Signal::EStop => "estop",
        Signal::Reset => "reset",
        Signal::StepMode => "step mode",
        Signal::StepButton => "step",
        Signal::ManualMode => "manual mode",
        Signal::Jog { .. } => "jog",
        other => match other.area() {
            Area::Timer => "timer",
            _ => "memory",
        },
    }
}

/// `text` with each whole word (`x10`, `y1+`, `C1`; never part of one:
/// `C1+1` is a word of its own) that `new` knows replaced.
pub(super) fn map_words<'a>(text: &str, new: impl Fn(&str) -> Option<&'a str>) -> String {
    let word = |c: char| c.is_ascii_alphanumeric() || matches!(c, '_' | '+' | '-' | ':');
    let mut out = String::with_capacity(text.len() + 16);
    let mut rest = text;
    while let Some(start) = rest.find(word) {
        out.push_str(&rest[..start]);
        let tail = &rest[start..];
        let end = tail.find(|c: char| !word(c)).unwrap_or(tail.len());
        let token = &tail[..end];
        // `x31:` ends a clause (`short of x31: C3 runs`); `I:part` is a name.
        match (new(token), token.strip_suffix(':')) {
            (Some(mapped), _) => out.push_str(mapped),
            (None, Some(bare)) if new(bare).is_some() => {
                out.push_str(new(bare).unwrap_or(bare));
                out.push(':');
            }
            _ => out.push_str(token),
        }
        rest = &tail[end..];
    }
    out.push_str(rest);
    out
}
