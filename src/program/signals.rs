//! Which signals a program uses, decided once from the table and the
//! options: the address allocation lays out exactly these, and the rungs
//! that reset "every output" or "every memory" read them from here.

use super::Literal;
use super::options::ProgramOptions;
use super::signal::{Alarm, Signal};
use crate::actuator::{ActuatorKind, CoilSet, Valves};
use crate::cell::Sign;
use crate::table::StepTable;
use std::collections::BTreeMap;

/// The coils of one actuator's valve.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Coils {
    /// `yi+` and `yi-` of a double-solenoid or 5/3 valve.
    Double { actuator: u32 },
    /// The one coil `yi` of a single-solenoid (`52mono`) valve.
    Single { actuator: u32 },
}

impl Coils {
    /// The coils of actuator `actuator`, as its kind has them.
    pub fn of(kind: ActuatorKind, actuator: u32) -> Coils {
        match kind.coils() {
            CoilSet::Single => Coils::Single { actuator },
            CoilSet::Double => Coils::Double { actuator },
        }
    }

    /// Its coils: the one that extends, then the one that retracts.
    pub fn signals(self) -> Vec<Signal> {
        std::iter::once(self.extend())
            .chain(self.retract())
            .collect()
    }

    pub fn actuator(self) -> u32 {
        match self {
            Coils::Double { actuator } | Coils::Single { actuator } => actuator,
        }
    }

    /// The coil that extends (the only one of a single-solenoid valve).
    pub fn extend(self) -> Signal {
        match self {
            Coils::Double { actuator } => Signal::Coil {
                actuator,
                sign: Sign::Plus,
            },
            Coils::Single { actuator } => Signal::SingleCoil { actuator },
        }
    }

    /// The coil that retracts, if the valve has one.
    pub fn retract(self) -> Option<Signal> {
        match self {
            Coils::Double { actuator } => Some(Signal::Coil {
                actuator,
                sign: Sign::Minus,
            }),
            Coils::Single { .. } => None,
        }
    }
}

/// Every bit signal of a program, in the order addresses are given.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Signals {
    /// START, each actuator's sensors 0…pmax, machine inputs, mode buttons.
    pub inputs: Vec<Signal>,
    /// Each actuator's valve, in ascending actuator number.
    pub valves: Vec<Coils>,
    /// The outputs after the coils: machine outputs, then alarms.
    pub outputs: Vec<Signal>,
    /// Middle-stop requests (and a drive's stop at each of its targets),
    /// then the memories of the safety checks, dwells and modes.
    pub memories: Vec<Signal>,
    /// Each actuator's kind: it decides its coils, its stops and what may
    /// stay on when the machine halts.
    pub kinds: BTreeMap<u32, ActuatorKind>,
}

impl Signals {
    /// Whether actuator `actuator` is an electric drive (its outputs are
    /// cut at every target and may not stay on).
    pub fn drives(&self, actuator: u32) -> bool {
        self.kinds.get(&actuator).is_some_and(|k| k.is_drive())
    }

    /// What says actuator `actuator` is at `position`, as its kind reads it
    /// (its own sensor on, for every kind that has one there).
    pub fn at(&self, actuator: u32, position: u32) -> Literal {
        let kind = self.kinds.get(&actuator).copied();
        let reading = kind.map_or(
            crate::actuator::Reading {
                sensor: position,
                on: true,
            },
            |k| k.reading(position),
        );
        let sensor = Signal::Sensor {
            actuator,
            position: reading.sensor,
        };
        if reading.on {
            Literal::is(sensor)
        } else {
            Literal::not(sensor)
        }
    }

    /// The sensors actuator `actuator` has, in address order.
    pub fn sensors_of(&self, actuator: u32) -> impl Iterator<Item = Signal> + '_ {
        self.inputs
            .iter()
            .copied()
            .filter(move |s| matches!(s, Signal::Sensor { actuator: a, .. } if *a == actuator))
    }

    /// Whether `signal` is an output of an electric drive (valve type
    /// `motor`): it runs the drive for as long as it is on.
    pub fn is_drive(&self, signal: Signal) -> bool {
        matches!(signal, Signal::Coil { actuator, .. } if self.drives(actuator))
    }

    /// Every output the machine drives (coils and machine outputs, not
    /// alarms): extend coils, then retract coils, then machine outputs.
    pub fn driven(&self) -> impl Iterator<Item = Signal> + '_ {
        self.valves
            .iter()
            .map(|v| v.extend())
            .chain(self.valves.iter().filter_map(|v| v.retract()))
            .chain(
                self.outputs
                    .iter()
                    .copied()
                    .filter(|s| matches!(s, Signal::MachineOutput(_))),
            )
    }

    /// The outputs of the criteria analysis (`miss1`…): on while a step
    /// has run out of time with its criterion unmet.
    pub fn misses(&self) -> impl Iterator<Item = Signal> + '_ {
        self.outputs
            .iter()
            .copied()
            .filter(|s| matches!(s, Signal::Missing(_)))
    }

    /// The alarm outputs.
    pub fn alarms(&self) -> impl Iterator<Item = Signal> + '_ {
        self.outputs
            .iter()
            .copied()
            .filter(|s| matches!(s, Signal::Alarm(_)))
    }
}

/// The signals a program of `table` under `options` uses.
pub(super) fn declare(table: &StepTable, options: &ProgramOptions, valves: &Valves) -> Signals {
    let safety = options.safety;
    let modes = &options.modes;
    let kinds: BTreeMap<u32, ActuatorKind> = table
        .actuators
        .iter()
        .map(|a| (a.number, valves.of(a.number, a.max_position)))
        .collect();
    let sensors = table.actuators.iter().flat_map(|actuator| {
        let number = actuator.number;
        kinds[&number]
            .sensed_positions(actuator.max_position)
            .into_iter()
            .map(move |position| Signal::Sensor {
                actuator: number,
                position,
            })
    });
    let mode_inputs = modes.buttons();
    let jogs = if modes.manual {
        jog_buttons(&kinds)
    } else {
        Vec::new()
    };
    let inputs = std::iter::once(Signal::Start)
        .chain(sensors)
        .chain(table.inputs.iter().map(|n| Signal::MachineInput(*n)))
        .chain(options.held_inputs().into_iter().map(Signal::MachineInput))
        .chain(mode_inputs)
        .chain(jogs)
        .collect();
    let coils = table
        .actuators
        .iter()
        .map(|a| Coils::of(kinds[&a.number], a.number))
        .collect();
    let alarms = [
        (safety.plausibility, Alarm::Sensor),
        (safety.watchdog, Alarm::Timeout),
        (!options.interlocks.is_empty(), Alarm::Interlock),
    ]
    .into_iter()
    .filter_map(|(wanted, alarm)| wanted.then_some(Signal::Alarm(alarm)));
    let outputs = table
        .outputs
        .iter()
        .map(|n| Signal::MachineOutput(*n))
        .chain(alarms)
        .collect();

    let drives = |actuator: &u32| kinds.get(actuator).is_some_and(|k| k.is_drive());
    // A drive stops at every target (it runs until its output is cut);
    // a cylinder only at a middle one.
    let mut stops: Vec<(u32, u32)> = table
        .steps
        .iter()
        .flat_map(|s| &s.moves)
        .filter(|m| {
            drives(&m.actuator)
                || (options.middle_stops
                    && table
                        .actuator(m.actuator)
                        .is_some_and(|a| a.is_middle(m.to)))
        })
        .map(|m| (m.actuator, m.to))
        .collect();
    stops.sort_unstable();
    stops.dedup();
    let mut memories: Vec<Signal> = stops
        .into_iter()
        .map(|(actuator, position)| Signal::StopAt { actuator, position })
        .collect();
    if safety.edge {
        memories.push(Signal::StartMemory);
    }
    if options.halts() {
        memories.push(Signal::Halt);
    }
    if safety.watchdog {
        memories.push(Signal::WatchdogArmed);
    }
    memories.extend(table.dwells().map(|d| Signal::DwellArmed(d.number)));
    memories.extend((1..=options.run_ons().len()).map(|n| Signal::RunOnArmed(n as u16)));
    memories.extend(options.zones().map(|(zone, _)| zone));
    if modes.any() {
        memories.push(Signal::CycleRequest);
        memories.push(Signal::Busy);
    }
    if modes.continuous {
        memories.push(Signal::AutoRun);
    }
    if modes.step {
        memories.push(Signal::StepPermit);
        memories.push(Signal::StepMemory);
    }
    if modes.manual {
        memories.push(Signal::ManualMemory);
    }
    if modes.reset {
        memories.push(Signal::Homing);
        memories.push(Signal::ResetMemory);
        let stages = modes.home_stages(table).map(|s| s.len()).unwrap_or(0);
        memories.extend((1..=stages).map(|n| Signal::HomeStage(n as u16)));
    }
    let mut signals = Signals {
        inputs,
        valves: coils,
        outputs,
        memories,
        kinds,
    };
    let jogged = signals.jogged_memories(options);
    signals.memories.extend(jogged);
    // Last, so that no other memory moves.
    if modes.manual {
        signals.memories.push(Signal::JogsReleased);
    }
    signals
}

/// The jog button that switches `coil` on.
pub(super) fn jog_of(coil: Signal) -> Signal {
    match coil {
        Signal::Coil { actuator, sign } => Signal::Jog { actuator, sign },
        Signal::SingleCoil { actuator } => Signal::Jog {
            actuator,
            sign: Sign::Plus,
        },
        other => other,
    }
}

impl Signals {
    /// Manual mode's memory of each actuator whose held coils a jog takes
    /// over (after every other memory, so none of theirs moves).
    fn jogged_memories(&self, options: &ProgramOptions) -> Vec<Signal> {
        self.valves
            .iter()
            .filter(|v| !self.held_by_jog(**v, options).is_empty())
            .map(|v| Signal::Jogged(v.actuator()))
            .collect()
    }

    /// The coils of `valve` a halt row holds on (hold-safe, `on stop … hold`)
    /// that its jogs take over: each stays on into manual as the halt left it,
    /// until a jog of its actuator is pressed; from then on it is on only while
    /// its button is held, as every other coil. A drive is never held; a coil
    /// that holds a part (a vacuum) stays as its jogs leave it.
    pub(super) fn held_by_jog(&self, valve: Coils, options: &ProgramOptions) -> Vec<Signal> {
        let signals = self;
        let actuator = valve.actuator();
        let kind = signals.kinds.get(&actuator);
        if signals.drives(actuator) || kind.is_some_and(|k| k.holds_part()) {
            return Vec::new();
        }
        valve
            .signals()
            .into_iter()
            .filter(|coil| options.halt.may_stay_on(*coil, false))
            .filter(|coil| signals.inputs.contains(&jog_of(*coil)))
            .collect()
    }
}

/// The jog buttons of manual mode, actuator by actuator: `+` then `-`; a
/// single-solenoid valve only `+` (its spring retracts it, no button can
/// do more).
pub fn jog_buttons(kinds: &BTreeMap<u32, ActuatorKind>) -> Vec<Signal> {
    kinds
        .iter()
        .flat_map(|(&actuator, kind)| {
            let signs: &[Sign] = if kind.jogs_back() {
                &[Sign::Plus, Sign::Minus]
            } else {
                &[Sign::Plus]
            };
            signs
                .iter()
                .map(move |&sign| Signal::Jog { actuator, sign })
        })
        .collect()
}
