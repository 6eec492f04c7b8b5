//! The cells of the SETTINGS sheet nothing read: each is named (W003, or
//! E030 where a value would be lost), with the label it was probably
//! meant as.

use std::collections::{BTreeMap, BTreeSet};

use super::{LABELS, Layout, Reader, label_of, setting_in_one_cell, text_of, valid_value};
use crate::cell::edit_distance;
use crate::diag::Diagnostics;
use crate::read::{CellValue, GridCell};

/// Names every filled cell not read so far. Above the first setting (not
/// on the row just above it) a row of one cell is the sheet's title or a
/// note, named only when it holds a setting and its value in one cell or
/// is spelt like a label; a one-cell row right above an actuator table's
/// header is its caption.
pub(super) fn name_the_rest(
    reader: &mut Reader,
    layout: &Layout,
    label_rows: &BTreeMap<u32, &'static str>,
    diags: &mut Diagnostics,
) {
    let first_row = label_rows
        .keys()
        .chain(&layout.header_rows)
        .copied()
        .chain(layout.tables.iter().map(|t| t.header.row))
        .min();
    let captions: BTreeSet<u32> = layout
        .tables
        .iter()
        .filter_map(|t| t.header.row.checked_sub(1))
        .collect();
    let rows: Vec<u32> = reader.rows.keys().copied().collect();
    for row in rows {
        let cells: Vec<&GridCell> = reader.row(row).collect();
        let lone_text = cells.len() == 1 && matches!(cells[0].value, CellValue::Text(_));
        let note = lone_text
            && (captions.contains(&row) || first_row.is_some_and(|first| row + 1 < first));
        for cell in &cells {
            if reader.seen.contains(&cell.pos) || reader.uncomputed(cell, diags) {
                continue;
            }
            let word = label_of(&cell.value).unwrap_or_default();
            if let Some((label, rest)) = setting_in_one_cell(&cell.value) {
                let right = cells.iter().find(|c| c.pos.col > cell.pos.col);
                match one_cell_setting(label, rest, cell, right.copied(), reader.grid) {
                    Some(message) => {
                        reader.mistyped(cell.pos, message, diags);
                        if right.is_some() {
                            reader.seen.extend(cells.iter().map(|c| c.pos));
                        }
                    }
                    None => reader.warn(
                        cell.pos,
                        format!(
                            "{} reads as a note: it starts with the setting {label}, but \"{rest}\" is no value of it; it was not read (to give the setting, write the label `{label}` alone and its value right of it)",
                            cell.value.describe()
                        ),
                        diags,
                    ),
                }
                continue;
            }
            let misspelt = match &cell.value {
                CellValue::Text(text) => misspelt_setting_in_text(text)
                    .into_iter()
                    .find(|(meant, value)| valid_value(meant, value, cell, reader.grid)),
                _ => None,
            };
            if let Some((meant, _)) = misspelt {
                reader.mistyped(
                    cell.pos,
                    format!(
                        "{} reads as the setting `{meant}` misspelt, with its value in one cell; spell it `{meant}` and write the value in the cell right of it (it was not read, so the program would lack the setting)",
                        cell.value.describe()
                    ),
                    diags,
                );
                continue;
            }
            if note && closest_label(&word).is_none() {
                // The sheet's title and notes, the table's caption.
                continue;
            }
            match unread_cell(&layout.table_rows, cell, &cells, label_rows) {
                Unread::Row(message) => {
                    reader.seen.extend(cells.iter().map(|c| c.pos));
                    reader.warn(cell.pos, message, diags);
                }
                Unread::Lost(message) => {
                    reader.seen.extend(cells.iter().map(|c| c.pos));
                    reader.error(cell.pos, message, diags);
                }
                Unread::Mistyped(message) => {
                    reader.seen.extend(cells.iter().map(|c| c.pos));
                    reader.mistyped(cell.pos, message, diags);
                }
                Unread::Ignored(message) => reader.warn(cell.pos, message, diags),
            }
        }
    }
}

/// What is said of a cell nothing read.
enum Unread {
    /// Values that would be lost (E030): a row of the actuator table
    /// outside it.
    Lost(String),
    /// W003 for a whole row: an unknown label with its values.
    Row(String),
    /// E046: a known label misspelt, with its values: the setting would be
    /// lost and the program written without it.
    Mistyped(String),
    /// W003: a value beside a setting's, any other cell.
    Ignored(String),
}

fn unread_cell(
    table_rows: &BTreeSet<u32>,
    cell: &GridCell,
    row: &[&GridCell],
    label_rows: &BTreeMap<u32, &'static str>,
) -> Unread {
    let describe = cell.value.describe();
    let first_on_row = row.first().is_some_and(|c| c.pos == cell.pos);
    let text = text_of(&cell.value);
    if first_on_row && row.len() > 1 && crate::cell::actuator_name(&text).is_some() {
        let table = if table_rows
            .first()
            .is_some_and(|first| *first < cell.pos.row)
        {
            "it is below the end of the actuator table (a label, a note or another table ends it)"
        } else {
            "no actuator | extend | retract header is above it"
        };
        return Unread::Lost(format!(
            "{describe} reads as a row of the actuator table, but {table}; its values were not read"
        ));
    }
    if let Some(label) = label_rows.get(&cell.pos.row) {
        return Unread::Ignored(format!(
            "{describe} is beside the setting {label}, in a column steptable does not read (notes go under a WHAT IT MEANS header); it was not read"
        ));
    }
    let word = label_of(&cell.value).unwrap_or_default();
    if first_on_row
        && row.len() > 1
        && let Some(known) = mistyped_label(&word)
    {
        return Unread::Mistyped(format!(
            "{describe} is not a setting steptable knows: did you mean `{known}`? Its row was not read, so the program would lack the setting; spell the label as the reference does"
        ));
    }
    let closest = label_of(&cell.value)
        .and_then(|label| closest_label(&label))
        .map(|known| format!(" (did you mean {known}?)"))
        .unwrap_or_default();
    if first_on_row && row.len() > 1 && !closest.is_empty() {
        return Unread::Row(format!(
            "{describe} is not a setting steptable knows{closest} ({}); its row was not read",
            LABELS.join(", ")
        ));
    }
    Unread::Ignored(format!(
        "{describe} is not a setting steptable knows{closest}, a setting's value or a row of the actuator table; it was not read"
    ))
}

/// E046's message for a SETTINGS cell that starts with the setting `label`
/// followed by `rest` (`modes: step`), with `right` the next cell on its
/// row; `None` for a note (`Target: 30 parts/min`, `Safety: wear
/// goggles`). A valid value is a setting written in one cell; so is a
/// value of one word (`target: codesys3`), an attempt at one. A label
/// with more words (`safety checks | all`) is one when the value right of
/// it is valid.
fn one_cell_setting(
    label: &'static str,
    rest: &str,
    cell: &GridCell,
    right: Option<&GridCell>,
    grid: &crate::read::Grid,
) -> Option<String> {
    let describe = cell.value.describe();
    if let Some(value_cell) = right {
        let value = text_of(&value_cell.value);
        return valid_value(label, &value, value_cell, grid).then(|| format!(
            "{describe} starts with the setting {label} but has more words after it: write the label `{label}` alone, its value right of it (the row was not read)"
        ));
    }
    let valid = valid_value(label, rest, cell, grid);
    // `target: codesys3`: one word meant as a value, misspelt (not a
    // number or a placeholder: `Target: 30`, `Modes: n/a` are notes).
    let word = rest.trim();
    let one_word = !word.contains(char::is_whitespace)
        && word.starts_with(char::is_alphabetic)
        && !super::headers::placeholder(word);
    // `modes: estop, required by CE`, `modes: stop and estp`, `target:
    // siemens S7-1500`: a value with a note or a typo beside it, where
    // values come from a closed list.
    let a_value_among = super::CLOSED_VALUES.contains(&label)
        && word
            .split(|c: char| c.is_whitespace() || matches!(c, ',' | ';' | '&' | '(' | ')'))
            .filter(|t| !t.is_empty() && !t.eq_ignore_ascii_case("and"))
            .any(|t| valid_value(label, t, cell, grid));
    let invalid = match valid {
        true => String::new(),
        false => format!(
            ", and \"{rest}\" is not a valid value of it ({})",
            super::value_problem(label, rest, cell, grid).unwrap_or_default()
        ),
    };
    (valid || one_word || a_value_among).then(|| format!(
        "{describe} holds the setting {label} and its value in one cell{invalid}; write the value in the cell right of \"{label}\" (it was not read)"
    ))
}

/// `scan-time`, `Safty`, `homeorder`: the label steptable knows within two
/// letters of `label`, the closest.
pub(super) fn closest_label(label: &str) -> Option<&'static str> {
    LABELS
        .into_iter()
        .chain(["actuator"])
        .map(|known| (edit_distance(&letters(label), &letters(known)), known))
        .min()
        .filter(|(distance, _)| *distance <= 2)
        .map(|(_, known)| known)
}

fn letters(text: &str) -> String {
    text.chars().filter(|c| c.is_alphabetic()).collect()
}

/// `mode`, `hold safe`, `on-halt`, `supervison`: a label steptable knows,
/// misspelt — the same letters, or one letter off (two in a label of eight
/// letters or more). Looser likenesses (`notes` and `modes`) are only
/// named ([`closest_label`]): a note row must not stop a conversion.
pub(super) fn mistyped_label(label: &str) -> Option<&'static str> {
    let word = letters(label).to_lowercase();
    if word.is_empty() {
        return None;
    }
    // The command line's name of a setting (`--scan`).
    if word == "scan" {
        return Some("scan time");
    }
    let length = word.chars().count();
    LABELS
        .into_iter()
        .filter_map(|known| {
            let known_letters = letters(known);
            let known_length = known_letters.chars().count();
            let allowed = if known_length >= 8 { 2 } else { 1 };
            // Lengths further apart than that are never close enough: every
            // move cell of a table is asked, so skip the distance there.
            if known_length.abs_diff(length) > allowed {
                return None;
            }
            let distance = edit_distance(&word, &known_letters);
            (distance <= allowed).then_some((distance, allowed, known))
        })
        .min()
        .map(|(_, _, known)| known)
}

/// A text that may hold a misspelt label and its value together (`mode:
/// all`, `scantime 20ms`): each reading of its first one to three words as
/// a label misspelt ([`mistyped_label`]), with the rest as the value. The
/// caller keeps a reading only with a valid value, so that a note (`Model:
/// DSNU-16`) stays one.
pub(super) fn misspelt_setting_in_text(text: &str) -> Vec<(&'static str, &str)> {
    let text = text.trim();
    let separator = separates_value;
    let mut readings = Vec::new();
    let mut words = 0;
    for (at, c) in text.char_indices() {
        let starts_word = !separator(c) && text[..at].ends_with(separator);
        if !starts_word || at == 0 {
            continue;
        }
        words += 1;
        if words > 3 {
            break;
        }
        let (label, value) = text.split_at(at);
        if let Some(meant) = mistyped_label(label.trim_end_matches(separator)) {
            readings.push((meant, value.trim()));
        }
    }
    readings
}

/// What people write between a label and its value in one cell: `:`,
/// `=`, a dash (`mode - all`, `safety — watchdog`) or space.
pub(super) fn separates_value(c: char) -> bool {
    matches!(c, ':' | '=' | '-' | '–' | '—') || c.is_whitespace()
}

/// A text that holds a setting's label and its value together (`target:
/// iec`, `scan time = 20ms`, `safety — watchdog`): the label it starts
/// with, and the rest.
pub(super) fn setting_in_text(text: &str) -> Option<(&'static str, &str)> {
    let text = text.trim();
    let lower = text.to_ascii_lowercase();
    LABELS.into_iter().find_map(|label| {
        let rest = lower.strip_prefix(label)?;
        let value = text[label.len()..].trim_start_matches(separates_value);
        (rest.starts_with(separates_value) && !value.trim().is_empty())
            .then_some((label, value.trim()))
    })
}
