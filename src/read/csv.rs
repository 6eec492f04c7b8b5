//! CSV: bytes → text (UTF-8 with or without BOM, UTF-16 with BOM,
//! Windows-1252) → one reading per delimiter that could be meant (`,` `;`
//! tab). Which reading is the table is decided by what parses as one
//! (`table::choose_reading`), not by counting characters: `;` also joins
//! items inside a cell (`C1+1; T=2s`).

use crate::cell::looks_like_item;
use crate::diag::{CellPos, Code, Diagnostics, Location};

use super::{CellValue, Grid, GridCell, MAX_FILLED_CELLS};

/// The CSV file read with one delimiter.
#[derive(Debug, Clone, PartialEq)]
pub struct CsvReading {
    pub delimiter: u8,
    pub grid: Grid,
    /// Fields that start with white space: Excel never writes a space after
    /// its delimiter, a person writing `C1+1; T=2s` in a cell does.
    pub spaced_fields: usize,
    /// Problems of this reading only (a decimal comma split in two).
    pub diags: Diagnostics,
}

impl CsvReading {
    /// The delimiter as messages name it.
    pub fn delimiter_name(&self) -> String {
        match self.delimiter {
            b',' => "comma".to_string(),
            b';' => "semicolon".to_string(),
            b'\t' => "tab".to_string(),
            other => format!("'{}'", char::from(other)),
        }
    }
}

/// Reads a CSV file: every plausible reading, the most likely first.
/// `None` (reported) when the bytes are no CSV text.
pub(super) fn read_csv(
    file: &str,
    bytes: &[u8],
    diags: &mut Diagnostics,
) -> Option<Vec<CsvReading>> {
    let whole_file = Location {
        file: file.to_string(),
        sheet: None,
        cell: None,
    };
    let text = match decode_text(bytes) {
        Ok((text, encoding)) => {
            if let Some(encoding) = encoding {
                diags.warning(
                    Code::W001Encoding,
                    whole_file.clone(),
                    format!("read as {encoding} text, not UTF-8"),
                );
            }
            crate::cell::composed(text)
        }
        Err(why) => {
            diags.error(Code::E002NotAWorkbook, whole_file, why);
            return None;
        }
    };
    // Excel's `sep=;` first line names the delimiter: the file is read with
    // it alone. The line is blanked, not removed, so rows stay file lines.
    let (text, candidates) = match declared_delimiter(&text) {
        Some((delimiter, line_end)) => {
            let rest = &text[line_end..];
            // A delimiter declared and never used, where another one is.
            let used = |d: u8| count_outside_quotes(rest, d);
            let instead = [b',', b';', b'\t'].into_iter().max_by_key(|d| used(*d));
            if used(delimiter) == 0
                && let Some(instead) = instead.filter(|d| used(*d) > 0)
            {
                let location = Location {
                    cell: Some(CellPos::new(0, 0)),
                    ..whole_file.clone()
                };
                diags.warning(
                    Code::W005Delimiter,
                    location,
                    format!(
                        "the first line sep={} declares the delimiter, but the file holds none outside quotes, and {} '{}': read with '{}' as declared, as Excel does; correct or remove the sep= line",
                        char::from(delimiter),
                        used(instead),
                        char::from(instead).escape_default(),
                        char::from(delimiter).escape_default(),
                    ),
                );
            }
            (rest.to_string(), vec![delimiter])
        }
        None => {
            let candidates = candidate_delimiters(&text);
            (text, candidates)
        }
    };
    let mut readings = Vec::new();
    let mut first_failure = None;
    for delimiter in candidates {
        let mut local = Diagnostics::new();
        match read_with(file, &text, delimiter, &mut local) {
            Some(reading) => readings.push(reading),
            None if first_failure.is_none() => first_failure = Some(local),
            None => {}
        }
    }
    if readings.is_empty() {
        diags.extend(first_failure.unwrap_or_default());
        return None;
    }
    Some(readings)
}

/// The delimiter a first line `sep=X` declares (Excel writes and reads it),
/// and where that line's text ends (its line break is kept).
fn declared_delimiter(text: &str) -> Option<(u8, usize)> {
    let end = text.find(['\r', '\n']).unwrap_or(text.len());
    let line = text[..end].trim_end_matches(' ');
    let declared = line
        .get(..4)?
        .eq_ignore_ascii_case("sep=")
        .then(|| &line[4..])?;
    match declared.as_bytes() {
        [d] if !matches!(d, b'"' | b'\r' | b'\n') && d.is_ascii() => Some((*d, end)),
        _ => None,
    }
}

/// How often `delimiter` occurs outside quotes.
fn count_outside_quotes(text: &str, delimiter: u8) -> usize {
    let mut in_quotes = false;
    text.bytes()
        .filter(|&b| {
            if b == b'"' {
                in_quotes = !in_quotes;
            }
            !in_quotes && b == delimiter
        })
        .count()
}

/// The delimiters that occur outside quotes, the most frequent first, and
/// comma (a one-column file has no delimiter at all).
fn candidate_delimiters(text: &str) -> Vec<u8> {
    let mut counts = [(b',', 0usize), (b';', 0), (b'\t', 0)];
    let mut in_quotes = false;
    for byte in text.bytes() {
        match byte {
            b'"' => in_quotes = !in_quotes,
            _ if in_quotes => {}
            _ => {
                if let Some(entry) = counts.iter_mut().find(|(d, _)| *d == byte) {
                    entry.1 += 1;
                }
            }
        }
    }
    // Stable: comma first on a tie.
    counts.sort_by_key(|c| std::cmp::Reverse(c.1));
    let mut found: Vec<u8> = counts
        .iter()
        .filter(|(_, n)| *n > 0)
        .map(|(d, _)| *d)
        .collect();
    if !found.contains(&b',') {
        found.push(b',');
    }
    found
}

fn read_with(file: &str, text: &str, delimiter: u8, diags: &mut Diagnostics) -> Option<CsvReading> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .delimiter(delimiter)
        .from_reader(text.as_bytes());
    let mut cells = Vec::new();
    let mut spaced_fields = 0;
    // Rows with a field written right after its delimiter, and fields with
    // a space after it following a filled one: in such a row, the second is
    // one cell's second item split off (`C1-0; T=2s` unquoted).
    let mut unspaced_rows = std::collections::HashSet::new();
    let mut split_off = Vec::new();
    let mut local = Diagnostics::new();
    // Lines are counted from byte offsets: the reader's own line numbers lag
    // behind with CRLF endings, and a quoted field may span lines.
    let mut counted_to = 0usize;
    let mut line = 1u64;
    let location = |row: u32, col: u32| Location {
        file: file.to_string(),
        sheet: None,
        cell: Some(CellPos::new(row, col)),
    };
    for record in reader.records() {
        let record = match record {
            Ok(r) => r,
            Err(err) => {
                let line = err.position().map(|p| p.line()).unwrap_or(1);
                diags.error(
                    Code::E002NotAWorkbook,
                    location(line.saturating_sub(1) as u32, 0),
                    format!("not valid CSV ({err})"),
                );
                return None;
            }
        };
        let bytes = text.as_bytes();
        let mut start = record
            .position()
            .map(|p| p.byte() as usize)
            .unwrap_or(counted_to)
            .min(bytes.len());
        // With CRLF the reader reports a record as starting on the LF.
        while start < bytes.len() && matches!(bytes[start], b'\r' | b'\n') {
            start += 1;
        }
        if start > counted_to {
            line += count_line_breaks(&bytes[counted_to..start]);
            counted_to = start;
        }
        let row = line.saturating_sub(1).min(u32::MAX as u64) as u32;
        let mut previous: Option<&str> = None;
        for (col, field) in record.iter().enumerate() {
            let col = col.min(u32::MAX as usize) as u32;
            if field.trim().is_empty() {
                previous = None;
                continue;
            }
            if cells.len() == MAX_FILLED_CELLS {
                diags.error(
                    Code::E024TableTooLarge,
                    location(row, col),
                    format!(
                        "the file has more than {MAX_FILLED_CELLS} filled cells; a table of 10,000 steps × 256 branches has fewer"
                    ),
                );
                return None;
            }
            if col > 0 && field.starts_with(char::is_whitespace) {
                spaced_fields += 1;
                // Items split from items: a STEP label and a move are never
                // one cell, nor are headers or the words of a note.
                if let Some(previous) = previous
                    && looks_like_item(field)
                    && looks_like_item(previous.rsplit([';', ',']).next().unwrap_or(previous))
                {
                    split_off.push((
                        row,
                        col,
                        previous.trim().to_string(),
                        field.trim().to_string(),
                    ));
                }
            } else if col > 0 {
                unspaced_rows.insert(row);
            }
            if delimiter == b',' {
                report_decimal_comma(previous, field, || location(row, col), &mut local);
            }
            previous = Some(field);
            cells.push(GridCell {
                pos: CellPos::new(row, col),
                value: CellValue::Text(field.to_string()),
            });
        }
    }
    // A tab never splits a cell of `;`-joined items; a row spaced throughout
    // is written so, whatever the others.
    if matches!(delimiter, b',' | b';') {
        let suspects = split_off
            .into_iter()
            .filter(|(row, ..)| unspaced_rows.contains(row));
        report_split_cells(suspects, delimiter, &location, &mut local);
    }
    Some(CsvReading {
        delimiter,
        grid: Grid {
            file: file.to_string(),
            sheet: None,
            cells,
            hidden: Vec::new(),
        },
        spaced_fields,
        diags: local,
    })
}

/// E050 at each field that is one cell's second item split off: spaced
/// after a filled field, in a row whose other fields start right after
/// their delimiter, or in a file whose fields mostly do.
fn report_split_cells(
    suspects: impl Iterator<Item = (u32, u32, String, String)>,
    delimiter: u8,
    location: &dyn Fn(u32, u32) -> Location,
    diags: &mut Diagnostics,
) {
    let name = char::from(delimiter);
    for (row, col, previous, field) in suspects {
        let advice = match delimiter {
            b',' => format!(
                "write them as one cell \"{previous}; {field}\" (items in a cell are joined by ';'), quoted if it holds a comma, or remove the space if \"{field}\" belongs to the next branch"
            ),
            _ => format!(
                "quote the cell (\"{previous}; {field}\") to keep it whole, or remove the space if \"{field}\" belongs to the next branch"
            ),
        };
        diags.error(
            Code::E050CellSplit,
            location(row, col),
            format!(
                "\"{field}\" follows \"{previous}\" after a space and a '{name}': the row's other cells start right after their '{name}', as a spreadsheet writes them, so this reads as one cell's items split in two (\"{field}\" would be a move of the next branch); {advice}"
            ),
        );
    }
}

/// E014 where a comma delimiter split a dwell's decimal comma (`T=1,5s`).
fn report_decimal_comma(
    previous: Option<&str>,
    field: &str,
    at: impl FnOnce() -> Location,
    diags: &mut Diagnostics,
) {
    if let Some(previous) = previous
        && ends_in_dwell_number(previous)
        && is_number_tail(field)
    {
        diags.error(
            Code::E014BadDwell,
            at(),
            format!(
                "\"{},{}\" was split in two by the comma that separates the CSV's cells: write the dwell with a decimal point (T=1.5s), or quote the cell",
                previous.trim(),
                field.trim()
            ),
        );
    }
}

/// `T=1` or `C1+1; T=1` — a dwell whose decimal comma may have split the cell.
fn ends_in_dwell_number(field: &str) -> bool {
    let last = field.rsplit([';', '\u{FF1B}']).next().unwrap_or(field);
    let squeezed: String = last.chars().filter(|c| !c.is_whitespace()).collect();
    let upper = squeezed.to_ascii_uppercase();
    upper
        .strip_prefix("T=")
        .is_some_and(|n| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()))
}

/// `5s`, `25ms`, `5`: the decimals of a split dwell.
fn is_number_tail(field: &str) -> bool {
    let t = field.trim();
    let digits = t.chars().take_while(char::is_ascii_digit).count();
    digits > 0
        && matches!(
            t[digits..].trim().to_ascii_lowercase().as_str(),
            "" | "s" | "ms" | "min"
        )
}

/// Line breaks in a byte slice: LF, CRLF and a lone CR each count once.
fn count_line_breaks(bytes: &[u8]) -> u64 {
    let mut count = 0;
    for (i, b) in bytes.iter().enumerate() {
        match b {
            b'\n' => count += 1,
            b'\r' if bytes.get(i + 1) != Some(&b'\n') => count += 1,
            _ => {}
        }
    }
    count
}

/// Decodes CSV bytes: UTF-8 (BOM optional), UTF-16 with a BOM (what Excel's
/// "Unicode text" writes), or else Windows-1252 (what older Excel writes in
/// Europe), which is reported; UTF-32 (by its BOM) is refused. Returns the text and, if it was not UTF-8, the
/// encoding found.
fn decode_text(bytes: &[u8]) -> Result<(String, Option<&'static str>), String> {
    if let Some(rest) = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]) {
        return String::from_utf8(rest.to_vec())
            .map(|t| (t, None))
            .map_err(|_| "starts with a UTF-8 byte order mark but is not valid UTF-8".to_string());
    }
    // A UTF-32 BOM begins with UTF-16's little-endian one: read as UTF-16,
    // the text would be every other character a NUL and no table found.
    if bytes.starts_with(&[0xFF, 0xFE, 0x00, 0x00]) || bytes.starts_with(&[0x00, 0x00, 0xFE, 0xFF])
    {
        return Err("UTF-32 text (its byte order mark says so), which steptable does not read; save the CSV as \"CSV UTF-8\" or UTF-16".to_string());
    }
    let utf16 = |rest: &[u8], little: bool| -> Result<(String, Option<&'static str>), String> {
        let units: Vec<u16> = rest
            .chunks_exact(2)
            .map(|p| {
                if little {
                    u16::from_le_bytes([p[0], p[1]])
                } else {
                    u16::from_be_bytes([p[0], p[1]])
                }
            })
            .collect();
        String::from_utf16(&units)
            .map(|t| (t, Some("UTF-16")))
            .map_err(|_| "UTF-16 text with invalid characters".to_string())
    };
    if let Some(rest) = bytes.strip_prefix(&[0xFF, 0xFE]) {
        return utf16(rest, true);
    }
    if let Some(rest) = bytes.strip_prefix(&[0xFE, 0xFF]) {
        return utf16(rest, false);
    }
    if bytes.contains(&0) {
        return Err("binary data, not a CSV text file".to_string());
    }
    match String::from_utf8(bytes.to_vec()) {
        Ok(text) => Ok((text, None)),
        Err(e) => {
            let offset = e.utf8_error().valid_up_to();
            encoding_rs::WINDOWS_1252
                .decode_without_bom_handling_and_without_replacement(bytes)
                .map(|text| (text.into_owned(), Some("Windows-1252")))
                .ok_or_else(|| {
                    format!(
                        "neither UTF-8 nor Windows-1252 text (invalid byte at offset {offset}); save the CSV as \"CSV UTF-8\""
                    )
                })
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn readings(text: &str) -> Vec<CsvReading> {
        read_csv("t.csv", text.as_bytes(), &mut Diagnostics::new()).unwrap()
    }

    #[test]
    fn every_delimiter_found_outside_quotes_is_a_reading() {
        let r = readings("STEP 1,\"C1+1; T=2s\"\n");
        assert_eq!(r.len(), 1, "the ; is inside quotes");
        let r = readings("C1+1; T=2s\nC1-0\n");
        assert_eq!(
            r.iter().map(|r| r.delimiter).collect::<Vec<_>>(),
            [b';', b',']
        );
        assert_eq!(r[0].spaced_fields, 1);
        assert_eq!(r[1].spaced_fields, 0);
    }

    #[test]
    fn a_decimal_comma_split_by_the_delimiter_is_an_error() {
        let r = readings(",BRANCH 1\nSTEP 1,C1+1; T=1,5s\nSTEP 2,C1-0\n");
        let comma = r.iter().find(|r| r.delimiter == b',').unwrap();
        let all: Vec<String> = comma
            .diags
            .clone()
            .into_sorted()
            .iter()
            .map(|d| d.to_string())
            .collect();
        assert!(
            all[0].contains("t.csv:2:3: error[E014]") && all[0].contains("T=1,5s"),
            "{all:?}"
        );
        assert!(ends_in_dwell_number("T = 12") && !ends_in_dwell_number("T=1.5s"));
        assert!(is_number_tail("5s") && is_number_tail(" 25 ms") && !is_number_tail("C1+1"));
    }

    #[test]
    fn a_sep_line_declares_one_ascii_delimiter() {
        assert_eq!(declared_delimiter("sep=;\nA;B"), Some((b';', 5)));
        assert_eq!(declared_delimiter("Sep=\t \r\nA"), Some((b'\t', 6)));
        assert_eq!(declared_delimiter("SEP=|"), Some((b'|', 5)));
        for not in [
            "sep=",
            "sep=ab\n",
            "sep=\"\n",
            ";BRANCH 1",
            "se",
            "sep=\u{2016}",
        ] {
            assert_eq!(declared_delimiter(not), None, "{not:?}");
        }
    }
}
