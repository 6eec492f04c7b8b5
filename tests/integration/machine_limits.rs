//! Machines that would run only by luck, or with a timer no PLC holds, are
//! refused before anything is written (E032 at the cell concerned):
//! - a middle stop must hold on every phase of the scan: its sensor has to
//!   stay in view for two scans (one to see it, one to switch the valve); a
//!   shorter glimpse that happens to pass the simulation's one scan phase is
//!   refused by convert, simulate and faults alike;
//! - a watchdog preset beyond the 655.35 s FST's 16-bit timer word holds
//!   would wrap round to a short one there.

use predicates::prelude::PredicateBooleanExt;
use predicates::str::contains;

use crate::helpers::{sample, steptable};

/// `(options, expected error fragment or None when it converts)`. The
/// paper's C2 stops at x21 and x22, C3 at x31; sensors are in view for 4 %
/// of the stroke (40 ms of the default 1 s).
const CASES: &[(&[&str], Option<&str>)] = &[
    // 150 ms stroke: 6 ms in view; the 10 ms simulation passed it by luck.
    (
        &["--stroke", "C2=150ms"],
        Some(
            "4:2: error[E032]: C2 stops at its middle position 1 in step 3, but its sensor x21 is in view for only 6.0 ms",
        ),
    ),
    // Only the retract stroke is too fast: only the stop on the way back.
    (
        &["--stroke", "C2=1s/150ms"],
        Some("error[E032]: C2 stops at its middle position 1 in step 3"),
    ),
    // A scan slower than half the glimpse: 40 ms in view, 21 ms scans.
    (&["--scan", "21ms"], Some("less than two 21 ms scans")),
    // Two scans exactly fit: accepted.
    (&["--scan", "20ms"], None),
    // A fast stroke on an actuator without middle stops is no concern.
    (&["--stroke", "C1=100ms"], None),
    // Without middle stops the program does not try to stop there.
];

#[test]
fn a_middle_stop_that_only_luck_would_make_is_refused_at_its_cell() {
    for (options, expected) in CASES {
        for command in ["convert", "simulate", "faults"] {
            let dir = tempfile::tempdir().unwrap();
            let assert = steptable()
                .arg(command)
                .arg(sample("paper_example.csv"))
                .args(*options)
                .args(if command == "simulate" {
                    vec![]
                } else {
                    vec!["-o"]
                })
                .args(if command == "simulate" {
                    None
                } else {
                    Some(dir.path().join("out"))
                })
                .assert();
            match expected {
                Some(fragment) => {
                    assert
                        .code(1)
                        .stderr(contains(*fragment))
                        .stderr(contains("internal").not());
                    assert!(
                        !dir.path().join("out").exists(),
                        "{command} {options:?} wrote files"
                    );
                }
                None => {
                    assert.success();
                }
            }
        }
    }
}

#[test]
fn the_glimpse_rule_leaves_a_program_without_middle_stops_alone() {
    // --no-middle-stop makes the paper fail its simulation by overrun, not
    // by the glimpse rule: the message is the simulation's.
    steptable()
        .args(["simulate", "--no-middle-stop", "--stroke", "C2=150ms"])
        .arg(sample("paper_example.csv"))
        .assert()
        .code(1)
        .stdout(contains("FAILED"))
        .stderr(contains("E032").not());
}

#[test]
fn a_watchdog_longer_than_a_plc_timer_holds_is_refused_at_its_step() {
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("long.csv");
    // Step 2 dwells 655 s: with its move it needs a 658 s watchdog.
    std::fs::write(&table, "C1+1\n\"C1-0;T=655s\"\n").unwrap();
    let out = dir.path().join("out");
    let convert = |args: &[&str]| {
        steptable()
            .arg("convert")
            .arg(&table)
            .args(args)
            .arg("-o")
            .arg(&out)
            .assert()
    };
    convert(&["--safety", "watchdog"]).code(1).stderr(contains(
        "long.csv:2:1: error[E032]: step 2's watchdog would need 658.0 s",
    ));
    assert!(!out.exists(), "nothing written");
    // The same machine without the watchdog converts; so does a stroke
    // that keeps the preset inside the timer.
    convert(&["--formats", "st"]).success();
    let stroke = dir.path().join("stroke.csv");
    std::fs::write(&stroke, "C1+1\nC1-0\n").unwrap();
    steptable()
        .args([
            "convert", "--safety", "watchdog", "--stroke", "C1=400s", "-o",
        ])
        .arg(dir.path().join("out2"))
        .arg(&stroke)
        .assert()
        .code(1)
        .stderr(contains(
            "1:1: error[E032]: step 1's watchdog would need 801.0 s",
        ));
}

/// A table whose inputs run past byte 255 of the process image (450
/// actuators with four positions: 2,251 inputs, %IX281.2 on iec) is E024
/// with the counts; the same table fits Festo's 16-bit words (I140.10).
#[test]
fn addresses_past_the_process_image_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("big.csv");
    let mut text = String::from(",BRANCH 1\n");
    for a in 1..=450 {
        text.push_str(&format!(
            "STEP {},C{a}+4\nSTEP {},C{a}-0\n",
            2 * a - 1,
            2 * a
        ));
    }
    std::fs::write(&path, text).unwrap();
    crate::helpers::steptable()
        .arg("check")
        .arg(&path)
        .args(["--target", "iec"])
        .assert()
        .code(1)
        .stderr(predicates::str::contains(
            "big.csv: error[E024]: the program needs 2251 inputs, which run to %IX281.2, past the last address of the process image (255)",
        ));
    crate::helpers::steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .success()
        .stdout(predicates::str::contains("I0.0 to I140.10"));
}
