//! Work beyond the budget is refused at once with its count (E033), counted
//! over everything that would run: the plain cycles, one cycle per jump,
//! and every fault case through all of them. A table of 1,000 steps and
//! 500 jumps once kept `faults` busy for minutes.

use std::time::{Duration, Instant};

use crate::helpers::{files_below, steptable};

/// `pairs` times C1 out and back, every return but the last with a jump
/// to the end: 2·pairs steps (and a closing one), pairs − 1 jumps on
/// inputs of their own.
fn out_and_back(dir: &std::path::Path, pairs: usize) -> std::path::PathBuf {
    let mut text = String::new();
    for k in 0..pairs {
        text.push_str("C1+1\n");
        if k + 1 < pairs {
            text.push_str(&format!("\"C1-0; J:end if I:j{k}\"\n"));
        } else {
            text.push_str("C1-0\n");
        }
    }
    let path = dir.join(format!("long{pairs}.csv"));
    std::fs::write(&path, text).unwrap();
    path
}

/// One hostile size and what the binary must do with it.
struct Row {
    /// Out-and-back pairs in the table.
    pairs: usize,
    args: &'static [&'static str],
    code: i32,
    /// In stderr when refused, in stdout when done.
    said: &'static [&'static str],
}

/// 1,000 steps with 499 jumps: 1,001 steps (the closing one too) in each
/// of 2 + 499 cycles, 501,501 in a proof; 1,004 fault cases (502 inputs
/// stuck at 1 and at 0). Twice that: 2,003,001 in a proof.
const ROWS: &[Row] = &[
    Row {
        pairs: 500,
        args: &["faults"],
        code: 1,
        said: &[
            "error[E033]: the fault analysis would fire 503507004 steps (1004 fault cases, each run through 501501 steps: 2 plain cycles and 499 jump cycles of up to 1001 steps); steptable fires at most 10000000: split the table, or give it fewer jumps",
        ],
    },
    Row {
        pairs: 500,
        args: &["faults", "--pairs"],
        code: 1,
        said: &["error[E033]: --pairs would simulate 504008 fault cases"],
    },
    // 120 steps with 59 jumps: 7,688 pairs are within the case budget,
    // not their 7,381 steps each; single faults are.
    Row {
        pairs: 60,
        args: &["faults", "--pairs"],
        code: 1,
        said: &[
            "error[E033]: the fault analysis would fire 56745128 steps (7688 fault cases, each run through 7381 steps",
        ],
    },
    Row {
        pairs: 60,
        args: &["faults"],
        code: 0,
        said: &["124 fault case(s) from power-up only"],
    },
    Row {
        pairs: 500,
        args: &["faults", "--faults", "3"],
        code: 1,
        said: &["error[E033]: --faults 3 would simulate "],
    },
    // `convert` builds the fault table by default: the same count, and how
    // to leave it out.
    Row {
        pairs: 500,
        args: &["convert"],
        code: 1,
        said: &[
            "error[E033]: the fault analysis would fire 503507004 steps",
            "or leave out the outputs that show the fault table (--formats without",
        ],
    },
    // Without the fault table, the proof itself is within its budget.
    Row {
        pairs: 500,
        args: &["convert", "--formats", "st"],
        code: 0,
        said: &[],
    },
    Row {
        pairs: 500,
        args: &["simulate"],
        code: 0,
        said: &["cycle 501 (takes J:end if I:j498 after step 998): steps 1, 2,"],
    },
    Row {
        pairs: 1000,
        args: &["simulate"],
        code: 1,
        said: &[
            "error[E033]: proving this table would fire 2003001 steps (2001 steps in each of 2 plain cycles and 999 jump cycles, one per jump); steptable fires at most 2000000",
        ],
    },
    Row {
        pairs: 1000,
        args: &["convert", "--formats", "st"],
        code: 1,
        said: &["error[E033]: proving this table would fire 2003001 steps"],
    },
    Row {
        pairs: 1000,
        args: &["faults"],
        code: 1,
        said: &["error[E033]: proving this table would fire 2003001 steps"],
    },
];

/// Every row: refused at once with nothing written, or done in seconds.
#[test]
fn a_thousand_steps_with_five_hundred_jumps_are_refused_at_once_with_the_count() {
    let dir = tempfile::tempdir().unwrap();
    for row in ROWS {
        let table = out_and_back(dir.path(), row.pairs);
        let out = dir.path().join("out");
        let started = Instant::now();
        let mut command = steptable();
        command.args(row.args).arg(&table);
        if row.args[0] != "simulate" {
            command.arg("-o").arg(&out);
        }
        let output = command.output().unwrap();
        let took = started.elapsed();
        let what = format!("{} pairs, {:?}", row.pairs, row.args);
        let stderr = String::from_utf8_lossy(&output.stderr);
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert_eq!(output.status.code(), Some(row.code), "{what}: {stderr}");
        let shown = if row.code == 0 { &stdout } else { &stderr };
        for said in row.said {
            assert!(shown.contains(said), "{what}: {said}\nnot in\n{shown}");
        }
        if row.code == 0 {
            // A loaded 2-core machine: generous, but not minutes.
            assert!(took < Duration::from_secs(20), "{what} took {took:?}");
        } else {
            assert!(took < Duration::from_secs(5), "{what} took {took:?}");
            assert!(files_below(&out).is_empty(), "{what} wrote files");
        }
        let _ = std::fs::remove_dir_all(&out);
    }
}
