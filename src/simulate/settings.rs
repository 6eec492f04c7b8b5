//! What a simulation is run with: the plant's parameters, the faults
//! present, what to record.

use std::collections::BTreeMap;

use crate::actuator::Machine;
use crate::cell::Name;
use crate::program::Signal;
use crate::stroke::Stroke;

/// Stroke fraction per second a 5/3 piston drifts with no coil on, unless
/// `--load` says otherwise.
pub const DEFAULT_DRIFT: f64 = 0.05;

/// How long the operator holds START.
pub(crate) const START_PRESS_MS: u32 = 100;
/// Idle time before the first press and between cycles.
pub(crate) const IDLE_MS: u32 = 500;
/// How long the machine takes to give an input a step waits for, unless
/// `SimSettings::input_delays` says otherwise.
pub const DEFAULT_INPUT_DELAY_MS: u32 = 500;

/// A sensor or push-button circuit fault: the input reads `stuck_at` always.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub struct Fault {
    pub signal: Signal,
    pub stuck_at: bool,
}

impl Fault {
    /// `x11 short circuit (stuck at 1)` / `x11 open circuit (stuck at 0)`.
    pub fn describe(&self) -> String {
        self.describe_as(self.signal.symbol())
    }

    /// The same with the signal called `name` (its designation in the
    /// outputs: `1B2 short circuit (stuck at 1)`).
    pub fn describe_as(&self, name: String) -> String {
        if self.stuck_at {
            format!("{name} short circuit (stuck at 1)")
        } else {
            format!("{name} open circuit (stuck at 0)")
        }
    }
}

/// Simulation settings.
#[derive(Debug, Clone, PartialEq)]
pub struct SimSettings {
    /// PLC scan time in milliseconds.
    pub scan_ms: u32,
    /// The machine: each actuator's kind, stroke times and load.
    pub machine: Machine,
    /// Half-width of a sensor's detection window, as a fraction of the stroke.
    pub window: f64,
    /// Number of START presses (cycles) to run.
    pub cycles: usize,
    /// Input faults, present from [`SimSettings::fault_onset_ms`] on.
    pub faults: Vec<Fault>,
    /// When the faults appear, in milliseconds of the run: 0 from power-up;
    /// later, in the middle of a cycle (the fault analysis's phases).
    pub fault_onset_ms: u64,
    /// Record every actuator's position at every scan (for the time diagram).
    pub record_trace: bool,
    /// Per machine input, how long after its step starts the machine gives
    /// the value the step waits for (default [`DEFAULT_INPUT_DELAY_MS`]),
    /// or the value of a jump the cycle takes (default: as its step starts).
    pub input_delays: BTreeMap<Name, u32>,
    /// End the run at the scan that finds the sequence's first hazard (any
    /// but a collision), and report only the first collision: the fault
    /// analysis needs no more (the rest of the report is then cut short).
    pub stop_at_hazard: bool,
    /// Record every combination of actuator places the run reaches
    /// ([`SimReport::places`]), for the collision check of later runs.
    pub record_places: bool,
    /// The combinations a healthy run reached: reaching another is a
    /// [`ProblemKind::Collision`](super::ProblemKind::Collision).
    pub known_places: Option<std::sync::Arc<Places>>,
}

/// Combinations of actuator places ([`Piston::place`](super::plant::Piston::place)), in table order.
/// A hash set (foldhash): every faulty run looks its combination up at
/// every change of place.
pub type Places = foldhash::HashSet<Vec<u32>>;

impl Default for SimSettings {
    fn default() -> Self {
        SimSettings {
            scan_ms: 10,
            machine: Machine::default(),
            window: 0.02,
            cycles: 2,
            faults: Vec::new(),
            fault_onset_ms: 0,
            record_trace: false,
            input_delays: BTreeMap::new(),
            stop_at_hazard: false,
            record_places: false,
            known_places: None,
        }
    }
}

impl SimSettings {
    pub fn stroke(&self, actuator: u32) -> Stroke {
        self.machine.strokes.of(actuator)
    }

    /// How long after its step starts the machine gives `input`.
    pub fn input_delay_ms(&self, input: &Name) -> u32 {
        self.input_delays
            .get(input)
            .copied()
            .unwrap_or(DEFAULT_INPUT_DELAY_MS)
    }
}
