//! `steptable convert` and `steptable check`.

use super::*;

#[derive(Args)]
pub(crate) struct ConvertArgs {
    /// Step-table files (.xlsx, .xlsm, .xls, .ods, .csv).
    #[arg(required = true)]
    pub(crate) inputs: Vec<PathBuf>,
    /// Output folder; each input gets a folder DIR/NAME/ in it.
    #[arg(short, long, value_name = "DIR", default_value = "steptable-out")]
    pub(crate) output: PathBuf,
    #[command(flatten)]
    pub(crate) files: FileArgs,
    #[command(flatten)]
    pub(crate) common: CommonArgs,
    #[command(flatten)]
    pub(crate) sim: SimArgs,
}

#[derive(Args)]
pub(crate) struct CheckArgs {
    /// Step-table files (.xlsx, .xlsm, .xls, .ods, .csv).
    #[arg(required = true)]
    pub(crate) inputs: Vec<PathBuf>,
    /// Check as `convert --formats LIST` would: the names each file's tool
    /// holds (FST's 9 characters only where an FST file is written).
    #[arg(long, value_name = "LIST", value_parser = parse_formats)]
    pub(crate) formats: Option<std::collections::BTreeSet<crate::emit::OutputKind>>,
    #[command(flatten)]
    pub(crate) common: CommonArgs,
}

pub(crate) fn run_check(args: &CheckArgs) -> i32 {
    let mut settings = args.common.settings();
    if let Some(formats) = &args.formats {
        settings.formats = formats.clone();
    }
    let report = Reporter::new(&args.common);
    let mut code = EXIT_OK;
    for input in &args.inputs {
        match crate::commands::convert::check(input, &settings) {
            Ok(checked) => {
                report.diagnostics(&checked.warnings);
                report.say(&format!(
                    "{}: ok: {}",
                    display_name(input),
                    summary(&checked.table, &checked.allocation)
                ));
            }
            Err(diagnostics) => {
                report.diagnostics(&diagnostics);
                report.say(&format!(
                    "{}: {} error(s)",
                    display_name(input),
                    diagnostics
                        .iter()
                        .filter(|d| d.severity == crate::diag::Severity::Error)
                        .count()
                ));
                code = code.max(EXIT_BAD_INPUT);
            }
        }
    }
    code
}

pub(crate) fn run_convert(args: &ConvertArgs) -> i32 {
    let report = Reporter::new(&args.common);
    let Some(settings) = output_settings(&args.common, &args.sim, &args.files) else {
        return EXIT_BAD_INPUT;
    };
    if let Some(problem) = write::output_folder_problem(&args.output) {
        report.diagnostics(&[problem]);
        return EXIT_BAD_INPUT;
    }
    let mut code = EXIT_OK;
    // One file named twice is one table: converted once, and said.
    let (inputs, repeated) = crate::batch::once_each(&args.inputs);
    for (again, first) in &repeated {
        report.say(&format!(
            "note: {} names the file {} again; converted once",
            again.display(),
            first.display()
        ));
    }
    let names = convert::output_names(&inputs);
    let kept = write::Inputs::new(&inputs);
    for (input, name) in inputs.iter().zip(&names) {
        let shown = display_name(input);
        let progress = super::progress::Progress::new("fault cases", false);
        let run = crate::commands::convert::run(
            input,
            name,
            &settings,
            &args.output,
            &kept,
            &|done, total| progress.update(done, total),
        );
        progress.finish();
        let run = match run {
            Ok(run) => run,
            Err(err) => {
                let internal = matches!(&err, crate::commands::CommandError::Internal(_));
                code = code.max(command_failed(&report, &shown, err));
                if !internal {
                    eprintln!("{shown}: not converted, nothing written");
                }
                continue;
            }
        };
        let (conversion, folder) = (&run.conversion, &run.folder);
        report.diagnostics(&conversion.warnings);
        match &run.written {
            Ok((_, cleanup)) => {
                // As the files lie in the folder: `NAME.beremiz/plc.xml`.
                let names: Vec<String> = conversion.files.iter().map(|f| f.name.clone()).collect();
                report.say(&format!(
                    "{shown}: {} -> {}/ ({})",
                    summary(&conversion.table, &conversion.allocation),
                    folder.display(),
                    names.join(", ")
                ));
                for line in &conversion.findings {
                    report.say(&format!("  {line}"));
                }
                for line in cleanup_lines(cleanup, folder, None) {
                    report.say(&line);
                }
            }
            Err(err) => {
                code = code.max(write_failed(&report, err));
                eprintln!("{shown}: not converted, nothing written");
            }
        }
    }
    code
}

/// What a conversion's cleanup did to the files an earlier run wrote into
/// `folder`, one line each (none when it did nothing): the outputs of
/// another input it replaced, the files it removed, the ones it kept for
/// the engineer. `named` puts the folder in each line, for a batch's
/// summary, where many folders are written.
pub(super) fn cleanup_lines(
    cleanup: &crate::write::Cleanup,
    folder: &std::path::Path,
    named: Option<&std::path::Path>,
) -> Vec<String> {
    let inside = |p: &std::path::Path| p.strip_prefix(folder).unwrap_or(p).display().to_string();
    let there = match named {
        Some(shown) => format!("in {}/ ", shown.display()),
        None => String::new(),
    };
    let mut lines = Vec::new();
    if !cleanup.replaced_from.is_empty() {
        lines.push(format!(
            "  replaced {there}the outputs an earlier run made there from another input: {}",
            cleanup.replaced_from.join(", ")
        ));
    }
    if !cleanup.removed.is_empty() {
        let names: Vec<String> = cleanup.removed.iter().map(|p| inside(p)).collect();
        lines.push(format!(
            "  removed {there}what an earlier run wrote there and this one did not: {}",
            names.join(", ")
        ));
    }
    if !cleanup.kept.is_empty() {
        let names: Vec<String> = (cleanup.kept.iter())
            .map(|(p, why)| format!("{} ({why})", inside(p)))
            .collect();
        lines.push(format!(
            "  kept {there}what an earlier run wrote there and this one did not, for you to remove: {}",
            names.join("; ")
        ));
    }
    lines
}
