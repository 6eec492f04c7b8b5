//! The operator's side of a run: idle, press START, watch each cycle to its
//! end (or its stall), idle again. Kept as a state between two scans
//! ([`Drive`]) rather than as nested loops, so that a run can be copied at
//! any scan and resumed later under other settings (the fault analysis
//! starts each faulty run where the healthy one stood when the fault
//! appeared).

use super::drive::{left_on_by_the_cycle, step_timeout_ms, timings};
use super::*;
use crate::program::{Alarm, StepKind};
use crate::simulate::plc::PlcProgram;

/// Where a run stands between two scans.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub(super) enum Stage {
    /// Waiting for the press of the next cycle: nothing may happen.
    Idle,
    /// A cycle is under way.
    Cycle,
    /// After the last cycle, until `until`: nothing may move on its own.
    Rest {
        until: u64,
    },
    Finished,
}

/// A run between two scans: the plant and the PLC ([`Run`]) and where the
/// operator's cycles stand.
#[derive(Clone)]
pub(super) struct Drive<'a> {
    pub(super) run: Run<'a>,
    pub(super) stage: Stage,
    pub(super) cycle: usize,
    cycles_wanted: usize,
    /// More steps than a cycle fires with every jump back taken a few
    /// times over: past it, jumps back never end.
    most_fires: usize,
    pub(super) press_at: u64,
    timeout: u64,
    /// The cycle under way.
    pub(super) report: CycleReport,
    /// When each step of the cycle under way fired.
    /// Which step fired when (a jump fires a step out of order).
    pub(super) fire_times: Vec<(usize, u64)>,
    /// `fire_times` and `cycles` hashed as they grow: the fingerprint taken
    /// at every scan of a fault run reads these rather than every step.
    pub(super) fired: u64,
    pub(super) ended: u64,
    pub(super) last_event: u64,
    /// The cycles ended, shared by the copies of the run (the fault
    /// analysis copies it hundreds of times; a cycle's steps are strings).
    pub(super) cycles: std::sync::Arc<Vec<CycleReport>>,
    pub(super) step_positions: Vec<Vec<f64>>,
    stalled_at: Option<usize>,
    first_cycle_end: u64,
    /// Runs of quiet scans stop at this time: a checkpoint of the fault
    /// analysis wants the run as it stands then.
    pub(super) horizon: u64,
}

impl<'a> Drive<'a> {
    /// Power-up, waiting for the first press.
    pub(super) fn new(
        table: &'a StepTable,
        program: &'a StepProgram,
        code: &'a PlcProgram,
        settings: &SimSettings,
        record: Option<io::IoSignals>,
        stepping: Stepping,
    ) -> Self {
        let run = Run::new(table, program, code, settings)
            .recording(record, stepping == Stepping::Events);
        let press_at = IDLE_MS as u64;
        let positions = run.positions();
        Drive {
            run,
            stage: Stage::Idle,
            cycle: 0,
            cycles_wanted: settings.cycles.max(1) + jumps_to_take(table).count(),
            most_fires: program.steps.len()
                * (1 + 4 * table.steps.iter().map(|s| s.jumps.len()).sum::<usize>()),
            press_at,
            timeout: step_timeout_ms(table, program, settings),
            report: CycleReport {
                press_ms: press_at,
                steps: Vec::new(),
                cycle_ms: None,
                jump: None,
                declined: Vec::new(),
            },
            fire_times: Vec::new(),
            fired: 0,
            ended: 0,
            last_event: 0,
            cycles: Default::default(),
            step_positions: vec![positions],
            stalled_at: None,
            first_cycle_end: u64::MAX,
            horizon: u64::MAX,
        }
    }

    pub(super) fn finished(&self) -> bool {
        self.stage == Stage::Finished
    }

    /// One scan and what the run makes of it, then the quiet scans after
    /// it; afterwards the next thing the run does is a scan (or nothing,
    /// once finished).
    pub(super) fn advance(&mut self) {
        match self.stage {
            Stage::Idle => {
                self.run.tick();
                if self.run.judged() {
                    self.stage = Stage::Finished;
                    return;
                }
                self.run.pass_quiet_scans(self.press_at.min(self.horizon));
            }
            Stage::Cycle => self.cycle_scan(),
            Stage::Rest { until } => {
                self.run.tick();
                if !self.run.judged() {
                    self.run.pass_quiet_scans(until.min(self.horizon));
                }
            }
            Stage::Finished => {}
        }
        self.settle();
    }

    /// Moves on when the stage is over: the press comes, the idle after
    /// the last cycle ends.
    fn settle(&mut self) {
        match self.stage {
            Stage::Idle if self.run.time_ms >= self.press_at => {
                self.report = CycleReport {
                    press_ms: self.press_at,
                    steps: Vec::new(),
                    cycle_ms: None,
                    jump: None,
                    declined: Vec::new(),
                };
                self.fire_times.clear();
                self.fired = 0;
                self.last_event = self.run.time_ms;
                self.stage = Stage::Cycle;
                // After the plain cycles, one per jump takes it.
                let plain = self.run.world.settings.cycles.max(1);
                self.run.jump_taken = self
                    .cycle
                    .checked_sub(plain)
                    .and_then(|n| jumps_to_take(self.run.table).nth(n));
                self.run.jump_given = false;
                self.run.declined.clear();
                self.report.jump = self
                    .run
                    .jump_taken
                    .map(|(index, jump)| (index + 1, jump.notation()));
            }
            Stage::Rest { until } if self.run.time_ms >= until || self.run.judged() => {
                self.stage = Stage::Finished;
            }
            _ => {}
        }
    }

    /// One scan of a cycle under way.
    fn cycle_scan(&mut self) {
        let program = self.run.program;
        // A press the PLC can see: held for two scans at least, however
        // slow the scan.
        let press_ms = START_PRESS_MS.max(2 * self.run.world.settings.scan_ms) as u64;
        self.run.world.start_pressed = self.run.time_ms < self.press_at + press_ms;
        let before = self.run.time_ms;
        let fired = self.run.tick();
        if self.run.judged() {
            self.close_report();
            self.stage = Stage::Finished;
            return;
        }
        if self.fire_times.len() > self.most_fires {
            // Jumps back that never end: nothing stalls, nothing finishes.
            let step = self.run.current_step();
            let message = format!(
                "the cycle never ends: {} steps have fired, jumping back again and again",
                self.fire_times.len()
            );
            self.run.problem(ProblemKind::Stall, step, message);
            self.stalled_at = Some(step);
            self.close_report();
            self.stage = Stage::Finished;
            return;
        }
        if let Some(index) = fired {
            // A boundary of the diagram: the previous step has ended.
            // (A closing END step is not a boundary: the cycle end is.)
            if self.cycle == 0 && index > 0 && program.steps[index].kind == StepKind::Table {
                self.step_positions.push(self.run.positions());
            }
            if index == 0 && !self.fire_times.is_empty() {
                // Step 1 again before the cycle was seen to end.
                self.end_cycle();
                return;
            }
            self.fire_times.push((index, before));
            self.fired = super::checkpoint::mix(self.fired, &[index as u64, before]);
            self.last_event = self.run.time_ms;
        }
        // The cycle ends when the machine is at rest: a closing step
        // fires on the home sensors while the last stroke still runs
        // into its end stop, and START must not come before it does.
        let run = &self.run;
        let done = self.last_step_fired()
            && run.plc.awaited == 0
            && run.all_moves_ended()
            && run.world.pistons.iter().all(plant::Piston::at_rest)
            && run.cycle_complete();
        if done {
            if self.cycle == 0 {
                self.step_positions.push(self.run.positions());
            }
            self.report.cycle_ms = Some(self.run.time_ms - self.press_at);
            self.end_cycle();
            return;
        }
        if self.run.time_ms - self.last_event > self.timeout {
            self.stall();
            return;
        }
        // Quiet scans pass at once until START is released or the wait
        // could time out.
        let scan = self.run.world.settings.scan_ms as u64;
        let release = if self.run.world.start_pressed {
            self.press_at + press_ms
        } else {
            u64::MAX
        };
        let timeout = (self.last_event + self.timeout + 1).saturating_sub(scan);
        self.run
            .pass_quiet_scans(release.min(timeout).min(self.horizon));
    }

    /// Whether the step that fired last closes the cycle (the last step,
    /// or the closing step a jump to the end fires).
    fn last_step_fired(&self) -> bool {
        let last = self.run.program.steps.len() - 1;
        self.fire_times
            .last()
            .is_some_and(|(index, _)| *index == last)
    }

    /// A cycle that was to take a jump took it: right after the jump's
    /// step, its target fired.
    fn check_jump_taken(&mut self) {
        let Some((index, jump)) = self.run.jump_taken else {
            return;
        };
        let target = jump.fires(self.run.program.steps.len() - 1);
        let after = self
            .fire_times
            .iter()
            .position(|(i, _)| *i == index)
            .and_then(|at| self.fire_times.get(at + 1))
            .map(|(i, _)| *i);
        if after == Some(target) {
            return;
        }
        let number = index + 1;
        let message = format!(
            "cycle {} was to take {} after step {number}, but {} (the machine gives I:{} {})",
            self.cycle + 1,
            jump.notation(),
            match after {
                Some(i) => format!("step {} came first", self.run.program.steps[i].number),
                None => "the cycle ended first".to_string(),
            },
            jump.input,
            match self.run.world.settings.input_delays.get(&jump.input) {
                Some(&ms) => format!("{} after its step starts", seconds(u64::from(ms))),
                None => "as its step starts".to_string(),
            },
        );
        let step = self.run.current_step();
        self.run.problem(ProblemKind::PathLost, step, message);
    }

    /// The cycle under way, timed, among the cycles.
    fn close_report(&mut self) {
        let mut report = std::mem::replace(
            &mut self.report,
            CycleReport {
                press_ms: self.press_at,
                steps: Vec::new(),
                cycle_ms: None,
                jump: None,
                declined: Vec::new(),
            },
        );
        let mut declined = std::mem::take(&mut self.run.declined);
        // A jump back tests its jumps again: each once.
        let mut seen = std::collections::BTreeSet::new();
        declined.retain(|d| seen.insert(d.clone()));
        report.declined = declined;
        report.steps = timings(
            self.run.program,
            &self.fire_times,
            self.run.time_ms,
            self.press_at,
            &self.run.spans,
        );
        let steps = report
            .steps
            .iter()
            .flat_map(|s| [s.start_ms, s.duration_ms]);
        let words: Vec<u64> = [report.press_ms, report.cycle_ms.map_or(u64::MAX, |c| c)]
            .into_iter()
            .chain(steps)
            .collect();
        self.ended = super::checkpoint::mix(self.ended, &words);
        std::sync::Arc::make_mut(&mut self.cycles).push(report);
    }

    /// The cycle has ended (or step 1 came again): every actuator must be
    /// home; then the next press, or the idle after the last cycle.
    fn end_cycle(&mut self) {
        let complete = self.report.cycle_ms.is_some();
        if self.cycle == 0 {
            self.first_cycle_end = self.run.time_ms;
        }
        if complete {
            let window = self.run.world.settings.window;
            let step = self.run.current_step();
            for p in &self.run.world.pistons {
                if !p.sensor(0, window) {
                    self.run.problems.push(Problem {
                        kind: ProblemKind::NotHome,
                        time_ms: self.run.time_ms,
                        step,
                        actuator: Some(p.number),
                        message: format!("C{} is not home at the end of the cycle", p.number),
                    });
                }
            }
        }
        if complete {
            self.check_jump_taken();
        }
        self.close_report();
        if complete && self.cycle + 1 < self.cycles_wanted {
            self.cycle += 1;
            // One press, one cycle: a cycle over before its press (steps
            // that only switch outputs take a scan each) must not start
            // the next from the same press while the machine idles.
            self.run.world.start_pressed = false;
            self.press_at = self.run.time_ms + IDLE_MS as u64;
            self.stage = Stage::Idle;
        } else {
            // A short idle after the last cycle: nothing may move on its own.
            self.run.world.start_pressed = false;
            self.stage = Stage::Rest {
                until: self.run.time_ms + IDLE_MS as u64,
            };
            self.settle();
        }
    }

    /// Nothing has happened for longer than any step may take: the run
    /// has stalled. Says what the awaited step waits for, which alarms are
    /// on and what the stopped machine keeps energised.
    fn stall(&mut self) {
        let (program, table) = (self.run.program, self.run.table);
        let ended = self.last_step_fired();
        let run = &mut self.run;
        let step_count = program.steps.len();
        let waiting = &program.steps[run.plc.awaited];
        // START was pressed and released; it only explains the wait when
        // nothing else is missing. The plant stands still while the
        // sequence waits: what is missing now is what was missing.
        let mut missing_literals = run.missing(run.plc.awaited);
        if missing_literals.len() > 1 {
            missing_literals.retain(|l| l.signal != Signal::Start);
        }
        let mut missing: Vec<String> = Vec::new();
        for text in missing_literals.iter().map(literal_text) {
            // A literal two checks both add is said once.
            if !missing.contains(&text) {
                missing.push(text);
            }
        }
        let alarms: Vec<String> = [Alarm::Sensor, Alarm::Timeout, Alarm::Interlock]
            .into_iter()
            .map(Signal::Alarm)
            .filter(|a| run.plc.bit(*a))
            .map(|a| a.symbol())
            .collect();
        // The closing transition is no table step: the table's last step
        // is the one whose moves or wait do not end.
        let last_table_step = program
            .steps
            .iter()
            .rev()
            .find(|s| s.kind == StepKind::Table)
            .map_or(step_count, |s| s.number);
        let waited_for = match missing.is_empty() {
            true => "its condition".to_string(),
            false => missing.join(" AND "),
        };
        let mut message = if ended {
            format!("the cycle never ends: the moves of step {last_table_step} do not finish")
        } else if waiting.kind == StepKind::EndOfCycle {
            format!("the cycle never ends after step {last_table_step}: waiting for {waited_for}")
        } else {
            format!(
                "step {} never fires: waiting for {waited_for}",
                waiting.number
            )
        };
        // The criteria analysis's outputs that are on: what the HMI shows.
        let shown: Vec<String> = program
            .criteria
            .iter()
            .zip(1u16..)
            .filter(|(_, n)| run.plc.bit(Signal::Missing(*n)))
            .map(|(l, n)| {
                let what = crate::program::describe_criterion(*l);
                format!("{} ({what})", Signal::Missing(n).symbol())
            })
            .collect();
        if !alarms.is_empty() {
            let missing = match shown.is_empty() {
                true => String::new(),
                false => format!("; missing: {}", shown.join(", ")),
            };
            message.push_str(&format!(" (alarm: {}{missing})", alarms.join(", ")));
        }
        // Waiting for the next cycle, an output the cycle leaves on (an
        // oven's heater until STOP) is on as in a healthy machine.
        let at_rest = run.plc.awaited == 0;
        let energised: Vec<String> = program
            .signals
            .driven()
            .filter(|s| run.plc.bit(*s) && !program.may_stay_on(*s))
            .filter(|s| !(at_rest && left_on_by_the_cycle(table, *s)))
            .map(|s| s.symbol())
            .collect();
        // The step it stalls in, not the one that never fires: the fault
        // table's step column is where the machine is.
        let stalled_in = run.current_step();
        run.problem(ProblemKind::Stall, stalled_in, message.clone());
        if !energised.is_empty() {
            run.problem(
                ProblemKind::Energised,
                stalled_in,
                format!(
                    "{message}; the stopped machine keeps {} on (not hold-safe)",
                    energised.join(", ")
                ),
            );
        }
        self.stalled_at = Some(stalled_in);
        self.close_report();
        self.stage = Stage::Finished;
    }

    /// Runs to the end.
    pub(super) fn run_to_end(&mut self) {
        while !self.finished() {
            self.advance();
        }
    }

    /// The report of a finished run, and the I/O it recorded.
    pub(super) fn finish(self) -> (SimReport, Option<io::IoTrace>) {
        let Drive {
            mut run,
            cycles,
            cycles_wanted,
            step_positions,
            stalled_at,
            first_cycle_end,
            ..
        } = self;
        let window = run.world.settings.window;
        let cycles = std::sync::Arc::unwrap_or_clone(cycles);
        if let (Some(first), Some(second)) = (cycles.first(), cycles.get(1))
            && first.cycle_ms.is_some()
            && second.cycle_ms.is_some()
        {
            let durations =
                |c: &CycleReport| c.steps.iter().map(|s| s.duration_ms).collect::<Vec<_>>();
            if durations(first) != durations(second) {
                run.problems.push(Problem {
                    kind: ProblemKind::CycleDiffers,
                    time_ms: run.time_ms,
                    step: run.current_step(),
                    actuator: None,
                    message: "the second cycle's step timing differs from the first".to_string(),
                });
            }
        }
        // Say where each run-through ended: "C2 ran through x22 to x23".
        for problem in &mut run.problems {
            if problem.kind != ProblemKind::RanThrough {
                continue;
            }
            if let Some(piston) = problem
                .actuator
                .and_then(|n| run.world.index_of.get(&n))
                .map(|i| &run.world.pistons[*i])
            {
                let end = match piston.sensor_on(window) {
                    Some(position) => Signal::Sensor {
                        actuator: piston.number,
                        position,
                    }
                    .symbol(),
                    None => format!("position {:.2}", piston.position_units()),
                };
                problem.message =
                    problem
                        .message
                        .replacen(" in step", &format!(" to {end} in step"), 1);
            }
        }
        let all_cycles_done =
            cycles.len() == cycles_wanted && cycles.iter().all(|c| c.cycle_ms.is_some());
        run.problems.sort_by_key(|p| p.time_ms);
        let report = SimReport {
            alarmed: run.alarmed,
            passed: run.problems.is_empty() && all_cycles_done,
            cycles,
            problems: run.problems,
            stalled_at,
            step_positions,
            actuators: run
                .table
                .actuators
                .iter()
                .map(|a| (a.number, a.max_position))
                .collect(),
            trace: run.trace,
            places: run.visited,
            spans: run
                .spans
                .into_iter()
                .filter(|s| s.from_ms < first_cycle_end)
                .collect(),
        };
        (report, run.io)
    }
}

/// The jumps the run takes after the plain `cycles`, one cycle each (in
/// table order), so that every path is run: the index of the jump's step
/// and the jump.
fn jumps_to_take(table: &StepTable) -> impl Iterator<Item = (usize, crate::table::Jump)> + '_ {
    table
        .steps
        .iter()
        .enumerate()
        .flat_map(|(index, step)| step.jumps.iter().map(move |j| (index, *j)))
}

/// Simulates from power-up to the end, stepping as `stepping` says,
/// logging when `inputs` change (and when they are read) when they are
/// given.
pub(in crate::simulate) fn run_logging_inputs(
    table: &StepTable,
    program: &StepProgram,
    code: &PlcProgram,
    settings: &SimSettings,
    inputs: Option<Vec<crate::program::Signal>>,
    record: Option<io::IoSignals>,
    stepping: Stepping,
) -> (SimReport, Option<io::InputLog>, Option<io::IoTrace>) {
    let mut drive = Drive::new(table, program, code, settings, record, stepping);
    drive.run.log_inputs(inputs, true);
    drive.run_to_end();
    let log = drive.run.take_input_log();
    let (report, trace) = drive.finish();
    (report, log, trace)
}

/// Simulates from power-up to the end.
pub(in crate::simulate) fn run(
    table: &StepTable,
    program: &StepProgram,
    code: &PlcProgram,
    settings: &SimSettings,
    record: Option<io::IoSignals>,
    stepping: Stepping,
) -> (SimReport, Option<io::IoTrace>) {
    let mut drive = Drive::new(table, program, code, settings, record, stepping);
    drive.run_to_end();
    drive.finish()
}
