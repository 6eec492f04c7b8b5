//! The choices that change a generated program: its safety checks, its
//! operating modes and the homing order RESET uses.

use super::Signal;
use crate::table::StepTable;

/// Choices that change the generated program.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ProgramOptions {
    /// Switch both coils off when an actuator reaches a middle target. Off only
    /// to show what the published method does without it (it hangs).
    pub middle_stops: bool,
    /// Safety checks carried by the program.
    pub safety: Safety,
    /// Operating modes carried by the program.
    pub modes: Modes,
    /// What may stay energised when the machine halts, and what the halt
    /// switches off.
    pub halt: HaltPolicy,
    /// Machine inputs that must be on for a cycle to start (SETTINGS
    /// `start permissive`: air pressure, a closed guard).
    pub permissive: Vec<crate::cell::Name>,
    /// Machine inputs that must stay on: one going off halts the machine
    /// and raises `alarm_il` (SETTINGS `interlock`: a guard door).
    pub interlocks: Vec<Interlock>,
    /// Supervision times by table step number (`--supervision 3=5s`, the
    /// SETTINGS row `supervision`): the watchdog's preset for those steps
    /// in place of the one from the plant model.
    pub supervision: std::collections::BTreeMap<usize, u32>,
}

impl ProgramOptions {
    /// Whether the program can halt: a safety check or the emergency stop
    /// that halts, or an interlock.
    pub fn halts(&self) -> bool {
        self.safety.halts(&self.modes) || !self.interlocks.is_empty()
    }

    /// Whether STOP acts at once (an `on stop` row) rather than letting the
    /// cycle finish.
    pub fn stops_now(&self) -> bool {
        self.modes.stop && !self.halt.on_stop.is_empty()
    }

    /// Whether the program has `event`: a STOP that acts at once, the
    /// emergency stop, a halt.
    pub fn has(&self, event: StopEvent) -> bool {
        match event {
            StopEvent::Stop => self.stops_now(),
            StopEvent::EStop => self.modes.estop,
            StopEvent::Halt => self.halts(),
        }
    }

    /// The outputs that run on after an event the program has: run-on n
    /// (timer `runonN`, memory `roN_arm`) is the n-th.
    pub fn run_ons(&self) -> Vec<RunOn> {
        self.halt
            .run_ons()
            .into_iter()
            .filter(|r| self.has(r.event))
            .collect()
    }

    /// The interlocks that hold for a range of steps, each with its zone
    /// memory (`zoneN`, set while the sequence is in the range).
    pub fn zones(&self) -> impl Iterator<Item = (Signal, Interlock)> + '_ {
        self.interlocks
            .iter()
            .filter(|i| i.steps.is_some())
            .enumerate()
            .map(|(n, i)| (Signal::InterlockZone(n as u16 + 1), *i))
    }

    /// The machine inputs the settings add to the table's (permissives,
    /// then interlocks), each once.
    pub fn held_inputs(&self) -> Vec<crate::cell::Name> {
        let mut names = self.permissive.clone();
        for interlock in &self.interlocks {
            if !names.contains(&interlock.input) {
                names.push(interlock.input);
            }
        }
        names
    }
}

impl Default for ProgramOptions {
    fn default() -> Self {
        ProgramOptions {
            middle_stops: true,
            safety: Safety::default(),
            modes: Modes::default(),
            halt: HaltPolicy::default(),
            permissive: Vec::new(),
            interlocks: Vec::new(),
            supervision: std::collections::BTreeMap::new(),
        }
    }
}

/// Which outputs may stay on in a stopped machine (SETTINGS `hold-safe`)
/// and which the program switches off when it halts (`de-energise on
/// halt`). Undeclared, a cylinder's coil may stay on (it holds the piston
/// where it is, as a stopped pneumatic machine does) and an alarm lamp is
/// meant to; a machine output (`Y:heater`, a motor, a spray valve) may
/// not: a machine that stops with it on is a hazard of energy.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct HaltPolicy {
    pub hold_safe: std::collections::BTreeSet<Signal>,
    pub off_on_halt: std::collections::BTreeSet<Signal>,
    /// Outputs the emergency stop leaves on (SETTINGS `hold on estop`: a
    /// vacuum gripper keeps its part, a clamp its workpiece).
    pub hold_on_estop: std::collections::BTreeSet<Signal>,
    /// What each named output does when STOP is pressed (SETTINGS `on
    /// stop`). Empty: STOP lets the cycle finish. Any entry makes STOP act
    /// at once, in any state: the sequence is abandoned, every coil and
    /// output goes off but those held or running on.
    pub on_stop: std::collections::BTreeMap<Signal, StopAction>,
    /// What the emergency stop and a halt do per output (SETTINGS `on
    /// estop`, `on halt`), as written; their `hold` and `off` are also in
    /// `hold_on_estop`, `off_on_halt` and `hold_safe`, which the rungs read.
    pub on_estop: std::collections::BTreeMap<Signal, StopAction>,
    pub on_halt: std::collections::BTreeMap<Signal, StopAction>,
}

/// An input that must stay on, always or while the sequence is in a range
/// of steps (`guard_closed in steps 3-5`: from step 3 firing until step 6
/// fires).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Interlock {
    pub input: crate::cell::Name,
    /// First and last step, as numbered in the table.
    pub steps: Option<(usize, usize)>,
}

/// What makes the machine stop, for the outputs' stop behaviour.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum StopEvent {
    /// STOP pressed (with an `on stop` row: at once).
    Stop,
    /// The emergency stop.
    EStop,
    /// A safety check or an interlock halts the machine.
    Halt,
}

impl StopEvent {
    pub const ALL: [StopEvent; 3] = [StopEvent::Stop, StopEvent::EStop, StopEvent::Halt];

    /// `STOP`, `the emergency stop`, `a halt`: after the word "after".
    pub fn text(self) -> &'static str {
        match self {
            StopEvent::Stop => "STOP",
            StopEvent::EStop => "the emergency stop",
            StopEvent::Halt => "a halt",
        }
    }
}

/// An output that stays on for a while after a stop event.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RunOn {
    pub event: StopEvent,
    pub output: Signal,
    pub ms: u32,
}

/// What an output does when the machine stops.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StopAction {
    Off,
    Hold,
    /// Stays on this many milliseconds more, then goes off (an oven's fan).
    OffAfter(u32),
}

impl HaltPolicy {
    /// Every output that runs on after an event, by event (STOP, the
    /// emergency stop, a halt), then signal.
    pub fn run_ons(&self) -> Vec<RunOn> {
        [
            (StopEvent::Stop, &self.on_stop),
            (StopEvent::EStop, &self.on_estop),
            (StopEvent::Halt, &self.on_halt),
        ]
        .into_iter()
        .flat_map(|(event, actions)| {
            actions
                .iter()
                .filter_map(move |(output, action)| match action {
                    StopAction::OffAfter(ms) => Some(RunOn {
                        event,
                        output: *output,
                        ms: *ms,
                    }),
                    _ => None,
                })
        })
        .collect()
    }

    /// Whether `output` may stay on in a machine that has stopped:
    /// `by_default` unless the SETTINGS rows say otherwise.
    pub fn may_stay_on(&self, output: Signal, by_default: bool) -> bool {
        if self.hold_safe.contains(&output)
            || self.hold_on_estop.contains(&output)
            || self.on_stop.get(&output) == Some(&StopAction::Hold)
        {
            return true;
        }
        if self.off_on_halt.contains(&output) {
            return false;
        }
        by_default
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
    /// Criteria analysis on the watchdog (which it brings): when a step
    /// runs out of time, one output per condition of the awaited transition
    /// says which are not met. Not part of `all`: it adds outputs an HMI
    /// reads, asked for by name.
    pub criteria: bool,
}

impl std::str::FromStr for Safety {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        Safety::parse(text)
    }
}

impl std::str::FromStr for Modes {
    type Err = String;

    fn from_str(text: &str) -> Result<Self, String> {
        Modes::parse(text)
    }
}

impl Safety {
    /// All four checks.
    pub fn all() -> Self {
        Safety {
            edge: true,
            precheck: true,
            plausibility: true,
            watchdog: true,
            criteria: false,
        }
    }

    /// The checks by name, as `--safety` and the SETTINGS sheet write
    /// them (besides `all` and `none`).
    pub const NAMES: [&str; 5] = ["edge", "precheck", "plausibility", "watchdog", "criteria"];

    /// Parses `edge,precheck,plausibility,watchdog,criteria` (any subset;
    /// `all`, `none`; `all` is every check but `criteria`). The criteria
    /// analysis reads the watchdog, so `criteria` brings `watchdog`.
    pub fn parse(text: &str) -> Result<Safety, String> {
        let mut safety = Safety::default();
        for item in named_set(text, &Safety::NAMES, "a safety check", Safety::expected)? {
            match item {
                "all" => safety = Safety::all(),
                "edge" => safety.edge = true,
                "precheck" => safety.precheck = true,
                "plausibility" => safety.plausibility = true,
                "watchdog" => safety.watchdog = true,
                "criteria" => {
                    safety.watchdog = true;
                    safety.criteria = true;
                }
                _ => {}
            }
        }
        Ok(safety)
    }

    /// What `--safety` and the SETTINGS row accept, for messages.
    pub fn expected() -> String {
        let mut all = Safety::NAMES.to_vec();
        all.extend(["all", "none"]);
        crate::diag::or_list(&all)
    }

    /// Whether the program has a `halt` memory: a check that stops the
    /// sequence (plausibility, watchdog) or an emergency stop sets it. The
    /// one place this is decided, for the allocation and the program.
    pub fn halts(self, modes: &Modes) -> bool {
        self.plausibility || self.watchdog || modes.estop
    }
}

/// The items of a `--safety` / `--modes` list, lower-cased, each checked
/// by the one list reader every option shares (`crate::named_set`): one of
/// `names`, `all` or `none`, each once, `all`/`none` alone.
fn named_set(
    text: &str,
    names: &[&'static str],
    what: &str,
    expected: fn() -> String,
) -> Result<Vec<&'static str>, String> {
    let expected = expected();
    crate::named_set::NameList {
        names,
        alone: &["all", "none"],
        expected: &expected,
    }
    .parse(text, |item| {
        format!("\"{item}\" is not {what} (expected {expected})")
    })
}

/// The operating modes a generated program carries (`--modes`).
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Modes {
    /// A CONTINUOUS switch repeats cycles while it is on.
    pub continuous: bool,
    /// A STOP button lets the cycle finish, then halts.
    pub stop: bool,
    /// An EMERGENCY STOP switches every coil off and blocks START until RESET.
    pub estop: bool,
    /// A RESET button homes every actuator.
    pub reset: bool,
    /// Single-step mode: with the STEP_MODE switch on, each transition
    /// fires only on a press of STEP_PB (its conditions still checked), at
    /// most one per press.
    pub step: bool,
    /// Manual mode: with the MAN_MODE selector at 1 the automatic cycle
    /// ends and each actuator moves only while its jog button is held,
    /// where it may move (`manual.rs`).
    pub manual: bool,
    /// Homing stages, each a set of actuators homed together; `None` is the
    /// default (the order the cycle returns them home).
    pub home_order: Option<Vec<Vec<u32>>>,
}

impl Modes {
    /// The modes by name, as `--modes` and the SETTINGS sheet write them
    /// (besides `all` and `none`).
    pub const NAMES: [&str; 6] = ["continuous", "stop", "estop", "reset", "step", "manual"];

    /// What `--modes` and the SETTINGS row accept, for messages.
    pub fn expected() -> String {
        let mut all = Modes::NAMES.to_vec();
        all.extend(["all", "none"]);
        crate::diag::or_list(&all)
    }

    /// Parses `continuous,stop,estop,reset,step,manual` (any subset; `all`,
    /// `none`; `all` is every mode, the commissioning modes step and manual
    /// too, as issue 42 asks: a machine-ready program has them all). An
    /// emergency stop needs RESET as its way out, so `estop` brings `reset`.
    pub fn parse(text: &str) -> Result<Modes, String> {
        let mut modes = Modes::default();
        for item in named_set(text, &Modes::NAMES, "an operating mode", Modes::expected)? {
            match item {
                "all" => {
                    modes.continuous = true;
                    modes.stop = true;
                    modes.estop = true;
                    modes.reset = true;
                    modes.step = true;
                    modes.manual = true;
                }
                "continuous" => modes.continuous = true,
                "stop" => modes.stop = true,
                "estop" => modes.estop = true,
                "reset" => modes.reset = true,
                "step" => modes.step = true,
                "manual" => modes.manual = true,
                _ => {}
            }
        }
        if modes.estop {
            modes.reset = true;
        }
        Ok(modes)
    }

    /// Parses `--home-order`: stages separated by `,`, actuators homed
    /// together joined by `&` or spaces: `C3&C4, C2, C1`. Each actuator as
    /// written (`C1`, `1A1`, `clamp`): which one a name means is known once
    /// the table's SETTINGS names are read
    /// (the naming authority's `Naming::actuator_called`).
    pub fn parse_home_order(text: &str) -> Result<Vec<Vec<String>>, String> {
        let mut stages = Vec::new();
        // Composed, as the table's names are read (a terminal may pass `Ö`
        // as O and a combining mark).
        let text = &*crate::cell::composed_str(text);
        for stage in text.split([',', ';']) {
            let mut actuators = Vec::new();
            // `C1&` or `&C2`: an actuator of the stage was lost.
            if stage.contains('&') && stage.split('&').any(|part| part.trim().is_empty()) {
                return Err(format!(
                    "the home order \"{}\" has a stage with an empty item beside its &; name each actuator of a stage (e.g. C3&C4)",
                    text.trim()
                ));
            }
            for item in stage_items(stage)? {
                let item = item.as_str();
                // A number, an ISO designation or a name (`gripper_arm`):
                // which actuator it means, the naming authority says once
                // the table's names are read.
                let (actuator, _) = bracketed(item);
                let named = crate::cell::parse_actuator(actuator).is_some()
                    || crate::cell::iso_actuator(actuator).is_some()
                    || actuator.starts_with(|c: char| c.is_alphabetic())
                        && actuator
                            .chars()
                            .all(|c| c.is_alphanumeric() || c == '_' || c == '-');
                if !named {
                    return Err(format!(
                        "\"{item}\" is not an actuator (expected C1, C2, …, its ISO designation 1A1, or its name from the SETTINGS actuator table)"
                    ));
                }
                actuators.push(item.to_string());
            }
            // `C2,,C1` or a trailing `,`: a stage was left out or a name lost.
            if actuators.is_empty() {
                return Err(format!(
                    "the home order \"{}\" has an empty stage between its commas; name each stage's actuators (e.g. C3&C4,C2,C1)",
                    text.trim()
                ));
            }
            stages.push(actuators);
        }
        Ok(stages)
    }

    pub fn any(&self) -> bool {
        self.continuous || self.stop || self.estop || self.reset || self.step || self.manual
    }

    /// The input of each mode that is on, in address order.
    pub fn buttons(&self) -> impl Iterator<Item = super::Signal> {
        use super::Signal;
        [
            (self.continuous, Signal::Continuous),
            (self.stop, Signal::Stop),
            (self.estop, Signal::EStop),
            (self.reset, Signal::Reset),
            (self.step, Signal::StepMode),
            (self.step, Signal::StepButton),
            (self.manual, Signal::ManualMode),
        ]
        .into_iter()
        .filter_map(|(on, signal)| on.then_some(signal))
    }

    /// The homing stages for a table: the given order, checked against the
    /// table, or by default the order the cycle returns them home.
    pub fn home_stages(&self, table: &StepTable) -> Result<Vec<Vec<u32>>, String> {
        table.home_stages(self.home_order.as_deref())
    }
}

/// The items of one home-order stage, parted at `&` and at spaces; `C 2`
/// is C2, as the table and `--valve` read it (a `C` alone names nothing),
/// and a number after an actuator (`C1 0`) is a split number, not an
/// actuator of its own.
fn stage_items(stage: &str) -> Result<Vec<String>, String> {
    let mut items: Vec<String> = Vec::new();
    // `then`, as steptable prints a home order (`C2, then C1`), only joins.
    let stage = match stage.trim_start().split_once(char::is_whitespace) {
        Some((then, rest)) if then.eq_ignore_ascii_case("then") => rest,
        _ => stage,
    };
    for part in stage.split('&') {
        let first = items.len();
        // `C2(gripper arm)`: the bracket parts the name as a space does.
        let part = part.replace('(', " (");
        let mut words = part.split_whitespace();
        while let Some(item) = words.next() {
            if item.starts_with('(') {
                named_as(&mut items, first, item, &mut words)?;
                continue;
            }
            joined(&mut items, first, item)?;
        }
    }
    Ok(items)
}

/// `C1 (clamp)`, as steptable prints an actuator: the name in brackets
/// (its words up to the closing one) goes with the item before it, which
/// the naming authority checks it names.
fn named_as<'a>(
    items: &mut [String],
    first: usize,
    opening: &'a str,
    words: &mut impl Iterator<Item = &'a str>,
) -> Result<(), String> {
    let mut name = vec![opening];
    while !name[name.len() - 1].ends_with(')') {
        match words.next() {
            Some(word) => name.push(word),
            None => return Err(format!("\"{}\" has no closing bracket", name.join(" "))),
        }
    }
    let name = name.join(" ");
    match items.len() > first {
        true => {
            let last = items.len() - 1;
            items[last] = format!("{} {name}", items[last]);
            Ok(())
        }
        false => Err(format!(
            "\"{name}\" follows no actuator: write the actuator before its name, C1 (clamp)"
        )),
    }
}

/// An item and the name it gives in brackets: `C1 (clamp)` → `C1`,
/// `clamp`.
pub fn bracketed(item: &str) -> (&str, Option<&str>) {
    // The first bracket opens the name; a name of the engineer's own that
    // holds brackets is read whole before this (`Naming::actuator_called`).
    match item
        .trim()
        .strip_suffix(')')
        .and_then(|i| i.split_once('('))
    {
        Some((actuator, name)) if !actuator.trim().is_empty() => {
            (actuator.trim(), Some(name.trim()))
        }
        _ => (item, None),
    }
}

/// Adds `item` to `items`, joined to the one before it in the same part
/// of the stage (from `first`) where a space split an actuator's number.
fn joined(items: &mut Vec<String>, first: usize, item: &str) -> Result<(), String> {
    let digits = !item.is_empty() && item.chars().all(|c| c.is_ascii_digit());
    if digits
        && items.len() > first
        && let Some(last) = items.last_mut()
    {
        if crate::cell::normalize(last) == "C" {
            last.push_str(item);
            return Ok(());
        }
        if crate::cell::parse_actuator(last).is_some() {
            return Err(format!(
                "\"{last} {item}\": a space splits the actuator's number (write {last}{item} if that is meant)"
            ));
        }
    }
    items.push(item.to_string());
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `C 2` is C2 in a home order as in the table; `C1 0` is a split
    /// number, said so; `C1 C2` and `C1&2` stay two items (rt24 F6).
    #[test]
    fn a_space_inside_an_actuators_number_is_read_as_the_table_reads_it() {
        let order = |t: &str| Modes::parse_home_order(t);
        assert_eq!(order("C 2, c 1").unwrap(), [vec!["C2"], vec!["c1"]]);
        assert_eq!(order("C3 C4&C 5").unwrap(), [vec!["C3", "C4", "C5"]]);
        let split = order("C2, C1 0").unwrap_err();
        assert!(split.contains("\"C1 0\": a space splits"), "{split}");
        assert!(
            order("C1&2")
                .unwrap_err()
                .contains("\"2\" is not an actuator")
        );
    }

    /// A run-on belongs to an event the program has: `on estop: fan off
    /// after 20s` without the emergency stop mode gives no run-on timer.
    #[test]
    fn run_ons_only_for_events_the_program_has() {
        let fan = Signal::MachineOutput(crate::cell::Name::new("fan").unwrap());
        let mut options = ProgramOptions::default();
        options
            .halt
            .on_estop
            .insert(fan, StopAction::OffAfter(20_000));
        assert!(options.run_ons().is_empty());
        options.modes.estop = true;
        assert_eq!(
            options.run_ons(),
            [RunOn {
                event: StopEvent::EStop,
                output: fan,
                ms: 20_000
            }]
        );
    }

    /// Zones are numbered from 1 (`zone1`), the interlocks without a step
    /// range left out.
    #[test]
    fn zones_count_from_one() {
        let name = |n: &str| crate::cell::Name::new(n).unwrap();
        let options = ProgramOptions {
            interlocks: vec![
                Interlock {
                    input: name("guard"),
                    steps: None,
                },
                Interlock {
                    input: name("door"),
                    steps: Some((2, 3)),
                },
            ],
            ..ProgramOptions::default()
        };
        let zones: Vec<Signal> = options.zones().map(|(zone, _)| zone).collect();
        assert_eq!(zones, [Signal::InterlockZone(1)]);
        assert_eq!(zones[0].symbol(), "zone1");
    }
}
