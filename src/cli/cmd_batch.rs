//! `steptable batch`: many inputs in parallel, with a progress bar and a summary.

use super::*;

#[derive(Args)]
pub(crate) struct BatchArgs {
    /// Files, folders (searched recursively for .xlsx .xlsm .xls .ods .csv) or glob patterns.
    #[arg(required = true)]
    pub(crate) paths: Vec<PathBuf>,
    /// Output folder: one folder per input, and summary.csv.
    #[arg(short, long, value_name = "DIR")]
    pub(crate) output: PathBuf,
    /// Conversions at once, 1 to 64 (default: all cores).
    #[arg(short, long, value_name = "N", value_parser = parse_jobs)]
    pub(crate) jobs: Option<usize>,
    /// No progress bar.
    #[arg(short, long)]
    pub(crate) quiet: bool,
    #[command(flatten)]
    pub(crate) files: FileArgs,
    #[command(flatten)]
    pub(crate) common: CommonArgs,
    #[command(flatten)]
    pub(crate) sim: SimArgs,
}

/// `-j N`: 0 would run nothing, and reading it as one job or as every core
/// would be a guess either way (`xargs -P 0` means as many as possible,
/// `make -j 0` is refused): refused, with what to write instead. More than
/// the most steptable runs is a note at the run, not an error.
fn parse_jobs(text: &str) -> Result<usize, String> {
    match text.trim().parse::<usize>() {
        Ok(0) => Err(format!(
            "-j takes 1 to {} jobs; 0 runs nothing (leave -j out for one job per core)",
            crate::batch::MAX_JOBS
        )),
        Ok(jobs) => Ok(jobs),
        Err(_) => Err(format!(
            "\"{text}\" is not a number of jobs; -j takes 1 to {}",
            crate::batch::MAX_JOBS
        )),
    }
}

pub(crate) fn run_batch(args: &BatchArgs) -> i32 {
    use crate::batch;

    let report = Reporter::new(&args.common);
    let Some(settings) = output_settings(&args.common, &args.sim, &args.files) else {
        return EXIT_BAD_INPUT;
    };
    // An output folder that is a file: one clear refusal, before any work.
    if let Some(problem) = write::output_folder_problem(&args.output) {
        report.diagnostics(&[problem]);
        return EXIT_BAD_INPUT;
    }
    let started = std::time::Instant::now();
    let expanded = batch::expand_inputs(&args.paths);
    report.diagnostics(&unmatched(&expanded.missing, NO_SUCH_PATH));
    report.diagnostics(&unmatched(&expanded.empty_folders, NO_TABLE_IN_FOLDER));
    if !expanded.outputs_skipped.is_empty() {
        report.say(&format!(
            "note: {} table(s) in the folders are outputs of an earlier run (listed in their folder's {}) and are not converted again, e.g. {}",
            expanded.outputs_skipped.len(),
            crate::manifest::FILE_NAME,
            display_name(&expanded.outputs_skipped[0])
        ));
    }
    for (again, first) in &expanded.repeated {
        report.say(&format!(
            "note: {} names the file {} again; converted once",
            again.display(),
            first.display()
        ));
    }
    let inputs = &expanded.found;
    let missing: &Vec<PathBuf> = &[&expanded.missing[..], &expanded.empty_folders[..]].concat();
    let jobs = job_count(args, &report);
    let bar = progress_bar(args, inputs.len());
    let on_done = |outcome: &batch::Outcome| {
        if let Some(bar) = &bar {
            bar.set_message(display_name(&outcome.input));
            bar.inc(1);
        }
    };
    // Ctrl-C: let the conversions under way finish (their files land whole),
    // skip the rest, and still write the summary.
    static STOP: std::sync::atomic::AtomicBool = std::sync::atomic::AtomicBool::new(false);
    let _ = ctrlc::set_handler(|| STOP.store(true, std::sync::atomic::Ordering::SeqCst));
    let outcomes = batch::run(inputs, &args.output, &settings, jobs, &STOP, &on_done);
    let interrupted = STOP.load(std::sync::atomic::Ordering::SeqCst);
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }
    let mut code = outcome_code(args, &outcomes, missing, &report);
    // A path that named nothing is a failed input too, in the closing
    // lines and in summary.csv (said above, when it was found).
    let mut outcomes = outcomes;
    outcomes.extend(unmatched_outcomes(&expanded));
    let run = Run {
        outcomes: &outcomes,
        interrupted,
        seconds: started.elapsed().as_secs_f64(),
        jobs,
    };
    run.say(args, &report);
    code = code.max(write_summary(args, &outcomes, inputs, &settings, &report));
    if interrupted {
        // The shell's convention for a run ended by Ctrl-C.
        return EXIT_INTERRUPTED;
    }
    code
}

const NO_SUCH_PATH: &str = "no such file or folder, and no file matches it as a pattern";
const NO_TABLE_IN_FOLDER: &str = "the folder holds no table (searched with its subfolders for .xlsx, .xlsm, .xls, .ods and .csv files)";

/// A path that names nothing, or a folder with nothing to convert, is an
/// input that cannot be read: E001, as convert says it, so a script
/// reading the JSON sees it too.
fn unmatched(missing: &[PathBuf], why: &str) -> Vec<Diagnostic> {
    missing
        .iter()
        .map(|path| Diagnostic {
            severity: Severity::Error,
            code: crate::diag::Code::E001Unreadable,
            location: crate::diag::Location {
                file: display_name(path),
                sheet: None,
                cell: None,
            },
            message: crate::read::dangling_link(path).unwrap_or_else(|| why.to_string()),
        })
        .collect()
}

/// The failed outcomes of the paths that named nothing to convert.
fn unmatched_outcomes(expanded: &crate::batch::Expanded) -> Vec<crate::batch::Outcome> {
    let said = [
        (&expanded.missing, NO_SUCH_PATH),
        (&expanded.empty_folders, NO_TABLE_IN_FOLDER),
    ];
    said.into_iter()
        .flat_map(|(paths, why)| {
            paths
                .iter()
                .zip(unmatched(paths, why))
                .map(|(path, diagnostic)| {
                    let mut outcome =
                        crate::batch::Outcome::new(path, "", crate::batch::Status::Failed);
                    outcome.diagnostics.push(diagnostic);
                    outcome
                })
        })
        .collect()
}

/// `-j`, or one job per core; never more than steptable runs at once.
fn job_count(args: &BatchArgs, report: &Reporter) -> usize {
    let jobs = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    if jobs > crate::batch::MAX_JOBS {
        report.say(&format!(
            "note: -j {jobs} is more than steptable runs at once; running {} jobs",
            crate::batch::MAX_JOBS
        ));
        return crate::batch::MAX_JOBS;
    }
    jobs
}

/// A progress bar on a terminal, unless `--quiet`.
fn progress_bar(args: &BatchArgs, inputs: usize) -> Option<indicatif::ProgressBar> {
    use std::io::IsTerminal;
    if args.quiet || !std::io::stderr().is_terminal() {
        return None;
    }
    let bar = indicatif::ProgressBar::new(inputs as u64);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{bar:30} {pos}/{len} workbooks, {per_sec}, {elapsed} {msg}",
        )
        .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
    );
    Some(bar)
}

/// Every input's diagnostics said, and the exit code their outcomes make.
fn outcome_code(
    args: &BatchArgs,
    outcomes: &[crate::batch::Outcome],
    missing: &[PathBuf],
    report: &Reporter,
) -> i32 {
    use crate::batch::Status;
    let mut code = if missing.is_empty() {
        EXIT_OK
    } else {
        EXIT_BAD_INPUT
    };
    for o in outcomes {
        report.diagnostics(&o.diagnostics);
        match o.status {
            Status::Converted => {}
            Status::Failed => code = code.max(EXIT_BAD_INPUT),
            Status::Internal => code = EXIT_INTERNAL,
            Status::Skipped => {}
        }
    }
    // Inputs sharing a name go to other folders than their own (the rule
    // convert uses too): said here and in summary.csv's `folder` column.
    for o in outcomes {
        if o.status == Status::Converted && crate::convert::renamed(&o.input, &o.name) {
            report.say(&format!(
                "note: {} -> {}/ (another input has the name {})",
                display_name(&o.input),
                args.output.join(&o.name).display(),
                crate::convert::output_name(&o.input)
            ));
        }
    }
    code
}

/// What a batch run did, for its closing lines.
struct Run<'a> {
    outcomes: &'a [crate::batch::Outcome],
    interrupted: bool,
    seconds: f64,
    jobs: usize,
}

impl Run<'_> {
    /// The count converted and failed, the speed, and each failure's
    /// first error.
    fn say(&self, args: &BatchArgs, report: &Reporter) {
        use crate::batch::Status;
        let failed: Vec<&crate::batch::Outcome> = self
            .outcomes
            .iter()
            .filter(|o| !matches!(o.status, Status::Converted | Status::Skipped))
            .collect();
        let skipped = self
            .outcomes
            .iter()
            .filter(|o| o.status == Status::Skipped)
            .count();
        if self.interrupted {
            report.say(&format!(
                "interrupted: {skipped} input(s) not started; everything written is complete"
            ));
        }
        let (seconds, jobs) = (self.seconds, self.jobs);
        report.say(&format!(
            "{} converted, {} failed, in {:.2} s ({:.1} workbooks/s, {} job{}) -> {}",
            self.outcomes.len() - failed.len() - skipped,
            failed.len(),
            seconds,
            self.outcomes.len() as f64 / seconds.max(1e-9),
            jobs,
            if jobs == 1 { "" } else { "s" },
            args.output.display()
        ));
        for o in &failed {
            // A diagnostic names its file; other failures need the name added.
            let input = display_name(&o.input);
            let first = match o.diagnostics.iter().find(|d| d.severity == Severity::Error) {
                // At another file (E040: an input an output would replace):
                // the line starts with the input that failed (rt25 F3).
                Some(d) if !d.to_string().starts_with(&format!("{input}:")) => {
                    format!("{input}: {d}")
                }
                Some(d) => d.to_string(),
                None => format!(
                    "{input}: {}",
                    o.message
                        .clone()
                        .unwrap_or_else(|| o.status.label().to_string())
                ),
            };
            report.say(&format!("  failed: {first}"));
        }
        // What a rerun did to an earlier run's files is said, as convert
        // says it: what it replaced or removed, what it kept for the
        // engineer to remove.
        for o in self.outcomes {
            let folder = args.output.join(&o.name);
            for line in super::cmd_convert::cleanup_lines(&o.cleanup, &folder, Some(&folder)) {
                report.say(&line);
            }
        }
    }
}

/// Writes `summary.csv` (or the name that does not overwrite the
/// engineer's own); the exit code of that.
fn write_summary(
    args: &BatchArgs,
    outcomes: &[crate::batch::Outcome],
    inputs: &[PathBuf],
    settings: &Settings,
    report: &Reporter,
) -> i32 {
    use crate::batch;
    match batch::summary_csv(outcomes) {
        Ok(mut file) => {
            file.name = batch::summary_name(&args.output).to_string();
            if file.name != "summary.csv" {
                report.say(&format!(
                    "note: {} holds a summary.csv of yours; the batch summary is {}",
                    args.output.display(),
                    file.name
                ));
            }
            // A list with no comment line: the manifest records how it
            // was made.
            let made_by = crate::provenance::MadeBy::new(
                recorded_invocation().as_deref(),
                "the batch's tables",
                &crate::provenance::settings_source(settings),
            );
            match write::write_into_named_folder(
                &args.output,
                &[file],
                &write::Inputs::new(inputs),
                settings.durability,
                Some(made_by.text()),
            ) {
                Ok(_) => EXIT_OK,
                Err(err) => write_failed(report, &err),
            }
        }
        Err(err) => {
            eprintln!("internal error: summary: {err}");
            EXIT_INTERNAL
        }
    }
}
