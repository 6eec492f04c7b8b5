//! Messy input through the binary, one case per class the second hostile
//! round found: content that was dropped silently, choices made without a
//! word. Each case states its exit code and what the engineer must read;
//! a refused input writes nothing.

use std::io::Write;
use std::path::Path;

use rust_xlsxwriter::Workbook;

use crate::helpers::{files_below, steptable};

/// One input, the command run on it, and what must come out.
struct Case {
    name: &'static str,
    file: &'static str,
    bytes: Vec<u8>,
    command: &'static [&'static str],
    code: i32,
    /// Each must appear in stdout or stderr.
    says: &'static [&'static str],
}

fn csv(text: &str) -> Vec<u8> {
    text.as_bytes().to_vec()
}

/// An `.xlsx` of sheets (name, hidden, rows from A1).
pub(crate) fn workbook(sheets: &[(&str, bool, &[&[&str]])]) -> Vec<u8> {
    let mut workbook = Workbook::new();
    // Excel cannot hide the sheet it opens on: open on the first visible one.
    let first_visible = sheets.iter().position(|s| !s.1);
    for (i, (name, hidden, rows)) in sheets.iter().enumerate() {
        let sheet = workbook.add_worksheet();
        sheet.set_name(*name).unwrap();
        for (r, row) in rows.iter().enumerate() {
            for (c, text) in row.iter().enumerate() {
                if !text.is_empty() {
                    sheet.write_string(r as u32, c as u16, *text).unwrap();
                }
            }
        }
        if *hidden {
            sheet.set_hidden(true);
        } else if Some(i) == first_visible {
            sheet.set_active(true);
        }
    }
    workbook.save_to_buffer().unwrap()
}

const FIG7: &[&[&str]] = &[
    &["", "BRANCH 1", "BRANCH 2"],
    &["STEP 1", "C1+1", ""],
    &["STEP 2", "C2+1", "C1-0"],
    &["STEP 3", "C2-0", ""],
];

const OLD: &[&[&str]] = &[&["", "BRANCH 1"], &["STEP 1", "C5+1"], &["STEP 2", "C5-0"]];

/// An `.xlsx` whose B2 holds a formula saved without its value, as programs
/// that write formulas without calculating them do.
pub(crate) fn uncomputed_formula() -> Vec<u8> {
    let mut bytes = workbook(&[("SEQUENTIAL CONTROL DESCRIPTION", false, FIG7)]);
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes.clone())).unwrap();
    let mut out = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let cell = regex::Regex::new(r#"<c r="B3"[^>]*>.*?</c>"#).unwrap();
    for i in 0..archive.len() {
        let mut entry = archive.by_index(i).unwrap();
        let name = entry.name().unwrap().to_string();
        let mut text = Vec::new();
        std::io::Read::read_to_end(&mut entry, &mut text).unwrap();
        if name == "xl/worksheets/sheet1.xml" {
            let xml = String::from_utf8(text).unwrap();
            assert!(cell.is_match(&xml));
            let xml = cell.replace(&xml, r#"<c r="B3" t="str"><f>"C2"&amp;"+1"</f></c>"#);
            text = xml.into_owned().into_bytes();
        }
        out.start_file(name, zip::write::SimpleFileOptions::default())
            .unwrap();
        out.write_all(&text).unwrap();
    }
    bytes = out.finish().unwrap().into_inner();
    bytes
}

/// A table and a SETTINGS sheet whose stroke row carries a comment.
fn settings_with(rows: &[&[&str]]) -> Vec<u8> {
    workbook(&[
        ("SEQUENTIAL CONTROL DESCRIPTION", false, FIG7),
        ("SETTINGS", false, rows),
    ])
}

fn cases() -> Vec<Case> {
    let check: &'static [&'static str] = &["check"];
    let simulate: &'static [&'static str] = &["simulate"];
    vec![
        Case {
            name: "misspelt BRANCH header over moves",
            file: "t.csv",
            bytes: csv(",BRANH 1,BRANCH 2\nSTEP 1,C1+1,C2+1\nSTEP 2,C1-0,C2-0\n"),
            command: check,
            code: 1,
            says: &[
                "t.csv:1:2: warning[W003]: \"BRANH 1\"",
                "t.csv:2:2: error[E010]: \"C1+1\" lies outside the table",
            ],
        },
        Case {
            name: "misspelt header of a one-branch table",
            file: "t.csv",
            bytes: csv(",BRANH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n"),
            command: check,
            code: 0,
            says: &["t.csv:1:2: warning[W003]: \"BRANH 1\"", "ok: 2 steps"],
        },
        Case {
            name: "row without a STEP label",
            file: "t.csv",
            bytes: csv(",BRANCH 1\nSTEP 1,C1+1\n,I:part_present\nSTEP 2,C1-0\n"),
            command: check,
            code: 1,
            says: &[
                "t.csv:3:2: error[E010]: \"I:part_present\"",
                "no STEP label",
            ],
        },
        Case {
            name: "STEP label with a comment",
            file: "t.csv",
            bytes: csv(",BRANCH 1\nSTEP 1,C1+1\nSTEP 2 (clamp),T=2s\nSTEP 3,C1-0\n"),
            command: simulate,
            code: 0,
            says: &["T=2s ran"],
        },
        Case {
            name: "two tables on one sheet",
            file: "t.csv",
            bytes: csv(
                ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n\n,BRANCH 1\nSTEP 1,C2+1\nSTEP 2,C2-0\n",
            ),
            command: check,
            code: 1,
            says: &["t.csv:5:2: error[E027]: a second table"],
        },
        Case {
            name: "a move below the last labelled row",
            file: "t.csv",
            bytes: csv(",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n,C2+1\n"),
            command: check,
            code: 1,
            says: &["t.csv:4:2: error[E010]: \"C2+1\"", "below the table"],
        },
        Case {
            name: "remarks column",
            file: "t.csv",
            bytes: csv(",BRANCH 1,remark\nSTEP 1,C1+1,clamp it\nSTEP 2,C1-0\n"),
            command: check,
            code: 0,
            says: &[
                "t.csv:1:3: warning[W003]: \"remark\"",
                "t.csv:2:3: warning[W003]: \"clamp it\"",
            ],
        },
        Case {
            name: "a ; inside a comma file's cell stays in its branch",
            file: "t.csv",
            bytes: csv(",BRANCH 1\nSTEP 1,C1+1; T=2s\nSTEP 2,C1-0\n"),
            command: check,
            code: 0,
            says: &["ok: 2 steps, 1 branch(es)"],
        },
        Case {
            name: "a one-column file whose ; may be either",
            file: "t.csv",
            bytes: csv("C1+1; T=2s\nC1-0\n"),
            command: check,
            code: 0,
            says: &[
                "warning[W005]: read as comma-separated",
                "ok: 2 steps, 1 branch(es)",
            ],
        },
        Case {
            name: "unquoted decimal comma in a comma file",
            file: "t.csv",
            bytes: csv(",BRANCH 1\nSTEP 1,C1+1; T=1,5s\nSTEP 2,C1-0\n"),
            command: check,
            code: 1,
            says: &["t.csv:2:3: error[E014]", "T=1,5s"],
        },
        Case {
            name: "decimal comma in a semicolon file",
            file: "t.csv",
            bytes: csv(";BRANCH 1;BRANCH 2\nSTEP 1;C1+1;T=1,5s\nSTEP 2;C1-0;\n"),
            command: simulate,
            code: 0,
            says: &["T=1.5s ran"],
        },
        Case {
            name: "hidden old sheet with the documented name",
            file: "t.xlsx",
            bytes: workbook(&[
                ("SEQUENTIAL CONTROL DESCRIPTION", true, OLD),
                ("v2", false, FIG7),
            ]),
            command: check,
            code: 0,
            says: &[
                "warning[W004]: the table was read from sheet \"v2\"",
                "is hidden",
                "ok: 3 steps",
            ],
        },
        Case {
            name: "legend sheet before the table",
            file: "t.xlsx",
            bytes: workbook(&[
                (
                    "Legend",
                    false,
                    &[
                        &["C1+1", "cylinder 1 extends"],
                        &["C1-0", "cylinder 1 home"],
                    ],
                ),
                ("Plan", false, FIG7),
            ]),
            command: check,
            code: 0,
            says: &[
                "warning[W004]: the table was read from sheet \"Plan\"",
                "Legend",
                "ok: 3 steps",
            ],
        },
        Case {
            name: "only a hidden sheet holds the table",
            file: "t.xlsx",
            bytes: workbook(&[("Notes", false, &[&["see the plan"]]), ("Plan", true, FIG7)]),
            command: check,
            code: 0,
            says: &["warning[W004]", "\"Plan\" is hidden", "ok: 3 steps"],
        },
        Case {
            name: "formula without a computed value",
            file: "t.xlsx",
            bytes: uncomputed_formula(),
            command: check,
            code: 1,
            says: &["!B3: error[E016]: the formula =\"C2\"&\"+1\" has no computed value"],
        },
        Case {
            name: "SETTINGS row naming C1 (clamp)",
            file: "t.xlsx",
            bytes: settings_with(&[
                &["actuator", "extend", "retract", "valve"],
                &["C1 (clamp)", "5s", "5s", "52mono"],
            ]),
            command: simulate,
            code: 0,
            // 5 s strokes of C1 (1 s without the row): out, home beside C2, C2 home.
            says: &["passed: cycle time 10.70 s"],
        },
        Case {
            name: "SETTINGS label misspelt",
            file: "t.xlsx",
            bytes: settings_with(&[&["scan-time", "20ms"]]),
            command: check,
            // A known label misspelt: its row would be lost (E046).
            code: 1,
            says: &[
                "SETTINGS!A1: error[E046]: \"scan-time\" is not a setting steptable knows: did you mean `scan time`?",
            ],
        },
        Case {
            name: "SETTINGS row that names no actuator",
            file: "t.xlsx",
            bytes: settings_with(&[&["actuator", "extend", "retract"], &["Cl", "5s", "5s"]]),
            command: check,
            code: 1,
            says: &["SETTINGS!A2: error[E030]: \"Cl\" is not an actuator"],
        },
    ]
}

#[test]
fn messy_input_is_read_or_reported_never_dropped() {
    let dir = tempfile::tempdir().unwrap();
    for (i, case) in cases().iter().enumerate() {
        let folder = dir.path().join(format!("case{i}"));
        std::fs::create_dir(&folder).unwrap();
        let input = folder.join(case.file);
        std::fs::write(&input, &case.bytes).unwrap();
        let output = steptable()
            .args(case.command)
            .arg(case.file)
            .current_dir(&folder)
            .output()
            .unwrap();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        );
        assert_eq!(
            output.status.code(),
            Some(case.code),
            "{}: {text}",
            case.name
        );
        for needle in case.says {
            assert!(
                text.contains(needle),
                "{}: expected {needle:?} in:\n{text}",
                case.name
            );
        }
        // A refused input converts to nothing.
        if case.code != 0 {
            let out = folder.join("out");
            let status = steptable()
                .args(["convert", case.file, "-o"])
                .arg(&out)
                .current_dir(&folder)
                .output()
                .unwrap();
            assert_eq!(status.status.code(), Some(1), "{}", case.name);
            assert!(files_below(&out).is_empty(), "{}", case.name);
        }
        assert!(Path::new(&input).exists());
    }
}
