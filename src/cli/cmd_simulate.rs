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
        let checked = match convert::check_path(input, &settings) {
            Ok(c) => c,
            Err(diagnostics) => {
                reporter.diagnostics(&diagnostics);
                code = code.max(EXIT_BAD_INPUT);
                continue;
            }
        };
        reporter.diagnostics(&checked.warnings);
        let (table, mut settings) = (checked.table, checked.settings);
        let lucky = convert::lucky_middle_stops(&table, &settings);
        if !lucky.is_empty() {
            reporter.diagnostics(&lucky);
            code = code.max(EXIT_BAD_INPUT);
            continue;
        }
        settings.simulation.record_trace = args.diagram.is_some();
        let program = convert::build_program(&table, &settings);
        if let Some(why) = steptable::simulate::over_budget(&table, &program, &settings.simulation)
        {
            reporter.diagnostics(&[convert::budget_error(&table, why)]);
            code = code.max(EXIT_BAD_INPUT);
            continue;
        }
        let report = steptable::simulate::simulate(&table, &program, &settings.simulation);
        // The diagram is written before anything is printed: with stdout
        // closed, printing ends the process (quietly), and the file the user
        // asked for must exist by then.
        let mut diagram = None;
        if let Some(dir) = &args.diagram {
            let symbols =
                steptable::symbols::SymbolTable::build(&program, &table, &settings.naming);
            let svg = steptable::emit::diagram::render_svg(
                name,
                &report,
                steptable::emit::diagram::DiagramKind::Time,
                &|n| symbols.actuator_parts(n),
            );
            let file = steptable::emit::OutputFile {
                name: format!("{name}.time.svg"),
                bytes: svg.into_bytes(),
            };
            match write::write_outputs(&dir.join(name), &[file], &kept, write::Durability::Rename) {
                Ok(paths) => diagram = Some(paths),
                Err(err) => code = code.max(write_failed(&reporter, &err)),
            }
        }
        reporter.say(&format!("{}: {}", display_name(input), report.verdict()));
        reporter.say(&steptable::simulate::report::step_table(&report));
        if !report.passed {
            // A script reading JSON sees why the run failed, as convert
            // reports the same machine.
            if reporter.json {
                reporter.error(
                    &table.file,
                    steptable::diag::Code::E032MachineCannotRun,
                    format!(
                        "the generated program fails its simulation: {}",
                        report.reason()
                    ),
                );
            }
            code = code.max(EXIT_BAD_INPUT);
        }
        for path in diagram.into_iter().flatten() {
            reporter.say(&format!("  diagram: {}", path.display()));
        }
    }
    code
}
