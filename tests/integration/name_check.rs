//! Issue 37, names and cell messages: one name check at every place a name
//! enters (table cells, SETTINGS rows, synth's letters), no second error
//! caused by a refused cell, and E010 shaped by what the cell looks like.
//! Each row runs the binary: exit code, code, cell, message, nothing written.

use std::path::Path;

use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;
use rust_xlsxwriter::{ExcelDateTime, Format, Workbook};

use crate::helpers::{files_below, steptable, write_xlsx_sheets};

/// A table whose STEP 2 cell (CSV 3:2) holds `item` beside `C1-0`; STEP 3
/// is a dwell so that `J:4` has somewhere to jump.
fn table_with(item: &str, off: &str) -> String {
    format!(
        ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0; {item}\nSTEP 3,T=1s\nSTEP 4,C2+1{off}\nSTEP 5,C2-0\n"
    )
}

/// Runs `convert` on `input` with `args` into a fresh folder: the exit
/// code, stderr, and whether anything was written.
fn convert(input: &Path, args: &[&str]) -> (i32, String, bool) {
    let out = input.with_extension("out");
    let output = steptable()
        .arg("convert")
        .arg(input)
        .args(args)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr).to_string();
    (
        output.status.code().unwrap_or(-1),
        stderr,
        !files_below(&out).is_empty(),
    )
}

/// Every entry point × every kind of collision: E015 at its cell, exit 1,
/// nothing written; and the same names where nothing collides pass.
#[test]
fn every_entry_point_refuses_every_kind_of_name_collision() {
    let dir = tempfile::tempdir().unwrap();
    // (what, item in STEP 2 or SETTINGS rows, modes, expected code, needle)
    let table_rows: &[(&str, &str, &str, i32, &str)] = &[
        // Mode buttons, only while their mode is on, in any case.
        (
            "jump on estop",
            "J:4 if I:estop",
            "estop",
            1,
            "button ESTOP",
        ),
        ("jump on EStop", "J:4 if I:EStop", "all", 1, "button ESTOP"),
        ("jump on stop", "J:4 if I:stop=0", "stop", 1, "button STOP"),
        ("jump on cont", "J:end if I:cont", "all", 1, "button CONT"),
        (
            "wait on reset_pb",
            "I:reset_pb",
            "reset",
            1,
            "button RESET_PB",
        ),
        ("output stop", "Y:stop+", "stop", 1, "button STOP"),
        ("wait on estop", "I:estop", "estop", 1, "button ESTOP"),
        ("jump on estop, no mode", "J:4 if I:estop", "none", 0, ""),
        ("wait on stop, no mode", "I:stop", "estop", 0, ""),
        // IL operators and the FB inputs IL reads as operators are names
        // like any in the table's ST programs (matiec accepts them there);
        // only synth's IL refuses them (below).
        ("wait on ld", "I:ld", "none", 0, ""),
        ("jump on st", "J:4 if I:st", "none", 0, ""),
        ("output s1", "Y:s1+", "none", 0, ""),
        ("wait on in", "I:in", "none", 0, ""),
        ("wait on pt", "I:PT", "none", 0, ""),
        ("wait on clk", "I:clk", "none", 0, ""),
        ("jump on cal", "J:4 if I:cal", "none", 0, ""),
        ("output ret", "Y:ret+", "none", 0, ""),
        ("wait on s", "I:s", "none", 0, ""),
        // Keywords, standard functions and blocks.
        ("wait on if", "I:if", "none", 1, "keyword"),
        // Words matiec, OpenPLC v3 or OpenPLC v4 reserve beyond the
        // classic keywords (each compiled to a refused .st with exit 0).
        ("wait on continue", "I:continue", "none", 1, "keyword"),
        (
            "jump on var_config",
            "J:4 if I:var_config",
            "none",
            1,
            "keyword",
        ),
        ("wait on r_edge", "I:r_edge", "none", 1, "keyword"),
        ("output non_retain", "Y:non_retain+", "none", 1, "keyword"),
        ("wait on ref", "I:ref", "none", 1, "keyword"),
        ("wait on null", "I:null", "none", 1, "keyword"),
        ("wait on this", "I:this", "none", 1, "keyword"),
        ("output method", "Y:method+", "none", 1, "keyword"),
        ("wait on interface", "I:interface", "none", 1, "keyword"),
        (
            "jump on property",
            "J:4 if I:property",
            "none",
            1,
            "keyword",
        ),
        (
            "wait on Config0",
            "I:Config0",
            "none",
            1,
            "generated program uses it",
        ),
        ("output ctu", "Y:ctu+", "none", 1, "standard function"),
        (
            "jump on max",
            "J:4 if I:max",
            "none",
            1,
            "standard function",
        ),
        // Addresses of STEP 7 and FST, the program's own names.
        ("wait on mw10", "I:mw10", "none", 1, "addresses such as I0"),
        (
            "jump on fw2",
            "J:4 if I:fw2",
            "none",
            1,
            "addresses such as I0",
        ),
        (
            "output x11",
            "Y:x11+",
            "none",
            1,
            "generated program uses it",
        ),
        (
            "wait on dwell1",
            "I:dwell1",
            "none",
            1,
            "generated program uses it",
        ),
        (
            "jump on active_step",
            "J:4 if I:active_step",
            "none",
            1,
            "uses it",
        ),
        (
            "output steptable_main",
            "Y:steptable_main+",
            "none",
            1,
            "uses it",
        ),
        // The words of the SETTINGS lists: `hold-safe | none` could not
        // tell a signal so named from the word.
        (
            "output none",
            "Y:none+",
            "none",
            1,
            "word of the SETTINGS rows",
        ),
        (
            "wait on all",
            "I:all",
            "none",
            1,
            "word of the SETTINGS rows",
        ),
        (
            "jump on default",
            "J:4 if I:Default",
            "none",
            1,
            "word of the SETTINGS rows",
        ),
        // The SFC chart's own programs, instances, steps and actions
        // (issue 39), refused whatever --formats says.
        (
            "output steptable_pre",
            "Y:steptable_pre+",
            "none",
            1,
            "uses it",
        ),
        (
            "wait on post_instance",
            "I:post_instance",
            "none",
            1,
            "uses it",
        ),
        ("wait on step_3", "I:step_3", "none", 1, "uses it"),
        (
            "jump on step_2_entry",
            "J:4 if I:step_2_entry",
            "none",
            1,
            "uses it",
        ),
        // What FST keeps of a name.
        (
            "jump on cycle_req_lamp",
            "J:4 if I:cycle_req_lamp",
            "none",
            1,
            "first 9",
        ),
    ];
    for (what, item, modes, code, needle) in table_rows {
        let off = match item.strip_prefix("Y:").and_then(|n| n.strip_suffix('+')) {
            Some(name) => format!("; Y:{name}-"),
            None => String::new(),
        };
        let input = dir
            .path()
            .join(format!("{}.csv", what.replace([' ', ','], "_")));
        std::fs::write(&input, table_with(item, &off)).unwrap();
        let (got, stderr, wrote) = convert(&input, &["--modes", modes, "--formats", "st,fst"]);
        assert_eq!(got, *code, "{what}: {stderr}");
        if *code == 1 {
            assert!(
                stderr.contains(":3:2: error[E015]: ") && stderr.contains(needle),
                "{what}: {stderr}"
            );
            assert!(!wrote, "{what}: written although refused");
        }
    }

    // SETTINGS rows: the same check, the buttons of the sheet's own modes.
    let table: &[&[&str]] = &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 2", "C1-0"]];
    let settings_rows: &[(&str, &[&[&str]], &str)] = &[
        (
            "permissive estop",
            &[&["modes", "estop"], &["start permissive", "estop"]],
            "SETTINGS!B2: error[E015]: start permissive: \"estop\" cannot name a machine signal while the program has the operating-mode button ESTOP",
        ),
        (
            "interlock STOP",
            &[&["modes", "stop"], &["interlock", "STOP"]],
            "SETTINGS!B2: error[E015]: interlock: \"stop\" cannot name a machine signal while the program has the operating-mode button STOP",
        ),
        // Two rows, one FST symbol: the check over the whole table sees
        // both (each row alone had no clash).
        (
            "permissive and interlock one in fst",
            &[
                &["start permissive", "part_present_a"],
                &["interlock", "part_present_b"],
            ],
            "SETTINGS!B2: error[E025]: interlock: part_present_b and part_present_a begin with the same 9 characters, which is all Festo FST keeps of a symbol (part_present_a is named in the start permissive row, SETTINGS!B1)",
        ),
        (
            "interlock none beside a name",
            &[&["interlock", "guard, none"]],
            "SETTINGS!B1: error[",
        ),
        (
            "interlock cycle_req_lamp",
            &[&["interlock", "cycle_req_lamp"]],
            "SETTINGS!B1: error[E015]: interlock: \"cycle_req_lamp\" cannot name a machine signal where a Festo FST file is written: FST keeps its first 9 characters",
        ),
    ];
    for (what, settings, message) in settings_rows {
        let input = dir.path().join(format!("{}.xlsx", what.replace(' ', "_")));
        write_xlsx_sheets(&input, &[("TABLE", table), ("SETTINGS", settings)]);
        let (got, stderr, wrote) = convert(&input, &["--formats", "st,fst"]);
        assert_eq!(got, 1, "{what}: {stderr}");
        assert!(stderr.contains(message), "{what}: {stderr}");
        assert!(!wrote, "{what}: written although refused");
    }

    // synth's letters: R and S are IL operators; memories skip them.
    for sequence in ["R1 R0 S1 S0", "A+ A- R+ R-"] {
        let out = dir.path().join("synth");
        steptable()
            .args(["synth", "--sequence", sequence, "-o"])
            .arg(&out)
            .assert()
            .code(1)
            .stderr(contains(
                "--sequence: error[E015]: R cannot name an actuator for synthesis: its signal r is an instruction-list operator",
            ));
        assert!(files_below(&out).is_empty(), "{sequence}");
    }
}

/// A refused cell makes no second error in the cells that are only wrong
/// because of it; an unrelated error is still said.
#[test]
fn a_refused_cell_causes_no_second_error() {
    let dir = tempfile::tempdir().unwrap();
    // (what, rows from STEP 1, the only errors expected: "line:col code")
    let rows: &[(&str, &[&str], &[&str])] = &[
        (
            "letter l for 1",
            &["C1+1", "C2+l; T=1s", "C2-0", "C1-0"],
            &["3:2 E010"],
        ),
        ("letter I in C1", &["CI+1", "C1-0"], &["2:2 E010"]),
        (
            "position out of range",
            &["C2+99", "C2-1", "C2-0"],
            &["2:2 E012"],
        ),
        ("actuator unknown", &["Cx+1", "C2-0"], &["2:2 E010"]),
        // Never back home: nothing to say for C2, whose moves are unknown.
        ("refused home move", &["C2+1", "C2-l"], &["3:2 E010"]),
        // C1 wrong on its own still is: one refused C2 move hides nothing else.
        (
            "unrelated error still said",
            &["C1+1", "C2+l", "C1+1", "C2-0", "C1-0"],
            &["3:2 E010", "4:2 E020"],
        ),
    ];
    for (what, steps, expected) in rows {
        let mut text = ",BRANCH 1\n".to_string();
        for (i, cell) in steps.iter().enumerate() {
            text.push_str(&format!("STEP {},\"{cell}\"\n", i + 1));
        }
        let input = dir.path().join(format!("{}.csv", what.replace(' ', "_")));
        std::fs::write(&input, text).unwrap();
        let (code, stderr, wrote) = convert(&input, &["--formats", "st"]);
        assert_eq!(code, 1, "{what}: {stderr}");
        assert!(!wrote, "{what}");
        let errors: Vec<String> = stderr
            .lines()
            .filter(|l| l.contains(": error["))
            .map(|l| {
                let cell = l.split(": error[").next().unwrap();
                let cell = cell.split_once(".csv:").map_or(cell, |(_, c)| c);
                let code = &l[l.find("error[").unwrap() + 6..][..4];
                format!("{cell} {code}")
            })
            .collect();
        assert_eq!(&errors, expected, "{what}: {stderr}");
    }
}

/// E010 says what a cell was probably meant to be, at its cell.
#[test]
fn e010_says_what_the_cell_probably_meant() {
    let dir = tempfile::tempdir().unwrap();
    for (cell, says) in [
        (
            "C2+l",
            "\"C2+l\" is not a move (did you mean C2+1? A letter stands where a digit belongs)",
        ),
        ("CI+1", "did you mean C1+1?"),
        ("C1+O", "did you mean C1+0?"),
        (
            "T 1s",
            "\"T 1s\" is not a move (did you mean T=1s? A dwell is written T=<time>, e.g. T=2s)",
        ),
        ("T:1s", "did you mean T=1s?"),
        ("I part", "did you mean I:part? A wait is written I:<input>"),
        (
            "Y vac+",
            "did you mean Y:vac+? An output is switched with Y:<output>+",
        ),
        (
            "J 3 if I:part",
            "did you mean J:3 if I:part? A jump is written",
        ),
        ("C1+1, T=1s", "separate items with `;`, not `,`: C1+1; T=1s"),
        (
            "A+",
            "a table writes moves as C<number>+<position>, e.g. C1+1 and C1-0; letter notation (A+, A1, B0) is for synth --sequence",
        ),
        ("A1", "letter notation (A+, A1, B0) is for synth --sequence"),
        ("B0", "letter notation (A+, A1, B0) is for synth --sequence"),
        (
            "C2+x",
            "\"C2+x\" is not a move (expected C<number>+<position>, e.g. C2+1)",
        ),
    ] {
        let input = dir.path().join("t.csv");
        std::fs::write(
            &input,
            format!(",BRANCH 1\nSTEP 1,\"{cell}\"\nSTEP 2,C3+1\nSTEP 3,C3-0\n"),
        )
        .unwrap();
        let (code, stderr, wrote) = convert(&input, &["--formats", "st"]);
        assert_eq!(code, 1, "{cell}: {stderr}");
        assert!(
            stderr.contains("t.csv:2:2: error[E010]: ") && stderr.contains(says),
            "{cell}: {stderr}"
        );
        assert!(!wrote, "{cell}");
    }

    // A valve typed out in full on the SETTINGS sheet.
    let input = dir.path().join("valve.xlsx");
    write_xlsx_sheets(
        &input,
        &[
            (
                "TABLE",
                &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 2", "C1-0"]],
            ),
            (
                "SETTINGS",
                &[
                    &["actuator", "extend", "retract", "valve"],
                    &["C1", "1s", "1s", "5/2 monostable"],
                ],
            ),
        ],
    );
    let (code, stderr, wrote) = convert(&input, &["--formats", "st"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(
        stderr.contains("SETTINGS!D2: error[E030]: valve of C1: \"5/2 monostable\" is not a valve type: did you mean 52mono?"),
        "{stderr}"
    );
    assert!(!wrote);
}

/// A date or time cell is named as the engineer sees it, not as the
/// serial number the spreadsheet stores.
#[test]
fn a_date_cell_is_described_as_a_date() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("dated.xlsx");
    let mut workbook = Workbook::new();
    let sheet = workbook.add_worksheet();
    sheet.set_name("TABLE").unwrap();
    let date = Format::new().set_num_format("yyyy-mm-dd");
    let time = Format::new().set_num_format("hh:mm");
    sheet.write_string(0, 1, "BRANCH 1").unwrap();
    for (row, label) in ["STEP 1", "STEP 2", "STEP 3"].iter().enumerate() {
        sheet.write_string(row as u32 + 1, 0, *label).unwrap();
    }
    // 2024-01-03 is the serial number 45294.
    let day = ExcelDateTime::from_ymd(2024, 1, 3).unwrap();
    sheet.write_datetime_with_format(1, 1, &day, &date).unwrap();
    let noon = ExcelDateTime::from_hms(12, 30, 0).unwrap();
    sheet
        .write_datetime_with_format(2, 1, &noon, &time)
        .unwrap();
    sheet.write_string(3, 1, "C1+1").unwrap();
    workbook.save(&input).unwrap();
    let (code, stderr, wrote) = convert(&input, &["--formats", "st"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(
        stderr.contains("TABLE!B2: error[E010]: the date 2024-01-03 is not a move")
            && stderr.contains("format the cell as text"),
        "{stderr}"
    );
    assert!(
        stderr.contains("TABLE!B3: error[E010]: the time 12:30:00 is not a move"),
        "{stderr}"
    );
    assert!(!stderr.contains("45294"), "{stderr}");
    assert!(!wrote);
}

/// A move typed in the row below the last STEP, with no label, is named at
/// its own row with what to do, not blamed on the step above it.
#[test]
fn an_unlabelled_row_below_the_last_step_is_named_as_such() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("below.xlsx");
    write_xlsx_sheets(
        &input,
        &[(
            "TABLE",
            &[
                &["", "BRANCH 1"],
                &["STEP 1", "C1+1"],
                &["STEP 2", "C2+1"],
                &["STEP 3", "C2-0"],
                &["", "C1-0"],
            ],
        )],
    );
    let (code, stderr, wrote) = convert(&input, &["--formats", "st"]);
    assert_eq!(code, 1, "{stderr}");
    assert!(
        stderr.contains("TABLE!B5: error[E010]: \"C1-0\" lies outside the table and would be lost: its row 5 has no STEP label, and it lies below the table's last step, STEP 3 (row 4); add the label STEP 4 in A5 to make it a step"),
        "{stderr}"
    );
    assert!(!wrote);
}

/// synth's E034 on a table names the cell to blame.
#[test]
fn synth_refuses_a_table_at_the_cell_to_blame() {
    let dir = tempfile::tempdir().unwrap();
    let cases: &[(&str, &[&[&str]], &str)] = &[
        (
            "dwell",
            &[
                &["", "BRANCH 1"],
                &["STEP 1", "C1+1"],
                &["STEP 2", "C1-0; T=1s"],
            ],
            "TABLE!B3: error[E034]: STEP 2 (C1-0; T=1s) is not one cylinder move",
        ),
        (
            "parallel",
            &[
                &["", "BRANCH 1", "BRANCH 2"],
                &["STEP 1", "C1+1", "C2+1"],
                &["STEP 2", "C1-0", "C2-0"],
            ],
            "TABLE!C2: error[E034]: STEP 1 moves 2 actuators at once",
        ),
        (
            "middle",
            &[
                &["", "BRANCH 1"],
                &["STEP 1", "C1+2"],
                &["STEP 2", "C1-1"],
                &["STEP 3", "C1-0"],
            ],
            "TABLE!B3: error[E034]: C1 has middle positions",
        ),
    ];
    for (what, rows, cell) in cases {
        let input = dir.path().join(format!("{what}.xlsx"));
        write_xlsx_sheets(&input, &[("TABLE", rows)]);
        let out = dir.path().join(format!("{what}-out"));
        steptable()
            .arg("synth")
            .arg(&input)
            .arg("-o")
            .arg(&out)
            .assert()
            .code(1)
            .stderr(contains(*cell));
        assert!(files_below(&out).is_empty(), "{what}");
    }
}

/// An option that names an input the table does not have is said, not
/// dropped: `--input-delay` for a misspelt or reserved name is W006.
#[test]
fn an_input_delay_for_no_input_of_the_table_is_said() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("wait.csv");
    std::fs::write(&input, ",BRANCH 1\nSTEP 1,C1+1; I:part\nSTEP 2,C1-0\n").unwrap();
    for name in ["prat", "ld", "estop"] {
        steptable()
            .arg("simulate")
            .arg(&input)
            .args(["--input-delay", &format!("{name}=2s")])
            .assert()
            .success()
            .stderr(contains(format!(
                "wait.csv: warning[W006]: --input-delay {name}=…: {name} is no machine input of this table (its inputs: part); nothing is delayed"
            )));
    }
    // The input the table has: delayed, and nothing said.
    steptable()
        .arg("simulate")
        .arg(&input)
        .args(["--input-delay", "part=2s"])
        .assert()
        .success()
        .stdout(contains("(I:part came after 2.00 s)"))
        .stderr(predicates::str::contains("W006").not());
}
