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

use crate::address::{Alarm, Allocation, Safety, Signal};
use crate::cell::Sign;
use crate::table::{Move, StepTable};
use crate::timing::Strokes;
use crate::valve::ValveType;

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

/// One step of the sequence.
#[derive(Debug, Clone, PartialEq)]
pub struct ProgramStep {
    /// One-based step number, as in the table.
    pub number: usize,
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
}

impl RungKind {
    /// The label on the PLC PROGRAM sheet.
    pub fn label(self) -> &'static str {
        match self {
            RungKind::MiddleStop => "MIDDLE STOP",
            RungKind::Edge => "EDGE",
            RungKind::Plausibility => "PLAUSIBILITY",
            RungKind::Watchdog => "WATCHDOG",
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

/// Choices that change the generated program.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ProgramOptions {
    /// Switch both coils off when an actuator reaches a middle target. Off only
    /// to show what the published method does without it (it hangs).
    pub middle_stops: bool,
    /// Safety checks carried by the program.
    pub safety: Safety,
}

impl Default for ProgramOptions {
    fn default() -> Self {
        ProgramOptions {
            middle_stops: true,
            safety: Safety::default(),
        }
    }
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
}

impl StepProgram {
    /// The steps that move something (all but a closing END step).
    pub fn move_steps(&self) -> impl Iterator<Item = &ProgramStep> {
        self.steps.iter().filter(|s| !s.moves.is_empty())
    }
}

/// Builds the step program of a checked table.
///
/// Step k fires when every sensor reached at the end of step k−1 is on; step 1
/// fires on START and every home sensor. Each move sets its coil and resets the
/// opposite one. A move to a middle position also sets a stop request, and a
/// rung switches both coils off the moment the middle sensor is reached: a
/// 5/3 valve only holds the piston with both coils off (DESIGN §4, trap 2).
pub fn build(
    table: &StepTable,
    allocation: &Allocation,
    options: ProgramOptions,
    strokes: &Strokes,
) -> StepProgram {
    let is_middle = |actuator: u32, position: u32| {
        table
            .actuator(actuator)
            .is_some_and(|a| position > 0 && position < a.max_position)
    };
    let middle_stops = options.middle_stops;
    let safety = options.safety;
    let halts = safety.plausibility || safety.watchdog;
    let targets = |moves: &[Move]| -> Vec<Literal> {
        moves
            .iter()
            .map(|m| {
                Literal::is(Signal::Sensor {
                    actuator: m.actuator,
                    position: m.to,
                })
            })
            .collect()
    };

    let mut steps = Vec::with_capacity(table.steps.len() + 1);
    for (index, step) in table.steps.iter().enumerate() {
        let mut condition: Vec<Literal> = if index == 0 {
            std::iter::once(Literal::is(Signal::Start))
                .chain(safety.edge.then_some(Literal::not(Signal::StartMemory)))
                .chain(table.actuators.iter().map(|a| {
                    Literal::is(Signal::Sensor {
                        actuator: a.number,
                        position: 0,
                    })
                }))
                .collect()
        } else {
            targets(&table.steps[index - 1].moves)
        };
        if safety.precheck {
            // A target sensor already on before the move starts is a lie.
            condition.extend(
                targets(&step.moves)
                    .into_iter()
                    .map(|l| Literal::not(l.signal)),
            );
        }
        if halts {
            condition.push(Literal::not(Signal::Halt));
        }

        let mut actions = Vec::new();
        for m in &step.moves {
            let pmax = table.actuator(m.actuator).map_or(1, |a| a.max_position);
            if allocation.valves.of(m.actuator, pmax) == ValveType::Mono52 {
                // One coil, held for as long as the cylinder must stay out;
                // switching it off lets the spring retract.
                let coil = Signal::SingleCoil {
                    actuator: m.actuator,
                };
                actions.push(match m.sign {
                    Sign::Plus => Action::Set(coil),
                    Sign::Minus => Action::Reset(coil),
                });
                continue;
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
        if safety.watchdog {
            actions.push(Action::StartTimer(
                Signal::Watchdog,
                watchdog_preset_ms(table, &step.moves, strokes),
            ));
            actions.push(Action::Set(Signal::WatchdogArmed));
        }
        steps.push(ProgramStep {
            number: step.number,
            moves: step.moves.clone(),
            condition,
            actions,
        });
    }
    if safety.watchdog
        && let Some(last) = table.steps.last()
    {
        // The end of the cycle is an event of its own: the watchdog must stop
        // once the last moves have finished, not run on while the machine idles.
        let mut condition = targets(&last.moves);
        condition.push(Literal::not(Signal::Halt));
        steps.push(ProgramStep {
            number: last.number + 1,
            moves: Vec::new(),
            condition,
            actions: vec![
                Action::Reset(Signal::Watchdog),
                Action::Reset(Signal::WatchdogArmed),
            ],
        });
    }

    let mut rungs = Vec::new();
    if middle_stops {
        for memory in &allocation.memories {
            let Signal::StopAt { actuator, position } = memory.signal else {
                continue;
            };
            let sensor = Signal::Sensor { actuator, position };
            rungs.push(Rung {
                kind: RungKind::MiddleStop,
                comment: format!(
                    "middle stop: C{actuator} stops at {} (both coils off, the 5/3 valve holds it)",
                    sensor.symbol()
                ),
                condition: vec![Literal::is(memory.signal), Literal::is(sensor)],
                actions: vec![
                    Action::Reset(Signal::Coil {
                        actuator,
                        sign: Sign::Plus,
                    }),
                    Action::Reset(Signal::Coil {
                        actuator,
                        sign: Sign::Minus,
                    }),
                    Action::Reset(memory.signal),
                ],
            });
        }
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
    StepProgram {
        init,
        steps,
        rungs,
        timers,
    }
}

/// Twice the longest move of the step plus one second, rounded up to 100 ms:
/// generous enough for a sticky valve, short enough to catch a lost sensor.
fn watchdog_preset_ms(table: &StepTable, moves: &[Move], strokes: &Strokes) -> u32 {
    let longest = moves
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
    let preset = 2 * longest + 1000;
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
    use crate::address::{Mnemonic, Target};

    /// The paper's example table (DESIGN §4), as a bare grid.
    pub(crate) fn paper_table() -> StepTable {
        crate::table::from_rows("paper.csv", &crate::template::PAPER_EXAMPLE)
            .expect("paper table is valid")
    }

    #[test]
    fn paper_program_matches_design_section_4() {
        let table = paper_table();
        let alloc = Allocation::new(&table, Target::Festo, Mnemonic::En);
        let program = build(
            &table,
            &alloc,
            ProgramOptions::default(),
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
        let alloc = Allocation::new(&table, Target::Festo, Mnemonic::En);
        let program = build(
            &table,
            &alloc,
            ProgramOptions::default(),
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
            &alloc,
            ProgramOptions {
                middle_stops: false,
                ..ProgramOptions::default()
            },
            &Strokes::default(),
        );
        assert!(plain.rungs.is_empty());
    }
}
