//! Electric drives (valve type `motor`): forward and reverse outputs cut at
//! every limit switch, so that a drive is never left running in a machine at
//! rest; a dead limit switch leaves it running, a hazard of energy the halt
//! of a safety check cuts; RESET homes it and cuts it at home.

use steptable::actuator::ActuatorKind;
use steptable::program::{Safety, Signal};
use steptable::simulate::Operator;
use steptable::simulate::scenario::scenario;

use crate::helpers::{Build, line_with, squeezed_stdout, steptable};

/// A gantry C1 out and back with a clamp C2 in between.
fn gantry(valve: ActuatorKind) -> Build {
    let rows = [vec!["C1+1"], vec!["C2+1"], vec!["C2-0"], vec!["C1-0"]];
    let mut build = Build::rows("gantry.csv", &rows);
    build
        .settings
        .simulation
        .machine
        .valves
        .per_actuator
        .insert(1, valve);
    build
}

fn outputs_on_at(build: &Build, modes: &str, script: &[(u64, Operator)], at: u64) -> Vec<Signal> {
    let build = Build {
        table: build.table.clone(),
        settings: build.settings.clone(),
    }
    .modes(modes);
    let program = build.program();
    let report = scenario(
        &build.table,
        &program,
        &build.settings.simulation,
        script,
        at + 10,
    );
    report.at(at).expect("sampled").outputs_on.clone()
}

fn press(at: u64, button: Operator) -> Vec<(u64, Operator)> {
    vec![(at, button), (at + 100, Operator::default())]
}

fn start() -> Operator {
    Operator {
        start: true,
        ..Operator::default()
    }
}

#[test]
fn a_drive_is_cut_at_every_limit_and_rests_with_its_outputs_off() {
    let y1 = |sign| Signal::Coil { actuator: 1, sign };
    let end = 12_000;
    // A cylinder keeps its last coil (the valve holds it); a drive is cut.
    let cylinder = outputs_on_at(
        &gantry(ActuatorKind::Bistable52),
        "",
        &press(500, start()),
        end,
    );
    assert!(
        cylinder.contains(&y1(steptable::cell::Sign::Minus)),
        "{cylinder:?}"
    );
    let drive = gantry(ActuatorKind::Motor);
    let after_cycle = outputs_on_at(&drive, "", &press(500, start()), end);
    assert!(
        !after_cycle
            .iter()
            .any(|s| matches!(s, Signal::Coil { actuator: 1, .. })),
        "{after_cycle:?}"
    );
    // Mid-travel the drive runs forward, nothing else of C1 on.
    let moving = outputs_on_at(&drive, "", &press(500, start()), 1_000);
    assert!(
        moving.contains(&y1(steptable::cell::Sign::Plus)),
        "{moving:?}"
    );
    // The cycle passes twice alike, and through the binary the written
    // program cuts the drive at each limit switch.
    let report =
        steptable::simulate::simulate(&drive.table, &drive.program(), &drive.settings.simulation);
    assert!(report.passed, "{:?}", report.problems);
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("gantry.csv");
    std::fs::write(&table, "C1+1\nC2+1\nC2-0\nC1-0\n").unwrap();
    steptable()
        .args(["convert", "--valve", "C1=motor", "--formats", "st", "-o"])
        .arg(dir.path())
        .arg(&table)
        .assert()
        .success();
    let st = std::fs::read_to_string(dir.path().join("gantry/gantry.st")).unwrap();
    for limit in ["x10", "x11"] {
        let position = &limit[2..];
        assert!(
            st.contains(&format!(
                "IF m1_{position} AND {limit} THEN\n    y1p := FALSE;\n    y1m := FALSE;"
            )),
            "{st}"
        );
    }
    assert!(
        st.contains("drive 1, forward (+) (cut at its limit switch)"),
        "{st}"
    );
}

#[test]
fn reset_homes_a_drive_and_cuts_it_at_home() {
    let drive = gantry(ActuatorKind::Motor);
    // START, EMERGENCY STOP while C1 travels out, RESET: homed, then cut.
    let mut script = press(500, start());
    script.push((
        1_100,
        Operator {
            estop: true,
            ..Operator::default()
        },
    ));
    script.push((1_300, Operator::default()));
    script.extend(press(
        2_000,
        Operator {
            reset: true,
            ..Operator::default()
        },
    ));
    let homed = outputs_on_at(&drive, "estop,reset", &script, 6_000);
    assert!(
        !homed
            .iter()
            .any(|s| matches!(s, Signal::Coil { actuator: 1, .. })),
        "{homed:?}"
    );
    let cylinder = outputs_on_at(
        &gantry(ActuatorKind::Closed53),
        "estop,reset",
        &script,
        6_000,
    );
    assert!(
        cylinder
            .iter()
            .any(|s| matches!(s, Signal::Coil { actuator: 1, .. })),
        "{cylinder:?}"
    );
}

#[test]
fn a_dead_limit_switch_leaves_the_drive_running_until_a_halt_cuts_it() {
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("gantry.csv");
    std::fs::write(&table, "C1+1\nC2+1\nC2-0\nC1-0\n").unwrap();
    let row = |extra: &[&str]| {
        let assert = steptable()
            .args(["faults", "--valve"])
            .args(extra)
            .arg(&table)
            .arg("-o")
            .arg(dir.path().join("out"))
            .assert()
            .success();
        line_with(&squeezed_stdout(&assert), "x11 open circuit")
    };
    // A cylinder on a closed-centre valve may keep its coil; a drive may not.
    assert!(
        row(&["C1=53closed"]).starts_with("x11 open circuit (stuck at 0) safe stall"),
        "{}",
        row(&["C1=53closed"])
    );
    assert_eq!(
        row(&["C1=motor"]),
        "x11 open circuit (stuck at 0) hazard at every moment 1 step 2 never fires: waiting for x11; the stopped machine keeps y1+ on (not hold-safe)"
    );
    // The watchdog halts, and a halt cuts every drive.
    assert!(
        row(&["C1=motor", "--safety", "all"])
            .starts_with("x11 open circuit (stuck at 0) safe stall at every moment alarm 1"),
        "{}",
        row(&["C1=motor", "--safety", "all"])
    );
    let program = Build {
        settings: {
            let mut s = gantry(ActuatorKind::Motor).settings;
            s.program.safety = Safety::all();
            s
        },
        ..gantry(ActuatorKind::Motor)
    }
    .program();
    let halt = program
        .rungs
        .iter()
        .find(|r| r.comment.starts_with("HALT:"))
        .expect("a halt rung");
    assert_eq!(
        halt.comment,
        "HALT: y1+, y1- off (drives, and de-energise on halt)"
    );
}

/// Red team on the kinds: a drive's step actions were commented "extend
/// C1" / "retract C1" in every language. Its contactors run it: each step
/// and rung comment of the ST, AWL and FST, and the report's times, say it
/// runs forward or in reverse, while the cylinder beside it still extends.
/// Broken on purpose (a drive's coil words back to extend/retract) this
/// failed on the ST.
#[test]
fn a_drive_s_step_comments_say_it_runs_in_every_language() {
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("gantry.csv");
    std::fs::write(&table, "C1+1\nC2+1\nC2-0\nC1-0\n").unwrap();
    steptable()
        .args(["convert", "--valve", "C1=motor", "--modes", "all", "-o"])
        .arg(dir.path())
        .args(["--formats", "st,awl,fst,report"])
        .arg(&table)
        .assert()
        .success();
    for suffix in [".st", ".awl", ".fst.txt"] {
        let text = std::fs::read_to_string(dir.path().join(format!("gantry/gantry{suffix}")))
            .unwrap_or_else(|e| panic!("{suffix}: {e}"));
        for said in [
            "y1+ on: run C1 forward, C1+1 towards x11",
            "y1- on: run C1 in reverse, C1-0 towards x10",
            "y2+ on: extend C2, C2+1 towards x21",
        ] {
            assert!(text.contains(said), "{suffix}: {said}\n{text}");
        }
        assert!(
            !text.contains("extend C1") && !text.contains("retract C1"),
            "{suffix}: {text}"
        );
    }
    let report = std::fs::read_to_string(dir.path().join("gantry/gantry.report.html")).unwrap();
    assert!(
        report.contains("valve motor, runs forward in 1s, runs in reverse in 1s"),
        "{report}"
    );
}
