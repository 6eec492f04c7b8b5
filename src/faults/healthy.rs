//! The healthy run the fault analysis is measured against, made once: a
//! conversion proves its program with it and hands it on, so that the
//! cycle is not simulated again from power-up for the fault table.

use crate::program::StepProgram;
use crate::simulate::io::{InputLog, IoSignals, IoTrace};
use crate::simulate::{SimReport, SimSettings, Simulator};
use crate::table::StepTable;

/// The healthy run the fault analysis measures every faulty run against:
/// its report with the combinations of positions it reached, and when each
/// input changed. A conversion proves its program with this very run
/// ([`healthy_run`]) and hands it on, so that the cycle is not simulated
/// again from power-up for the fault table.
#[derive(Clone)]
pub struct Healthy {
    pub report: SimReport,
    pub log: InputLog,
}

/// The settings of the healthy run the analysis under `settings` needs:
/// no faults, the places recorded (a trace changes nothing the analysis
/// reads, so a proof that records one for the diagram serves too).
pub(super) fn yardstick_settings(settings: &SimSettings) -> SimSettings {
    SimSettings {
        record_places: true,
        faults: Vec::new(),
        fault_onset_ms: 0,
        ..settings.clone()
    }
}

/// [`yardstick_settings`] without the trace: the healthy run an analysis
/// makes for itself, and copies, draws nothing.
pub(super) fn untraced_yardstick(settings: &SimSettings) -> SimSettings {
    SimSettings {
        record_trace: false,
        ..yardstick_settings(settings)
    }
}

/// Runs `program` healthy under `settings`, as the fault analysis needs it
/// and as the proof of a conversion does: the same report, with the places
/// it reached and the log of its inputs beside it.
pub fn healthy_run(table: &StepTable, program: &StepProgram, settings: &SimSettings) -> Healthy {
    healthy_run_recording(table, program, settings, None).0
}

/// [`healthy_run`], also recording `signals` and the positions at every
/// scan when given (the report's timeline): the same one run.
pub fn healthy_run_recording(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    signals: Option<IoSignals>,
) -> (Healthy, Option<IoTrace>) {
    let run =
        Simulator::new(table, program).run_recorded(&yardstick_settings(settings), signals, true);
    let healthy = Healthy {
        report: run.report,
        log: run.log.unwrap_or_default(),
    };
    (healthy, run.trace)
}
