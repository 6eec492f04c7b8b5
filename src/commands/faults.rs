//! `faults`: what every sensor stuck at 1 or 0 (or several at once) does
//! to the machine, as `NAME.faults.csv` in `DIR/NAME/`.

use std::path::{Path, PathBuf};

use super::CommandError;
use crate::convert;
use crate::diag::{Code, Diagnostic, Location, Severity};
use crate::emit::{OutputFile, OutputKind};
use crate::faults::{self, FaultTable};
use crate::program::StepProgram;
use crate::provenance::{self, MadeBy};
use crate::settings::Settings;
use crate::symbols::SymbolTable;
use crate::table::StepTable;
use crate::write::{self, WriteError};

/// How many faults at once, and how the command line asked for it (the
/// budget's message names the option).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FaultsOptions {
    /// Up to this many faults at once (1 to 4).
    pub at_once: usize,
    /// Asked for as `--pairs` rather than `--faults K`.
    pub pairs: bool,
}

/// What a fault analysis found and wrote.
#[derive(Debug)]
pub struct FaultsRun {
    pub table: StepTable,
    pub warnings: Vec<Diagnostic>,
    pub result: FaultTable,
    /// The table's names and designations, as in every output of convert.
    pub symbols: SymbolTable,
    /// The paths written, or why the table could not be written (the
    /// analysis stands: the caller still shows it).
    pub written: Result<Vec<PathBuf>, WriteError>,
}

/// Analyses the table `input` under `settings` and writes its fault table
/// into `out/name/`, never over a file of `inputs`; `progress(done,
/// total)` is called as the cases run.
pub fn run(
    input: &Path,
    name: &str,
    settings: &Settings,
    options: FaultsOptions,
    out: &Path,
    inputs: &write::Inputs,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<FaultsRun, CommandError> {
    let checked = convert::check_path(input, settings).map_err(CommandError::Input)?;
    let warnings = checked.warnings;
    let (table, settings) = (checked.table, checked.settings);
    let analysed = analyse(&table, &settings, options, progress).map_err(|e| e.after(&warnings));
    let (program, result) = analysed?;
    let symbols = SymbolTable::build(&program, &table, &settings.naming);
    let made_by = MadeBy::of_run(&settings, &table.file);
    let file = crate::emit::faults_csv::render(&result, &|s| symbols.designation(s), &|t| {
        symbols.explain(t)
    })
    .map(|bytes| OutputFile {
        name: OutputKind::Faults.file_name(name),
        bytes,
    })
    .map_err(|e| CommandError::Internal(format!("fault table: {e}")))?;
    let file = provenance::stamp(file, &made_by).map_err(CommandError::Internal)?;
    let written = write::write_outputs(
        &out.join(name),
        &[file],
        inputs,
        settings.durability,
        Some(made_by.text()),
    );
    Ok(FaultsRun {
        table,
        warnings,
        result,
        symbols,
        written,
    })
}

/// The healthy program, both budgets (cases and steps fired) and the
/// analysis, with the program it ran.
fn analyse(
    table: &StepTable,
    settings: &Settings,
    options: FaultsOptions,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<(StepProgram, FaultTable), CommandError> {
    let at_once = options.at_once;
    let convert::Proven {
        program, healthy, ..
    } = convert::proven_program(table, settings, &settings.simulation, Some(at_once), false)?;
    // The program `convert` would refuse to write (a board too small, a
    // wrong pin) has no fault table either: the same errors.
    convert::allocate(&program, settings, &table.file).map_err(CommandError::Input)?;
    let cases = faults::case_count(&program, at_once);
    if cases > faults::MAX_CASES {
        let asked = if options.pairs {
            "--pairs".to_string()
        } else {
            format!("--faults {at_once}")
        };
        return Err(CommandError::Input(vec![Diagnostic {
            severity: Severity::Error,
            code: Code::E033OverBudget,
            location: Location {
                file: table.file.clone(),
                sheet: None,
                cell: None,
            },
            message: format!(
                "{asked} would simulate {cases} fault cases ({} inputs, each stuck at 1 and at 0, up to {at_once} at once); steptable runs at most {}: analyse fewer faults at once (single faults without {}), or split the table",
                program.signals.inputs.len(),
                faults::MAX_CASES,
                if options.pairs { "--pairs" } else { "--faults" },
            ),
        }]));
    }
    if let Some(why) = faults::over_budget(table, &program, &settings.simulation, at_once) {
        return Err(CommandError::Input(vec![convert::budget_error(table, why)]));
    }
    let result = faults::analyse_from(
        table,
        &program,
        &settings.simulation,
        at_once,
        faults::FaultRuns::Resumed,
        progress,
        healthy,
    );
    Ok((program, result))
}
