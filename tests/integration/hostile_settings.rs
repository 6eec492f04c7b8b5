//! Hostile settings, table-driven: motion the emergency stop would not stop,
//! settings for actuators or inputs the table does not have. Each row goes
//! through the binary (`convert`): its exit code, its code at its cell (or
//! option), and nothing written for a refused one.

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{convert_sheets, files_below};

/// One hostile input: the SETTINGS rows, the options, and what must come out.
struct Case {
    what: &'static str,
    table: &'static [&'static [&'static str]],
    settings: &'static [&'static [&'static str]],
    args: &'static [&'static str],
    exit: i32,
    /// `SETTINGS!B2: error[E030]` or `error[E030]` for an option; empty for none.
    code_at: &'static str,
    says: &'static str,
}

const TWO: &[&[&str]] = &[
    &["C1+1; Y:vacuum+"],
    &["C2+1"],
    &["C2-0"],
    &["C1-0; Y:vacuum-"],
];

/// The row through `convert`, as every hostile table is
/// ([`crate::helpers::convert_sheets`]), with the exit code of the row.
fn run(case: &Case) {
    let (_dir, out, assert) = convert_sheets(case.table, case.settings, case.args, case.exit);
    let assert = if case.code_at.is_empty() {
        assert.stderr(contains("error[").not())
    } else {
        assert.stderr(contains(case.code_at))
    };
    assert.stderr(contains(case.says));
    if case.exit != 0 {
        assert!(
            !out.exists() || files_below(&out).is_empty(),
            "{}: refused but wrote files",
            case.what
        );
    }
}

/// `hold on estop` and `on estop` may keep on only what holds a part and
/// moves nothing: a motor's contactor or a valve coil is E030 at the cell.
#[test]
fn the_emergency_stop_keeps_no_motion_on() {
    let cases = [
        Case {
            what: "a drive held on",
            table: TWO,
            settings: &[
                &["modes", "estop"],
                &["hold on estop", "C1"],
                &["actuator", "extend", "retract", "valve"],
                &["C1", "", "", "motor"],
            ],
            args: &[],
            exit: 1,
            code_at: "SETTINGS!B2: error[E030]: hold on estop: y1+ is a contactor of drive C1",
            says: "keeps the drive running through the EMERGENCY STOP",
        },
        Case {
            what: "a drive's contactor running on",
            table: TWO,
            settings: &[
                &["modes", "estop"],
                &["on estop", "y1+ off after 30s"],
                &["actuator", "extend", "retract", "valve"],
                &["C1", "", "", "motor"],
            ],
            args: &[],
            exit: 1,
            code_at: "SETTINGS!B2: error[E030]: on estop: y1+ is a contactor of drive C1",
            says: "every drive stops",
        },
        Case {
            what: "a bistable coil held",
            table: TWO,
            settings: &[&["modes", "estop"], &["on estop", "y2+ hold, vacuum hold"]],
            args: &[],
            exit: 1,
            code_at: "SETTINGS!B2: error[E030]: on estop: y2+ is a valve coil of C2",
            says: "drives the piston on from wherever it stood",
        },
        Case {
            what: "a spring-return coil running on",
            table: TWO,
            settings: &[
                &["modes", "estop"],
                &["on estop", "y2 off after 30s"],
                &["actuator", "extend", "retract", "valve"],
                &["C2", "", "", "52mono"],
            ],
            args: &[],
            exit: 1,
            code_at: "SETTINGS!B2: error[E030]: on estop: y2 is a valve coil of C2",
            says: "a clamp on a 52bi valve keeps its position",
        },
        Case {
            what: "a coil held by --valve's 53closed",
            table: TWO,
            settings: &[&["modes", "estop"], &["hold on estop", "y1-"]],
            args: &["--valve", "C1=53closed"],
            exit: 1,
            code_at: "SETTINGS!B2: error[E030]: hold on estop: y1- is a valve coil of C1",
            says: "only a machine output that holds a part",
        },
        Case {
            what: "the vacuum held (a machine output)",
            table: TWO,
            settings: &[&["modes", "estop"], &["hold on estop", "vacuum"]],
            args: &[],
            exit: 0,
            code_at: "",
            says: "",
        },
    ];
    for case in &cases {
        run(case);
    }
}

/// A valve, stroke, load or input delay for an actuator or input the table
/// does not have is E030 naming it, at its SETTINGS cell or its option; a
/// real one converts.
#[test]
fn settings_for_what_the_table_does_not_have_are_refused() {
    const WAITS: &[&[&str]] = &[&["C1+1"], &["I:part; C2+1"], &["C2-0"], &["C1-0"]];
    let cases = [
        Case {
            what: "--valve for C9",
            table: TWO,
            settings: &[],
            args: &["--valve", "C9=52mono"],
            exit: 1,
            code_at: "h.xlsx: error[E030]: --valve C9=…: the table has no actuator C9 (it has C1, C2)",
            says: "would do nothing",
        },
        Case {
            what: "--stroke for C9",
            table: TWO,
            settings: &[],
            args: &["--stroke", "C9=2s"],
            exit: 1,
            code_at: "error[E030]: --stroke C9=…: the table has no actuator C9",
            says: "would do nothing",
        },
        Case {
            what: "--load for C9",
            table: TWO,
            settings: &[],
            args: &["--load", "C9=0.2"],
            exit: 1,
            code_at: "error[E030]: --load C9=…: the table has no actuator C9",
            says: "would do nothing",
        },
        Case {
            what: "--input-delay for an input no step waits for",
            table: WAITS,
            settings: &[],
            // A batch gives one option to tables that differ: a warning.
            args: &["--input-delay", "prt=2s"],
            exit: 0,
            code_at: "",
            says: "warning[W006]: --input-delay prt=…: prt is no machine input of this table (its inputs: part); nothing is delayed",
        },
        Case {
            what: "a SETTINGS actuator row for C9",
            table: TWO,
            settings: &[
                &["actuator", "extend", "retract", "valve"],
                &["C1", "2s", "2s", "52bi"],
                &["C9", "2s", "2s", "52mono"],
            ],
            args: &[],
            exit: 1,
            code_at: "SETTINGS!A3: error[E030]: the actuator table names C9, which the table does not have (it has C1, C2)",
            says: "its settings would do nothing",
        },
        Case {
            what: "a SETTINGS row for C9 at the default stroke (as the old template wrote C1 to C8)",
            table: TWO,
            settings: &[
                &["actuator", "extend", "retract", "valve"],
                &["C9", "1s", "1s", ""],
            ],
            args: &[],
            exit: 0,
            code_at: "SETTINGS!B2: warning[W003]: the time cells of C9 (B2, C2) hold 1s",
            says: "they were not read",
        },
        Case {
            what: "the real ones",
            table: WAITS,
            settings: &[
                &["actuator", "extend", "retract", "valve"],
                &["C2", "2s", "2s", "52mono"],
            ],
            args: &[
                "--valve",
                "C1=52mono",
                "--stroke",
                "C1=2s",
                "--input-delay",
                "part=1s",
            ],
            exit: 0,
            code_at: "",
            says: "",
        },
    ];
    for case in &cases {
        run(case);
    }
}

/// A safety or mode row misspelt (red team rt7, finding 7): the program
/// would be written without it, so it is E046 at the label's cell naming
/// the label meant, exit 1, nothing written; a note row merely like a
/// label (`notes`, two letters from `modes`) stays a warning.
#[test]
fn a_misspelt_setting_is_refused_at_its_cell() {
    let mistyped: [(&[&[&str]], &str, &str); 8] = [
        (
            &[&["mode", "all"]],
            "SETTINGS!A1: error[E046]",
            "did you mean `modes`?",
        ),
        (
            &[&["hold safe", "C1"]],
            "SETTINGS!A1: error[E046]",
            "did you mean `hold-safe`?",
        ),
        (
            &[&["safety", "watchdog"], &["on-halt", "y1+ off"]],
            "SETTINGS!A2: error[E046]",
            "did you mean `on halt`?",
        ),
        (
            &[&["safety", "watchdog"], &["supervison", "1=5s"]],
            "SETTINGS!A2: error[E046]",
            "did you mean `supervision`?",
        ),
        (
            &[&["Safty", "watchdog"]],
            "SETTINGS!A1: error[E046]",
            "did you mean `safety`?",
        ),
        (
            &[&["MODES.", "all"]],
            "SETTINGS!A1: error[E046]",
            "did you mean `modes`?",
        ),
        (
            &[&["scan-time", "20ms"]],
            "SETTINGS!A1: error[E046]",
            "did you mean `scan time`?",
        ),
        (
            &[&["modes: step", ""], &["target", "iec"]],
            "SETTINGS!A1: error[E046]",
            "holds the setting modes and its value in one cell",
        ),
    ];
    for (settings, code_at, says) in mistyped {
        run(&Case {
            what: "a misspelt setting",
            table: TWO,
            settings,
            args: &[],
            exit: 1,
            code_at,
            says,
        });
    }
    run(&Case {
        what: "a note row like a label",
        table: TWO,
        settings: &[&["notes", "checked by the panel builder"]],
        args: &[],
        exit: 0,
        code_at: "",
        says: "SETTINGS!A1: warning[W003]",
    });
}
