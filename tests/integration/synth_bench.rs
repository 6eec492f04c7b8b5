//! Synthesised controllers are proven on the shared simulation, not on a
//! model of their own: the bench (`simulate::bench`) moves the machine as
//! the step program's proof does, scan for scan; on it, a synthesised
//! controller and the converted program of the same table drive the
//! machine through the same moves (on the same scans when no memory is
//! needed); and a wrong equation fails the proof. Should synthesis verify
//! against a plant or a scan loop that drifts from the one converted
//! programs run on, one of these fails.

use steptable::actuator::Valves;
use steptable::program::{ProgramOptions, Signal, StepProgram, build};
use steptable::simulate::bench::{Bench, Controller};
use steptable::simulate::plc::{PlcProgram, PlcState};
use steptable::simulate::scenario::scenario;
use steptable::simulate::{Operator, SimSettings};
use steptable::stroke::Strokes;
use steptable::synth::controller::OnMachine;
use steptable::synth::equations::Expr;
use steptable::synth::{self, verify};
use steptable::table::{StepTable, from_rows};

fn table(cells: &[&str]) -> StepTable {
    let rows: Vec<[&str; 1]> = cells.iter().map(|c| [*c]).collect();
    from_rows("bench.csv", &rows).expect("a valid table")
}

fn program(table: &StepTable) -> StepProgram {
    build(
        table,
        &ProgramOptions::default(),
        &Valves::default(),
        &Strokes::default(),
    )
}

/// START pressed for the first scan only.
fn press_start_once(bench: &mut Bench) {
    bench.press(Operator {
        start: bench.time_ms() == 0,
        ..Operator::default()
    });
}

/// What `controller` does to `table`'s machine in `scans` scans from one
/// START: every sensor that switched on, at its scan, and every scan's
/// positions.
fn on_bench(
    table: &StepTable,
    controller: &mut dyn Controller,
    scans: usize,
) -> (Vec<(usize, Signal)>, Vec<Vec<f64>>) {
    let mut bench = Bench::for_table(table, &SimSettings::default());
    let sensors: Vec<Signal> = table
        .actuators
        .iter()
        .flat_map(|a| {
            (0..=a.max_position).map(|position| Signal::Sensor {
                actuator: a.number,
                position,
            })
        })
        .collect();
    let mut on: Vec<bool> = sensors.iter().map(|s| bench.input(*s)).collect();
    let mut events = Vec::new();
    let mut positions = Vec::new();
    for scan in 0..scans {
        press_start_once(&mut bench);
        let conflicts = bench.scan(controller).unwrap();
        assert!(
            conflicts.is_empty(),
            "scan {scan}: both coils of {conflicts:?}"
        );
        for (was, sensor) in on.iter_mut().zip(&sensors) {
            let now = bench.input(*sensor);
            if now && !*was {
                events.push((scan, *sensor));
            }
            *was = now;
        }
        positions.push(bench.positions());
    }
    (events, positions)
}

/// The bench is the proof's scan loop: the paper's table (middle stops on
/// 5/3 valves, parallel moves) converted and run on it stands, scan for
/// scan, where the step program's scripted run (`scenario`, the run every
/// proof and fault analysis makes) has it.
#[test]
fn the_bench_moves_the_machine_as_the_proof_of_a_converted_program_does() {
    let table = from_rows("paper.csv", &steptable::template_workbook::PAPER_EXAMPLE).unwrap();
    let program = program(&table);
    let code = PlcProgram::compile(&program);
    let settings = SimSettings::default();
    let scans = 3000;
    let script = [
        (
            0,
            Operator {
                start: true,
                ..Operator::default()
            },
        ),
        (settings.scan_ms as u64, Operator::default()),
    ];
    let proof = scenario(&table, &program, &settings, &script, scans as u64 * 10);
    let (events, positions) = on_bench(&table, &mut PlcState::new(&code), scans);
    let proof_positions: Vec<Vec<f64>> =
        proof.samples.iter().map(|s| s.positions.clone()).collect();
    assert_eq!(positions, proof_positions);
    // And the cycle did run: every step fired, C1 came home last.
    assert_eq!(proof.fired.len(), program.steps.len());
    assert!(events.len() > table.steps.len(), "{events:?}");
}

/// A synthesised controller and the converted program of one table on one
/// machine: the same moves in the same order; with no memory, each on the
/// same scan, the machine at the same place at every scan of the cycle (a
/// memory costs the synthesised controller one scan where it is set).
#[test]
fn a_synthesised_controller_moves_the_machine_as_the_converted_program_does() {
    for (cells, memories) in [
        (&["C1+1", "C2+1", "C1-0", "C2-0"][..], 0),
        (&["C1+1", "C1-0", "C2+1", "C2-0"][..], 1),
        (&["C1+1", "C2+1", "C3+1", "C3-0", "C2-0", "C1-0"][..], 1),
    ] {
        let table = table(cells);
        let program = program(&table);
        let code = PlcProgram::compile(&program);
        let s = synth::synthesize(&synth::from_table(&table).unwrap()).unwrap();
        assert_eq!(s.modified.memories, memories, "{cells:?}");
        let scans = 300 * cells.len();
        let (converted, converted_at) = on_bench(&table, &mut PlcState::new(&code), scans);
        let (synthesised, synthesised_at) = on_bench(&table, &mut OnMachine::new(&s), scans);
        // One cycle: the converted program waits for the next START, the
        // synthesised one cycles on until STOP.
        let cycle = converted.len();
        assert!(cycle >= cells.len(), "{cells:?}: {converted:?}");
        let sensors = |events: &[(usize, Signal)]| -> Vec<Signal> {
            events.iter().take(cycle).map(|(_, s)| *s).collect()
        };
        assert_eq!(sensors(&synthesised), sensors(&converted), "{cells:?}");
        if memories == 0 {
            assert_eq!(&synthesised[..cycle], &converted[..], "{cells:?}");
            let end = converted[cycle - 1].0;
            assert_eq!(synthesised_at[..=end], converted_at[..=end], "{cells:?}");
        }
    }
}

/// A wrong equation does not pass: each equation of the classic, negated
/// in turn, fails the cycling proof and the mode proof on the bench.
#[test]
fn a_wrong_equation_fails_the_proof() {
    let s = synth::synthesize(&synth::sequence::parse("A1 A0 B1 B0").unwrap()).unwrap();
    assert!(verify::verify(&s, 2).passed);
    for k in 0..s.equations.len() {
        let mut wrong = s.clone();
        let e = &mut wrong.equations[k];
        e.expr = Expr::Not(Box::new(e.expr.clone()));
        let token = s.modified.token(e.action);
        let v = verify::verify(&wrong, 2);
        assert!(!v.passed, "{token} negated passed: {:?}", v.observed);
        assert!(v.modes.is_err(), "{token} negated passed the mode proof");
    }
}
