//! How the output workbook looks on screen and on paper: the cell formats
//! every sheet shares, the page setup (A4, fit to one page wide, header rows
//! repeated, file and date in the footer) and the row heights of wrapped
//! text, estimated here because neither Excel nor every LibreOffice grows a
//! row for wrapped text it did not lay out itself.

use rust_xlsxwriter::{Format, FormatAlign, FormatBorder, Worksheet, XlsxError};

use crate::faults::Outcome;

/// Characters a portrait A4 page holds across at 100 % (Calibri 11, the
/// default margins): wider sheets print landscape.
pub const PORTRAIT_CHARS: f64 = 90.0;

/// Points of one line of text (the sheet's default row height).
const LINE_POINTS: f64 = 15.0;

/// The formats of the workbook.
pub struct Formats {
    pub title: Format,
    /// A column header: bold, boxed, on the template's header blue.
    pub header: Format,
    /// A cell of a list: boxed, wrapped, aligned to the top.
    pub cell: Format,
}

impl Formats {
    pub fn new() -> Self {
        Formats {
            title: Format::new().set_bold().set_font_size(14),
            header: Format::new()
                .set_bold()
                .set_border(FormatBorder::Thin)
                .set_background_color("#D9E1F2")
                .set_text_wrap()
                .set_align(FormatAlign::Top),
            cell: cell(),
        }
    }

    /// A FAULTS row's cell, filled by its outcome: hazards red, safe stalls
    /// amber, faults without effect green (light tints, so the text stays
    /// readable and a black-and-white print still tells them apart by the
    /// OUTCOME column).
    pub fn outcome(&self, outcome: Outcome) -> Format {
        cell().set_background_color(outcome_fill(outcome))
    }
}

fn cell() -> Format {
    Format::new()
        .set_border(FormatBorder::Thin)
        .set_text_wrap()
        .set_align(FormatAlign::Top)
}

/// The fill of a FAULTS row of this outcome (`RRGGBB`).
pub fn outcome_fill(outcome: Outcome) -> &'static str {
    match outcome {
        Outcome::Hazard => "#F4B6B6",
        Outcome::SafeStall => "#FFE08A",
        Outcome::NoEffect => "#C6EFCE",
    }
}

/// How one sheet prints.
pub struct Page {
    /// The rows repeated on every printed page (the column headers).
    pub repeat: Option<(u32, u32)>,
    /// The widths of the printed columns, in characters: landscape when
    /// they are wider than a portrait page.
    pub widths: Vec<f64>,
    /// Fit to one page wide; off where manual page breaks decide the
    /// pages (Excel ignores them on a sheet scaled to fit).
    pub fit_width: bool,
}

impl Page {
    /// Sets the columns' widths and the page setup.
    pub fn apply(&self, sheet: &mut Worksheet) -> Result<(), XlsxError> {
        for (col, width) in self.widths.iter().enumerate() {
            sheet.set_column_width(col as u16, *width)?;
        }
        // A4, as the engineers steptable is made for print.
        sheet.set_paper_size(9);
        if self.landscape() {
            sheet.set_landscape();
        } else {
            sheet.set_portrait();
        }
        if self.fit_width {
            sheet.set_print_fit_to_pages(1, 0);
        }
        if let Some((first, last)) = self.repeat {
            sheet.set_repeat_rows(first, last)?;
        }
        sheet.set_header("&C&A");
        // File name left, page in the middle, date right: a printed sheet
        // says which workbook it came from and when it was printed.
        sheet.set_footer("&L&F&CPage &P of &N&R&D");
        Ok(())
    }

    pub fn landscape(&self) -> bool {
        self.widths.iter().sum::<f64>() > PORTRAIT_CHARS
    }
}

/// The height in points of a row of wrapped cells: as many lines as its
/// longest cell needs in its column (`widths` in characters), at least one.
pub fn row_points(texts: &[&str], widths: &[f64]) -> f64 {
    let lines = texts
        .iter()
        .zip(widths)
        .map(|(text, width)| lines_of(text, *width))
        .max()
        .unwrap_or(1)
        .max(1);
    lines as f64 * LINE_POINTS
}

/// Lines `text` wraps to in a column `width` characters wide: words are
/// not split, so a line holds a little less than the width.
fn lines_of(text: &str, width: f64) -> usize {
    let room = ((width - 1.0) * 0.95).max(1.0) as usize;
    text.split('\n')
        .map(|paragraph| {
            let mut lines = 1;
            let mut used = 0;
            for word in paragraph.split(' ') {
                let len = word.chars().count();
                if used > 0 && used + 1 + len > room {
                    lines += 1 + len / room.max(1);
                    used = len % room.max(1);
                } else {
                    used += len + usize::from(used > 0);
                }
            }
            lines
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wrapped_text_counts_its_lines() {
        assert_eq!(lines_of("", 10.0), 1);
        assert_eq!(lines_of("short", 20.0), 1);
        assert_eq!(lines_of("one two three four five six", 11.0), 4);
        assert_eq!(lines_of("a\nb", 20.0), 2);
        assert_eq!(row_points(&["x", "a\nb\nc"], &[5.0, 20.0]), 45.0);
    }
}
