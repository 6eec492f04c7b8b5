//! Hostile and broken inputs, made here rather than committed as binaries:
//! each gets its exit code and its message, and nothing is written.

use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use rust_xlsxwriter::{Formula, Workbook};

use crate::helpers::{files_below, sample, steptable};

struct Case {
    name: &'static str,
    file: &'static str,
    bytes: Vec<u8>,
    code: i32,
    needle: &'static str,
}

fn case(
    name: &'static str,
    file: &'static str,
    bytes: Vec<u8>,
    code: i32,
    needle: &'static str,
) -> Case {
    Case {
        name,
        file,
        bytes,
        code,
        needle,
    }
}

fn csv(text: &str) -> Vec<u8> {
    text.as_bytes().to_vec()
}

fn paper_csv() -> String {
    std::fs::read_to_string(sample("paper_example.csv")).unwrap()
}

/// An .xlsx made by `fill`, as bytes.
fn xlsx(fill: impl FnOnce(&mut rust_xlsxwriter::Worksheet)) -> Vec<u8> {
    let mut workbook = Workbook::new();
    let sheet = workbook.add_worksheet();
    fill(sheet);
    workbook.save_to_buffer().unwrap()
}

/// A zip with one entry of `size` zero bytes (it packs to almost nothing).
fn zip_of_zeros(name: &str, size: usize) -> Vec<u8> {
    let mut buffer = std::io::Cursor::new(Vec::new());
    let mut zip = zip::ZipWriter::new(&mut buffer);
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        .large_file(true);
    zip.start_file(name, options).unwrap();
    let chunk = vec![0u8; 1 << 20];
    for _ in 0..size / chunk.len() {
        zip.write_all(&chunk).unwrap();
    }
    zip.finish().unwrap();
    buffer.into_inner()
}

/// A minimal `.xlsx` written straight as XML: one sheet whose rows come
/// from `rows` (called once per row, so millions of cells stay cheap), and
/// a shared string table if given.
fn raw_xlsx(rows: usize, row: &str, shared_strings: Option<&str>) -> Vec<u8> {
    let mut buffer = std::io::Cursor::new(Vec::new());
    let mut zip = zip::ZipWriter::new(&mut buffer);
    let options = zip::write::SimpleFileOptions::default()
        .compression_method(zip::CompressionMethod::Deflated)
        .large_file(true);
    let parts = [
        (
            "[Content_Types].xml",
            r#"<?xml version="1.0" encoding="UTF-8"?><Types xmlns="http://schemas.openxmlformats.org/package/2006/content-types"><Default Extension="rels" ContentType="application/vnd.openxmlformats-package.relationships+xml"/><Default Extension="xml" ContentType="application/xml"/><Override PartName="/xl/workbook.xml" ContentType="application/vnd.openxmlformats-officedocument.spreadsheetml.sheet.main+xml"/><Override PartName="/xl/worksheets/sheet1.xml" ContentType="application/vnd.openxmlformats-officedocument.spreadsheetml.worksheet+xml"/></Types>"#,
        ),
        (
            "_rels/.rels",
            r#"<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Id="rId1" Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/officeDocument" Target="xl/workbook.xml"/></Relationships>"#,
        ),
        (
            "xl/workbook.xml",
            r#"<?xml version="1.0" encoding="UTF-8"?><workbook xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main" xmlns:r="http://schemas.openxmlformats.org/officeDocument/2006/relationships"><sheets><sheet name="Sheet1" sheetId="1" r:id="rId1"/></sheets></workbook>"#,
        ),
        (
            "xl/_rels/workbook.xml.rels",
            r#"<?xml version="1.0" encoding="UTF-8"?><Relationships xmlns="http://schemas.openxmlformats.org/package/2006/relationships"><Relationship Id="rId1" Type="http://schemas.openxmlformats.org/officeDocument/2006/relationships/worksheet" Target="worksheets/sheet1.xml"/></Relationships>"#,
        ),
    ];
    for (name, text) in parts {
        zip.start_file(name, options).unwrap();
        zip.write_all(text.as_bytes()).unwrap();
    }
    if let Some(strings) = shared_strings {
        zip.start_file("xl/sharedStrings.xml", options).unwrap();
        zip.write_all(strings.as_bytes()).unwrap();
    }
    zip.start_file("xl/worksheets/sheet1.xml", options).unwrap();
    zip.write_all(br#"<?xml version="1.0" encoding="UTF-8"?><worksheet xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main"><sheetData>"#).unwrap();
    for _ in 0..rows {
        zip.write_all(row.as_bytes()).unwrap();
    }
    zip.write_all(b"</sheetData></worksheet>").unwrap();
    zip.finish().unwrap();
    buffer.into_inner()
}

/// A minimal `.ods` whose one sheet is `table` (rows of ODF XML).
pub(crate) fn ods_of(table: &str) -> Vec<u8> {
    let mut buffer = std::io::Cursor::new(Vec::new());
    let mut zip = zip::ZipWriter::new(&mut buffer);
    let stored =
        zip::write::SimpleFileOptions::default().compression_method(zip::CompressionMethod::Stored);
    zip.start_file("mimetype", stored).unwrap();
    zip.write_all(b"application/vnd.oasis.opendocument.spreadsheet")
        .unwrap();
    zip.start_file(
        "META-INF/manifest.xml",
        zip::write::SimpleFileOptions::default(),
    )
    .unwrap();
    zip.write_all(br#"<?xml version="1.0" encoding="UTF-8"?><manifest:manifest xmlns:manifest="urn:oasis:names:tc:opendocument:xmlns:manifest:1.0" manifest:version="1.2"><manifest:file-entry manifest:full-path="/" manifest:media-type="application/vnd.oasis.opendocument.spreadsheet"/><manifest:file-entry manifest:full-path="content.xml" manifest:media-type="text/xml"/></manifest:manifest>"#).unwrap();
    zip.start_file("content.xml", zip::write::SimpleFileOptions::default())
        .unwrap();
    write!(
        zip,
        r#"<?xml version="1.0" encoding="UTF-8"?><office:document-content xmlns:office="urn:oasis:names:tc:opendocument:xmlns:office:1.0" xmlns:table="urn:oasis:names:tc:opendocument:xmlns:table:1.0" xmlns:text="urn:oasis:names:tc:opendocument:xmlns:text:1.0" office:version="1.2"><office:body><office:spreadsheet><table:table table:name="Sheet1">{table}</table:table></office:spreadsheet></office:body></office:document-content>"#
    )
    .unwrap();
    zip.finish().unwrap();
    buffer.into_inner()
}

fn cases() -> Vec<Case> {
    let paper_xlsx = std::fs::read(sample("paper_example.xlsx")).unwrap();
    let paper_ods =
        std::fs::read(crate::helpers::root().join("tests/fixtures/paper_example_grid.ods"))
            .unwrap();
    let long_row: String = (0..16_384).map(|i| format!("junk{i},")).collect();
    let many_steps: String = (0..10_001)
        .map(|i| if i % 2 == 0 { "C1+1\n" } else { "C1-0\n" })
        .collect();
    let many_branches: String = (1..=300).map(|i| format!("C{i}+1,")).collect::<String>()
        + "\n"
        + &(1..=300).map(|i| format!("C{i}-0,")).collect::<String>();
    vec![
        case("empty csv", "empty.csv", vec![], 1, "E003"),
        case(
            "whitespace csv",
            "blank.csv",
            csv(" \n\t\n  \r\n"),
            1,
            "E003",
        ),
        case("bom only", "bom.csv", vec![0xEF, 0xBB, 0xBF], 1, "E003"),
        case(
            "binary csv",
            "binary.csv",
            vec![0, 1, 2, 3, 255, 0, 9],
            1,
            "binary data",
        ),
        case(
            "bad utf-16",
            "utf16.csv",
            vec![0xFF, 0xFE, 0x00, 0xD8, 0x41, 0x00],
            1,
            "UTF-16 text with invalid characters",
        ),
        case(
            "a byte Windows-1252 leaves undefined",
            "cp.csv",
            vec![b'C', b'1', b'+', 0x81, b'\n'],
            1,
            "W001",
        ),
        case("never home", "home.csv", csv("C1+1\n"), 1, "E022"),
        case("too many steps", "steps.csv", csv(&many_steps), 1, "E024"),
        case(
            "too many branches",
            "branches.csv",
            csv(&many_branches),
            1,
            "E024",
        ),
        case(
            "a very long cell",
            "long.csv",
            csv(&format!("C1+1\nC{}-0\n", "1".repeat(5000))),
            1,
            "E013",
        ),
        case(
            "a number",
            "number.csv",
            csv(",BRANCH 1\nSTEP 1,1.5\n"),
            1,
            "\"1.5\" is not a move",
        ),
        case(
            "a formula as text",
            "formula.csv",
            csv(",BRANCH 1\nSTEP 1,=C1+1\nSTEP 2,C1-0\n"),
            1,
            "\"=C1+1\" is not a move",
        ),
        case(
            "two moves in a cell without a ;",
            "two.csv",
            csv(",BRANCH 1\nSTEP 1,C1+1 C2+1\nSTEP 2,C1-0\n"),
            1,
            "is not a move",
        ),
        case(
            "math letters",
            "math.csv",
            csv(",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,\u{1D49E}1-0\n"),
            1,
            "E010",
        ),
        case("actuator zero", "c0.csv", csv("C0+1\nC0-0\n"), 1, "E011"),
        case(
            "actuator too large",
            "c1000.csv",
            csv("C1000+1\nC1000-0\n"),
            1,
            "E011",
        ),
        case(
            "position too large",
            "p64.csv",
            csv("C1+64\nC1-0\n"),
            1,
            "E012",
        ),
        case(
            "a control character",
            "bell.csv",
            csv(",BRANCH 1\nSTEP 1,C1+\u{7}1\nSTEP 2,C1-0\n"),
            1,
            "E010",
        ),
        case(
            "headers without moves",
            "headers.csv",
            csv(",BRANCH 1,BRANCH 2\nSTEP 1,,\nSTEP 2,,\n"),
            1,
            "no moves",
        ),
        case(
            "an unterminated quote",
            "quote.csv",
            csv(",BRANCH 1\nSTEP 1,\"C1+1\nSTEP 2,C1-0\n"),
            1,
            "E0",
        ),
        case(
            "a 16,384-column row of junk",
            "wide.csv",
            csv(&long_row),
            1,
            "E003",
        ),
        case(
            "a move outside the table",
            "outside.csv",
            csv(",BRANCH 1\nSTEP 1,C1+1,C2+1\nSTEP 2,C1-0,C2-0\n"),
            1,
            "outside the table",
        ),
        case(
            "unknown extension",
            "table.pdf",
            paper_csv().into_bytes(),
            1,
            "unknown file type",
        ),
        case(
            "no extension",
            "table",
            paper_csv().into_bytes(),
            1,
            "unknown file type",
        ),
        case("zero-byte xlsx", "zero.xlsx", vec![], 1, "E002"),
        case(
            "random bytes xlsx",
            "random.xlsx",
            (0..4096u32)
                .map(|i| (i.wrapping_mul(2654435761) >> 13) as u8)
                .collect(),
            1,
            "E002",
        ),
        case(
            "truncated xlsx",
            "half.xlsx",
            paper_xlsx[..paper_xlsx.len() / 2].to_vec(),
            1,
            "E002",
        ),
        case(
            "a zip without a workbook",
            "plain.xlsx",
            zip_of_zeros("hello.txt", 1 << 20),
            1,
            "E002",
        ),
        case(
            "xlsx named ods",
            "wrong.ods",
            paper_xlsx.clone(),
            1,
            "not a readable .ods workbook",
        ),
        case(
            "ods named xlsx",
            "wrong.xlsx",
            paper_ods.clone(),
            1,
            "not a readable .xlsx workbook",
        ),
        case(
            "csv named xlsx",
            "text.xlsx",
            paper_csv().into_bytes(),
            1,
            "not a readable .xlsx workbook",
        ),
        case(
            "random bytes xls",
            "random.xls",
            vec![0xD0, 0xCF, 0x11, 0xE0, 1, 2, 3, 4, 5, 6, 7, 8],
            1,
            "E002",
        ),
        case(
            "random bytes ods",
            "random.ods",
            vec![b'P', b'K', 3, 4, 9, 9, 9],
            1,
            "E002",
        ),
        case(
            "a zip bomb",
            "bomb.xlsx",
            zip_of_zeros("xl/worksheets/sheet1.xml", 300 << 20),
            1,
            "unpacks to 300 MiB",
        ),
        case("an empty workbook", "empty.xlsx", xlsx(|_| {}), 1, "E003"),
        case(
            // 6.2 GB and 4.4 s in calamine before the .ods guard.
            "ods cells a million repeated rows apart",
            "spread.ods",
            ods_of(concat!(
                r#"<table:table-row><table:table-cell office:value-type="string"><text:p>C1+1</text:p></table:table-cell></table:table-row>"#,
                r#"<table:table-row table:number-rows-repeated="999998"><table:table-cell table:number-columns-repeated="99"/></table:table-row>"#,
                r#"<table:table-row><table:table-cell table:number-columns-repeated="98"/><table:table-cell office:value-type="string"><text:p>C1-0</text:p></table:table-cell></table:table-row>"#,
            )),
            1,
            "its cells spread over a rectangle of 99000000 cells",
        ),
        case(
            // calamine reserved room for 4 billion strings and aborted.
            "a shared string table claiming 4 billion strings",
            "strings.xlsx",
            raw_xlsx(
                1,
                r#"<row r="1"><c r="A1" t="s"><v>0</v></c></row>"#,
                Some(
                    r#"<?xml version="1.0" encoding="UTF-8"?><sst xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main" count="4000000000" uniqueCount="4000000000"><si><t>C1+1</t></si></sst>"#,
                ),
            ),
            1,
            "claims 4000000000 shared strings",
        ),
        case(
            // calamine decoded the string whole: 245 KB holding 250 MB took 739 MB.
            "a shared string longer than a cell can hold",
            "long-string.xlsx",
            raw_xlsx(
                1,
                r#"<row r="1"><c r="A1" t="s"><v>0</v></c></row>"#,
                Some(&format!(
                    r#"<?xml version="1.0" encoding="UTF-8"?><sst xmlns="http://schemas.openxmlformats.org/spreadsheetml/2006/main" count="1" uniqueCount="1"><si><t>{}</t></si></sst>"#,
                    "C".repeat(1 << 20)
                )),
            ),
            1,
            "error[E005]: xl/sharedStrings.xml holds a text of more than 32768 characters; a cell holds at most 32767",
        ),
        case(
            "an inline string longer than a cell can hold",
            "long-inline.xlsx",
            raw_xlsx(
                1,
                &format!(
                    r#"<row r="1"><c r="A1" t="inlineStr"><is><t>{}</t></is></c></row>"#,
                    "&amp;".repeat(40_000)
                ),
                None,
            ),
            1,
            "error[E005]: xl/worksheets/sheet1.xml holds a text of more than 32768 characters",
        ),
        case(
            "3,000,100 filled cells",
            "dense.xlsx",
            raw_xlsx(
                30_001,
                &format!("<row>{}</row>", "<c><v>1</v></c>".repeat(100)),
                None,
            ),
            1,
            "the sheet has more than 3000000 filled cells",
        ),
        case(
            // Found while measuring #7: read as one dense rectangle this
            // needed 17 billion cells and the process aborted.
            "moves at A1 and XFD1048576",
            "corners.xlsx",
            xlsx(|s| {
                s.write_string(0, 0, "C1+1").unwrap();
                s.write_string(1_048_575, 16_383, "C1-0").unwrap();
            }),
            1,
            "table has 1048576 steps × 16384 branches",
        ),
        case(
            "a number cell",
            "num.xlsx",
            xlsx(|s| {
                s.write_string(0, 0, "C1+1").unwrap();
                s.write_number(1, 0, 42.0).unwrap();
                s.write_string(2, 0, "C1-0").unwrap();
            }),
            1,
            "the number 42 is not a move",
        ),
        case(
            "a boolean cell",
            "bool.xlsx",
            xlsx(|s| {
                s.write_string(0, 0, "C1+1").unwrap();
                s.write_boolean(1, 0, true).unwrap();
                s.write_string(2, 0, "C1-0").unwrap();
            }),
            1,
            "the value TRUE is not a move",
        ),
        case(
            "an error value",
            "ref.xlsx",
            xlsx(|s| {
                s.write_string(0, 0, "C1+1").unwrap();
                s.write_formula(1, 0, Formula::new("=1/0").set_result("#DIV/0!"))
                    .unwrap();
                s.write_string(2, 0, "C1-0").unwrap();
            }),
            1,
            "E010",
        ),
        case(
            "only junk far away",
            "far.xlsx",
            xlsx(|s| {
                s.write_string(1_048_575, 16_383, "junk").unwrap();
            }),
            1,
            "E003",
        ),
        case(
            "a sheet that is not there",
            "sheet.xlsx",
            paper_xlsx.clone(),
            1,
            "E004",
        ),
    ]
}

#[test]
fn every_hostile_file_is_refused_with_its_message_and_writes_nothing() {
    let cases = cases();
    assert!(cases.len() >= 40, "{} cases", cases.len());
    let dir = tempfile::tempdir().unwrap();
    for (i, c) in cases.iter().enumerate() {
        let folder = dir.path().join(format!("case{i}"));
        std::fs::create_dir(&folder).unwrap();
        let path = folder.join(c.file);
        std::fs::write(&path, &c.bytes).unwrap();
        let out = folder.join("out");
        let mut cmd = steptable();
        cmd.arg("convert").arg(&path).arg("-o").arg(&out);
        if c.file == "sheet.xlsx" {
            cmd.args(["--sheet", "NOPE"]);
        }
        let start = Instant::now();
        let output = cmd.output().unwrap();
        let took = start.elapsed();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(c.code), "{}: {stderr}", c.name);
        assert!(
            stderr.contains(c.needle),
            "{}: expected {:?} in: {stderr}",
            c.name,
            c.needle
        );
        assert!(!stderr.contains("panicked"), "{}: {stderr}", c.name);
        assert!(
            files_below(&out).is_empty(),
            "{}: wrote {:?}",
            c.name,
            files_below(&out)
        );
        assert!(took < Duration::from_secs(20), "{} took {took:?}", c.name);
    }
}

#[test]
fn a_folder_named_like_a_table_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let fake: PathBuf = dir.path().join("folder.csv");
    std::fs::create_dir(&fake).unwrap();
    steptable()
        .arg("check")
        .arg(&fake)
        .assert()
        .code(1)
        .stderr(predicates::str::contains("is a folder"));
}

/// Older Excel in Europe saves CSV as Windows-1252: read, with a warning.
#[test]
fn a_windows_1252_csv_is_read_with_a_warning() {
    let dir = tempfile::tempdir().unwrap();
    let path: &Path = &dir.path().join("alt.csv");
    let mut bytes =
        b"Zylinder f\xfcr die Presse\n,BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1\x960\n".to_vec();
    bytes.extend_from_slice(b"Stra\xdfe\n");
    std::fs::write(path, bytes).unwrap();
    steptable()
        .arg("check")
        .arg(path)
        .assert()
        .success()
        .stderr(predicates::str::contains(
            "warning[W001]: read as Windows-1252 text, not UTF-8",
        ))
        .stdout(predicates::str::contains("ok: 2 steps"));
}

/// A formula whose cached value is a move is that move.
#[test]
fn a_formula_showing_a_move_is_a_move() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("formula.xlsx");
    let bytes = xlsx(|s| {
        s.write_formula(0, 0, Formula::new("=\"C1+\"&\"1\"").set_result("C1+1"))
            .unwrap();
        s.write_string(1, 0, "C1-0").unwrap();
    });
    std::fs::write(&path, bytes).unwrap();
    steptable().arg("check").arg(&path).assert().success();
}

/// Input names that are no safe folder name (`...csv`, `..csv`, 250
/// characters) still write every file inside `DIR/NAME/`, and nothing
/// beside it.
#[test]
fn odd_input_names_write_inside_the_output_folder() {
    let dir = tempfile::tempdir().unwrap();
    let long = format!("{}.csv", "n".repeat(250));
    for name in ["...csv", "..csv", long.as_str()] {
        let work = dir.path().join(format!("w{}", name.len()));
        let out = work.join("out");
        std::fs::create_dir_all(&work).unwrap();
        let input = work.join(name);
        std::fs::write(&input, "C1+1\nC1-0\n").unwrap();
        crate::helpers::steptable()
            .arg("convert")
            .arg(&input)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        // Beside the input only the output folder; inside it one folder.
        let beside: Vec<_> = std::fs::read_dir(&work).unwrap().flatten().collect();
        assert_eq!(beside.len(), 2, "{name}: {beside:?}");
        let folders: Vec<_> = std::fs::read_dir(&out).unwrap().flatten().collect();
        assert_eq!(folders.len(), 1, "{name}");
        let files = crate::helpers::files_below(&folders[0].path());
        assert_eq!(files.len(), crate::helpers::all_files(), "{name}");
    }
}
