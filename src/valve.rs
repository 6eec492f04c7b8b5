//! Valve types per actuator. The valve decides how many coils an actuator has,
//! what the program holds, how a middle stop is made, and what the piston does
//! when no coil is on.

use std::collections::BTreeMap;
use std::fmt;

/// A directional valve.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum ValveType {
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
}

impl std::str::FromStr for ValveType {
    type Err = String;

    /// `52bi`, `5/2 mono`, `53-closed`, … in any case.
    fn from_str(text: &str) -> Result<Self, String> {
        let t = text
            .trim()
            .to_ascii_lowercase()
            .replace(['/', ' ', '-'], "");
        ValveType::ALL
            .into_iter()
            .find(|v| v.name() == t)
            .ok_or_else(|| {
                // `5/2 monostable`, `5/3 closed centre`: the name is its start.
                let meant = ValveType::ALL
                    .into_iter()
                    .filter(|v| t.starts_with(v.name()))
                    .max_by_key(|v| v.name().len())
                    .map(|v| format!(": did you mean {v}?"))
                    .unwrap_or_default();
                format!(
                    "\"{}\" is not a valve type{meant} (expected {})",
                    text.trim(),
                    crate::diag::or_list(&ValveType::names())
                )
            })
    }
}

impl ValveType {
    pub const ALL: [ValveType; 6] = [
        ValveType::Bistable52,
        ValveType::Mono52,
        ValveType::Closed53,
        ValveType::Exhaust53,
        ValveType::Pressure53,
        ValveType::Motor,
    ];

    /// Every valve type's name, as `--valve` and the SETTINGS sheet write it.
    pub fn names() -> Vec<&'static str> {
        ValveType::ALL.map(ValveType::name).to_vec()
    }

    /// The name used in `--valve` and on the SETTINGS sheet.
    pub fn name(self) -> &'static str {
        match self {
            ValveType::Bistable52 => "52bi",
            ValveType::Mono52 => "52mono",
            ValveType::Closed53 => "53closed",
            ValveType::Exhaust53 => "53exhaust",
            ValveType::Pressure53 => "53pressure",
            ValveType::Motor => "motor",
        }
    }

    /// Whether the valve has a centre position, so it can stop a piston between ends.
    pub fn has_centre(self) -> bool {
        matches!(
            self,
            ValveType::Closed53 | ValveType::Exhaust53 | ValveType::Pressure53 | ValveType::Motor
        )
    }

    /// The valve an actuator gets unless told otherwise.
    pub fn default_for(max_position: u32) -> ValveType {
        if max_position > 1 {
            ValveType::Closed53
        } else {
            ValveType::Bistable52
        }
    }
}

impl fmt::Display for ValveType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Valve types given explicitly, per actuator number.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Valves {
    pub per_actuator: BTreeMap<u32, ValveType>,
}

impl Valves {
    /// The valve of actuator `number` whose highest position is `max_position`.
    pub fn of(&self, number: u32, max_position: u32) -> ValveType {
        self.per_actuator
            .get(&number)
            .copied()
            .unwrap_or(ValveType::default_for(max_position))
    }
}

/// A drift rate in stroke per second, from 0 to 10 (`0.05`; a decimal comma
/// as a spreadsheet cell may hold it, `0,05`).
pub fn parse_load(text: &str) -> Option<f64> {
    text.trim()
        .replace(',', ".")
        .parse::<f64>()
        .ok()
        .filter(|l| (0.0..=10.0).contains(l))
}

/// An option's list that gives one actuator twice (`--valve
/// C1=52mono,C1=52bi`): refused, as the SETTINGS sheet refuses a row twice,
/// rather than the later value silently winning.
pub fn given_twice(item: &str, actuator: u32) -> String {
    format!("\"{item}\": C{actuator} is given twice; give each actuator once")
}

/// Parses `--load C2=0.1,C3=0.05`.
pub fn parse_loads(text: &str) -> Result<BTreeMap<u32, f64>, String> {
    let mut loads = BTreeMap::new();
    for item in text.split(',').map(str::trim).filter(|i| !i.is_empty()) {
        let (name, value) = item.split_once('=').ok_or_else(|| {
            format!("\"{item}\": expected C<number>=<stroke per second>, e.g. C2=0.1")
        })?;
        let actuator = crate::cell::parse_actuator(name)
            .ok_or_else(|| format!("\"{item}\": expected an actuator such as C2 before ="))?;
        let load = parse_load(value).ok_or_else(|| {
            format!("\"{item}\": expected a drift from 0 to 10 stroke per second")
        })?;
        if loads.insert(actuator, load).is_some() {
            return Err(given_twice(item, actuator));
        }
    }
    Ok(loads)
}

/// Parses `--valve C1=52mono,C2=53closed`.
pub fn parse_valves(text: &str) -> Result<BTreeMap<u32, ValveType>, String> {
    let mut valves = BTreeMap::new();
    for item in text.split(',').map(str::trim).filter(|i| !i.is_empty()) {
        let (name, valve) = item
            .split_once('=')
            .ok_or_else(|| format!("\"{item}\": expected C<number>=<valve>, e.g. C1=52mono"))?;
        let actuator = crate::cell::parse_actuator(name)
            .ok_or_else(|| format!("\"{item}\": expected an actuator such as C1 before ="))?;
        let valve: ValveType = valve.parse().map_err(|e| format!("\"{item}\": {e}"))?;
        if valves.insert(actuator, valve).is_some() {
            return Err(given_twice(item, actuator));
        }
    }
    Ok(valves)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loads_parse_as_on_the_settings_sheet() {
        let loads = parse_loads("C2=0.1, c3 = 0.05").unwrap();
        assert_eq!(loads[&2], 0.1);
        assert_eq!(loads[&3], 0.05);
        assert_eq!(parse_load("0,1"), Some(0.1));
        assert_eq!(parse_load("10"), Some(10.0));
        assert_eq!(parse_load("10.5"), None);
        assert_eq!(parse_load("-1"), None);
        assert!(parse_loads("C1000=0.1").is_err());
        assert!(parse_loads("C0=0.1").is_err());
        assert!(parse_loads("C2").is_err());
    }

    #[test]
    fn valve_names_parse() {
        let v = parse_valves("C1=52mono, c2 = 5/3closed,C3=53PRESSURE").unwrap();
        assert_eq!(v[&1], ValveType::Mono52);
        assert_eq!(v[&2], ValveType::Closed53);
        assert_eq!(v[&3], ValveType::Pressure53);
        assert!(
            parse_valves("C1=52")
                .unwrap_err()
                .contains("not a valve type")
        );
        let monostable = "5/2 monostable".parse::<ValveType>().unwrap_err();
        assert!(monostable.contains("did you mean 52mono?"), "{monostable}");
        let closed = "5/3 closed centre".parse::<ValveType>().unwrap_err();
        assert!(closed.contains("did you mean 53closed?"), "{closed}");
        assert_eq!(Valves::default().of(4, 3), ValveType::Closed53);
        // A drive stops anywhere (its outputs off) and is named motor.
        assert_eq!("Motor".parse::<ValveType>(), Ok(ValveType::Motor));
        assert!(ValveType::Motor.has_centre());
        assert!(ValveType::ALL.contains(&ValveType::Motor));
        assert_eq!(Valves::default().of(4, 1), ValveType::Bistable52);
    }
}
