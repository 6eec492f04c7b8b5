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
                self.report.reason()
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
    let diagram = match diagram {
        Some(dir) => {
            let made_by = MadeBy::of_run(&settings, &table.file);
            let symbols = SymbolTable::build(&program, &table, &settings.naming);
            let parts = |n| symbols.actuator_parts(n);
            let file = OutputFile {
                name: CommandFile::TimeDiagram.file_name(name),
                bytes: render_svg(name, &report, DiagramKind::Time, &parts).into_bytes(),
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
        diagram,
    })
}

/// What a scenario did and wrote.
#[derive(Debug)]
pub struct ScenarioRun {
    pub warnings: Vec<Diagnostic>,
    /// The scenario's run, printed as a step table.
    pub table: String,
}

/// Runs the program of the table `input` under `settings` with the
/// operator's events `written` (`("press", "STOP@step3")`, in the order of
/// the command line), for as long after the last event as one healthy
/// cycle takes. An event the program cannot run is E042.
pub fn scenario(
    input: &Path,
    settings: &Settings,
    written: &[(String, String)],
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
    bad.extend(events::check(&events));
    if !bad.is_empty() {
        let at = |message| event_error(&table, message);
        return Err(refused(bad.into_iter().map(at).collect()));
    }
    let sim = &settings.simulation;
    let proof = simulate::simulate(&table, &program, sim);
    // As long after the last event as a healthy cycle takes, and a second
    // to see the machine stand.
    let cycle = proof
        .cycles
        .first()
        .and_then(|c| c.cycle_ms)
        .unwrap_or(10_000);
    let tail = cycle + 1_000;
    let until = u64::from(events::LATEST_MS) + tail;
    let (run, _) = sc::scenario_events(&table, &program, sim, &events, (tail, until), None);
    let symbols = SymbolTable::build(&program, &table, naming);
    let designation = |s| symbols.designation(s);
    let actuator = |n| symbols.actuator(n);
    let names = printed::Names {
        signal: &designation,
        actuator: &actuator,
    };
    let numbers: Vec<u32> = table.actuators.iter().map(|a| a.number).collect();
    let printed = printed::render(&run, &events, &program, &numbers, &names);
    Ok(ScenarioRun {
        warnings,
        table: printed,
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
