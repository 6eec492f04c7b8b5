//! What every analysis of some fault sets on one program shares: the
//! healthy run it is measured against, the moments the faults appear at,
//! and each set's onset at each moment (the scan its run leaves the healthy
//! one). The runs themselves are made on demand, from checkpoints of the
//! healthy run at the onsets asked for: the fault table runs every onset,
//! a mitigation's trial only until its first hazard.

use super::cases::{Cases, SetRuns, Verdict};
use super::healthy::untraced_yardstick;
use super::phases::{self, Moment, moments};
use super::{FaultRuns, Healthy, MAX_PHASE_WORK, healthy_run};
use crate::program::StepProgram;
use crate::simulate::io::InputLog;
use crate::simulate::{Checkpoints, Fault, SimReport, SimSettings, Simulator};
use crate::table::StepTable;

/// Fault sets on one program, their moments and onsets, before any run.
pub(super) struct Plan<'t> {
    table: &'t StepTable,
    simulator: Simulator<'t>,
    /// The healthy run's settings (its checkpoints are made under them).
    healthy_settings: SimSettings,
    /// The settings of every faulty run but its faults and their onset.
    run_settings: SimSettings,
    pub(super) moments: Vec<Moment>,
    /// The healthy run's inputs, when faults appear at every moment.
    inputs: Option<phases::HealthyInputs>,
    pub(super) sets: Vec<Vec<Fault>>,
    /// Each set at each moment, as the moment its run leaves the healthy
    /// one (`None`: it never does).
    pub(super) onsets: Vec<Vec<Option<u64>>>,
    /// Sets left out: a fault of theirs never reads otherwise.
    pub(super) equivalent: usize,
    /// The cases at every moment, when they were beyond the budget.
    pub(super) phases_skipped: Option<usize>,
    /// Runs resume from the healthy run's checkpoints.
    pub(super) resumable: bool,
    /// An alarm came on in the healthy run.
    pub(super) healthy_alarmed: bool,
}

impl<'t> Plan<'t> {
    /// The plan of `sets` on `program`, measured against `healthy`
    /// ([`healthy_run`] under the same settings) when it is given. Whether
    /// faults appear at every moment or at power-up only is decided on
    /// `counted` sets: those of the whole table the sets belong to, so that
    /// a few of its sets run again are run as in the table. When `by_reads`
    /// and the runs resume from the healthy run, a fault's onset is where
    /// the healthy run reads its input while it differs (the healthy log's
    /// reads are then the program's own).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn new(
        table: &'t StepTable,
        program: &'t StepProgram,
        settings: &SimSettings,
        mut sets: Vec<Vec<Fault>>,
        counted: usize,
        runs: FaultRuns,
        healthy: Option<Healthy>,
        by_reads: bool,
    ) -> Plan<'t> {
        // What the healthy cycle does is the yardstick: the combinations of
        // positions it reaches are the ones a faulty run may reach, its
        // moments are when faults appear, its inputs tell which of those
        // runs are one and the same. Its log says when each input changes:
        // a log, not a copy of every scan (a long table has millions).
        let healthy_settings = untraced_yardstick(settings);
        let Healthy {
            report: healthy,
            log,
        } = healthy.unwrap_or_else(|| healthy_run(table, program, &healthy_settings));
        let mut moments = moments(&healthy, table, settings.scan_ms as u64);
        let cases_at_every_moment = counted.max(sets.len()) * moments.len();
        // A jump's cycle is one more cycle each run may go through.
        let jumps: usize = table.steps.iter().map(|s| s.jumps.len()).sum();
        let too_long = cases_at_every_moment
            .saturating_mul(table.steps.len().max(1))
            .saturating_mul(1 + jumps)
            > MAX_PHASE_WORK;
        let mut equivalent = 0;
        // A copy of a healthy run that found problems carries them (and the
        // alarms after them) into every run resumed from it, which a faulty
        // run judged at its first hazard never reaches: such a table's runs
        // go from power-up.
        let resumable = !too_long && runs == FaultRuns::Resumed && healthy.problems.is_empty();
        // Faults at every moment but for a cycle too long for them.
        let inputs = (!too_long).then(|| match by_reads && resumable && log.reads_logged {
            true => phases::HealthyInputs::by_reads(log),
            false => phases::HealthyInputs::new(log),
        });
        let onsets: Vec<Vec<Option<u64>>> = match &inputs {
            None => {
                moments.truncate(1);
                sets.iter().map(|_| vec![Some(0)]).collect()
            }
            Some(inputs) => {
                // A fault that never reads other than the healthy input
                // (STOP stuck at 1: it is normally closed) adds nothing to a
                // set: the set is the smaller one, already in the table.
                let inert = |f: &Fault| !inputs.differs(std::slice::from_ref(f), 0);
                let before = sets.len();
                sets.retain(|set| set.len() == 1 || !set.iter().any(inert));
                equivalent = before - sets.len();
                onsets_of(inputs, &sets, &moments)
            }
        };
        let run_settings = SimSettings {
            known_places: Some(std::sync::Arc::new(healthy.places)),
            ..settings.clone()
        };
        Plan {
            table,
            simulator: Simulator::new(table, program),
            healthy_settings,
            run_settings,
            moments,
            inputs,
            sets,
            onsets,
            equivalent,
            phases_skipped: too_long.then_some(cases_at_every_moment),
            resumable,
            healthy_alarmed: healthy.alarmed,
        }
    }

    /// The healthy run copied at the onsets `wanted` (per set) and, when
    /// `at_changes`, wherever an input changes: a run back in step with it
    /// goes on from where its faulty input next differs, which a run that
    /// goes through every onset does often (elsewhere a run starts from the
    /// latest copy before its onset). When `log_inputs`, the run also logs
    /// its inputs (it is then a healthy run of its own). `None` when runs go
    /// from power-up.
    pub(super) fn copies(
        &self,
        wanted: &[Vec<u64>],
        at_changes: bool,
        log_inputs: bool,
    ) -> Option<Checkpoints<'_>> {
        let inputs = self.inputs.as_ref().filter(|_| self.resumable)?;
        let times: Vec<u64> = wanted
            .iter()
            .flatten()
            .copied()
            .chain(inputs.change_times().filter(|_| at_changes))
            .collect();
        // Copied only at the onsets, it is looked at where a run comes back
        // in step: where an input changes back to its faulty value.
        let marks = (!at_changes).then(|| {
            let mut marks: Vec<u64> = inputs.change_times().collect();
            marks.sort_unstable();
            marks
        });
        Some(self.simulator.checkpoints(
            &self.healthy_settings,
            &times,
            marks.as_deref(),
            log_inputs,
        ))
    }

    /// Runs each set's `wanted` onsets (in their order, the set's planned
    /// onsets `planned[i]`, earliest first, marking where its runs' states
    /// are kept) into `runs[i]`, from `copies` of the healthy run (from
    /// power-up without), until `enough` says a verdict ends the set's
    /// search; calls `progress` after each onset.
    pub(super) fn run(
        &self,
        copies: Option<&Checkpoints<'_>>,
        planned: &[Vec<u64>],
        wanted: &[Vec<u64>],
        runs: &mut [SetRuns],
        enough: &(dyn Fn(&Verdict) -> bool + Sync),
        progress: &(dyn Fn() + Sync),
    ) {
        use rayon::prelude::*;
        let cases = Cases {
            simulator: &self.simulator,
            settings: self.run_settings.clone(),
            resumed: copies.zip(self.inputs.as_ref()),
        };
        runs.par_iter_mut()
            .zip(wanted)
            .zip(planned)
            .zip(&self.sets)
            .for_each(|(((runs, wanted), planned), set)| {
                for &onset in wanted {
                    if runs.at(onset).is_none() {
                        cases.verdict(set, onset, planned, runs);
                    }
                    let verdict = runs.at(onset).expect("a run gives its onset a verdict");
                    let stop = enough(verdict);
                    progress();
                    if stop {
                        break;
                    }
                }
            });
    }

    /// Whether `healthy`, another run of this plan's program, is the run
    /// the plan was made from: the same inputs at the same times, so the
    /// same moments and onsets, and the same places reached.
    pub(super) fn made_from(&self, healthy: &SimReport, log: Option<&InputLog>) -> bool {
        let scan_ms = self.run_settings.scan_ms as u64;
        healthy.problems.is_empty()
            && log
                .zip(self.inputs.as_ref())
                .is_some_and(|(log, i)| log.same_inputs(i.log()))
            && self.run_settings.known_places.as_deref() == Some(&healthy.places)
            && moments(healthy, self.table, scan_ms) == self.moments
    }
}

/// Each set at each moment, as the moment its run leaves the healthy one.
fn onsets_of(
    inputs: &phases::HealthyInputs,
    sets: &[Vec<Fault>],
    moments: &[Moment],
) -> Vec<Vec<Option<u64>>> {
    sets.iter()
        .map(|set| {
            let columns = inputs.columns(set);
            let onset = |m: &Moment| inputs.onset_of(&columns, m.at_ms);
            moments.iter().map(onset).collect()
        })
        .collect()
}

/// Each set's distinct onsets, the earliest first: a later case whose
/// fault changed nothing until an earlier case's run stood where it stands
/// ends as that run, found on its trail.
pub(super) fn distinct_onsets(onsets: &[Vec<Option<u64>>]) -> Vec<Vec<u64>> {
    onsets
        .iter()
        .map(|at| {
            // An onset never read runs nothing.
            let run = at.iter().flatten().copied().filter(|d| *d != phases::NEVER);
            let mut distinct: Vec<u64> = run.collect();
            distinct.sort_unstable();
            distinct.dedup();
            distinct
        })
        .collect()
}
