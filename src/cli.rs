//! Command-line parsing (clap) and the commands. Raw arguments become
//! validated [`Settings`] before any work starts; exit codes are 0 (ok),
//! 1 (bad input, diagnostics printed) and 2 (internal or I/O failure).

use std::io::Write;
use std::path::PathBuf;

use clap::{Args, Parser, Subcommand, ValueEnum};

use steptable::address::{Mnemonic, Safety, Target};
use steptable::convert::{self, Failure, OutputKind, Settings};
use steptable::diag::{Diagnostic, Severity};
use steptable::emit::diagram::DiagramKind;
use steptable::output;
use steptable::read::display_name;

const EXIT_OK: i32 = 0;
const EXIT_BAD_INPUT: i32 = 1;
const EXIT_INTERNAL: i32 = 2;

#[derive(Parser)]
#[command(
    name = "steptable",
    version,
    about = "Turn a step table of pneumatic cylinder moves into I/O address lists and PLC programs"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Convert step tables into address sheets and PLC programs.
    Convert(ConvertArgs),
    /// Read and check step tables without writing anything.
    Check(CheckArgs),
    /// Simulate the generated program against a model of the pneumatics.
    Simulate(SimulateArgs),
    /// Tabulate what every sensor fault (stuck at 1 or 0) does to the machine.
    Faults(FaultsArgs),
    /// Work with the output templates.
    #[command(subcommand)]
    Templates(TemplatesCommand),
    /// Write an empty step-table workbook to fill in Excel or LibreOffice.
    Template(TemplateArgs),
    /// Convert many workbooks at once, in parallel, with a summary.
    Batch(BatchArgs),
    /// Synthesise minimal logic equations for a single-branch sequence.
    Synth(SynthArgs),
}

#[derive(Args)]
struct SynthArgs {
    /// A single-branch step table of two-position actuators (any format convert reads).
    #[arg(required_unless_present = "sequence", conflicts_with = "sequence")]
    input: Option<PathBuf>,
    /// The sequence itself: "A1 A0 B1 B0", "A+ A- B+ B-" or "C1+1 C1-0 C2+1 C2-0".
    #[arg(long, value_name = "TEXT")]
    sequence: Option<String>,
    /// Output folder; the results go to DIR/NAME/.
    #[arg(short, long, value_name = "DIR", default_value = "steptable-out")]
    output: PathBuf,
    /// Read this sheet instead of the default choice.
    #[arg(long, value_name = "NAME")]
    sheet: Option<String>,
    /// Memory insertion: exact (proven minimal), ga (the paper's GA, with GP
    /// for the equations) or both (default; the better is kept).
    #[arg(long, value_enum, default_value_t = MethodArg::Both)]
    method: MethodArg,
    /// Seed of the GA and GP (PCG: the same answer on every machine).
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Population size μ of the GA and GP.
    #[arg(long, default_value_t = 500)]
    mu: usize,
    /// (μ+λ)/μ of the GA and GP.
    #[arg(long, default_value_t = 4)]
    ratio: usize,
    /// Generations of the GA.
    #[arg(long, default_value_t = 400)]
    generations: usize,
}

#[derive(Clone, Copy, ValueEnum)]
enum MethodArg {
    Exact,
    Ga,
    Both,
}

#[derive(Args)]
struct BatchArgs {
    /// Files, folders (searched recursively for .xlsx .xlsm .xls .ods .csv) or glob patterns.
    #[arg(required = true)]
    paths: Vec<PathBuf>,
    /// Output folder: one folder per input, and summary.csv.
    #[arg(short, long, value_name = "DIR")]
    output: PathBuf,
    /// Conversions at once (default: all cores).
    #[arg(short, long, value_name = "N")]
    jobs: Option<usize>,
    /// No progress bar.
    #[arg(short, long)]
    quiet: bool,
    #[command(flatten)]
    files: FileArgs,
    #[command(flatten)]
    common: CommonArgs,
    #[command(flatten)]
    sim: SimArgs,
}

#[derive(Args)]
struct TemplateArgs {
    /// The workbook to write.
    #[arg(
        short,
        long,
        value_name = "FILE",
        default_value = "steptable-template.xlsx"
    )]
    output: PathBuf,
    /// Number of branch columns.
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u16).range(1..=256))]
    branches: u16,
    /// Number of step rows.
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u32).range(1..=10000))]
    steps: u32,
    /// Replace the file if it exists (it may hold a filled-in table).
    #[arg(long)]
    force: bool,
}

#[derive(Subcommand)]
enum TemplatesCommand {
    /// Write the built-in templates into DIR, to edit and use with --templates.
    Export {
        /// Folder to write the templates into (created if missing).
        dir: PathBuf,
    },
}

#[derive(Args)]
struct FaultsArgs {
    /// Step-table files (.xlsx, .xlsm, .xls, .ods, .csv).
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Also every pair of faults.
    #[arg(long)]
    pairs: bool,
    /// Output folder for NAME/NAME.faults.csv.
    #[arg(short, long, value_name = "DIR", default_value = "steptable-out")]
    output: PathBuf,
    #[command(flatten)]
    common: CommonArgs,
    #[command(flatten)]
    sim: SimArgs,
}

#[derive(Args)]
struct SimulateArgs {
    /// Step-table files (.xlsx, .xlsm, .xls, .ods, .csv).
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Generate the program without middle stops, as the published method
    /// does, to see why they matter.
    #[arg(long)]
    no_middle_stop: bool,
    #[command(flatten)]
    common: CommonArgs,
    #[command(flatten)]
    sim: SimArgs,
}

#[derive(Args)]
struct SimArgs {
    /// Stroke times per actuator, extend/retract: C2=1.5s/0.8s,C3=2s (default 1s/1s).
    #[arg(long, value_name = "LIST", value_parser = parse_strokes)]
    stroke: Option<StrokeMap>,
    /// Drift of a 5/3 piston with no coil on, stroke per second: C2=0.1 (the load
    /// on an exhausted centre, the creep of a pressurised one; default 0.05).
    #[arg(long, value_name = "LIST", value_parser = parse_loads)]
    load: Option<std::collections::BTreeMap<u32, f64>>,
    /// PLC scan time of the simulation and of the generated task.
    #[arg(long, value_name = "TIME", value_parser = parse_scan)]
    scan: Option<u32>,
}

type StrokeMap = std::collections::BTreeMap<u32, steptable::timing::Stroke>;

fn parse_strokes(text: &str) -> Result<StrokeMap, String> {
    steptable::timing::parse_strokes(text)
}

fn parse_scan(text: &str) -> Result<u32, String> {
    steptable::timing::parse_duration_ms(text)
        .filter(|ms| *ms <= 1000)
        .ok_or_else(|| format!("\"{text}\" is not a scan time from 1ms to 1s, such as 10ms"))
}

impl SimArgs {
    fn apply(&self, settings: &mut Settings) {
        if let Some(scan) = self.scan {
            settings.simulation.scan_ms = scan;
            settings.explicit.scan = true;
        }
        if let Some(loads) = &self.load {
            settings.simulation.loads = loads.clone();
        }
        if let Some(strokes) = &self.stroke {
            settings.simulation.strokes.per_actuator = strokes.clone();
        }
    }
}

#[derive(Args)]
struct ConvertArgs {
    /// Step-table files (.xlsx, .xlsm, .xls, .ods, .csv).
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    /// Output folder; each input gets a folder DIR/NAME/ in it.
    #[arg(short, long, value_name = "DIR", default_value = "steptable-out")]
    output: PathBuf,
    #[command(flatten)]
    files: FileArgs,
    #[command(flatten)]
    common: CommonArgs,
    #[command(flatten)]
    sim: SimArgs,
}

/// What files to write and how they look.
#[derive(Args)]
struct FileArgs {
    /// Horizontal axis of NAME.diagram.svg: step (displacement-step) or time.
    #[arg(long, value_enum, default_value_t = DiagramArg::Step)]
    diagram: DiagramArg,
    /// Files to write: xlsx, st, fst, io, diagram, faults, plcopen, codesys,
    /// gvl, tia, awl, sdf, fst-alloc, rockwell (default all).
    #[arg(long, value_name = "LIST", value_parser = parse_formats)]
    formats: Option<std::collections::BTreeSet<OutputKind>>,
    /// Folder of templates that replace the built-in ones by file name
    /// (start from `steptable templates export DIR`).
    #[arg(long, value_name = "DIR")]
    templates: Option<PathBuf>,
}

/// The settings of a command that writes files: common flags, simulation
/// flags and file options. `None` (the problem printed) for a broken
/// template folder.
fn output_settings(common: &CommonArgs, sim: &SimArgs, files: &FileArgs) -> Option<Settings> {
    let mut settings = common.settings();
    sim.apply(&mut settings);
    match files.apply(&mut settings) {
        Ok(()) => Some(settings),
        Err(err) => {
            eprintln!("{err}");
            None
        }
    }
}

impl FileArgs {
    /// Applies the options; a broken template folder is the user's error.
    fn apply(&self, settings: &mut Settings) -> Result<(), String> {
        settings.diagram = match self.diagram {
            DiagramArg::Step => DiagramKind::Step,
            DiagramArg::Time => DiagramKind::Time,
        };
        if let Some(formats) = &self.formats {
            settings.formats = formats.clone();
        }
        if let Some(dir) = &self.templates {
            settings.templates =
                steptable::emit::templates::Templates::load_dir(dir).map_err(|e| e.to_string())?;
        }
        Ok(())
    }
}

#[derive(Clone, Copy, ValueEnum)]
enum DiagramArg {
    Step,
    Time,
}

#[derive(Args)]
struct CheckArgs {
    /// Step-table files (.xlsx, .xlsm, .xls, .ods, .csv).
    #[arg(required = true)]
    inputs: Vec<PathBuf>,
    #[command(flatten)]
    common: CommonArgs,
}

#[derive(Args)]
struct CommonArgs {
    /// Address dialect: festo (I0.0/O0.0, 16-bit words), iec (%IX0.0/%QX0.0), siemens (I0.0/Q0.0).
    #[arg(long, value_enum)]
    target: Option<TargetArg>,
    /// Operand letters for siemens: en (I/Q) or de (E/A).
    #[arg(long, value_enum)]
    mnemonic: Option<MnemonicArg>,
    /// Read this sheet instead of "SEQUENTIAL CONTROL DESCRIPTION" or the first sheet with moves.
    #[arg(long, value_name = "NAME")]
    sheet: Option<String>,
    /// How to print problems: human (default) or json (one object per line on stdout).
    #[arg(long, value_enum, default_value_t = MessageFormat::Human)]
    message_format: MessageFormat,
    /// Valve per actuator: C1=52mono,C2=53closed (52bi, 52mono, 53closed, 53exhaust, 53pressure).
    #[arg(long, value_name = "LIST", value_parser = parse_valves)]
    valve: Option<std::collections::BTreeMap<u32, steptable::valve::ValveType>>,
    /// Safety checks in the generated program: edge, precheck, plausibility, watchdog (or all).
    #[arg(long, value_name = "LIST", value_parser = parse_safety)]
    safety: Option<Safety>,
}

fn parse_formats(text: &str) -> Result<std::collections::BTreeSet<OutputKind>, String> {
    OutputKind::parse_list(text)
}

fn parse_valves(
    text: &str,
) -> Result<std::collections::BTreeMap<u32, steptable::valve::ValveType>, String> {
    steptable::valve::parse_valves(text)
}

fn parse_loads(text: &str) -> Result<std::collections::BTreeMap<u32, f64>, String> {
    let mut loads = std::collections::BTreeMap::new();
    for item in text.split(',').map(str::trim).filter(|i| !i.is_empty()) {
        let (name, value) = item.split_once('=').ok_or_else(|| {
            format!("\"{item}\": expected C<number>=<stroke per second>, e.g. C2=0.1")
        })?;
        let actuator = steptable::cell::normalize(name)
            .strip_prefix('C')
            .and_then(|n| n.parse::<u32>().ok())
            .ok_or_else(|| format!("\"{item}\": expected an actuator such as C2 before ="))?;
        let load: f64 = value
            .trim()
            .parse()
            .ok()
            .filter(|l: &f64| (0.0..=10.0).contains(l))
            .ok_or_else(|| {
                format!("\"{item}\": expected a drift from 0 to 10 stroke per second")
            })?;
        loads.insert(actuator, load);
    }
    Ok(loads)
}

fn parse_safety(text: &str) -> Result<Safety, String> {
    Safety::parse(text)
}

#[derive(Clone, Copy, ValueEnum)]
enum TargetArg {
    Festo,
    Iec,
    Siemens,
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
enum MessageFormat {
    Human,
    Json,
}

#[derive(Clone, Copy, ValueEnum)]
enum MnemonicArg {
    En,
    De,
}

impl CommonArgs {
    /// Settings from the flags; those given explicitly are marked so that a
    /// workbook's SETTINGS sheet does not change them.
    fn settings(&self) -> Settings {
        let mut settings = Settings::new();
        if let Some(target) = self.target {
            settings.target = match target {
                TargetArg::Festo => Target::Festo,
                TargetArg::Iec => Target::Iec,
                TargetArg::Siemens => Target::Siemens,
            };
            settings.explicit.target = true;
        }
        if let Some(mnemonic) = self.mnemonic {
            settings.mnemonic = match mnemonic {
                MnemonicArg::En => Mnemonic::En,
                MnemonicArg::De => Mnemonic::De,
            };
            settings.explicit.mnemonic = true;
        }
        if let Some(safety) = self.safety {
            settings.program.safety = safety;
            settings.explicit.safety = true;
        }
        if let Some(valves) = &self.valve {
            settings.simulation.valves.per_actuator = valves.clone();
        }
        settings.sheet = self.sheet.clone();
        settings
    }
}

/// Runs the command line and returns the process exit code.
pub fn run() -> i32 {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(err) => {
            let _ = err.print();
            return if err.use_stderr() {
                EXIT_INTERNAL
            } else {
                EXIT_OK
            };
        }
    };
    match cli.command {
        Command::Convert(args) => run_convert(&args),
        Command::Check(args) => run_check(&args),
        Command::Simulate(args) => run_simulate(&args),
        Command::Faults(args) => run_faults(&args),
        Command::Template(args) => run_template(&args),
        Command::Batch(args) => run_batch(&args),
        Command::Synth(args) => run_synth(&args),
        Command::Templates(TemplatesCommand::Export { dir }) => {
            match steptable::emit::templates::export_defaults(&dir) {
                Ok(written) => {
                    for path in written {
                        out(&path.display().to_string());
                    }
                    EXIT_OK
                }
                Err(err) => {
                    eprintln!("error: {}: {err}", dir.display());
                    EXIT_INTERNAL
                }
            }
        }
    }
}

/// Prints to stdout; a closed pipe (`steptable check … | head`) is not an error.
fn out(line: &str) {
    let mut stdout = std::io::stdout().lock();
    if writeln!(stdout, "{line}").is_err() {
        std::process::exit(EXIT_OK);
    }
}

/// Where results and problems go: human text (results on stdout, problems
/// on stderr), or JSON diagnostics on stdout with the human lines on stderr.
struct Reporter {
    json: bool,
}

impl Reporter {
    fn new(common: &CommonArgs) -> Self {
        Reporter {
            json: common.message_format == MessageFormat::Json,
        }
    }

    fn diagnostics(&self, diagnostics: &[Diagnostic]) {
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
    fn say(&self, line: &str) {
        if self.json {
            eprintln!("{line}");
        } else {
            out(line);
        }
    }
}

fn summary(
    table: &steptable::table::StepTable,
    allocation: &steptable::address::Allocation,
) -> String {
    format!(
        "{} steps, {} branch(es), {} actuators, {} inputs, {} outputs",
        table.steps.len(),
        table.branches,
        table.actuators.len(),
        allocation.inputs.len(),
        allocation.outputs.len()
    )
}

fn run_check(args: &CheckArgs) -> i32 {
    let settings = args.common.settings();
    let report = Reporter::new(&args.common);
    let mut code = EXIT_OK;
    for input in &args.inputs {
        match convert::check_path(input, &settings) {
            Ok(checked) => {
                report.diagnostics(&checked.warnings);
                report.say(&format!(
                    "{}: ok: {}",
                    display_name(input),
                    summary(
                        &checked.table,
                        &convert::build_program(&checked.table, &checked.settings).0
                    )
                ));
            }
            Err(diagnostics) => {
                report.diagnostics(&diagnostics);
                report.say(&format!(
                    "{}: {} error(s)",
                    display_name(input),
                    diagnostics
                        .iter()
                        .filter(|d| d.severity == steptable::diag::Severity::Error)
                        .count()
                ));
                code = code.max(EXIT_BAD_INPUT);
            }
        }
    }
    code
}

fn run_simulate(args: &SimulateArgs) -> i32 {
    let mut settings = args.common.settings();
    let reporter = Reporter::new(&args.common);
    args.sim.apply(&mut settings);
    settings.program.middle_stops = !args.no_middle_stop;
    let mut code = EXIT_OK;
    for input in &args.inputs {
        let checked = match convert::check_path(input, &settings) {
            Ok(c) => c,
            Err(diagnostics) => {
                reporter.diagnostics(&diagnostics);
                code = code.max(EXIT_BAD_INPUT);
                continue;
            }
        };
        reporter.diagnostics(&checked.warnings);
        let (table, settings) = (checked.table, checked.settings);
        let (_, program) = convert::build_program(&table, &settings);
        let report = steptable::simulate::simulate(&table, &program, &settings.simulation);
        reporter.say(&format!("{}: {}", display_name(input), report.verdict()));
        reporter.say(&steptable::simulate::report::step_table(&report));
        if !report.passed {
            code = code.max(EXIT_BAD_INPUT);
        }
    }
    code
}

fn run_faults(args: &FaultsArgs) -> i32 {
    let mut settings = args.common.settings();
    let report = Reporter::new(&args.common);
    args.sim.apply(&mut settings);
    let mut code = EXIT_OK;
    let names = convert::output_names(&args.inputs);
    for (input, name) in args.inputs.iter().zip(&names) {
        let checked = match convert::check_path(input, &settings) {
            Ok(c) => c,
            Err(diagnostics) => {
                report.diagnostics(&diagnostics);
                code = code.max(EXIT_BAD_INPUT);
                continue;
            }
        };
        let (table, settings) = (checked.table, checked.settings);
        let (allocation, program) = convert::build_program(&table, &settings);
        let result = steptable::faults::analyse(
            &table,
            &program,
            &allocation,
            &settings.simulation,
            args.pairs,
        );
        report.say(&format!("{}: {}", display_name(input), result.summary()));
        let rows = steptable::faults::rows(&result);
        let width = rows.iter().map(|r| r[0].len()).max().unwrap_or(5).max(5);
        report.say(&format!(
            "  {:<width$}  {:<10}  {:>4}  explanation",
            "fault", "outcome", "step"
        ));
        for r in &rows {
            report.say(&format!(
                "  {:<width$}  {:<10}  {:>4}  {}",
                r[0], r[1], r[2], r[3]
            ));
        }
        let file = convert::OutputFile {
            name: format!("{name}.faults.csv"),
            bytes: match steptable::faults::render_csv(&result) {
                Ok(b) => b,
                Err(e) => {
                    eprintln!("internal error: {e}");
                    code = EXIT_INTERNAL;
                    continue;
                }
            },
        };
        if let Err(err) = output::write_files(&args.output.join(name), &[file], &args.inputs) {
            eprintln!("error: {err}");
            code = EXIT_INTERNAL;
        }
    }
    code
}

fn run_batch(args: &BatchArgs) -> i32 {
    use std::io::IsTerminal;
    use steptable::batch::{self, Status};

    let report = Reporter::new(&args.common);
    let Some(settings) = output_settings(&args.common, &args.sim, &args.files) else {
        return EXIT_BAD_INPUT;
    };
    let started = std::time::Instant::now();
    let (inputs, missing) = batch::expand_inputs(&args.paths, &args.output);
    for path in &missing {
        eprintln!(
            "{}: error: no such file or folder, and no file matches it as a pattern",
            path.display()
        );
    }
    let jobs = args
        .jobs
        .unwrap_or_else(|| std::thread::available_parallelism().map_or(1, |n| n.get()));
    let bar = if !args.quiet && std::io::stderr().is_terminal() {
        let bar = indicatif::ProgressBar::new(inputs.len() as u64);
        bar.set_style(
            indicatif::ProgressStyle::with_template(
                "{bar:30} {pos}/{len} workbooks, {per_sec}, {elapsed} {msg}",
            )
            .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
        );
        Some(bar)
    } else {
        None
    };
    let on_done = |outcome: &batch::Outcome| {
        if let Some(bar) = &bar {
            bar.set_message(display_name(&outcome.input));
            bar.inc(1);
        }
    };
    let outcomes = batch::run(&inputs, &args.output, &settings, jobs, &on_done);
    if let Some(bar) = &bar {
        bar.finish_and_clear();
    }

    let mut code = if missing.is_empty() {
        EXIT_OK
    } else {
        EXIT_BAD_INPUT
    };
    for o in &outcomes {
        report.diagnostics(&o.diagnostics);
        match o.status {
            Status::Converted => {}
            Status::Failed => code = code.max(EXIT_BAD_INPUT),
            Status::Internal => code = EXIT_INTERNAL,
        }
    }
    let failed: Vec<&batch::Outcome> = outcomes
        .iter()
        .filter(|o| o.status != Status::Converted)
        .collect();
    let seconds = started.elapsed().as_secs_f64();
    report.say(&format!(
        "{} converted, {} failed, in {:.2} s ({:.1} workbooks/s, {} jobs) -> {}",
        outcomes.len() - failed.len(),
        failed.len() + missing.len(),
        seconds,
        outcomes.len() as f64 / seconds.max(1e-9),
        jobs,
        args.output.display()
    ));
    for o in &failed {
        // A diagnostic names its file; other failures need the name added.
        let first = match o.diagnostics.iter().find(|d| d.severity == Severity::Error) {
            Some(d) => d.to_string(),
            None => format!(
                "{}: {}",
                display_name(&o.input),
                o.message
                    .clone()
                    .unwrap_or_else(|| o.status.label().to_string())
            ),
        };
        report.say(&format!("  failed: {first}"));
    }
    match batch::summary_csv(&outcomes) {
        Ok(file) => {
            if let Err(err) = output::write_files(&args.output, &[file], &inputs) {
                eprintln!("error: {err}");
                code = EXIT_INTERNAL;
            }
        }
        Err(err) => {
            eprintln!("internal error: summary: {err}");
            code = EXIT_INTERNAL;
        }
    }
    code
}

fn run_synth(args: &SynthArgs) -> i32 {
    use steptable::synth::{self, SynthError, output as synth_out};

    let (sequence, name, inputs) = match (&args.input, &args.sequence) {
        (_, Some(text)) => match synth::sequence::parse(text) {
            Ok(s) => (s, "sequence".to_string(), Vec::new()),
            Err(why) => {
                eprintln!("--sequence: error: {why}");
                return EXIT_BAD_INPUT;
            }
        },
        (Some(input), None) => {
            let mut settings = Settings::new();
            settings.sheet = args.sheet.clone();
            let checked = match convert::check_path(input, &settings) {
                Ok(c) => c,
                Err(diagnostics) => {
                    for d in diagnostics {
                        eprintln!("{d}");
                    }
                    return EXIT_BAD_INPUT;
                }
            };
            match synth::from_table(&checked.table) {
                Ok(s) => (s, convert::output_name(input), vec![input.clone()]),
                Err(why) => {
                    eprintln!("{}: error: {why}", display_name(input));
                    return EXIT_BAD_INPUT;
                }
            }
        }
        (None, None) => {
            eprintln!("error: give a step table or --sequence");
            return EXIT_BAD_INPUT;
        }
    };
    let options = synth::Options {
        method: match args.method {
            MethodArg::Exact => synth::Method::Exact,
            MethodArg::Ga => synth::Method::Ga,
            MethodArg::Both => synth::Method::Both,
        },
        ga: synth::ga::GaParams {
            mu: args.mu,
            ratio: args.ratio,
            generations: args.generations,
            seed: args.seed,
            ..synth::ga::GaParams::default()
        },
        gp: synth::gp::GpParams {
            mu: args.mu,
            ratio: args.ratio,
            seed: args.seed,
            ..synth::gp::GpParams::default()
        },
    };
    let synthesis = match synth::synthesize_with(&sequence, options) {
        Ok(s) => s,
        Err(err @ SynthError::Unsuitable(_)) => {
            eprintln!("error: {err}");
            return EXIT_BAD_INPUT;
        }
        Err(err) => {
            eprintln!("error: {err}");
            return EXIT_BAD_INPUT;
        }
    };
    let verification = synth::verify::verify(&synthesis, 2);
    let report = synth_out::report_text(&synthesis, &verification);
    out(&report);
    let workbook = match synth_out::workbook(&synthesis, &verification) {
        Ok(b) => b,
        Err(err) => {
            eprintln!("internal error: workbook: {err}");
            return EXIT_INTERNAL;
        }
    };
    let files = vec![
        convert::OutputFile {
            name: format!("{name}.synth.txt"),
            bytes: report.into_bytes(),
        },
        convert::OutputFile {
            name: format!("{name}.synth.json"),
            bytes: synth_out::report_json(&synthesis, &verification, args.seed).into_bytes(),
        },
        convert::OutputFile {
            name: format!("{name}.equations.st"),
            bytes: synth_out::structured_text(&synthesis, &name).into_bytes(),
        },
        convert::OutputFile {
            name: format!("{name}.equations.il"),
            bytes: synth_out::instruction_list(&synthesis, &name).into_bytes(),
        },
        convert::OutputFile {
            name: format!("{name}.xlsx"),
            bytes: workbook,
        },
    ];
    if let Err(err) = output::write_files(&args.output.join(&name), &files, &inputs) {
        eprintln!("error: {err}");
        return EXIT_INTERNAL;
    }
    if !verification.passed {
        eprintln!(
            "internal error: the synthesised controller fails its simulation ({}); please report this sequence",
            verification.problem.unwrap_or_default()
        );
        return EXIT_INTERNAL;
    }
    EXIT_OK
}

fn run_template(args: &TemplateArgs) -> i32 {
    if args.output.exists() && !args.force {
        eprintln!(
            "error: {} exists and may hold your table; choose another -o or add --force",
            args.output.display()
        );
        return EXIT_BAD_INPUT;
    }
    let bytes = match steptable::template::template_workbook(args.branches, args.steps) {
        Ok(b) => b,
        Err(err) => {
            eprintln!("internal error: template: {err}");
            return EXIT_INTERNAL;
        }
    };
    let folder = match args.output.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let name = args
        .output
        .file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_else(|| "steptable-template.xlsx".to_string());
    match output::write_files(&folder, &[convert::OutputFile { name, bytes }], &[]) {
        Ok(_) => {
            out(&format!(
                "{}: {} branches x {} steps; fill the yellow cells, then: steptable convert {}",
                args.output.display(),
                args.branches,
                args.steps,
                args.output.display()
            ));
            EXIT_OK
        }
        Err(err) => {
            eprintln!("error: {err}");
            EXIT_INTERNAL
        }
    }
}

fn run_convert(args: &ConvertArgs) -> i32 {
    let report = Reporter::new(&args.common);
    let Some(settings) = output_settings(&args.common, &args.sim, &args.files) else {
        return EXIT_BAD_INPUT;
    };
    let mut code = EXIT_OK;
    let names = convert::output_names(&args.inputs);
    for (input, name) in args.inputs.iter().zip(&names) {
        let conversion = match convert::convert_path_as(input, name, &settings) {
            Ok(c) => c,
            Err(Failure::Input(diagnostics)) => {
                report.diagnostics(&diagnostics);
                eprintln!("{}: not converted, nothing written", display_name(input));
                code = code.max(EXIT_BAD_INPUT);
                continue;
            }
            Err(Failure::Internal(why)) => {
                eprintln!("{}: internal error: {why}", display_name(input));
                code = EXIT_INTERNAL;
                continue;
            }
            Err(Failure::Template(err)) => {
                eprintln!("{}: not converted, nothing written", display_name(input));
                if err.user {
                    eprintln!("{err}");
                    code = code.max(EXIT_BAD_INPUT);
                } else {
                    eprintln!("internal error: {err}");
                    code = EXIT_INTERNAL;
                }
                continue;
            }
        };
        report.diagnostics(&conversion.warnings);
        let folder = args.output.join(&conversion.name);
        match output::write_files(&folder, &conversion.files, &args.inputs) {
            Ok(written) => {
                let names: Vec<String> = written
                    .iter()
                    .filter_map(|p| p.file_name().map(|n| n.to_string_lossy().to_string()))
                    .collect();
                report.say(&format!(
                    "{}: {} -> {}/ ({})",
                    display_name(input),
                    summary(&conversion.table, &conversion.allocation),
                    folder.display(),
                    names.join(", ")
                ));
            }
            Err(err) => {
                eprintln!("error: {err}");
                code = EXIT_INTERNAL;
            }
        }
    }
    code
}
