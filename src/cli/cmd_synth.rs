//! `steptable synth`: logic synthesis for single-branch sequences.

use super::*;
use std::io::IsTerminal;

#[derive(Args)]
pub(crate) struct SynthArgs {
    /// A single-branch step table of two-position actuators (any format convert reads).
    #[arg(required_unless_present = "sequence", conflicts_with = "sequence")]
    pub(crate) input: Option<PathBuf>,
    /// The sequence itself: "A1 A0 B1 B0", "A+ A- B+ B-" or "C1+1 C1-0 C2+1 C2-0".
    #[arg(long, value_name = "TEXT")]
    pub(crate) sequence: Option<String>,
    /// Output folder; the results go to DIR/NAME/.
    #[arg(short, long, value_name = "DIR", default_value = "steptable-out")]
    pub(crate) output: PathBuf,
    /// Read this sheet instead of the default choice (a table's; a
    /// sequence has none).
    #[arg(long, value_name = "NAME", conflicts_with = "sequence")]
    pub(crate) sheet: Option<String>,
    /// Memory insertion: exact (proven minimal), ga (the paper's GA, with GP
    /// for the equations) or both (default; the better is kept).
    #[arg(long, value_enum, default_value_t = MethodArg::Both)]
    pub(crate) method: MethodArg,
    /// Seed of the GA and GP (PCG: the same answer on every machine).
    #[arg(long, default_value_t = 1)]
    pub(crate) seed: u64,
    /// Population size μ of the GA and GP (2 to 5,000).
    #[arg(long, default_value_t = 500, value_parser = parse_mu)]
    pub(crate) mu: usize,
    /// (μ+λ)/μ of the GA and GP (2 to 6).
    #[arg(long, default_value_t = 4, value_parser = parse_ratio)]
    pub(crate) ratio: usize,
    /// Generations of the GA (1 to 100,000).
    #[arg(long, default_value_t = 400, value_parser = parse_generations)]
    pub(crate) generations: usize,
    /// The longest the synthesis may search (1 s to 1 h, e.g. 30s). Past it
    /// (or on Ctrl-C) the comparison of equations keeps its best so far and
    /// says what is proven; a search for the memories that has not ended is
    /// error E033.
    #[arg(long, value_name = "TIME", default_value = "5s", value_parser = parse_time_limit)]
    pub(crate) time_limit: std::time::Duration,
    /// Which point of the front to keep: memories (default; the proven
    /// fewest, then their smallest equations) or nodes (the smallest
    /// equations found with the fewest memories or one more).
    #[arg(long, value_enum, default_value_t = PreferArg::Memories)]
    pub(crate) prefer: PreferArg,
    /// How to print problems: human (default) or json (one object per line
    /// on stdout; the report then goes to stderr).
    #[arg(long, value_enum, default_value_t = MessageFormat::Human)]
    pub(crate) message_format: MessageFormat,
    /// Folder of templates that replace the built-in ones by file name
    /// (equations.st.j2, equations.il.j2; start from `steptable templates export DIR`).
    #[arg(long, value_name = "DIR")]
    pub(crate) templates: Option<PathBuf>,
}

fn parse_time_limit(text: &str) -> Result<std::time::Duration, String> {
    super::args::unit_given(text, text)?;
    match crate::stroke::parse_duration_ms(text) {
        Some(ms) if ms >= 1000 => Ok(std::time::Duration::from_millis(ms.into())),
        _ => Err("the time limit is a duration from 1 s to 1 h, e.g. 30s".to_string()),
    }
}

/// A whole number within `low..=high`, or why not.
fn bounded(text: &str, low: usize, high: usize, what: &str) -> Result<usize, String> {
    match text.trim().parse::<usize>() {
        Ok(n) if (low..=high).contains(&n) => Ok(n),
        _ => Err(format!("{what} is a whole number from {low} to {high}")),
    }
}

// The paper's ranges are μ 50-5000 and (μ+λ)/μ 2-6; beyond them the
// population outgrows memory (μ = 10^8 asked for 3.2 GB at once).
fn parse_mu(text: &str) -> Result<usize, String> {
    bounded(text, 2, 5000, "μ")
}

fn parse_ratio(text: &str) -> Result<usize, String> {
    bounded(text, 2, 6, "(μ+λ)/μ")
}

fn parse_generations(text: &str) -> Result<usize, String> {
    bounded(text, 1, 100_000, "the number of generations")
}

#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum PreferArg {
    Memories,
    Nodes,
}

#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum MethodArg {
    Exact,
    Ga,
    Both,
}

pub(crate) fn run_synth(args: &SynthArgs) -> i32 {
    use crate::commands::synth::{self as command, SynthSource};
    use crate::synth;

    let reporter = Reporter::for_format(args.message_format);
    let templates = match &args.templates {
        Some(dir) => match crate::settings::user_templates::load_dir(dir) {
            Ok(templates) => templates,
            Err(err) => {
                eprintln!("{err}");
                return EXIT_BAD_INPUT;
            }
        },
        None => crate::emit::templates::Templates::default(),
    };
    let source = match (&args.input, &args.sequence) {
        (_, Some(text)) => SynthSource::Sequence(text),
        (Some(path), None) => SynthSource::Table {
            path,
            sheet: args.sheet.as_deref(),
        },
        (None, None) => {
            eprintln!("error: give a step table or --sequence");
            return EXIT_BAD_INPUT;
        }
    };
    let shown = match source {
        SynthSource::Table { path, .. } => display_name(path),
        SynthSource::Sequence(_) => "--sequence".to_string(),
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
        time_limit: Some(args.time_limit),
        prefer: match args.prefer {
            PreferArg::Memories => synth::Prefer::Memories,
            PreferArg::Nodes => synth::Prefer::Nodes,
        },
    };
    // Ctrl-C ends the search; the comparison of equations keeps its best.
    let _ = ctrlc::set_handler(synth::interrupt);
    let progress = SearchProgress::new(args.time_limit);
    let run = command::run(
        source,
        options,
        &templates,
        &args.output,
        recorded_invocation().as_deref(),
        &|done, total| progress.update(done, total),
    );
    progress.finish();
    let run = match run {
        Ok(run) => run,
        Err(err) => return command_failed(&reporter, &shown, err),
    };
    reporter.diagnostics(&run.warnings);
    reporter.say(&run.report);
    match run.written {
        Ok(paths) => {
            let names: Vec<String> = paths
                .iter()
                .filter_map(|p| p.file_name())
                .map(|n| n.to_string_lossy().to_string())
                .collect();
            reporter.say(&format!(
                "wrote {}/ ({})",
                run.folder.display(),
                names.join(", ")
            ));
            EXIT_OK
        }
        Err(err) => write_failed(&reporter, &err),
    }
}

/// On a terminal: a spinner while the memories are searched, then a bar of
/// the candidates compared for the smallest equations.
struct SearchProgress {
    bar: Option<indicatif::ProgressBar>,
    counting: std::sync::Once,
}

impl SearchProgress {
    fn new(limit: std::time::Duration) -> Self {
        let bar = std::io::stderr().is_terminal().then(|| {
            let bar = indicatif::ProgressBar::new_spinner();
            bar.set_message(format!(
                "searching for the fewest memory operations (at most {} s; Ctrl-C stops)",
                limit.as_secs()
            ));
            bar.enable_steady_tick(std::time::Duration::from_millis(200));
            bar
        });
        SearchProgress {
            bar,
            counting: std::sync::Once::new(),
        }
    }

    fn update(&self, done: usize, total: usize) {
        let Some(bar) = &self.bar else {
            return;
        };
        self.counting.call_once(|| {
            bar.set_style(
                indicatif::ProgressStyle::with_template(
                    "{bar:30} {pos}/{len} candidates for the smallest equations, {elapsed} (Ctrl-C keeps the best so far)",
                )
                .unwrap_or_else(|_| indicatif::ProgressStyle::default_bar()),
            );
        });
        // Set each time: the front's second comparison has its own total.
        bar.set_length(total as u64);
        bar.set_position(done as u64);
    }

    fn finish(&self) {
        if let Some(bar) = &self.bar {
            bar.finish_and_clear();
        }
    }
}
