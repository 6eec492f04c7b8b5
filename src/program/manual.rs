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
//! - Both buttons of one actuator held: neither coil.
//! - Not while the EMERGENCY STOP is pressed, not while any interlock input
//!   is off (ranged ones too: manual has no step to exempt).
//! - A drive is cut at the limit switch of the way it runs.

use super::signals::{Coils, Signals};
use super::{Action, Literal, ProgramOptions, Rung, RungKind, Signal};
use crate::cell::Sign;

/// The manual-mode rungs: the cycle's end, then each actuator's jogs.
/// They run after the homing rungs and before the emergency stop's, which
/// stays the last word on every coil.
pub(super) fn rungs(signals: &Signals, timers: &[Signal], options: &ProgramOptions) -> Vec<Rung> {
    let mut rungs = vec![end_of_automatic(signals, timers, options)];
    for valve in &signals.valves {
        rungs.extend(jog_rungs(*valve, signals, options));
    }
    rungs
}

/// MAN_MODE at 1: the automatic cycle ends, every output off but those
/// the halt policy holds.
fn end_of_automatic(signals: &Signals, timers: &[Signal], options: &ProgramOptions) -> Rung {
    let held: Vec<Signal> = signals
        .driven()
        .filter(|s| !signals.is_drive(*s) && options.halt.may_stay_on(*s, false))
        .collect();
    let mut actions: Vec<Action> = signals
        .driven()
        .filter(|s| !held.contains(s))
        .map(Action::Reset)
        .collect();
    actions.extend(
        signals
            .memories
            .iter()
            .filter(|m| {
                matches!(
                    m,
                    Signal::CycleRequest
                        | Signal::Busy
                        | Signal::AutoRun
                        | Signal::StopAt { .. }
                        | Signal::DwellArmed(_)
                        | Signal::InterlockZone(_)
                        | Signal::WatchdogArmed
                        | Signal::Awaited(_)
                        | Signal::Homing
                        | Signal::HomeStage(_)
                )
            })
            .map(|m| Action::Reset(*m)),
    );
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

/// What every jog needs: manual mode, the EMERGENCY STOP not pressed,
/// every interlock closed.
fn may_jog(options: &ProgramOptions) -> Vec<Literal> {
    let mut condition = vec![Literal::is(Signal::ManualMode)];
    if options.modes.estop {
        condition.push(Literal::is(Signal::EStop));
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
        let coil = match (valve, sign) {
            (Coils::Single { .. }, Sign::Minus) => continue,
            (Coils::Single { .. }, Sign::Plus) => valve.extend(),
            (Coils::Double { .. }, _) => Signal::Coil { actuator, sign },
        };
        let mut condition = may_jog(options);
        condition.push(Literal::is(jog(sign)));
        if let Coils::Double { .. } = valve {
            condition.push(Literal::not(jog(sign.opposite())));
        }
        let verb = match (drive, sign) {
            (true, Sign::Plus) => "runs forward",
            (true, Sign::Minus) => "runs in reverse",
            (false, Sign::Plus) => "extends",
            (false, Sign::Minus) => "retracts",
        };
        let mut comment = format!(
            "jog C{actuator}: {} on while {} is held",
            coil.symbol(),
            jog(sign).symbol()
        );
        if let Coils::Double { .. } = valve {
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
            actions: vec![Action::Set(coil)],
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
        assert_eq!(rungs.len(), 1 + 2 * 4);
        assert!(
            rungs[0]
                .actions
                .contains(&super::Action::Reset(Signal::Sequence))
        );
        for rung in &rungs[1..] {
            let [super::Action::Set(Signal::Coil { actuator, sign })] = rung.actions[..] else {
                panic!("{rung:?}");
            };
            let jog = |sign| Signal::Jog { actuator, sign };
            for literal in [
                Literal::is(Signal::ManualMode),
                Literal::is(Signal::EStop),
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
