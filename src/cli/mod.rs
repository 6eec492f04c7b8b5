//! The command line: clap parses, the library's commands
//! ([`crate::commands`], [`crate::batch`]) do the work and return what they
//! found and wrote, and this layer prints it. Raw arguments become
//! validated [`Settings`] before any work starts, with the command line as
//! the outputs record it ([`invocation`]); exit codes are 0 (ok), 1 (bad
//! input, diagnostics printed) and 2 (internal or I/O failure).

use std::io::Write;
use std::path::PathBuf;

use clap::builder::TypedValueParser;
use clap::{Args, Parser, Subcommand, ValueEnum};

use crate::address::{Board, Mnemonic, Target};
use crate::convert;
use crate::diag::{Diagnostic, Severity};
use crate::emit::OutputKind;
use crate::emit::diagram::DiagramKind;
use crate::program::{Modes, Safety};
use crate::read::display_name;
use crate::settings::{Given, Settings};
use crate::symbols::Scheme;
use crate::write;

/// `eprintln!` that never panics: with standard error closed or full
/// (`2>/dev/full`, `2>&1 | head`) std's panics (exit 101); the message is
/// lost either way, and the exit code must stay what the work earned.
macro_rules! eprintln {
    ($($arg:tt)*) => {{
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

mod args;
mod cmd_batch;
mod cmd_convert;
mod cmd_faults;
mod cmd_simulate;
mod cmd_synth;
mod cmd_template;
mod invocation;
mod progress;

use args::*;
use cmd_batch::*;
use cmd_convert::*;
use cmd_faults::*;
use cmd_simulate::*;
use cmd_synth::*;
use cmd_template::*;

pub(crate) const EXIT_OK: i32 = 0;
pub(crate) const EXIT_BAD_INPUT: i32 = 1;
pub(crate) const EXIT_INTERNAL: i32 = 2;
/// `batch` interrupted by Ctrl-C (128 + SIGINT, as shells report it).
pub(crate) const EXIT_INTERRUPTED: i32 = 130;

#[derive(Parser)]
#[command(
    name = "steptable",
    version,
    about = "Turn a step table of pneumatic cylinder moves into I/O address lists and PLC programs"
)]
pub struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand)]
pub(crate) enum Command {
    /// Convert step tables into address sheets and PLC programs.
    Convert(ConvertArgs),
    /// Read and check step tables without writing anything.
    Check(CheckArgs),
    /// Simulate the generated program against a model of the pneumatics.
    Simulate(SimulateArgs),
    /// Tabulate what every sensor fault (stuck at 1 or 0) does to the machine.
    Faults(FaultsArgs),
    /// Export the output templates (the layouts of the PLC program files) to
    /// edit and use with --templates; not `template`, the empty workbook.
    #[command(subcommand)]
    Templates(TemplatesCommand),
    /// Write an empty step-table workbook to fill in Excel or LibreOffice;
    /// not `templates`, the layouts of the output files.
    Template(TemplateArgs),
    /// Convert many workbooks at once, in parallel, with a summary.
    Batch(BatchArgs),
    /// Synthesise minimal logic equations for a single-branch sequence.
    Synth(SynthArgs),
}

/// The command line as the outputs record it, set once per run.
static INVOCATION: std::sync::OnceLock<String> = std::sync::OnceLock::new();

/// The command line as the outputs record it (see [`invocation`]).
pub(crate) fn recorded_invocation() -> Option<String> {
    INVOCATION.get().cloned()
}

/// Runs the command line and returns the process exit code.
pub fn run() -> i32 {
    let argv: Vec<std::ffi::OsString> = std::env::args_os().skip(1).collect();
    let _ = INVOCATION.set(invocation::invocation(&argv));
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(err) if !err.use_stderr() => {
            // --help and --version: through `out`, so that a full disk or
            // a failed stdout is exit 2 like any other output's failure.
            out(err.render().to_string().trim_end());
            return with_stdout(EXIT_OK);
        }
        Err(err) => {
            let args: Vec<String> = std::env::args_os()
                .skip(1)
                .map(|a| a.to_string_lossy().to_string())
                .collect();
            // A script that asked for JSON gets the reason as JSON too.
            if asks_for_json(&args) {
                out(&command_line_json(&err.render().to_string()));
            }
            let _ = err.print();
            if let Some(tip) = confused_command(&args) {
                eprintln!("\n{tip}");
            }
            // A wrong option is wrong input, like a wrong cell: exit 1 (2
            // stays for internal and I/O failures).
            return EXIT_BAD_INPUT;
        }
    };
    let code = match cli.command {
        Command::Convert(args) => run_convert(&args),
        Command::Check(args) => run_check(&args),
        Command::Simulate(args) => run_simulate(&args),
        Command::Faults(args) => run_faults(&args),
        Command::Template(args) => run_template(&args),
        Command::Batch(args) => run_batch(&args),
        Command::Synth(args) => run_synth(&args),
        Command::Templates(TemplatesCommand::Export { dir, force }) => {
            use crate::settings::user_templates::{ExportError, export_defaults};
            match export_defaults(&dir, force) {
                Ok(written) => {
                    for path in written {
                        out(&path.display().to_string());
                    }
                    EXIT_OK
                }
                Err(ExportError::Exists(paths)) => {
                    for path in paths {
                        eprintln!(
                            "error: {} exists and may hold your edits; nothing written (add --force to replace the templates)",
                            path.display()
                        );
                    }
                    EXIT_BAD_INPUT
                }
                Err(ExportError::Write(err)) => {
                    write_failed(&Reporter::for_format(MessageFormat::Human), &err)
                }
            }
        }
    };
    with_stdout(code)
}

/// Whether the command line asks for `--message-format json`, read from
/// the raw words, since it could not be parsed.
fn asks_for_json(args: &[String]) -> bool {
    args.windows(2)
        .any(|w| w[0] == "--message-format" && w[1] == "json")
        || args.iter().any(|a| a == "--message-format=json")
}

/// Clap's error as one JSON diagnostic (E041): its first line, without the
/// `error: ` prefix; no file, sheet or cell.
fn command_line_json(rendered: &str) -> String {
    let first = rendered.lines().next().unwrap_or("");
    let message = first.strip_prefix("error: ").unwrap_or(first);
    serde_json::json!({
        "file": null,
        "sheet": null,
        "cell": null,
        "row": null,
        "column": null,
        "severity": "error",
        "code": crate::diag::Code::E041BadCommandLine.as_str(),
        "message": message,
    })
    .to_string()
}

/// What became of standard output: written, closed by its reader, or
/// failed (a full disk). Set once, read when the command ends.
static STDOUT: std::sync::Mutex<Option<std::io::Error>> = std::sync::Mutex::new(None);

/// Prints to stdout. After the first failure nothing more is printed, and
/// the command still ends with the exit code its work earned: a closed pipe
/// (`steptable check … | head`) is quiet and changes nothing, any other
/// failure (`> /dev/full`) is an I/O error at the end (exit 2).
pub(crate) fn out(line: &str) {
    let mut failed = STDOUT.lock().unwrap_or_else(|e| e.into_inner());
    if failed.is_some() {
        return;
    }
    let mut stdout = std::io::stdout().lock();
    if let Err(err) = writeln!(stdout, "{line}").and_then(|()| stdout.flush()) {
        *failed = Some(err);
    }
}

/// The exit code of a command that earned `code`, once standard output's
/// fate is known.
fn with_stdout(code: i32) -> i32 {
    let failed = STDOUT.lock().unwrap_or_else(|e| e.into_inner());
    match failed.as_ref() {
        Some(err) if err.kind() != std::io::ErrorKind::BrokenPipe => {
            eprintln!("error: cannot write to standard output: {err}");
            code.max(EXIT_INTERNAL)
        }
        _ => code,
    }
}

/// The command meant when `template` (the empty workbook) and `templates`
/// (the output layouts) were swapped: `template export DIR`, or
/// `templates` with the workbook's options.
pub(crate) fn confused_command(args: &[String]) -> Option<String> {
    let rest = &args[1.min(args.len())..];
    match args.first().map(String::as_str) {
        Some("template") if rest.first().is_some_and(|a| a == "export") => Some(format!(
            "tip: did you mean `steptable templates {}`? `template` writes the empty step-table workbook; `templates export DIR` writes the layouts of the output files",
            rest.join(" ")
        )),
        Some("templates")
            if !rest
                .first()
                .is_some_and(|a| ["export", "help", "-h", "--help"].contains(&a.as_str())) =>
        {
            Some(
                "tip: did you mean `steptable template` (the empty step-table workbook, `-o FILE.xlsx`)? `templates export DIR` writes the layouts of the output files".to_string(),
            )
        }
        _ => None,
    }
}

/// Where results and problems go: human text (results on stdout, problems
/// on stderr), or JSON diagnostics on stdout with the human lines on stderr.
pub(crate) struct Reporter {
    pub(crate) json: bool,
}

impl Reporter {
    pub(crate) fn new(common: &CommonArgs) -> Self {
        Reporter::for_format(common.message_format)
    }

    pub(crate) fn for_format(format: MessageFormat) -> Self {
        Reporter {
            json: format == MessageFormat::Json,
        }
    }

    pub(crate) fn diagnostics(&self, diagnostics: &[Diagnostic]) {
        if self.json {
            for d in diagnostics {
                out(&d.to_json());
            }
        } else {
            let mut stderr = std::io::stderr().lock();
            for d in diagnostics {
                let _ = writeln!(stderr, "{d}");
            }
        }
    }

    /// A line for people.
    pub(crate) fn say(&self, line: &str) {
        if self.json {
            eprintln!("{line}");
        } else {
            out(line);
        }
    }
}

/// Says why a library command produced nothing for `input`; the exit code.
pub(crate) fn command_failed(
    report: &Reporter,
    input: &str,
    err: crate::commands::CommandError,
) -> i32 {
    use crate::commands::CommandError;
    match err {
        CommandError::Input(diagnostics) => {
            report.diagnostics(&diagnostics);
            EXIT_BAD_INPUT
        }
        CommandError::Template(err) if err.user => {
            eprintln!("{err}");
            EXIT_BAD_INPUT
        }
        CommandError::Template(err) => {
            eprintln!("{input}: internal error: {err}");
            EXIT_INTERNAL
        }
        CommandError::Internal(why) => {
            eprintln!("{input}: internal error: {why}");
            EXIT_INTERNAL
        }
        CommandError::Write(err) => write_failed(report, &err),
    }
}

/// Says why outputs were not written; the exit code: 1 when something of
/// the engineer's is in their place (E040), 2 for an I/O failure.
pub(crate) fn write_failed(report: &Reporter, err: &write::WriteError) -> i32 {
    match err {
        write::WriteError::Taken(problems) => {
            report.diagnostics(problems);
            EXIT_BAD_INPUT
        }
        write::WriteError::Io { .. } => {
            eprintln!("error: {err}");
            EXIT_INTERNAL
        }
    }
}

/// One line on a table and its wiring: the counts, and the address ranges
/// in the target's notation, first to last (what the panel must have).
pub(crate) fn summary(
    table: &crate::table::StepTable,
    allocation: &crate::address::Allocation,
) -> String {
    let range = |points: &[crate::address::Assigned]| match (points.first(), points.last()) {
        (Some(first), Some(last)) => format!(
            "{} to {}",
            first.address.display(allocation.mnemonic),
            last.address.display(allocation.mnemonic)
        ),
        _ => "none".to_string(),
    };
    format!(
        "{} steps, {} branch(es), {} actuators, {} inputs, {} outputs; addresses {}, {}",
        table.steps.len(),
        table.branches,
        table.actuators.len(),
        allocation.inputs.len(),
        allocation.outputs.len(),
        range(&allocation.inputs),
        range(&allocation.outputs)
    )
}
