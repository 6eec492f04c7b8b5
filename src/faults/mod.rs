//! Sensor faults (Quezada et al. 2016; DESIGN §6): every input stuck at 1
//! (short circuit) or at 0 (open circuit), alone or up to four at once, appearing at
//! power-up and at every phase of the cycle, and classified as no effect,
//! safe stall or hazard.

mod cases;
mod healthy;
pub mod mitigation;
mod phases;
mod plan;
pub mod search;
mod single_step;
#[cfg(test)]
mod step_tests;

pub use healthy::{Healthy, healthy_run, healthy_run_recording};
pub use phases::{Moment, Phase, moments};

use crate::program::{Signal, StepProgram};
use crate::simulate::{Fault, ProblemKind, SimReport, SimSettings};
use crate::table::StepTable;
use cases::{SetRuns, Verdict};
use healthy::untraced_yardstick;
use plan::{Plan, distinct_onsets};

/// What a fault does to the machine.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Outcome {
    /// The machine runs its cycles as without the fault.
    NoEffect,
    /// The sequence waits at a step and nothing moves.
    SafeStall,
    /// Something moves that should not, too early, or a valve sees both coils.
    Hazard,
}

impl Outcome {
    pub fn label(self) -> &'static str {
        match self {
            Outcome::NoEffect => "no effect",
            Outcome::SafeStall => "safe stall",
            Outcome::Hazard => "hazard",
        }
    }
}

/// One fault set, made to appear at every moment of the cycle: the worst
/// of what it does.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FaultCase {
    pub faults: Vec<Fault>,
    /// The worst outcome over every moment the faults appeared at.
    pub outcome: Outcome,
    /// The first moment that gives it.
    pub phase: Phase,
    /// The SFC step the machine is in when the finding the explanation
    /// names first happens (see [`judge`]).
    pub step: Option<usize>,
    pub explanation: String,
    /// An alarm output came on in that run: the machine said so.
    pub detected: bool,
    /// The outcome at each of the table's moments, in their order.
    pub outcomes: Vec<Outcome>,
}

impl FaultCase {
    /// How many moments the faults give a hazard at.
    pub fn hazard_moments(&self) -> usize {
        self.outcomes
            .iter()
            .filter(|o| **o == Outcome::Hazard)
            .count()
    }

    /// `x11 short circuit (stuck at 1) + x20 open circuit (stuck at 0)`.
    pub fn fault_text(&self) -> String {
        self.fault_text_as(&|s: Signal| s.symbol())
    }

    /// The same with each signal called as `name` says.
    pub fn fault_text_as(&self, name: &dyn Fn(Signal) -> String) -> String {
        self.faults
            .iter()
            .map(|f| f.describe_as(name(f.signal)))
            .collect::<Vec<_>>()
            .join(" + ")
    }
}

/// All fault cases of one program.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FaultTable {
    pub cases: Vec<FaultCase>,
    /// The moments each fault set was made to appear at.
    pub moments: Vec<Moment>,
    /// Simulations run: the (fault set, moment) cases left once those that
    /// give the same run are merged and those that change nothing dropped.
    pub runs: usize,
    /// Set, to their number, when the cases at every moment times the
    /// steps each runs through would have been more than [`MAX_PHASE_WORK`]:
    /// faults then appear at power-up only.
    pub phases_skipped: Option<usize>,
    /// Sets of several faults left out because one of their faults never
    /// reads other than the healthy input: each is a smaller set.
    pub equivalent: usize,
}

impl FaultTable {
    /// How many cases have each outcome.
    pub fn count(&self, outcome: Outcome) -> usize {
        self.cases.iter().filter(|c| c.outcome == outcome).count()
    }

    /// `24 fault case(s) at 18 moments of the cycle (132 runs): 10 no
    /// effect, 8 safe stall, 6 hazard`.
    pub fn summary(&self) -> String {
        let reach = match self.phases_skipped {
            Some(cases) => format!(
                "from power-up only ({cases} cases at every moment of this long cycle are beyond the budget)"
            ),
            None => format!("at {} moments of the cycle", self.moments.len()),
        };
        let merged = match self.equivalent {
            0 => String::new(),
            n => format!(
                "; {n} set(s) left out, each holding a fault that never reads other than without it"
            ),
        };
        format!(
            "{} fault case(s) {reach} ({} runs{merged}): {} no effect, {} safe stall, {} hazard",
            self.cases.len(),
            self.runs,
            self.count(Outcome::NoEffect),
            self.count(Outcome::SafeStall),
            self.count(Outcome::Hazard)
        )
    }
}

/// The most work the faults at every moment may take, in (fault set,
/// moment) cases times the steps of the cycle (about a second): past it,
/// faults appear at power-up only, and the summary says so.
pub const MAX_PHASE_WORK: usize = 1_000_000;

/// The most steps one fault analysis may fire, over all its runs (about
/// ten seconds of work): faulty runs from power-up go through every cycle,
/// each jump's too.
pub const MAX_FAULT_STEPS: usize = 10_000_000;

/// Why the fault analysis of `program` with `at_once` faults is beyond
/// the budget, when it is: the count and what to do instead (E033).
/// Counted before any simulation: each case from power-up fires up to
/// every step of every cycle, a jump's cycles included.
pub fn over_budget(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    at_once: usize,
) -> Option<String> {
    let cases = case_count(program, at_once);
    let run = crate::simulate::run_steps(table, program, settings);
    let steps = cases.saturating_mul(run);
    let jumps: usize = table.steps.iter().map(|s| s.jumps.len()).sum();
    (steps > MAX_FAULT_STEPS).then(|| {
        format!(
            "the fault analysis would fire {steps} steps ({cases} fault cases, each run through {run} steps: {} plain cycles and {jumps} jump cycles of up to {} steps); steptable fires at most {MAX_FAULT_STEPS}: split the table, or give it fewer jumps",
            settings.cycles.max(1),
            program.steps.len()
        )
    })
}

/// Every single fault of every input (START, each sensor, machine inputs
/// and buttons), in address order.
pub fn single_faults(program: &StepProgram) -> Vec<Fault> {
    program
        .signals
        .inputs
        .iter()
        .flat_map(|&signal| [true, false].map(|stuck_at| Fault { signal, stuck_at }))
        .collect()
}

/// The most fault cases one analysis runs: every pair of a large table's
/// faults grows with the square of its inputs (2,049 single faults make two
/// million pairs, hours of simulation), so more is refused up front.
pub const MAX_CASES: usize = 100_000;

/// The most faults one case may hold (`faults --faults K`).
pub const MAX_AT_ONCE: usize = 4;

/// Every fault set to simulate: each single fault and, up to `at_once`
/// faults in a set, every combination of faults on different inputs
/// (singles first, then pairs, …, each in address order).
pub fn fault_sets(program: &StepProgram, at_once: usize) -> Vec<Vec<Fault>> {
    let singles = single_faults(program);
    let mut sets: Vec<Vec<Fault>> = singles.iter().map(|f| vec![*f]).collect();
    let mut last: Vec<(Vec<Fault>, usize)> =
        (0..singles.len()).map(|i| (vec![singles[i]], i)).collect();
    for _ in 1..at_once.clamp(1, MAX_AT_ONCE) {
        let mut next = Vec::new();
        for (set, after) in &last {
            for (j, f) in singles.iter().enumerate().skip(after + 1) {
                if set.iter().all(|g| g.signal != f.signal) {
                    let mut bigger = set.clone();
                    bigger.push(*f);
                    next.push((bigger, j));
                }
            }
        }
        sets.extend(next.iter().map(|(set, _)| set.clone()));
        last = next;
    }
    sets
}

/// How many cases [`fault_sets`] makes, without making them: for each size
/// j up to `at_once`, the ways to choose j of the n inputs times the two
/// stuck values of each.
pub fn case_count(program: &StepProgram, at_once: usize) -> usize {
    let n = program.signals.inputs.len();
    let mut total = 0usize;
    let mut choose = 1usize; // C(n, j), built up j by j
    for j in 1..=at_once.clamp(1, MAX_AT_ONCE) {
        choose = choose.saturating_mul(n.saturating_sub(j - 1)) / j;
        total = total.saturating_add(choose.saturating_mul(1 << j));
    }
    total
}

/// Simulates each fault set and classifies it.
pub fn analyse(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    at_once: usize,
) -> FaultTable {
    analyse_observed(table, program, settings, at_once, &|_, _| {})
}

/// How the fault analysis runs each case.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FaultRuns {
    /// From a copy of the healthy run where the fault appears, stopping as
    /// soon as the run is back in step with the healthy one (its state and
    /// inputs the same): the rest is the case of the same fault appearing
    /// when its input next differs, or no effect. A run also stops where an
    /// earlier run of the same faults stood at one of their onsets: the
    /// rest is that run's.
    #[default]
    Resumed,
    /// Each from power-up to its end: the plain reference the resumed runs
    /// are tested against.
    FromPowerUp,
}

/// Like [`analyse`], on every core, calling `progress(done, total)` after
/// each case (from any thread) so that a long analysis can be shown.
pub fn analyse_observed(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    at_once: usize,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> FaultTable {
    analyse_runs(
        table,
        program,
        settings,
        at_once,
        FaultRuns::Resumed,
        progress,
    )
}

/// Like [`analyse_observed`], running the cases as `runs` says.
pub fn analyse_runs(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    at_once: usize,
    runs: FaultRuns,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> FaultTable {
    analyse_from(table, program, settings, at_once, runs, progress, None)
}

/// Like [`analyse_runs`], measured against `healthy` ([`healthy_run`] under
/// the same settings) when it is given, else against a run of its own.
pub fn analyse_from(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    at_once: usize,
    runs: FaultRuns,
    progress: &(dyn Fn(usize, usize) + Sync),
    healthy: Option<Healthy>,
) -> FaultTable {
    let sets = fault_sets(program, at_once);
    analyse_sets(table, program, settings, sets, runs, progress, healthy)
}

/// Like [`analyse_from`], for the fault sets given rather than every set of
/// up to so many faults.
pub fn analyse_sets(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    sets: Vec<Vec<Fault>>,
    runs: FaultRuns,
    progress: &(dyn Fn(usize, usize) + Sync),
    healthy: Option<Healthy>,
) -> FaultTable {
    let counted = sets.len();
    let plan = Plan::new(table, program, settings, sets, counted, runs, healthy, true);
    let planned = distinct_onsets(&plan.onsets);
    let total = planned.iter().map(Vec::len).sum();
    let done = std::sync::atomic::AtomicUsize::new(0);
    let mut runs: Vec<SetRuns> = plan.sets.iter().map(|_| SetRuns::default()).collect();
    let copies = plan.copies(&planned, true, false);
    plan.run(
        copies.as_ref(),
        &planned,
        &planned,
        &mut runs,
        &|_| false,
        &|| {
            let n = done.fetch_add(1, std::sync::atomic::Ordering::Relaxed) + 1;
            progress(n, total);
        },
    );
    let mut cases: Vec<FaultCase> = (0..plan.sets.len())
        .map(|i| worst_case(&plan, i, &runs[i]))
        .collect();
    if let Some(case) = cases.iter_mut().find(|c| c.faults == [single_step::SHORT])
        && let Some((step, explanation)) = single_step::step_button_hazard(table, program, settings)
    {
        case.outcome = Outcome::Hazard;
        case.step = Some(step);
        case.explanation = explanation;
        case.outcomes.fill(Outcome::Hazard);
    }
    FaultTable {
        cases,
        moments: plan.moments,
        runs: total,
        phases_skipped: plan.phases_skipped,
        equivalent: plan.equivalent,
    }
}

/// Set `i`'s case: the worst verdict over the moments its faults appeared
/// at (its onsets, the scan its run left the healthy one, per moment;
/// `None`: it never did), with the outcome at every moment; each onset's
/// verdict in `runs`.
fn worst_case(plan: &Plan<'_>, i: usize, runs: &SetRuns) -> FaultCase {
    let (faults, moments, onsets) = (&plan.sets[i], &plan.moments, &plan.onsets[i]);
    let no_effect = Verdict {
        outcome: Outcome::NoEffect,
        step: None,
        explanation: "the input never reads other than without the fault".to_string(),
        detected: false,
    };
    // Read nowhere while it differs: the run is the healthy one.
    let unread = cases::as_without(plan.healthy_alarmed);
    let mut outcomes = Vec::with_capacity(moments.len());
    let mut worst: Option<(Phase, &Verdict)> = None;
    for (moment, onset) in moments.iter().zip(onsets) {
        let verdict = match onset {
            None => &no_effect,
            Some(phases::NEVER) => &unread,
            Some(d) => runs.at(*d).expect("every planned onset is run"),
        };
        outcomes.push(verdict.outcome);
        if worst.is_none_or(|(_, w)| verdict.outcome > w.outcome) {
            worst = Some((moment.phase, verdict));
        }
    }
    let (phase, verdict) = worst.unwrap_or((Phase::PowerUp, &no_effect));
    FaultCase {
        faults: faults.to_vec(),
        outcome: verdict.outcome,
        phase,
        step: verdict.step,
        explanation: verdict.explanation.clone(),
        detected: verdict.detected,
        outcomes,
    }
}

/// Why a fault has no effect, when its run is the healthy one's.
pub(crate) const AS_WITHOUT: &str = "the cycle runs as without the fault";

/// The verdict on one faulty run: its outcome, the step concerned and why.
/// A hazard is the first the sequence shows (a move too early, motion no
/// step commands, both coils, a start without START) or a combination of
/// positions the healthy cycle never has; the explanation gives the
/// sequence's reason first (the stall, the early step) and then the
/// combination. A collision found after the first sequence hazard is not
/// part of the verdict: a run may stop at that hazard.
///
/// The step given is the SFC step the machine is in (0 at rest, k while
/// table step k's moves run) when the finding the explanation names first
/// happens: the step a move started too early enters, the step a run
/// stalls in, the step during which a collision comes about.
pub fn judge(report: &SimReport) -> (Outcome, Option<usize>, String) {
    let sequence = report
        .problems
        .iter()
        .find(|p| p.kind.is_hazard() && p.kind != ProblemKind::Collision);
    let collision = report
        .problems
        .iter()
        .find(|p| p.kind == ProblemKind::Collision)
        .filter(|c| sequence.is_none_or(|s| c.time_ms <= s.time_ms));
    match (sequence, collision) {
        (Some(s), None) => (Outcome::Hazard, Some(s.step), s.message.clone()),
        (Some(s), Some(c)) => (
            Outcome::Hazard,
            Some(s.step),
            format!("{}; {}", s.message, c.message),
        ),
        (None, Some(c)) => match report.stalled_at {
            Some(step) => (
                Outcome::Hazard,
                Some(step),
                format!("{}; {}", report.reason(), c.message),
            ),
            None => (Outcome::Hazard, Some(c.step), c.message.clone()),
        },
        (None, None) => {
            if let Some(step) = report.stalled_at {
                return (Outcome::SafeStall, Some(step), report.reason());
            }
            let explanation = match report
                .problems
                .iter()
                .find(|p| p.kind == ProblemKind::CycleDiffers)
            {
                Some(p) => format!("runs, but {}", p.message),
                None => AS_WITHOUT.to_string(),
            };
            (Outcome::NoEffect, None, explanation)
        }
    }
}

/// The rows of the fault table: fault, outcome, when it appears, whether
/// an alarm came on, step, explanation; each signal called as `name` says
/// (its designation in the outputs), also in the explanation (`text`).
pub fn rows(
    table: &FaultTable,
    name: &dyn Fn(Signal) -> String,
    text: &dyn Fn(&str) -> String,
) -> Vec<[String; 6]> {
    table
        .cases
        .iter()
        .map(|c| {
            [
                c.fault_text_as(name),
                c.outcome.label().to_string(),
                c.appears(table.moments.len()),
                c.detected_text().to_string(),
                c.step.map(|s| s.to_string()).unwrap_or_default(),
                text(&c.explanation),
            ]
        })
        .collect()
}

impl FaultCase {
    /// `alarm` when an alarm output came on, else empty.
    pub fn detected_text(&self) -> &'static str {
        if self.detected { "alarm" } else { "" }
    }

    /// When the fault gives its outcome: `while step 3 moves (4 of 18
    /// moments)`, or `at every moment` when all give it.
    pub fn appears(&self, moments: usize) -> String {
        let giving = self.outcomes.iter().filter(|o| **o == self.outcome).count();
        if moments <= 1 {
            self.phase.label()
        } else if giving == moments {
            "at every moment".to_string()
        } else {
            format!("{} ({giving} of {moments} moments)", self.phase.label())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::program::{self, ProgramOptions};

    #[test]
    fn paper_single_faults_are_classified() {
        let table = crate::program::tests::paper_table();
        let program = program::build(
            &table,
            &ProgramOptions::default(),
            &crate::actuator::Valves::default(),
            &crate::stroke::Strokes::default(),
        );
        let result = analyse(&table, &program, &SimSettings::default(), 1);
        assert_eq!(result.cases.len(), 24);
        let case = |symbol: &str, stuck: bool| {
            result
                .cases
                .iter()
                .find(|c| c.faults[0].signal.symbol() == symbol && c.faults[0].stuck_at == stuck)
                .unwrap()
        };
        // START stuck at 1: the machine starts by itself.
        assert_eq!(case("START", true).outcome, Outcome::Hazard);
        // START stuck at 0: nothing ever starts.
        assert_eq!(case("START", false).outcome, Outcome::SafeStall);
        // x11 open: step 2 waits for ever, the machine stalls in step 1.
        assert_eq!(case("x11", false).outcome, Outcome::SafeStall);
        assert_eq!(case("x11", false).step, Some(1));
        // x11 short: step 2 starts while C1 is still moving.
        assert_eq!(case("x11", true).outcome, Outcome::Hazard);
        assert!(
            result
                .summary()
                .starts_with("24 fault case(s) at 17 moments of the cycle (")
        );
        // Open from power-up, x21 stalls step 4 (C2 never gets there); open
        // while step 4 moves C2 away from it, it is a collision risk.
        let x21 = case("x21", false);
        assert_eq!(x21.outcomes[0], Outcome::SafeStall);
        assert_eq!(x21.outcome, Outcome::Hazard);
        assert_eq!(x21.phase, Phase::Moving(4));
        assert!(
            x21.explanation.contains("collision risk"),
            "{}",
            x21.explanation
        );
        assert_eq!(x21.outcomes.len(), result.moments.len());
        // The count the budget is checked against is the count run.
        for at_once in 1..=MAX_AT_ONCE {
            assert_eq!(
                case_count(&program, at_once),
                fault_sets(&program, at_once).len(),
                "{at_once}"
            );
        }
        assert_eq!(case_count(&program, 2), 24 + 4 * 66);
        // 12 inputs: 220 ways to choose three, each with 8 stuck values.
        assert_eq!(case_count(&program, 3), 24 + 4 * 66 + 8 * 220);
        let triples = fault_sets(&program, 3);
        let distinct: std::collections::BTreeSet<&Vec<Fault>> = triples.iter().collect();
        assert_eq!(distinct.len(), triples.len(), "no set twice");
        assert!(triples.iter().all(|set| {
            set.windows(2)
                .all(|w| w[0].signal != w[1].signal && w[0] < w[1])
        }));
    }
}
