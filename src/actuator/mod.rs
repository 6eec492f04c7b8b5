//! The actuator model: what a kind of actuator is. One type,
//! [`ActuatorKind`], owns every decision that differs between kinds — its
//! coils or contactors ([`CoilSet`]), the positions it can hold, what may
//! stay on when the machine halts, its default, how the simulated plant
//! moves it ([`plant`]) and how its failures are said. The program, the
//! settings, the table checks and the simulator ask the kind; none of them
//! matches on it. Which kind each actuator of a machine is, its loads and
//! the option parsers are the machine description ([`machine`]).
//!
//! Adding a kind: a variant here with its arms, its plant arms in
//! [`plant`], its words in `words.rs`, and its tests.

pub mod machine;
pub mod plant;
mod words;

use std::fmt;

pub use machine::{Machine, Valves, parse_load, parse_loads, parse_valves};
pub use plant::Spool;

/// A kind of actuator: a cylinder on one of the directional valves, or an
/// electric drive.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ActuatorKind {
    /// 5/2 double solenoid, bistable: keeps the last coil's position
    /// (default for two-position actuators).
    Bistable52,
    /// 5/2 single solenoid with spring return: coil on = extend, off = retract.
    Mono52,
    /// 5/3 closed centre: no coil holds the piston (default with middle positions).
    Closed53,
    /// 5/3 exhausted centre: no coil vents both chambers; a load drifts the piston.
    Exhaust53,
    /// 5/3 pressurised centre: no coil pressurises both chambers; the piston
    /// creeps towards the rod side (the larger area pushes).
    Pressure53,
    /// Not a valve: an electric drive (a gantry, a conveyor axis) with
    /// forward and reverse contactors as its + and - outputs and limit
    /// switches as its sensors. It runs only while an output is on, so the
    /// program cuts the drive at every target; with neither on it stands.
    Motor,
    /// Not a cylinder: a vacuum gripper (a suction cup). Its one output
    /// `yi` switches the vacuum on; its one sensor, the vacuum switch
    /// `xi1`, reads 1 once the part is held (after the build-up time) and
    /// drops once the vacuum is gone (after the release time). Position 1
    /// is held (`Ci+1`), position 0 released (`Ci-0`): the program reads
    /// "released" as the vacuum switch off. A halt or an EMERGENCY STOP
    /// keeps the vacuum on unless the engineer says otherwise: switched
    /// off, it drops the part wherever the arm is.
    Vacuum,
    /// Not a cylinder: a pneumatic swivel (semi-rotary) drive, as on the
    /// Festo MPS stations' swivel arms (a DSM/DRVS vane drive), on a 5/2
    /// double-solenoid valve. `yi+` swivels it to its end stop at 180°
    /// (position 1), `yi-` back to 0° (position 0, home), a proximity
    /// sensor at each end stop. It keeps turning to the stop its valve last
    /// chose and cannot stand between the stops: a middle position is E045.
    Swivel,
}

/// The outputs that move an actuator of a kind.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CoilSet {
    /// `yi+` and `yi-`: two coils, or a drive's two contactors.
    Double,
    /// The one coil `yi` (a spring takes the actuator back).
    Single,
}

/// What says an actuator is at a position: sensor `sensor` showing `on`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Reading {
    pub sensor: u32,
    pub on: bool,
}

impl std::str::FromStr for ActuatorKind {
    type Err = String;

    /// `52bi`, `5/2 mono`, `53-closed`, … in any case.
    fn from_str(text: &str) -> Result<Self, String> {
        let t = text
            .trim()
            .to_ascii_lowercase()
            .replace(['/', ' ', '-'], "");
        ActuatorKind::ALL
            .into_iter()
            .find(|v| v.name() == t)
            .ok_or_else(|| {
                // `5/2 monostable`, `5/3 closed centre`: the name is its start.
                let meant = ActuatorKind::ALL
                    .into_iter()
                    .filter(|v| t.starts_with(v.name()))
                    .max_by_key(|v| v.name().len())
                    .map(|v| format!(": did you mean {v}?"))
                    .unwrap_or_default();
                format!(
                    "\"{}\" is not a valve type{meant} (expected {})",
                    text.trim(),
                    crate::diag::or_list(&ActuatorKind::names())
                )
            })
    }
}

impl ActuatorKind {
    pub const ALL: [ActuatorKind; 8] = [
        ActuatorKind::Bistable52,
        ActuatorKind::Mono52,
        ActuatorKind::Closed53,
        ActuatorKind::Exhaust53,
        ActuatorKind::Pressure53,
        ActuatorKind::Motor,
        ActuatorKind::Vacuum,
        ActuatorKind::Swivel,
    ];

    /// Every kind's name, as `--valve` and the SETTINGS sheet write it.
    pub fn names() -> Vec<&'static str> {
        ActuatorKind::ALL.map(ActuatorKind::name).to_vec()
    }

    /// The name used in `--valve` and on the SETTINGS sheet.
    pub fn name(self) -> &'static str {
        match self {
            ActuatorKind::Bistable52 => "52bi",
            ActuatorKind::Mono52 => "52mono",
            ActuatorKind::Closed53 => "53closed",
            ActuatorKind::Exhaust53 => "53exhaust",
            ActuatorKind::Pressure53 => "53pressure",
            ActuatorKind::Motor => "motor",
            ActuatorKind::Vacuum => "vacuum",
            ActuatorKind::Swivel => "swivel",
        }
    }

    /// The kind an actuator gets unless told otherwise.
    pub fn default_for(max_position: u32) -> ActuatorKind {
        if max_position > 1 {
            ActuatorKind::Closed53
        } else {
            ActuatorKind::Bistable52
        }
    }

    /// The positions whose sensor it has, in address order: every position
    /// 0…`max_position` of every kind today. The program declares exactly
    /// these inputs; its conditions, plausibility rungs and homing read them
    /// through [`ActuatorKind::reading`].
    pub fn sensed_positions(self, max_position: u32) -> Vec<u32> {
        match self {
            // The vacuum switch alone: "released" is that switch off.
            ActuatorKind::Vacuum => vec![1],
            _ => (0..=max_position).collect(),
        }
    }

    /// How the program sees that it is at `position`: the sensor it reads
    /// and the level that sensor shows there (its own sensor on, for every
    /// kind that has one at `position`).
    pub fn reading(self, position: u32) -> Reading {
        match (self, position) {
            (ActuatorKind::Vacuum, 0) => Reading {
                sensor: 1,
                on: false,
            },
            _ => Reading {
                sensor: position,
                on: true,
            },
        }
    }

    /// The highest position it can hold, if its kind bounds it: a gripper
    /// holds (1) or releases (0), a swivel drive stands at one of its two
    /// end stops, nothing further (E045 refuses more).
    pub fn highest_position(self) -> Option<u32> {
        match self {
            ActuatorKind::Vacuum | ActuatorKind::Swivel => Some(1),
            _ => None,
        }
    }

    /// Whether its output holds a part and moves nothing: left on through
    /// a halt or an EMERGENCY STOP by default (switched off, a vacuum
    /// gripper drops its part wherever the arm stands).
    pub fn holds_part(self) -> bool {
        self == ActuatorKind::Vacuum
    }

    /// Whether the kind stops between its ends with no output on (a 5/3
    /// valve's centre, a drive standing), so it may hold a middle position.
    pub fn has_centre(self) -> bool {
        match self {
            ActuatorKind::Closed53
            | ActuatorKind::Exhaust53
            | ActuatorKind::Pressure53
            | ActuatorKind::Motor => true,
            ActuatorKind::Bistable52
            | ActuatorKind::Mono52
            | ActuatorKind::Vacuum
            | ActuatorKind::Swivel => false,
        }
    }

    /// The kinds that may hold a middle position, for the messages that
    /// refuse one.
    pub fn centred() -> Vec<&'static str> {
        ActuatorKind::ALL
            .into_iter()
            .filter(|k| k.has_centre())
            .map(ActuatorKind::name)
            .collect()
    }

    /// The outputs that move it.
    pub fn coils(self) -> CoilSet {
        match self {
            ActuatorKind::Mono52 | ActuatorKind::Vacuum => CoilSet::Single,
            ActuatorKind::Bistable52
            | ActuatorKind::Closed53
            | ActuatorKind::Exhaust53
            | ActuatorKind::Pressure53
            | ActuatorKind::Motor
            | ActuatorKind::Swivel => CoilSet::Double,
        }
    }

    /// Whether it runs only while an output is on (an electric drive): the
    /// program cuts it at every target, and no halt may leave its outputs on.
    pub fn is_drive(self) -> bool {
        self == ActuatorKind::Motor
    }

    /// Whether a load (`--load`) moves it with no output on: only a 5/3
    /// centre that vents or pressurises its chambers lets one.
    pub fn load_drifts(self) -> bool {
        matches!(self, ActuatorKind::Exhaust53 | ActuatorKind::Pressure53)
    }

    /// Whether it has a jog button for `-` as well as `+`: a single coil's
    /// spring is the way back (`52mono`), but a coil that holds a part
    /// (a vacuum) stays on by itself, so its jogN- switches it off.
    pub fn jogs_back(self) -> bool {
        self.coils() == CoilSet::Double || self.holds_part()
    }

    /// The kinds with one jog button only, for the message that refuses
    /// a second: `52mono cylinder`.
    pub fn one_jog() -> Vec<String> {
        ActuatorKind::ALL
            .into_iter()
            .filter(|k| !k.jogs_back())
            .map(|k| format!("{} {}", k.name(), k.noun()))
            .collect()
    }
}

impl fmt::Display for ActuatorKind {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinds_parse_by_name() {
        let monostable = "5/2 monostable".parse::<ActuatorKind>().unwrap_err();
        assert!(monostable.contains("did you mean 52mono?"), "{monostable}");
        let closed = "5/3 closed centre".parse::<ActuatorKind>().unwrap_err();
        assert!(closed.contains("did you mean 53closed?"), "{closed}");
        // A drive stops anywhere (its outputs off) and is named motor.
        assert_eq!("Motor".parse::<ActuatorKind>(), Ok(ActuatorKind::Motor));
        assert!(ActuatorKind::ALL.contains(&ActuatorKind::Motor));
    }

    #[test]
    fn each_kind_says_what_it_is() {
        assert!(ActuatorKind::Motor.has_centre());
        assert!(!ActuatorKind::Mono52.has_centre());
        assert_eq!(ActuatorKind::Mono52.coils(), CoilSet::Single);
        assert_eq!(ActuatorKind::Motor.coils(), CoilSet::Double);
        assert!(ActuatorKind::Motor.is_drive());
        assert!(!ActuatorKind::Closed53.is_drive());
        assert!(ActuatorKind::Exhaust53.load_drifts());
        assert!(!ActuatorKind::Closed53.load_drifts());
        assert_eq!(
            ActuatorKind::centred(),
            ["53closed", "53exhaust", "53pressure", "motor"]
        );
        assert_eq!(ActuatorKind::default_for(3), ActuatorKind::Closed53);
        assert_eq!(ActuatorKind::default_for(1), ActuatorKind::Bistable52);
    }

    #[test]
    fn a_vacuum_gripper_reads_released_as_its_switch_off() {
        let vacuum = "Vacuum".parse::<ActuatorKind>().unwrap();
        assert_eq!(vacuum, ActuatorKind::Vacuum);
        assert_eq!(vacuum.coils(), CoilSet::Single);
        assert_eq!(vacuum.sensed_positions(1), [1]);
        assert_eq!(ActuatorKind::Mono52.sensed_positions(1), [0, 1]);
        let released = vacuum.reading(0);
        assert_eq!((released.sensor, released.on), (1, false));
        let held = vacuum.reading(1);
        assert_eq!((held.sensor, held.on), (1, true));
        assert_eq!(vacuum.highest_position(), Some(1));
        assert_eq!(ActuatorKind::Closed53.highest_position(), None);
        assert!(vacuum.holds_part() && !vacuum.has_centre() && !vacuum.is_drive());
        assert!(!ActuatorKind::centred().contains(&"vacuum"));
    }

    #[test]
    fn a_swivel_drive_has_two_coils_and_its_two_end_stops_only() {
        let swivel = "Swivel".parse::<ActuatorKind>().unwrap();
        assert_eq!(swivel, ActuatorKind::Swivel);
        let words = "swivel drive".parse::<ActuatorKind>().unwrap_err();
        assert!(words.contains("did you mean swivel?"), "{words}");
        assert_eq!(swivel.coils(), CoilSet::Double);
        assert_eq!(swivel.sensed_positions(1), [0, 1]);
        assert_eq!(swivel.highest_position(), Some(1));
        assert!(!swivel.has_centre() && !swivel.is_drive() && !swivel.holds_part());
        assert!(!swivel.load_drifts());
        assert_eq!(ActuatorKind::default_for(1), ActuatorKind::Bistable52);
    }
}
