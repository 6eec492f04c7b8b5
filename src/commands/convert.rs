//! `convert` and `check` for one table: [`crate::convert`]'s stages in
//! memory, then the write of the whole set of files into `DIR/NAME/`
//! ([`crate::write::write_conversion`]); `check` stops before anything is
//! rendered. `batch` runs [`run`] for each of its tables.

use std::path::{Path, PathBuf};

use super::CommandError;
use crate::address::Allocation;
use crate::convert::{self, Conversion};
use crate::diag::Diagnostic;
use crate::settings::Settings;
use crate::table::StepTable;
use crate::write::{self, WriteError};

/// What a conversion made and wrote.
#[derive(Debug)]
pub struct ConvertRun {
    pub conversion: Conversion,
    /// The folder the files go into (`DIR/NAME/`).
    pub folder: PathBuf,
    /// The paths written and what became of the files of an earlier run,
    /// or why nothing was written.
    pub written: Result<(Vec<PathBuf>, write::Cleanup), WriteError>,
}

/// Converts the table `input` under `settings` and writes every output
/// into `out/name/`, never over a file of `inputs`; `progress(done, total)`
/// is called as the fault analysis runs its cases.
pub fn run(
    input: &Path,
    name: &str,
    settings: &Settings,
    out: &Path,
    inputs: &write::Inputs,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<ConvertRun, CommandError> {
    let checked = convert::check_path(input, settings).map_err(CommandError::Input)?;
    let warnings = checked.warnings.clone();
    let conversion = convert::generate_observed(name, checked, progress)
        .map_err(|f| CommandError::from(f).after(&warnings))?;
    let folder = out.join(&conversion.name);
    let written = write::write_conversion(
        &folder,
        &conversion.files,
        inputs,
        settings.durability,
        Some(conversion.made_by.text()),
    )
    .map_err(|err| match err {
        // Each problem is at an output's path: among several inputs, it
        // names the one it belongs to too, in either message format.
        WriteError::Taken(problems) => WriteError::Taken(
            problems
                .into_iter()
                .map(|mut d| {
                    d.message = format!("(converting {}) {}", input.display(), d.message);
                    d
                })
                .collect(),
        ),
        err => err,
    });
    Ok(ConvertRun {
        conversion,
        folder,
        written,
    })
}

/// What `check` found in a table that passes: the table, its addresses
/// and its warnings.
#[derive(Debug)]
pub struct CheckRun {
    pub table: StepTable,
    pub allocation: Allocation,
    pub warnings: Vec<Diagnostic>,
}

/// Reads and checks the table `input` under `settings`, its addresses too
/// (pins and the board are part of what convert would refuse); writes
/// nothing. The problems, warnings among them, when it does not pass.
pub fn check(input: &Path, settings: &Settings) -> Result<CheckRun, Vec<Diagnostic>> {
    let checked = convert::check_path(input, settings)?;
    let program = convert::build_program(&checked.table, &checked.settings);
    let refused = convert::refused_without_a_run(&checked.table, &checked.settings, &program);
    if !refused.is_empty() {
        return Err(refused.into_iter().chain(checked.warnings).collect());
    }
    let allocation = convert::allocate(&program, &checked.settings, &checked.table.file)?;
    // What the outputs asked for would lose or refuse, as convert says it.
    let name = convert::output_name(input);
    let mut warnings = checked.warnings;
    match convert::output_findings(
        &name,
        &checked.table,
        &checked.settings,
        &program,
        &allocation,
    ) {
        Ok(found) => warnings.extend(found),
        Err(refused) => return Err(refused.into_iter().chain(warnings).collect()),
    }
    Ok(CheckRun {
        table: checked.table,
        allocation,
        warnings,
    })
}
