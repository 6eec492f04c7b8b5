//! The thirteenth round of hostile input: what rt24 left and the red team
//! rt25 found on the command line, in scenarios and in output folders. A
//! home order refused `C 2`, which the table reads as C2; `--stroke
//! C1=0,8s` was told `"0" is not a stroke time`; a RESET pressed at
//! power-up and a press 0.1 s after the last were printed as presses the
//! program never saw; `a.xlsx` converted into `a.csv`'s folder replaced its
//! outputs without a word; batch's `failed:` line named the file that
//! converted; W006 blamed a `--target` nobody gave. Each row goes through
//! the binary.

use crate::helpers::{sample, steptable};
use crate::hostile_round9::workbook;

/// Runs steptable with `args` in `dir`; the exit code and what it said on
/// stdout and stderr.
fn said(dir: &std::path::Path, args: &[&str]) -> (Option<i32>, String) {
    let output = steptable().current_dir(dir).args(args).output().unwrap();
    let said = [&output.stdout, &output.stderr].map(|b| String::from_utf8_lossy(b).into_owned());
    (output.status.code(), said.concat())
}

/// `simulate` of the paper's example with `args`, as `said` gives it.
fn simulate_paper(args: &[&str]) -> (Option<i32>, String) {
    let dir = tempfile::tempdir().unwrap();
    let paper = sample("paper_example.xlsx");
    let mut all = vec!["simulate", paper.to_str().unwrap()];
    all.extend(args);
    said(dir.path(), &all)
}

/// `C 2` in a home order is C2, as the table and `--valve` read it; `C1 0`
/// is a number a space splits, said so, on the SETTINGS sheet (E030) and on
/// the command line (rt24 F6).
#[test]
fn a_home_order_reads_an_actuators_number_as_the_table_does() {
    let dir = tempfile::tempdir().unwrap();
    let settings: &[&[&str]] = &[&["home order", "C 2, C1"]];
    std::fs::write(
        dir.path().join("spaced.xlsx"),
        workbook(&[], &[("SETTINGS", settings)]),
    )
    .unwrap();
    let (code, out) = said(dir.path(), &["check", "spaced.xlsx"]);
    assert_eq!(code, Some(0), "{out}");
    let (code, out) = said(
        dir.path(),
        &["check", "spaced.xlsx", "--home-order", "C 1, C 2"],
    );
    assert_eq!(code, Some(0), "{out}");

    let settings: &[&[&str]] = &[&["home order", "C2, C1 0"]];
    std::fs::write(
        dir.path().join("split.xlsx"),
        workbook(&[], &[("SETTINGS", settings)]),
    )
    .unwrap();
    let (code, out) = said(dir.path(), &["check", "split.xlsx"]);
    assert_eq!(code, Some(1), "{out}");
    assert!(
        out.contains("SETTINGS!B1: error[E030]") && out.contains("\"C1 0\": a space splits"),
        "{out}"
    );
    let (code, out) = said(
        dir.path(),
        &["check", "spaced.xlsx", "--home-order", "C1 0"],
    );
    assert_ne!(code, Some(0), "{out}");
    assert!(out.contains("\"C1 0\": a space splits"), "{out}");
}

/// A decimal comma in a command-line list is split by the list's comma:
/// said as that, with what to write, not as a bad value and an item
/// without `=` (rt24 F8, rt25 F1).
#[test]
fn a_decimal_comma_in_a_list_is_said_to_split_its_number() {
    for (option, value, hint) in [
        ("--stroke", "C1=0,8s", "(C1=0.8s)"),
        ("--stroke", "C2=1,5s/1s", "(C2=1.5s/1s)"),
        (
            "--stroke",
            "C1=1,000ms",
            "write C1=1000ms for a thousands' comma, or C1=1.000ms",
        ),
        ("--input-delay", "x=1,5s", "(x=1.5s)"),
        ("--load", "C1=0,5", "(C1=0.5)"),
        ("--supervision", "3=1,5s", "(3=1.5s)"),
    ] {
        let (code, out) = simulate_paper(&[option, value]);
        assert_ne!(code, Some(0), "{option} {value}: {out}");
        assert!(
            out.contains("the comma parts the list's items") && out.contains(hint),
            "{option} {value}: {out}"
        );
    }
    // Two whole items stay two items.
    let (code, out) = simulate_paper(&["--stroke", "C1=1s,C2=2s"]);
    assert_eq!(code, Some(0), "{out}");
}

/// A press the program never sees is not printed as a press alone: RESET
/// pressed at power-up (the program takes a RESET held through power-up as
/// none), and a press exactly 0.1 s after the last (let go and pressed in
/// one scan) (rt25 F4, F5).
#[test]
fn a_press_the_program_never_sees_is_said_so() {
    let (code, out) = simulate_paper(&["--modes", "reset", "--press", "RESET@0s"]);
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains("RESET_PB pressed at power-up: no press for the program"),
        "{out}"
    );
    assert!(!out.contains("homing starts"), "{out}");
    let (code, out) = simulate_paper(&[
        "--modes",
        "reset",
        "--press",
        "RESET@0.2s",
        "--press",
        "RESET@+100ms",
    ]);
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains("--press RESET@+100ms: RESET_PB pressed while still down"),
        "{out}"
    );
    // 10 ms later it is a press of its own, and homes again.
    let (_, out) = simulate_paper(&[
        "--modes",
        "reset",
        "--press",
        "RESET@0.2s",
        "--press",
        "RESET@+110ms",
    ]);
    assert_eq!(out.matches("homing starts").count(), 2, "{out}");
    assert!(!out.contains("still down"), "{out}");
}

/// Outputs an earlier run made from another input (`a.csv`, then
/// `sub/a.xlsx` into the same folder) are replaced, and the run says from
/// which; a rerun of the same table says nothing of it (rt25 F2).
#[test]
fn replacing_another_inputs_outputs_is_said() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("sub")).unwrap();
    std::fs::copy(sample("paper_example.csv"), dir.path().join("a.csv")).unwrap();
    std::fs::copy(
        sample("drilling_station.xlsx"),
        dir.path().join("sub/a.xlsx"),
    )
    .unwrap();
    let convert = |input: &str| {
        said(
            dir.path(),
            &["convert", input, "-o", "cv", "--formats", "st,io"],
        )
    };
    let (code, out) = convert("a.csv");
    assert_eq!(code, Some(0), "{out}");
    let (_, out) = convert("a.csv");
    assert!(!out.contains("replaced the outputs"), "{out}");
    let (code, out) = convert("sub/a.xlsx");
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains("replaced the outputs an earlier run made there from another input: a.csv"),
        "{out}"
    );
}

/// batch's `failed:` line starts with the input that failed, also where
/// its error is at another file (E040 at the input an output would
/// replace) (rt25 F3).
#[test]
fn a_failed_line_starts_with_the_input_that_failed() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir_all(dir.path().join("plant/press")).unwrap();
    std::fs::copy(
        sample("paper_example.csv"),
        dir.path().join("plant/press.csv"),
    )
    .unwrap();
    std::fs::copy(
        sample("drilling_station.xlsx"),
        dir.path().join("plant/press/press.steptable.xlsx"),
    )
    .unwrap();
    let (code, out) = said(
        dir.path(),
        &["batch", "plant", "-o", "plant", "--quiet", "-j", "1"],
    );
    assert_eq!(code, Some(1), "{out}");
    let failed = out.lines().find(|l| l.contains("failed: ")).unwrap_or("");
    assert!(
        failed.starts_with("  failed: plant/press.csv: ") && failed.contains("error[E040]"),
        "{out}"
    );
}

/// A board on the command line overrides the sheet's target: W006 names
/// `--board`, not a `--target` that was never given (rt25 F6).
#[test]
fn w006_names_the_option_given() {
    let dir = tempfile::tempdir().unwrap();
    let settings: &[&[&str]] = &[&["target", "siemens"]];
    std::fs::write(
        dir.path().join("s.xlsx"),
        workbook(&[], &[("SETTINGS", settings)]),
    )
    .unwrap();
    let (code, out) = said(dir.path(), &["check", "s.xlsx", "--board", "rpi"]);
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains("SETTINGS!B1: warning[W006]: target: --board (OpenPLC's addresses) on the command line wins"),
        "{out}"
    );
    let (_, out) = said(dir.path(), &["check", "s.xlsx", "--target", "iec"]);
    assert!(
        out.contains("target: --target on the command line wins"),
        "{out}"
    );
}

/// Letters a space splits in a jump's target or keyword are not joined:
/// `J:e nd if I:x` is no `J:end`, `J:end i f I:x` no jump (rt23 F6).
#[test]
fn a_jumps_word_split_by_a_space_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    for (item, why) in [
        ("J:e nd if I:x", "a space splits its target \"e nd\""),
        ("J:en d  if I:x", "a space splits its target \"en d\""),
        ("J:end i f I:x", "a space splits its word if"),
    ] {
        let table = format!(",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,\"C1-0; {item}\"\n");
        std::fs::write(dir.path().join("j.csv"), table).unwrap();
        let (code, out) = said(dir.path(), &["check", "j.csv"]);
        assert_eq!(code, Some(1), "{item}: {out}");
        assert!(
            out.contains("j.csv:3:2: error[E017]") && out.contains(why),
            "{item}: {out}"
        );
    }
}

/// One actuator under two of its names in a home order is named with both
/// spellings, not as `C1` twice (rt23 F9).
#[test]
fn a_home_order_naming_one_actuator_twice_says_both_spellings() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("h.csv"),
        ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n",
    )
    .unwrap();
    let (code, out) = said(
        dir.path(),
        &[
            "check",
            "h.csv",
            "--modes",
            "reset",
            "--home-order",
            "C1,1A1",
        ],
    );
    assert_eq!(code, Some(1), "{out}");
    assert!(
        out.contains("error[E030]: the home order names C1 twice, as C1 and 1A1"),
        "{out}"
    );
}

/// The home order takes an actuator as steptable prints it, `C1 (clamp)`,
/// the name in brackets checked to be the actuator's (rt27 F1).
#[test]
fn a_home_order_takes_an_actuator_as_steptable_prints_it() {
    let dir = tempfile::tempdir().unwrap();
    let settings: &[&[&str]] = &[
        &["modes", "reset"],
        &[],
        &["actuator", "valve"],
        &["C1 (clamp)"],
        &["C2 (gripper arm)"],
    ];
    std::fs::write(
        dir.path().join("n.xlsx"),
        workbook(&[], &[("SETTINGS", settings)]),
    )
    .unwrap();
    let check = |order: &str| said(dir.path(), &["check", "n.xlsx", "--home-order", order]);
    let (code, out) = check("C2 (gripper arm), C1 (clamp)");
    assert_eq!(code, Some(0), "{out}");
    let (code, out) = check("C2, C1 (lift)");
    assert_eq!(code, Some(1), "{out}");
    assert!(
        out.contains("error[E030]: the home order names \"C1 (lift)\", but lift is no name of C1"),
        "{out}"
    );
    let (code, out) = check("(clamp) C1, C2");
    assert_ne!(code, Some(0), "{out}");
    assert!(out.contains("\"(clamp)\" follows no actuator"), "{out}");
}

/// The fix told for an extend/retract pair with two decimal commas is
/// itself accepted; a split input value is told it is 0 or 1, not to write
/// 10 (rt27 F4, F5).
#[test]
fn the_fix_a_message_tells_is_one_that_reads() {
    let dir = tempfile::tempdir().unwrap();
    let (code, out) = simulate_paper(&["--stroke", "C1=1,5s/0,8s"]);
    assert_ne!(code, Some(0), "{out}");
    assert!(
        out.contains("write a decimal point (C1=1.5s/0.8s)"),
        "{out}"
    );
    let (code, out) = simulate_paper(&["--stroke", "C1=1.5s/0.8s"]);
    assert_eq!(code, Some(0), "{out}");

    std::fs::write(
        dir.path().join("v.csv"),
        ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,\"C1-0; J:end if I:y=1 0\"\n",
    )
    .unwrap();
    let (code, out) = said(dir.path(), &["check", "v.csv"]);
    assert_eq!(code, Some(1), "{out}");
    assert!(
        out.contains("an input's value is 0 or 1") && !out.contains("I:y=10"),
        "{out}"
    );
}

/// START held through power-up under the edge check starts nothing, and
/// the table says so, as it does for RESET (rt27 F6).
#[test]
fn start_at_power_up_under_the_edge_check_is_said_to_be_no_press() {
    let (code, out) = simulate_paper(&["--safety", "edge", "--press", "START@0s"]);
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains("START pressed at power-up: no press for the program"),
        "{out}"
    );
    assert!(!out.contains("step 1 "), "{out}");
    // Without the edge check START is read by its level: it starts.
    let (_, out) = simulate_paper(&["--press", "START@0s"]);
    assert!(!out.contains("at power-up"), "{out}");
    assert!(out.contains("step 1 "), "{out}");
}

/// batch says what it did to an earlier run's files as convert does: the
/// outputs of another input it replaced, the files it removed (rt27 F7).
#[test]
fn batch_says_what_it_replaced_and_removed() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::create_dir(dir.path().join("bin")).unwrap();
    std::fs::copy(sample("paper_example.csv"), dir.path().join("bin/a.csv")).unwrap();
    let batch = |formats: &str| {
        said(
            dir.path(),
            &["batch", "bin", "-o", "ob", "-q", "--formats", formats],
        )
    };
    let (code, out) = batch("st,io");
    assert_eq!(code, Some(0), "{out}");
    std::fs::remove_file(dir.path().join("bin/a.csv")).unwrap();
    std::fs::copy(sample("oven.xlsx"), dir.path().join("bin/a.xlsx")).unwrap();
    let (code, out) = batch("st,io");
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains(
            "replaced in ob/a/ the outputs an earlier run made there from another input: a.csv"
        ),
        "{out}"
    );
    let (code, out) = batch("st");
    assert_eq!(code, Some(0), "{out}");
    assert!(
        out.contains(
            "removed in ob/a/ what an earlier run wrote there and this one did not: a.io.csv"
        ),
        "{out}"
    );
    assert!(!out.contains("replaced"), "{out}");
}

/// What convert prints of an actuator and of a home order reads back: the
/// whole RESET line (`…, then C1 (clamp)`), `C2(gripper arm)` without the
/// space, and `C2 (gripper arm)=2s` in `--stroke`, `--valve`, `--load`;
/// empty brackets and another's name are refused (rt28 F1–F4).
#[test]
fn what_convert_prints_of_an_actuator_reads_back() {
    let dir = tempfile::tempdir().unwrap();
    let settings: &[&[&str]] = &[
        &["modes", "reset"],
        &[],
        &["actuator", "valve"],
        &["C1 (clamp)"],
        &["C2 (gripper arm)"],
    ];
    std::fs::write(
        dir.path().join("n.xlsx"),
        workbook(&[], &[("SETTINGS", settings)]),
    )
    .unwrap();
    let (code, out) = said(
        dir.path(),
        &["convert", "n.xlsx", "-o", "o", "--formats", "st"],
    );
    assert_eq!(code, Some(0), "{out}");
    let printed = out
        .lines()
        .find_map(|l| l.trim().strip_prefix("RESET homes "))
        .unwrap_or_else(|| panic!("no RESET line: {out}"))
        .to_string();
    for order in [
        printed.as_str(),
        "C2 (gripper arm), then C1 (clamp)",
        "C2(gripper arm),C1",
    ] {
        let (code, out) = said(dir.path(), &["check", "n.xlsx", "--home-order", order]);
        assert_eq!(code, Some(0), "{order}: {out}");
    }
    let (code, out) = said(
        dir.path(),
        &["check", "n.xlsx", "--home-order", "C2 (), C1"],
    );
    assert_eq!(code, Some(1), "{out}");
    assert!(out.contains("but () is no name of C2"), "{out}");
    for (option, value) in [
        ("--stroke", "C2 (gripper arm)=2s"),
        ("--valve", "C1 (clamp)=52bi"),
        ("--load", "1A1 (clamp)=0.1"),
    ] {
        let (code, out) = said(dir.path(), &["simulate", "n.xlsx", option, value]);
        assert_eq!(code, Some(0), "{option} {value}: {out}");
    }
    let (code, out) = said(
        dir.path(),
        &["simulate", "n.xlsx", "--stroke", "C2 (clamp)=2s"],
    );
    assert_eq!(code, Some(1), "{out}");
    assert!(out.contains("no actuator is named C2 (clamp)"), "{out}");
}

/// A name of the engineer's own is read first (`x (x)` is C2's name, not
/// C1 named x as printed); a name that reads as another actuator printed
/// so (`1A1 (x)`) is refused; `C2(gripper arm)=…` and its decimal-comma
/// fix read in a list; a misspelt name in brackets gets the closest; the
/// made-by line credits the command line with what it gave (rt29).
#[test]
fn a_printed_actuator_and_a_name_with_brackets_are_told_apart() {
    let dir = tempfile::tempdir().unwrap();
    let write = |file: &str, names: &[&str]| {
        let mut rows: Vec<&[&str]> = vec![&["modes", "reset"], &[], &["actuator", "valve"]];
        let names: Vec<[&str; 1]> = names.iter().map(|n| [*n]).collect();
        rows.extend(names.iter().map(|n| &n[..]));
        std::fs::write(dir.path().join(file), workbook(&[], &[("SETTINGS", &rows)])).unwrap();
    };
    write("own.xlsx", &["C1 (x)", "C2 (x (x))"]);
    let (code, out) = said(
        dir.path(),
        &["simulate", "own.xlsx", "--stroke", "x (x)=3s"],
    );
    assert_eq!(code, Some(0), "{out}");
    // C2 slowed: its step takes about 3 s; C1's stays about 1 s.
    let takes = |step: &str| {
        let line = out
            .lines()
            .find(|l| l.trim_start().starts_with(step))
            .unwrap_or("");
        line.split_whitespace()
            .nth(3)
            .and_then(|d| d.parse::<f64>().ok())
            .unwrap_or(0.0)
    };
    assert!(takes("2 ") > 2.5 && takes("1 ") < 1.5, "{out}");

    write("printed.xlsx", &["C1 (x)", "C2 (1A1 (x))"]);
    let (code, out) = said(dir.path(), &["check", "printed.xlsx"]);
    assert_eq!(code, Some(1), "{out}");
    assert!(
        out.contains("error[E015]")
            && out.contains("it reads as actuator C1 as steptable prints one"),
        "{out}"
    );

    write("arm.xlsx", &["C1 (clamp)", "C2 (gripper arm)"]);
    let (code, out) = said(
        dir.path(),
        &["simulate", "arm.xlsx", "--stroke", "C2(gripper arm)=0,8s"],
    );
    assert_ne!(code, Some(0), "{out}");
    assert!(out.contains("(C2(gripper arm)=0.8s)"), "{out}");
    let (code, out) = said(
        dir.path(),
        &["simulate", "arm.xlsx", "--stroke", "C2(gripper arm)=0.8s"],
    );
    assert_eq!(code, Some(0), "{out}");
    let (code, out) = said(
        dir.path(),
        &[
            "check",
            "arm.xlsx",
            "--home-order",
            "C2 (gripper arm), then C1 (clmp)",
        ],
    );
    assert_eq!(code, Some(1), "{out}");
    assert!(out.contains("did you mean clamp?"), "{out}");
    let (code, out) = said(
        dir.path(),
        &[
            "convert",
            "arm.xlsx",
            "-o",
            "o",
            "--formats",
            "st",
            "--stroke",
            "C2 (gripper arm)=2s",
        ],
    );
    assert_eq!(code, Some(0), "{out}");
    let st = std::fs::read_to_string(dir.path().join("o/arm/arm.st")).unwrap();
    let made = st.lines().next().unwrap_or("");
    assert!(
        made.contains("the SETTINGS sheet (actuator names, modes)"),
        "{made}"
    );
}
