//! The actuator tables of the SETTINGS sheet (`actuator | extend |
//! retract | valve | load`): their columns, their rows, and each row's
//! valve, load and stroke times.

use std::collections::BTreeMap;

use super::headers::{column_word, header_unit, unread_header};
use super::{ActuatorColumns, COLUMNS, Layout, Reader, known_label, label_of, text_of, value_text};
use crate::actuator::ActuatorKind;
use crate::diag::{CellPos, Code, Diagnostics};
use crate::read::{CellValue, Grid, GridCell};
use crate::settings::Given;
use crate::stroke::{Stroke, parse_duration_ms};

/// The columns of the actuator table headed at `header`; a header cell
/// that is none of them is named, since its column would not be read.
pub(super) fn actuator_columns(
    reader: &mut Reader,
    header: CellPos,
    diags: &mut Diagnostics,
) -> ActuatorColumns {
    let mut columns = ActuatorColumns {
        header,
        extend: None,
        retract: None,
        valve: None,
        load: None,
        name: None,
        last_col: header.col,
    };
    reader.seen.insert(header);
    let cells: Vec<&GridCell> = reader
        .row(header.row)
        .filter(|c| c.pos.col > header.col)
        .collect();
    for cell in cells {
        // A label beside the table is a setting of its own.
        if known_label(&cell.value).is_some() {
            break;
        }
        columns.last_col = cell.pos.col;
        let label = label_of(&cell.value).unwrap_or_default();
        let slot = match column_word(&label) {
            "extend" => &mut columns.extend,
            "retract" => &mut columns.retract,
            "valve" => &mut columns.valve,
            "load" => &mut columns.load,
            "name" => &mut columns.name,
            _ if reader.uncomputed(cell, diags) => continue,
            _ => {
                unread_header(reader, cell, &label, header, diags);
                continue;
            }
        };
        if slot.is_some() {
            reader.error(
                cell.pos,
                format!(
                    "the actuator table has two {label} columns; remove one (this one was not read)"
                ),
                diags,
            );
            continue;
        }
        reader.seen.insert(cell.pos);
        *slot = Some(cell.pos.col);
    }
    columns
}

/// The rows of an actuator table: from the header down, blank rows
/// included, to a row that starts with a label, another table's header or
/// a note (named). A row whose first cell is no actuator (`C2`, `C2
/// (clamp)`) is an error when it holds values, which would otherwise be
/// lost; an actuator given twice (in any actuator table) is an error at
/// the second, naming the first.
pub(super) fn read_actuator_rows(
    reader: &mut Reader,
    columns: &ActuatorColumns,
    layout: &Layout,
    first_rows: &mut BTreeMap<u32, CellPos>,
    diags: &mut Diagnostics,
) {
    let grid = reader.grid;
    let header = columns.header;
    let value_cols: Vec<u32> = [
        columns.extend,
        columns.retract,
        columns.valve,
        columns.load,
        columns.name,
    ]
    .into_iter()
    .flatten()
    .collect();

    let in_table = |c: &GridCell| (header.col..=columns.last_col).contains(&c.pos.col);
    let mut rows_read = 0;
    let mut ended_by_note = false;
    // Row by row below the header, blank rows skipped (each next row found
    // in the index: a sheet of many tables is read in time).
    let mut row = header.row;
    while let Some(next) = reader.rows.range(row + 1..).next().map(|(r, _)| *r) {
        row = next;
        if layout.header_rows.contains(&row) || layout.table_rows.contains(&row) {
            break;
        }
        let cells: Vec<&GridCell> = reader
            .row(row)
            .filter(|c| in_table(c) && !reader.seen.contains(&c.pos))
            .collect();
        let name_cell = cells.iter().copied().find(|c| c.pos.col == header.col);
        // A label in the table's first column: the settings go on below.
        if reader
            .at(CellPos::new(row, header.col))
            .is_some_and(|c| known_label(&c.value).is_some())
        {
            break;
        }
        if cells.is_empty() {
            continue;
        }
        // Which actuator a formula never computed names cannot be told.
        if name_cell.is_some_and(|c| reader.uncomputed(c, diags)) {
            reader.seen.extend(cells.iter().map(|c| c.pos));
            continue;
        }
        rows_read += 1;
        // Right of the last headed column, on a row of the table: a value
        // that would otherwise be lost.
        let beyond: Vec<&GridCell> = reader
            .row(row)
            .filter(|c| c.pos.col > columns.last_col && !reader.seen.contains(&c.pos))
            .collect();
        for cell in beyond {
            let message = format!(
                "{} is right of the actuator table, in a column without a header (expected {})",
                cell.value.describe(),
                COLUMNS.join(", ")
            );
            headerless(reader, cell, message, diags);
        }
        let values: Vec<&GridCell> = cells
            .iter()
            .copied()
            .filter(|c| c.pos.col != header.col)
            .collect();
        // The template's name column, beside or instead of `C1 (clamp)`.
        let typed = columns
            .name
            .and_then(|col| cells.iter().copied().find(|c| c.pos.col == col));
        let start = row_actuator(reader, (name_cell, typed), &values, first_rows, diags);
        let actuator = match start {
            RowStart::Skip => continue,
            RowStart::Note => {
                ended_by_note = true;
                break;
            }
            RowStart::Actuator(actuator) => actuator,
        };
        for cell in values.iter().filter(|c| !value_cols.contains(&c.pos.col)) {
            unread_value(reader, cell, columns.header.row, actuator, diags);
        }
        let at = |col: u32| cells.iter().copied().find(|c| c.pos.col == col);
        read_actuator_row(grid, actuator, columns, &at, &mut reader.settings, diags);
    }
    // Only a note ended it: no row at all.
    if rows_read <= usize::from(ended_by_note) {
        reader.warn(
            header,
            "this actuator table has no row of an actuator with values below its header; nothing was read from it".to_string(),
            diags,
        );
    }
}

/// How a row of an actuator table starts.
enum RowStart {
    /// Not read (said why).
    Skip,
    /// A note under the table, which ends it.
    Note,
    Actuator(u32),
}

/// The actuator a row's first cell names: an error when it names none but
/// the row holds values, or names one given before; its engineer's name
/// (`C1 (clamp)`) is kept for every output.
fn row_actuator(
    reader: &mut Reader,
    (name_cell, typed): (Option<&GridCell>, Option<&GridCell>),
    values: &[&GridCell],
    first_rows: &mut BTreeMap<u32, CellPos>,
    diags: &mut Diagnostics,
) -> RowStart {
    let grid = reader.grid;
    let Some(name_cell) = name_cell else {
        reader.seen.extend(values.iter().map(|c| c.pos));
        reader.error(
            values[0].pos,
            "this row of the actuator table names no actuator in its first column; write C1, C2, … there".to_string(),
            diags,
        );
        return RowStart::Skip;
    };
    let name = text_of(&name_cell.value);
    let Some(actuator) = crate::cell::actuator_name(&name) else {
        if values.is_empty() && !crate::cell::looks_like_move(&name) {
            // A note under the table ends it.
            reader.warn(
                name_cell.pos,
                format!(
                    "{} is not an actuator; the actuator table ends above it",
                    name_cell.value.describe()
                ),
                diags,
            );
            return RowStart::Note;
        }
        reader.seen.extend(values.iter().map(|c| c.pos));
        // `C1 0`: a space splits its number.
        let split = match crate::cell::split_number(&name) {
            true => "a space splits its number; ",
            false => "",
        };
        reader.error(
            name_cell.pos,
            format!(
                "\"{name}\" is not an actuator ({split}expected C1 to C{}, optionally with a comment: C1 (clamp)); the row's values were not read",
                crate::cell::MAX_ACTUATOR
            ),
            diags,
        );
        return RowStart::Skip;
    };
    reader.seen.extend(values.iter().map(|c| c.pos));
    let comment = crate::cell::actuator_comment(&name);
    reader.seen.insert(name_cell.pos);
    // The template lists C1 to C8 with their cells empty: a row naming
    // only its actuator says "the defaults", which is what it gets. It
    // reads as nothing, so it may repeat or name an actuator the table
    // lacks without a word.
    if values.is_empty() && comment.is_none() {
        return RowStart::Skip;
    }
    if let Some(earlier) = first_rows.get(&actuator) {
        reader.error(
            name_cell.pos,
            format!(
                "C{actuator} is given twice in the actuator table: here and at {}; remove one (this row was not read)",
                grid.cell_name(*earlier)
            ),
            diags,
        );
        return RowStart::Skip;
    }
    first_rows.insert(actuator, name_cell.pos);
    // `C1 (clamp)` or the name column: the engineer's name of the
    // actuator, for every output (crate::symbols), even on a row with no
    // other value.
    if let Some(name) = actuator_name(grid, actuator, (name_cell, comment), typed, diags) {
        reader.settings.names.insert(actuator, name);
    }
    RowStart::Actuator(actuator)
}

/// The name of `actuator` from its first cell's comment (`C1 (clamp)`) or
/// its name column, with the cell it came from. Both given and different:
/// E030 at the name column's cell, and the first cell's name is kept.
fn actuator_name(
    grid: &Grid,
    actuator: u32,
    (first, comment): (&GridCell, Option<String>),
    typed: Option<&GridCell>,
    diags: &mut Diagnostics,
) -> Option<crate::symbols::ActuatorName> {
    let at = |cell: &GridCell| grid.location(cell.pos);
    let typed = typed
        .map(|cell| (cell, crate::cell::visible_text(&text_of(&cell.value))))
        .filter(|(_, text)| !text.trim().is_empty());
    match (comment, typed) {
        (Some(text), Some((cell, name))) if !text.trim().eq_ignore_ascii_case(name.trim()) => {
            diags.error(
                Code::E030BadSetting,
                at(cell),
                format!(
                    "C{actuator} is named \"{}\" in {} and \"{}\" here; keep one name (this one was not read)",
                    text.trim(),
                    grid.cell_name(first.pos),
                    name.trim()
                ),
            );
            Some(crate::symbols::ActuatorName {
                text,
                at: at(first),
            })
        }
        (Some(text), _) => Some(crate::symbols::ActuatorName {
            text,
            at: at(first),
        }),
        (None, Some((cell, name))) => Some(crate::symbols::ActuatorName {
            text: name.trim().to_string(),
            at: at(cell),
        }),
        (None, None) => None,
    }
}

/// The advice for a placeholder (`-`, `n/a`) in a cell of the actuator
/// table: an empty cell is what gives the default, and a `-` might as
/// well stand for a value to be filled in, so it is not read as one.
fn empty_for_default(text: &str) -> &'static str {
    match super::headers::placeholder(text) {
        true => "; leave the cell empty for the default",
        false => "",
    }
}

/// A time typed as text without a unit (`1000`, `0.02`) is read as
/// seconds, as a number cell is; typed as text, it may have meant
/// milliseconds: W007 at the cell, with both spellings.
pub(super) fn said_without_unit(grid: &Grid, cell: &GridCell, text: &str, diags: &mut Diagnostics) {
    let text = text.trim();
    if matches!(cell.value, CellValue::Text(_)) && crate::cell::without_unit(text) {
        diags.warning(
            Code::W007Assumed,
            grid.location(cell.pos),
            crate::cell::read_as_seconds(text),
        );
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
        match text.parse::<ActuatorKind>() {
            Ok(valve) => {
                settings.valves.insert(actuator, valve);
                (settings.actuator_cells).insert((actuator, "valve"), grid.location(cell.pos));
            }
            // The parser's message says what was probably meant.
            Err(why) => diags.error(
                Code::E030BadSetting,
                grid.location(cell.pos),
                format!("valve of C{actuator}: {why}{}", empty_for_default(&text)),
            ),
        }
    }
    if let Some(cell) = columns.load.and_then(at)
        && let Some(text) = value_text(grid, cell, diags)
    {
        match crate::actuator::parse_load(&text) {
            Some(load) => {
                settings.loads.insert(actuator, load);
                (settings.actuator_cells).insert((actuator, "load"), grid.location(cell.pos));
            }
            None => diags.error(
                Code::E030BadSetting,
                grid.location(cell.pos),
                format!("load of C{actuator}: \"{text}\" is not a drift in stroke per second from 0 to 10, such as 0.05{}", empty_for_default(&text)),
            ),
        }
    }
    // Only a cell that was read is recorded: one refused (E030) is not
    // "taken as given" afterwards (W007 of a kind's own time).
    let mut stroke_at = Vec::new();
    let mut time = |col: Option<u32>, what: &'static str| -> Option<u32> {
        let cell = col.and_then(at)?;
        let text = value_text(grid, cell, diags)?;
        // A unit in the column's header (`Extend time [ms]`) is the unit
        // of its bare numbers; a unit in the cell itself wins.
        let header_unit = header_unit(grid, CellPos::new(columns.header.row, col?));
        let bare = crate::cell::without_unit(&text);
        let read = match &header_unit {
            Some(Ok(unit)) if bare => format!("{}{unit}", text.trim()),
            // `[min]` over 1: neither 1 s nor a unit steptable reads.
            Some(Err(unit)) if bare => {
                diags.error(
                    Code::E030BadSetting,
                    grid.location(cell.pos),
                    format!("stroke time of C{actuator}: \"{text}\" stands under a header {unit}; write the unit in the cell, such as 1.5s or 800ms"),
                );
                return None;
            }
            _ => text.clone(),
        };
        let Some(ms) = parse_duration_ms(&read) else {
            let why = if crate::cell::thousands_comma(&text) {
                crate::cell::thousands_comma_words(&text)
            } else if let Some(ms) = time_in_ms(&read) {
                // `0.5ms`, `1,5` under `[ms]`: a time, but not one a
                // stroke can take.
                let unit = match read != text {
                    true => " (in the header's unit)",
                    false => "",
                };
                format!(
                    "\"{text}\"{unit} is {ms} ms, and a stroke time is whole milliseconds from 1ms to 3600s"
                )
            } else {
                format!(
                    "\"{text}\" is not a time such as 1.5s or 800ms{}",
                    empty_for_default(&text)
                )
            };
            diags.error(
                Code::E030BadSetting,
                grid.location(cell.pos),
                format!("stroke time of C{actuator}: {why}"),
            );
            return None;
        };
        if header_unit.is_none() {
            said_without_unit(grid, cell, &text, diags);
        }
        stroke_at.push((what, grid.location(cell.pos)));
        Some(ms)
    };
    let (extend, retract) = (
        time(columns.extend, "extend"),
        time(columns.retract, "retract"),
    );
    if extend.is_none() && retract.is_none() {
        return;
    }
    for (what, at) in stroke_at {
        settings.actuator_cells.insert((actuator, what), at);
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

/// A value of the actuator table in a column without a header: W003, or
/// E046 when it is what only a read column holds (`52mono`, `3s`): that
/// value would be lost, and the header it asks for is the engineer's to
/// write.
fn headerless(reader: &mut Reader, cell: &GridCell, message: String, diags: &mut Diagnostics) {
    match super::headers::value_kind(&text_of(&cell.value)) {
        Some(kind) => reader.mistyped(
            cell.pos,
            format!(
                "{message}, and it is {kind}; nothing is written, since the actuator would lose it"
            ),
            diags,
        ),
        None => reader.warn(cell.pos, format!("{message}; it was not read"), diags),
    }
}

/// The milliseconds a time written in s or ms (a decimal comma or point)
/// stands for, whatever its range: `0.5ms` is 0.5.
fn time_in_ms(text: &str) -> Option<f64> {
    if crate::cell::split_number(text) {
        return None;
    }
    let lower: String = text
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_lowercase()
        .replace(',', ".");
    let (number, scale) = match lower.strip_suffix("ms") {
        Some(n) => (n, 1.0),
        None => (lower.strip_suffix('s').unwrap_or(&lower), 1000.0),
    };
    let value: f64 = number.parse().ok()?;
    (value.is_finite() && number.chars().all(|c| c.is_ascii_digit() || c == '.'))
        .then_some(value * scale)
}

/// A value of C`actuator`'s row in a column nothing reads: under a header
/// naming none (W003), or under none at all ([`headerless`]).
fn unread_value(
    reader: &mut Reader,
    cell: &GridCell,
    header_row: u32,
    actuator: u32,
    diags: &mut Diagnostics,
) {
    let headed = reader.row(header_row).any(|c| c.pos.col == cell.pos.col);
    let message = |column: &str| {
        format!(
            "{} of C{actuator} is {column} (expected {})",
            cell.value.describe(),
            COLUMNS.join(", ")
        )
    };
    match headed {
        // Its header's E046 says what the column's values are: that is
        // their word, not a second one each.
        true if reader.refused_headers.contains(&(header_row, cell.pos.col)) => {
            reader.seen.insert(cell.pos);
        }
        true => {
            let column = message("in a column whose header names none steptable reads");
            reader.warn(cell.pos, format!("{column}; it was not read"), diags)
        }
        false => headerless(reader, cell, message("in a column without a header"), diags),
    }
}
