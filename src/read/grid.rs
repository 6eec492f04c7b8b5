//! A sheet as read: its filled cells with absolute positions.

use crate::diag::{CellPos, Location};

/// The value of one non-empty cell.
#[derive(Debug, Clone, PartialEq)]
pub enum CellValue {
    Text(String),
    Number(f64),
    Bool(bool),
    /// A date or time, as the workbook shows it.
    Date(String),
    /// An error value such as `#REF!`.
    Error(String),
    /// A formula (its text) saved without a computed value.
    Uncomputed(String),
}

impl CellValue {
    /// The value as a message names it: `"C1+1"`, `the number 42`.
    pub fn describe(&self) -> String {
        match self {
            CellValue::Text(t) => {
                let t = t.trim();
                if t.chars().count() > 40 {
                    let head: String = t.chars().take(37).collect();
                    format!("\"{head}…\"")
                } else {
                    format!("\"{t}\"")
                }
            }
            CellValue::Number(n) => format!("the number {n}"),
            CellValue::Bool(b) => format!("the value {}", if *b { "TRUE" } else { "FALSE" }),
            // A time of day or a duration has no `-` (2024-01-03 has).
            CellValue::Date(d) if d.contains('-') => format!("the date {d}"),
            CellValue::Date(d) => format!("the time {d}"),
            CellValue::Error(e) => format!("the error {e}"),
            CellValue::Uncomputed(f) => format!("the formula {f} (never computed)"),
        }
    }
}

/// One non-empty cell at its absolute position on the sheet.
#[derive(Debug, Clone, PartialEq)]
pub struct GridCell {
    pub pos: CellPos,
    pub value: CellValue,
}

/// The sheet that holds the step table, as read.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// File name for messages.
    pub file: String,
    /// Sheet name; `None` for CSV.
    pub sheet: Option<String>,
    /// Non-empty cells in row-major order.
    pub cells: Vec<GridCell>,
    /// Cells under a merge, which the spreadsheet hides (E049 at each): not
    /// read, but known, so that what follows only from their absence (a
    /// step without its move, a move from the wrong position) is not said
    /// a second time.
    pub hidden: Vec<GridCell>,
}

impl Grid {
    /// A grid of text cells laid out from A1 (blank strings are empty
    /// cells), as if read from `sheet` of `file` — for tests and generated
    /// tables.
    pub fn from_text_rows<R, S>(file: &str, sheet: Option<&str>, rows: &[R]) -> Grid
    where
        R: AsRef<[S]>,
        S: AsRef<str>,
    {
        let mut cells = Vec::new();
        for (r, row) in rows.iter().enumerate() {
            for (c, text) in row.as_ref().iter().enumerate() {
                let text = text.as_ref();
                if !text.trim().is_empty() {
                    cells.push(GridCell {
                        pos: CellPos::new(r as u32, c as u32),
                        value: CellValue::Text(text.to_string()),
                    });
                }
            }
        }
        Grid {
            file: file.to_string(),
            sheet: sheet.map(str::to_string),
            cells,
            hidden: Vec::new(),
        }
    }

    /// The location of a cell of this grid, for diagnostics.
    pub fn location(&self, pos: CellPos) -> Location {
        Location {
            file: self.file.clone(),
            sheet: self.sheet.clone(),
            cell: Some(pos),
        }
    }

    /// A cell as messages name it: `D7` on a sheet, `7:4` in a CSV file.
    pub fn cell_name(&self, pos: CellPos) -> String {
        if self.sheet.is_some() {
            pos.a1()
        } else {
            format!("{}:{}", pos.row + 1, pos.col + 1)
        }
    }

    /// The location of the sheet as a whole.
    pub fn sheet_location(&self) -> Location {
        Location {
            file: self.file.clone(),
            sheet: self.sheet.clone(),
            cell: None,
        }
    }
}
