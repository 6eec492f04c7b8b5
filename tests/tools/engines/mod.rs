//! Engines that run the files steptable writes, as a user's tool would, and
//! the cases they are run on. Each engine takes a written file and the input
//! trace recorded by steptable's own simulation of the same table, runs one
//! PLC cycle per recorded scan, and returns the outputs of every scan; the
//! caller compares them with the simulation's ([`IoTrace::compare`]).

pub mod awlsim;
pub mod fst;
pub mod matiec;
pub mod plcxml;
pub mod rll;
pub mod scl;

use std::path::{Path, PathBuf};

use steptable::address::{Allocation, Mnemonic};
use steptable::convert;
use steptable::settings::{Given, Settings};
use steptable::simulate;
use steptable::simulate::io::{IoSignals, IoTrace};

use crate::helpers::steptable;

/// The engine a check runs written files in, when a check is split per
/// engine so that a missing engine is an ignored check, not a pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Engine {
    /// The FST interpreter of these tests (always there).
    Fst,
    Matiec,
    Awlsim,
    /// The SCL interpreter of these tests (always there).
    Scl,
    /// The RLL interpreter of these tests, after the `l5x` crate's parse.
    Rll,
}

/// One table converted with one set of options: the written files and the
/// simulation's recorded I/O.
pub struct Case {
    /// `press_station.xlsx --target iec --modes all --safety all`.
    pub label: String,
    /// Folder holding the written files `NAME.*`.
    pub dir: PathBuf,
    pub name: String,
    pub allocation: Allocation,
    /// The Festo allocation the FST files use whatever the target.
    pub festo: Allocation,
    pub mnemonic: Mnemonic,
    pub trace: IoTrace,
}

impl Case {
    pub fn file(&self, suffix: &str) -> PathBuf {
        self.dir.join(format!("{}{suffix}", self.name))
    }

    /// Compares an engine's outputs with the simulation; the error names the
    /// case, the engine, the scan and the signal.
    pub fn check(
        &self,
        engine: &str,
        outputs: Result<Vec<Vec<bool>>, String>,
    ) -> Result<(), String> {
        let outputs = outputs.map_err(|e| format!("{}: {engine}: {e}", self.label))?;
        self.trace
            .compare(&outputs)
            .map_err(|m| format!("{}: {engine}: {m}", self.label))
    }
}

/// The library settings the command-line arguments of a case stand for.
pub fn settings_for(args: &[&str]) -> Settings {
    let mut settings = Settings::new();
    for pair in args.chunks(2) {
        match pair {
            ["--target", t] => settings.give(Given {
                target: Some(t.parse().expect("target")),
                ..Given::default()
            }),
            ["--board", b] => settings.give(
                Given {
                    board: Some(b.parse().expect("board")),
                    ..Given::default()
                }
                .with_board_target(),
            ),
            ["--mnemonic", m] => settings.give(Given {
                mnemonic: Some(m.parse().expect("mnemonic")),
                ..Given::default()
            }),
            ["--safety", s] => settings.give(Given {
                safety: Some(s.parse().expect("safety list")),
                ..Given::default()
            }),
            ["--designations", d] => settings.give(Given {
                designations: Some(d.parse().expect("designations")),
                ..Given::default()
            }),
            ["--modes", m] => settings.give(Given {
                modes: Some(m.parse().expect("modes")),
                ..Given::default()
            }),
            ["--valve", v] => settings.give(Given {
                valves: steptable::actuator::parse_valves(v).expect("valve list"),
                ..Given::default()
            }),
            ["--input-delay", list] => {
                for item in list.split(',') {
                    let (name, time) = item.split_once('=').expect("input=time");
                    let name = steptable::cell::Name::new(name).expect("input name");
                    let ms = steptable::stroke::parse_duration_ms(time).expect("time");
                    settings.simulation.input_delays.insert(name, ms);
                }
            }
            // Which files are written does not change the program.
            ["--formats", _] => {}
            other => panic!("settings_for does not know {other:?}"),
        }
    }
    settings
}

/// Converts `input` with `args` through the binary into `out`, and simulates
/// the same table with the library, recording every input and output of the
/// written program at every scan.
pub fn prepare(input: &Path, args: &[&str], out: &Path) -> Case {
    let label = format!(
        "{} {}",
        input.file_name().unwrap().to_string_lossy(),
        args.join(" ")
    );
    steptable()
        .arg("convert")
        .arg(input)
        .args(args)
        .arg("-o")
        .arg(out)
        .assert()
        .success();
    let name = convert::output_name(input);
    let checked = convert::check_path(input, &settings_for(args)).expect("valid table");
    record(
        &label,
        out.join(&name),
        &name,
        &checked.table,
        &checked.settings,
    )
}

/// An engine's run of a step program: per scan, the outputs and the step
/// the program shows at the end of the scan (`active_step`, the AWL step
/// flag that is on, the FST step label).
pub struct Stepped {
    pub outputs: Vec<Vec<bool>>,
    pub steps: Vec<usize>,
}

/// An engine's printed scans, one line each: the outputs as 0/1, a space,
/// then what tells the step, read by `step`.
pub fn stepped_lines(
    text: &str,
    step: impl Fn(&str) -> Result<usize, String>,
) -> Result<Stepped, String> {
    let mut run = Stepped {
        outputs: Vec::new(),
        steps: Vec::new(),
    };
    for line in text.lines().filter(|l| !l.is_empty()) {
        let (outputs, shown) = line
            .split_once(' ')
            .ok_or_else(|| format!("no step after the outputs: {line}"))?;
        run.outputs
            .push(outputs.chars().map(|c| c == '1').collect());
        run.steps.push(step(shown.trim())?);
    }
    Ok(run)
}

impl Case {
    /// Like [`Case::check`], and the step the program shows must be the
    /// simulation's at every scan.
    pub fn check_stepped(&self, engine: &str, run: Result<Stepped, String>) -> Result<(), String> {
        let run = run.map_err(|e| format!("{}: {engine}: {e}", self.label))?;
        self.check(engine, Ok(run.outputs))?;
        for (scan, recorded) in self.trace.scans.iter().enumerate() {
            let shown = run.steps.get(scan).copied();
            if shown != Some(recorded.step) {
                return Err(format!(
                    "{}: {engine}: scan {scan} ({} ms): the program shows step {}, the simulation is in step {}",
                    self.label,
                    recorded.time_ms,
                    shown.map_or("none".to_string(), |s| s.to_string()),
                    recorded.step
                ));
            }
        }
        Ok(())
    }
}

/// Simulates a checked table and records its I/O (the files must already be
/// in `dir`); the run must pass.
pub fn record(
    label: &str,
    dir: PathBuf,
    name: &str,
    table: &steptable::table::StepTable,
    settings: &Settings,
) -> Case {
    let (case, report) = record_run(label, dir, name, table, settings);
    assert!(report.passed, "{label}: {}", report.verdict());
    case
}

/// Like [`record`], for a run that need not pass (one with faults): its
/// report comes back beside it.
pub fn record_run(
    label: &str,
    dir: PathBuf,
    name: &str,
    table: &steptable::table::StepTable,
    settings: &Settings,
) -> (Case, simulate::SimReport) {
    record_with(label, dir, name, table, settings, |program, signals| {
        simulate::simulate_recording(table, program, &settings.simulation, signals)
    })
}

/// The case of `table` under `settings`, its I/O recorded by `run` (the
/// standard simulation, or a scripted one pressing STOP or RESET) over the
/// signals of the allocation the written files use; what `run` found comes
/// back beside it.
pub fn record_with<R>(
    label: &str,
    dir: PathBuf,
    name: &str,
    table: &steptable::table::StepTable,
    settings: &Settings,
    run: impl FnOnce(&steptable::program::StepProgram, IoSignals) -> (R, IoTrace),
) -> (Case, R) {
    let program = convert::build_program(table, settings);
    let allocation = convert::allocate(&program, settings, &table.file).expect("valid pins");
    let festo = convert::festo_allocation(&program, &allocation);
    let signals = IoSignals {
        inputs: allocation.inputs.iter().map(|a| a.signal).collect(),
        outputs: allocation.outputs.iter().map(|a| a.signal).collect(),
        max_scans: None,
    };
    let (report, trace) = run(&program, signals);
    let case = Case {
        label: label.to_string(),
        dir,
        name: name.to_string(),
        mnemonic: allocation.mnemonic,
        allocation,
        festo,
        trace,
    };
    (case, report)
}

/// What one engine test of an operating scenario converts and records.
pub struct Scenario<'a> {
    pub input: &'a Path,
    /// The folder the conversion writes to.
    pub out: PathBuf,
    /// The input's stem (the written files' base name).
    pub stem: &'a str,
    pub args: &'a [&'a str],
    /// `--formats`.
    pub formats: &'a str,
    pub script: Vec<(u64, simulate::Operator)>,
    pub until_ms: u64,
}

/// The recording loop of every scenario test (single step, homing,
/// supervision): converts `input` with `args`, then records the program
/// on the simulated scenario (the simulation settings changed by
/// `adjust`, such as a fault). Returns the case the engines replay and the
/// simulation's report.
pub fn record_scenario(
    scenario: &Scenario,
    label: &str,
    adjust: impl FnOnce(&mut simulate::SimSettings),
) -> (Case, simulate::scenario::ScenarioReport) {
    steptable()
        .arg("convert")
        .arg(scenario.input)
        .args(scenario.args)
        .args(["--formats", scenario.formats, "-o"])
        .arg(&scenario.out)
        .assert()
        .success();
    let checked = convert::check_path(scenario.input, &settings_for(scenario.args)).unwrap();
    let mut simulation = checked.settings.simulation.clone();
    adjust(&mut simulation);
    record_with(
        label,
        scenario.out.join(scenario.stem),
        scenario.stem,
        &checked.table,
        &checked.settings,
        |program, signals| {
            simulate::scenario::scenario_recording(
                &checked.table,
                program,
                &simulation,
                &scenario.script,
                scenario.until_ms,
                signals,
            )
        },
    )
}

/// Converts `input` with `args` into `format` under `out` and records the
/// written program on the events the command line would give (`("press",
/// "STOP@step2")`, as `simulate --press` reads them), 8 s after the last,
/// 60 s at most: the case the engines replay, labelled `stem` and the
/// arguments, and what the simulation saw.
pub fn convert_and_record<S: AsRef<str>>(
    input: &Path,
    out: &Path,
    stem: &str,
    args: &[&str],
    format: &str,
    written: &[(S, S)],
) -> (Case, simulate::scenario::ScenarioReport) {
    use simulate::scenario::{events, scenario_events};
    steptable()
        .arg("convert")
        .arg(input)
        .args(args)
        .args(["--formats", format, "-o"])
        .arg(out)
        .assert()
        .success();
    let checked = convert::check_path(input, &settings_for(args)).unwrap();
    let (table, settings) = (&checked.table, &checked.settings);
    record_with(
        &format!("{stem} {}", args.join(" ")),
        out.join(stem),
        stem,
        table,
        settings,
        |program, signals| {
            let parsed: Vec<_> = written
                .iter()
                .map(|(o, t)| {
                    events::parse(o.as_ref(), t.as_ref(), program, table, &settings.naming)
                })
                .collect::<Result<_, _>>()
                .unwrap();
            let sim = &settings.simulation;
            // As long a run as `simulate` makes of the same events.
            let tail = simulate::scenario::tail_after_events(table, program, sim);
            let (report, trace) = scenario_events(
                table,
                program,
                sim,
                &parsed,
                (tail, u64::MAX),
                Some(signals),
            );
            (report, trace.unwrap())
        },
    )
}

/// Runs the case's written `format` file (`st`, `awl`, else FST) in its
/// engine over the recorded inputs: the outputs of every scan.
pub fn run_written(case: &Case, format: &str, python: &Path) -> Result<Vec<Vec<bool>>, String> {
    match format {
        "st" => matiec::run(
            &crate::shared(),
            &case.file(".st"),
            &case.trace,
            &case.allocation,
        ),
        "awl" => awlsim::run(
            python,
            &case.file(".awl"),
            case.mnemonic,
            &case.trace,
            &case.allocation,
        ),
        _ => {
            let text = read_ansi(&case.file(".fst.txt"))?;
            fst::run(&text, &case.trace, &case.festo)
        }
    }
}

/// The recorded inputs, one line of 0/1 per scan.
pub fn input_lines(trace: &IoTrace) -> String {
    let mut text = String::with_capacity(trace.scans.len() * (trace.signals.inputs.len() + 1));
    for scan in &trace.scans {
        text.extend(scan.inputs.iter().map(|b| if *b { '1' } else { '0' }));
        text.push('\n');
    }
    text
}

/// An engine's printed outputs, one line of 0/1 per scan.
pub fn output_lines(text: &str) -> Vec<Vec<bool>> {
    text.lines()
        .filter(|l| !l.is_empty())
        .map(|l| l.chars().map(|c| c == '1').collect())
        .collect()
}

/// Runs `work` over `items` on two threads (the machine's two cores) and
/// gathers what it returns, in no particular order.
pub fn on_two_threads<T: Sync, R: Send>(items: &[T], work: impl Fn(&T) -> Vec<R> + Sync) -> Vec<R> {
    std::thread::scope(|scope| {
        let handles: Vec<_> = items
            .chunks(items.len().div_ceil(2).max(1))
            .map(|chunk| scope.spawn(|| chunk.iter().flat_map(&work).collect::<Vec<R>>()))
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("worker"))
            .collect()
    })
}

/// A file steptable writes in Windows-1252 (`.fst.txt`, `.sdf`), as the
/// Windows tool reads it.
pub fn read_ansi(path: &Path) -> Result<String, String> {
    let bytes = std::fs::read(path).map_err(|e| format!("{}: {e}", path.display()))?;
    Ok(encoding_rs::WINDOWS_1252.decode(&bytes).0.into_owned())
}
