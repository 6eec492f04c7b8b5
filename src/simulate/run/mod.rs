//! One run of the program against the plant, scan by scan: the state of
//! the run and what each scan checks.

mod checkpoint;
mod cycle;
mod drive;
mod machine;

pub use checkpoint::{Checkpoints, Course, Resumed, Trail};
pub(super) use checkpoint::{checkpoints, resume};
pub(super) use cycle::{run, run_logging_inputs};

use super::plant::Piston;
use super::plc::{PlcState, scan};
pub(in crate::simulate) use super::world::{World, pistons, read_input};
use super::*;
use crate::cell::{Name, Sign};
use crate::program::{Literal, Signal, StepProgram};
use crate::table::{Move, StepTable};

/// A move in progress: set when its step fires.
#[derive(Debug, Clone)]
pub(in crate::simulate) struct ActiveMove {
    pub(in crate::simulate) piston: usize,
    pub(in crate::simulate) mv: Move,
    pub(in crate::simulate) step: usize,
    pub(in crate::simulate) reached: bool,
    pub(in crate::simulate) ran_through: bool,
}

impl ActiveMove {
    /// The stroke fractions below and above which the piston has run
    /// through this move's target: beyond its sensor's window.
    pub(in crate::simulate) fn run_through_bounds(
        &self,
        piston: &Piston,
        window: f64,
    ) -> (f64, f64) {
        let target = piston.sensor_point(self.mv.to);
        let half = piston.window(window);
        (target - half, target + half)
    }
}

#[derive(Clone)]
pub(in crate::simulate) struct Run<'a> {
    pub(in crate::simulate) program: &'a StepProgram,
    /// What the PLC's inputs read from: the plant, the operator, the machine.
    pub(in crate::simulate) world: World,
    pub(in crate::simulate) plc: PlcState<'a>,
    pub(in crate::simulate) time_ms: u64,
    pub(in crate::simulate) problems: Vec<Problem>,
    /// The moves of the step that fired last.
    pub(in crate::simulate) active: Vec<ActiveMove>,
    /// Per piston, the last move commanded: it may finish settling into its
    /// target window after the next step has fired.
    pub(in crate::simulate) last_move: Vec<Option<ActiveMove>>,
    pub(in crate::simulate) pending: Vec<(u64, Name, bool)>,
    /// Inputs the machine gave for the step that fired last.
    pub(in crate::simulate) answered: Vec<Name>,
    /// The jump the machine takes in the cycle under way: the index of its
    /// step and the jump (its input given once that step has fired).
    pub(in crate::simulate) jump_taken: Option<(usize, crate::table::Jump)>,
    /// The machine has given that jump's input in this cycle (once: a
    /// jump back must not loop for ever).
    pub(in crate::simulate) jump_given: bool,
    /// The jumps tested and not taken in the cycle under way (the step
    /// they leave, one-based, and the jump): the other side of each path.
    pub(in crate::simulate) declined: Vec<(usize, String)>,
    pub(in crate::simulate) table: &'a StepTable,
    /// Dwell timers: PLC index, dwell number, when it started (if running).
    pub(in crate::simulate) dwells: Vec<(usize, u16, Option<u64>)>,
    pub(in crate::simulate) spans: Vec<Span>,
    pub(in crate::simulate) trace: Vec<(u64, Vec<f64>)>,
    /// Per piston, the PLC indices of its `+`, `-` and single coil.
    pub(in crate::simulate) coils: Vec<(Option<usize>, Option<usize>, Option<usize>)>,
    /// The I/O of every scan, when recorded for a replay in another engine.
    pub(in crate::simulate) io: Option<io::IoTrace>,
    /// The inputs' changes, when logged for the fault analysis.
    pub(in crate::simulate) input_log: Option<io::InputLog>,
    /// Jump over scans in which nothing can change (see [`Run::pass_quiet_scans`]);
    /// off, the run steps every scan (the reference it is tested against).
    pub(in crate::simulate) event_driven: bool,
    /// The last scan changed nothing: the PLC's state, the inputs it read,
    /// the run's findings and every piston's sensors and rest stayed as
    /// they were.
    pub(in crate::simulate) quiet: bool,
    /// The pistons that moved in the last scan (all of them before the
    /// first).
    pub(in crate::simulate) moving: Vec<usize>,
    /// A hazard is among the problems.
    pub(in crate::simulate) hazard_seen: bool,
    /// A collision is among the problems.
    pub(in crate::simulate) collided: bool,
    /// A step has fired in this run: before the first, the machine stands
    /// at power-up and no step is under way.
    pub(in crate::simulate) fired_any: bool,
    /// The PLC indices of the alarm outputs, and whether one came on.
    pub(in crate::simulate) alarm_bits: Vec<usize>,
    pub(in crate::simulate) alarmed: bool,
    /// Every piston's [`Piston::place`] now, and the combinations reached.
    pub(in crate::simulate) places: Vec<u32>,
    pub(in crate::simulate) visited: Places,
}

impl Run<'_> {
    /// The literals of step `index`'s condition that do not hold now.
    pub(in crate::simulate) fn missing(&self, index: usize) -> Vec<Literal> {
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
    pub(in crate::simulate) fn cycle_complete(&self) -> bool {
        self.missing(0).iter().all(|l| {
            matches!(
                l.signal,
                Signal::Start | Signal::StartMemory | Signal::CycleRequest
            )
        })
    }

    pub(in crate::simulate) fn problem(&mut self, kind: ProblemKind, step: usize, message: String) {
        self.problem_of(kind, step, None, message);
    }

    /// The pistons have reached a new combination of places: recorded, and
    /// checked against the healthy cycle's when given.
    pub(in crate::simulate) fn visit(&mut self) {
        if self.world.settings.record_places && !self.visited.contains(&self.places) {
            self.visited.insert(self.places.clone());
        }
        let Some(known) = &self.world.settings.known_places else {
            return;
        };
        // A run judged by its first hazard is judged by its first collision
        // (`faults::judge`): the later ones need no words.
        if known.contains(&self.places) || (self.world.settings.stop_at_hazard && self.collided) {
            return;
        }
        let combination: Vec<String> = self
            .world
            .pistons
            .iter()
            .zip(&self.places)
            .map(|(p, place)| place_text(p.number, *place))
            .collect();
        let step = self.current_step();
        self.problem(
            ProblemKind::Collision,
            step,
            format!(
                "collision risk: {} ({}), positions the healthy cycle never has together",
                combination.join(", "),
                if self.fired_any {
                    format!("during step {step}")
                } else {
                    "at power-up, before step 1 fires".to_string()
                }
            ),
        );
    }

    /// The run has found a hazard of the sequence and was asked to stop at
    /// the first (the fault analysis: what comes after does not change its
    /// verdict).
    pub(in crate::simulate) fn judged(&self) -> bool {
        self.world.settings.stop_at_hazard && self.hazard_seen
    }

    /// A problem that concerns one actuator.
    pub(in crate::simulate) fn problem_of(
        &mut self,
        kind: ProblemKind,
        step: usize,
        actuator: Option<u32>,
        message: String,
    ) {
        // One report per kind and step is enough to explain what happened.
        if self
            .problems
            .iter()
            .any(|p| p.kind == kind && p.step == step && p.message == message)
        {
            return;
        }
        // A collision is judged with what the sequence does after it.
        self.hazard_seen |= kind.is_hazard() && kind != ProblemKind::Collision;
        self.collided |= kind == ProblemKind::Collision;
        self.problems.push(Problem {
            kind,
            time_ms: self.time_ms,
            step,
            actuator,
            message,
        });
    }

    /// One PLC scan plus one scan period of the plant. Returns the index of the
    /// step that fired, if any.
    pub(in crate::simulate) fn tick(&mut self) -> Option<usize> {
        // Inputs are read from the plant as it stands at the start of the
        // scan; the plant does not move while the program runs.
        // The machine gives the inputs its steps wait for.
        let now = self.time_ms;
        self.world.faults_active = now >= self.world.settings.fault_onset_ms;
        let machine = &mut self.world.machine;
        let waiting = self.pending.len();
        self.pending.retain(|(at, name, value)| {
            if *at <= now {
                machine.insert(*name, *value);
                false
            } else {
                true
            }
        });
        let problems = self.problems.len();
        let mut quiet = self.pending.len() == waiting;
        let world = &self.world;
        let read = |s: Signal| read_input(s, world);
        if let Some(log) = self.input_log.as_mut() {
            log.scan(now, read);
        }
        let recorded_inputs = self.io.as_ref().map(|io| {
            io.signals
                .inputs
                .iter()
                .map(|s| read_input(*s, world))
                .collect::<Vec<bool>>()
        });
        let result = scan(&mut self.plc, &read, self.world.settings.scan_ms as u64);
        if let (Some(io), Some(inputs)) = (self.io.as_mut(), recorded_inputs) {
            let outputs = io
                .signals
                .outputs
                .iter()
                .map(|s| self.plc.bit(*s))
                .collect();
            io.push(io::ScanIo {
                time_ms: now,
                inputs,
                outputs,
                step: self.program.step_in(self.plc.awaited),
            });
        }
        quiet &= !result.changed;
        self.alarmed |= result.changed && self.alarm_bits.iter().any(|&i| self.plc.bit_at(i));
        if let Some(fired) = result.fired {
            self.on_fire(fired, result.waited_at, result.jumped);
        }
        self.track_dwells(now);

        // Outputs to valves, then the plant moves for one scan period. With
        // the outputs as they were, a piston at rest stays at rest: only the
        // moving ones need a look.
        let mut moved_on = false;
        let mut due = std::mem::take(&mut self.moving);
        if result.changed || !self.event_driven {
            due.clear();
            due.extend(0..self.world.pistons.len());
        }
        for &i in &due {
            let number = self.world.pistons[i].number;
            let (plus_at, minus_at, single_at) = self.coils[i];
            let on = |at: Option<usize>| at.is_some_and(|i| self.plc.bit_at(i));
            let plus = on(plus_at) || on(single_at);
            let minus = on(minus_at);
            let piston = &self.world.pistons[i];
            let was_at_rest = piston.at_rest();
            let was_at = piston.s;
            let kind = piston.valve;
            let actuated = self.world.actuate(i, plus, minus);
            if actuated.conflict {
                let step = self.current_step();
                let who = kind.both_on(number);
                self.problem(
                    ProblemKind::CoilConflict,
                    step,
                    format!("{who} y{number}+ and y{number}- in step {step}"),
                );
            }
            if let Some(direction) = actuated.moved {
                self.check_motion(i, direction);
            }
            // The inputs the next scan reads stay those this one read (a
            // sensor's change is a change of place).
            let piston = &self.world.pistons[i];
            quiet &= piston.at_rest() == was_at_rest;
            if piston.s != was_at {
                let place = piston.place(self.world.settings.window);
                if place != self.places[i] {
                    self.places[i] = place;
                    moved_on = true;
                }
            }
        }
        quiet &= !moved_on;
        if moved_on {
            self.visit();
        }
        due.retain(|&i| self.world.pistons[i].velocity() != 0.0);
        self.moving = due;
        self.time_ms += self.world.settings.scan_ms as u64;
        quiet &= !self.update_reached();
        self.quiet = quiet && self.problems.len() == problems;
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

    /// The SFC step the machine is in (symbols' numbering: 0 at rest, k
    /// while table step k's moves run): what every problem reports as its
    /// step, so that the fault table's `step` column means one thing.
    pub(in crate::simulate) fn current_step(&self) -> usize {
        self.program.step_in(self.plc.awaited)
    }

    pub(in crate::simulate) fn on_fire(
        &mut self,
        fired: usize,
        waited_at: usize,
        jumped: Option<usize>,
    ) {
        self.fired_any = true;
        let step = &self.program.steps[fired];
        self.machine_on_fire(fired, waited_at, jumped);
        let operator = self.world.operator;
        // In single step, START asks for the cycle and a STEP_PB press
        // later fires its step 1.
        let stepped = operator.step_mode && operator.step;
        if fired == 0
            && !(self.world.start_pressed || operator.start || operator.continuous || stepped)
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
        // The closing transition starts nothing: the last step's moves are
        // still watched, and a step that then starts before they finish is
        // the hazard (judge the machine, not the sequence).
        if step.kind == crate::program::StepKind::EndOfCycle {
            return;
        }
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

    pub(in crate::simulate) fn check_motion(&mut self, piston: usize, direction: Sign) {
        let p = &self.world.pistons[piston];
        let number = p.number;
        let s = p.s;
        let commanded = self.last_move[piston]
            .as_ref()
            .filter(|a| a.mv.sign == direction)
            .cloned();
        let Some(a) = commanded else {
            if self.jogged(piston, direction) {
                return;
            }
            let step = self.current_step();
            let homing = self.program.signals.memories.contains(&Signal::Homing)
                && (self.plc.bit(Signal::Homing) || read_input(Signal::Reset, &self.world));
            let when = if homing {
                "RESET reads pressed: the program homes the machine".to_string()
            } else if !self.fired_any {
                "at power-up, before step 1 fires".to_string()
            } else {
                format!("during step {step}")
            };
            self.problem(
                ProblemKind::OutsideStep,
                step,
                format!(
                    "unintended motion: C{number} moves {} although no step moves it that way ({when})",
                    if direction == Sign::Plus { "+" } else { "-" }
                ),
            );
            return;
        };
        let (low, high) =
            a.run_through_bounds(&self.world.pistons[piston], self.world.settings.window);
        let beyond = match direction {
            Sign::Plus => s > high,
            Sign::Minus => s < low,
        };
        if beyond && !a.ran_through {
            for m in self.last_move[piston]
                .iter_mut()
                .chain(self.active.iter_mut().filter(|m| m.piston == piston))
            {
                m.ran_through = true;
            }
            self.problem_of(
                ProblemKind::RanThrough,
                a.step,
                Some(number),
                format!(
                    "C{number} ran through {} in step {}",
                    sensor_symbol(&a.mv),
                    a.step
                ),
            );
        }
    }

    /// Marks the moves that have reached their target; returns whether one
    /// just did.
    pub(in crate::simulate) fn update_reached(&mut self) -> bool {
        let window = self.world.settings.window;
        let mut any = false;
        for a in &mut self.active {
            if !a.reached && !a.ran_through && self.world.pistons[a.piston].sensor(a.mv.to, window)
            {
                a.reached = true;
                any = true;
            }
        }
        any
    }

    /// After a quiet scan, passes at once every following scan that is
    /// certain to be quiet too and to start before `until_ms` (when the
    /// caller changes what the operator does or checks the time): the same
    /// PLC state reading the same inputs does the same nothing, so only the
    /// timers and the moving pistons advance. It stops short of the scan in
    /// which a timer runs out, the machine answers, or a piston reaches a
    /// sensor's edge, an end or the point where it would run through its
    /// target; those scans run one by one. The pistons advance scan by scan
    /// so that every position is the very number the stepper computes.
    pub(in crate::simulate) fn pass_quiet_scans(&mut self, until_ms: u64) {
        if !(self.event_driven && self.quiet) {
            return;
        }
        let scan = self.world.settings.scan_ms as u64;
        let window = self.world.settings.window;
        let mut scans = until_ms
            .saturating_sub(self.time_ms)
            .div_ceil(scan)
            .min(self.plc.scans_before_a_timer_ends(scan));
        let onset = (!self.world.faults_active).then_some(self.world.settings.fault_onset_ms);
        if let Some(at) = self.pending.iter().map(|(at, _, _)| *at).chain(onset).min() {
            scans = scans.min(at.saturating_sub(self.time_ms).div_ceil(scan));
        }
        for &i in &self.moving {
            let p = &self.world.pistons[i];
            // Where the run would see the piston run through its target.
            let mark = self.last_move[i]
                .as_ref()
                .filter(|a| !a.ran_through)
                .map(|a| a.run_through_bounds(p, window));
            scans = p.scans_before_an_event(window, mark, scans);
        }
        if scans == 0 {
            return;
        }
        if let Some(io) = self.io.as_mut() {
            io.repeat_last(scans, scan);
        }
        for &i in &self.moving {
            let p = &mut self.world.pistons[i];
            for _ in 0..scans {
                p.advance();
            }
        }
        self.plc.pass_quiet_scans(scans, scan);
        self.time_ms += scans * scan;
        if self.world.settings.record_trace {
            let positions = self.positions();
            record_point(&mut self.trace, self.time_ms, positions);
        }
    }

    /// Every move under way has reached its target sensor and come to rest
    /// (against the end stop, or held by a closed centre).
    pub(in crate::simulate) fn all_moves_ended(&self) -> bool {
        self.active.iter().all(|a| {
            let p = &self.world.pistons[a.piston];
            a.reached && p.at_rest() && p.sensor(a.mv.to, self.world.settings.window)
        })
    }

    pub(in crate::simulate) fn positions(&self) -> Vec<f64> {
        self.world
            .pistons
            .iter()
            .map(Piston::position_units)
            .collect()
    }
}

/// `C2 at x23`, `C2 between x22 and x23`.
fn place_text(actuator: u32, place: u32) -> String {
    let sensor = |position| Signal::Sensor { actuator, position }.symbol();
    if place.is_multiple_of(2) {
        format!("C{actuator} at {}", sensor(place / 2))
    } else {
        format!(
            "C{actuator} between {} and {}",
            sensor(place / 2),
            sensor(place / 2 + 1)
        )
    }
}

pub(in crate::simulate) fn sensor_symbol(m: &Move) -> String {
    Signal::Sensor {
        actuator: m.actuator,
        position: m.to,
    }
    .symbol()
}

pub(in crate::simulate) fn literal_text(l: &Literal) -> String {
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
pub(in crate::simulate) fn record_point(
    trace: &mut Vec<(u64, Vec<f64>)>,
    time_ms: u64,
    positions: Vec<f64>,
) {
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
