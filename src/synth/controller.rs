//! The synthesised program as the written files run it: the equations with
//! the operating modes around them, so that the program can run a machine: START (its rising edge, with the machine home)
//! starts cycling; STOP (normally closed) ends the cycling at the end of the
//! cycle under way; EMERGENCY STOP (normally closed) switches every coil off
//! in the same scan and refuses START until RESET; RESET (with the emergency
//! stop released) sets the memories to their start values and drives every
//! cylinder home. As in the `convert` route's programs, the buttons are
//! `START`, `STOP`, `ESTOP` and `RESET_PB`.
//!
//! [`Program`] is this logic and the equations scan by scan, exactly as the
//! written ST and IL programs do it (the templates render the same steps).
//! It is wired to the machine as those programs are ([`Wired`]): actuator
//! `i` (0-based) is cylinder `C<i+1>` of the shared plant, its end
//! switches the sensors `x<i+1>0`, `x<i+1>1`, its coils `y<i+1>+` and
//! `y<i+1>-`. So the proof (`verify`) runs it, and the written file in
//! matiec, on the bench every converted program runs on
//! (`simulate::bench`).

use super::Synthesis;
use super::sequence::Operation;
use crate::cell::Sign;
use crate::program::Signal;
use crate::simulate::bench::Controller;

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

    /// Sensor states and memories now, one bit per variable.
    pub fn state(&self) -> u32 {
        self.state
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

/// Each actuator's (retracted, extended) end switches.
pub type Ends = [(bool, bool)];

/// A program under test that speaks in end switches and buttons, scan by
/// scan: each actuator's (plus, minus) coils, or why the scan failed.
pub type ScanFn<'c> = dyn FnMut(&Ends, Buttons) -> Result<Vec<(bool, bool)>, String> + 'c;

/// A program of `actuators` cylinders wired to the shared machine as the
/// written files are: end switches and buttons in, coils out.
pub struct Wired<'c, 'f> {
    actuators: usize,
    program: &'f mut ScanFn<'c>,
    coils: Vec<(bool, bool)>,
}

impl<'c, 'f> Wired<'c, 'f> {
    pub fn new(actuators: usize, program: &'f mut ScanFn<'c>) -> Self {
        Wired {
            actuators,
            program,
            coils: Vec::new(),
        }
    }
}

/// Actuator `i`'s (0-based) number on the shared machine.
pub fn actuator_number(i: usize) -> u32 {
    i as u32 + 1
}

/// The end switches of `actuators` cylinders and the buttons as the
/// machine's inputs read (STOP and ESTOP normally closed: 0 is pressed).
fn read(actuators: usize, input: &dyn Fn(Signal) -> bool) -> (Vec<(bool, bool)>, Buttons) {
    let sensor = |i: usize, position| {
        input(Signal::Sensor {
            actuator: actuator_number(i),
            position,
        })
    };
    let ends = (0..actuators)
        .map(|i| (sensor(i, 0), sensor(i, 1)))
        .collect();
    let buttons = Buttons {
        start: input(Signal::Start),
        stop: !input(Signal::Stop),
        estop: !input(Signal::EStop),
        reset: input(Signal::Reset),
    };
    (ends, buttons)
}

/// Whether `output` is one of `coils` and on.
fn coil(coils: &[(bool, bool)], output: Signal) -> bool {
    let Signal::Coil { actuator, sign } = output else {
        return false;
    };
    let Some(&(plus, minus)) = (actuator as usize)
        .checked_sub(1)
        .and_then(|i| coils.get(i))
    else {
        return false;
    };
    if sign == Sign::Plus { plus } else { minus }
}

impl Controller for Wired<'_, '_> {
    fn scan(&mut self, input: &dyn Fn(Signal) -> bool, _scan_ms: u64) -> Result<(), String> {
        let (ends, buttons) = read(self.actuators, input);
        self.coils = (self.program)(&ends, buttons)?;
        Ok(())
    }

    fn output(&self, output: Signal) -> bool {
        coil(&self.coils, output)
    }
}

/// The synthesised program on the machine; its coils are those of its
/// last scan.
pub struct OnMachine<'a> {
    pub program: Program<'a>,
    coils: Vec<(bool, bool)>,
}

impl<'a> OnMachine<'a> {
    pub fn new(s: &'a Synthesis) -> Self {
        OnMachine {
            program: Program::new(s),
            coils: Vec::new(),
        }
    }
}

impl Controller for OnMachine<'_> {
    fn scan(&mut self, input: &dyn Fn(Signal) -> bool, _scan_ms: u64) -> Result<(), String> {
        let (ends, buttons) = read(self.program.s.modified.actuators, input);
        self.coils = self.program.scan(&ends, buttons);
        Ok(())
    }

    fn output(&self, output: Signal) -> bool {
        coil(&self.coils, output)
    }
}
