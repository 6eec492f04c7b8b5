//! `steptable faults`: what every sensor stuck at 1 or 0 does to the
//! machine, as a table on the terminal and `NAME.faults.csv`.

use super::*;

#[derive(Args)]
pub(crate) struct FaultsArgs {
    /// Step-table files (.xlsx, .xlsm, .xls, .ods, .csv).
    #[arg(required = true)]
    pub(crate) inputs: Vec<PathBuf>,
    /// Also every pair of faults (the same as --faults 2).
    #[arg(long, conflicts_with = "faults")]
    pub(crate) pairs: bool,
    /// Up to K faults at once, on different inputs (1 to 4; default 1).
    #[arg(long, value_name = "K", value_parser = clap::value_parser!(u8).range(1..=4))]
    pub(crate) faults: Option<u8>,
    /// Output folder for NAME/NAME.faults.csv.
    #[arg(short, long, value_name = "DIR", default_value = "steptable-out")]
    pub(crate) output: PathBuf,
    #[command(flatten)]
    pub(crate) common: CommonArgs,
    #[command(flatten)]
    pub(crate) sim: SimArgs,
}

pub(crate) fn run_faults(args: &FaultsArgs) -> i32 {
    let mut settings = args.common.settings();
    let report = Reporter::new(&args.common);
    args.sim.apply(&mut settings);
    let mut code = EXIT_OK;
    let names = convert::output_names(&args.inputs);
    let kept = write::Inputs::new(&args.inputs);
    for (input, name) in args.inputs.iter().zip(&names) {
        let checked = match convert::check_path(input, &settings) {
            Ok(c) => c,
            Err(diagnostics) => {
                report.diagnostics(&diagnostics);
                code = code.max(EXIT_BAD_INPUT);
                continue;
            }
        };
        report.diagnostics(&checked.warnings);
        let (table, settings) = (checked.table, checked.settings);
        let program = match convert::healthy_program(&table, &settings, &settings.simulation) {
            Ok((program, _)) => program,
            Err(Failure::Input(diagnostics)) => {
                report.diagnostics(&diagnostics);
                code = code.max(EXIT_BAD_INPUT);
                continue;
            }
            Err(Failure::Internal(why)) => {
                eprintln!("{}: internal error: {why}", display_name(input));
                code = EXIT_INTERNAL;
                continue;
            }
            Err(Failure::Template(err)) => {
                eprintln!("{}: internal error: {err}", display_name(input));
                code = EXIT_INTERNAL;
                continue;
            }
        };
        let at_once = if args.pairs {
            2
        } else {
            args.faults.unwrap_or(1) as usize
        };
        let cases = steptable::faults::case_count(&program, at_once);
        if cases > steptable::faults::MAX_CASES {
            report.diagnostics(&[Diagnostic {
                severity: Severity::Error,
                code: steptable::diag::Code::E033OverBudget,
                location: steptable::diag::Location {
                    file: table.file.clone(),
                    sheet: None,
                    cell: None,
                },
                message: format!(
                    "{} would simulate {cases} fault cases ({} inputs, each stuck at 1 and at 0, up to {at_once} at once); steptable runs at most {}: analyse fewer faults at once (single faults without {}), or split the table",
                    if args.pairs { "--pairs".to_string() } else { format!("--faults {at_once}") },
                    program.signals.inputs.len(),
                    steptable::faults::MAX_CASES,
                    if args.pairs { "--pairs" } else { "--faults" },
                ),
            }]);
            code = code.max(EXIT_BAD_INPUT);
            continue;
        }
        if let Some(why) =
            steptable::faults::over_budget(&table, &program, &settings.simulation, at_once)
        {
            report.diagnostics(&[convert::budget_error(&table, why)]);
            code = code.max(EXIT_BAD_INPUT);
            continue;
        }
        // The table's designations, as in every output of convert.
        let symbols = steptable::symbols::SymbolTable::build(&program, &table, &settings.naming);
        let progress = super::progress::Progress::new("fault cases", false);
        let result = steptable::faults::analyse_observed(
            &table,
            &program,
            &settings.simulation,
            at_once,
            &|done, total| progress.update(done, total),
        );
        progress.finish();
        // The table is written before anything is printed (see simulate).
        let file = steptable::emit::OutputFile {
            name: format!("{name}.faults.csv"),
            bytes: match steptable::emit::faults_csv::render(
                &result,
                &|s| symbols.designation(s),
                &|t| symbols.designate(t),
            ) {
                Ok(b) => b,
                Err(e) => {
                    eprintln!("internal error: {e}");
                    code = EXIT_INTERNAL;
                    continue;
                }
            },
        };
        if let Err(err) = write::write_outputs(
            &args.output.join(name),
            &[file],
            &kept,
            write::Durability::Rename,
        ) {
            code = code.max(write_failed(&report, &err));
        }
        report.say(&format!("{}: {}", display_name(input), result.summary()));
        let rows = steptable::faults::rows(&result, &|s| symbols.designation(s), &|t| {
            symbols.designate(t)
        });
        let width = rows.iter().map(|r| r[0].len()).max().unwrap_or(5).max(5);
        let when = rows.iter().map(|r| r[2].len()).max().unwrap_or(7).max(7);
        report.say(&format!(
            "  {:<width$}  {:<10}  {:<when$}  {:<8}  {:>4}  explanation",
            "fault", "outcome", "appears", "detected", "step"
        ));
        for r in &rows {
            report.say(&format!(
                "  {:<width$}  {:<10}  {:<when$}  {:<8}  {:>4}  {}",
                r[0], r[1], r[2], r[3], r[4], r[5]
            ));
        }
    }
    code
}
