//! The safety checks: with all four, no single sensor or START fault that
//! is there from power-up is a hazard of the sequence on any sample; what
//! remains is the overrun of a dead middle-position sensor, a collision
//! risk no input check can stop in time. Faults that appear mid-cycle add
//! the shorts no input check can tell from the real thing. Without the
//! checks the paper's example has hazards.

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
/// Nor can a dead sensor at a middle position: the cylinder runs on to its
/// next position, and the only sign of it, that next sensor, comes after
/// the overrun; the fault table calls it a collision risk.
///
/// Mid-cycle, three more kinds remain, each one no check of the inputs can
/// catch: a sensor that shorts while its cylinder travels towards it (or a
/// START, CONTINUOUS or RESET button that shorts) reads exactly as the
/// arrival (the press) would; and a halt that leaves a piston on a valve that keeps its
/// position running on (a collision risk: de-energising is not stopping).
#[test]
fn with_all_four_checks_only_middle_sensor_overruns_remain_hazards() {
    for path in samples() {
        let table = fault_table(&path, Safety::all());
        let checked = convert::check_path(&path, &Settings::new()).unwrap();
        let is_machine_input =
            |c: &&faults::FaultCase| matches!(c.faults[0].signal, Signal::MachineInput(_));
        let is_middle_overrun = |c: &&faults::FaultCase| match c.faults[0].signal {
            Signal::Sensor { actuator, position } => {
                let pmax = checked
                    .table
                    .actuator(actuator)
                    .map_or(0, |a| a.max_position);
                !c.faults[0].stuck_at
                    && position > 0
                    && position < pmax
                    && c.explanation.contains(" ran through ")
                    && c.explanation.contains("collision risk: ")
            }
            _ => false,
        };
        // From power-up: as the checks promise, for START and the sensors
        // (a CONTINUOUS switch stuck on is the operator's choice of
        // continuous running, whatever the checks).
        let is_watched = |c: &&faults::FaultCase| {
            matches!(c.faults[0].signal, Signal::Start | Signal::Sensor { .. })
        };
        let hazards: Vec<String> = table
            .cases
            .iter()
            .filter(|c| c.outcomes[0] == Outcome::Hazard && is_watched(c))
            .filter(|c| !is_middle_overrun(c))
            .map(|c| format!("{}: {}", c.fault_text(), c.explanation))
            .collect();
        assert!(hazards.is_empty(), "{}: {hazards:#?}", path.display());
        // Mid-cycle: each remaining hazard is one of the kinds above.
        let looks_real = |c: &&faults::FaultCase| {
            let fault = c.faults[0];
            let symbol = fault.signal.symbol();
            fault.stuck_at
                && match fault.signal {
                    // A button that shorts reads as the operator's press.
                    Signal::Start | Signal::Continuous => {
                        c.explanation.contains("without a START press")
                    }
                    Signal::Reset => c.explanation.contains("RESET reads pressed"),
                    // In single step a shorted STEP_PB is one press.
                    Signal::StepButton => c.explanation.contains("without a STEP_PB press"),
                    Signal::Sensor { .. } => {
                        c.explanation
                            .contains(&format!("had not reached {symbol})"))
                            || c.explanation.contains(&format!(
                                "before C{} reached {symbol}",
                                &symbol[1..symbol.len() - 1]
                            ))
                    }
                    _ => false,
                }
        };
        let unexplained: Vec<String> = table
            .cases
            .iter()
            .filter(|c| c.outcome == Outcome::Hazard && !is_machine_input(c))
            .filter(|c| !is_middle_overrun(c) && !looks_real(c))
            .filter(|c| !c.explanation.contains("collision risk: "))
            .map(|c| format!("{}: {}", c.fault_text(), c.explanation))
            .collect();
        assert!(
            unexplained.is_empty(),
            "{}: {unexplained:#?}",
            path.display()
        );
        assert_eq!(table.cases.len(), 2 * (1 + table_inputs(&path)));
        // An input a step waits for stalls the machine when it is lost; one
        // the sequence only jumps on loses the jump's path, and the machine
        // runs on without it (the explanation says which jump): a hazard no
        // check on the inputs can catch (a bad part goes on as a good one).
        let only_jumps = |signal: Signal| {
            let steps = &checked.table.steps;
            let named = |n| Signal::MachineInput(n) == signal;
            steps.iter().flat_map(|s| &s.jumps).any(|j| named(j.input))
                && !steps.iter().flat_map(|s| &s.waits).any(|w| named(w.input))
        };
        for case in table.cases.iter().filter(is_machine_input) {
            let expected = match (case.faults[0].stuck_at, only_jumps(case.faults[0].signal)) {
                (true, _) => Outcome::Hazard,
                (false, false) => Outcome::SafeStall,
                (false, true) => {
                    assert!(
                        case.explanation.contains("was to take J:"),
                        "{}",
                        case.explanation
                    );
                    Outcome::Hazard
                }
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
        + checked.settings.program.modes.buttons().count()
        + convert::build_program(&checked.table, &checked.settings)
            .signals
            .inputs
            .iter()
            .filter(|s| matches!(s, Signal::Jog { .. }))
            .count()
}

#[test]
fn without_checks_the_paper_has_hazards_and_each_check_removes_some() {
    let paper = sample("paper_example.xlsx");
    let none = fault_table(&paper, Safety::default()).count(Outcome::Hazard);
    assert!(none > 0);
    // Hazardous (fault, moment) cases: each check takes some away.
    let cells = |t: &faults::FaultTable| {
        t.cases
            .iter()
            .flat_map(|c| &c.outcomes)
            .filter(|o| **o == Outcome::Hazard)
            .count()
    };
    let none_cells = cells(&fault_table(&paper, Safety::default()));
    for check in ["edge", "precheck", "plausibility"] {
        let fewer = cells(&fault_table(&paper, Safety::parse(check).unwrap()));
        assert!(fewer < none_cells, "{check}: {fewer} vs {none_cells}");
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
    let simulation = read_sheet(&out.join("paper_example.steptable.xlsx"), "SIMULATION");
    assert!(
        simulation[1][0].starts_with("passed"),
        "{:?}",
        simulation[1]
    );
    // The PLC PROGRAM sheet shows each step starting its watchdog timer,
    // with the preset, beside the memories it sets.
    let program = read_sheet(&out.join("paper_example.steptable.xlsx"), "PLC PROGRAM");
    // Step 1's actions are on the row of step 0, whose START enters it.
    let step1 = program
        .iter()
        .find(|r| r[0] == "STEP 0")
        .unwrap_or_else(|| panic!("{program:?}"));
    assert!(
        step1[2].contains("START watchdog (") && step1[2].contains(" ms)"),
        "{step1:?}"
    );
    // From power-up, only the overruns of the dead middle sensors x22 and
    // x31 remain; the other hazards need the fault to appear mid-cycle.
    let faults = read_sheet(&out.join("paper_example.steptable.xlsx"), "FAULTS");
    assert!(
        faults[1][0].starts_with("24 fault case(s) at 17 moments of the cycle"),
        "{:?}",
        faults[1]
    );
    assert_eq!(faults[3][..3], ["FAULT", "OUTCOME", "APPEARS"]);
    let hazards: Vec<&String> = faults
        .iter()
        .filter(|r| r.get(1).is_some_and(|o| o == "hazard"))
        .filter(|r| r.get(2).is_some_and(|a| a.starts_with("from power-up")))
        .map(|r| &r[0])
        .collect();
    assert_eq!(
        hazards,
        [
            "x22 open circuit (stuck at 0)",
            "x31 open circuit (stuck at 0)"
        ],
        "{faults:?}"
    );
}
