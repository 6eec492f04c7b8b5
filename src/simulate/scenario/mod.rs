//! Scripted runs for the operating modes: the operator presses STOP, the
//! EMERGENCY STOP or RESET at given times, and the run records what the
//! machine did scan by scan. The standard proof ([`super::simulate`]) only
//! ever presses START; this shows what the other buttons do.

use crate::program::Signal;
use crate::program::StepProgram;
use crate::table::StepTable;

pub mod check;
pub mod events;
pub mod table;

pub use events::{Act, Event, When};

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
    /// Homing runs (the `homing` memory is set), or ran within this scan
    /// (RESET with every actuator home, or nearly: set and done at once).
    pub homing: bool,
    /// A halt (the EMERGENCY STOP's, a check's) waits for RESET: START
    /// is refused.
    pub halted: bool,
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
    /// `(time_ms, event index)` of every event of an event script that
    /// happened, in order; the events after the last are those that never
    /// came (their step was not entered before the run ended).
    pub happened: Vec<(u64, usize)>,
    /// When START was pressed for an event script without a START event.
    pub auto_start_ms: Option<u64>,
    /// The run stopped at this time because it had run [`SCAN_BUDGET`]
    /// scans one by one, before its events and their tail were over.
    pub cut_ms: Option<u64>,
    /// Dwells and waits for a machine input, as they ran (the timeline
    /// shades them as the report's does).
    pub spans: Vec<super::Span>,
    /// `(time_ms, SFC step left, what did it)` of every cycle abandoned:
    /// the sequence sent back to step 0 by a rung (manual mode, RESET, a
    /// STOP at once), not by its closing transition.
    pub abandoned: Vec<(u64, usize, crate::program::RungKind)>,
    /// The events (by index) that pressed or held a button already down
    /// (a press still within its 0.1 s, a hold): no new edge, so the
    /// program saw no new press.
    pub still_down: Vec<usize>,
}

/// The most scans a scenario runs one by one (quiet scans passed at once
/// do not count): every one keeps a sample, and an event script must not
/// fill the memory of the machine it runs on.
pub const SCAN_BUDGET: usize = 200_000;

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
    run_script(table, program, settings, &mut Timed(script), until_ms, None).0
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
    let (report, trace) = run_script(
        table,
        program,
        settings,
        &mut Timed(script),
        until_ms,
        Some(signals),
    );
    (report, trace.unwrap_or_default())
}

/// How long a scenario runs on after its last event: as long as a
/// healthy cycle takes (10 s when none completes), a second to see the
/// machine stand, the longest run-on of an output after a stop (an oven's
/// fan) and the longest step supervision time (a stall the event causes
/// raises its alarm within the run), so that what the last event starts
/// is seen to its end. `simulate`'s scenarios and their replays in the
/// engines share it.
pub fn tail_after_events(table: &StepTable, program: &StepProgram, settings: &SimSettings) -> u64 {
    let proof = super::simulate(table, program, settings);
    let cycle = proof
        .cycles
        .first()
        .and_then(|c| c.cycle_ms)
        .unwrap_or(10_000);
    let run_on = program.run_ons.iter().map(|r| u64::from(r.ms)).max();
    // A homing stage's supervision too: its alarm comes after the RESET.
    let supervision = program
        .steps
        .iter()
        .flat_map(|s| &s.actions)
        .chain(program.rungs.iter().flat_map(|r| &r.actions))
        .filter_map(|a| match a {
            crate::program::Action::StartTimer(Signal::Watchdog, ms) => Some(u64::from(*ms)),
            _ => None,
        })
        .max();
    cycle + 1_000 + run_on.unwrap_or(0) + supervision.unwrap_or(0)
}

/// Runs `program` from power-up with the operator's `events` (each
/// happening in the order given), until `tail_ms` after the last has
/// happened (an event waiting for a step that has not come `tail_ms`
/// after the event before it never happens), or `until_ms` at the latest;
/// records `signals` at every scan when given (the timeline, a replay in
/// an engine). Without an event on START, START is pressed at 0.5 s as in
/// the proof. Quiet scans are passed at once, as the proof passes them.
pub fn scenario_events(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    events: &[Event],
    (tail_ms, until_ms): (u64, u64),
    signals: Option<super::io::IoSignals>,
) -> (ScenarioReport, Option<super::io::IoTrace>) {
    let mut script = Events::new(events, tail_ms);
    run_script(table, program, settings, &mut script, until_ms, signals)
}

/// What the operator does, scan by scan.
trait Script {
    /// Sets the buttons and faults for the scan about to run at `now`;
    /// `arrived` is the SFC step the scan before arrived at (see
    /// [`arrival`]), `happened` gathers the events that happen now.
    fn apply(
        &mut self,
        world: &mut super::world::World,
        now: u64,
        arrived: Option<usize>,
        happened: &mut Vec<(u64, usize)>,
    );
    /// Whether the run may end now.
    fn done(&self, _now: u64) -> bool {
        false
    }
    /// When the script pressed START on its own.
    fn auto_start_ms(&self) -> Option<u64> {
        None
    }
    /// The events that pressed a button already down.
    fn still_down(&self) -> Vec<usize> {
        Vec::new()
    }
    /// The earliest time the script may change anything with time alone
    /// (a press let go, an event at a time, the run's end): quiet scans
    /// before it may be passed at once. `None`: run every scan.
    fn quiet_until(&self) -> Option<u64> {
        None
    }
}

/// A script of operator states by time: each from its time on.
struct Timed<'a>(&'a [(u64, Operator)]);

impl Script for Timed<'_> {
    fn apply(
        &mut self,
        world: &mut super::world::World,
        now: u64,
        _: Option<usize>,
        _: &mut Vec<(u64, usize)>,
    ) {
        if let Some((_, operator)) = self.0.iter().rev().find(|(t, _)| *t <= now) {
            world.operator = *operator;
        }
    }
}

/// How long a press holds a button, as the proof holds START: 0.1 s, and
/// two scans at least, so that the PLC sees it however slow the scan.
fn press_ms(world: &super::world::World) -> u64 {
    u64::from(super::START_PRESS_MS.max(2 * world.settings.scan_ms))
}

/// A script of events, each armed when the one before it has happened.
struct Events<'a> {
    events: &'a [Event],
    next: usize,
    /// When the last event happened (0 before the first).
    last_ms: u64,
    /// The step the scan before arrived at, until an event takes it.
    arrived: Option<usize>,
    /// Buttons pressed (not held), with when they are let go.
    releases: Vec<(u64, Signal)>,
    /// START pressed at 0.5 s when no event touches it.
    auto_start: bool,
    /// When it was.
    started_ms: Option<u64>,
    tail_ms: u64,
    still_down: Vec<usize>,
}

impl<'a> Events<'a> {
    fn new(events: &'a [Event], tail_ms: u64) -> Self {
        let auto_start = !events.iter().any(|e| e.act.signal() == Signal::Start);
        Events {
            events,
            next: 0,
            last_ms: 0,
            arrived: None,
            releases: Vec::new(),
            auto_start,
            started_ms: None,
            tail_ms,
            still_down: Vec::new(),
        }
    }

    /// Whether event `k` happens at the scan at `now`.
    fn due(&self, k: usize, now: u64) -> bool {
        match self.events[k].when {
            When::At(t) => now >= t,
            When::After(d) => now >= self.last_ms + d,
            When::Step(s) => self.arrived == Some(s),
        }
    }
}

impl Script for Events<'_> {
    fn apply(
        &mut self,
        world: &mut super::world::World,
        now: u64,
        arrived: Option<usize>,
        happened: &mut Vec<(u64, usize)>,
    ) {
        self.arrived = arrived;
        if self.auto_start && now >= u64::from(super::IDLE_MS) {
            self.auto_start = false;
            self.started_ms = Some(now);
            self.releases.push((now + press_ms(world), Signal::Start));
            set(&mut world.operator, Signal::Start, true);
        }
        let mut let_go = Vec::new();
        self.releases.retain(|(t, s)| {
            let due = *t <= now;
            if due {
                let_go.push(*s);
            }
            !due
        });
        for &signal in &let_go {
            set(&mut world.operator, signal, false);
        }
        while self.next < self.events.len() && self.due(self.next, now) {
            let act = self.events[self.next].act;
            // Down, or let go in this very scan (a press 0.1 s after the
            // last): the program reads it down in both scans.
            let down = |s: Signal| is_down(&world.operator, s) || let_go.contains(&s);
            if matches!(act, Act::Press(s) | Act::Hold(s) if down(s)) {
                self.still_down.push(self.next);
            }
            match act {
                Act::Press(s) => {
                    set(&mut world.operator, s, true);
                    self.releases.retain(|(_, r)| *r != s);
                    self.releases.push((now + press_ms(world), s));
                }
                Act::Hold(s) => {
                    set(&mut world.operator, s, true);
                    self.releases.retain(|(_, r)| *r != s);
                }
                Act::Release(s) => set(&mut world.operator, s, false),
                Act::Stick(signal, stuck_at) => world.stick(signal, stuck_at),
            }
            happened.push((now, self.next));
            self.last_ms = now;
            self.next += 1;
            // A step's event after this one waits for the program to
            // arrive at its step anew: being in it now is not arriving.
            self.arrived = None;
        }
    }

    fn done(&self, now: u64) -> bool {
        // A step not entered a healthy cycle (and a second) after the event
        // before it is not coming: the machine stands or cycles elsewhere.
        let waiting = match self.events.get(self.next) {
            None => true,
            Some(event) => matches!(event.when, When::Step(_)),
        };
        waiting && now >= self.last_ms + self.tail_ms
    }

    fn quiet_until(&self) -> Option<u64> {
        let next = self.events.get(self.next).and_then(|e| match e.when {
            When::At(t) => Some(t),
            When::After(d) => Some(self.last_ms + d),
            When::Step(_) => None,
        });
        let start = self.auto_start.then_some(u64::from(super::IDLE_MS));
        let releases = self.releases.iter().map(|(t, _)| *t);
        let end = self.last_ms + self.tail_ms;
        Some(releases.chain(next).chain(start).fold(end, u64::min))
    }

    fn auto_start_ms(&self) -> Option<u64> {
        self.started_ms
    }

    fn still_down(&self) -> Vec<usize> {
        self.still_down.clone()
    }
}

/// Whether the operator's button `signal` is down (pressed or held).
fn is_down(operator: &Operator, signal: Signal) -> bool {
    match signal {
        Signal::Start => operator.start,
        Signal::Stop => operator.stop,
        Signal::EStop => operator.estop,
        Signal::Reset => operator.reset,
        Signal::Continuous => operator.continuous,
        Signal::StepMode => operator.step_mode,
        Signal::StepButton => operator.step,
        Signal::ManualMode => operator.manual,
        Signal::Jog { .. } => operator.jogs.held(signal),
        _ => false,
    }
}

/// Presses or lets go of the operator's button `signal`.
fn set(operator: &mut Operator, signal: Signal, on: bool) {
    match signal {
        Signal::Start => operator.start = on,
        Signal::Stop => operator.stop = on,
        Signal::EStop => operator.estop = on,
        Signal::Reset => operator.reset = on,
        Signal::Continuous => operator.continuous = on,
        Signal::StepMode => operator.step_mode = on,
        Signal::StepButton => operator.step = on,
        Signal::ManualMode => operator.manual = on,
        // The scenario's check keeps the jogs within the operator's hands.
        Signal::Jog { .. } if on => {
            operator.jogs = operator.jogs.with(signal).unwrap_or(operator.jogs)
        }
        Signal::Jog { .. } => operator.jogs = operator.jogs.without(signal),
        _ => {}
    }
}

fn run_script(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
    script: &mut dyn Script,
    until_ms: u64,
    record: Option<super::io::IoSignals>,
) -> (ScenarioReport, Option<super::io::IoTrace>) {
    let code = PlcProgram::compile(program);
    let mut run =
        Run::new(table, program, &code, settings).recording(record, script.quiet_until().is_some());
    let outputs: Vec<(usize, Signal)> = program
        .steps
        .iter()
        .flat_map(|s| &s.actions)
        .chain(program.rungs.iter().flat_map(|r| &r.actions))
        .map(|a| a.signal())
        .filter(|s| s.area() == crate::program::Area::Output)
        .filter_map(|s| run.plc().index_of(s).map(|i| (i, s)))
        .collect::<std::collections::BTreeMap<_, _>>()
        .into_iter()
        .collect();
    let mut fired = Vec::new();
    let mut samples = Vec::new();
    let mut happened = Vec::new();
    let mut cut_ms = None;
    let mut abandoned = Vec::new();
    let mut arrived = None;
    let mut arrivals = Arrivals::default();
    while run.time_ms() < until_ms && !script.done(run.time_ms()) {
        if samples.len() >= SCAN_BUDGET {
            cut_ms = Some(run.time_ms());
            break;
        }
        let step = run.current_step();
        let now = run.time_ms();
        script.apply(run.world_mut(), now, arrived, &mut happened);
        if let Some(index) = run.tick() {
            fired.push((now, program.steps[index].number));
        }
        let scan = run.last_scan();
        let mut taken = sample(&run, &outputs);
        taken.homing |= scan.is_some_and(|s| s.homed);
        if let Some(left) = scan.and_then(|s| s.abandoned) {
            abandoned.push((now, program.step_in(left.waited_at), left.by));
        }
        arrived = scan.and_then(|s| arrivals.arrival(program, s, taken.homing));
        samples.push(taken);
        // A step just entered (or left), or homing just done, is seen by
        // the script at the next scan: that one runs, whatever follows it.
        let entered = arrived.is_some() || arrivals.homed || run.current_step() != step;
        if let Some(until) = script.quiet_until().filter(|_| !entered) {
            let at = run.time_ms();
            run.pass_quiet_scans(until.min(until_ms));
            if run.time_ms() > at {
                samples.push(sample(&run, &outputs));
            }
        }
    }
    let (problems, io, spans) = run.into_findings();
    let report = ScenarioReport {
        fired,
        samples,
        problems,
        happened,
        auto_start_ms: script.auto_start_ms(),
        cut_ms,
        spans,
        abandoned,
        still_down: script.still_down(),
    };
    (report, io)
}

/// Where the sequence arrives, scan by scan, for `@stepK`.
#[derive(Default)]
struct Arrivals {
    /// The scan before homed (or went on homing, as it does while RESET
    /// is held).
    homing: bool,
    /// Its homing was done by the homing rungs (not cut by manual mode).
    homed: bool,
}

impl Arrivals {
    /// The SFC step a scan arrived at, the one `@stepK` waits for: the
    /// step a transition entered (step 0 by the closing transition: the
    /// end of a cycle), or step 0 at the first scan without homing after
    /// homing was done (the machine home, RESET let go: ready for START;
    /// the scan printed `homing done`). A cycle abandoned (manual mode,
    /// RESET starting to home, a STOP at once) arrives nowhere: the
    /// sequence is back in step 0 but no cycle ended and the machine is
    /// not ready.
    fn arrival(
        &mut self,
        program: &StepProgram,
        scan: super::plc::ScanResult,
        homing: bool,
    ) -> Option<usize> {
        let homing_done = self.homing && self.homed && !homing;
        (self.homing, self.homed) = (homing, scan.homed);
        if scan.abandoned.is_some() {
            return None;
        }
        match scan.fired {
            Some(index) => Some(program.step_entered(index)),
            None => homing_done.then_some(crate::program::INITIAL_STEP),
        }
    }
}

/// The machine as the scan just run left it.
fn sample(run: &Run, outputs: &[(usize, Signal)]) -> Sample {
    Sample {
        time_ms: run.time_ms(),
        positions: run.positions(),
        outputs_on: outputs
            .iter()
            .filter(|(i, _)| run.plc().bit_at(*i))
            .map(|(_, s)| *s)
            .collect(),
        step: run.current_step(),
        homing: run.plc().bit(Signal::Homing),
        halted: run.plc().bit(Signal::Halt),
    }
}
