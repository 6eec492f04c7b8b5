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
    // The fault table is the one file written: no PLC tool's name limit.
    settings.formats = [OutputKind::Faults].into();
    let options = crate::commands::faults::FaultsOptions {
        at_once: if args.pairs {
            2
        } else {
            args.faults.unwrap_or(1) as usize
        },
        pairs: args.pairs,
    };
    let mut code = EXIT_OK;
    let names = convert::output_names(&args.inputs);
    let kept = write::Inputs::new(&args.inputs);
    for (input, name) in args.inputs.iter().zip(&names) {
        let progress = super::progress::Progress::new("fault cases", false);
        let run = crate::commands::faults::run(
            input,
            name,
            &settings,
            options,
            &args.output,
            &kept,
            &|done, total| progress.update(done, total),
        );
        progress.finish();
        let run = match run {
            Ok(run) => run,
            Err(err) => {
                code = code.max(command_failed(&report, &display_name(input), err));
                continue;
            }
        };
        report.diagnostics(&run.warnings);
        report.say(&format!(
            "{}: {}",
            display_name(input),
            run.result.summary()
        ));
        let symbols = &run.symbols;
        let rows = crate::faults::rows(&run.result, &|s| symbols.designation(s), &|t| {
            symbols.explain(t)
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
        match run.written {
            Ok(paths) => {
                for path in paths {
                    report.say(&format!("  wrote {}", path.display()));
                }
            }
            Err(err) => code = code.max(write_failed(&report, &err)),
        }
    }
    code
}
