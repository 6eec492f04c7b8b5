//! Power-up, how long a step may take, and the timing of every step.

use super::*;
use crate::cell::Sign;
use crate::program::{Action, Signal, StepKind, StepProgram};
use crate::simulate::plc::{PlcProgram, PlcState};
use crate::table::StepTable;
use std::sync::atomic::{AtomicU64, Ordering::Relaxed};

/// The longest a step may take before the run counts as stalled: well past
/// the slowest stroke, and past the program's own watchdog so that its alarm
/// is seen.
pub(super) fn step_timeout_ms(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
) -> u64 {
    let watchdog = program
        .steps
        .iter()
        .flat_map(|s| &s.actions)
        .filter_map(|a| match a {
            Action::StartTimer(_, ms) => Some(*ms as u64 + 1000),
            _ => None,
        })
        .max()
        .unwrap_or(0);
    let longest = table
        .actuators
        .iter()
        .map(|a| {
            let s = settings.stroke(a.number);
            s.extend_ms.max(s.retract_ms)
        })
        .max()
        .unwrap_or(1000) as u64;
    // A step may also dwell and wait for the machine before it completes.
    let dwell = table.dwells().map(|d| d.ms).max().unwrap_or(0) as u64;
    let wait = if table.inputs.is_empty() {
        0
    } else {
        table
            .inputs
            .iter()
            .map(|n| settings.input_delay_ms(n))
            .max()
            .unwrap_or(0) as u64
    };
    // An output that runs on after a stop, once the watchdog has halted.
    let run_on = program.run_ons.iter().map(|r| r.ms).max().unwrap_or(0) as u64;
    (2 * longest + 500 + dwell + wait).max(watchdog) + run_on
}

/// Whether the table's cycle ends with `output` on: its last switch in
/// the table switches it on.
pub(super) fn left_on_by_the_cycle(table: &StepTable, output: Signal) -> bool {
    let Signal::MachineOutput(name) = output else {
        return false;
    };
    table
        .steps
        .iter()
        .flat_map(|s| &s.switches)
        .rfind(|w| w.output == name)
        .is_some_and(|w| w.on)
}

impl<'a> Run<'a> {
    /// Power-up: every piston home, the PLC in its initial state.
    pub(in crate::simulate) fn new(
        table: &'a StepTable,
        program: &'a StepProgram,
        code: &'a PlcProgram,
        settings: &SimSettings,
    ) -> Run<'a> {
        let mut world = World::new(settings, pistons(table, settings));
        world.machine = table
            .inputs
            .iter()
            .filter_map(|n| machine::rest_value(table, *n).map(|v| (*n, v)))
            // A healthy machine holds its start permissives on.
            .chain(program.permissive.iter().map(|n| (*n, true)))
            .collect();
        let mut run = Run {
            program,
            world,
            plc: PlcState::new(code),
            time_ms: 0,
            problems: Vec::new(),
            active: Vec::new(),
            last_move: vec![None; table.actuators.len()],
            pending: Vec::new(),
            answered: Vec::new(),
            jump_taken: None,
            jump_given: false,
            declined: Vec::new(),
            table,
            dwells: Vec::new(),
            spans: Vec::new(),
            trace: Vec::new(),
            coils: Vec::new(),
            io: None,
            io_outputs: Vec::new(),
            input_log: None,
            log_sources: Vec::new(),
            log_slot: Vec::new(),
            read_marks: ReadMarks::new(0),
            sources: std::sync::Arc::from([]),
            stuck: (u32::MAX, Vec::new()),
            event_driven: false,
            quiet: false,
            moving: (0..table.actuators.len()).collect(),
            hazard_seen: false,
            collided: false,
            fired_any: false,
            start_before: false,
            step_before: false,
            step_mode_before: false,
            alarm_bits: Vec::new(),
            alarmed: false,
            places: Vec::new(),
            visited: Places::default(),
            last_scan: None,
        };
        run.dwells = table
            .dwells()
            .filter_map(|d| {
                run.plc
                    .index_of(Signal::Dwell(d.number))
                    .map(|at| (at, d.number, None))
            })
            .collect();
        run.places = run
            .world
            .pistons
            .iter()
            .map(|p| p.place(settings.window))
            .collect();
        run.visit();
        run.coils = table
            .actuators
            .iter()
            .map(|a| {
                let at = |s: Signal| run.plc.index_of(s);
                (
                    at(Signal::Coil {
                        actuator: a.number,
                        sign: Sign::Plus,
                    }),
                    at(Signal::Coil {
                        actuator: a.number,
                        sign: Sign::Minus,
                    }),
                    at(Signal::SingleCoil { actuator: a.number }),
                )
            })
            .collect();
        run.sources = run
            .plc
            .signals()
            .iter()
            .map(|s| run.world.source(*s))
            .collect();
        run.alarm_bits = program
            .signals
            .alarms()
            .filter_map(|a| run.plc.index_of(a))
            .collect();
        run
    }
}

impl Run<'_> {
    /// Runs on under `settings` (a copy of a run, resumed with its faults),
    /// its scan time kept.
    pub(in crate::simulate) fn set_settings(&mut self, settings: &SimSettings) {
        self.world.settings = std::sync::Arc::new(SimSettings {
            scan_ms: self.world.settings.scan_ms,
            ..settings.clone()
        });
        self.world.faults_changed += 1;
        self.world.faults_active = self.time_ms >= settings.fault_onset_ms;
    }

    /// The faults by the PLC's index of their input, found again when they
    /// changed (a scenario sticks inputs as it goes).
    pub(super) fn stuck_by_index(&mut self) -> &[(usize, bool)] {
        if self.stuck.0 != self.world.faults_changed {
            let faults = &self.world.settings.faults;
            let at = |f: &Fault| Some((self.plc.index_of(f.signal)?, f.stuck_at));
            self.stuck = (
                self.world.faults_changed,
                faults.iter().filter_map(at).collect(),
            );
        }
        &self.stuck.1
    }

    /// Logs the inputs of every scan from now on, when `inputs` are given,
    /// and when `reads`, when each is read.
    pub(in crate::simulate) fn log_inputs(&mut self, inputs: Option<Vec<Signal>>, reads: bool) {
        let logged = inputs.as_deref().unwrap_or_default();
        self.log_sources = logged.iter().map(|s| (*s, self.world.source(*s))).collect();
        self.log_slot = match inputs {
            Some(_) if reads => self
                .plc
                .signals()
                .iter()
                .map(|s| logged.iter().position(|l| l == s))
                .collect(),
            _ => Vec::new(),
        };
        self.read_marks = ReadMarks::new(if reads { logged.len() } else { 0 });
        self.input_log = inputs.map(|inputs| {
            let mut log = io::InputLog::new(self.world.settings.scan_ms, inputs);
            log.reads_logged = reads;
            log
        });
    }

    /// The log of the inputs of a run that has ended, if it kept one.
    pub(in crate::simulate) fn take_input_log(&mut self) -> Option<io::InputLog> {
        let last_ms = self.time_ms;
        let marks = &self.read_marks;
        self.input_log.take().map(|mut log| {
            // What the last scans read, until the run ended.
            log.read_until(marks.take(), last_ms + u64::from(log.scan_ms));
            // The last scan: quiet ones after the last the run stepped
            // through read what it read.
            log.last_ms = log
                .last_ms
                .max(last_ms.saturating_sub(u64::from(log.scan_ms)));
            log
        })
    }

    /// An input read by the simulator judging the run (not the program):
    /// marked as read, when the inputs are logged.
    pub(in crate::simulate) fn read(&self, signal: Signal) -> bool {
        if self.input_log.as_ref().is_some_and(|l| l.reads_logged)
            && let Some(k) = self.log_sources.iter().position(|(s, _)| *s == signal)
        {
            self.read_marks.mark(k);
        }
        read_input(signal, &self.world)
    }
}

/// The logged inputs read since the last scan logged, 64 to a word,
/// marked through a shared borrow (the readers hold one). Atomic only to
/// be shared by the copies of a run the fault analysis reads on every
/// core: one thread marks, with plain loads and stores.
#[derive(Debug, Default)]
pub(in crate::simulate) struct ReadMarks(Vec<AtomicU64>);

impl ReadMarks {
    fn new(inputs: usize) -> ReadMarks {
        ReadMarks(
            (0..inputs.div_ceil(64))
                .map(|_| AtomicU64::new(0))
                .collect(),
        )
    }

    /// Marks the `k`-th logged input as read.
    pub(in crate::simulate) fn mark(&self, k: usize) {
        let word = &self.0[k / 64];
        word.store(word.load(Relaxed) | 1 << (k % 64), Relaxed);
    }

    /// The words marked, each cleared.
    pub(in crate::simulate) fn take(&self) -> impl Iterator<Item = u64> + '_ {
        self.0.iter().map(|w| w.swap(0, Relaxed))
    }
}

impl Clone for ReadMarks {
    fn clone(&self) -> ReadMarks {
        ReadMarks(
            self.0
                .iter()
                .map(|w| AtomicU64::new(w.load(Relaxed)))
                .collect(),
        )
    }
}

pub(super) fn timings(
    program: &StepProgram,
    fire_times: &[(usize, u64)],
    end: u64,
    press_at: u64,
    spans: &[Span],
) -> Vec<StepTiming> {
    // The table's steps only: the closing transition is no step of its own
    // (it leads back to step 0), so the last step lasts until the cycle ends.
    let fire_times: Vec<(usize, u64)> = fire_times
        .iter()
        .copied()
        .filter(|(index, _)| program.steps[*index].kind == StepKind::Table)
        .collect();
    fire_times
        .iter()
        .enumerate()
        .map(|(i, (index, t))| {
            let next = fire_times.get(i + 1).map_or(end, |f| f.1);
            let step = &program.steps[*index];
            let notes: Vec<String> = spans
                .iter()
                .filter(|s| s.from_ms >= *t && s.from_ms < next)
                .map(|s| {
                    if s.label.starts_with("I:") {
                        format!("{} came after {}", s.label, seconds(s.to_ms - t))
                    } else {
                        format!(
                            "{} ran {:.2}–{}",
                            s.label,
                            (s.from_ms - t) as f64 / 1000.0,
                            seconds(s.to_ms - t)
                        )
                    }
                })
                .collect();
            StepTiming {
                step: step.number,
                start_ms: t - press_at,
                duration_ms: next - t,
                moves: step.title.clone(),
                notes: notes.join("; "),
            }
        })
        .collect()
}
