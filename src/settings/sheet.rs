//! The SETTINGS sheet of a workbook: target, mnemonics, scan time, safety
//! checks and stroke times per actuator, next to the table they belong to.
//! Command-line flags override it; an invalid value is an error naming its cell.
//!
//! Layout: a label in any cell (`target`, `mnemonic`, `scan time`, `safety`)
//! with its value in the next filled cell to the right; and a small table
//! headed `actuator | extend | retract` with rows such as `C2 | 1.5s | 0.8s`.
//! A header row `SETTING | VALUE | WHAT IT MEANS` (the template's) makes the
//! column under a notes header (`what it means`, `notes`, `comment`, …) the
//! labels' notes.
//!
//! Every filled cell is read or named: a setting given twice is E030 at the
//! second, naming the first; a cell beside a setting, a row of the actuator
//! table outside it, an unknown label are named (W003, or E030 where values
//! would be lost). Only the sheet's title and notes above the first setting
//! (and the actuator table's one-cell caption right above its header) are
//! left alone.

mod actuators;
mod elsewhere;
mod headers;
mod unread;

use std::collections::{BTreeMap, BTreeSet};

use super::Given;
use crate::address::{Mnemonic, Target};
use crate::diag::{CellPos, Code, Diagnostics, or_list};
use crate::program::{Modes, Safety};
use crate::read::{CellValue, Grid, GridCell};
use crate::stroke::parse_scan;
use actuators::{actuator_columns, read_actuator_rows, said_without_unit};
pub use elsewhere::{written_elsewhere, written_with_table};
use unread::name_the_rest;

/// Where the actuator table's columns are: its header cell and the columns
/// of extend and retract times, and of the optional valve and load.
struct ActuatorColumns {
    header: CellPos,
    extend: Option<u32>,
    retract: Option<u32>,
    valve: Option<u32>,
    load: Option<u32>,
    /// The engineer's names (the template's `name` column), beside or
    /// instead of `C1 (clamp)` in the first column.
    name: Option<u32>,
    /// The last column with a header (read or named) on the header row.
    last_col: u32,
}

/// The labels of the settings, as written on the sheet (with the reader:
/// the table stage knows them too, to say a setting written beside a table).
pub use crate::sheets::SETTING_LABELS as LABELS;

/// The columns an actuator table may have, after `actuator`.
const COLUMNS: [&str; 5] = ["extend", "retract", "valve", "load", "name"];

/// Headers of a column of notes beside the settings (the template's `WHAT
/// IT MEANS`): its cells on the labels' rows are the engineer's, not read.
const NOTE_HEADERS: [&str; 9] = [
    "what it means",
    "meaning",
    "note",
    "notes",
    "comment",
    "comments",
    "remark",
    "remarks",
    "description",
];

/// The words of a settings header row besides the notes headers.
const TITLE_WORDS: [&str; 3] = ["setting", "settings", "value"];

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

/// The known label a cell holds (`Target:` is `target`).
fn known_label(value: &CellValue) -> Option<&'static str> {
    let label = label_of(value)?;
    LABELS.into_iter().find(|known| *known == label)
}

/// A cell that holds a label and its value together (`target: iec`,
/// `scan time = 20ms`): the label it starts with, and the rest.
fn setting_in_one_cell(value: &CellValue) -> Option<(&'static str, &str)> {
    match value {
        CellValue::Text(text) => unread::setting_in_text(text),
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

/// The sheet as it is read: its filled cells, and which of them have been
/// read or named so far (every other one is named at the end).
struct Reader<'g> {
    grid: &'g Grid,
    /// The filled cells, row by row (text of only white space is empty).
    cells: Vec<&'g GridCell>,
    /// The same, by row: every look-up is within a row, so that a sheet
    /// of many cells is read in time that grows with them, not their square.
    rows: BTreeMap<u32, Vec<&'g GridCell>>,
    seen: BTreeSet<CellPos>,
    /// The actuator table's headers refused with E046 (row, column): the
    /// values under them are part of that error.
    refused_headers: BTreeSet<(u32, u32)>,
    settings: Given,
}

impl<'g> Reader<'g> {
    fn new(grid: &'g Grid) -> Self {
        let cells: Vec<&GridCell> = grid
            .cells
            .iter()
            .filter(|c| !matches!(&c.value, CellValue::Text(t) if t.trim().is_empty()))
            .collect();
        let mut rows: BTreeMap<u32, Vec<&GridCell>> = BTreeMap::new();
        for cell in &cells {
            rows.entry(cell.pos.row).or_default().push(cell);
        }
        Reader {
            grid,
            cells,
            rows,
            seen: BTreeSet::new(),
            refused_headers: BTreeSet::new(),
            settings: Given::default(),
        }
    }

    fn row(&self, row: u32) -> impl Iterator<Item = &'g GridCell> + '_ {
        self.rows.get(&row).into_iter().flatten().copied()
    }

    fn at(&self, pos: CellPos) -> Option<&'g GridCell> {
        self.row(pos.row).find(|c| c.pos == pos)
    }

    /// The next filled cell right of `pos` on its row.
    fn right_of(&self, pos: CellPos) -> Option<&'g GridCell> {
        self.row(pos.row)
            .filter(|c| c.pos.col > pos.col)
            .min_by_key(|c| c.pos.col)
    }

    fn warn(&mut self, pos: CellPos, message: String, diags: &mut Diagnostics) {
        self.seen.insert(pos);
        diags.warning(Code::W003Ignored, self.grid.location(pos), message);
    }

    /// E046: a setting misspelt or written with its value in one cell.
    fn mistyped(&mut self, pos: CellPos, message: String, diags: &mut Diagnostics) {
        self.seen.insert(pos);
        diags.error(Code::E046MistypedSetting, self.grid.location(pos), message);
    }

    /// E016 for a formula never computed where a label or a header was
    /// looked for: what it holds cannot be told (a setting's label, an
    /// actuator table's column), and the program would lack it.
    fn uncomputed(&mut self, cell: &GridCell, diags: &mut Diagnostics) -> bool {
        let CellValue::Uncomputed(formula) = &cell.value else {
            return false;
        };
        self.seen.insert(cell.pos);
        diags.error(
            Code::E016FormulaNotComputed,
            self.grid.location(cell.pos),
            format!(
                "the formula {formula} has no computed value, so steptable cannot tell which setting, column or value it holds (the program would be written without it); open and save the workbook in Excel or LibreOffice, or type it"
            ),
        );
        true
    }

    fn error(&mut self, pos: CellPos, message: String, diags: &mut Diagnostics) {
        self.seen.insert(pos);
        diags.error(Code::E030BadSetting, self.grid.location(pos), message);
    }
}

/// What the structure of the sheet is, found before its values are read.
struct Layout {
    /// The columns under a notes header.
    notes: BTreeSet<u32>,
    /// Rows of `SETTING | VALUE | …` headers.
    header_rows: BTreeSet<u32>,
    /// The actuator tables, by header.
    tables: Vec<ActuatorColumns>,
    /// The rows of their headers.
    table_rows: BTreeSet<u32>,
}

/// Reads the settings sheet. Problems go to `diags` with their cells; every
/// filled cell is read or named.
pub fn parse(grid: &Grid, diags: &mut Diagnostics) -> Given {
    let mut reader = Reader::new(grid);
    let mut layout = settings_headers(&mut reader, diags);
    let headers: Vec<CellPos> = reader
        .cells
        .iter()
        .filter(|c| actuator_header(&reader, c))
        .map(|c| c.pos)
        .collect();
    for header in headers {
        layout.table_rows.insert(header.row);
        layout
            .tables
            .push(actuator_columns(&mut reader, header, diags));
    }
    let label_rows = read_labels(&mut reader, &layout, diags);
    let mut first_rows: BTreeMap<u32, CellPos> = BTreeMap::new();
    for columns in &layout.tables {
        read_actuator_rows(&mut reader, columns, &layout, &mut first_rows, diags);
    }
    name_the_rest(&mut reader, &layout, &label_rows, diags);
    reader.settings.with_board_target()
}

/// The rows `SETTING | VALUE | WHAT IT MEANS`: the columns under a notes
/// header hold the labels' notes; any other header is named.
fn settings_headers(reader: &mut Reader, diags: &mut Diagnostics) -> Layout {
    let mut layout = Layout {
        notes: BTreeSet::new(),
        header_rows: BTreeSet::new(),
        tables: Vec::new(),
        table_rows: BTreeSet::new(),
    };
    let rows: BTreeSet<u32> = reader
        .cells
        .iter()
        .filter(|c| label_of(&c.value).as_deref() == Some("value"))
        .filter(|value| {
            reader.row(value.pos.row).any(|c| {
                c.pos.col < value.pos.col
                    && matches!(label_of(&c.value).as_deref(), Some("setting" | "settings"))
            })
        })
        .map(|c| c.pos.row)
        .collect();
    for row in &rows {
        let cells: Vec<&GridCell> = reader.row(*row).collect();
        // Each of SETTING and VALUE heads one column.
        let mut headed: Vec<String> = Vec::new();
        for cell in cells {
            let label = label_of(&cell.value).unwrap_or_default();
            let word = label.trim_end_matches('s').to_string();
            if NOTE_HEADERS.contains(&label.as_str()) {
                layout.notes.insert(cell.pos.col);
                reader.seen.insert(cell.pos);
            } else if TITLE_WORDS.contains(&label.as_str()) && !headed.contains(&word) {
                headed.push(word);
                reader.seen.insert(cell.pos);
            } else {
                reader.warn(
                    cell.pos,
                    format!(
                        "{} heads no column steptable reads (expected SETTING, VALUE, and a column of notes headed {}); its column was not read",
                        cell.value.describe(),
                        or_list(&NOTE_HEADERS.map(str::to_uppercase))
                    ),
                    diags,
                );
            }
        }
    }
    layout.header_rows = rows;
    layout
}

/// Whether `cell` heads an actuator table: `actuator`, or a longer header
/// that starts with it (`Actuator (cylinder)`, `Actuators`) beside a
/// column's header (`extend`) on its row — a note alone is no table.
fn actuator_header(reader: &Reader, cell: &GridCell) -> bool {
    let Some(label) = label_of(&cell.value) else {
        return false;
    };
    if label == "actuator" {
        return true;
    }
    let first = label
        .split(|c: char| !c.is_alphanumeric())
        .next()
        .unwrap_or("");
    matches!(first, "actuator" | "actuators")
        && reader.row(cell.pos.row).any(|c| {
            c.pos.col > cell.pos.col
                && label_of(&c.value).is_some_and(|l| COLUMNS.contains(&headers::column_word(&l)))
        })
}

/// Reads every labelled setting; returns the rows that hold a label, each
/// with its first. A label given twice is E030 at the second.
fn read_labels(
    reader: &mut Reader,
    layout: &Layout,
    diags: &mut Diagnostics,
) -> BTreeMap<u32, &'static str> {
    let grid = reader.grid;
    let mut label_rows: BTreeMap<u32, &'static str> = BTreeMap::new();
    let mut first: BTreeMap<&'static str, CellPos> = BTreeMap::new();
    let labels: Vec<(&GridCell, &'static str)> = reader
        .cells
        .iter()
        .filter_map(|c| known_label(&c.value).map(|l| (*c, l)))
        .collect();
    for (cell, label) in labels {
        reader.seen.insert(cell.pos);
        label_rows.entry(cell.pos.row).or_insert(label);
        // The notes beside a label are the engineer's.
        let notes: Vec<CellPos> = reader
            .row(cell.pos.row)
            .filter(|c| layout.notes.contains(&c.pos.col))
            .map(|c| c.pos)
            .collect();
        reader.seen.extend(notes);
        // A label with nothing but a note or another label beside it
        // gives nothing (the value left blank): said, so that a value
        // typed in the wrong column is not lost without a word.
        let Some(value_cell) = reader.right_of(cell.pos).filter(|v| {
            !layout.notes.contains(&v.pos.col)
                && known_label(&v.value).is_none()
                && label_of(&v.value).as_deref() != Some("actuator")
        }) else {
            match value_in_notes(reader, layout, cell.pos, label) {
                Some(note) => reader.error(
                    note.pos,
                    format!(
                        "{} reads as the value of {label}, but lies in the column of notes, where nothing is read, while the value's cell {} is empty (the program would be made without it); move it there",
                        note.value.describe(),
                        grid.cell_name(CellPos::new(cell.pos.row, cell.pos.col + 1)),
                    ),
                    diags,
                ),
                None => reader.warn(
                    cell.pos,
                    format!(
                        "{label} has no value in the cell right of it; nothing was read for it (write the value there)"
                    ),
                    diags,
                ),
            }
            continue;
        };
        reader.seen.insert(value_cell.pos);
        if let Some(earlier) = first.get(label) {
            reader.error(
                value_cell.pos,
                format!(
                    "{label} is given twice: here and at {}; remove one (this one was not read)",
                    grid.cell_name(*earlier)
                ),
                diags,
            );
            continue;
        }
        first.insert(label, value_cell.pos);
        let Some(value) = value_text(grid, value_cell, diags) else {
            continue;
        };
        let at = grid.location(value_cell.pos);
        reader.settings.cells.insert(label, at.clone());
        apply(&mut reader.settings, label, &value, value_cell, grid, diags);
    }
    label_rows
}

/// The note beside `label` (at `at`) that is a valid value of it: the
/// value typed one column too far right, into the notes.
fn value_in_notes<'g>(
    reader: &Reader<'g>,
    layout: &Layout,
    at: CellPos,
    label: &'static str,
) -> Option<&'g GridCell> {
    let note = reader
        .row(at.row)
        .find(|c| c.pos.col > at.col && layout.notes.contains(&c.pos.col))?;
    let text = match &note.value {
        CellValue::Text(t) => t.trim().to_string(),
        CellValue::Number(n) => format!("{n}"),
        _ => return None,
    };
    // Only where values come from a closed list: a note on a row that takes
    // names (`hold-safe | | gripper keeps part`) would read as a value too.
    // `none` and `default` change nothing.
    let closed = CLOSED_VALUES.contains(&label);
    let neutral = matches!(text.to_ascii_lowercase().as_str(), "none" | "default");
    (closed && !neutral && valid_value(label, &text, note, reader.grid)).then_some(note)
}

/// The settings whose values come from a closed list of words, so that a
/// note is not mistaken for one.
const CLOSED_VALUES: [&str; 7] = [
    "target",
    "board",
    "mnemonic",
    "designations",
    "modes",
    "safety",
    "scan time",
];

/// Whether `value` is a valid value of the setting `label`, as written or
/// in the dress a note gives it (`(all)`, `"all"`, `all.`, `20ms (PLC)`,
/// `watchdog; edge`): where settings are not read, a value so dressed
/// would be lost all the same.
fn valid_value(label: &'static str, value: &str, cell: &GridCell, grid: &Grid) -> bool {
    let valid =
        |value: &str| !value.trim().is_empty() && value_problem(label, value, cell, grid).is_none();
    valid(value) || undressed(value).is_some_and(|v| valid(&v))
}

/// Why `value` is not a valid value of the setting `label` (E030's
/// message, without the label), or `None` when it is one.
fn value_problem(label: &'static str, value: &str, cell: &GridCell, grid: &Grid) -> Option<String> {
    let mut scratch = Diagnostics::new();
    apply(
        &mut Given::default(),
        label,
        value,
        cell,
        grid,
        &mut scratch,
    );
    scratch
        .iter()
        .find(|d| d.severity == crate::diag::Severity::Error)
        .map(|d| {
            d.message
                .trim_start_matches(label)
                .trim_start_matches(": ")
                .to_string()
        })
}

/// `value` without the dress of a note: trailing `.`, `;` or `,`, a
/// wrapping pair of brackets or quotes, a trailing remark in brackets, and
/// `;` between items for `,`. `None` when there is none.
fn undressed(value: &str) -> Option<String> {
    let mut v = value.trim().trim_end_matches(['.', ';', ',']).trim();
    for (open, close) in [('(', ')'), ('[', ']'), ('"', '"'), ('\'', '\''), ('“', '”')] {
        if let Some(inner) = v.strip_prefix(open).and_then(|v| v.strip_suffix(close)) {
            v = inner.trim();
        }
    }
    if let Some((before, _)) = v.split_once(" (").filter(|(_, rest)| rest.ends_with(')')) {
        v = before.trim();
    }
    // `step and manual`, `step & manual`: a list written as words.
    let v = v
        .replace(';', ",")
        .replace(" and ", ", ")
        .replace(" & ", ", ");
    (v != value.trim()).then_some(v)
}

/// The value of one labelled setting, into `settings`; E030 when it is
/// not valid.
fn apply(
    settings: &mut Given,
    label: &'static str,
    value: &str,
    value_cell: &GridCell,
    grid: &Grid,
    diags: &mut Diagnostics,
) {
    let at = grid.location(value_cell.pos);
    let lower = value.to_ascii_lowercase();
    let mut said = |message: String| {
        diags.error(
            Code::E030BadSetting,
            at.clone(),
            format!("{label}: {message}"),
        );
    };
    let mut bad =
        |expected: String| said(format!("\"{value}\" is not valid (expected {expected})"));
    match label {
        // `default`: festo, or iec when a board is named (the
        // template's own value, so that its board list never
        // conflicts with its target).
        "target" if lower == "default" => {}
        "target" => match value.parse::<Target>() {
            Ok(target) => settings.target = Some(target),
            Err(_) => {
                let mut names = vec!["default"];
                names.extend(Target::NAMES);
                bad(or_list(&names))
            }
        },
        "board" if lower == "none" => {}
        "board" => match value.parse::<crate::address::Board>() {
            Ok(board) => settings.board = Some(board),
            Err(_) => bad(format!(
                "none or one of {}",
                crate::address::BOARDS.map(|b| b.name).join(", ")
            )),
        },
        "mnemonic" => match value.parse::<Mnemonic>() {
            Ok(mnemonic) => settings.mnemonic = Some(mnemonic),
            Err(_) => bad(or_list(&Mnemonic::names())),
        },
        "designations" => match value.parse::<crate::symbols::Scheme>() {
            Ok(scheme) => settings.designations = Some(scheme),
            Err(_) => bad(or_list(&crate::symbols::Scheme::ALL.map(|s| s.name()))),
        },
        "scan time" => match parse_scan(value) {
            Ok(ms) => {
                said_without_unit(grid, value_cell, value, diags);
                settings.scan_ms = Some(ms)
            }
            Err(_) if crate::cell::thousands_comma(value) => {
                said(crate::cell::thousands_comma_words(value))
            }
            Err(_) => bad("a scan time from 1ms to 1s, such as 10ms".to_string()),
        },
        // The parsers say which item is wrong (unknown, twice, empty).
        "safety" => match value.parse::<Safety>() {
            Ok(safety) => settings.safety = Some(safety),
            Err(why) => said(why),
        },
        "modes" => match value.parse::<Modes>() {
            Ok(modes) => settings.modes = Some(modes),
            Err(why) => said(why),
        },
        "supervision" if lower == "none" => {}
        "supervision" => match crate::program::parse_supervision(value) {
            Ok(times) => settings.supervision = Some(times),
            Err(why) => said(why),
        },
        "home order" if lower == "default" => {}
        "home order" => match Modes::parse_home_order(value) {
            Ok(order) => settings.home_order = Some(order),
            Err(why) => said(why),
        },
        // The rows that list outputs or inputs by name: read as a list
        // here, checked against the table once it is read.
        other => {
            if let Some(row) = super::halt::Row::from_label(other)
                && lower != "none"
            {
                settings
                    .named
                    .insert(row, super::halt::NamedList::parse(value, at.clone()));
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::unread::closest_label;
    use super::*;
    use crate::actuator::ActuatorKind;
    use crate::cell::edit_distance;
    use crate::stroke::Stroke;

    fn grid(rows: &[&[&str]]) -> Grid {
        Grid::from_text_rows("t.xlsx", Some("SETTINGS"), rows)
    }

    /// Deleting a letter costs one, as does each letter of a label left
    /// over: a near-miss of a label is told from a word that merely shares
    /// its start (two cargo mutants survivors made deletions free).
    #[test]
    fn the_edit_distance_counts_every_deleted_letter() {
        let d = edit_distance;
        assert_eq!(d("ab", ""), 2);
        assert_eq!(d("abc", "a"), 2);
        assert_eq!(d("safety", "safty"), 1);
        assert_eq!(d("scantime", "scan"), 4);
        assert_eq!(d("", "abc"), 3);
        assert_eq!(closest_label("safty"), Some("safety"));
        assert_eq!(closest_label("scanner"), None);
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
        assert_eq!(s.valves.get(&1), Some(&ActuatorKind::Closed53));
        assert_eq!(s.scan_ms, Some(20));
        let found = diags.into_sorted();
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(found[0].message.contains("oops"), "{found:?}");
        assert_eq!(found[0].location.cell, Some(CellPos::new(1, 6)));
    }

    /// On a sheet without a single known setting, every label with a value
    /// is named, the closest known one offered when it is spelt like one.
    #[test]
    fn unknown_labels_are_named_with_the_closest_known_one() {
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
        let cells: Vec<String> = found
            .iter()
            .map(|d| d.location.cell.unwrap().a1())
            .collect();
        // A label spelt like a known one is named once for its row (E046:
        // the setting would be lost); other words and their values each.
        assert_eq!(
            cells,
            ["A1", "A2", "A3", "A4", "B4", "A5", "B5", "A6", "B6"],
            "{found:?}"
        );
        assert!(
            found[0].message.contains("did you mean `scan time`?")
                && found[0].code == Code::E046MistypedSetting,
            "{found:?}"
        );
        assert!(
            found[1].message.contains("did you mean `safety`?"),
            "{found:?}"
        );
        assert!(!found[3].message.contains("did you mean"), "{found:?}");
    }

    /// Below the first setting nothing is a note: an unknown label, a lone
    /// word, a row of cells are each named (the row once, at its first cell).
    #[test]
    fn every_cell_below_the_first_setting_is_read_or_named() {
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
        let cells: Vec<String> = found
            .iter()
            .map(|d| d.location.cell.unwrap().a1())
            .collect();
        assert_eq!(cells, ["A2", "B2", "A3", "A4", "C4", "D4"], "{found:?}");
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
        assert_eq!(s.valves.get(&1), Some(&ActuatorKind::Mono52), "{all:?}");
        assert_eq!(s.strokes[&1].extend_ms, 5000);
        assert_eq!(
            s.strokes[&3].extend_ms, 1000,
            "rows after a bad one are still read"
        );
        assert_eq!(
            s.strokes[&4].extend_ms, 1000,
            "a blank row does not end the table"
        );
        let expected = [
            "SETTINGS!A1: error[E046]: \"scan-time\" is not a setting",
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

    fn cells_and_messages(diags: Diagnostics) -> Vec<(String, String)> {
        diags
            .into_sorted()
            .iter()
            .map(|d| {
                (
                    format!("{} {}", d.code.as_str(), d.location.cell.unwrap().a1()),
                    d.message.clone(),
                )
            })
            .collect()
    }

    /// A setting given twice is E030 at the second, naming the first, and
    /// the first is the one read: a label twice, an actuator twice (in the
    /// table, or in a second table), a column header twice.
    #[test]
    fn a_setting_given_twice_is_an_error_naming_both_cells() {
        let mut diags = Diagnostics::new();
        let s = parse(
            &grid(&[
                &["target", "iec"],
                &["target", "siemens"],
                &["actuator", "extend", "retract", "valve", "valve"],
                &["C1", "1s", "1s", "52mono"],
                &["C1 (clamp)", "2s", "2s", "52bi"],
                &["C2"],
                &["C2", "3s"],
            ]),
            &mut diags,
        );
        assert_eq!(s.target, Some(Target::Iec));
        assert_eq!(s.valves.get(&1), Some(&ActuatorKind::Mono52));
        assert_eq!(s.strokes[&2].extend_ms, 3000, "a name alone gives nothing");
        let found = cells_and_messages(diags);
        let codes: Vec<&str> = found.iter().map(|(c, _)| c.as_str()).collect();
        assert_eq!(
            codes,
            // C2 alone (A6) is the template's row: it says nothing, so
            // C2 below it is no repetition.
            ["E030 B2", "E030 E3", "E030 A5"],
            "{found:#?}"
        );
        assert!(found[0].1.contains("target is given twice: here and at B1"));
        assert!(found[1].1.contains("two valve columns"));
        assert!(
            found[2]
                .1
                .contains("C1 is given twice in the actuator table: here and at A4")
        );
    }

    /// The template's layout: `SETTING | VALUE | | WHAT IT MEANS`, notes in
    /// the last column, a caption above the actuator table; nothing named.
    /// A value in a column no header reads is named.
    #[test]
    fn notes_under_a_notes_header_are_the_engineers_and_other_cells_named() {
        let mut diags = Diagnostics::new();
        let s = parse(
            &grid(&[
                &["SETTINGS"],
                &["Used by steptable convert for this workbook."],
                &[],
                &["SETTING", "VALUE", "", "WHAT IT MEANS"],
                &["target", "default", "", "Address style"],
                &["board", "rpi", "", "The board"],
                &["mnemonic", "", "", "Operand letters"],
                &[],
                &["Stroke times per actuator."],
                &["actuator", "extend", "retract", "valve"],
                &["C1", "1s", "1s"],
            ]),
            &mut diags,
        );
        assert_eq!(s.target, Some(Target::Iec), "the board decides");
        assert_eq!(s.mnemonic, None, "a blank value gives nothing");
        let found = cells_and_messages(diags);
        assert_eq!(found.len(), 1, "{found:#?}");
        assert_eq!(found[0].0, "W003 A7", "only the blank value is said");
        let mut diags = Diagnostics::new();
        parse(
            &grid(&[
                &["target", "iec", "oops"],
                &["scan time: 20ms"],
                &["mnemonic", "de", "", "", "far right"],
            ]),
            &mut diags,
        );
        let found = cells_and_messages(diags);
        let codes: Vec<&str> = found.iter().map(|(c, _)| c.as_str()).collect();
        // The setting and its value in one cell would be lost: E046.
        assert_eq!(codes, ["W003 C1", "E046 A2", "W003 E3"], "{found:#?}");
        assert!(found[0].1.contains("beside the setting target"));
        assert!(
            found[1]
                .1
                .contains("holds the setting scan time and its value in one cell")
        );
    }

    /// An actuator row outside the actuator table — with no header above
    /// it, or below a note that ends the table — would lose its values:
    /// E030. A blank row does not end the table.
    #[test]
    fn an_actuator_row_outside_the_table_is_an_error() {
        let mut diags = Diagnostics::new();
        let s = parse(
            &grid(&[
                &["C9", "2s", "2s"],
                &["safety", "all"],
                &[],
                &["actuator", "extend", "retract"],
                &["C1", "1s", "1s"],
                &[],
                &["C2", "2s", "2s"],
                &["spare cylinders:"],
                &["C3", "3s", "3s"],
            ]),
            &mut diags,
        );
        assert_eq!(s.strokes[&2].extend_ms, 2000);
        assert!(!s.strokes.contains_key(&3) && !s.strokes.contains_key(&9));
        let found = cells_and_messages(diags);
        let codes: Vec<&str> = found.iter().map(|(c, _)| c.as_str()).collect();
        assert_eq!(codes, ["E030 A1", "W003 A8", "E030 A9"], "{found:#?}");
        assert!(
            found[0]
                .1
                .contains("no actuator | extend | retract header is above it")
        );
        assert!(found[2].1.contains("below the end of the actuator table"));
    }

    /// A sheet of many cells is read in time that grows with them: 50,000
    /// rows of actuators, of actuator tables, of settings with a stray
    /// beside them (each look-up is within a row, and the next row of a
    /// table is found in the index, not by scanning). Read whole for every
    /// table or every row, the tables alone took 80 s for 100,000.
    #[test]
    fn a_sheet_of_many_cells_is_read_in_linear_time() {
        for row in [
            ["C1", "1s", "1s"],
            ["actuator", "x", ""],
            ["target", "iec", "oops"],
        ] {
            let mut rows: Vec<[&str; 3]> = vec![["actuator", "extend", "retract"]];
            rows.extend(std::iter::repeat_n(row, 50_000));
            let grid = grid(&rows.iter().map(|r| &r[..]).collect::<Vec<_>>());
            let start = std::time::Instant::now();
            parse(&grid, &mut Diagnostics::new());
            assert!(
                start.elapsed().as_secs() < 10,
                "{row:?}: {:?}",
                start.elapsed()
            );
        }
    }
}
