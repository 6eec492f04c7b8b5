//! Manual mode (`--modes manual`, in `all`) in simulation: the MAN_MODE
//! selector ends the automatic cycle, each actuator of the paper's example
//! moves while its jog button is held, a forbidden jog (both buttons of one
//! cylinder, any jog under the EMERGENCY STOP) moves nothing, and back in
//! automatic the cycle starts after RESET. The events are those of
//! `tests/fixtures/manual_scenario.txt`, which the engines replay
//! (tests/tools/manual.rs). The hostile inputs of the mode, through the
//! binary, are at the end.

use steptable::program::{Signal, StepProgram};
use steptable::simulate::scenario::{ScenarioReport, check, events, scenario_events};
use steptable::table::StepTable;

use crate::helpers::{Build, Refused, assert_refused, manual_events as fixture_events, steptable};

fn run(build: &Build, written: &[(String, String)]) -> (StepTable, StepProgram, ScenarioReport) {
    let program = build.program();
    let table = &build.table;
    let parsed: Vec<_> = written
        .iter()
        .map(|(o, t)| events::parse(o, t, &program, table, &build.settings.naming))
        .collect::<Result<_, _>>()
        .expect("valid events");
    assert!(check::check(&parsed, 10).is_empty());
    let sim = &build.settings.simulation;
    let (report, _) = scenario_events(table, &program, sim, &parsed, (8_000, 60_000), None);
    (build.table.clone(), program, report)
}

fn coil(actuator: u32, plus: bool) -> Signal {
    Signal::Coil {
        actuator,
        sign: if plus {
            steptable::cell::Sign::Plus
        } else {
            steptable::cell::Sign::Minus
        },
    }
}

/// Whether `signal` is on in every sample from `from` to `to` (ms), or
/// (`on` false) off in every one.
fn always(report: &ScenarioReport, (from, to): (u64, u64), signal: Signal, on: bool) -> bool {
    report
        .samples
        .iter()
        .filter(|s| (from..to).contains(&s.time_ms))
        .all(|s| s.outputs_on.contains(&signal) == on)
}

fn position(report: &ScenarioReport, at: u64, actuator: usize) -> f64 {
    report.at(at).unwrap().positions[actuator - 1]
}

#[test]
fn jogs_move_each_actuator_refuse_forbidden_jogs_and_auto_starts_after_reset() {
    let build = Build::paper().modes("all");
    let (_, _, report) = run(&build, &fixture_events());
    // C1 (52bi) out while jog1+ is held, home while jog1- is.
    assert!(always(&report, (600, 1_900), coil(1, true), true));
    assert!(position(&report, 1_950, 1) > 0.95, "C1 out");
    assert!(always(&report, (2_100, 2_400), coil(1, true), false));
    assert!(position(&report, 3_950, 1) < 0.05, "C1 home");
    // C2 (5/3 closed centre) stops where jog2+ was let go.
    let held = position(&report, 5_300, 2);
    assert!(held > 0.2 && held < 2.8, "C2 between its ends: {held}");
    assert_eq!(held, position(&report, 5_450, 2), "C2 held by the centre");
    assert!(position(&report, 6_950, 2) < 0.05, "C2 home");
    // START in manual: nothing fires until the cycle after RESET.
    assert!(
        report.fired.iter().all(|(t, _)| *t > 19_000),
        "{:?}",
        report.fired
    );
    // Both buttons of C3: neither coil, C3 stays home.
    assert!(always(&report, (7_500, 8_500), coil(3, true), false));
    assert!(always(&report, (7_500, 8_500), coil(3, false), false));
    assert!(position(&report, 8_450, 3) < 0.05);
    // C3 alone: out while jog3+ is held, home again.
    assert!(always(&report, (8_800, 9_600), coil(3, true), true));
    assert!(position(&report, 9_650, 3) > 0.5, "C3 moved out");
    assert!(position(&report, 11_350, 3) < 0.05, "C3 home");
    // C4 out and back.
    assert!(position(&report, 13_050, 4) > 0.95, "C4 out");
    assert!(position(&report, 14_750, 4) < 0.05, "C4 home");
    // Under the EMERGENCY STOP jog1+ moves nothing.
    assert!(always(&report, (15_500, 16_500), coil(1, true), false));
    assert!(position(&report, 16_450, 1) < 0.05);
    // Step 0 all through manual; the cycle after RESET and START runs to
    // its end and the machine stands home, with no problem found.
    assert!(
        report
            .samples
            .iter()
            .filter(|s| s.time_ms < 19_000)
            .all(|s| s.step == 0)
    );
    let steps: Vec<usize> = report.fired.iter().map(|(_, s)| *s).collect();
    assert_eq!(steps, (1..=9).collect::<Vec<_>>());
    assert!(report.problems.is_empty(), "{:?}", report.problems);
    let last = report.samples.last().unwrap();
    assert!(last.positions.iter().all(|p| p.abs() < 0.05));
}

/// Red-team findings: leaving manual with jog2+ still held switches the
/// coil off in that scan (C2, a 5/3 closed centre, stops where it is); a
/// jog after the EMERGENCY STOP was released but not reset moves nothing.
#[test]
fn leaving_manual_with_a_jog_held_and_a_halt_not_reset_move_nothing() {
    let build = Build::paper().modes("all");
    let written = [
        ("hold", "MAN_MODE@0.5s"),
        ("hold", "jog2+@1s"),
        ("release", "MAN_MODE@1.5s"),
        ("release", "jog2+@3s"),
        ("press", "ESTOP@4s"),
        ("hold", "MAN_MODE@5s"),
        ("hold", "jog1+@5.5s"),
        ("release", "jog1+@6.5s"),
    ]
    .map(|(o, t)| (o.to_string(), t.to_string()));
    let (_, _, report) = run(&build, &written);
    assert!(always(&report, (1_100, 1_450), coil(2, true), true));
    assert!(always(&report, (1_520, 4_000), coil(2, true), false));
    let stopped = position(&report, 1_600, 2);
    assert_eq!(stopped, position(&report, 3_900, 2), "C2 stands");
    // The halt the emergency stop left waits for RESET: no jog.
    assert!(always(&report, (5_500, 6_500), coil(1, true), false));
    assert!(position(&report, 6_450, 1) < 0.05);
}

/// MAN_MODE mid-cycle: the sequence is back at step 0 the scan after and
/// every coil is off; leaving manual away from home, START does nothing.
#[test]
fn entering_manual_ends_the_cycle_and_start_waits_for_home() {
    let build = Build::paper().modes("all");
    let written = [
        ("press", "START@0.5s"),
        ("hold", "MAN_MODE@step3"),
        ("release", "MAN_MODE@+1s"),
        ("press", "START@+1s"),
    ]
    .map(|(o, t)| (o.to_string(), t.to_string()));
    let (_, _, report) = run(&build, &written);
    let (at, _) = report.happened[1];
    let after = report.at(at + 20).unwrap();
    assert_eq!(after.step, 0);
    assert!(after.outputs_on.is_empty(), "{:?}", after.outputs_on);
    // C1 stands out (it was not home), so START after manual is ignored.
    let steps: Vec<usize> = report.fired.iter().map(|(_, s)| *s).collect();
    assert_eq!(steps, [1, 2, 3], "no cycle after manual away from home");
}

const CASES: &[Refused] = &[
    Refused {
        what: "manual given twice on SETTINGS",
        table: &[&["C1+1"], &["C1-0"]],
        settings: &[&["modes", "manual, manual"]],
        args: &[],
        code_at: "SETTINGS!B1: error[E030]",
    },
    Refused {
        what: "manual contradicted by none on SETTINGS",
        table: &[&["C1+1"], &["C1-0"]],
        settings: &[&["modes", "manual, none"]],
        args: &[],
        code_at: "SETTINGS!B1: error[E030]",
    },
    Refused {
        what: "manual beside all on SETTINGS",
        table: &[&["C1+1"], &["C1-0"]],
        settings: &[&["modes", "all, manual"]],
        args: &[],
        code_at: "SETTINGS!B1: error[E030]",
    },
    Refused {
        what: "manual given twice on the command line",
        table: &[&["C1+1"], &["C1-0"]],
        settings: &[],
        args: &["--modes", "manual,MANUAL"],
        code_at: "\"manual\" is given twice",
    },
    Refused {
        what: "jog as a mode",
        table: &[&["C1+1"], &["C1-0"]],
        settings: &[],
        args: &["--modes", "jog"],
        code_at: "\"jog\" is not an operating mode",
    },
    Refused {
        what: "a machine input named like a jog button",
        table: &[&["C1+1"], &["I:jog1p"], &["C1-0"]],
        settings: &[],
        args: &["--modes", "manual"],
        code_at: "TABLE!A2: error[E015]",
    },
    Refused {
        what: "a machine output named like C2's retract jog, in another case",
        table: &[&["C1+1"], &["C2+1; Y:Jog2M+"], &["C2-0; C1-0; Y:Jog2M-"]],
        settings: &[],
        args: &["--modes", "all"],
        code_at: "TABLE!A2: error[E015]",
    },
    Refused {
        what: "a machine input named like the MAN_MODE selector, the mode on SETTINGS",
        table: &[&["C1+1"], &["I:man_mode"], &["C1-0"]],
        settings: &[&["modes", "manual"]],
        args: &[],
        code_at: "TABLE!A2: error[E015]",
    },
    Refused {
        what: "C2's extend coil named like C1's jog button (C1 c, C2 c_jog)",
        table: &[&["C1+1"], &["C2+1"], &["C2-0"], &["C1-0"]],
        settings: &[
            &["modes", "manual"],
            &["actuator", "name"],
            &["C1", "c"],
            &["C2", "c_jog"],
        ],
        args: &["--designations", "names"],
        code_at: "SETTINGS!B4: error[E025]: C2 (c_jog): c_jog_out is named for C1's jog button at SETTINGS!B3 too",
    },
    Refused {
        what: "C1's jog button named like C2's retract coil, the jog later (C1 c_jog, C2 c)",
        table: &[&["C1+1"], &["C2+1"], &["C2-0"], &["C1-0"]],
        settings: &[
            &["modes", "manual"],
            &["actuator", "name"],
            &["C1", "c_jog"],
            &["C2", "c"],
        ],
        args: &[],
        code_at: "SETTINGS!B4: error[E025]: C2 (c): its jog button c_jog_out is named for C1 at SETTINGS!B3 too",
    },
    Refused {
        what: "a machine input named like the retract jog names that jog, not the extend one",
        table: &[&["C1+1"], &["I:clamp_jog_in"], &["C1-0"]],
        settings: &[
            &["modes", "manual"],
            &["actuator", "name"],
            &["C1", "clamp"],
        ],
        args: &["--designations", "names"],
        code_at: "the operating-mode button CLAMP_JOG_IN ",
    },
    Refused {
        what: "an interlock input named like a jog button",
        table: &[&["C1+1"], &["C1-0"]],
        settings: &[&["modes", "manual"], &["interlock", "jog1m"]],
        args: &[],
        code_at: "SETTINGS!B2: error[E015]",
    },
];

/// Each row through the binary: exit 1, its code at its cell, nothing
/// written.
#[test]
fn hostile_manual_inputs_are_refused_with_their_cell() {
    assert_refused(CASES);
}

/// Manual mode on a table that moves no actuator (the oven: a horn, a
/// heater, a fan) has nothing to jog: it is left out, W006 at the `modes`
/// cell (or naming `--modes`), and no MAN_MODE input is declared.
#[test]
fn manual_on_a_table_without_actuators_is_left_out_and_said() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("lamp.xlsx");
    let table: &[&[&str]] = &[&["Y:lamp+"], &["T=1s"], &["Y:lamp-"]];
    let settings: &[&[&str]] = &[&["modes", "manual, stop"]];
    let sheets = [
        ("SEQUENTIAL CONTROL DESCRIPTION", table),
        ("SETTINGS", settings),
    ];
    crate::helpers::write_xlsx_sheets(&path, &sheets);
    for (args, said) in [
        (
            &[][..],
            "SETTINGS!B1: warning[W006]: modes: manual mode jogs actuators",
        ),
        (
            &["--modes", "all"][..],
            "warning[W006]: --modes: manual mode jogs actuators",
        ),
    ] {
        let out = dir.path().join(format!("out{}", args.len()));
        let run = steptable()
            .arg("convert")
            .arg(&path)
            .args(args)
            .args(["--formats", "st", "-o"])
            .arg(&out)
            .assert()
            .success();
        let stderr = String::from_utf8_lossy(&run.get_output().stderr).into_owned();
        assert!(stderr.contains(said), "{args:?}: {stderr}");
        let st = std::fs::read_to_string(out.join("lamp/lamp.st")).unwrap();
        assert!(!st.contains("MAN_MODE"), "{args:?}");
    }
    // A scenario that jogs it says why there is no button (red team rt7
    // F18.2: it said "turn it on with --modes manual" to one who had).
    for event in ["MAN_MODE@1s", "jog1+@1s"] {
        let run = steptable()
            .arg("simulate")
            .arg(&path)
            .args(["--modes", "manual,stop", "--hold", event])
            .assert()
            .code(1);
        let stderr = String::from_utf8_lossy(&run.get_output().stderr).into_owned();
        assert!(
            stderr.contains("error[E042]")
                && stderr.contains("the table moves no actuator, so manual mode is left out")
                && !stderr.contains("turn it on"),
            "{event}: {stderr}"
        );
    }
}

/// The jog names are free for a machine signal without the mode.
#[test]
fn the_jog_names_are_taken_only_with_the_mode() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("free.xlsx");
    let table: &[&[&str]] = &[&["C1+1"], &["I:jog1p"], &["C1-0"]];
    crate::helpers::write_xlsx_sheets(&path, &[("TABLE", table)]);
    steptable().arg("check").arg(&path).assert().success();
}

/// A jog input pinned on the ADDRESSES sheet to the address another pin
/// holds is E035 at its cell; pinned alone, it keeps its address.
#[test]
fn a_pinned_jog_address_that_collides_is_refused_at_its_cell() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("pinned.xlsx");
    let table: &[&[&str]] = &[&["C1+1"], &["C1-0"]];
    let pins: &[&[&str]] = &[&["START", "I1.0"], &["jog1+", "I1.0"]];
    crate::helpers::write_xlsx_sheets(&path, &[("TABLE", table), ("ADDRESSES", pins)]);
    let out = dir.path().join("out");
    let run = steptable()
        .arg("convert")
        .arg(&path)
        .args(["--modes", "manual", "--target", "siemens", "-o"])
        .arg(&out)
        .assert()
        .code(1);
    let stderr = String::from_utf8_lossy(&run.get_output().stderr).into_owned();
    assert!(stderr.contains("ADDRESSES!B2: error[E035]"), "{stderr}");
    assert!(!out.exists());
    let pins: &[&[&str]] = &[&["jog1m", "I1.0"]];
    crate::helpers::write_xlsx_sheets(&path, &[("TABLE", table), ("ADDRESSES", pins)]);
    steptable()
        .arg("convert")
        .arg(&path)
        .args([
            "--modes",
            "manual",
            "--target",
            "siemens",
            "--formats",
            "io",
            "-o",
        ])
        .arg(&out)
        .assert()
        .success();
    let io = std::fs::read_to_string(out.join("pinned/pinned.io.csv")).unwrap();
    let line = io
        .lines()
        .find(|l| l.contains(",jog1-,"))
        .expect("jog1- listed");
    assert!(line.contains("I1.0"), "{line}");
}

/// Scenario events of the mode, through `simulate`: E042 naming the
/// option for a jog without the mode, the retract jog of a one-coil valve,
/// and a fifth jog button held at once.
#[test]
fn hostile_jog_events_are_refused() {
    let paper = crate::helpers::sample("paper_example.xlsx");
    let cases: [(&[&str], &str); 3] = [
        (
            &["--modes", "estop", "--hold", "jog1+@1s"],
            "--hold jog1+@1s: the program has no jog button called \"jog1+\": manual mode is off",
        ),
        (
            &[
                "--modes",
                "manual",
                "--valve",
                "C1=52mono",
                "--hold",
                "jog1-@1s",
            ],
            "--hold jog1-@1s: the program has no jog button called \"jog1-\": each actuator has jogN+ and jogN- (a 52mono cylinder only jogN+: its spring is the way back)",
        ),
        (
            &[
                "--modes",
                "manual",
                "--hold",
                "jog1+@1s",
                "--hold",
                "jog2+@1s",
                "--hold",
                "jog3+@1s",
                "--hold",
                "jog4+@1s",
                "--hold",
                "jog4-@1.5s",
            ],
            "--hold jog4-@1.5s: at most 4 jog buttons can be held at once (5 are)",
        ),
    ];
    for (args, said) in cases {
        let run = steptable()
            .arg("simulate")
            .arg(&paper)
            .args(args)
            .assert()
            .code(1);
        let stderr = String::from_utf8_lossy(&run.get_output().stderr).into_owned();
        assert!(
            stderr.contains("E042") && stderr.contains(said),
            "{args:?}: {stderr}"
        );
    }
}

/// The fault table classifies the mode's inputs in the automatic cycle: a
/// MAN_MODE stuck at 1 ends the cycle where it is (a collision risk when
/// it comes mid-move); stuck at 0 and every jog button stuck either way
/// show no effect — the faults the guide says no check can catch.
#[test]
fn the_fault_table_classifies_the_manual_inputs() {
    use steptable::cell::Sign;
    use steptable::faults::Outcome;
    let table = Build::paper().modes("manual").faults();
    let outcome = |signal: Signal, stuck_at: bool| {
        let case = table.cases.iter().find(|c| {
            c.faults.len() == 1 && c.faults[0].signal == signal && c.faults[0].stuck_at == stuck_at
        });
        case.unwrap_or_else(|| panic!("{signal:?} stuck at {stuck_at} is a case"))
            .outcome
    };
    // Stuck at 1 from rest: the cycle never starts (a safe stall); coming
    // mid-move it cuts the cycle there, the 5/2 cylinders finishing their
    // strokes and the 5/3 ones stopping: positions the healthy cycle
    // never has together, a collision risk, as switching to manual
    // mid-cycle is.
    assert_eq!(outcome(Signal::ManualMode, true), Outcome::Hazard);
    let stuck = table.cases.iter().find(|c| {
        c.faults.len() == 1 && c.faults[0].signal == Signal::ManualMode && c.faults[0].stuck_at
    });
    let explanation = &stuck.unwrap().explanation;
    assert!(explanation.contains("step 1 never fires"), "{explanation}");
    assert!(explanation.contains("collision risk"), "{explanation}");
    assert_eq!(outcome(Signal::ManualMode, false), Outcome::NoEffect);
    for actuator in 1..=4 {
        for sign in [Sign::Plus, Sign::Minus] {
            let jog = Signal::Jog { actuator, sign };
            assert_eq!(outcome(jog, true), Outcome::NoEffect, "{jog:?}");
            assert_eq!(outcome(jog, false), Outcome::NoEffect, "{jog:?}");
        }
    }
}

/// A coil a halt row holds on (`hold-safe | C1`, C1 a spring-return clamp)
/// stays on into manual as the halt left it; once its jog is pressed it is
/// the button's, on only while held, as every other coil: a tap does not
/// latch it (the 53closed piston stops where the tap left it).
#[test]
fn a_held_coil_stays_until_jogged_then_follows_its_button() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("held.xlsx");
    let table: &[&[&str]] = &[&["C1+1"], &["C2+1"], &["C2-0"], &["C1-0"]];
    let last_line = |valve: &str, events: &[&str]| {
        let settings: &[&[&str]] = &[
            &["modes", "all"],
            &["hold-safe", "C1"],
            &["actuator", "valve", "extend", "retract"],
            &["C1", valve, "2s", "2s"],
        ];
        crate::helpers::write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
        let run = steptable().arg("simulate").arg(&path).args(events).assert();
        let stdout = String::from_utf8_lossy(&run.get_output().stdout).into_owned();
        stdout.lines().last().unwrap_or_default().to_string()
    };
    let into_manual = ["--press", "START@0.5s", "--hold", "MAN_MODE@step2"];
    let kept = last_line("52mono", &into_manual);
    assert!(
        kept.contains("C1 at 1.00") && kept.contains("on: y1"),
        "{kept}"
    );
    let mut tapped = into_manual.to_vec();
    tapped.extend(["--press", "jog1+@+1s"]);
    let released = last_line("52mono", &tapped);
    assert!(
        released.contains("C1 at 0.00") && !released.contains("y1"),
        "{released}"
    );
    let tap = [
        "--hold",
        "MAN_MODE@0.3s",
        "--hold",
        "jog1+@0.5s",
        "--release",
        "jog1+@0.6s",
        "--release",
        "MAN_MODE@4s",
    ];
    let stopped = last_line("53closed", &tap);
    assert!(
        stopped.contains("C1 at 0.0") && !stopped.contains("y1+"),
        "{stopped}"
    );
}
