//! What the machine does when it stops or may not go on: a STOP that
//! acts at once, outputs that run on after a stop, the halt switching off
//! what may not stay on, and interlocks (always, or over a range of steps).

use super::signals::Signals;
use super::{Action, Alarm, Literal, ProgramOptions, ProgramStep, Rung, RungKind, Signal};

/// Each run-on starts its timer when its event finds its output on, and
/// switches the output off when the timer has run out.
pub(super) fn run_on_rungs(run_ons: &[super::RunOn]) -> Vec<Rung> {
    use super::StopEvent;
    let mut rungs = Vec::new();
    for (i, run_on) in run_ons.iter().enumerate() {
        let n = i as u16 + 1;
        let (timer, armed) = (Signal::RunOn(n), Signal::RunOnArmed(n));
        let output = run_on.output;
        let time = crate::cell::duration_text(run_on.ms);
        let event = run_on.event.text();
        // Switched off by something else (the emergency stop, manual mode,
        // a halt row, a step), the run-on is over: RESET must not find it
        // armed and switch the output on again.
        rungs.push(Rung {
            kind: RungKind::RunOn,
            comment: format!(
                "run-on {n}: {} switched off otherwise, the run-on is over",
                output.symbol()
            ),
            condition: vec![Literal::is(armed), Literal::not(output)],
            actions: vec![Action::Reset(armed), Action::Reset(timer)],
        });
        rungs.push(Rung {
            kind: RungKind::RunOn,
            comment: format!(
                "run-on {n}: {} off once {time} have passed after {event}",
                output.symbol()
            ),
            condition: vec![Literal::is(armed), Literal::not(timer)],
            actions: vec![Action::Reset(output), Action::Reset(armed)],
        });
        let happened = match run_on.event {
            StopEvent::Stop => Literal::not(Signal::Stop),
            StopEvent::EStop => Literal::not(Signal::EStop),
            StopEvent::Halt => Literal::is(Signal::Halt),
        };
        rungs.push(Rung {
            kind: RungKind::RunOn,
            comment: format!(
                "run-on {n}: {event} finds {} on: it stays on {time}",
                output.symbol()
            ),
            condition: vec![happened, Literal::is(output), Literal::not(armed)],
            actions: vec![Action::Set(armed), Action::StartTimer(timer, run_on.ms)],
        });
    }
    rungs
}

/// RESET switches every output off, but a run-on under way runs its time
/// out (a fan cooling a heater after STOP or the emergency stop): in the
/// RESET rung's scan (`reset`, its condition) and after it, an armed
/// run-on's output is on again, so the output never drops, and its own
/// rung ends it on time. Only then: a step of a later cycle may switch it
/// off before its time is up.
pub(super) fn run_ons_through_reset(run_ons: &[super::RunOn], reset: &[Literal]) -> Vec<Rung> {
    (1..=run_ons.len() as u16)
        .zip(run_ons)
        .map(|(n, run_on)| {
            let mut condition = reset.to_vec();
            condition.push(Literal::is(Signal::RunOnArmed(n)));
            Rung {
                kind: RungKind::RunOn,
                comment: format!(
                    "run-on {n}: RESET leaves {} on until its time is up",
                    run_on.output.symbol()
                ),
                condition,
                actions: vec![Action::Set(run_on.output)],
            }
        })
        .collect()
}

/// A step that switches a running-on output on again ends its run-on.
pub(super) fn end_run_ons(run_ons: &[super::RunOn], steps: &mut [ProgramStep]) {
    for step in steps {
        let mut ended = Vec::new();
        for action in &step.actions {
            for (i, run_on) in run_ons.iter().enumerate() {
                if *action == Action::Set(run_on.output) {
                    ended.push(Action::Reset(Signal::RunOnArmed(i as u16 + 1)));
                    ended.push(Action::Reset(Signal::RunOn(i as u16 + 1)));
                }
            }
        }
        step.actions.extend(ended);
    }
}

/// An interlock input that goes off halts the machine where it is and
/// raises `alarm_il`; RESET (or a restart) clears the halt. One guarding
/// a range of steps guards the homing too: homing moves every actuator
/// and has no step to exempt, as manual's jogs have none.
pub(super) fn interlock_rung(options: &ProgramOptions) -> Vec<Rung> {
    let zones: Vec<(Signal, super::Interlock)> = options.zones().collect();
    let halt = || {
        vec![
            Action::Set(Signal::Halt),
            Action::Set(Signal::Alarm(Alarm::Interlock)),
        ]
    };
    let mut rungs = Vec::new();
    for interlock in &options.interlocks {
        let name = interlock.input;
        let off = Literal::not(Signal::MachineInput(name));
        let mut condition = vec![off];
        let mut comment = format!("INTERLOCK: {name} off halts the machine");
        let ranged = zones.iter().find(|(_, i)| i == interlock);
        if let Some((zone, i)) = ranged
            && let Some((first, last)) = i.steps
        {
            condition.push(Literal::is(*zone));
            comment.push_str(&format!(" in steps {first} to {last}"));
        }
        rungs.push(Rung {
            kind: RungKind::Interlock,
            comment,
            condition,
            actions: halt(),
        });
        if ranged.is_some() && options.modes.reset {
            rungs.push(Rung {
                kind: RungKind::Interlock,
                comment: format!("INTERLOCK: {name} off halts the homing"),
                condition: vec![off, Literal::is(Signal::Homing)],
                actions: halt(),
            });
        }
    }
    rungs
}

/// A zone memory is set when the range's first step fires and reset when
/// the step after its last fires (the end of the cycle after the last).
pub(super) fn mark_zones(options: &ProgramOptions, steps: &mut [ProgramStep]) {
    for (zone, interlock) in options.zones() {
        let Some((first, last)) = interlock.steps else {
            continue;
        };
        for step in steps.iter_mut() {
            if step.number == first {
                step.actions.push(Action::Set(zone));
            } else if step.number == last + 1 {
                step.actions.push(Action::Reset(zone));
            }
        }
    }
}

/// A halt switches off the outputs declared `de-energise on halt` and every
/// drive's (valve type `motor`, unless `hold-safe`): a heater or a motor
/// must not stay on in a machine that has stopped on a fault.
pub(super) fn halt_off_rung(signals: &Signals, policy: &super::HaltPolicy) -> Option<Rung> {
    let drive = |s: &Signal| signals.is_drive(*s) && !policy.hold_safe.contains(s);
    let off: Vec<Signal> = signals
        .driven()
        .filter(|s| policy.off_on_halt.contains(s) || drive(s))
        .collect();
    if off.is_empty() {
        return None;
    }
    let names: Vec<String> = off.iter().map(|s| s.symbol()).collect();
    Some(Rung {
        kind: RungKind::HaltOff,
        comment: format!(
            "HALT: {} off ({})",
            names.join(", "),
            if off.iter().any(drive) {
                "drives, and de-energise on halt"
            } else {
                "de-energise on halt"
            }
        ),
        condition: vec![Literal::is(Signal::Halt)],
        actions: off.into_iter().map(Action::Reset).collect(),
    })
}

/// STOP that acts at once (SETTINGS `on stop`): in any state the sequence
/// is abandoned (back to STEP 1, no cycle asked for or under way, no dwell,
/// watchdog or homing running) and every coil and output goes off but
/// those held or running on (their rungs: `build::run_on_rungs`).
pub(super) fn stop_now_rungs(
    signals: &Signals,
    timers: &[Signal],
    policy: &super::HaltPolicy,
    rungs: &mut Vec<Rung>,
) {
    use super::StopAction;
    let kept: Vec<String> = signals
        .driven()
        .filter_map(|s| match policy.on_stop.get(&s) {
            Some(StopAction::Hold) => Some(format!("{} held", s.symbol())),
            Some(StopAction::OffAfter(ms)) => Some(format!(
                "{} off after {}",
                s.symbol(),
                crate::cell::duration_text(*ms)
            )),
            _ => None,
        })
        .collect();
    let mut actions: Vec<Action> = signals
        .driven()
        .filter(|s| matches!(policy.on_stop.get(s), None | Some(StopAction::Off)))
        .map(Action::Reset)
        .collect();
    // An actuator whose coil or contactor stays on keeps its stop requests:
    // without them a drive runs past its limit switch and a piston past
    // the middle position it was heading for.
    let still_driven: Vec<Signal> = signals
        .driven()
        .filter(|s| !matches!(policy.on_stop.get(s), None | Some(StopAction::Off)))
        .collect();
    actions.extend(
        signals
            .memories
            .iter()
            .filter(|m| !stop_request_of(m, &still_driven))
            .filter(|m| ends_with_the_cycle(m))
            .map(|m| Action::Reset(*m)),
    );
    // No transition is awaited any more, so no criterion is missing.
    actions.extend(signals.misses().map(Action::Reset));
    actions.extend(
        timers
            .iter()
            .filter(|t| !matches!(t, Signal::RunOn(_)))
            .map(|t| Action::Reset(*t)),
    );
    actions.push(Action::Reset(Signal::Sequence));
    rungs.push(Rung {
        kind: RungKind::StopNow,
        comment: format!(
            "STOP (normally closed): stop at once, {}",
            all_off_but(&kept)
        ),
        condition: vec![Literal::not(Signal::Stop)],
        actions,
    });
}

/// Whether `m` is the stop request (middle stop, a drive's limit) of an
/// actuator one of whose coils is in `kept_on`: that coil still drives it,
/// so the request must stay to stop it where the sequence meant it to.
pub(super) fn stop_request_of(m: &Signal, kept_on: &[Signal]) -> bool {
    let Signal::StopAt { actuator, .. } = *m else {
        return false;
    };
    kept_on.iter().any(|s| {
        matches!(*s, Signal::Coil { actuator: a, .. } | Signal::SingleCoil { actuator: a } if a == actuator)
    })
}

/// `every coil and output off`, `… off but fan (off after 20s)`.
pub(super) fn all_off_but(kept: &[String]) -> String {
    if kept.is_empty() {
        "every coil and output off".to_string()
    } else {
        format!("every coil and output off but {}", kept.join(", "))
    }
}

/// The memories a cycle leaves that end with it (a STOP at once, manual
/// mode): requests, stop requests, dwells, zones, the watchdog, homing.
pub(super) fn ends_with_the_cycle(m: &Signal) -> bool {
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
}
