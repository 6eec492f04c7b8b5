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

/// The rows of the sheet: the first two used columns, signal then address.
/// A row `SIGNAL | ADDRESS` is the header: what stands above it is the
/// sheet's title and notes (the template workbook's). Any cell right of the
/// two columns below the header is reported, not dropped silently.
pub fn parse(grid: &Grid, diags: &mut Diagnostics) -> Vec<PinRow> {
    let Some(first_col) = grid.cells.iter().map(|c| c.pos.col).min() else {
        return Vec::new();
    };
    let text = |value: &CellValue| match value {
        CellValue::Text(t) => t.trim().to_string(),
        other => other.describe(),
    };
    let is = |cell: &crate::read::GridCell, col: u32, word: &str| {
        cell.pos.col == col && text(&cell.value).eq_ignore_ascii_case(word)
    };
    let header = grid
        .cells
        .iter()
        .filter(|c| is(c, first_col, "signal"))
        .map(|c| c.pos.row)
        .find(|row| {
            grid.cells
                .iter()
                .any(|c| c.pos.row == *row && is(c, first_col + 1, "address"))
        });
    let mut rows: std::collections::BTreeMap<u32, [Option<(String, Location)>; 2]> =
        std::collections::BTreeMap::new();
    for cell in grid
        .cells
        .iter()
        .filter(|c| header.is_none_or(|h| c.pos.row > h))
    {
        let at = grid.location(cell.pos);
        match cell.pos.col - first_col {
            column @ (0 | 1) => {
                rows.entry(cell.pos.row).or_default()[column as usize] =
                    Some((text(&cell.value), at));
            }
            _ => diags.warning(
                Code::W003Ignored,
                at,
                format!(
                    "{} is not read: the ADDRESSES sheet has two columns, signal and address",
                    cell.value.describe()
                ),
            ),
        }
    }
    let mut pins = Vec::new();
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_header_and_strays() {
        let grid = Grid::from_text_rows(
            "t.xlsx",
            Some("ADDRESSES"),
            &[
                vec!["", "ADDRESSES", "", "a title"],
                vec!["", "SIGNAL", "ADDRESS"],
                vec!["", "START", "I0.0", "note"],
                vec!["", "y1+", ""],
                vec!["", "", "Q0.1"],
                vec!["", " x11 ", " I0.2 "],
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
        assert_eq!(pins[3].address_at.cell.map(|c| c.a1()), Some("C6".into()));
        let found: Vec<String> = diags
            .into_sorted()
            .iter()
            .map(|d| format!("{} {}", d.code.as_str(), d.location.cell.unwrap().a1()))
            .collect();
        assert_eq!(found, ["W003 D3"]);
    }
}
