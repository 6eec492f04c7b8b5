//! Workbooks through calamine: the sheets, which of them holds the table,
//! and each filled cell's value.

use std::io::Cursor;

use calamine::{Data, Ods, Range, Reader, Xls, Xlsx, open_workbook_from_rs};

use super::*;
use crate::cell::{header_kind, looks_like_move};
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
    if let Some((code, message)) = refusal_before_decoding(format, &bytes) {
        diags.error(code, whole_file, message);
        return None;
    }
    let mut workbook = open(format, bytes, &whole_file, diags)?;
    let names = workbook.names();
    let mut side = SideSheets {
        file,
        names: &names,
        workbook: &mut workbook,
    };
    let settings = side.read(SETTINGS_SHEET, "its settings", Code::E030BadSetting, diags);
    let addresses = side.read(
        ADDRESSES_SHEET,
        "its pinned addresses",
        Code::E035BadPinnedAddress,
        diags,
    );
    let read = |workbook: &mut Box<dyn SheetSource>, name: &str, diags: &mut Diagnostics| {
        read_sheet(file, workbook, name, diags)
    };
    let table = pick_table(&mut workbook, &names, wanted, &whole_file, diags, &read)?;
    Some(Input {
        table,
        settings,
        addresses,
        csv_readings: Vec::new(),
    })
}

/// What refuses a workbook before calamine decodes it: one that unpacks
/// too large, or whose structure would make the decoder loop or allocate
/// without bound.
fn refusal_before_decoding(format: Format, bytes: &[u8]) -> Option<(Code, String)> {
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
    if format == Format::Ods
        && let Some(why) = guard_ods::oversized_sheet(bytes, MAX_FILLED_CELLS as u64)
    {
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
    whole_file: &Location,
    diags: &mut Diagnostics,
) -> Option<Box<dyn SheetSource>> {
    let cursor = Cursor::new(bytes);
    let opened: Result<Box<dyn SheetSource>, String> = match format {
        Format::Xlsx => open_workbook_from_rs::<Xlsx<_>, _>(cursor)
            .map(|w| Box::new(w) as Box<dyn SheetSource>)
            .map_err(|e| e.to_string()),
        Format::Xls => open_workbook_from_rs::<Xls<_>, _>(cursor)
            .map(|w| Box::new(w) as Box<dyn SheetSource>)
            .map_err(|e| e.to_string()),
        Format::Ods => open_workbook_from_rs::<Ods<_>, _>(cursor)
            .map(|w| Box::new(w) as Box<dyn SheetSource>)
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
fn read_sheet(
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

/// The side sheets (SETTINGS, ADDRESSES) of one workbook.
struct SideSheets<'a> {
    file: &'a str,
    names: &'a [String],
    workbook: &'a mut Box<dyn SheetSource>,
}

impl SideSheets<'_> {
    /// A side sheet is found by its name in any case and without the
    /// spaces around it; one that is hidden is used all the same, and said
    /// so. Two sheets that both match (`SETTINGS` and `Settings `) are an
    /// error naming both: reading one would drop the other's rows without a
    /// word. `code` is the code of that sheet's rows.
    fn read(
        &mut self,
        wanted: &str,
        used: &str,
        code: Code,
        diags: &mut Diagnostics,
    ) -> Option<Grid> {
        let names = self.names;
        let matching: Vec<&String> = names.iter().filter(|n| is_side(n, wanted)).collect();
        let name = (*matching.first()?).clone();
        if matching.len() > 1 {
            let quoted: Vec<String> = matching.iter().map(|n| format!("\"{n}\"")).collect();
            let whole_file = Location {
                file: self.file.to_string(),
                sheet: None,
                cell: None,
            };
            diags.error(
                code,
                whole_file,
                format!(
                    "{} sheets are each the {wanted} sheet ({}: names are compared without case and the spaces around them); keep one, or merge their rows into one",
                    matching.len(),
                    quoted.join(", ")
                ),
            );
            return None;
        }
        let grid = read_sheet(self.file, self.workbook, &name, diags)?;
        if self.workbook.hidden().contains(&name) {
            diags.warning(
                Code::W004SheetChoice,
                grid.sheet_location(),
                format!("the {wanted} sheet is hidden but {used} are used"),
            );
        }
        Some(grid)
    }
}

/// Whether the sheet `name` is the side sheet `wanted` (SETTINGS,
/// ADDRESSES): the one comparison the reader makes of a side sheet's name.
fn is_side(name: &str, wanted: &str) -> bool {
    name.trim().eq_ignore_ascii_case(wanted)
}

/// The side sheet `name` is, if any: read for its settings or pins, never
/// as the table.
fn side_sheet_of(name: &str) -> Option<&'static str> {
    [SETTINGS_SHEET, ADDRESSES_SHEET]
        .into_iter()
        .find(|side| is_side(name, side))
}

type SheetReader<'a> =
    dyn Fn(&mut Box<dyn SheetSource>, &str, &mut Diagnostics) -> Option<Grid> + 'a;

/// The sheet holding the step table: the one asked for (not the SETTINGS or
/// ADDRESSES sheet: E004); else the one named
/// SEQUENTIAL CONTROL DESCRIPTION unless it is hidden; else the visible sheet
/// that best holds a table (BRANCH/STEP headers first, then the most moves;
/// the side sheets are not candidates),
/// and a hidden one only when no visible sheet holds a table. Any choice
/// among several, or of a hidden sheet, is said (W004).
fn pick_table(
    workbook: &mut Box<dyn SheetSource>,
    names: &[String],
    wanted: Option<&str>,
    whole_file: &Location,
    diags: &mut Diagnostics,
    read_sheet: &SheetReader,
) -> Option<Grid> {
    let whole_file = whole_file.clone();
    let find = |wanted: &str| {
        names
            .iter()
            .find(|n| n.trim().eq_ignore_ascii_case(wanted.trim()))
    };
    if let Some(wanted) = wanted {
        let name = asked_sheet(names, wanted, &whole_file, diags)?;
        return read_sheet(workbook, name, diags);
    }
    let hidden = workbook.hidden();
    let is_hidden = |name: &str| hidden.iter().any(|h| h == name);
    if let Some(name) = find(TABLE_SHEET)
        && !is_hidden(name)
    {
        return read_sheet(workbook, name, diags);
    }
    // A sheet that could not be read may be the one with the table: say why.
    let mut unread = Diagnostics::new();
    let mut candidates: Vec<(TableScore, Grid)> = Vec::new();
    // The side sheets are read as such, never as the table.
    for name in names.iter().filter(|n| side_sheet_of(n).is_none()) {
        let mut local = Diagnostics::new();
        match read_sheet(workbook, name, &mut local) {
            Some(grid) => {
                if let Some(score) = table_score(&grid, is_hidden(name)) {
                    candidates.push((score, grid));
                }
            }
            None => unread.extend(local),
        }
    }
    // The best score wins; the first sheet on a tie.
    let best = candidates
        .iter()
        .enumerate()
        .max_by(|(i, (a, _)), (j, (b, _))| a.cmp(b).then(j.cmp(i)))
        .map(|(i, _)| i);
    let Some(best) = best else {
        diags.extend(unread);
        diags.error(
            Code::E003NoTable,
            whole_file,
            format!(
                "no step table found: no sheet named \"{TABLE_SHEET}\" and no sheet holding moves such as C1+1"
            ),
        );
        return None;
    };
    let (score, grid) = candidates.swap_remove(best);
    say_choice(&grid, score, &candidates, find(TABLE_SHEET), diags);
    Some(grid)
}

/// The sheet `--sheet` names (E004 when there is none, or when it is a
/// side sheet).
fn asked_sheet<'n>(
    names: &'n [String],
    wanted: &str,
    whole_file: &Location,
    diags: &mut Diagnostics,
) -> Option<&'n String> {
    let whole_file = whole_file.clone();
    let Some(name) = names
        .iter()
        .find(|n| n.trim().eq_ignore_ascii_case(wanted.trim()))
    else {
        diags.error(
            Code::E004NoSuchSheet,
            whole_file,
            format!(
                "no sheet named \"{wanted}\" (the workbook has: {})",
                names.join(", ")
            ),
        );
        return None;
    };
    // The SETTINGS or ADDRESSES sheet is read as such already: read as
    // the table too, its cells would be both settings and moves, and
    // one reading would call the other's cells unread.
    if let Some(side) = side_sheet_of(name) {
        let tables: Vec<&str> = names
            .iter()
            .filter(|n| side_sheet_of(n).is_none())
            .map(String::as_str)
            .collect();
        diags.error(
            Code::E004NoSuchSheet,
            whole_file,
            format!(
                "\"{name}\" is the {side} sheet, read for the table's {}, not a step table; name the sheet that holds the table with --sheet (the other sheets: {})",
                if side == SETTINGS_SHEET { "settings" } else { "pinned addresses" },
                if tables.is_empty() { "none".to_string() } else { tables.join(", ") }
            ),
        );
        return None;
    }
    Some(name)
}

/// W004 when the table's sheet was chosen among several, or is hidden.
fn say_choice(
    grid: &Grid,
    score: TableScore,
    candidates: &[(TableScore, Grid)],
    table_sheet: Option<&String>,
    diags: &mut Diagnostics,
) {
    let others: Vec<String> = candidates
        .iter()
        .map(|(s, g)| {
            let name = g.sheet.clone().unwrap_or_default();
            if s.visible {
                name
            } else {
                format!("{name} (hidden)")
            }
        })
        .collect();
    let chosen = grid.sheet.clone().unwrap_or_default();
    let mut why = Vec::new();
    if let Some(name) = table_sheet {
        why.push(format!("the sheet \"{name}\" is hidden"));
    }
    if !score.visible {
        why.push(format!(
            "\"{chosen}\" is hidden but no visible sheet holds a table"
        ));
    }
    if !others.is_empty() {
        why.push(format!(
            "other sheets also hold moves: {}",
            others.join(", ")
        ));
    }
    if !why.is_empty() {
        diags.warning(
            Code::W004SheetChoice,
            grid.sheet_location(),
            format!(
                "the table was read from sheet \"{chosen}\": {}; choose another with --sheet",
                why.join("; ")
            ),
        );
    }
}

/// How well a sheet holds a step table; `None` when it holds none.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct TableScore {
    visible: bool,
    /// BRANCH n / STEP n headers: a legend of example moves has none.
    headers: bool,
    moves: usize,
}

fn table_score(grid: &Grid, hidden: bool) -> Option<TableScore> {
    let mut headers = false;
    let mut moves = 0;
    for cell in &grid.cells {
        if let CellValue::Text(t) = &cell.value {
            headers |= header_kind(t).is_some();
            moves += usize::from(looks_like_move(t));
        }
    }
    (headers || moves > 0).then_some(TableScore {
        visible: !hidden,
        headers,
        moves,
    })
}

/// The two things we need from any calamine reader, object-safe.
trait SheetSource {
    fn names(&self) -> Vec<String>;
    /// The names of hidden sheets (also "very hidden" ones).
    fn hidden(&self) -> Vec<String>;
    /// The filled cells of one sheet.
    fn grid(&mut self, file: &str, name: &str) -> Result<Grid, SheetError>;
}

fn hidden_sheets(sheets: &[calamine::Sheet]) -> Vec<String> {
    sheets
        .iter()
        .filter(|s| s.visible != calamine::SheetVisible::Visible)
        .map(|s| s.name.clone())
        .collect()
}

/// Why a sheet could not be read.
enum SheetError {
    /// calamine could not decode it.
    Unreadable(String),
    /// More than [`MAX_FILLED_CELLS`] filled cells.
    TooManyCells,
}

/// `.xlsx` is read cell by cell as the sheet's XML streams past: memory
/// follows the filled cells, not the rectangle around them (a sheet with
/// cells at A1 and XFD1048576 would otherwise need 17 billion empty cells).
impl SheetSource for Xlsx<Cursor<Vec<u8>>> {
    fn names(&self) -> Vec<String> {
        self.sheet_names()
    }

    fn hidden(&self) -> Vec<String> {
        hidden_sheets(self.sheets_metadata())
    }

    fn grid(&mut self, file: &str, name: &str) -> Result<Grid, SheetError> {
        let unreadable = |e: calamine::XlsxError| SheetError::Unreadable(e.to_string());
        let mut reader = self.worksheet_cells_reader(name).map_err(unreadable)?;
        let mut cells = Vec::new();
        while let Some(cell) = reader
            .next_cell_with_formula_metadata()
            .map_err(unreadable)?
        {
            let (row, col) = cell.pos;
            let data: Data = cell.value.into();
            // A formula saved by a program that never computed it has no
            // value; read as empty, what the engineer wrote would vanish.
            let value = match (&data, cell.formula) {
                (Data::Empty, Some(formula)) => Some(CellValue::Uncomputed(formula_text(formula))),
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
        })
    }
}

/// The text of a formula as the cell holds it, for messages.
fn formula_text(formula: calamine::XlsxFormulaMetadata) -> String {
    match formula {
        calamine::XlsxFormulaMetadata::Normal { formula }
        | calamine::XlsxFormulaMetadata::Shared { formula, .. } => format!("={formula}"),
        _ => "a shared formula".to_string(),
    }
}

/// `.xls` and `.ods`: calamine decodes these whole; their grids are small
/// (65,536 × 256 for `.xls`).
macro_rules! whole_sheet_source {
    ($reader:ty) => {
        impl SheetSource for $reader {
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
                Ok(grid_from_range(file, name, &range))
            }
        }
    };
}
whole_sheet_source!(Xls<Cursor<Vec<u8>>>);
whole_sheet_source!(Ods<Cursor<Vec<u8>>>);

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
            CellValue::Text(s.clone())
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
    }
}
