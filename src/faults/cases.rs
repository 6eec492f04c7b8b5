//! One fault case's verdict: a run resumed from the healthy run (or run
//! from power-up, the reference), handed on to a later onset of the same
//! faults when it comes back in step with the healthy run, and ended as an
//! earlier run of the same faults when it stands where that one stood.

use foldhash::HashMap;

use super::{AS_WITHOUT, Outcome, judge, phases};
use crate::simulate::{
    Checkpoints, Course, Fault, Resumed, SimReport, SimSettings, Simulator, Trail,
};

/// What one run of a fault set says.
#[derive(Debug, Clone)]
pub(super) struct Verdict {
    pub(super) outcome: Outcome,
    pub(super) step: Option<usize>,
    pub(super) explanation: String,
    pub(super) detected: bool,
}

impl Verdict {
    pub(super) fn of(report: &SimReport) -> Self {
        let (outcome, step, explanation) = judge(report);
        Verdict {
            outcome,
            step,
            explanation,
            detected: report.alarmed,
        }
    }
}

/// The verdict of a run that is the healthy one (whose alarms say
/// `detected`).
pub(super) fn as_without(detected: bool) -> Verdict {
    Verdict {
        outcome: Outcome::NoEffect,
        step: None,
        explanation: AS_WITHOUT.to_string(),
        detected,
    }
}

/// What every case of one analysis shares.
pub(super) struct Cases<'s, 'a> {
    pub(super) simulator: &'s Simulator<'a>,
    /// The settings of every faulty run but its faults and their onset.
    pub(super) settings: SimSettings,
    /// The healthy run's checkpoints and inputs, when runs are resumed.
    pub(super) resumed: Option<(&'s Checkpoints<'s>, &'s phases::HealthyInputs)>,
}

/// What the runs of one fault set have found so far: which verdict each
/// onset has, and the states the runs passed through with nothing found,
/// under the number of the verdict they led to.
#[derive(Default)]
pub(super) struct SetRuns {
    by_onset: HashMap<u64, usize>,
    verdicts: Vec<Verdict>,
    trail: Trail,
}

impl SetRuns {
    /// The verdict on the faults appearing at `onset`, once run.
    pub(super) fn at(&self, onset: u64) -> Option<&Verdict> {
        self.by_onset.get(&onset).map(|&i| &self.verdicts[i])
    }
}

impl Cases<'_, '_> {
    /// Runs `faults` appearing at `onset` unless `runs` already knows the
    /// verdict, and keeps it there (with the later onsets the run turned
    /// out to share, and the states it passed through at `onsets`, all the
    /// onsets planned for these faults, in order).
    pub(super) fn verdict(&self, faults: &[Fault], onset: u64, onsets: &[u64], runs: &mut SetRuns) {
        enum Found {
            New(Verdict),
            Known(usize),
        }
        let mut chain = Vec::new();
        let mut passed = Vec::new();
        let mut at = onset;
        let columns = self
            .resumed
            .map(|(_, inputs)| inputs.columns(faults))
            .unwrap_or_default();
        let found = loop {
            if let Some(&known) = runs.by_onset.get(&at) {
                break Found::Known(known);
            }
            chain.push(at);
            let run = SimSettings {
                faults: faults.to_vec(),
                fault_onset_ms: at,
                record_trace: false,
                stop_at_hazard: true,
                ..self.settings.clone()
            };
            let Some((checkpoints, inputs)) = self.resumed else {
                break Found::New(Verdict::of(&self.simulator.run(&run)));
            };
            let in_step = |t| inputs.divergence_of(&columns, t) != Some(t);
            let course = Course {
                checkpoints,
                in_step: &in_step,
                trail: &runs.trail,
                marks: onsets,
            };
            match self.simulator.resume(&course, &run, &mut passed) {
                Resumed::Report(report) => break Found::New(Verdict::of(&report)),
                Resumed::Joined { run } => break Found::Known(run),
                // From here the run is the healthy one until the faulty
                // input next differs: the case of the faults appearing then.
                Resumed::InStep { at_ms } => match inputs.divergence_of(&columns, at_ms) {
                    Some(next) => at = next,
                    None => break Found::New(as_without(checkpoints.report.alarmed)),
                },
            }
        };
        let index = match found {
            Found::Known(index) => index,
            Found::New(verdict) => {
                runs.verdicts.push(verdict);
                runs.verdicts.len() - 1
            }
        };
        for at in chain {
            runs.by_onset.insert(at, index);
        }
        for point in passed {
            runs.trail.entry(point).or_insert(index);
        }
    }
}
