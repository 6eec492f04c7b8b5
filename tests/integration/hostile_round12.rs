//! The twelfth round of hostile input: what the red team rt22 found and
//! the last session left. `T=1, 5s` was read as 1.5 s without a word; a
//! split number in a dwell was "not a move"; `--stroke Ölpumpe=2s` was
//! refused though the table names Ölpumpe; `check --formats sdf` said no
//! W008 that convert says; `I:tür` was told to use letters; a chain of
//! links was "does not exist"; a value beside a refused label got a second
//! word. Each row goes through the binary.

use crate::helpers::steptable;
use crate::hostile_round9::workbook;

/// Runs `command` on `bytes` saved as `name` in a new folder (convert
/// writes into it); the exit code and what it said on stdout and stderr.
fn run(command: &str, name: &str, bytes: Vec<u8>, args: &[&str]) -> (Option<i32>, String) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(name);
    std::fs::write(&path, bytes).unwrap();
    let mut cmd = steptable();
    cmd.arg(command).args(args).arg(&path);
    if command == "convert" {
        cmd.arg("-o").arg(dir.path().join("out"));
    }
    let output = cmd.output().unwrap();
    let said = [&output.stdout, &output.stderr].map(|b| String::from_utf8_lossy(b).into_owned());
    (output.status.code(), said.concat())
}

fn table_with(item: &str) -> Vec<u8> {
    format!(",BRANCH 1\nSTEP 1,\"C1+1; {item}\"\nSTEP 2,C1-0\n").into_bytes()
}

/// A space beside a dwell's decimal separator splits its number as a space
/// between two digits does: `T=1, 5s` is `T=1,5s` or `T=1` and a stray
/// `5s`, which is not ours to guess (rt22 F9, MEDIUM: read as 1.5 s). Such
/// an item is called a dwell or a jump, not "not a move" (rt22 F17).
#[test]
fn a_space_beside_a_decimal_separator_splits_the_number() {
    for (item, meant) in [
        ("T=1, 5s", "write T=1,5s"),
        ("T=1. 5s", "write T=1.5s"),
        ("T=1 .5s", "write T=1.5s"),
        ("T=1 ,5s", "write T=1,5s"),
        ("T=1 . 5s", "write T=1.5s"),
        ("T = 1 5 s", "write T = 15 s"),
    ] {
        let (code, said) = run("check", "dwell.csv", table_with(item), &[]);
        assert_eq!(code, Some(1), "{item}: {said}");
        assert!(
            said.contains("dwell.csv:2:2: error[E010]")
                && said.contains("is not a dwell as written")
                && said.contains(meant),
            "{item}: {said}"
        );
    }
    let (code, said) = run("check", "jump.csv", table_with("J:1 0 if I:x"), &[]);
    assert_eq!(code, Some(1), "{said}");
    assert!(said.contains("is not a jump as written"), "{said}");
    // Written without the space, the same dwell is read.
    for item in ["T=1,5s", "T=1.5s"] {
        let (code, said) = run("check", "dwell.csv", table_with(item), &[]);
        assert_eq!(code, Some(0), "{item}: {said}");
    }
}

/// The command line names an actuator as the table does, beyond A-Z too
/// (`--stroke Ölpumpe=2s`, `--valve`, `--home-order`), in any case and
/// composed as a macOS terminal may not pass it (rt22 F8, MEDIUM).
#[test]
fn the_command_line_names_an_actuator_as_the_table_does() {
    let settings: &[&[&str]] = &[&["actuator", "name"], &["C1", "Ölpumpe"]];
    let bytes = || workbook(&[], &[("SETTINGS", settings)]);
    let decomposed = "O\u{308}lpumpe";
    // What a run printed, from its verdict on (each runs in its own folder).
    let verdict = |said: String| said.split_once("passed").map(|(_, v)| v.to_string());
    let plain = verdict(run("simulate", "u.xlsx", bytes(), &[]).1);
    let slow = verdict(run("simulate", "u.xlsx", bytes(), &["--stroke", "C1=3s"]).1);
    assert!(slow.is_some());
    assert_ne!(plain, slow, "a 3 s stroke is slower");
    for name in ["Ölpumpe", "ölpumpe", decomposed] {
        let given = format!("{name}=3s");
        let (code, said) = run("simulate", "u.xlsx", bytes(), &["--stroke", &given]);
        assert_eq!(code, Some(0), "{name}: {said}");
        assert_eq!(verdict(said), slow, "{name} is C1");
    }
    let valve = format!("{decomposed}=52mono");
    let (code, said) = run("check", "u.xlsx", bytes(), &["--valve", &valve]);
    assert_eq!(code, Some(0), "{said}");
    let (code, said) = run(
        "check",
        "u.xlsx",
        bytes(),
        &[
            "--modes",
            "reset",
            "--home-order",
            &format!("{decomposed},C2"),
        ],
    );
    assert_eq!(code, Some(0), "{said}");
    // A name nobody has is E030 with the one the table has.
    let (code, said) = run("simulate", "u.xlsx", bytes(), &["--stroke", "Olpumpe=3s"]);
    assert_eq!(code, Some(1), "{said}");
    assert!(
        said.contains("error[E030]") && said.contains("did you mean Ölpumpe?"),
        "{said}"
    );
}

/// `check --formats LIST` says what `convert --formats LIST` says of the
/// outputs: the code page's loss (W008) too (rt22 F18).
#[test]
fn check_says_what_the_code_page_loses() {
    let csv = ",BRANCH 1\nSTEP 1 (links → rechts),C1+1\nSTEP 2,C1-0\n";
    let (code, said) = run("check", "cp.csv", csv.into(), &["--formats", "sdf"]);
    assert_eq!(code, Some(0), "{said}");
    assert!(
        said.contains("warning[W008]") && said.contains("cp.sdf") && said.contains("\"→\""),
        "{said}"
    );
    let (code, said) = run("convert", "cp.csv", csv.into(), &["--formats", "sdf"]);
    assert_eq!(code, Some(0), "{said}");
    assert!(said.contains("warning[W008]"), "{said}");
    let (code, said) = run("check", "cp.csv", csv.into(), &["--formats", "st"]);
    assert_eq!(code, Some(0), "{said}");
    assert!(!said.contains("W008"), "an ST file keeps the arrow: {said}");
}

/// A machine signal's name with a letter beyond a-z is told which letter
/// and its ASCII spelling, as an actuator's name is (rt22 F16).
#[test]
fn a_signal_name_with_an_umlaut_is_told_its_ascii_spelling() {
    for (item, spelt) in [("I:tür", "\"tuer\""), ("Y:Straße+", "\"strasse\"")] {
        let (code, said) = run("check", "nm.csv", table_with(item), &[]);
        assert_eq!(code, Some(1), "{said}");
        assert!(
            said.contains("error[E015]")
                && said.contains("is no letter a-z")
                && said.contains(&format!("write it {spelt}")),
            "{item}: {said}"
        );
    }
}

/// A chain of links names the one that leads nowhere; links in a loop are
/// called a loop, not "does not exist" (rt22 F14).
#[cfg(unix)]
#[test]
fn a_chain_or_loop_of_links_is_said_as_it_is() {
    use std::os::unix::fs::symlink;
    let dir = tempfile::tempdir().unwrap();
    let at = |name: &str| dir.path().join(name);
    symlink("gone.csv", at("chain2.csv")).unwrap();
    symlink("chain2.csv", at("chain1.csv")).unwrap();
    symlink("loopB.csv", at("loopA.csv")).unwrap();
    symlink("loopA.csv", at("loopB.csv")).unwrap();
    for (input, said_of_it) in [
        (
            "chain1.csv",
            "is a link to chain2.csv, a link to gone.csv, which does not exist",
        ),
        ("loopA.csv", "the links lead round in a loop"),
    ] {
        for command in ["convert", "batch"] {
            let run = steptable()
                .arg(command)
                .arg(at(input))
                .arg("-o")
                .arg(at(command))
                .output()
                .unwrap();
            let said = String::from_utf8_lossy(&run.stderr);
            assert_eq!(run.status.code(), Some(1), "{said}");
            assert!(said.contains(said_of_it), "{command} {input}: {said}");
            assert!(
                input == "chain1.csv" || !said.contains("does not exist"),
                "{said}"
            );
        }
    }
}

/// A value an error already speaks for gets no "not read" note of its own:
/// the value beside a setting written with the table, the rows of an
/// actuator table there, the values under a refused `Type` header (rt22
/// F13).
#[test]
fn a_value_an_error_speaks_for_gets_no_second_word() {
    let below = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n\n";
    for (rows, code) in [
        ("modes,all\n", "E030"),
        ("mode,all\n", "E046"),
        ("actuator,extend,retract\nC1,2s,1s\n", "E030"),
    ] {
        let (exit, said) = run("check", "w.csv", format!("{below}{rows}").into(), &[]);
        assert_eq!(exit, Some(1), "{said}");
        assert!(
            said.contains(&format!("w.csv:5:1: error[{code}]")),
            "{said}"
        );
        assert!(!said.contains("W003"), "{rows}: {said}");
    }
    let settings: &[&[&str]] = &[
        &["actuator", "extend", "retract", "Type"],
        &["C1", "", "", "52mono"],
        &["C2", "", "", "-"],
    ];
    let (exit, said) = run(
        "check",
        "q.xlsx",
        workbook(&[], &[("SETTINGS", settings)]),
        &[],
    );
    assert_eq!(exit, Some(1), "{said}");
    assert!(said.contains("SETTINGS!D1: error[E046]"), "{said}");
    assert!(!said.contains("W003"), "{said}");
    // A value beside a note steptable does not read is still named.
    let (_, said) = run("check", "n.csv", format!("{below}remark,all\n").into(), &[]);
    assert!(said.contains("W003"), "{said}");
}

/// A space inside a time on the SETTINGS sheet splits its number as it does
/// in the table: a stroke time `1 5s` or `0, 8s`, a scan time `2 0ms`, a
/// run-on `fan off after 2 0s` are refused at their cells, never joined
/// (rt23 F1, HIGH: 15 s, 20 ms and 20 s with exit 0). A decimal comma that
/// a comma file split off (`scantime: 0,02s` unquoted) is said as that
/// (rt17 F5, HIGH: the setting vanished without a word).
#[test]
fn a_split_time_on_the_settings_sheet_is_refused() {
    let settings: &[&[&str]] = &[
        &["scan time", "2 0ms"],
        &["modes", "stop, reset"],
        &["on stop", "fan off after 2 0s"],
        &[],
        &["actuator", "extend", "retract"],
        &["C1", "1 5s", "0, 8s"],
        &["C2", "1. 5 s", "1 .5s"],
    ];
    let (code, said) = run(
        "check",
        "s.xlsx",
        workbook(&[], &[("SETTINGS", settings)]),
        &[],
    );
    assert_eq!(code, Some(1), "{said}");
    for cell in ["B1", "B3", "B6", "C6", "B7", "C7"] {
        assert!(
            said.contains(&format!("SETTINGS!{cell}: error[E030]")),
            "{cell}: {said}"
        );
    }
    let (code, said) = run(
        "check",
        "s.xlsx",
        workbook(&[], &[]),
        &["--safety", "watchdog", "--supervision", "1=1 0s"],
    );
    assert_eq!(code, Some(1), "{said}");
    assert!(said.contains("\"1=1 0s\": expected a time"), "{said}");
    for line in ["scantime: 0,02s", ",,,scan time: 0,02s"] {
        let csv = format!(",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n\n{line}\n");
        let (code, said) = run("check", "c.csv", csv.into(), &[]);
        assert_eq!(code, Some(1), "{line}: {said}");
        assert!(
            said.contains("error[E046]") && said.contains("split by the file's comma"),
            "{line}: {said}"
        );
        assert!(!said.contains("W003"), "{said}");
    }
}

/// The name of a wait or output is checked as typed: `I:part²` is no
/// `part2`, a zero-width space in it is no space to drop (rt23 F2).
#[test]
fn a_signal_name_is_checked_as_typed() {
    for (item, why) in [
        ("I:part²", "\"²\" is no letter a-z"),
        ("Y:part₂+", "\"₂\" is no letter a-z"),
        ("I:part\u{200B}present", "the invisible character U+200B"),
        ("I:ｐart", "\"ｐ\" is no letter a-z"),
    ] {
        let (code, said) = run("check", "n.csv", table_with(item), &[]);
        assert_eq!(code, Some(1), "{item}: {said}");
        assert!(
            said.contains("error[E015]") && said.contains(why),
            "{item}: {said}"
        );
    }
    // A plus or minus the move reader takes still switches an output.
    let (code, said) = run("check", "n.csv", table_with("Y:lamp\u{2212}"), &[]);
    assert_eq!(code, Some(0), "{said}");
}

/// More spaces beside a decimal separator: `T=. 5s`, `T=1 .s`; a split
/// wait or output is called one; `T= .5s` (a space after `=`) is read
/// (rt23 F4, F5, and its wording).
#[test]
fn every_space_beside_a_separator_splits_a_dwell() {
    for (item, kind) in [
        ("T=. 5s", "a dwell"),
        ("T=, 5s", "a dwell"),
        ("T=1 .s", "a dwell"),
        ("T=1. s", "a dwell"),
        ("T=1 .5ms", "a dwell"),
        ("J:5 .0 if I:x", "a jump"),
        ("I:part=1 0", "a wait"),
        ("Y:lamp1 0+", "an output"),
    ] {
        let (code, said) = run("check", "d.csv", table_with(item), &[]);
        assert_eq!(code, Some(1), "{item}: {said}");
        assert!(
            said.contains(&format!(
                "is not {kind} as written (a space splits a number"
            )),
            "{item}: {said}"
        );
    }
    let (code, said) = run("check", "d.csv", table_with("T= .5s"), &[]);
    assert_eq!(code, Some(0), "{said}");
}

/// Names are one in any case by Unicode's full case mapping: `FUSSPEDAL`
/// names `Fußpedal`, and `straße` beside `STRASSE` is E025 (rt23 F7).
#[test]
fn names_are_compared_by_full_case_mapping() {
    let settings: &[&[&str]] = &[&["actuator", "name"], &["C1", "Fußpedal"]];
    let (code, said) = run(
        "simulate",
        "f.xlsx",
        workbook(&[], &[("SETTINGS", settings)]),
        &["--stroke", "FUSSPEDAL=3s"],
    );
    assert_eq!(code, Some(0), "{said}");
    let settings: &[&[&str]] = &[&["actuator", "name"], &["C1", "straße"], &["C2", "STRASSE"]];
    let (code, said) = run(
        "check",
        "f.xlsx",
        workbook(&[], &[("SETTINGS", settings)]),
        &[],
    );
    assert_eq!(code, Some(1), "{said}");
    assert!(said.contains("error[E025]"), "{said}");
}

/// A long chain of links that ends at no loop is not called a loop; an
/// actuator table written with the step table leaves its column of notes
/// named (rt23 F3, F8).
#[cfg(unix)]
#[test]
fn a_long_chain_and_a_note_column_are_said_as_they_are() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("l0.csv"),
        ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n",
    )
    .unwrap();
    for i in 1..=45 {
        let link = dir.path().join(format!("l{i}.csv"));
        std::os::unix::fs::symlink(format!("l{}.csv", i - 1), link).unwrap();
    }
    let run_on = steptable()
        .arg("check")
        .arg(dir.path().join("l45.csv"))
        .output()
        .unwrap();
    let said = String::from_utf8_lossy(&run_on.stderr);
    assert_eq!(run_on.status.code(), Some(1), "{said}");
    assert!(
        said.contains("more than 40 links") && !said.contains("loop"),
        "{said}"
    );
    let csv = ",BRANCH 1,,x\nSTEP 1,C1+1,,actuator,extend,retract,foo\nSTEP 2,C1-0,,C1,2s,1s,bar\n";
    let (code, said) = run("check", "a.csv", csv.into(), &[]);
    assert_eq!(code, Some(1), "{said}");
    assert!(said.contains("2:4: error[E030]"), "{said}");
    for cell in ["2:7", "3:7"] {
        assert!(
            said.contains(&format!("{cell}: warning[W003]")),
            "{cell}: {said}"
        );
    }
    assert!(
        !said.contains("2:5: warning") && !said.contains("3:5: warning"),
        "{said}"
    );
}

/// Red team rt24: a comma CSV's setting whose label has a field of its own
/// and whose decimal comma the file split (`scan time,0,02s`,
/// `supervision,2=10,5s`) is E046, not a W003 with exit 0 (F1, HIGH); `C1
/// 0` heading an actuator table's row is no C1 named 0 (F2, HIGH); `STEP 1
/// 0` is no STEP 10 (F4); a dotless ı is no i (F5: `kırmızı` and `kirmizi`
/// are two names).
#[test]
fn what_rt24_found_split_or_merged() {
    for line in [
        "scan time,0,02s",
        "supervision,2=10,5s",
        "supervision: 2=10,5s",
    ] {
        let csv = format!(",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n\n{line}\n");
        let (code, said) = run("check", "c.csv", csv.into(), &[]);
        assert_eq!(code, Some(1), "{line}: {said}");
        assert!(
            said.contains("c.csv:5:1: error[E046]") && said.contains("split by the file's comma"),
            "{line}: {said}"
        );
        assert!(!said.contains("W003"), "{line}: {said}");
    }
    let settings: &[&[&str]] = &[&["actuator", "extend", "retract"], &["C1 0", "3s", "3s"]];
    let (code, said) = run(
        "check",
        "a.xlsx",
        workbook(&[], &[("SETTINGS", settings)]),
        &[],
    );
    assert_eq!(code, Some(1), "{said}");
    assert!(
        said.contains("SETTINGS!A2: error[E030]") && said.contains("a space splits its number"),
        "{said}"
    );
    let csv = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 1 0,C1-0\n";
    let (code, said) = run("check", "l.csv", csv.into(), &[]);
    assert_eq!(code, Some(1), "{said}");
    assert!(said.contains("l.csv:3:2: error[E010]"), "{said}");
    let settings: &[&[&str]] = &[
        &["actuator", "name"],
        &["C1", "kırmızı"],
        &["C2", "kirmizi"],
    ];
    let (code, said) = run(
        "check",
        "k.xlsx",
        workbook(&[], &[("SETTINGS", settings)]),
        &["--formats", "st"],
    );
    assert_eq!(code, Some(0), "two names: {said}");
}
