//! Reading: file bytes → one sheet as a grid of cells with absolute positions.
//! Workbooks (`.xlsx`, `.xlsm`, `.xls`, `.ods`) go through calamine; CSV is
//! decoded here (UTF-8 with or without BOM, UTF-16 with BOM; `,` `;` or tab).

mod csv;
mod grid;
mod sheet_choice;
mod workbook;
use workbook::read_workbook;
// Guards in front of calamine's readers, against files that would make it
// allocate without bound.
mod guard_ods;
mod guard_ole;
mod guard_xlsx;
pub use csv::CsvReading;
pub use grid::{CellValue, Grid, GridCell};
use std::io::Cursor;
use std::path::Path;
pub use workbook::MAX_FILLED_CELLS;

use crate::diag::{Code, Diagnostics, Location};

/// Largest input file read, in bytes.
pub const MAX_FILE_BYTES: u64 = 64 * 1024 * 1024;
/// Largest size a zipped workbook (.xlsx, .xlsm, .ods) may unpack to.
pub const MAX_UNPACKED_BYTES: u64 = 256 * 1024 * 1024;

pub use crate::sheets::{ADDRESSES_SHEET, SETTINGS_SHEET, TABLE_SHEET};

/// What was read from one input file: the step table's sheet and, for a
/// workbook that has one, its SETTINGS sheet.
#[derive(Debug, Clone, PartialEq)]
pub struct Input {
    pub table: Grid,
    pub settings: Option<Grid>,
    /// The ADDRESSES sheet, when a workbook has one.
    pub addresses: Option<Grid>,
    /// A CSV file's readings, one per delimiter that could be meant, when
    /// there is more than one: the table decides which is the table.
    pub csv_readings: Vec<CsvReading>,
    /// A workbook's other sheets (neither the table's nor a side sheet):
    /// settings written there are not read, and are said so.
    pub others: Vec<Grid>,
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
    // A folder or a missing file is E001 whatever its name ends in (a
    // folder `line.xlsx`, a missing `notes` are no unknown file types).
    let meta = match std::fs::metadata(path) {
        Ok(meta) => meta,
        Err(err) => {
            let why = dangling_link(path).unwrap_or_else(|| format!("cannot read file: {err}"));
            diags.error(Code::E001Unreadable, whole_file, why);
            return None;
        }
    };
    if meta.is_dir() {
        diags.error(
            Code::E001Unreadable,
            whole_file,
            "is a folder, not a table file; to convert every table in a folder, use `steptable batch FOLDER -o DIR`",
        );
        return None;
    }
    let Some(format) = Format::from_path(path) else {
        diags.error(
            Code::E002NotAWorkbook,
            whole_file,
            "unknown file type (expected .xlsx, .xlsm, .xls, .ods or .csv)",
        );
        return None;
    };
    if meta.len() > MAX_FILE_BYTES {
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
            if let Some(name) = sheet {
                diags.warning(
                    Code::W006NoEffect,
                    Location {
                        file: file.to_string(),
                        sheet: None,
                        cell: None,
                    },
                    format!("--sheet {name} has no effect on a CSV file, which has no sheets; the file was read as it is"),
                );
            }
            let mut readings = csv::read_csv(file, &bytes, diags)?;
            if readings.len() == 1 {
                let only = readings.remove(0);
                diags.extend(only.diags);
                return Some(Input {
                    table: only.grid,
                    settings: None,
                    addresses: None,
                    csv_readings: Vec::new(),
                    others: Vec::new(),
                });
            }
            Some(Input {
                table: readings[0].grid.clone(),
                settings: None,
                addresses: None,
                csv_readings: readings,
                others: Vec::new(),
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

/// What a path that cannot be opened is, when it is a symbolic link to
/// nothing: `ls` lists it, so "no such file" alone would puzzle.
pub fn dangling_link(path: &Path) -> Option<String> {
    let target = std::fs::read_link(path).ok()?;
    if std::fs::metadata(path).is_ok() {
        return None;
    }
    // Followed link by link: a chain names the link that leads nowhere, a
    // loop is called one.
    let mut said = format!("is a link to {}", display_name(&target));
    let mut seen = vec![path.to_path_buf()];
    let mut at = path.to_path_buf();
    let mut target = target;
    loop {
        let next = match target.is_absolute() {
            true => target.clone(),
            false => at.parent().unwrap_or(Path::new("")).join(&target),
        };
        if seen.contains(&next) {
            return Some(format!("{said}, and the links lead round in a loop"));
        }
        // The system follows 40 links at most.
        if seen.len() > 40 {
            return Some(format!(
                "{said}, …: a chain of more than 40 links, which the system does not follow"
            ));
        }
        match std::fs::read_link(&next) {
            Ok(further) => {
                said.push_str(&format!(", a link to {}", display_name(&further)));
                seen.push(next.clone());
                at = next;
                target = further;
            }
            Err(_) => return Some(format!("{said}, which does not exist")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diag::CellPos;

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
