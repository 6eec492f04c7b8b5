//! The step program: the one intermediate model every output language is
//! rendered from and the simulator executes (DESIGN §4).
//!
//! Execution model, per PLC scan:
//! 1. The sequence waits at one transition (the first after power-up). If
//!    its condition (an AND of literals) holds, its actions run in order and
//!    the sequence waits at the next; after the last, the closing `end of
//!    cycle`, it waits at the first again. At most one fires per scan.
//! 2. Then every rung runs: if its condition holds, its actions run. Rungs are
//!    the logic that must act while the sequence waits, such as middle stops.
//!
//! Step numbers are those of SFC, GRAFCET and S7-GRAPH, and every output
//! shows these and no others: step 0 is the initial step (at rest, waiting
//! for START), step k is active while table step k's moves run. Each
//! [`ProgramStep`] is the transition that *enters* its step: it waits in
//! [`StepProgram::step_in`] (the step before it, 0 for the first) and its
//! actions are those of the step it enters ([`StepProgram::step_entered`]);
//! the closing transition re-enters step 0. Actions are stored (SET/RESET)
//! and run once, as the step is entered, in the scan its transition fires,
//! which is why they are written under the transition that leaves the step
//! before.
//!
//! Conditions are conjunctions of (possibly negated) signals and actions are
//! SET / RESET of outputs or memories, which is what every target language has
//! in common. Dwell timers, machine inputs and extra outputs become further
//! signals; one-coil valves simply get different actions.

mod build;
mod jumps;
mod manual;
mod modes;
mod options;
mod signal;
mod signals;
mod stops;
mod supervision;

pub use build::build;
pub use jumps::StepJump;
pub use options::{
    HaltPolicy, Interlock, Modes, ProgramOptions, RunOn, Safety, StopAction, StopEvent, bracketed,
};
pub use signal::{Alarm, Area, Signal};
pub use signals::{Coils, Signals, jog_buttons};
pub use supervision::{
    describe as describe_criterion, expected_ms as expected_step_ms,
    parse_times as parse_supervision,
};

use crate::table::Move;

/// The SFC initial step: the machine at rest, waiting for START (and where
/// RESET, a STOP that acts at once and power-up leave the sequence).
pub const INITIAL_STEP: usize = 0;

/// What the initial step is, in every program's comments.
pub const INITIAL_TITLE: &str = "initial step: at rest, waits for START";

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

    /// The same signal read the other way.
    pub fn negate(self) -> Self {
        Literal {
            negated: !self.negated,
            ..self
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
    /// The closing transition: the last step is done, the sequence is back
    /// in the initial step 0.
    EndOfCycle,
}

/// One transition of the sequence with the actions of the step it enters
/// (the table's sentence `STEP k IF … THEN …`).
#[derive(Debug, Clone, PartialEq)]
pub struct ProgramStep {
    /// One-based number of the table step it fires, as in the table; the
    /// closing transition has the number after the last step.
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
    /// Jumps tested before it while the sequence waits at it: each fires
    /// another step in its place (`J:7 if I:reject`).
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
    /// Manual mode: the automatic cycle's end and the jogs.
    Manual,
    /// A pressurised-centre valve's `-` coil holding its piston home.
    HoldHome,
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
            RungKind::Manual => "MANUAL",
            RungKind::HoldHome => "HOLD HOME",
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
    /// The criteria of the criteria analysis (`--safety criteria`):
    /// output `Missing(n)` reports criterion n (1-based) unmet.
    pub criteria: Vec<Literal>,
}

/// The watchdog preset `actions` start, where no PLC timer of every
/// target holds it.
fn watchdog_past_timers(actions: &[Action]) -> Option<u32> {
    actions.iter().find_map(|a| match a {
        Action::StartTimer(Signal::Watchdog, ms) if *ms > crate::cell::MAX_DWELL_MS => Some(*ms),
        _ => None,
    })
}

impl StepProgram {
    /// The steps whose watchdog preset no PLC timer of every target holds
    /// (FST counts 1/100 s in a 16-bit word: 655.35 s at most), with the
    /// preset in ms: such a program is refused (E032), not written.
    pub fn watchdogs_beyond_timers(&self) -> impl Iterator<Item = (&ProgramStep, u32)> {
        (self.steps.iter()).filter_map(|step| Some((step, watchdog_past_timers(&step.actions)?)))
    }

    /// The homing stages whose watchdog preset no PLC timer of every
    /// target holds (a stroke so slow that twice it passes 655.35 s), each
    /// rung that starts one with the preset: refused (E032) as a step's.
    pub fn homing_watchdogs_beyond_timers(&self) -> impl Iterator<Item = (&Rung, u32)> {
        (self.rungs.iter()).filter_map(|rung| Some((rung, watchdog_past_timers(&rung.actions)?)))
    }
    /// Whether the program takes the button `button` held through power-up
    /// as no press: it acts on the button's rising edge, whose memory is
    /// set at power-up (RESET always, START under the edge check).
    pub fn no_press_at_power_up(&self, button: Signal) -> bool {
        let memory = match button {
            Signal::Start => Signal::StartMemory,
            Signal::Reset => Signal::ResetMemory,
            _ => return false,
        };
        self.init.contains(&Action::Set(memory))
    }

    /// Whether STOP acts at once (an `on stop` row) rather than letting
    /// the cycle finish.
    pub fn stops_now(&self) -> bool {
        !self.halt.on_stop.is_empty() && self.signals.inputs.contains(&Signal::Stop)
    }

    /// The SFC step the program is in while it waits at the transition
    /// `steps[index]`: the table step fired before it, or the initial step
    /// 0 before the first (and past the end: the closing transition leads
    /// back there).
    pub fn step_in(&self, index: usize) -> usize {
        match index.checked_sub(1).and_then(|i| self.steps.get(i)) {
            Some(before) if before.kind == StepKind::Table => before.number,
            _ => INITIAL_STEP,
        }
    }

    /// The SFC step entered when `steps[index]` fires: its table step, or
    /// the initial step for the closing transition.
    pub fn step_entered(&self, index: usize) -> usize {
        match self.steps.get(index) {
            Some(step) if step.kind == StepKind::Table => step.number,
            _ => INITIAL_STEP,
        }
    }

    /// What the step the program is in while it waits at `steps[index]`
    /// does: the table step's notation (`C1+1, C2+1; T=2s`), or what the
    /// initial step waits for.
    pub fn title_in(&self, index: usize) -> String {
        match index.checked_sub(1).and_then(|i| self.steps.get(i)) {
            Some(before) if before.kind == StepKind::Table => before.title.clone(),
            _ => INITIAL_TITLE.to_string(),
        }
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
            text.push_str(&format!(" GOTO STEP {INITIAL_STEP}"));
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
    use crate::actuator::Valves;
    use crate::stroke::Strokes;
    use crate::table::StepTable;

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
            .filter(|s| s.kind == StepKind::Table)
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

    /// SFC numbering: the program is in step 0 until START, in step k while
    /// table step k's moves run, and the closing transition (step 8 done:
    /// C1 home at x10) leads back to step 0.
    #[test]
    fn steps_are_numbered_as_in_sfc() {
        let table = paper_table();
        let program = build(
            &table,
            &ProgramOptions::default(),
            &Valves::default(),
            &Strokes::default(),
        );
        assert_eq!(program.steps.len(), 9);
        let waits_in: Vec<usize> = (0..9).map(|i| program.step_in(i)).collect();
        assert_eq!(waits_in, [0, 1, 2, 3, 4, 5, 6, 7, 8]);
        let enters: Vec<usize> = (0..9).map(|i| program.step_entered(i)).collect();
        assert_eq!(enters, [1, 2, 3, 4, 5, 6, 7, 8, INITIAL_STEP]);
        let closing = &program.steps[8];
        assert_eq!(closing.kind, StepKind::EndOfCycle);
        assert_eq!(
            paper_sentence(&closing.condition, &closing.actions, Signal::symbol),
            "IF x10 THEN"
        );
        assert_eq!(program.title_in(0), INITIAL_TITLE);
        assert_eq!(program.title_in(4), "C3+2, C2+2");
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
