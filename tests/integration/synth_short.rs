//! The shortest sequences synthesise and pass every proof, STOP included:
//! `A1 A0` (one cylinder out and back) once exited 2 because the mode
//! proof pressed STOP after its first cycle had ended, and still wrote the
//! five files of a program that had failed its proof. A failed proof
//! writes nothing.

use predicates::str::contains;

use crate::helpers::{files_below, steptable};

/// One way to write a short sequence, right or wrong, and what the binary
/// must answer.
struct Row {
    sequence: &'static str,
    code: i32,
    said: &'static str,
}

const ROWS: &[Row] = &[
    Row {
        sequence: "A1 A0",
        code: 0,
        said: "modes: passed",
    },
    Row {
        sequence: "A+ A-",
        code: 0,
        said: "modes: passed",
    },
    Row {
        sequence: "B1 B0",
        code: 0,
        said: "modes: passed",
    },
    Row {
        sequence: "A0 A1",
        code: 0,
        said: "modes: passed",
    },
    Row {
        sequence: "A1 A0 A1 A0",
        code: 0,
        said: "modes: passed",
    },
    Row {
        sequence: "A1 A1 A0",
        code: 1,
        said: "changes nothing",
    },
    Row {
        sequence: "A1",
        code: 1,
        said: "error[E0",
    },
    Row {
        sequence: "A1 B1 A0",
        code: 1,
        said: "error[E0",
    },
];

#[test]
fn the_shortest_sequences_pass_every_proof_and_a_refusal_writes_nothing() {
    for row in ROWS {
        let dir = tempfile::tempdir().unwrap();
        let assert = steptable()
            .args(["synth", "--sequence", row.sequence, "-o"])
            .arg(dir.path())
            .assert();
        let output = assert.get_output();
        let text = format!(
            "{}{}",
            String::from_utf8_lossy(&output.stdout),
            String::from_utf8_lossy(&output.stderr)
        );
        assert_eq!(
            output.status.code(),
            Some(row.code),
            "{}: {text}",
            row.sequence
        );
        assert!(text.contains(row.said), "{}: {text}", row.sequence);
        assert!(!text.contains("internal error"), "{}: {text}", row.sequence);
        let written = files_below(dir.path());
        if row.code == 0 {
            assert_eq!(written.len(), 5, "{}: {written:?}", row.sequence);
        } else {
            assert!(written.is_empty(), "{}: {written:?}", row.sequence);
        }
    }
    // The proof of `A1 A0`: STOP during the last cycle ends it there.
    steptable()
        .args(["synth", "--sequence", "A1 A0", "-o"])
        .arg(tempfile::tempdir().unwrap().path())
        .assert()
        .success()
        .stdout(contains("simulation: passed"))
        .stdout(contains(
            "modes: passed (START, STOP at the end of the cycle",
        ));
}

/// `synth` on a workbook says what of its SETTINGS and ADDRESSES it does
/// not build: a safety row (modes, safety, interlock, …) is E034 at its
/// cell and nothing is written (a proven controller without the engineer's
/// interlock would mislead); any other setting or pin is W006 at its cell.
#[test]
fn synth_refuses_the_safety_rows_it_cannot_build_and_names_the_rest() {
    let dir = tempfile::tempdir().unwrap();
    let table: &[&[&str]] = &[&["C1+1"], &["C2+1"], &["C1-0"], &["C2-0"]];
    let cases: &[(&[&[&str]], i32, &str)] = &[
        (
            &[&["interlock", "guard"]],
            1,
            "SETTINGS!B1: error[E034]: interlock: synth does not build this",
        ),
        (
            &[&["modes", "stop"]],
            1,
            "SETTINGS!B1: error[E034]: modes: synth does not build this",
        ),
        (
            &[&["start permissive", "air"]],
            1,
            "error[E034]: start permissive: synth does not build",
        ),
        (
            &[&["actuator", "valve"], &["C1", "vacuum"]],
            1,
            "error[E034]: C1 is a gripper on valve type vacuum: synth's equations drive",
        ),
        (
            &[&["actuator", "valve"], &["C2", "motor"]],
            1,
            "error[E034]: C2 is a drive on valve type motor",
        ),
        (
            &[&["actuator", "valve"], &["C2", "52mono"]],
            1,
            "error[E034]: C2 is a cylinder on valve type 52mono",
        ),
        (
            &[&["actuator", "valve"], &["C2", "swivel"]],
            0,
            "warning[W006]: synth does not use the actuator table",
        ),
        (
            &[&["target", "siemens"]],
            0,
            "SETTINGS!B1: warning[W006]: target: synth does not use this setting",
        ),
        (
            &[&["scan time", "50ms"]],
            0,
            "SETTINGS!B1: warning[W006]: scan time: synth does not use",
        ),
    ];
    for (settings, code, message) in cases {
        let path = dir.path().join("s.xlsx");
        crate::helpers::write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
        let out = dir.path().join("out");
        let _ = std::fs::remove_dir_all(&out);
        let assert = steptable()
            .args(["synth", "--method", "exact", "-o"])
            .arg(&out)
            .arg(&path)
            .assert()
            .code(*code)
            .stderr(contains(*message));
        drop(assert);
        if *code != 0 {
            assert!(files_below(&out).is_empty(), "{message}: nothing written");
        }
    }
    // A home order: synth's own W006, not convert's advice to add reset to
    // the modes (synth has no modes to add it to).
    let path = dir.path().join("h.xlsx");
    crate::helpers::write_xlsx_sheets(
        &path,
        &[("TABLE", table), ("SETTINGS", &[&["home order", "C2, C1"]])],
    );
    let output = steptable()
        .args(["synth", "--method", "exact", "-o"])
        .arg(dir.path().join("out3"))
        .arg(&path)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    assert_eq!(
        stderr.matches("SETTINGS!B1: warning[W006]").count(),
        1,
        "{stderr}"
    );
    assert!(
        stderr.contains("home order: synth does not use this setting"),
        "{stderr}"
    );
    assert!(!stderr.contains("reset"), "{stderr}");
    // Pins on ADDRESSES are named too.
    let path = dir.path().join("p.xlsx");
    crate::helpers::write_xlsx_sheets(
        &path,
        &[("TABLE", table), ("ADDRESSES", &[&["START", "I0.5"]])],
    );
    steptable()
        .args(["synth", "--method", "exact", "-o"])
        .arg(dir.path().join("out2"))
        .arg(&path)
        .assert()
        .success()
        .stderr(contains(
            "warning[W006]: START I0.5: synth does not use pinned addresses",
        ));
}
