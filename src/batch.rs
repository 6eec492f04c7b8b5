//! Batch conversion: many inputs (files, folders walked recursively, glob
//! patterns) converted in parallel, each into its own folder; a failing file
//! never stops the others, and `summary.csv` lists what happened to each.

use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::Instant;

use rayon::prelude::*;

use crate::convert;
use crate::diag::{Diagnostic, Severity};
use crate::emit::OutputFile;
use crate::manifest;
use crate::read::Format;
use crate::settings::Settings;
use crate::write;

/// What happened to one input.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    Converted,
    /// The input is wrong (diagnostics say why); nothing written for it.
    Failed,
    /// A bug, a template that is not the user's, or an I/O failure.
    Internal,
    /// Not started: the run was interrupted (Ctrl-C) first.
    Skipped,
}

impl Status {
    pub fn label(self) -> &'static str {
        match self {
            Status::Converted => "converted",
            Status::Failed => "failed",
            Status::Internal => "internal error",
            Status::Skipped => "skipped (interrupted)",
        }
    }
}

/// The outcome of one input.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub input: PathBuf,
    /// Output folder name (distinct for colliding input names).
    pub name: String,
    pub status: Status,
    pub diagnostics: Vec<Diagnostic>,
    /// For internal failures and problems that are no cell's: what went wrong.
    pub message: Option<String>,
    pub steps: Option<usize>,
    pub actuators: Option<usize>,
    pub millis: u128,
    /// The simulation's verdict (`passed: cycle time 7.47 s`), its cycle
    /// time, and the fault table's hazards (when the outputs asked for the
    /// fault analysis), for a converted input.
    pub verdict: Option<String>,
    pub cycle_ms: Option<u64>,
    pub hazards: Option<usize>,
    /// What the conversion did to the files an earlier run wrote into the
    /// input's folder: replaced, removed, kept for the engineer.
    pub cleanup: write::Cleanup,
}

impl Outcome {
    /// An outcome of `status` with nothing else known yet.
    pub fn new(input: &Path, name: &str, status: Status) -> Outcome {
        Outcome {
            input: input.to_path_buf(),
            name: name.to_string(),
            status,
            diagnostics: Vec::new(),
            message: None,
            steps: None,
            actuators: None,
            millis: 0,
            verdict: None,
            cycle_ms: None,
            hazards: None,
            cleanup: write::Cleanup::default(),
        }
    }

    pub fn error_count(&self) -> usize {
        let cells = self
            .diagnostics
            .iter()
            .filter(|d| d.severity == Severity::Error)
            .count();
        cells + usize::from(self.message.is_some() && self.status != Status::Converted)
    }

    /// The first error, as one line.
    pub fn first_error(&self) -> Option<String> {
        self.diagnostics
            .iter()
            .find(|d| d.severity == Severity::Error)
            .map(|d| d.to_string())
            .or_else(|| self.message.clone())
    }
}

/// The inputs of a batch: the files and patterns given, expanded.
#[derive(Debug, Clone, Default)]
pub struct Expanded {
    pub found: Vec<PathBuf>,
    /// Paths that are neither a file, a folder nor a pattern matching something.
    pub missing: Vec<PathBuf>,
    /// Tables in the folders walked that a run wrote (its manifest says so,
    /// and they are unchanged since): left out, and counted to be said.
    pub outputs_skipped: Vec<PathBuf>,
    /// Folders that hold no table at all: a CI job pointed at the wrong
    /// folder must not hear that all is well.
    pub empty_folders: Vec<PathBuf>,
    /// Paths that reached a file found before (`x.xlsx ./x.xlsx`), each
    /// with the first: converted once, and said.
    pub repeated: Vec<(PathBuf, PathBuf)>,
}

/// The files and patterns to convert, expanded. Folders are walked
/// recursively for `.xlsx .xlsm .xls .ods .csv`, skipping hidden files, Excel
/// lock files (`~$…`) and the files a run wrote, as the manifest of their
/// folder records them byte for byte — never by their names alone — so a
/// rerun, even `batch . -o .`, does not convert its own outputs while an
/// engineer's table named like one still counts. A file named outright is
/// always an input.
pub fn expand_inputs(paths: &[PathBuf]) -> Expanded {
    let mut manifests = std::collections::BTreeMap::new();
    let mut expanded = Expanded::default();
    let mut keep = |files: Vec<PathBuf>, expanded: &mut Expanded| {
        for file in files {
            if manifest::written_by_a_run(&file, &mut manifests) {
                expanded.outputs_skipped.push(file);
            } else {
                expanded.found.push(file);
            }
        }
    };
    for path in paths {
        if path.is_dir() {
            let mut files = Vec::new();
            walk(path, &mut files);
            if files.is_empty() {
                expanded.empty_folders.push(path.clone());
            }
            files.sort();
            keep(files, &mut expanded);
        } else if path.is_file() {
            expanded.found.push(path.clone());
        } else {
            let pattern = path.to_string_lossy();
            let matches: Vec<PathBuf> = glob::glob(&pattern)
                .map(|paths| {
                    paths
                        .filter_map(Result::ok)
                        .filter(|p| p.is_file() && !hidden_or_lock(p))
                        .collect()
                })
                .unwrap_or_default();
            if matches.is_empty() {
                expanded.missing.push(path.clone());
            }
            keep(matches, &mut expanded);
        }
    }
    // The same file named twice (a folder and a pattern) is converted once.
    (expanded.found, expanded.repeated) = once_each(&expanded.found);
    expanded.outputs_skipped.sort();
    expanded.outputs_skipped.dedup();
    expanded
}

/// `paths` with each file once (`x.xlsx` and `./x.xlsx` are one), and each
/// path left out with the one it repeats.
pub fn once_each(paths: &[PathBuf]) -> (Vec<PathBuf>, Vec<(PathBuf, PathBuf)>) {
    let mut first = std::collections::BTreeMap::new();
    let (mut once, mut repeated) = (Vec::new(), Vec::new());
    for path in paths {
        let real = std::fs::canonicalize(path).unwrap_or_else(|_| path.clone());
        match first.get(&real) {
            Some(earlier) => repeated.push((path.clone(), PathBuf::clone(earlier))),
            None => {
                first.insert(real, path.clone());
                once.push(path.clone());
            }
        }
    }
    (once, repeated)
}

/// The file name for the batch summary in `out`: `summary.csv`, unless a
/// file of that name is there that no run recorded writing (a user's
/// table, or a summary of a version without manifests): then
/// `steptable-summary.csv`, so that nothing the user wrote is overwritten.
pub fn summary_name(out: &Path) -> &'static str {
    let ours = std::fs::symlink_metadata(out.join("summary.csv")).is_err()
        || match manifest::Manifest::read(out) {
            manifest::Found::Manifest(m) => m.vouches_for(out, "summary.csv"),
            _ => false,
        };
    if ours {
        "summary.csv"
    } else {
        "steptable-summary.csv"
    }
}

/// The header of `summary.csv`. New columns come last, so that a script
/// reading the earlier columns by place reads them still.
const SUMMARY_HEADER: [&str; 11] = [
    "file",
    "status",
    "errors",
    "first error",
    "steps",
    "actuators",
    "milliseconds",
    "folder",
    "verdict",
    "cycle seconds",
    "hazards",
];

fn walk(dir: &Path, files: &mut Vec<PathBuf>) {
    walk_once(dir, files, &mut std::collections::BTreeSet::new());
}

/// Walks `dir` unless it was walked already: a folder reached again through
/// a symbolic link (a link to itself, or to a parent) is walked once.
fn walk_once(dir: &Path, files: &mut Vec<PathBuf>, seen: &mut std::collections::BTreeSet<PathBuf>) {
    let Ok(real) = std::fs::canonicalize(dir) else {
        return;
    };
    if !seen.insert(real) {
        return;
    }
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if hidden_or_lock(&path) {
            continue;
        }
        if path.is_dir() {
            walk_once(&path, files, seen);
        } else if Format::from_path(&path)
            .is_some_and(|f| f != Format::Csv || has_csv_extension(&path))
        {
            files.push(path);
        }
    }
}

/// A hidden file or folder, or the lock file Excel keeps beside an open
/// workbook (`~$line.xlsx`, which `*.xlsx` matches): never a table.
fn hidden_or_lock(path: &Path) -> bool {
    path.file_name()
        .map(|n| n.to_string_lossy())
        .is_some_and(|n| n.starts_with('.') || n.starts_with("~$"))
}

/// Folders hold many `.txt` files that are not tables: only `.csv` counts there.
fn has_csv_extension(path: &Path) -> bool {
    path.extension()
        .is_some_and(|e| e.to_string_lossy().eq_ignore_ascii_case("csv"))
}

/// Most conversions run at once: more threads than this only cost memory.
pub const MAX_JOBS: usize = 64;

/// Converts every input into `out/NAME/`, `jobs` at a time, calling
/// `on_done` as each finishes. Once `stop` is set, inputs not yet started are
/// skipped; those under way finish (their files land whole). Outcomes come
/// back in input order.
pub fn run(
    inputs: &[PathBuf],
    out: &Path,
    settings: &Settings,
    jobs: usize,
    stop: &AtomicBool,
    on_done: &(dyn Fn(&Outcome) + Sync),
) -> Vec<Outcome> {
    let names = convert::output_names(inputs);
    let kept = write::Inputs::new(inputs);
    let convert_one = |(input, name): (&PathBuf, &String)| {
        let outcome = if stop.load(Ordering::SeqCst) {
            Outcome::new(input, name, Status::Skipped)
        } else {
            convert_one(input, name, out, settings, &kept)
        };
        on_done(&outcome);
        outcome
    };
    let work: Vec<(&PathBuf, &String)> = inputs.iter().zip(&names).collect();
    match rayon::ThreadPoolBuilder::new()
        .num_threads(jobs.max(1))
        .build()
    {
        Ok(pool) => pool.install(|| work.into_par_iter().map(convert_one).collect()),
        // No thread pool (an exotic platform): one at a time still works.
        Err(_) => work.into_iter().map(convert_one).collect(),
    }
}

fn convert_one(
    input: &Path,
    name: &str,
    out: &Path,
    settings: &Settings,
    all_inputs: &write::Inputs,
) -> Outcome {
    let start = Instant::now();
    let mut outcome = Outcome::new(input, name, Status::Converted);
    use crate::commands::{CommandError, convert::run};
    match run(input, name, settings, out, all_inputs, &|_, _| {}) {
        Ok(run) => {
            let conversion = run.conversion;
            outcome.steps = Some(conversion.table.steps.len());
            outcome.actuators = Some(conversion.table.actuators.len());
            outcome.verdict = Some(conversion.simulation.verdict());
            outcome.cycle_ms = conversion
                .simulation
                .cycles
                .first()
                .and_then(|c| c.cycle_ms);
            outcome.hazards = conversion.faults.as_ref().map(|f| {
                f.cases
                    .iter()
                    .filter(|c| c.outcome == crate::faults::Outcome::Hazard)
                    .count()
            });
            outcome.diagnostics = conversion.warnings;
            match run.written {
                Ok((_, cleanup)) => outcome.cleanup = cleanup,
                // Something of the engineer's is in the way: said, kept.
                Err(write::WriteError::Taken(problems)) => {
                    outcome.status = Status::Failed;
                    // Nothing was written: no verdict to file.
                    (outcome.verdict, outcome.cycle_ms, outcome.hazards) = (None, None, None);
                    outcome.diagnostics.extend(problems);
                }
                Err(err) => {
                    outcome.status = Status::Internal;
                    outcome.message = Some(err.to_string());
                }
            }
        }
        Err(CommandError::Input(diagnostics)) => {
            outcome.status = Status::Failed;
            outcome.diagnostics = diagnostics;
        }
        Err(CommandError::Template(err)) => {
            outcome.status = if err.user {
                Status::Failed
            } else {
                Status::Internal
            };
            outcome.message = Some(err.to_string());
        }
        Err(CommandError::Internal(why)) => {
            outcome.status = Status::Internal;
            outcome.message = Some(why);
        }
        Err(CommandError::Write(err)) => {
            outcome.status = Status::Internal;
            outcome.message = Some(err.to_string());
        }
    }
    outcome.millis = start.elapsed().as_millis();
    outcome
}

/// `summary.csv`: file, status, error count, first error, steps, actuators,
/// milliseconds, the folder in the output folder its files went to
/// (empty where nothing was written), the simulation's verdict, the cycle
/// time in seconds and the fault table's hazard count (empty where the
/// outputs asked for no fault analysis) — one row per input, in input order.
pub fn summary_csv(outcomes: &[Outcome]) -> Result<OutputFile, csv::Error> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(SUMMARY_HEADER)?;
    for o in outcomes {
        writer.write_record([
            o.input.display().to_string(),
            o.status.label().to_string(),
            o.error_count().to_string(),
            o.first_error().unwrap_or_default(),
            o.steps.map(|s| s.to_string()).unwrap_or_default(),
            o.actuators.map(|s| s.to_string()).unwrap_or_default(),
            o.millis.to_string(),
            if o.status == Status::Converted {
                o.name.clone()
            } else {
                String::new()
            },
            o.verdict.clone().unwrap_or_default(),
            o.cycle_ms
                .map(|ms| format!("{:.2}", ms as f64 / 1000.0))
                .unwrap_or_default(),
            o.hazards.map(|h| h.to_string()).unwrap_or_default(),
        ])?;
    }
    let bytes = writer
        .into_inner()
        .map_err(|e| csv::Error::from(std::io::Error::other(e.to_string())))?;
    Ok(OutputFile {
        name: "summary.csv".to_string(),
        bytes,
    })
}
