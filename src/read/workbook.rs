//! Workbooks through calamine: the sheets, which of them holds the table,
//! and each filled cell's value.

use std::io::Cursor;

use calamine::{Data, Ods, Range, Reader, Xls, Xlsx, open_workbook_from_rs};

use super::sheet_choice::{
    Region, SheetError, SheetReader, SheetSource, SideSheets, misnamed_side_sheets,
    names_a_side_sheet, pick_table,
};
use super::*;
use crate::diag::{CellPos, Code, Diagnostics, Location};

pub(super) fn read_workbook(
    file: &str,
    format: Format,
    bytes: Vec<u8>,
    wanted: Option<&str>,
    diags: &mut Diagnostics,
) -> Option<Input> {
    let whole_file = Location {
        file: file.to_string(),
        sheet: None,
        cell: None,
    };
    // calamine gives no .ods merges: the guard's pass notes them.
    let ods = (format == Format::Ods).then(|| guard_ods::survey(&bytes, MAX_FILLED_CELLS as u64));
    let ods_oversized = ods.as_ref().and_then(|s| s.oversized.clone());
    if let Some((code, message)) = refusal_before_decoding(format, &bytes, ods_oversized) {
        diags.error(code, whole_file, message);
        return None;
    }
    let mut workbook = open(format, bytes, ods, &whole_file, diags)?;
    let names = workbook.names();
    let read = |workbook: &mut Box<dyn SheetSource>, name: &str, diags: &mut Diagnostics| {
        read_sheet(file, workbook, name, diags)
    };
    let mut side = SideSheets {
        file,
        names: &names,
        workbook: &mut workbook,
        read: &read,
    };
    let settings = side.read(SETTINGS_SHEET, "its settings", Code::E030BadSetting, diags);
    let addresses = side.read(
        ADDRESSES_SHEET,
        "its pinned addresses",
        Code::E035BadPinnedAddress,
        diags,
    );
    misnamed_side_sheets(file, &names, diags);
    let mut passed_over = None;
    let mut table = pick_table(
        &mut workbook,
        &names,
        wanted,
        &whole_file,
        diags,
        &read,
        &mut passed_over,
    );
    let (mut settings, mut addresses) = (settings, addresses);
    for grid in [&mut table, &mut settings, &mut addresses]
        .into_iter()
        .flatten()
    {
        let regions = (grid.sheet.as_deref()).map_or_else(Vec::new, |n| workbook.merged(n));
        refuse_hidden_under_merges(grid, &regions, diags);
    }
    let table = table?;
    // The sheets picking the table read, else each read now.
    let others = match passed_over {
        Some(grids) => grids
            .into_iter()
            .filter(|g| !g.sheet.as_deref().is_some_and(names_a_side_sheet))
            .collect(),
        None => other_sheets(&mut workbook, &names, &table, &read),
    };
    Some(Input {
        table,
        settings,
        addresses,
        csv_readings: Vec::new(),
        others,
    })
}

/// The sheets read as neither the table nor a side sheet (nor one named
/// like a side sheet, E046 already): only looked over for settings written
/// there, so one that cannot be read is left out.
fn other_sheets(
    workbook: &mut Box<dyn SheetSource>,
    names: &[String],
    table: &Grid,
    read: &SheetReader,
) -> Vec<Grid> {
    names
        .iter()
        .filter(|n| Some(n.as_str()) != table.sheet.as_deref() && !names_a_side_sheet(n))
        .filter_map(|name| read(workbook, name, &mut Diagnostics::new()))
        .collect()
}

/// What refuses a workbook before calamine decodes it: one that unpacks
/// too large, or whose structure would make the decoder loop or allocate
/// without bound.
fn refusal_before_decoding(
    format: Format,
    bytes: &[u8],
    ods_oversized: Option<String>,
) -> Option<(Code, String)> {
    if matches!(format, Format::Xlsx | Format::Ods)
        && let Some(unpacked) = unpacked_size(bytes)
        && unpacked > MAX_UNPACKED_BYTES
    {
        return Some((
            Code::E005TooLarge,
            format!(
                "the workbook unpacks to {} MiB; the limit is {} MiB",
                unpacked / (1024 * 1024),
                MAX_UNPACKED_BYTES / (1024 * 1024)
            ),
        ));
    }
    if format == Format::Xlsx
        && let Some(why) = guard_xlsx::impossible_string_count(bytes)
    {
        return Some((
            Code::E002NotAWorkbook,
            format!("the workbook is damaged and could not be decoded ({why})"),
        ));
    }
    if format == Format::Xlsx
        && let Some(why) = guard_xlsx::overlong_text(bytes)
    {
        return Some((Code::E005TooLarge, why));
    }
    if let Some(why) = ods_oversized {
        return Some((Code::E024TableTooLarge, why));
    }
    if format == Format::Xls
        && let Some(refusal) = guard_ole::unsafe_to_decode(bytes)
    {
        return Some(match refusal {
            guard_ole::Refusal::Damaged(why) => (
                Code::E002NotAWorkbook,
                format!("the workbook is damaged and could not be decoded ({why})"),
            ),
            guard_ole::Refusal::TooLarge(why) => (Code::E024TableTooLarge, why),
        });
    }
    None
}

/// The workbook opened by calamine's reader of its format (E002 when it
/// cannot be).
fn open(
    format: Format,
    bytes: Vec<u8>,
    ods: Option<guard_ods::Survey>,
    whole_file: &Location,
    diags: &mut Diagnostics,
) -> Option<Box<dyn SheetSource>> {
    let recalculate = format == Format::Xlsx && guard_xlsx::values_to_recalculate(&bytes);
    let cursor = Cursor::new(bytes);
    let opened: Result<Box<dyn SheetSource>, String> = match format {
        Format::Xlsx => open_workbook_from_rs::<Xlsx<_>, _>(cursor)
            .map(|xlsx| Box::new(XlsxSource { xlsx, recalculate }) as Box<dyn SheetSource>)
            .map_err(|e| e.to_string()),
        Format::Xls => open_workbook_from_rs::<Xls<_>, _>(cursor)
            .map(|w| Box::new(w) as Box<dyn SheetSource>)
            .map_err(|e| e.to_string()),
        Format::Ods => open_workbook_from_rs::<Ods<_>, _>(cursor)
            .map(|ods_reader| {
                let survey = ods.unwrap_or_default();
                Box::new(OdsSource {
                    ods: ods_reader,
                    survey,
                }) as Box<dyn SheetSource>
            })
            .map_err(|e| e.to_string()),
        Format::Csv => Err("internal: CSV is not a workbook".to_string()),
    };
    match opened {
        Ok(w) => Some(w),
        Err(err) => {
            diags.error(
                Code::E002NotAWorkbook,
                whole_file.clone(),
                format!("not a readable {} workbook ({err})", format_name(format)),
            );
            None
        }
    }
}

/// One sheet's grid, or the error that says why it cannot be read.
pub(super) fn read_sheet(
    file: &str,
    workbook: &mut Box<dyn SheetSource>,
    name: &str,
    diags: &mut Diagnostics,
) -> Option<Grid> {
    match workbook.grid(file, name) {
        Ok(grid) => Some(grid),
        Err(err) => {
            let (code, message) = match err {
                SheetError::Unreadable(why) => (
                    Code::E002NotAWorkbook,
                    format!("sheet could not be read ({why})"),
                ),
                SheetError::TooManyCells => (
                    Code::E024TableTooLarge,
                    format!(
                        "the sheet has more than {MAX_FILLED_CELLS} filled cells; a table of 10,000 steps × 256 branches has fewer"
                    ),
                ),
            };
            let sheet = Location {
                file: file.to_string(),
                sheet: Some(name.to_string()),
                cell: None,
            };
            diags.error(code, sheet, message);
            None
        }
    }
}

fn hidden_sheets(sheets: &[calamine::Sheet]) -> Vec<String> {
    sheets
        .iter()
        .filter(|s| s.visible != calamine::SheetVisible::Visible)
        .map(|s| s.name.clone())
        .collect()
}

/// `.xlsx` is read cell by cell as the sheet's XML streams past: memory
/// follows the filled cells, not the rectangle around them (a sheet with
/// cells at A1 and XFD1048576 would otherwise need 17 billion empty cells).
/// An `.xlsx` workbook, and whether it asks to be calculated again when
/// opened: its formulas' saved values are then placeholders.
struct XlsxSource {
    xlsx: Xlsx<Cursor<Vec<u8>>>,
    recalculate: bool,
}

impl SheetSource for XlsxSource {
    fn names(&self) -> Vec<String> {
        self.xlsx.sheet_names()
    }

    fn hidden(&self) -> Vec<String> {
        hidden_sheets(self.xlsx.sheets_metadata())
    }

    fn merged(&mut self, name: &str) -> Vec<Region> {
        let merges = self
            .xlsx
            .merge_cells_by_sheet_name(name)
            .unwrap_or_default();
        merges.iter().map(|d| (d.start, d.end)).collect()
    }

    fn grid(&mut self, file: &str, name: &str) -> Result<Grid, SheetError> {
        let unreadable = |e: calamine::XlsxError| SheetError::Unreadable(e.to_string());
        let recalculate = self.recalculate;
        let mut reader = self.xlsx.worksheet_cells_reader(name).map_err(unreadable)?;
        let mut cells = Vec::new();
        while let Some(cell) = reader
            .next_cell_with_formula_metadata()
            .map_err(unreadable)?
        {
            let (row, col) = cell.pos;
            let data: Data = cell.value.into();
            // A formula saved by a program that never computed it has no
            // value; read as empty, what the engineer wrote would vanish.
            // One saved with the placeholder 0 for a value (XlsxWriter's),
            // in a workbook that asks to be calculated when opened, is no
            // better: Excel shows what the formula computes, never the 0.
            let placeholder = matches!(data, Data::Int(0)) || data == Data::Float(0.0);
            let value = match (&data, cell.formula) {
                (Data::Empty, Some(formula)) => Some(CellValue::Uncomputed(formula_text(formula))),
                (_, Some(formula)) if recalculate && placeholder => {
                    Some(CellValue::Uncomputed(formula_text(formula)))
                }
                _ => cell_value(&data),
            };
            if let Some(value) = value {
                if cells.len() == MAX_FILLED_CELLS {
                    return Err(SheetError::TooManyCells);
                }
                cells.push(GridCell {
                    pos: CellPos::new(row, col),
                    value,
                });
            }
        }
        Ok(Grid {
            file: file.to_string(),
            sheet: Some(name.to_string()),
            cells,
            hidden: Vec::new(),
        })
    }
}

/// The text of a formula as the cell holds it, for messages.
fn formula_text(formula: calamine::XlsxFormulaMetadata) -> String {
    match formula {
        calamine::XlsxFormulaMetadata::Normal { formula }
        | calamine::XlsxFormulaMetadata::Shared { formula, .. } => format!("={formula}"),
        _ => "=… (a formula shared with another cell)".to_string(),
    }
}

/// A value under a merged cell but its first is hidden in Excel and
/// LibreOffice: read, the program would do what nobody sees in the table;
/// dropped, what the engineer wrote would be lost. E049 at each, and the
/// cell leaves the grid (no second error about it).
fn refuse_hidden_under_merges(grid: &mut Grid, regions: &[Region], diags: &mut Diagnostics) {
    if regions.is_empty() {
        return;
    }
    let under = |pos: CellPos| {
        regions.iter().find(|((r0, c0), (r1, c1))| {
            (*r0..=*r1).contains(&pos.row)
                && (*c0..=*c1).contains(&pos.col)
                && (pos.row, pos.col) != (*r0, *c0)
        })
    };
    let mut hidden = Vec::new();
    let mut kept = Vec::with_capacity(grid.cells.len());
    for cell in std::mem::take(&mut grid.cells) {
        match under(cell.pos) {
            Some(&((r0, c0), (r1, c1))) => {
                hidden.push((cell.pos, cell.value.describe(), (r0, c0), (r1, c1)));
                grid.hidden.push(cell);
            }
            None => kept.push(cell),
        }
    }
    grid.cells = kept;
    for (pos, value, first, last) in hidden {
        let first = CellPos::new(first.0, first.1).a1();
        let last = CellPos::new(last.0, last.1).a1();
        diags.error(
            Code::E049HiddenUnderMerge,
            grid.location(pos),
            format!(
                "{value} lies under the merged cell {first}:{last}, where the spreadsheet shows only {first}'s value: steptable would read what nobody sees on the sheet; unmerge the cells, then keep or clear it"
            ),
        );
    }
}

/// `.xls` and `.ods`: calamine decodes these whole; their grids are small
/// (65,536 × 256 for `.xls`).
macro_rules! whole_sheet_source {
    ($reader:ty, $merged:expr) => {
        impl SheetSource for $reader {
            fn merged(&mut self, name: &str) -> Vec<Region> {
                $merged(self, name)
            }

            fn names(&self) -> Vec<String> {
                self.sheet_names()
            }

            fn hidden(&self) -> Vec<String> {
                hidden_sheets(self.sheets_metadata())
            }

            fn grid(&mut self, file: &str, name: &str) -> Result<Grid, SheetError> {
                let range = self
                    .worksheet_range(name)
                    .map_err(|e| SheetError::Unreadable(e.to_string()))?;
                let mut grid = grid_from_range(file, name, &range);
                // A formula saved without its value reads as an empty cell
                // in the values: found among the formulas.
                if let Ok(formulas) = self.worksheet_formula(name) {
                    add_uncomputed(&mut grid, &formulas);
                }
                Ok(grid)
            }
        }
    };
}
whole_sheet_source!(Xls<Cursor<Vec<u8>>>, |xls: &mut Xls<_>, name: &str| {
    let merges = xls.merge_cells_by_sheet_name(name).unwrap_or_default();
    merges.iter().map(|d| (d.start, d.end)).collect()
});
whole_sheet_source!(Ods<Cursor<Vec<u8>>>, |_: &mut Ods<_>, _: &str| Vec::new());

/// An `.ods` workbook and what the guard's pass over it found, which
/// calamine does not give: its merges, and which formulas were saved with a
/// value (one that computes `""` reads as empty, yet was computed).
struct OdsSource {
    ods: Ods<Cursor<Vec<u8>>>,
    survey: guard_ods::Survey,
}

impl SheetSource for OdsSource {
    fn names(&self) -> Vec<String> {
        SheetSource::names(&self.ods)
    }

    fn hidden(&self) -> Vec<String> {
        SheetSource::hidden(&self.ods)
    }

    fn grid(&mut self, file: &str, name: &str) -> Result<Grid, SheetError> {
        let mut grid = SheetSource::grid(&mut self.ods, file, name)?;
        if let Some(computed) = self.survey.computed.get(name) {
            grid.cells.retain(|c| {
                !matches!(c.value, CellValue::Uncomputed(_))
                    || !computed.contains(&(c.pos.row, c.pos.col))
            });
        }
        Ok(grid)
    }

    fn merged(&mut self, name: &str) -> Vec<Region> {
        self.survey.merged.get(name).cloned().unwrap_or_default()
    }
}

/// Most filled cells read from one sheet: a full table (10,000 steps × 256
/// branches) with its labels fits; a sheet of millions of cells is refused.
pub const MAX_FILLED_CELLS: usize = 3_000_000;

/// What a filled cell holds; `None` for an empty or blank one.
fn cell_value(data: &Data) -> Option<CellValue> {
    Some(match data {
        Data::Empty => return None,
        Data::String(s) => {
            if s.trim().is_empty() {
                return None;
            }
            CellValue::Text(crate::cell::composed(s.clone()))
        }
        Data::Int(i) => CellValue::Number(*i as f64),
        Data::Float(f) => CellValue::Number(*f),
        Data::Bool(b) => CellValue::Bool(*b),
        Data::DateTime(dt) => CellValue::Date(date_text(dt)),
        Data::DateTimeIso(s) | Data::DurationIso(s) => CellValue::Date(s.clone()),
        Data::Error(e) => CellValue::Error(e.to_string()),
    })
}

/// A date cell as the engineer saw it (`2024-01-03`, `12:30:00`,
/// `2024-01-03 08:15:00`), not as the serial number calamine's `Display`
/// prints (45294).
fn date_text(dt: &calamine::ExcelDateTime) -> String {
    let (year, month, day, hour, minute, second, _) = dt.to_ymd_hms_milli();
    let time = format!("{hour:02}:{minute:02}:{second:02}");
    let serial = dt.as_f64();
    if dt.is_duration() && serial.is_finite() {
        // A duration may pass 24 hours: its hours are counted whole.
        let seconds = (serial * 86_400.0).round().clamp(0.0, 1e12) as u64;
        format!(
            "{}:{:02}:{:02}",
            seconds / 3600,
            seconds / 60 % 60,
            seconds % 60
        )
    } else if (0.0..1.0).contains(&serial) {
        time
    } else if (hour, minute, second) == (0, 0, 0) {
        format!("{year:04}-{month:02}-{day:02}")
    } else {
        format!("{year:04}-{month:02}-{day:02} {time}")
    }
}

/// Each formula of `formulas` at a cell `grid` holds no value of, as
/// [`CellValue::Uncomputed`]: a program that does not calculate saved it.
fn add_uncomputed(grid: &mut Grid, formulas: &Range<String>) {
    let (row0, col0) = formulas.start().unwrap_or((0, 0));
    let valued: std::collections::HashSet<CellPos> = grid.cells.iter().map(|c| c.pos).collect();
    for (r, c, formula) in formulas.used_cells() {
        let pos = CellPos::new(row0 + r as u32, col0 + c as u32);
        if formula.trim().is_empty() || valued.contains(&pos) {
            continue;
        }
        let text = formula.strip_prefix("of:").unwrap_or(formula);
        let text = match text.starts_with('=') {
            true => text.to_string(),
            false => format!("={text}"),
        };
        grid.cells.push(GridCell {
            pos,
            value: CellValue::Uncomputed(text),
        });
    }
    grid.cells.sort_by_key(|c| (c.pos.row, c.pos.col));
}

fn grid_from_range(file: &str, sheet: &str, range: &Range<Data>) -> Grid {
    // calamine's Range starts at its first non-empty cell: add the start back.
    let (row0, col0) = range.start().unwrap_or((0, 0));
    let mut cells = Vec::new();
    for (r, c, data) in range.used_cells() {
        let Some(value) = cell_value(data) else {
            continue;
        };
        cells.push(GridCell {
            pos: CellPos::new(row0 + r as u32, col0 + c as u32),
            value,
        });
    }
    Grid {
        file: file.to_string(),
        sheet: Some(sheet.to_string()),
        cells,
        hidden: Vec::new(),
    }
}
