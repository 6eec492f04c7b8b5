//! Step supervision with criteria analysis (`--safety criteria`, S7-GRAPH's
//! supervision and criteria analysis): the step watchdog of `--safety
//! watchdog` is the supervision timer, and when it runs out, one output per
//! criterion says which condition of the awaited transition is not met.
//!
//! A criterion is an input literal (a sensor, a waited-for machine input, an
//! interlock, a precheck's "target sensor still off", single step's
//! "STEP_MODE off") of some transition of the sequence; criterion n has an
//! "awaited" memory `crit{n}`, kept by the transitions themselves: each one
//! that fires sets the memories of the criteria of the transition it makes
//! the sequence wait at and resets the others', so that exactly the awaited
//! transition's are on (none at rest).
//! The rungs then light `miss{n}` while the timeout alarm is on, criterion n
//! is awaited and its literal does not hold. Everything is SET/RESET of bits
//! in rungs and transitions, so every language renders it as it renders the
//! rest of the program, and the simulation runs it as it runs the rest.

use std::collections::BTreeMap;

use crate::cell::Sign;
use crate::stroke::Strokes;
use crate::table::{Step, StepTable};

use super::{Action, Alarm, Literal, ProgramStep, Rung, RungKind, Signal, Signals};

/// The criteria of the transitions of `steps`, each once, in the inputs'
/// address order (a literal before its negation): bit n−1 of the missing
/// outputs is criterion n. The first transition (waiting at rest for START)
/// has none: at rest the watchdog does not run.
pub(super) fn criteria(steps: &[ProgramStep], signals: &Signals) -> Vec<Literal> {
    let mut found: Vec<Literal> = steps.iter().skip(1).flat_map(awaited).collect();
    let rank = |l: &Literal| {
        let at = signals.inputs.iter().position(|s| *s == l.signal);
        (at.unwrap_or(usize::MAX), l.negated)
    };
    found.sort_by_key(rank);
    found.dedup();
    found
}

/// The criteria of one transition: its condition's input literals, and
/// where it needs single step's permit, "STEP_MODE off": a step whose
/// time runs out in single step waits for a STEP_PB press (or the switch
/// turned off), and the HMI says so — also of a selector stuck on, which
/// leaves the machine standing mid-cycle.
fn awaited(step: &ProgramStep) -> impl Iterator<Item = Literal> + '_ {
    let permit = step
        .condition
        .contains(&Literal::is(Signal::StepPermit))
        .then_some(Literal::not(Signal::StepMode));
    step.condition
        .iter()
        .copied()
        .filter(|l| l.signal.is_input())
        .chain(permit)
}

/// The number of criterion `literal` (1-based), if it is one.
fn number(criteria: &[Literal], literal: Literal) -> Option<u16> {
    let at = criteria.iter().position(|c| *c == literal)?;
    Some(at as u16 + 1)
}

/// Declares the criteria's signals: the missing outputs after the alarms,
/// the awaited memories after the other memories.
pub(super) fn declare(criteria: &[Literal], signals: &mut Signals) {
    let numbers = 1..=criteria.len() as u16;
    signals.outputs.extend(numbers.clone().map(Signal::Missing));
    signals.memories.extend(numbers.map(Signal::Awaited));
}

/// The numbers of the criteria waited for at program step `index`.
fn waited_at(steps: &[ProgramStep], criteria: &[Literal], index: usize) -> Vec<u16> {
    if index == 0 {
        return Vec::new();
    }
    let mut numbers: Vec<u16> = awaited(&steps[index])
        .filter_map(|l| number(criteria, l))
        .collect();
    numbers.sort_unstable();
    numbers.dedup();
    numbers
}

/// Adds to every transition (each step's own and its jumps) the actions
/// that move the awaited memories from the criteria of the transition it
/// leaves to those of the one it makes the sequence wait at.
pub(super) fn track(steps: &mut [ProgramStep], criteria: &[Literal]) {
    let count = steps.len();
    for index in 0..count {
        let from = waited_at(steps, criteria, index);
        let own = waited_at(steps, criteria, (index + 1) % count);
        let jumps: Vec<Vec<u16>> = steps[index]
            .jumps
            .iter()
            .map(|j| waited_at(steps, criteria, j.next))
            .collect();
        steps[index].actions.extend(moves(&from, &own));
        for (jump, to) in steps[index].jumps.iter_mut().zip(jumps) {
            jump.actions.extend(moves(&from, &to));
        }
    }
}

/// Resets the awaited memories in `from` but not in `to`, sets those in
/// `to` but not in `from`.
fn moves(from: &[u16], to: &[u16]) -> Vec<Action> {
    let resets = from
        .iter()
        .filter(|n| !to.contains(n))
        .map(|n| Action::Reset(Signal::Awaited(*n)));
    let sets = to
        .iter()
        .filter(|n| !from.contains(n))
        .map(|n| Action::Set(Signal::Awaited(*n)));
    resets.chain(sets).collect()
}

/// Per criterion: its missing output on while the timeout alarm is on, it
/// is awaited and it does not hold, off once it holds; and all of them off
/// once the alarm is (RESET clears the alarm).
pub(super) fn rungs(criteria: &[Literal]) -> Vec<Rung> {
    let alarm = Signal::Alarm(Alarm::Timeout);
    let mut rungs = Vec::new();
    for (literal, n) in criteria.iter().zip(1u16..) {
        let unmet = Literal {
            signal: literal.signal,
            negated: !literal.negated,
        };
        let what = describe(*literal);
        rungs.push(Rung {
            kind: RungKind::Watchdog,
            comment: format!("criteria analysis: the step ran out of time waiting for {what}"),
            condition: vec![Literal::is(Signal::Awaited(n)), Literal::is(alarm), unmet],
            actions: vec![Action::Set(Signal::Missing(n))],
        });
        rungs.push(Rung {
            kind: RungKind::Watchdog,
            comment: format!("criteria analysis: {what} holds"),
            condition: vec![*literal],
            actions: vec![Action::Reset(Signal::Missing(n))],
        });
    }
    if !criteria.is_empty() {
        rungs.push(Rung {
            kind: RungKind::Watchdog,
            comment: "criteria analysis: no timeout alarm, nothing missing".to_string(),
            condition: vec![Literal::not(alarm)],
            actions: (1..=criteria.len() as u16)
                .map(|n| Action::Reset(Signal::Missing(n)))
                .collect(),
        });
    }
    rungs
}

/// `x21`, `x21 off` in the method's symbols (the rung comments).
pub fn describe(literal: Literal) -> String {
    if literal.negated {
        format!("{} off", literal.signal.symbol())
    } else {
        literal.signal.symbol()
    }
}

/// How long table step `step` takes in a healthy machine: its longest
/// move (from the stroke times), then its longest dwell, in milliseconds.
pub fn expected_ms(table: &StepTable, step: &Step, strokes: &Strokes) -> (u64, u64) {
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
    (longest, dwell)
}

/// The watchdog's preset for `step`: its supervision time where one is
/// given, else twice its longest move plus its longest dwell plus one
/// second, rounded up to 100 ms: generous enough for a sticky valve, short
/// enough to catch a lost sensor.
pub(super) fn preset_ms(
    table: &StepTable,
    step: &Step,
    strokes: &Strokes,
    given: &BTreeMap<usize, u32>,
) -> u32 {
    if let Some(ms) = given.get(&step.number) {
        return *ms;
    }
    let (longest, dwell) = expected_ms(table, step, strokes);
    rounded_preset(2 * longest + dwell + 1000)
}

/// The watchdog's preset for a homing stage (`--safety watchdog` with
/// RESET): twice the slowest full retract of its actuators plus one
/// second, as for a step, so that a dead home switch halts the homing
/// and cuts its drives instead of leaving them on for good.
pub(super) fn homing_preset_ms(stage: &[u32], strokes: &Strokes) -> u32 {
    let longest = stage
        .iter()
        .map(|a| u64::from(strokes.of(*a).retract_ms))
        .max()
        .unwrap_or(0);
    rounded_preset(2 * longest + 1000)
}

/// Up to 100 ms; rounding up never pushes a preset a timer holds past
/// what it holds.
fn rounded_preset(preset: u64) -> u32 {
    let most = crate::cell::MAX_DWELL_MS as u64;
    let rounded = preset.div_ceil(100) * 100;
    let rounded = if preset <= most {
        rounded.min(most)
    } else {
        rounded
    };
    rounded.min(u32::MAX as u64) as u32
}

/// Supervision times by step, as `--supervision` and the SETTINGS row
/// `supervision` write them: `3=5s, 5=800ms`. Each step once, a time with
/// its unit from 10 ms to 655.35 s (what a timer of every target holds).
/// Whether the steps exist and the times are long enough is checked
/// against the table (`convert`).
pub fn parse_times(text: &str) -> Result<BTreeMap<usize, u32>, String> {
    let mut times = BTreeMap::new();
    for item in text.split(',').map(str::trim) {
        if item.is_empty() {
            return Err(format!(
                "\"{text}\" has an empty item; give STEP=TIME, e.g. 3=5s"
            ));
        }
        let (step, time) = item
            .split_once('=')
            .ok_or_else(|| format!("\"{item}\": expected STEP=TIME, e.g. 3=5s"))?;
        let step: usize = step
            .trim()
            .parse()
            .ok()
            .filter(|n| *n >= 1)
            .ok_or_else(|| format!("\"{item}\": {} is not a step number (1, 2, …)", step.trim()))?;
        let time = time.trim();
        let ms = crate::stroke::parse_duration_ms(time)
            .filter(|_| time.ends_with(|c: char| c.is_ascii_alphabetic()))
            .ok_or_else(|| {
                format!("\"{item}\": expected a time with its unit, such as 5s or 800ms")
            })?;
        if !(crate::cell::MIN_DWELL_MS..=crate::cell::MAX_DWELL_MS).contains(&ms) {
            return Err(format!(
                "\"{item}\": a supervision time runs from 10 ms to 655.35 s (a timer of every target: FST counts 1/100 s in a 16-bit word)"
            ));
        }
        if times.insert(step, ms).is_some() {
            return Err(format!(
                "\"{item}\": step {step} is given twice; give each step once"
            ));
        }
    }
    Ok(times)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn supervision_times_are_read_step_by_step_and_refused_when_wrong() {
        let times = parse_times("3=5s, 5 = 800ms").unwrap();
        assert_eq!(times, BTreeMap::from([(3, 5_000), (5, 800)]));
        for bad in [
            "",
            "3",
            "x=5s",
            "0=5s",
            "3=5",
            "3=5s,3=6s",
            "3=700s",
            "3=5ms",
            "3=5s,",
        ] {
            assert!(parse_times(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn a_transition_moves_the_awaited_memories_from_its_criteria_to_the_next() {
        assert_eq!(
            moves(&[1, 2], &[2, 3]),
            [
                Action::Reset(Signal::Awaited(1)),
                Action::Set(Signal::Awaited(3))
            ]
        );
        assert!(moves(&[4], &[4]).is_empty());
    }
}
