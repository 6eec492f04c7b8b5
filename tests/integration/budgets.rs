//! Work beyond the budget is refused at once with its count (E033), counted
//! over everything that would run: the plain cycles, one cycle per jump,
//! and every fault case through all of them. A table of 1,000 steps and
//! 500 jumps once kept `faults` busy for minutes.

use std::time::{Duration, Instant};

use predicates::str::contains;

use crate::helpers::{files_below, steptable};

/// `pairs` times C1 out and back, every return but the last with a jump
/// to the end: 2·pairs steps, pairs − 1 jumps on inputs of their own.
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

/// Runs `args` on `table`, which must be refused with E033 at once.
fn refused_at_once(args: &[&str], table: &std::path::Path, out: &std::path::Path) -> String {
    let started = Instant::now();
    let assert = steptable()
        .args(args)
        .arg(table)
        .arg("-o")
        .arg(out)
        .assert()
        .code(1);
    let took = started.elapsed();
    assert!(took < Duration::from_secs(5), "{args:?} took {took:?}");
    assert!(files_below(out).is_empty(), "{args:?} wrote files");
    String::from_utf8_lossy(&assert.get_output().stderr).to_string()
}

/// Hostile sizes: each refused (with its count and the budget named) or
/// done, never a run of minutes.
#[test]
fn a_thousand_steps_with_five_hundred_jumps_are_refused_at_once_with_the_count() {
    let dir = tempfile::tempdir().unwrap();
    let table = out_and_back(dir.path(), 500);
    let out = dir.path().join("out");
    // 1,001 steps (the closing one too) in each of 2 + 499 cycles, for
    // each of 1,004 fault cases (502 inputs stuck at 1 and at 0).
    let faults = refused_at_once(&["faults"], &table, &out);
    assert!(
        faults.contains(
            "error[E033]: the fault analysis would fire 503507004 steps (1004 fault cases, each run through 501501 steps: 2 plain cycles and 499 jump cycles of up to 1001 steps); steptable fires at most 10000000"
        ),
        "{faults}"
    );
    // `convert` builds the fault table by default: the same count, and
    // how to leave it out.
    let convert = refused_at_once(&["convert"], &table, &out);
    assert!(
        convert.contains("error[E033]: the fault analysis would fire 503507004 steps"),
        "{convert}"
    );
    assert!(
        convert.contains("or leave out the outputs that show the fault table (--formats without"),
        "{convert}"
    );
    // Pairs are counted the same way (the case budget is not the only one).
    let pairs = refused_at_once(&["faults", "--pairs"], &table, &out);
    assert!(pairs.contains("error[E033]"), "{pairs}");
    // Without the fault table the proof itself is within its budget.
    let started = Instant::now();
    steptable()
        .args(["simulate"])
        .arg(&table)
        .assert()
        .success()
        .stdout(contains(
            "cycle 501 (takes J:end if I:j498 after step 998): steps 1, 2,",
        ));
    let took = started.elapsed();
    assert!(took < Duration::from_secs(15), "simulate took {took:?}");
    // Twice the steps and jumps: the proof alone is beyond its budget.
    let bigger = out_and_back(dir.path(), 1000);
    let simulate = steptable()
        .args(["simulate"])
        .arg(&bigger)
        .assert()
        .code(1)
        .get_output()
        .stderr
        .clone();
    let simulate = String::from_utf8_lossy(&simulate);
    assert!(
        simulate.contains(
            "error[E033]: proving this table would fire 2003001 steps (2001 steps in each of 2 plain cycles and 999 jump cycles, one per jump); steptable fires at most 2000000"
        ),
        "{simulate}"
    );
    let convert = refused_at_once(&["convert", "--formats", "st"], &bigger, &out);
    assert!(
        convert.contains("error[E033]: proving this table would fire 2003001 steps"),
        "{convert}"
    );
}
