//! Names where the engineer types them (issue 37): the home order (its
//! SETTINGS row and `--home-order`) and `--load` take an actuator as C1,
//! its ISO designation 1A1 or its name from the SETTINGS actuator table,
//! and the made-by line names actuators as that table writes them. Rows
//! through the binary with [`crate::hostile_round3::run`]: exit code, code
//! at its cell or option, nothing written for a refused one.

use crate::helpers::{steptable, write_xlsx_sheets};
use crate::hostile_round3::{Case, NAMED, TWO, run};

/// The home order and `--load` take an actuator as the engineer would type
/// it: its number, its ISO designation or its name from the SETTINGS
/// actuator table. Misspelt, unknown, repeated under two names, given by
/// name and number: E030 at the cell or naming the option, with the
/// closest name where one is near, nothing written.
#[test]
fn the_home_order_and_load_take_names_and_refuse_what_no_actuator_answers_to() {
    const MODES: &[&[&str]] = &[
        &["modes", "all"],
        &["actuator", "extend", "retract"],
        &["C1 (lift)", "1s", "1s"],
        &["C2 (clamp)", "1s", "1s"],
    ];
    let cases = [
        Case {
            what: "a misspelt name on the SETTINGS row",
            sheets: &[
                ("TABLE", TWO),
                (
                    "SETTINGS",
                    &[
                        &["modes", "all"],
                        &["home order", "clmap, lift"],
                        &["actuator", "extend", "retract"],
                        &["C1 (lift)", "1s", "1s"],
                        &["C2 (clamp)", "1s", "1s"],
                    ],
                ),
            ],
            args: &["--formats", "st"],
            exit: 1,
            says: &[
                "SETTINGS!B2: error[E030]: the home order names \"clmap\", which is no actuator",
                "did you mean clamp?",
            ],
            never: &[],
        },
        Case {
            what: "a misspelt name in --home-order",
            sheets: &[("TABLE", TWO), ("SETTINGS", MODES)],
            args: &["--home-order", "2A1 lfit", "--formats", "st"],
            exit: 1,
            says: &[
                "h.xlsx: error[E030]: the home order names \"lfit\", which is no actuator",
                "did you mean lift? (--home-order)",
            ],
            never: &[],
        },
        Case {
            what: "a name with a space parted into two items of a stage",
            sheets: &[
                ("TABLE", TWO),
                (
                    "SETTINGS",
                    &[
                        &["modes", "all"],
                        &["actuator", "extend", "retract"],
                        &["C1 (gripper arm)", "1s", "1s"],
                        &["C2 (clamp)", "1s", "1s"],
                    ],
                ),
            ],
            args: &["--home-order", "clamp, gripper arm", "--formats", "st"],
            exit: 1,
            says: &[
                "h.xlsx: error[E030]: the home order names \"gripper arm\" as 2 actuators, but a space parts the actuators of a stage: write the name as gripper_arm (--home-order)",
            ],
            never: &["\"arm\", which is no actuator"],
        },
        Case {
            what: "one actuator's valve given by its name and its ISO designation",
            sheets: &[("TABLE", TWO), ("SETTINGS", MODES)],
            args: &["--valve", "lift=52mono,1A1=52bi", "--formats", "st"],
            exit: 1,
            says: &[
                "h.xlsx: error[E030]: --valve lift=…: lift is C1, which --valve gives as 1A1 too; give each actuator once",
            ],
            never: &[],
        },
        Case {
            what: "one actuator under two names",
            sheets: &[("TABLE", TWO), ("SETTINGS", MODES)],
            args: &["--home-order", "clamp, 2A1, lift", "--formats", "st"],
            exit: 1,
            says: &[
                "h.xlsx: error[E030]: the home order names C2 twice, as clamp and 2A1; name each actuator once (--home-order)",
            ],
            never: &[],
        },
        Case {
            what: "an ISO designation the table lacks",
            sheets: &[("TABLE", TWO), ("SETTINGS", MODES)],
            args: &["--home-order", "clamp, lift, 3A1", "--formats", "st"],
            exit: 1,
            says: &[
                "h.xlsx: error[E030]: the home order names C3, which the table does not move (--home-order)",
            ],
            never: &[],
        },
        Case {
            what: "a generated name is no actuator",
            sheets: &[("TABLE", TWO), ("SETTINGS", MODES)],
            args: &["--home-order", "clamp, start", "--formats", "st"],
            exit: 1,
            says: &["h.xlsx: error[E030]: the home order names \"start\", which is no actuator"],
            never: &["did you mean"],
        },
        Case {
            what: "a load for a misspelt name",
            sheets: &[("TABLE", TWO), ("SETTINGS", MODES)],
            args: &["--load", "clmap=0.1", "--formats", "st"],
            exit: 1,
            says: &[
                "h.xlsx: error[E030]: --load clmap=…: no actuator is named clmap",
                "did you mean clamp?",
            ],
            never: &[],
        },
        Case {
            what: "a load by name and by number",
            sheets: &[("TABLE", TWO), ("SETTINGS", MODES)],
            args: &["--load", "clamp=0.1,C2=0.2", "--formats", "st"],
            exit: 1,
            says: &["error[E030]: --load clamp=…: clamp is C2, which is given by number too"],
            never: &[],
        },
        Case {
            what: "a load by ISO designation on a valve that holds",
            sheets: &[("TABLE", TWO), ("SETTINGS", MODES)],
            args: &["--load", "2A1=0.1", "--formats", "st"],
            exit: 0,
            says: &["warning[W006]: --load C2=0.1: C2's valve is 52bi"],
            never: &["error["],
        },
        Case {
            what: "a load and valve by name",
            sheets: &[("TABLE", TWO), ("SETTINGS", MODES)],
            args: &[
                "--load",
                "clamp=0.1",
                "--valve",
                "2a1=53exhaust",
                "--formats",
                "st",
            ],
            exit: 0,
            says: &[],
            never: &["error[", "W006"],
        },
    ];
    for case in &cases {
        run(case);
    }
}

/// A home order by names, ISO designations or numbers is one order: RESET
/// homes the lift (C1) before the clamp (C2) whichever way it is written,
/// on the SETTINGS row and on the command line, where the cycle's own
/// order homes the clamp first.
#[test]
fn a_home_order_by_name_homes_as_the_same_order_by_number() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("h.xlsx");
    let settings: &[&[&str]] = &[
        &["modes", "all"],
        &["actuator", "extend", "retract"],
        &["C1 (lift)", "1s", "1s"],
        &["C2 (clamp)", "1s", "1s"],
        &["home order", "lift, clamp"],
    ];
    write_xlsx_sheets(&path, &[("TABLE", TWO), ("SETTINGS", settings)]);
    let plain = dir.path().join("p.xlsx");
    write_xlsx_sheets(&plain, &[("TABLE", TWO), ("SETTINGS", &settings[..4])]);
    let homes = |input: &std::path::Path, args: &[&str], out: &str| -> String {
        let assert = steptable()
            .arg("convert")
            .arg(input)
            .args(args)
            .args(["--formats", "st", "-o"])
            .arg(dir.path().join(out))
            .assert()
            .success();
        String::from_utf8_lossy(&assert.get_output().stdout).to_string()
    };
    let own = homes(&plain, &[], "own");
    // Said with the engineer's names.
    assert!(
        own.contains("RESET homes C2 (clamp), then C1 (lift)"),
        "{own}"
    );
    for (input, args, out) in [
        (&path, &[][..], "row"),
        (&plain, &["--home-order", "1A1, 2a1"][..], "iso"),
        (&plain, &["--home-order", "Lift,clamp"][..], "names"),
        (&plain, &["--home-order", "C1,C2"][..], "numbers"),
    ] {
        let stdout = homes(input, args, out);
        assert!(
            stdout.contains("RESET homes C1 (lift), then C2 (clamp)"),
            "{args:?}: {stdout}"
        );
    }
}

/// The line each output records of how it was made names an actuator whose
/// settings came from the SETTINGS sheet as the engineer's actuator table
/// writes it (`C1 (lift) stroke`), and not one the command line set by its
/// name (`--stroke clamp=2s`); the names themselves came from the sheet
/// too (`actuator names`).
#[test]
fn the_made_by_line_names_the_actuators_as_the_engineer_wrote_them() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("h.xlsx");
    write_xlsx_sheets(&path, &[("TABLE", TWO), ("SETTINGS", NAMED)]);
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(&path)
        .args(["--stroke", "clamp=2s", "--formats", "st", "-o"])
        .arg(&out)
        .assert()
        .success();
    let st = std::fs::read_to_string(out.join("h/h.st")).unwrap();
    let line = st.lines().next().unwrap();
    assert!(
        line.contains("settings: the command line, the SETTINGS sheet (C1 (lift) stroke, actuator names), defaults for the rest"),
        "{line}"
    );
}
