//! Building the step program from a checked table (DESIGN §4): the steps of
//! the sequence, the end of the cycle, and the rungs every scan runs.

use super::jumps::add_jumps;
use super::modes::{before_estop, edge_rungs, homing_rungs, mode_rungs};
use super::signals::{self, Coils, Signals};
use super::stops::{
    end_run_ons, halt_off_rung, interlock_rung, mark_zones, run_on_rungs, stop_now_rungs,
};
use super::supervision;
use super::{
    Action, Alarm, Literal, ProgramOptions, ProgramStep, Rung, RungKind, Signal, StepKind,
    StepProgram,
};
use crate::actuator::Valves;
use crate::cell::Sign;
use crate::stroke::Strokes;
use crate::table::{Move, Step, StepTable};

/// What must hold for a step of the table to be complete: every move at its
/// target sensor, every wait met, every dwell run out (its arming memory
/// cleared when its timer started, and the timer stopped).
fn completion(signals: &Signals, step: &Step) -> Vec<Literal> {
    let mut literals: Vec<Literal> = step
        .moves
        .iter()
        .map(|m| signals.at(m.actuator, m.to))
        .collect();
    literals.extend(step.waits.iter().map(wait_literal));
    for d in &step.dwells {
        literals.push(Literal::not(Signal::DwellArmed(d.number)));
        literals.push(Literal::not(Signal::Dwell(d.number)));
    }
    literals
}

/// What a step needs besides the step before it being complete, whichever
/// way it fires (after that step, or in place of another by a jump): its
/// target sensors still off (a sensor on before its move starts is a lie),
/// no halt, and every interlock that covers the step closed: the interlock
/// rung halts only later in the scan, and a step fired in the scan its
/// guard opens would start its moves behind the open guard. In single-step
/// mode a table step (not the closing transition, which moves nothing)
/// also needs the step permit a STEP_PB press gives.
fn guards(
    signals: &Signals,
    moves: &[Move],
    number: usize,
    table_step: bool,
    options: &ProgramOptions,
) -> Vec<Literal> {
    let mut literals = Vec::new();
    for interlock in &options.interlocks {
        let covers = interlock
            .steps
            .is_none_or(|(first, last)| (first..=last).contains(&number));
        let literal = Literal::is(Signal::MachineInput(interlock.input));
        if covers && !literals.contains(&literal) {
            literals.push(literal);
        }
    }
    if options.safety.precheck {
        literals.extend(moves.iter().map(|m| signals.at(m.actuator, m.to).negate()));
    }
    if options.halts() {
        literals.push(Literal::not(Signal::Halt));
    }
    if options.modes.step && table_step {
        literals.push(Literal::is(Signal::StepPermit));
    }
    literals
}

fn wait_literal(w: &crate::table::Wait) -> Literal {
    Literal {
        signal: Signal::MachineInput(w.input),
        negated: !w.value,
    }
}

/// The actions that move actuator `m` (its coils, and its stop request at
/// a middle target or a drive's target).
fn move_actions(signals: &Signals, m: &Move, actions: &mut Vec<Action>) {
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
    // A stop request left from reaching the previous target must not cut
    // this new move; the target's own is set (middle stops, drives).
    let stop = |position| Signal::StopAt {
        actuator: m.actuator,
        position,
    };
    if signals.memories.contains(&stop(m.from)) {
        actions.push(Action::Reset(stop(m.from)));
    }
    if signals.memories.contains(&stop(m.to)) {
        actions.push(Action::Set(stop(m.to)));
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
    let mut signals = signals::declare(table, options, valves);
    let safety = options.safety;
    let modes = &options.modes;
    let homes: Vec<Literal> = table
        .actuators
        .iter()
        .map(|a| signals.at(a.number, 0))
        .collect();
    // Ready for a cycle: every actuator home and every start permissive on.
    let ready: Vec<Literal> = homes
        .iter()
        .copied()
        .chain(
            options
                .permissive
                .iter()
                .map(|n| Literal::is(Signal::MachineInput(*n))),
        )
        .collect();
    let mut steps = sequence_steps(table, options, &signals, &ready, strokes);
    steps.extend(end_of_cycle(table, options, &signals));
    let criteria = if safety.criteria {
        supervision::criteria(&steps, &signals)
    } else {
        Vec::new()
    };
    supervision::declare(&criteria, &mut signals);

    let mut rungs = Vec::new();
    rungs.extend(middle_stop_rungs(&signals));
    rungs.extend(dwell_rungs(table, &signals));
    if modes.any() {
        mode_rungs(
            safety,
            modes,
            options.halts(),
            options.stops_now(),
            &ready,
            &mut rungs,
        );
    }
    let mut init = Vec::new();
    if safety.edge {
        // START already pressed at power-up is no rising edge.
        init.push(Action::Set(Signal::StartMemory));
        rungs.extend(edge_rungs(
            RungKind::Edge,
            Signal::Start,
            Signal::StartMemory,
        ));
    }
    if safety.plausibility {
        rungs.extend(plausibility_rungs(table, &signals));
    }
    let mut timers = Vec::new();
    if safety.watchdog {
        timers.push(Signal::Watchdog);
        rungs.push(watchdog_rung());
        rungs.extend(supervision::rungs(&criteria));
    }
    timers.extend(table.dwells().map(|d| Signal::Dwell(d.number)));
    let run_ons = options.run_ons();
    timers.extend((1..=run_ons.len()).map(|n| Signal::RunOn(n as u16)));
    rungs.extend(interlock_rung(options));
    mark_zones(options, &mut steps);
    if options.halts() {
        rungs.extend(halt_off_rung(&signals, &options.halt));
    }
    if options.stops_now() {
        stop_now_rungs(&signals, &timers, &options.halt, &mut rungs);
    }
    rungs.extend(run_on_rungs(&run_ons));
    end_run_ons(&run_ons, &mut steps);
    // Last: a jump fires its target's actions as they finally are.
    add_jumps(
        table,
        options,
        &mut steps,
        |index| completion(&signals, &table.steps[index]),
        |target| {
            let table_step = target.kind == StepKind::Table;
            guards(&signals, &target.moves, target.number, table_step, options)
        },
    );
    // After the jumps, which copy their target's actions: each transition
    // moves the awaited criteria from where it leaves to where it leads.
    supervision::track(&mut steps, &criteria);
    if modes.any() {
        homing_rungs(
            table, &signals, &timers, options, &run_ons, strokes, &mut rungs,
        );
    }
    if modes.manual {
        before_estop(&mut rungs, super::manual::rungs(&signals, &timers, options));
    }
    pressurised_centres_held_home(table, &signals, &mut rungs);
    if modes.reset {
        super::modes::reset_edge(&mut init, &mut rungs);
    }
    StepProgram {
        criteria,
        init,
        steps,
        rungs,
        timers,
        signals,
        halt: options.halt.clone(),
        permissive: options.held_inputs(),
        run_ons,
    }
}

/// The steps of the table: each fires when the one before is complete.
fn sequence_steps(
    table: &StepTable,
    options: &ProgramOptions,
    signals: &Signals,
    homes: &[Literal],
    strokes: &Strokes,
) -> Vec<ProgramStep> {
    let safety = options.safety;
    let modes = &options.modes;
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
            completion(signals, &table.steps[index - 1])
        };
        condition.extend(guards(signals, &step.moves, step.number, true, options));

        let mut actions = Vec::new();
        for m in &step.moves {
            move_actions(signals, m, &mut actions);
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
            // A supervision time given for a step that waits times the wait.
            if step.waits.is_empty() || options.supervision.contains_key(&step.number) {
                actions.push(Action::StartTimer(
                    Signal::Watchdog,
                    supervision::preset_ms(table, step, strokes, &options.supervision),
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
            jumps: Vec::new(),
        });
    }
    steps
}

/// The closing transition: once the last step is done the sequence is
/// back in the initial step 0, as an SFC's last transition leads back to
/// its initial step. Every program has it, so that the step the program
/// shows is 0 only at rest and the last step's number while its moves
/// run; it also stops the watchdog, ends `busy` for the modes, and waits
/// for the last step's inputs and dwells (STEP 1 cannot wait for those,
/// which nothing gives at power-up).
fn end_of_cycle(
    table: &StepTable,
    options: &ProgramOptions,
    signals: &Signals,
) -> Option<ProgramStep> {
    let safety = options.safety;
    let modes = &options.modes;
    let last = table.steps.last()?;
    // The end of the cycle is an event of its own: the watchdog must stop
    // once the last moves have finished, not run on while the machine
    // idles, and a new cycle may be asked for only now.
    let mut condition = completion(signals, last);
    condition.extend(guards(signals, &[], last.number + 1, false, options));
    let mut actions = Vec::new();
    if safety.watchdog {
        actions.push(Action::Reset(Signal::Watchdog));
        actions.push(Action::Reset(Signal::WatchdogArmed));
    }
    if modes.any() {
        actions.push(Action::Reset(Signal::Busy));
    }
    Some(ProgramStep {
        number: last.number + 1,
        kind: StepKind::EndOfCycle,
        title: "end of cycle".to_string(),
        moves: Vec::new(),
        condition,
        actions,
        jumps: Vec::new(),
    })
}

/// Both coils off the moment a middle target is reached: a 5/3 valve only
/// holds the piston with both coils off (DESIGN §4, trap 2).
fn middle_stop_rungs(signals: &Signals) -> Vec<Rung> {
    let mut rungs = Vec::new();
    for &memory in &signals.memories {
        let Signal::StopAt { actuator, position } = memory else {
            continue;
        };
        let sensor = signals.at(actuator, position);
        // Every stop request is of an actuator of the table, so of a kind.
        let Some(kind) = signals.kinds.get(&actuator) else {
            continue;
        };
        let comment = kind.stop_comment(actuator, &sensor.signal.symbol());
        rungs.push(Rung {
            kind: RungKind::MiddleStop,
            comment,
            condition: vec![Literal::is(memory), sensor],
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
    rungs
}

/// Each dwell starts its timer once the other items of its branch are done.
fn dwell_rungs(table: &StepTable, signals: &Signals) -> Vec<Rung> {
    let mut rungs = Vec::new();
    for step in &table.steps {
        for d in &step.dwells {
            // The dwell starts once the other items of its branch are done.
            let mut condition = vec![Literal::is(Signal::DwellArmed(d.number))];
            condition.extend(
                step.branch_moves(d.branch)
                    .map(|m| signals.at(m.actuator, m.to)),
            );
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
    rungs
}

/// Two sensors of one actuator on at once halt the sequence (of the
/// sensors its kind has).
fn plausibility_rungs(table: &StepTable, signals: &Signals) -> Vec<Rung> {
    let mut rungs = Vec::new();
    for a in &table.actuators {
        let sensors: Vec<Signal> = signals.sensors_of(a.number).collect();
        for (i, &low) in sensors.iter().enumerate() {
            for &high in &sensors[i + 1..] {
                rungs.push(Rung {
                    kind: RungKind::Plausibility,
                    comment: format!(
                        "plausibility: C{} cannot be at {} and {} at once",
                        a.number,
                        low.symbol(),
                        high.symbol()
                    ),
                    condition: vec![Literal::is(low), Literal::is(high)],
                    actions: vec![
                        Action::Set(Signal::Halt),
                        Action::Set(Signal::Alarm(Alarm::Sensor)),
                    ],
                });
            }
        }
    }
    rungs
}

/// A 5/3 pressurised-centre valve with both coils off pushes on both
/// sides of the piston, which creeps out (the larger area wins): at home
/// with its `+` coil off, its `-` coil holds it there (at power-up, after
/// manual's jogs, wherever the sequence leaves it home). Before the
/// emergency stop's rung, which stays the last word; a middle stop, away
/// from home, is left as its rung left it.
fn pressurised_centres_held_home(table: &StepTable, signals: &Signals, rungs: &mut Vec<Rung>) {
    let held = table.actuators.iter().filter(|a| {
        signals.kinds.get(&a.number) == Some(&crate::actuator::ActuatorKind::Pressure53)
    });
    let coil = |actuator, sign| Signal::Coil { actuator, sign };
    let hold: Vec<Rung> = held
        .map(|a| Rung {
            kind: RungKind::HoldHome,
            comment: format!(
                "C{}: a pressurised centre creeps out with both coils off; its - coil holds it home",
                a.number
            ),
            condition: vec![
                Literal::not(coil(a.number, Sign::Plus)),
                signals.at(a.number, 0),
            ],
            actions: vec![Action::Set(coil(a.number, Sign::Minus))],
        })
        .collect();
    before_estop(rungs, hold);
}

/// A step (or homing stage) that does not finish in time raises the
/// alarm and halts. Not in a machine halted already (an EMERGENCY STOP,
/// an interlock): a stopped step is not one that ran out of time, and
/// the criteria analysis would blame a sensor for it.
fn watchdog_rung() -> Rung {
    Rung {
        kind: RungKind::Watchdog,
        comment: "watchdog: the step did not finish in time".to_string(),
        condition: vec![
            Literal::is(Signal::WatchdogArmed),
            Literal::not(Signal::Watchdog),
            Literal::not(Signal::Halt),
        ],
        // Once: the halt it sets holds the rung off until RESET, which
        // disarms the watchdog (one coil of its own contacts per rung, so
        // that Ladder draws it).
        actions: vec![
            Action::Set(Signal::Halt),
            Action::Set(Signal::Alarm(Alarm::Timeout)),
        ],
    }
}
