//! Step supervision with criteria analysis (`--safety criteria`) in
//! simulation: a sensor that fails stalls its step, the watchdog runs out,
//! and the missing outputs name exactly the conditions of the awaited
//! transition that are not met. The hostile inputs are in
//! `supervision_hostile.rs`.

use steptable::program::{Alarm, Literal, Signal, StepProgram};
use steptable::simulate::scenario::{ScenarioReport, scenario};
use steptable::simulate::{Fault, Operator, SimSettings};
use steptable::table::StepTable;

use crate::helpers::Build;

fn sensor(actuator: u32, position: u32) -> Signal {
    Signal::Sensor { actuator, position }
}

fn paper_with(safety: &str, faults: Vec<Fault>) -> (StepTable, StepProgram, SimSettings) {
    let simulation = SimSettings {
        faults,
        ..SimSettings::default()
    };
    let build = Build::paper()
        .safety(safety.parse().unwrap())
        .simulation(simulation.clone());
    let program = build.program();
    (build.table, program, simulation)
}

/// START pressed at 0.5 s for 0.1 s, the run for `until_ms`.
fn started(
    table: &StepTable,
    program: &StepProgram,
    simulation: &SimSettings,
    until_ms: u64,
) -> ScenarioReport {
    let pressed = Operator {
        start: true,
        ..Operator::default()
    };
    let script = [
        (0, Operator::default()),
        (500, pressed),
        (600, Operator::default()),
    ];
    scenario(table, program, simulation, &script, until_ms)
}

/// The criteria whose missing output is on at the end of the run.
fn missing(program: &StepProgram, report: &ScenarioReport) -> Vec<Literal> {
    let end = report.samples.last().unwrap();
    end.outputs_on
        .iter()
        .filter_map(|s| match s {
            Signal::Missing(n) => Some(program.criteria[usize::from(*n) - 1]),
            _ => None,
        })
        .collect()
}

fn alarm_on(report: &ScenarioReport) -> bool {
    let end = report.samples.last().unwrap();
    end.outputs_on.contains(&Signal::Alarm(Alarm::Timeout))
}

/// x23 open circuit: step 2 (C2+3) never completes. Its watchdog (twice
/// the 1 s stroke, plus 1 s) runs out at about 4.5 s, and the one missing
/// output on is x23's.
#[test]
fn a_sensor_stuck_off_stalls_its_step_and_is_named_missing() {
    let fault = Fault {
        signal: sensor(2, 3),
        stuck_at: false,
    };
    let (table, program, simulation) = paper_with("criteria", vec![fault]);
    let before = started(&table, &program, &simulation, 4_000);
    assert!(!alarm_on(&before), "the watchdog ran out early");
    assert!(missing(&program, &before).is_empty());
    let report = started(&table, &program, &simulation, 6_000);
    let steps: Vec<usize> = report.fired.iter().map(|(_, s)| *s).collect();
    assert_eq!(steps, [1, 2]);
    assert!(alarm_on(&report));
    assert_eq!(missing(&program, &report), [Literal::is(sensor(2, 3))]);
}

/// Step 5 waits for two sensors (x32 and x22); with x32 stuck off only
/// x32 is missing, x22 having come.
#[test]
fn of_two_conditions_only_the_unmet_one_is_missing() {
    let fault = Fault {
        signal: sensor(3, 2),
        stuck_at: false,
    };
    let (table, program, simulation) = paper_with("criteria", vec![fault]);
    let report = started(&table, &program, &simulation, 12_000);
    let steps: Vec<usize> = report.fired.iter().map(|(_, s)| *s).collect();
    assert_eq!(steps, [1, 2, 3, 4]);
    assert!(alarm_on(&report));
    assert_eq!(missing(&program, &report), [Literal::is(sensor(3, 2))]);
}

/// With the precheck a move starts only while its target sensor is off:
/// x23 stuck on holds step 2 (C2+3) back once step 1 is done, and the
/// criterion missing is "x23 off".
#[test]
fn a_sensor_stuck_on_is_missing_as_a_sensor_that_must_be_off() {
    let fault = Fault {
        signal: sensor(2, 3),
        stuck_at: true,
    };
    let (table, program, simulation) = paper_with("precheck,criteria", vec![fault]);
    let report = started(&table, &program, &simulation, 6_000);
    let steps: Vec<usize> = report.fired.iter().map(|(_, s)| *s).collect();
    assert_eq!(steps, [1]);
    assert!(alarm_on(&report));
    assert_eq!(missing(&program, &report), [Literal::not(sensor(2, 3))]);
}

/// A healthy machine: three cycles, no missing output ever on, and the
/// program with the criteria analysis fires every step at the scan the
/// watchdog alone does.
#[test]
fn a_healthy_machine_never_shows_a_missing_condition() {
    let (table, program, simulation) = paper_with("criteria", Vec::new());
    let (_, plain, _) = paper_with("watchdog", Vec::new());
    let report = started(&table, &program, &simulation, 9_000);
    assert_eq!(report.fired.len(), 9, "{:?}", report.fired);
    assert!(report.problems.is_empty(), "{:?}", report.problems);
    let lit = |s: &steptable::simulate::scenario::Sample| {
        s.outputs_on
            .iter()
            .any(|o| matches!(o, Signal::Missing(_) | Signal::Alarm(_)))
    };
    assert!(!report.samples.iter().any(lit));
    let plain = started(&table, &plain, &simulation, 9_000);
    assert_eq!(report.fired, plain.fired);
}

/// Every criterion is an input literal of some transition, each once, in
/// address order; the paper's example needs all eleven sensors but none
/// negated, and its criteria count the missing outputs.
#[test]
fn the_criteria_are_the_transitions_inputs_in_address_order() {
    let (_, program, _) = paper_with("criteria", Vec::new());
    let expected: Vec<Literal> = program
        .signals
        .inputs
        .iter()
        .filter(|s| matches!(s, Signal::Sensor { .. }))
        .map(|s| Literal::is(*s))
        .collect();
    assert_eq!(program.criteria, expected);
    let missing = program
        .signals
        .outputs
        .iter()
        .filter(|s| matches!(s, Signal::Missing(_)))
        .count();
    assert_eq!(missing, 11);
    // The watchdog alone has none of it.
    let (_, plain, _) = paper_with("watchdog", Vec::new());
    assert!(plain.criteria.is_empty());
    assert!(
        plain
            .signals
            .outputs
            .iter()
            .all(|s| !matches!(s, Signal::Missing(_)))
    );
}

/// The fault table with the criteria analysis: its outcomes are the
/// watchdog's alone (the analysis only reports), and every sensor open
/// circuit the watchdog catches names that sensor, and only it, missing.
#[test]
fn the_fault_table_names_the_missing_sensor_of_every_stall_it_catches() {
    let with = Build::paper().safety("criteria".parse().unwrap()).faults();
    let plain = Build::paper().safety("watchdog".parse().unwrap()).faults();
    let outcomes = |t: &steptable::faults::FaultTable| -> Vec<_> {
        t.cases
            .iter()
            .map(|c| (c.outcome, c.step, c.detected))
            .collect()
    };
    assert_eq!(outcomes(&with), outcomes(&plain));
    let mut named = 0;
    for case in &with.cases {
        let fault = case.faults[0];
        let Signal::Sensor { .. } = fault.signal else {
            continue;
        };
        if fault.stuck_at || !case.detected {
            continue;
        }
        let symbol = fault.signal.symbol();
        let shown = case.explanation.split("missing: ").nth(1).unwrap_or("");
        let shown = shown.split(')').next().unwrap_or("");
        assert!(
            shown.ends_with(&format!("({symbol}")) && !shown.contains(','),
            "{}: {}",
            symbol,
            case.explanation
        );
        named += 1;
    }
    assert_eq!(named, 7, "the paper's watchdog catches seven dead sensors");
}

/// Every sample (jumps, waits, dwells, drives among them), with every
/// check, the criteria analysis and every mode: each transition, its own
/// or a jump, moves the awaited memories from the criteria of the
/// transition it leaves to exactly those of the one it makes the sequence
/// wait at; so after any path through the table only the awaited
/// transition's criteria are on.
#[test]
fn every_transition_leaves_exactly_the_awaited_criteria_on() {
    use steptable::program::Action;
    let awaited = |program: &StepProgram, index: usize| -> Vec<u16> {
        let mut on: Vec<u16> = match index {
            0 => Vec::new(),
            // A step single step lets fire only on a press waits for
            // "STEP_MODE off" too.
            _ => program.steps[index]
                .condition
                .iter()
                .map(|l| match *l == Literal::is(Signal::StepPermit) {
                    true => Literal::not(Signal::StepMode),
                    false => *l,
                })
                .filter_map(|l| program.criteria.iter().position(|c| *c == l))
                .map(|n| n as u16 + 1)
                .collect(),
        };
        on.sort_unstable();
        on.dedup();
        on
    };
    let after = |from: Vec<u16>, actions: &[Action]| -> Vec<u16> {
        let mut on = from;
        for action in actions {
            match action {
                Action::Set(Signal::Awaited(n)) => on.push(*n),
                Action::Reset(Signal::Awaited(n)) => on.retain(|m| m != n),
                _ => {}
            }
        }
        on.sort_unstable();
        on.dedup();
        on
    };
    let mut jumps = 0;
    for entry in std::fs::read_dir(crate::helpers::root().join("samples")).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "xlsx") {
            continue;
        }
        let build = Build::path(&path)
            .safety("edge,precheck,plausibility,criteria".parse().unwrap())
            .modes("all");
        // The oven waits on its dwells alone: no input, no criterion.
        let program = build.program();
        let count = program.steps.len();
        for (i, step) in program.steps.iter().enumerate() {
            let own = after(awaited(&program, i), &step.actions);
            assert_eq!(own, awaited(&program, (i + 1) % count), "{path:?} {i}");
            for jump in &step.jumps {
                jumps += 1;
                let to = after(awaited(&program, i), &jump.actions);
                assert_eq!(to, awaited(&program, jump.next), "{path:?} {}", jump.title);
            }
        }
    }
    assert!(jumps > 0, "a sample has jumps");
}

/// A step that waits on a machine input is not timed (a part may take as
/// long as it takes) until it is given a supervision time: the press
/// station's step 1 waits for part_present, given 5 s late; untimed it
/// waits, supervised 3 s it raises the alarm with part_present missing.
#[test]
fn a_supervision_time_times_a_waiting_step() {
    let path = crate::helpers::sample("press_station.xlsx");
    let part = steptable::cell::Name::new("part_present").unwrap();
    let run = |times: &[(usize, u32)]| {
        let mut build = Build::path(&path).safety("criteria".parse().unwrap());
        build.settings.program.supervision = times.iter().copied().collect();
        build.settings.simulation.input_delays = [(part, 5_000)].into();
        let program = build.program();
        let simulation = build.settings.simulation.clone();
        let report = started(&build.table, &program, &simulation, 5_000);
        (program, report)
    };
    let (_, untimed) = run(&[]);
    assert!(!alarm_on(&untimed));
    let (program, timed) = run(&[(1, 3_000)]);
    assert!(alarm_on(&timed));
    assert_eq!(
        missing(&program, &timed),
        [Literal::is(Signal::MachineInput(part))]
    );
}

/// A scenario runs on long enough for the supervision it arms: a 12 s
/// supervision of step 4 with x32 stuck at 0 raises `alarm_wd` and names
/// x32 missing within `simulate`'s run. The run used to end a healthy
/// cycle and a second after the event, at 10.94 s, before the alarm at
/// 15.09 s, so the engineer saw a silent stall.
#[test]
fn a_scenario_lasts_until_the_supervision_it_arms_runs_out() {
    let out = crate::helpers::steptable()
        .arg("simulate")
        .arg(crate::helpers::sample("paper_example.csv"))
        .args(["--safety", "criteria", "--supervision", "4=12s"])
        .args(["--stick", "x32=0@step3"])
        .assert()
        .get_output()
        .stdout
        .clone();
    let out = String::from_utf8(out).unwrap();
    let alarm = out
        .lines()
        .find(|l| l.contains("alarm_wd on"))
        .unwrap_or_else(|| panic!("the alarm within the run: {out}"));
    assert!(alarm.trim_start().starts_with("15.09 s"), "{alarm}");
    let last = out.lines().last().unwrap();
    assert!(
        last.contains("in step 4") && last.contains("miss"),
        "{last}"
    );
}
