//! The machine a controller runs against: the plant's pistons, the
//! operator's buttons, the machine's own inputs and the faults present.
//! One scan reads its inputs here ([`read_input`]) and moves the plant
//! here ([`World::actuate`]), whichever controller runs it: the step
//! program in a proof or a fault run (`run`), or any controller on the
//! bench (`bench.rs`, which builds on this world), such as a synthesised one. So a converted
//! program and a synthesised controller are proven against the very same
//! machine, not against two models of it.

use std::collections::BTreeMap;
use std::sync::Arc;

use super::plant::Piston;
use super::{DEFAULT_DRIFT, Operator, SimSettings};
use crate::cell::{Name, Sign};
use crate::program::Signal;
use crate::table::StepTable;

/// Everything the PLC's inputs are read from.
#[derive(Clone)]
pub(in crate::simulate) struct World {
    /// Shared: a copy of the run (the fault analysis's checkpoints) keeps
    /// them until it is resumed under others.
    pub(in crate::simulate) settings: Arc<SimSettings>,
    pub(in crate::simulate) pistons: Vec<Piston>,
    /// Each actuator's piston, by number (shared by the run's copies).
    pub(in crate::simulate) index_of: Arc<PistonIndex>,
    pub(in crate::simulate) start_pressed: bool,
    /// Buttons other than START (the standard proof leaves them alone).
    pub(in crate::simulate) operator: Operator,
    /// Machine inputs as the machine gives them.
    pub(in crate::simulate) machine: BTreeMap<Name, bool>,
    /// The faults have appeared (the run has reached their onset).
    pub(in crate::simulate) faults_active: bool,
    /// Counts the changes of the faults in `settings`: a reader that
    /// resolved them once knows when to do it again.
    pub(in crate::simulate) faults_changed: u32,
}

/// Each actuator's piston by its number, looked up at every reading of a
/// sensor: a table by number (numbers go up to [`crate::cell::MAX_ACTUATOR`])
/// rather than a map.
pub(in crate::simulate) struct PistonIndex(Vec<Option<usize>>);

impl PistonIndex {
    fn new(pistons: &[Piston]) -> PistonIndex {
        let size = pistons.iter().map(|p| p.number as usize + 1).max();
        let mut index = vec![None; size.unwrap_or(0)];
        for (i, p) in pistons.iter().enumerate() {
            index[p.number as usize] = Some(i);
        }
        PistonIndex(index)
    }

    /// The piston of actuator `number`, if the table has it.
    pub(in crate::simulate) fn get(&self, number: &u32) -> Option<&usize> {
        self.0.get(*number as usize)?.as_ref()
    }
}

/// What one scan's outputs did to a piston.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(in crate::simulate) struct Actuated {
    /// Both coils were on (a 5/2 valve keeps its spool, a 5/3 centres).
    pub(in crate::simulate) conflict: bool,
    /// The direction the piston moved in during the scan, if it moved.
    pub(in crate::simulate) moved: Option<Sign>,
}

impl World {
    /// The machine at power-up with `pistons`, nothing pressed, no
    /// machine input given; the scan time at least 1 ms.
    pub(in crate::simulate) fn new(settings: &SimSettings, pistons: Vec<Piston>) -> World {
        let index_of = PistonIndex::new(&pistons);
        World {
            settings: Arc::new(SimSettings {
                scan_ms: settings.scan_ms.max(1),
                ..settings.clone()
            }),
            pistons,
            index_of: Arc::new(index_of),
            start_pressed: false,
            operator: Operator::default(),
            machine: BTreeMap::new(),
            faults_active: settings.fault_onset_ms == 0,
            faults_changed: 0,
        }
    }

    /// The input `signal` reads `stuck_at` from this scan on (a scenario
    /// sticks inputs as it goes). Every change of the faults goes through
    /// here or a new `settings`, and counts in `faults_changed`.
    pub(in crate::simulate) fn stick(&mut self, signal: Signal, stuck_at: bool) {
        let settings = Arc::make_mut(&mut self.settings);
        settings.faults.retain(|f| f.signal != signal);
        settings.faults.push(super::Fault { signal, stuck_at });
        // Faults from power-up on: the ones present are the ones stuck so far.
        settings.fault_onset_ms = 0;
        self.faults_active = true;
        self.faults_changed += 1;
    }

    /// The outputs of one scan to piston `i`'s valve (`plus` and `minus`
    /// as its coils or a drive's contactors read), then the plant moves
    /// it for one scan period.
    pub(in crate::simulate) fn actuate(&mut self, i: usize, plus: bool, minus: bool) -> Actuated {
        let window = self.settings.window;
        let piston = &mut self.pistons[i];
        let was = piston.spool;
        let conflict = piston.drive(plus, minus);
        piston.settle(was, window);
        Actuated {
            conflict,
            moved: piston.advance(),
        }
    }
}

/// One piston per actuator of `table`, home, on its valve with its stroke
/// and load as `settings` give them.
pub(in crate::simulate) fn pistons(table: &StepTable, settings: &SimSettings) -> Vec<Piston> {
    let scan_ms = settings.scan_ms.max(1);
    table
        .actuators
        .iter()
        .map(|a| {
            Piston::with_valve(
                a.number,
                a.max_position,
                settings.stroke(a.number),
                scan_ms,
                settings.machine.valves.of(a.number, a.max_position),
                settings
                    .machine
                    .loads
                    .get(&a.number)
                    .copied()
                    .unwrap_or(DEFAULT_DRIFT),
            )
        })
        .collect()
}

/// The value an input reads: a fault overrides the plant. STOP and
/// EMERGENCY STOP are normally closed: they read 1 until pressed.
pub(in crate::simulate) fn read_input(signal: Signal, world: &World) -> bool {
    if world.faults_active
        && let Some(f) = world.settings.faults.iter().find(|f| f.signal == signal)
    {
        return f.stuck_at;
    }
    read_unfaulted(signal, world)
}

/// Where one input is read from, found once rather than at every reading
/// (a fault run reads a dozen inputs at each of its scans).
#[derive(Debug, Clone, Copy)]
pub(in crate::simulate) enum InputSource {
    /// Sensor `position` of the piston at index `piston`.
    Sensor { piston: usize, position: u32 },
    /// Anything else, read as [`read_input`] reads it.
    Other(Signal),
}

impl World {
    /// Where `signal` is read from.
    pub(in crate::simulate) fn source(&self, signal: Signal) -> InputSource {
        match signal {
            Signal::Sensor { actuator, position } => match self.index_of.get(&actuator) {
                Some(&piston) => InputSource::Sensor { piston, position },
                None => InputSource::Other(signal),
            },
            _ => InputSource::Other(signal),
        }
    }

    /// What an input found at `source` reads without its faults.
    #[inline]
    pub(in crate::simulate) fn read_source(&self, source: InputSource) -> bool {
        match source {
            InputSource::Sensor { piston, position } => {
                self.pistons[piston].sensor(position, self.settings.window)
            }
            InputSource::Other(signal) => read_unfaulted(signal, self),
        }
    }
}

/// What an input reads without its faults.
fn read_unfaulted(signal: Signal, world: &World) -> bool {
    // By reference: a copy of the buttons at every reading costs more than
    // the reading.
    let operator = &world.operator;
    match signal {
        Signal::Start => world.start_pressed || operator.start,
        Signal::Sensor { actuator, position } => world
            .index_of
            .get(&actuator)
            .is_some_and(|i| world.pistons[*i].sensor(position, world.settings.window)),
        Signal::MachineInput(name) => world.machine.get(&name).copied().unwrap_or(false),
        Signal::Continuous => operator.continuous,
        Signal::Stop => !operator.stop,
        Signal::EStop => !operator.estop,
        Signal::Reset => operator.reset,
        Signal::StepMode => operator.step_mode,
        Signal::StepButton => operator.step,
        Signal::ManualMode => operator.manual,
        Signal::Jog { .. } => operator.jogs.held(signal),
        _ => false,
    }
}
