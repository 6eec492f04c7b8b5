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
        symbols,
        diagram,
    })
}
