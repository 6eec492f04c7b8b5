//! The operating modes' logic (`--modes`): START, CONTINUOUS and STOP turn
//! into a cycle request; RESET homes the actuators stage by stage; the
//! EMERGENCY STOP switches everything off. All of it is rungs of the one
//! step program, so every language and the simulator get it alike.

use super::stops::all_off_but;
use super::{Action, Coils, Literal, Modes, Rung, RungKind, Safety, Signal, Signals};
use crate::cell::Sign;
use crate::table::StepTable;

/// START, CONTINUOUS and STOP turn into a cycle request; STEP 1 consumes it.
pub(super) fn mode_rungs(
    safety: Safety,
    modes: &Modes,
    halts: bool,
    stops_now: bool,
    homes: &[Literal],
    rungs: &mut Vec<Rung>,
) {
    // Ready for a new cycle: none under way, no halt, not homing, all home.
    let mut ready = vec![Literal::not(Signal::Busy)];
    if halts {
        ready.push(Literal::not(Signal::Halt));
    }
    if modes.reset {
        ready.push(Literal::not(Signal::Homing));
    }
    ready.extend(homes.iter().copied());

    rungs.extend(forget_request(modes));
    let mut start = vec![Literal::is(Signal::Start)];
    if safety.edge {
        start.push(Literal::not(Signal::StartMemory));
    }
    if modes.stop {
        start.push(Literal::is(Signal::Stop));
    }
    start.extend(ready.iter().copied());
    let mut start_actions = vec![Action::Set(Signal::CycleRequest)];
    if modes.continuous {
        start_actions.push(Action::Set(Signal::AutoRun));
    }
    rungs.push(Rung {
        kind: RungKind::Mode,
        comment: "START: one cycle (machine home and ready)".to_string(),
        condition: start,
        actions: start_actions,
    });
    if modes.continuous {
        let mut again = vec![
            Literal::is(Signal::Continuous),
            Literal::is(Signal::AutoRun),
        ];
        again.extend(ready.iter().copied());
        rungs.push(Rung {
            kind: RungKind::Mode,
            comment: "CONTINUOUS: the next cycle once this one has ended".to_string(),
            condition: again,
            actions: vec![Action::Set(Signal::CycleRequest)],
        });
        rungs.push(Rung {
            kind: RungKind::Mode,
            comment: "CONTINUOUS off: no further cycles".to_string(),
            condition: vec![Literal::not(Signal::Continuous)],
            actions: vec![Action::Reset(Signal::AutoRun)],
        });
        // A start permissive (air, a closed guard: the machine inputs among
        // `homes`) that goes off ends continuous operation, as a START it
        // refuses is forgotten: its return must not start a cycle.
        for permissive in homes
            .iter()
            .filter(|l| matches!(l.signal, Signal::MachineInput(_)))
        {
            rungs.push(Rung {
                kind: RungKind::Mode,
                comment: format!(
                    "{} off: no further cycles (START again once it is back)",
                    permissive.signal.symbol()
                ),
                condition: vec![Literal::not(permissive.signal)],
                actions: vec![Action::Reset(Signal::AutoRun)],
            });
        }
    }
    if modes.stop && !stops_now {
        let mut actions = vec![Action::Reset(Signal::CycleRequest)];
        if modes.continuous {
            actions.push(Action::Reset(Signal::AutoRun));
        }
        rungs.push(Rung {
            kind: RungKind::Mode,
            comment: "STOP (normally closed): finish this cycle, start no other".to_string(),
            condition: vec![Literal::not(Signal::Stop)],
            actions,
        });
    }
    if modes.step {
        rungs.extend(step_rungs());
    }
}

/// A cycle request step 1 did not take in the scan it could is forgotten
/// (the START rung after these sets it again while START is held): a START
/// refused (a precheck, an interlock) must not start the cycle when the
/// fault is cleared minutes later. In single step the request waits for
/// the STEP_PB press that may fire step 1, and is forgotten once a press
/// did not, or as single step is switched off.
fn forget_request(modes: &Modes) -> Vec<Rung> {
    let rung = |comment: &str, extra: Option<Literal>| Rung {
        kind: RungKind::Mode,
        comment: comment.to_string(),
        condition: std::iter::once(Literal::is(Signal::CycleRequest))
            .chain(extra)
            .collect(),
        actions: vec![Action::Reset(Signal::CycleRequest)],
    };
    if !modes.step {
        return vec![rung(
            "a cycle request step 1 did not take is forgotten: START must be pressed again",
            None,
        )];
    }
    vec![
        rung(
            "a cycle request step 1 did not take with its permit is forgotten: START must be pressed again",
            Some(Literal::is(Signal::StepPermit)),
        ),
        rung(
            "STEP_MODE off: a request left from single step is forgotten, START must be pressed again",
            Some(Literal::not(Signal::StepMode)),
        ),
    ]
}

/// Single-step mode: the permit every table step's transition needs. In
/// automatic (STEP_MODE off) it is always on; in single-step it is on for
/// the one scan after STEP_PB's rising edge, so that a press fires at most
/// one step and only one whose conditions hold at that scan (S7-GRAPH's
/// transition with T_PUSH). The rungs run after the sequence: the permit
/// they set is read by the next scan's sequence.
fn step_rungs() -> Vec<Rung> {
    let rung = |comment: &str, condition: Vec<Literal>, action: Action| Rung {
        kind: RungKind::Mode,
        comment: comment.to_string(),
        condition,
        actions: vec![action],
    };
    [
        rung(
            "STEP_MODE off: automatic, every step may fire",
            vec![Literal::not(Signal::StepMode)],
            Action::Set(Signal::StepPermit),
        ),
        rung(
            "STEP_MODE on: single step, a step fires only on a STEP_PB press",
            vec![Literal::is(Signal::StepMode)],
            Action::Reset(Signal::StepPermit),
        ),
        rung(
            "STEP_PB pressed in single step: the next scan may fire one step",
            vec![
                Literal::is(Signal::StepMode),
                Literal::is(Signal::StepButton),
                Literal::not(Signal::StepMemory),
            ],
            Action::Set(Signal::StepPermit),
        ),
    ]
    .into_iter()
    .chain(edge_rungs(
        RungKind::Mode,
        Signal::StepButton,
        Signal::StepMemory,
    ))
    .collect()
}

/// RESET is remembered for the next scan, so that it acts only on its
/// rising edge: after every rung that reads it, before the emergency
/// stop's. RESET already pressed at power-up is no press.
pub(super) fn reset_edge(init: &mut Vec<Action>, rungs: &mut Vec<Rung>) {
    init.push(Action::Set(Signal::ResetMemory));
    let edge = edge_rungs(RungKind::Edge, Signal::Reset, Signal::ResetMemory);
    before_estop(rungs, edge);
}

/// `new` rungs placed before the emergency stop's rung (at the end without
/// one), which stays the last word on every coil.
pub(super) fn before_estop(rungs: &mut Vec<Rung>, new: impl IntoIterator<Item = Rung>) {
    let at = rungs
        .iter()
        .position(|r| r.kind == RungKind::EmergencyStop)
        .unwrap_or(rungs.len());
    rungs.splice(at..at, new);
}

/// `button` remembered for the next scan in `memory`, so that a rung that
/// also asks `NOT memory` sees only its rising edge (START under `--safety
/// edge`, STEP_PB, RESET_PB).
pub(super) fn edge_rungs(kind: RungKind, button: Signal, memory: Signal) -> [Rung; 2] {
    let name = button.symbol();
    [
        Rung {
            kind,
            comment: format!("edge: remember {name} for the next scan"),
            condition: vec![Literal::is(button)],
            actions: vec![Action::Set(memory)],
        },
        Rung {
            kind,
            comment: format!("edge: {name} released"),
            condition: vec![Literal::not(button)],
            actions: vec![Action::Reset(memory)],
        },
    ]
}

/// RESET, the homing stages and the emergency stop, which comes last so
/// that nothing after it can switch a coil back on in the same scan.
pub(super) fn homing_rungs(
    table: &StepTable,
    signals: &Signals,
    timers: &[Signal],
    options: &super::ProgramOptions,
    run_ons: &[super::RunOn],
    strokes: &crate::stroke::Strokes,
    rungs: &mut Vec<Rung>,
) {
    let modes = &options.modes;
    let outputs: Vec<Signal> = signals.driven().collect();
    if modes.reset {
        let stages = modes.home_stages(table).unwrap_or_default();
        // With the watchdog each stage is supervised as a step is.
        let presets: Vec<u32> = if options.safety.watchdog {
            stages
                .iter()
                .map(|stage| super::supervision::homing_preset_ms(stage, strokes))
                .collect()
        } else {
            Vec::new()
        };
        let homing = Homing {
            stages: &stages,
            presets: &presets,
        };
        let reset = reset_rung(signals, timers, options, &outputs, &homing);
        let kept = super::stops::run_ons_through_reset(run_ons, &reset.condition);
        rungs.push(reset);
        rungs.extend(kept);
        home_stage_rungs(signals, options, &homing, rungs);
    }
    if modes.estop {
        rungs.push(estop_rung(signals, options, run_ons, &outputs));
    }
}

/// RESET pressed where it may act: on its rising edge (a RESET held, or
/// jammed, as the EMERGENCY STOP is released starts nothing: EN 60204-1
/// wants a deliberate reset), not under the EMERGENCY STOP, and (homing
/// moves every actuator) not behind an open guard, one guarding a range
/// of steps too: homing has no step to exempt.
pub(super) fn reset_pressed(options: &super::ProgramOptions) -> Vec<Literal> {
    let mut condition = vec![
        Literal::is(Signal::Reset),
        Literal::not(Signal::ResetMemory),
    ];
    if options.modes.estop {
        condition.push(Literal::is(Signal::EStop));
    }
    // A STOP that acts at once, held: its rung comes first in the scan, and
    // homing would drive the coils for the scan RESET is read in.
    if options.stops_now() {
        condition.push(Literal::is(Signal::Stop));
    }
    condition.extend(
        options
            .interlocks
            .iter()
            .map(|i| Literal::is(Signal::MachineInput(i.input))),
    );
    condition
}

/// The homing stages (actuator numbers), and with the watchdog each
/// stage's supervision time (else none).
struct Homing<'a> {
    stages: &'a [Vec<u32>],
    presets: &'a [u32],
}

impl Homing<'_> {
    /// Stage `i` (0-based) supervised: the watchdog restarted with its
    /// preset and armed.
    fn supervise(&self, i: usize) -> Vec<Action> {
        self.presets.get(i).map_or_else(Vec::new, |ms| {
            vec![
                Action::StartTimer(Signal::Watchdog, *ms),
                Action::Set(Signal::WatchdogArmed),
            ]
        })
    }
}

/// RESET abandons the cycle: every output and the cycle's memories off,
/// the first of `stages` homing stages on. The one coil of a spring-return
/// valve homed in a later stage stays as it is until its stage: cutting it
/// is that actuator's move home, out of the order (a clamp would open
/// while the tool is still down).
fn reset_rung(
    signals: &Signals,
    timers: &[Signal],
    options: &super::ProgramOptions,
    outputs: &[Signal],
    homing: &Homing,
) -> Rung {
    let stages = homing.stages;
    let later: Vec<u32> = stages.iter().skip(1).flatten().copied().collect();
    let waits_for_its_stage =
        |s: &Signal| matches!(s, Signal::SingleCoil { actuator } if later.contains(actuator));
    let memories = &signals.memories;
    let mut condition = reset_pressed(options);
    // In manual RESET homes nothing (its own rung: `manual::reset_rung`).
    if options.modes.manual {
        condition.push(Literal::not(Signal::ManualMode));
    }
    let mut actions: Vec<Action> = outputs
        .iter()
        .filter(|s| !waits_for_its_stage(s))
        .map(|s| Action::Reset(*s))
        .collect();
    // Forget the interrupted cycle: requests, stops, dwells, alarms.
    actions.extend(
        memories
            .iter()
            .filter(|m| {
                matches!(
                    m,
                    Signal::Halt
                        | Signal::CycleRequest
                        | Signal::Busy
                        | Signal::AutoRun
                        | Signal::StopAt { .. }
                        | Signal::DwellArmed(_)
                        | Signal::InterlockZone(_)
                        | Signal::WatchdogArmed
                        | Signal::Awaited(_)
                )
            })
            .map(|m| Action::Reset(*m)),
    );
    actions.extend(signals.alarms().map(Action::Reset));
    let supervised = homing.supervise(0);
    // A run-on keeps its timer: the fan cooling a heater runs its time
    // out through RESET (`stops::run_ons_through_reset`).
    actions.extend(
        timers
            .iter()
            .filter(|t| supervised.is_empty() || **t != Signal::Watchdog)
            .filter(|t| !matches!(t, Signal::RunOn(_)))
            .map(|t| Action::Reset(*t)),
    );
    actions.extend(supervised);
    actions.push(Action::Set(Signal::Homing));
    for n in 1..=stages.len() {
        let stage = Signal::HomeStage(n as u16);
        actions.push(if n == 1 {
            Action::Set(stage)
        } else {
            Action::Reset(stage)
        });
    }
    actions.push(Action::Reset(Signal::Sequence));
    Rung {
        kind: RungKind::Homing,
        comment: "RESET: abandon the cycle, every output off, home stage by stage".to_string(),
        condition,
        actions,
    }
}

/// Each homing stage drives its actuators home (unless halted) and, once
/// they all are, hands on to the next stage or ends the homing.
fn home_stage_rungs(
    signals: &Signals,
    options: &super::ProgramOptions,
    homing: &Homing,
    rungs: &mut Vec<Rung>,
) {
    let stages = homing.stages;
    // A machine without actuators (an oven) has nothing to home: the
    // homing RESET started ends the next scan, or START would wait forever.
    if stages.is_empty() {
        rungs.push(Rung {
            kind: RungKind::Homing,
            comment: "homing done: no actuator to home, the machine is ready".to_string(),
            condition: vec![Literal::is(Signal::Homing)],
            actions: vec![Action::Reset(Signal::Homing)],
        });
    }
    for (i, stage) in stages.iter().enumerate() {
        let memory = Signal::HomeStage(i as u16 + 1);
        let names: Vec<String> = stage.iter().map(|a| format!("C{a}")).collect();
        let mut drive = Vec::new();
        let mut home = vec![Literal::is(memory)];
        for &actuator in stage {
            if signals.valves.contains(&Coils::Single { actuator }) {
                drive.push(Action::Reset(Signal::SingleCoil { actuator }));
            } else {
                drive.push(Action::Set(Signal::Coil {
                    actuator,
                    sign: Sign::Minus,
                }));
                drive.push(Action::Reset(Signal::Coil {
                    actuator,
                    sign: Sign::Plus,
                }));
            }
            home.push(signals.at(actuator, 0));
        }
        // A halt while homing (an interlock opening, a plausibility
        // fault) stops driving: the halt's own rungs then hold or
        // de-energise the outputs as for any halt.
        let mut condition = vec![Literal::is(memory)];
        if options.halts() {
            condition.push(Literal::not(Signal::Halt));
        }
        // Nor in manual, whose rung ends the homing later in this scan:
        // a coil a halt row holds would keep what this rung set.
        if options.modes.manual {
            condition.push(Literal::not(Signal::ManualMode));
        }
        rungs.push(Rung {
            kind: RungKind::Homing,
            comment: format!("homing stage {}: {} home", i + 1, names.join(", ")),
            condition,
            actions: drive,
        });
        // A drive runs as long as its output is on: one at home is cut
        // there, not when the whole stage is (its end stop is no brake).
        if stage.len() > 1 {
            rungs.extend(
                stage
                    .iter()
                    .filter(|&&a| signals.drives(a))
                    .map(|&actuator| Rung {
                        kind: RungKind::Homing,
                        comment: format!("homing stage {}: C{actuator} home, its drive cut", i + 1),
                        condition: vec![Literal::is(memory), signals.at(actuator, 0)],
                        actions: vec![Action::Reset(Signal::Coil {
                            actuator,
                            sign: Sign::Minus,
                        })],
                    }),
            );
        }
        rungs.extend(halted_stage(signals, options, memory, stage, &names));
        let mut done = vec![Action::Reset(memory)];
        // A drive runs as long as its output is on: cut it at home.
        done.extend(
            stage
                .iter()
                .filter(|&&a| signals.drives(a))
                .map(|&actuator| {
                    Action::Reset(Signal::Coil {
                        actuator,
                        sign: Sign::Minus,
                    })
                }),
        );
        if i + 1 < stages.len() {
            done.push(Action::Set(Signal::HomeStage(i as u16 + 2)));
            done.extend(homing.supervise(i + 1));
        } else {
            done.push(Action::Reset(Signal::Homing));
            if !homing.presets.is_empty() {
                done.extend([
                    Action::Reset(Signal::Watchdog),
                    Action::Reset(Signal::WatchdogArmed),
                ]);
            }
        }
        rungs.push(Rung {
            kind: RungKind::Homing,
            comment: format!(
                "homing stage {} done: {}",
                i + 1,
                if i + 1 < stages.len() {
                    "next stage"
                } else {
                    "the machine is home and ready"
                }
            ),
            condition: home,
            actions: done,
        });
    }
}

/// A halt while a stage homes (an interlock opening, a plausibility
/// fault) stops its drives: the `-` coils the stage switched on go off (a
/// closed-centre valve then holds the piston, a drive stops), but for a
/// coil the halt policy names (`hold-safe`, `on halt`: its own rungs act).
/// A one-coil valve homes with its coil off already. Without
/// it the coil stayed latched and the piston drove home behind an open
/// guard. RESET, pressed again once the halt is cleared, homes anew.
fn halted_stage(
    signals: &Signals,
    options: &super::ProgramOptions,
    memory: Signal,
    stage: &[u32],
    names: &[String],
) -> Option<Rung> {
    if !options.halts() {
        return None;
    }
    let halt = &options.halt;
    let held = |s: &Signal| halt.hold_safe.contains(s) || halt.on_halt.contains_key(s);
    let actions: Vec<Action> = stage
        .iter()
        .filter(|&&actuator| !signals.valves.contains(&Coils::Single { actuator }))
        .map(|&actuator| Signal::Coil {
            actuator,
            sign: Sign::Minus,
        })
        .filter(|coil| !held(coil))
        .map(Action::Reset)
        .collect();
    (!actions.is_empty()).then(|| Rung {
        kind: RungKind::Homing,
        comment: format!("homing halted: the drives of {} stop", names.join(", ")),
        condition: vec![Literal::is(memory), Literal::is(Signal::Halt)],
        actions,
    })
}

/// The EMERGENCY STOP (normally closed): every output off but those held
/// or run on, the halt set, the cycle and the homing forgotten.
fn estop_rung(
    signals: &Signals,
    options: &super::ProgramOptions,
    run_ons: &[super::RunOn],
    outputs: &[Signal],
) -> Rung {
    let hold_on_estop = &options.halt.hold_on_estop;
    let memories = &signals.memories;
    let runs_on = |s: &Signal| {
        run_ons
            .iter()
            .any(|r| r.event == super::StopEvent::EStop && r.output == *s)
    };
    let mut held: Vec<String> = outputs
        .iter()
        .filter(|s| hold_on_estop.contains(s))
        .map(|s| format!("{} (hold on estop)", s.symbol()))
        .collect();
    held.extend(
        run_ons
            .iter()
            .filter(|r| r.event == super::StopEvent::EStop)
            .map(|r| {
                format!(
                    "{} (off after {})",
                    r.output.symbol(),
                    crate::cell::duration_text(r.ms)
                )
            }),
    );
    let mut actions: Vec<Action> = outputs
        .iter()
        .filter(|s| !hold_on_estop.contains(s) && !runs_on(s))
        .map(|s| Action::Reset(*s))
        .collect();
    actions.push(Action::Set(Signal::Halt));
    actions.extend(
        memories
            .iter()
            .filter(|m| {
                matches!(
                    m,
                    Signal::CycleRequest
                        | Signal::Busy
                        | Signal::AutoRun
                        | Signal::Homing
                        | Signal::HomeStage(_)
                )
            })
            .map(|m| Action::Reset(*m)),
    );
    Rung {
        kind: RungKind::EmergencyStop,
        comment: format!(
            "EMERGENCY STOP (normally closed): {}, START blocked until RESET",
            all_off_but(&held)
        ),
        condition: vec![Literal::not(Signal::EStop)],
        actions,
    }
}

#[cfg(test)]
mod tests {
    use super::super::{Literal, ProgramOptions, Signal, StepKind, build};
    use crate::actuator::Valves;
    use crate::stroke::Strokes;

    /// In single step every way into a table step needs the permit, a
    /// jump too; the way back to step 0 (the closing transition, or a jump
    /// to the end) moves nothing and needs none.
    #[test]
    fn every_table_step_and_jump_into_one_needs_the_step_permit() {
        let rows: [[&str; 1]; 6] = [
            ["C1+1"],
            ["C1-0; J:5 if I:reject; J:end if I:abort"],
            ["C2+1"],
            ["C2-0"],
            ["C3+1"],
            ["C3-0"],
        ];
        let table = crate::table::from_rows("jumps.csv", &rows).expect("valid table");
        let options = ProgramOptions {
            modes: super::super::Modes::parse("step").unwrap(),
            ..ProgramOptions::default()
        };
        let program = build(&table, &options, &Valves::default(), &Strokes::default());
        let permit = Literal::is(Signal::StepPermit);
        for step in &program.steps {
            let table_step = step.kind == StepKind::Table;
            assert_eq!(step.condition.contains(&permit), table_step, "{step:?}");
            for jump in &step.jumps {
                let into_table = program.steps[jump.fires].kind == StepKind::Table;
                assert_eq!(jump.condition.contains(&permit), into_table, "{jump:?}");
            }
        }
        let jumps: usize = program.steps.iter().map(|s| s.jumps.len()).sum();
        assert_eq!(jumps, 2);
        // Without the mode no condition reads it.
        let plain = build(
            &table,
            &ProgramOptions::default(),
            &Valves::default(),
            &Strokes::default(),
        );
        assert!(plain.steps.iter().all(|s| !s.condition.contains(&permit)));
    }
}
