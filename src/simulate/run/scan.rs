//! One scan of the PLC and one scan period of the plant, and the quiet
//! scans passed at once: how a run moves on in time.

use super::{Run, read_input};
use crate::simulate::ProblemKind;
use crate::simulate::io;
use crate::simulate::plant::Piston;
use crate::simulate::plc::{ScanResult, scan_indexed};

impl Run<'_> {
    /// One PLC scan plus one scan period of the plant. Returns the index of the
    /// step that fired, if any.
    pub(in crate::simulate) fn tick(&mut self) -> Option<usize> {
        // Inputs are read from the plant as it stands at the start of the
        // scan; the plant does not move while the program runs.
        // The machine gives the inputs its steps wait for.
        let now = self.time_ms;
        self.world.faults_active = now >= self.world.settings.fault_onset_ms;
        let machine = &mut self.world.machine;
        let waiting = self.pending.len();
        self.pending.retain(|(at, name, value)| {
            if *at <= now {
                machine.insert(*name, *value);
                false
            } else {
                true
            }
        });
        let problems = self.problems.len();
        let mut quiet = self.pending.len() == waiting;
        let (result, recorded_inputs) = self.scan_plc(now);
        if let (Some(io), Some(inputs)) = (self.io.as_mut(), recorded_inputs) {
            let on = |at: &Option<usize>| at.is_some_and(|i| self.plc.bit_at(i));
            let outputs = self.io_outputs.iter().map(on).collect();
            io.push(io::ScanIo {
                time_ms: now,
                inputs,
                outputs,
                step: self.program.step_in(self.plc.awaited),
            });
        }
        quiet &= !result.changed;
        self.alarmed |= result.changed && self.alarm_bits.iter().any(|&i| self.plc.bit_at(i));
        self.on_scan(result);
        self.track_dwells(now);

        // Outputs to valves, then the plant moves for one scan period. With
        // the outputs as they were, a piston at rest stays at rest: only the
        // moving ones need a look.
        let mut moved_on = false;
        let mut due = std::mem::take(&mut self.moving);
        if result.changed || !self.event_driven {
            due.clear();
            due.extend(0..self.world.pistons.len());
        }
        for &i in &due {
            let number = self.world.pistons[i].number;
            let (plus_at, minus_at, single_at) = self.coils[i];
            let on = |at: Option<usize>| at.is_some_and(|i| self.plc.bit_at(i));
            let plus = on(plus_at) || on(single_at);
            let minus = on(minus_at);
            let piston = &self.world.pistons[i];
            let was_at_rest = piston.at_rest();
            let was_at = piston.s;
            let kind = piston.valve;
            let actuated = self.world.actuate(i, plus, minus);
            if actuated.conflict {
                let step = self.current_step();
                let who = kind.both_on(number);
                self.problem(
                    ProblemKind::CoilConflict,
                    step,
                    format!("{who} y{number}+ and y{number}- in step {step}"),
                );
            }
            if let Some(direction) = actuated.moved {
                self.check_motion(i, direction);
            }
            // The inputs the next scan reads stay those this one read (a
            // sensor's change is a change of place).
            let piston = &self.world.pistons[i];
            quiet &= piston.at_rest() == was_at_rest;
            if piston.s != was_at {
                let place = piston.place(self.world.settings.window);
                if place != self.places[i] {
                    self.places[i] = place;
                    moved_on = true;
                }
            }
        }
        quiet &= !moved_on;
        if moved_on {
            self.visit();
        }
        due.retain(|&i| self.world.pistons[i].velocity() != 0.0);
        self.moving = due;
        self.time_ms += self.world.settings.scan_ms as u64;
        quiet &= !self.update_reached();
        self.quiet = quiet && self.problems.len() == problems;
        if self.world.settings.record_trace {
            let positions = self
                .world
                .pistons
                .iter()
                .map(Piston::position_units)
                .collect();
            record_point(&mut self.trace, self.time_ms, positions);
        }
        result.fired
    }

    /// One PLC scan on the inputs as the world gives them now, logged
    /// when the run keeps a log; the inputs read, when it records its I/O.
    fn scan_plc(&mut self, now: u64) -> (ScanResult, Option<Vec<bool>>) {
        self.stuck_by_index();
        let world = &self.world;
        let faulty = world.faults_active && !world.settings.faults.is_empty();
        if let Some(log) = self.input_log.as_mut() {
            log.read_until(self.read_marks.take(), now);
            let sources = &self.log_sources;
            log.scan(now, |k| {
                let (signal, source) = sources[k];
                match faulty {
                    true => read_input(signal, world),
                    false => world.read_source(source),
                }
            });
        }
        let recorded_inputs = self.io.as_ref().map(|io| {
            io.signals
                .inputs
                .iter()
                .map(|s| read_input(*s, world))
                .collect::<Vec<bool>>()
        });
        let (sources, stuck) = (&self.sources, &self.stuck.1);
        let (slots, marks) = (&self.log_slot, &self.read_marks);
        let read = |i: usize| {
            if let Some(&Some(k)) = slots.get(i) {
                marks.mark(k);
            }
            if faulty && let Some(&(_, value)) = stuck.iter().find(|(at, _)| *at == i) {
                return value;
            }
            world.read_source(sources[i])
        };
        let scan_ms = self.world.settings.scan_ms as u64;
        (scan_indexed(&mut self.plc, &read, scan_ms), recorded_inputs)
    }

    /// What the sequence did in the scan just run: a step fired, or a
    /// cycle abandoned (manual mode, RESET, a STOP at once), which leaves
    /// no step under way: the next cycle starts fresh, and its step 1 is
    /// not "started before" the abandoned step finished.
    fn on_scan(&mut self, result: ScanResult) {
        if let Some(fired) = result.fired {
            self.on_fire(fired, result.waited_at, result.jumped);
        }
        if result.abandoned.is_some() {
            self.active.clear();
        }
        self.last_scan = Some(result);
        self.start_before = self.world.start_pressed || self.world.operator.start;
        self.step_before = self.world.operator.step;
        self.step_mode_before = self.world.operator.step_mode;
    }

    /// The SFC step the machine is in (symbols' numbering: 0 at rest, k
    /// while table step k's moves run): what every problem reports as its
    /// step, so that the fault table's `step` column means one thing.
    pub(in crate::simulate) fn current_step(&self) -> usize {
        self.program.step_in(self.plc.awaited)
    }

    /// After a quiet scan, passes at once every following scan that is
    /// certain to be quiet too and to start before `until_ms` (when the
    /// caller changes what the operator does or checks the time): the same
    /// PLC state reading the same inputs does the same nothing, so only the
    /// timers and the moving pistons advance. It stops short of the scan in
    /// which a timer runs out, the machine answers, or a piston reaches a
    /// sensor's edge, an end or the point where it would run through its
    /// target; those scans run one by one. The pistons advance scan by scan
    /// so that every position is the very number the stepper computes.
    pub(in crate::simulate) fn pass_quiet_scans(&mut self, until_ms: u64) {
        if !(self.event_driven && self.quiet) {
            return;
        }
        let scan = self.world.settings.scan_ms as u64;
        let window = self.world.settings.window;
        let mut scans = until_ms
            .saturating_sub(self.time_ms)
            .div_ceil(scan)
            .min(self.plc.scans_before_a_timer_ends(scan));
        let onset = (!self.world.faults_active).then_some(self.world.settings.fault_onset_ms);
        if let Some(at) = self.pending.iter().map(|(at, _, _)| *at).chain(onset).min() {
            scans = scans.min(at.saturating_sub(self.time_ms).div_ceil(scan));
        }
        for &i in &self.moving {
            let p = &self.world.pistons[i];
            // Where the run would see the piston run through its target.
            let mark = self.last_move[i]
                .as_ref()
                .filter(|a| !a.ran_through)
                .map(|a| a.run_through_bounds(p, window));
            scans = p.scans_before_an_event(window, mark, scans);
        }
        if scans == 0 {
            return;
        }
        if let Some(io) = self.io.as_mut() {
            io.repeat_last(scans, scan);
        }
        for &i in &self.moving {
            let p = &mut self.world.pistons[i];
            for _ in 0..scans {
                p.advance();
            }
        }
        self.plc.pass_quiet_scans(scans, scan);
        self.time_ms += scans * scan;
        if self.world.settings.record_trace {
            let positions = self.positions();
            record_point(&mut self.trace, self.time_ms, positions);
        }
    }

    pub(in crate::simulate) fn positions(&self) -> Vec<f64> {
        self.world
            .pistons
            .iter()
            .map(Piston::position_units)
            .collect()
    }
}

/// Adds a point to the position trace, keeping only the corners of the
/// polyline: a point on the straight line through the two before it
/// replaces the last one. A 1,200 s stroke at a 1 ms scan kept 4.7 million
/// points (692 MB, a 67 MB diagram) for a handful of straight lines.
pub(super) fn record_point(trace: &mut Vec<(u64, Vec<f64>)>, time_ms: u64, positions: Vec<f64>) {
    if let [.., (t0, p0), (t1, p1)] = trace.as_slice() {
        let (dt0, dt1) = ((t1 - t0) as f64, (time_ms - t1) as f64);
        let straight = p0.iter().zip(p1).zip(&positions).all(|((a, b), c)| {
            // Same speed before and after the middle point, to well below
            // what a diagram can show.
            ((b - a) * dt1 - (c - b) * dt0).abs() <= 1e-9 * dt0 * dt1
        });
        if straight {
            *trace.last_mut().expect("two points") = (time_ms, positions);
            return;
        }
    }
    trace.push((time_ms, positions));
}
