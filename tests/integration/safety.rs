//! The safety checks: with all four, no single sensor or START fault is a
//! hazard on any sample; without them the paper's example has hazards.

use steptable::convert;
use steptable::faults::{self, Outcome};
use steptable::program::{Safety, Signal};
use steptable::settings::Settings;

use crate::helpers::{Build, read_sheet, sample, samples, steptable};

fn fault_table(path: &std::path::Path, safety: Safety) -> faults::FaultTable {
    Build::path(path).safety(safety).faults()
}

/// The checks watch START and the cylinder sensors. A machine input the
/// sequence waits for (a part sensor) cannot be checked this way: shorted,
/// it lets the machine run on without the part, and the fault table says so.
#[test]
fn with_all_four_checks_no_single_start_or_sensor_fault_is_a_hazard() {
    for path in samples() {
        let table = fault_table(&path, Safety::all());
        let is_machine_input =
            |c: &&faults::FaultCase| matches!(c.faults[0].signal, Signal::MachineInput(_));
        let hazards: Vec<String> = table
            .cases
            .iter()
            .filter(|c| c.outcome == Outcome::Hazard && !is_machine_input(c))
            .map(|c| format!("{}: {}", c.fault_text(), c.explanation))
            .collect();
        assert!(hazards.is_empty(), "{}: {hazards:#?}", path.display());
        assert_eq!(table.cases.len(), 2 * (1 + table_inputs(&path)));
        for case in table.cases.iter().filter(is_machine_input) {
            let expected = if case.faults[0].stuck_at {
                Outcome::Hazard
            } else {
                Outcome::SafeStall
            };
            assert_eq!(case.outcome, expected, "{}", case.fault_text());
        }
    }
}

fn table_inputs(path: &std::path::Path) -> usize {
    let checked = convert::check_path(path, &Settings::new()).unwrap();
    checked
        .table
        .actuators
        .iter()
        .map(|a| a.max_position as usize + 1)
        .sum::<usize>()
        + checked.table.inputs.len()
}

#[test]
fn without_checks_the_paper_has_hazards_and_each_check_removes_some() {
    let paper = sample("paper_example.xlsx");
    let none = fault_table(&paper, Safety::default()).count(Outcome::Hazard);
    assert!(none > 0);
    for check in ["edge", "precheck", "plausibility"] {
        let fewer = fault_table(&paper, Safety::parse(check).unwrap()).count(Outcome::Hazard);
        assert!(fewer < none, "{check}: {fewer} vs {none}");
    }
}

#[test]
fn convert_with_safety_lists_alarms_and_passes_simulation() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(sample("paper_example.xlsx"))
        .args(["--safety", "edge,precheck,plausibility,watchdog", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let out = dir.path().join("paper_example");
    let io = std::fs::read_to_string(out.join("paper_example.io.csv")).unwrap();
    assert!(io.contains("O1.5,alarm_pl,alarm,,,,"), "{io}");
    assert!(io.contains("O1.6,alarm_wd,alarm,,,,"), "{io}");
    let simulation = read_sheet(&out.join("paper_example.xlsx"), "SIMULATION");
    assert!(
        simulation[1][0].starts_with("passed"),
        "{:?}",
        simulation[1]
    );
    let faults = read_sheet(&out.join("paper_example.xlsx"), "FAULTS");
    assert!(faults[1][0].contains(", 0 hazard"), "{:?}", faults[1]);
}
