//! Executes the step program exactly as the program module defines it: one
//! scan reads the inputs, may fire the awaited step, then runs every rung.
//! This is the same model the `.st` and `.fst.txt` are rendered from.

use std::collections::BTreeMap;

use crate::address::Signal;
use crate::program::{Action, Literal, StepProgram};

/// The PLC's memory: the awaited step, outputs, internal bits and timers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlcState {
    /// Index into `program.steps` of the step the sequence waits to fire.
    pub awaited: usize,
    /// Outputs, memories and running timers currently on (absent = off).
    bits: BTreeMap<Signal, bool>,
    /// Running timers: elapsed and preset milliseconds.
    timers: BTreeMap<Signal, (u64, u64)>,
}

impl PlcState {
    /// Power-up state: waiting at step 1, everything off, then the program's
    /// initial actions.
    pub fn new(program: &StepProgram) -> Self {
        let mut state = PlcState {
            awaited: 0,
            bits: BTreeMap::new(),
            timers: BTreeMap::new(),
        };
        state.apply(&program.init);
        state
    }

    /// Whether an output or memory bit is on.
    pub fn bit(&self, signal: Signal) -> bool {
        self.bits.get(&signal).copied().unwrap_or(false)
    }

    fn apply(&mut self, actions: &[Action]) {
        for action in actions {
            match *action {
                Action::StartTimer(timer, preset) => {
                    self.timers.insert(timer, (0, preset as u64));
                }
                Action::Reset(signal) => {
                    self.timers.remove(&signal);
                }
                Action::Set(_) => {}
            }
            self.bits.insert(action.signal(), action.value());
        }
    }

    /// Advances every running timer by one scan; a timer whose preset has
    /// elapsed stops (its bit goes off).
    fn advance_timers(&mut self, scan_ms: u64) {
        let mut expired = Vec::new();
        for (timer, (elapsed, preset)) in &mut self.timers {
            *elapsed += scan_ms;
            if *elapsed >= *preset {
                expired.push(*timer);
            }
        }
        for timer in expired {
            self.timers.remove(&timer);
            self.bits.insert(timer, false);
        }
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
    let value = |state: &PlcState, literal: &Literal| -> bool {
        let raw = match literal.signal {
            Signal::Start | Signal::Sensor { .. } => input(literal.signal),
            other => state.bit(other),
        };
        raw != literal.negated
    };
    let mut fired = None;
    if let Some(step) = program.steps.get(state.awaited)
        && step.condition.iter().all(|l| value(state, l))
    {
        state.apply(&step.actions);
        fired = Some(state.awaited);
        state.awaited = (state.awaited + 1) % program.steps.len();
    }
    for rung in &program.rungs {
        if rung.condition.iter().all(|l| value(state, l)) {
            state.apply(&rung.actions);
        }
    }
    ScanResult { fired }
}
