//! Executes the step program exactly as the program module defines it: one
//! scan advances the timers, may fire the awaited step, then runs every rung.
//! This is the same model the `.st` and `.fst.txt` are rendered from.
//!
//! For speed the program is compiled once into signal indices, so a scan
//! touches plain vectors rather than maps.

use std::collections::BTreeMap;

use crate::program::Signal;
use crate::program::{Action, Literal, StepProgram};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Lit {
    index: usize,
    negated: bool,
    input: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Op {
    Set(usize),
    Reset(usize),
    Start(usize, u64),
    /// The sequence goes back to STEP 1.
    Restart,
}

#[derive(Debug, Clone, PartialEq, Eq)]
struct Rule {
    condition: Vec<Lit>,
    actions: Vec<Op>,
}

/// The PLC's memory: the awaited step, outputs, internal bits and timers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlcState {
    /// Index into `program.steps` of the step the sequence waits to fire.
    pub awaited: usize,
    /// Every signal the program uses, by index.
    signals: Vec<Signal>,
    index: BTreeMap<Signal, usize>,
    /// Outputs, memories and running timers currently on.
    bits: Vec<bool>,
    /// Running timers: elapsed and preset milliseconds, by signal index.
    timers: Vec<Option<(u64, u64)>>,
    steps: Vec<Rule>,
    rungs: Vec<Rule>,
}

impl PlcState {
    /// Power-up state: waiting at step 1, everything off, then the program's
    /// initial actions.
    pub fn new(program: &StepProgram) -> Self {
        // Every signal named by a condition or an action, indexed once.
        let mut signals: Vec<Signal> = program
            .steps
            .iter()
            .flat_map(|s| s.condition.iter())
            .chain(program.rungs.iter().flat_map(|r| r.condition.iter()))
            .map(|l| l.signal)
            .chain(
                program
                    .steps
                    .iter()
                    .flat_map(|s| &s.actions)
                    .chain(program.rungs.iter().flat_map(|r| &r.actions))
                    .chain(&program.init)
                    .map(|a| a.signal()),
            )
            .collect();
        signals.sort();
        signals.dedup();
        let index: BTreeMap<Signal, usize> =
            signals.iter().enumerate().map(|(i, s)| (*s, i)).collect();
        let mut state = PlcState {
            awaited: 0,
            bits: vec![false; signals.len()],
            timers: vec![None; signals.len()],
            steps: program
                .steps
                .iter()
                .map(|s| compile(&index, &s.condition, &s.actions))
                .collect(),
            rungs: program
                .rungs
                .iter()
                .map(|r| compile(&index, &r.condition, &r.actions))
                .collect(),
            signals,
            index,
        };
        let init = compile(&state.index, &[], &program.init);
        state.apply(&init.actions);
        state
    }

    /// The index of a signal, if the program uses it.
    pub fn index_of(&self, signal: Signal) -> Option<usize> {
        self.index.get(&signal).copied()
    }

    /// The signal at an index.
    pub fn signal(&self, index: usize) -> Signal {
        self.signals[index]
    }

    /// Whether an output or memory bit (or a running timer) is on.
    pub fn bit(&self, signal: Signal) -> bool {
        self.index_of(signal).is_some_and(|i| self.bits[i])
    }

    /// The same by index.
    pub fn bit_at(&self, index: usize) -> bool {
        self.bits[index]
    }

    fn apply(&mut self, actions: &[Op]) {
        for action in actions {
            match *action {
                Op::Set(i) => self.bits[i] = true,
                Op::Reset(i) => {
                    self.bits[i] = false;
                    self.timers[i] = None;
                }
                Op::Start(i, preset) => {
                    self.bits[i] = true;
                    self.timers[i] = Some((0, preset));
                }
                Op::Restart => self.awaited = 0,
            }
        }
    }

    /// Advances every running timer by one scan; a timer whose preset has
    /// elapsed stops (its bit goes off).
    fn advance_timers(&mut self, scan_ms: u64) {
        for i in 0..self.timers.len() {
            if let Some((elapsed, preset)) = &mut self.timers[i] {
                *elapsed += scan_ms;
                if *elapsed >= *preset {
                    self.timers[i] = None;
                    self.bits[i] = false;
                }
            }
        }
    }

    fn holds(&self, condition: &[Lit], input: &dyn Fn(Signal) -> bool) -> bool {
        condition.iter().all(|l| {
            let raw = if l.input {
                input(self.signals[l.index])
            } else {
                self.bits[l.index]
            };
            raw != l.negated
        })
    }
}

fn compile(index: &BTreeMap<Signal, usize>, condition: &[Literal], actions: &[Action]) -> Rule {
    let at = |s: Signal| index.get(&s).copied().unwrap_or(0);
    Rule {
        condition: condition
            .iter()
            .map(|l| Lit {
                index: at(l.signal),
                negated: l.negated,
                input: l.signal.is_input(),
            })
            .collect(),
        actions: actions
            .iter()
            .map(|a| match *a {
                Action::Reset(Signal::Sequence) => Op::Restart,
                Action::Set(s) => Op::Set(at(s)),
                Action::Reset(s) => Op::Reset(at(s)),
                Action::StartTimer(s, ms) => Op::Start(at(s), ms as u64),
            })
            .collect(),
    }
}

/// What one scan did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ScanResult {
    /// Index of the step that fired in this scan, if any.
    pub fired: Option<usize>,
}

/// Runs one PLC scan of `scan_ms` milliseconds. `input` gives the value of an
/// input signal as read at the start of the scan.
pub fn scan(
    program: &StepProgram,
    state: &mut PlcState,
    input: &dyn Fn(Signal) -> bool,
    scan_ms: u64,
) -> ScanResult {
    state.advance_timers(scan_ms);
    let mut fired = None;
    let awaited = state.awaited;
    if awaited < state.steps.len() && state.holds(&state.steps[awaited].condition, input) {
        let actions = std::mem::take(&mut state.steps[awaited].actions);
        state.apply(&actions);
        state.steps[awaited].actions = actions;
        fired = Some(awaited);
        state.awaited = (awaited + 1) % program.steps.len();
    }
    for r in 0..state.rungs.len() {
        if state.holds(&state.rungs[r].condition, input) {
            let actions = std::mem::take(&mut state.rungs[r].actions);
            state.apply(&actions);
            state.rungs[r].actions = actions;
        }
    }
    ScanResult { fired }
}
