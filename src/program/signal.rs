//! The program's vocabulary: every signal a step program reads or writes,
//! its role (input, output, memory, timer) and the names every output
//! language and address list uses for it (DESIGN §3).

use crate::cell::{Name, Sign};
use crate::table::StepTable;

/// Input, output, internal memory or timer.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Area {
    Input,
    Output,
    Memory,
    Timer,
}

/// Alarm outputs raised by the safety checks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Alarm {
    /// Two sensors of one actuator on at once (plausibility check).
    Sensor,
    /// A step did not finish in time (watchdog).
    Timeout,
    /// An interlock input went off (SETTINGS `interlock`).
    Interlock,
}

/// Every signal the step program reads or writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Signal {
    /// The START push-button.
    Start,
    /// Sensor `xij`: actuator i stands at position j.
    Sensor {
        actuator: u32,
        position: u32,
    },
    /// Valve coil `yi+` / `yi-`.
    Coil {
        actuator: u32,
        sign: Sign,
    },
    /// The one coil `yi` of a single-solenoid valve (on = extend).
    SingleCoil {
        actuator: u32,
    },
    /// Memory: actuator i must stop when it reaches middle position j.
    StopAt {
        actuator: u32,
        position: u32,
    },
    /// Memory: START as read in the previous scan (rising-edge detection).
    StartMemory,
    /// Memory: a safety check stopped the sequence.
    Halt,
    /// Alarm output of a safety check.
    Alarm(Alarm),
    /// The step watchdog timer; as a condition, true while it runs.
    Watchdog,
    /// Memory: the watchdog is timing a step.
    WatchdogArmed,
    /// A machine input a step waits for (`I:part_present`).
    MachineInput(Name),
    /// A machine output a step switches (`Y:vacuum+`).
    MachineOutput(Name),
    /// Dwell timer n (`T=2s`); as a condition, true while it runs.
    Dwell(u16),
    /// Memory: dwell n waits for its branch to finish before its timer starts.
    DwellArmed(u16),
    /// Run-on timer n: the n-th output that stays on for a while after
    /// STOP (SETTINGS `on stop | fan off after 20s`); true while it runs.
    RunOn(u16),
    /// Memory: run-on n is timing; when its timer has run out, its output
    /// goes off.
    RunOnArmed(u16),
    /// Memory: the sequence is in the steps of the n-th interlock with a
    /// step range (SETTINGS `interlock | guard_closed in steps 3-5`).
    InterlockZone(u16),
    /// Operating-mode inputs: the CONTINUOUS switch, the STOP and EMERGENCY
    /// STOP buttons (normally closed: 1 = not pressed), the RESET button.
    Continuous,
    Stop,
    EStop,
    Reset,
    /// Memory: a cycle was asked for (START, or CONTINUOUS at a cycle's end).
    CycleRequest,
    /// Memory: a cycle is under way (from STEP 1 to the end of the cycle).
    Busy,
    /// Memory: continuous operation was started and not stopped.
    AutoRun,
    /// Memory: the homing sequence runs.
    Homing,
    /// Memory: homing stage n runs.
    HomeStage(u16),
    /// Not a bit: the sequence itself. `Reset(Sequence)` sends it back to
    /// STEP 1 (each language has its own statement for that).
    Sequence,
}

impl Signal {
    pub fn area(self) -> Area {
        match self {
            Signal::Start
            | Signal::Sensor { .. }
            | Signal::MachineInput(_)
            | Signal::Continuous
            | Signal::Stop
            | Signal::EStop
            | Signal::Reset => Area::Input,
            Signal::Coil { .. }
            | Signal::SingleCoil { .. }
            | Signal::Alarm(_)
            | Signal::MachineOutput(_) => Area::Output,
            Signal::StopAt { .. }
            | Signal::StartMemory
            | Signal::Halt
            | Signal::WatchdogArmed
            | Signal::DwellArmed(_)
            | Signal::RunOnArmed(_)
            | Signal::InterlockZone(_)
            | Signal::CycleRequest
            | Signal::Busy
            | Signal::AutoRun
            | Signal::Homing
            | Signal::HomeStage(_)
            | Signal::Sequence => Area::Memory,
            Signal::Watchdog | Signal::Dwell(_) | Signal::RunOn(_) => Area::Timer,
        }
    }

    /// Whether the plant (not the program) gives this signal's value.
    pub fn is_input(self) -> bool {
        self.area() == Area::Input
    }

    /// The symbol of the published method, as on the address sheets (`x21`, `y2+`).
    pub fn symbol(self) -> String {
        match self {
            Signal::Start => "START".to_string(),
            Signal::Sensor { actuator, position } => format!("x{}", pair(actuator, position)),
            Signal::Coil { actuator, sign } => format!("y{actuator}{}", sign.symbol()),
            Signal::SingleCoil { actuator } => format!("y{actuator}"),
            Signal::StopAt { actuator, position } => format!("m{actuator}_{position}"),
            // At most 9 characters: the shortest limit of any target (FST).
            Signal::StartMemory => "start_mem".to_string(),
            Signal::Halt => "halt".to_string(),
            Signal::Alarm(Alarm::Sensor) => "alarm_pl".to_string(),
            Signal::Alarm(Alarm::Timeout) => "alarm_wd".to_string(),
            Signal::Alarm(Alarm::Interlock) => "alarm_il".to_string(),
            Signal::Watchdog => "watchdog".to_string(),
            Signal::WatchdogArmed => "wd_armed".to_string(),
            Signal::MachineInput(name) | Signal::MachineOutput(name) => name.to_string(),
            Signal::Dwell(n) => format!("dwell{n}"),
            Signal::DwellArmed(n) => format!("dw{n}_arm"),
            Signal::RunOn(n) => format!("runon{n}"),
            Signal::RunOnArmed(n) => format!("ro{n}_arm"),
            Signal::InterlockZone(n) => format!("zone{n}"),
            Signal::Continuous => "CONT".to_string(),
            Signal::Stop => "STOP".to_string(),
            Signal::EStop => "ESTOP".to_string(),
            // RESET is an FST and IL keyword.
            Signal::Reset => "RESET_PB".to_string(),
            Signal::CycleRequest => "cycle_req".to_string(),
            Signal::Busy => "busy".to_string(),
            Signal::AutoRun => "auto_run".to_string(),
            Signal::Homing => "homing".to_string(),
            Signal::HomeStage(n) => format!("home{n}"),
            Signal::Sequence => "sequence".to_string(),
        }
    }

    /// An identifier legal in IEC 61131-3 and every other target language
    /// (`+`/`-` become `p`/`m`; no keyword, no double underscore).
    pub fn ident(self) -> String {
        match self {
            Signal::Coil { actuator, sign } => {
                format!("y{actuator}{}", if sign == Sign::Plus { 'p' } else { 'm' })
            }
            other => other.symbol(),
        }
    }

    /// The symbolic operand in Festo FST, which keeps 9 characters: the
    /// identifier, with a long machine signal name cut to its first 9 (the
    /// table check makes sure those tell every name apart).
    pub fn fst_symbol(self) -> String {
        crate::names::fst_stem(&self.ident())
    }

    /// The `kind` column of the allocation list.
    pub fn kind(self) -> &'static str {
        match self {
            Signal::Start => "start",
            Signal::Sensor { .. } => "sensor",
            Signal::Coil { .. } | Signal::SingleCoil { .. } => "coil",
            Signal::Alarm(_) => "alarm",
            Signal::MachineInput(_) => "input",
            Signal::MachineOutput(_) => "output",
            Signal::Continuous => "continuous",
            Signal::Stop => "stop",
            Signal::EStop => "estop",
            Signal::Reset => "reset",
            other => match other.area() {
                Area::Timer => "timer",
                _ => "memory",
            },
        }
    }

    /// A human description ("cylinder 2, middle position 1").
    pub fn comment(self, table: &StepTable) -> String {
        let pmax = |a: u32| table.actuator(a).map(|x| x.max_position).unwrap_or(1);
        match self {
            Signal::Start => "START push-button".to_string(),
            Signal::Sensor { actuator, position } => {
                let which = if position == 0 {
                    "home position 0".to_string()
                } else if position == pmax(actuator) {
                    format!("end position {position}")
                } else {
                    format!("middle position {position}")
                };
                format!("cylinder {actuator}, {which}")
            }
            Signal::Coil { actuator, sign } => match sign {
                Sign::Plus => format!("cylinder {actuator}, coil + (extend)"),
                Sign::Minus => format!("cylinder {actuator}, coil - (retract)"),
            },
            Signal::SingleCoil { actuator } => {
                format!("cylinder {actuator}, coil (on: extend; off: the spring retracts)")
            }
            Signal::StopAt { actuator, position } => {
                format!("cylinder {actuator} stops at middle position {position}")
            }
            Signal::StartMemory => "START in the previous scan (rising edge)".to_string(),
            Signal::Halt => "sequence stopped by a safety check".to_string(),
            Signal::Alarm(Alarm::Sensor) => {
                "alarm: two sensors of one cylinder on at once".to_string()
            }
            Signal::Alarm(Alarm::Timeout) => "alarm: a step did not finish in time".to_string(),
            Signal::Alarm(Alarm::Interlock) => "alarm: an interlock input went off".to_string(),
            Signal::Watchdog => "step watchdog timer".to_string(),
            Signal::WatchdogArmed => "watchdog is timing a step".to_string(),
            Signal::MachineInput(name) => {
                let waits = |s: &crate::table::Step| s.waits.iter().any(|w| w.input == name);
                let jumps = |s: &crate::table::Step| s.jumps.iter().any(|j| j.input == name);
                let mut uses = vec![format!("machine input {name}")];
                if table.steps.iter().any(waits) {
                    uses.push(format!("waited for in {}", steps_where(table, waits)));
                }
                if table.steps.iter().any(jumps) {
                    uses.push(format!("jumped on after {}", steps_where(table, jumps)));
                }
                uses.join(", ")
            }
            Signal::MachineOutput(name) => {
                let steps = steps_where(table, |s| s.switches.iter().any(|w| w.output == name));
                format!("machine output {name}, switched in {steps}")
            }
            Signal::Dwell(n) | Signal::DwellArmed(n) => {
                let what = table
                    .steps
                    .iter()
                    .find_map(|s| {
                        s.dwells.iter().find(|d| d.number == n).map(|d| {
                            format!(
                                "STEP {}, branch {}, {}",
                                s.number,
                                d.branch + 1,
                                crate::cell::dwell_text(d.ms)
                            )
                        })
                    })
                    .unwrap_or_default();
                if matches!(self, Signal::Dwell(_)) {
                    format!("dwell timer {n} ({what})")
                } else {
                    format!("dwell {n} waits for its branch to finish ({what})")
                }
            }
            // The program knows which output (StepProgram::comment).
            Signal::RunOn(n) => format!("run-on timer {n} (an output on after STOP)"),
            Signal::RunOnArmed(n) => format!("run-on {n} is timing"),
            Signal::InterlockZone(n) => {
                format!("the sequence is in the steps of interlock zone {n}")
            }
            Signal::Continuous => "CONTINUOUS switch (on: repeat cycles)".to_string(),
            Signal::Stop => {
                "STOP push-button, normally closed (0: finish the cycle, then halt)".to_string()
            }
            Signal::EStop => {
                "EMERGENCY STOP, normally closed (0: every coil off at once)".to_string()
            }
            Signal::Reset => "RESET push-button (home every actuator)".to_string(),
            Signal::CycleRequest => "a cycle was asked for".to_string(),
            Signal::Busy => "a cycle is under way".to_string(),
            Signal::AutoRun => "continuous operation runs".to_string(),
            Signal::Homing => "the homing sequence runs".to_string(),
            Signal::HomeStage(n) => format!("homing stage {n} runs"),
            Signal::Sequence => "the step sequence".to_string(),
        }
    }
}

/// `STEP 2` or `STEPS 2, 5`.
fn steps_where(table: &StepTable, test: impl Fn(&crate::table::Step) -> bool) -> String {
    let numbers: Vec<String> = table
        .steps
        .iter()
        .filter(|s| test(s))
        .map(|s| s.number.to_string())
        .collect();
    match numbers.len() {
        1 => format!("STEP {}", numbers[0]),
        _ => format!("STEPS {}", numbers.join(", ")),
    }
}

/// `21` for actuator 2 position 1; `12_3` once either number has two digits,
/// so that `x1_23` and `x12_3` can never be confused.
fn pair(actuator: u32, position: u32) -> String {
    if actuator <= 9 && position <= 9 {
        format!("{actuator}{position}")
    } else {
        format!("{actuator}_{position}")
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::names::{KEYWORDS, reserved_name, signal_problem};

    #[test]
    fn symbols_are_unambiguous_identifiers() {
        let a = Signal::Sensor {
            actuator: 1,
            position: 23,
        };
        let b = Signal::Sensor {
            actuator: 12,
            position: 3,
        };
        assert_ne!(a.ident(), b.ident());
        assert_eq!(
            Signal::Sensor {
                actuator: 2,
                position: 1
            }
            .ident(),
            "x21"
        );
        assert_eq!(
            Signal::Coil {
                actuator: 2,
                sign: Sign::Minus
            }
            .ident(),
            "y2m"
        );
        assert_eq!(
            Signal::Coil {
                actuator: 2,
                sign: Sign::Minus
            }
            .symbol(),
            "y2-"
        );
    }

    #[test]
    fn every_identifier_is_legal_in_every_target_language() {
        let signals = [
            Signal::Start,
            Signal::Sensor {
                actuator: 999,
                position: 63,
            },
            Signal::Sensor {
                actuator: 9,
                position: 9,
            },
            Signal::Coil {
                actuator: 999,
                sign: Sign::Plus,
            },
            Signal::Coil {
                actuator: 1,
                sign: Sign::Minus,
            },
            Signal::StopAt {
                actuator: 999,
                position: 62,
            },
            Signal::StartMemory,
            Signal::Halt,
            Signal::Alarm(Alarm::Sensor),
            Signal::Alarm(Alarm::Timeout),
            Signal::Alarm(Alarm::Interlock),
            Signal::Watchdog,
            Signal::WatchdogArmed,
            Signal::Dwell(255),
            Signal::DwellArmed(255),
            Signal::RunOn(255),
            Signal::RunOnArmed(255),
            Signal::InterlockZone(255),
            Signal::Continuous,
            Signal::Stop,
            Signal::EStop,
            Signal::Reset,
            Signal::CycleRequest,
            Signal::Busy,
            Signal::AutoRun,
            Signal::Homing,
            Signal::HomeStage(999),
        ];
        for signal in signals {
            let id = signal.ident();
            let mut chars = id.chars();
            assert!(
                chars.next().is_some_and(|c| c.is_ascii_alphabetic()),
                "{id}"
            );
            assert!(chars.all(|c| c.is_ascii_alphanumeric() || c == '_'), "{id}");
            assert!(!id.contains("__") && !id.ends_with('_'), "{id}");
            // 9 characters: FST's symbolic operands; STEP 7 allows 24.
            assert!(id.len() <= 9, "{id} is longer than 9 characters");
            assert!(
                !KEYWORDS.contains(&id.to_ascii_uppercase().as_str()),
                "{id} is a keyword"
            );
            // No table may name a machine signal like one of the program's
            // own; the mode buttons' names are taken only while their mode is
            // on, and then in any case.
            if matches!(
                signal,
                Signal::Continuous | Signal::Stop | Signal::EStop | Signal::Reset
            ) {
                let buttons: Vec<String> = crate::program::Modes::parse("all")
                    .unwrap()
                    .buttons()
                    .map(|b| b.ident().to_ascii_lowercase())
                    .collect();
                assert!(signal_problem(&id, &buttons).is_some(), "{id}");
                assert!(signal_problem(&id, &[]).is_none(), "{id}");
                continue;
            }
            assert!(
                reserved_name(&id.to_ascii_lowercase()).is_some(),
                "{id} is not reserved"
            );
            assert!(
                reserved_name(&signal.fst_symbol().to_ascii_lowercase()).is_some(),
                "{id} in FST is not reserved"
            );
        }
    }

    #[test]
    fn every_signal_has_the_kind_of_its_role() {
        assert_eq!(Signal::Watchdog.kind(), "timer");
        assert_eq!(Signal::Dwell(1).kind(), "timer");
        assert_eq!(Signal::Halt.kind(), "memory");
        assert_eq!(Signal::Reset.kind(), "reset");
        assert_eq!(Signal::SingleCoil { actuator: 1 }.kind(), "coil");
    }

    #[test]
    fn long_machine_names_keep_nine_characters_in_fst() {
        let name = crate::cell::Name::new("part_present").unwrap();
        assert_eq!(Signal::MachineInput(name).ident(), "part_present");
        assert_eq!(Signal::MachineInput(name).fst_symbol(), "part_pres");
        assert!(reserved_name("x11").is_some());
        assert!(reserved_name("reset").is_some());
        assert_eq!(reserved_name("vacuum"), None);
    }
}
