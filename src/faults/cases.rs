//! One fault case's verdict: a run resumed from the healthy run (or run
//! from power-up, the reference), handed on to a later onset of the same
//! faults when it comes back in step with the healthy run.

use std::collections::HashMap;

use super::{AS_WITHOUT, Outcome, judge, phases};
use crate::simulate::{Checkpoints, Fault, Resumed, SimReport, SimSettings, Simulator};

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

/// What every case of one analysis shares.
pub(super) struct Cases<'s, 'a> {
    pub(super) simulator: &'s Simulator<'a>,
    /// The settings of every faulty run but its faults and their onset.
    pub(super) settings: SimSettings,
    /// The healthy run's checkpoints and inputs, when runs are resumed.
    pub(super) resumed: Option<(&'s Checkpoints<'s>, &'s phases::HealthyInputs)>,
}

impl Cases<'_, '_> {
    /// The verdict on `faults` appearing at `onset`, remembered in `memo`
    /// (by onset) with the verdicts of the later onsets it turned out to
    /// share.
    pub(super) fn verdict(
        &self,
        faults: &[Fault],
        onset: u64,
        memo: &mut HashMap<u64, Verdict>,
    ) -> Verdict {
        let mut chain = Vec::new();
        let mut at = onset;
        let columns = self
            .resumed
            .map(|(_, inputs)| inputs.columns(faults))
            .unwrap_or_default();
        let verdict = loop {
            if let Some(known) = memo.get(&at) {
                break known.clone();
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
                break Verdict::of(&self.simulator.run(&run));
            };
            let in_step = |t| inputs.divergence_of(&columns, t) != Some(t);
            match self.simulator.resume(checkpoints, &run, &in_step) {
                Resumed::Report(report) => break Verdict::of(&report),
                // From here the run is the healthy one until the faulty
                // input next differs: the case of the faults appearing then.
                Resumed::InStep { at_ms } => match inputs.divergence_of(&columns, at_ms) {
                    Some(next) => at = next,
                    None => {
                        break Verdict {
                            outcome: Outcome::NoEffect,
                            step: None,
                            explanation: AS_WITHOUT.to_string(),
                            detected: checkpoints.report.alarmed,
                        };
                    }
                },
            }
        };
        for at in chain {
            memo.insert(at, verdict.clone());
        }
        verdict
    }
}
