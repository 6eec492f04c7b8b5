//! Where the table lies on its sheet: which rows are steps and which columns
//! branches, found by the `BRANCH n` / `STEP n` headers or as a bare grid of
//! moves; and the audit that every other filled cell in or beside that region
//! is reported, never silently dropped.

use std::collections::BTreeSet;

use crate::cell::{Header, header_kind, looks_like_item, parse_items};
use crate::diag::{CellPos, Code, Diagnostics};
use crate::read::{CellValue, Grid, GridCell};

/// The table's frame on the sheet.
pub(super) struct Frame {
    /// Rows that are steps, top to bottom.
    pub step_rows: Vec<u32>,
    /// Step rows carry a `STEP n` label (trailing empty labelled rows are allowed).
    pub labelled: bool,
    /// Columns that are branches, left to right.
    pub branch_cols: Vec<u32>,
    /// The row of the `BRANCH n` headers, if there are any.
    pub header_row: Option<u32>,
    /// The column of the `STEP n` labels, if there are any.
    pub label_col: Option<u32>,
}

impl Frame {
    /// The label cell of step row `index` (`STEP 3 (clamp part)`), if the
    /// table has labels and that row has one.
    pub(super) fn label_cell<'g>(&self, grid: &'g Grid, index: usize) -> Option<&'g GridCell> {
        let col = self.label_col?;
        let row = *self.step_rows.get(index)?;
        grid.cells.iter().find(|c| c.pos == CellPos::new(row, col))
    }

    /// The number each step row's `STEP n` label says, with the label's
    /// cell (none for a row without one).
    pub(super) fn step_labels(&self, grid: &Grid) -> Vec<Option<(u32, CellPos)>> {
        let Some(col) = self.label_col else {
            return vec![None; self.step_rows.len()];
        };
        let cells: Vec<CellPos> = (self.step_rows.iter())
            .map(|row| CellPos::new(*row, col))
            .collect();
        let numbers = header_numbers(grid, &cells);
        numbers
            .into_iter()
            .zip(cells)
            .map(|(n, pos)| n.map(|n| (n, pos)))
            .collect()
    }
}

/// Finds step rows and branch columns: by headers, or as a bare grid of moves.
/// Two tables on one sheet are an error (E027): merging them would run one
/// machine's steps after the other's.
pub(super) fn find_frame(grid: &Grid, diags: &mut Diagnostics) -> Option<Frame> {
    let mut branch_headers: Vec<CellPos> = Vec::new();
    let mut step_labels: Vec<CellPos> = Vec::new();
    for cell in &grid.cells {
        if let CellValue::Text(t) = &cell.value {
            match header_kind(t) {
                Some(Header::Branch(_)) => branch_headers.push(cell.pos),
                Some(Header::Step(_)) => step_labels.push(cell.pos),
                None => {}
            }
        }
    }
    if two_tables(grid, &branch_headers, &step_labels, diags) {
        return None;
    }

    if !branch_headers.is_empty() {
        let header_row = branch_headers[0].row;
        let branch_cols: Vec<u32> = sorted_unique(branch_headers.iter().map(|p| p.col));
        let first_branch = *branch_cols.first()?;
        let last_branch = *branch_cols.last()?;
        warn_on_branch_numbers(grid, header_row, &branch_cols, diags);
        let labels: Vec<CellPos> = step_labels
            .iter()
            .copied()
            .filter(|p| p.row > header_row && p.col < first_branch)
            .collect();
        if let Some(label_col) = labels.first().map(|p| p.col) {
            let step_rows = sorted_unique(labels.iter().map(|p| p.row));
            warn_on_label_numbers(grid, label_col, &step_rows, diags);
            return Some(Frame {
                step_rows,
                labelled: true,
                branch_cols,
                header_row: Some(header_row),
                label_col: Some(label_col),
            });
        }
        // No labels: rows below the header down to the last move in the branch columns.
        let last_row = grid
            .cells
            .iter()
            .filter(|c| c.pos.row > header_row && (first_branch..=last_branch).contains(&c.pos.col))
            .filter(|c| matches!(&c.value, CellValue::Text(t) if looks_like_item(t)))
            .map(|c| c.pos.row)
            .max()?;
        return Some(Frame {
            step_rows: (header_row + 1..=last_row).collect(),
            labelled: false,
            branch_cols,
            header_row: Some(header_row),
            label_col: None,
        });
    }

    let move_cells: Vec<CellPos> = grid
        .cells
        .iter()
        .filter(|c| matches!(&c.value, CellValue::Text(t) if looks_like_item(t)))
        .map(|c| c.pos)
        .collect();

    if let Some(label_col) = step_labels.first().map(|p| p.col) {
        let step_rows = sorted_unique(step_labels.iter().map(|p| p.row));
        let last_col = move_cells
            .iter()
            .filter(|p| p.col > label_col && step_rows.binary_search(&p.row).is_ok())
            .map(|p| p.col)
            .max()?;
        warn_on_label_numbers(grid, label_col, &step_rows, diags);
        return Some(Frame {
            step_rows,
            labelled: true,
            branch_cols: (label_col + 1..=last_col).collect(),
            header_row: None,
            label_col: Some(label_col),
        });
    }

    // A bare grid: the bounding box of the cells that look like moves.
    let min_row = move_cells.iter().map(|p| p.row).min()?;
    let max_row = move_cells.iter().map(|p| p.row).max()?;
    let min_col = move_cells.iter().map(|p| p.col).min()?;
    let max_col = move_cells.iter().map(|p| p.col).max()?;
    Some(Frame {
        step_rows: (min_row..=max_row).collect(),
        labelled: false,
        branch_cols: (min_col..=max_col).collect(),
        header_row: None,
        label_col: None,
    })
}

/// BRANCH headers on more than one row, or STEP labels in more than one
/// column, are two tables: reported (E027), since either merging them or
/// silently taking one would lose what the engineer wrote.
fn two_tables(
    grid: &Grid,
    branch_headers: &[CellPos],
    step_labels: &[CellPos],
    diags: &mut Diagnostics,
) -> bool {
    let header_rows = sorted_unique(branch_headers.iter().map(|p| p.row));
    // A title above the table may start like a label ("Step 1: …").
    let below = |p: &&CellPos| header_rows.first().is_none_or(|h| p.row > *h);
    let label_cols = sorted_unique(step_labels.iter().filter(below).map(|p| p.col));
    let (what, first, second) = if header_rows.len() > 1 {
        let on = |row: u32| branch_headers.iter().find(|p| p.row == row).copied();
        ("BRANCH headers", on(header_rows[0]), on(header_rows[1]))
    } else if label_cols.len() > 1 {
        let on = |col: u32| {
            step_labels
                .iter()
                .filter(below)
                .find(|p| p.col == col)
                .copied()
        };
        ("STEP labels", on(label_cols[0]), on(label_cols[1]))
    } else {
        return false;
    };
    let (Some(first), Some(second)) = (first, second) else {
        return false;
    };
    diags.error(
        Code::E027TwoTables,
        grid.location(second),
        format!(
            "a second table: {what} at {} and at {}; {} holds one step table (put the other {}, or delete it)",
            grid.cell_name(first),
            grid.cell_name(second),
            if grid.sheet.is_some() { "a sheet" } else { "a CSV file" },
            if grid.sheet.is_some() { "on its own sheet and choose it with --sheet" } else { "in its own file" }
        ),
    );
    true
}

fn sorted_unique(values: impl Iterator<Item = u32>) -> Vec<u32> {
    values.collect::<BTreeSet<_>>().into_iter().collect()
}

/// Steps are numbered by their order on the sheet; a `STEP n` label that
/// says otherwise (a copied row, a skipped number, two rows swapped) is
/// worth a warning, since every output uses the row order.
fn warn_on_label_numbers(grid: &Grid, label_col: u32, step_rows: &[u32], diags: &mut Diagnostics) {
    let cells: Vec<CellPos> = step_rows
        .iter()
        .map(|row| CellPos::new(*row, label_col))
        .collect();
    warn_on_numbers(
        grid,
        &cells,
        ("row is labelled STEP", "step", "steps"),
        diags,
    );
}

/// Branches are numbered by their order too: a `BRANCH n` header that says
/// otherwise (a copied column: `BRANCH 1, BRANCH 1`) is worth a warning,
/// since every output names branches by their place.
fn warn_on_branch_numbers(
    grid: &Grid,
    header_row: u32,
    branch_cols: &[u32],
    diags: &mut Diagnostics,
) {
    let cells: Vec<CellPos> = branch_cols
        .iter()
        .map(|col| CellPos::new(header_row, *col))
        .collect();
    warn_on_numbers(
        grid,
        &cells,
        ("column is headed BRANCH", "branch", "branches"),
        diags,
    );
}

/// W002 for each `STEP n` / `BRANCH n` cell (in table order) whose number
/// is not its place. A run of cells shifted alike (a copied row and every
/// row below it) is one warning, at its first cell; every change of the
/// shift is another, so of two swapped labels both cells are named. A
/// label another cell carries too names that cell.
fn warn_on_numbers(
    grid: &Grid,
    cells: &[CellPos],
    (says, one, many): (&str, &str, &str),
    diags: &mut Diagnostics,
) {
    let numbers = header_numbers(grid, cells);
    let mut said_shift = 0i64;
    for (k, (pos, number)) in cells.iter().zip(&numbers).enumerate() {
        let Some(n) = *number else { continue };
        let shift = i64::from(n) - (k as i64 + 1);
        if shift == said_shift || shift == 0 {
            said_shift = shift;
            continue;
        }
        said_shift = shift;
        let twin = cells
            .iter()
            .zip(&numbers)
            .find(|(other, m)| *other != pos && **m == Some(n))
            .map(|(other, _)| {
                let word = says.rsplit(' ').next().unwrap_or_default();
                format!(" ({} is {word} {n} too)", grid.cell_name(*other))
            })
            .unwrap_or_default();
        // `STEP 2.5`, a step put in between: named as written.
        let written = grid
            .cells
            .iter()
            .find(|c| c.pos == *pos)
            .and_then(|c| match &c.value {
                CellValue::Text(t) => Some(t.clone()),
                _ => None,
            })
            .filter(|t| {
                let number_end = t
                    .trim()
                    .find(|c: char| c.is_ascii_digit())
                    .and_then(|start| {
                        t.trim()[start..]
                            .find(|c: char| !c.is_ascii_digit())
                            .map(|i| start + i)
                    });
                number_end.is_some_and(|i| crate::cell::decimals(&t.trim()[i..]).is_some())
            });
        let label = match written {
            Some(t) => {
                let verb = says.rsplit_once(' ').map_or(says, |(verb, _)| verb);
                format!("{verb} \"{}\" (labels are whole numbers)", t.trim())
            }
            None => format!("{says} {n}"),
        };
        diags.warning(
            Code::W002StepNumber,
            grid.location(*pos),
            format!(
                "this {label} but is {one} {} of the table{twin}; {many} are numbered by their order",
                k + 1
            ),
        );
    }
}

/// The number each `STEP n` / `BRANCH n` cell says.
fn header_numbers(grid: &Grid, cells: &[CellPos]) -> Vec<Option<u32>> {
    cells
        .iter()
        .map(
            |pos| match grid.cells.iter().find(|c| c.pos == *pos).map(|c| &c.value) {
                Some(CellValue::Text(t)) => match header_kind(t) {
                    Some(Header::Step(n) | Header::Branch(n)) => Some(n),
                    _ => None,
                },
                _ => None,
            },
        )
        .collect()
}

/// Reports every filled cell in or beside the table that is not part of it:
/// an error when it looks like table content that would be lost (a move in a
/// row without a STEP label or a column without a BRANCH header), else a
/// warning naming it. Cells far from the table (titles, notes) are left alone
/// unless they read as moves. `lost` hears each move-like cell refused, with the index of the step
/// its moves would have come in.
pub(super) fn report_unused(
    grid: &Grid,
    frame: &Frame,
    lost: &mut dyn FnMut(&str, usize),
    diags: &mut Diagnostics,
) {
    let (Some(&first_row), Some(&last_row)) = (frame.step_rows.first(), frame.step_rows.last())
    else {
        return;
    };
    let (Some(&first_branch), Some(&last_branch)) =
        (frame.branch_cols.first(), frame.branch_cols.last())
    else {
        return;
    };
    let step_rows: BTreeSet<u32> = frame.step_rows.iter().copied().collect();
    let branch_cols: BTreeSet<u32> = frame.branch_cols.iter().copied().collect();
    let top = frame.header_row.unwrap_or(first_row);
    let left = frame.label_col.unwrap_or(first_branch);
    // The region and a margin of one cell around it.
    let near_rows = top.saturating_sub(1)..=last_row.saturating_add(1);
    let near_cols = left.saturating_sub(1)..=last_branch.saturating_add(1);

    for cell in &grid.cells {
        let CellPos { row, col } = cell.pos;
        let in_step_row = step_rows.contains(&row);
        let is_header = frame.header_row == Some(row) && branch_cols.contains(&col);
        let is_label = in_step_row && frame.label_col == Some(col);
        if (in_step_row && branch_cols.contains(&col)) || is_label || is_header {
            continue;
        }
        let text = match &cell.value {
            CellValue::Text(t) => Some(t.as_str()),
            _ => None,
        };
        // `STEP` over the column of STEP labels, in the row of BRANCH
        // headers: the corner header many tables have, read as what it is.
        let corner = frame.header_row == Some(row) && frame.label_col == Some(col);
        if corner && text.is_some_and(heads_the_labels) {
            continue;
        }
        // Below the table, a row whose label cell holds a note (`Note, C1
        // first`) is a note: only what reads wholly as moves would be lost.
        let note_row = row > last_row
            && frame
                .label_col
                .and_then(|c| grid.cells.iter().find(|g| g.pos == CellPos::new(row, c)))
                .is_some_and(|label| match &label.value {
                    CellValue::Text(t) => header_kind(t).is_none(),
                    _ => false,
                });
        let item_like = text.is_some_and(|t| match note_row {
            true => reads_as_items(t),
            false => looks_like_item(t),
        });
        let in_header_row = frame.header_row == Some(row);
        match why_lost(grid, frame, cell.pos, in_step_row) {
            Some(why) if item_like => {
                let text = text.unwrap_or_default().trim();
                lost(text, frame.step_rows.iter().filter(|r| **r < row).count());
                let message = format!("\"{text}\" lies outside the table and would be lost: {why}");
                diags.error(Code::E010NotAMove, grid.location(cell.pos), message)
            }
            // `C2+1` under the last STEP label: step 3 typed a column to
            // the left, a row without a label.
            _ if row > last_row
                && frame.label_col == Some(col)
                && text.is_some_and(reads_as_items) =>
            {
                let text = text.unwrap_or_default().trim();
                lost(text, frame.step_rows.len());
                let message = format!(
                    "\"{text}\" lies outside the table and would be lost: it is in the column of STEP labels below the last step, a row without a STEP label (a move goes in a BRANCH column, beside its STEP n label)"
                );
                diags.error(Code::E010NotAMove, grid.location(cell.pos), message)
            }
            Some(why)
                if near_rows.contains(&row) && near_cols.contains(&col)
                    || in_step_row
                    || in_header_row
                    || note_row =>
            {
                warn_ignored(grid, cell.pos, &cell.value, &why, diags)
            }
            _ if near_rows.contains(&row) && near_cols.contains(&col) => warn_ignored(
                grid,
                cell.pos,
                &cell.value,
                "it lies beside the table",
                diags,
            ),
            _ if text.is_some_and(reads_as_items) => warn_ignored(
                grid,
                cell.pos,
                &cell.value,
                "it reads as a move but lies away from the table",
                diags,
            ),
            // What a formula nobody computed shows cannot be told: it may be
            // a move or a step below the table, as well as a title (E016).
            _ if matches!(cell.value, CellValue::Uncomputed(_)) => {
                warn_ignored(grid, cell.pos, &cell.value, "", diags)
            }
            _ => {}
        }
    }
}

/// Why the cell at `pos` (not part of the table) would be lost: in the row
/// of BRANCH headers, in a step's row outside the BRANCH columns, in a row
/// without a STEP label among, above or below the steps. `None` for a cell
/// beside or away from the table.
fn why_lost(grid: &Grid, frame: &Frame, pos: CellPos, in_step_row: bool) -> Option<String> {
    let CellPos { row, col } = pos;
    let (&first_row, &last_row) = (frame.step_rows.first()?, frame.step_rows.last()?);
    let (&first_branch, &last_branch) = (frame.branch_cols.first()?, frame.branch_cols.last()?);
    let left = frame.label_col.unwrap_or(first_branch);
    let near_cols = left.saturating_sub(1)..=last_branch.saturating_add(1);
    let last_label = |row: u32| {
        frame
            .step_rows
            .iter()
            .rposition(|r| *r < row)
            .map(|k| k + 1)
    };
    let in_rows = (first_row..=last_row).contains(&row);
    let in_cols = (first_branch..=last_branch).contains(&col);
    let below_header = frame.header_row.is_none_or(|h| row > h);
    let in_header_row = frame.header_row == Some(row);
    if in_header_row {
        Some("it is in the row of BRANCH headers but is not a BRANCH n header".to_string())
    } else if in_step_row && col < first_branch {
        Some("its column, left of the first BRANCH, has no BRANCH header".to_string())
    } else if in_step_row {
        Some("its column has no BRANCH header".to_string())
    } else if in_rows && (in_cols || near_cols.contains(&col)) {
        let label = frame.label_col.map(|c| CellPos::new(row, c));
        let unread = label.filter(|l| {
            let value = grid.cells.iter().find(|c| c.pos == *l).map(|c| &c.value);
            matches!(value, Some(CellValue::Uncomputed(_)))
        });
        Some(match last_label(row) {
            // Its label is there, as a formula nobody computed (E016 there).
            _ if let Some(label) = unread => format!(
                "its row's STEP label in {} is a formula without a computed value, so the row is no step steptable can read",
                grid.cell_name(label)
            ),
            // `STEP 2a`: a label, but not one of a step.
            Some(k)
                if frame.labelled
                    && let Some(text) = misread_label(grid, label) =>
            {
                format!(
                    "its row (between STEP {k} and STEP {}) is labelled \"{text}\", which is not STEP and a whole number, so the row is no step; label it STEP {} (steps are numbered by their order), or move the cell into a step's row",
                    k + 1,
                    k + 1
                )
            }
            Some(k) if frame.labelled => {
                format!(
                    "its row (between STEP {k} and STEP {}) has no STEP label; give it one, or move the cell into a step's row",
                    k + 1
                )
            }
            _ => "its row is not a step of the table".to_string(),
        })
    } else if in_cols
        && row < first_row
        && (frame.header_row.is_some_and(|h| row > h) || row + 1 == first_row)
    {
        // Between the BRANCH headers and the first step, or right above
        // the first step: a move there would come before STEP 1.
        Some(format!(
            "its row {} has no STEP label, and it lies above the table's first step (row {})",
            row + 1,
            first_row + 1
        ))
    } else if in_cols && below_header && row > last_row {
        // Its own row is named, not the last step's: that one is fine.
        let label_cell = frame.label_col.map(|col| CellPos::new(row, col));
        let label_held = label_cell.and_then(|at| grid.cells.iter().find(|c| c.pos == at));
        Some(match frame.label_col.filter(|_| frame.labelled) {
            Some(_) if let Some(text) = misread_label(grid, label_cell) => format!(
                "its row {} lies below the table's last step, STEP {} (row {}), and is labelled \"{text}\", which is not STEP and a whole number; label it STEP {} to make it a step",
                row + 1,
                frame.step_rows.len(),
                last_row + 1,
                frame.step_rows.len() + 1,
            ),
            // Its label cell holds a note, not a label: no label to add.
            Some(col) if let Some(held) = label_held => format!(
                "its row {} lies below the table's last step, STEP {} (row {}), and is no step: its label cell {} holds {}",
                row + 1,
                frame.step_rows.len(),
                last_row + 1,
                grid.cell_name(CellPos::new(row, col)),
                held.value.describe()
            ),
            Some(col) => format!(
                "its row {} has no STEP label, and it lies below the table's last step, STEP {} (row {}); add the label STEP {} in {} to make it a step",
                row + 1,
                frame.step_rows.len(),
                last_row + 1,
                frame.step_rows.len() + 1,
                grid.cell_name(CellPos::new(row, col))
            ),
            None => format!(
                "its row {} lies below the table's last step (row {})",
                row + 1,
                last_row + 1
            ),
        })
    } else {
        None
    }
}

/// A corner header over the STEP labels: `STEP`, `Steps`, `Step no.`.
fn heads_the_labels(text: &str) -> bool {
    let word = text.trim().trim_end_matches('.').to_ascii_lowercase();
    matches!(
        word.as_str(),
        "step" | "steps" | "step no" | "step nr" | "step #"
    )
}

/// Text that parses wholly as cell items, as a note never does.
fn reads_as_items(text: &str) -> bool {
    let items = parse_items(text);
    !items.is_empty() && items.iter().all(Result::is_ok)
}

/// W003 for a cell in or beside the table that is not part of it; E016 for
/// a formula there that was never computed: what it holds cannot be told
/// (a STEP label, a BRANCH header, a move), and the table would lose it.
fn warn_ignored(grid: &Grid, pos: CellPos, value: &CellValue, why: &str, diags: &mut Diagnostics) {
    if let CellValue::Uncomputed(formula) = value {
        diags.error(
            Code::E016FormulaNotComputed,
            grid.location(pos),
            format!(
                "the formula {formula} has no computed value, so steptable cannot tell whether it is a STEP label, a BRANCH header or a move (the table would be read without it); open and save the workbook in Excel or LibreOffice, or type it"
            ),
        );
        return;
    }
    diags.warning(
        Code::W003Ignored,
        grid.location(pos),
        format!(
            "{} is not part of the step table and was not read: {why}",
            value.describe()
        ),
    );
}

/// The text of the label cell `at` when it reads as a step's label gone
/// wrong (`STEP 2a`, `Step two`): a row the engineer meant as a step.
fn misread_label(grid: &Grid, at: Option<CellPos>) -> Option<String> {
    let at = at?;
    let cell = grid.cells.iter().find(|c| c.pos == at)?;
    let CellValue::Text(text) = &cell.value else {
        return None;
    };
    let lower = text.trim().to_ascii_lowercase();
    lower.starts_with("step").then(|| text.trim().to_string())
}

#[cfg(test)]
mod tests {
    use crate::diag::Diagnostics;
    use crate::read::Grid;

    /// Every diagnostic of building `rows` (a sheet named S), and whether a table came out.
    fn build(rows: &[&[&str]]) -> (bool, Vec<String>) {
        let grid = Grid::from_text_rows("t.xlsx", Some("S"), rows);
        let mut diags = Diagnostics::new();
        let ok = super::super::build(&grid, &mut diags).is_some();
        (
            ok,
            diags.into_sorted().iter().map(|d| d.to_string()).collect(),
        )
    }

    #[test]
    fn a_misspelt_branch_header_loses_nothing() {
        let (ok, all) = build(&[
            &["", "BRANH 1", "BRANCH 2"],
            &["STEP 1", "C1+1", "C2+1"],
            &["STEP 2", "C1-0", "C2-0"],
        ]);
        assert!(!ok);
        assert!(
            all[0].contains("S!B1: warning[W003]: \"BRANH 1\""),
            "{all:?}"
        );
        assert!(
            all[2].contains("S!B2: error[E010]: \"C1+1\" lies outside"),
            "{all:?}"
        );
        assert!(all[3].contains("S!B3: error[E010]"), "{all:?}");
        // The column left is headed BRANCH 2 but is the table's first.
        assert!(
            all.iter().any(|d| d.contains("S!C1: warning[W002]")),
            "{all:?}"
        );
    }

    #[test]
    fn a_row_without_a_step_label_is_an_error_not_a_loss() {
        let (ok, all) = build(&[
            &["", "BRANCH 1"],
            &["STEP 1", "C1+1"],
            &["", "T=2s"],
            &["STEP 2", "C1-0"],
        ]);
        assert!(!ok);
        assert_eq!(all.len(), 1, "{all:?}");
        assert!(
            all[0].contains("S!B3: error[E010]: \"T=2s\"")
                && all[0].contains("between STEP 1 and STEP 2"),
            "{all:?}"
        );
    }

    #[test]
    fn labels_with_comments_are_steps() {
        let (ok, all) = build(&[
            &["", "BRANCH 1"],
            &["STEP 1 (clamp)", "C1+1"],
            &["STEP 2: release", "C1-0"],
        ]);
        assert!(ok && all.is_empty(), "{all:?}");
    }

    #[test]
    fn two_tables_on_one_sheet_are_refused() {
        let (ok, all) = build(&[
            &["", "BRANCH 1"],
            &["STEP 1", "C1+1"],
            &["STEP 2", "C1-0"],
            &[],
            &["", "BRANCH 1"],
            &["STEP 1", "C2+1"],
            &["STEP 2", "C2-0"],
        ]);
        assert!(!ok);
        assert!(
            all[0].contains("S!B5: error[E027]: a second table"),
            "{all:?}"
        );
        // Side by side: STEP labels in two columns.
        let (ok, all) = build(&[
            &["STEP 1", "C1+1", "", "STEP 1", "C2+1"],
            &["STEP 2", "C1-0", "", "STEP 2", "C2-0"],
        ]);
        assert!(!ok && all[0].contains("error[E027]"), "{all:?}");
    }

    #[test]
    fn notes_beside_the_table_are_named_and_far_ones_left_alone() {
        let (ok, all) = build(&[
            &["My machine"],
            &[],
            &["", "BRANCH 1", "remarks"],
            &["STEP 1", "C1+1", "clamp"],
            &["STEP 2", "C1-0"],
            &[],
            &["Note: C1 is the clamp, see drawing 4711"],
        ]);
        assert!(ok);
        assert_eq!(all.len(), 2, "{all:?}");
        assert!(
            all[0].contains("S!C3: warning[W003]: \"remarks\""),
            "{all:?}"
        );
        assert!(all[1].contains("S!C4: warning[W003]: \"clamp\""), "{all:?}");
        // A move far from the table is still named.
        let (ok, all) = build(&[
            &["", "BRANCH 1"],
            &["STEP 1", "C1+1"],
            &["STEP 2", "C1-0"],
            &[],
            &[],
            &["", "", "", "C2+1"],
        ]);
        assert!(ok);
        assert!(all[0].contains("S!D6: warning[W003]: \"C2+1\""), "{all:?}");
    }

    #[test]
    fn a_move_below_the_labelled_rows_is_an_error() {
        let (ok, all) = build(&[
            &["", "BRANCH 1"],
            &["STEP 1", "C1+1"],
            &["STEP 2", "C1-0"],
            &["", "C2+1"],
        ]);
        assert!(!ok);
        assert!(
            all[0].contains("S!B4: error[E010]") && all[0].contains("below"),
            "{all:?}"
        );
    }
}
