//! The operating modes around the synthesised equations, so that the written
//! program can run a machine: START (its rising edge, with the machine home)
//! starts cycling; STOP (normally closed) ends the cycling at the end of the
//! cycle under way; EMERGENCY STOP (normally closed) switches every coil off
//! in the same scan and refuses START until RESET; RESET (with the emergency
//! stop released) sets the memories to their start values and drives every
//! cylinder home. As in the `convert` route's programs, the buttons are
//! `START`, `STOP`, `ESTOP` and `RESET_PB`.
//!
//! [`Program`] is this logic and the equations scan by scan, exactly as the
//! written ST and IL programs do it (the templates render the same steps),
//! and [`run`] drives a plant with any controller and a script of button
//! presses, so that the written file in matiec and this model are run
//! against the same plant and their traces compared.

use super::Synthesis;
use super::sequence::Operation;
use crate::stroke::Stroke;

/// The buttons in one scan, as the operator works them (`stop` and `estop`
/// true while pressed; the inputs of those two read 0 then).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Buttons {
    pub start: bool,
    pub stop: bool,
    pub estop: bool,
    pub reset: bool,
}

/// The mode flags of the program.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
struct Flags {
    start_last: bool,
    running: bool,
    stopping: bool,
    away: bool,
    halted: bool,
    homing: bool,
}

/// The synthesised program with its modes, as the written files run it.
pub struct Program<'a> {
    s: &'a Synthesis,
    /// Sensor states and memories, one bit per variable.
    state: u32,
    flags: Flags,
}

impl<'a> Program<'a> {
    /// At power-up: every variable at its start value, nothing running.
    pub fn new(s: &'a Synthesis) -> Self {
        Program {
            s,
            state: s.modified.initial_state(),
            flags: Flags::default(),
        }
    }

    fn equation(&self, var: usize, value: bool) -> bool {
        self.s.drives(Operation { var, value }, self.state)
    }

    /// One scan: `ends[i]` = (retracted, extended) switches of actuator i;
    /// returns each actuator's (plus, minus) coils.
    pub fn scan(&mut self, ends: &[(bool, bool)], buttons: Buttons) -> Vec<(bool, bool)> {
        let seq = &self.s.modified;
        // Sensor states: 1 from the extended end until the retracted end.
        for (i, (home, end)) in ends.iter().enumerate() {
            if *end {
                self.state |= 1 << i;
            }
            if *home {
                self.state &= !(1 << i);
            }
        }
        let initial = seq.initial_state();
        let home = self.state == initial;
        let f = &mut self.flags;
        let start_edge = buttons.start && !f.start_last;
        f.start_last = buttons.start;
        if buttons.estop {
            *f = Flags {
                start_last: f.start_last,
                halted: true,
                ..Flags::default()
            };
        } else if buttons.reset {
            *f = Flags {
                start_last: f.start_last,
                homing: true,
                ..Flags::default()
            };
        } else {
            if f.homing && home {
                f.homing = false;
            }
            if f.running && !home {
                f.away = true;
            }
            if f.running && f.away && home {
                f.away = false;
                if f.stopping {
                    f.running = false;
                    f.stopping = false;
                }
            }
            if start_edge && home && !f.halted && !f.running && !f.homing {
                f.running = true;
            }
            if f.running && buttons.stop {
                f.stopping = true;
            }
        }
        let flags = *f;
        let enable = flags.running && !buttons.estop;
        let coils = (0..seq.actuators)
            .map(|i| {
                let starts_extended = (initial >> i) & 1 == 1;
                (
                    (enable && self.equation(i, true)) || (flags.homing && starts_extended),
                    (enable && self.equation(i, false)) || (flags.homing && !starts_extended),
                )
            })
            .collect();
        let mut next = self.state;
        for var in seq.actuators..seq.variables() {
            if enable {
                if self.equation(var, false) {
                    next &= !(1 << var);
                } else if self.equation(var, true) {
                    next |= 1 << var;
                }
            }
            if flags.homing {
                next = (next & !(1 << var)) | (initial & (1 << var));
            }
        }
        self.state = next;
        coils
    }
}

/// A move that ended, at its scan: `(scan, "A1")`.
pub type Trace = Vec<(usize, String)>;

/// Each actuator's (retracted, extended) end switches.
pub type Ends = [(bool, bool)];

/// A program under test, scan by scan: each actuator's (plus, minus) coils.
pub type Controller<'c> = dyn FnMut(&Ends, Buttons) -> Result<Vec<(bool, bool)>, String> + 'c;

/// Runs `scans` scans of `controller` against the plant (bistable 5/2
/// valves, strokes of `stroke_ms`, every cylinder where the sequence starts
/// it) with `script` giving the buttons of each scan; the moves in the order
/// they ended, or the scan where a valve saw both coils.
pub fn run(
    s: &Synthesis,
    stroke_ms: u32,
    scans: usize,
    script: &dyn Fn(usize) -> Buttons,
    controller: &mut Controller,
) -> Result<Trace, String> {
    const SCAN_MS: u32 = 10;
    const WINDOW: f64 = 0.02;
    let seq = &s.modified;
    let initial = seq.initial_state();
    let stroke = Stroke {
        extend_ms: stroke_ms,
        retract_ms: stroke_ms,
    };
    let mut pistons = super::verify::pistons_at_start(seq, stroke, SCAN_MS);
    let mut at_end: Vec<Option<bool>> = (0..seq.actuators)
        .map(|i| Some((initial >> i) & 1 == 1))
        .collect();
    let mut trace = Trace::new();
    for scan in 0..scans {
        let ends: Vec<(bool, bool)> = pistons
            .iter()
            .map(|p| (p.sensor(0, WINDOW), p.sensor(1, WINDOW)))
            .collect();
        let coils = controller(&ends, script(scan))?;
        for (i, p) in pistons.iter_mut().enumerate() {
            let (plus, minus) = coils.get(i).copied().unwrap_or_default();
            if p.drive(plus, minus) {
                return Err(format!(
                    "scan {scan}: the valve of {} sees both coils",
                    seq.var_name(i)
                ));
            }
            p.advance();
            let now = if p.sensor(1, WINDOW) {
                Some(true)
            } else if p.sensor(0, WINDOW) {
                Some(false)
            } else {
                None
            };
            if now.is_some() && now != at_end[i] {
                trace.push((
                    scan,
                    seq.token(Operation {
                        var: i,
                        value: now == Some(true),
                    }),
                ));
                at_end[i] = now;
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
