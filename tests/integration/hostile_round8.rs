//! The eighth round of hostile input: what the red team rt14 found in the
//! spreadsheet's own structure. A value under a merged cell, which Excel
//! and LibreOffice hide behind the merge's first cell, was read as if it
//! were seen (or, on SETTINGS, dropped). Each row goes through the binary:
//! its exit code, the code at its cell, and that nothing was written.

use crate::helpers::steptable;
use rust_xlsxwriter::{Format, Workbook, Worksheet};

/// `check` and `convert` of `bytes` (saved as `name`) both exit 1, say
/// each of `says`, and write nothing.
pub(crate) fn refused(name: &str, bytes: Vec<u8>, says: &[&str]) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).unwrap();
    for command in ["check", "convert"] {
        let out = dir.path().join("out");
        let mut run = steptable();
        run.arg(command).arg(&path);
        if command == "convert" {
            run.arg("-o").arg(&out);
        }
        let output = run.output().unwrap();
        let said = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{name}, {command}: {said}");
        for line in says {
            assert!(said.contains(line), "{name}, {command}: no {line}\n{said}");
        }
        assert!(!out.exists(), "{name}, {command} wrote files");
    }
}

pub(crate) fn write_rows(sheet: &mut Worksheet, rows: &[&[&str]]) {
    for (r, row) in rows.iter().enumerate() {
        for (c, text) in row.iter().enumerate().filter(|(_, t)| !t.is_empty()) {
            sheet.write_string(r as u32, c as u16, *text).unwrap();
        }
    }
}

const FOUR: &[&[&str]] = &[
    &["", "BRANCH 1"],
    &["STEP 1", "C1+1"],
    &["STEP 2", "C2+1"],
    &["STEP 3", "C2-0"],
    &["STEP 4", "C1-0"],
];

/// An `.xlsx` of the four-step table whose `merge` cells are merged, then
/// `under` written beneath the merge's first cell, where Excel hides it.
pub(crate) fn merged_xlsx(
    settings: Option<&[&[&str]]>,
    merge: (u32, u16, u32, u16),
    under: (u32, u16, &str),
) -> Vec<u8> {
    let mut workbook = Workbook::new();
    let table = workbook.add_worksheet();
    table.set_name("SEQUENTIAL CONTROL DESCRIPTION").unwrap();
    write_rows(table, FOUR);
    let sheet = match settings {
        Some(rows) => {
            let sheet = workbook.add_worksheet();
            sheet.set_name("SETTINGS").unwrap();
            write_rows(sheet, rows);
            sheet
        }
        None => workbook.worksheet_from_index(0).unwrap(),
    };
    let (r0, c0, r1, c1) = merge;
    let first = sheet_text(settings.unwrap_or(FOUR), r0, c0);
    sheet
        .merge_range(r0, c0, r1, c1, &first, &Format::new())
        .unwrap();
    sheet.write_string(under.0, under.1, under.2).unwrap();
    workbook.save_to_buffer().unwrap()
}

fn sheet_text(rows: &[&[&str]], row: u32, col: u16) -> String {
    let row = rows.get(row as usize).copied().unwrap_or_default();
    row.get(col as usize)
        .copied()
        .unwrap_or_default()
        .to_string()
}

/// A move, a setting's value, a step beneath a merged cell is E049 at its
/// cell, naming the merge; it was read (a move nobody sees in the table)
/// or dropped (a setting) with exit 0 (rt14 F1).
#[test]
fn a_value_hidden_under_a_merged_cell_is_refused_at_its_cell() {
    refused(
        "move.xlsx",
        merged_xlsx(None, (2, 1, 2, 2), (2, 2, "C3+1")),
        &[
            "!C3: error[E049]: \"C3+1\" lies under the merged cell B3:C3, where the spreadsheet shows only B3's value",
        ],
    );
    refused(
        "label.xlsx",
        merged_xlsx(None, (3, 0, 4, 0), (4, 0, "STEP 4")),
        &["!A5: error[E049]: \"STEP 4\" lies under the merged cell A4:A5"],
    );
    let settings: &[&[&str]] = &[&["modes", "estop, reset"], &["interlock", ""]];
    refused(
        "setting.xlsx",
        merged_xlsx(Some(settings), (1, 0, 1, 1), (1, 1, "guard")),
        &["SETTINGS!B2: error[E049]: \"guard\" lies under the merged cell A2:B2"],
    );
}

/// A merge with nothing beneath its first cell (a title over the table, a
/// header over two columns) hides nothing: the table converts.
#[test]
fn a_merge_that_hides_nothing_is_read() {
    let mut workbook = Workbook::new();
    let sheet = workbook.add_worksheet();
    let rows: Vec<&[&str]> = std::iter::once(&["Clamp and drill"][..])
        .chain(std::iter::once(&[""][..]))
        .chain(FOUR.iter().copied())
        .collect();
    write_rows(sheet, &rows);
    sheet
        .merge_range(0, 0, 0, 3, "Clamp and drill", &Format::new())
        .unwrap();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("title.xlsx");
    std::fs::write(&path, workbook.save_to_buffer().unwrap()).unwrap();
    let output = steptable().arg("check").arg(&path).output().unwrap();
    let said = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{said}");
    assert!(!said.contains("E049"), "{said}");
}

/// An `.ods` merge is a cell spanning columns or rows; the cells it covers
/// keep their content in the file (LibreOffice asks whether to keep it when
/// merging). calamine reads that content as any other cell.
#[test]
fn a_value_under_an_ods_merge_is_refused_at_its_cell() {
    let cell = |text: &str| {
        format!(
            "<table:table-cell office:value-type=\"string\"><text:p>{text}</text:p></table:table-cell>"
        )
    };
    let row = |cells: &[String]| format!("<table:table-row>{}</table:table-row>", cells.concat());
    let table = [
        row(&[cell(""), cell("BRANCH 1")]),
        row(&[cell("STEP 1"), cell("C1+1")]),
        row(&[
            cell("STEP 2"),
            "<table:table-cell table:number-columns-spanned=\"2\" office:value-type=\"string\"><text:p>C2+1</text:p></table:table-cell>".to_string(),
            "<table:covered-table-cell office:value-type=\"string\"><text:p>C3+1</text:p></table:covered-table-cell>".to_string(),
        ]),
        row(&[cell("STEP 3"), cell("C2-0")]),
        row(&[cell("STEP 4"), cell("C1-0")]),
    ]
    .concat();
    refused(
        "merge.ods",
        crate::hostile::ods_of(&table),
        &["!C3: error[E049]: \"C3+1\" lies under the merged cell B3:C3"],
    );
}

/// `check` of the CSV `text`: its exit code and what it said (stdout,
/// then stderr).
fn check_csv(text: &str) -> (Option<i32>, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.csv");
    std::fs::write(&path, text).unwrap();
    let output = steptable().arg("check").arg(&path).output().unwrap();
    let said = [&output.stdout, &output.stderr].map(|b| String::from_utf8_lossy(b).into_owned());
    (output.status.code(), said.concat())
}

/// `STEP 2;C1-0; T=2s` unquoted: the semicolon inside the cell split it,
/// and the dwell became branch 2's move of that step, exit 0 (rt14 F7).
/// The space after the delimiter gives the split away: E050 at it.
#[test]
fn a_cell_split_by_an_unquoted_delimiter_is_refused() {
    let cases: &[(&str, &str, &str)] = &[
        (
            "semicolon file",
            ";BRANCH 1;BRANCH 2\nSTEP 1;C1+1;C2+1\nSTEP 2;C1-0; T=2s\nSTEP 3;;C2-0\n",
            "t.csv:3:3: error[E050]: \"T=2s\" follows \"C1-0\" after a space and a ';'",
        ),
        (
            "comma file",
            ",BRANCH 1,BRANCH 2\nSTEP 1,C1+1,C2+1\nSTEP 2,C1-0, C2-0\n",
            "t.csv:3:3: error[E050]: \"C2-0\" follows \"C1-0\" after a space and a ','",
        ),
    ];
    for (name, text, says) in cases {
        let (code, said) = check_csv(text);
        assert_eq!(code, Some(1), "{name}: {said}");
        assert!(said.contains(says), "{name}: {said}");
        // The STEP label and the first move are never one cell.
        assert_eq!(said.matches("E050").count(), 1, "{name}: {said}");
    }
    // A row, or a file, written with a space after every delimiter: read
    // as written.
    let row_spaced =
        ";BRANCH 1;BRANCH 2\nSTEP 1;C1+1;C2+1\nSTEP 2; C1-0; T=2s\nSTEP 3;;C2-0\nSTEP 4;;T=1s\n";
    let (code, said) = check_csv(row_spaced);
    assert_eq!(code, Some(0), "{said}");
    let spaced = ";BRANCH 1;BRANCH 2\nSTEP 1; C1+1; C2+1\nSTEP 2; C1-0; T=2s\nSTEP 3; ; C2-0\n";
    let (code, said) = check_csv(spaced);
    assert_eq!(code, Some(0), "{said}");
    // Quoted, the cell is whole.
    let quoted = ";BRANCH 1;BRANCH 2\nSTEP 1;C1+1;C2+1\nSTEP 2;\"C1-0; T=2s\";\nSTEP 3;;C2-0\n";
    let (code, said) = check_csv(quoted);
    assert_eq!(code, Some(0), "{said}");
}

/// Excel's `sep=,` first line names the delimiter. It was a W003 cell and
/// the delimiter was guessed from the content, overruling it (rt14 F28).
#[test]
fn a_sep_line_names_the_delimiter() {
    // Declared and used: read with it, the line used (no W003).
    let (code, said) = check_csv("sep=;\n;BRANCH 1;BRANCH 2\nSTEP 1;C1+1;C2+1\nSTEP 2;C1-0;C2-0\n");
    assert_eq!(code, Some(0), "{said}");
    assert!(
        said.contains("2 branch(es)") && !said.contains("W003"),
        "{said}"
    );
    // A delimiter no other reading knows.
    let (code, said) = check_csv("SEP=|\r\n|BRANCH 1\r\nSTEP 1|C1+1; T=1s\r\nSTEP 2|C1-0\r\n");
    assert_eq!(code, Some(0), "{said}");
    assert!(said.contains("2 steps, 1 branch(es)"), "{said}");
    // Declared and never used, where another is: read as declared (no
    // table), and said.
    let (code, said) = check_csv("sep=,\n;BRANCH 1\nSTEP 1;C1+1\nSTEP 2;C1-0\n");
    assert_eq!(code, Some(1), "{said}");
    assert!(
        said.contains("t.csv:1:1: warning[W005]: the first line sep=, declares the delimiter, but the file holds none outside quotes, and 3 ';'"),
        "{said}"
    );
    // Rows stay file lines: the move on line 4 is named there.
    let (code, said) = check_csv("sep=;\n;BRANCH 1\nSTEP 1;C1+1\nSTEP 2;C1-0;C9+1\n");
    assert_eq!(code, Some(1), "{said}");
    assert!(said.contains("t.csv:4:3: error[E010]"), "{said}");
}

/// Settings written below or beside the table on its sheet were read as
/// notes and left alone, exit 0: an interlock the engineer wrote was not
/// in the program (rt14 F23). Settings are read from SETTINGS only: E030 at
/// the label, naming where they go.
#[test]
fn a_setting_written_with_the_table_is_refused() {
    let below: Vec<&[&str]> = FOUR
        .iter()
        .copied()
        .chain([&[""][..], &[""], &["interlock", "guard in steps 2-3"]])
        .collect();
    let mut workbook = Workbook::new();
    write_rows(workbook.add_worksheet(), &below);
    refused(
        "below.xlsx",
        workbook.save_to_buffer().unwrap(),
        &[
            "!A8: error[E030]: \"interlock\" and its value name a setting, but they lie with the step table, where settings are not read (the program would be made without it); move them to the SETTINGS sheet",
        ],
    );
    let beside: Vec<Vec<&str>> = FOUR
        .iter()
        .enumerate()
        .map(|(i, row)| {
            let mut row = row.to_vec();
            if i == 1 {
                row.extend(["", "Modes:", "estop, reset"]);
            }
            row
        })
        .collect();
    let beside: Vec<&[&str]> = beside.iter().map(Vec::as_slice).collect();
    let mut workbook = Workbook::new();
    write_rows(workbook.add_worksheet(), &beside);
    refused(
        "beside.xlsx",
        workbook.save_to_buffer().unwrap(),
        &["!D2: error[E030]: \"Modes:\" and its value name a setting"],
    );
    let (code, said) = check_csv(",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n\n\nhome order,C1\n");
    assert_eq!(code, Some(1), "{said}");
    assert!(
        said.contains("t.csv:6:1: error[E030]: \"home order\" and its value name a setting")
            && said.contains("a CSV file holds the step table only"),
        "{said}"
    );
    // A title word alone is a note.
    let (code, said) = check_csv(",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n\n\nSafety\n");
    assert_eq!(code, Some(0), "{said}");
}

/// An actuator table headed `extend time | retract time | valve type`: its
/// columns were notes (W003), and the program was written with the default
/// strokes and valves, exit 0 (rt14 F21). A header's first word names its
/// column when no other word names another.
#[test]
fn an_actuator_header_with_a_unit_or_a_word_after_it_is_read() {
    let settings: &[&[&str]] = &[
        &[
            "Actuator (cylinder)",
            "Extend time [s]",
            "retract time",
            "Valves",
        ],
        &["C1", "2s", "3s", "53closed"],
        &["C2", "1s", "1s", "52bi"],
    ];
    let mut workbook = Workbook::new();
    write_rows(workbook.add_worksheet(), FOUR);
    let sheet = workbook.add_worksheet();
    sheet.set_name("SETTINGS").unwrap();
    write_rows(sheet, settings);
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("a.xlsx");
    std::fs::write(&path, workbook.save_to_buffer().unwrap()).unwrap();
    let output = steptable().arg("simulate").arg(&path).output().unwrap();
    let said = [&output.stdout, &output.stderr].map(|b| String::from_utf8_lossy(b).into_owned());
    let said = said.concat();
    assert_eq!(output.status.code(), Some(0), "{said}");
    assert!(!said.contains("W003"), "{said}");
    // C1 extends in 2 s (less a scan to the sensor), C2 in 1 s: the
    // table's times, not the default strokes.
    assert!(said.contains("1.96 s  C1+1"), "{said}");
    assert!(said.contains("0.98 s  C2+1"), "{said}");
    // Two known words: which column is meant cannot be told, and read as
    // a note the column's values would be lost (rt16 F8).
    let settings: &[&[&str]] = &[&["actuator", "extend/retract"], &["C1", "2s"]];
    let mut workbook = Workbook::new();
    write_rows(workbook.add_worksheet(), FOUR);
    let sheet = workbook.add_worksheet();
    sheet.set_name("SETTINGS").unwrap();
    write_rows(sheet, settings);
    std::fs::write(&path, workbook.save_to_buffer().unwrap()).unwrap();
    let output = steptable().arg("check").arg(&path).output().unwrap();
    let said = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{said}");
    assert!(
        said.contains("SETTINGS!B1: error[E046]: \"extend/retract\" heads no column"),
        "{said}"
    );
}

/// The template's `SETTING | VALUE | WHAT IT MEANS`: a value typed into
/// the notes column, its own cell empty, was a note, with a W003 at the
/// label and exit 0; the setting was not in the program (rt14 F15). A
/// note that is a valid value of its row's setting is E030 at it, where
/// values come from a closed list (a note on a row of names is a note).
#[test]
fn a_value_typed_into_the_notes_column_is_refused() {
    let settings: &[&[&str]] = &[
        &["SETTING", "VALUE", "WHAT IT MEANS"],
        &["modes", "estop, reset", "the modes the program has"],
        &["safety", "", "watchdog"],
        // A row that takes names: its note is a note (W003 at the label).
        &["hold-safe", "", "gripper keeps part"],
    ];
    let mut workbook = Workbook::new();
    write_rows(workbook.add_worksheet(), FOUR);
    let sheet = workbook.add_worksheet();
    sheet.set_name("SETTINGS").unwrap();
    write_rows(sheet, settings);
    refused(
        "notes.xlsx",
        workbook.save_to_buffer().unwrap(),
        &[
            "SETTINGS!C3: error[E030]: \"watchdog\" reads as the value of safety, but lies in the column of notes, where nothing is read, while the value's cell B3 is empty",
            "SETTINGS!A4: warning[W003]: hold-safe has no value",
        ],
    );
}

/// The red team rt15 on the rules above: a setting's value far right of
/// its label, a misspelt label, a label and value in one cell (on the
/// table's sheet and in a CSV); a tab-split cell; a note or a header row
/// with spaces (no E050); an .ods formula that computes "" (no E016); a
/// note's row below the table (no advice to label a filled cell).
#[test]
fn the_red_teams_second_look_at_the_reading_rules() {
    let table = ",BRANCH 1,BRANCH 2\nSTEP 1,C1+1,C2+1\nSTEP 2,C1-0,C2-0\n\n";
    let rows: &[(&str, Option<i32>, &str)] = &[
        (
            "modes,,,all\n",
            Some(1),
            "t.csv:5:1: error[E030]: \"modes\" and its value name a setting",
        ),
        (
            "mode,all\n",
            Some(1),
            "t.csv:5:1: error[E046]: \"mode\" and its value read as the setting `modes` misspelt",
        ),
        (
            "safety=all\n",
            Some(1),
            "t.csv:5:1: error[E046]: \"safety=all\" holds the setting safety and its value in one cell",
        ),
        // A label beside what is no value of it is a note.
        ("Target,30 parts/min\n", Some(0), "ok: 2 steps"),
        ("Model,DSNU-16\n", Some(0), "ok: 2 steps"),
        ("Target date: June\n", Some(0), "ok: 2 steps"),
        (
            "Note,see drawing, page 3\n",
            Some(0),
            "ok: 2 steps, 2 branch(es)",
        ),
        // A note row's part under a BRANCH header is a note, named (rt16
        // F14); only one that reads wholly as moves would be lost.
        (
            "Note,C2 stops midway\n",
            Some(0),
            "t.csv:5:2: warning[W003]: \"C2 stops midway\" is not part of the step table and was not read: its row 5 lies below the table's last step, STEP 2 (row 3), and is no step: its label cell 5:1 holds \"Note\"",
        ),
        (
            "Note,C2+1\n",
            Some(1),
            "t.csv:5:2: error[E010]: \"C2+1\" lies outside the table and would be lost",
        ),
    ];
    let mut broken = Vec::new();
    for (line, code, says) in rows {
        let (got, said) = check_csv(&format!("{table}{line}"));
        if got != *code || !said.contains(says) {
            broken.push(format!("{line}: exit {got:?}\n{said}"));
        }
    }
    // A tab never splits a cell of items: a space after it is alignment.
    let (got, said) = check_csv("\tBRANCH 1\tBRANCH 2\nSTEP 1\tC1+1\t C2+1\nSTEP 2\tC1-0\t C2-0\n");
    if got != Some(0) {
        broken.push(format!("tab: exit {got:?}\n{said}"));
    }
    let (got, said) = check_csv(";BRANCH 1; BRANCH 2\nSTEP 1;C1+1;C2+1\nSTEP 2;C1-0;C2-0\n");
    if got != Some(0) {
        broken.push(format!("spaced header: exit {got:?}\n{said}"));
    }
    assert!(broken.is_empty(), "{}", broken.join("\n\n"));
}

/// A formula that computes "" (`=IF(...;"";...)`, common in templates) is
/// saved in an .ods with its value type: computed, an empty cell, not E016.
#[test]
fn an_ods_formula_that_computes_nothing_is_an_empty_cell() {
    let cell = |text: &str| {
        format!(
            "<table:table-cell office:value-type=\"string\"><text:p>{text}</text:p></table:table-cell>"
        )
    };
    let row = |cells: &[String]| format!("<table:table-row>{}</table:table-row>", cells.concat());
    let empty = "<table:table-cell table:formula=\"of:=IF(1=1;&quot;&quot;;&quot;C3+1&quot;)\" office:value-type=\"string\" office:string-value=\"\" calcext:value-type=\"string\"/>".to_string();
    let table = [
        row(&[cell(""), cell("BRANCH 1")]),
        row(&[cell("STEP 1"), cell("C1+1")]),
        row(&[cell("STEP 2"), cell("C1-0")]),
        row(&[cell(""), empty]),
    ]
    .concat();
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("e.ods");
    std::fs::write(&path, crate::hostile::ods_of(&table)).unwrap();
    let output = steptable().arg("check").arg(&path).output().unwrap();
    let said = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{said}");
    assert!(!said.contains("E016"), "{said}");
}
