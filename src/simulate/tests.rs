use super::*;
use crate::program::{self, ProgramOptions, Signal};
use crate::stroke::Stroke;

fn run(rows: &[Vec<&str>], options: ProgramOptions, settings: &SimSettings) -> SimReport {
    let table = crate::table::from_rows("t.csv", rows).expect("valid table");
    let program = program::build(
        &table,
        &options,
        &settings.machine.valves,
        &settings.machine.strokes,
    );
    simulate(&table, &program, settings)
}

/// The paper's example, as rows of cells.
fn paper() -> Vec<Vec<&'static str>> {
    crate::template_workbook::PAPER_EXAMPLE
        .iter()
        .map(|r| r.to_vec())
        .collect()
}

#[test]
fn the_papers_program_runs_two_identical_cycles() {
    let report = run(&paper(), ProgramOptions::default(), &SimSettings::default());
    assert!(report.passed, "{}: {:?}", report.verdict(), report.problems);
    assert_eq!(report.cycles.len(), 2);
    assert_eq!(report.cycles[0].steps.len(), 8);
    let ms = report.cycles[0].cycle_ms.unwrap();
    // 8 steps: C1 1 s, C2 1 s, C2 2/3 s, C3 1 s, C3 1 s, C3 0.5 s, C2 2/3 s and C3 0.5 s … ≈ 7–8 s
    assert!((6_000..10_000).contains(&ms), "{ms}");
    // Positions at the step boundaries: C2 stands at 2 after step 4.
    let c2 = report.actuators.iter().position(|a| a.0 == 2).unwrap();
    assert!(
        (report.step_positions[4][c2] - 2.0).abs() < 0.1,
        "{:?}",
        report.step_positions[4]
    );
}

#[test]
fn without_middle_stops_the_paper_hangs_in_step_5() {
    let report = run(
        &paper(),
        ProgramOptions {
            middle_stops: false,
            ..ProgramOptions::default()
        },
        &SimSettings::default(),
    );
    assert!(!report.passed);
    // Stalled in step 4 (C2's move never ends), waiting for step 5.
    assert_eq!(report.stalled_at, Some(4));
    assert_eq!(
        report.reason(),
        "step 5 never fires: waiting for x22; C2 ran through x22 to x23 in step 4"
    );
}

#[test]
fn a_stuck_sensor_stalls_or_endangers() {
    let open = SimSettings {
        faults: vec![Fault {
            signal: Signal::Sensor {
                actuator: 1,
                position: 1,
            },
            stuck_at: false,
        }],
        ..SimSettings::default()
    };
    let report = run(&paper(), ProgramOptions::default(), &open);
    // In step 1 (C1+ never reaches x11), waiting for step 2.
    assert_eq!(report.stalled_at, Some(1));
    assert!(report.hazard().is_none(), "{:?}", report.problems);

    let short = SimSettings {
        faults: vec![Fault {
            signal: Signal::Sensor {
                actuator: 1,
                position: 1,
            },
            stuck_at: true,
        }],
        ..SimSettings::default()
    };
    let report = run(&paper(), ProgramOptions::default(), &short);
    let hazard = report.hazard().expect("a hazard");
    assert_eq!(hazard.kind, ProblemKind::Premature, "{:?}", report.problems);
}

#[test]
fn slow_strokes_change_the_cycle_time() {
    let mut slow = SimSettings::default();
    slow.machine.strokes.per_actuator.insert(
        1,
        Stroke {
            extend_ms: 3000,
            retract_ms: 500,
        },
    );
    let fast = run(&paper(), ProgramOptions::default(), &SimSettings::default());
    let report = run(&paper(), ProgramOptions::default(), &slow);
    assert!(report.passed, "{:?}", report.problems);
    let delta = report.cycles[0].cycle_ms.unwrap() as i64 - fast.cycles[0].cycle_ms.unwrap() as i64;
    assert!((1400..=1600).contains(&delta), "{delta}");
}

#[test]
fn sixty_three_positions_on_one_cylinder_pass_with_every_check() {
    // Sensors 1/63 of the stroke apart: their windows must not overlap, or
    // the plausibility check would see two at once.
    let rows = vec![vec!["C1+63"], vec!["C1-31"], vec!["C1+32"], vec!["C1-0"]];
    let options = ProgramOptions {
        safety: crate::program::Safety::all(),
        ..ProgramOptions::default()
    };
    let report = run(&rows, options, &SimSettings::default());
    assert!(report.passed, "{}", report.verdict());
}

/// A closing step fires on the home sensor while the last stroke still runs
/// into its end stop; a long stroke took longer than the idle between two
/// START presses, so the second cycle began from a moving piston and its
/// timing differed (reported as a bug in steptable).
#[test]
fn a_long_last_stroke_ends_before_the_next_start_with_every_closing_step() {
    let rows = vec![vec!["C1+1"], vec!["C1-0"]];
    for retract_ms in [20_000, 26_000, 40_000] {
        let mut settings = SimSettings::default();
        settings.machine.strokes.per_actuator.insert(
            1,
            Stroke {
                extend_ms: 1000,
                retract_ms,
            },
        );
        for options in [
            ProgramOptions {
                safety: crate::program::Safety::all(),
                ..ProgramOptions::default()
            },
            ProgramOptions {
                modes: crate::program::Modes::parse("all").unwrap(),
                ..ProgramOptions::default()
            },
        ] {
            let report = run(&rows, options, &settings);
            assert!(report.passed, "{retract_ms} ms: {}", report.verdict());
            // The cycle lasts until the piston is home: 98 % of the extend
            // stroke to reach x11, then the whole way back.
            let cycle = report.cycles[0].cycle_ms.unwrap();
            assert!(
                cycle >= u64::from(980 + retract_ms * 98 / 100),
                "{retract_ms} ms: {cycle}"
            );
        }
    }
}

/// The I/O recorded for the engines' replays is the same, scan for scan,
/// whether the run jumps over quiet scans or steps through each; and the
/// log of the inputs' changes agrees with it.
#[test]
fn the_recorded_io_is_the_same_both_ways() {
    let dwells_and_waits: Vec<Vec<&str>> = vec![
        vec!["C1+1; T=300ms", "I:part_present"],
        vec!["C2+2", "Y:vacuum+"],
        vec!["C2-0; T=50ms", "Y:vacuum-"],
        vec!["C1-0"],
    ];
    for (rows, options) in [
        (paper(), ProgramOptions::default()),
        (
            paper(),
            ProgramOptions {
                safety: crate::program::Safety::all(),
                ..ProgramOptions::default()
            },
        ),
        (dwells_and_waits, ProgramOptions::default()),
    ] {
        let table = crate::table::from_rows("t.csv", &rows).expect("valid table");
        let settings = SimSettings::default();
        let program = program::build(
            &table,
            &options,
            &settings.machine.valves,
            &settings.machine.strokes,
        );
        let signals = io::IoSignals {
            inputs: program.signals.inputs.clone(),
            outputs: program.signals.driven().collect(),
            max_scans: None,
        };
        let code = plc::PlcProgram::compile(&program);
        let record = |stepping| {
            run::run(
                &table,
                &program,
                &code,
                &settings,
                Some(signals.clone()),
                stepping,
            )
        };
        let (events, events_io) = record(Stepping::Events);
        let (scans, scans_io) = record(Stepping::EveryScan);
        assert!(events.passed, "{:?}", events.problems);
        assert_eq!(events, scans);
        let (events_io, scans_io) = (events_io.expect("recorded"), scans_io.expect("recorded"));
        assert!(scans_io.scans.len() > 500, "{}", scans_io.scans.len());
        assert_eq!(events_io, scans_io);
        // The fault analysis's log of the inputs' changes says what the
        // recording of every scan says.
        let logging = |stepping| {
            let inputs = Some(signals.inputs.clone());
            run::run_logging_inputs(&table, &program, &code, &settings, inputs, None, stepping)
        };
        let (logged, log, _) = logging(Stepping::Events);
        let log = log.expect("logged");
        assert_eq!(logged, events);
        assert!(log.same_inputs(&io::InputLog::of_trace(&scans_io)));
        assert!(log.changes.iter().any(|(_, c)| c.len() > 1), "{log:?}");
        // Every scan an input is read on, stepped one by one, lies in a
        // span the run passing quiet scans at once logged as read: a fault
        // of that input is read there (and nowhere else).
        let every_scan = logging(Stepping::EveryScan).1.expect("logged");
        assert!(every_scan.same_inputs(&log));
        for (k, spans) in every_scan.reads.iter().enumerate() {
            assert!(!spans.is_empty() || log.reads[k].is_empty());
            for &(from, to) in spans {
                for at in (from..to).step_by(settings.scan_ms as usize) {
                    let covered = log.reads[k].iter().any(|&(f, t)| f <= at && at < t);
                    assert!(covered, "{}: read at {at} ms", signals.inputs[k].symbol());
                }
            }
        }
        assert!(log.reads.iter().any(|r| !r.is_empty()));
    }
}

/// A jump back on an input stuck on loops for ever: the run stops after
/// a bounded number of steps and says so, rather than running on.
#[test]
fn a_jump_back_that_never_ends_stops_the_run() {
    let rows = vec![
        vec!["C1+1"],
        vec!["C2+1"],
        vec!["C2-0; J:2 if I:not_gripped"],
        vec!["C1-0"],
    ];
    let input = crate::cell::Name::new("not_gripped").unwrap();
    let settings = SimSettings {
        faults: vec![Fault {
            signal: Signal::MachineInput(input),
            stuck_at: true,
        }],
        ..SimSettings::default()
    };
    let report = run(&rows, ProgramOptions::default(), &settings);
    assert!(!report.passed);
    let stall = report
        .problems
        .iter()
        .find(|p| p.kind == ProblemKind::Stall)
        .expect("the loop is cut");
    assert_eq!(
        stall.message,
        "the cycle never ends: 26 steps have fired, jumping back again and again"
    );
    // The jump itself, taken on a faulty input, is the hazard.
    assert!(
        report
            .problems
            .iter()
            .any(|p| p.kind == ProblemKind::Premature
                && p.message.contains("took J:2 if I:not_gripped after step 3"))
    );
}

/// A resumed run hands the runs after it only the states it passed through
/// once its faults had appeared and before it found anything: a later run
/// standing there ends as it did, which would be wrong for a state reached
/// with a collision already found, or one the faults had not yet reached.
#[test]
fn a_resumed_run_hands_on_only_the_states_before_its_first_finding() {
    let table = crate::table::from_rows("t.csv", &paper()).expect("valid table");
    let healthy_settings = SimSettings {
        record_places: true,
        ..SimSettings::default()
    };
    let program = program::build(
        &table,
        &ProgramOptions::default(),
        &healthy_settings.machine.valves,
        &healthy_settings.machine.strokes,
    );
    let simulator = Simulator::new(&table, &program);
    let healthy = simulator.run(&healthy_settings);
    // x21 opens while step 4 moves C2 away from it: a collision risk, and
    // the run goes on to a stall.
    let cycle = &healthy.cycles[0];
    let onset = cycle.press_ms + cycle.steps[3].start_ms + u64::from(healthy_settings.scan_ms);
    let settings = SimSettings {
        faults: vec![Fault {
            signal: Signal::Sensor {
                actuator: 2,
                position: 1,
            },
            stuck_at: false,
        }],
        fault_onset_ms: onset,
        stop_at_hazard: true,
        known_places: Some(std::sync::Arc::new(healthy.places.clone())),
        ..SimSettings::default()
    };
    let never_in_step = |_| false;
    // States kept at every scan.
    let every_scan: Vec<u64> = (0..2_000).map(|k| k * 10).collect();
    // From the checkpoint at the onset, and from power-up (no checkpoint).
    for times in [vec![onset], vec![]] {
        let checkpoints = simulator.checkpoints(&healthy_settings, &times, None, false);
        let course = Course {
            checkpoints: &checkpoints,
            in_step: &never_in_step,
            trail: &Trail::default(),
            marks: &every_scan,
        };
        let mut passed = Vec::new();
        let Resumed::Report(report) = simulator.resume(&course, &settings, &mut passed) else {
            panic!("nothing to stop at");
        };
        // What a run from power-up finds (the diagram's positions are left
        // out of a copy).
        assert_eq!(report.problems, simulator.run(&settings).problems);
        let first = &report.problems[0];
        assert!(
            report
                .problems
                .iter()
                .any(|p| p.kind == ProblemKind::Collision && p.time_ms == first.time_ms),
            "{:?}",
            report.problems
        );
        // In step 5, waiting for step 6.
        assert_eq!(report.stalled_at, Some(5), "{:?}", report.problems);
        assert!(!passed.is_empty());
        assert!(
            passed
                .iter()
                .all(|(at, _)| (onset..=first.time_ms).contains(at)),
            "{onset}..={}: {passed:?}",
            first.time_ms
        );
        // The same faults appearing then, on that trail, end as that run.
        let trail: Trail = passed.iter().map(|point| (*point, 7)).collect();
        let course = Course {
            trail: &trail,
            ..course
        };
        let mut again = Vec::new();
        let joined = simulator.resume(&course, &settings, &mut again);
        assert!(matches!(joined, Resumed::Joined { run: 7 }), "{joined:?}");
        assert!(again.is_empty());
    }
}
