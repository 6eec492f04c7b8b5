//! The step program: the one intermediate model every output language is
//! rendered from and the simulator executes (DESIGN §4).
//!
//! Execution model, per PLC scan:
//! 1. The sequence waits at one step (step 1 after power-up). If that step's
//!    condition (an AND of literals) holds, its actions run in order and the
//!    sequence waits at the next step; after the last step it waits at step 1.
//!    At most one step fires per scan.
//! 2. Then every rung runs: if its condition holds, its actions run. Rungs are
//!    the logic that must act while the sequence waits, such as middle stops.
//!
//! Conditions are conjunctions of (possibly negated) signals and actions are
//! SET / RESET of outputs or memories, which is what every target language has
//! in common. Dwell timers, machine inputs and extra outputs become further
//! signals; one-coil valves simply get different actions.

mod modes;
mod options;
mod signal;
mod signals;

pub use options::{Modes, ProgramOptions, Safety};
pub use signal::{Alarm, Area, Signal};
pub use signals::{Coils, Signals};

use crate::cell::Sign;
use crate::table::{Move, Step, StepTable};
use crate::timing::Strokes;
use crate::valve::Valves;
use modes::{homing_rungs, mode_rungs};

/// A signal in a condition, possibly negated.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Literal {
    pub signal: Signal,
    pub negated: bool,
}

impl Literal {
    pub fn is(signal: Signal) -> Self {
        Literal {
            signal,
            negated: false,
        }
    }

    pub fn not(signal: Signal) -> Self {
        Literal {
            signal,
            negated: true,
        }
    }
}

/// What a step or rung does to an output, memory bit or timer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Action {
    Set(Signal),
    /// Resets a bit; on a timer, stops it.
    Reset(Signal),
    /// (Re)starts a timer with a preset in milliseconds. As a condition a
    /// timer is true while it runs; it stops by itself once the preset elapsed.
    StartTimer(Signal, u32),
}

impl Action {
    pub fn signal(self) -> Signal {
        match self {
            Action::Set(s) | Action::Reset(s) | Action::StartTimer(s, _) => s,
        }
    }

    /// The value written: true for SET and for starting a timer.
    pub fn value(self) -> bool {
        matches!(self, Action::Set(_) | Action::StartTimer(..))
    }

    /// The verb of the paper's notation.
    pub fn verb(self) -> &'static str {
        match self {
            Action::Set(_) => "SET",
            Action::Reset(_) => "RESET",
            Action::StartTimer(..) => "START",
        }
    }
}

/// Where a step of the program comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepKind {
    /// A row of the table.
    Table,
    /// The closing step that notices the end of the cycle (watchdog, modes).
    EndOfCycle,
}

/// One step of the sequence.
#[derive(Debug, Clone, PartialEq)]
pub struct ProgramStep {
    /// One-based step number, as in the table.
    pub number: usize,
    pub kind: StepKind,
    /// What the step does in the table's notation (`C1+1, C2+1; T=2s`), or
    /// `end of cycle`.
    pub title: String,
    /// The table's moves of this step (for comments).
    pub moves: Vec<Move>,
    /// All literals must hold for the step to fire.
    pub condition: Vec<Literal>,
    /// Run in order when the step fires.
    pub actions: Vec<Action>,
}

/// What a rung is for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RungKind {
    MiddleStop,
    Edge,
    Plausibility,
    Watchdog,
    Dwell,
    Mode,
    Homing,
    EmergencyStop,
}

impl RungKind {
    /// The label on the PLC PROGRAM sheet.
    pub fn label(self) -> &'static str {
        match self {
            RungKind::MiddleStop => "MIDDLE STOP",
            RungKind::Edge => "EDGE",
            RungKind::Plausibility => "PLAUSIBILITY",
            RungKind::Watchdog => "WATCHDOG",
            RungKind::Dwell => "DWELL",
            RungKind::Mode => "MODE",
            RungKind::Homing => "HOMING",
            RungKind::EmergencyStop => "EMERGENCY STOP",
        }
    }
}

/// Logic evaluated on every scan after the sequence.
#[derive(Debug, Clone, PartialEq)]
pub struct Rung {
    pub kind: RungKind,
    /// What the rung is for, in words.
    pub comment: String,
    pub condition: Vec<Literal>,
    pub actions: Vec<Action>,
}

/// The complete step program of one table.
#[derive(Debug, Clone, PartialEq)]
pub struct StepProgram {
    /// Run once at power-up, before the first scan.
    pub init: Vec<Action>,
    pub steps: Vec<ProgramStep>,
    pub rungs: Vec<Rung>,
    /// Timers, advanced at the start of every scan.
    pub timers: Vec<Signal>,
    /// Every bit signal the program uses, in address order.
    pub signals: Signals,
}

impl StepProgram {
    /// The steps of the table (all but a closing END step).
    pub fn table_steps(&self) -> impl Iterator<Item = &ProgramStep> {
        self.steps.iter().filter(|s| s.kind == StepKind::Table)
    }
}

/// What must hold for a step of the table to be complete: every move at its
/// target sensor, every wait met, every dwell run out (its arming memory
/// cleared when its timer started, and the timer stopped).
fn completion(step: &Step) -> Vec<Literal> {
    let mut literals: Vec<Literal> = step
        .moves
        .iter()
        .map(|m| {
            Literal::is(Signal::Sensor {
                actuator: m.actuator,
                position: m.to,
            })
        })
        .collect();
    literals.extend(step.waits.iter().map(wait_literal));
    for d in &step.dwells {
        literals.push(Literal::not(Signal::DwellArmed(d.number)));
        literals.push(Literal::not(Signal::Dwell(d.number)));
    }
    literals
}

fn wait_literal(w: &crate::table::Wait) -> Literal {
    Literal {
        signal: Signal::MachineInput(w.input),
        negated: !w.value,
    }
}

/// The actions that move actuator `m` (its coils, and its middle-stop request).
fn move_actions(
    table: &StepTable,
    signals: &Signals,
    middle_stops: bool,
    m: &Move,
    actions: &mut Vec<Action>,
) {
    let is_middle = |actuator: u32, position: u32| {
        table
            .actuator(actuator)
            .is_some_and(|a| a.is_middle(position))
    };
    if signals.valves.contains(&Coils::Single {
        actuator: m.actuator,
    }) {
        // One coil, held for as long as the cylinder must stay out;
        // switching it off lets the spring retract.
        let coil = Signal::SingleCoil {
            actuator: m.actuator,
        };
        actions.push(match m.sign {
            Sign::Plus => Action::Set(coil),
            Sign::Minus => Action::Reset(coil),
        });
        return;
    }
    // Two coils: the move's coil is set and held (it is the valve's
    // only memory across a power dip), the opposite one reset.
    actions.push(Action::Set(Signal::Coil {
        actuator: m.actuator,
        sign: m.sign,
    }));
    actions.push(Action::Reset(Signal::Coil {
        actuator: m.actuator,
        sign: m.sign.opposite(),
    }));
    if middle_stops {
        // A stop request left from reaching the previous middle target
        // must not cut this new move.
        if is_middle(m.actuator, m.from) {
            actions.push(Action::Reset(Signal::StopAt {
                actuator: m.actuator,
                position: m.from,
            }));
        }
        if is_middle(m.actuator, m.to) {
            actions.push(Action::Set(Signal::StopAt {
                actuator: m.actuator,
                position: m.to,
            }));
        }
    }
}

/// Builds the step program of a checked table.
///
/// Step k fires when step k−1 is complete (its moves at their sensors, its
/// waits met, its dwells run out); step 1 fires on START and every home
/// sensor. Each move sets its coil and resets the opposite one. A move to a
/// middle position also sets a stop request, and a rung switches both coils
/// off the moment the middle sensor is reached: a 5/3 valve only holds the
/// piston with both coils off (DESIGN §4, trap 2). A dwell is armed when its
/// step fires and a rung starts its timer once the other items of its branch
/// are done. Operating modes (`options.modes`) add rungs for the buttons and
/// a homing sequence.
pub fn build(
    table: &StepTable,
    options: &ProgramOptions,
    valves: &Valves,
    strokes: &Strokes,
) -> StepProgram {
    let signals = signals::declare(table, options, valves);
    let middle_stops = options.middle_stops;
    let safety = options.safety;
    let modes = &options.modes;
    let halts = safety.halts(modes);
    let homes: Vec<Literal> = table
        .actuators
        .iter()
        .map(|a| {
            Literal::is(Signal::Sensor {
                actuator: a.number,
                position: 0,
            })
        })
        .collect();
    // The end of the cycle is a step of its own when something must notice
    // it (the watchdog, the modes) or when the last step ends on more than
    // its moves: STEP 1 cannot wait for the last step's machine inputs,
    // which nothing gives at power-up.
    let last_waits = table
        .steps
        .last()
        .is_some_and(|s| !s.waits.is_empty() || !s.dwells.is_empty());
    let end_step = safety.watchdog || modes.any() || last_waits;

    let mut steps = Vec::with_capacity(table.steps.len() + 1);
    for (index, step) in table.steps.iter().enumerate() {
        let mut condition: Vec<Literal> = if index == 0 {
            let mut first = if modes.any() {
                // The buttons' rungs turn START and CONTINUOUS into a request.
                vec![Literal::is(Signal::CycleRequest)]
            } else {
                std::iter::once(Literal::is(Signal::Start))
                    .chain(safety.edge.then_some(Literal::not(Signal::StartMemory)))
                    .collect()
            };
            first.extend(homes.iter().copied());
            first
        } else {
            completion(&table.steps[index - 1])
        };
        if safety.precheck {
            // A target sensor already on before the move starts is a lie.
            condition.extend(step.moves.iter().map(|m| {
                Literal::not(Signal::Sensor {
                    actuator: m.actuator,
                    position: m.to,
                })
            }));
        }
        if halts {
            condition.push(Literal::not(Signal::Halt));
        }

        let mut actions = Vec::new();
        for m in &step.moves {
            move_actions(table, &signals, middle_stops, m, &mut actions);
        }
        for switch in &step.switches {
            let output = Signal::MachineOutput(switch.output);
            actions.push(if switch.on {
                Action::Set(output)
            } else {
                Action::Reset(output)
            });
        }
        actions.extend(
            step.dwells
                .iter()
                .map(|d| Action::Set(Signal::DwellArmed(d.number))),
        );
        if index == 0 && modes.any() {
            actions.push(Action::Reset(Signal::CycleRequest));
            actions.push(Action::Set(Signal::Busy));
        }
        if safety.watchdog {
            if step.waits.is_empty() {
                actions.push(Action::StartTimer(
                    Signal::Watchdog,
                    watchdog_preset_ms(table, step, strokes),
                ));
                actions.push(Action::Set(Signal::WatchdogArmed));
            } else {
                // Waiting for a part may take as long as it takes: a step
                // that waits on a machine input is not timed.
                actions.push(Action::Reset(Signal::Watchdog));
                actions.push(Action::Reset(Signal::WatchdogArmed));
            }
        }
        steps.push(ProgramStep {
            number: step.number,
            kind: StepKind::Table,
            title: step.text(),
            moves: step.moves.clone(),
            condition,
            actions,
        });
    }
    if end_step && let Some(last) = table.steps.last() {
        // The end of the cycle is an event of its own: the watchdog must stop
        // once the last moves have finished, not run on while the machine
        // idles, and a new cycle may be asked for only now.
        let mut condition = completion(last);
        if halts {
            condition.push(Literal::not(Signal::Halt));
        }
        let mut actions = Vec::new();
        if safety.watchdog {
            actions.push(Action::Reset(Signal::Watchdog));
            actions.push(Action::Reset(Signal::WatchdogArmed));
        }
        if modes.any() {
            actions.push(Action::Reset(Signal::Busy));
        }
        steps.push(ProgramStep {
            number: last.number + 1,
            kind: StepKind::EndOfCycle,
            title: "end of cycle".to_string(),
            moves: Vec::new(),
            condition,
            actions,
        });
    }

    let mut rungs = Vec::new();
    if middle_stops {
        for &memory in &signals.memories {
            let Signal::StopAt { actuator, position } = memory else {
                continue;
            };
            let sensor = Signal::Sensor { actuator, position };
            rungs.push(Rung {
                kind: RungKind::MiddleStop,
                comment: format!(
                    "middle stop: C{actuator} stops at {} (both coils off, the 5/3 valve holds it)",
                    sensor.symbol()
                ),
                condition: vec![Literal::is(memory), Literal::is(sensor)],
                actions: vec![
                    Action::Reset(Signal::Coil {
                        actuator,
                        sign: Sign::Plus,
                    }),
                    Action::Reset(Signal::Coil {
                        actuator,
                        sign: Sign::Minus,
                    }),
                    Action::Reset(memory),
                ],
            });
        }
    }
    for step in &table.steps {
        for d in &step.dwells {
            // The dwell starts once the other items of its branch are done.
            let mut condition = vec![Literal::is(Signal::DwellArmed(d.number))];
            condition.extend(step.branch_moves(d.branch).map(|m| {
                Literal::is(Signal::Sensor {
                    actuator: m.actuator,
                    position: m.to,
                })
            }));
            condition.extend(
                step.waits
                    .iter()
                    .filter(|w| w.branch == d.branch)
                    .map(wait_literal),
            );
            rungs.push(Rung {
                kind: RungKind::Dwell,
                comment: format!(
                    "dwell {}: STEP {}, branch {} waits {} once its other items are done",
                    d.number,
                    step.number,
                    d.branch + 1,
                    crate::cell::dwell_text(d.ms)
                ),
                condition,
                actions: vec![
                    Action::StartTimer(Signal::Dwell(d.number), d.ms),
                    Action::Reset(Signal::DwellArmed(d.number)),
                ],
            });
        }
    }
    if modes.any() {
        mode_rungs(safety, modes, &homes, &mut rungs);
    }
    let mut init = Vec::new();
    if safety.edge {
        // START already pressed at power-up is no rising edge.
        init.push(Action::Set(Signal::StartMemory));
        rungs.push(Rung {
            kind: RungKind::Edge,
            comment: "edge: remember START for the next scan".to_string(),
            condition: vec![Literal::is(Signal::Start)],
            actions: vec![Action::Set(Signal::StartMemory)],
        });
        rungs.push(Rung {
            kind: RungKind::Edge,
            comment: "edge: START released".to_string(),
            condition: vec![Literal::not(Signal::Start)],
            actions: vec![Action::Reset(Signal::StartMemory)],
        });
    }
    if safety.plausibility {
        for a in &table.actuators {
            for low in 0..a.max_position {
                for high in low + 1..=a.max_position {
                    let sensor = |position| Signal::Sensor {
                        actuator: a.number,
                        position,
                    };
                    rungs.push(Rung {
                        kind: RungKind::Plausibility,
                        comment: format!(
                            "plausibility: C{} cannot be at {} and {} at once",
                            a.number,
                            sensor(low).symbol(),
                            sensor(high).symbol()
                        ),
                        condition: vec![Literal::is(sensor(low)), Literal::is(sensor(high))],
                        actions: vec![
                            Action::Set(Signal::Halt),
                            Action::Set(Signal::Alarm(Alarm::Sensor)),
                        ],
                    });
                }
            }
        }
    }
    let mut timers = Vec::new();
    if safety.watchdog {
        timers.push(Signal::Watchdog);
        rungs.push(Rung {
            kind: RungKind::Watchdog,
            comment: "watchdog: the step did not finish in time".to_string(),
            condition: vec![
                Literal::is(Signal::WatchdogArmed),
                Literal::not(Signal::Watchdog),
            ],
            actions: vec![
                Action::Set(Signal::Halt),
                Action::Set(Signal::Alarm(Alarm::Timeout)),
                Action::Reset(Signal::WatchdogArmed),
            ],
        });
    }
    timers.extend(table.dwells().map(|d| Signal::Dwell(d.number)));
    if modes.any() {
        homing_rungs(table, &signals, &timers, modes, &mut rungs);
    }
    StepProgram {
        init,
        steps,
        rungs,
        timers,
        signals,
    }
}

/// Twice the longest move of the step plus its longest dwell plus one
/// second, rounded up to 100 ms: generous enough for a sticky valve, short
/// enough to catch a lost sensor.
fn watchdog_preset_ms(table: &StepTable, step: &Step, strokes: &Strokes) -> u32 {
    let dwell = step.dwells.iter().map(|d| d.ms as u64).max().unwrap_or(0);
    let longest = step
        .moves
        .iter()
        .map(|m| {
            let pmax = table
                .actuator(m.actuator)
                .map(|a| a.max_position)
                .unwrap_or(1)
                .max(1);
            let stroke = strokes.of(m.actuator);
            let full = match m.sign {
                Sign::Plus => stroke.extend_ms,
                Sign::Minus => stroke.retract_ms,
            };
            (full as u64 * m.from.abs_diff(m.to) as u64).div_ceil(pmax as u64)
        })
        .max()
        .unwrap_or(0);
    let preset = 2 * longest + dwell + 1000;
    (preset.div_ceil(100) * 100).min(u32::MAX as u64) as u32
}

/// `IF a AND b THEN SET y1+ RESET y1-` in the paper's notation, with symbols
/// from `name`. Only actions on outputs are listed when `outputs_only`.
pub fn paper_sentence(
    condition: &[Literal],
    actions: &[Action],
    name: impl Fn(Signal) -> String,
) -> String {
    let mut text = format!("IF {}", condition_text(condition, &name, "AND", "NOT "));
    text.push_str(" THEN");
    for action in actions {
        if *action == Action::Reset(Signal::Sequence) {
            text.push_str(" GOTO STEP 1");
            continue;
        }
        text.push_str(&format!(" {} {}", action.verb(), name(action.signal())));
        if let Action::StartTimer(_, ms) = action {
            text.push_str(&format!(" ({ms} ms)"));
        }
    }
    text
}

/// A conjunction as text, e.g. `x11 AND NOT x12`.
pub fn condition_text(
    condition: &[Literal],
    name: impl Fn(Signal) -> String,
    and: &str,
    not: &str,
) -> String {
    condition
        .iter()
        .map(|l| {
            if l.negated {
                format!("{not}{}", name(l.signal))
            } else {
                name(l.signal)
            }
        })
        .collect::<Vec<_>>()
        .join(&format!(" {and} "))
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The paper's example table (DESIGN §4), as a bare grid.
    pub(crate) fn paper_table() -> StepTable {
        crate::table::from_rows("paper.csv", &crate::template_workbook::PAPER_EXAMPLE)
            .expect("paper table is valid")
    }

    #[test]
    fn paper_program_matches_design_section_4() {
        let table = paper_table();
        let program = build(
            &table,
            &ProgramOptions::default(),
            &Valves::default(),
            &Strokes::default(),
        );
        let lines: Vec<String> = program
            .steps
            .iter()
            .map(|s| {
                let outputs: Vec<Action> = s
                    .actions
                    .iter()
                    .copied()
                    .filter(|a| matches!(a.signal(), Signal::Coil { .. }))
                    .collect();
                paper_sentence(&s.condition, &outputs, Signal::symbol)
            })
            .collect();
        assert_eq!(
            lines,
            [
                "IF START AND x10 AND x20 AND x30 AND x40 THEN SET y1+ RESET y1-",
                "IF x11 THEN SET y2+ RESET y2-",
                "IF x23 THEN SET y2- RESET y2+",
                "IF x21 THEN SET y3+ RESET y3- SET y2+ RESET y2-",
                "IF x32 AND x22 THEN SET y3- RESET y3+ SET y2- RESET y2+",
                "IF x30 AND x21 THEN SET y3+ RESET y3- SET y2+ RESET y2- SET y4+ RESET y4-",
                "IF x31 AND x22 AND x41 THEN SET y3- RESET y3+ SET y2- RESET y2+ SET y4- RESET y4+",
                "IF x30 AND x20 AND x40 THEN SET y1- RESET y1+",
            ]
        );
    }

    #[test]
    fn middle_targets_get_a_stop_rung() {
        let table = paper_table();
        let program = build(
            &table,
            &ProgramOptions::default(),
            &Valves::default(),
            &Strokes::default(),
        );
        // C2 stops at 1 and 2, C3 at 1 (C3's pmax is 2).
        let rungs: Vec<String> = program
            .rungs
            .iter()
            .map(|r| paper_sentence(&r.condition, &r.actions, Signal::symbol))
            .collect();
        assert_eq!(
            rungs,
            [
                "IF m2_1 AND x21 THEN RESET y2+ RESET y2- RESET m2_1",
                "IF m2_2 AND x22 THEN RESET y2+ RESET y2- RESET m2_2",
                "IF m3_1 AND x31 THEN RESET y3+ RESET y3- RESET m3_1",
            ]
        );
        // Step 5 moves C2 from middle 2 to middle 1: it withdraws the old request.
        assert!(
            program.steps[4]
                .actions
                .contains(&Action::Reset(Signal::StopAt {
                    actuator: 2,
                    position: 2
                }))
        );
        let plain = build(
            &table,
            &ProgramOptions {
                middle_stops: false,
                ..ProgramOptions::default()
            },
            &Valves::default(),
            &Strokes::default(),
        );
        assert!(plain.rungs.is_empty());
    }
}
