//! A drive (valve type `motor`) cut at a limit switch coasts to the
//! switch's point, moving out and moving back: where it stands after each
//! move, at a middle stop and at both ends, is the switch's point exactly,
//! not where the switch tripped. (The carwash's outputs are the same
//! either way, so only its positions show a break in one direction.)

use steptable::actuator::ActuatorKind;
use steptable::simulate::Operator;
use steptable::simulate::scenario::scenario;

use crate::helpers::{Build, steptable};

/// C1, a drive with a middle stop, out to 1, out to 2, back to 1 and home,
/// resting while C2 strokes after each of its moves.
const ROWS: [&[&str]; 8] = [
    &["C1+1"],
    &["C2+1"],
    &["C1+2"],
    &["C2-0"],
    &["C1-1"],
    &["C2+1"],
    &["C2-0"],
    &["C1-0"],
];

#[test]
fn a_cut_drive_coasts_to_its_limit_switch_in_each_direction() {
    let mut build = Build::rows("drive.csv", &ROWS);
    build
        .settings
        .simulation
        .machine
        .valves
        .per_actuator
        .insert(1, ActuatorKind::Motor);
    let program = build.program();
    let script = [
        (
            500,
            Operator {
                start: true,
                ..Operator::default()
            },
        ),
        (600, Operator::default()),
    ];
    let report = scenario(
        &build.table,
        &program,
        &build.settings.simulation,
        &script,
        15_000,
    );
    assert!(report.problems.is_empty(), "{:?}", report.problems);
    let fired = |step: usize| {
        report
            .fired
            .iter()
            .find(|(_, s)| *s == step)
            .unwrap_or_else(|| panic!("step {step} never fired: {:?}", report.fired))
            .0
    };
    // Half-way through each C2 stroke, C1 has long been cut and stands.
    let c1_at = |time: u64| report.at(time).expect("sampled").positions[0];
    for (step, direction, expected) in [(2, "+", 1.0), (4, "+", 2.0), (6, "-", 1.0)] {
        let at = c1_at(fired(step) + 500);
        assert!(
            (at - expected).abs() < 1e-9,
            "after moving {direction}, C1 stands at {at}, not at its switch's point {expected}"
        );
    }
    let home = c1_at(fired(8) + 2_000);
    assert!(home.abs() < 1e-9, "home: C1 stands at {home}");
    // Through the binary the drive's cycle passes, twice alike.
    let dir = tempfile::tempdir().unwrap();
    let table = dir.path().join("drive.csv");
    let text: String = ROWS.iter().map(|r| format!("{}\n", r[0])).collect();
    std::fs::write(&table, text).unwrap();
    steptable()
        .args(["simulate", "--valve", "C1=motor"])
        .arg(&table)
        .assert()
        .success()
        .stdout(predicates::str::contains("second START: identical cycle"));
}
