//! The sixth round of hostile input: what the fifth round's red team
//! (rt11) left open. Homing that ran for good on a dead home switch, a
//! watchdog that blamed a sensor for an EMERGENCY STOP, a drive kept
//! running through a halt, a guard on a range of steps that RESET homed
//! behind, a halt nothing could acknowledge, a jump whose number two rows
//! answer to, a valve kind no table could use, and findings, folders and
//! refusals said otherwise than the README says. Each row goes through the
//! binary: its exit code, each code at its cell, and what was written.

use crate::helpers::{convert_csv, convert_sheets, root, simulate_sheets, steptable};

fn stderr(assert: &assert_cmd::assert::Assert) -> String {
    String::from_utf8_lossy(&assert.get_output().stderr).into_owned()
}

fn simulate(input: &std::path::Path, args: &[&str]) -> String {
    let assert = steptable()
        .arg("simulate")
        .arg(input)
        .args(args)
        .assert()
        .code(0);
    crate::helpers::squeezed_stdout(&assert)
}

/// The car wash's gantry is a drive (`motor`). Its home switch dead as
/// RESET homes: with the watchdog the homing stage is supervised as a
/// step is (twice its slowest retract plus 1 s), its alarm halts, the
/// halt cuts the drive; the run ends saying the homing is not done, not
/// "at rest". Without the watchdog the drive's reverse contactor is still
/// on at the end, and the last line lists it.
#[test]
fn a_dead_home_switch_halts_the_homing_and_is_never_at_rest() {
    let carwash = root().join("samples/carwash.xlsx");
    let events = [
        "--press",
        "START@0.5s",
        "--press",
        "ESTOP@step2",
        "--stick",
        "x10=0@+1s",
        "--press",
        "RESET@+1s",
    ];
    let mut supervised = vec!["--safety", "all"];
    supervised.extend(events);
    let said = simulate(&carwash, &supervised);
    assert!(said.contains("3.02 s homing starts"), "{said}");
    assert!(said.contains("20.02 s alarm_wd on"), "{said}");
    let end = crate::helpers::line_with(&said, "ended at");
    assert!(end.contains("in step 0, homing not done"), "{end}");
    assert!(!end.contains("y1-"), "the drive runs on: {end}");
    let bare = simulate(&carwash, &events);
    let end = crate::helpers::line_with(&bare, "ended at");
    assert!(
        end.contains("homing not done") && end.contains("on: y1-") && !end.contains("at rest"),
        "{end}"
    );
}

/// An EMERGENCY STOP is no step running out of time: the watchdog's alarm
/// and the criteria analysis's `miss` outputs stay off while the machine
/// is halted, where they blamed a sensor (x23) 3 s after the press.
#[test]
fn a_halted_machine_is_no_step_out_of_time() {
    let paper = root().join("samples/paper_example.xlsx");
    let said = simulate(
        &paper,
        &[
            "--modes",
            "estop,reset",
            "--safety",
            "criteria",
            "--press",
            "START@0.5s",
            "--press",
            "ESTOP@step2",
        ],
    );
    assert!(!said.contains("alarm_wd"), "{said}");
    assert!(!said.contains("miss"), "{said}");
    // Not silenced for good: a step that does run out of time still halts.
    let stuck = simulate(
        &paper,
        &[
            "--modes",
            "estop,reset",
            "--safety",
            "criteria",
            "--press",
            "START@0.5s",
            "--stick",
            "x23=0@step2",
        ],
    );
    assert!(stuck.contains("alarm_wd on"), "{stuck}");
}

/// A halt stops every drive: a halt row that keeps a drive's contactor on
/// (`hold-safe`, `on halt … hold`, `… off after`) is E030 at its cell, as
/// `hold on estop` is; switching it off is accepted.
#[test]
fn no_halt_row_keeps_a_drive_running() {
    let table = crate::hostile_round4::FOUR;
    let with = |row: &'static [&'static str]| -> Vec<&'static [&'static str]> {
        vec![
            &["safety", "watchdog"],
            row,
            &["actuator", "valve"],
            &["C2", "motor"],
        ]
    };
    let refused: [(&[&str], &str); 3] = [
        (
            &["hold-safe", "C2"],
            "hold-safe: y2+ is a contactor of drive C2",
        ),
        (
            &["on halt", "C2 hold"],
            "on halt: y2+ is a contactor of drive C2",
        ),
        (
            &["on halt", "y2- off after 2s"],
            "on halt: y2- is a contactor of drive C2",
        ),
    ];
    for (row, says) in refused {
        let settings = with(row);
        let (_dir, out, assert) = convert_sheets(table, &settings, &[], 1);
        let stderr = stderr(&assert);
        assert!(
            stderr.contains(&format!("SETTINGS!B2: error[E030]: {says}")),
            "{row:?}: {stderr}"
        );
        assert_eq!(stderr.matches("error[").count(), 1, "{row:?}: {stderr}");
        assert!(!out.exists(), "{row:?}: refused but wrote files");
    }
    let settings = with(&["on halt", "C2 off"]);
    convert_sheets(table, &settings, &[], 0);
}

/// A formula saved without its value is E016 alone: the cell may have
/// moved anything, so no error follows from reading it as empty (here
/// "C2-0" in step 3 would have moved C2 from where it never went).
#[test]
fn a_formula_without_its_value_makes_no_second_error() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.xlsx");
    std::fs::write(&path, crate::messy::uncomputed_formula()).unwrap();
    let assert = steptable().arg("check").arg(&path).assert().code(1);
    let stderr = stderr(&assert);
    assert!(stderr.contains("!B3: error[E016]"), "{stderr}");
    assert_eq!(stderr.matches("error[").count(), 1, "{stderr}");
}

/// Where the STEP labels are off, a jump's number may mean its place or
/// the row labelled so: two rows answer to `J:6`, and the jump is E028 at
/// its cell, naming both. Labels numbered otherwise throughout (10, 20,
/// …) leave one reading, and the table converts with W002.
#[test]
fn a_jump_two_rows_answer_to_is_refused_at_its_cell() {
    let off = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C2+1\nSTEP 3,C2-0; J:6 if I:r\nSTEP 5,Y:lamp+; T=1s\nSTEP 6,Y:lamp-; I:ok\nSTEP 7,C3+1\nSTEP 8,C3-0\nSTEP 9,C1-0\n";
    let (_dir, out, assert) = convert_csv(off, &[], 1);
    let refused = stderr(&assert);
    assert!(
        refused.contains("t.csv:4:2: error[E028]: \"J:6 if I:r\" in STEP 3: step 6 of the table is the row labelled STEP 7 (7:1), and the row labelled STEP 6 (6:1) is step 5"),
        "{refused}"
    );
    assert!(!out.exists());
    let tens = ",BRANCH 1\nSTEP 10,C1+1\nSTEP 20,C2+1\nSTEP 30,C2-0; J:5 if I:r\nSTEP 40,T=1s\nSTEP 50,C1-0\n";
    let (_dir, _out, assert) = convert_csv(tens, &["--formats", "st"], 0);
    assert!(stderr(&assert).contains("warning[W002]"));
    let fine = off
        .replace("STEP 5,", "STEP 4,")
        .replace("STEP 6,", "STEP 5,")
        .replace("STEP 7,", "STEP 6,")
        .replace("STEP 8,", "STEP 7,")
        .replace("STEP 9,", "STEP 8,");
    convert_csv(&fine, &["--formats", "st"], 0);
}

/// A guard on a range of steps guards the homing too (homing moves every
/// actuator and has no step to exempt, as manual's jogs have none): RESET
/// homes nothing while it is open, and it opening while RESET homes
/// halts the homing.
#[test]
fn a_guard_on_a_range_of_steps_guards_the_homing() {
    let table = crate::hostile_round4::FOUR;
    let settings: &[&[&str]] = &[
        &["modes", "estop, reset"],
        &["interlock", "guard in steps 2-3"],
    ];
    let open = [
        "--press",
        "START@0.5s",
        "--stick",
        "guard=0@step2",
        "--press",
        "RESET@+1s",
    ];
    let (said, stderr, code) = simulate_sheets(table, settings, &open);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(!said.contains("homing starts"), "{said}");
    let opening = [
        "--press",
        "START@0.5s",
        "--press",
        "ESTOP@step2",
        "--press",
        "RESET@+1s",
        "--stick",
        "guard=0@+0.3s",
    ];
    let (said, stderr, code) = simulate_sheets(table, settings, &opening);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        said.contains("homing starts") && said.contains("alarm_il on"),
        "{said}"
    );
    assert!(said.contains("homing not done"), "{said}");
}

/// SETTINGS rows, command-line options, and what the warning says (none).
type Case = (
    &'static [&'static [&'static str]],
    &'static [&'static str],
    Option<&'static str>,
);

/// A halt without RESET is for good: W012 at what asks for it (the
/// `safety` option on the command line: the file; an `interlock` or `on
/// stop` row: its cell). With RESET (or the emergency stop, which brings
/// it) nothing is said.
#[test]
fn a_halt_nothing_can_acknowledge_is_said() {
    let table = crate::hostile_round4::FOUR;
    let cases: [Case; 6] = [
        (
            &[],
            &["--safety", "watchdog"],
            Some("h.xlsx: warning[W012]: the step watchdog halts"),
        ),
        (
            &[&["interlock", "guard"]],
            &[],
            Some("SETTINGS!B1: warning[W012]: interlock: an input going off halts"),
        ),
        (
            &[&["modes", "stop"], &["on stop", "C1 off"]],
            &[],
            Some("SETTINGS!B2: warning[W012]: on stop: STOP abandons the cycle"),
        ),
        (
            &[&["safety", "plausibility"]],
            &[],
            Some("SETTINGS!B1: warning[W012]"),
        ),
        (&[], &["--safety", "watchdog", "--modes", "reset"], None),
        (&[&["interlock", "guard"]], &["--modes", "estop"], None),
    ];
    for (settings, args, says) in cases {
        let (_dir, _out, assert) = convert_sheets(table, settings, args, 0);
        let stderr = stderr(&assert);
        match says {
            Some(says) => assert!(stderr.contains(says), "{settings:?} {args:?}: {stderr}"),
            None => assert!(!stderr.contains("W012"), "{settings:?} {args:?}: {stderr}"),
        }
    }
}

/// A pressurised-centre valve (`53pressure`) rests home on its `-` coil,
/// which holds the piston there whenever its `+` coil is off: a
/// two-position table converts and passes, in every language's rung.
#[test]
fn a_pressurised_centre_rests_home_on_its_minus_coil() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    steptable()
        .arg("convert")
        .arg(root().join("samples/drilling_station.xlsx"))
        .args(["--valve", "C1=53pressure", "--formats", "st", "-o"])
        .arg(&out)
        .assert()
        .code(0);
    let st = std::fs::read_to_string(out.join("drilling_station/drilling_station.st")).unwrap();
    assert!(
        st.contains("IF NOT y1p AND x10 THEN\n    y1m := TRUE;"),
        "{st}"
    );
}

/// Scenario findings speak the chosen designations, as every other line.
#[test]
fn scenario_problems_speak_the_chosen_designations() {
    let paper = root().join("samples/paper_example.xlsx");
    let said = simulate(&paper, &["--designations", "iso", "--stick", "2B3=0@step3"]);
    assert!(
        said.contains("problem: 2A1 ran through 2B3 in step 3"),
        "{said}"
    );
}

/// A folder with no table is no success (a CI job pointed at the wrong
/// folder): E001 at the folder, exit 1, as a pattern matching nothing.
#[test]
fn a_folder_without_a_table_is_an_error() {
    let dir = tempfile::tempdir().unwrap();
    let empty = dir.path().join("empty");
    std::fs::create_dir(&empty).unwrap();
    std::fs::write(empty.join("readme.txt"), "hi").unwrap();
    let assert = steptable()
        .arg("batch")
        .arg(&empty)
        .args(["--quiet", "-o"])
        .arg(dir.path().join("out"))
        .assert()
        .code(1);
    assert!(
        stderr(&assert).contains("empty: error[E001]: the folder holds no table"),
        "{}",
        stderr(&assert)
    );
}

/// `--diagram` with a scenario's events is refused, and under
/// `--message-format json` said as one E041 object on stdout.
#[test]
fn a_diagram_refused_for_a_scenario_is_said_in_json() {
    let assert = steptable()
        .arg("simulate")
        .arg(root().join("samples/paper_example.xlsx"))
        .args([
            "--diagram",
            "dd",
            "--press",
            "START@1s",
            "--message-format",
            "json",
        ])
        .assert()
        .code(1);
    let stdout = String::from_utf8_lossy(&assert.get_output().stdout).into_owned();
    let v: serde_json::Value = serde_json::from_str(stdout.trim()).expect(&stdout);
    assert_eq!(v["code"], "E041", "{stdout}");
}

/// An interlock's halt leaves every coil as the sequence left it: a
/// piston on a closed-centre valve under way when the guard opens drives
/// on to its end, which its centre would have stopped. W013 at the
/// `interlock` cell names those actuators; not once `de-energise on halt`
/// names them, nor for 5/2 valves (nothing the program does stops them).
#[test]
fn a_guard_that_leaves_pistons_driving_is_said() {
    let table = crate::hostile_round4::FOUR;
    let closed: &[&[&str]] = &[
        &["modes", "estop"],
        &["interlock", "guard"],
        &["actuator", "valve"],
        &["C1", "53closed"],
        &["C2", "53closed"],
    ];
    let (_dir, _out, assert) = convert_sheets(table, closed, &[], 0);
    let said = stderr(&assert);
    assert!(
        said.contains("SETTINGS!B2: warning[W013]: interlock: its halt leaves the coils of C1 and C2 as the sequence left them"),
        "{said}"
    );
    let mut stopped = closed.to_vec();
    stopped.push(&["de-energise on halt", "C1, C2"]);
    let (_dir, _out, assert) = convert_sheets(table, &stopped, &[], 0);
    assert!(!stderr(&assert).contains("W013"), "{}", stderr(&assert));
    let bistable: &[&[&str]] = &[&["modes", "estop"], &["interlock", "guard"]];
    let (_dir, _out, assert) = convert_sheets(table, bistable, &[], 0);
    assert!(!stderr(&assert).contains("W013"), "{}", stderr(&assert));
}

/// RESET switches every output off but a run-on under way: the oven's fan,
/// which STOP leaves on 20 s to cool the coil, runs its time out through
/// the RESET pressed 2 s later (it went off with RESET at 14.50 s).
#[test]
fn reset_leaves_a_run_on_to_finish() {
    let oven = root().join("samples/oven.xlsx");
    let dir = tempfile::tempdir().unwrap();
    let report = dir.path().join("r");
    let assert = steptable()
        .arg("simulate")
        .arg(&oven)
        .args(["--target", "siemens", "--modes", "stop,reset"])
        .args(["--press", "START@0.5s", "--press", "STOP@+12s"])
        .args(["--press", "RESET@+2s", "--report"])
        .arg(&report)
        .assert()
        .code(0);
    let said = crate::helpers::squeezed_stdout(&assert);
    assert!(said.contains("14.50 s --press RESET@+2s"), "{said}");
    let page = crate::helpers::files_below(&report)
        .into_iter()
        .find(|f| f.extension().is_some_and(|e| e == "html"))
        .unwrap();
    let html = std::fs::read_to_string(page).unwrap();
    assert!(
        html.contains(r#"data-signal="fan" data-edges="0:0 10510:1 32500:0""#),
        "the fan's edges: {}",
        html.split("data-signal=\"fan\"")
            .nth(1)
            .unwrap_or("")
            .chars()
            .take(80)
            .collect::<String>()
    );
}

/// `bytes` (an `.xlsx`) with the cell `cell` of `sheet` (`sheet2.xml`)
/// made a formula saved without its value.
pub(crate) fn uncomputed(bytes: Vec<u8>, sheet: &str, cell: &str, formula: &str) -> Vec<u8> {
    use std::io::{Read, Write};
    let mut archive = zip::ZipArchive::new(std::io::Cursor::new(bytes)).unwrap();
    let mut out = zip::ZipWriter::new(std::io::Cursor::new(Vec::new()));
    let pattern = regex::Regex::new(&format!(r#"<c r="{cell}"[^>]*>.*?</c>"#)).unwrap();
    for i in 0..archive.len() {
        let mut entry = archive.by_index(i).unwrap();
        let name = entry.name().unwrap().to_string();
        let mut text = Vec::new();
        entry.read_to_end(&mut text).unwrap();
        if name == format!("xl/worksheets/{sheet}") {
            let xml = String::from_utf8(text).unwrap();
            assert!(pattern.is_match(&xml), "{cell} in {sheet}");
            let replaced = format!(r#"<c r="{cell}" t="str"><f>{formula}</f></c>"#);
            text = pattern
                .replace(&xml, replaced.as_str())
                .into_owned()
                .into_bytes();
        }
        out.start_file(name, zip::write::SimpleFileOptions::default())
            .unwrap();
        out.write_all(&text).unwrap();
    }
    out.finish().unwrap().into_inner()
}

/// A SETTINGS label or an actuator table's header saved as a formula
/// without its value cannot be read: which setting or column it is cannot
/// be told, and the program would lack it (a guard's interlock, a drive's
/// valve type). E016 at the cell, nothing written, where it was a W003.
#[test]
fn a_settings_label_without_its_value_is_e016() {
    let table = crate::hostile_round4::FOUR;
    let cases: [(&[&[&str]], &str, &str); 2] = [
        (
            &[&["modes", "estop, reset"], &["interlock", "guard"]],
            "A2",
            "\"inter\"&amp;\"lock\"",
        ),
        (
            &[&["actuator", "valve"], &["C1", "motor"]],
            "B1",
            "\"val\"&amp;\"ve\"",
        ),
    ];
    for (settings, cell, formula) in cases {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("h.xlsx");
        let bytes =
            crate::messy::workbook(&[("TABLE", false, table), ("SETTINGS", false, settings)]);
        std::fs::write(&path, uncomputed(bytes, "sheet2.xml", cell, formula)).unwrap();
        let out = dir.path().join("out");
        let assert = steptable()
            .arg("convert")
            .arg(&path)
            .arg("-o")
            .arg(&out)
            .assert()
            .code(1);
        let said = stderr(&assert);
        assert!(
            said.contains(&format!("SETTINGS!{cell}: error[E016]: the formula")),
            "{cell}: {said}"
        );
        assert!(!out.exists(), "{cell}: refused but wrote files");
    }
}

/// A STOP that acts at once ends the watchdog and the homing that would
/// cut a drive: `on stop` keeping a drive's contactor on is E030, as the
/// halt rows are.
#[test]
fn no_stop_row_keeps_a_drive_running() {
    let table = crate::hostile_round4::FOUR;
    let settings: &[&[&str]] = &[
        &["modes", "stop, estop, reset"],
        &["on stop", "C1 hold"],
        &["actuator", "valve"],
        &["C1", "motor"],
    ];
    let (_dir, out, assert) = convert_sheets(table, settings, &[], 1);
    let said = stderr(&assert);
    assert!(
        said.contains("SETTINGS!B2: error[E030]: on stop: y1+ is a contactor of drive C1 (valve type motor): kept on at STOP"),
        "{said}"
    );
    assert!(!out.exists());
}

/// Where two rows answer to a step number (the labels off), an interlock's
/// range and a supervision time naming it are E030, as a jump is E028.
#[test]
fn a_step_two_rows_answer_to_is_refused_in_settings() {
    let table: &[&[&str]] = &[
        &["", "BRANCH 1"],
        &["STEP 1", "C1+1"],
        &["STEP 2", "C2+1"],
        &["STEP 3", "C2-0"],
        &["STEP 6", "C3+1"],
        &["STEP 5", "C3-0"],
        &["STEP 4", "C1-0"],
    ];
    let cases: [(&[&[&str]], &str); 2] = [
        (
            &[
                &["modes", "estop, reset"],
                &["interlock", "guard in step 4"],
            ],
            "SETTINGS!B2: error[E030]: interlock: \"guard in step 4\": step 4 of the table is the row labelled STEP 6 (A5), and the row labelled STEP 4 (A7) is step 6",
        ),
        (
            &[&["safety", "watchdog"], &["supervision", "6=10s"]],
            "SETTINGS!B2: error[E030]: supervision: step 6: step 6 of the table is the row labelled STEP 4 (A7)",
        ),
    ];
    for (settings, says) in cases {
        let (_dir, out, assert) = convert_sheets(table, settings, &[], 1);
        let said = stderr(&assert);
        assert!(said.contains(says), "{settings:?}: {said}");
        assert!(!out.exists());
    }
}

/// A homing stage's watchdog past what a PLC timer holds on every target
/// (655.35 s: FST's 16-bit preset) is E032, as a step's is; it was written
/// as `LOAD V66100`.
#[test]
fn a_homing_watchdog_past_the_timers_is_e032() {
    let table = ",BRANCH 1\nSTEP 1,C1+2\nSTEP 2,C1-1\nSTEP 3,C1-0\n";
    let args = [
        "--modes",
        "estop,reset",
        "--safety",
        "watchdog",
        "--stroke",
        "C1=1s/330s",
    ];
    let (_dir, out, assert) = convert_csv(table, &args, 1);
    let said = stderr(&assert);
    assert!(
        said.contains("error[E032]: a homing stage's watchdog would need 661.0 s"),
        "{said}"
    );
    assert!(!out.exists());
}

/// A drive that shares a homing stage with a slower cylinder is cut at
/// its own home switch, not when the stage is done; and a homing the
/// EMERGENCY STOP ends is "abandoned", never "done".
#[test]
fn a_drive_is_cut_at_home_within_its_stage_and_an_abandoned_homing_is_said() {
    let table = crate::hostile_round4::FOUR;
    let settings: &[&[&str]] = &[
        &["modes", "estop, reset"],
        &["home order", "C1 C2"],
        &["actuator", "valve", "extend", "retract"],
        &["C1", "motor", "1s", "1s"],
        &["C2", "53closed", "1s", "4s"],
    ];
    let dead = [
        "--press",
        "START@0.5s",
        "--press",
        "ESTOP@step3",
        "--stick",
        "x20=0@+0.1s",
        "--press",
        "RESET@+1s",
    ];
    let (said, stderr, code) = simulate_sheets(table, settings, &dead);
    assert_eq!(code, Some(0), "{stderr}");
    let end = crate::helpers::line_with(&said, "ended at");
    assert!(
        end.contains("homing not done") && !end.contains("y1-"),
        "{said}"
    );
    let abandoned = [
        "--press",
        "START@0.5s",
        "--press",
        "ESTOP@step3",
        "--press",
        "RESET@+1s",
        "--press",
        "ESTOP@+0.5s",
    ];
    let (said, stderr, code) = simulate_sheets(table, settings, &abandoned);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        said.contains("homing abandoned, the machine not home") && !said.contains("homing done"),
        "{said}"
    );
}

/// A machine with no actuator is home wherever STOP leaves it: the oven's
/// `on stop` row without RESET is no halt for good (no W012).
#[test]
fn an_oven_stopped_at_once_needs_no_reset() {
    let dir = tempfile::tempdir().unwrap();
    let assert = steptable()
        .arg("convert")
        .arg(root().join("samples/oven.xlsx"))
        .args([
            "--target",
            "siemens",
            "--modes",
            "stop",
            "--formats",
            "awl",
            "-o",
        ])
        .arg(dir.path().join("out"))
        .assert()
        .code(0);
    assert!(!stderr(&assert).contains("W012"), "{}", stderr(&assert));
}

/// The four-step table with a heater on through steps 2 and 3.
const HEATED: &[&[&str]] = &[
    &["", "BRANCH 1"],
    &["STEP 1", "C1+1"],
    &["STEP 2", "C2+1; Y:heater+"],
    &["STEP 3", "C2-0"],
    &["STEP 4", "C1-0; Y:heater-"],
];

/// The edges of `signal` on the page `simulate --report` wrote for
/// `settings` (over the heated table) and `args`.
fn edges(settings: &[&[&str]], args: &[&str], signal: &str) -> String {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("h.xlsx");
    crate::helpers::write_xlsx_sheets(&path, &[("TABLE", HEATED), ("SETTINGS", settings)]);
    let report = dir.path().join("r");
    steptable()
        .arg("simulate")
        .arg(&path)
        .args(args)
        .arg("--report")
        .arg(&report)
        .assert()
        .code(0);
    let page = crate::helpers::files_below(&report)
        .into_iter()
        .find(|f| f.extension().is_some_and(|e| e == "html"))
        .unwrap();
    let html = std::fs::read_to_string(page).unwrap();
    let key = format!("data-signal=\"{signal}\" data-edges=\"");
    let rest = html
        .split(key.as_str())
        .nth(1)
        .unwrap_or_else(|| panic!("{signal}"));
    rest.split('"').next().unwrap().to_string()
}

/// A run-on something else switched off is over (rt13): the emergency
/// stop, or an interlock's halt with `de-energise on halt`, cuts the
/// heater STOP left running on, and the RESET that follows leaves it off
/// (it switched it on again for the rest of the 20 s).
#[test]
fn reset_leaves_off_a_run_on_something_else_ended() {
    let heated: &[&[&str]] = &[
        &["modes", "stop, estop, reset"],
        &["on stop", "heater off after 20s"],
    ];
    let estop = [
        "--press",
        "START@0s",
        "--press",
        "STOP@step3",
        "--press",
        "ESTOP@+1s",
        "--press",
        "RESET@+2s",
    ];
    assert_eq!(edges(heated, &estop, "heater"), "0:0 990:1 2980:0");
    let guarded: &[&[&str]] = &[
        &["modes", "stop, estop, reset"],
        &["on stop", "heater off after 20s"],
        &["de-energise on halt", "heater"],
        &["interlock", "guard"],
    ];
    let halt = [
        "--press",
        "START@0s",
        "--press",
        "STOP@step3",
        "--stick",
        "guard=0@+1s",
        "--stick",
        "guard=1@+1s",
        "--press",
        "RESET@+1s",
    ];
    assert_eq!(edges(guarded, &halt, "heater"), "0:0 990:1 2980:0");
}

/// A STOP that acts at once, held: RESET homes nothing (rt13: the homing
/// coils came on for the scan RESET was read in, and a 5/2 piston made
/// its full stroke with STOP pressed).
#[test]
fn reset_homes_nothing_while_an_at_once_stop_is_held() {
    let settings: &[&[&str]] = &[&["modes", "stop, estop, reset"], &["on stop", "heater off"]];
    let args = [
        "--press",
        "START@0s",
        "--hold",
        "STOP@step3",
        "--press",
        "RESET@+1s",
    ];
    let (said, stderr, code) = simulate_sheets(HEATED, settings, &args);
    assert_eq!(code, Some(0), "{stderr}");
    assert!(
        !said.contains("homing starts") && !said.contains("problem"),
        "{said}"
    );
}

/// A label two rows carry answers to its number twice (rt13): `J:5`
/// with labels 1 2 3 5 5 6 is E028 naming both rows; W013 names no
/// pressurised centre (its coils off, it creeps out).
#[test]
fn a_label_two_rows_carry_and_a_pressurised_guard() {
    let table = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C2+1\nSTEP 3,C2-0; J:5 if I:r\nSTEP 5,T=1s\nSTEP 5,C3+1\nSTEP 6,C3-0; C1-0\n";
    let (_dir, out, assert) = convert_csv(table, &[], 1);
    let said = stderr(&assert);
    assert!(
        said.contains("t.csv:4:2: error[E028]: \"J:5 if I:r\" in STEP 3: step 5 of the table is the row labelled STEP 5 (6:1), and the row labelled STEP 5 (5:1) is step 4"),
        "{said}"
    );
    assert!(!out.exists());
    let pressurised: &[&[&str]] = &[
        &["modes", "estop"],
        &["interlock", "guard"],
        &["actuator", "valve"],
        &["C1", "53pressure"],
        &["C2", "53closed"],
    ];
    let (_dir, _out, assert) = convert_sheets(crate::hostile_round4::FOUR, pressurised, &[], 0);
    let said = stderr(&assert);
    assert!(said.contains("leaves the coils of C2 as"), "{said}");
}
