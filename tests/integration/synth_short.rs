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
