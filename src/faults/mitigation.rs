//! The mitigation of each hazard of a fault table, verified rather than
//! guessed: the same faults are run again on the program with each safety
//! check it does not carry yet (and, when no single one catches the
//! hazard, with all of them at once), exactly as `steptable faults
//! --safety …` would run them. A check *catches* the hazard when the faults
//! then give no hazard at any moment of the cycle (a safe stall, with or
//! without an alarm, or no effect: every moment is run); one that does not
//! is named with the first moment at which the hazard stays (the runs stop
//! there). What no check catches is said so, with what would (a remedy
//! outside the program, not simulated).

use super::search::{Found, first_hazards};
use super::{FaultCase, FaultTable, Healthy, Outcome};
use crate::program::{self, ProgramOptions, Safety, Signal};
use crate::simulate::SimSettings;
use crate::table::StepTable;

/// Whether steptable would write a program at the addresses asked for (a
/// check's alarm output may need one more than an OpenPLC board wires:
/// E036). The caller's, who knows the target and the board.
pub type Fits<'a> = dyn Fn(&crate::program::StepProgram) -> bool + Sync + 'a;

/// The checks a mitigation may add, in the order `--safety` names them
/// (the criteria analysis only reports, so it is not one).
const CHECKS: [&str; 4] = ["edge", "precheck", "plausibility", "watchdog"];

/// The same faults, run on the program with some checks added.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Trial {
    /// The checks the program would carry: those it has and those added.
    pub safety: Safety,
    /// The checks added, by name.
    pub added: Vec<&'static str>,
    /// What the faults do under those checks: the first moment that gives
    /// a hazard, or, when none does, their case as `faults --safety` gives it.
    pub found: Found,
    /// The moments of the cycle that program's fault table has.
    pub moments: usize,
    /// The cycle is too long for faults at every moment: that fault table,
    /// and the trial, make them appear at power-up only.
    pub power_up_only: bool,
}

impl Trial {
    /// `--safety plausibility`, or the whole list when the program carries
    /// checks already (`--safety` replaces the checks, it does not add).
    pub fn option(&self) -> String {
        let names: Vec<&str> = CHECKS
            .iter()
            .copied()
            .filter(|n| has(self.safety, n))
            .collect();
        if names.len() == CHECKS.len() && !self.safety.criteria {
            return "--safety all".to_string();
        }
        let mut names = names.join(",");
        if self.safety.criteria {
            names.push_str(",criteria");
        }
        format!("--safety {names}")
    }

    /// Whether the faults give no hazard at any moment under the checks.
    pub fn catches(&self) -> bool {
        matches!(self.found, Found::Clear(_))
    }
}

/// What catches one hazard, as verified.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Mitigation {
    /// Each check the program does not carry, alone, then (when none of
    /// them catches the hazard and two or more were tried) all of them.
    pub trials: Vec<Trial>,
    /// What would catch what remains, outside the program; empty when a
    /// trial catches it.
    pub remedy: String,
}

impl Mitigation {
    /// The trials that catch the hazard.
    pub fn catching(&self) -> impl Iterator<Item = &Trial> {
        self.trials.iter().filter(|t| t.catches())
    }

    /// One line for the fault table: `caught by --safety watchdog (safe
    /// stall, alarm)`; `not caught by --safety precheck or --safety
    /// plausibility (still a hazard if it appears while step 1 moves)`, the
    /// first moment at which it stays one, as `faults --safety …` names it;
    /// and, when nothing catches it, `no built-in check catches it at every
    /// moment; what would (not simulated): …`.
    pub fn text(&self) -> String {
        let mut parts = Vec::new();
        // The trials that leave a hazard, by the moment it stays at.
        let mut stays: Vec<(String, Vec<String>)> = Vec::new();
        for trial in &self.trials {
            match &trial.found {
                Found::Clear(case) => {
                    let alarm = if case.detected { ", alarm" } else { "" };
                    let only = match trial.power_up_only {
                        true => {
                            "; faults from power-up only, the cycle being too long for every moment"
                        }
                        false => "",
                    };
                    parts.push(format!(
                        "caught by {} ({}{alarm}{only})",
                        trial.option(),
                        case.outcome.label()
                    ));
                }
                Found::Hazard { phase, .. } => {
                    let at = phase.label();
                    match stays.iter_mut().find(|(l, _)| *l == at) {
                        Some((_, options)) => options.push(trial.option()),
                        None => stays.push((at, vec![trial.option()])),
                    }
                }
            }
        }
        for (at, options) in stays {
            parts.push(format!(
                "not caught by {} (still a hazard if it appears {at})",
                options.join(" or ")
            ));
        }
        if !self.remedy.is_empty() {
            parts.push(format!(
                "no built-in check catches it at every moment; what would (not simulated): {}",
                self.remedy
            ));
        }
        parts.join("; ")
    }
}

/// Whether `safety` has the check called `name`.
fn has(safety: Safety, name: &str) -> bool {
    match name {
        "edge" => safety.edge,
        "precheck" => safety.precheck,
        "plausibility" => safety.plausibility,
        "watchdog" => safety.watchdog,
        _ => false,
    }
}

fn with(mut safety: Safety, name: &str) -> Safety {
    match name {
        "edge" => safety.edge = true,
        "precheck" => safety.precheck = true,
        "plausibility" => safety.plausibility = true,
        _ => safety.watchdog = true,
    }
    safety
}

/// The mitigation of every hazard of `faults` (the table of the program
/// built from `table` under `options`, analysed under `settings`), in the
/// order of its cases; `None` for a case that is no hazard. The hazards
/// alone are run again, once per trial program, each resumed from that
/// program's healthy run as the fault analysis does. `healthy` is the
/// healthy run of the program without the checks, when the caller has it
/// ([`super::healthy_run`] under `settings`): a trial program's own is
/// expected to be the same, and is checked to be.
pub fn mitigations(
    table: &StepTable,
    options: &ProgramOptions,
    settings: &SimSettings,
    faults: &FaultTable,
    healthy: Option<&Healthy>,
    fits: &Fits<'_>,
) -> Vec<Option<Mitigation>> {
    let hazards: Vec<&FaultCase> = faults
        .cases
        .iter()
        .filter(|c| c.outcome == Outcome::Hazard)
        .collect();
    let missing: Vec<&'static str> = CHECKS
        .into_iter()
        .filter(|n| !has(options.safety, n))
        .collect();
    // No hazard, or no check to try: nothing to run.
    let trials = match hazards.is_empty() || missing.is_empty() {
        true => vec![Vec::new(); hazards.len()],
        false => verify(table, options, settings, &hazards, &missing, healthy, fits),
    };
    let mut verified = hazards.iter().zip(trials).map(|(case, trials)| {
        let remedy = if trials.iter().any(Trial::catches) {
            String::new()
        } else {
            remedy(table, options, case, &trials).to_string()
        };
        Mitigation { trials, remedy }
    });
    faults
        .cases
        .iter()
        .map(|c| {
            (c.outcome == Outcome::Hazard)
                .then(|| verified.next())
                .flatten()
        })
        .collect()
}

/// The trials of each of `hazards`: each check of `missing` alone, then,
/// for the hazards none of them catches, all of them together; measured
/// against `healthy` (made here when the caller has none).
fn verify(
    table: &StepTable,
    options: &ProgramOptions,
    settings: &SimSettings,
    hazards: &[&FaultCase],
    missing: &[&'static str],
    healthy: Option<&Healthy>,
    fits: &Fits<'_>,
) -> Vec<Vec<Trial>> {
    let own;
    let healthy = match healthy {
        Some(healthy) => healthy,
        None => {
            let machine = &settings.machine;
            let program = program::build(table, options, &machine.valves, &machine.strokes);
            own = super::healthy_run(table, &program, &super::untraced_yardstick(settings));
            &own
        }
    };
    // The checks alone, side by side: each is a program of its own.
    use rayon::prelude::*;
    let alone: Vec<Option<Vec<Trial>>> = missing
        .par_iter()
        .map(|name| run_trials(table, options, settings, hazards, &[name], healthy, fits))
        .collect();
    let mut trials: Vec<Vec<Trial>> = vec![Vec::new(); hazards.len()];
    // The checks steptable would build: together they are tried too (one
    // it refuses, such as a watchdog longer than a PLC timer holds, leaves
    // the others).
    let mut built: Vec<&'static str> = Vec::new();
    for (name, found) in missing.iter().zip(alone) {
        let Some(found) = found else { continue };
        built.push(*name);
        for (i, trial) in found.into_iter().enumerate() {
            trials[i].push(trial);
        }
    }
    // Together, for the hazards no single check catches.
    let uncaught: Vec<usize> = (0..hazards.len())
        .filter(|&i| !trials[i].iter().any(Trial::catches))
        .collect();
    if built.len() > 1 && !uncaught.is_empty() {
        let rest: Vec<&FaultCase> = uncaught.iter().map(|&i| hazards[i]).collect();
        let together = run_trials(table, options, settings, &rest, &built, healthy, fits);
        for (i, trial) in uncaught.into_iter().zip(together.into_iter().flatten()) {
            trials[i].push(trial);
        }
    }
    trials
}

/// Runs `cases` on the program with the checks `added`: each one's trial,
/// in their order. A program that does not pass its own healthy cycle with
/// them (a check that stops a sound machine), or that steptable would not
/// write, is no mitigation: `None`.
fn run_trials(
    table: &StepTable,
    options: &ProgramOptions,
    settings: &SimSettings,
    cases: &[&FaultCase],
    added: &[&'static str],
    expected: &Healthy,
    fits: &Fits<'_>,
) -> Option<Vec<Trial>> {
    let safety = added.iter().fold(options.safety, |s, n| with(s, n));
    let options = ProgramOptions {
        safety,
        ..options.clone()
    };
    let machine = &settings.machine;
    let program = program::build(table, &options, &machine.valves, &machine.strokes);
    // A program steptable refuses to write (E032: a watchdog no PLC timer
    // holds; E036: an alarm output beyond what the board wires) is no
    // mitigation either.
    if program.watchdogs_beyond_timers().next().is_some()
        || program.homing_watchdogs_beyond_timers().next().is_some()
        || !fits(&program)
    {
        return None;
    }
    let sets = cases.iter().map(|c| c.faults.clone()).collect();
    let searched = first_hazards(table, &program, settings, sets, Some(expected))?;
    let (moments, power_up_only) = (searched.moments.len(), searched.power_up_only);
    let trials = searched.found.into_iter().map(|found| Trial {
        safety,
        added: added.to_vec(),
        found,
        moments,
        power_up_only,
    });
    Some(trials.collect())
}

/// What would catch the hazard that remains, by what it is: the kinds of
/// hazard no check on the inputs can catch (docs/simulation-and-faults.md,
/// "Safety checks"). Read from the hazard the trial with the most checks
/// leaves (all of them together, when they were tried: its explanation is
/// of what remains under every check), else from the case.
fn remedy(
    table: &StepTable,
    options: &ProgramOptions,
    case: &FaultCase,
    trials: &[Trial],
) -> &'static str {
    let explanation = trials
        .iter()
        .max_by_key(|t| t.added.len())
        .and_then(|t| match &t.found {
            Found::Hazard { explanation, .. } => Some(explanation),
            Found::Clear(_) => None,
        })
        .unwrap_or(&case.explanation);
    if explanation.contains("not hold-safe") {
        let kept: Vec<&str> = kept_on(explanation).collect();
        let switched_off = |s: &&str| options.halt.off_on_halt.iter().any(|o| o.symbol() == *s);
        if !kept.is_empty() && kept.iter().all(switched_off) {
            // The halt would switch them off: what is missing is a check
            // that halts in the step that waits.
            return "a supervision time for the step that waits (SETTINGS supervision: the watchdog leaves a step that waits on a machine input untimed), so that a check halts it and the halt switches the output off";
        }
        return "a halt that switches the output off (SETTINGS on halt), with a check that halts";
    }
    // Motion no step commands, under the checks: a halt that cut a coil
    // let the valve's spring (or a drifting centre) move the piston. A
    // better sensor leaves it moving on every halt.
    let stop = case
        .faults
        .iter()
        .any(|f| matches!(f.signal, Signal::Stop | Signal::EStop));
    if explanation.contains("unintended motion") && !stop {
        return "a valve that holds the piston where it is without its coil (a 5/3 closed centre, or a 5/2 bistable), or a halt that leaves that coil on (SETTINGS on halt): the halt cut a coil and the valve moved the piston";
    }
    let Some(fault) = case.faults.first().copied() else {
        return "a redundant sensor";
    };
    let collision = explanation.contains("collision risk");
    // The sequence's own reason comes first: a step started early because
    // this very sensor read as the arrival.
    let read_as_arrival =
        explanation.contains(&format!("had not reached {})", fault.signal.symbol()));
    match (fault.signal, fault.stuck_at) {
        (Signal::MachineInput(_), _) => {
            "the machine input's own monitoring (a second, diverse sensor): stuck, it reads as the machine's real answer"
        }
        (Signal::Start | Signal::Continuous | Signal::StepButton | Signal::Jog { .. }, true) => {
            "a two-channel button: a shorted button reads as the operator's press"
        }
        (Signal::Reset, true) => "a RESET that acts only on a stopped machine",
        (Signal::StepMode | Signal::ManualMode, _) => {
            "a mode selector with two contacts (a key switch): a stuck contact reads as the mode chosen"
        }
        (Signal::Sensor { .. }, true) if read_as_arrival || !collision => {
            "a minimum travel time before the sensor counts, or a position transducer: a sensor that shorts as its cylinder travels towards it reads as the arrival"
        }
        (Signal::Sensor { actuator, position }, false)
            if explanation.contains(" ran through ")
                && table
                    .actuator(actuator)
                    .is_some_and(|a| position > 0 && position < a.max_position) =>
        {
            "a mechanical stop or a second sensor at that middle position: the cylinder runs on past the dead sensor"
        }
        // A stop that cuts the coils lets a piston on a spring-return or
        // 5/2 valve move on its own.
        _ if collision || matches!(fault.signal, Signal::Stop | Signal::EStop) => {
            "5/3 closed-centre valves and a halt that switches the coils off, so that the machine stops where it is"
        }
        (Signal::Sensor { .. }, _) => "a redundant sensor at that position",
        _ => "a redundant, monitored input",
    }
}

/// The outputs a stopped machine keeps on, as the explanation names them.
fn kept_on(explanation: &str) -> impl Iterator<Item = &str> {
    let listed = explanation
        .split_once("the stopped machine keeps ")
        .and_then(|(_, rest)| rest.split_once(" on (not hold-safe)"))
        .map_or("", |(list, _)| list);
    listed.split(", ").filter(|s| !s.is_empty())
}

#[cfg(test)]
#[path = "mitigation_tests.rs"]
mod tests;
