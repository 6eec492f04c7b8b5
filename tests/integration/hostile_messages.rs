//! Hostile inputs whose failure must be said plainly: a UTF-32 CSV, an
//! event at power-up, a failed simulation read as JSON. Table-driven through
//! the binary: exit code, code, where, and what the message says.

use predicates::str::contains;

use crate::helpers::steptable;

struct Case {
    what: &'static str,
    bytes: Vec<u8>,
    args: &'static [&'static str],
    exit: i32,
    /// Expected on stderr (human) or stdout (JSON).
    stderr: &'static str,
    stdout: &'static str,
}

const TWO: &str = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n";
const MIDDLE: &str = ",BRANCH 1\nSTEP 1,C1+2\nSTEP 2,C1-1\nSTEP 3,T=2s\nSTEP 4,C1-0\n";

fn utf32(text: &str, little: bool) -> Vec<u8> {
    let mut bytes = Vec::new();
    let bom: u32 = 0xFEFF;
    for c in std::iter::once(bom).chain(text.chars().map(u32::from)) {
        bytes.extend(if little {
            c.to_le_bytes()
        } else {
            c.to_be_bytes()
        });
    }
    bytes
}

#[test]
fn failures_are_said_plainly() {
    let cases = [
        Case {
            what: "UTF-32 little-endian",
            bytes: utf32(TWO, true),
            args: &["check"],
            exit: 1,
            stderr: "t.csv: error[E002]: UTF-32 text (its byte order mark says so), which steptable does not read",
            stdout: "",
        },
        Case {
            what: "UTF-32 big-endian",
            bytes: utf32(TWO, false),
            args: &["check"],
            exit: 1,
            stderr: "error[E002]: UTF-32 text",
            stdout: "",
        },
        Case {
            // A pressurised centre cannot hold a middle position: the
            // piston creeps out while step 3 dwells there. (At home the
            // program holds it with its - coil.)
            what: "a piston creeping is said in the step it creeps in",
            bytes: MIDDLE.as_bytes().to_vec(),
            args: &["simulate", "--valve", "C1=53pressure"],
            exit: 1,
            stderr: "",
            stdout: "at 1.94 s: unintended motion: C1 moves + although no step moves it that way (during step 3)",
        },
        Case {
            what: "a pressurised centre rests home on its - coil",
            bytes: TWO.as_bytes().to_vec(),
            args: &["simulate", "--valve", "C1=53pressure"],
            exit: 0,
            stderr: "",
            stdout: "passed: cycle time 1.96 s",
        },
        Case {
            what: "a failed simulation in JSON",
            bytes: MIDDLE.as_bytes().to_vec(),
            args: &[
                "simulate",
                "--valve",
                "C1=53pressure",
                "--message-format",
                "json",
            ],
            exit: 1,
            stderr: "FAILED",
            stdout: "\"code\":\"E032\",\"column\":null,\"file\":",
        },
        Case {
            what: "a UTF-16 CSV still reads",
            bytes: {
                let mut b = vec![0xFF, 0xFE];
                b.extend(TWO.encode_utf16().flat_map(u16::to_le_bytes));
                b
            },
            args: &["check"],
            exit: 0,
            stderr: "W001",
            stdout: "ok",
        },
    ];
    for case in &cases {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.csv");
        std::fs::write(&path, &case.bytes).unwrap();
        let (command, rest) = case.args.split_first().unwrap();
        let assert = steptable()
            .arg(command)
            .arg(&path)
            .args(rest)
            .assert()
            .code(case.exit)
            .stderr(contains(case.stderr))
            .stdout(contains(case.stdout));
        if case.args.contains(&"json") {
            let stdout = String::from_utf8(assert.get_output().stdout.clone()).unwrap();
            let line = stdout
                .lines()
                .next()
                .unwrap_or_else(|| panic!("{}: no JSON", case.what));
            let v: serde_json::Value = serde_json::from_str(line).unwrap();
            assert!(
                v["message"]
                    .as_str()
                    .unwrap()
                    .contains("fails its simulation"),
                "{}: {v}",
                case.what
            );
        }
    }
}

/// A dwell without a unit is read as seconds and said (W007 at its cell,
/// with both spellings); with a unit nothing is said.
#[test]
fn a_dwell_without_a_unit_is_said() {
    let dir = tempfile::tempdir().unwrap();
    let cases = [
        (
            "T=500",
            Some(
                "\"T=500\" has no unit and is read as 500 seconds: write T=500s, or T=500ms if milliseconds were meant",
            ),
        ),
        (
            "T = 2",
            Some("\"T = 2\" has no unit and is read as 2 seconds: write T=2s"),
        ),
        (
            "T=1.5",
            Some("\"T=1.5\" has no unit and is read as 1.5 seconds: write T=1.5s"),
        ),
        ("T=500ms", None),
        ("T=2s", None),
    ];
    for (dwell, message) in cases {
        let path = dir.path().join("t.csv");
        std::fs::write(
            &path,
            format!(",BRANCH 1\nSTEP 1,\"C1+1; {dwell}\"\nSTEP 2,C1-0\n"),
        )
        .unwrap();
        let output = steptable().arg("check").arg(&path).output().unwrap();
        assert_eq!(output.status.code(), Some(0), "{dwell}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        match message {
            Some(message) => assert!(
                stderr.contains(&format!("t.csv:2:2: warning[W007]: {message}")),
                "{stderr}"
            ),
            None => assert!(!stderr.contains("W007"), "{stderr}"),
        }
    }
}

/// What would be dropped without a word is said: `--load` for a valve that
/// holds its piston, `--sheet` for a CSV file (W006), and a copied BRANCH
/// header (W002 at its cell); the run goes on.
#[test]
fn options_and_headers_that_do_nothing_are_said() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.csv");
    std::fs::write(
        &path,
        ",BRANCH 1,BRANCH 1\nSTEP 1,C1+1,C2+1\nSTEP 2,C1-0,C2-0\n",
    )
    .unwrap();
    let cases: &[(&[&str], &str)] = &[
        (
            &[],
            "t.csv:1:3: warning[W002]: this column is headed BRANCH 1 but is branch 2 of the table",
        ),
        (
            &["--valve", "C1=52bi", "--load", "C1=0.5"],
            "t.csv: warning[W006]: --load C1=0.5: C1's valve is 52bi, which holds the piston",
        ),
        (&["--load", "C2=0.5"], "--load C2=0.5: C2's valve is 52bi"),
        (
            &["--sheet", "EXAMPLE"],
            "t.csv: warning[W006]: --sheet EXAMPLE has no effect on a CSV file",
        ),
    ];
    for (args, message) in cases {
        let output = steptable()
            .arg("simulate")
            .arg(&path)
            .args(*args)
            .output()
            .unwrap();
        assert_eq!(output.status.code(), Some(0), "{args:?}");
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert!(stderr.contains(message), "{args:?}: {stderr}");
    }
    // Where the load moves the piston, nothing is said.
    let output = steptable()
        .arg("simulate")
        .arg(&path)
        .args(["--valve", "C1=53exhaust", "--load", "C1=0.5"])
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert!(!stderr.contains("W006"), "{stderr}");
}

/// A wrong command line under `--message-format json` is one JSON object
/// (E041, the parser's reason) on stdout, exit 1; without it stdout stays
/// empty.
#[test]
fn a_wrong_command_line_is_json_when_json_is_asked() {
    for args in [
        &[
            "check",
            "x.csv",
            "--message-format",
            "json",
            "--valve",
            "C1=bogus",
        ][..],
        &[
            "convert",
            "x.csv",
            "--message-format=json",
            "--modes",
            "stop,stop",
        ],
        &["simulate", "x.csv", "--message-format", "json", "--bogus"],
    ] {
        let output = steptable().args(args).output().unwrap();
        assert_eq!(output.status.code(), Some(1), "{args:?}");
        let stdout = String::from_utf8_lossy(&output.stdout);
        let value: serde_json::Value = serde_json::from_str(stdout.trim()).unwrap();
        assert_eq!(value["code"], "E041", "{stdout}");
        assert_eq!(value["severity"], "error");
        assert!(value["file"].is_null());
        let message = value["message"].as_str().unwrap();
        assert!(
            !message.is_empty() && !message.starts_with("error:"),
            "{message}"
        );
    }
    let output = steptable()
        .args(["check", "x.csv", "--bogus"])
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(1));
    assert!(output.stdout.is_empty());
}
