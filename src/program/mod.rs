//! The step program: the one intermediate model every output language is
//! rendered from and the simulator executes (DESIGN §4).
//!
//! Execution model, per PLC scan:
//! 1. The sequence waits at one step (step 1 after power-up). If that step's
//!    condition (an AND of literals) holds, its actions run in order and the
//!    sequence waits at the next step; after the last step it waits at step 1.
//!    At most one step fires per scan.
//! 2. Then every rung runs: if its condition holds, its actions run. Rungs are
//!    the logic that must act while the sequence waits, such as middle stops.
//!
//! Conditions are conjunctions of (possibly negated) signals and actions are
//! SET / RESET of outputs or memories, which is what every target language has
//! in common. Dwell timers, machine inputs and extra outputs become further
//! signals; one-coil valves simply get different actions.

mod build;
mod jumps;
mod modes;
mod options;
mod signal;
mod signals;
mod stops;

pub use build::build;
pub use jumps::StepJump;
pub use options::{
    HaltPolicy, Interlock, Modes, ProgramOptions, RunOn, Safety, StopAction, StopEvent,
};
pub use signal::{Alarm, Area, Signal};
pub use signals::{Coils, Signals};

use crate::table::Move;

/// A signal in a condition, possibly negated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Literal {
    pub signal: Signal,
    pub negated: bool,
}

impl Literal {
    pub fn is(signal: Signal) -> Self {
        Literal {
            signal,
            negated: false,
        }
    }

    pub fn not(signal: Signal) -> Self {
        Literal {
            signal,
            negated: true,
        }
    }
}

/// What a step or rung does to an output, memory bit or timer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    Set(Signal),
    /// Resets a bit; on a timer, stops it.
    Reset(Signal),
    /// (Re)starts a timer with a preset in milliseconds. As a condition a
    /// timer is true while it runs; it stops by itself once the preset elapsed.
    StartTimer(Signal, u32),
}

impl Action {
    pub fn signal(self) -> Signal {
        match self {
            Action::Set(s) | Action::Reset(s) | Action::StartTimer(s, _) => s,
        }
    }

    /// The value written: true for SET and for starting a timer.
    pub fn value(self) -> bool {
        matches!(self, Action::Set(_) | Action::StartTimer(..))
    }

    /// The verb of the paper's notation.
    pub fn verb(self) -> &'static str {
        match self {
            Action::Set(_) => "SET",
            Action::Reset(_) => "RESET",
            Action::StartTimer(..) => "START",
        }
    }
}

/// Where a step of the program comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepKind {
    /// A row of the table.
    Table,
    /// The closing step that notices the end of the cycle (watchdog, modes).
    EndOfCycle,
}

/// One step of the sequence.
#[derive(Debug, Clone, PartialEq)]
pub struct ProgramStep {
    /// One-based step number, as in the table.
    pub number: usize,
    pub kind: StepKind,
    /// What the step does in the table's notation (`C1+1, C2+1; T=2s`), or
    /// `end of cycle`.
    pub title: String,
    /// The table's moves of this step (for comments).
    pub moves: Vec<Move>,
    /// All literals must hold for the step to fire.
    pub condition: Vec<Literal>,
    /// Run in order when the step fires.
    pub actions: Vec<Action>,
    /// Jumps tested before the step while the sequence waits at it: each
    /// fires another step in its place (`J:7 if I:reject`).
    pub jumps: Vec<StepJump>,
}

/// What a rung is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RungKind {
    MiddleStop,
    Edge,
    Plausibility,
    Watchdog,
    Dwell,
    Mode,
    Homing,
    EmergencyStop,
    /// A halt switches off what may not stay on.
    HaltOff,
    /// An interlock input went off.
    Interlock,
    /// STOP acts at once (SETTINGS `on stop`).
    StopNow,
    /// An output running on after STOP.
    RunOn,
}

impl RungKind {
    /// The label on the PLC PROGRAM sheet.
    pub fn label(self) -> &'static str {
        match self {
            RungKind::MiddleStop => "MIDDLE STOP",
            RungKind::Edge => "EDGE",
            RungKind::Plausibility => "PLAUSIBILITY",
            RungKind::Watchdog => "WATCHDOG",
            RungKind::Dwell => "DWELL",
            RungKind::Mode => "MODE",
            RungKind::Homing => "HOMING",
            RungKind::EmergencyStop => "EMERGENCY STOP",
            RungKind::HaltOff => "HALT",
            RungKind::Interlock => "INTERLOCK",
            RungKind::StopNow => "STOP",
            RungKind::RunOn => "RUN-ON",
        }
    }
}

/// Logic evaluated on every scan after the sequence.
#[derive(Debug, Clone, PartialEq)]
pub struct Rung {
    pub kind: RungKind,
    /// What the rung is for, in words.
    pub comment: String,
    pub condition: Vec<Literal>,
    pub actions: Vec<Action>,
}

/// The complete step program of one table.
#[derive(Debug, Clone, PartialEq)]
pub struct StepProgram {
    /// Run once at power-up, before the first scan.
    pub init: Vec<Action>,
    pub steps: Vec<ProgramStep>,
    pub rungs: Vec<Rung>,
    /// Timers, advanced at the start of every scan.
    pub timers: Vec<Signal>,
    /// Every bit signal the program uses, in address order.
    pub signals: Signals,
    /// What may stay on when the machine stops (the fault analysis judges
    /// a stopped machine by it).
    pub halt: HaltPolicy,
    /// The start permissives and interlocks: machine inputs a healthy
    /// machine holds on.
    pub permissive: Vec<crate::cell::Name>,
    /// The outputs that run on after a stop event: run-on n is the n-th.
    pub run_ons: Vec<RunOn>,
}

impl StepProgram {
    /// Whether STOP acts at once (an `on stop` row) rather than letting
    /// the cycle finish.
    pub fn stops_now(&self) -> bool {
        !self.halt.on_stop.is_empty() && self.signals.inputs.contains(&Signal::Stop)
    }

    /// The number of the step at `index` among the steps (the sequence
    /// awaits it next after a jump): STEP 1 past the end.
    pub fn number_at(&self, index: usize) -> usize {
        self.steps.get(index).map_or(1, |s| s.number)
    }

    /// Whether `output` may stay on in a machine that has stopped: a
    /// cylinder's coil holds its piston, an alarm lamp tells the operator;
    /// a drive's output keeps it running, a machine output (a heater, a
    /// motor) does harm. The SETTINGS rows (`hold-safe`, `de-energise on
    /// halt`, `on stop: hold`) say otherwise per output.
    pub fn may_stay_on(&self, output: Signal) -> bool {
        let by_default = match output {
            Signal::Coil { .. } => !self.signals.is_drive(output),
            Signal::SingleCoil { .. } | Signal::Alarm(_) => true,
            _ => false,
        };
        self.halt.may_stay_on(output, by_default)
    }
}

/// `IF a AND b THEN SET y1+ RESET y1-` in the paper's notation, with symbols
/// from `name`. Only actions on outputs are listed when `outputs_only`.
pub fn paper_sentence(
    condition: &[Literal],
    actions: &[Action],
    name: impl Fn(Signal) -> String,
) -> String {
    let mut text = format!("IF {}", condition_text(condition, &name, "AND", "NOT "));
    text.push_str(" THEN");
    for action in actions {
        if *action == Action::Reset(Signal::Sequence) {
            text.push_str(" GOTO STEP 1");
            continue;
        }
        text.push_str(&format!(" {} {}", action.verb(), name(action.signal())));
        if let Action::StartTimer(_, ms) = action {
            text.push_str(&format!(" ({ms} ms)"));
        }
    }
    text
}

/// A conjunction as text, e.g. `x11 AND NOT x12`.
pub fn condition_text(
    condition: &[Literal],
    name: impl Fn(Signal) -> String,
    and: &str,
    not: &str,
) -> String {
    condition
        .iter()
        .map(|l| {
            if l.negated {
                format!("{not}{}", name(l.signal))
            } else {
                name(l.signal)
            }
        })
        .collect::<Vec<_>>()
        .join(&format!(" {and} "))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::stroke::Strokes;
    use crate::table::StepTable;
    use crate::valve::Valves;

    /// The paper's example table (DESIGN §4), as a bare grid.
    pub(crate) fn paper_table() -> StepTable {
        crate::table::from_rows("paper.csv", &crate::template_workbook::PAPER_EXAMPLE)
            .expect("paper table is valid")
    }

    #[test]
    fn paper_program_matches_design_section_4() {
        let table = paper_table();
        let program = build(
            &table,
            &ProgramOptions::default(),
            &Valves::default(),
            &Strokes::default(),
        );
        let lines: Vec<String> = program
            .steps
            .iter()
            .map(|s| {
                let outputs: Vec<Action> = s
                    .actions
                    .iter()
                    .copied()
                    .filter(|a| matches!(a.signal(), Signal::Coil { .. }))
                    .collect();
                paper_sentence(&s.condition, &outputs, Signal::symbol)
            })
            .collect();
        assert_eq!(
            lines,
            [
                "IF START AND x10 AND x20 AND x30 AND x40 THEN SET y1+ RESET y1-",
                "IF x11 THEN SET y2+ RESET y2-",
                "IF x23 THEN SET y2- RESET y2+",
                "IF x21 THEN SET y3+ RESET y3- SET y2+ RESET y2-",
                "IF x32 AND x22 THEN SET y3- RESET y3+ SET y2- RESET y2+",
                "IF x30 AND x21 THEN SET y3+ RESET y3- SET y2+ RESET y2- SET y4+ RESET y4-",
                "IF x31 AND x22 AND x41 THEN SET y3- RESET y3+ SET y2- RESET y2+ SET y4- RESET y4+",
                "IF x30 AND x20 AND x40 THEN SET y1- RESET y1+",
            ]
        );
    }

    #[test]
    fn middle_targets_get_a_stop_rung() {
        let table = paper_table();
        let program = build(
            &table,
            &ProgramOptions::default(),
            &Valves::default(),
            &Strokes::default(),
        );
        // C2 stops at 1 and 2, C3 at 1 (C3's pmax is 2).
        let rungs: Vec<String> = program
            .rungs
            .iter()
            .map(|r| paper_sentence(&r.condition, &r.actions, Signal::symbol))
            .collect();
        assert_eq!(
            rungs,
            [
                "IF m2_1 AND x21 THEN RESET y2+ RESET y2- RESET m2_1",
                "IF m2_2 AND x22 THEN RESET y2+ RESET y2- RESET m2_2",
                "IF m3_1 AND x31 THEN RESET y3+ RESET y3- RESET m3_1",
            ]
        );
        // Step 5 moves C2 from middle 2 to middle 1: it withdraws the old request.
        assert!(
            program.steps[4]
                .actions
                .contains(&Action::Reset(Signal::StopAt {
                    actuator: 2,
                    position: 2
                }))
        );
        let plain = build(
            &table,
            &ProgramOptions {
                middle_stops: false,
                ..ProgramOptions::default()
            },
            &Valves::default(),
            &Strokes::default(),
        );
        assert!(plain.rungs.is_empty());
    }
}
