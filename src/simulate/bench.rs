//! The bench: any controller against the plant, one PLC scan at a time.
//! A scan reads the inputs as the machine stands at its start, runs the
//! controller, writes its outputs to the valves and lets the plant move
//! for one scan period: the same [`World`] the step program's proofs and
//! fault runs read and move (`run`), so a controller proven here is proven
//! against the machine a converted program is. The synthesised
//! controllers (`synth::verify`) are proven here, and a converted
//! program's [`PlcState`] runs here too, so the two can be compared on one
//! machine.
//!
//! What the bench does not do is judge: which moves were due, which step
//! a move belongs to, what counts as a hazard. A step program's proof
//! judges those from its steps (`run`); a synthesised controller, which
//! has no steps, is judged by its sequence of actions (`synth::verify`).

use super::plc::{PlcState, scan};
use super::world::{World, pistons, read_input};
use super::{Operator, SimSettings};
use crate::cell::Sign;
use crate::program::Signal;
use crate::stroke::Stroke;
use crate::table::StepTable;

/// A program under test, scan by scan: it reads the machine's inputs as
/// [`Signal`]s and sets its outputs, the valve coils among them
/// ([`Signal::Coil`], [`Signal::SingleCoil`]).
pub trait Controller {
    /// One scan of `scan_ms`; `input` reads an input as it stood at the
    /// start of the scan. An error ends the run (a controller running in
    /// another engine that failed).
    fn scan(&mut self, input: &dyn Fn(Signal) -> bool, scan_ms: u64) -> Result<(), String>;

    /// Whether `output` is on after the last scan.
    fn output(&self, output: Signal) -> bool;
}

/// The step program, as its proof executes it.
impl Controller for PlcState<'_> {
    fn scan(&mut self, input: &dyn Fn(Signal) -> bool, scan_ms: u64) -> Result<(), String> {
        scan(self, input, scan_ms);
        Ok(())
    }

    fn output(&self, output: Signal) -> bool {
        self.bit(output)
    }
}

/// A two-position cylinder on a bistable 5/2 valve (DESIGN §7's
/// actuators), and where it stands at power-up.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Cylinder {
    pub number: u32,
    pub stroke: Stroke,
    /// At its extended end, its valve that way (a sequence that begins by
    /// retracting it); otherwise home.
    pub extended: bool,
}

/// The plant and the operator, between two scans.
pub struct Bench {
    world: World,
    time_ms: u64,
}

impl Bench {
    /// The plant of `table` as its proof builds it: every actuator home on
    /// its valve, with its stroke and load.
    pub fn for_table(table: &StepTable, settings: &SimSettings) -> Bench {
        Bench {
            world: World::new(settings, pistons(table, settings)),
            time_ms: 0,
        }
    }

    /// `cylinders`, each where it stands at power-up.
    pub fn cylinders(cylinders: &[Cylinder], settings: &SimSettings) -> Bench {
        let scan_ms = settings.scan_ms.max(1);
        let pistons = cylinders
            .iter()
            .map(|c| {
                let mut p = super::plant::Piston::new(c.number, 1, c.stroke, scan_ms);
                if c.extended {
                    p.drive(true, false);
                    p.s = 1.0;
                }
                p
            })
            .collect();
        Bench {
            world: World::new(settings, pistons),
            time_ms: 0,
        }
    }

    /// The operator's buttons from the next scan on.
    pub fn press(&mut self, operator: Operator) {
        self.world.operator = operator;
    }

    /// The time of the next scan, in milliseconds from power-up.
    pub fn time_ms(&self) -> u64 {
        self.time_ms
    }

    /// What an input reads now (a sensor, a button).
    pub fn input(&self, signal: Signal) -> bool {
        read_input(signal, &self.world)
    }

    /// Every actuator's position in sensor units, in the bench's order.
    pub fn positions(&self) -> Vec<f64> {
        self.world
            .pistons
            .iter()
            .map(super::plant::Piston::position_units)
            .collect()
    }

    /// One scan of `controller` and one scan period of the plant; the
    /// actuators whose valve saw both coils in it.
    pub fn scan(&mut self, controller: &mut dyn Controller) -> Result<Vec<u32>, String> {
        let world = &mut self.world;
        world.faults_active = self.time_ms >= world.settings.fault_onset_ms;
        let scan_ms = world.settings.scan_ms as u64;
        controller.scan(&|s| read_input(s, world), scan_ms)?;
        let mut conflicts = Vec::new();
        for i in 0..world.pistons.len() {
            let number = world.pistons[i].number;
            let coil = |sign| {
                controller.output(Signal::Coil {
                    actuator: number,
                    sign,
                })
            };
            let plus =
                coil(Sign::Plus) || controller.output(Signal::SingleCoil { actuator: number });
            if world.actuate(i, plus, coil(Sign::Minus)).conflict {
                conflicts.push(number);
            }
        }
        self.time_ms += scan_ms;
        Ok(conflicts)
    }
}
