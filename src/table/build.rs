//! Building a table from a sheet: its cells found in the frame of its
//! headers, each parsed (with a hint for a cell that is almost a move),
//! and the result checked against the rules ([`super::check`]).

use super::check;
use super::frame::{Frame, find_frame};
use super::*;
use crate::actuator::Valves;
use crate::cell::{
    CellError, ItemError, MAX_ACTUATOR, MAX_POSITION, item_texts, move_attempts, not_a_move_hint,
    parse_items,
};
use crate::diag::{Code, Diagnostics, Location};
use crate::read::{CellValue, Grid};

/// A table cell found on the sheet, before parsing.
struct RawCell {
    pos: CellPos,
    value: CellValue,
    branch: usize,
}

/// Builds the table from a sheet and checks it. Returns `None` when any error
/// was found (all of them are in `diags`).
pub fn build(grid: &Grid, diags: &mut Diagnostics) -> Option<StepTable> {
    build_for(grid, &Valves::default(), true, diags)
}

/// [`build`] for the valves the settings give by number: a position a
/// kind cannot hold (E045) is said with the table's other errors, in one
/// run, and no E022 then asks to complete that move.
///
/// `fst`: a Festo FST file is written, so a name whose first 9 characters
/// are reserved is refused too (E015).
pub fn build_for(
    grid: &Grid,
    valves: &Valves,
    fst: bool,
    diags: &mut Diagnostics,
) -> Option<StepTable> {
    let errors_before = diags.error_count();
    let Some(frame) = find_frame(grid, diags) else {
        if diags.error_count() == errors_before {
            diags.error(
                Code::E003NoTable,
                grid.sheet_location(),
                "no step table found: expected BRANCH n / STEP n headers or cells such as C1+1",
            );
        }
        return None;
    };
    if frame.branch_cols.len() > MAX_BRANCHES || frame.step_rows.len() > MAX_STEPS {
        diags.error(
            Code::E024TableTooLarge,
            grid.sheet_location(),
            format!(
                "table has {} steps × {} branches; the limit is {MAX_STEPS} steps × {MAX_BRANCHES} branches",
                frame.step_rows.len(),
                frame.branch_cols.len()
            ),
        );
        return None;
    }

    let rows = step_cells(grid, &frame);
    // A move in a cell outside the table is refused too: the actuator's
    // position is unknown from the step it would have followed.
    let mut refused = check::Refused::default();
    let mut lost = |text: &str, step: usize| {
        for actuator in item_texts(text).into_iter().flat_map(move_attempts) {
            refused.add(actuator, step);
        }
    };
    frame::report_unused(grid, &frame, &mut lost, diags);
    // A move hidden under a merge (E049) is refused as well, at its step.
    for cell in &grid.hidden {
        if let CellValue::Text(text) = &cell.value {
            // In a step's row, its index; between rows, the next step's.
            let step = frame
                .step_rows
                .iter()
                .filter(|r| **r < cell.pos.row)
                .count();
            lost(text, step);
        }
    }

    // Parse every cell.
    let mut parsed: Vec<Vec<(CellItem, CellPos, usize)>> = Vec::with_capacity(rows.len());
    for (step, row) in rows.iter().enumerate() {
        let mut items = Vec::new();
        for raw in row {
            let mut refuse = |actuator| refused.add(actuator, step);
            for item in parse_cell(grid, raw, diags, &mut refuse) {
                items.push((item, raw.pos, raw.branch));
            }
        }
        parsed.push(items);
    }

    // Steps without moves: trailing labelled rows are unused template rows;
    // any other empty step is an error (we never renumber silently).
    let last_with_moves = rows.iter().rposition(|r| !r.is_empty());
    let Some(last_with_moves) = last_with_moves else {
        diags.error(
            Code::E003NoTable,
            grid.sheet_location(),
            "the step table has no moves: fill at least one cell such as C1+1",
        );
        return None;
    };
    // A step whose row holds a cell hidden under a merge lacks it for that
    // reason alone (E049 there).
    let hides = |i: usize| grid.hidden.iter().any(|c| c.pos.row == frame.step_rows[i]);
    for (i, row) in rows.iter().enumerate().take(last_with_moves) {
        if row.is_empty() && !hides(i) {
            let first_col = frame.branch_cols.first().copied().unwrap_or(0);
            let pos = CellPos::new(frame.step_rows[i], first_col);
            let what = if frame.labelled {
                format!("STEP {} has no move", i + 1)
            } else {
                format!("row {} of the table has no move", i + 1)
            };
            diags.error(
                Code::E023EmptyStep,
                grid.location(pos),
                format!("{what}; every step needs at least one move (delete the empty row)"),
            );
        }
    }
    // An unused template row is dropped, but not the engineer's words on
    // its label (`STEP 9 (spare)`): said, so a step meant to be filled
    // is not lost without a word.
    for index in last_with_moves + 1..frame.step_rows.len() {
        if let Some(cell) = frame.label_cell(grid, index)
            && let CellValue::Text(text) = &cell.value
            && crate::cell::step_comment(text).is_some()
        {
            diags.warning(
                Code::W003Ignored,
                grid.location(cell.pos),
                format!("\"{}\" labels a step with no move after the last one; the step and its comment are not used", text.trim()),
            );
        }
    }
    parsed.truncate(last_with_moves + 1);

    let table = check::check(grid, &frame, parsed, (&refused, valves, fst), diags);
    if diags.error_count() > errors_before {
        None
    } else {
        table
    }
}

/// The raw cells of every step row, by row, in their branches.
fn step_cells(grid: &Grid, frame: &Frame) -> Vec<Vec<RawCell>> {
    let row_index: BTreeMap<u32, usize> = frame
        .step_rows
        .iter()
        .enumerate()
        .map(|(i, r)| (*r, i))
        .collect();
    let col_index: BTreeMap<u32, usize> = frame
        .branch_cols
        .iter()
        .enumerate()
        .map(|(i, c)| (*c, i))
        .collect();
    let mut rows: Vec<Vec<RawCell>> = (0..frame.step_rows.len()).map(|_| Vec::new()).collect();
    for cell in &grid.cells {
        let Some(&r) = row_index.get(&cell.pos.row) else {
            continue;
        };
        if let Some(&branch) = col_index.get(&cell.pos.col) {
            rows[r].push(RawCell {
                pos: cell.pos,
                value: cell.value.clone(),
                branch,
            });
        }
    }
    rows
}

/// The items of a cell; each refused move-like item is told to `refuse`
/// with the actuator it was probably about.
fn parse_cell(
    grid: &Grid,
    raw: &RawCell,
    diags: &mut Diagnostics,
    refuse: &mut dyn FnMut(Option<u32>),
) -> Vec<CellItem> {
    let location = grid.location(raw.pos);
    let text = match &raw.value {
        CellValue::Text(t) => t,
        other => {
            let (code, message) = not_a_move(other);
            diags.error(code, location, message);
            // Refused whole: it may have moved any actuator.
            refuse(None);
            return Vec::new();
        }
    };
    let chars = text.chars().count();
    if chars > MAX_CELL_CHARS {
        diags.error(
            Code::E013CellTooLong,
            location,
            format!("the cell holds {chars} characters; a move has at most {MAX_CELL_CHARS}"),
        );
        for actuator in item_texts(text).into_iter().flat_map(move_attempts) {
            refuse(actuator);
        }
        return Vec::new();
    }
    let results = parse_items(text);
    if results.is_empty() {
        diags.error(
            Code::E010NotAMove,
            location.clone(),
            format!(
                "\"{}\" is not a move (expected C<number>+<position>, e.g. C2+1)",
                text.trim()
            ),
        );
    }
    let mut items = Vec::with_capacity(results.len());
    for (part, result) in item_texts(text).into_iter().zip(results) {
        match result {
            Ok(item) => {
                if let CellItem::Dwell { ms } = item
                    && crate::cell::without_unit(part)
                {
                    let number = part.split_once('=').map_or("", |(_, n)| n.trim());
                    let seconds = crate::cell::duration_text(ms);
                    let millis = match number.parse::<u32>() {
                        Ok(n)
                            if (crate::cell::MIN_DWELL_MS..=crate::cell::MAX_DWELL_MS)
                                .contains(&n) =>
                        {
                            format!(", or T={n}ms if milliseconds were meant")
                        }
                        _ => String::new(),
                    };
                    diags.warning(
                        Code::W007Assumed,
                        location.clone(),
                        format!(
                            "\"{}\" has no unit and is read as {} seconds: write T={seconds}{millis}",
                            part.trim(),
                            seconds.trim_end_matches('s'),
                        ),
                    );
                }
                items.push(item)
            }
            Err(error) => {
                for actuator in move_attempts(part) {
                    refuse(actuator);
                }
                report_item_error(error, text, part, &location, diags)
            }
        }
    }
    items
}

/// Why a cell that holds no text is no move, with its code.
fn not_a_move(value: &CellValue) -> (Code, String) {
    match value {
        CellValue::Bool(b) => (
            Code::E010NotAMove,
            format!(
                "the value {} is not a move (expected text such as C2+1)",
                if *b { "TRUE" } else { "FALSE" }
            ),
        ),
        CellValue::Date(_) => (
            Code::E010NotAMove,
            format!(
                "{} is not a move: the spreadsheet took what was typed for a date or time; format the cell as text and type the move, e.g. C2+1",
                value.describe()
            ),
        ),
        CellValue::Error(e) => (
            Code::E010NotAMove,
            format!("the cell shows the error {e}, not a move"),
        ),
        CellValue::Uncomputed(formula) => (
            Code::E016FormulaNotComputed,
            format!(
                "the formula {formula} has no computed value (the file was saved by a program that does not calculate); open and save it in Excel or LibreOffice, or type the move"
            ),
        ),
        CellValue::Number(n) => (
            Code::E010NotAMove,
            format!("the number {n} is not a move (expected text such as C2+1)"),
        ),
        CellValue::Text(t) => (
            Code::E010NotAMove,
            format!("\"{}\" is not a move", t.trim()),
        ),
    }
}

/// Reports a refused item of the cell `text`: E010 quotes the item
/// (`part`) and says what it was probably meant to be.
fn report_item_error(
    error: ItemError,
    text: &str,
    part: &str,
    location: &Location,
    diags: &mut Diagnostics,
) {
    let location = location.clone();
    match error {
        ItemError::Move(CellError::NotAMove) => diags.error(
            Code::E010NotAMove,
            location,
            match split_item_kind(part) {
                Some(kind) => format!(
                    "\"{}\" is not {kind} ({})",
                    part.trim(),
                    crate::cell::split_number_hint(part).unwrap_or_default()
                ),
                None => format!(
                    "\"{}\" is not a move ({})",
                    part.trim(),
                    not_a_move_hint(part)
                ),
            },
        ),
        ItemError::Move(CellError::BadActuator(n)) => diags.error(
            Code::E011BadActuator,
            location,
            format!(
                "\"{}\": actuator number {n} is out of range (expected 1 to {MAX_ACTUATOR})",
                text.trim()
            ),
        ),
        ItemError::Move(CellError::BadPosition(n)) => diags.error(
            Code::E012BadPosition,
            location,
            format!(
                "\"{}\": position {n} is out of range (expected 0 to {MAX_POSITION})",
                text.trim()
            ),
        ),
        ItemError::BadDwell(message) => diags.error(Code::E014BadDwell, location, message),
        ItemError::BadName(message) => diags.error(Code::E015BadName, location, message),
        ItemError::BadJump(message) => diags.error(Code::E017BadJump, location, message),
    }
}

/// What a refused item whose number a space splits was written as (`T = 1
/// 5 s` is a dwell, `J:1 0 if I:x` a jump), when it is no move.
fn split_item_kind(part: &str) -> Option<&'static str> {
    if !crate::cell::split_number(part) {
        return None;
    }
    let upper = part.trim_start().to_ascii_uppercase();
    match upper.chars().next() {
        Some('T') => Some("a dwell as written"),
        Some('J') => Some("a jump as written"),
        Some('I') => Some("a wait as written"),
        Some('Y') => Some("an output as written"),
        _ => None,
    }
}

/// Builds and checks a table from rows of cell text laid out as a bare grid
/// from A1 (empty strings are empty cells), as if read from the CSV file
/// `file`. For tests, benchmarks and generated tables.
pub fn from_rows<R, S>(file: &str, rows: &[R]) -> Result<StepTable, Vec<crate::diag::Diagnostic>>
where
    R: AsRef<[S]>,
    S: AsRef<str>,
{
    let grid = Grid::from_text_rows(file, None, rows);
    let mut diags = Diagnostics::new();
    match build(&grid, &mut diags) {
        Some(table) => Ok(table),
        None => Err(diags.into_sorted()),
    }
}
