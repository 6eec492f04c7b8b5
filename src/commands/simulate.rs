//! `simulate`: the generated program against the model of the machine,
//! with its verdict, step timing and, when asked, the displacement-time
//! diagram `NAME.time.svg` in `DIR/NAME/`.

use std::path::{Path, PathBuf};

use super::CommandError;
use crate::convert::{self, Failure};
use crate::diag::{Code, Diagnostic, Location, Severity};
use crate::emit::diagram::{DiagramKind, render_svg};
use crate::emit::{CommandFile, OutputFile};
use crate::provenance::{self, MadeBy};
use crate::settings::Settings;
use crate::simulate::{self, SimReport};
use crate::symbols::SymbolTable;
use crate::table::StepTable;
use crate::write::{self, WriteError};

/// What a simulation found and wrote.
#[derive(Debug)]
pub struct SimulateRun {
    pub table: StepTable,
    pub warnings: Vec<Diagnostic>,
    pub report: SimReport,
    /// The program's names: what the run found is said in them.
    pub symbols: SymbolTable,
    /// With a diagram asked for: the paths written, or why not.
    pub diagram: Option<Result<Vec<PathBuf>, WriteError>>,
}

impl SimulateRun {
    /// E032 when the program fails its simulation (the report says why).
    pub fn failure(&self) -> Option<Diagnostic> {
        (!self.report.passed).then(|| Diagnostic {
            severity: Severity::Error,
            code: Code::E032MachineCannotRun,
            location: Location {
                file: self.table.file.clone(),
                sheet: None,
                cell: None,
            },
            message: format!(
                "the generated program fails its simulation: {}",
                self.symbols.explain(&self.report.reason())
            ),
        })
    }
}

/// Simulates the program of the table `input` under `settings` (a failed
/// run is a report, not an error: it is what the command shows); with
/// `diagram`, writes the run's time diagram into `diagram/name/`, never
/// over a file of `inputs`.
pub fn run(
    input: &Path,
    name: &str,
    settings: &Settings,
    diagram: Option<&Path>,
    inputs: &write::Inputs,
) -> Result<SimulateRun, CommandError> {
    let checked = convert::check_path(input, settings).map_err(CommandError::Input)?;
    let warnings = checked.warnings;
    let (table, mut settings) = (checked.table, checked.settings);
    let refused = |problems: Vec<Diagnostic>| CommandError::Input(problems).after(&warnings);
    let lucky = convert::lucky_middle_stops(&table, &settings);
    if !lucky.is_empty() {
        return Err(refused(lucky));
    }
    settings.simulation.record_trace = diagram.is_some();
    let program = convert::build_program(&table, &settings);
    if let Some(why) = simulate::over_budget(&table, &program, &settings.simulation) {
        return Err(refused(vec![convert::budget_error(&table, why)]));
    }
    let report = simulate::simulate(&table, &program, &settings.simulation);
    let symbols = SymbolTable::build(&program, &table, &settings.naming);
    let diagram = match diagram {
        Some(dir) => {
            let made_by = MadeBy::of_run(&settings, &table.file);
            let file = OutputFile {
                name: CommandFile::TimeDiagram.file_name(name),
                bytes: render_svg(name, &report, DiagramKind::Time, &symbols).into_bytes(),
            };
            let file = provenance::stamp(file, &made_by)
                .map_err(|why| CommandError::from(Failure::Internal(why)))?;
            Some(write::write_outputs(
                &dir.join(name),
                &[file],
                inputs,
                settings.durability,
                Some(made_by.text()),
            ))
        }
        None => None,
    };
    Ok(SimulateRun {
        table,
        warnings,
        report,
        symbols,
        diagram,
    })
}

/// What a scenario did and wrote.
#[derive(Debug)]
pub struct ScenarioRun {
    pub warnings: Vec<Diagnostic>,
    /// The problems the run found, as the table prints them (W014): what a
    /// script reading JSON sees of them.
    pub problems: Vec<Diagnostic>,
    /// The scenario's run, printed as a step table.
    pub table: String,
    /// With a report asked for: the paths written, or why not.
    pub report: Option<Result<Vec<PathBuf>, WriteError>>,
}

/// Where a scenario's page goes, if asked for: the folder (the page lands
/// in `dir/NAME/`), the outputs' name, and the inputs never to overwrite.
pub struct ScenarioReport<'a> {
    pub dir: &'a Path,
    pub name: &'a str,
    pub inputs: &'a write::Inputs,
}

/// Runs the program of the table `input` under `settings` with the
/// operator's events `written` (`("press", "STOP@step3")`, in the order of
/// the command line), for as long after the last event as one healthy
/// cycle takes; with `report`, draws the run on the report's timeline in
/// `NAME.scenario.report.html`. An event the program cannot run is E042,
/// and nothing is run or written.
pub fn scenario(
    input: &Path,
    settings: &Settings,
    written: &[(String, String)],
    report: Option<ScenarioReport>,
) -> Result<ScenarioRun, CommandError> {
    use crate::simulate::scenario::{self as sc, events, table as printed};
    let checked = convert::check_path(input, settings).map_err(CommandError::Input)?;
    let warnings = checked.warnings;
    let (table, settings) = (checked.table, checked.settings);
    let refused = |problems: Vec<Diagnostic>| CommandError::Input(problems).after(&warnings);
    let program = convert::build_program(&table, &settings);
    let naming = &settings.naming;
    let mut events = Vec::new();
    let mut bad = Vec::new();
    for (option, text) in written {
        match events::parse(option, text, &program, &table, naming) {
            Ok(event) => events.push(event),
            Err(why) => bad.push(why),
        }
    }
    bad.extend(sc::check::check(&events, settings.simulation.scan_ms));
    if !bad.is_empty() {
        let at = |message| event_error(&table, message);
        return Err(refused(bad.into_iter().map(at).collect()));
    }
    let sim = &settings.simulation;
    let tail = sc::tail_after_events(&table, &program, sim);
    // The events and their tail end the run (or the scan budget does).
    let until = u64::MAX;
    // The page draws as much of the run as the report's timeline does.
    let signals = report.is_some().then(|| simulate::io::IoSignals {
        max_scans: Some(crate::emit::report::TIMELINE_SCANS),
        ..simulate::io::IoSignals::every(&program)
    });
    let (run, trace) = sc::scenario_events(&table, &program, sim, &events, (tail, until), signals);
    let symbols = SymbolTable::build(&program, &table, naming);
    let designation = |s| symbols.designation(s);
    let actuator = |n| symbols.actuator_in_finding(n);
    let explain = |text: &str| symbols.explain(text);
    let names = printed::Names {
        signal: &designation,
        actuator: &actuator,
        explain: &explain,
    };
    let numbers: Vec<u32> = table.actuators.iter().map(|a| a.number).collect();
    let printed = printed::render(&run, &events, &program, &numbers, &names);
    let report = match (report, trace) {
        (Some(to), Some(trace)) => {
            let drawn = Drawn {
                table: &table,
                settings: &settings,
                run: &run,
                events: &events,
                trace: &trace,
                printed: &printed,
                names: &names,
            };
            Some(write_scenario_page(&drawn, &to)?)
        }
        _ => None,
    };
    let problems = printed::problems(&run)
        .map(|p| Diagnostic {
            severity: Severity::Warning,
            code: Code::W014ScenarioProblem,
            location: Location {
                file: table.file.clone(),
                sheet: None,
                cell: None,
            },
            message: format!(
                "at {:.2} s in step {}: {}",
                p.time_ms as f64 / 1000.0,
                p.step,
                explain(&p.message)
            ),
        })
        .collect();
    Ok(ScenarioRun {
        warnings,
        problems,
        table: printed,
        report,
    })
}

/// E042 at the table's file (an event is no cell of it).
fn event_error(table: &StepTable, message: String) -> Diagnostic {
    Diagnostic {
        severity: Severity::Error,
        code: Code::E042BadScenarioEvent,
        location: Location {
            file: table.file.clone(),
            sheet: None,
            cell: None,
        },
        message,
    }
}

/// A scenario's run with what the page draws it from.
struct Drawn<'a> {
    table: &'a StepTable,
    settings: &'a Settings,
    run: &'a simulate::scenario::ScenarioReport,
    events: &'a [simulate::scenario::Event],
    trace: &'a simulate::io::IoTrace,
    printed: &'a str,
    names: &'a simulate::scenario::table::Names<'a>,
}

/// Writes `NAME.scenario.report.html` into `to.dir/NAME/`: the outcome of
/// the write, or an internal failure to stamp it.
fn write_scenario_page(
    drawn: &Drawn,
    to: &ScenarioReport,
) -> Result<Result<Vec<PathBuf>, WriteError>, CommandError> {
    use crate::emit::report::{scenario as page, timeline};
    let table = drawn.table;
    let actuators: Vec<(u32, u32)> = table
        .actuators
        .iter()
        .map(|a| (a.number, a.max_position))
        .collect();
    // No further than the recording goes (it stops at the report's limit).
    let recorded = drawn.trace.scans.last().map_or(0, |s| s.time_ms);
    let positions: Vec<(u64, Vec<f64>)> = drawn
        .run
        .samples
        .iter()
        .take_while(|s| s.time_ms <= recorded)
        .map(|s| (s.time_ms, s.positions.clone()))
        .collect();
    // Each event at the scan it happened in, as the printed table has it.
    let marks: Vec<(u64, String)> = drawn
        .run
        .happened
        .iter()
        .map(|(t, k)| (*t, drawn.events[*k].written.clone()))
        .collect();
    let source = Path::new(&table.file)
        .file_name()
        .map_or(table.file.clone(), |n| n.to_string_lossy().to_string());
    let bytes = page::render(&page::ScenarioPage {
        name: to.name,
        source: &source,
        printed: drawn.printed,
        drawn: timeline::Drawn {
            press_ms: 0,
            spans: &drawn.run.spans,
            actuators: &actuators,
            positions: &positions,
            marks: &marks,
        },
        trace: drawn.trace,
        signal: drawn.names.signal,
        actuator: drawn.names.actuator,
    });
    let made_by = MadeBy::of_run(drawn.settings, &table.file);
    let file = OutputFile {
        name: CommandFile::ScenarioReport.file_name(to.name),
        bytes: bytes.into_bytes(),
    };
    let file = provenance::stamp(file, &made_by)
        .map_err(|why| CommandError::from(Failure::Internal(why)))?;
    Ok(write::write_outputs(
        &to.dir.join(to.name),
        &[file],
        to.inputs,
        drawn.settings.durability,
        Some(made_by.text()),
    ))
}
