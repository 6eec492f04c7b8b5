//! A fault set's first hazard, rather than its outcome at every moment:
//! what a mitigation's trial needs to know. A check catches a hazard only
//! when no moment gives one any more, so a trial whose faults give a hazard
//! at one moment has its answer there, and its other moments need no run.
//! The moments most likely to give a hazard are tried first: those at
//! which a faulty sensor's cylinder has just set off towards it (a short
//! then reads as the arrival, a dead middle sensor is run through), which
//! the checks on the inputs cannot tell from the real thing; then the
//! others in the cycle's order. The first moment of each set is tried for
//! every set at once (one copy of the healthy run at each), the rest only
//! for the sets that gave no hazard there.

use super::cases::{SetRuns, Verdict};
use super::plan::{Plan, distinct_onsets};
use super::{FaultCase, FaultRuns, Healthy, Moment, Outcome, Phase, single_step, worst_case};
use crate::program::{Signal, StepProgram};
use crate::simulate::{Fault, SimSettings};
use crate::table::StepTable;

/// What the runs of one fault set found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Found {
    /// A hazard when the faults appear at this moment (the first of the
    /// cycle that gives one): the search stopped there.
    Hazard {
        /// The moment's place among the cycle's moments, and its phase.
        moment: usize,
        phase: Phase,
        /// The SFC step the explanation is about, and the explanation.
        step: Option<usize>,
        explanation: String,
    },
    /// No hazard at any moment: the set's case, as the fault table of the
    /// same program gives it.
    Clear(FaultCase),
}

/// Each set's first hazard on `program` (resumed from `healthy` when it is
/// given, [`super::healthy_run`] under the same settings), in the order of
/// `sets`, and the moments of that program's cycle.
pub fn first_hazards(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    sets: Vec<Vec<Fault>>,
    healthy: Option<Healthy>,
) -> (Vec<Found>, Vec<Moment>) {
    let plan = Plan::new(table, program, settings, sets, FaultRuns::Resumed, healthy);
    let planned = distinct_onsets(&plan.onsets);
    let mut runs: Vec<SetRuns> = plan.sets.iter().map(|_| SetRuns::default()).collect();
    // A shorted STEP_PB is judged in single step, not by its runs.
    let stepping = plan
        .sets
        .iter()
        .any(|s| *s == [single_step::SHORT])
        .then(|| single_step::step_button_hazard(table, program, settings))
        .flatten();
    let judged = |i: usize| stepping.is_some() && plan.sets[i] == [single_step::SHORT];
    let hazard = |v: &Verdict| v.outcome == Outcome::Hazard;
    let orders: Vec<Vec<usize>> = (0..plan.sets.len())
        .map(|i| likely_first(table, &plan.sets[i], &plan.moments))
        .collect();
    let tries: Vec<Vec<u64>> = (0..plan.sets.len())
        .map(|i| distinct_in(&orders[i], &plan.onsets[i]))
        .collect();
    let first: Vec<Vec<u64>> = (0..plan.sets.len())
        .map(|i| match judged(i) {
            true => Vec::new(),
            false => tries[i].iter().take(1).copied().collect(),
        })
        .collect();
    plan.run(false, &planned, &first, &mut runs, &hazard, &|| {});
    // Only the first onset's verdict counts here: a run handed on to a later
    // onset may have found a hazard there, but the moments between are not
    // run yet.
    let found_first = |i: usize| {
        first[i]
            .first()
            .and_then(|&onset| runs[i].at(onset))
            .is_some_and(hazard)
    };
    let rest: Vec<Vec<u64>> = (0..plan.sets.len())
        .map(|i| match judged(i) || found_first(i) {
            true => Vec::new(),
            false => tries[i].clone(),
        })
        .collect();
    if rest.iter().any(|r| !r.is_empty()) {
        plan.run(false, &planned, &rest, &mut runs, &hazard, &|| {});
    }
    let found = (0..plan.sets.len())
        .map(|i| {
            if judged(i) {
                let (step, explanation) = stepping.clone().expect("judged in single step");
                return Found::Hazard {
                    moment: 0,
                    phase: plan.moments[0].phase,
                    step: Some(step),
                    explanation,
                };
            }
            match first_hazard(&orders[i], &plan.onsets[i], &runs[i]) {
                Some((moment, verdict)) => Found::Hazard {
                    moment,
                    phase: plan.moments[moment].phase,
                    step: verdict.step,
                    explanation: verdict.explanation.clone(),
                },
                None => Found::Clear(worst_case(
                    &plan.sets[i],
                    &plan.moments,
                    &plan.onsets[i],
                    &runs[i],
                )),
            }
        })
        .collect();
    (found, plan.moments)
}

/// The first moment in `order` whose onset gave a hazard, with that
/// verdict. The search runs the moments in that order and stops at a
/// hazard, so every moment before it in the order has been run (or has no
/// onset: the faults change nothing there).
fn first_hazard<'r>(
    order: &[usize],
    onsets: &[Option<u64>],
    runs: &'r SetRuns,
) -> Option<(usize, &'r Verdict)> {
    order.iter().find_map(|&m| {
        let verdict = runs.at(onsets[m]?)?;
        (verdict.outcome == Outcome::Hazard).then_some((m, verdict))
    })
}

/// The moments in the order they are tried: first those at which a
/// faulty sensor's cylinder has just set off towards the sensor's
/// position, then the rest, each group in the cycle's order.
fn likely_first(table: &StepTable, set: &[Fault], moments: &[Moment]) -> Vec<usize> {
    let towards = |phase: Phase| {
        let Phase::Moving(k) = phase else {
            return false;
        };
        let Some(step) = table.steps.get(k.wrapping_sub(1)) else {
            return false;
        };
        set.iter().any(|f| match f.signal {
            Signal::Sensor { actuator, position } => step
                .moves
                .iter()
                .any(|m| m.actuator == actuator && m.to == position),
            _ => false,
        })
    };
    let (mut order, rest): (Vec<usize>, Vec<usize>) =
        (0..moments.len()).partition(|&m| towards(moments[m].phase));
    order.extend(rest);
    order
}

/// The distinct onsets of the moments in `order`, in that order.
fn distinct_in(order: &[usize], onsets: &[Option<u64>]) -> Vec<u64> {
    let mut distinct: Vec<u64> = Vec::new();
    for onset in order.iter().filter_map(|&m| onsets[m]) {
        if !distinct.contains(&onset) {
            distinct.push(onset);
        }
    }
    distinct
}
