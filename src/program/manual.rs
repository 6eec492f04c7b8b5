//! Manual mode (`--modes manual`): the MAN_MODE selector ends the automatic
//! cycle, and each actuator moves only while one of its jog buttons is held
//! and only where it may move. Rungs of the one step program, SET and RESET
//! of bits like every other mode, so every language and the simulator
//! carry it alike.
//!
//! The safe choices, each a literal of a rung below:
//! - In manual every scan sends the sequence back to step 0 and clears what
//!   a cycle leaves (requests, stop requests, dwells, the watchdog, homing),
//!   so no step action survives the scan and START does nothing.
//! - Every output goes off but those the halt policy lets stay on in a
//!   stopped machine (a vacuum holding its part); a coil is on only in the
//!   scan its jog rung sets it, so only while its button is held.
//! - Both buttons of one actuator held: neither coil; a jog switches the
//!   other coil of its valve off (one a halt held on), never two at once.
//! - Not until every jog button has read released in manual (`jog_ok`):
//!   a button held or stuck as the selector turns moves nothing.
//! - Not while the EMERGENCY STOP or STOP is pressed, nor while a halt (the
//!   emergency stop's, a check's) waits for RESET, not while any interlock
//!   input is off (ranged ones too: manual has no step to exempt).
//! - The scan manual ends in switches off what the jogs left on (a button
//!   still held as the selector turns), as entering it does.
//! - A coil that holds a part (a vacuum) stays on by itself: its jogN+
//!   switches it on, its jogN- off.
//! - A coil a halt row holds on stays on into manual until a jog of its
//!   actuator is pressed (`joggedN`); from then on it follows its button,
//!   so a tap never latches it.
//! - A drive is cut at the limit switch of the way it runs.
//! - A held coil keeps its actuator's stop request (a 5/3 piston stops at
//!   the middle position it was heading for, as after a halt) until a jog
//!   of the actuator takes it over.
//! - RESET clears the halt and the alarms, homes nothing, touches no
//!   output.

use super::signals::{Coils, Signals};
use super::{Action, Literal, ProgramOptions, Rung, RungKind, Signal};
use crate::cell::Sign;

/// The manual-mode rungs: the cycle's end, then each actuator's jogs.
/// They run after the homing rungs and before the emergency stop's, which
/// stays the last word on every coil.
pub(super) fn rungs(signals: &Signals, timers: &[Signal], options: &ProgramOptions) -> Vec<Rung> {
    // First the held coils a jog took over: they follow their buttons, and
    // go off with manual, before the memory saying so is cleared.
    let mut rungs: Vec<Rung> = signals
        .valves
        .iter()
        .flat_map(|valve| follow_rungs(*valve, signals, options))
        .collect();
    rungs.extend([
        end_of_manual(signals, options),
        end_of_automatic(signals, timers, options),
    ]);
    rungs.extend(reset_rung(signals, options));
    rungs.extend([
        Rung {
            kind: RungKind::Manual,
            comment: "MAN_MODE remembered for the scan manual ends in".to_string(),
            condition: vec![Literal::is(Signal::ManualMode)],
            actions: vec![Action::Set(Signal::ManualMemory)],
        },
        jogs_released(signals),
    ]);
    for valve in &signals.valves {
        rungs.extend(taken_over(*valve, signals, options));
        rungs.extend(jog_rungs(*valve, signals, options));
    }
    rungs
}

/// Every jog button read released in manual: from then on the jogs may
/// act. A button held or stuck as the selector turns moves nothing (a mode
/// change alone must not start motion) until every button reads released.
fn jogs_released(signals: &Signals) -> Rung {
    let mut condition = vec![Literal::is(Signal::ManualMode)];
    condition.extend(
        signals
            .inputs
            .iter()
            .filter(|s| matches!(s, Signal::Jog { .. }))
            .map(|jog| Literal::not(*jog)),
    );
    Rung {
        kind: RungKind::Manual,
        comment: "every jog button released in manual: the jogs may act (one held or stuck as the selector turns moves nothing)".to_string(),
        condition,
        actions: vec![Action::Set(Signal::JogsReleased)],
    }
}

/// A jog of `valve`'s actuator pressed in manual: its held coils are the
/// jog buttons' from now until manual ends.
fn taken_over(valve: Coils, signals: &Signals, options: &ProgramOptions) -> Vec<Rung> {
    let actuator = valve.actuator();
    let held = signals.held_by_jog(valve, options);
    if held.is_empty() {
        return Vec::new();
    }
    // The stop request a held coil kept is the operator's once he jogs.
    let stop_requests: Vec<Signal> = signals
        .memories
        .iter()
        .filter(|m| super::stops::stop_request_of(m, &held))
        .copied()
        .collect();
    [Sign::Plus, Sign::Minus]
        .map(|sign| Signal::Jog { actuator, sign })
        .into_iter()
        .filter(|jog| signals.inputs.contains(jog))
        .map(|jog| Rung {
            kind: RungKind::Manual,
            comment: format!(
                "{} pressed in manual: C{actuator}'s held coils follow its jog buttons until manual ends",
                jog.symbol()
            ),
            condition: vec![
                Literal::is(Signal::ManualMode),
                Literal::is(Signal::JogsReleased),
                Literal::is(jog),
            ],
            actions: std::iter::once(Action::Set(Signal::Jogged(actuator)))
                .chain(stop_requests.iter().map(|m| Action::Reset(*m)))
                .collect(),
        })
        .collect()
}

/// Each held coil a jog took over: off while its button is not held, and
/// off in the scan manual ends (its button may still be held then).
fn follow_rungs(valve: Coils, signals: &Signals, options: &ProgramOptions) -> Vec<Rung> {
    let actuator = valve.actuator();
    let jogged = Signal::Jogged(actuator);
    signals
        .held_by_jog(valve, options)
        .into_iter()
        .flat_map(|coil| {
            let jog = super::signals::jog_of(coil);
            [
                Rung {
                    kind: RungKind::Manual,
                    comment: format!(
                        "C{actuator} jogged: {} on only while {} is held",
                        coil.symbol(),
                        jog.symbol()
                    ),
                    condition: vec![Literal::is(jogged), Literal::not(jog)],
                    actions: vec![Action::Reset(coil)],
                },
                Rung {
                    kind: RungKind::Manual,
                    comment: format!("C{actuator} jogged: {} off as manual ends", coil.symbol()),
                    condition: vec![Literal::is(jogged), Literal::not(Signal::ManualMode)],
                    actions: vec![Action::Reset(coil)],
                },
            ]
            .into_iter()
            .chain(options.modes.stop.then(|| Rung {
                kind: RungKind::Manual,
                comment: format!(
                    "C{actuator} jogged: {} off while STOP is pressed (its jog stopped)",
                    coil.symbol()
                ),
                condition: vec![Literal::is(jogged), Literal::not(Signal::Stop)],
                actions: vec![Action::Reset(coil)],
            }))
        })
        .collect()
}

/// The outputs a stopped machine may keep on (the halt policy's), and the
/// resets of every other.
fn all_off_but_held(signals: &Signals, options: &ProgramOptions) -> (Vec<Signal>, Vec<Action>) {
    let held: Vec<Signal> = signals
        .driven()
        .filter(|s| !signals.is_drive(*s) && options.halt.may_stay_on(*s, false))
        .collect();
    let actions = signals
        .driven()
        .filter(|s| !held.contains(s))
        .map(Action::Reset)
        .collect();
    (held, actions)
}

/// MAN_MODE back at 0: in that scan every output goes off but those the
/// halt policy holds, so a jog button still held as the selector turns
/// leaves nothing running in automatic.
fn end_of_manual(signals: &Signals, options: &ProgramOptions) -> Rung {
    let (held, mut actions) = all_off_but_held(signals, options);
    actions.push(Action::Reset(Signal::ManualMemory));
    actions.push(Action::Reset(Signal::JogsReleased));
    actions.extend(
        signals
            .memories
            .iter()
            .filter(|m| matches!(m, Signal::Jogged(_)))
            .map(|m| Action::Reset(*m)),
    );
    let kept: Vec<String> = held.iter().map(|s| s.symbol()).collect();
    Rung {
        kind: RungKind::Manual,
        comment: format!(
            "MAN_MODE back to 0: manual ends, {}",
            super::stops::all_off_but(&kept)
        ),
        condition: vec![
            Literal::not(Signal::ManualMode),
            Literal::is(Signal::ManualMemory),
        ],
        actions,
    }
}

/// MAN_MODE at 1: the automatic cycle ends, every output off but those
/// the halt policy holds.
fn end_of_automatic(signals: &Signals, timers: &[Signal], options: &ProgramOptions) -> Rung {
    let (held, mut actions) = all_off_but_held(signals, options);
    // A held coil keeps its actuator's stop request, as a halt does: a 5/3
    // piston still stops at the middle position it was heading for.
    actions.extend(
        signals
            .memories
            .iter()
            .filter(|m| super::stops::ends_with_the_cycle(m))
            .filter(|m| !super::stops::stop_request_of(m, &held))
            .map(|m| Action::Reset(*m)),
    );
    // No transition is awaited in manual, so no criterion is missing
    // (the alarm itself waits for RESET).
    actions.extend(signals.misses().map(Action::Reset));
    // A run-on keeps its own timer: it switches its output off itself.
    actions.extend(
        timers
            .iter()
            .filter(|t| !matches!(t, Signal::RunOn(_)))
            .map(|t| Action::Reset(*t)),
    );
    actions.push(Action::Reset(Signal::Sequence));
    let kept: Vec<String> = held.iter().map(|s| s.symbol()).collect();
    Rung {
        kind: RungKind::Manual,
        comment: format!(
            "MAN_MODE (1 = manual): the automatic cycle ends, back to step {}, {}, START ignored",
            super::INITIAL_STEP,
            super::stops::all_off_but(&kept)
        ),
        condition: vec![Literal::is(Signal::ManualMode)],
        actions,
    }
}

/// RESET in manual: the halt and the alarms cleared, nothing homed and
/// no output touched (the automatic RESET rung, which switches every
/// output off and starts the homing, needs MAN_MODE off).
fn reset_rung(signals: &Signals, options: &ProgramOptions) -> Option<Rung> {
    if !options.modes.reset {
        return None;
    }
    let mut condition = super::modes::reset_pressed(options);
    condition.insert(2, Literal::is(Signal::ManualMode));
    let mut actions: Vec<Action> = signals
        .memories
        .iter()
        .filter(|m| **m == Signal::Halt)
        .map(|m| Action::Reset(*m))
        .collect();
    actions.extend(signals.alarms().map(Action::Reset));
    (!actions.is_empty()).then(|| Rung {
        kind: RungKind::Manual,
        comment: "RESET in manual: the halt and the alarms cleared, nothing homed".to_string(),
        condition,
        actions,
    })
}

/// What every jog needs: manual mode, the EMERGENCY STOP and STOP not
/// pressed (a stop overrides the jog it relates to, as in automatic) and
/// no halt waiting for RESET, every interlock closed.
fn may_jog(signals: &Signals, options: &ProgramOptions) -> Vec<Literal> {
    let mut condition = vec![
        Literal::is(Signal::ManualMode),
        Literal::is(Signal::JogsReleased),
    ];
    if options.modes.estop {
        condition.push(Literal::is(Signal::EStop));
    }
    if options.modes.stop {
        condition.push(Literal::is(Signal::Stop));
    }
    if signals.memories.contains(&Signal::Halt) {
        condition.push(Literal::not(Signal::Halt));
    }
    for interlock in &options.interlocks {
        let closed = Literal::is(Signal::MachineInput(interlock.input));
        if !condition.contains(&closed) {
            condition.push(closed);
        }
    }
    condition
}

/// The jog rungs of one actuator: each of its coils on while its button is
/// held and the other is not.
fn jog_rungs(valve: Coils, signals: &Signals, options: &ProgramOptions) -> Vec<Rung> {
    let actuator = valve.actuator();
    let drive = signals.drives(actuator);
    let max = signals
        .inputs
        .iter()
        .filter_map(|s| match s {
            Signal::Sensor {
                actuator: a,
                position,
            } if *a == actuator => Some(*position),
            _ => None,
        })
        .max()
        .unwrap_or(1);
    let jog = |sign| Signal::Jog { actuator, sign };
    let mut rungs = Vec::new();
    for sign in [Sign::Plus, Sign::Minus] {
        if !signals.inputs.contains(&jog(sign)) {
            continue;
        }
        // A single coil's jogN- (a vacuum's release) switches it off.
        let (coil, action) = match valve {
            Coils::Single { .. } if sign == Sign::Minus => {
                (valve.extend(), Action::Reset(valve.extend()))
            }
            Coils::Single { .. } => (valve.extend(), Action::Set(valve.extend())),
            Coils::Double { .. } => {
                let coil = Signal::Coil { actuator, sign };
                (coil, Action::Set(coil))
            }
        };
        let mut condition = may_jog(signals, options);
        condition.push(Literal::is(jog(sign)));
        if signals.inputs.contains(&jog(sign.opposite())) {
            condition.push(Literal::not(jog(sign.opposite())));
        }
        let mut actions = vec![action];
        if let Coils::Double { .. } = valve {
            // The other coil off first: a halt may have held it on.
            actions.insert(
                0,
                Action::Reset(Signal::Coil {
                    actuator,
                    sign: sign.opposite(),
                }),
            );
        }
        let kind = signals.kinds.get(&actuator);
        let (plus, minus) = match valve {
            _ if drive => crate::actuator::ActuatorKind::Motor.move_words(),
            Coils::Single { .. } => kind.map_or(("extends", "retracts"), |k| k.single_coil_words()),
            Coils::Double { .. } => kind.map_or(("extends", "retracts"), |k| k.move_words()),
        };
        let verb = if sign == Sign::Plus { plus } else { minus };
        let state = if matches!(action, Action::Reset(_)) {
            "off"
        } else {
            "on"
        };
        // A coil that holds a part stays as its jog left it (a vacuum
        // keeps the part until its release jog); the others drop with
        // their button.
        let holds = kind.is_some_and(|k| k.holds_part());
        let when = if holds { "when" } else { "while" };
        let pressed = if holds { "pressed" } else { "held" };
        let mut comment = format!(
            "jog C{actuator}: {} {state} {when} {} is {pressed}",
            coil.symbol(),
            jog(sign).symbol()
        );
        if signals.inputs.contains(&jog(sign.opposite())) {
            comment.push_str(&format!(" and {} is not", jog(sign.opposite()).symbol()));
        }
        if drive {
            // A drive runs past its limit switch unless cut there.
            let limit = if sign == Sign::Plus { max } else { 0 };
            let sensor = Signal::Sensor {
                actuator,
                position: limit,
            };
            condition.push(Literal::not(sensor));
            comment.push_str(&format!(", short of {}", sensor.symbol()));
        }
        comment.push_str(&format!(": C{actuator} {verb}"));
        rungs.push(Rung {
            kind: RungKind::Manual,
            comment,
            condition,
            actions,
        });
    }
    rungs
}

#[cfg(test)]
mod tests {
    use super::super::{Literal, Modes, ProgramOptions, RungKind, Signal, build};
    use crate::actuator::Valves;
    use crate::cell::Sign;
    use crate::stroke::Strokes;

    fn manual(modes: &str) -> crate::program::StepProgram {
        let table = crate::program::tests::paper_table();
        let options = ProgramOptions {
            modes: Modes::parse(modes).unwrap(),
            ..ProgramOptions::default()
        };
        build(&table, &options, &Valves::default(), &Strokes::default())
    }

    /// Each coil is set by one jog rung, which needs its own button, not
    /// the other, the selector and the emergency stop; the cycle's end
    /// comes first and sends the sequence home.
    #[test]
    fn every_jog_needs_its_button_alone_in_manual_without_estop() {
        let program = manual("manual,estop");
        let rungs: Vec<_> = program
            .rungs
            .iter()
            .filter(|r| r.kind == RungKind::Manual)
            .collect();
        // The cycle's two ends, RESET in manual, man_mem, jog_ok, the jogs.
        assert_eq!(rungs.len(), 5 + 2 * 4);
        // Leaving manual switches every coil off (the jog a button still
        // held left on); entering it ends the cycle.
        let leave = rungs[0];
        assert!(leave.condition.contains(&Literal::not(Signal::ManualMode)));
        assert!(leave.condition.contains(&Literal::is(Signal::ManualMemory)));
        assert!(leave.actions.contains(&super::Action::Reset(Signal::Coil {
            actuator: 2,
            sign: Sign::Plus
        })));
        assert!(
            rungs[1]
                .actions
                .contains(&super::Action::Reset(Signal::Sequence))
        );
        assert!(program.signals.memories.contains(&Signal::Halt));
        for rung in &rungs[5..] {
            let [
                super::Action::Reset(Signal::Coil { sign: other, .. }),
                super::Action::Set(Signal::Coil { actuator, sign }),
            ] = rung.actions[..]
            else {
                panic!("{rung:?}");
            };
            // Never both coils: the other goes off as this one comes on.
            assert_eq!(other, sign.opposite());
            let jog = |sign| Signal::Jog { actuator, sign };
            for literal in [
                Literal::is(Signal::ManualMode),
                Literal::is(Signal::JogsReleased),
                Literal::is(Signal::EStop),
                Literal::not(Signal::Halt),
                Literal::is(jog(sign)),
                Literal::not(jog(sign.opposite())),
            ] {
                assert!(rung.condition.contains(&literal), "{rung:?}");
            }
        }
        // The emergency stop's rung stays last.
        assert_eq!(
            program.rungs.last().map(|r| r.kind),
            Some(RungKind::EmergencyStop)
        );
        let jogs = program
            .signals
            .inputs
            .iter()
            .filter(|s| matches!(s, Signal::Jog { .. }))
            .count();
        assert_eq!(jogs, 8);
        assert!(program.signals.inputs.contains(&Signal::Jog {
            actuator: 3,
            sign: Sign::Minus
        }));
    }

    /// Without the mode no jog input, no manual rung.
    #[test]
    fn without_manual_no_jog() {
        let program = manual("estop");
        assert!(program.rungs.iter().all(|r| r.kind != RungKind::Manual));
        assert!(
            program
                .signals
                .inputs
                .iter()
                .all(|s| !matches!(s, Signal::Jog { .. } | Signal::ManualMode))
        );
    }
}
