//! The red team's round on the engineer's names: an actuator's name and the
//! signal names it gives (`clamp_home`, `clamp_out`) are usable in SETTINGS
//! rows under every scheme, so under every scheme they may not read as
//! another actuator, a coil, a machine signal or a word of the rows; a halt
//! row must never switch off a different output than the one it names.
//! Each row runs the binary: exit code, code, cell, nothing written.

use crate::helpers::{files_below, steptable, write_xlsx_sheets};

const TABLE: &[&[&str]] = &[
    &["", "BRANCH 1"],
    &["STEP 1", "C1+1"],
    &["STEP 2", "C2+1; Y:clamp_out+"],
    &["STEP 3", "C2-0; Y:clamp_out-"],
    &["STEP 4", "C1-0"],
];

/// Runs `args` on a workbook of TABLE and `settings`: exit code, stderr,
/// whether anything was written.
fn run(
    dir: &std::path::Path,
    what: &str,
    settings: &[&[&str]],
    args: &[&str],
) -> (i32, String, bool) {
    let input = dir.join(format!("{}.xlsx", what.replace([' ', ','], "_")));
    write_xlsx_sheets(&input, &[("TABLE", TABLE), ("SETTINGS", settings)]);
    let out = dir.join(format!("{}.out", what.replace([' ', ','], "_")));
    let output = steptable()
        .arg("convert")
        .arg(&input)
        .args(args)
        .arg("-o")
        .arg(&out)
        .output()
        .unwrap();
    (
        output.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&output.stderr).to_string(),
        !files_below(&out).is_empty(),
    )
}

#[test]
fn actuator_names_that_could_mean_something_else_are_refused_under_every_scheme() {
    let dir = tempfile::tempdir().unwrap();
    let head: &[&str] = &["actuator", "extend", "retract", "valve"];
    // (what, settings rows, message at its cell)
    let cases: &[(&str, &[&[&str]], &str)] = &[
        (
            "actuators named after each other",
            &[
                &["de-energise on halt", "C1"],
                head,
                &["C1 (C2)"],
                &["C2 (C1)"],
            ],
            "SETTINGS!A3: error[E015]: C1 (C2): \"C2\" cannot name an actuator",
        ),
        (
            "an actuator named like a single coil",
            &[head, &["C1", "", "", "52mono"], &["C2 (y1)"]],
            "SETTINGS!A3: error[E015]: C2 (y1): \"y1\" cannot name an actuator",
        ),
        (
            "an actuator named none",
            &[&["de-energise on halt", "none"], head, &["C1 (none)"]],
            "SETTINGS!A3: error[E015]: C1 (none): \"none\" cannot name an actuator",
        ),
        (
            "an actuator named all",
            &[head, &["C2 (All)"]],
            "SETTINGS!A2: error[E015]: C2 (All): \"All\" cannot name an actuator",
        ),
        (
            "a signal name of an actuator that is a machine output",
            &[&["de-energise on halt", "clamp_out"], head, &["C1 (clamp)"]],
            "SETTINGS!A3: error[E025]: C1 (clamp): clamp_out is named in cell B3 too",
        ),
        (
            "a signal name of an actuator that is a start permissive",
            &[&["start permissive", "punch_home"], head, &["C2 (punch)"]],
            "SETTINGS!A3: error[E025]: C2 (punch): punch_home is named in the start permissive row",
        ),
    ];
    for (what, settings, message) in cases {
        for scheme in ["paper", "iso", "names"] {
            let (code, stderr, wrote) = run(
                dir.path(),
                &format!("{what} {scheme}"),
                settings,
                &["--designations", scheme],
            );
            assert_eq!(code, 1, "{what} under {scheme}: {stderr}");
            assert!(stderr.contains(message), "{what} under {scheme}: {stderr}");
            assert!(!wrote, "{what} under {scheme}: written although refused");
        }
    }
    // The same names where nothing collides pass, and the halt row cuts
    // the coil it names.
    let (code, stderr, _) = run(
        dir.path(),
        "no collision",
        &[
            &["safety", "all"],
            &["de-energise on halt", "punch_in"],
            head,
            &["C2 (punch)"],
        ],
        &["--formats", "st"],
    );
    assert_eq!(code, 0, "{stderr}");
    let st = std::fs::read_to_string(
        dir.path()
            .join("no_collision.out/no_collision/no_collision.st"),
    )
    .unwrap();
    let halt = st.split("IF halt THEN").nth(1).expect("a halt rung");
    let halt = halt.split("END_IF").next().unwrap();
    assert!(
        halt.contains("y2m := FALSE") && !halt.contains("y2p"),
        "{halt}"
    );
}

#[test]
fn run_on_times_and_overrides_by_name_are_said_at_their_cells() {
    let dir = tempfile::tempdir().unwrap();
    // A run-on without its unit: read as seconds, W007 at the row.
    let (code, stderr, _) = run(
        dir.path(),
        "run on",
        &[&["modes", "all"], &["on estop", "clamp_out off after 300"]],
        &["--formats", "st"],
    );
    assert_eq!(code, 0, "{stderr}");
    assert!(
        stderr.contains(
            "SETTINGS!B2: warning[W007]: on estop: \"clamp_out off after 300\": \"300\" has no unit"
        ),
        "{stderr}"
    );
    // The command line overrides a valve by the actuator's name, and a
    // stroke both of whose cells it replaces: W006 at each cell.
    let settings: &[&[&str]] = &[
        &["actuator", "extend", "retract", "valve"],
        &["C1 (gripper)", "2s", "2s", "52mono"],
    ];
    let (code, stderr, _) = run(
        dir.path(),
        "override",
        settings,
        &[
            "--valve",
            "gripper=52bi",
            "--stroke",
            "C1=1s",
            "--formats",
            "st",
        ],
    );
    assert_eq!(code, 0, "{stderr}");
    for cell in [
        "B2: warning[W006]: extend",
        "C2: warning[W006]: retract",
        "D2: warning[W006]: valve",
    ] {
        assert!(
            stderr.contains(&format!("SETTINGS!{cell} of C1")),
            "{cell}: {stderr}"
        );
    }
}

#[test]
fn lists_with_an_empty_item_are_refused_on_the_command_line() {
    let dir = tempfile::tempdir().unwrap();
    for (option, value) in [
        ("--valve", ","),
        ("--valve", "C1=52mono,,C2=52bi"),
        ("--stroke", "C1=2s,"),
        ("--load", ",C1=0.1"),
        ("--input-delay", "a=1s,,b=2s"),
        ("--home-order", "C1&, C2"),
    ] {
        let (code, stderr, wrote) = run(
            dir.path(),
            &format!("empty {}", value.len()),
            &[&["modes", "all"]],
            &[option, value],
        );
        assert_eq!(code, 1, "{option} {value}: {stderr}");
        assert!(stderr.contains("empty item"), "{option} {value}: {stderr}");
        assert!(!wrote, "{option} {value}");
    }
}

#[test]
fn iso_fault_explanations_name_the_actuator_by_its_designation() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("iso.xlsx");
    write_xlsx_sheets(&input, &[("TABLE", TABLE)]);
    let output = steptable()
        .arg("faults")
        .arg(&input)
        .args(["--designations", "iso", "-o"])
        .arg(dir.path().join("out"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{stdout}");
    assert!(stdout.contains("(1A1 had not reached 1B2)"), "{stdout}");
    assert!(!stdout.contains("C1 had"), "{stdout}");
}

/// An unused template row after the last step is dropped, but a comment
/// the engineer wrote on its label is said (W003 at the label), not lost.
#[test]
fn a_comment_on_an_unused_step_row_is_said() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("spare.xlsx");
    let table: &[&[&str]] = &[
        &["", "BRANCH 1"],
        &["STEP 1", "C1+1"],
        &["STEP 2", "C1-0"],
        &["STEP 3 (spare step)", ""],
        &["STEP 4", ""],
    ];
    write_xlsx_sheets(&input, &[("TABLE", table)]);
    let output = steptable().arg("check").arg(&input).output().unwrap();
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(output.status.code(), Some(0), "{stderr}");
    assert!(
        stderr.contains(
            "TABLE!A4: warning[W003]: \"STEP 3 (spare step)\" labels a step with no move"
        ),
        "{stderr}"
    );
    assert!(
        !stderr.contains("A5"),
        "a plain unused row is no news: {stderr}"
    );
}
