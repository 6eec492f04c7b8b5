//! What a scan checks: the moves of the step that fired, the motion no
//! step commanded, the run through a target, the combinations of places
//! the healthy cycle never has; and the words of each problem.

use super::{ActiveMove, Run};
use crate::cell::Sign;
use crate::program::{Literal, Signal, StepProgram};
use crate::simulate::plant::Piston;
use crate::simulate::{Problem, ProblemKind};
use crate::table::Move;

impl Run<'_> {
    /// The literals of step `index`'s condition that do not hold now.
    pub(super) fn missing(&self, index: usize) -> Vec<Literal> {
        let Some(step) = self.program.steps.get(index) else {
            return Vec::new();
        };
        step.condition
            .iter()
            .copied()
            .filter(|l| {
                let raw = if l.signal.is_input() {
                    self.read(l.signal)
                } else {
                    self.plc.bit(l.signal)
                };
                raw == l.negated
            })
            .collect()
    }

    /// Whether the cycle has ended: STEP 1 waits for nothing but a start.
    pub(super) fn cycle_complete(&self) -> bool {
        self.missing(0).iter().all(|l| {
            matches!(
                l.signal,
                Signal::Start | Signal::StartMemory | Signal::CycleRequest
            )
        })
    }

    pub(super) fn problem(&mut self, kind: ProblemKind, step: usize, message: String) {
        self.problem_of(kind, step, None, message);
    }

    /// The pistons have reached a new combination of places: recorded, and
    /// checked against the healthy cycle's when given.
    pub(super) fn visit(&mut self) {
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
            .map(|(p, place)| place_text(p, *place))
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
    pub(super) fn judged(&self) -> bool {
        self.world.settings.stop_at_hazard && self.hazard_seen
    }

    /// A problem that concerns one actuator.
    pub(super) fn problem_of(
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

    pub(super) fn on_fire(&mut self, fired: usize, waited_at: usize, jumped: Option<usize>) {
        self.fired_any = true;
        let step = &self.program.steps[fired];
        self.machine_on_fire(fired, waited_at, jumped);
        let operator = self.world.operator;
        // In single step, START asks for the cycle and a STEP_PB press
        // later fires its step 1; a table step fired with no press is the
        // hazard (a shorted STEP_PB reads as one), whatever START did.
        let single = operator.step_mode && self.step_mode_before;
        let stepped = operator.step_mode && (operator.step || self.step_before);
        if single && !stepped && step.kind == crate::program::StepKind::Table {
            self.problem(
                ProblemKind::UnexpectedStep,
                step.number,
                format!(
                    "step {} fired in single step without a STEP_PB press",
                    step.number
                ),
            );
        } else if fired == 0
            && !(self.world.start_pressed
                || operator.start
                || self.start_before
                || operator.continuous
                || stepped)
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
                let (n, sensor) = (a.mv.actuator, sensor_symbol(self.program, &a.mv));
                let kind = self.program.signals.kinds.get(&n);
                kind.and_then(|k| k.unreached_said(n, a.mv.to, &sensor))
                    .unwrap_or_else(|| format!("C{n} had not reached {sensor}"))
            })
            .collect();
        // The closing transition starts nothing: the last step's moves are
        // still watched, and a step that then starts before they finish is
        // the hazard (judge the machine, not the sequence). But a closing
        // transition that fires before they have reached their targets
        // (a home sensor shorted, a drive stopped short by it) makes the
        // program ready for START while the machine is not home: the next
        // press starts step 1 early, whenever the operator gives it.
        if step.kind == crate::program::StepKind::EndOfCycle {
            if let (false, Some(last)) = (unfinished.is_empty(), self.active.first()) {
                let last = last.step;
                self.problem(
                    ProblemKind::Premature,
                    last,
                    format!(
                        "the cycle ended before step {last} finished ({}): the program is ready for START with the machine not home, and the next press starts step 1 early",
                        unfinished.join(", ")
                    ),
                );
            }
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

    pub(super) fn check_motion(&mut self, piston: usize, direction: Sign) {
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
                && (self.plc.bit(Signal::Homing) || self.read(Signal::Reset));
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
                    sensor_symbol(self.program, &a.mv),
                    a.step
                ),
            );
        }
    }

    /// Marks the moves that have reached their target; returns whether one
    /// just did.
    pub(super) fn update_reached(&mut self) -> bool {
        let window = self.world.settings.window;
        let mut any = false;
        for a in &mut self.active {
            if !a.reached && !a.ran_through && self.world.pistons[a.piston].reads(a.mv.to, window) {
                a.reached = true;
                any = true;
            }
        }
        any
    }

    /// Every move under way has reached its target sensor and come to rest
    /// (against the end stop, or held by a closed centre).
    pub(super) fn all_moves_ended(&self) -> bool {
        self.active.iter().all(|a| {
            let p = &self.world.pistons[a.piston];
            a.reached && p.at_rest() && p.reads(a.mv.to, self.world.settings.window)
        })
    }
}

/// `C2 at x23`, `C2 between x22 and x23`.
fn place_text(piston: &Piston, place: u32) -> String {
    let actuator = piston.number;
    // A position its kind reads as another switch off (a gripper released).
    let sensor = |position| {
        let r = piston.valve.reading(position);
        let signal = Signal::Sensor {
            actuator,
            position: r.sensor,
        };
        literal_text(&Literal {
            signal,
            negated: !r.on,
        })
    };
    if let Some(said) = piston.valve.place_said(actuator, place, &sensor) {
        return said;
    }
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

/// What shows that move `m` has reached its target (`x11`; `NOT x31` for
/// a kind that reads a position as another sensor off).
pub(super) fn sensor_symbol(program: &StepProgram, m: &Move) -> String {
    literal_text(&program.signals.at(m.actuator, m.to))
}

pub(super) fn literal_text(l: &Literal) -> String {
    if l.negated {
        format!("NOT {}", l.signal.symbol())
    } else {
        l.signal.symbol()
    }
}
