//! The SETTINGS sheet and the options that give lists, against hostile
//! input (issue 37): a list keeps every item or refuses it, rows that
//! contradict each other are E030 naming both cells, a setting given twice
//! is an error naming both places, every cell is read or named, and the
//! errors about settings name their cells. Each through the binary: exit
//! code, message, cell, and nothing written when refused.

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{files_below, steptable, write_xlsx_sheets};

/// Six steps: C2 goes out and back in steps 2-3, C3 in steps 4-5.
const SIX: &[&[&str]] = &[
    &["C1+1"],
    &["C2+1"],
    &["C2-0"],
    &["C3+1"],
    &["C3-0"],
    &["C1-0"],
];

/// A gripper: the vacuum is on while C1 is out.
const GRIPPER: &[&[&str]] = &[
    &["C1+1; Y:vacuum+; Y:heater+"],
    &["C1-0; Y:vacuum-; Y:heater-"],
];

fn workbook(dir: &std::path::Path, table: &[&[&str]], settings: &[&[&str]]) -> std::path::PathBuf {
    let path = dir.join("line.xlsx");
    write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
    path
}

/// `convert` into `DIR/out`: the assertion, and the output folder.
fn convert(
    input: &std::path::Path,
    extra: &[&str],
) -> (assert_cmd::assert::Assert, std::path::PathBuf) {
    let out = input.parent().unwrap().join("out");
    let _ = std::fs::remove_dir_all(&out);
    let assert = steptable()
        .arg("convert")
        .arg(input)
        .args(extra)
        .args(["--formats", "st,io", "-o"])
        .arg(&out)
        .assert();
    (assert, out)
}

/// Refused: exit 1, every message given, nothing written.
fn refused(input: &std::path::Path, extra: &[&str], messages: &[&str]) {
    let (mut assert, out) = convert(input, extra);
    assert = assert.code(1);
    for message in messages {
        assert = assert.stderr(contains(*message));
    }
    assert!(
        files_below(&out).is_empty(),
        "nothing written: {messages:?}"
    );
}

/// Where the guard going off halts the six-step machine: for each moment
/// of a healthy cycle, the step it waits for when the guard opens then.
fn stalls(path: &std::path::Path) -> Vec<Option<usize>> {
    let build = crate::helpers::Build::path(path);
    let program = build.program();
    let mut simulation = build.settings.simulation.clone();
    let healthy = steptable::simulate::simulate(&build.table, &program, &simulation);
    let moments = steptable::faults::moments(&healthy, &build.table, 10);
    simulation.faults = vec![steptable::simulate::Fault {
        signal: steptable::program::Signal::MachineInput(
            steptable::cell::Name::new("guard").unwrap(),
        ),
        stuck_at: false,
    }];
    moments
        .iter()
        .map(|m| {
            simulation.fault_onset_ms = m.at_ms;
            steptable::simulate::simulate(&build.table, &program, &simulation).stalled_at
        })
        .collect()
}

/// Item 1: `guard in steps 2-3, guard in steps 5-6` is two interlocks, each
/// over its range (the second was dropped); `guard in steps 2-3, guard`
/// keeps the whole-cycle one; an item written twice is E030 at the cell.
#[test]
fn an_interlock_keeps_every_range_it_lists() {
    let dir = tempfile::tempdir().unwrap();
    let path = workbook(
        dir.path(),
        SIX,
        &[&["interlock", "guard in steps 2-3, guard in steps 5-6"]],
    );
    let (assert, out) = convert(&path, &[]);
    assert.success();
    let st = std::fs::read_to_string(out.join("line/line.st")).unwrap();
    assert!(
        st.contains("INTERLOCK: guard off halts the machine in steps 2 to 3"),
        "{st}"
    );
    assert!(
        st.contains("INTERLOCK: guard off halts the machine in steps 5 to 6"),
        "{st}"
    );
    // The guard opening halts the machine in either range, waiting for
    // the step after it, and nowhere else: stalled in the step before
    // (the SFC step it is in, waiting for steps 3, 4, 6 and 7).
    let halts = stalls(&path);
    for stalled_in in [2, 3, 5, 6] {
        assert!(
            halts.contains(&Some(stalled_in)),
            "halts in step {stalled_in}: {halts:?}"
        );
    }
    assert!(
        halts.iter().all(|s| matches!(s, None | Some(1..=6))),
        "only in the ranges: {halts:?}"
    );

    let path = workbook(
        dir.path(),
        SIX,
        &[&["interlock", "guard in steps 2-3, guard"]],
    );
    let (assert, out) = convert(&path, &[]);
    assert.success();
    let st = std::fs::read_to_string(out.join("line/line.st")).unwrap();
    assert!(
        st.contains("INTERLOCK: guard off halts the machine in steps 2 to 3"),
        "{st}"
    );
    assert_eq!(
        st.matches("INTERLOCK: guard off halts the machine").count(),
        2,
        "the whole-cycle interlock is kept beside the range: {st}"
    );
    // Open in step 4 (waiting for step 5): only the whole-cycle one halts there.
    assert!(
        stalls(&path).contains(&Some(4)),
        "halts outside the range too"
    );

    let path = workbook(
        dir.path(),
        SIX,
        &[&["interlock", "guard in steps 2-3, Guard in steps 2 - 3"]],
    );
    refused(
        &path,
        &[],
        &["SETTINGS!B1: error[E030]: interlock: \"Guard in steps 2 - 3\" is named twice"],
    );
    let path = workbook(dir.path(), SIX, &[&["start permissive", "air_ok, air_ok"]]);
    refused(
        &path,
        &[],
        &["SETTINGS!B1: error[E030]: start permissive: air_ok is named twice"],
    );
    let path = workbook(dir.path(), GRIPPER, &[&["hold-safe", "vacuum, C1, y1+"]]);
    refused(
        &path,
        &[],
        &["SETTINGS!B1: error[E030]: hold-safe: y1+ is named twice"],
    );
}

/// Item 2: rows that say different things of one output at one event are
/// E030 at the later row, naming the other's cell, in either order on the
/// sheet; rows that agree are accepted.
#[test]
fn contradictory_halt_rows_are_errors_naming_both_cells() {
    let dir = tempfile::tempdir().unwrap();
    let cases: [(&[&str], &[&str], &str); 7] = [
        (
            &["hold on estop", "vacuum"],
            &["on estop", "vacuum off"],
            "on estop: this row switches vacuum off at an emergency stop, but hold on estop at SETTINGS!B{hold} keeps it on; say one or the other",
        ),
        (
            &["hold on estop", "vacuum"],
            &["on estop", "vacuum off after 5s"],
            "on estop: this row switches vacuum off after 5s at an emergency stop, but hold on estop at SETTINGS!B{hold} keeps it on",
        ),
        (
            &["hold-safe", "heater"],
            &["on halt", "heater off"],
            "on halt: this row switches heater off at a halt, but hold-safe at SETTINGS!B{hold} keeps it on",
        ),
        (
            &["hold-safe", "heater"],
            &["de-energise on halt", "heater"],
            "de-energise on halt: this row switches heater off at a halt, but hold-safe at SETTINGS!B{hold} keeps it on",
        ),
        (
            &["de-energise on halt", "heater"],
            &["on halt", "heater hold"],
            "on halt: this row keeps heater on at a halt, but de-energise on halt at SETTINGS!B{hold} switches it off",
        ),
        (
            &["de-energise on halt", "heater"],
            &["on halt", "heater off after 20s"],
            "on halt: this row switches heater off after 20s at a halt, but de-energise on halt at SETTINGS!B{hold} switches it off",
        ),
        (
            &["hold on estop", "heater"],
            &["de-energise on halt", "heater"],
            "the emergency stop keeps heater on, but a halt switches it off, and the emergency stop halts (hold on estop at SETTINGS!B{hold} keeps it on, de-energise on halt at SETTINGS!B{other} switches it off)",
        ),
    ];
    for (first, second, message) in cases {
        for flipped in [false, true] {
            let (a, b) = if flipped {
                (second, first)
            } else {
                (first, second)
            };
            let settings: &[&[&str]] = &[&["modes", "estop"], a, b];
            let path = workbook(dir.path(), GRIPPER, settings);
            // The error is at the row named second in the message, the
            // first's cell in its text (rows 2 and 3 in either order).
            let (hold, other) = if flipped { (3, 2) } else { (2, 3) };
            let estop_first = message.starts_with("the emergency stop");
            let at = if estop_first { hold } else { other };
            let message = message
                .replace("{hold}", &hold.to_string())
                .replace("{other}", &other.to_string());
            refused(
                &path,
                &[],
                &[&format!("SETTINGS!B{at}: error[E030]: {message}")],
            );
        }
    }
    // Two rows that say the same thing of an output agree.
    let path = workbook(
        dir.path(),
        GRIPPER,
        &[
            &["modes", "estop"],
            &["de-energise on halt", "heater"],
            &["on halt", "heater off"],
            &["hold on estop", "vacuum"],
            &["on estop", "vacuum hold"],
        ],
    );
    convert(&path, &[])
        .0
        .success()
        .stderr(contains("E030").not());
}

/// Item 3: a setting given twice — a SETTINGS row, an actuator of the
/// actuator table, an actuator in an option's list — is an error naming
/// both places; nothing is written.
#[test]
fn a_setting_given_twice_is_refused_naming_both_places() {
    let dir = tempfile::tempdir().unwrap();
    let path = workbook(
        dir.path(),
        SIX,
        &[&["target", "iec"], &["target", "siemens"]],
    );
    refused(
        &path,
        &[],
        &["SETTINGS!B2: error[E030]: target is given twice: here and at B1; remove one"],
    );
    let path = workbook(
        dir.path(),
        SIX,
        &[
            &["actuator", "extend", "retract", "valve"],
            &["C1", "1s", "1s", "52mono"],
            &["C1 (clamp)", "2s", "2s", "52bi"],
        ],
    );
    refused(
        &path,
        &[],
        &["SETTINGS!A3: error[E030]: C1 is given twice in the actuator table: here and at A2"],
    );
    let path = workbook(dir.path(), SIX, &[&["scan time", "10ms"]]);
    for (option, list, message) in [
        (
            "--valve",
            "C1=52mono,C1=52bi",
            "\"C1=52bi\": C1 is given twice",
        ),
        ("--stroke", "C1=2s,C1=3s", "\"C1=3s\": C1 is given twice"),
        ("--load", "C2=0.1,C2=0.2", "\"C2=0.2\": C2 is given twice"),
        (
            "--input-delay",
            "part=1s,part=2s",
            "\"part=2s\": part is given twice",
        ),
    ] {
        refused(&path, &[option, list], &[message]);
    }
}

/// Item 4 through the binary: an actuator row after a blank row is read;
/// one with no header above it is E030 at its cell (nothing written); a
/// value in a column no header reads is W003 at its cell.
#[test]
fn every_cell_of_the_settings_sheet_is_read_or_named() {
    let dir = tempfile::tempdir().unwrap();
    let path = workbook(
        dir.path(),
        SIX,
        &[
            &["actuator", "extend", "retract"],
            &["C1", "1s", "1s"],
            &[],
            &["C2", "3s", "3s"],
        ],
    );
    let assert = steptable()
        .args(["simulate"])
        .arg(&path)
        .assert()
        .success()
        .stderr(contains("W003").not());
    let stdout = crate::helpers::squeezed_stdout(&assert);
    // C2's 3 s stroke was read: step 2 (`2 0.98 s 2.98 s C2+1`) takes
    // about 3 s.
    let step2 = crate::helpers::line_with(&stdout, "2 ");
    let duration: f64 = step2.split(' ').nth(3).unwrap().parse().unwrap();
    assert!(duration > 2.5, "{stdout}");

    let path = workbook(
        dir.path(),
        SIX,
        &[&["target", "iec"], &[], &["C2", "3s", "3s"]],
    );
    refused(
        &path,
        &[],
        &[
            "SETTINGS!A3: error[E030]: \"C2\" reads as a row of the actuator table, but no actuator | extend | retract header is above it; its values were not read",
        ],
    );
    let path = workbook(dir.path(), SIX, &[&["target", "iec", "oops"]]);
    convert(&path, &[]).0.success().stderr(contains(
        "SETTINGS!C1: warning[W003]: \"oops\" is beside the setting target",
    ));
}

/// Item 5: the target/board conflict names both cells; a bad home order
/// and a home order without reset are at the home order's cell, in the
/// JSON messages too.
#[test]
fn errors_about_settings_name_their_cells() {
    let dir = tempfile::tempdir().unwrap();
    let path = workbook(dir.path(), SIX, &[&["target", "festo"], &["board", "rpi"]]);
    refused(
        &path,
        &[],
        &[
            "line.xlsx: SETTINGS!B2: error[E036]: the rpi board is OpenPLC's, whose addresses are %IX/%QX, but the target is festo: make the target iec (or openplc, or default), or leave it out (the board from SETTINGS!B2, the target from SETTINGS!B1)",
        ],
    );
    let path = workbook(dir.path(), SIX, &[&["board", "rpi"]]);
    refused(
        &path,
        &["--target", "festo"],
        &[
            "SETTINGS!B1: error[E036]: the rpi board is OpenPLC's",
            "(the board from SETTINGS!B1, the target from --target)",
        ],
    );
    let path = workbook(
        dir.path(),
        SIX,
        &[&["modes", "reset"], &["home order", "C1, C2"]],
    );
    refused(
        &path,
        &[],
        &["SETTINGS!B2: error[E030]: the home order leaves out C3"],
    );
    let json = steptable()
        .arg("check")
        .arg(&path)
        .args(["--message-format", "json"])
        .assert()
        .code(1);
    let line = String::from_utf8_lossy(&json.get_output().stdout).to_string();
    assert!(
        line.contains(r#""cell":"B2""#) && line.contains(r#""sheet":"SETTINGS""#),
        "{line}"
    );
    let path = workbook(dir.path(), SIX, &[&["home order", "C3, C2, C1"]]);
    convert(&path, &[]).0.success().stderr(contains(
        "SETTINGS!B1: warning[W006]: the home order is used by the reset mode only",
    ));
    // From the command line, the file and the option are named.
    convert(&path, &["--home-order", "C1"]).0.code(1).stderr(
        contains("line.xlsx: error[E030]: the home order leaves out C2")
            .and(contains("(--home-order)")),
    );
}

/// A `modes` / `safety` / `home order` list that gives a name twice, leaves
/// an item empty, or puts `all`/`none` beside names is refused, on the
/// SETTINGS sheet (E030 at the cell) and on the command line (exit 1,
/// nothing written) — read one way it would be silently wrong.
#[test]
fn list_items_given_twice_empty_or_beside_all_are_refused() {
    let cases: &[(&str, &str, &str)] = &[
        ("modes", "stop, stop", "\"stop\" is given twice"),
        ("modes", "stop,,estop", "has an empty item"),
        ("modes", "stop,", "has an empty item"),
        ("modes", "none, stop", "\"none\" stands alone"),
        ("modes", "all, reset", "\"all\" stands alone"),
        ("modes", "STOP, stop", "\"stop\" is given twice"),
        ("safety", "edge, edge", "\"edge\" is given twice"),
        ("safety", "edge, , watchdog", "has an empty item"),
        ("safety", "all, none", "\"all\" stands alone"),
        ("home order", "C3,,C2,C1", "has an empty stage"),
        ("home order", "C3, C2, C1,", "has an empty stage"),
    ];
    let dir = tempfile::tempdir().unwrap();
    for (label, value, message) in cases {
        let settings: &[&[&str]] = &[&["modes", "reset"], &[label, value]];
        let rows = if *label == "modes" {
            &settings[1..]
        } else {
            settings
        };
        let path = workbook(dir.path(), SIX, rows);
        let cell = format!("SETTINGS!B{}: error[E030]", rows.len());
        refused(&path, &[], &[cell.as_str(), message]);
        let flag = format!("--{}", label.replace(' ', "-"));
        let plain = dir.path().join("plain.xlsx");
        write_xlsx_sheets(&plain, &[("TABLE", SIX)]);
        let mut extra = vec![flag.as_str(), value];
        if *label != "modes" {
            extra.extend(["--modes", "reset"]);
        }
        let (assert, out) = convert(&plain, &extra);
        assert.code(1).stderr(contains(*message));
        assert!(files_below(&out).is_empty(), "{flag} {value}");
    }
    // The forms that stay: one name, all, none, and spaces around commas.
    for (flag, value) in [
        ("--modes", "none"),
        ("--modes", "all"),
        ("--modes", " stop , estop "),
        ("--safety", "none"),
        ("--home-order", "C3 & C2, C1"),
    ] {
        let plain = dir.path().join("plain.xlsx");
        write_xlsx_sheets(&plain, &[("TABLE", SIX)]);
        let mut extra = vec![flag, value];
        if flag != "--modes" {
            extra.extend(["--modes", "reset"]);
        }
        convert(&plain, &extra).0.success();
    }
}

/// The command line wins over the SETTINGS sheet, and says so at each cell
/// it overrides (W006), per row and per actuator; a time typed as text
/// without a unit is W007 at its cell; a load the valve makes useless is
/// W006 at the load's cell.
#[test]
fn what_the_sheet_says_and_is_not_used_is_said_at_its_cell() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("line.xlsx");
    write_xlsx_sheets(
        &path,
        &[
            ("TABLE", SIX),
            (
                "SETTINGS",
                &[
                    &["modes", "stop"],
                    &["scan time", "0.02"],
                    &[],
                    &["actuator", "extend", "retract", "valve", "load"],
                    &["C1", "1000", "1s", "52bi", "0.3"],
                ],
            ),
        ],
    );
    let run = |extra: &[&str]| {
        let output = steptable()
            .arg("simulate")
            .arg(&path)
            .args(extra)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr).to_string();
        assert_eq!(output.status.code(), Some(0), "{extra:?}: {stderr}");
        stderr
    };
    let plain = run(&[]);
    for message in [
        "SETTINGS!B2: warning[W007]: \"0.02\" has no unit and is read as 0.02 seconds",
        "SETTINGS!B5: warning[W007]: \"1000\" has no unit and is read as 1000 seconds",
        "SETTINGS!E5: warning[W006]: the actuator table's load C1=0.3: C1's valve is 52bi",
    ] {
        assert!(plain.contains(message), "{message}\n{plain}");
    }
    assert!(!plain.contains("wins over this cell"), "{plain}");
    let overridden = run(&[
        "--modes",
        "estop",
        "--valve",
        "C1=53exhaust",
        "--stroke",
        "C1=2s/2s",
    ]);
    for message in [
        "SETTINGS!B1: warning[W006]: modes: --modes on the command line wins over this cell; it was not used",
        "SETTINGS!D5: warning[W006]: valve of C1: --valve on the command line wins over this cell",
        "SETTINGS!B5: warning[W006]: extend of C1: --stroke on the command line wins over this cell",
        "SETTINGS!C5: warning[W006]: retract of C1: --stroke on the command line wins over this cell",
    ] {
        assert!(overridden.contains(message), "{message}\n{overridden}");
    }
}
