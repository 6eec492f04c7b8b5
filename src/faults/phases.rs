//! When a fault appears: from power-up, or at a moment of the healthy
//! cycle (before a step fires, while its moves run, during its dwell or
//! wait, at rest after the cycle). A sensor that fails mid-trip can do what
//! the same sensor failed at power-up cannot: the machine is elsewhere.
//!
//! Many moments give the same run. A fault that appears while the input
//! reads, in the healthy run, the very value it sticks at changes nothing
//! until the healthy input would leave that value: the run is the one the
//! fault gives appearing then. Moments are merged on that first scan on
//! which the faulty input differs from the healthy one (a fault that never
//! differs has no effect and needs no run at all).

use crate::simulate::io::InputLog;
use crate::simulate::{Fault, SimReport};
use crate::table::StepTable;

/// A moment of the healthy cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Phase {
    PowerUp,
    /// The sequence waits at the step, its condition not yet met.
    BeforeStep(usize),
    /// The step has fired; its moves are under way.
    Moving(usize),
    /// The step's dwell runs or it waits for a machine input.
    Waiting(usize),
    /// The cycle has ended; the machine waits for START.
    AtRest,
}

impl Phase {
    /// `while step 3 moves`, as the fault table says when a fault appears.
    pub fn label(self) -> String {
        match self {
            Phase::PowerUp => "from power-up".to_string(),
            Phase::BeforeStep(k) => format!("before step {k} fires"),
            Phase::Moving(k) => format!("while step {k} moves"),
            Phase::Waiting(k) => format!("during step {k}'s dwell or wait"),
            Phase::AtRest => "at rest after the cycle".to_string(),
        }
    }
}

/// A phase and the time of the run at which faults appear in it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Moment {
    pub phase: Phase,
    pub at_ms: u64,
}

/// Power-up, then for each step of the healthy run's first cycle: the scan
/// before it fires (from step 2 on), the scan after (when it moves
/// something), the middle of each dwell or wait; then rest after the cycle.
pub fn moments(healthy: &SimReport, table: &StepTable, scan_ms: u64) -> Vec<Moment> {
    let mut moments = vec![Moment {
        phase: Phase::PowerUp,
        at_ms: 0,
    }];
    let Some(cycle) = healthy.cycles.first() else {
        return moments;
    };
    for timing in &cycle.steps {
        let step = timing.step;
        let fired = cycle.press_ms + timing.start_ms;
        if step > 1 {
            moments.push(Moment {
                phase: Phase::BeforeStep(step),
                at_ms: fired.saturating_sub(scan_ms),
            });
        }
        let moves = table
            .steps
            .get(step - 1)
            .is_some_and(|s| !s.moves.is_empty());
        if moves {
            moments.push(Moment {
                phase: Phase::Moving(step),
                at_ms: fired + scan_ms,
            });
        }
        let ends = fired + timing.duration_ms;
        if let Some(span) = healthy
            .spans
            .iter()
            .find(|s| s.from_ms >= fired && s.from_ms < ends.max(fired + 1))
        {
            moments.push(Moment {
                phase: Phase::Waiting(step),
                at_ms: (span.from_ms + span.to_ms) / 2,
            });
        }
    }
    if let Some(ms) = cycle.cycle_ms {
        let next = healthy.cycles.get(1).map(|c| c.press_ms);
        let at = cycle.press_ms + ms + 2 * scan_ms;
        if next.is_none_or(|press| at < press) {
            moments.push(Moment {
                phase: Phase::AtRest,
                at_ms: at,
            });
        }
    }
    moments
}

/// The healthy run's inputs, as the times each changes ([`InputLog`]), to
/// tell when a fault first makes a difference.
pub struct HealthyInputs {
    log: InputLog,
    /// A faulty input leaves the healthy run only where the run reads it
    /// while it differs ([`InputLog::reads`]), not where it differs.
    by_reads: bool,
}

/// The onset of a fault that differs from the healthy input but is never
/// read while it does: its run is the healthy one, never left.
pub const NEVER: u64 = u64::MAX;

impl HealthyInputs {
    pub fn new(log: InputLog) -> Self {
        HealthyInputs {
            log,
            by_reads: false,
        }
    }

    /// The same, a faulty run leaving the healthy one where it reads a
    /// faulty input while it differs: until then it reads what the
    /// healthy run reads and does what it does.
    pub fn by_reads(log: InputLog) -> Self {
        HealthyInputs {
            log,
            by_reads: true,
        }
    }

    /// Where faults appearing at `from_ms` leave the healthy run, as
    /// [`HealthyInputs::divergence_of`] says; [`NEVER`] when they differ
    /// but are never read while they do.
    pub fn onset_of(&self, columns: &[(usize, bool)], from_ms: u64) -> Option<u64> {
        self.divergence_of(columns, from_ms)
            .or_else(|| self.plain_divergence(columns, from_ms).map(|_| NEVER))
    }

    /// The log itself.
    pub fn log(&self) -> &InputLog {
        &self.log
    }

    /// Every time at which a faulty run that is back in step with the
    /// healthy one may next leave it: where an input changes or, when runs
    /// leave it [`HealthyInputs::by_reads`], where an input changes while
    /// it is read or starts being read.
    pub fn change_times(&self) -> Box<dyn Iterator<Item = u64> + '_> {
        let changes = self.log.changes.iter().map(|(_, changes)| changes);
        if !self.by_reads {
            return Box::new(changes.flat_map(|c| c.iter().map(|(at, _)| *at)));
        }
        Box::new(changes.zip(&self.log.reads).flat_map(|(changes, reads)| {
            let read = |at: &u64| {
                let span = reads.partition_point(|(_, to)| to <= at);
                reads.get(span).is_some_and(|(from, _)| from <= at)
            };
            let changed = changes.iter().map(|(at, _)| *at).filter(read);
            changed.chain(reads.iter().map(|(from, _)| *from))
        }))
    }

    /// Whether one of `faults` ever reads other than the healthy run did,
    /// at or after `from_ms` (whether it is read then or not).
    pub fn differs(&self, faults: &[Fault], from_ms: u64) -> bool {
        self.plain_divergence(&self.columns(faults), from_ms)
            .is_some()
    }

    /// The faults as (input column, stuck value), for
    /// [`HealthyInputs::divergence_of`] (a faulty run asks at every scan).
    pub fn columns(&self, faults: &[Fault]) -> Vec<(usize, bool)> {
        faults
            .iter()
            .filter_map(|f| {
                let c = self.log.inputs.iter().position(|s| *s == f.signal)?;
                Some((c, f.stuck_at))
            })
            .collect()
    }

    /// Where faults given as columns, appearing at `from_ms`, leave the
    /// healthy run: the first scan at which one reads otherwise or,
    /// [`HealthyInputs::by_reads`], at which one is read while it does.
    pub fn divergence_of(&self, columns: &[(usize, bool)], from_ms: u64) -> Option<u64> {
        if !self.by_reads {
            return self.plain_divergence(columns, from_ms);
        }
        let first =
            |&(c, stuck_at): &(usize, bool)| self.first_read_difference(c, stuck_at, from_ms);
        columns.iter().filter_map(first).min()
    }

    /// The first scan at or after `from_ms` at which one of the faults
    /// given as columns reads otherwise than the healthy run did.
    fn plain_divergence(&self, columns: &[(usize, bool)], from_ms: u64) -> Option<u64> {
        let first = |&(c, stuck_at): &(usize, bool)| self.first_difference(c, stuck_at, from_ms);
        columns.iter().filter_map(first).min()
    }

    /// The first scan at or after `from_ms` at which input `c` is read
    /// while it reads otherwise than `stuck_at`.
    fn first_read_difference(&self, c: usize, stuck_at: bool, from_ms: u64) -> Option<u64> {
        let (changes, reads) = (&self.log.changes[c].1, &self.log.reads[c]);
        let mut from = from_ms;
        loop {
            let differs = self.first_difference(c, stuck_at, from)?;
            // It differs until its next change (two values: back to the
            // stuck one), or to the end.
            let next = changes.partition_point(|(at, _)| *at <= differs);
            let until = changes.get(next).map_or(NEVER, |(at, _)| *at);
            let read = reads.partition_point(|(_, to)| *to <= differs);
            if let Some(&(read_from, _)) = reads.get(read)
                && read_from < until
            {
                return Some(read_from.max(differs));
            }
            if until == NEVER {
                return None;
            }
            from = until;
        }
    }

    fn first_difference(&self, c: usize, stuck_at: bool, from_ms: u64) -> Option<u64> {
        // The first scan at or after `from_ms`.
        let (first_ms, last_ms) = (self.log.first_ms, self.log.last_ms);
        let scan_ms = u64::from(self.log.scan_ms.max(1));
        let from = first_ms + from_ms.saturating_sub(first_ms).div_ceil(scan_ms) * scan_ms;
        if from > last_ms {
            return None;
        }
        let (initial, changes) = &self.log.changes[c];
        let seen = changes.partition_point(|(at, _)| *at <= from);
        let now = if seen == 0 {
            *initial
        } else {
            changes[seen - 1].1
        };
        if now != stuck_at {
            return Some(from);
        }
        changes[seen..]
            .iter()
            .find(|(_, value)| *value != stuck_at)
            .map(|(at, _)| *at)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// One input, scanned every 10 ms from 0 to 100: off until 30, on
    /// until 60, off again; read in [0, 20), [40, 50) and [70, 80).
    fn log() -> InputLog {
        let mut log = InputLog::new(10, vec![crate::program::Signal::Start]);
        log.changes = vec![(false, vec![(30, true), (60, false)])];
        log.reads = vec![vec![(0, 20), (40, 50), (70, 80)]];
        log.reads_logged = true;
        (log.first_ms, log.last_ms) = (0, 100);
        log
    }

    #[test]
    fn a_fault_leaves_the_healthy_run_where_it_is_read_while_it_differs() {
        let (plain, read) = (HealthyInputs::new(log()), HealthyInputs::by_reads(log()));
        let (open, short) = ([(0, false)], [(0, true)]);
        // Stuck at 0: it differs in [30, 60), read there in [40, 50).
        assert_eq!(plain.onset_of(&open, 0), Some(30));
        assert_eq!(read.onset_of(&open, 0), Some(40));
        assert_eq!(read.onset_of(&open, 31), Some(40));
        // From the span's end on it differs unread, then no longer differs.
        assert_eq!(read.onset_of(&open, 50), Some(NEVER));
        // A moment off the scans counts from the next scan (50).
        assert_eq!(read.onset_of(&open, 41), Some(NEVER));
        assert_eq!(read.onset_of(&open, 39), Some(40));
        assert_eq!(read.onset_of(&open, 60), None);
        assert_eq!(plain.onset_of(&open, 60), None);
        // Stuck at 1: it differs in [0, 30) and from 60, read in [0, 20)
        // and [70, 80).
        assert_eq!(read.onset_of(&short, 0), Some(0));
        assert_eq!(read.onset_of(&short, 20), Some(70));
        assert_eq!(plain.onset_of(&short, 20), Some(20));
        assert_eq!(read.onset_of(&short, 65), Some(70));
        assert_eq!(read.onset_of(&short, 71), Some(NEVER));
        assert_eq!(read.onset_of(&short, 80), Some(NEVER));
        // A set leaves where its first fault is read while it differs.
        let both = [(0, true), (0, false)];
        assert_eq!(read.onset_of(&both, 20), Some(40));
        // Where a run back in step may leave again: changes while read
        // (none here) and the spans' beginnings.
        let times: Vec<u64> = read.change_times().collect();
        assert_eq!(times, [0, 40, 70]);
        let plain_times: Vec<u64> = plain.change_times().collect();
        assert_eq!(plain_times, [30, 60]);
    }
}
