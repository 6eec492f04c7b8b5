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
