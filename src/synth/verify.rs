//! Proof by simulation that a synthesised controller runs its sequence, on
//! the bench every converted program runs on (`simulate::bench`: the same
//! plant, the same scan, the same inputs read): the program as the written
//! files run it ([`Program`], the equations evaluated every 10 ms scan on
//! the state read at its start, coils driving bistable 5/2 valves, memories
//! set and reset, reset winning) cycles from START, and then runs an
//! operator's script of STOP, EMERGENCY STOP and RESET ([`check`]). A
//! sensor letter `a` is 1 from the moment cylinder A's extended end switch
//! reads until its retracted one does, so the state changes only when a
//! move ends.
//!
//! The bench moves the plant; what is judged here is what the sequence
//! says: the actions in their order, each cycle like the last.

use super::Synthesis;
use super::controller::{Buttons, OnMachine, Program, ScanFn, Wired, actuator_number};
use super::sequence::Operation;
use crate::program::Signal;
use crate::simulate::bench::{Bench, Controller, Cylinder};
use crate::simulate::{Operator, SimSettings};
use crate::stroke::Stroke;

/// The result of simulating a synthesised controller.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Verification {
    pub passed: bool,
    /// The actions observed, as tokens, in order.
    pub observed: Vec<String>,
    /// Time of two complete cycles, in milliseconds.
    pub millis: u64,
    pub problem: Option<String>,
    /// The mode proof ([`check`]): the moves it saw, or what went wrong.
    pub modes: Result<usize, String>,
}

/// Runs `cycles` cycles of the program from START (1 s strokes), then
/// the mode proof.
pub fn verify(synthesis: &Synthesis, cycles: usize) -> Verification {
    Verification {
        modes: check(synthesis).map(|trace| trace.len()),
        ..cycling(synthesis, cycles)
    }
}

/// The bench for `s`: one cylinder per actuator with strokes of
/// `stroke_ms`, each where the sequence starts it (extended when its first
/// move retracts it).
pub fn bench(s: &Synthesis, stroke_ms: u32) -> Bench {
    let initial = s.modified.initial_state();
    let cylinders: Vec<Cylinder> = (0..s.modified.actuators)
        .map(|i| Cylinder {
            number: actuator_number(i),
            stroke: Stroke {
                extend_ms: stroke_ms,
                retract_ms: stroke_ms,
            },
            extended: (initial >> i) & 1 == 1,
        })
        .collect();
    Bench::cylinders(&cylinders, &SimSettings::default())
}

/// The program cycling from one START press until `cycles` cycles of
/// actions (memories among them) happened in order (`modes` left empty).
fn cycling(synthesis: &Synthesis, cycles: usize) -> Verification {
    // Nothing happening for 3 s (300 scans) is a stall.
    const TIMEOUT_SCANS: u32 = 300;
    let seq = &synthesis.modified;
    let expected: Vec<String> = (0..cycles)
        .flat_map(|_| seq.actions.iter().map(|a| seq.token(*a)))
        .collect();
    let mut bench = bench(synthesis, Stroke::default().extend_ms);
    let mut program = OnMachine::new(synthesis);
    let mut observed: Vec<String> = Vec::new();
    let mut since_event = 0u32;
    let failed = |observed: Vec<String>, millis, problem: String| Verification {
        passed: false,
        observed,
        millis,
        problem: Some(problem),
        modes: Ok(0),
    };
    while observed.len() < expected.len() {
        // START for the first scan only: its rising edge starts cycling.
        bench.press(Operator {
            start: bench.time_ms() == 0,
            ..Operator::default()
        });
        let state = program.program.state();
        let conflicts = match bench.scan(&mut program) {
            Ok(conflicts) => conflicts,
            Err(why) => return failed(observed, bench.time_ms(), why),
        };
        if let Some(&number) = conflicts.first() {
            let name = seq.var_name(number as usize - 1);
            let why = format!("the valve of {name} sees both coils");
            return failed(observed, bench.time_ms(), why);
        }
        // Every variable that changed, in variable order.
        for token in changes(synthesis, state, program.program.state()) {
            if expected.get(observed.len()) != Some(&token) {
                let due = expected.get(observed.len()).cloned().unwrap_or_default();
                let why = format!(
                    "expected {due} as action {}, but {token} happened",
                    observed.len() + 1
                );
                observed.push(token);
                return failed(observed, bench.time_ms(), why);
            }
            observed.push(token);
            since_event = 0;
        }
        since_event += 1;
        if since_event > TIMEOUT_SCANS {
            let why = format!(
                "nothing happens after {} actions (state {})",
                observed.len(),
                seq.state_text(program.program.state())
            );
            return failed(observed, bench.time_ms(), why);
        }
    }
    Verification {
        passed: true,
        observed,
        millis: bench.time_ms(),
        problem: None,
        modes: Ok(0),
    }
}

/// The actions that took the program's state from `before` to `after`.
fn changes(s: &Synthesis, before: u32, after: u32) -> Vec<String> {
    (0..s.modified.variables())
        .filter(|var| (before ^ after) >> var & 1 == 1)
        .map(|var| {
            s.modified.token(Operation {
                var,
                value: (after >> var) & 1 == 1,
            })
        })
        .collect()
}

/// A move that ended, at its scan: `(scan, "A1")`.
pub type Trace = Vec<(usize, String)>;

/// Runs `scans` scans of `program` on [`bench`] (strokes of `stroke_ms`)
/// with `script` giving the buttons of each scan; the moves in the order
/// they ended, or the scan where a valve saw both coils.
pub fn run(
    s: &Synthesis,
    stroke_ms: u32,
    scans: usize,
    script: &dyn Fn(usize) -> Buttons,
    program: &mut ScanFn,
) -> Result<Trace, String> {
    let seq = &s.modified;
    let mut bench = bench(s, stroke_ms);
    let mut wired = Wired::new(seq.actuators, program);
    let at_end = |bench: &Bench, i: usize| {
        let sensor = |position| {
            bench.input(Signal::Sensor {
                actuator: actuator_number(i),
                position,
            })
        };
        if sensor(1) {
            Some(true)
        } else if sensor(0) {
            Some(false)
        } else {
            None
        }
    };
    let mut was: Vec<Option<bool>> = (0..seq.actuators).map(|i| at_end(&bench, i)).collect();
    let mut trace = Trace::new();
    for scan in 0..scans {
        let b = script(scan);
        bench.press(Operator {
            start: b.start,
            stop: b.stop,
            estop: b.estop,
            reset: b.reset,
            ..Operator::default()
        });
        if let Some(&number) = bench.scan(&mut wired as &mut dyn Controller)?.first() {
            let name = seq.var_name(number as usize - 1);
            return Err(format!("scan {scan}: the valve of {name} sees both coils"));
        }
        for (i, was) in was.iter_mut().enumerate() {
            let now = at_end(&bench, i);
            if now.is_some() && now != *was {
                let value = now == Some(true);
                trace.push((scan, seq.token(Operation { var: i, value })));
                *was = now;
            }
        }
    }
    Ok(trace)
}

/// The strokes of the mode proof's plant, in ms.
pub const STROKE_MS: u32 = 200;

/// When the operator works the buttons in the mode proof, for a cycle of at
/// most `cycle` scans.
#[derive(Debug, Clone, Copy)]
pub struct Script {
    pub start: usize,
    pub stop: usize,
    pub restart: usize,
    pub estop: usize,
    pub start_in_estop: usize,
    pub release: usize,
    pub start_before_reset: usize,
    pub reset: usize,
    pub last_start: usize,
    pub last_stop: usize,
    pub scans: usize,
}

impl Script {
    /// Nothing for a while (nothing may move), START; STOP in the first or
    /// second cycle (cycling ends, then nothing); START again (cycling), the
    /// emergency stop pressed half-way into a cycle and START while it is
    /// held and once released (both refused until RESET); RESET (every
    /// cylinder home); START and STOP for one last cycle.
    pub fn for_cycle(cycle: usize) -> Script {
        let estop = 6 * cycle + 100 + cycle / 2;
        let release = estop + cycle;
        let last_start = release + 2 * cycle + 50;
        Script {
            start: 50,
            stop: cycle + 100,
            restart: 4 * cycle + 100,
            estop,
            start_in_estop: estop + 20,
            release,
            start_before_reset: release + 10,
            reset: release + 40,
            last_start,
            // Within the first cycle's first stroke: a two-action cycle
            // (`A1 A0`, 40 scans) is over 50 scans after its START.
            last_stop: last_start + 10,
            scans: last_start + 2 * cycle + 100,
        }
    }

    /// The buttons of scan `scan` (each press lasts five scans).
    pub fn buttons(&self, scan: usize) -> Buttons {
        let pulse = |at: usize| (at..at + 5).contains(&scan);
        Buttons {
            start: pulse(self.start)
                || pulse(self.restart)
                || pulse(self.start_in_estop)
                || pulse(self.start_before_reset)
                || pulse(self.last_start),
            stop: pulse(self.stop) || pulse(self.last_stop),
            estop: (self.estop..self.release).contains(&scan),
            reset: pulse(self.reset),
        }
    }
}

/// The mode proof's script for `s`: a cycle's scans at [`STROKE_MS`] (every
/// action's stroke and some slack).
pub fn script_for(s: &Synthesis) -> Script {
    Script::for_cycle(s.modified.actions.len() * (STROKE_MS as usize / 10 + 3))
}

/// Runs the mode proof on the model of the program and checks what the
/// operator would see; the trace, or the first thing that went wrong.
pub fn check(s: &Synthesis) -> Result<Trace, String> {
    let script = script_for(s);
    let mut program = Program::new(s);
    let trace = run(
        s,
        STROKE_MS,
        script.scans,
        &|scan| script.buttons(scan),
        &mut |ends, buttons| Ok(program.scan(ends, buttons)),
    )?;
    judge(s, &script, &trace)?;
    Ok(trace)
}

/// What the trace of the mode proof must show.
pub fn judge(s: &Synthesis, script: &Script, trace: &Trace) -> Result<(), String> {
    let seq = &s.modified;
    let cycle: Vec<String> = seq
        .actions
        .iter()
        .filter(|a| !seq.is_memory(a.var))
        .map(|a| seq.token(*a))
        .collect();
    let between = |from: usize, to: usize| -> Vec<String> {
        trace
            .iter()
            .filter(|(scan, _)| (from..to).contains(scan))
            .map(|(_, t)| t.clone())
            .collect()
    };
    let whole_cycles = |moves: &[String]| {
        !moves.is_empty()
            && moves.len().is_multiple_of(cycle.len())
            && moves.iter().zip(cycle.iter().cycle()).all(|(m, c)| m == c)
    };
    if let Some((scan, token)) = trace.iter().find(|(scan, _)| *scan < script.start) {
        return Err(format!("{token} moved at scan {scan}, before START"));
    }
    let first = between(script.start, script.restart);
    if !whole_cycles(&first) {
        return Err(format!(
            "after START and STOP the machine did not run whole cycles and halt: {first:?}"
        ));
    }
    let cycling = between(script.restart, script.estop);
    if cycling.is_empty()
        || !cycling
            .iter()
            .zip(cycle.iter().cycle())
            .all(|(m, c)| m == c)
    {
        return Err(format!("the second START did not cycle: {cycling:?}"));
    }
    let after_estop = between(script.estop + STROKE_MS as usize / 10 + 2, script.reset);
    if !after_estop.is_empty() {
        return Err(format!(
            "moves began after the emergency stop, with START pressed while it was held and before RESET: {after_estop:?}"
        ));
    }
    let initial = seq.initial_state();
    let homing = between(script.reset, script.last_start);
    let home_tokens: Vec<String> = (0..seq.actuators)
        .map(|i| {
            seq.token(Operation {
                var: i,
                value: (initial >> i) & 1 == 1,
            })
        })
        .collect();
    if let Some(away) = homing.iter().find(|t| !home_tokens.contains(t)) {
        return Err(format!("RESET moved {away}, away from home"));
    }
    let last = between(script.last_start, script.scans);
    if last != cycle {
        return Err(format!(
            "after RESET, START and STOP the machine did not run one cycle: {last:?}"
        ));
    }
    Ok(())
}
