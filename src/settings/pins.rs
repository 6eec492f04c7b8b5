//! The ADDRESSES sheet: signals pinned to the addresses the panel's wiring
//! gives them, one row each (`START | I0.0`). The rows are read here as
//! text; which signal and which address they mean is decided against the
//! program and the target (`convert`), where the errors name these cells.

use crate::diag::{Code, Diagnostics, Location};
use crate::read::{CellValue, Grid};

/// One row of the ADDRESSES sheet as written (a missing signal or address
/// is empty, located at the row's other cell: `convert` reports it with the
/// rest).
#[derive(Debug, Clone, PartialEq)]
pub struct PinRow {
    /// The signal as the allocation list names it: `START`, `x11`, `y1+`,
    /// `part_present`.
    pub signal: String,
    pub address: String,
    pub signal_at: Location,
    pub address_at: Location,
}

/// The rows of the sheet: the two columns of the `SIGNAL | ADDRESS`
/// header (or, without one, the first two used columns), signal then
/// address. What stands above the header is the sheet's title and notes
/// (the template workbook's), except in the address column and on the row
/// just above the header, where a cell would be a pin or a header that is
/// not read. Any other cell — right or left of the two columns, right of
/// the header — is reported, never dropped silently.
pub fn parse(grid: &Grid, diags: &mut Diagnostics) -> Vec<PinRow> {
    let text = |value: &CellValue| match value {
        CellValue::Text(t) => t.trim().to_string(),
        other => other.describe(),
    };
    let cells: Vec<&crate::read::GridCell> = grid
        .cells
        .iter()
        .filter(|c| !matches!(&c.value, CellValue::Text(t) if t.trim().is_empty()))
        .collect();
    let is =
        |cell: &crate::read::GridCell, word: &str| text(&cell.value).eq_ignore_ascii_case(word);
    // Looked up by position: a sheet of many cells is read in linear time.
    let addresses: std::collections::BTreeSet<crate::diag::CellPos> = cells
        .iter()
        .filter(|c| is(c, "address"))
        .map(|c| c.pos)
        .collect();
    let header = cells.iter().find(|c| {
        is(c, "signal") && addresses.contains(&crate::diag::CellPos::new(c.pos.row, c.pos.col + 1))
    });
    let Some(first_col) = header
        .map(|h| h.pos.col)
        .or_else(|| cells.iter().map(|c| c.pos.col).min())
    else {
        return Vec::new();
    };
    let header_row = header.map(|h| h.pos.row);
    let mut rows: std::collections::BTreeMap<u32, [Option<(String, Location)>; 2]> =
        std::collections::BTreeMap::new();
    let mut uncomputed = std::collections::BTreeSet::new();
    for cell in &cells {
        let at = grid.location(cell.pos);
        let column = cell.pos.col.checked_sub(first_col);
        let why = match header_row {
            // The header's own two cells.
            Some(h) if cell.pos.row == h && matches!(column, Some(0 | 1)) => continue,
            Some(h) if cell.pos.row == h => format!(
                "{} heads no column steptable reads: the ADDRESSES sheet has two columns, SIGNAL and ADDRESS",
                cell.value.describe()
            ),
            // Title and notes above the header, but in the address column
            // or just above the header; a formula nobody computed there
            // may be a pin as well as a title (E016 below).
            Some(h)
                if cell.pos.row + 1 < h
                    && column != Some(1)
                    && !matches!(cell.value, CellValue::Uncomputed(_)) =>
            {
                continue;
            }
            Some(h)
                if let CellValue::Uncomputed(formula) = &cell.value
                    && cell.pos.row < h =>
            {
                diags.error(Code::E016FormulaNotComputed, at, uncomputed_pin(formula));
                continue;
            }
            Some(h) if cell.pos.row < h => format!(
                "{} is above the SIGNAL | ADDRESS header, where nothing is read (a pin goes in a row below it)",
                cell.value.describe()
            ),
            _ => match column {
                // What a formula nobody computed pins cannot be told: the
                // program would be written without the pin (E016, and the
                // row is read no further).
                Some(0 | 1) if let CellValue::Uncomputed(formula) = &cell.value => {
                    uncomputed.insert(cell.pos.row);
                    diags.error(Code::E016FormulaNotComputed, at, uncomputed_pin(formula));
                    continue;
                }
                Some(column @ (0 | 1)) => {
                    rows.entry(cell.pos.row).or_default()[column as usize] =
                        Some((text(&cell.value), at));
                    continue;
                }
                _ => format!(
                    "{} is not read: the ADDRESSES sheet has two columns, signal and address",
                    cell.value.describe()
                ),
            },
        };
        diags.warning(Code::W003Ignored, at, why);
    }
    let mut pins = Vec::new();
    rows.retain(|row, _| !uncomputed.contains(row));
    for row in rows.into_values() {
        match row {
            [Some((signal, signal_at)), Some((address, address_at))] => pins.push(PinRow {
                signal,
                address,
                signal_at,
                address_at,
            }),
            [Some((signal, at)), None] => pins.push(PinRow {
                signal,
                address: String::new(),
                signal_at: at.clone(),
                address_at: at,
            }),
            [None, Some((address, at))] => pins.push(PinRow {
                signal: String::new(),
                address,
                signal_at: at.clone(),
                address_at: at,
            }),
            [None, None] => {}
        }
    }
    pins
}

/// E016's message on the ADDRESSES sheet.
fn uncomputed_pin(formula: &str) -> String {
    format!(
        "the formula {formula} has no computed value, so steptable cannot tell which signal or address it pins (the program would be written without the pin); open and save the workbook in Excel or LibreOffice, or type it"
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rows under the header are read; above it lie the title and notes,
    /// but for the address column and the row just above the header; a cell
    /// right of the header, or right or left of the two columns, is named.
    #[test]
    fn rows_header_and_strays() {
        let grid = Grid::from_text_rows(
            "t.xlsx",
            Some("ADDRESSES"),
            &[
                vec!["", "ADDRESSES", "", "a title"],
                vec!["", "a note", "START | I0.0 is a pin"],
                vec![],
                vec!["", "SIGNAL", "ADDRESS", "comment"],
                vec!["", "START", "I0.0", "note"],
                vec!["", "y1+", ""],
                vec!["", "", "Q0.1"],
                vec!["x", " x11 ", " I0.2 "],
            ],
        );
        let mut diags = Diagnostics::new();
        let pins = parse(&grid, &mut diags);
        let pairs: Vec<(&str, &str)> = pins
            .iter()
            .map(|p| (p.signal.as_str(), p.address.as_str()))
            .collect();
        assert_eq!(
            pairs,
            [
                ("START", "I0.0"),
                ("y1+", ""),
                ("", "Q0.1"),
                ("x11", "I0.2")
            ]
        );
        assert_eq!(pins[3].address_at.cell.map(|c| c.a1()), Some("C8".into()));
        let found: Vec<String> = diags
            .into_sorted()
            .iter()
            .map(|d| format!("{} {}", d.code.as_str(), d.location.cell.unwrap().a1()))
            .collect();
        assert_eq!(found, ["W003 C2", "W003 D4", "W003 D5", "W003 A8"]);
        // The row just above the header is checked whole.
        let grid = Grid::from_text_rows(
            "t.xlsx",
            Some("ADDRESSES"),
            &[
                vec!["Pins"],
                vec!["SIGNAL", "ADDRESS"],
                vec!["START", "I0.0"],
            ],
        );
        let mut diags = Diagnostics::new();
        assert_eq!(parse(&grid, &mut diags).len(), 1);
        let found = diags.into_sorted();
        assert_eq!(found.len(), 1, "{found:?}");
        assert_eq!(
            found[0].location.cell,
            Some(crate::diag::CellPos::new(0, 0))
        );
    }
}
