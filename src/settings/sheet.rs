//! The SETTINGS sheet of a workbook: target, mnemonics, scan time, safety
//! checks and stroke times per actuator, next to the table they belong to.
//! Command-line flags override it; an invalid value is an error naming its cell.
//!
//! Layout: a label in any cell (`target`, `mnemonic`, `scan time`, `safety`)
//! with its value in the next filled cell to the right; and a small table
//! headed `actuator | extend | retract` with rows such as `C2 | 1.5s | 0.8s`.

use super::Given;
use crate::address::{Mnemonic, Target};
use crate::diag::{CellPos, Code, Diagnostics};
use crate::program::{Modes, Safety};
use crate::read::{CellValue, Grid, GridCell};
use crate::stroke::{Stroke, parse_duration_ms, parse_scan};
use crate::valve::ValveType;

/// Where the actuator table's columns are: its header cell and the columns
/// of extend and retract times, and of the optional valve and load.
struct ActuatorColumns {
    header: CellPos,
    extend: Option<u32>,
    retract: Option<u32>,
    valve: Option<u32>,
    load: Option<u32>,
}

/// The labels of the settings, as written on the sheet.
pub const LABELS: [&str; 15] = [
    "target",
    "board",
    "on stop",
    "on estop",
    "on halt",
    "hold-safe",
    "de-energise on halt",
    "start permissive",
    "interlock",
    "hold on estop",
    "mnemonic",
    "scan time",
    "safety",
    "modes",
    "home order",
];

/// The columns an actuator table may have, after `actuator`.
const COLUMNS: [&str; 4] = ["extend", "retract", "valve", "load"];

fn text_of(value: &CellValue) -> String {
    match value {
        CellValue::Text(t) => t.trim().to_string(),
        CellValue::Number(n) => format!("{n}"),
        CellValue::Bool(b) => b.to_string(),
        CellValue::Date(d) | CellValue::Error(d) | CellValue::Uncomputed(d) => d.clone(),
    }
}

fn label_of(value: &CellValue) -> Option<String> {
    match value {
        CellValue::Text(t) => Some(t.trim().trim_end_matches(':').trim().to_ascii_lowercase()),
        _ => None,
    }
}

/// The value of a cell as text, or `None` (reported) for a formula that was
/// never computed: its text is not what the engineer sees.
fn value_text(grid: &Grid, cell: &GridCell, diags: &mut Diagnostics) -> Option<String> {
    if let CellValue::Uncomputed(formula) = &cell.value {
        diags.error(
            Code::E016FormulaNotComputed,
            grid.location(cell.pos),
            format!(
                "the formula {formula} has no computed value; open and save the workbook in Excel or LibreOffice, or type the value"
            ),
        );
        return None;
    }
    Some(text_of(&cell.value))
}

/// Reads the settings sheet. Problems go to `diags` with their cells;
/// a row or column that looks meant for steptable but is not read is named.
pub fn parse(grid: &Grid, diags: &mut Diagnostics) -> Given {
    let mut settings = Given::default();
    let value_right_of = |pos: CellPos| {
        grid.cells
            .iter()
            .filter(|c| c.pos.row == pos.row && c.pos.col > pos.col)
            .min_by_key(|c| c.pos.col)
    };
    let mut stroke_header: Option<ActuatorColumns> = None;
    let mut label_cols: Vec<u32> = Vec::new();
    // Label cells and their values, which may sit beside the actuator table.
    let mut read_elsewhere: Vec<CellPos> = Vec::new();
    for cell in &grid.cells {
        let Some(label) = label_of(&cell.value) else {
            continue;
        };
        if label == "actuator" {
            stroke_header = Some(actuator_columns(grid, cell.pos, diags));
            continue;
        }
        if !LABELS.contains(&label.as_str()) {
            continue;
        }
        label_cols.push(cell.pos.col);
        read_elsewhere.push(cell.pos);
        let Some(value_cell) = value_right_of(cell.pos) else {
            continue;
        };
        read_elsewhere.push(value_cell.pos);
        let Some(value) = value_text(grid, value_cell, diags) else {
            continue;
        };
        let lower = value.to_ascii_lowercase();
        let mut bad = |expected: &str| {
            diags.error(
                Code::E030BadSetting,
                grid.location(value_cell.pos),
                format!("{label}: \"{value}\" is not valid (expected {expected})"),
            );
        };
        match label.as_str() {
            "target" => match value.parse::<Target>() {
                Ok(target) => settings.target = Some(target),
                Err(_) => bad("festo, iec, openplc or siemens"),
            },
            "board" if lower == "none" => {}
            "board" => match value.parse::<crate::address::Board>() {
                Ok(board) => settings.board = Some(board),
                Err(_) => bad(&format!(
                    "none or one of {}",
                    crate::address::BOARDS.map(|b| b.name).join(", ")
                )),
            },
            "mnemonic" => match value.parse::<Mnemonic>() {
                Ok(mnemonic) => settings.mnemonic = Some(mnemonic),
                Err(_) => bad("en or de"),
            },
            "scan time" => match parse_scan(&value) {
                Ok(ms) => settings.scan_ms = Some(ms),
                Err(_) => bad("a scan time from 1ms to 1s, such as 10ms"),
            },
            "safety" => match value.parse::<Safety>() {
                Ok(safety) => settings.safety = Some(safety),
                Err(_) => bad("none, all, or some of edge, precheck, plausibility, watchdog"),
            },
            "modes" => match value.parse::<Modes>() {
                Ok(modes) => settings.modes = Some(modes),
                Err(_) => bad("none, all, or some of continuous, stop, estop, reset"),
            },
            // The rows that list outputs or inputs by name: read as a list
            // here, checked against the table once it is read.
            other if super::halt::Row::from_label(other).is_some() => {
                let row = super::halt::Row::from_label(other).expect("matched");
                if lower != "none" {
                    settings.named.insert(
                        row,
                        super::halt::NamedList::parse(&value, grid.location(value_cell.pos)),
                    );
                }
            }
            "home order" if lower == "default" => {}
            "home order" => match Modes::parse_home_order(&value) {
                Ok(order) => settings.home_order = Some(order),
                Err(_) => bad("stages of actuators such as C3&C4, C2, C1"),
            },
            _ => {}
        }
    }
    report_unknown_labels(grid, &label_cols, stroke_header.as_ref(), diags);
    if let Some(columns) = stroke_header {
        read_actuator_rows(grid, &columns, &read_elsewhere, &mut settings, diags);
    }
    settings.with_board_target()
}

/// The columns of the actuator table headed at `header`; a header cell
/// that is none of them is named, since its column would not be read.
fn actuator_columns(grid: &Grid, header: CellPos, diags: &mut Diagnostics) -> ActuatorColumns {
    let mut columns = ActuatorColumns {
        header,
        extend: None,
        retract: None,
        valve: None,
        load: None,
    };
    for cell in grid
        .cells
        .iter()
        .filter(|c| c.pos.row == header.row && c.pos.col > header.col)
    {
        let label = label_of(&cell.value).unwrap_or_default();
        let slot = match label.as_str() {
            "extend" => &mut columns.extend,
            "retract" => &mut columns.retract,
            "valve" => &mut columns.valve,
            "load" => &mut columns.load,
            _ => {
                diags.warning(
                    Code::W003Ignored,
                    grid.location(cell.pos),
                    format!(
                        "{} heads no column steptable reads (expected {}); its column was not read",
                        cell.value.describe(),
                        COLUMNS.join(", ")
                    ),
                );
                continue;
            }
        };
        slot.get_or_insert(cell.pos.col);
    }
    columns
}

/// The rows of the actuator table: from the header down to the first row
/// with nothing in the table's columns. A row whose first cell is no
/// actuator (`C2`, `C2 (clamp)`) is an error when it holds values, which
/// would otherwise be lost.
fn read_actuator_rows(
    grid: &Grid,
    columns: &ActuatorColumns,
    read_elsewhere: &[CellPos],
    settings: &mut Given,
    diags: &mut Diagnostics,
) {
    let header = columns.header;
    let value_cols: Vec<u32> = [columns.extend, columns.retract, columns.valve, columns.load]
        .into_iter()
        .flatten()
        .collect();
    // Every headed column counts, so a value under a header we do not read is named.
    let last_col = grid
        .cells
        .iter()
        .filter(|c| c.pos.row == header.row)
        .map(|c| c.pos.col)
        .max()
        .unwrap_or(header.col);
    let in_table = |c: &&GridCell| (header.col..=last_col).contains(&c.pos.col);
    let mut row = header.row + 1;
    loop {
        let cells: Vec<&GridCell> = grid
            .cells
            .iter()
            .filter(|c| c.pos.row == row)
            .filter(in_table)
            .collect();
        if cells.is_empty() {
            break;
        }
        // Right of the last headed column, on a row of the table: a value
        // that would otherwise be lost.
        for cell in grid.cells.iter().filter(|c| {
            c.pos.row == row && c.pos.col > last_col && !read_elsewhere.contains(&c.pos)
        }) {
            diags.warning(
                Code::W003Ignored,
                grid.location(cell.pos),
                format!(
                    "{} is right of the actuator table, in a column without a header (expected {}); it was not read",
                    cell.value.describe(),
                    COLUMNS.join(", ")
                ),
            );
        }
        row += 1;
        let at = |col: u32| cells.iter().copied().find(|c| c.pos.col == col);
        let values: Vec<&GridCell> = cells
            .iter()
            .copied()
            .filter(|c| c.pos.col != header.col)
            .collect();
        let Some(name_cell) = at(header.col) else {
            diags.error(
                Code::E030BadSetting,
                grid.location(values[0].pos),
                "this row of the actuator table names no actuator in its first column; write C1, C2, … there".to_string(),
            );
            continue;
        };
        let name = text_of(&name_cell.value);
        let Some(actuator) = crate::cell::actuator_name(&name) else {
            if values.is_empty() && !crate::cell::looks_like_move(&name) {
                // A note under the table ends it.
                diags.warning(
                    Code::W003Ignored,
                    grid.location(name_cell.pos),
                    format!(
                        "{} is not an actuator; the actuator table ends above it",
                        name_cell.value.describe()
                    ),
                );
                break;
            }
            diags.error(
                Code::E030BadSetting,
                grid.location(name_cell.pos),
                format!(
                    "\"{name}\" is not an actuator (expected C1 to C{}, optionally with a comment: C1 (clamp)); the row's values were not read",
                    crate::cell::MAX_ACTUATOR
                ),
            );
            continue;
        };
        for cell in &values {
            if !value_cols.contains(&cell.pos.col) {
                diags.warning(
                    Code::W003Ignored,
                    grid.location(cell.pos),
                    format!(
                        "{} of C{actuator} is in a column without a header (expected {}); it was not read",
                        cell.value.describe(),
                        COLUMNS.join(", ")
                    ),
                );
            }
        }
        read_actuator_row(grid, actuator, columns, &at, settings, diags);
    }
}

fn read_actuator_row<'g>(
    grid: &Grid,
    actuator: u32,
    columns: &ActuatorColumns,
    at: &dyn Fn(u32) -> Option<&'g GridCell>,
    settings: &mut Given,
    diags: &mut Diagnostics,
) {
    if let Some(cell) = columns.valve.and_then(at)
        && let Some(text) = value_text(grid, cell, diags)
    {
        match text.parse::<ValveType>() {
            Ok(valve) => {
                settings.valves.insert(actuator, valve);
            }
            // The parser's message says what was probably meant.
            Err(why) => diags.error(
                Code::E030BadSetting,
                grid.location(cell.pos),
                format!("valve of C{actuator}: {why}"),
            ),
        }
    }
    if let Some(cell) = columns.load.and_then(at)
        && let Some(text) = value_text(grid, cell, diags)
    {
        match crate::valve::parse_load(&text) {
            Some(load) => {
                settings.loads.insert(actuator, load);
            }
            None => diags.error(
                Code::E030BadSetting,
                grid.location(cell.pos),
                format!("load of C{actuator}: \"{text}\" is not a drift in stroke per second from 0 to 10, such as 0.05"),
            ),
        }
    }
    let mut time = |col: Option<u32>| -> Option<u32> {
        let cell = col.and_then(at)?;
        let text = value_text(grid, cell, diags)?;
        let ms = parse_duration_ms(&text);
        if ms.is_none() {
            diags.error(
                Code::E030BadSetting,
                grid.location(cell.pos),
                format!(
                    "stroke time of C{actuator}: \"{text}\" is not a time such as 1.5s or 800ms"
                ),
            );
        }
        ms
    };
    let (extend, retract) = (time(columns.extend), time(columns.retract));
    if extend.is_none() && retract.is_none() {
        return;
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

/// `scan-time`, `Safty`, `homeorder`: a label within two letters of one
/// steptable knows.
fn resembles_a_label(label: &str) -> bool {
    let letters = |t: &str| -> Vec<char> { t.chars().filter(|c| c.is_alphabetic()).collect() };
    let label = letters(label);
    LABELS
        .iter()
        .chain(["actuator"].iter())
        .any(|known| edit_distance(&label, &letters(known)) <= 2)
}

/// Levenshtein distance, for the few short labels above.
fn edit_distance(a: &[char], b: &[char]) -> usize {
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.iter().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let above = row[j + 1];
            row[j + 1] = (diagonal + usize::from(ca != cb))
                .min(row[j] + 1)
                .min(above + 1);
            diagonal = above;
        }
    }
    row[b.len()]
}

/// A label with a value beside it, in the column of the known labels or
/// spelt like one, that is no setting (`scan-time`, `safty`): its row would
/// be ignored.
fn report_unknown_labels(
    grid: &Grid,
    label_cols: &[u32],
    actuators: Option<&ActuatorColumns>,
    diags: &mut Diagnostics,
) {
    let actuator_rows = actuators.map(|a| a.header.row);
    for cell in &grid.cells {
        if actuator_rows.is_some_and(|r| cell.pos.row >= r) {
            continue;
        }
        let Some(label) = label_of(&cell.value) else {
            continue;
        };
        if !label_cols.contains(&cell.pos.col) && !resembles_a_label(&label) {
            continue;
        }
        let has_value = grid
            .cells
            .iter()
            .any(|c| c.pos.row == cell.pos.row && c.pos.col == cell.pos.col + 1);
        if !has_value
            || LABELS.contains(&label.as_str())
            || matches!(label.as_str(), "setting" | "settings")
        {
            continue;
        }
        diags.warning(
            Code::W003Ignored,
            grid.location(cell.pos),
            format!(
                "{} is not a setting steptable knows ({}); its row was not read",
                cell.value.describe(),
                LABELS.join(", ")
            ),
        );
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(rows: &[&[&str]]) -> Grid {
        Grid::from_text_rows("t.xlsx", Some("SETTINGS"), rows)
    }

    /// Deleting a letter costs one, as does each letter of a label left
    /// over: a near-miss of a label is told from a word that merely shares
    /// its start (two cargo mutants survivors made deletions free).
    #[test]
    fn the_edit_distance_counts_every_deleted_letter() {
        let d = |a: &str, b: &str| {
            edit_distance(
                &a.chars().collect::<Vec<_>>(),
                &b.chars().collect::<Vec<_>>(),
            )
        };
        assert_eq!(d("ab", ""), 2);
        assert_eq!(d("abc", "a"), 2);
        assert_eq!(d("safety", "safty"), 1);
        assert_eq!(d("scantime", "scan"), 4);
        assert_eq!(d("", "abc"), 3);
        assert!(resembles_a_label("safty"));
        assert!(!resembles_a_label("scanner"));
    }

    #[test]
    fn cells_right_of_the_actuator_table_are_named_and_labels_beside_it_read() {
        let mut diags = Diagnostics::new();
        let s = parse(
            &grid(&[
                &["actuator", "extend", "retract", "valve", "load"],
                &["C1", "1s", "1s", "53closed", "0.2", "", "oops"],
                &["C2", "2s", "1s", "", "", "", "scan time", "20ms"],
            ]),
            &mut diags,
        );
        assert_eq!(s.loads.get(&1), Some(&0.2));
        assert_eq!(s.valves.get(&1), Some(&ValveType::Closed53));
        assert_eq!(s.scan_ms, Some(20));
        let found = diags.into_sorted();
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(found[0].message.contains("oops"), "{found:?}");
        assert_eq!(found[0].location.cell, Some(CellPos::new(1, 6)));
    }

    #[test]
    fn labels_within_two_letters_of_a_known_one_are_named_others_left_alone() {
        let mut diags = Diagnostics::new();
        parse(
            &grid(&[
                &["scan-tme", "20ms"],
                &["Safty", "all"],
                &["home ordr", "C1"],
                &["comment", "hello"],
                &["owner", "me"],
                &["zzzzzzzz", "x"],
            ]),
            &mut diags,
        );
        let found = diags.into_sorted();
        let cells: Vec<_> = found.iter().map(|d| d.location.cell).collect();
        assert_eq!(
            cells,
            [
                Some(CellPos::new(0, 0)),
                Some(CellPos::new(1, 0)),
                Some(CellPos::new(2, 0))
            ],
            "{found:?}"
        );
    }

    #[test]
    fn an_unknown_label_in_the_column_of_the_known_ones_is_named() {
        let mut diags = Diagnostics::new();
        parse(
            &grid(&[
                &["target", "festo"],
                &["comment", "hello"],
                &["note"],
                &["x", "", "owner", "me"],
            ]),
            &mut diags,
        );
        let found = diags.into_sorted();
        let cells: Vec<_> = found.iter().map(|d| d.location.cell).collect();
        assert_eq!(cells, [Some(CellPos::new(1, 0))], "{found:?}");
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

    #[test]
    fn nothing_meant_for_steptable_is_dropped_silently() {
        let mut diags = Diagnostics::new();
        let s = parse(
            &grid(&[
                &["scan-time", "20ms"],
                &["safety", "all"],
                &[],
                &["actuator", "extend", "retract", "valve", "remark"],
                &["C1 (clamp)", "5s", "5s", "52mono", "old valve"],
                &["", "2s", "1s"],
                &["C2x", "1s", "1s"],
                &["C3", "1s", "1s"],
                &[],
                &["C4", "1s"],
            ]),
            &mut diags,
        );
        let all: Vec<String> = diags.into_sorted().iter().map(|d| d.to_string()).collect();
        assert_eq!(s.valves.get(&1), Some(&ValveType::Mono52), "{all:?}");
        assert_eq!(s.strokes[&1].extend_ms, 5000);
        assert_eq!(
            s.strokes[&3].extend_ms, 1000,
            "rows after a bad one are still read"
        );
        assert!(!s.strokes.contains_key(&4), "the table ends at a blank row");
        let expected = [
            "SETTINGS!A1: warning[W003]: \"scan-time\" is not a setting",
            "SETTINGS!E4: warning[W003]: \"remark\" heads no column",
            "SETTINGS!E5: warning[W003]: \"old valve\" of C1",
            "SETTINGS!B6: error[E030]: this row of the actuator table names no actuator",
            "SETTINGS!A7: error[E030]: \"C2x\" is not an actuator",
        ];
        assert_eq!(all.len(), expected.len(), "{all:#?}");
        for (got, want) in all.iter().zip(expected) {
            assert!(got.contains(want), "{got}\n{want}");
        }
    }
}
