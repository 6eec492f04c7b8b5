//! The headers of an actuator table's columns: which column a header
//! names (`Extend time [ms]`, `valves`, `Extended`), its unit, and what is
//! said of one steptable does not read.

use super::{COLUMNS, Reader, label_of, text_of};
use crate::actuator::ActuatorKind;
use crate::diag::{CellPos, Diagnostics};
use crate::read::{Grid, GridCell};
use crate::stroke::parse_duration_ms;

/// A header of no column steptable reads: E046 where the values under it
/// would be lost (a column misspelt, named in another word or two named,
/// or values only a read column holds), else W003.
pub(super) fn unread_header(
    reader: &mut Reader,
    cell: &GridCell,
    label: &str,
    header: CellPos,
    diags: &mut Diagnostics,
) {
    // `vlave`, `extnd` over values: the column meant, misspelt.
    // Read as a note, the program would be written with the
    // default valve or stroke: an error, as a misspelt setting.
    let below = reader
        .grid
        .cells
        .iter()
        .any(|c| c.pos.col == cell.pos.col && c.pos.row > header.row);
    // `Extnd time [s]`: the first word misspelt, more after it.
    let first = label
        .split(|c: char| !c.is_alphanumeric())
        .next()
        .unwrap_or("");
    let meant = misspelt_column(label)
        .or_else(|| misspelt_column(first).filter(|_| !COLUMNS.contains(&first)));
    // Refused below (E046), the header speaks for the values under it.
    let refused = (header.row, cell.pos.col);
    if let Some(meant) = meant.filter(|_| below) {
        refuse_column(
            reader,
            refused,
            cell.pos,
            format!(
                "{} heads no column steptable reads: did you mean `{meant}`? (expected {}); nothing is written, since the actuators would lose what the column holds",
                cell.value.describe(),
                COLUMNS.join(", ")
            ),
            diags,
        );
        return;
    }
    // `stroke time extend`, `solenoid valve`, `Load on extend`:
    // a column named in another word than the first, or two
    // columns named. Which column is meant is the engineer's to
    // say; read as a note, its values would be lost.
    let named = columns_named(label);
    if below && !named.is_empty() {
        let which = match named.as_slice() {
            [one] => {
                format!("it names the column `{one}`, but not as its first word: head it `{one}`")
            }
            _ => format!(
                "it names the columns {}: head it with the one it holds",
                named
                    .iter()
                    .map(|c| format!("`{c}`"))
                    .collect::<Vec<_>>()
                    .join(" and ")
            ),
        };
        refuse_column(
            reader,
            refused,
            cell.pos,
            format!(
                "{} heads no column steptable reads: {which} (expected {}), or with a word naming none for a column of notes; nothing is written, since the actuators would lose what the column holds",
                cell.value.describe(),
                COLUMNS.join(", ")
            ),
            diags,
        );
        return;
    }
    // `Type` over `52mono`, `out` over `3s`: values only a
    // column steptable reads holds, under a header naming none.
    if let Some(meant) = column_of_values(reader, cell.pos) {
        refuse_column(
            reader,
            refused,
            cell.pos,
            format!(
                "{} heads no column steptable reads, but {meant}; nothing is written, since the actuators would lose them",
                cell.value.describe()
            ),
            diags,
        );
        return;
    }
    reader.warn(
        cell.pos,
        format!(
            "{} heads no column steptable reads (expected {}); its column was not read",
            cell.value.describe(),
            COLUMNS.join(", ")
        ),
        diags,
    );
}

/// The column a header names: its label, or its first word when that is a
/// column's and no other word is (`extend time`, `Valve type`, `load (kg)`:
/// an engineer's header says what the column holds).
pub(super) fn column_word(label: &str) -> &str {
    let mut words = label
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty());
    // A plural names the column too (`valves`, `names`).
    let column = |w: &str| COLUMNS.into_iter().find(|c| names_column(w, c));
    match words.next().and_then(&column) {
        Some(known) if !words.any(|w| column(w).is_some()) => known,
        _ => label,
    }
}

/// Whether `word` is the column's word, its plural or another form of it
/// (`extended`, `extending`, `extension`, `retraction`).
fn names_column(word: &str, column: &str) -> bool {
    let forms: &[&str] = match column {
        "extend" => &["extended", "extending", "extension"],
        "retract" => &["retracted", "retracting", "retraction"],
        _ => &[],
    };
    word == column || word.strip_suffix('s') == Some(column) || forms.contains(&word)
}

/// What the values under an unread header all are, when that is what a
/// column steptable reads holds: valve types, or times with a unit. The
/// cells right below it, to the first gap; the first that fits neither
/// ends the look (a sheet of many headers is read in linear time).
fn column_of_values(reader: &Reader, header: CellPos) -> Option<&'static str> {
    // The table's rows: each starts with an actuator's name (`C2`, `C2
    // (lift)`); the first that does not ends the look.
    let name_col = reader.row(header.row).next().map(|c| c.pos.col);
    let below = |row: u32| {
        let mut cells = reader.row(row);
        let first = cells.next()?;
        let names = Some(first.pos.col) == name_col
            && crate::cell::actuator_name(&text_of(&first.value)).is_some();
        names.then_some(())?;
        std::iter::once(first)
            .chain(cells)
            .find(|c| c.pos.col == header.col)
            .map(|c| text_of(&c.value))
    };
    let (mut times, mut any, mut placeholders) = (true, false, 0);
    // A bounded look: many headers stacked in one column are each looked
    // down from.
    for value in (header.row + 1..).map_while(below).take(100) {
        // `-`, `n/a`: an actuator without one, not a note. A column of
        // only those is no column of values.
        if placeholder(&value) {
            placeholders += 1;
            if placeholders > 16 {
                return None;
            }
            continue;
        }
        any = true;
        let kind = value_kind(&value);
        // One valve type is one valve lost (`52mono` beside `default`).
        if kind == Some(VALVE) {
            return Some(
                "a value under it is a valve type: head it `valve` (and empty any placeholder under it, `-`, `n/a`: an empty cell gives the default valve)",
            );
        }
        times &= kind == Some(TIME);
    }
    (any && times).then_some("every value under it is a time: head it `extend` or `retract`")
}

const VALVE: &str = "a valve type: head it `valve`";
const TIME: &str = "a time: head it `extend` or `retract`";

/// What a value only a column steptable reads holds is (a valve type, a
/// time with a unit), with the header it asks for.
pub(super) fn value_kind(value: &str) -> Option<&'static str> {
    if value.parse::<ActuatorKind>().is_ok() {
        Some(VALVE)
    } else if parse_duration_ms(value).is_some() && !crate::cell::without_unit(value) {
        Some(TIME)
    } else {
        None
    }
}

/// A cell written for "none" (`-`, `n/a`, `—`).
pub(super) fn placeholder(value: &str) -> bool {
    let value = value.trim().to_ascii_lowercase();
    matches!(
        value.as_str(),
        "-" | "—" | "–" | "n/a" | "na" | "none" | "tbd" | "tba" | "default"
    ) || !value.is_empty() && value.chars().all(|c| c == '?' || c == '-')
}

/// The unit a time column's header states (`Extend time [ms]`, `retract
/// (s)`, `extend in milliseconds`): `Ok("ms")` or `Ok("s")`; `Err` with
/// the words for a unit steptable does not read stroke times in (`[min]`,
/// `[us]`) or for two units (`(s or ms)`), whose bare numbers cannot be
/// read as either; `None` for a header that states none.
pub(super) fn header_unit(grid: &Grid, header: CellPos) -> Option<Result<&'static str, String>> {
    let cell = grid.cells.iter().find(|c| c.pos == header)?;
    let label = label_of(&cell.value)?;
    let (mut units, mut other) = (Vec::new(), Vec::new());
    for word in label.split(|c: char| !c.is_alphanumeric()) {
        match word {
            "ms" | "msec" | "millisecond" | "milliseconds" => units.push("ms"),
            "s" | "sec" | "secs" | "second" | "seconds" => units.push("s"),
            "min" | "mins" | "minute" | "minutes" | "h" | "hr" | "hrs" | "hour" | "hours"
            | "us" | "µs" | "microsecond" | "microseconds" | "ns" => other.push(word.to_string()),
            _ => {}
        }
    }
    units.dedup();
    match (units.as_slice(), other.first()) {
        (_, Some(word)) => Some(Err(format!(
            "in `{word}`, a unit steptable does not read a stroke time in"
        ))),
        ([], None) => None,
        ([unit], None) => Some(Ok(*unit)),
        _ => Some(Err("that names both s and ms".to_string())),
    }
}

/// The columns a header's words name, in the order of [`COLUMNS`]: a
/// column's word, its plural, `extension`/`retraction`, or one misspelt
/// (`extnd`) in a word of four letters or more.
fn columns_named(label: &str) -> Vec<&'static str> {
    let words: Vec<&str> = label
        .split(|c: char| !c.is_alphanumeric())
        .filter(|w| !w.is_empty())
        .collect();
    COLUMNS
        .into_iter()
        .filter(|column| {
            words.iter().any(|w| {
                names_column(w, column)
                    || (column.len() > 4 && w.starts_with(&column[..column.len() - 1]))
                    || (w.chars().count() >= 4 && misspelt_column(w) == Some(column))
            })
        })
        .collect()
}

/// The actuator table's column `label` misspells: one letter off, or the
/// same letters in another order (`vlave`).
fn misspelt_column(label: &str) -> Option<&'static str> {
    let sorted = |t: &str| {
        let mut letters: Vec<char> = t.chars().collect();
        letters.sort_unstable();
        letters
    };
    COLUMNS.iter().copied().find(|known| {
        crate::cell::edit_distance(label, known) == 1 || sorted(label) == sorted(known)
    })
}

/// E046 at the header `refused` (its row and column) of a column whose
/// values would be lost: the header speaks for the values under it, which
/// get no W003 of their own.
fn refuse_column(
    reader: &mut Reader,
    refused: (u32, u32),
    pos: CellPos,
    message: String,
    diags: &mut Diagnostics,
) {
    reader.refused_headers.insert(refused);
    reader.mistyped(pos, message, diags);
}
