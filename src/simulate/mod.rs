//! Simulation: proof that a generated program runs the machine (DESIGN §5).
//!
//! A cyclic PLC scan (read inputs, execute the step program, write outputs)
//! runs against the plant model. An operator presses START, the program must
//! drive every step in order, every move must end at its target sensor without
//! running through it, nothing may move outside its step, no valve may see both
//! coils, everything must be home at the end, and a second START must run an
//! identical second cycle.

pub mod bench;
pub mod io;
pub mod plant;
pub mod plc;
pub mod report;
mod run;

pub use run::{Checkpoints, Course, Resumed, Trail};
pub mod scenario;
mod settings;
mod world;

use crate::program::StepProgram;
use crate::table::StepTable;

pub use report::*;
pub use settings::*;

/// How a run advances through time. Both give the same report, scan for
/// scan; the stepper is the plain reference the event-driven run is tested
/// against.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Stepping {
    /// Every scan that can change something runs; scans in which nothing
    /// can (no input, timer or position crosses a threshold) pass at once.
    #[default]
    Events,
    /// Every scan runs.
    EveryScan,
}

/// The most steps one proof may fire (about three seconds of work): its
/// plain cycles and one cycle per jump, each of up to every step, so a
/// table of many steps and many jumps grows with their product.
pub const MAX_PROOF_STEPS: usize = 2_000_000;

/// The steps a run of `program` fires at most: every step in each plain
/// cycle and in each jump's cycle. The unit the budgets count in.
pub fn run_steps(table: &StepTable, program: &StepProgram, settings: &SimSettings) -> usize {
    let jumps: usize = table.steps.iter().map(|s| s.jumps.len()).sum();
    program
        .steps
        .len()
        .saturating_mul(settings.cycles.max(1) + jumps)
}

/// Why a proof of `program` is beyond the budget, when it is: the count
/// and what to do instead (error E033).
pub fn over_budget(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
) -> Option<String> {
    let steps = run_steps(table, program, settings);
    (steps > MAX_PROOF_STEPS).then(|| {
        let jumps: usize = table.steps.iter().map(|s| s.jumps.len()).sum();
        format!(
            "proving this table would fire {steps} steps ({} steps in each of {} plain cycles and {jumps} jump cycles, one per jump); steptable fires at most {MAX_PROOF_STEPS}: split the table, or give it fewer jumps",
            program.steps.len(),
            settings.cycles.max(1)
        )
    })
}

/// Simulates `program` (built from `table`) against the plant.
pub fn simulate(table: &StepTable, program: &StepProgram, settings: &SimSettings) -> SimReport {
    simulate_stepping(table, program, settings, Stepping::Events)
}

/// Simulates like [`simulate`], advancing through time as `stepping` says.
pub fn simulate_stepping(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    stepping: Stepping,
) -> SimReport {
    Simulator::new(table, program).run_stepping(settings, stepping)
}

/// A program ready to be simulated many times under different settings
/// (the fault analysis): it is compiled once.
pub struct Simulator<'a> {
    table: &'a StepTable,
    program: &'a StepProgram,
    code: plc::PlcProgram,
}

/// A run kept beyond its report ([`Simulator::run_recorded`]).
pub struct Recorded {
    pub report: SimReport,
    /// When each of the program's inputs changed, when logged.
    pub log: Option<io::InputLog>,
    /// The signals and positions of every scan, when recorded.
    pub trace: Option<io::IoTrace>,
}

impl<'a> Simulator<'a> {
    pub fn new(table: &'a StepTable, program: &'a StepProgram) -> Self {
        Simulator {
            table,
            program,
            code: plc::PlcProgram::compile(program),
        }
    }

    /// The same as [`simulate`].
    pub fn run(&self, settings: &SimSettings) -> SimReport {
        self.run_stepping(settings, Stepping::Events)
    }

    fn run_stepping(&self, settings: &SimSettings, stepping: Stepping) -> SimReport {
        run::run(
            self.table,
            self.program,
            &self.code,
            settings,
            None,
            stepping,
        )
        .0
    }

    /// Runs under `settings` from power-up to the end, copying the run at
    /// each of `times` (scan times) for [`Simulator::resume`], and
    /// fingerprinting it at every scan, or only at `times` and `marks`
    /// (sorted) when they are given; when `log_inputs`, also logging when
    /// each input changes (the run is then a healthy run as
    /// [`Simulator::run_recorded`] makes it, its log in `log`).
    pub fn checkpoints(
        &self,
        settings: &SimSettings,
        times: &[u64],
        marks: Option<&[u64]>,
        log_inputs: bool,
    ) -> Checkpoints<'_> {
        let inputs = log_inputs.then(|| self.program.signals.inputs.clone());
        run::checkpoints(
            (self.table, self.program, &self.code),
            settings,
            times,
            marks,
            inputs,
        )
    }

    /// Runs under `settings`, whose faults appear at
    /// `settings.fault_onset_ms`, from the copy of the checkpointed run at
    /// that time (from power-up when there is none): the same report as
    /// [`Simulator::run`]. When the checkpointed run passed, it stops early
    /// at a later scan at which the course's `in_step` holds and it stands
    /// exactly where that run stood, nothing found yet ([`Resumed::InStep`]);
    /// and it stops where it stands as an earlier run on the course's
    /// trail stood ([`Resumed::Joined`]). The states it passed through,
    /// nothing found yet, are added to `passed`, for the trail of the runs
    /// after it.
    pub fn resume(
        &self,
        course: &Course<'_, '_>,
        settings: &SimSettings,
        passed: &mut Vec<(u64, u64)>,
    ) -> Resumed {
        run::resume(
            course,
            self.table,
            self.program,
            &self.code,
            settings,
            passed,
        )
    }

    /// Runs under `settings` as [`Simulator::run`] does, recording
    /// `signals` and the positions at every scan when given (a report's
    /// timeline), and logging the scans on which the program's inputs
    /// change when `log_inputs` (the fault analysis's healthy run): the one
    /// entry for a healthy run kept beyond its report, whether a
    /// conversion's proof, the fault table's yardstick or both.
    pub fn run_recorded(
        &self,
        settings: &SimSettings,
        signals: Option<io::IoSignals>,
        log_inputs: bool,
    ) -> Recorded {
        let settings = SimSettings {
            record_trace: settings.record_trace || signals.is_some(),
            ..settings.clone()
        };
        let inputs = log_inputs.then(|| self.program.signals.inputs.clone());
        let (report, log, trace) = run::run_logging_inputs(
            self.table,
            self.program,
            &self.code,
            &settings,
            inputs,
            signals,
            Stepping::Events,
        );
        Recorded { report, log, trace }
    }

    /// The same as [`simulate_recording`].
    pub fn run_recording(
        &self,
        settings: &SimSettings,
        signals: io::IoSignals,
    ) -> (SimReport, io::IoTrace) {
        let (report, trace) = run::run(
            self.table,
            self.program,
            &self.code,
            settings,
            Some(signals),
            Stepping::Events,
        );
        (report, trace.unwrap_or_default())
    }
}

/// Simulates like [`simulate`] and records `signals` at every scan, so that
/// a written program can be replayed in its own engine and compared.
pub fn simulate_recording(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    signals: io::IoSignals,
) -> (SimReport, io::IoTrace) {
    Simulator::new(table, program).run_recording(settings, signals)
}

#[cfg(test)]
mod tests;
