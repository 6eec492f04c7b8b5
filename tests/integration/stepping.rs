//! The event-driven simulator against the scan-by-scan reference: the same
//! report (every problem at the same scan, every step timing, every point
//! of the position trace) on every sample under every fault and pair of
//! faults, and on random tables with dwells, waits, machine outputs, every
//! valve type and scan time.

use steptable::actuator::ActuatorKind;
use steptable::convert::{Checked, build_program, check_path};
use steptable::faults::{Outcome, fault_sets, judge};
use steptable::program::{self, ProgramOptions, Safety, StepProgram};
use steptable::random_table::{Shape, SplitMix64, random_rows};
use steptable::settings::Settings;
use steptable::simulate::{ProblemKind, SimSettings, Stepping, simulate_stepping};
use steptable::stroke::Stroke;
use steptable::table::StepTable;

use crate::helpers::samples;

/// Runs both ways; on a difference, names the first field that differs.
fn assert_same_run(what: &str, table: &StepTable, program: &StepProgram, settings: &SimSettings) {
    let events = simulate_stepping(table, program, settings, Stepping::Events);
    let scans = simulate_stepping(table, program, settings, Stepping::EveryScan);
    if events == scans {
        return;
    }
    assert_eq!(events.problems, scans.problems, "{what}: problems");
    assert_eq!(events.cycles, scans.cycles, "{what}: cycles");
    assert_eq!(events.spans, scans.spans, "{what}: dwells and waits");
    assert_eq!(events.trace, scans.trace, "{what}: position trace");
    assert_eq!(events, scans, "{what}");
}

/// A run that stops at its first hazard reaches the verdict the whole run
/// reaches (the same first hazard, or the same stall and its reason), with
/// the collision check on as the fault analysis runs it.
fn assert_same_verdict(
    what: &str,
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
) {
    let healthy = SimSettings {
        faults: Vec::new(),
        record_places: true,
        ..settings.clone()
    };
    let healthy = simulate_stepping(table, program, &healthy, Stepping::Events);
    let checked = SimSettings {
        known_places: Some(std::sync::Arc::new(healthy.places)),
        ..settings.clone()
    };
    let whole = simulate_stepping(table, program, &checked, Stepping::Events);
    let cut = SimSettings {
        stop_at_hazard: true,
        ..checked.clone()
    };
    let cut = simulate_stepping(table, program, &cut, Stepping::Events);
    assert_eq!(judge(&cut), judge(&whole), "{what}");
    if settings.faults.is_empty() {
        // A run is never a collision risk against itself.
        let collisions = whole
            .problems
            .iter()
            .filter(|p| p.kind == ProblemKind::Collision);
        assert_eq!(collisions.count(), 0, "{what}");
        if whole.passed {
            assert_eq!(
                judge(&whole).0,
                Outcome::NoEffect,
                "{what}: the healthy run"
            );
        }
    }
    // And both steppings see the same collisions.
    let scans = simulate_stepping(table, program, &checked, Stepping::EveryScan);
    assert_eq!(whole.problems, scans.problems, "{what}");
}

fn checked(path: &std::path::Path, settings: &Settings) -> Checked {
    match check_path(path, settings) {
        Ok(checked) => checked,
        Err(diags) => panic!("{}: {diags:?}", path.display()),
    }
}

#[test]
fn both_simulators_agree_on_every_sample_under_every_fault() {
    for path in samples() {
        for safety in [Safety::default(), Safety::all()] {
            let mut settings = Settings::default();
            settings.program.safety = safety;
            let checked = checked(&path, &settings);
            let program = build_program(&checked.table, &checked.settings);
            let sim = SimSettings {
                record_trace: true,
                ..checked.settings.simulation.clone()
            };
            // Pairs on the paper's example only: the samples' singles cover
            // every kind of signal, the pairs add faults that meet.
            let pairs = path.ends_with("paper_example.xlsx") && safety == Safety::default();
            let mut sets = fault_sets(&program, if pairs { 2 } else { 1 });
            sets.insert(0, Vec::new());
            for faults in sets {
                let run = SimSettings {
                    faults: faults.clone(),
                    ..sim.clone()
                };
                let what = format!("{} {safety:?} {faults:?}", path.display());
                assert_same_run(&what, &checked.table, &program, &run);
                assert_same_verdict(&what, &checked.table, &program, &run);
            }
        }
    }
}

/// A random table with dwells, waits and machine outputs added to some
/// steps, and random plant settings.
/// A random table with its program and the plant it runs: valves
/// centred where a middle stop needs them, 5/2 ones (bistable or spring
/// return), vacuum grippers or swivel drives elsewhere, or electric
/// drives, by the dice.
pub(crate) fn random_machine(seed: u64) -> (Vec<Vec<String>>, StepTable, StepProgram, SimSettings) {
    let (rows, mut sim, options) = random_case(seed);
    let Ok(table) = steptable::table::from_rows("random.csv", &rows) else {
        panic!("seed {seed}: the generator made an invalid table: {rows:?}");
    };
    let mut rng = SplitMix64::new(seed);
    for a in &table.actuators {
        let choice = rng.range(0, 5) as usize;
        let valve = if a.max_position > 1 {
            [
                ActuatorKind::Closed53,
                ActuatorKind::Exhaust53,
                ActuatorKind::Pressure53,
                ActuatorKind::Motor,
            ][choice % 4]
        } else {
            // A two-position actuator may also be a vacuum gripper or a
            // swivel drive.
            [
                ActuatorKind::Bistable52,
                ActuatorKind::Mono52,
                ActuatorKind::Closed53,
                ActuatorKind::Motor,
                ActuatorKind::Vacuum,
                ActuatorKind::Swivel,
            ][choice]
        };
        sim.machine.valves.per_actuator.insert(a.number, valve);
    }
    let program = program::build(&table, &options, &sim.machine.valves, &sim.machine.strokes);
    (rows, table, program, sim)
}

fn random_case(seed: u64) -> (Vec<Vec<String>>, SimSettings, ProgramOptions) {
    let mut rng = SplitMix64::new(seed ^ 0x5eed);
    let shape = Shape {
        actuators: rng.range(1, 5),
        max_position: rng.range(1, 3),
        branches: rng.range(1, 3),
        steps: rng.range(2, 10),
    };
    let mut rows = random_rows(seed, shape);
    let mut lamp_on = false;
    let last = rows.len() - 1;
    for (i, row) in rows.iter_mut().enumerate() {
        match rng.range(0, 5) {
            0 => row[0].push_str(&format!("; T={}ms", rng.range(1, 80) * 10)),
            1 => row.push(format!("I:in{}", rng.range(1, 2))),
            2 if !lamp_on && i < last => {
                row.push("Y:lamp+".to_string());
                lamp_on = true;
            }
            _ => {}
        }
    }
    if lamp_on {
        rows[last].push("Y:lamp-".to_string());
    }
    steptable::random_table::add_jumps(seed, &mut rows);
    let mut sim = SimSettings {
        scan_ms: [1, 3, 10, 25][rng.range(0, 3) as usize],
        window: [0.02, 0.05, 0.1][rng.range(0, 2) as usize],
        cycles: rng.range(1, 3) as usize,
        record_trace: true,
        ..SimSettings::default()
    };
    for a in 1..=shape.actuators {
        sim.machine.strokes.per_actuator.insert(
            a,
            Stroke {
                extend_ms: rng.range(1, 300) * 10,
                retract_ms: rng.range(1, 300) * 10,
            },
        );
        sim.machine.loads.insert(a, rng.range(0, 20) as f64 / 100.0);
    }
    sim.input_delays.insert(
        steptable::cell::Name::new("in1").expect("name"),
        rng.range(0, 100) * 10,
    );
    let options = ProgramOptions {
        safety: if rng.range(0, 1) == 0 {
            Safety::default()
        } else {
            Safety::all()
        },
        ..ProgramOptions::default()
    };
    (rows, sim, options)
}

#[test]
fn both_simulators_agree_on_random_tables_and_faults() {
    let mut compared = 0;
    let mut with_jumps = 0;
    for seed in 0..1000u64 {
        let (rows, table, program, sim) = random_machine(seed);
        with_jumps += usize::from(table.steps.iter().any(|s| !s.jumps.is_empty()));
        // The dice go on where the valves' left off.
        let mut rng = SplitMix64::new(seed);
        for _ in &table.actuators {
            rng.range(0, 2);
        }
        let healthy = format!("seed {seed} {rows:?}");
        assert_same_run(&healthy, &table, &program, &sim);
        assert_same_verdict(&healthy, &table, &program, &sim);
        // One random fault and one random pair.
        let singles = fault_sets(&program, 1);
        let pairs = fault_sets(&program, 2);
        for sets in [&singles, &pairs] {
            let faults = sets[rng.range(0, sets.len() as u32 - 1) as usize].clone();
            // From power-up, or appearing at any moment of the first cycles
            // (not only on a scan's tick).
            let onset = match rng.range(0, 1) {
                0 => 0,
                _ => rng.range(1, 12_000) as u64,
            };
            let run = SimSettings {
                faults: faults.clone(),
                fault_onset_ms: onset,
                ..sim.clone()
            };
            let what = format!("{healthy} {faults:?} from {onset} ms");
            assert_same_run(&what, &table, &program, &run);
            assert_same_verdict(&what, &table, &program, &run);
        }
        compared += 3;
    }
    assert_eq!(compared, 3000);
    // Jumps on inputs are among them (about a third of the tables).
    assert!(with_jumps >= 200, "{with_jumps} tables with jumps");
}
