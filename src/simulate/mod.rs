//! Simulation: proof that a generated program runs the machine (DESIGN §5).
//!
//! A cyclic PLC scan (read inputs, execute the step program, write outputs)
//! runs against the plant model. An operator presses START, the program must
//! drive every step in order, every move must end at its target sensor without
//! running through it, nothing may move outside its step, no valve may see both
//! coils, everything must be home at the end, and a second START must run an
//! identical second cycle.

pub mod io;
mod machine;
pub mod plant;
pub mod plc;
pub mod report;
pub mod scenario;

use std::collections::BTreeMap;

use crate::cell::{Name, Sign};
use crate::program::{Action, Literal, StepKind, StepProgram};
use crate::program::{Alarm, Signal};
use crate::table::{Move, StepTable};
use crate::timing::{Stroke, Strokes};
use crate::valve::Valves;
use plant::Piston;
use plc::{PlcState, scan};

/// Stroke fraction per second a 5/3 piston drifts with no coil on, unless
/// `--load` says otherwise.
pub const DEFAULT_DRIFT: f64 = 0.05;

/// How long the operator holds START.
const START_PRESS_MS: u32 = 100;
/// Idle time before the first press and between cycles.
const IDLE_MS: u32 = 500;
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
        if self.stuck_at {
            format!("{} short circuit (stuck at 1)", self.signal.symbol())
        } else {
            format!("{} open circuit (stuck at 0)", self.signal.symbol())
        }
    }
}

/// Simulation settings.
#[derive(Debug, Clone, PartialEq)]
pub struct SimSettings {
    /// PLC scan time in milliseconds.
    pub scan_ms: u32,
    /// Stroke times of every actuator.
    pub strokes: Strokes,
    /// Valve types given explicitly (the others get the default for their positions).
    pub valves: Valves,
    /// Drift, in stroke per second, of a piston on a 5/3 valve with no coil
    /// on: the load on an exhausted centre (towards home), the creep of a
    /// pressurised centre (outwards). Per actuator; default 0.05.
    pub loads: BTreeMap<u32, f64>,
    /// Half-width of a sensor's detection window, as a fraction of the stroke.
    pub window: f64,
    /// Number of START presses (cycles) to run.
    pub cycles: usize,
    /// Input faults present from the start of the run.
    pub faults: Vec<Fault>,
    /// Record every actuator's position at every scan (for the time diagram).
    pub record_trace: bool,
    /// Per machine input, how long after its step starts the machine gives
    /// the value the step waits for (default [`DEFAULT_INPUT_DELAY_MS`]).
    pub input_delays: BTreeMap<Name, u32>,
}

impl Default for SimSettings {
    fn default() -> Self {
        SimSettings {
            scan_ms: 10,
            strokes: Strokes::default(),
            valves: Valves::default(),
            loads: BTreeMap::new(),
            window: 0.02,
            cycles: 2,
            faults: Vec::new(),
            record_trace: false,
            input_delays: BTreeMap::new(),
        }
    }
}

impl SimSettings {
    pub fn stroke(&self, actuator: u32) -> Stroke {
        self.strokes.of(actuator)
    }
}

/// What went wrong in a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum ProblemKind {
    /// The sequence waits for ever (a safe stall unless something else happened).
    Stall,
    /// A move passed its target sensor.
    RanThrough,
    /// An actuator moved although no step was moving it (or the wrong way).
    OutsideStep,
    /// A valve saw both coils.
    CoilConflict,
    /// A step fired before the previous step's moves physically finished.
    Premature,
    /// A cycle started without a START press.
    UnexpectedStart,
    /// The cycle ended with an actuator away from home.
    NotHome,
    /// The second cycle differs from the first.
    CycleDiffers,
}

impl ProblemKind {
    /// Whether this problem can hurt someone or something (DESIGN §6): a move
    /// that starts too early, motion no step commands, both coils, a start
    /// without START. A run-through is a move that goes on in the direction
    /// its own step commanded to the cylinder's next sensor or end stop
    /// because its target sensor is dead: it fails the run, and the sequence
    /// then stalls, but it is not motion outside the step.
    pub fn is_hazard(self) -> bool {
        !matches!(
            self,
            ProblemKind::Stall
                | ProblemKind::CycleDiffers
                | ProblemKind::RanThrough
                | ProblemKind::NotHome
        )
    }
}

/// One problem, when it happened and in which step.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    pub kind: ProblemKind,
    pub time_ms: u64,
    /// The step the problem concerns (one-based).
    pub step: usize,
    pub message: String,
}

/// Timing of one step in one cycle.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StepTiming {
    pub step: usize,
    /// When the step fired, from the START press of its cycle.
    pub start_ms: u64,
    /// Until the next step fired (or, for the last step, until its moves ended).
    pub duration_ms: u64,
    /// What the step does, in the table's notation.
    pub moves: String,
    /// Dwells and waits of the step, as they happened: `T=2s from 1.21 s`,
    /// `I:part_present after 0.50 s`.
    pub notes: String,
}

/// A span of time in the run (absolute milliseconds) with a label: a dwell
/// running or a step waiting for a machine input. Drawn on the time diagram.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Span {
    pub from_ms: u64,
    pub to_ms: u64,
    pub label: String,
}

/// The operator's buttons and switches at one moment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Operator {
    pub start: bool,
    pub continuous: bool,
    /// STOP pressed (the normally closed input reads 0).
    pub stop: bool,
    /// EMERGENCY STOP pressed (the normally closed input reads 0).
    pub estop: bool,
    pub reset: bool,
}

/// One complete or interrupted cycle.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CycleReport {
    /// Absolute time of the START press.
    pub press_ms: u64,
    pub steps: Vec<StepTiming>,
    /// From the START press to the end of the last move, when the cycle completed.
    pub cycle_ms: Option<u64>,
}

/// The result of a simulation run.
#[derive(Debug, Clone, PartialEq)]
pub struct SimReport {
    pub passed: bool,
    pub cycles: Vec<CycleReport>,
    pub problems: Vec<Problem>,
    /// Step the sequence waited at when the run ended (one-based), if stalled.
    pub stalled_at: Option<usize>,
    /// Positions in sensor units of every actuator (table order) at each step
    /// boundary of the first cycle: before step 1, …, after the last step.
    pub step_positions: Vec<Vec<f64>>,
    /// Actuator numbers, in the order of every position vector.
    pub actuators: Vec<(u32, u32)>,
    /// `(time_ms, positions)` at every scan, when recorded.
    pub trace: Vec<(u64, Vec<f64>)>,
    /// Dwells and waits of the first cycle, in absolute time.
    pub spans: Vec<Span>,
}

impl SimReport {
    /// One line: `passed: cycle 8.46 s` or the reason it failed.
    pub fn verdict(&self) -> String {
        if self.passed {
            let ms = self
                .cycles
                .first()
                .and_then(|c| c.cycle_ms)
                .unwrap_or_default();
            format!("passed: cycle time {}", seconds(ms))
        } else {
            format!("FAILED: {}", self.reason())
        }
    }

    /// Why the run failed: a stall with the run-throughs that explain it, or
    /// else the first problem.
    pub fn reason(&self) -> String {
        let stall = self.problems.iter().find(|p| p.kind == ProblemKind::Stall);
        let Some(first) = stall.or(self.problems.first()) else {
            return "no problem recorded".to_string();
        };
        let mut text = first.message.clone();
        if first.kind == ProblemKind::Stall {
            for p in self
                .problems
                .iter()
                .filter(|p| p.kind == ProblemKind::RanThrough)
            {
                text.push_str("; ");
                text.push_str(&p.message);
            }
        }
        text
    }

    /// Whether any hazard happened.
    pub fn hazard(&self) -> Option<&Problem> {
        self.problems.iter().find(|p| p.kind.is_hazard())
    }
}

/// `1.23 s`.
pub fn seconds(ms: u64) -> String {
    format!("{:.2} s", ms as f64 / 1000.0)
}

/// A move in progress: set when its step fires.
#[derive(Debug, Clone)]
struct ActiveMove {
    piston: usize,
    mv: Move,
    step: usize,
    reached: bool,
    ran_through: bool,
}

struct Run<'a> {
    program: &'a StepProgram,
    /// What the PLC's inputs read from: the plant, the operator, the machine.
    world: World,
    plc: PlcState,
    time_ms: u64,
    problems: Vec<Problem>,
    /// The moves of the step that fired last.
    active: Vec<ActiveMove>,
    /// Per piston, the last move commanded: it may finish settling into its
    /// target window after the next step has fired.
    last_move: Vec<Option<ActiveMove>>,
    pending: Vec<(u64, Name, bool)>,
    /// Inputs the machine gave for the step that fired last.
    answered: Vec<Name>,
    table: &'a StepTable,
    /// Dwell timers: PLC index, dwell number, when it started (if running).
    dwells: Vec<(usize, u16, Option<u64>)>,
    spans: Vec<Span>,
    trace: Vec<(u64, Vec<f64>)>,
    /// Per piston, the PLC indices of its `+`, `-` and single coil.
    coils: Vec<(Option<usize>, Option<usize>, Option<usize>)>,
    /// The I/O of every scan, when recorded for a replay in another engine.
    io: Option<io::IoTrace>,
}

/// Everything the PLC's inputs are read from.
struct World {
    settings: SimSettings,
    pistons: Vec<Piston>,
    index_of: BTreeMap<u32, usize>,
    start_pressed: bool,
    /// Buttons other than START (the standard proof leaves them alone).
    operator: Operator,
    /// Machine inputs as the machine gives them.
    machine: BTreeMap<Name, bool>,
}

impl Run<'_> {
    /// The literals of step `index`'s condition that do not hold now.
    fn missing(&self, index: usize) -> Vec<Literal> {
        let Some(step) = self.program.steps.get(index) else {
            return Vec::new();
        };
        step.condition
            .iter()
            .copied()
            .filter(|l| {
                let raw = if l.signal.is_input() {
                    read_input(l.signal, &self.world)
                } else {
                    self.plc.bit(l.signal)
                };
                raw == l.negated
            })
            .collect()
    }
}

impl Run<'_> {
    /// Whether the cycle has ended: STEP 1 waits for nothing but a start.
    fn cycle_complete(&self) -> bool {
        self.missing(0).iter().all(|l| {
            matches!(
                l.signal,
                Signal::Start | Signal::StartMemory | Signal::CycleRequest
            )
        })
    }

    fn problem(&mut self, kind: ProblemKind, step: usize, message: String) {
        // One report per kind and step is enough to explain what happened.
        if self
            .problems
            .iter()
            .any(|p| p.kind == kind && p.step == step && p.message == message)
        {
            return;
        }
        self.problems.push(Problem {
            kind,
            time_ms: self.time_ms,
            step,
            message,
        });
    }

    /// One PLC scan plus one scan period of the plant. Returns the index of the
    /// step that fired, if any.
    fn tick(&mut self) -> Option<usize> {
        // Inputs are read from the plant as it stands at the start of the
        // scan; the plant does not move while the program runs.
        // The machine gives the inputs its steps wait for.
        let now = self.time_ms;
        let machine = &mut self.world.machine;
        self.pending.retain(|(at, name, value)| {
            if *at <= now {
                machine.insert(*name, *value);
                false
            } else {
                true
            }
        });
        let world = &self.world;
        let read = |s: Signal| read_input(s, world);
        let recorded_inputs = self.io.as_ref().map(|io| {
            io.signals
                .inputs
                .iter()
                .map(|s| read_input(*s, world))
                .collect::<Vec<bool>>()
        });
        let result = scan(
            self.program,
            &mut self.plc,
            &read,
            self.world.settings.scan_ms as u64,
        );
        if let (Some(io), Some(inputs)) = (self.io.as_mut(), recorded_inputs) {
            let outputs = io
                .signals
                .outputs
                .iter()
                .map(|s| self.plc.bit(*s))
                .collect();
            io.scans.push(io::ScanIo {
                time_ms: now,
                inputs,
                outputs,
            });
        }
        if let Some(fired) = result.fired {
            self.on_fire(fired);
        }
        self.track_dwells(now);

        // Outputs to valves, then the plant moves for one scan period.
        for i in 0..self.world.pistons.len() {
            let number = self.world.pistons[i].number;
            let (plus_at, minus_at, single_at) = self.coils[i];
            let on = |at: Option<usize>| at.is_some_and(|i| self.plc.bit_at(i));
            let plus = on(plus_at) || on(single_at);
            let minus = on(minus_at);
            if self.world.pistons[i].drive(plus, minus) {
                let step = self.current_step();
                self.problem(
                    ProblemKind::CoilConflict,
                    step,
                    format!("the valve of C{number} sees both coils y{number}+ and y{number}- in step {step}"),
                );
            }
            if let Some(direction) = self.world.pistons[i].advance() {
                self.check_motion(i, direction);
            }
        }
        self.time_ms += self.world.settings.scan_ms as u64;
        self.update_reached();
        if self.world.settings.record_trace {
            let positions = self
                .world
                .pistons
                .iter()
                .map(Piston::position_units)
                .collect();
            record_point(&mut self.trace, self.time_ms, positions);
        }
        result.fired
    }

    /// The one-based number of the step whose moves are under way.
    fn current_step(&self) -> usize {
        let n = self.program.steps.len();
        let last_fired = (self.plc.awaited + n - 1) % n;
        self.program.steps[last_fired].number
    }

    fn on_fire(&mut self, fired: usize) {
        let step = &self.program.steps[fired];
        self.machine_on_fire(fired);
        if fired == 0
            && !(self.world.start_pressed
                || self.world.operator.start
                || self.world.operator.continuous)
        {
            self.problem(
                ProblemKind::UnexpectedStart,
                step.number,
                "the cycle started without a START press".to_string(),
            );
        }
        let unfinished: Vec<String> = self
            .active
            .iter()
            .filter(|a| !a.reached)
            .map(|a| {
                format!(
                    "C{} had not reached {}",
                    a.mv.actuator,
                    sensor_symbol(&a.mv)
                )
            })
            .collect();
        if !unfinished.is_empty() {
            self.problem(
                ProblemKind::Premature,
                step.number,
                format!(
                    "step {} started before step {} finished ({})",
                    step.number,
                    self.active[0].step,
                    unfinished.join(", ")
                ),
            );
        }
        self.active = step
            .moves
            .iter()
            .filter_map(|m| {
                self.world
                    .index_of
                    .get(&m.actuator)
                    .map(|&piston| ActiveMove {
                        piston,
                        mv: *m,
                        step: step.number,
                        reached: false,
                        ran_through: false,
                    })
            })
            .collect();
        for a in &self.active {
            self.last_move[a.piston] = Some(a.clone());
        }
    }

    fn check_motion(&mut self, piston: usize, direction: Sign) {
        let p = &self.world.pistons[piston];
        let window = p.window(self.world.settings.window);
        let number = p.number;
        let s = p.s;
        let commanded = self.last_move[piston]
            .as_ref()
            .filter(|a| a.mv.sign == direction)
            .cloned();
        let Some(a) = commanded else {
            let step = self.current_step();
            self.problem(
                ProblemKind::OutsideStep,
                step,
                format!(
                    "C{number} moves {} although no step moves it that way (during step {step})",
                    if direction == Sign::Plus { "+" } else { "-" }
                ),
            );
            return;
        };
        let target = p.sensor_point(a.mv.to);
        let beyond = match direction {
            Sign::Plus => s > target + window,
            Sign::Minus => s < target - window,
        };
        if beyond && !a.ran_through {
            for m in self.last_move[piston]
                .iter_mut()
                .chain(self.active.iter_mut().filter(|m| m.piston == piston))
            {
                m.ran_through = true;
            }
            self.problem(
                ProblemKind::RanThrough,
                a.step,
                format!(
                    "C{number} ran through {} in step {}",
                    sensor_symbol(&a.mv),
                    a.step
                ),
            );
        }
    }

    fn update_reached(&mut self) {
        let window = self.world.settings.window;
        for a in &mut self.active {
            if !a.reached && !a.ran_through && self.world.pistons[a.piston].sensor(a.mv.to, window)
            {
                a.reached = true;
            }
        }
    }

    /// Every move under way has reached its target sensor and come to rest
    /// (against the end stop, or held by a closed centre).
    fn all_moves_ended(&self) -> bool {
        self.active.iter().all(|a| {
            let p = &self.world.pistons[a.piston];
            a.reached && p.at_rest() && p.sensor(a.mv.to, self.world.settings.window)
        })
    }

    fn positions(&self) -> Vec<f64> {
        self.world
            .pistons
            .iter()
            .map(Piston::position_units)
            .collect()
    }
}

/// The value an input reads: a fault overrides the plant. STOP and
/// EMERGENCY STOP are normally closed: they read 1 until pressed.
fn read_input(signal: Signal, world: &World) -> bool {
    if let Some(f) = world.settings.faults.iter().find(|f| f.signal == signal) {
        return f.stuck_at;
    }
    let operator = world.operator;
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
        _ => false,
    }
}

fn sensor_symbol(m: &Move) -> String {
    Signal::Sensor {
        actuator: m.actuator,
        position: m.to,
    }
    .symbol()
}

fn literal_text(l: &Literal) -> String {
    if l.negated {
        format!("NOT {}", l.signal.symbol())
    } else {
        l.signal.symbol()
    }
}

/// Adds a point to the position trace, keeping only the corners of the
/// polyline: a point on the straight line through the two before it
/// replaces the last one. A 1,200 s stroke at a 1 ms scan kept 4.7 million
/// points (692 MB, a 67 MB diagram) for a handful of straight lines.
fn record_point(trace: &mut Vec<(u64, Vec<f64>)>, time_ms: u64, positions: Vec<f64>) {
    if let [.., (t0, p0), (t1, p1)] = trace.as_slice() {
        let (dt0, dt1) = ((t1 - t0) as f64, (time_ms - t1) as f64);
        let straight = p0.iter().zip(p1).zip(&positions).all(|((a, b), c)| {
            // Same speed before and after the middle point, to well below
            // what a diagram can show.
            ((b - a) * dt1 - (c - b) * dt0).abs() <= 1e-9 * dt0 * dt1
        });
        if straight {
            *trace.last_mut().expect("two points") = (time_ms, positions);
            return;
        }
    }
    trace.push((time_ms, positions));
}

/// The longest a step may take before the run counts as stalled: well past
/// the slowest stroke, and past the program's own watchdog so that its alarm
/// is seen.
fn step_timeout_ms(table: &StepTable, program: &StepProgram, settings: &SimSettings) -> u64 {
    let watchdog = program
        .steps
        .iter()
        .flat_map(|s| &s.actions)
        .filter_map(|a| match a {
            Action::StartTimer(_, ms) => Some(*ms as u64 + 1000),
            _ => None,
        })
        .max()
        .unwrap_or(0);
    let longest = table
        .actuators
        .iter()
        .map(|a| {
            let s = settings.stroke(a.number);
            s.extend_ms.max(s.retract_ms)
        })
        .max()
        .unwrap_or(1000) as u64;
    // A step may also dwell and wait for the machine before it completes.
    let dwell = table.dwells().map(|d| d.ms).max().unwrap_or(0) as u64;
    let wait = if table.inputs.is_empty() {
        0
    } else {
        table
            .inputs
            .iter()
            .map(|n| {
                settings
                    .input_delays
                    .get(n)
                    .copied()
                    .unwrap_or(DEFAULT_INPUT_DELAY_MS)
            })
            .max()
            .unwrap_or(0) as u64
    };
    (2 * longest + 500 + dwell + wait).max(watchdog)
}

impl<'a> Run<'a> {
    /// Power-up: every piston home, the PLC in its initial state.
    fn new(table: &'a StepTable, program: &'a StepProgram, settings: &SimSettings) -> Run<'a> {
        let scan_ms = settings.scan_ms.max(1);
        let pistons: Vec<Piston> = table
            .actuators
            .iter()
            .map(|a| {
                Piston::with_valve(
                    a.number,
                    a.max_position,
                    settings.stroke(a.number),
                    scan_ms,
                    settings.valves.of(a.number, a.max_position),
                    settings
                        .loads
                        .get(&a.number)
                        .copied()
                        .unwrap_or(DEFAULT_DRIFT),
                )
            })
            .collect();
        let index_of = pistons
            .iter()
            .enumerate()
            .map(|(i, p)| (p.number, i))
            .collect();
        let settings_scan = SimSettings {
            scan_ms,
            ..settings.clone()
        };
        let mut run = Run {
            program,
            world: World {
                settings: settings_scan,
                pistons,
                index_of,
                start_pressed: false,
                operator: Operator::default(),
                machine: table
                    .inputs
                    .iter()
                    .filter_map(|n| machine::rest_value(table, *n).map(|v| (*n, v)))
                    .collect(),
            },
            plc: PlcState::new(program),
            time_ms: 0,
            problems: Vec::new(),
            active: Vec::new(),
            last_move: vec![None; table.actuators.len()],
            pending: Vec::new(),
            answered: Vec::new(),
            table,
            dwells: Vec::new(),
            spans: Vec::new(),
            trace: Vec::new(),
            coils: Vec::new(),
            io: None,
        };
        run.dwells = table
            .dwells()
            .filter_map(|d| {
                run.plc
                    .index_of(Signal::Dwell(d.number))
                    .map(|at| (at, d.number, None))
            })
            .collect();
        run.coils = table
            .actuators
            .iter()
            .map(|a| {
                let at = |s: Signal| run.plc.index_of(s);
                (
                    at(Signal::Coil {
                        actuator: a.number,
                        sign: Sign::Plus,
                    }),
                    at(Signal::Coil {
                        actuator: a.number,
                        sign: Sign::Minus,
                    }),
                    at(Signal::SingleCoil { actuator: a.number }),
                )
            })
            .collect();
        run
    }
}

/// Simulates `program` (built from `table`) against the plant.
pub fn simulate(table: &StepTable, program: &StepProgram, settings: &SimSettings) -> SimReport {
    run(table, program, settings, None).0
}

/// Simulates like [`simulate`] and records `signals` at every scan, so that
/// a written program can be replayed in its own engine and compared.
pub fn simulate_recording(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    signals: io::IoSignals,
) -> (SimReport, io::IoTrace) {
    let (report, trace) = run(table, program, settings, Some(signals));
    (report, trace.unwrap_or_default())
}

fn run(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    record: Option<io::IoSignals>,
) -> (SimReport, Option<io::IoTrace>) {
    let mut run = Run::new(table, program, settings);
    run.io = record.map(|signals| io::IoTrace {
        scan_ms: run.world.settings.scan_ms,
        signals,
        scans: Vec::new(),
    });
    let timeout = step_timeout_ms(table, program, settings);
    let step_count = program.steps.len();
    let mut cycles: Vec<CycleReport> = Vec::new();
    let mut step_positions = vec![run.positions()];
    let mut stalled_at = None;
    let mut first_cycle_end = u64::MAX;

    // Idle before the first press: nothing may happen.
    let mut press_at = IDLE_MS as u64;
    'cycles: for cycle in 0..settings.cycles.max(1) {
        while run.time_ms < press_at {
            run.tick();
        }
        let mut report = CycleReport {
            press_ms: press_at,
            steps: Vec::new(),
            cycle_ms: None,
        };
        let mut fire_times: Vec<u64> = Vec::new();
        let mut last_event = run.time_ms;
        loop {
            // A press the PLC can see: held for two scans at least, however
            // slow the scan.
            let press_ms = START_PRESS_MS.max(2 * run.world.settings.scan_ms) as u64;
            run.world.start_pressed = run.time_ms < press_at + press_ms;
            let before = run.time_ms;
            let fired = run.tick();
            if let Some(index) = fired {
                // A boundary of the diagram: the previous step has ended.
                // (A closing END step is not a boundary: the cycle end is.)
                if cycle == 0 && index > 0 && program.steps[index].kind == StepKind::Table {
                    step_positions.push(run.positions());
                }
                if index == 0 && !fire_times.is_empty() {
                    // Step 1 again before the cycle was seen to end.
                    break;
                }
                fire_times.push(before);
                last_event = run.time_ms;
            }
            // The cycle ends when the machine is at rest: a closing step
            // fires on the home sensors while the last stroke still runs
            // into its end stop, and START must not come before it does.
            let done = fire_times.len() == step_count
                && run.plc.awaited == 0
                && run.all_moves_ended()
                && run.world.pistons.iter().all(plant::Piston::at_rest)
                && run.cycle_complete();
            if done {
                if cycle == 0 {
                    step_positions.push(run.positions());
                }
                report.cycle_ms = Some(run.time_ms - press_at);
                break;
            }
            if run.time_ms - last_event > timeout {
                let waiting = &program.steps[run.plc.awaited];
                // START was pressed and released; it only explains the wait
                // when nothing else is missing.
                // The plant stands still while the sequence waits: what is
                // missing now is what was missing.
                let mut missing_literals = run.missing(run.plc.awaited);
                if missing_literals.len() > 1 {
                    missing_literals.retain(|l| l.signal != Signal::Start);
                }
                let missing: Vec<String> = missing_literals.iter().map(literal_text).collect();
                let alarms: Vec<String> = [Alarm::Sensor, Alarm::Timeout]
                    .into_iter()
                    .map(Signal::Alarm)
                    .filter(|a| run.plc.bit(*a))
                    .map(|a| a.symbol())
                    .collect();
                let mut message = if fire_times.len() == step_count {
                    format!(
                        "the cycle never ends: the moves of step {} do not finish",
                        program.steps[step_count - 1].number
                    )
                } else {
                    format!(
                        "step {} never fires: waiting for {}",
                        waiting.number,
                        if missing.is_empty() {
                            "its condition".to_string()
                        } else {
                            missing.join(" AND ")
                        }
                    )
                };
                if !alarms.is_empty() {
                    message.push_str(&format!(" (alarm: {})", alarms.join(", ")));
                }
                run.problem(ProblemKind::Stall, waiting.number, message);
                stalled_at = Some(waiting.number);
                report.steps = timings(program, &fire_times, run.time_ms, press_at, &run.spans);
                cycles.push(report);
                break 'cycles;
            }
        }
        report.steps = timings(program, &fire_times, run.time_ms, press_at, &run.spans);
        if cycle == 0 {
            first_cycle_end = run.time_ms;
        }
        // Every actuator home at the end of the cycle.
        if report.cycle_ms.is_some() {
            for p in &run.world.pistons {
                if !p.sensor(0, settings.window) {
                    let step = program.steps[step_count - 1].number;
                    run.problems.push(Problem {
                        kind: ProblemKind::NotHome,
                        time_ms: run.time_ms,
                        step,
                        message: format!("C{} is not home at the end of the cycle", p.number),
                    });
                }
            }
        }
        let complete = report.cycle_ms.is_some();
        cycles.push(report);
        if !complete {
            break;
        }
        press_at = run.time_ms + IDLE_MS as u64;
    }
    // A short idle after the last cycle: nothing may move on its own.
    if stalled_at.is_none() {
        let until = run.time_ms + IDLE_MS as u64;
        run.world.start_pressed = false;
        while run.time_ms < until {
            run.tick();
        }
    }

    if let (Some(first), Some(second)) = (cycles.first(), cycles.get(1))
        && first.cycle_ms.is_some()
        && second.cycle_ms.is_some()
    {
        let durations = |c: &CycleReport| c.steps.iter().map(|s| s.duration_ms).collect::<Vec<_>>();
        if durations(first) != durations(second) {
            run.problems.push(Problem {
                kind: ProblemKind::CycleDiffers,
                time_ms: run.time_ms,
                step: 1,
                message: "the second cycle's step timing differs from the first".to_string(),
            });
        }
    }
    // Say where each run-through ended: "C2 ran through x22 to x23".
    for problem in &mut run.problems {
        if problem.kind != ProblemKind::RanThrough {
            continue;
        }
        if let Some(piston) = problem
            .message
            .strip_prefix('C')
            .and_then(|rest| rest.split(' ').next())
            .and_then(|n| n.parse::<u32>().ok())
            .and_then(|n| run.world.index_of.get(&n))
            .map(|i| &run.world.pistons[*i])
        {
            let end = match piston.sensor_on(settings.window) {
                Some(position) => Signal::Sensor {
                    actuator: piston.number,
                    position,
                }
                .symbol(),
                None => format!("position {:.2}", piston.position_units()),
            };
            problem.message =
                problem
                    .message
                    .replacen(" in step", &format!(" to {end} in step"), 1);
        }
    }
    let all_cycles_done =
        cycles.len() == settings.cycles.max(1) && cycles.iter().all(|c| c.cycle_ms.is_some());
    run.problems.sort_by_key(|p| p.time_ms);
    let report = SimReport {
        passed: run.problems.is_empty() && all_cycles_done,
        cycles,
        problems: run.problems,
        stalled_at,
        step_positions,
        actuators: table
            .actuators
            .iter()
            .map(|a| (a.number, a.max_position))
            .collect(),
        trace: run.trace,
        spans: run
            .spans
            .into_iter()
            .filter(|s| s.from_ms < first_cycle_end)
            .collect(),
    };
    (report, run.io)
}

fn timings(
    program: &StepProgram,
    fire_times: &[u64],
    end: u64,
    press_at: u64,
    spans: &[Span],
) -> Vec<StepTiming> {
    fire_times
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let next = fire_times.get(i + 1).copied().unwrap_or(end);
            let step = &program.steps[i];
            let notes: Vec<String> = spans
                .iter()
                .filter(|s| s.from_ms >= *t && s.from_ms < next)
                .map(|s| {
                    if s.label.starts_with("I:") {
                        format!("{} came after {}", s.label, seconds(s.to_ms - t))
                    } else {
                        format!(
                            "{} ran {:.2}–{}",
                            s.label,
                            (s.from_ms - t) as f64 / 1000.0,
                            seconds(s.to_ms - t)
                        )
                    }
                })
                .collect();
            StepTiming {
                step: step.number,
                start_ms: t - press_at,
                duration_ms: next - t,
                // The closing step moves nothing (its row stays blank, as it always has).
                moves: match step.kind {
                    StepKind::Table => step.title.clone(),
                    StepKind::EndOfCycle => String::new(),
                },
                notes: notes.join("; "),
            }
        })
        .collect()
}

#[cfg(test)]
mod tests;
