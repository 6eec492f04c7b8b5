//! A guard in front of calamine's `.ods` reader. calamine lays each sheet
//! out as one dense rectangle of cells, counting rows and columns that
//! ODF writes as "repeated" (`table:number-rows-repeated`), up to 100
//! million cells: a 1 KB file with a cell at A1 and one a million rows and
//! 99 columns away took 6.2 GB and 4.4 s. Here the rectangle around each
//! sheet's filled cells is measured from `content.xml` as it streams past,
//! before calamine sees the file. The same pass notes each sheet's merged
//! cells (a cell's `table:number-columns-spanned`), which calamine does not
//! give: what lies under them is hidden in the spreadsheet.

use std::collections::HashMap;
use std::io::{BufReader, Cursor};

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

/// What one pass over `content.xml` found.
#[derive(Default)]
pub struct Survey {
    /// Why the `.ods` file is not decoded, if it is not: the sheet whose
    /// filled cells spread over more than `max_cells` cells.
    pub oversized: Option<String>,
    /// Each sheet's merged cells: first and last (row, column), inclusive.
    pub merged: HashMap<String, Vec<super::sheet_choice::Region>>,
    /// Each sheet's formula cells saved with a value (`office:value-type`),
    /// as (row, column): one that computes `""` is computed, not missing.
    pub computed: HashMap<String, std::collections::HashSet<(u32, u32)>>,
}

/// The survey of an `.ods` file. Anything this pass cannot read (not a zip,
/// no `content.xml`, bad XML) is left to calamine to report.
pub fn survey(bytes: &[u8], max_cells: u64) -> Survey {
    let mut found = Survey::default();
    found.oversized = walk(bytes, max_cells, &mut found);
    found
}

fn walk(bytes: &[u8], max_cells: u64, found: &mut Survey) -> Option<String> {
    let mut archive = zip::ZipArchive::new(Cursor::new(bytes)).ok()?;
    let content = archive.by_name("content.xml").ok()?;
    // Streamed: the sheet XML is never held whole beside calamine's copy.
    let mut reader = Reader::from_reader(BufReader::new(content));
    let mut buf = Vec::new();
    let mut sheet = Sheet::default();
    loop {
        let event = reader.read_event_into(&mut buf).ok()?;
        match &event {
            Event::Start(e) | Event::Empty(e) => {
                let filled_element = matches!(event, Event::Start(_));
                match e.name().as_ref() {
                    "table:table" => sheet = Sheet::default(),
                    "table:table-row" => sheet.start_row(repeat(e, "table:number-rows-repeated")),
                    "table:table-cell" | "table:covered-table-cell" => {
                        let filled = filled_element || has_attribute(e, "office:value-type");
                        let spans = (
                            repeat(e, "table:number-rows-spanned"),
                            repeat(e, "table:number-columns-spanned"),
                        );
                        let at = |n: u64| u32::try_from(n).unwrap_or(u32::MAX);
                        let (row, col) = (sheet.row, sheet.col);
                        if has_attribute(e, "table:formula")
                            && has_attribute(e, "office:value-type")
                            && let Some(name) = &sheet.name
                        {
                            // Repeated across columns or rows, each cell it
                            // stands for (a bounded few: a rectangle of
                            // formulas saved with values is rare).
                            let cells = found.computed.entry(name.clone()).or_default();
                            let rows = sheet.repeats.min(256);
                            let cols = repeat(e, "table:number-columns-repeated").min(256);
                            for r in 0..rows {
                                for c in 0..cols {
                                    cells.insert((
                                        at(row.saturating_add(r)),
                                        at(col.saturating_add(c)),
                                    ));
                                }
                            }
                        }
                        if spans != (1, 1)
                            && let Some(name) = &sheet.name
                        {
                            found.merged.entry(name.clone()).or_default().push((
                                (at(row), at(col)),
                                (
                                    at(row.saturating_add(spans.0 - 1)),
                                    at(col.saturating_add(spans.1 - 1)),
                                ),
                            ));
                        }
                        sheet.cell(repeat(e, "table:number-columns-repeated"), filled);
                    }
                    _ => {}
                }
            }
            Event::End(e) if e.name().as_ref() == "table:table-row" => sheet.end_row(),
            Event::End(e) if e.name().as_ref() == "table:table" => {
                let span = sheet.span();
                if span > max_cells {
                    let name = sheet.name.clone().unwrap_or_default();
                    return Some(format!(
                        "sheet {name}: its cells spread over a rectangle of {span} cells; at most {max_cells} are read"
                    ));
                }
            }
            Event::Eof => return None,
            _ => {}
        }
        if let Event::Start(e) = &event
            && e.name().as_ref() == "table:table"
        {
            sheet.name = attribute(e, "table:name");
        }
        buf.clear();
    }
}

/// Where the filled cells of one sheet lie.
#[derive(Default)]
struct Sheet {
    name: Option<String>,
    /// The first row of the current row element, and how many it stands for.
    row: u64,
    repeats: u64,
    col: u64,
    rows: Option<(u64, u64)>,
    cols: Option<(u64, u64)>,
}

impl Sheet {
    fn start_row(&mut self, repeats: u64) {
        self.repeats = repeats;
        self.col = 0;
    }

    fn end_row(&mut self) {
        self.row = self.row.saturating_add(self.repeats);
    }

    fn cell(&mut self, repeats: u64, filled: bool) {
        if filled {
            let last_col = self.col.saturating_add(repeats - 1);
            let last_row = self.row.saturating_add(self.repeats - 1);
            self.cols = Some(widen(self.cols, self.col, last_col));
            self.rows = Some(widen(self.rows, self.row, last_row));
        }
        self.col = self.col.saturating_add(repeats);
    }

    fn span(&self) -> u64 {
        match (self.rows, self.cols) {
            (Some((r0, r1)), Some((c0, c1))) => (r1 - r0 + 1).saturating_mul(c1 - c0 + 1),
            _ => 0,
        }
    }
}

fn widen(range: Option<(u64, u64)>, low: u64, high: u64) -> (u64, u64) {
    match range {
        None => (low, high),
        Some((a, b)) => (a.min(low), b.max(high)),
    }
}

fn attribute(e: &BytesStart, name: &str) -> Option<String> {
    e.attributes()
        .flatten()
        .find(|a| a.key.as_ref() == name)
        .map(|a| a.value.to_string())
}

fn has_attribute(e: &BytesStart, name: &str) -> bool {
    attribute(e, name).is_some()
}

/// A repeat count; a missing, unreadable or zero one counts once.
fn repeat(e: &BytesStart, name: &str) -> u64 {
    attribute(e, name)
        .and_then(|v| v.trim().parse::<u64>().ok())
        .filter(|n| *n > 0)
        .unwrap_or(1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::Write;

    fn ods(table: &str) -> Vec<u8> {
        let mut buffer = Cursor::new(Vec::new());
        let mut zip = zip::ZipWriter::new(&mut buffer);
        let options = zip::write::SimpleFileOptions::default();
        zip.start_file("content.xml", options).unwrap();
        write!(
            zip,
            r#"<office:document-content xmlns:office="o" xmlns:table="t" xmlns:text="x"><office:body><office:spreadsheet><table:table table:name="S">{table}</table:table></office:spreadsheet></office:body></office:document-content>"#
        )
        .unwrap();
        zip.finish().unwrap();
        buffer.into_inner()
    }

    #[test]
    fn measures_the_rectangle_with_repeated_rows_and_columns() {
        let corners = ods(concat!(
            r#"<table:table-row><table:table-cell office:value-type="string"><text:p>C1+1</text:p></table:table-cell></table:table-row>"#,
            r#"<table:table-row table:number-rows-repeated="999998"><table:table-cell table:number-columns-repeated="99"/></table:table-row>"#,
            r#"<table:table-row><table:table-cell table:number-columns-repeated="98"/><table:table-cell office:value-type="string"><text:p>C1-0</text:p></table:table-cell></table:table-row>"#,
        ));
        let why = survey(&corners, 3_000_000).oversized.expect("refused");
        assert!(
            why.contains("sheet S") && why.contains("99000000 cells"),
            "{why}"
        );
        // Empty repeated cells around a small table do not count.
        let small = ods(concat!(
            r#"<table:table-row table:number-rows-repeated="1000"><table:table-cell table:number-columns-repeated="1000"/></table:table-row>"#,
            r#"<table:table-row><table:table-cell/><table:table-cell><text:p>C1+1</text:p></table:table-cell></table:table-row>"#,
        ));
        assert_eq!(survey(&small, 3_000_000).oversized, None);
    }

    #[test]
    fn notes_each_sheets_merged_cells() {
        let book = ods(
            r#"<table:table-row><table:table-cell/><table:table-cell table:number-columns-spanned="2" table:number-rows-spanned="3" office:value-type="string"><text:p>x</text:p></table:table-cell><table:covered-table-cell/></table:table-row>"#,
        );
        assert_eq!(survey(&book, 1000).merged["S"], vec![((0, 1), (2, 2))]);
        let plain = ods(r#"<table:table-row><table:table-cell/></table:table-row>"#);
        assert!(survey(&plain, 1000).merged.is_empty());
    }
}
