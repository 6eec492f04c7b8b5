//! `steptable template` and `steptable templates export`.

use super::*;

#[derive(Args)]
pub(crate) struct TemplateArgs {
    /// The workbook to write.
    #[arg(
        short,
        long,
        value_name = "FILE",
        default_value = "steptable-template.xlsx"
    )]
    pub(crate) output: PathBuf,
    /// Number of branch columns.
    #[arg(long, default_value_t = 4, value_parser = clap::value_parser!(u16).range(1..=256))]
    pub(crate) branches: u16,
    /// Number of step rows.
    #[arg(long, default_value_t = 20, value_parser = clap::value_parser!(u32).range(1..=10000))]
    pub(crate) steps: u32,
    /// Replace the file if it exists (it may hold a filled-in table).
    #[arg(long)]
    pub(crate) force: bool,
}

#[derive(Subcommand)]
pub(crate) enum TemplatesCommand {
    /// Write the built-in templates into DIR, to edit and use with --templates.
    Export {
        /// Folder to write the templates into (created if missing).
        dir: PathBuf,
        /// Replace templates already in the folder (they may be your edits).
        #[arg(long)]
        force: bool,
    },
}

pub(crate) fn run_template(args: &TemplateArgs) -> i32 {
    if args.output.is_dir() {
        eprintln!(
            "error: {} is a folder; give the workbook's file name, e.g. {}",
            args.output.display(),
            args.output.join("steptable-template.xlsx").display()
        );
        return EXIT_BAD_INPUT;
    }
    let is_xlsx = args
        .output
        .extension()
        .is_some_and(|e| e.to_string_lossy().eq_ignore_ascii_case("xlsx"));
    if !is_xlsx {
        eprintln!(
            "error: {}: the template is an Excel workbook; give it a name ending in .xlsx",
            args.output.display()
        );
        return EXIT_BAD_INPUT;
    }
    if args.output.exists() && !args.force {
        eprintln!(
            "error: {} exists and may hold your table; choose another -o or add --force",
            args.output.display()
        );
        return EXIT_BAD_INPUT;
    }
    let bytes = match crate::template_workbook::template_workbook(args.branches, args.steps) {
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
    match write::write_files(
        &folder,
        &[crate::emit::OutputFile { name, bytes }],
        &write::Inputs::none(),
        write::Durability::Rename,
    ) {
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
        Err(err) => write_failed(&Reporter::for_format(MessageFormat::Human), &err),
    }
}
