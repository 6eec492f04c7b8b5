//! The output workbook on paper and as a list to work through: every
//! sheet's page setup, the filters of the list sheets, and FAULTS with the
//! hazards first, each row filled by its outcome; read back from the
//! written `NAME.steptable.xlsx` (LibreOffice renders it in the tools suite).

use crate::helpers::{read_sheet, sample, steptable, xlsx_part};
use std::path::{Path, PathBuf};

/// The paper's example converted to its workbook.
fn paper_workbook(dir: &Path) -> PathBuf {
    steptable()
        .arg("convert")
        .arg(sample("paper_example.xlsx"))
        .args(["--formats", "xlsx,faults", "-o"])
        .arg(dir)
        .assert()
        .success();
    dir.join("paper_example/paper_example.steptable.xlsx")
}

/// The sheets in order, each with whether it prints landscape, whether it
/// is fitted to one page wide, and its repeated header row (1-based).
const SHEETS: [(&str, bool, bool, Option<u32>); 7] = [
    ("SEQUENTIAL CONTROL DESCRIPTION", false, true, Some(3)),
    ("INPUT ADDRESSES", false, true, Some(1)),
    ("OUTPUT ADDRESSES", false, true, Some(1)),
    ("PLC PROGRAM", true, true, Some(1)),
    ("SIMULATION", false, true, Some(5)),
    // Kept whole by page breaks instead, which a fitted sheet ignores.
    ("DIAGRAM", false, false, None),
    ("FAULTS", true, true, Some(4)),
];

#[test]
fn every_sheet_prints_on_a4_one_page_wide_with_its_headers_and_footer() {
    let dir = tempfile::tempdir().unwrap();
    let book = paper_workbook(dir.path());
    let workbook = xlsx_part(&book, "xl/workbook.xml");
    for (k, (name, landscape, fitted, repeat)) in SHEETS.iter().enumerate() {
        assert!(
            workbook.contains(&format!("<sheet name=\"{name}\" sheetId=\"{}\"", k + 1)),
            "{name}: {workbook}"
        );
        let xml = xlsx_part(&book, &format!("xl/worksheets/sheet{}.xml", k + 1));
        let setup = xml
            .split("<pageSetup ")
            .nth(1)
            .and_then(|p| p.split("/>").next())
            .unwrap_or_else(|| panic!("{name}: no page setup"));
        assert!(setup.contains("paperSize=\"9\""), "{name}: {setup}");
        let orientation = if *landscape { "landscape" } else { "portrait" };
        assert!(
            setup.contains(&format!("orientation=\"{orientation}\"")),
            "{name}: {setup}"
        );
        assert_eq!(
            xml.contains("<pageSetUpPr fitToPage=\"1\"/>") && setup.contains("fitToHeight=\"0\""),
            *fitted,
            "{name}: fit to one page wide: {xml}"
        );
        assert!(
            xml.contains(
                "<oddFooter>&amp;L&amp;F&amp;CPage &amp;P of &amp;N&amp;R&amp;D</oddFooter>"
            ),
            "{name}: footer with file, page and date"
        );
        let titles = format!("<definedName name=\"_xlnm.Print_Titles\" localSheetId=\"{k}\">");
        match repeat {
            Some(row) => assert!(
                workbook.contains(&format!(
                    "{titles}{}!${row}:${row}</definedName>",
                    quoted(name)
                )),
                "{name}: header row {row} on every page: {workbook}"
            ),
            None => assert!(!workbook.contains(&titles), "{name}"),
        }
    }
}

/// A sheet's name as a reference spells it: quoted where it has a space.
fn quoted(name: &str) -> String {
    if name.contains(' ') {
        format!("'{name}'")
    } else {
        name.to_string()
    }
}

/// The `ref` of a sheet's autofilter.
fn autofilter(book: &Path, sheet: usize) -> Option<String> {
    let xml = xlsx_part(book, &format!("xl/worksheets/sheet{sheet}.xml"));
    let part = xml.split("<autoFilter ref=\"").nth(1)?;
    Some(part.split('"').next()?.to_string())
}

#[test]
fn list_sheets_filter_their_rows() {
    let dir = tempfile::tempdir().unwrap();
    let book = paper_workbook(dir.path());
    let last_row = |name: &str| read_sheet(&book, name).len();
    let inputs = last_row("INPUT ADDRESSES");
    let outputs = last_row("OUTPUT ADDRESSES");
    let steps = last_row("SIMULATION");
    let faults = last_row("FAULTS");
    assert_eq!(inputs, 13, "START and 11 sensors under the header");
    assert_eq!(autofilter(&book, 2), Some(format!("A1:C{inputs}")));
    assert_eq!(autofilter(&book, 3), Some(format!("A1:C{outputs}")));
    assert_eq!(autofilter(&book, 5), Some(format!("A5:D{steps}")));
    assert_eq!(autofilter(&book, 7), Some(format!("A4:F{faults}")));
    // The table and the program are not lists to filter.
    for sheet in [1, 4, 6] {
        assert_eq!(autofilter(&book, sheet), None, "sheet {sheet}");
    }
}

/// The fill colour (`RRGGBB`) of every cell style, by style index.
fn style_fills(book: &Path) -> Vec<Option<String>> {
    let styles = xlsx_part(book, "xl/styles.xml");
    let section = |tag: &str| -> String {
        let start = styles.find(&format!("<{tag} ")).expect(tag);
        let end = styles.find(&format!("</{tag}>")).expect(tag);
        styles[start..end].to_string()
    };
    let fills: Vec<Option<String>> = section("fills")
        .split("<fill>")
        .skip(1)
        .map(|fill| {
            let rgb = fill.split("<fgColor rgb=\"FF").nth(1)?;
            Some(rgb[..6].to_string())
        })
        .collect();
    section("cellXfs")
        .split("<xf ")
        .skip(1)
        .map(|xf| {
            let id: usize = xf
                .split("fillId=\"")
                .nth(1)?
                .split('"')
                .next()?
                .parse()
                .ok()?;
            fills.get(id).cloned().flatten()
        })
        .collect()
}

#[test]
fn faults_list_hazards_first_each_row_filled_by_its_outcome() {
    let dir = tempfile::tempdir().unwrap();
    let book = paper_workbook(dir.path());
    let sheet = read_sheet(&book, "FAULTS");
    assert_eq!(sheet[3][..2], ["FAULT", "OUTCOME"]);
    let outcomes: Vec<&str> = sheet[4..].iter().map(|r| r[1].as_str()).collect();
    let rank = |o: &str| {
        ["hazard", "safe stall", "no effect"]
            .iter()
            .position(|x| *x == o)
    };
    let ranks: Vec<usize> = outcomes.iter().map(|o| rank(o).expect(o)).collect();
    assert!(ranks.windows(2).all(|w| w[0] <= w[1]), "{outcomes:?}");
    assert!(outcomes.contains(&"hazard") && outcomes.contains(&"safe stall"));
    // The same rows as the fault table, only in another order.
    let csv = dir.path().join("paper_example/paper_example.faults.csv");
    let mut listed: Vec<String> = csv::Reader::from_path(csv)
        .unwrap()
        .records()
        .map(|r| r.unwrap()[0].to_string())
        .collect();
    let mut shown: Vec<String> = sheet[4..].iter().map(|r| r[0].clone()).collect();
    listed.sort();
    shown.sort();
    assert_eq!(shown, listed);
    let fills = style_fills(&book);
    let xml = xlsx_part(&book, "xl/worksheets/sheet7.xml");
    for (i, outcome) in outcomes.iter().enumerate() {
        let row = i + 5;
        for col in ["A", "B", "F"] {
            let style: usize = xml
                .split(&format!("<c r=\"{col}{row}\" s=\""))
                .nth(1)
                .and_then(|p| p.split('"').next())
                .and_then(|s| s.parse().ok())
                .unwrap_or_else(|| panic!("{col}{row} has no style"));
            let expected = match *outcome {
                "hazard" => "F4B6B6",
                "safe stall" => "FFE08A",
                _ => "C6EFCE",
            };
            assert_eq!(
                fills[style].as_deref(),
                Some(expected),
                "{col}{row} ({outcome})"
            );
        }
    }
}
