//! Issue 37's last items, table-driven: swapped step labels (W002 at both
//! cells), comments longer than STEP 7's symbol table holds (W008), a
//! duplicate pin named by the engineer's name too, a value in a hidden
//! row, the valve list (the home order and `--load` by name are in
//! `typed_names.rs`). Each row goes through the binary (`convert`): its exit code, each
//! code at its cell (or option), and nothing written for a refused one.

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{files_below, steptable, write_xlsx_sheets};

/// One input and what must come out of it.
pub(crate) struct Case {
    pub(crate) what: &'static str,
    pub(crate) sheets: &'static [(&'static str, &'static [&'static [&'static str]])],
    pub(crate) args: &'static [&'static str],
    pub(crate) exit: i32,
    /// Each must be in stderr: `TABLE!A3: warning[W002]: …`.
    pub(crate) says: &'static [&'static str],
    /// None may be in stderr (a second warning for the same shift).
    pub(crate) never: &'static [&'static str],
}

pub(crate) const TWO: &[&[&str]] = &[
    &["", "BRANCH 1", "BRANCH 2"],
    &["STEP 1", "C1+1"],
    &["STEP 2", "", "C2+1"],
    &["STEP 3", "", "C2-0"],
    &["STEP 4", "C1-0"],
];

pub(crate) const NAMED: &[&[&str]] = &[
    &["actuator", "extend", "retract"],
    &["C1 (lift)", "1s", "1s"],
    &["C2 (clamp)", "1s", "1s"],
];

pub(crate) fn run(case: &Case) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("h.xlsx");
    write_xlsx_sheets(&path, case.sheets);
    let out = dir.path().join("out");
    let assert = steptable()
        .arg("convert")
        .arg(&path)
        .args(case.args)
        .arg("-o")
        .arg(&out)
        .assert()
        .code(case.exit);
    let mut assert = assert;
    for needle in case.says {
        assert = assert.stderr(contains(*needle));
    }
    for needle in case.never {
        assert = assert.stderr(contains(*needle).not());
    }
    let written = files_below(&out);
    if case.exit == 0 {
        assert!(!written.is_empty(), "{}: nothing written", case.what);
    } else {
        assert!(
            written.is_empty(),
            "{}: refused but wrote {written:?}",
            case.what
        );
    }
}

/// Step labels that disagree with their rows: every change of the shift is
/// named at its cell (both of two swapped labels), a label twice names the
/// other cell, and a copied row shifting every label below it is one
/// warning, not one per row.
#[test]
fn step_labels_out_of_place_are_named_at_every_cell_that_changes() {
    let cases = [
        Case {
            what: "two labels swapped",
            sheets: &[(
                "TABLE",
                &[
                    &["", "BRANCH 1", "BRANCH 2"],
                    &["STEP 1", "C1+1"],
                    &["STEP 3", "", "C2+1"],
                    &["STEP 2", "", "C2-0"],
                    &["STEP 4", "C1-0"],
                ],
            )],
            args: &["--formats", "st"],
            exit: 0,
            says: &[
                "TABLE!A3: warning[W002]: this row is labelled STEP 3 but is step 2 of the table; steps are numbered",
                "TABLE!A4: warning[W002]: this row is labelled STEP 2 but is step 3 of the table; steps are numbered",
            ],
            never: &["TABLE!A5: warning[W002]"],
        },
        Case {
            what: "one label twice",
            sheets: &[(
                "TABLE",
                &[
                    &["", "BRANCH 1", "BRANCH 2"],
                    &["STEP 1", "C1+1"],
                    &["STEP 2", "", "C2+1"],
                    &["STEP 2", "", "C2-0"],
                    &["STEP 4", "C1-0"],
                ],
            )],
            args: &["--formats", "st"],
            exit: 0,
            says: &[
                "TABLE!A4: warning[W002]: this row is labelled STEP 2 but is step 3 of the table (A3 is STEP 2 too)",
            ],
            never: &["TABLE!A3: warning[W002]", "TABLE!A5: warning[W002]"],
        },
        Case {
            what: "a copied row shifts every label below it",
            sheets: &[(
                "TABLE",
                &[
                    &["", "BRANCH 1", "BRANCH 2"],
                    &["STEP 1", "C1+1"],
                    &["STEP 1", "", "C2+1"],
                    &["STEP 2", "", "C2-0"],
                    &["STEP 3", "C1-0"],
                ],
            )],
            args: &["--formats", "st"],
            exit: 0,
            says: &["TABLE!A3: warning[W002]: this row is labelled STEP 1 but is step 2"],
            never: &["TABLE!A4: warning[W002]", "TABLE!A5: warning[W002]"],
        },
        Case {
            what: "two branch headers swapped",
            sheets: &[(
                "TABLE",
                &[
                    &["", "BRANCH 2", "BRANCH 1"],
                    &["STEP 1", "C1+1"],
                    &["STEP 2", "", "C2+1"],
                    &["STEP 3", "", "C2-0"],
                    &["STEP 4", "C1-0"],
                ],
            )],
            args: &["--formats", "st"],
            exit: 0,
            says: &[
                "TABLE!B1: warning[W002]: this column is headed BRANCH 2 but is branch 1",
                "TABLE!C1: warning[W002]: this column is headed BRANCH 1 but is branch 2",
            ],
            never: &[],
        },
    ];
    for case in &cases {
        run(case);
    }
}

/// A duplicate or colliding pin names the signal by its paper symbol and
/// by the engineer's name, so the row is found whichever the sheet uses.
#[test]
fn a_pin_given_twice_is_named_by_the_engineers_name_too() {
    let cases = [
        Case {
            what: "a named signal pinned twice",
            sheets: &[
                ("TABLE", TWO),
                ("SETTINGS", NAMED),
                (
                    "ADDRESSES",
                    &[
                        &["SIGNAL", "ADDRESS"],
                        &["clamp_end", "I0.1"],
                        &["x21", "I0.2"],
                    ],
                ),
            ],
            args: &["--target", "siemens", "--formats", "st"],
            exit: 1,
            says: &["ADDRESSES!A3: error[E035]: x21 (clamp_end) is pinned twice (first at A2)"],
            never: &[],
        },
        Case {
            what: "an address taken by a named signal",
            sheets: &[
                ("TABLE", TWO),
                ("SETTINGS", NAMED),
                (
                    "ADDRESSES",
                    &[
                        &["SIGNAL", "ADDRESS"],
                        &["x21", "I0.1"],
                        &["lift_home", "I0.1"],
                    ],
                ),
            ],
            args: &["--target", "siemens", "--formats", "st"],
            exit: 1,
            says: &["ADDRESSES!B3: error[E035]: \"I0.1\" is already x21 (clamp_end)'s address"],
            never: &[],
        },
        Case {
            what: "a named input on an output address",
            sheets: &[
                ("TABLE", TWO),
                ("SETTINGS", NAMED),
                (
                    "ADDRESSES",
                    &[&["SIGNAL", "ADDRESS"], &["lift_home", "Q0.1"]],
                ),
            ],
            args: &["--target", "siemens", "--formats", "st"],
            exit: 1,
            says: &[
                "ADDRESSES!B2: error[E035]: x10 (lift_home) is an input, but \"Q0.1\" is an output address",
            ],
            never: &[],
        },
        Case {
            what: "an unnamed signal twice keeps its symbol alone",
            sheets: &[
                ("TABLE", TWO),
                (
                    "ADDRESSES",
                    &[&["SIGNAL", "ADDRESS"], &["x21", "I0.1"], &["x21", "I0.2"]],
                ),
            ],
            args: &["--target", "siemens", "--formats", "st"],
            exit: 1,
            says: &["ADDRESSES!A3: error[E035]: x21 is pinned twice (first at A2)"],
            never: &[],
        },
    ];
    for case in &cases {
        run(case);
    }
}

/// A step comment or actuator name longer than STEP 7's symbol table's
/// 80-character comment: cut to 77 and `...` in `NAME.sdf` (every row's
/// comment field at most 80), whole in the `.awl`, W008 naming the symbols;
/// a comment within 80 is not cut and not said.
#[test]
fn a_comment_longer_than_the_symbol_table_holds_is_cut_and_said() {
    const LONG: &str = "lift the part over the fence and put it down gently on the conveyor belt for the next station";
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("h.xlsx");
    let step = format!("STEP 1 ({LONG})");
    let name =
        "C2 (the clamp that holds the workpiece while the drill runs through it, on the left side)";
    let table: &[&[&str]] = &[
        &["", "BRANCH 1", "BRANCH 2"],
        &[&step, "C1+1"],
        &["STEP 2", "", "C2+1"],
        &["STEP 3", "", "C2-0"],
        &["STEP 4", "C1-0"],
    ];
    let settings: &[&[&str]] = &[&["actuator", "extend"], &[name, "1s"]];
    write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(&path)
        .args(["--target", "siemens", "--formats", "awl,sdf", "-o"])
        .arg(&out)
        .assert()
        .success()
        .stderr(contains(
            "h.xlsx: warning[W008]: h.sdf: the comment of x20 and",
        ))
        .stderr(contains("step_1"))
        .stderr(contains(
            "longer than the 80 characters a STEP 7 symbol table holds",
        ));
    let sdf = std::fs::read_to_string(out.join("h/h.sdf")).unwrap();
    for line in sdf.lines() {
        let comment = line.rsplit("\",\"").next().unwrap().trim_end_matches('"');
        assert!(comment.chars().count() <= 80, "{line}");
    }
    let cut: String = format!("STEP 1 is active: C1+1 ({LONG}")
        .chars()
        .take(77)
        .collect();
    assert!(sdf.contains(&format!("{cut}...\"")), "{sdf}");
    let awl = std::fs::read_to_string(out.join("h/h.awl")).unwrap();
    assert!(awl.contains(LONG), "the .awl keeps the comment whole");
    // Short comments: nothing cut, nothing said.
    let short = dir.path().join("s.xlsx");
    write_xlsx_sheets(&short, &[("TABLE", TWO)]);
    steptable()
        .arg("convert")
        .arg(&short)
        .args(["--target", "siemens", "--formats", "sdf", "-o"])
        .arg(dir.path().join("short"))
        .assert()
        .success()
        .stderr(contains("W008").not());
}

/// Hidden rows and columns are read like visible ones (the reader cannot
/// tell them apart; docs/guide.md says so): a step in a hidden row is
/// converted, a SETTINGS row in a hidden row is in force, and a wrong cell
/// in a hidden row or column is reported at its cell, nothing written.
#[test]
fn hidden_rows_and_columns_are_read_like_visible_ones() {
    use rust_xlsxwriter::Workbook;
    let dir = tempfile::tempdir().unwrap();
    let write = |name: &str, step2: &str, hide_col: bool| {
        let mut workbook = Workbook::new();
        let ws = workbook.add_worksheet();
        ws.set_name("TABLE").unwrap();
        let rows: [[&str; 3]; 5] = [
            ["", "BRANCH 1", "BRANCH 2"],
            ["STEP 1", "C1+1", ""],
            ["STEP 2", "", step2],
            ["STEP 3", "", "C2-0"],
            ["STEP 4", "C1-0", ""],
        ];
        for (r, row) in rows.iter().enumerate() {
            for (c, text) in row.iter().enumerate() {
                if !text.is_empty() {
                    ws.write_string(r as u32, c as u16, *text).unwrap();
                }
            }
        }
        ws.set_row_hidden(2).unwrap();
        if hide_col {
            ws.set_column_hidden(2).unwrap();
        }
        let settings = workbook.add_worksheet();
        settings.set_name("SETTINGS").unwrap();
        settings.write_string(0, 0, "target").unwrap();
        settings.write_string(0, 1, "siemens").unwrap();
        settings.set_row_hidden(0).unwrap();
        let path = dir.path().join(name);
        workbook.save(&path).unwrap();
        path
    };
    let good = write("good.xlsx", "C2+1", true);
    let out = dir.path().join("good");
    steptable()
        .arg("convert")
        .arg(&good)
        .args(["--formats", "awl", "-o"])
        .arg(&out)
        .assert()
        .success()
        .stdout(contains("good.xlsx: 4 steps, 2 branch(es), 2 actuators"));
    // The hidden SETTINGS row's target is in force: STEP 7 operands.
    let awl = std::fs::read_to_string(out.join("good/good.awl")).unwrap();
    assert!(awl.contains("C2+1"), "the hidden step is converted");
    assert!(awl.contains("the SETTINGS sheet (target)"), "{awl}");
    assert!(
        awl.contains("S     Q 0.0;"),
        "siemens packs from Q 0.0: {awl}"
    );
    let bad = write("bad.xlsx", "C2+l", false);
    let out = dir.path().join("bad");
    steptable()
        .arg("convert")
        .arg(&bad)
        .args(["--formats", "awl", "-o"])
        .arg(&out)
        .assert()
        .code(1)
        .stderr(contains("bad.xlsx: TABLE!C3: error[E010]"));
    assert!(files_below(&out).is_empty());
}

/// Issue 37's "smaller" list: the valve error names every valve type the
/// library has (`motor` among them), on the SETTINGS sheet at its cell and
/// for `--valve`, exit 1, nothing written.
#[test]
fn an_unknown_valve_lists_every_valve_type() {
    let every = steptable::actuator::ActuatorKind::ALL
        .iter()
        .map(|v| v.name())
        .collect::<Vec<_>>();
    let (last, rest) = every.split_last().unwrap();
    let list = format!("(expected {} or {last})", rest.join(", "));
    assert!(list.contains("motor"), "{list}");
    let cases = [
        Case {
            what: "on the SETTINGS sheet",
            sheets: &[
                ("TABLE", TWO),
                (
                    "SETTINGS",
                    &[
                        &["actuator", "extend", "retract", "valve"],
                        &["C1", "1s", "1s", "pneumatic"],
                    ],
                ),
            ],
            args: &["--formats", "st"],
            exit: 1,
            says: &["SETTINGS!D2: error[E030]: valve of C1: \"pneumatic\" is not a valve type"],
            never: &[],
        },
        Case {
            what: "on the command line",
            sheets: &[("TABLE", TWO)],
            args: &["--valve", "C1=pneumatic", "--formats", "st"],
            exit: 1,
            says: &["'--valve <LIST>': \"C1=pneumatic\": \"pneumatic\" is not a valve type"],
            never: &[],
        },
    ];
    for case in &cases {
        run(case);
        // The whole list, from the library's own.
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("v.xlsx");
        write_xlsx_sheets(&path, case.sheets);
        steptable()
            .arg("check")
            .arg(&path)
            .args(
                case.args
                    .iter()
                    .filter(|a| !["--formats", "st"].contains(a)),
            )
            .assert()
            .code(1)
            .stderr(contains(list.as_str()));
    }
}
