//! The healthy run as the fault analysis uses it: copied at the scans where
//! faults appear, so that each faulty run starts there instead of at
//! power-up, and fingerprinted at every scan it ran, so that a faulty run
//! that has come back to exactly the healthy state can stop: from there on
//! it is the healthy run until its faulty input next reads otherwise. The
//! runs of one fault set are fingerprinted too: a run that stands where an
//! earlier run under the same faults stood at the same scan goes on as it
//! did (a sensor stuck at a value nothing reads yet changes nothing until
//! the step that reads it, whenever the fault appeared before).

use foldhash::HashMap;
use std::hash::{BuildHasher, Hash, Hasher};

use super::cycle::Drive;
use super::*;

/// Copies of one run at chosen scans, and a fingerprint of its state at
/// every scan it ran.
pub struct Checkpoints<'a> {
    /// By time: a run whose onset has no copy of its own starts from the
    /// latest copy before it (until the onset it is the healthy run).
    at: std::collections::BTreeMap<u64, Drive<'a>>,
    /// By time, in order: where the cycle stood (checked first, it is
    /// cheap) and the fingerprint.
    fingerprints: Vec<(u64, Progress, u64)>,
    /// The run's report.
    pub report: SimReport,
    /// When each input changed, when it was asked for: the run is then the
    /// healthy run a fault analysis is measured against, as
    /// [`crate::simulate::Simulator::run_recorded`] gives it.
    pub log: Option<io::InputLog>,
}

/// How a resumed run ended.
#[derive(Debug)]
pub enum Resumed {
    /// It ran to its end (or its first hazard).
    Report(Box<SimReport>),
    /// At the scan of this time it stood exactly where the healthy run
    /// stood, with nothing found yet.
    InStep { at_ms: u64 },
    /// It stood where an earlier run under the same faults stood at the
    /// same scan, nothing found yet by either: it ends as that run did.
    /// The number is the one that run's states were kept under.
    Joined { run: usize },
}

/// The states runs under one fault set passed through with nothing found
/// yet: (scan time, fingerprint), each with the number of the run (the
/// caller's) that went on from it. foldhash, like the fingerprints: looked
/// up at every onset of every run.
pub type Trail = HashMap<(u64, u64), usize>;

/// Where a run's cycle stands: the cycle, the steps fired in it, the step
/// awaited. Runs that differ here differ; runs that agree are compared by
/// fingerprint.
type Progress = (usize, usize, usize);

impl<'a> Drive<'a> {
    fn progress(&self) -> Progress {
        (self.cycle, self.fire_times.len(), self.run.plc.awaited)
    }

    /// A copy to resume from later: without what only the run's own report
    /// needs (the diagram's trace and step positions, the dwell spans, the
    /// places reached, the recorded I/O, the log of its inputs).
    fn snapshot(&mut self) -> Drive<'a> {
        let kept = (
            std::mem::take(&mut self.run.trace),
            std::mem::take(&mut self.run.visited),
            std::mem::take(&mut self.run.spans),
            std::mem::take(&mut self.step_positions),
            self.run.io.take(),
            self.run.input_log.take(),
        );
        let copy = self.clone();
        (
            self.run.trace,
            self.run.visited,
            self.run.spans,
            self.step_positions,
            self.run.io,
            self.run.input_log,
        ) = kept;
        copy
    }

    /// A hash of everything that decides what the run does from here on
    /// and what its report will say (the time is the caller's key): two
    /// runs with the same fingerprint at the same time, reading the same
    /// inputs, go on alike. 64 bits: a false match is a one in 10^19 event.
    /// foldhash's quality hasher, not SipHash: the fingerprint is taken at
    /// every scan of every run, and nothing here is an attacker's input.
    fn fingerprint(&self) -> u64 {
        let mut h = foldhash::quality::FixedState::with_seed(0x5eed).build_hasher();
        (
            self.stage,
            self.cycle,
            self.press_at,
            self.last_event,
            (self.fired, self.fire_times.len()),
            self.report.press_ms,
            (self.ended, self.cycles.len()),
        )
            .hash(&mut h);
        let run = &self.run;
        run.plc.hash_state(&mut h);
        for p in &run.world.pistons {
            (p.s.to_bits(), p.spool).hash(&mut h);
        }
        (
            run.world.start_pressed,
            run.world.operator,
            &run.world.machine,
            &run.pending,
            &run.answered,
            run.jump_given,
            &run.declined,
            &run.dwells,
            run.alarmed,
            run.hazard_seen,
        )
            .hash(&mut h);
        // Each move in three words, and which pistons have a last move 64
        // to a word: a long line has a last move per piston, hashed field
        // by field they were a third of the fingerprint. (A piston's index
        // and a step number stay far below 2^32.)
        for a in run.active.iter().chain(run.last_move.iter().flatten()) {
            h.write_u64(a.piston as u64 | (a.step as u64) << 32);
            h.write_u64(u64::from(a.mv.actuator) | u64::from(a.mv.from) << 32);
            h.write_u64(
                u64::from(a.mv.to) | u64::from(a.reached) << 32 | u64::from(a.ran_through) << 33,
            );
        }
        for chunk in run.last_move.chunks(64) {
            let word = chunk.iter().enumerate();
            h.write_u64(word.fold(0, |w, (i, last)| w | u64::from(last.is_some()) << i));
        }
        h.finish()
    }
}

/// `words` hashed onto `hash`: a record's running fingerprint.
pub(super) fn mix(hash: u64, words: &[u64]) -> u64 {
    let mut h = foldhash::quality::FixedState::with_seed(hash).build_hasher();
    for w in words {
        h.write_u64(*w);
    }
    h.finish()
}

/// Runs from power-up to the end, copying the run at each of `times` (scan
/// times; one the run never stops at is left out) and fingerprinting it at
/// every scan (or, given `marks`, at those and `times`); logging when
/// `inputs` change when they are given.
pub(in crate::simulate) fn checkpoints<'a>(
    (table, program, code): (&'a StepTable, &'a StepProgram, &'a plc::PlcProgram),
    settings: &SimSettings,
    times: &[u64],
    marks: Option<&[u64]>,
    inputs: Option<Vec<crate::program::Signal>>,
) -> Checkpoints<'a> {
    let mut times: Vec<u64> = times.to_vec();
    times.sort_unstable();
    times.dedup();
    // Fingerprinted at every scan, or where a run resumed from it looks.
    let looked_at = |now: u64| {
        let at = |m: &[u64]| m.binary_search(&now).is_ok();
        marks.is_none_or(|m| at(m) || at(&times))
    };
    let mut copies = times.iter().copied().peekable();
    let mut drive = Drive::new(table, program, code, settings, None, Stepping::Events);
    // Its reads are not logged: runs planned on its log go where inputs differ.
    drive.run.log_inputs(inputs, false);
    let mut at = std::collections::BTreeMap::new();
    let mut fingerprints = Vec::new();
    while !drive.finished() {
        let now = drive.run.time_ms;
        while copies.next_if(|t| *t < now).is_some() {}
        if copies.next_if_eq(&now).is_some() {
            at.insert(now, drive.snapshot());
        }
        if looked_at(now) {
            fingerprints.push((now, drive.progress(), drive.fingerprint()));
        }
        drive.horizon = copies.peek().copied().unwrap_or(u64::MAX);
        drive.advance();
    }
    let log = drive.run.take_input_log();
    Checkpoints {
        at,
        fingerprints,
        report: drive.finish().0,
        log,
    }
}

/// Where a resumed run goes: the healthy run's checkpoints, whether its
/// inputs read as the healthy run's at a time, and the states earlier runs
/// under the same faults passed through at the marked scans.
pub struct Course<'c, 'a> {
    pub checkpoints: &'c Checkpoints<'a>,
    pub in_step: &'c dyn Fn(u64) -> bool,
    pub trail: &'c Trail,
    /// The scan times, in order, at which states are kept on the trail and
    /// looked up there: the faults' onsets, where the later runs start (a
    /// fingerprint at every scan would cost as much as the scan).
    pub marks: &'c [u64],
}

impl Course<'_, '_> {
    /// Whether states are kept and looked up at the scan of `at_ms`.
    fn marked(&self, at_ms: u64) -> bool {
        self.marks.binary_search(&at_ms).is_ok()
    }

    /// The earlier run that stood at the scan of `at_ms` in the state of
    /// `fingerprint`, if one did.
    fn earlier_run(&self, at_ms: u64, fingerprint: u64) -> Option<usize> {
        self.trail.get(&(at_ms, fingerprint)).copied()
    }
}

impl Checkpoints<'_> {
    /// Where the run's cycle stood at the scan of `at_ms`, and its
    /// fingerprint, if it ran that scan.
    fn state_at(&self, at_ms: u64) -> Option<(Progress, u64)> {
        let k = self
            .fingerprints
            .binary_search_by_key(&at_ms, |(at, _, _)| *at)
            .ok()?;
        let (_, progress, fingerprint) = self.fingerprints[k];
        Some((progress, fingerprint))
    }
}

/// Runs under `settings` (their faults appearing at `from_ms`) from the
/// checkpoint at `from_ms`, or from power-up when there is none. When the
/// checkpointed run passed, the run stops at the first later scan at which
/// `in_step` holds (its inputs read as the healthy run's do) and its state
/// is the healthy run's, with nothing found yet; and at the first marked
/// scan at which it stands where the trail says an earlier run stood. The
/// states it passed through at marked scans, its faults appeared and
/// nothing found yet, are added to `passed`.
pub(in crate::simulate) fn resume<'a>(
    course: &Course<'_, 'a>,
    table: &'a StepTable,
    program: &'a StepProgram,
    code: &'a plc::PlcProgram,
    settings: &SimSettings,
    passed: &mut Vec<(u64, u64)>,
) -> Resumed {
    let checkpoints = course.checkpoints;
    let from_ms = settings.fault_onset_ms;
    let mut drive = match checkpoints.at.range(..=from_ms).next_back() {
        Some((_, checkpoint)) => {
            // Standing where an earlier run stood from the start (until its
            // onset a run is the healthy one): no copy.
            if checkpoint.run.problems.is_empty()
                && course.marked(from_ms)
                && let Some((_, fingerprint)) = checkpoints.state_at(from_ms)
                && let Some(run) = course.earlier_run(from_ms, fingerprint)
            {
                return Resumed::Joined { run };
            }
            let mut drive = checkpoint.clone();
            drive.run.set_settings(settings);
            drive.horizon = u64::MAX;
            drive
        }
        None => Drive::new(table, program, code, settings, None, Stepping::Events),
    };
    let may_stop = checkpoints.report.passed;
    while !drive.finished() {
        let now = drive.run.time_ms;
        // The faults have appeared (the next scan reads them), nothing found.
        if now >= from_ms && drive.run.problems.is_empty() {
            let mut known = None;
            let mut fingerprint = || *known.get_or_insert_with(|| drive.fingerprint());
            // Not where the faulty input already differs: that would only hand
            // the case over to a run starting at this very scan.
            if may_stop
                && now > from_ms
                && let Some((progress, healthy)) = checkpoints.state_at(now)
                && progress == drive.progress()
                && (course.in_step)(now)
                && fingerprint() == healthy
            {
                return Resumed::InStep { at_ms: now };
            }
            if course.marked(now) {
                let fingerprint = fingerprint();
                if let Some(run) = course.earlier_run(now, fingerprint) {
                    return Resumed::Joined { run };
                }
                passed.push((now, fingerprint));
            }
        }
        drive.advance();
    }
    Resumed::Report(Box::new(drive.finish().0))
}
