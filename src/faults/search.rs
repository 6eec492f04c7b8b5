//! A fault set's first hazard, rather than its outcome at every moment:
//! what a mitigation's trial needs to know. A check catches a hazard only
//! when no moment gives one any more, so a trial whose faults give a hazard
//! at one moment has its answer there, and its other moments need no run.
//! The moments most likely to give a hazard are tried first: those at
//! which a faulty sensor's cylinder has just set off towards it (a short
//! then reads as the arrival, a dead middle sensor is run through), which
//! the checks on the inputs cannot tell from the real thing, and the
//! moments right after them; then the others in the cycle's order. The first moment of each set is tried for
//! every set at once, the rest only for the sets that gave no hazard there,
//! all from one pass of the healthy run copied at every onset.

use super::cases::{SetRuns, Verdict};
use super::healthy::untraced_yardstick;
use super::plan::{Plan, distinct_onsets};
use super::{
    FaultCase, FaultRuns, Healthy, Moment, Outcome, Phase, healthy_run, single_step, worst_case,
};
use crate::program::{Signal, StepProgram};
use crate::simulate::{Checkpoints, Fault, SimSettings};
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

/// What a search found, per set, and where it looked.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Searched {
    pub found: Vec<Found>,
    /// The moments of the program's cycle the faults appeared at.
    pub moments: Vec<Moment>,
    /// The cycle was too long for faults at every moment (as `faults`
    /// decides it for the whole table): they appeared at power-up only.
    pub power_up_only: bool,
}

/// Each set's first hazard on `program`, in the order of `sets`, and the
/// moments of that program's cycle; `None` when the program does not pass
/// its own healthy cycle. `expected` is a healthy run the program's own is
/// expected to be (that of the same table without the checks a trial adds,
/// which change nothing in a healthy cycle): the runs are planned from it,
/// and the copy of the program's own healthy run the first runs start from
/// is checked against it on the way (the same inputs at the same times, the
/// same places), so that the program is not run healthy once more to plan.
/// Where the two differ, the plan is made again from the program's own run.
pub fn first_hazards(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    sets: Vec<Vec<Fault>>,
    expected: Option<&Healthy>,
) -> Option<Searched> {
    // The budget counts the sets of the table these belong to, as `faults`
    // with this program would: the moments are then the ones it runs.
    let counted = super::case_count(program, sets.iter().map(Vec::len).max().unwrap_or(1));
    // A shorted STEP_PB is judged in single step, not by its runs.
    let stepping = sets
        .iter()
        .any(|s| *s == [single_step::SHORT])
        .then(|| single_step::step_button_hazard(table, program, settings))
        .flatten();
    let own = match expected {
        Some(expected) => {
            let plan = Plan::new(
                table,
                program,
                settings,
                sets.clone(),
                counted,
                FaultRuns::Resumed,
                Some(expected.clone()),
                false,
            );
            let search = Search::new(table, &plan, stepping.clone());
            match plan.copies(&search.copied(), false, true) {
                Some(copies) => {
                    if copies.report.passed && plan.made_from(&copies.report, copies.log.as_ref()) {
                        return Some(search.finish(&plan, Some(copies)));
                    }
                    let Checkpoints { report, log, .. } = copies;
                    Healthy {
                        report,
                        log: log.unwrap_or_default(),
                    }
                }
                None => healthy_run(table, program, &untraced_yardstick(settings)),
            }
        }
        None => healthy_run(table, program, &untraced_yardstick(settings)),
    };
    if !own.report.passed {
        return None;
    }
    let plan = Plan::new(
        table,
        program,
        settings,
        sets,
        counted,
        FaultRuns::Resumed,
        Some(own),
        false,
    );
    let search = Search::new(table, &plan, stepping);
    let copies = plan.copies(&search.copied(), false, false);
    Some(search.finish(&plan, copies))
}

/// The order each set's moments are tried in, and what has been found.
struct Search {
    orders: Vec<Vec<usize>>,
    /// Each set's distinct onsets in that order.
    tries: Vec<Vec<u64>>,
    /// The first of them, for every set but one judged otherwise.
    first: Vec<Vec<u64>>,
    runs: Vec<SetRuns>,
    /// Sets judged in single step (a shorted STEP_PB, when it is a hazard
    /// there), and that judgement: the step and why.
    judged: Vec<bool>,
    stepping: Option<(usize, String)>,
}

impl Search {
    fn new(table: &StepTable, plan: &Plan<'_>, stepping: Option<(usize, String)>) -> Search {
        let orders: Vec<Vec<usize>> = plan
            .sets
            .iter()
            .map(|set| likely_first(table, set, &plan.moments))
            .collect();
        let tries: Vec<Vec<u64>> = orders
            .iter()
            .zip(&plan.onsets)
            .map(|(order, onsets)| distinct_in(order, onsets))
            .collect();
        let judged: Vec<bool> = plan
            .sets
            .iter()
            .map(|s| stepping.is_some() && *s == [single_step::SHORT])
            .collect();
        let first = tries
            .iter()
            .zip(&judged)
            .map(|(t, judged)| match judged {
                true => Vec::new(),
                false => t.iter().take(1).copied().collect(),
            })
            .collect();
        Search {
            orders,
            tries,
            first,
            runs: plan.sets.iter().map(|_| SetRuns::default()).collect(),
            judged,
            stepping,
        }
    }

    /// The onsets the healthy run is copied at: every onset a set may
    /// try. A copy costs a few hundred times less than a pass of the
    /// healthy run, which copying only the first onsets took twice.
    fn copied(&self) -> Vec<Vec<u64>> {
        let tries = self.tries.iter().zip(&self.judged);
        tries
            .map(|(t, judged)| if *judged { Vec::new() } else { t.clone() })
            .collect()
    }

    /// Runs the first onset of every set from `copies` (copied at every
    /// onset [`Search::copied`] names), then the others of the sets that
    /// gave no hazard there, until one does.
    fn finish(mut self, plan: &Plan<'_>, copies: Option<Checkpoints<'_>>) -> Searched {
        let planned = distinct_onsets(&plan.onsets);
        let hazard = |v: &Verdict| v.outcome == Outcome::Hazard;
        plan.run(
            copies.as_ref(),
            &planned,
            &self.first,
            &mut self.runs,
            &hazard,
            &|| {},
        );
        // Only the first onset's verdict counts here: a run handed on to a
        // later onset may have found a hazard there, but the moments
        // between are not run yet.
        let rest: Vec<Vec<u64>> = (0..plan.sets.len())
            .map(|i| {
                let found = self.first[i]
                    .first()
                    .and_then(|&onset| self.runs[i].at(onset))
                    .is_some_and(hazard);
                match self.judged[i] || found {
                    true => Vec::new(),
                    false => self.tries[i].clone(),
                }
            })
            .collect();
        if rest.iter().any(|r| !r.is_empty()) {
            plan.run(
                copies.as_ref(),
                &planned,
                &rest,
                &mut self.runs,
                &hazard,
                &|| {},
            );
        }
        let found = (0..plan.sets.len()).map(|i| self.found(plan, i)).collect();
        Searched {
            found,
            moments: plan.moments.clone(),
            power_up_only: plan.phases_skipped.is_some(),
        }
    }

    /// What the runs of set `i` found.
    fn found(&self, plan: &Plan<'_>, i: usize) -> Found {
        if let (true, Some((step, explanation))) = (self.judged[i], &self.stepping) {
            return Found::Hazard {
                moment: 0,
                phase: plan.moments[0].phase,
                step: Some(*step),
                explanation: explanation.clone(),
            };
        }
        match first_hazard(&self.orders[i], &plan.onsets[i], &self.runs[i]) {
            Some((moment, verdict)) => Found::Hazard {
                moment,
                phase: plan.moments[moment].phase,
                step: verdict.step,
                explanation: verdict.explanation.clone(),
            },
            None => Found::Clear(worst_case(plan, i, &self.runs[i])),
        }
    }
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
/// position, then the moments right after those, then the rest, each
/// group in the cycle's order. A check that catches a short as the
/// cylinder sets off often leaves the hazard one moment later, when the
/// cylinder has arrived and the check has nothing left to tell apart: on a
/// typical line that order takes a third fewer runs than the cycle's.
fn likely_first(table: &StepTable, set: &[Fault], moments: &[Moment]) -> Vec<usize> {
    let towards = |m: usize| {
        let Phase::Moving(k) = moments[m].phase else {
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
    let towards: Vec<bool> = (0..moments.len()).map(towards).collect();
    let group = |m: usize| match towards[m] {
        true => 0,
        false if m > 0 && towards[m - 1] => 1,
        false => 2,
    };
    // The cycle's order within each group.
    (0..3)
        .flat_map(|g| (0..moments.len()).filter(move |&m| group(m) == g))
        .collect()
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::program::{self, ProgramOptions, Safety};

    /// A yardstick that is not the program's own healthy run (here, the
    /// same program run at a 20 ms scan) is found out on the way, and the
    /// search is planned again from the program's own run: the same answer
    /// as without a yardstick, not one planned from the wrong moments.
    #[test]
    fn a_yardstick_that_is_not_the_programs_own_run_is_replaced() {
        let table = crate::program::tests::paper_table();
        let options = ProgramOptions {
            safety: Safety {
                precheck: true,
                ..Safety::default()
            },
            ..ProgramOptions::default()
        };
        let program = program::build(
            &table,
            &options,
            &crate::actuator::Valves::default(),
            &crate::stroke::Strokes::default(),
        );
        let settings = SimSettings::default();
        let sets: Vec<Vec<Fault>> = super::super::single_faults(&program)
            .into_iter()
            .map(|f| vec![f])
            .collect();
        let own = first_hazards(&table, &program, &settings, sets.clone(), None).unwrap();
        let right = healthy_run(&table, &program, &untraced_yardstick(&settings));
        let slower = SimSettings {
            scan_ms: 20,
            ..settings.clone()
        };
        let wrong = healthy_run(&table, &program, &untraced_yardstick(&slower));
        assert_ne!(wrong.log, right.log, "the yardstick differs");
        for yardstick in [&right, &wrong] {
            let found = first_hazards(&table, &program, &settings, sets.clone(), Some(yardstick));
            assert_eq!(found.as_ref(), Some(&own));
        }
        assert!(own.found.iter().any(|f| matches!(f, Found::Clear(_))));
        assert!(own.found.iter().any(|f| matches!(f, Found::Hazard { .. })));
        assert!(!own.power_up_only);
    }
}
