//! Scripted runs for the operating modes: the operator presses STOP, the
//! EMERGENCY STOP or RESET at given times, and the run records what the
//! machine did scan by scan. The standard proof ([`super::simulate`]) only
//! ever presses START; this shows what the other buttons do.

use crate::program::Signal;
use crate::program::StepProgram;
use crate::table::StepTable;

use super::plant::Piston;
use super::plc::PlcProgram;
use super::run::Run;
use super::{Operator, Problem, SimSettings};

/// The machine at the end of one scan.
#[derive(Debug, Clone, PartialEq)]
pub struct Sample {
    pub time_ms: u64,
    /// Positions in sensor units, in table order.
    pub positions: Vec<f64>,
    /// Outputs switched on (coils, machine outputs, alarms).
    pub outputs_on: Vec<Signal>,
    /// The step the program is in (its `active_step`): 0 at rest, k while
    /// table step k's moves run.
    pub step: usize,
    /// Homing runs (the `homing` memory is set).
    pub homing: bool,
}

/// What a scripted run did.
#[derive(Debug, Clone, PartialEq)]
pub struct ScenarioReport {
    /// `(time_ms, step number)` of every step that fired.
    pub fired: Vec<(u64, usize)>,
    /// One sample per scan.
    pub samples: Vec<Sample>,
    /// Problems the run checks found (motion outside a step is expected
    /// while homing).
    pub problems: Vec<Problem>,
}

impl ScenarioReport {
    /// The sample at or just after `time_ms`.
    pub fn at(&self, time_ms: u64) -> Option<&Sample> {
        self.samples.iter().find(|s| s.time_ms >= time_ms)
    }

    /// Times at which STEP 1 fired: the starts of the cycles.
    pub fn cycle_starts(&self) -> Vec<u64> {
        self.fired
            .iter()
            .filter(|(_, step)| *step == 1)
            .map(|(t, _)| *t)
            .collect()
    }
}

/// Runs `program` from power-up for `until_ms`, with the operator's buttons
/// as `script` says: each entry gives the buttons' state from its time on.
pub fn scenario(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    script: &[(u64, Operator)],
    until_ms: u64,
) -> ScenarioReport {
    run_script(table, program, settings, script, until_ms, None).0
}

/// Like [`scenario`], and records `signals` at every scan, so that the
/// written program can be replayed in its own engine with the operator's
/// presses (STOP, EMERGENCY STOP, RESET) and compared scan by scan.
pub fn scenario_recording(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    script: &[(u64, Operator)],
    until_ms: u64,
    signals: super::io::IoSignals,
) -> (ScenarioReport, super::io::IoTrace) {
    let (report, trace) = run_script(table, program, settings, script, until_ms, Some(signals));
    (report, trace.unwrap_or_default())
}

fn run_script(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    script: &[(u64, Operator)],
    until_ms: u64,
    record: Option<super::io::IoSignals>,
) -> (ScenarioReport, Option<super::io::IoTrace>) {
    let code = PlcProgram::compile(program);
    let mut run = Run::new(table, program, &code, settings);
    run.io = record.map(|signals| super::io::IoTrace::new(run.world.settings.scan_ms, signals));
    let outputs: Vec<(usize, Signal)> = program
        .steps
        .iter()
        .flat_map(|s| &s.actions)
        .chain(program.rungs.iter().flat_map(|r| &r.actions))
        .map(|a| a.signal())
        .filter(|s| s.area() == crate::program::Area::Output)
        .filter_map(|s| run.plc.index_of(s).map(|i| (i, s)))
        .collect::<std::collections::BTreeMap<_, _>>()
        .into_iter()
        .collect();
    let mut fired = Vec::new();
    let mut samples = Vec::new();
    while run.time_ms < until_ms {
        if let Some((_, operator)) = script.iter().rev().find(|(t, _)| *t <= run.time_ms) {
            run.world.operator = *operator;
        }
        let before = run.time_ms;
        if let Some(index) = run.tick() {
            fired.push((before, program.steps[index].number));
        }
        samples.push(Sample {
            time_ms: run.time_ms,
            positions: run
                .world
                .pistons
                .iter()
                .map(Piston::position_units)
                .collect(),
            outputs_on: outputs
                .iter()
                .filter(|(i, _)| run.plc.bit_at(*i))
                .map(|(_, s)| *s)
                .collect(),
            step: program.step_in(run.plc.awaited),
            homing: run.plc.bit(Signal::Homing),
        });
    }
    let report = ScenarioReport {
        fired,
        samples,
        problems: run.problems,
    };
    (report, run.io)
}
