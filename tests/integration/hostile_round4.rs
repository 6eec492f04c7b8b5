//! The fourth round of hostile input, table-driven: what two red teams
//! found from the README alone. A comma CSV read by its semicolons (the
//! engineer's moves lost, a program written for one dwell), sheets whose
//! names differ only in case or spaces, a SETTINGS sheet misnamed, tables
//! `check` accepts that made `convert` fail, and a fault table blind to a
//! cycle that ends before its last moves do. Each row goes through the
//! binary: its exit code, each code at its cell, and what was read.

use crate::helpers::{convert_csv, convert_workbook, files_below, steptable, write_xlsx_sheets};

/// C1 out, C2 out and back, C1 back: the smallest table with two
/// actuators and a last step that returns one home.
pub(crate) const FOUR: &[&[&str]] = &[
    &["", "BRANCH 1"],
    &["STEP 1", "C1+1"],
    &["STEP 2", "C2+1"],
    &["STEP 3", "C2-0"],
    &["STEP 4", "C1-0"],
];

/// `faults` on `table` written as `t.csv`: what it prints.
fn faults_of(table: &str, args: &[&str]) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.csv");
    std::fs::write(&path, table).unwrap();
    let assert = steptable()
        .arg("faults")
        .arg(&path)
        .args(args)
        .arg("-o")
        .arg(dir.path().join("out"))
        .assert()
        .code(0);
    stdout(&assert)
}

fn stderr(assert: &assert_cmd::assert::Assert) -> String {
    String::from_utf8_lossy(&assert.get_output().stderr).into_owned()
}

fn stdout(assert: &assert_cmd::assert::Assert) -> String {
    String::from_utf8_lossy(&assert.get_output().stdout).into_owned()
}

/// A comma CSV with steps numbered 10, 20, … (W002 at each label) or a
/// remarks column (W003 at each note), and a cell written `C2-0; T=1s` as
/// the guide writes it: the reading by commas reads every move, so it wins
/// over the one by semicolons, which leaves moves in unread cells; and no
/// W005, since that other reading is no table of every cell.
#[test]
fn a_comma_table_with_a_semicolon_in_a_cell_is_read_by_its_commas() {
    let cases: [(&str, &str, &[&str], &str); 3] = [
        (
            "steps numbered in tens",
            ",BRANCH 1\nSTEP 10,C1+1\nSTEP 20,C2+1\nSTEP 30,C2-0; T=1s\nSTEP 40,C1-0\n",
            &["t.csv:2:1: warning[W002]", "t.csv:5:1: warning[W002]"],
            "4 steps, 1 branch(es), 2 actuators",
        ),
        (
            "a remarks column",
            ",BRANCH 1,BRANCH 2,\nSTEP 1,C1+1,,note a\nSTEP 2,C2+1,C3+1,note b\nSTEP 3,C2-0; T=1s,C3-0,note c\nSTEP 4,C1-0,,note d\n",
            &["t.csv:2:4: warning[W003]", "t.csv:5:4: warning[W003]"],
            "4 steps, 2 branch(es), 3 actuators",
        ),
        (
            "the paper's example with remarks",
            ",BRANCH 1,BRANCH 2,BRANCH 3,remarks\nSTEP 1,C1+1,,,clamp\nSTEP 2,C2+1,,,lift\nSTEP 3,C2-0,C3+1; T=2s,,press\nSTEP 4,C3-0,,,\nSTEP 5,C1-0,,,unclamp\n",
            &["t.csv:1:5: warning[W003]", "t.csv:2:5: warning[W003]"],
            "5 steps, 3 branch(es), 3 actuators",
        ),
    ];
    for (what, table, says, read) in cases {
        let (_dir, out, assert) = convert_csv(table, &[], 0);
        let (err, said) = (stderr(&assert), stdout(&assert));
        for needle in says {
            assert!(err.contains(needle), "{what}: no {needle} in {err}");
        }
        assert!(!err.contains("W005"), "{what}: {err}");
        assert!(!err.contains("error"), "{what}: {err}");
        assert!(said.contains(read), "{what}: {said}");
        assert!(!files_below(&out).is_empty(), "{what}: nothing written");
    }
}

/// Sheets whose names differ only in case or the spaces around them:
/// `--sheet` reads the sheet of exactly that name, and two loose matches
/// with no exact one (or two sheets that are each the template's table
/// sheet) are E047, naming both, with nothing written.
#[test]
fn sheets_alike_but_for_case_or_spaces_are_never_a_silent_choice() {
    let one: &[&[&str]] = &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 2", "C1-0"]];
    let two: &[&[&str]] = &[
        &["", "BRANCH 1"],
        &["STEP 1", "C2+1"],
        &["STEP 2", "C3+1"],
        &["STEP 3", "C2-0; C3-0"],
    ];
    let scd = "SEQUENTIAL CONTROL DESCRIPTION";
    type Sheets<'a> = &'a [(&'a str, &'a [&'a [&'a str]])];
    let cases: [(&str, Sheets, &[&str], i32, &str); 5] = [
        (
            "--sheet names the second sheet exactly",
            &[("Line A ", two), ("Line A", one)],
            &["--sheet", "Line A"],
            0,
            "2 steps, 1 branch(es), 1 actuators",
        ),
        (
            "--sheet matches two sheets loosely, none exactly",
            &[("Line A ", two), ("line a", one)],
            &["--sheet", "LINE A"],
            1,
            "error[E047]: 2 sheets are each the sheet \"LINE A\" (\"Line A \", \"line a\"",
        ),
        (
            "two sheets are each the template's table sheet",
            &[("Sequential Control Description ", two), (scd, one)],
            &[],
            1,
            "error[E047]",
        ),
        (
            "the template's table sheet named exactly",
            &[("Sequential Control Description ", two), (scd, one)],
            &["--sheet", scd],
            0,
            "2 steps, 1 branch(es), 1 actuators",
        ),
        (
            "one loose match is that sheet",
            &[("Line A ", two), ("Other", one)],
            &["--sheet", "line a"],
            0,
            "3 steps, 1 branch(es), 2 actuators",
        ),
    ];
    for (what, sheets, args, exit, says) in cases {
        let (_dir, out, assert) = convert_workbook(sheets, args, exit);
        let all = format!("{}{}", stderr(&assert), stdout(&assert));
        assert!(all.contains(says), "{what}: no {says} in {all}");
        assert_eq!(files_below(&out).is_empty(), exit != 0, "{what}");
    }
}

/// A SETTINGS or ADDRESSES sheet under a name one letter off, or under
/// Excel's name for a copy: E046 at that sheet, nothing written (the
/// program would lack its EMERGENCY STOP, checks or pins without a word).
#[test]
fn a_misnamed_settings_sheet_is_an_error_at_that_sheet() {
    let table: &[&[&str]] = &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 2", "C1-0"]];
    let settings: &[&[&str]] = &[&["modes", "all"], &["safety", "all"]];
    let pins: &[&[&str]] = &[&["SIGNAL", "ADDRESS"], &["x10", "I1.0"]];
    type Sheet<'a> = (&'a str, &'a [&'a [&'a str]]);
    let cases: [(Sheet, &str); 4] = [
        (("Setting", settings), "h.xlsx: Setting: error[E046]"),
        (
            ("SETTINGS (2)", settings),
            "h.xlsx: SETTINGS (2): error[E046]",
        ),
        (("settngs", settings), "h.xlsx: settngs: error[E046]"),
        (("ADRESSES", pins), "h.xlsx: ADRESSES: error[E046]"),
    ];
    for ((name, rows), says) in cases {
        let sheets = [("SEQUENTIAL CONTROL DESCRIPTION", table), (name, rows)];
        let (_dir, out, assert) = convert_workbook(&sheets, &[], 1);
        let err = stderr(&assert);
        assert!(err.contains(says), "{name}: no {says} in {err}");
        assert!(files_below(&out).is_empty(), "{name}: refused but wrote");
    }
    // A sheet of another name is no side sheet misspelt.
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("h.xlsx");
    write_xlsx_sheets(
        &path,
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", table),
            ("NOTES", settings),
        ],
    );
    steptable().arg("check").arg(&path).assert().code(0);
}

/// Tables `check` accepts convert: steps that only switch an output (the
/// cycle is over before START is released, and one press is one cycle),
/// and a jump that ends the cycle in step 1 under `--safety edge`.
#[test]
fn tables_check_accepts_convert() {
    let cases: [(&str, &str, &[&str]); 4] = [
        (
            "output-only steps",
            ",BRANCH 1\nSTEP 1,Y:lamp+\nSTEP 2,Y:lamp-\n",
            &[],
        ),
        (
            "output-only steps with every mode and check",
            ",BRANCH 1\nSTEP 1,Y:r+\nSTEP 2,Y:r-\n",
            &["--modes", "all", "--safety", "all"],
        ),
        (
            "a jump ending the cycle in step 1, edge check",
            ",BRANCH 1\nSTEP 1,J:end if I:r\nSTEP 2,C1+1\nSTEP 3,C2+1\nSTEP 4,C2-0; J:6 if I:s\nSTEP 5,T=1s\nSTEP 6,C1-0\n",
            &["--safety", "edge"],
        ),
        (
            "the same with every mode",
            ",BRANCH 1\nSTEP 1,J:end if I:r\nSTEP 2,C1+1\nSTEP 3,C2+1\nSTEP 4,C2-0; J:6 if I:s\nSTEP 5,T=1s\nSTEP 6,C1-0\n",
            &["--safety", "edge", "--modes", "all"],
        ),
    ];
    for (what, table, args) in cases {
        let (_dir, out, assert) = convert_csv(table, args, 0);
        let said = stdout(&assert);
        assert!(said.contains("simulation passed"), "{what}: {said}");
        assert!(!files_below(&out).is_empty(), "{what}");
    }
}

/// A fault that ends the cycle before the last step's moves have reached
/// their targets (a home sensor shorted, a motor stopped short by its
/// shorted limit switch, a vacuum switch that reads "released" at once)
/// leaves the program ready for START with the machine not home: a hazard,
/// not "no effect" or a safe stall; and no check is said to catch it.
#[test]
fn a_cycle_that_ends_before_its_last_moves_is_a_hazard() {
    let four = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C2+1\nSTEP 3,C2-0\nSTEP 4,C1-0\n";
    let vacuum = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C2+1\nSTEP 3,C1-0\nSTEP 4,C2-0\n";
    let cases: [(&str, &str, &[&str], &str); 3] = [
        ("a pneumatic home sensor", four, &[], "x10 short circuit"),
        (
            "a motor's home switch",
            four,
            &["--valve", "C1=motor"],
            "x10 short circuit",
        ),
        (
            "a vacuum switch",
            vacuum,
            &["--valve", "C2=vacuum"],
            "x21 open circuit",
        ),
    ];
    for (what, table, args, fault) in cases {
        let said = faults_of(table, args);
        let row = said
            .lines()
            .find(|l| l.contains(fault))
            .unwrap_or_else(|| panic!("{what}: no {fault} row in {said}"));
        assert!(row.contains("hazard"), "{what}: {row}");
        assert!(
            row.contains("the cycle ended before step 4 finished"),
            "{what}: {row}"
        );
    }
    // The mitigation column: no check catches a motor stranded by its
    // shorted home switch (precheck was said to).
    let (_dir, out, _) = convert_csv(
        ",BRANCH 1,BRANCH 2\nSTEP 1,C1+1,C2+1\nSTEP 2,C1-0,C2-0\n",
        &["--valve", "C1=vacuum,C2=motor"],
        0,
    );
    let report = std::fs::read_to_string(out.join("t/t.report.html")).unwrap();
    let row = report
        .split("<tr")
        .find(|r| r.contains("x20 short circuit"))
        .expect("an x20 short row");
    assert!(row.contains("hazard"), "{row}");
    assert!(!row.contains("caught by --safety precheck ("), "{row}");
}

/// On an OpenPLC board, a check whose alarm output the board does not wire
/// is no mitigation (`convert --safety watchdog` would refuse it, E036),
/// and `faults` refuses a program too large for the board as `convert`
/// does.
#[test]
fn the_board_bounds_the_mitigations_and_the_fault_table() {
    let table = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C2+1\nSTEP 3,C2-0\nSTEP 4,C1-0\n";
    let args = ["--board", "uno", "--valve", "C1=motor"];
    let (_dir, out, _) = convert_csv(table, &args, 0);
    let report = std::fs::read_to_string(out.join("t/t.report.html")).unwrap();
    assert!(report.contains("hazard"), "the table has hazards");
    assert!(
        !report.contains("--safety watchdog"),
        "proposed off the board"
    );
    let (_dir, _, refused) =
        convert_csv(table, &[&args[..], &["--safety", "watchdog"]].concat(), 1);
    assert!(stderr(&refused).contains("error[E036]"));
    let dir = tempfile::tempdir().unwrap();
    let assert = steptable()
        .arg("faults")
        .arg(crate::helpers::sample("paper_example.xlsx"))
        .args(["--board", "uno", "-o"])
        .arg(dir.path().join("out"))
        .assert()
        .code(1);
    assert!(
        stderr(&assert).contains("error[E036]"),
        "{}",
        stderr(&assert)
    );
    assert!(files_below(&dir.path().join("out")).is_empty());
}

/// A hazard that stays under every check as motion no step commands (the
/// halt cut a spring-return valve's coil) is answered with a valve that
/// holds without its coil, not with a better sensor: the remedy is read
/// from the hazard that remains, not from the fault's kind.
#[test]
fn the_remedy_answers_the_motion_a_halt_leaves() {
    let settings: &[&[&str]] = &[
        &["on halt", "y1 off"],
        &["actuator", "extend", "retract", "valve"],
        &["C1", "", "", "52mono"],
    ];
    let sheets = [
        ("SEQUENTIAL CONTROL DESCRIPTION", FOUR),
        ("SETTINGS", settings),
    ];
    let (_dir, out, _) = convert_workbook(&sheets, &["--safety", "all"], 0);
    let report = std::fs::read_to_string(out.join("h/h.report.html")).unwrap();
    let rows: Vec<&str> = report
        .split("<tr")
        .filter(|r| r.contains("unintended motion") && r.contains("what would"))
        .collect();
    assert!(!rows.is_empty(), "no hazard of motion a halt leaves");
    for row in rows {
        assert!(row.contains("without its coil"), "{row}");
        assert!(!row.contains("a redundant sensor"), "{row}");
        assert!(!row.contains("minimum travel time"), "{row}");
    }
}

/// A jump input stuck off (a dead reject sensor) loses the path the jump
/// exists for: a hazard naming the cycle and the jump, never "no effect".
#[test]
fn a_lost_jump_path_is_a_hazard() {
    let said = faults_of(
        ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0;J:end if I:reject\nSTEP 3,C2+1\nSTEP 4,C2-0\n",
        &[],
    );
    let row = said
        .lines()
        .find(|l| l.contains("reject open circuit"))
        .unwrap_or_else(|| panic!("no reject row in {said}"));
    assert!(row.contains("hazard"), "{row}");
    assert!(row.contains("was to take J:end if I:reject"), "{row}");
}

/// The Ladder bodies' rung comments (plausibility, jog, middle stop) speak
/// the designations chosen and name the actuators, as every other body.
#[test]
fn ladder_comments_speak_the_chosen_designations() {
    let settings: &[&[&str]] = &[
        &["designations", "names"],
        &["actuator", "name"],
        &["C1", "Clamp"],
        &["C2", "punch"],
    ];
    let sheets = [
        ("SEQUENTIAL CONTROL DESCRIPTION", FOUR),
        ("SETTINGS", settings),
    ];
    let args = ["--modes", "all", "--safety", "all", "--formats", "ld"];
    let (_dir, out, _) = convert_workbook(&sheets, &args, 0);
    let ld = std::fs::read_to_string(out.join("h/h.ld.xml")).unwrap();
    let comments: Vec<&str> = ld
        .split("<xhtml:p>")
        .skip(1)
        .filter_map(|c| c.split("</xhtml:p>").next())
        .filter(|c| c.starts_with("plausibility") || c.starts_with("jog"))
        .collect();
    assert!(!comments.is_empty(), "no plausibility or jog rung");
    for comment in comments {
        for paper in ["x10", "x11", "y1+", "jog1+"] {
            assert!(!comment.contains(paper), "{paper} in {comment}");
        }
        assert!(
            comment.contains("Clamp") || comment.contains("punch"),
            "{comment}"
        );
    }
}

/// An actuator-table column header misspelt over values (`vlave`, `extnd`)
/// is E046 at the header, as a misspelt setting: read as a note, the
/// program would get the default valve and stroke without a word. A header
/// far from any column (`remarks`) stays W003.
#[test]
fn a_misspelt_actuator_column_is_an_error_at_its_header() {
    let table: &[&[&str]] = &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 2", "C1-0"]];
    let cases: [(&[&[&str]], i32, &str); 3] = [
        (
            &[
                &["actuator", "extend", "retract", "vlave"],
                &["C1", "3s", "1s", "52mono"],
            ],
            1,
            "SETTINGS!D1: error[E046]",
        ),
        (
            &[&["actuator", "extnd", "retract"], &["C1", "3s", "1s"]],
            1,
            "SETTINGS!B1: error[E046]",
        ),
        (
            &[&["actuator", "extend", "remarks"], &["C1", "3s", "spare"]],
            0,
            "SETTINGS!C1: warning[W003]",
        ),
    ];
    for (settings, exit, says) in cases {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("h.xlsx");
        write_xlsx_sheets(
            &path,
            &[
                ("SEQUENTIAL CONTROL DESCRIPTION", table),
                ("SETTINGS", settings),
            ],
        );
        let assert = steptable().arg("check").arg(&path).assert().code(exit);
        let err = stderr(&assert);
        assert!(err.contains(says), "{says}: {err}");
    }
}

/// `synth` names its signals by the paper's symbols: the actuators' names
/// on the SETTINGS sheet are W006 at their cells, not dropped in silence.
#[test]
fn synth_says_it_leaves_the_actuators_names_out() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("h.xlsx");
    write_xlsx_sheets(
        &path,
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", FOUR),
            (
                "SETTINGS",
                &[&["actuator", "name"], &["C1", "clamp"], &["C2", "punch"]],
            ),
        ],
    );
    let assert = steptable()
        .arg("synth")
        .arg(&path)
        .arg("-o")
        .arg(dir.path().join("out"))
        .assert()
        .code(0);
    let err = stderr(&assert);
    for cell in ["SETTINGS!B2: warning[W006]", "SETTINGS!B3: warning[W006]"] {
        assert!(err.contains(cell), "{cell}: {err}");
    }
}

/// A check steptable refuses to build (a watchdog longer than a PLC timer
/// holds: a 400 s stroke) leaves the others: they are still tried
/// together, and named so, where none alone catches the hazard.
#[test]
fn the_checks_that_can_be_built_are_tried_together() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(crate::helpers::sample("paper_example.xlsx"))
        .args(["--stroke", "C1=400s", "--formats", "report", "-o"])
        .arg(&out)
        .assert()
        .code(0);
    let report =
        std::fs::read_to_string(out.join("paper_example/paper_example.report.html")).unwrap();
    assert!(
        !report.contains("--safety watchdog"),
        "a watchdog it refuses"
    );
    assert!(
        report.contains("--safety edge,precheck,plausibility"),
        "the three built checks together are named"
    );
}

/// The messages name the options as the command line spells them (`--scan`,
/// not `--scan-time`), and a dwell's range as it is (655.35 s, the most a
/// PLC timer holds: accepted, 655.36 s refused).
#[test]
fn messages_name_the_option_and_the_range_as_they_are() {
    let table: &[&[&str]] = &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 2", "C1-0"]];
    let settings: &[&[&str]] = &[&["scan time", "20ms"]];
    let sheets = [
        ("SEQUENTIAL CONTROL DESCRIPTION", table),
        ("SETTINGS", settings),
    ];
    let (_dir, _, assert) = convert_workbook(&sheets, &["--scan", "10ms"], 0);
    let err = stderr(&assert);
    assert!(
        err.contains("SETTINGS!B1: warning[W006]: scan time: --scan on the command line wins"),
        "{err}"
    );
    convert_csv(",BRANCH 1\nSTEP 1,C1+1; T=655.35s\nSTEP 2,C1-0\n", &[], 0);
    let (_dir, _, refused) =
        convert_csv(",BRANCH 1\nSTEP 1,C1+1; T=655.36s\nSTEP 2,C1-0\n", &[], 1);
    assert!(
        stderr(&refused).contains("from 10 ms to 655.35 s"),
        "{}",
        stderr(&refused)
    );
}
