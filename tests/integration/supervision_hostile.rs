//! The hostile inputs of step supervision (`--supervision`, the SETTINGS
//! row `supervision`, `--safety criteria`), each through the binary: exit
//! 1, its code at its cell (or the option's message), nothing written.

use crate::helpers::{Refused, assert_refused, steptable, write_xlsx_sheets};

/// C1 out (1 s), C1 home (1 s).
const TWO: &[&[&str]] = &[&["C1+1"], &["C1-0"]];

/// C1 out (1 s) while step 1 waits for I:part, which the proof answers
/// after `--input-delay` (0.5 s unless given); C1 home.
const WAITING: &[&[&str]] = &[&["C1+1; I:part"], &["C1-0"]];

const CASES: &[Refused] = &[
    Refused {
        what: "a supervision time without the watchdog",
        table: TWO,
        settings: &[],
        args: &["--supervision", "1=5s"],
        code_at: "error[E030]: --supervision: a supervision time sets the step watchdog",
    },
    Refused {
        what: "a supervision row beside a safety row without the watchdog (contradictory)",
        table: TWO,
        settings: &[&["safety", "edge"], &["supervision", "1=5s"]],
        args: &[],
        code_at: "SETTINGS!B2: error[E030]",
    },
    Refused {
        what: "the SETTINGS row against the command line's --safety none",
        table: TWO,
        settings: &[&["supervision", "1=5s"]],
        args: &["--safety", "none"],
        code_at: "SETTINGS!B1: error[E030]",
    },
    Refused {
        what: "a step the table does not have, on the command line",
        table: TWO,
        settings: &[],
        args: &["--safety", "watchdog", "--supervision", "3=5s"],
        code_at: "error[E030]: --supervision: step 3 is not a step of the table",
    },
    Refused {
        what: "a step the table does not have, on SETTINGS",
        table: TWO,
        settings: &[&["safety", "criteria"], &["supervision", "1=5s, 7=5s"]],
        args: &[],
        code_at: "SETTINGS!B2: error[E030]",
    },
    Refused {
        what: "a time shorter than the step takes",
        table: TWO,
        settings: &[],
        args: &["--safety", "criteria", "--supervision", "1=800ms"],
        code_at: "step 1's 800ms is not longer than the 1s",
    },
    Refused {
        what: "a waiting step's time shorter than the proof's wait (rt7 finding 10: was an internal error)",
        table: WAITING,
        settings: &[],
        args: &[
            "--safety",
            "watchdog",
            "--input-delay",
            "part=3s",
            "--supervision",
            "1=2s",
        ],
        code_at: "error[E030]: --supervision: step 1's 2s is not longer than the 3s the step takes in the program's proof, which answers its wait for I:part after 3s",
    },
    Refused {
        what: "a waiting step's time shorter than the proof's wait, on SETTINGS",
        table: WAITING,
        settings: &[&["safety", "watchdog"], &["supervision", "1=1200ms"]],
        args: &["--input-delay", "part=2s"],
        code_at: "SETTINGS!B2: error[E030]: supervision: step 1's",
    },
    Refused {
        what: "a time shorter than the step takes, on SETTINGS",
        table: TWO,
        settings: &[&["safety", "watchdog"], &["supervision", "2=1s"]],
        args: &[],
        code_at: "SETTINGS!B2: error[E030]",
    },
    Refused {
        what: "a time beyond what a timer holds, on SETTINGS",
        table: TWO,
        settings: &[&["safety", "watchdog"], &["supervision", "1=700s"]],
        args: &[],
        code_at: "SETTINGS!B2: error[E030]",
    },
    Refused {
        what: "a time beyond what a timer holds, on the command line",
        table: TWO,
        settings: &[],
        args: &["--safety", "watchdog", "--supervision", "1=700s"],
        code_at: "655.35 s",
    },
    Refused {
        what: "a time without its unit",
        table: TWO,
        settings: &[&["safety", "watchdog"], &["supervision", "1=5"]],
        args: &[],
        code_at: "SETTINGS!B2: error[E030]",
    },
    Refused {
        what: "step 0, no table step",
        table: TWO,
        settings: &[],
        args: &["--safety", "watchdog", "--supervision", "0=5s"],
        code_at: "0 is not a step number",
    },
    Refused {
        what: "a step given twice",
        table: TWO,
        settings: &[],
        args: &["--safety", "watchdog", "--supervision", "1=5s,1=6s"],
        code_at: "step 1 is given twice",
    },
    Refused {
        what: "the option repeated",
        table: TWO,
        settings: &[],
        args: &[
            "--safety",
            "watchdog",
            "--supervision",
            "1=5s",
            "--supervision",
            "2=5s",
        ],
        code_at: "cannot be used multiple times",
    },
    Refused {
        what: "the supervision row twice on SETTINGS",
        table: TWO,
        settings: &[
            &["safety", "watchdog"],
            &["supervision", "1=5s"],
            &["supervision", "2=5s"],
        ],
        args: &[],
        code_at: "SETTINGS!B3: error[E030]",
    },
    Refused {
        what: "criteria beside all",
        table: TWO,
        settings: &[&["safety", "all, criteria"]],
        args: &[],
        code_at: "SETTINGS!B1: error[E030]",
    },
    Refused {
        what: "criteria given twice on the command line",
        table: TWO,
        settings: &[],
        args: &["--safety", "criteria,criteria"],
        code_at: "\"criteria\" is given twice",
    },
    Refused {
        what: "a machine input named like a missing output",
        table: &[&["C1+1"], &["I:miss1"], &["C1-0"]],
        settings: &[],
        args: &["--safety", "criteria"],
        code_at: "TABLE!A2: error[E015]",
    },
    Refused {
        what: "a machine output named like an awaited memory, without the analysis",
        table: &[&["C1+1"], &["Y:Crit2+"], &["C1-0; Y:Crit2-"]],
        settings: &[],
        args: &[],
        code_at: "TABLE!A2: error[E015]",
    },
    Refused {
        what: "the missing outputs beyond the board's outputs",
        table: TWO,
        settings: &[],
        args: &["--board", "uno", "--safety", "criteria"],
        code_at: "error[E036]: the program needs 5 outputs",
    },
];

#[test]
fn hostile_supervision_inputs_are_refused_with_their_cell() {
    assert_refused(CASES);
}

/// The same table with a valid time on either side converts, and the time
/// is the watchdog's preset of that step in the written program.
#[test]
fn a_valid_supervision_time_is_the_steps_watchdog_preset() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("h.xlsx");
    let settings: &[&[&str]] = &[&["safety", "criteria"], &["supervision", "2=4.5s"]];
    write_xlsx_sheets(&path, &[("TABLE", TWO), ("SETTINGS", settings)]);
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(&path)
        .args(["--formats", "st", "-o"])
        .arg(&out)
        .assert()
        .success();
    let st = std::fs::read_to_string(out.join("h/h.st")).unwrap();
    assert!(st.contains("wd_pt := T#4500ms;"), "{st}");
    // Step 1 keeps the plant model's: twice 1 s, plus 1 s.
    assert!(st.contains("wd_pt := T#3000ms;"), "{st}");
    let cli = dir.path().join("cli");
    steptable()
        .arg("convert")
        .arg(dir.path().join("h.xlsx"))
        .args(["--supervision", "1=1.5s", "--formats", "st", "-o"])
        .arg(&cli)
        .assert()
        .success();
    let st = std::fs::read_to_string(cli.join("h/h.st")).unwrap();
    // The command line's word wins over the SETTINGS row, whole.
    assert!(st.contains("wd_pt := T#1500ms;"), "{st}");
    assert!(!st.contains("T#4500ms"), "{st}");
}

/// `check` and `convert` agree on a waiting step's supervision time (rt7
/// finding 10, where `check` passed and `convert` stopped with an
/// internal error): C1 moves in 100 ms while step 1 waits for I:part (0.5
/// s in the proof), so 300 ms is refused by both with E030, exit 1, and
/// nothing written; 700 ms is accepted by both — unless `convert` is told
/// the input comes after 1 s.
#[test]
fn check_and_convert_agree_on_a_waiting_steps_time() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("waits.xlsx");
    let settings: &[&[&str]] = &[
        &["safety", "watchdog"],
        &["actuator", "extend", "retract"],
        &["C1", "100ms", "100ms"],
    ];
    write_xlsx_sheets(&path, &[("TABLE", WAITING), ("SETTINGS", settings)]);
    let out = dir.path().join("out");
    for (time, delay, code) in [
        ("1=300ms", None, 1),
        ("1=700ms", None, 0),
        ("1=700ms", Some("part=1s"), 1),
    ] {
        let said = "error[E030]: --supervision: step 1's";
        let check = steptable()
            .arg("check")
            .arg(&path)
            .args(["--supervision", time])
            .assert();
        if delay.is_none() {
            let check = check.code(code);
            let stderr = String::from_utf8_lossy(&check.get_output().stderr).into_owned();
            assert_eq!(stderr.contains(said), code == 1, "{time}: {stderr}");
        }
        let mut convert = steptable();
        convert
            .arg("convert")
            .arg(&path)
            .args(["--supervision", time]);
        if let Some(delay) = delay {
            convert.args(["--input-delay", delay]);
        }
        let run = convert
            .args(["--formats", "st", "-o"])
            .arg(&out)
            .assert()
            .code(code);
        let stderr = String::from_utf8_lossy(&run.get_output().stderr).into_owned();
        assert_eq!(
            stderr.contains(said),
            code == 1,
            "{time} {delay:?}: {stderr}"
        );
        assert!(!stderr.contains("internal error"), "{stderr}");
        assert_eq!(out.exists(), code == 0, "{time} {delay:?}");
        let _ = std::fs::remove_dir_all(&out);
    }
}
