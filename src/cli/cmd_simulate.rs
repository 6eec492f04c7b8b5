//! `steptable simulate`: the generated program against a model of the
//! pneumatics, with the verdict and the step timing.

use super::*;

#[derive(Args)]
#[command(group(clap::ArgGroup::new("events").multiple(true).args(["press", "hold", "release", "stick"])))]
pub(crate) struct SimulateArgs {
    /// Step-table files (.xlsx, .xlsm, .xls, .ods, .csv).
    #[arg(required = true)]
    pub(crate) inputs: Vec<PathBuf>,
    /// Generate the program without middle stops, as the published method
    /// does, to see why they matter.
    #[arg(long)]
    pub(crate) no_middle_stop: bool,
    /// Also write the run's displacement-time diagram (dwells and waits
    /// shaded) to DIR/NAME/NAME.time.svg; not with a scenario, whose run
    /// `--report DIR` draws.
    #[arg(long, value_name = "DIR")]
    pub(crate) diagram: Option<PathBuf>,
    /// Scenario: press an operator's button at a moment and let go after
    /// 0.1 s: `STOP@step3` (when the program enters step 3), `RESET@+2s`
    /// (after the event before), `ESTOP@4.0s`, `START@500ms`. Repeatable;
    /// events happen in the order written.
    #[arg(long, value_name = "BUTTON@WHEN")]
    pub(crate) press: Vec<String>,
    /// Scenario: press a button (or turn a switch on) and keep it there.
    #[arg(long, value_name = "BUTTON@WHEN")]
    pub(crate) hold: Vec<String>,
    /// Scenario: let go of a held button.
    #[arg(long, value_name = "BUTTON@WHEN")]
    pub(crate) release: Vec<String>,
    /// Scenario: an input reads 0 or 1 from a moment on, whatever the
    /// machine does (a broken wire, a stuck sensor): `x21=0@4.0s`.
    #[arg(long, value_name = "INPUT=0|1@WHEN")]
    pub(crate) stick: Vec<String>,
    /// With a scenario: also draw its run on the report's timeline, in
    /// DIR/NAME/NAME.scenario.report.html.
    #[arg(long, value_name = "DIR", requires = "events")]
    pub(crate) report: Option<PathBuf>,
    #[command(flatten)]
    pub(crate) common: CommonArgs,
    #[command(flatten)]
    pub(crate) sim: SimArgs,
}

pub(crate) fn run_simulate(args: &SimulateArgs) -> i32 {
    let mut settings = args.common.settings();
    let reporter = Reporter::new(&args.common);
    args.sim.apply(&mut settings);
    settings.program.middle_stops = !args.no_middle_stop;
    // What it draws holds names of any length: no tool's limit applies.
    settings.formats = [OutputKind::Diagram, OutputKind::Report].into();
    let mut code = EXIT_OK;
    let names = convert::output_names(&args.inputs);
    let kept = write::Inputs::new(&args.inputs).named_by("--diagram");
    let events = written_events(args);
    if !events.is_empty() && args.diagram.is_some() {
        // Refused with the reason, where clap's conflict would say only
        // that the two options do not go together.
        use clap::CommandFactory;
        let mut cli = Cli::command().bin_name("steptable");
        let simulate = cli
            .find_subcommand_mut("simulate")
            .map(|c| c.clone().bin_name("steptable simulate"));
        let err = simulate.unwrap_or(cli).error(
            clap::error::ErrorKind::ArgumentConflict,
            "--diagram draws the proof's cycle, which a scenario (--press, --hold, --release, --stick) replaces: draw the scenario's run with --report DIR (its timeline, with the positions), or leave out the events",
        );
        let _ = err.print();
        // A script reading JSON hears it as every refused command line.
        if reporter.json {
            out(&super::command_line_json(&err.render().to_string()));
        }
        return EXIT_BAD_INPUT;
    }
    if !events.is_empty() {
        return run_scenarios(args, &settings, &events, &reporter);
    }
    for (input, name) in args.inputs.iter().zip(&names) {
        // The diagram is written before anything is printed: with stdout
        // closed, printing ends the process (quietly), and the file the user
        // asked for must exist by then.
        let run =
            crate::commands::simulate::run(input, name, &settings, args.diagram.as_deref(), &kept);
        let mut run = match run {
            Ok(run) => run,
            Err(err) => {
                code = code.max(command_failed(&reporter, &display_name(input), err));
                continue;
            }
        };
        reporter.diagnostics(&run.warnings);
        let diagram = match run.diagram.take() {
            Some(Ok(paths)) => paths,
            Some(Err(err)) => {
                code = code.max(write_failed(&reporter, &err));
                Vec::new()
            }
            None => Vec::new(),
        };
        // Said in the engineer's names (`C1 (clamp)`, `1B2`).
        let explain = |text: &str| run.symbols.explain(text);
        reporter.say(&format!(
            "{}: {}",
            display_name(input),
            explain(&run.report.verdict())
        ));
        reporter.say(&explain(&crate::simulate::report::step_table(&run.report)));
        if let Some(failure) = run.failure() {
            // A script reading JSON sees why the run failed, as convert
            // reports the same machine.
            if reporter.json {
                reporter.diagnostics(&[failure]);
            }
            code = code.max(EXIT_BAD_INPUT);
        }
        for path in diagram {
            reporter.say(&format!("  diagram: {}", path.display()));
        }
    }
    code
}

/// The scenario's events as written, in the order of the command line
/// (clap keeps each option's values apart; their places say the order).
fn written_events(args: &SimulateArgs) -> Vec<(String, String)> {
    use clap::CommandFactory;
    let given = [
        ("press", &args.press),
        ("hold", &args.hold),
        ("release", &args.release),
        ("stick", &args.stick),
    ];
    let matches = Cli::command()
        .try_get_matches_from(std::env::args_os())
        .ok();
    let sub = matches
        .as_ref()
        .and_then(|m| m.subcommand_matches("simulate"));
    let mut events: Vec<(usize, String, String)> = Vec::new();
    for (option, values) in given {
        // Parsed from the process's own command line; a library caller
        // (no such line) gets the options in the order of this list.
        let places: Vec<usize> = sub
            .and_then(|m| m.indices_of(option))
            .map(|i| i.collect())
            .unwrap_or_default();
        for (k, value) in values.iter().enumerate() {
            let place = places.get(k).copied().unwrap_or(usize::MAX);
            events.push((place, option.to_string(), value.clone()));
        }
    }
    events.sort_by_key(|(place, _, _)| *place);
    events.into_iter().map(|(_, o, v)| (o, v)).collect()
}

/// `simulate` with a scenario: each table's run printed as a step table.
fn run_scenarios(
    args: &SimulateArgs,
    settings: &Settings,
    events: &[(String, String)],
    reporter: &Reporter,
) -> i32 {
    let mut code = EXIT_OK;
    let names = convert::output_names(&args.inputs);
    let kept = write::Inputs::new(&args.inputs).named_by("--report");
    for (input, name) in args.inputs.iter().zip(&names) {
        let report = args
            .report
            .as_deref()
            .map(|dir| crate::commands::simulate::ScenarioReport {
                dir,
                name,
                inputs: &kept,
            });
        let run = crate::commands::simulate::scenario(input, settings, events, report);
        let run = match run {
            Ok(run) => run,
            Err(err) => {
                code = code.max(command_failed(reporter, &display_name(input), err));
                continue;
            }
        };
        reporter.diagnostics(&run.warnings);
        // Written before anything is printed, as `--diagram` is: with
        // stdout closed, printing ends the process.
        let written = match run.report {
            Some(Ok(paths)) => paths,
            Some(Err(err)) => {
                code = code.max(write_failed(reporter, &err));
                Vec::new()
            }
            None => Vec::new(),
        };
        reporter.say(&format!("{}: scenario", display_name(input)));
        reporter.say(&run.table);
        // The table goes to stderr under JSON: its problems go to stdout.
        if reporter.json {
            reporter.diagnostics(&run.problems);
        }
        for path in written {
            reporter.say(&format!("  report: {}", path.display()));
        }
    }
    code
}
