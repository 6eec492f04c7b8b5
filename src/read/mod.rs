//! Reading: file bytes → one sheet as a grid of cells with absolute positions.
//! Workbooks (`.xlsx`, `.xlsm`, `.xls`, `.ods`) go through calamine; CSV is
//! decoded here (UTF-8 with or without BOM, UTF-16 with BOM; `,` `;` or tab).

mod csv;
// Guards in front of calamine's readers, against files that would make it
// allocate without bound.
mod guard_ods;
mod guard_ole;
mod guard_xlsx;
pub use csv::CsvReading;
use std::io::Cursor;
use std::path::Path;

use calamine::{Data, Ods, Range, Reader, Xls, Xlsx, open_workbook_from_rs};

use crate::cell::{header_kind, looks_like_move};
use crate::diag::{CellPos, Code, Diagnostics, Location};

/// Largest input file read, in bytes.
pub const MAX_FILE_BYTES: u64 = 64 * 1024 * 1024;
/// Largest size a zipped workbook (.xlsx, .xlsm, .ods) may unpack to.
pub const MAX_UNPACKED_BYTES: u64 = 256 * 1024 * 1024;

/// The sheet name of the published method's table.
pub const TABLE_SHEET: &str = "SEQUENTIAL CONTROL DESCRIPTION";

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
            CellValue::Date(d) => format!("the date {d}"),
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

/// The sheet name of the engineer's settings, when a workbook has one.
pub const SETTINGS_SHEET: &str = "SETTINGS";

/// What was read from one input file: the step table's sheet and, for a
/// workbook that has one, its SETTINGS sheet.
#[derive(Debug, Clone, PartialEq)]
pub struct Input {
    pub table: Grid,
    pub settings: Option<Grid>,
    /// A CSV file's readings, one per delimiter that could be meant, when
    /// there is more than one: the table decides which is the table.
    pub csv_readings: Vec<CsvReading>,
}

/// Which reader a file needs, decided by its extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Xlsx,
    Xls,
    Ods,
    Csv,
}

impl Format {
    /// The format for a file name, or `None` for an extension we do not read.
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "xlsx" | "xlsm" => Some(Format::Xlsx),
            "xls" => Some(Format::Xls),
            "ods" => Some(Format::Ods),
            "csv" | "txt" | "tsv" => Some(Format::Csv),
            _ => None,
        }
    }
}

/// Reads the file at `path` and returns the sheet holding the step table.
/// Problems go to `diags`; `None` means nothing usable was read.
pub fn read_path(path: &Path, sheet: Option<&str>, diags: &mut Diagnostics) -> Option<Input> {
    let file = display_name(path);
    let whole_file = Location {
        file: file.clone(),
        sheet: None,
        cell: None,
    };
    let Some(format) = Format::from_path(path) else {
        diags.error(
            Code::E002NotAWorkbook,
            whole_file,
            "unknown file type (expected .xlsx, .xlsm, .xls, .ods or .csv)",
        );
        return None;
    };
    match std::fs::metadata(path) {
        Ok(meta) if meta.len() > MAX_FILE_BYTES => {
            diags.error(
                Code::E005TooLarge,
                whole_file,
                format!(
                    "file is {} MiB; the limit is {} MiB",
                    meta.len() / (1024 * 1024),
                    MAX_FILE_BYTES / (1024 * 1024)
                ),
            );
            return None;
        }
        Ok(meta) if meta.is_dir() => {
            diags.error(Code::E001Unreadable, whole_file, "is a folder, not a file");
            return None;
        }
        _ => {}
    }
    match std::fs::read(path) {
        Ok(bytes) => read_bytes(&file, format, bytes, sheet, diags),
        Err(err) => {
            diags.error(
                Code::E001Unreadable,
                whole_file,
                format!("cannot read file: {err}"),
            );
            None
        }
    }
}

/// The file name shown in messages: the name as given, without `./`.
pub fn display_name(path: &Path) -> String {
    let shown = path.to_string_lossy();
    shown.strip_prefix("./").unwrap_or(&shown).to_string()
}

/// Reads an in-memory file of a known format. Never panics, whatever the bytes.
pub fn read_bytes(
    file: &str,
    format: Format,
    bytes: Vec<u8>,
    sheet: Option<&str>,
    diags: &mut Diagnostics,
) -> Option<Input> {
    match format {
        Format::Csv => {
            let mut readings = csv::read_csv(file, &bytes, diags)?;
            if readings.len() == 1 {
                let only = readings.remove(0);
                diags.extend(only.diags);
                return Some(Input {
                    table: only.grid,
                    settings: None,
                    csv_readings: Vec::new(),
                });
            }
            Some(Input {
                table: readings[0].grid.clone(),
                settings: None,
                csv_readings: readings,
            })
        }
        _ => {
            // calamine is a large parser of untrusted zip and OLE data; a panic
            // deep inside it (fuzzing found one in its OLE reader) must become
            // a diagnostic, not a crash, and not a backtrace on the terminal.
            let result = quietly(|| {
                let mut local = Diagnostics::new();
                let grid = read_workbook(file, format, bytes, sheet, &mut local);
                (grid, local)
            });
            match result {
                Ok((grid, local)) => {
                    diags.extend(local);
                    grid
                }
                Err(_) => {
                    diags.error(
                        Code::E002NotAWorkbook,
                        Location {
                            file: file.to_string(),
                            sheet: None,
                            cell: None,
                        },
                        "the workbook is damaged and could not be decoded",
                    );
                    None
                }
            }
        }
    }
}

thread_local! {
    /// Set while this thread decodes a workbook: its panics are caught and
    /// reported as E002, so the panic hook stays silent about them.
    static DECODING: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs `work`, turning a panic into `Err` without printing it. The panic
/// hook is wrapped once per process; panics outside `quietly` still print.
fn quietly<T>(work: impl FnOnce() -> T) -> std::thread::Result<T> {
    static HOOK: std::sync::Once = std::sync::Once::new();
    HOOK.call_once(|| {
        let previous = std::panic::take_hook();
        std::panic::set_hook(Box::new(move |info| {
            if !DECODING.with(|d| d.get()) {
                previous(info);
            }
        }));
    });
    DECODING.with(|d| d.set(true));
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(work));
    DECODING.with(|d| d.set(false));
    result
}

fn read_workbook(
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
    if matches!(format, Format::Xlsx | Format::Ods)
        && let Some(unpacked) = unpacked_size(&bytes)
        && unpacked > MAX_UNPACKED_BYTES
    {
        diags.error(
            Code::E005TooLarge,
            whole_file,
            format!(
                "the workbook unpacks to {} MiB; the limit is {} MiB",
                unpacked / (1024 * 1024),
                MAX_UNPACKED_BYTES / (1024 * 1024)
            ),
        );
        return None;
    }
    if format == Format::Xlsx
        && let Some(why) = guard_xlsx::impossible_string_count(&bytes)
    {
        diags.error(
            Code::E002NotAWorkbook,
            whole_file.clone(),
            format!("the workbook is damaged and could not be decoded ({why})"),
        );
        return None;
    }
    if format == Format::Xlsx
        && let Some(why) = guard_xlsx::overlong_text(&bytes)
    {
        diags.error(Code::E005TooLarge, whole_file.clone(), why);
        return None;
    }
    if format == Format::Ods
        && let Some(why) = guard_ods::oversized_sheet(&bytes, MAX_FILLED_CELLS as u64)
    {
        diags.error(Code::E024TableTooLarge, whole_file, why);
        return None;
    }
    if format == Format::Xls
        && let Some(refusal) = guard_ole::unsafe_to_decode(&bytes)
    {
        let (code, message) = match refusal {
            guard_ole::Refusal::Damaged(why) => (
                Code::E002NotAWorkbook,
                format!("the workbook is damaged and could not be decoded ({why})"),
            ),
            guard_ole::Refusal::TooLarge(why) => (Code::E024TableTooLarge, why),
        };
        diags.error(code, whole_file, message);
        return None;
    }
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
    let mut workbook = match opened {
        Ok(w) => w,
        Err(err) => {
            diags.error(
                Code::E002NotAWorkbook,
                whole_file,
                format!("not a readable {} workbook ({err})", format_name(format)),
            );
            return None;
        }
    };
    let names = workbook.names();
    let read_sheet = |workbook: &mut Box<dyn SheetSource>, name: &str, diags: &mut Diagnostics| {
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
    };

    let settings_name = names
        .iter()
        .find(|n| n.trim().eq_ignore_ascii_case(SETTINGS_SHEET))
        .cloned();
    let settings = settings_name.and_then(|name| {
        let grid = read_sheet(&mut workbook, &name, diags)?;
        if workbook.hidden().contains(&name) {
            diags.warning(
                Code::W004SheetChoice,
                grid.sheet_location(),
                "the SETTINGS sheet is hidden but its settings are used",
            );
        }
        Some(grid)
    });
    let table = pick_table(
        &mut workbook,
        &names,
        wanted,
        &whole_file,
        diags,
        &read_sheet,
    )?;
    Some(Input {
        table,
        settings,
        csv_readings: Vec::new(),
    })
}

type SheetReader<'a> =
    dyn Fn(&mut Box<dyn SheetSource>, &str, &mut Diagnostics) -> Option<Grid> + 'a;

/// The sheet holding the step table: the one asked for; else the one named
/// SEQUENTIAL CONTROL DESCRIPTION unless it is hidden; else the visible sheet
/// that best holds a table (BRANCH/STEP headers first, then the most moves),
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
        let Some(name) = find(wanted) else {
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
    for name in names {
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
    if let Some(name) = find(TABLE_SHEET) {
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
    Some(grid)
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

/// The total unpacked size a zip archive declares, if it is one. A zip bomb
/// declares its size honestly or fails its checks while being unpacked.
fn unpacked_size(bytes: &[u8]) -> Option<u64> {
    let archive = zip::ZipArchive::new(Cursor::new(bytes)).ok()?;
    Some(archive.decompressed_size()?.min(u64::MAX as u128) as u64)
}

fn format_name(format: Format) -> &'static str {
    match format {
        Format::Xlsx => ".xlsx",
        Format::Xls => ".xls",
        Format::Ods => ".ods",
        Format::Csv => ".csv",
    }
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
        Data::DateTime(dt) => CellValue::Date(dt.to_string()),
        Data::DateTimeIso(s) | Data::DurationIso(s) => CellValue::Date(s.clone()),
        Data::Error(e) => CellValue::Error(e.to_string()),
    })
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

#[cfg(test)]
mod tests {
    use super::*;

    fn text_at(grid: &Grid, row: u32, col: u32) -> Option<&str> {
        grid.cells.iter().find_map(|c| match &c.value {
            CellValue::Text(t) if c.pos == CellPos::new(row, col) => Some(t.as_str()),
            _ => None,
        })
    }

    #[test]
    fn csv_delimiters_and_bom_are_detected() {
        for (bytes, _) in [
            (
                b"\xEF\xBB\xBF,BRANCH 1,BRANCH 2\nSTEP 1,C1+1,\n".to_vec(),
                ',',
            ),
            (b";BRANCH 1;BRANCH 2\nSTEP 1;C1+1;\n".to_vec(), ';'),
            (b"\tBRANCH 1\tBRANCH 2\nSTEP 1\tC1+1\t\n".to_vec(), '\t'),
        ] {
            let mut diags = Diagnostics::new();
            let grid = read_bytes("t.csv", Format::Csv, bytes, None, &mut diags)
                .unwrap()
                .table;
            assert!(!diags.has_errors());
            assert_eq!(text_at(&grid, 0, 1), Some("BRANCH 1"));
            assert_eq!(text_at(&grid, 1, 1), Some("C1+1"));
        }
    }

    #[test]
    fn utf16_csv_is_read() {
        let mut bytes = vec![0xFF, 0xFE];
        for unit in "C1+1\nC1-0\n".encode_utf16() {
            bytes.extend_from_slice(&unit.to_le_bytes());
        }
        let mut diags = Diagnostics::new();
        let grid = read_bytes("t.csv", Format::Csv, bytes, None, &mut diags)
            .unwrap()
            .table;
        assert_eq!(text_at(&grid, 1, 0), Some("C1-0"));
    }

    #[test]
    fn binary_and_corrupt_inputs_are_diagnosed() {
        let mut diags = Diagnostics::new();
        assert!(read_bytes("x.csv", Format::Csv, vec![0, 1, 2, 255], None, &mut diags).is_none());
        assert!(
            read_bytes(
                "x.xlsx",
                Format::Xlsx,
                b"PK\x03\x04garbage".to_vec(),
                None,
                &mut diags
            )
            .is_none()
        );
        assert!(read_bytes("x.ods", Format::Ods, vec![], None, &mut diags).is_none());
        assert!(read_bytes("x.xls", Format::Xls, vec![0xD0, 0xCF], None, &mut diags).is_none());
        assert_eq!(diags.error_count(), 4);
    }
}
