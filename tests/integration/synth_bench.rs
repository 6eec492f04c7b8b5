//! Synthesised controllers are proven on the shared simulation, not on a
//! model of their own: the bench (`simulate::bench`) moves the machine as
//! the step program's proof does, scan for scan; on it, a synthesised
//! controller and the converted program of the same table drive the
//! machine through the same moves (on the same scans when no memory is
//! needed); and a wrong equation fails the proof. Should synthesis verify
//! against a plant or a scan loop that drifts from the one converted
//! programs run on, one of these fails.

use steptable::actuator::Valves;
use steptable::cell::Sign;
use steptable::program::{Modes, ProgramOptions, Signal, StepProgram, build};
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

/// What a controller makes of the operator's buttons on `table`'s machine,
/// scripted by what the machine does (a memory costs the synthesised
/// controller a scan, so the script waits for sensors, not for times).
#[derive(Debug)]
struct Reactions {
    /// The sensors that came on from START (CONTINUOUS on) with STOP
    /// pressed once the first move ended, until the machine rested.
    stopped_cycle: Vec<Signal>,
    /// The coils on in the scan EMERGENCY STOP was pressed in.
    coils_at_estop: Vec<Signal>,
    /// The machine, at rest, moved on a START after an EMERGENCY STOP was
    /// pressed and released (and before RESET).
    started_while_halted: bool,
    /// The scans after RESET at which each home sensor came on.
    homed_at: Vec<(usize, Signal)>,
    /// The first sensor a START after the homing switched on.
    restarted_with: Option<Signal>,
}

/// A scripted operator on the bench, recording the sensors that come on.
struct Operated<'c> {
    bench: Bench,
    controller: &'c mut dyn Controller,
    sensors: Vec<Signal>,
    on: Vec<bool>,
}

impl Operated<'_> {
    /// One scan with `operator`'s buttons: the sensors that came on.
    fn scan(&mut self, operator: Operator) -> Vec<Signal> {
        self.bench.press(operator);
        self.bench.scan(self.controller).unwrap();
        let mut came = Vec::new();
        for (was, sensor) in self.on.iter_mut().zip(&self.sensors) {
            let now = self.bench.input(*sensor);
            if now && !*was {
                came.push(*sensor);
            }
            *was = now;
        }
        came
    }

    /// `scans` scans with `operator`'s buttons: the sensors that came on.
    fn hold(&mut self, operator: Operator, scans: usize) -> Vec<(usize, Signal)> {
        (0..scans)
            .flat_map(|k| self.scan(operator).into_iter().map(move |s| (k, s)))
            .collect()
    }
}

fn reactions(table: &StepTable, controller: &mut dyn Controller) -> Reactions {
    let bench = Bench::for_table(table, &SimSettings::default());
    let sensors: Vec<Signal> = table
        .actuators
        .iter()
        .flat_map(|a| {
            [0, 1].map(|position| Signal::Sensor {
                actuator: a.number,
                position,
            })
        })
        .collect();
    let on = sensors.iter().map(|s| bench.input(*s)).collect();
    let mut m = Operated {
        bench,
        controller,
        sensors,
        on,
    };
    let idle = Operator {
        continuous: true,
        ..Operator::default()
    };
    let start = Operator {
        start: true,
        ..idle
    };
    let stop = Operator { stop: true, ..idle };
    let estop = Operator {
        estop: true,
        ..idle
    };
    let reset = Operator {
        reset: true,
        ..idle
    };
    // STOP pressed once the first move has ended: the cycle goes on to
    // its end, and no other starts.
    let mut stopped_cycle = m.scan(start);
    while stopped_cycle.is_empty() {
        stopped_cycle = m.scan(idle);
    }
    stopped_cycle.extend(m.hold(stop, 5).into_iter().map(|(_, s)| s));
    stopped_cycle.extend(m.hold(idle, 3000).into_iter().map(|(_, s)| s));
    // EMERGENCY STOP at rest, released: START does not start a halted
    // machine; RESET then lets it.
    m.hold(estop, 10);
    m.hold(idle, 10);
    let before = m.bench.positions();
    m.scan(start);
    m.hold(idle, 500);
    let started_while_halted = m.bench.positions() != before;
    m.hold(reset, 5);
    m.hold(idle, 100);
    // EMERGENCY STOP while the cycle's second move runs.
    let mut came = m.scan(start);
    while came.is_empty() {
        came = m.scan(idle);
    }
    m.hold(idle, 20);
    m.scan(estop);
    let coils_at_estop = table
        .actuators
        .iter()
        .flat_map(|a| {
            [Sign::Plus, Sign::Minus].map(|sign| Signal::Coil {
                actuator: a.number,
                sign,
            })
        })
        .filter(|c| m.controller.output(*c))
        .collect();
    // Held until the pistons its valves kept going have stopped.
    m.hold(estop, 1000);
    m.hold(idle, 10);
    // RESET: home.
    let mut homed_at = m.hold(reset, 5);
    homed_at.extend(m.hold(idle, 3000).into_iter().map(|(k, s)| (k + 5, s)));
    let restarted_with = m
        .scan(start)
        .into_iter()
        .chain(m.hold(stop, 3000).into_iter().map(|(_, s)| s))
        .next();
    Reactions {
        stopped_cycle,
        coils_at_estop,
        started_while_halted,
        homed_at,
        restarted_with,
    }
}

/// The claims of docs/synthesis.md ("What differs from a converted
/// program"), held on one machine: a synthesised controller and the
/// converted program of the same sequence with `--modes all`
/// (CONTINUOUS on) react alike to STOP (the cycle under way ends, no other
/// starts), EMERGENCY STOP (every coil off in the scan it is pressed in,
/// START refused until RESET) and RESET (the machine home, START starts
/// the cycle again); they differ where the text says: RESET homes the
/// converted program's actuators stage by stage in the home order, the
/// synthesised controller's all at once.
#[test]
fn a_synthesised_controller_reacts_to_the_buttons_as_the_converted_program_does() {
    let cells = ["C1+1", "C2+1", "C1-0", "C2-0"];
    let table = table(&cells);
    let options = ProgramOptions {
        modes: Modes::parse("all").unwrap(),
        ..ProgramOptions::default()
    };
    let program = build(&table, &options, &Valves::default(), &Strokes::default());
    let code = PlcProgram::compile(&program);
    let s = synth::synthesize(&synth::from_table(&table).unwrap()).unwrap();
    let converted = reactions(&table, &mut PlcState::new(&code));
    let synthesised = reactions(&table, &mut OnMachine::new(&s));
    let sensor = |actuator, position| Signal::Sensor { actuator, position };
    let cycle = vec![sensor(1, 1), sensor(2, 1), sensor(1, 0), sensor(2, 0)];
    for r in [&converted, &synthesised] {
        assert_eq!(r.stopped_cycle, cycle, "{r:?}");
        assert_eq!(r.coils_at_estop, [], "{r:?}");
        assert!(!r.started_while_halted, "{r:?}");
        assert_eq!(r.restarted_with, Some(sensor(1, 1)), "{r:?}");
    }
    // The ESTOP came while C2 extended; its valve kept it going: both out
    // when RESET comes. The converted program homes C1, then C2 (the
    // order the cycle brings them home); the synthesised both at once.
    let homes = |r: &Reactions| -> Vec<Signal> { r.homed_at.iter().map(|(_, s)| *s).collect() };
    assert_eq!(homes(&converted), [sensor(1, 0), sensor(2, 0)]);
    assert_eq!(homes(&synthesised), [sensor(1, 0), sensor(2, 0)]);
    let (c1, c2) = (converted.homed_at[0].0, converted.homed_at[1].0);
    assert!(c2 > c1 + 10, "converted homed in one stage: {converted:?}");
    assert_eq!(
        synthesised.homed_at[0].0, synthesised.homed_at[1].0,
        "{synthesised:?}"
    );
}
