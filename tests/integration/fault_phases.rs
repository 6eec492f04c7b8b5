//! Faults that appear mid-cycle: the analysis runs each fault set once per
//! distinct moment it makes a difference (moments at which the faulty input
//! reads as the healthy one are merged, faults that never differ are not
//! run). Every verdict in the table must be what that fault alone, made to
//! appear at that moment, gives; and the healthy run is never anything but
//! a pass.

use steptable::convert::{build_program, check_path};
use steptable::faults::{self, FaultRuns, Outcome, judge};
use steptable::program::Safety;
use steptable::random_table::{Shape, SplitMix64, random_rows};
use steptable::settings::Settings;
use steptable::simulate::{SimSettings, simulate};

use crate::helpers::samples;
use crate::stepping::random_machine;

/// Resumed runs (from the healthy run's copy where the fault appears,
/// stopping once back in step) against runs from power-up to their end:
/// the same fault table, verdict for verdict.
fn assert_same_table(
    what: &str,
    table: &steptable::table::StepTable,
    program: &steptable::program::StepProgram,
    sim: &SimSettings,
    at_once: usize,
) -> faults::FaultTable {
    let run = |runs| faults::analyse_runs(table, program, sim, at_once, runs, &|_, _| {});
    let (resumed, reference) = (run(FaultRuns::Resumed), run(FaultRuns::FromPowerUp));
    for (a, b) in resumed.cases.iter().zip(&reference.cases) {
        assert_eq!(a, b, "{what}: {}", b.fault_text());
    }
    // The same table but for the runs made: resumed runs go from where a
    // faulty input is first read while it differs, and merge more.
    let made = |t: &faults::FaultTable| (t.moments.clone(), t.phases_skipped, t.equivalent);
    assert_eq!(resumed.cases, reference.cases, "{what}");
    assert_eq!(made(&resumed), made(&reference), "{what}");
    assert!(resumed.runs <= reference.runs, "{what}");
    resumed
}

#[test]
fn resumed_fault_runs_give_the_table_of_runs_from_power_up() {
    for path in samples() {
        for safety in [Safety::default(), Safety::all()] {
            let mut settings = Settings::default();
            settings.program.safety = safety;
            let checked = check_path(&path, &settings).expect("a sample converts");
            let program = build_program(&checked.table, &checked.settings);
            let pairs = path.ends_with("paper_example.xlsx");
            let what = format!("{} {safety:?}", path.display());
            let sim = &checked.settings.simulation;
            assert_same_table(&what, &checked.table, &program, sim, 1 + usize::from(pairs));
        }
    }
    let mut moments = 0;
    for seed in 0..200u64 {
        let (rows, table, program, mut sim) = random_machine(seed);
        sim.record_trace = false;
        let what = format!("seed {seed} {rows:?}");
        moments += assert_same_table(&what, &table, &program, &sim, 1)
            .moments
            .len();
    }
    assert!(moments > 1000, "{moments} moments");
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig { cases: 48, ..proptest::prelude::ProptestConfig::default() })]

    /// The fault table's file, byte for byte, whichever way its runs went:
    /// resumed from the healthy run and cut short where they rejoin it,
    /// measured against the proof's own healthy run (one simulation of the
    /// cycle per conversion), or each from power-up to its end.
    #[test]
    fn the_fault_table_file_is_the_same_however_its_runs_are_cut(seed in 0u64..1_000_000) {
        assert_cut_alike(seed)?;
    }
}

/// Seeds the property above once failed on: a healthy run with a hazard of
/// its own, whose copies carried it (and the alarms after it) into the
/// resumed runs, so that their table said `alarm` where none came.
#[test]
fn the_fault_table_is_the_same_however_cut_where_the_healthy_run_fails() {
    for seed in [314_496, 520_190] {
        if let Err(e) = assert_cut_alike(seed) {
            panic!("{e}");
        }
    }
}

fn assert_cut_alike(seed: u64) -> Result<(), proptest::test_runner::TestCaseError> {
    let (rows, table, program, sim) = random_machine(seed);
    let csv = |t: &faults::FaultTable| {
        steptable::emit::faults_csv::render(t, &|s| s.symbol(), &|t| t.to_string())
            .expect("renders")
    };
    let run =
        |runs, healthy| faults::analyse_from(&table, &program, &sim, 1, runs, &|_, _| {}, healthy);
    let reference = csv(&run(FaultRuns::FromPowerUp, None));
    let resumed = csv(&run(FaultRuns::Resumed, None));
    // The proof's run records the diagram's trace; the analysis reads
    // nothing of it.
    let proof = SimSettings {
        record_trace: true,
        ..sim.clone()
    };
    let shared = csv(&run(
        FaultRuns::Resumed,
        Some(faults::healthy_run(&table, &program, &proof)),
    ));
    proptest::prop_assert_eq!(&resumed, &reference, "seed {} {:?}", seed, rows);
    proptest::prop_assert_eq!(&shared, &reference, "seed {} {:?}", seed, rows);
    Ok(())
}

/// A healthy run handed in without the log of what it read (a copy's
/// log keeps only the inputs' changes) is planned where the inputs differ:
/// read as "never read", every fault would be no effect.
#[test]
fn a_healthy_run_without_its_reads_is_planned_where_inputs_differ() {
    for path in samples() {
        let settings = Settings::default();
        let checked = check_path(&path, &settings).expect("a sample converts");
        let program = build_program(&checked.table, &checked.settings);
        let (table, sim) = (&checked.table, &checked.settings.simulation);
        let mut unread = faults::healthy_run(table, &program, sim);
        assert!(unread.log.reads_logged, "{}", path.display());
        unread.log.reads_logged = false;
        unread.log.reads.iter_mut().for_each(Vec::clear);
        let run = |runs, healthy| {
            faults::analyse_from(table, &program, sim, 1, runs, &|_, _| {}, healthy)
        };
        let (planned, reference) = (
            run(FaultRuns::Resumed, Some(unread)),
            run(FaultRuns::FromPowerUp, None),
        );
        assert_eq!(planned.cases, reference.cases, "{}", path.display());
        assert_eq!(planned.runs, reference.runs, "{}", path.display());
    }
}

#[test]
fn every_verdict_is_what_the_fault_alone_gives_when_it_appears_then() {
    let mut replayed = 0;
    let mut hazards = 0;
    for seed in 0..300u64 {
        let (rows, table, program, mut sim) = random_machine(seed);
        sim.record_trace = false;
        let what = format!("seed {seed} {rows:?}");
        let healthy = simulate(
            &table,
            &program,
            &SimSettings {
                record_places: true,
                ..sim.clone()
            },
        );
        if !healthy.passed {
            // A machine that cannot run its cycle gets no fault table.
            continue;
        }
        assert_eq!(
            judge(&healthy).0,
            Outcome::NoEffect,
            "{what}: the healthy run"
        );
        let analysed = faults::analyse(&table, &program, &sim, 1);
        assert!(analysed.phases_skipped.is_none(), "{what}");
        let known = std::sync::Arc::new(healthy.places.clone());
        let mut rng = SplitMix64::new(seed ^ 0xfa17);
        for case in &analysed.cases {
            assert_eq!(case.outcomes.len(), analysed.moments.len(), "{what}");
            assert_eq!(
                case.outcomes.iter().max(),
                Some(&case.outcome),
                "{what}: the worst is reported"
            );
            // The reported moment, and one more by the dice.
            let reported = analysed
                .moments
                .iter()
                .position(|m| m.phase == case.phase)
                .expect("the reported phase is a moment");
            let other = rng.range(0, analysed.moments.len() as u32 - 1) as usize;
            for m in [reported, other] {
                let moment = analysed.moments[m];
                let alone = simulate(
                    &table,
                    &program,
                    &SimSettings {
                        faults: case.faults.clone(),
                        fault_onset_ms: moment.at_ms,
                        known_places: Some(known.clone()),
                        ..sim.clone()
                    },
                );
                let (outcome, step, explanation) = judge(&alone);
                assert_eq!(
                    outcome,
                    case.outcomes[m],
                    "{what}: {} appearing {} ({} ms): {explanation}",
                    case.fault_text(),
                    moment.phase.label(),
                    moment.at_ms
                );
                if m == reported {
                    assert_eq!(
                        (step, &explanation),
                        (case.step, &case.explanation),
                        "{what}: {}",
                        case.fault_text()
                    );
                    hazards += usize::from(outcome == Outcome::Hazard);
                }
                replayed += 1;
            }
        }
    }
    eprintln!("fault phases: {replayed} replays, {hazards} of them hazards");
    assert!(replayed > 4000, "{replayed} replays");
    assert!(hazards > 300, "{hazards} hazards replayed");
}

/// A long cycle would take minutes at every moment: its faults appear at
/// power-up only, and the summary says so.
#[test]
fn a_long_cycle_gets_its_faults_from_power_up_only_and_says_so() {
    let shape = Shape {
        actuators: 12,
        max_position: 1,
        branches: 1,
        steps: 200,
    };
    let table = steptable::table::from_rows("long.csv", &random_rows(7, shape)).unwrap();
    let program = steptable::convert::build_program(&table, &steptable::settings::Settings::new());
    let analysed = faults::analyse(&table, &program, &SimSettings::default(), 1);
    // Power-up, before each of steps 2…200, while each moves, at rest.
    let moments_of_the_cycle = 1 + 199 + 200 + 1;
    assert_eq!(analysed.moments.len(), 1);
    assert_eq!(analysed.phases_skipped, Some(2 * 25 * moments_of_the_cycle));
    assert!(
        analysed
            .summary()
            .starts_with("50 fault case(s) from power-up only (20050 cases at every moment"),
        "{}",
        analysed.summary()
    );
    assert!(analysed.cases.iter().all(|c| c.outcomes.len() == 1));
}
