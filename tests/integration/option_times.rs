//! Issue 37, a time on the command line without its unit: `--stroke C1=2`
//! could mean 2 s or 2 ms, and an option has no cell to warn at (the
//! SETTINGS sheet's W007), so every option that takes a time refuses a bare
//! number, exit 1, naming both readings, and writes nothing; the same time
//! with its unit is taken. A time not written as a plain number
//! (`1e1ms`, `0x2s`) is refused saying what is expected.

use crate::helpers::{files_below, sample, steptable};

#[test]
fn a_time_without_its_unit_is_refused_on_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    let table = sample("press_station.xlsx");
    // (command, option, bare value, the message's needle, the value with a unit)
    let rows: &[(&str, &str, &str, &str, &str)] = &[
        (
            "convert",
            "--stroke",
            "C1=2",
            "2 has no unit: write 2s or 2ms",
            "C1=2s",
        ),
        (
            "convert",
            "--stroke",
            "C1=1s/800",
            "800 has no unit",
            "C1=1s/800ms",
        ),
        (
            "simulate",
            "--stroke",
            "c2 = 1.5",
            "1.5 has no unit",
            "c2 = 1.5s",
        ),
        (
            "convert",
            "--scan",
            "10",
            "10 has no unit: write 10s or 10ms",
            "10ms",
        ),
        (
            "faults",
            "--input-delay",
            "part_present=2",
            "2 has no unit",
            "part_present=2s",
        ),
        // Issue 37's round 3: a number not written plainly is refused
        // saying what is expected, not blamed on its range.
        (
            "convert",
            "--scan",
            "1e1ms",
            "\"1e1ms\" is not written as a time: expected a plain number and its unit, such as 10ms",
            "10ms",
        ),
        (
            "convert",
            "--stroke",
            "C1=1e1s",
            "\"1e1s\" is not written as a time: expected a plain number and its unit",
            "C1=10s",
        ),
        (
            "faults",
            "--input-delay",
            "part_present=0x2s",
            "\"0x2s\" is not written as a time",
            "part_present=2s",
        ),
    ];
    for (command, option, bare, needle, with_unit) in rows {
        let out = dir
            .path()
            .join(format!("bare{}", option.len() + bare.len()));
        let output = steptable()
            .arg(command)
            .arg(&table)
            .arg(option)
            .arg(bare)
            .args(if *command == "simulate" {
                vec![]
            } else {
                vec!["-o".as_ref(), out.as_os_str()]
            })
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        assert_eq!(output.status.code(), Some(1), "{option} {bare}: {stderr}");
        assert!(stderr.contains(needle), "{option} {bare}: {stderr}");
        assert!(files_below(&out).is_empty(), "{option} {bare}: written");
        let out = dir
            .path()
            .join(format!("unit{}", option.len() + bare.len()));
        steptable()
            .arg(command)
            .arg(&table)
            .arg(option)
            .arg(with_unit)
            .args(if *command == "simulate" {
                vec![]
            } else {
                vec!["-o".as_ref(), out.as_os_str()]
            })
            .assert()
            .success();
    }
    let output = steptable()
        .args(["synth", "--sequence", "A1 B1 A0 B0", "--time-limit", "30"])
        .arg("-o")
        .arg(dir.path().join("synth"))
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(1), "{stderr}");
    assert!(stderr.contains("30 has no unit"), "{stderr}");
}
