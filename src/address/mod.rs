//! Addresses: which input, output and memory bit each signal gets, for each PLC
//! dialect, and the symbol names every output language uses for them (DESIGN §3).

use std::fmt;

mod modes;
mod names;
pub use modes::Modes;

pub use names::{KEYWORDS, reserved_name};

use crate::cell::{Name, Sign};
use crate::table::StepTable;
use crate::valve::{ValveType, Valves};

/// The PLC dialect whose address notation is used.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Target {
    /// Festo FST: 16-bit words, `I0.0` / `O0.0`, the paper's layout.
    #[default]
    Festo,
    /// IEC 61131-3 direct addresses `%IX0.0` / `%QX0.0`, 8 bits per byte (CODESYS, OpenPLC).
    Iec,
    /// Siemens `I0.0` / `Q0.0` (German `E` / `A`), 8 bits per byte.
    Siemens,
}

impl Target {
    pub fn name(self) -> &'static str {
        match self {
            Target::Festo => "festo",
            Target::Iec => "iec",
            Target::Siemens => "siemens",
        }
    }

    fn bits_per_unit(self) -> u32 {
        match self {
            Target::Festo => 16,
            Target::Iec | Target::Siemens => 8,
        }
    }
}

/// English or German operand letters (Siemens `I`/`Q` or `E`/`A`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Mnemonic {
    #[default]
    En,
    De,
}

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
            | Signal::CycleRequest
            | Signal::Busy
            | Signal::AutoRun
            | Signal::Homing
            | Signal::HomeStage(_)
            | Signal::Sequence => Area::Memory,
            Signal::Watchdog | Signal::Dwell(_) => Area::Timer,
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
            Signal::Watchdog => "watchdog".to_string(),
            Signal::WatchdogArmed => "wd_armed".to_string(),
            Signal::MachineInput(name) | Signal::MachineOutput(name) => name.to_string(),
            Signal::Dwell(n) => format!("dwell{n}"),
            Signal::DwellArmed(n) => format!("dw{n}_arm"),
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
        self.ident().chars().take(9).collect()
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
            Signal::Watchdog => "step watchdog timer".to_string(),
            Signal::WatchdogArmed => "watchdog is timing a step".to_string(),
            Signal::MachineInput(name) => {
                let steps = steps_where(table, |s| s.waits.iter().any(|w| w.input == name));
                format!("machine input {name}, waited for in {steps}")
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

/// A bit address: unit (word or byte, per target) and bit.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Address {
    pub area: Area,
    pub target: Target,
    pub unit: u32,
    pub bit: u32,
}

impl Address {
    fn from_index(area: Area, target: Target, index: u32) -> Self {
        let width = target.bits_per_unit();
        Address {
            area,
            target,
            unit: index / width,
            bit: index % width,
        }
    }

    /// The address in the target's notation (`I0.1`, `%QX0.1`, `E0.1`).
    pub fn display(self, mnemonic: Mnemonic) -> String {
        let letter = match (self.target, self.area, mnemonic) {
            (Target::Festo, Area::Input, _) => "I",
            (Target::Festo, Area::Output, _) => "O",
            (Target::Festo, Area::Memory, _) => "F",
            (Target::Iec, Area::Input, _) => "%IX",
            (Target::Iec, Area::Output, _) => "%QX",
            (Target::Iec, Area::Memory, _) => "%MX",
            (Target::Siemens, Area::Input, Mnemonic::En) => "I",
            (Target::Siemens, Area::Input, Mnemonic::De) => "E",
            (Target::Siemens, Area::Output, Mnemonic::En) => "Q",
            (Target::Siemens, Area::Output, Mnemonic::De) => "A",
            (Target::Siemens, Area::Memory, _) => "M",
            (Target::Iec, Area::Timer, _) => "%MW",
            (Target::Festo | Target::Siemens, Area::Timer, _) => "T",
        };
        if self.area == Area::Timer {
            return format!("{letter}{}", self.unit);
        }
        format!("{letter}{}.{}", self.unit, self.bit)
    }

    /// The physical byte and bit (a 16-bit Festo word is two bytes, low
    /// byte first), as Siemens and IEC addresses count them.
    pub fn byte_bit(self) -> (u32, u32) {
        match self.target {
            Target::Festo => (self.unit * 2 + self.bit / 8, self.bit % 8),
            Target::Iec | Target::Siemens => (self.unit, self.bit),
        }
    }

    /// The same physical bit as an IEC direct address (`%IX1.2`), for the
    /// located variables of Structured Text. A 16-bit Festo word is two bytes,
    /// low byte first: `I0.10` is `%IX1.2`.
    pub fn iec(self) -> String {
        let (byte, bit) = self.byte_bit();
        let prefix = match self.area {
            Area::Input => "%IX",
            Area::Output => "%QX",
            Area::Memory | Area::Timer => "%MX",
        };
        format!("{prefix}{byte}.{bit}")
    }
}

/// The safety checks a generated program carries (`--safety`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Safety {
    /// A cycle starts only on a rising edge of START.
    pub edge: bool,
    /// A move starts only while its target sensor is still off.
    pub precheck: bool,
    /// Two sensors of one actuator on at once stops the sequence.
    pub plausibility: bool,
    /// A step that does not finish in time raises an alarm and stops.
    pub watchdog: bool,
}

impl Safety {
    /// All four checks.
    pub fn all() -> Self {
        Safety {
            edge: true,
            precheck: true,
            plausibility: true,
            watchdog: true,
        }
    }

    /// Parses `edge,precheck,plausibility,watchdog` (any subset; `all`, `none`).
    pub fn parse(text: &str) -> Result<Safety, String> {
        let mut safety = Safety::default();
        for item in text.split(',').map(|s| s.trim().to_ascii_lowercase()) {
            match item.as_str() {
                "" | "none" => {}
                "all" => safety = Safety::all(),
                "edge" => safety.edge = true,
                "precheck" => safety.precheck = true,
                "plausibility" => safety.plausibility = true,
                "watchdog" => safety.watchdog = true,
                other => {
                    return Err(format!(
                        "\"{other}\" is not a safety check (expected edge, precheck, plausibility, watchdog, all or none)"
                    ));
                }
            }
        }
        Ok(safety)
    }

    pub fn any(self) -> bool {
        self.edge || self.precheck || self.plausibility || self.watchdog
    }

    /// Whether the program has a `halt` memory: a check that stops the
    /// sequence (plausibility, watchdog) or an emergency stop sets it. The
    /// one place this is decided, for the allocation and the program.
    pub fn halts(self, modes: &Modes) -> bool {
        self.plausibility || self.watchdog || modes.estop
    }
}

/// One signal with its address.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Assigned {
    pub signal: Signal,
    pub address: Address,
}

/// The complete I/O and memory allocation of one table for one target.
#[derive(Debug, Clone, PartialEq)]
pub struct Allocation {
    pub target: Target,
    pub mnemonic: Mnemonic,
    /// In address order: START, then each actuator's sensors.
    pub inputs: Vec<Assigned>,
    /// In address order.
    pub outputs: Vec<Assigned>,
    /// Internal memory bits of the program (middle-stop requests, safety).
    pub memories: Vec<Assigned>,
    /// Timers (the step watchdog).
    pub timers: Vec<Assigned>,
    /// The safety checks this allocation has room for.
    pub safety: Safety,
    /// The operating modes this allocation has room for.
    pub modes: Modes,
    /// The valve types given explicitly.
    pub valves: Valves,
}

impl Allocation {
    /// Allocates addresses for every signal the table needs.
    ///
    /// Inputs: START first, then for each actuator in ascending number its
    /// sensors 0…pmax, packed densely. Outputs on Festo follow the paper: all
    /// `+` coils from `O0.1` on, all `-` coils from bit 1 of the next free word.
    /// On IEC and Siemens targets each valve's two coils sit side by side
    /// (`+` then `-`), as they do on a valve terminal.
    pub fn new(table: &StepTable, target: Target, mnemonic: Mnemonic) -> Self {
        Self::with_safety(table, target, mnemonic, Safety::default())
    }

    /// As [`Allocation::new`], plus the alarm outputs, memories and timer the
    /// chosen safety checks need. Alarm outputs follow the coils.
    pub fn with_safety(
        table: &StepTable,
        target: Target,
        mnemonic: Mnemonic,
        safety: Safety,
    ) -> Self {
        Self::with_options(
            table,
            target,
            mnemonic,
            safety,
            &Modes::default(),
            &Valves::default(),
        )
    }

    /// The same signals allocated for another target (the FST files always
    /// use Festo operands).
    pub fn for_target(&self, table: &StepTable, target: Target, mnemonic: Mnemonic) -> Self {
        Self::with_options(
            table,
            target,
            mnemonic,
            self.safety,
            &self.modes,
            &self.valves,
        )
    }

    /// The full allocation. A single-solenoid (`52mono`) actuator gets one
    /// output, in the place its `+` coil would have; its `-` place stays free,
    /// so no other address moves when a valve type changes.
    pub fn with_options(
        table: &StepTable,
        target: Target,
        mnemonic: Mnemonic,
        safety: Safety,
        modes: &Modes,
        valves: &Valves,
    ) -> Self {
        let sensors = table.actuators.iter().flat_map(|actuator| {
            (0..=actuator.max_position).map(|position| Signal::Sensor {
                actuator: actuator.number,
                position,
            })
        });
        // Machine inputs after the sensors, then the operating-mode buttons.
        let mode_inputs = [
            (modes.continuous, Signal::Continuous),
            (modes.stop, Signal::Stop),
            (modes.estop, Signal::EStop),
            (modes.reset, Signal::Reset),
        ]
        .into_iter()
        .filter_map(|(wanted, signal)| wanted.then_some(signal));
        let inputs: Vec<Assigned> = std::iter::once(Signal::Start)
            .chain(sensors)
            .chain(table.inputs.iter().map(|n| Signal::MachineInput(*n)))
            .chain(mode_inputs)
            .enumerate()
            .map(|(index, signal)| Assigned {
                signal,
                address: Address::from_index(Area::Input, target, index as u32),
            })
            .collect();

        let count = table.actuators.len() as u32;
        let mut outputs = Vec::with_capacity(2 * table.actuators.len());
        for (rank, actuator) in table.actuators.iter().enumerate() {
            let rank = rank as u32;
            let (plus, minus) = match target {
                Target::Festo => {
                    let width = target.bits_per_unit();
                    let minus_base = (count + 1).div_ceil(width) * width;
                    (rank + 1, minus_base + rank + 1)
                }
                Target::Iec | Target::Siemens => (2 * rank, 2 * rank + 1),
            };
            if valves.of(actuator.number, actuator.max_position) == ValveType::Mono52 {
                outputs.push(Assigned {
                    signal: Signal::SingleCoil {
                        actuator: actuator.number,
                    },
                    address: Address::from_index(Area::Output, target, plus),
                });
                continue;
            }
            for (sign, index) in [(Sign::Plus, plus), (Sign::Minus, minus)] {
                outputs.push(Assigned {
                    signal: Signal::Coil {
                        actuator: actuator.number,
                        sign,
                    },
                    address: Address::from_index(Area::Output, target, index),
                });
            }
        }
        outputs.sort_by_key(|a| a.address);
        let mut next_output = outputs
            .last()
            .map(|a| a.address.unit * target.bits_per_unit() + a.address.bit + 1)
            .unwrap_or(0);
        for name in &table.outputs {
            outputs.push(Assigned {
                signal: Signal::MachineOutput(*name),
                address: Address::from_index(Area::Output, target, next_output),
            });
            next_output += 1;
        }
        let alarms = [
            (safety.plausibility, Alarm::Sensor),
            (safety.watchdog, Alarm::Timeout),
        ];
        for (wanted, alarm) in alarms {
            if wanted {
                outputs.push(Assigned {
                    signal: Signal::Alarm(alarm),
                    address: Address::from_index(Area::Output, target, next_output),
                });
                next_output += 1;
            }
        }

        let mut memories = Vec::new();
        let mut stops: Vec<(u32, u32)> = table
            .steps
            .iter()
            .flat_map(|s| &s.moves)
            .filter(|m| {
                table
                    .actuator(m.actuator)
                    .is_some_and(|a| a.is_middle(m.to))
            })
            .map(|m| (m.actuator, m.to))
            .collect();
        stops.sort_unstable();
        stops.dedup();
        let mut extra = Vec::new();
        if safety.edge {
            extra.push(Signal::StartMemory);
        }
        if safety.halts(modes) {
            extra.push(Signal::Halt);
        }
        if safety.watchdog {
            extra.push(Signal::WatchdogArmed);
        }
        extra.extend(table.dwells().map(|d| Signal::DwellArmed(d.number)));
        if modes.any() {
            extra.push(Signal::CycleRequest);
            extra.push(Signal::Busy);
        }
        if modes.continuous {
            extra.push(Signal::AutoRun);
        }
        if modes.reset {
            extra.push(Signal::Homing);
            let stages = modes.home_stages(table).map(|s| s.len()).unwrap_or(0);
            extra.extend((1..=stages).map(|n| Signal::HomeStage(n as u16)));
        }
        let signals = stops
            .into_iter()
            .map(|(actuator, position)| Signal::StopAt { actuator, position })
            .chain(extra);
        for (index, signal) in signals.enumerate() {
            memories.push(Assigned {
                signal,
                address: Address::from_index(Area::Memory, target, index as u32),
            });
        }
        // T0 is the watchdog's; dwell n gets timer n.
        let timer = |signal, unit| Assigned {
            signal,
            address: Address {
                area: Area::Timer,
                target,
                unit,
                bit: 0,
            },
        };
        let timers = safety
            .watchdog
            .then(|| timer(Signal::Watchdog, 0))
            .into_iter()
            .chain(
                table
                    .dwells()
                    .map(|d| timer(Signal::Dwell(d.number), d.number as u32)),
            )
            .collect();

        Allocation {
            target,
            mnemonic,
            inputs,
            outputs,
            memories,
            timers,
            safety,
            modes: modes.clone(),
            valves: valves.clone(),
        }
    }

    /// The address of a signal.
    pub fn address_of(&self, signal: Signal) -> Option<Address> {
        self.inputs
            .iter()
            .chain(&self.outputs)
            .chain(&self.memories)
            .chain(&self.timers)
            .find(|a| a.signal == signal)
            .map(|a| a.address)
    }

    /// The address of a signal in the target's notation, or `?` if it has none
    /// (which the program builder never lets happen).
    pub fn display(&self, signal: Signal) -> String {
        self.address_of(signal)
            .map(|a| a.display(self.mnemonic))
            .unwrap_or_else(|| "?".to_string())
    }
}

impl fmt::Display for Target {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table(rows: &[&[&str]]) -> StepTable {
        crate::table::from_rows("t.csv", rows).expect("valid table")
    }

    #[test]
    fn festo_outputs_follow_the_paper() {
        let t = table(&[&["C1+1", "C2+1"], &["C1-0", "C2-0"]]);
        let alloc = Allocation::new(&t, Target::Festo, Mnemonic::En);
        let outs: Vec<String> = alloc
            .outputs
            .iter()
            .map(|a| format!("{} {}", a.address.display(Mnemonic::En), a.signal.symbol()))
            .collect();
        assert_eq!(outs, ["O0.1 y1+", "O0.2 y2+", "O1.1 y1-", "O1.2 y2-"]);
    }

    #[test]
    fn forty_actuators_get_unique_valid_addresses() {
        let plus: Vec<String> = (1..=40).map(|i| format!("C{i}+1")).collect();
        let minus: Vec<String> = (1..=40).map(|i| format!("C{i}-0")).collect();
        let plus_ref: Vec<&str> = plus.iter().map(String::as_str).collect();
        let minus_ref: Vec<&str> = minus.iter().map(String::as_str).collect();
        let t = table(&[&plus_ref, &minus_ref]);
        for target in [Target::Festo, Target::Iec, Target::Siemens] {
            let alloc = Allocation::new(&t, target, Mnemonic::En);
            let mut seen = std::collections::BTreeSet::new();
            for a in alloc.inputs.iter().chain(&alloc.outputs) {
                assert!(a.address.bit < target.bits_per_unit());
                assert!(
                    seen.insert(a.address),
                    "{target}: duplicate {:?}",
                    a.address
                );
            }
            assert_eq!(alloc.inputs.len(), 81);
            assert_eq!(alloc.outputs.len(), 80);
        }
    }

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
    fn festo_words_map_to_iec_bytes() {
        let addr = Address {
            area: Area::Input,
            target: Target::Festo,
            unit: 0,
            bit: 10,
        };
        assert_eq!(addr.display(Mnemonic::En), "I0.10");
        assert_eq!(addr.iec(), "%IX1.2");
        let q = Address {
            area: Area::Output,
            target: Target::Siemens,
            unit: 3,
            bit: 7,
        };
        assert_eq!(q.display(Mnemonic::De), "A3.7");
        assert_eq!(q.iec(), "%QX3.7");
    }
}

#[cfg(test)]
mod identifier_tests {
    use super::*;

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
            Signal::Watchdog,
            Signal::WatchdogArmed,
            Signal::Dwell(255),
            Signal::DwellArmed(255),
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
        }
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
