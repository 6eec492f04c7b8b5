//! The machine around the cylinders, as the simulator plays it: it answers
//! the inputs steps wait for (and takes the answers back once the sequence
//! has moved on), and it watches that dwells and waits were really met, not
//! passed on a faulty input.

use super::{Run, sensor_symbol};
use crate::cell::Name;
use crate::program::StepKind;
use crate::simulate::{ProblemKind, Span};
use crate::table::StepTable;

impl Run<'_> {
    /// Notes when each dwell timer starts and stops (for the step timing
    /// and the diagram).
    pub(super) fn track_dwells(&mut self, now: u64) {
        for i in 0..self.dwells.len() {
            let (at, number, started) = self.dwells[i];
            match (self.plc.bit_at(at), started) {
                (true, None) => {
                    self.dwells[i].2 = Some(now);
                    self.check_dwell_start(number);
                }
                (false, Some(from)) => {
                    self.dwells[i].2 = None;
                    let ms = self
                        .table
                        .dwells()
                        .find(|d| d.number == number)
                        .map_or(0, |d| d.ms);
                    self.spans.push(Span {
                        from_ms: from,
                        to_ms: now,
                        label: crate::cell::dwell_text(ms),
                    });
                }
                _ => {}
            }
        }
    }

    /// A dwell must start only once its branch is really done: its moves at
    /// their targets and its waits answered by the machine, not by a faulty
    /// input.
    pub(super) fn check_dwell_start(&mut self, number: u16) {
        let Some((step, dwell)) = self
            .table
            .steps
            .iter()
            .find_map(|s| s.dwells.iter().find(|d| d.number == number).map(|d| (s, d)))
        else {
            return;
        };
        let mut missing: Vec<String> = step
            .branch_moves(dwell.branch)
            .filter(|m| {
                !self
                    .active
                    .iter()
                    .any(|a| a.mv.actuator == m.actuator && a.reached)
            })
            .map(|m| format!("C{} reached {}", m.actuator, sensor_symbol(self.program, m)))
            .collect();
        missing.extend(
            step.waits
                .iter()
                .filter(|w| w.branch == dwell.branch && !self.machine_gave(w))
                .map(|w| format!("the machine gave {}", wait_text(w))),
        );
        if !missing.is_empty() {
            self.problem(
                ProblemKind::Premature,
                step.number,
                format!(
                    "dwell {} ({}) of step {} started before {}",
                    number,
                    crate::cell::dwell_text(dwell.ms),
                    step.number,
                    missing.join(" and ")
                ),
            );
        }
    }

    /// Whether the machine itself (not a faulty input) gives what `wait` asks.
    pub(super) fn machine_gave(&self, wait: &crate::table::Wait) -> bool {
        self.machine_gives(wait.input, wait.value)
    }

    /// Whether the machine itself (not a faulty input) gives `input` = `value`.
    fn machine_gives(&self, input: Name, value: bool) -> bool {
        self.world.machine.get(&input).copied().unwrap_or(false) == value
    }

    /// What the machine does when a step fires: check the waits of the step
    /// that ended, take back old answers, schedule the new step's.
    pub(super) fn machine_on_fire(
        &mut self,
        fired: usize,
        waited_at: usize,
        jumped: Option<usize>,
    ) {
        let step = &self.program.steps[fired];
        // The step that just ended must have had its waits answered by the
        // machine: one that read true only through a fault let the sequence
        // run on without the part. (After a jump, the step done is the
        // jump's own, not the one before the step that fired.)
        if let Some(n) = jumped {
            self.check_jump(n, fired, waited_at);
        }
        if let Some(done) = waited_at
            .checked_sub(1)
            .and_then(|i| self.table.steps.get(i))
        {
            let skipped: Vec<String> = done
                .waits
                .iter()
                .filter(|w| !self.machine_gave(w))
                .map(wait_text)
                .collect();
            if !skipped.is_empty() {
                // The closing transition is no table step: the cycle ended.
                let started = match step.kind {
                    crate::program::StepKind::EndOfCycle => "the cycle ended".to_string(),
                    _ => format!("step {} started", step.number),
                };
                self.problem(
                    ProblemKind::Premature,
                    self.program.step_entered(fired),
                    format!(
                        "{started} before the machine gave {}",
                        skipped.join(" and ")
                    ),
                );
            }
        }
        // The machine withdraws its answers once the sequence has moved on
        // (the part was taken, the door closed again): each input goes back
        // to its rest value.
        // An input the new step waits for with the same value stays as it is
        // (the part is still there).
        let still_wanted: Vec<(Name, bool)> = match step.kind {
            StepKind::Table => self
                .table
                .steps
                .get(fired)
                .map(|s| s.waits.iter().map(|w| (w.input, w.value)).collect())
                .unwrap_or_default(),
            StepKind::EndOfCycle => Vec::new(),
        };
        for name in std::mem::take(&mut self.answered) {
            let current = self.world.machine.get(&name).copied();
            if current.is_some_and(|v| still_wanted.contains(&(name, v))) {
                continue;
            }
            self.pending.retain(|(_, n, _)| *n != name);
            if let Some(rest) = rest_value(self.table, name) {
                self.world.machine.insert(name, rest);
            }
        }
        if step.kind == StepKind::Table
            && let Some(table_step) = self.table.steps.get(fired)
        {
            for wait in &table_step.waits {
                let delay = self.world.settings.input_delay_ms(&wait.input) as u64;
                let now = self.time_ms;
                self.answered.push(wait.input);
                if !self.machine_gave(wait) {
                    self.pending.push((now + delay, wait.input, wait.value));
                    self.spans.push(Span {
                        from_ms: now,
                        to_ms: now + delay,
                        label: format!("I:{}", wait.input),
                    });
                }
            }
        }
        // Every jump of the step that fired is tested once the step is
        // done: the machine gives each jump input the value this cycle's
        // path needs, from the step's start (a step shorter than the input
        // delay must still see it) unless `--input-delay` names the input.
        // The cycle that takes a jump gives its value once (a jump back
        // must not loop for ever); every other jump is not taken.
        if step.kind == StepKind::Table
            && let Some(table_step) = self.table.steps.get(fired)
        {
            for jump in &table_step.jumps {
                let take = !self.jump_given && self.jump_taken == Some((fired, *jump));
                self.jump_given |= take;
                let value = if take { jump.value } else { !jump.value };
                self.pending.retain(|(_, n, _)| *n != jump.input);
                if !self.answered.contains(&jump.input) {
                    self.answered.push(jump.input);
                }
                let delay = self.world.settings.input_delays.get(&jump.input);
                match delay {
                    Some(&ms) if take && ms > 0 => {
                        self.world.machine.insert(jump.input, !value);
                        self.pending
                            .push((self.time_ms + u64::from(ms), jump.input, value));
                    }
                    _ => {
                        self.world.machine.insert(jump.input, value);
                    }
                }
                if !take {
                    self.declined.push((fired + 1, jump.notation()));
                }
            }
        }
    }
}

impl Run<'_> {
    /// A jump fired: the machine must have given its input. One taken on
    /// a faulty input sends the machine down a path nobody asked for.
    /// `n` is the jump's place among its step's jumps.
    fn check_jump(&mut self, n: usize, fired: usize, waited_at: usize) {
        let Some(jump) = waited_at
            .checked_sub(1)
            .and_then(|i| self.table.steps.get(i))
            .and_then(|s| s.jumps.get(n))
            .copied()
        else {
            return;
        };
        if !self.machine_gives(jump.input, jump.value) {
            self.problem(
                ProblemKind::Premature,
                self.program.step_entered(fired),
                format!(
                    "the sequence took {} after step {waited_at} although the machine did not give I:{}={}",
                    jump.notation(),
                    jump.input,
                    u8::from(jump.value)
                ),
            );
        }
    }
}

/// What a machine input reads while no step waits for it: the opposite of
/// what its first wait asks for (no part yet, door not yet open).
/// An input only jumps on rests at the value that does not jump.
pub(super) fn rest_value(table: &StepTable, input: Name) -> Option<bool> {
    let waits = table.steps.iter().flat_map(|s| &s.waits);
    let jumps = table.steps.iter().flat_map(|s| &s.jumps);
    waits
        .filter(|w| w.input == input)
        .map(|w| !w.value)
        .chain(jumps.filter(|j| j.input == input).map(|j| !j.value))
        .next()
}

/// `part_present=1`.
fn wait_text(w: &crate::table::Wait) -> String {
    format!("{}={}", w.input, u8::from(w.value))
}

/// The operator's own motion in manual mode.
impl Run<'_> {
    /// Whether a motion is the operator's in manual mode: its jog button is
    /// held, or it is what its valve does after a jog without a coil on (a
    /// 5/2 bistable finishes the stroke a jog began, a single-solenoid
    /// valve's spring retracts, a 5/3 centre lets a load drift). A 5/3
    /// closed centre and a drive stop on release: their motion without the
    /// button stays unintended.
    pub(in crate::simulate) fn jogged(&self, piston: usize, direction: crate::cell::Sign) -> bool {
        let p = &self.world.pistons[piston];
        let read = |s| self.read(s);
        if !self
            .program
            .signals
            .inputs
            .contains(&crate::program::Signal::ManualMode)
            || !read(crate::program::Signal::ManualMode)
        {
            return false;
        }
        let jog = crate::program::Signal::Jog {
            actuator: p.number,
            sign: direction,
        };
        read(jog) || p.valve.moves_on_after_a_jog()
    }
}
