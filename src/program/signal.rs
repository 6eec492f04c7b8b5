//! The program's vocabulary: every signal a step program reads or writes,
//! its area (input, output, memory, timer) and its symbol in the published
//! method's notation (DESIGN §3), which messages use. What each output
//! calls it is the symbol table's to decide (`symbols`), never the program's.

use crate::cell::{Name, Sign};

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
    /// Single-step mode: the STEP_MODE switch (on: one step per press) and
    /// the STEP_PB push-button.
    StepMode,
    StepButton,
    /// Manual mode (`--modes manual`): the MAN_MODE selector (1 = manual,
    /// 0 = automatic) and the jog buttons of actuator `actuator`: `+`
    /// extends (a drive runs forward), `-` retracts (reverse). A
    /// single-solenoid valve has only `+`: its spring is the way back.
    ManualMode,
    Jog {
        actuator: u32,
        sign: Sign,
    },
    /// Memory: MAN_MODE as read in the previous scan, so that the scan
    /// manual ends in switches off what a jog left on.
    ManualMemory,
    /// Memory: every jog button has read released in this manual spell, so
    /// a button held or stuck as the selector turns moves nothing.
    JogsReleased,
    /// Memory: actuator n was jogged in this manual spell, so its coils a
    /// halt row holds on follow its jog buttons (on while held) until
    /// manual ends.
    Jogged(u32),
    /// Memory: the sequence may fire a transition in this scan (always in
    /// automatic, for one scan after a STEP_PB press in single-step).
    StepPermit,
    /// Memory: STEP_PB as read in the previous scan (its rising edge).
    StepMemory,
    /// RESET_PB as read in the previous scan: RESET acts on its press.
    ResetMemory,
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
    /// Criteria analysis (`--safety criteria`): criterion n is a condition
    /// of the transition the sequence waits at (memory `crit{n}`), and
    /// output `miss{n}` is on while the step has run out of time with it
    /// unmet.
    Awaited(u16),
    Missing(u16),
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
            | Signal::Reset
            | Signal::StepMode
            | Signal::StepButton
            | Signal::ManualMode
            | Signal::Jog { .. } => Area::Input,
            Signal::Coil { .. }
            | Signal::SingleCoil { .. }
            | Signal::Alarm(_)
            | Signal::Missing(_)
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
            | Signal::StepPermit
            | Signal::StepMemory
            | Signal::ResetMemory
            | Signal::ManualMemory
            | Signal::JogsReleased
            | Signal::Jogged(_)
            | Signal::Awaited(_)
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
            Signal::StepMode => "STEP_MODE".to_string(),
            Signal::StepButton => "STEP_PB".to_string(),
            Signal::ManualMode => "MAN_MODE".to_string(),
            Signal::Jog { actuator, sign } => format!("jog{actuator}{}", sign.symbol()),
            Signal::StepPermit => "step_ok".to_string(),
            Signal::StepMemory => "step_mem".to_string(),
            Signal::ResetMemory => "reset_mem".to_string(),
            Signal::ManualMemory => "man_mem".to_string(),
            Signal::JogsReleased => "jog_ok".to_string(),
            Signal::Jogged(n) => format!("jogged{n}"),
            Signal::CycleRequest => "cycle_req".to_string(),
            Signal::Busy => "busy".to_string(),
            Signal::AutoRun => "auto_run".to_string(),
            Signal::Homing => "homing".to_string(),
            Signal::HomeStage(n) => format!("home{n}"),
            Signal::Awaited(n) => format!("crit{n}"),
            Signal::Missing(n) => format!("miss{n}"),
            Signal::Sequence => "sequence".to_string(),
        }
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
