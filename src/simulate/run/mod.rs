//! One run of the program against the plant, scan by scan: the state of
//! the run ([`Run`], its fields private to this module), one scan
//! (`scan.rs`), what each scan checks (`checks.rs`), the machine's side
//! (`machine.rs`), the operator's cycles (`cycle.rs`) and the fault
//! analysis's checkpoints (`checkpoint.rs`). The rest of the simulator
//! sees a run through [`run`], [`run_logging_inputs`], [`checkpoints`],
//! [`resume`] and, for a scripted scenario, the few methods below.

mod checkpoint;
mod checks;
mod cycle;
mod drive;
mod machine;
mod scan;

pub use checkpoint::{Checkpoints, Course, Resumed, Trail};
pub(super) use checkpoint::{checkpoints, resume};
pub(super) use cycle::{run, run_logging_inputs};

use super::plant::Piston;
use super::plc::PlcState;
use super::world::{InputSource, World, pistons, read_input};
use super::*;
use crate::cell::Name;
use crate::program::{Signal, StepProgram};
use crate::table::{Move, StepTable};

use checks::{literal_text, sensor_symbol};

/// A move in progress: set when its step fires.
#[derive(Debug, Clone)]
pub(super) struct ActiveMove {
    piston: usize,
    mv: Move,
    step: usize,
    reached: bool,
    ran_through: bool,
}

impl ActiveMove {
    /// The stroke fractions below and above which the piston has run
    /// through this move's target: beyond its sensor's window.
    pub(super) fn run_through_bounds(&self, piston: &Piston, window: f64) -> (f64, f64) {
        let target = piston.sensor_point(self.mv.to);
        let half = piston.window(window);
        (target - half, target + half)
    }
}

#[derive(Clone)]
pub(in crate::simulate) struct Run<'a> {
    program: &'a StepProgram,
    /// What the PLC's inputs read from: the plant, the operator, the machine.
    world: World,
    plc: PlcState<'a>,
    time_ms: u64,
    problems: Vec<Problem>,
    /// The moves of the step that fired last.
    active: Vec<ActiveMove>,
    /// Per piston, the last move commanded: it may finish settling into its
    /// target window after the next step has fired.
    last_move: Vec<Option<ActiveMove>>,
    pending: Vec<(u64, Name, bool)>,
    /// Inputs the machine gave for the step that fired last.
    answered: Vec<Name>,
    /// The jump the machine takes in the cycle under way: the index of its
    /// step and the jump (its input given once that step has fired).
    jump_taken: Option<(usize, crate::table::Jump)>,
    /// The machine has given that jump's input in this cycle (once: a
    /// jump back must not loop for ever).
    jump_given: bool,
    /// The jumps tested and not taken in the cycle under way (the step
    /// they leave, one-based, and the jump): the other side of each path.
    declined: Vec<(usize, String)>,
    table: &'a StepTable,
    /// Dwell timers: PLC index, dwell number, when it started (if running).
    dwells: Vec<(usize, u16, Option<u64>)>,
    spans: Vec<Span>,
    trace: Vec<(u64, Vec<f64>)>,
    /// Per piston, the PLC indices of its `+`, `-` and single coil.
    coils: Vec<(Option<usize>, Option<usize>, Option<usize>)>,
    /// The I/O of every scan, when recorded for a replay in another engine.
    io: Option<io::IoTrace>,
    /// The PLC index of each output recorded, found once for every scan.
    io_outputs: Vec<Option<usize>>,
    /// The inputs' changes, when logged for the fault analysis.
    input_log: Option<io::InputLog>,
    /// Where each logged input is read from.
    log_sources: Vec<(Signal, InputSource)>,
    /// Each PLC input's place in the log, and the logged inputs read since
    /// the last scan logged (marked through a shared borrow: the readers
    /// hold one).
    log_slot: Vec<Option<usize>>,
    read_marks: drive::ReadMarks,
    /// Where each of the PLC's inputs is read from, by its index there
    /// (shared by the run's copies).
    sources: std::sync::Arc<[InputSource]>,
    /// The faults, by the PLC's index of their input, and the value each
    /// is stuck at; as of the world's `faults_changed` count.
    stuck: (u32, Vec<(usize, bool)>),
    /// Jump over scans in which nothing can change (see [`Run::pass_quiet_scans`]);
    /// off, the run steps every scan (the reference it is tested against).
    event_driven: bool,
    /// The last scan changed nothing: the PLC's state, the inputs it read,
    /// the run's findings and every piston's sensors and rest stayed as
    /// they were.
    quiet: bool,
    /// The pistons that moved in the last scan (all of them before the
    /// first).
    moving: Vec<usize>,
    /// A hazard is among the problems.
    hazard_seen: bool,
    /// A collision is among the problems.
    collided: bool,
    /// A step has fired in this run: before the first, the machine stands
    /// at power-up and no step is under way.
    fired_any: bool,
    /// The operator held START in the scan before: a cycle request START
    /// set then (the last scan of its press) fires step 1 in this one.
    start_before: bool,
    /// The operator held STEP_PB in the scan before (the permit its press
    /// set then fires a step in this one), and STEP_MODE was on then (the
    /// scan that computed the permit this one reads).
    step_before: bool,
    step_mode_before: bool,
    /// The PLC indices of the alarm outputs, and whether one came on.
    alarm_bits: Vec<usize>,
    alarmed: bool,
    /// Every piston's [`Piston::place`] now, and the combinations reached.
    places: Vec<u32>,
    visited: Places,
    /// What the last scan run one by one did (a scenario reads it: a
    /// cycle abandoned, homing done).
    last_scan: Option<super::plc::ScanResult>,
}

/// What a scripted scenario (`scenario`) does with a run: it presses the
/// operator's buttons in the world, scans, and reads the PLC and the
/// plant; the run's bookkeeping stays behind these methods.
impl<'a> Run<'a> {
    /// The run records every scan's I/O when `record` names the signals,
    /// and passes quiet scans at once when `event_driven`.
    pub(in crate::simulate) fn recording(
        mut self,
        record: Option<io::IoSignals>,
        event_driven: bool,
    ) -> Run<'a> {
        self.io = record.map(|signals| io::IoTrace::new(self.world.settings.scan_ms, signals));
        self.io_outputs = self.io.as_ref().map_or_else(Vec::new, |io| {
            let at = |s: &Signal| self.plc.index_of(*s);
            io.signals.outputs.iter().map(at).collect()
        });
        self.event_driven = event_driven;
        self
    }

    pub(in crate::simulate) fn time_ms(&self) -> u64 {
        self.time_ms
    }

    /// The operator's buttons and the machine's inputs, to change.
    pub(in crate::simulate) fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    pub(in crate::simulate) fn plc(&self) -> &PlcState<'a> {
        &self.plc
    }

    /// What the last scan run by [`Run::tick`] did.
    pub(in crate::simulate) fn last_scan(&self) -> Option<super::plc::ScanResult> {
        self.last_scan
    }

    /// The problems found, the I/O recorded and the dwell and wait spans
    /// the run went through, once it is over.
    pub(in crate::simulate) fn into_findings(
        self,
    ) -> (Vec<Problem>, Option<io::IoTrace>, Vec<Span>) {
        (self.problems, self.io, self.spans)
    }
}
