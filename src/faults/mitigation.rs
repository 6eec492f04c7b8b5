//! The mitigation of each hazard of a fault table, verified rather than
//! guessed: the same faults are run again, at every moment of the cycle,
//! on the program with each safety check it does not carry yet (and, when
//! no single one catches the hazard, with all of them at once), exactly as
//! `steptable faults --safety …` would run them. A check *catches* the
//! hazard when the faults then give no hazard at any moment (a safe stall,
//! with or without an alarm, or no effect); one that only narrows it to
//! fewer moments is named with the moments left. What no check catches is
//! said so, with what would (a remedy outside the program, not simulated).

use super::{FaultCase, FaultRuns, FaultTable, Outcome, analyse_sets};
use crate::program::{self, ProgramOptions, Safety, Signal};
use crate::simulate::SimSettings;
use crate::table::StepTable;

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
    /// The faults' case under those checks, as `faults --safety` gives it.
    pub case: FaultCase,
    /// The moments of the cycle that program's fault table has.
    pub moments: usize,
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
        self.case.outcome != Outcome::Hazard
    }

    /// How many moments still give a hazard.
    fn hazard_moments(&self) -> usize {
        self.case.hazard_moments()
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
    /// The moments the hazard appears at without any added check: a trial
    /// that leaves as many narrows nothing.
    pub hazard_moments: usize,
}

impl Mitigation {
    /// The trials that catch the hazard.
    pub fn catching(&self) -> impl Iterator<Item = &Trial> {
        self.trials.iter().filter(|t| t.catches())
    }

    /// One line for the fault table: `caught by --safety watchdog (safe
    /// stall, alarm)`; `under --safety precheck or --safety plausibility it
    /// stays a hazard while step 1 moves (2 of 17 moments)` (the moments
    /// left, as `faults --safety …` says them); `not caught by --safety edge
    /// or --safety watchdog`; and, when nothing catches it, `no built-in
    /// check catches it at every moment; what would (not simulated): …`.
    pub fn text(&self) -> String {
        let mut parts = Vec::new();
        // The trials that narrow the hazard, by the moments they leave.
        let mut narrowed: Vec<(String, Vec<String>)> = Vec::new();
        let mut useless = Vec::new();
        for trial in &self.trials {
            if trial.catches() {
                let alarm = if trial.case.detected { ", alarm" } else { "" };
                parts.push(format!(
                    "caught by {} ({}{alarm})",
                    trial.option(),
                    trial.case.outcome.label()
                ));
            } else if trial.hazard_moments() < self.hazard_moments {
                let left = trial.case.appears(trial.moments);
                match narrowed.iter_mut().find(|(l, _)| *l == left) {
                    Some((_, options)) => options.push(trial.option()),
                    None => narrowed.push((left, vec![trial.option()])),
                }
            } else {
                useless.push(trial.option());
            }
        }
        for (left, options) in narrowed {
            parts.push(format!(
                "under {} it stays a hazard {left}",
                options.join(" or ")
            ));
        }
        if !useless.is_empty() {
            parts.push(format!("not caught by {}", useless.join(" or ")));
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
/// program's healthy run as the fault analysis does.
pub fn mitigations(
    table: &StepTable,
    options: &ProgramOptions,
    settings: &SimSettings,
    faults: &FaultTable,
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
    // The checks alone, side by side: each is a program of its own.
    use rayon::prelude::*;
    let alone: Vec<Option<Vec<Trial>>> = missing
        .par_iter()
        .map(|name| run_trials(table, options, settings, &hazards, &[name]))
        .collect();
    let mut trials: Vec<Vec<Trial>> = vec![Vec::new(); hazards.len()];
    for found in alone.into_iter().flatten() {
        for (i, trial) in found.into_iter().enumerate() {
            trials[i].push(trial);
        }
    }
    // Together, for the hazards no single check catches.
    let uncaught: Vec<usize> = (0..hazards.len())
        .filter(|&i| !trials[i].iter().any(Trial::catches))
        .collect();
    if missing.len() > 1 && !uncaught.is_empty() {
        let rest: Vec<&FaultCase> = uncaught.iter().map(|&i| hazards[i]).collect();
        let together = run_trials(table, options, settings, &rest, &missing);
        for (i, trial) in uncaught.into_iter().zip(together.into_iter().flatten()) {
            trials[i].push(trial);
        }
    }
    let mut verified = hazards.iter().zip(trials).map(|(case, trials)| {
        let remedy = if trials.iter().any(Trial::catches) {
            String::new()
        } else {
            remedy(table, case, &trials).to_string()
        };
        let hazard_moments = case.hazard_moments();
        Mitigation {
            trials,
            remedy,
            hazard_moments,
        }
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

/// Runs `cases` on the program with the checks `added`: each one's trial,
/// in their order. A program that does not pass its own healthy cycle with
/// them (a check that stops a sound machine) is no mitigation: `None`.
fn run_trials(
    table: &StepTable,
    options: &ProgramOptions,
    settings: &SimSettings,
    cases: &[&FaultCase],
    added: &[&'static str],
) -> Option<Vec<Trial>> {
    let safety = added.iter().fold(options.safety, |s, n| with(s, n));
    let options = ProgramOptions {
        safety,
        ..options.clone()
    };
    let machine = &settings.machine;
    let program = program::build(table, &options, &machine.valves, &machine.strokes);
    let healthy = super::healthy_run(
        table,
        &program,
        &SimSettings {
            record_trace: false,
            ..super::yardstick_settings(settings)
        },
    );
    if !healthy.report.passed {
        return None;
    }
    let sets = cases.iter().map(|c| c.faults.clone()).collect();
    let run = analyse_sets(
        table,
        &program,
        settings,
        sets,
        FaultRuns::Resumed,
        &|_, _| {},
        Some(healthy),
    );
    let moments = run.moments.len();
    let trials = run.cases.into_iter().map(|case| Trial {
        safety,
        added: added.to_vec(),
        case,
        moments,
    });
    Some(trials.collect())
}

/// What would catch the hazard that remains, by what it is: the kinds of
/// hazard no check on the inputs can catch (docs/simulation-and-faults.md,
/// "Safety checks"). Read from the trial that leaves the fewest moments a
/// hazard (its explanation is of the hazard that remains), else the case.
fn remedy(table: &StepTable, case: &FaultCase, trials: &[Trial]) -> &'static str {
    let explanation = trials
        .iter()
        .min_by_key(|t| t.hazard_moments())
        .map_or(&case.explanation, |t| &t.case.explanation);
    if explanation.contains("not hold-safe") {
        return "a halt that switches the output off (SETTINGS on halt), with a check that halts";
    }
    let Some(fault) = case.faults.first().copied() else {
        return "a redundant sensor";
    };
    match (fault.signal, fault.stuck_at) {
        (Signal::MachineInput(_), true) => {
            "the machine input's own monitoring (a second, diverse sensor): shorted, it looks like the real thing"
        }
        (Signal::Start | Signal::Continuous, true) => {
            "a two-channel button: a shorted button reads as the operator's press"
        }
        (Signal::Reset, true) => "a RESET that acts only on a stopped machine",
        (Signal::Sensor { .. }, true) if !explanation.contains("collision risk") => {
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
        _ if explanation.contains("collision risk") => {
            "5/3 closed-centre valves and a halt that switches the coils off, so that the machine stops where it is"
        }
        _ => "a redundant sensor at that position",
    }
}

#[cfg(test)]
#[path = "mitigation_tests.rs"]
mod tests;
