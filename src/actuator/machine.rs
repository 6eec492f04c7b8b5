//! The machine description: which kind each actuator is, and the option
//! lists that give kinds and loads per actuator (`--valve`, `--load`).

use std::collections::BTreeMap;

use super::ActuatorKind;
use crate::stroke::{Strokes, given_twice};

/// The machine a table runs on, as the engineer describes it (the
/// `--valve`, `--stroke` and `--load` options and the SETTINGS actuator
/// table): each actuator's kind, its stroke times and its load. The
/// simulation runs this machine; the program reads its kinds and strokes.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Machine {
    /// Kinds given explicitly (the others get the default for their positions).
    pub valves: Valves,
    /// Stroke times of every actuator.
    pub strokes: Strokes,
    /// Drift, in stroke per second, of a piston on a 5/3 valve with no coil
    /// on: the load on an exhausted centre (towards home), the creep of a
    /// pressurised centre (outwards). Per actuator; default 0.05.
    pub loads: BTreeMap<u32, f64>,
}

/// Valve types given explicitly, per actuator number.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Valves {
    pub per_actuator: BTreeMap<u32, ActuatorKind>,
}

impl Valves {
    /// The valve of actuator `number` whose highest position is `max_position`.
    pub fn of(&self, number: u32, max_position: u32) -> ActuatorKind {
        self.per_actuator
            .get(&number)
            .copied()
            .unwrap_or(ActuatorKind::default_for(max_position))
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
pub fn parse_valves(text: &str) -> Result<BTreeMap<u32, ActuatorKind>, String> {
    let mut valves = BTreeMap::new();
    for item in text.split(',').map(str::trim).filter(|i| !i.is_empty()) {
        let (name, valve) = item
            .split_once('=')
            .ok_or_else(|| format!("\"{item}\": expected C<number>=<valve>, e.g. C1=52mono"))?;
        let actuator = crate::cell::parse_actuator(name)
            .ok_or_else(|| format!("\"{item}\": expected an actuator such as C1 before ="))?;
        let valve: ActuatorKind = valve.parse().map_err(|e| format!("\"{item}\": {e}"))?;
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
        assert_eq!(v[&1], ActuatorKind::Mono52);
        assert_eq!(v[&2], ActuatorKind::Closed53);
        assert_eq!(v[&3], ActuatorKind::Pressure53);
        assert!(
            parse_valves("C1=52")
                .unwrap_err()
                .contains("not a valve type")
        );
        assert_eq!(Valves::default().of(4, 3), ActuatorKind::Closed53);
        assert_eq!(Valves::default().of(4, 1), ActuatorKind::Bistable52);
    }
}
