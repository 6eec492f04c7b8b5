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
}

impl ValveType {
    pub const ALL: [ValveType; 5] = [
        ValveType::Bistable52,
        ValveType::Mono52,
        ValveType::Closed53,
        ValveType::Exhaust53,
        ValveType::Pressure53,
    ];

    /// The name used in `--valve` and on the SETTINGS sheet.
    pub fn name(self) -> &'static str {
        match self {
            ValveType::Bistable52 => "52bi",
            ValveType::Mono52 => "52mono",
            ValveType::Closed53 => "53closed",
            ValveType::Exhaust53 => "53exhaust",
            ValveType::Pressure53 => "53pressure",
        }
    }

    pub fn parse(text: &str) -> Option<ValveType> {
        let t = text
            .trim()
            .to_ascii_lowercase()
            .replace(['/', ' ', '-'], "");
        ValveType::ALL.into_iter().find(|v| v.name() == t)
    }

    /// Whether the valve has a centre position, so it can stop a piston between ends.
    pub fn has_centre(self) -> bool {
        matches!(
            self,
            ValveType::Closed53 | ValveType::Exhaust53 | ValveType::Pressure53
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

/// Parses `--valve C1=52mono,C2=53closed`.
pub fn parse_valves(text: &str) -> Result<BTreeMap<u32, ValveType>, String> {
    let mut valves = BTreeMap::new();
    for item in text.split(',').map(str::trim).filter(|i| !i.is_empty()) {
        let (name, valve) = item
            .split_once('=')
            .ok_or_else(|| format!("\"{item}\": expected C<number>=<valve>, e.g. C1=52mono"))?;
        let actuator = crate::cell::normalize(name)
            .strip_prefix('C')
            .and_then(|n| n.parse::<u32>().ok())
            .filter(|n| (1..=crate::cell::MAX_ACTUATOR).contains(n))
            .ok_or_else(|| format!("\"{item}\": expected an actuator such as C1 before ="))?;
        let valve = ValveType::parse(valve).ok_or_else(|| {
            format!(
                "\"{item}\": \"{}\" is not a valve type (expected 52bi, 52mono, 53closed, 53exhaust or 53pressure)",
                valve.trim()
            )
        })?;
        valves.insert(actuator, valve);
    }
    Ok(valves)
}

#[cfg(test)]
mod tests {
    use super::*;

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
        assert_eq!(Valves::default().of(4, 3), ValveType::Closed53);
        assert_eq!(Valves::default().of(4, 1), ValveType::Bistable52);
    }
}
