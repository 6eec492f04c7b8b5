//! A stopped machine is judged by what it leaves on: a stall with a heater,
//! a motor or a spray valve still on is a hazard of energy unless SETTINGS
//! declares that output `hold-safe`; `de-energise on halt` makes the
//! program switch it off when a check halts the machine.

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{line_with, squeezed_stdout, steptable, write_xlsx_sheets};

/// C1 carries a part under a heater that is on while C1 is out.
const HEATED: &[&[&str]] = &[&["C1+1; Y:heater+"], &["C1-0; Y:heater-"]];

fn workbook(dir: &std::path::Path, settings: &[&[&str]]) -> std::path::PathBuf {
    let path = dir.join("heated.xlsx");
    write_xlsx_sheets(&path, &[("TABLE", HEATED), ("SETTINGS", settings)]);
    path
}

fn faults(input: &std::path::Path, extra: &[&str]) -> assert_cmd::assert::Assert {
    let out = input.parent().unwrap().join("out");
    steptable()
        .arg("faults")
        .arg(input)
        .args(extra)
        .arg("-o")
        .arg(out)
        .assert()
}

/// The fault table's row of x11 open, its columns' padding squeezed.
fn x11_open(assert: &assert_cmd::assert::Assert) -> String {
    line_with(&squeezed_stdout(assert), "x11 open circuit")
}

#[test]
fn a_stall_that_leaves_the_heater_on_is_a_hazard_unless_it_is_hold_safe() {
    let dir = tempfile::tempdir().unwrap();
    // x11 dead: C1 never reports out, step 2 never fires, the heater stays on.
    let input = workbook(dir.path(), &[&["scan time", "10ms"]]);
    assert_eq!(
        x11_open(&faults(&input, &[]).success()),
        "x11 open circuit (stuck at 0) hazard at every moment 1 step 2 never fires: waiting for x11; the stopped machine keeps heater on (not hold-safe)"
    );
    let input = workbook(dir.path(), &[&["hold-safe", "heater"]]);
    assert_eq!(
        x11_open(&faults(&input, &[]).success()),
        "x11 open circuit (stuck at 0) safe stall at every moment 1 step 2 never fires: waiting for x11"
    );
    // A coil holds its cylinder: a stall with C1's coil on is safe, unless
    // the engineer says the coil must go off.
    let input = workbook(
        dir.path(),
        &[&["hold-safe", "heater"], &["de-energise on halt", "C1"]],
    );
    faults(&input, &[])
        .success()
        .stderr(contains(
            "warning[W006]: de-energise on halt: the program never halts",
        ))
        .stdout(contains("the stopped machine keeps y1+ on (not hold-safe)"));
}

#[test]
fn de_energise_on_halt_switches_the_heater_off_when_the_watchdog_halts() {
    let dir = tempfile::tempdir().unwrap();
    let input = workbook(dir.path(), &[&["de-energise on halt", "heater"]]);
    // The watchdog halts the stalled machine, and the halt switches the
    // heater off: what was a hazard of energy is a safe stall.
    assert_eq!(
        x11_open(&faults(&input, &["--safety", "watchdog"]).success()),
        "x11 open circuit (stuck at 0) safe stall at every moment alarm 1 step 2 never fires: waiting for x11 AND NOT halt (alarm: alarm_wd)"
    );
    let out = dir.path().join("conv");
    steptable()
        .arg("convert")
        .arg(&input)
        .args(["--safety", "watchdog", "--formats", "st", "-o"])
        .arg(&out)
        .assert()
        .success();
    let st = std::fs::read_to_string(out.join("heated/heated.st")).unwrap();
    assert!(st.contains("HALT: heater off"), "{st}");
    // Without the declaration, the halted machine keeps it on.
    let input = workbook(dir.path(), &[&["scan time", "10ms"]]);
    faults(&input, &["--safety", "watchdog"])
        .success()
        .stdout(contains(
            "the stopped machine keeps heater on (not hold-safe)",
        ));
}

#[test]
fn a_name_that_is_no_output_of_the_table_is_an_error_at_its_cell() {
    let dir = tempfile::tempdir().unwrap();
    let input = workbook(
        dir.path(),
        &[
            &["hold-safe", "heater, fan, y1"],
            &["de-energise on halt", "heater"],
        ],
    );
    steptable()
        .arg("check")
        .arg(&input)
        .assert()
        .code(1)
        .stderr(contains(
            "SETTINGS!B1: error[E030]: hold-safe: \"fan\" is not an output of this table (expected a machine output, a coil such as y1+, or an actuator: heater, C1, y1+, y1-)",
        ))
        .stderr(contains("SETTINGS!B2: error[E030]: de-energise on halt: this row switches heater off at a halt, but hold-safe at SETTINGS!B1 keeps it on; say one or the other"))
        // C1's valve has two coils: y1 names none of them.
        .stderr(contains("hold-safe: \"y1\" is not an output of this table"))
        .stdout(contains(": ok:").not());
}

/// The car wash of Quezada et al. 2016: its homing button P (RESET) shorted
/// while the gantry travels drives the gantry whatever the other inputs,
/// as they found; a dead limit switch leaves the gantry's drive (MP2, y1+),
/// the spray valve and the brush motor on, until the watchdog's halt
/// switches them off (a drive's outputs always, the others as SETTINGS
/// says).
#[test]
fn the_carwash_flags_its_stuck_homing_button_and_its_halt_switches_the_motors_off() {
    let dir = tempfile::tempdir().unwrap();
    let row = |extra: &[&str], fault: &str| {
        let assert = steptable()
            .arg("faults")
            .arg(crate::helpers::sample("carwash.xlsx"))
            .args(extra)
            .arg("-o")
            .arg(dir.path())
            .assert()
            .success();
        line_with(&squeezed_stdout(&assert), fault)
    };
    for extra in [&[][..], &["--safety", "all"]] {
        assert_eq!(
            row(extra, "RESET_PB short circuit"),
            "RESET_PB short circuit (stuck at 1) hazard before step 3 fires (1 of 8 moments) 0 unintended motion: C1 moves - although no step moves it that way (RESET reads pressed: the program homes the machine)",
            "{extra:?}"
        );
    }
    assert_eq!(
        row(&[], "x11 open circuit"),
        "x11 open circuit (stuck at 0) hazard at every moment 2 step 3 never fires: waiting for x11; the stopped machine keeps y1+, spray, brush on (not hold-safe)"
    );
    assert!(
        row(&["--safety", "all"], "x11 open circuit")
            .starts_with("x11 open circuit (stuck at 0) safe stall at every moment alarm 2"),
    );
}

/// A start permissive (SETTINGS `start permissive | air_ok`): a machine
/// input no step waits for, on in a healthy machine, without which no
/// cycle starts; it gets an address like any machine input.
#[test]
fn a_start_permissive_is_an_input_a_cycle_needs_to_start() {
    let dir = tempfile::tempdir().unwrap();
    let input = workbook(
        dir.path(),
        &[&["start permissive", "air_ok"], &["hold-safe", "heater"]],
    );
    let out = dir.path().join("conv");
    steptable()
        .arg("convert")
        .arg(&input)
        .args(["--formats", "io,st", "-o"])
        .arg(&out)
        .assert()
        .success()
        .stdout(contains("4 inputs"));
    let io = std::fs::read_to_string(out.join("heated/heated.io.csv")).unwrap();
    assert!(io.contains("I0.3,air_ok,"), "{io}");
    let st = std::fs::read_to_string(out.join("heated/heated.st")).unwrap();
    assert!(st.contains("START AND x10 AND air_ok"), "{st}");
    let stdout = squeezed_stdout(&faults(&input, &[]).success());
    assert!(
        stdout.contains("air_ok open circuit (stuck at 0) safe stall at every moment 0 step 1 never fires: waiting for air_ok"),
        "{stdout}"
    );
    assert!(
        stdout.contains("air_ok short circuit (stuck at 1) no effect at every moment the input never reads other than without the fault"),
        "{stdout}"
    );
    // Not a name an input may have (E015, as in a table cell), an output.
    for (name, code, why) in [
        ("start", "E015", "cannot name a machine signal"),
        (
            "heater",
            "E030",
            "heater is a machine output of the table, not an input",
        ),
        ("air ok", "E015", "is not a name"),
    ] {
        let input = workbook(dir.path(), &[&["start permissive", name]]);
        steptable()
            .arg("check")
            .arg(&input)
            .assert()
            .code(1)
            .stderr(contains(format!(
                "SETTINGS!B1: error[{code}]: start permissive: "
            )))
            .stderr(contains(why));
    }
}

/// An interlock (SETTINGS `interlock | guard_closed`): an input that must
/// stay on; going off, it halts the machine where it is, raises `alarm_il`,
/// and with `de-energise on halt` the heater goes off.
#[test]
fn an_interlock_that_opens_halts_the_machine_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let input = workbook(
        dir.path(),
        &[
            &["interlock", "guard_closed"],
            &["de-energise on halt", "heater"],
        ],
    );
    let out = dir.path().join("conv");
    steptable()
        .arg("convert")
        .arg(&input)
        .args(["--formats", "io,st", "-o"])
        .arg(&out)
        .assert()
        .success()
        // The interlock halts, so de-energise on halt has an effect.
        .stderr(contains("W006").not());
    let io = std::fs::read_to_string(out.join("heated/heated.io.csv")).unwrap();
    assert!(io.contains(",guard_closed,"), "{io}");
    assert!(io.contains(",alarm_il,alarm,"), "{io}");
    let st = std::fs::read_to_string(out.join("heated/heated.st")).unwrap();
    assert!(
        st.contains("INTERLOCK: guard_closed off halts the machine"),
        "{st}"
    );
    let stdout = squeezed_stdout(&faults(&input, &[]).success());
    let row = line_with(&stdout, "guard_closed open circuit");
    // Open from power-up or mid-cycle: the machine halts, says so, and
    // nothing it leaves on is a hazard.
    assert!(row.contains(" safe stall at every moment alarm "), "{row}");
    assert!(row.contains("NOT halt (alarm: alarm_il)"), "{row}");
}

/// `hold on estop | vacuum`: the emergency stop switches every coil and
/// output off but the vacuum, so the gripper keeps its part; without an
/// emergency stop the row is W006.
#[test]
fn hold_on_estop_keeps_the_gripper_holding_through_an_emergency_stop() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("gripper.xlsx");
    let table: &[&[&str]] = &[&["C1+1; Y:vacuum+"], &["C1-0; Y:vacuum-"]];
    let settings: &[&[&str]] = &[&["hold on estop", "vacuum"], &["modes", "estop, reset"]];
    write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
    let out = dir.path().join("conv");
    steptable()
        .arg("convert")
        .arg(&path)
        .args(["--formats", "st", "-o"])
        .arg(&out)
        .assert()
        .success()
        .stderr(contains("W006").not());
    let st = std::fs::read_to_string(out.join("gripper/gripper.st")).unwrap();
    assert!(
        st.contains("every coil and output off but vacuum (hold on estop)"),
        "{st}"
    );
    // The emergency stop's wire breaks while C1 moves out, vacuum on: the
    // machine stops holding the part, which is no hazard of energy.
    let stdout = squeezed_stdout(&faults(&path, &[]).success());
    let row = line_with(&stdout, "ESTOP open circuit");
    assert!(!row.contains("keeps vacuum on"), "{row}");
    let settings: &[&[&str]] = &[&["hold on estop", "vacuum"]];
    write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
    steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .success()
        .stderr(contains(
            "warning[W006]: hold on estop: the program has no emergency stop",
        ));
}

/// `interlock | guard_closed in steps 2-3`: the guard may be open while C1
/// travels out (step 1) or home (step 4) and at rest; the machine halts
/// only from step 2 firing until step 4 fires. A guard that breaks at any
/// moment halts it there (waiting for step 3 or 4), where an interlock
/// without a range halts wherever it is; a range to the last step ends with
/// the cycle. A step the table does not have is E030 at the cell.
#[test]
fn an_interlock_over_a_step_range_halts_only_there() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("zoned.xlsx");
    let table: &[&[&str]] = &[&["C1+1"], &["C2+1"], &["C2-0"], &["C1-0"]];
    let stalls = |interlock: &str| -> Vec<Option<usize>> {
        let settings: &[&[&str]] = &[&["interlock", interlock]];
        write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
        let build = crate::helpers::Build::path(&path);
        let program = build.program();
        let mut simulation = build.settings.simulation.clone();
        let healthy = steptable::simulate::simulate(&build.table, &program, &simulation);
        let moments = steptable::faults::moments(&healthy, &build.table, 10);
        simulation.faults = vec![steptable::simulate::Fault {
            signal: steptable::program::Signal::MachineInput(
                steptable::cell::Name::new("guard_closed").unwrap(),
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
    };
    // Open before the range, the machine waits in step 1, before the
    // range's first step (no move starts behind an open guard); open inside
    // it, it halts there: stalled in steps 1 to 3 (the SFC step it is in).
    let zoned = stalls("guard_closed in steps 2-3");
    assert!(
        zoned.iter().all(|s| matches!(s, Some(1..=3))),
        "halts only in the zone: {zoned:?}"
    );
    // Over the whole range, not only its first step: in step 2 (waiting
    // for step 3) and in step 3 (waiting for step 4), never in step 4.
    assert!(
        zoned.contains(&Some(2)) && zoned.contains(&Some(3)),
        "halts in both steps of the range: {zoned:?}"
    );
    // One step written alone is a zone of that step: the machine halts
    // waiting for step 3 or 4 (in step 2 or 3) whenever the guard opens.
    let one_step = stalls("guard_closed in step 3");
    assert!(
        one_step.iter().all(|s| matches!(s, Some(2 | 3))),
        "halts only in step 3: {one_step:?}"
    );
    let everywhere = stalls("guard_closed");
    assert!(everywhere.contains(&Some(1)), "{everywhere:?}");
    // A zone to the last step ends with the cycle (its own END step): the
    // guard may be open at rest, and the next cycle halts in the zone.
    let to_the_end = stalls("guard_closed in steps 3-4");
    assert!(
        to_the_end.iter().all(|s| matches!(s, Some(2..=4))),
        "halts only from step 3 to the end: {to_the_end:?}"
    );
    let settings: &[&[&str]] = &[&["interlock", "guard_closed in steps 3-5"]];
    write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
    steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .failure()
        .stderr(contains(
            "SETTINGS!B1: error[E030]: interlock: \"guard_closed in steps 3-5\" has no step range of this table",
        ));
}

/// Names in the halt rows: `y1` is the one coil of a single-solenoid valve
/// (C1 on 52mono), and two held inputs whose first 9 characters are the
/// same are refused (FST keeps 9), even when neither is the table's.
#[test]
fn a_single_coil_is_named_y1_and_held_inputs_differ_in_nine_characters() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("mono.xlsx");
    let table: &[&[&str]] = &[&["C1+1; Y:heater+"], &["C1-0; Y:heater-"]];
    let write = |rows: &[&[&str]]| {
        let mut settings: Vec<&[&str]> = rows.to_vec();
        settings.extend_from_slice(&[&[""], &["actuator", "valve"], &["C1", "52mono"]]);
        write_xlsx_sheets(
            &path,
            &[
                ("SEQUENTIAL CONTROL DESCRIPTION", table),
                ("SETTINGS", &settings),
            ],
        );
    };
    write(&[&["hold-safe", "y1, heater"]]);
    steptable().arg("check").arg(&path).assert().success();
    // A two-coil valve's coils are y1+ and y1-.
    let settings: &[&[&str]] = &[&["hold-safe", "y1+, y1-"]];
    write_xlsx_sheets(
        &path,
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", table),
            ("SETTINGS", settings),
        ],
    );
    steptable().arg("check").arg(&path).assert().success();
    write(&[&["interlock", "guard_closed_a, guard_closed_b"]]);
    steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .failure()
        .stderr(contains(
            "interlock: guard_closed_b and guard_closed_a begin with the same 9 characters",
        ));
}

/// A value right of the actuator table is W003 on the table's rows, and
/// so is a note far right on a row of the labels above it (every cell of
/// the sheet is read or named; notes go under a WHAT IT MEANS header).
#[test]
fn what_lies_right_of_the_settings_and_the_actuator_table_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("noted.xlsx");
    let table: &[&[&str]] = &[&["C1+1"], &["C1-0"]];
    let settings: &[&[&str]] = &[
        &[
            "scan time",
            "10ms",
            "",
            "",
            "",
            "wired by the panel builder",
        ],
        &[""],
        &["actuator", "extend", "retract"],
        &["C1", "1s", "1s", "", "", "2s?"],
    ];
    write_xlsx_sheets(
        &path,
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", table),
            ("SETTINGS", settings),
        ],
    );
    steptable()
        .arg("check")
        .arg(&path)
        .assert()
        .success()
        .stderr(contains("SETTINGS!F4: warning[W003]"))
        .stderr(contains(
            "SETTINGS!F1: warning[W003]: \"wired by the panel builder\" is beside the setting scan time",
        ));
}
