//! Executes the step program exactly as the program module defines it: one
//! scan advances the timers, may fire the awaited step, then runs every rung.
//! This is the same model the `.st` and `.fst.txt` are rendered from.
//!
//! For speed the program is compiled once into signal indices, so a scan
//! touches plain vectors rather than maps.

use crate::program::Signal;
use crate::program::{Action, Literal, RungKind, StepProgram};

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Lit {
    index: usize,
    negated: bool,
    input: bool,
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Op {
    Set(usize),
    Reset(usize),
    Start(usize, u64),
    /// The sequence goes back to STEP 1.
    Restart,
}

#[derive(Debug, Clone, PartialEq, Eq)]
struct Rule {
    condition: Vec<Lit>,
    actions: Vec<Op>,
}

/// A step's jump: when `rule` holds, step `fires` fires in its place and
/// the sequence waits at `next`.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Jump {
    rule: Rule,
    fires: usize,
    next: usize,
}

/// The step program compiled into signal indices, once for every run of
/// it (the fault analysis runs one program dozens of times).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlcProgram {
    /// Every signal the program uses, by index.
    signals: Vec<Signal>,
    /// The index of each: hashed, not a tree of signal comparisons (a
    /// stalled fault run looks up every output of the machine).
    index: foldhash::HashMap<Signal, usize>,
    steps: Vec<Rule>,
    /// Per step, its jumps in the order they are tested.
    jumps: Vec<Vec<Jump>>,
    rungs: Vec<Rule>,
    /// Each rung's kind: what abandoned a cycle (manual mode, RESET, a
    /// STOP at once), and which rung ends homing.
    kinds: Vec<RungKind>,
    /// The index of the `homing` memory, if the program homes.
    homing: Option<usize>,
    init: Vec<Op>,
}

impl PlcProgram {
    pub fn compile(program: &StepProgram) -> Self {
        // Every signal named by a condition or an action, indexed once.
        let jumps = program.steps.iter().flat_map(|s| &s.jumps);
        let mut signals: Vec<Signal> = program
            .steps
            .iter()
            .flat_map(|s| s.condition.iter())
            .chain(jumps.clone().flat_map(|j| &j.condition))
            .chain(program.rungs.iter().flat_map(|r| r.condition.iter()))
            .map(|l| l.signal)
            .chain(
                program
                    .steps
                    .iter()
                    .flat_map(|s| &s.actions)
                    .chain(program.rungs.iter().flat_map(|r| &r.actions))
                    .chain(jumps.flat_map(|j| &j.actions))
                    .chain(&program.init)
                    .map(|a| a.signal()),
            )
            .collect();
        signals.sort();
        signals.dedup();
        let index: foldhash::HashMap<Signal, usize> =
            signals.iter().enumerate().map(|(i, s)| (*s, i)).collect();
        let rules = |rules: &mut dyn Iterator<Item = (&[Literal], &[Action])>| {
            rules
                .map(|(condition, actions)| compile(&index, condition, actions))
                .collect()
        };
        PlcProgram {
            steps: rules(
                &mut program
                    .steps
                    .iter()
                    .map(|s| (&s.condition[..], &s.actions[..])),
            ),
            jumps: program
                .steps
                .iter()
                .map(|s| {
                    s.jumps
                        .iter()
                        .map(|j| Jump {
                            rule: compile(&index, &j.condition, &j.actions),
                            fires: j.fires,
                            next: j.next,
                        })
                        .collect()
                })
                .collect(),
            rungs: rules(
                &mut program
                    .rungs
                    .iter()
                    .map(|r| (&r.condition[..], &r.actions[..])),
            ),
            kinds: program.rungs.iter().map(|r| r.kind).collect(),
            homing: index.get(&Signal::Homing).copied(),
            init: compile(&index, &[], &program.init).actions,
            signals,
            index,
        }
    }
}

/// Bits by index, 64 to a word (and how many): a state is hashed at
/// every scan of a fault run, a word at a time.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Bits(Vec<u64>, usize);

impl Bits {
    fn new(len: usize) -> Bits {
        Bits(vec![0; len.div_ceil(64)], len)
    }

    #[inline]
    fn get(&self, i: usize) -> bool {
        self.0[i / 64] >> (i % 64) & 1 == 1
    }

    /// Sets bit `i` to `on`; whether it changed.
    #[inline]
    fn put(&mut self, i: usize, on: bool) -> bool {
        let (word, mask) = (&mut self.0[i / 64], 1u64 << (i % 64));
        let was = *word & mask != 0;
        if on {
            *word |= mask;
        } else {
            *word &= !mask;
        }
        was != on
    }
}

/// The PLC's memory: the awaited step, outputs, internal bits and timers.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PlcState<'a> {
    /// Index into `program.steps` of the step the sequence waits to fire.
    pub awaited: usize,
    code: &'a PlcProgram,
    /// Outputs, memories and running timers currently on.
    bits: Bits,
    /// Running timers: elapsed and preset milliseconds, by signal index.
    timers: Vec<Option<(u64, u64)>>,
    /// The indices of the running timers, so that a scan visits only them.
    running: Vec<usize>,
}

impl<'a> PlcState<'a> {
    /// Power-up state: waiting at step 1, everything off, then the program's
    /// initial actions.
    pub fn new(code: &'a PlcProgram) -> Self {
        let mut state = PlcState {
            awaited: 0,
            code,
            bits: Bits::new(code.signals.len()),
            timers: vec![None; code.signals.len()],
            running: Vec::new(),
        };
        let _ = state.apply(&code.init);
        state
    }

    /// The index of a signal, if the program uses it.
    pub fn index_of(&self, signal: Signal) -> Option<usize> {
        self.code.index.get(&signal).copied()
    }

    /// Every signal the program uses, by index.
    pub fn signals(&self) -> &'a [Signal] {
        &self.code.signals
    }

    /// The signal at an index.
    pub fn signal(&self, index: usize) -> Signal {
        self.code.signals[index]
    }

    /// Whether an output or memory bit (or a running timer) is on.
    pub fn bit(&self, signal: Signal) -> bool {
        self.index_of(signal).is_some_and(|i| self.bits.get(i))
    }

    /// Feeds what decides the PLC's next scans (the awaited step, every
    /// bit, every timer) to `hasher`.
    pub fn hash_state(&self, hasher: &mut impl std::hash::Hasher) {
        use std::hash::Hash;
        for word in &self.bits.0 {
            hasher.write_u64(*word);
        }
        // The running timers alone, as a sum of each one's hash: the same
        // timers hash alike in whatever order they started, and most of a
        // long table's timers are off.
        use std::hash::BuildHasher;
        let each = foldhash::quality::FixedState::with_seed(0x7173);
        let running = self
            .running
            .iter()
            .filter_map(|&i| Some((i, self.timers[i]?)));
        let timers = running.fold(0u64, |sum, timer| sum.wrapping_add(each.hash_one(timer)));
        (self.awaited, self.bits.1, self.running.len(), timers).hash(hasher);
    }

    /// The same by index.
    pub fn bit_at(&self, index: usize) -> bool {
        self.bits.get(index)
    }

    /// Applies `actions`; returns whether any of them changed the state (a
    /// timer started again counts: its elapsed time went back to 0).
    fn apply(&mut self, actions: &[Op]) -> bool {
        let mut changed = false;
        for action in actions {
            match *action {
                Op::Set(i) => {
                    changed |= self.bits.put(i, true);
                }
                Op::Reset(i) => {
                    changed |= self.bits.put(i, false);
                    if self.timers[i].take().is_some() {
                        changed = true;
                        self.running.retain(|r| *r != i);
                    }
                }
                Op::Start(i, preset) => {
                    changed = true;
                    self.bits.put(i, true);
                    if self.timers[i].replace((0, preset)).is_none() {
                        self.running.push(i);
                    }
                }
                Op::Restart => {
                    changed |= self.awaited != 0;
                    self.awaited = 0;
                }
            }
        }
        changed
    }

    /// Advances every running timer by one scan; a timer whose preset has
    /// elapsed stops (its bit goes off). Returns whether one did.
    fn advance_timers(&mut self, scan_ms: u64) -> bool {
        let mut expired = false;
        let (timers, bits) = (&mut self.timers, &mut self.bits);
        self.running.retain(|&i| {
            let Some((elapsed, preset)) = &mut timers[i] else {
                return false;
            };
            *elapsed += scan_ms;
            if *elapsed >= *preset {
                timers[i] = None;
                bits.put(i, false);
                expired = true;
                return false;
            }
            true
        });
        expired
    }

    /// How many scans from now may pass with no timer running out: the
    /// scan in which the first one does is not among them.
    pub fn scans_before_a_timer_ends(&self, scan_ms: u64) -> u64 {
        self.running
            .iter()
            .filter_map(|&i| self.timers[i])
            .map(|(elapsed, preset)| (preset - elapsed).div_ceil(scan_ms) - 1)
            .min()
            .unwrap_or(u64::MAX)
    }

    /// `scans` quiet scans at once: the running timers advance, nothing else
    /// changes (the caller has made sure none runs out, see
    /// [`PlcState::scans_before_a_timer_ends`]).
    pub fn pass_quiet_scans(&mut self, scans: u64, scan_ms: u64) {
        for &i in &self.running {
            if let Some((elapsed, _)) = &mut self.timers[i] {
                *elapsed += scans * scan_ms;
            }
        }
    }

    fn homing(&self) -> bool {
        self.code.homing.is_some_and(|i| self.bits.get(i))
    }

    fn holds(&self, condition: &[Lit], input: &dyn Fn(usize) -> bool) -> bool {
        condition.iter().all(|l| {
            let raw = if l.input {
                input(l.index)
            } else {
                self.bits.get(l.index)
            };
            raw != l.negated
        })
    }
}

fn compile(
    index: &foldhash::HashMap<Signal, usize>,
    condition: &[Literal],
    actions: &[Action],
) -> Rule {
    let at = |s: Signal| index.get(&s).copied().unwrap_or(0);
    Rule {
        condition: condition
            .iter()
            .map(|l| Lit {
                index: at(l.signal),
                negated: l.negated,
                input: l.signal.is_input(),
            })
            .collect(),
        actions: actions
            .iter()
            .map(|a| match *a {
                Action::Reset(Signal::Sequence) => Op::Restart,
                Action::Set(s) => Op::Set(at(s)),
                Action::Reset(s) => Op::Reset(at(s)),
                Action::StartTimer(s, ms) => Op::Start(at(s), ms as u64),
            })
            .collect(),
    }
}

/// What one scan did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ScanResult {
    /// Index of the step that fired in this scan, if any.
    pub fired: Option<usize>,
    /// Index of the step the sequence waited at when one fired: the step
    /// before it is the one that was done (a jump fires another step).
    pub waited_at: usize,
    /// Which of that step's jumps fired it, if one did (its place among
    /// the step's jumps, which is its place in the table's cell order).
    pub jumped: Option<usize>,
    /// Whether the scan changed the PLC's state beyond its timers' elapsed
    /// time: a step fired, a bit went on or off, a timer started or ran out.
    /// A scan that changed nothing is repeated exactly by the next one that
    /// reads the same inputs, until a timer runs out.
    pub changed: bool,
    /// A rung sent the sequence back to step 0 from the step it waited at
    /// (manual mode, RESET, a STOP at once): the cycle under way was
    /// abandoned, not finished.
    pub abandoned: Option<Abandoned>,
    /// Homing ended with the machine home (its last stage's rung), not cut
    /// short by manual mode or a STOP.
    pub homed: bool,
}

/// A cycle abandoned by a rung: where the sequence waited, and the kind of
/// rung that sent it back to step 0.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Abandoned {
    /// Index of the step the sequence waited at.
    pub waited_at: usize,
    pub by: RungKind,
}

/// Runs one PLC scan of `scan_ms` milliseconds. `input` gives the value of an
/// input signal as read at the start of the scan.
pub fn scan(state: &mut PlcState, input: &dyn Fn(Signal) -> bool, scan_ms: u64) -> ScanResult {
    let code = state.code;
    scan_indexed(state, &|i| input(code.signals[i]), scan_ms)
}

/// The same, `input` reading a signal by its index in the program
/// ([`PlcState::signals`]): a reader that resolved each input once
/// reads it without a lookup.
pub fn scan_indexed(
    state: &mut PlcState,
    input: &dyn Fn(usize) -> bool,
    scan_ms: u64,
) -> ScanResult {
    let code = state.code;
    let mut changed = state.advance_timers(scan_ms);
    let mut fired = None;
    let awaited = state.awaited;
    let mut jumped = None;
    // A jump is tested before the step it leaves out.
    if let Some((n, jump)) = code.jumps.get(awaited).and_then(|jumps| {
        jumps
            .iter()
            .enumerate()
            .find(|(_, j)| state.holds(&j.rule.condition, input))
    }) {
        jumped = Some(n);
        state.apply(&jump.rule.actions);
        fired = Some(jump.fires);
        changed = true;
        state.awaited = jump.next;
    } else if let Some(step) = code.steps.get(awaited)
        && state.holds(&step.condition, input)
    {
        state.apply(&step.actions);
        fired = Some(awaited);
        changed = true;
        state.awaited = (awaited + 1) % code.steps.len();
    }
    let mut abandoned = None;
    let mut homed = false;
    for (rung, kind) in code.rungs.iter().zip(&code.kinds) {
        if state.holds(&rung.condition, input) {
            let (waiting, homing) = (state.awaited, state.homing());
            changed |= state.apply(&rung.actions);
            if state.awaited != waiting && abandoned.is_none() {
                abandoned = Some(Abandoned {
                    waited_at: waiting,
                    by: *kind,
                });
            }
            homed |= *kind == RungKind::Homing && homing && !state.homing();
        }
    }
    ScanResult {
        fired,
        waited_at: awaited,
        jumped,
        changed,
        abandoned,
        homed,
    }
}
