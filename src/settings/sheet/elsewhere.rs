//! Settings written where they are not read: with the step table (on its
//! sheet, or in a CSV file), or on a workbook's sheet of another name.

use super::headers::column_word;
use super::{COLUMNS, known_label, label_of, text_of, unread, valid_value};
use crate::diag::{CellPos, Code, Diagnostics};
use crate::read::{CellValue, Grid, GridCell};

const CSV_HOLDS_NO_SETTINGS: &str = "a CSV file holds the step table only: write them on a workbook's SETTINGS sheet (`steptable template` writes one), or give them on the command line where an option does";

/// Settings written with the step table (on its sheet, or in a CSV), where
/// settings are not read: a label with a valid value right of it on its
/// row is E030, a misspelt label with one E046, a label and a valid value
/// in one cell E046 (as on SETTINGS). A label whose neighbour is no value
/// of it (`Target | 30 parts/min`, `Model | DSNU-16`) is a note.
pub fn written_with_table(table: &Grid, diags: &mut Diagnostics) {
    let instead = match table.sheet {
        Some(_) => "move them to the SETTINGS sheet",
        None => CSV_HOLDS_NO_SETTINGS,
    };
    // Where the value of one setting goes, as the sheet or file allows.
    let value_right_of = |label: &str| match table.sheet {
        Some(_) => {
            format!("move it to the SETTINGS sheet, with its value in the cell right of {label}")
        }
        None => CSV_HOLDS_NO_SETTINGS.replace("them", "it"),
    };
    let lost = "where settings are not read (the program would be made without it)";
    if let Some((header, row)) = actuator_table(table) {
        diags.error(
            Code::E030BadSetting,
            table.location(header),
            format!("an actuator table (headed here, its first row at {}) lies with the step table, {lost}: the valves, stroke times, loads or names it gives would be lost; {instead}", table.cell_name(row)),
        );
        // Its rows up to a blank one, in its columns steptable reads: the
        // error is of them all (a column of notes is said as ever).
        let rows = table_rows(table, header);
        let read: std::collections::HashSet<u32> = (table.cells.iter())
            .filter(|c| c.pos.row == header.row)
            .filter(|c| label_of(&c.value).is_some_and(|l| COLUMNS.contains(&column_word(&l))))
            .map(|c| c.pos.col)
            .chain([header.col])
            .collect();
        for cell in table.cells.iter().filter(|c| rows.contains(&c.pos.row)) {
            if read.contains(&cell.pos.col) {
                diags.speaks_for(table.location(cell.pos));
            }
        }
    }
    for (i, cell) in table.cells.iter().enumerate() {
        let CellValue::Text(text) = &cell.value else {
            continue;
        };
        let at = table.location(cell.pos);
        let written = text.trim();
        // `scantime: 0,02s` unquoted in a comma file: the decimal comma
        // split the value into the next field, and neither half reads as a
        // setting alone.
        if let Some(split) = split_by_comma(table, i) {
            let (meant, joined, next) = split;
            diags.error(
                Code::E046MistypedSetting,
                at,
                format!("\"{written}\" and the fields right of it read as \"{joined}\", the setting `{meant}` and its value split by the file's comma (quote the cell, or write the value with a point), lying with the step table, {lost}; {}", value_right_of(&format!("\"{meant}\""))),
            );
            // The fields between it and the last are part of it.
            let row = table.cells.iter().filter(|c| c.pos.row == next.row);
            for c in row.filter(|c| c.pos.col > cell.pos.col && c.pos.col <= next.col) {
                diags.speaks_for(table.location(c.pos));
            }
            continue;
        }
        if let Some((meant, value)) = unread::setting_in_text(text) {
            if valid_value(meant, value, cell, table) {
                diags.error(
                    Code::E046MistypedSetting,
                    at,
                    format!("\"{written}\" holds the setting {meant} and its value in one cell, lying with the step table, {lost}; {}", value_right_of(&format!("\"{meant}\""))),
                );
            }
            continue;
        }
        let misspelt = unread::misspelt_setting_in_text(text)
            .into_iter()
            .find(|(meant, value)| valid_value(meant, value, cell, table));
        if let Some((meant, _)) = misspelt {
            diags.error(
                Code::E046MistypedSetting,
                at,
                format!("\"{written}\" reads as the setting `{meant}` misspelt, with its value in one cell, lying with the step table, {lost}; spell it `{meant}` and {}", value_right_of("it")),
            );
            continue;
        }
        // The cells are in row-major order: the next one right of it is
        // the next filled cell, when that is on its row.
        let Some(value_cell) = table.cells.get(i + 1).filter(|c| c.pos.row == cell.pos.row) else {
            continue;
        };
        let value = text_of(&value_cell.value);
        let label = label_of(&cell.value).unwrap_or_default();
        if let Some(known) = known_label(&cell.value) {
            if valid_value(known, &value, value_cell, table) {
                diags.error(
                    Code::E030BadSetting,
                    at,
                    format!("\"{written}\" and its value name a setting, but they lie with the step table, {lost}; {instead}"),
                );
                diags.speaks_for(table.location(value_cell.pos));
            }
        } else if let Some(meant) = unread::mistyped_label(&label)
            && valid_value(meant, &value, value_cell, table)
        {
            diags.error(
                Code::E046MistypedSetting,
                at,
                format!("\"{written}\" and its value read as the setting `{meant}` misspelt, lying with the step table, {lost}; spell it `{meant}`; {instead}"),
            );
            diags.speaks_for(table.location(value_cell.pos));
        }
    }
}

/// The setting a CSV's cell `i` and the fields right of it make once the
/// comma between two of them is taken for a decimal comma (`scantime: 0` |
/// `02s`, or `scan time` | `0` | `02s`), when they do not read as one
/// without it: its label, the text joined, and the last field's place.
fn split_by_comma(table: &Grid, i: usize) -> Option<(&'static str, String, CellPos)> {
    if table.sheet.is_some() {
        return None;
    }
    let cell = &table.cells[i];
    // The field right of `at`, when it is the next one on the row.
    let right_of = |at: usize| {
        let (this, next) = (&table.cells[at], table.cells.get(at + 1)?);
        let adjacent = next.pos.row == this.pos.row && next.pos.col == this.pos.col + 1;
        adjacent.then_some(next)
    };
    let text = |c: &GridCell| match &c.value {
        CellValue::Text(t) => Some(t.trim().to_string()),
        _ => None,
    };
    // Only a value whose digits the comma parted (`0,02s`, `1,5s`).
    let parted = |left: &str, right: &str| {
        left.ends_with(|c: char| c.is_ascii_digit())
            && right.starts_with(|c: char| c.is_ascii_digit())
    };
    let next = right_of(i)?;
    let (first, second) = (text(cell)?, text(next)?);
    if parted(&first, &second) {
        // Read with a decimal point too: in a list (`supervision`) a comma
        // also parts items.
        for point in [',', '.'] {
            let joined = format!("{first}{point}{second}");
            let as_written = unread::setting_in_text(&joined)
                .into_iter()
                .chain(unread::misspelt_setting_in_text(&joined));
            let meant = as_written
                .filter(|(meant, value)| valid_value(meant, value, cell, table))
                .map(|(meant, _)| meant);
            if let Some(meant) = meant.into_iter().next() {
                return Some((meant, format!("{first},{second}"), next.pos));
            }
        }
    }
    // `scan time` | `0` | `02s`: the label in a field of its own.
    let last = right_of(i + 1)?;
    let third = text(last)?;
    if !parted(&second, &third) {
        return None;
    }
    let label = known_label(&cell.value)
        .or_else(|| unread::mistyped_label(&label_of(&cell.value).unwrap_or_default()))?;
    let valid = [',', '.']
        .iter()
        .any(|point| valid_value(label, &format!("{second}{point}{third}"), next, table));
    valid.then(|| (label, format!("{first},{second},{third}"), last.pos))
}

/// Settings written on a workbook's sheet of another name (`Config`,
/// `PARAMETERS`), found as [`written_with_table`] finds them: one W015 per
/// sheet, at the first, since only the sheet named SETTINGS is read for
/// them. A warning, not an error: such a sheet may be a legend of example
/// rows, and the table is read as written.
pub fn written_elsewhere(others: &[Grid], has_settings: bool, diags: &mut Diagnostics) {
    let advice = match has_settings {
        true => "move the rows to the SETTINGS sheet",
        false => "rename the sheet SETTINGS, or move the rows there,",
    };
    for grid in others {
        // An actuator table there is found as with the step table.
        let mut found = Diagnostics::new();
        written_with_table(grid, &mut found);
        let Some(first) = found.iter().next() else {
            continue;
        };
        let sheet = grid.sheet.clone().unwrap_or_default();
        let cell = first.location.cell.map(CellPos::a1).unwrap_or_default();
        let count = found.iter().count();
        let which = match count {
            1 => format!("a setting with its value at {cell}"),
            n => format!("{n} settings with their values, the first at {cell}"),
        };
        diags.warning(
            Code::W015SettingsElsewhere,
            first.location.clone(),
            format!("the sheet \"{sheet}\" holds what reads as {which}, but settings are read from the sheet named SETTINGS only: not read, the program is made without them; {advice} if they are meant"),
        );
    }
}

/// The rows of the actuator table headed at `header`: its own and those
/// below whose first cell is filled, up to a blank one.
fn table_rows(grid: &Grid, header: CellPos) -> std::ops::Range<u32> {
    let filled: std::collections::HashSet<CellPos> = grid
        .cells
        .iter()
        .filter(|c| !text_of(&c.value).trim().is_empty())
        .map(|c| c.pos)
        .collect();
    let end = (header.row + 1..)
        .find(|row| !filled.contains(&CellPos::new(*row, header.col)))
        .unwrap_or(header.row + 1);
    header.row..end
}

/// An actuator table on a sheet where it is not read: a header whose
/// first word is `actuator` with a column's header right of it, over a row
/// naming an actuator with a value in one of those columns. The header's
/// cell and that row's first cell.
fn actuator_table(grid: &Grid) -> Option<(CellPos, CellPos)> {
    let heads_a_table = |value: &CellValue| {
        label_of(value).is_some_and(|label| {
            let first = label.split(|c: char| !c.is_alphanumeric()).next();
            matches!(first, Some("actuator" | "actuators"))
        })
    };
    // Nearly every step table has no such header: no index built for it.
    if !grid.cells.iter().any(|c| heads_a_table(&c.value)) {
        return None;
    }
    // Look-ups by place, so that a sheet of many cells is looked over in
    // time that grows with them.
    let values: std::collections::HashMap<CellPos, &CellValue> =
        grid.cells.iter().map(|c| (c.pos, &c.value)).collect();
    let texts: std::collections::HashMap<CellPos, String> =
        values.iter().map(|(pos, v)| (*pos, text_of(v))).collect();
    let mut rows: std::collections::BTreeMap<u32, Vec<u32>> = std::collections::BTreeMap::new();
    for pos in texts.keys() {
        rows.entry(pos.row).or_default().push(pos.col);
    }
    grid.cells.iter().find_map(|cell| {
        if !heads_a_table(&cell.value) {
            return None;
        }
        let header = cell.pos;
        let columns: Vec<u32> = rows[&header.row]
            .iter()
            .copied()
            .filter(|col| *col > header.col)
            .filter(|col| {
                values
                    .get(&CellPos::new(header.row, *col))
                    .and_then(|v| label_of(v))
                    .is_some_and(|l| COLUMNS.contains(&column_word(&l)))
            })
            .collect();
        if columns.is_empty() {
            return None;
        }
        // The next rows, up to a blank one: the first naming an actuator
        // with a value in one of those columns.
        (header.row + 1..header.row.saturating_add(50))
            .map(|row| CellPos::new(row, header.col))
            .take_while(|pos| texts.contains_key(pos))
            .find(|pos| {
                crate::cell::actuator_name(&texts[pos]).is_some()
                    && columns.iter().any(|col| {
                        texts
                            .get(&CellPos::new(pos.row, *col))
                            .is_some_and(|t| !t.trim().is_empty())
                    })
            })
            .map(|row| (header, row))
    })
}
