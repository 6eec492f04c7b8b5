//! One small table per kind of mitigation, where the answer is known: a
//! halt that switches a heater off, checks that leave a short only at the
//! moments its cylinder travels, the edge on START, and a dead middle
//! sensor nothing in the program catches; and every trial agrees with the
//! fault table `faults --safety …` gives for the program with those checks.

use super::*;
use crate::faults::{Phase, analyse};

fn table(rows: &[&[&str]]) -> StepTable {
    crate::table::from_rows("t.csv", rows).expect("a valid table")
}

fn build(table: &StepTable, options: &ProgramOptions) -> crate::program::StepProgram {
    program::build(
        table,
        options,
        &crate::actuator::Valves::default(),
        &crate::stroke::Strokes::default(),
    )
}

/// The table's fault analysis under `options` and the mitigation of the
/// hazard of `signal` stuck at `stuck_at`.
fn mitigation_of(
    table: &StepTable,
    options: &ProgramOptions,
    signal: &str,
    stuck_at: bool,
) -> (FaultCase, Mitigation) {
    let settings = SimSettings::default();
    let faults = analyse(table, &build(table, options), &settings, 1);
    let verified = mitigations(table, options, &settings, &faults, None, &|_| true);
    assert_eq!(verified.len(), faults.cases.len());
    let i = faults
        .cases
        .iter()
        .position(|c| c.faults[0].signal.symbol() == signal && c.faults[0].stuck_at == stuck_at)
        .expect("the fault is in the table");
    let case = faults.cases[i].clone();
    assert_eq!(case.outcome, Outcome::Hazard, "{}", case.explanation);
    (
        case,
        verified[i].clone().expect("a hazard has a mitigation"),
    )
}

fn trial<'m>(m: &'m Mitigation, option: &str) -> &'m Trial {
    m.trials
        .iter()
        .find(|t| t.option() == option)
        .unwrap_or_else(|| panic!("{option} tried: {}", m.text()))
}

/// The fault table of the program with a trial's checks.
fn full_table(t: &Trial, table: &StepTable, options: &ProgramOptions) -> FaultTable {
    let options = ProgramOptions {
        safety: t.safety,
        ..options.clone()
    };
    analyse(table, &build(table, &options), &SimSettings::default(), 1)
}

/// The phases at which the faults of `case` give a hazard under a trial's
/// checks, from the whole fault table of that program.
fn hazard_phases(
    t: &Trial,
    case: &FaultCase,
    table: &StepTable,
    options: &ProgramOptions,
) -> Vec<Phase> {
    let full = full_table(t, table, options);
    let same = full.cases.iter().find(|c| c.faults == case.faults).unwrap();
    full.moments
        .iter()
        .zip(&same.outcomes)
        .filter(|(_, o)| **o == Outcome::Hazard)
        .map(|(m, _)| m.phase)
        .collect()
}

/// The phase a trial found the hazard staying at.
fn stays_at(t: &Trial) -> Phase {
    match &t.found {
        Found::Hazard { phase, .. } => *phase,
        Found::Clear(case) => panic!("{} catches it: {case:?}", t.option()),
    }
}

/// A dead end sensor stops the machine with its heater on: an energy
/// hazard. With SETTINGS `on halt | heater off` the watchdog catches it: it
/// halts the machine, and the halt switches the heater off (a safe stall
/// with its alarm, at every moment). Without that row a halt leaves the
/// heater on, and the watchdog is no mitigation.
#[test]
fn the_watchdog_catches_a_dead_sensor_that_leaves_a_heater_on() {
    let t = table(&[&["C1+1; Y:heater+"], &["C1-0; Y:heater-"]]);
    let (_, m) = mitigation_of(&t, &ProgramOptions::default(), "x11", false);
    assert!(!trial(&m, "--safety watchdog").catches(), "{}", m.text());
    assert!(m.remedy.contains("on halt"), "{}", m.remedy);
    let heater = Signal::MachineOutput(crate::cell::Name::new("heater").unwrap());
    let mut options = ProgramOptions::default();
    options.halt.off_on_halt.insert(heater);
    let (case, m) = mitigation_of(&t, &options, "x11", false);
    assert!(
        case.explanation.contains("not hold-safe"),
        "{}",
        case.explanation
    );
    let watchdog = trial(&m, "--safety watchdog");
    assert!(watchdog.catches());
    let Found::Clear(caught) = &watchdog.found else {
        unreachable!("it catches")
    };
    assert_eq!(caught.outcome, Outcome::SafeStall);
    assert!(caught.detected);
    assert!(!trial(&m, "--safety edge").catches());
    assert!(m.remedy.is_empty(), "caught: no remedy outside the program");
    assert!(
        m.text()
            .starts_with("caught by --safety watchdog (safe stall, alarm)"),
        "{}",
        m.text()
    );
    // Caught by a single check: the checks together are not tried.
    assert!(m.trials.iter().all(|t| t.added.len() == 1));
}

/// A shorted end sensor starts the next step early. The precheck (the
/// move waits for its target sensor to be off) and the plausibility check
/// (two sensors of one cylinder on) catch it when it is there before the
/// cylinder leaves; a short while the cylinder travels towards the sensor
/// reads as the arrival, and stays a hazard under every check: the moment
/// each trial names.
#[test]
fn a_shorted_end_sensor_stays_a_hazard_while_its_cylinder_travels() {
    let t = table(&[&["C1+1"], &["C1-0"]]);
    let options = ProgramOptions::default();
    let (case, m) = mitigation_of(&t, &options, "x11", true);
    for option in ["--safety precheck", "--safety plausibility"] {
        let narrowed = trial(&m, option);
        assert!(!narrowed.catches());
        let left = hazard_phases(narrowed, &case, &t, &options);
        assert!(
            !left.is_empty() && left.len() < narrowed.moments,
            "{left:?}"
        );
        assert!(
            left.iter()
                .all(|p| matches!(p, Phase::Moving(1) | Phase::BeforeStep(2))),
            "{option}: {left:?}"
        );
        assert!(left.contains(&stays_at(narrowed)), "{option}");
    }
    for t in &m.trials {
        let at = stays_at(t);
        assert!(
            matches!(at, Phase::Moving(1) | Phase::BeforeStep(2)),
            "{}: {at:?}",
            t.option()
        );
        let left = hazard_phases(t, &case, &table(&[&["C1+1"], &["C1-0"]]), &options);
        assert!(left.contains(&at), "{}: {at:?} {left:?}", t.option());
    }
    // None catches it alone, so all four are tried together.
    assert!(!trial(&m, "--safety all").catches());
    assert!(m.remedy.contains("minimum travel time"), "{}", m.remedy);
    let text = m.text();
    assert!(
        text.starts_with("not caught by --safety edge or --safety precheck or --safety plausibility or --safety watchdog (still a hazard if it appears while step 1 moves); "),
        "{text}"
    );
    assert!(
        text.contains("no built-in check catches it at every moment"),
        "{text}"
    );
}

/// START shorted starts the machine by itself. With the edge check a
/// START held from power-up is no press; shorting at rest after a cycle
/// it reads exactly as one.
#[test]
fn the_edge_narrows_a_shorted_start_to_rest_after_the_cycle() {
    let t = table(&[&["C1+1"], &["C1-0"]]);
    let options = ProgramOptions::default();
    let (_, m) = mitigation_of(&t, &options, "START", true);
    let edge = trial(&m, "--safety edge");
    let (case, _) = mitigation_of(&t, &options, "START", true);
    assert_eq!(hazard_phases(edge, &case, &t, &options), [Phase::AtRest]);
    // The search finds the one moment left, after every other.
    assert_eq!(stays_at(edge), Phase::AtRest);
    assert!(
        m.text()
            .contains("not caught by --safety edge or --safety all (still a hazard if it appears at rest after the cycle)"),
        "{}",
        m.text()
    );
    assert!(m.remedy.contains("two-channel"), "{}", m.remedy);
}

/// A dead middle sensor lets its cylinder run on into positions the
/// cycle never has: no check on the inputs catches the overrun in time.
#[test]
fn no_check_catches_a_dead_middle_sensor() {
    let t = crate::program::tests::paper_table();
    let options = ProgramOptions::default();
    let (case, m) = mitigation_of(&t, &options, "x22", false);
    assert!(m.trials.iter().all(|t| !t.catches()));
    assert_eq!(m.trials.len(), 5, "four checks alone, then all four");
    for t in &m.trials {
        assert!(matches!(t.found, Found::Hazard { .. }), "{}", t.option());
    }
    assert!(m.remedy.starts_with("a mechanical stop"), "{}", m.remedy);
    assert!(case.explanation.contains(" ran through "));
}

/// Verified, not guessed: a trial that catches the hazard is the case of
/// the same faults in the fault table of the program with those checks, as
/// `faults --safety` makes it; one that does not names a moment at which
/// that table gives the hazard, with its step and, at the table's own first
/// hazard moment, its explanation. The checks the program carries are not
/// proposed, and the option names them with the one added (`--safety`
/// replaces the list).
#[test]
fn each_trial_is_the_fault_table_of_the_program_with_its_checks() {
    let t = crate::program::tests::paper_table();
    let options = ProgramOptions {
        safety: Safety {
            plausibility: true,
            ..Safety::default()
        },
        ..ProgramOptions::default()
    };
    let settings = SimSettings::default();
    let faults = analyse(&t, &build(&t, &options), &settings, 1);
    let verified = mitigations(&t, &options, &settings, &faults, None, &|_| true);
    let mut checked = 0;
    for (case, m) in faults.cases.iter().zip(&verified) {
        let Some(m) = m else {
            assert_ne!(case.outcome, Outcome::Hazard);
            continue;
        };
        for trial in &m.trials {
            assert!(!trial.added.contains(&"plausibility"));
            assert!(trial.safety.plausibility, "the check carried stays");
            let with = ProgramOptions {
                safety: trial.safety,
                ..options.clone()
            };
            let full = analyse(&t, &build(&t, &with), &settings, 1);
            let same = full.cases.iter().find(|c| c.faults == case.faults).unwrap();
            match &trial.found {
                Found::Clear(caught) => assert_eq!(caught, same, "{}", trial.option()),
                Found::Hazard {
                    moment,
                    phase,
                    explanation,
                    ..
                } => {
                    assert_eq!(
                        same.outcomes[*moment],
                        Outcome::Hazard,
                        "{}",
                        trial.option()
                    );
                    assert_eq!(full.moments[*moment].phase, *phase);
                    if *phase == same.phase {
                        assert_eq!(*explanation, same.explanation, "{}", trial.option());
                    }
                }
            }
            assert_eq!(trial.moments, full.moments.len());
            checked += 1;
        }
    }
    assert!(checked > 0);
    let m = verified.iter().flatten().next().unwrap();
    assert!(
        m.trials
            .iter()
            .any(|t| t.option() == "--safety precheck,plausibility"),
        "{}",
        m.text()
    );
}

/// A program that carries every check has none to propose: each hazard
/// gets no trial, and the cell says no built-in check catches it, with
/// what would.
#[test]
fn a_program_with_every_check_gets_only_the_remedy() {
    let t = crate::program::tests::paper_table();
    let options = ProgramOptions {
        safety: Safety::all(),
        ..ProgramOptions::default()
    };
    let (_, m) = mitigation_of(&t, &options, "x22", false);
    assert!(m.trials.is_empty());
    assert!(
        m.text()
            .starts_with("no built-in check catches it at every moment; what would (not simulated): a mechanical stop"),
        "{}",
        m.text()
    );
}

/// The halt already switches the heater off (SETTINGS `on halt`), but the
/// step waits on a machine input, which the watchdog leaves untimed: no
/// check halts there, and the remedy is the supervision time that would,
/// not the SETTINGS row the engineer already has (red team rt9).
#[test]
fn a_heater_the_halt_switches_off_wants_a_check_that_halts() {
    let t = table(&[&["C1+1; Y:heat+; I:part"], &["C1-0; Y:heat-"]]);
    let heat = Signal::MachineOutput(crate::cell::Name::new("heat").unwrap());
    let mut options = ProgramOptions::default();
    options.halt.off_on_halt.insert(heat);
    let (case, m) = mitigation_of(&t, &options, "x11", false);
    assert!(
        case.explanation.contains("not hold-safe"),
        "{}",
        case.explanation
    );
    assert!(m.remedy.starts_with("a supervision time"), "{}", m.remedy);
    // Without the row, the row is what is missing.
    let (_, m) = mitigation_of(&t, &ProgramOptions::default(), "x11", false);
    assert!(m.remedy.contains("SETTINGS on halt"), "{}", m.remedy);
}
