//! The SETTINGS sheet of a workbook: target, mnemonics, scan time, safety
//! checks and stroke times per actuator, next to the table they belong to.
//! Command-line flags override it; an invalid value is an error naming its cell.
//!
//! Layout: a label in any cell (`target`, `mnemonic`, `scan time`, `safety`)
//! with its value in the next filled cell to the right; and a small table
//! headed `actuator | extend | retract` with rows such as `C2 | 1.5s | 0.8s`.

use std::collections::BTreeMap;

use crate::address::{Mnemonic, Modes, Safety, Target};
use crate::diag::{CellPos, Code, Diagnostics};
use crate::read::{CellValue, Grid};
use crate::timing::{Stroke, parse_duration_ms};
use crate::valve::ValveType;

/// What a SETTINGS sheet says; `None` where it says nothing.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct SheetSettings {
    pub target: Option<Target>,
    pub mnemonic: Option<Mnemonic>,
    pub scan_ms: Option<u32>,
    pub safety: Option<Safety>,
    /// Operating modes (`continuous, stop, estop, reset`).
    pub modes: Option<Modes>,
    /// Homing stages (`C3&C4, C2, C1`).
    pub home_order: Option<Vec<Vec<u32>>>,
    pub strokes: BTreeMap<u32, Stroke>,
    /// Valve types from the table's `valve` column.
    pub valves: BTreeMap<u32, ValveType>,
    /// Drift rates from the table's `load` column (stroke per second).
    pub loads: BTreeMap<u32, f64>,
}

/// Where the actuator table's columns are: its header cell and the columns
/// of extend and retract times, and of the optional valve and load.
struct ActuatorColumns {
    header: CellPos,
    extend: u32,
    retract: u32,
    valve: Option<u32>,
    load: Option<u32>,
}

/// The labels of the settings, as written on the sheet.
pub const LABELS: [&str; 6] = [
    "target",
    "mnemonic",
    "scan time",
    "safety",
    "modes",
    "home order",
];

fn text_of(value: &CellValue) -> String {
    match value {
        CellValue::Text(t) => t.trim().to_string(),
        CellValue::Number(n) => format!("{n}"),
        CellValue::Bool(b) => b.to_string(),
        CellValue::Date(d) | CellValue::Error(d) => d.clone(),
    }
}

fn label_of(value: &CellValue) -> Option<String> {
    match value {
        CellValue::Text(t) => Some(t.trim().trim_end_matches(':').trim().to_ascii_lowercase()),
        _ => None,
    }
}

/// Reads the settings sheet. Problems go to `diags` with their cells.
pub fn parse(grid: &Grid, diags: &mut Diagnostics) -> SheetSettings {
    let mut settings = SheetSettings::default();
    let value_right_of = |pos: CellPos| {
        grid.cells
            .iter()
            .filter(|c| c.pos.row == pos.row && c.pos.col > pos.col)
            .min_by_key(|c| c.pos.col)
    };
    let mut stroke_header: Option<ActuatorColumns> = None;
    for cell in &grid.cells {
        let Some(label) = label_of(&cell.value) else {
            continue;
        };
        if label == "actuator" {
            let column = |name: &str| {
                grid.cells
                    .iter()
                    .find(|c| {
                        c.pos.row == cell.pos.row && label_of(&c.value).as_deref() == Some(name)
                    })
                    .map(|c| c.pos.col)
            };
            if let (Some(extend), Some(retract)) = (column("extend"), column("retract")) {
                stroke_header = Some(ActuatorColumns {
                    header: cell.pos,
                    extend,
                    retract,
                    valve: column("valve"),
                    load: column("load"),
                });
            }
            continue;
        }
        if !LABELS.contains(&label.as_str()) {
            continue;
        }
        let Some(value_cell) = value_right_of(cell.pos) else {
            continue;
        };
        let value = text_of(&value_cell.value);
        let lower = value.to_ascii_lowercase();
        let mut bad = |expected: &str| {
            diags.error(
                Code::E030BadSetting,
                grid.location(value_cell.pos),
                format!("{label}: \"{value}\" is not valid (expected {expected})"),
            );
        };
        match label.as_str() {
            "target" => match lower.as_str() {
                "festo" => settings.target = Some(Target::Festo),
                "iec" => settings.target = Some(Target::Iec),
                "siemens" => settings.target = Some(Target::Siemens),
                _ => bad("festo, iec or siemens"),
            },
            "mnemonic" => match lower.as_str() {
                "en" => settings.mnemonic = Some(Mnemonic::En),
                "de" => settings.mnemonic = Some(Mnemonic::De),
                _ => bad("en or de"),
            },
            "scan time" => match parse_duration_ms(&value).filter(|ms| *ms <= 1000) {
                Some(ms) => settings.scan_ms = Some(ms),
                None => bad("a scan time from 1ms to 1s, such as 10ms"),
            },
            "safety" => match Safety::parse(&value) {
                Ok(safety) => settings.safety = Some(safety),
                Err(_) => bad("none, all, or some of edge, precheck, plausibility, watchdog"),
            },
            "modes" => match Modes::parse(&value) {
                Ok(modes) => settings.modes = Some(modes),
                Err(_) => bad("none, all, or some of continuous, stop, estop, reset"),
            },
            "home order" if lower == "default" => {}
            "home order" => match Modes::parse_home_order(&value) {
                Ok(order) => settings.home_order = Some(order),
                Err(_) => bad("stages of actuators such as C3&C4, C2, C1"),
            },
            _ => {}
        }
    }
    if let Some(ActuatorColumns {
        header,
        extend: extend_col,
        retract: retract_col,
        valve: valve_col,
        load: load_col,
    }) = stroke_header
    {
        let mut rows: Vec<u32> = grid
            .cells
            .iter()
            .filter(|c| c.pos.col == header.col && c.pos.row > header.row)
            .map(|c| c.pos.row)
            .collect();
        rows.dedup();
        for row in rows {
            let at = |col: u32| {
                grid.cells
                    .iter()
                    .find(|c| c.pos.row == row && c.pos.col == col)
            };
            let Some(name_cell) = at(header.col) else {
                continue;
            };
            let name = crate::cell::normalize(&text_of(&name_cell.value));
            // The table ends at the first row that names no actuator.
            let Some(actuator) = name
                .strip_prefix('C')
                .and_then(|n| n.parse::<u32>().ok())
                .filter(|n| (1..=crate::cell::MAX_ACTUATOR).contains(n))
            else {
                break;
            };
            if let Some(cell) = valve_col.and_then(&at) {
                let text = text_of(&cell.value);
                match ValveType::parse(&text) {
                    Some(valve) => {
                        settings.valves.insert(actuator, valve);
                    }
                    None => diags.error(
                        Code::E030BadSetting,
                        grid.location(cell.pos),
                        format!("valve of C{actuator}: \"{text}\" is not a valve type (expected 52bi, 52mono, 53closed, 53exhaust or 53pressure)"),
                    ),
                }
            }
            if let Some(cell) = load_col.and_then(&at) {
                let text = text_of(&cell.value);
                match text.replace(',', ".").parse::<f64>() {
                    Ok(load) if (0.0..=10.0).contains(&load) => {
                        settings.loads.insert(actuator, load);
                    }
                    _ => diags.error(
                        Code::E030BadSetting,
                        grid.location(cell.pos),
                        format!("load of C{actuator}: \"{text}\" is not a drift in stroke per second from 0 to 10, such as 0.05"),
                    ),
                }
            }
            let mut time = |col: u32| -> Option<u32> {
                let cell = at(col)?;
                let text = text_of(&cell.value);
                let ms = parse_duration_ms(&text);
                if ms.is_none() {
                    diags.error(
                        Code::E030BadSetting,
                        grid.location(cell.pos),
                        format!("stroke time of C{actuator}: \"{text}\" is not a time such as 1.5s or 800ms"),
                    );
                }
                ms
            };
            let (extend, retract) = (
                at(extend_col).and_then(|_| time(extend_col)),
                at(retract_col).and_then(|_| time(retract_col)),
            );
            if extend.is_none() && retract.is_none() {
                continue;
            }
            let default = Stroke::default();
            settings.strokes.insert(
                actuator,
                Stroke {
                    extend_ms: extend.unwrap_or(default.extend_ms),
                    retract_ms: retract.unwrap_or(default.retract_ms),
                },
            );
        }
    }
    settings
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(rows: &[&[&str]]) -> Grid {
        Grid::from_text_rows("t.xlsx", Some("SETTINGS"), rows)
    }

    #[test]
    fn reads_every_setting() {
        let mut diags = Diagnostics::new();
        let s = parse(
            &grid(&[
                &["SETTINGS"],
                &["target", "siemens", "note"],
                &["Mnemonic:", "DE"],
                &["scan time", "20ms"],
                &["safety", "edge, watchdog"],
                &[],
                &["actuator", "extend", "retract"],
                &["C1", "1.5s", "0.8s"],
                &["c2", "2"],
                &["notes below"],
            ]),
            &mut diags,
        );
        assert!(!diags.has_errors(), "{diags:?}");
        assert_eq!(s.target, Some(Target::Siemens));
        assert_eq!(s.mnemonic, Some(Mnemonic::De));
        assert_eq!(s.scan_ms, Some(20));
        assert_eq!(
            s.safety.map(|x| (x.edge, x.watchdog, x.precheck)),
            Some((true, true, false))
        );
        assert_eq!(
            s.strokes[&1],
            Stroke {
                extend_ms: 1500,
                retract_ms: 800
            }
        );
        assert_eq!(
            s.strokes[&2],
            Stroke {
                extend_ms: 2000,
                retract_ms: 1000
            }
        );
    }

    #[test]
    fn invalid_values_name_their_cells() {
        let mut diags = Diagnostics::new();
        parse(
            &grid(&[
                &["target", "beckhoff"],
                &["scan time", "5s"],
                &["actuator", "extend", "retract"],
                &["C1", "fast", "1s"],
            ]),
            &mut diags,
        );
        let messages: Vec<String> = diags.into_sorted().iter().map(|d| d.to_string()).collect();
        assert!(
            messages[0].contains("SETTINGS!B1: error[E030]: target: \"beckhoff\""),
            "{messages:?}"
        );
        assert!(messages[1].contains("SETTINGS!B2"), "{messages:?}");
        assert!(
            messages[2].contains("SETTINGS!B4") && messages[2].contains("\"fast\""),
            "{messages:?}"
        );
    }
}
