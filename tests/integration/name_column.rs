//! The template's SETTINGS actuator table has a `name` column: the
//! engineer's name of each actuator (`clamp`), the same as `C1 (clamp)` in
//! its first column, read back by the reader and carried to every output.
//! Hostile rows: two names for one actuator, one name for two, a name the
//! program already uses, another actuator's label, a name on an actuator
//! the table does not move, two name columns, each with its code and cell.

use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;

use crate::helpers::{
    Refused, assert_refused, read_sheet, steptable, write_xlsx_sheets, xlsx_part,
};

const TABLE: &[&[&str]] = &[&["C1+1", ""], &["", "C2+1"], &["C1-0", "C2-0"]];
const HEADER: &[&str] = &["actuator", "extend", "retract", "valve", "name"];

#[test]
fn the_templates_name_column_is_read_back() {
    let dir = tempfile::tempdir().unwrap();
    let template = dir.path().join("plant.xlsx");
    steptable()
        .args(["template", "-o"])
        .arg(&template)
        .assert()
        .success();
    let sheet = xlsx_part(&template, "xl/worksheets/sheet2.xml");
    assert!(sheet.contains("promptTitle=\"name\""), "an input message");
    // The engineer types names into the template's cells, as laid out.
    let mut rows = read_sheet(&template, "SETTINGS");
    let header = rows
        .iter()
        .position(|r| r.first().map(String::as_str) == Some("actuator"))
        .expect("the actuator table");
    assert_eq!(rows[header][..5], *HEADER);
    for row in &mut rows {
        row.resize(5, String::new());
    }
    rows[header + 1][4] = "clamp".to_string();
    rows[header + 2][4] = "punch".to_string();
    let rows: Vec<Vec<&str>> = rows
        .iter()
        .map(|r| r.iter().map(String::as_str).collect())
        .collect();
    let rows: Vec<&[&str]> = rows.iter().map(Vec::as_slice).collect();
    let filled = dir.path().join("filled.xlsx");
    write_xlsx_sheets(&filled, &[("TABLE", TABLE), ("SETTINGS", &rows)]);
    let out = dir.path().join("out");
    steptable()
        .args(["convert", "--formats", "io", "-o"])
        .arg(&out)
        .arg(&filled)
        .assert()
        .success()
        .stderr(contains("W0").not());
    let io = std::fs::read_to_string(out.join("filled/filled.io.csv")).unwrap();
    assert!(io.contains("cylinder 1 (clamp), home position 0"), "{io}");
    assert!(io.contains("cylinder 2 (punch)"), "{io}");
}

#[test]
fn a_name_column_refuses_what_would_mean_two_things() {
    assert_refused(&[
        Refused {
            what: "two names for one actuator",
            table: TABLE,
            settings: &[HEADER, &["C1 (clamp)", "1s", "1s", "", "gripper"]],
            args: &[],
            code_at: "SETTINGS!E2: error[E030]: C1 is named \"clamp\" in A2 and \"gripper\" here",
        },
        Refused {
            what: "one name for two actuators",
            table: TABLE,
            settings: &[
                HEADER,
                &["C1", "", "", "", "clamp"],
                &["C2", "", "", "", "Clamp"],
            ],
            args: &[],
            code_at: "SETTINGS!E3: error[E025]: C2 (Clamp): clamp is named for C1 at SETTINGS!E2 too",
        },
        Refused {
            what: "a name the program already uses",
            table: TABLE,
            settings: &[HEADER, &["C1", "", "", "", "x20"]],
            args: &[],
            code_at: "SETTINGS!E2: error[E015]: C1 (x20): \"x20\" cannot name an actuator",
        },
        Refused {
            what: "another actuator's label",
            table: TABLE,
            settings: &[HEADER, &["C1", "", "", "", "C2"]],
            args: &[],
            code_at: "SETTINGS!E2: error[E015]: C1 (C2)",
        },
        Refused {
            what: "another actuator's ISO designation (the punch named 1A1, C1's)",
            table: TABLE,
            settings: &[HEADER, &["C2", "", "", "", "1A1"]],
            args: &[],
            code_at: "SETTINGS!E2: error[E015]: C2 (1A1): \"1A1\" cannot name an actuator: it reads as an ISO 1219 designation (1A1 is C1",
        },
        Refused {
            what: "a solenoid's ISO designation",
            table: TABLE,
            settings: &[HEADER, &["C1", "", "", "", "2m1"]],
            args: &[],
            code_at: "SETTINGS!E2: error[E015]: C1 (2m1)",
        },
        Refused {
            what: "another actuator's label with a Cyrillic C",
            table: TABLE,
            settings: &[HEADER, &["C1", "", "", "", "С2"]],
            args: &[],
            code_at: "SETTINGS!E2: error[E015]: C1 (С2): \"С2\" cannot name an actuator: it reads as actuator C2",
        },
        Refused {
            what: "another actuator's label with a space and a subscript digit",
            table: TABLE,
            settings: &[HEADER, &["C1", "", "", "", "c ₂"]],
            args: &[],
            code_at: "SETTINGS!E2: error[E015]: C1 (c ₂)",
        },
        Refused {
            what: "the EMERGENCY STOP button's name under --modes all",
            table: TABLE,
            settings: &[HEADER, &["C2", "", "", "", "EStop"]],
            args: &["--modes", "all"],
            code_at: "SETTINGS!E2: error[E015]: C2 (EStop): \"EStop\" cannot name an actuator: it is the program's operating-mode button ESTOP",
        },
        Refused {
            what: "a jog button's paper name under --modes manual",
            table: TABLE,
            settings: &[HEADER, &["C2", "", "", "", "jog1p"]],
            args: &["--modes", "manual"],
            code_at: "SETTINGS!E2: error[E015]: C2 (jog1p)",
        },
        Refused {
            what: "two name columns",
            table: TABLE,
            settings: &[&["actuator", "name", "name"], &["C1", "clamp", "gripper"]],
            args: &[],
            code_at: "SETTINGS!C1: error[E030]: the actuator table has two name columns",
        },
    ]);
}

/// An actuator may carry its own ISO designation as its name, and a
/// button's name is free for an actuator while the program has no such
/// button.
#[test]
fn its_own_designation_and_an_absent_buttons_name_are_names() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("own.xlsx");
    let settings: &[&[&str]] = &[
        HEADER,
        &["C1", "", "", "", "1A1"],
        &["C2", "", "", "", "estop"],
    ];
    write_xlsx_sheets(&path, &[("TABLE", TABLE), ("SETTINGS", settings)]);
    steptable().arg("check").arg(&path).assert().success();
}

#[test]
fn a_name_on_an_actuator_the_table_does_not_move_is_said() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("h.xlsx");
    let settings: &[&[&str]] = &[HEADER, &["C5", "", "", "", "feeder"]];
    write_xlsx_sheets(&path, &[("TABLE", TABLE), ("SETTINGS", settings)]);
    steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .success()
        .stderr(contains(
            "SETTINGS!E2: warning[W006]: C5 is named \"feeder\", but the table does not move C5; the name is not used",
        ));
    // The same name given both ways is one name, said once.
    let settings: &[&[&str]] = &[HEADER, &["C1 (clamp)", "", "", "", "Clamp"]];
    write_xlsx_sheets(&path, &[("TABLE", TABLE), ("SETTINGS", settings)]);
    steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .success()
        .stderr(contains("SETTINGS").not());
}
