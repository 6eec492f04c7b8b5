//! Hostile cells of the actuator table and the table errors they meet
//! (red team rt8, findings 5, 6, 9 and 10), table-driven through the
//! binary (`convert`): each row's exit code, its code at its cell, what
//! else must be said in the same run, and what must not be said.
//!
//! - a time whose comma may separate thousands (`1,000ms`) is read by no
//!   time cell (E030 on SETTINGS, E014 as a dwell); `1,5s` is 1.5 s in
//!   every one;
//! - a refused stroke time is not "taken as given" afterwards (no W007);
//! - the old template's `1s | 1s` for an actuator the table lacks is W003
//!   at its cells, any other value for it E030, its name alone nothing;
//! - a position a kind cannot hold (E045) is said with the table's other
//!   errors, and no E022 asks to complete that move.

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{convert_sheets, files_below};

struct Case {
    what: &'static str,
    table: &'static [&'static [&'static str]],
    settings: &'static [&'static [&'static str]],
    exit: i32,
    /// The code at its cell (`SETTINGS!B2: error[E030]: …`).
    code_at: &'static str,
    /// Said in the same run as well.
    says: &'static [&'static str],
    /// Never said.
    not: &'static [&'static str],
}

const TABLE: &[&[&str]] = &[
    &["", "BRANCH 1"],
    &["STEP 1", "C1+1"],
    &["STEP 2", "C2+1"],
    &["STEP 3", "C2-0"],
    &["STEP 4", "C1-0"],
];

const HEAD: &[&str] = &["actuator", "extend", "retract", "valve"];

fn run(case: &Case) {
    let (_dir, out, assert) = convert_sheets(case.table, case.settings, &[], case.exit);
    let mut assert = assert.stderr(contains(case.code_at));
    for said in case.says {
        assert = assert.stderr(contains(*said));
    }
    for never in case.not {
        assert = assert.stderr(contains(*never).not());
    }
    if case.exit != 0 {
        assert!(
            !out.exists() || files_below(&out).is_empty(),
            "{}: refused but wrote files",
            case.what
        );
    }
}

#[test]
fn hostile_actuator_cells_are_said_at_their_cells() {
    let cases = [
        Case {
            what: "a stroke time with a thousands comma (finding 9)",
            table: TABLE,
            settings: &[HEAD, &["C1", "1,000ms", "1,000ms", ""]],
            exit: 1,
            code_at: "SETTINGS!B2: error[E030]: stroke time of C1: \"1,000ms\" has a comma that may separate thousands (1000ms) or be a decimal comma (1.000ms)",
            says: &["SETTINGS!C2: error[E030]", "(1.5s, 1000ms)"],
            not: &[],
        },
        Case {
            what: "a swivel drive's time with a thousands comma",
            table: TABLE,
            settings: &[HEAD, &["C2", "1,500s", "", "swivel"]],
            exit: 1,
            code_at: "SETTINGS!B2: error[E030]: stroke time of C2: \"1,500s\" has a comma",
            says: &[],
            not: &["W007"],
        },
        Case {
            what: "a scan time with a thousands comma",
            table: TABLE,
            settings: &[&["scan time", "0,010s"]],
            exit: 1,
            code_at: "SETTINGS!B1: error[E030]: scan time: \"0,010s\" has a comma that may separate thousands",
            says: &[],
            not: &[],
        },
        Case {
            what: "a dwell with a thousands comma",
            table: &[
                &["", "BRANCH 1"],
                &["STEP 1", "C1+1; T=1,000s"],
                &["STEP 2", "C1-0"],
            ],
            settings: &[HEAD, &["C1", "2s", "2s", ""]],
            exit: 1,
            code_at: "TABLE!B2: error[E014]: dwell \"T=1,000s\" has a comma that may separate thousands (T=1000s)",
            says: &[],
            not: &[],
        },
        Case {
            what: "a decimal comma, as every time cell reads it",
            table: TABLE,
            settings: &[HEAD, &["C1", "1,5s", "0,8s", ""]],
            exit: 0,
            code_at: "",
            says: &[],
            not: &["error[", "warning["],
        },
        Case {
            what: "an unreadable stroke time of a swivel drive (finding 6)",
            table: TABLE,
            settings: &[HEAD, &["C2", "5min", "800ms", "swivel"]],
            exit: 1,
            code_at: "SETTINGS!B2: error[E030]: stroke time of C2: \"5min\" is not a time",
            says: &[],
            not: &["W007", "taken as given"],
        },
        Case {
            what: "an unreadable time beside the old template's 1s",
            table: TABLE,
            settings: &[HEAD, &["C2", "1h", "1s", "swivel"]],
            exit: 1,
            code_at: "SETTINGS!B2: error[E030]: stroke time of C2: \"1h\" is not a time",
            says: &["SETTINGS!C2: warning[W007]: retract of C2: 1s is taken as given"],
            not: &["SETTINGS!B2: warning[W007]"],
        },
        Case {
            what: "the old template's rows for actuators the table lacks (finding 5)",
            table: TABLE,
            settings: &[
                HEAD,
                &["C1", "1s", "1s", ""],
                &["C2", "1s", "1s", ""],
                &["C3", "1s", "1s", ""],
                &["C4", "1s", "1s", ""],
            ],
            exit: 0,
            code_at: "SETTINGS!B4: warning[W003]: the time cells of C3 (B4, C4) hold 1s, which the template of earlier steptable versions wrote in every row, but the table does not move C3 (it has C1, C2); they were not read",
            says: &["SETTINGS!B5: warning[W003]: the time cells of C4 (B5, C5)"],
            not: &["error[", "of C1 (", "of C2 ("],
        },
        Case {
            what: "half a placeholder row",
            table: TABLE,
            settings: &[HEAD, &["C7", "", "1000ms", ""]],
            exit: 0,
            code_at: "SETTINGS!C2: warning[W003]: the time cells of C7 (C2) hold 1s",
            says: &[],
            not: &["error["],
        },
        Case {
            what: "another time for an actuator the table lacks",
            table: TABLE,
            settings: &[HEAD, &["C5", "2s", "2s", ""]],
            exit: 1,
            code_at: "SETTINGS!A2: error[E030]: the actuator table names C5, which the table does not have (it has C1, C2)",
            says: &[],
            not: &["W003"],
        },
        Case {
            what: "the placeholder times beside a valve for an absent actuator",
            table: TABLE,
            settings: &[HEAD, &["C5", "1s", "1s", "52bi"]],
            exit: 1,
            code_at: "SETTINGS!A2: error[E030]: the actuator table names C5",
            says: &[],
            not: &["W003"],
        },
        Case {
            what: "an absent actuator's name alone",
            table: TABLE,
            settings: &[HEAD, &["C5", "", "", ""]],
            exit: 0,
            code_at: "",
            says: &[],
            not: &["SETTINGS!"],
        },
        Case {
            what: "a gripper's impossible position with other table errors (finding 10)",
            table: &[
                &["", "BRANCH 1", "BRANCH 2"],
                &["STEP 1", "C1+1", "C2+2"],
                &["STEP 2", "I:fired", ""],
                &["STEP 3", "C1-0", "C2-0"],
                &["STEP 4", "C3+1", ""],
            ],
            settings: &[HEAD, &["C2", "", "", "vacuum"]],
            exit: 1,
            code_at: "TABLE!C2: error[E045]: \"C2+2\" asks C2 for position 2, but C2 is a gripper",
            says: &[
                "TABLE!B3: error[E015]",
                "TABLE!B5: error[E022]: C3 ends the cycle",
            ],
            not: &[],
        },
        Case {
            what: "a gripper left at its impossible position",
            table: &[
                &["", "BRANCH 1", "BRANCH 2"],
                &["STEP 1", "C1+1", "C2+2"],
                &["STEP 2", "C1-0", ""],
            ],
            settings: &[HEAD, &["C2", "", "", "vacuum"]],
            exit: 1,
            code_at: "TABLE!C2: error[E045]: \"C2+2\" asks C2 for position 2",
            says: &[],
            not: &["E022", "add C2-0"],
        },
        Case {
            what: "a swivel drive's middle position with a dwell error",
            table: &[
                &["", "BRANCH 1"],
                &["STEP 1", "C2+1; T=0"],
                &["STEP 2", "C2+2"],
                &["STEP 3", "C2-0"],
            ],
            settings: &[HEAD, &["C2", "", "", "swivel"]],
            exit: 1,
            code_at: "TABLE!B2: error[E045]: \"C2+1\" makes position 1 a middle position of C2",
            says: &["TABLE!B2: error[E014]"],
            not: &[],
        },
    ];
    for case in &cases {
        run(case);
    }
}
