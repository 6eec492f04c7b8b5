//! `steptable simulate`: the generated program against a model of the
//! pneumatics, with the verdict and the step timing.

use super::*;

#[derive(Args)]
pub(crate) struct SimulateArgs {
    /// Step-table files (.xlsx, .xlsm, .xls, .ods, .csv).
    #[arg(required = true)]
    pub(crate) inputs: Vec<PathBuf>,
    /// Generate the program without middle stops, as the published method
    /// does, to see why they matter.
    #[arg(long)]
    pub(crate) no_middle_stop: bool,
    /// Also write the run's displacement-time diagram (dwells and waits
    /// shaded) to DIR/NAME/NAME.time.svg.
    #[arg(long, value_name = "DIR")]
    pub(crate) diagram: Option<PathBuf>,
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
    let mut code = EXIT_OK;
    let names = convert::output_names(&args.inputs);
    let kept = write::Inputs::new(&args.inputs);
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
