//! The PLC's inputs and outputs at every scan of a run, recorded so that a
//! program file can be replayed in another engine (matiec, awlsim, an FST
//! interpreter) and its outputs compared with this simulation scan by scan.
//!
//! Replaying the recorded inputs is the same as driving the engine from the
//! plant until the first scan whose outputs differ: up to there the plant saw
//! the same coils, so it gave the same inputs. The first difference is the
//! finding.

use crate::program::Signal;

/// Which signals to record: the inputs fed to the engine and the outputs
/// compared, each in a fixed order.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct IoSignals {
    pub inputs: Vec<Signal>,
    pub outputs: Vec<Signal>,
    /// Record at most this many scans (the report's timeline, whose memory
    /// and width grow with the scans); `None` records the whole run.
    pub max_scans: Option<usize>,
}

impl IoSignals {
    /// Every input of `program` and every output it drives, then the
    /// alarms and the criteria's `miss` outputs: what a logic analyser on
    /// the machine would show.
    pub fn every(program: &crate::program::StepProgram) -> IoSignals {
        let signals = &program.signals;
        IoSignals {
            inputs: signals.inputs.clone(),
            outputs: signals
                .driven()
                .chain(signals.alarms())
                .chain(signals.misses())
                .collect(),
            max_scans: None,
        }
    }
}

/// One scan: the inputs as read at its start, the outputs as written at its end.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ScanIo {
    /// Time at the start of the scan, from power-up.
    pub time_ms: u64,
    pub inputs: Vec<bool>,
    pub outputs: Vec<bool>,
    /// The step the program is in at the end of the scan, as it shows it
    /// (`active_step`, the AWL step flags, the FST step): 0 at rest, k while
    /// table step k's moves run.
    pub step: usize,
}

/// Every scan of a run.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct IoTrace {
    pub scan_ms: u32,
    pub signals: IoSignals,
    pub scans: Vec<ScanIo>,
    /// The run went on past `signals.max_scans`: `scans` holds its start.
    pub cut: bool,
}

/// The first scan at which an engine's outputs differ from the simulation.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Mismatch {
    pub scan: usize,
    pub time_ms: u64,
    pub signal: Signal,
    pub expected: bool,
    pub actual: bool,
}

impl std::fmt::Display for Mismatch {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "scan {} ({} ms): {} is {} in the engine, {} in the simulation",
            self.scan,
            self.time_ms,
            self.signal.symbol(),
            u8::from(self.actual),
            u8::from(self.expected)
        )
    }
}

/// The inputs a run read, as the scans on which each changed: what the
/// fault analysis asks of the healthy run (when does a faulty input first
/// read otherwise) without a copy of every scan. Quiet scans read what the
/// scan before them read, so only the scans the run steps through are read.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct InputLog {
    pub scan_ms: u32,
    pub inputs: Vec<Signal>,
    /// Per input: its value at the first scan, then `(time, value)` at
    /// every scan on which it changed.
    pub changes: Vec<(bool, Vec<(u64, bool)>)>,
    /// Times of the first and the last scan (none yet: both 0).
    pub first_ms: u64,
    pub last_ms: u64,
    /// Per input: the spans of time `[from, to)` in which the run read it
    /// (the program, or the simulator judging the run): a fault of an
    /// input changes nothing until it is read while it differs. A scan's
    /// reads stand for the quiet scans after it, which read the same.
    pub reads: Vec<Vec<(u64, u64)>>,
    /// The reads were logged (else `reads` says nothing).
    pub reads_logged: bool,
    scanned: bool,
    /// What the last scan read, 64 inputs to a word: a scan is compared
    /// with it a word at a time (most scans change no input).
    now: Vec<u64>,
}

impl InputLog {
    pub fn new(scan_ms: u32, inputs: Vec<Signal>) -> Self {
        InputLog {
            scan_ms,
            changes: vec![(false, Vec::new()); inputs.len()],
            reads: vec![Vec::new(); inputs.len()],
            now: vec![0; inputs.len().div_ceil(64)],
            inputs,
            ..InputLog::default()
        }
    }

    /// The same inputs changing at the same times: the logs of two runs
    /// that read the same machine (whatever each read of it).
    pub fn same_inputs(&self, other: &InputLog) -> bool {
        (
            self.scan_ms,
            &self.inputs,
            &self.changes,
            self.first_ms,
            self.last_ms,
        ) == (
            other.scan_ms,
            &other.inputs,
            &other.changes,
            other.first_ms,
            other.last_ms,
        )
    }

    /// The inputs marked in `marks` (by their place in the log, 64 to a
    /// word) were read from the last scan logged until `until_ms`.
    pub(in crate::simulate) fn read_until(
        &mut self,
        marks: impl Iterator<Item = u64>,
        until_ms: u64,
    ) {
        let from = self.last_ms;
        for (w, mut bits) in marks.enumerate() {
            while bits != 0 {
                let k = w * 64 + bits.trailing_zeros() as usize;
                bits &= bits - 1;
                let spans = &mut self.reads[k];
                match spans.last_mut() {
                    Some(last) if last.1 >= from => last.1 = last.1.max(until_ms),
                    _ => spans.push((from, until_ms)),
                }
            }
        }
    }

    /// The scan at `time_ms` read `read(k)` for the `k`-th input.
    pub(in crate::simulate) fn scan(&mut self, time_ms: u64, read: impl Fn(usize) -> bool) {
        for (w, was) in self.now.iter_mut().enumerate() {
            let end = self.changes.len().min(w * 64 + 64);
            let inputs = &mut self.changes[w * 64..end];
            let word =
                (0..inputs.len()).fold(0u64, |word, b| word | u64::from(read(w * 64 + b)) << b);
            let changed = match self.scanned {
                true => word ^ *was,
                false => u64::MAX,
            };
            if changed != 0 {
                for (b, (first, changes)) in inputs.iter_mut().enumerate() {
                    let value = word >> b & 1 == 1;
                    if !self.scanned {
                        *first = value;
                    } else if changed >> b & 1 == 1 {
                        changes.push((time_ms, value));
                    }
                }
            }
            *was = word;
        }
        if !self.scanned {
            self.first_ms = time_ms;
            self.scanned = true;
        }
        self.last_ms = time_ms;
    }

    /// The log of a trace that recorded every scan's inputs.
    #[cfg(test)]
    pub fn of_trace(trace: &IoTrace) -> Self {
        let mut log = InputLog::new(trace.scan_ms, trace.signals.inputs.clone());
        for scan in &trace.scans {
            log.scan(scan.time_ms, |k| scan.inputs[k]);
        }
        log
    }
}

impl IoTrace {
    /// An empty recording of `signals`.
    pub fn new(scan_ms: u32, signals: IoSignals) -> IoTrace {
        IoTrace {
            scan_ms,
            signals,
            scans: Vec::new(),
            cut: false,
        }
    }

    /// Keeps `scan` unless the recording is full.
    pub(crate) fn push(&mut self, scan: ScanIo) {
        if self
            .signals
            .max_scans
            .is_some_and(|max| self.scans.len() >= max)
        {
            self.cut = true;
        } else {
            self.scans.push(scan);
        }
    }

    /// Records `scans` more scans, `scan_ms` apart, that read and wrote what
    /// the last one did (the quiet scans the run passes at once), within the
    /// same limit as [`IoTrace::push`].
    pub(crate) fn repeat_last(&mut self, scans: u64, scan_ms: u64) {
        let Some(last) = self.scans.last().cloned() else {
            return;
        };
        let room = self
            .signals
            .max_scans
            .map_or(usize::MAX, |max| max.saturating_sub(self.scans.len()));
        let kept = usize::try_from(scans).unwrap_or(usize::MAX).min(room);
        self.cut |= kept < usize::try_from(scans).unwrap_or(usize::MAX);
        self.scans.extend((1..=kept as u64).map(|j| ScanIo {
            time_ms: last.time_ms + j * scan_ms,
            ..last.clone()
        }));
    }

    /// Compares an engine's outputs, one vector per scan in the order of
    /// `signals.outputs`, with the recorded ones. A run that ended early is a
    /// mismatch at the first missing scan.
    pub fn compare(&self, engine: &[Vec<bool>]) -> Result<(), Mismatch> {
        for (scan, recorded) in self.scans.iter().enumerate() {
            let Some(actual) = engine.get(scan) else {
                return Err(Mismatch {
                    scan,
                    time_ms: recorded.time_ms,
                    signal: self
                        .signals
                        .outputs
                        .first()
                        .copied()
                        .unwrap_or(Signal::Start),
                    expected: recorded.outputs.first().copied().unwrap_or(false),
                    actual: !recorded.outputs.first().copied().unwrap_or(false),
                });
            };
            for (k, signal) in self.signals.outputs.iter().enumerate() {
                let expected = recorded.outputs[k];
                let got = actual.get(k).copied().unwrap_or(!expected);
                if got != expected {
                    return Err(Mismatch {
                        scan,
                        time_ms: recorded.time_ms,
                        signal: *signal,
                        expected,
                        actual: got,
                    });
                }
            }
        }
        Ok(())
    }

    /// How many scans turned an output on or off: a trace with none proves
    /// nothing.
    pub fn output_changes(&self) -> usize {
        self.scans
            .windows(2)
            .filter(|w| w[0].outputs != w[1].outputs)
            .count()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::Sign;

    fn trace() -> IoTrace {
        let coil = Signal::Coil {
            actuator: 1,
            sign: Sign::Plus,
        };
        IoTrace {
            scan_ms: 10,
            signals: IoSignals {
                inputs: vec![Signal::Start],
                outputs: vec![coil],
                max_scans: None,
            },
            scans: (0..4)
                .map(|i| ScanIo {
                    time_ms: i * 10,
                    inputs: vec![i == 1],
                    outputs: vec![i >= 1],
                    step: usize::from(i >= 1),
                })
                .collect(),
            cut: false,
        }
    }

    #[test]
    fn passed_quiet_scans_are_recorded_within_the_limit() {
        let mut open = trace();
        open.repeat_last(3, 10);
        assert_eq!(open.scans.len(), 7);
        assert_eq!(open.scans[6].time_ms, 60);
        assert_eq!(open.scans[6].outputs, vec![true]);
        assert!(!open.cut);
        let mut capped = trace();
        capped.signals.max_scans = Some(5);
        capped.repeat_last(1_000_000, 10);
        assert_eq!(capped.scans.len(), 5);
        assert!(capped.cut, "a run past the limit says it was cut");
    }

    #[test]
    fn a_differing_output_names_its_scan_and_signal() {
        let t = trace();
        let mut engine: Vec<Vec<bool>> = t.scans.iter().map(|s| s.outputs.clone()).collect();
        assert_eq!(t.compare(&engine), Ok(()));
        assert_eq!(t.output_changes(), 1);
        engine[2][0] = false;
        let m = t.compare(&engine).unwrap_err();
        assert_eq!(
            (m.scan, m.time_ms, m.expected, m.actual),
            (2, 20, true, false)
        );
        assert_eq!(
            m.to_string(),
            "scan 2 (20 ms): y1+ is 0 in the engine, 1 in the simulation"
        );
        engine.truncate(3);
        engine[2][0] = true;
        assert_eq!(t.compare(&engine).unwrap_err().scan, 3);
    }
}
