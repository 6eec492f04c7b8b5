//! Which reading of a CSV file is the table: the one that reads as a table
//! with the fewest problems. `;` both separates a European CSV's cells and
//! joins items inside a cell (`C1+1; T=2s`), so counting characters picks
//! wrongly; building each reading does not.

use crate::diag::{Code, Diagnostics};
use crate::read::{CsvReading, Grid};

use super::{StepTable, build};

/// The grid of the reading that is the table; `diags` gets that reading's
/// problems, and W005 when another reading is also a valid but different
/// table that leaves no cell unread (the choice is then said, not silent).
pub fn choose_reading(readings: Vec<CsvReading>, diags: &mut Diagnostics) -> Option<Grid> {
    let mut scored: Vec<(Score, CsvReading, Diagnostics, Option<StepTable>)> = readings
        .into_iter()
        .map(|reading| {
            let mut local = reading.diags.clone();
            let table = build(&reading.grid, &mut local);
            let lost_moves = lost_moves(&reading.grid, &local);
            let score = Score {
                no_table: super::frame::find_frame(&reading.grid, &mut Diagnostics::new())
                    .is_none(),
                lost_moves,
                warnings: local.warning_count(),
                errors: local.error_count(),
                spaced_fields: reading.spaced_fields,
                fewer_branches: usize::MAX - table.as_ref().map_or(0, |t| t.branches),
            };
            (score, reading, local, table)
        })
        .collect();
    // The smallest score wins; the earlier (more frequent delimiter) on a tie.
    let best = (0..scored.len()).min_by_key(|&i| (scored[i].0, i))?;
    let (_, chosen, _, chosen_table) = scored.swap_remove(best);
    if let Some(table) = &chosen_table
        && let Some((_, other, _, Some(other_table))) =
            scored.iter().find(|(score, _, diags, table)| {
                score.errors == 0
                    && !diags.iter().any(|d| d.code == Code::W003Ignored)
                    && table.is_some()
            })
        && layout(other_table) != layout(table)
    {
        diags.warning(
            Code::W005Delimiter,
            chosen.grid.sheet_location(),
            format!(
                "read as {}-separated ({} branch(es), {} steps); read as {}-separated it would be another table ({} branch(es), {} steps): quote cells that hold a {} or save the file from a spreadsheet",
                chosen.delimiter_name(),
                table.branches,
                table.steps.len(),
                other.delimiter_name(),
                other_table.branches,
                other_table.steps.len(),
                char::from(other.delimiter).escape_default(),
            ),
        );
    }
    diags.extend(chosen.diags);
    Some(chosen.grid)
}

/// A table found at all first (a wrong delimiter usually lumps each line
/// into one cell), then the fewest moves left in unread cells (a reading
/// that leaves an engineer's `STEP 20,C2+1` behind loses to one that reads
/// it, whatever else that one warns of: labels numbered 10, 20, …, a
/// remarks column), then the fewest cells left unread (warnings), fewest
/// errors, fewest fields that start with a space (Excel never writes one
/// after its delimiter), most branches (a real delimiter gives the table
/// its columns).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct Score {
    no_table: bool,
    lost_moves: usize,
    warnings: usize,
    errors: usize,
    spaced_fields: usize,
    fewer_branches: usize,
}

/// How many of the moves in `grid` sit in cells `diags` reports unread
/// (W003): `STEP 20,C2+1` lumped into one cell by the wrong delimiter
/// holds one.
fn lost_moves(grid: &Grid, diags: &Diagnostics) -> usize {
    let unread: std::collections::BTreeSet<_> = diags
        .iter()
        .filter(|d| d.code == Code::W003Ignored)
        .filter_map(|d| d.location.cell)
        .collect();
    grid.cells
        .iter()
        .filter(|c| unread.contains(&c.pos))
        .filter_map(|c| match &c.value {
            crate::read::CellValue::Text(text) => Some(text),
            _ => None,
        })
        .map(|text| {
            text.split([',', ';', '\t'])
                .filter(|item| crate::cell::looks_like_move(item.trim()))
                .count()
        })
        .sum()
}

/// What the table means, branch by branch.
fn layout(table: &StepTable) -> Vec<Vec<String>> {
    table
        .steps
        .iter()
        .map(|s| (0..table.branches).map(|b| s.cell_text(b)).collect())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn choose(text: &str) -> (u32, Vec<String>) {
        let mut diags = Diagnostics::new();
        let readings = crate::read::read_bytes(
            "t.csv",
            crate::read::Format::Csv,
            text.into(),
            None,
            &mut diags,
        )
        .unwrap()
        .csv_readings;
        let grid = choose_reading(readings, &mut diags).unwrap();
        let branches = grid.cells.iter().map(|c| c.pos.col).max().unwrap_or(0) + 1;
        let all = diags.into_sorted().iter().map(|d| d.to_string()).collect();
        (branches, all)
    }

    #[test]
    fn a_semicolon_inside_a_comma_file_stays_in_its_cell() {
        // One branch: the dwell follows C1+1 in its own branch.
        let (columns, all) = choose(",BRANCH 1\nSTEP 1,C1+1; T=2s\nSTEP 2,C1-0\n");
        assert_eq!(columns, 2, "{all:?}");
        assert!(all.is_empty(), "{all:?}");
        // Bare, one column: the space after ; marks an in-cell separator.
        let (columns, all) = choose("C1+1; T=2s\nC1-0\n");
        assert_eq!(columns, 1);
        assert!(
            all[0].contains("warning[W005]: read as comma-separated"),
            "{all:?}"
        );
    }

    #[test]
    fn a_european_file_is_read_by_its_semicolons() {
        let (columns, all) = choose(";BRANCH 1;BRANCH 2\nSTEP 1;C1+1;T=1,5s\nSTEP 2;C1-0;\n");
        assert_eq!(columns, 3, "{all:?}");
        assert!(all.is_empty(), "{all:?}");
    }
}
