//! Executes the step program exactly as the program module defines it: one
//! scan reads the inputs, may fire the awaited step, then runs every rung.
//! This is the same model the `.st` and `.fst.txt` are rendered from.

use std::collections::BTreeMap;

use crate::address::Signal;
use crate::program::{Action, Literal, StepProgram};

/// The PLC's memory: the awaited step, outputs and internal bits.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlcState {
    /// Index into `program.steps` of the step the sequence waits to fire.
    pub awaited: usize,
    /// Outputs and memories currently on (absent = off).
    bits: BTreeMap<Signal, bool>,
}

impl PlcState {
    /// Power-up state: waiting at step 1, every output and memory off.
    pub fn new() -> Self {
        PlcState {
            awaited: 0,
            bits: BTreeMap::new(),
        }
    }

    /// Whether an output or memory bit is on.
    pub fn bit(&self, signal: Signal) -> bool {
        self.bits.get(&signal).copied().unwrap_or(false)
    }

    fn apply(&mut self, actions: &[Action]) {
        for action in actions {
            self.bits.insert(action.signal(), action.value());
        }
    }
}

impl Default for PlcState {
    fn default() -> Self {
        Self::new()
    }
}

/// What one scan did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ScanResult {
    /// Index of the step that fired in this scan, if any.
    pub fired: Option<usize>,
}

/// Runs one PLC scan. `input` gives the value of an input signal as read at
/// the start of the scan.
pub fn scan(
    program: &StepProgram,
    state: &mut PlcState,
    input: &dyn Fn(Signal) -> bool,
) -> ScanResult {
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
