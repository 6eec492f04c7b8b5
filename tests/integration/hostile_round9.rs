//! The ninth round of hostile input: what the red teams rt15 and rt16
//! left. A misspelt label with its value in one cell (`mode: all`) was
//! dropped without a word on the table's sheet and only W003 on SETTINGS;
//! an actuator-table header naming its column in another word than the
//! first (`stroke time extend`, `solenoid valve`) lost the column's values
//! with a W003; settings on a sheet of another name (`PARAMETERS`) were
//! ignored in silence. Each row goes through the binary: exit code, the
//! code at its cell, and that a refused input writes nothing.

use crate::helpers::steptable;
use crate::hostile_round8::{refused, write_rows};
use rust_xlsxwriter::Workbook;

const TABLE: &[&[&str]] = &[
    &["", "BRANCH 1", "BRANCH 2"],
    &["STEP 1", "C1+1"],
    &["STEP 2", "C2+1"],
    &["STEP 3", "C2-0", "C1-0"],
];

/// A workbook of the table, with `below` written two rows under it on its
/// sheet, and each `(name, rows)` sheet after it.
pub(crate) fn workbook(below: &[&str], sheets: &[(&str, &[&[&str]])]) -> Vec<u8> {
    let mut workbook = Workbook::new();
    let table = workbook.add_worksheet();
    table.set_name("SEQUENTIAL CONTROL DESCRIPTION").unwrap();
    write_rows(table, TABLE);
    for (c, text) in below.iter().enumerate() {
        table.write_string(6, c as u16, *text).unwrap();
    }
    for (name, rows) in sheets {
        let sheet = workbook.add_worksheet();
        sheet.set_name(*name).unwrap();
        write_rows(sheet, rows);
    }
    workbook.save_to_buffer().unwrap()
}

/// `check` of `bytes`: exit code and what was said.
pub(crate) fn check(bytes: Vec<u8>) -> (Option<i32>, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.xlsx");
    std::fs::write(&path, bytes).unwrap();
    let output = steptable().arg("check").arg(&path).output().unwrap();
    let said = [&output.stdout, &output.stderr].map(|b| String::from_utf8_lossy(b).into_owned());
    (output.status.code(), said.concat())
}

/// A misspelt label and a valid value of the label meant, in one cell:
/// E046 on the table's sheet, in a CSV and on SETTINGS (rt16 F6), as the
/// same label spelt right is. A note that only looks like one (`Model:
/// DSNU-16`, `Note: mode all`) is read as a note.
#[test]
fn a_misspelt_setting_with_its_value_in_one_cell_is_refused() {
    let table_sheet = "SEQUENTIAL CONTROL DESCRIPTION!A7: error[E046]";
    for text in [
        "mode: all",
        "mode all",
        "mode = all",
        "saftey=all",
        "scantime 20ms",
    ] {
        refused(
            "table.xlsx",
            workbook(&[text], &[]),
            &[table_sheet, "misspelt, with its value in one cell"],
        );
        let settings: &[&[&str]] = &[&["target", "iec"], &[], &[text]];
        refused(
            "settings.xlsx",
            workbook(&[], &[("SETTINGS", settings)]),
            &[
                "SETTINGS!A3: error[E046]",
                "misspelt, with its value in one cell",
            ],
        );
    }
    refused(
        "table.csv",
        b",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n\nmode: estop\n".to_vec(),
        &["table.csv:5:1: error[E046]", "`modes` misspelt"],
    );
    for note in ["Model: DSNU-16", "Note: mode all", "mode: see drawing"] {
        let (code, said) = check(workbook(&[note], &[]));
        assert_eq!(code, Some(0), "{note}: {said}");
        assert!(!said.contains("E046"), "{note}: {said}");
        let settings: &[&[&str]] = &[&["target", "iec"], &[], &[note]];
        let (code, said) = check(workbook(&[], &[("SETTINGS", settings)]));
        assert_eq!(code, Some(0), "{note}: {said}");
        assert!(
            said.contains("SETTINGS!A3: warning[W003]"),
            "{note}: {said}"
        );
    }
}

/// An actuator-table header that names a column in another word than its
/// first, or names two, over values: E046 at the header, nothing written
/// (rt16 F8); the values had been dropped with a W003. A header that names
/// none (`designation`) is a column of notes, W003 as before.
#[test]
fn an_actuator_header_naming_its_column_elsewhere_is_refused() {
    let rows = [
        (
            "stroke time extend",
            "2s",
            "the column `extend`, but not as its first word",
        ),
        (
            "Time to extend",
            "2s",
            "the column `extend`, but not as its first word",
        ),
        (
            "ExtendTime",
            "2s",
            "the column `extend`, but not as its first word",
        ),
        (
            "solenoid valve",
            "52bi",
            "the column `valve`, but not as its first word",
        ),
        (
            "Actuator name",
            "clamp",
            "the column `name`, but not as its first word",
        ),
        ("Load on extend", "0.2", "the columns `extend` and `load`"),
        ("name of valve", "clamp", "the columns `valve` and `name`"),
    ];
    for (header, value, says) in rows {
        let settings: &[&[&str]] = &[&["actuator", "retract", header], &["C1", "1s", value]];
        refused(
            "header.xlsx",
            workbook(&[], &[("SETTINGS", settings)]),
            &["SETTINGS!C1: error[E046]", says],
        );
    }
    // Another form of the column's word, first: that column (rt17 F8).
    for header in ["Extended", "Extending", "Extension time"] {
        let settings: &[&[&str]] = &[&["actuator", header], &["C1", "2s"]];
        let (code, said) = check(workbook(&[], &[("SETTINGS", settings)]));
        assert_eq!(code, Some(0), "{header}: {said}");
        assert!(
            !said.contains("W003") && !said.contains("E046"),
            "{header}: {said}"
        );
    }
    // No value under it: nothing is lost, a W003 names the header.
    let settings: &[&[&str]] = &[&["actuator", "retract", "solenoid valve"], &["C1", "1s"]];
    let (code, said) = check(workbook(&[], &[("SETTINGS", settings)]));
    assert_eq!(code, Some(0), "{said}");
    assert!(said.contains("SETTINGS!C1: warning[W003]"), "{said}");
    let settings: &[&[&str]] = &[
        &["actuator", "retract", "designation"],
        &["C1", "1s", "1A1"],
    ];
    let (code, said) = check(workbook(&[], &[("SETTINGS", settings)]));
    assert_eq!(code, Some(0), "{said}");
    assert!(said.contains("SETTINGS!C1: warning[W003]"), "{said}");
}

/// Settings on a sheet of another name (`PARAMETERS`, `Config`): only the
/// sheet named SETTINGS is read, and those were ignored without a word
/// (rt15 F10). Now W015 at the first, counting them, once per sheet; the
/// table is converted as written. A sheet of notes says nothing.
#[test]
fn settings_on_a_sheet_of_another_name_are_said() {
    let params: &[&[&str]] = &[
        &["SETTING", "VALUE"],
        &["modes", "estop, reset"],
        &["safety", "all"],
    ];
    let (code, said) = check(workbook(&[], &[("PARAMETERS", params)]));
    assert_eq!(code, Some(0), "{said}");
    assert!(
        said.contains(
            "PARAMETERS!A2: warning[W015]: the sheet \"PARAMETERS\" holds what reads as 2 settings"
        ),
        "{said}"
    );
    assert_eq!(said.matches("W015").count(), 1, "{said}");
    let config: &[&[&str]] = &[&["mode: estop"]];
    let (code, said) = check(workbook(&[], &[("Config", config)]));
    assert_eq!(code, Some(0), "{said}");
    assert!(said.contains("Config!A1: warning[W015]"), "{said}");
    // Beside a SETTINGS sheet, too: what the other one holds is lost.
    let settings: &[&[&str]] = &[&["target", "iec"]];
    let (code, said) = check(workbook(
        &[],
        &[("SETTINGS", settings), ("Config", &[&["modes", "all"]])],
    ));
    assert_eq!(code, Some(0), "{said}");
    assert!(said.contains("Config!A1: warning[W015]"), "{said}");
    let legend: &[&[&str]] = &[&["Target", "30 parts/min"], &["Model", "DSNU-16"]];
    let labels_only: &[&[&str]] = &[&["SETTING", "VALUE"], &["modes"]];
    let title: &[&[&str]] = &[&["Drawing 4711, rev. B"]];
    for notes in [legend, labels_only, title] {
        let (code, said) = check(workbook(&[], &[("Notes", notes)]));
        assert_eq!(code, Some(0), "{said}");
        assert!(!said.contains("W015"), "{said}");
    }
}

/// A CSV note row below the table whose comma splits the note (`Note: C2
/// is the clamp, C1 the slide`): the part in a branch column was E010 "would
/// be lost" for looking like a move (rt16 F14). In a row whose label cell
/// holds a note, only what reads wholly as moves would be lost.
#[test]
fn a_csv_note_split_by_its_comma_is_a_note() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.csv");
    let table = ",BRANCH 1,BRANCH 2\nSTEP 1,C1+1,\nSTEP 2,C2+1,\nSTEP 3,C2-0,C1-0\n";
    std::fs::write(
        &path,
        format!("{table}Note: C2 is the clamp, C1 the slide\n"),
    )
    .unwrap();
    let output = steptable().arg("check").arg(&path).output().unwrap();
    let said = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{said}");
    assert!(
        said.contains("t.csv:5:2: warning[W003]: \"C1 the slide\""),
        "{said}"
    );
    refused(
        "t.csv",
        format!("{table}Note: then,C1+1\n").into_bytes(),
        &["t.csv:5:2: error[E010]: \"C1+1\" lies outside the table"],
    );
}

/// A move hidden under a merge is E049 at its cell, and nothing else: the
/// step it was in was also E023 "has no move", and the actuator's next move
/// E020 for starting from the wrong position, cells only wrong because the
/// hidden one was not read (rt15 F11).
#[test]
fn a_move_hidden_under_a_merge_is_said_once() {
    // STEP 2's C2+1 (B3) under a merge of A3:B3, its STEP label's cell.
    let bytes = crate::hostile_round8::merged_xlsx(None, (2, 0, 2, 1), (2, 1, "C2+1"));
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("m.xlsx");
    std::fs::write(&path, bytes).unwrap();
    let output = steptable().arg("check").arg(&path).output().unwrap();
    let said = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{said}");
    assert!(said.contains("!B3: error[E049]"), "{said}");
    assert_eq!(said.matches("error[").count(), 1, "{said}");
}

/// A unit in a time column's header is the unit of its bare numbers:
/// `Extend time [ms]` over 500 was read as 500 s, a cycle of 882 s, exit 0
/// (rt17 F1). A unit written in the cell wins; a header without one leaves
/// a bare text time to W007, as before.
#[test]
fn a_unit_in_a_time_columns_header_is_the_unit_of_its_numbers() {
    let simulate = |settings: &[&[&str]]| {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.xlsx");
        std::fs::write(&path, workbook(&[], &[("SETTINGS", settings)])).unwrap();
        let output = steptable().arg("simulate").arg(&path).output().unwrap();
        let said =
            [&output.stdout, &output.stderr].map(|b| String::from_utf8_lossy(b).into_owned());
        (output.status.code(), said.concat())
    };
    // C1 extends in 500 ms (less a scan to its sensor).
    for header in ["Extend time [ms]", "extend (ms)", "extend in milliseconds"] {
        let (code, said) = simulate(&[&["actuator", header], &["C1", "500"]]);
        assert_eq!(code, Some(0), "{header}: {said}");
        assert!(said.contains("0.49 s  C1+1"), "{header}: {said}");
        assert!(!said.contains("W007"), "{header}: {said}");
    }
    let (_, said) = simulate(&[&["actuator", "Extend time [ms]"], &["C1", "2s"]]);
    assert!(said.contains("1.96 s  C1+1"), "{said}");
    let (_, said) = simulate(&[&["actuator", "Extend time [s]"], &["C1", "2"]]);
    assert!(
        said.contains("1.96 s  C1+1") && !said.contains("W007"),
        "{said}"
    );
    let (_, said) = simulate(&[&["actuator", "extend"], &["C1", "2"]]);
    assert!(
        said.contains("1.96 s  C1+1") && said.contains("W007"),
        "{said}"
    );
}

/// An actuator table written with the step table (below it, or in a CSV)
/// or on a sheet of another name was dropped without a word: the program
/// ran with the default valves and strokes, exit 0 (rt17 F2, F3). With
/// the table it is E030 at its header; on another sheet W015.
#[test]
fn an_actuator_table_where_it_is_not_read_is_said() {
    refused(
        "t.csv",
        b",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n\nactuator,extend,retract,valve\nC1,3s,2s,52mono\n"
            .to_vec(),
        &["t.csv:5:1: error[E030]: an actuator table (headed here, its first row at 6:1)"],
    );
    let mut book = Workbook::new();
    let table = book.add_worksheet();
    table.set_name("SEQUENTIAL CONTROL DESCRIPTION").unwrap();
    write_rows(table, TABLE);
    for (r, row) in [["actuator", "valve"], ["C1 (clamp)", "52mono"]]
        .iter()
        .enumerate()
    {
        for (c, text) in row.iter().enumerate() {
            table
                .write_string(8 + r as u32, 3 + c as u16, *text)
                .unwrap();
        }
    }
    refused(
        "t.xlsx",
        book.save_to_buffer().unwrap(),
        &["SEQUENTIAL CONTROL DESCRIPTION!D9: error[E030]: an actuator table"],
    );
    let cylinders: &[&[&str]] = &[&["Actuators", "extend", "retract"], &["C1", "3s", "2s"]];
    let (code, said) = check(workbook(&[], &[("Cylinders", cylinders)]));
    assert_eq!(code, Some(0), "{said}");
    assert!(said.contains("Cylinders!A1: warning[W015]"), "{said}");
    // A legend of actuators without values is no table.
    let legend: &[&[&str]] = &[&["Actuator", "name"], &["C1"], &["C2"]];
    let (code, said) = check(workbook(&[], &[("Legend", legend)]));
    assert_eq!(code, Some(0), "{said}");
    assert!(!said.contains("W015"), "{said}");
}

/// What the red team rt17 found around the one-cell rule: a value dressed
/// as a note writes it (`mode (all)`, `mode: all.`, `mode=all;`,
/// `scantime: 20ms (PLC)`) passed in silence on the table's sheet; `scan`,
/// the command line's name, was two W003s; a label with words after it
/// (`safety checks | all`) was told to put its value right of it, where it
/// was; a copy `SETTINGS (2)` beside SETTINGS was told to be renamed
/// SETTINGS, which makes two.
#[test]
fn the_red_teams_look_at_the_one_cell_rule() {
    for text in [
        "mode (all)",
        "mode: all.",
        "mode \"all\"",
        "mode=all;",
        "scantime: 20ms (PLC)",
        "saftey: watchdog; edge",
        "scan: 20ms",
    ] {
        refused(
            "dressed.xlsx",
            workbook(&[text], &[]),
            &["SEQUENTIAL CONTROL DESCRIPTION!A7: error[E046]"],
        );
    }
    let scan: &[&[&str]] = &[&["scan", "10ms"]];
    refused(
        "scan.xlsx",
        workbook(&[], &[("SETTINGS", scan)]),
        &[
            "SETTINGS!A1: error[E046]: \"scan\" is not a setting steptable knows: did you mean `scan time`?",
        ],
    );
    let extra: &[&[&str]] = &[&["safety checks", "all"]];
    refused(
        "extra.xlsx",
        workbook(&[], &[("SETTINGS", extra)]),
        &[
            "SETTINGS!A1: error[E046]: \"safety checks\" starts with the setting safety but has more words after it: write the label `safety` alone",
        ],
    );
    let settings: &[&[&str]] = &[&["target", "iec"]];
    refused(
        "copy.xlsx",
        workbook(
            &[],
            &[
                ("SETTINGS", settings),
                ("SETTINGS (2)", &[&["modes", "all"]]),
            ],
        ),
        &["move what it holds to the sheet SETTINGS and delete it"],
    );
    let (_, said) = check(workbook(
        &[],
        &[
            ("SETTINGS", settings),
            ("SETTINGS old", &[&["modes", "all"]]),
        ],
    ));
    assert!(
        said.contains("W015") && said.contains("move the rows to the SETTINGS sheet"),
        "{said}"
    );
}

/// A header naming no column over values only a read column holds (`Type`
/// over valve types, `out` over times): those were lost with a W003 that
/// said the column had no header (rt17 F7). Now E046 at the header, naming
/// the column meant; a column of other notes stays W003.
#[test]
fn a_column_of_valves_or_times_under_an_unknown_header_is_refused() {
    for (header, value, says) in [
        (
            "Type",
            "52mono",
            "a value under it is a valve type: head it `valve`",
        ),
        (
            "out",
            "3s",
            "every value under it is a time: head it `extend` or `retract`",
        ),
        ("Zeit ausfahren", "1500ms", "every value under it is a time"),
    ] {
        let settings: &[&[&str]] = &[&["actuator", "retract", header], &["C1", "1s", value]];
        refused(
            "column.xlsx",
            workbook(&[], &[("SETTINGS", settings)]),
            &["SETTINGS!C1: error[E046]", says],
        );
    }
    let settings: &[&[&str]] = &[
        &["actuator", "retract", "remark"],
        &["C1", "1s", "check seals"],
    ];
    let (code, said) = check(workbook(&[], &[("SETTINGS", settings)]));
    assert_eq!(code, Some(0), "{said}");
    assert!(
        said.contains("is in a column whose header names none steptable reads"),
        "{said}"
    );
}

/// Another sheet of many cells (a data log, or rows of actuator tables) is
/// looked over in time that grows with its cells: each cell's right-hand
/// neighbour was found by a scan of the whole sheet.
#[test]
fn a_large_other_sheet_is_looked_over_in_linear_time() {
    let mut book = Workbook::new();
    let table = book.add_worksheet();
    table.set_name("SEQUENTIAL CONTROL DESCRIPTION").unwrap();
    write_rows(table, TABLE);
    let log = book.add_worksheet();
    log.set_name("Log").unwrap();
    for row in 0..60_000u32 {
        log.write_string(row, 0, "actuator").unwrap();
        log.write_string(row, 1, "extend").unwrap();
        log.write_string(row, 2, format!("sample {row}")).unwrap();
    }
    let start = std::time::Instant::now();
    let (code, said) = check(book.save_to_buffer().unwrap());
    assert_eq!(code, Some(0), "{said}");
    assert!(start.elapsed().as_secs() < 12, "{:?}", start.elapsed());
}

/// What the red team rt18 found in the header rules: a header unit
/// steptable does not read stroke times in (`[min]`, `[us]`, `(s or ms)`)
/// read its bare numbers as seconds, a minute as a second, exit 0; an
/// actuator table of number cells was not found with the step table or on
/// another sheet.
#[test]
fn a_header_unit_not_read_and_an_actuator_table_of_numbers_are_said() {
    for header in [
        "Extend time [min]",
        "extend (minutes)",
        "extend [us]",
        "extend (s or ms)",
    ] {
        let settings: &[&[&str]] = &[&["actuator", header], &["C1", "1"]];
        refused(
            "unit.xlsx",
            workbook(&[], &[("SETTINGS", settings)]),
            &["SETTINGS!B2: error[E030]: stroke time of C1: \"1\" stands under a header"],
        );
    }
    // A unit in the cell is read whatever the header says.
    let settings: &[&[&str]] = &[&["actuator", "Extend time [min]"], &["C1", "2s"]];
    let (code, said) = check(workbook(&[], &[("SETTINGS", settings)]));
    assert_eq!(code, Some(0), "{said}");
    let numbers = || {
        let mut book = Workbook::new();
        let table = book.add_worksheet();
        table.set_name("SEQUENTIAL CONTROL DESCRIPTION").unwrap();
        write_rows(table, TABLE);
        table.write_string(8, 0, "actuator").unwrap();
        table.write_string(8, 1, "Extend time [ms]").unwrap();
        table.write_string(9, 0, "C1").unwrap();
        table.write_number(9, 1, 500).unwrap();
        book
    };
    refused(
        "numbers.xlsx",
        numbers().save_to_buffer().unwrap(),
        &["SEQUENTIAL CONTROL DESCRIPTION!A9: error[E030]: an actuator table"],
    );
    let mut book = Workbook::new();
    let table = book.add_worksheet();
    table.set_name("SEQUENTIAL CONTROL DESCRIPTION").unwrap();
    write_rows(table, TABLE);
    let other = book.add_worksheet();
    other.set_name("Cylinders").unwrap();
    other.write_string(0, 0, "actuator").unwrap();
    other.write_string(0, 1, "extend [ms]").unwrap();
    other.write_string(1, 0, "C1").unwrap();
    other.write_number(1, 1, 500).unwrap();
    let (code, said) = check(book.save_to_buffer().unwrap());
    assert_eq!(code, Some(0), "{said}");
    assert!(said.contains("Cylinders!A1: warning[W015]"), "{said}");
}
