//! The pipeline, end to end and in memory: read → table → program → addresses
//! → every output file. Writing to disk is [`crate::write`]'s job.

mod allocate;
mod beside;
pub use allocate::{allocate, festo_allocation};
pub use findings::output_findings;
mod findings;
mod given;
mod idle_rows;
use idle_rows::{guard_leaves_motion, halts_for_good, rows_without_their_event};
mod jump_outputs;
mod kind_times;
mod untimed;
use home_order::home_order_by_name;
mod home_order;
use given::{
    by_name, delays_without_their_input, loads_without_effect, names_of_the_whole_table,
    overridden_by_the_command_line, settings_without_their_actuator, supervision_times,
};
mod physics;
mod placeholder_rows;
pub use physics::lucky_middle_stops;
mod pins;
mod report;

use std::path::Path;

use crate::address::Allocation;
use crate::diag::{Code, Diagnostic, Diagnostics, Location};
use crate::emit::OutputFile;
use crate::emit::templates::TemplateError;
use crate::emit::{self, EmitInput, OutputKind};
use crate::faults::{self, FaultTable};
use crate::program::{self, StepProgram};
use crate::read::{self, Format};
use crate::settings::Settings;
use crate::settings::halt::{self, Row};
use crate::simulate::{self, SimReport, SimSettings};
use crate::table::{self, StepTable};

/// A table that passed every check, with any warnings.
#[derive(Debug, Clone)]
pub struct Checked {
    pub table: StepTable,
    pub warnings: Vec<Diagnostic>,
    /// The settings in force for this file (command line over SETTINGS sheet).
    pub settings: Settings,
}

/// Everything a conversion produced.
#[derive(Debug, Clone)]
pub struct Conversion {
    /// Base name of the outputs (the input's file stem).
    pub name: String,
    pub table: StepTable,
    pub allocation: Allocation,
    pub program: StepProgram,
    /// Every name the outputs give (built once, read by every emitter).
    pub symbols: crate::symbols::SymbolTable,
    /// The simulation that proved the program.
    pub simulation: SimReport,
    /// Every single input fault, simulated and classified (when an output
    /// shows it: the fault table or the workbook).
    pub faults: Option<FaultTable>,
    pub files: Vec<OutputFile>,
    pub warnings: Vec<Diagnostic>,
    /// How the files were made, as each records it.
    pub made_by: crate::provenance::MadeBy,
    /// What the conversion found, a line each: the verdict and cycle time,
    /// the hazards, the homing order, a program without STOP (see
    /// [`findings::lines`]).
    pub findings: Vec<String>,
}

/// Why a conversion produced nothing.
#[derive(Debug)]
pub enum Failure {
    /// The input is wrong; every problem found is listed.
    Input(Vec<Diagnostic>),
    /// A bug or an environment problem.
    Internal(String),
    /// A template failed to render: the user's (fix it) or a default (a bug).
    Template(TemplateError),
}

/// Reads and checks one file. The result carries the settings in force for
/// it: `settings`, with the file's SETTINGS sheet filling in what the command
/// line did not set explicitly.
pub fn check_path(path: &Path, settings: &Settings) -> Result<Checked, Vec<Diagnostic>> {
    let mut diags = Diagnostics::new();
    let input = read::read_path(path, settings.sheet.as_deref(), &mut diags);
    finish_check(input, diags, settings)
}

/// Reads and checks an in-memory file of a known format.
pub fn check_bytes(
    file: &str,
    format: Format,
    bytes: Vec<u8>,
    settings: &Settings,
) -> Result<Checked, Vec<Diagnostic>> {
    let mut diags = Diagnostics::new();
    let input = read::read_bytes(file, format, bytes, settings.sheet.as_deref(), &mut diags);
    finish_check(input, diags, settings)
}

fn finish_check(
    input: Option<read::Input>,
    mut diags: Diagnostics,
    settings: &Settings,
) -> Result<Checked, Vec<Diagnostic>> {
    let Some(input) = input else {
        return Err(diags.into_sorted());
    };
    let sheet_given = input
        .settings
        .as_ref()
        .map(|sheet| crate::settings::parse(sheet, &mut diags));
    let mut effective = match &sheet_given {
        Some(given) => settings.with_sheet(given),
        None => settings.clone(),
    };
    let mut input = input;
    if let Some(grid) = &input.addresses {
        effective.pins = crate::settings::pins::parse(grid, &mut diags);
    }
    if !input.csv_readings.is_empty() {
        let readings = std::mem::take(&mut input.csv_readings);
        if let Some(grid) = table::choose_reading(readings, &mut diags) {
            input.table = grid;
        }
    }
    crate::settings::written_with_table(&input.table, &mut diags);
    let has_settings = input.settings.is_some();
    crate::settings::written_elsewhere(&input.others, has_settings, &mut diags);
    let valves = &effective.simulation.machine.valves;
    let writes_fst = effective.writes_fst();
    let table = table::build_for(&input.table, valves, writes_fst, &mut diags);
    if let Some(table) = &table {
        by_name(table, &mut effective, &input.table.file, &mut diags);
        // A home order from the SETTINGS sheet is blamed on its cell; one
        // from the command line on the file, naming the option.
        let home_order_at = effective.cells.get("home order").cloned();
        home_order_by_name(
            table,
            &mut effective,
            home_order_at.as_ref(),
            &input.table.file,
            &mut diags,
        );
        given::manual_without_actuators(table, &mut effective, &input.table.file, &mut diags);
        let modes = &effective.program.modes;
        let mut buttons: Vec<String> = modes
            .buttons()
            .map(|b| b.symbol().to_ascii_lowercase())
            .collect();
        buttons.extend(given::jog_names(table, &effective));
        let machine = table::Machine {
            valves: &effective.simulation.machine.valves,
            home_order: modes.home_order.as_deref(),
            home_order_at: home_order_at.as_ref(),
            reset: modes.reset,
            buttons: &buttons,
            fst: writes_fst,
        };
        table::check_machine(table, &machine, &input.table, &mut diags);
        kind_times::kind_times(table, &mut effective, sheet_given.as_ref(), &mut diags);
        let sheet = input.settings.as_ref().zip(sheet_given.as_ref());
        settings_without_their_actuator(table, settings, sheet, &input.table.file, &mut diags);
        loads_without_effect(
            table,
            &effective,
            sheet_given.as_ref(),
            &input.table,
            &mut diags,
        );
        supervision_times(table, &effective, &input.table.file, &mut diags);
        if let Some(sheet) = &sheet_given {
            overridden_by_the_command_line(&settings.given, sheet, &effective.naming, &mut diags);
        }
        let named = &effective.named;
        effective.program.halt = halt::resolve(
            table,
            &effective.simulation.machine.valves,
            &effective.naming,
            named,
            &mut diags,
        );
        effective.program.permissive = halt::resolve_held_inputs(
            table,
            (&buttons, writes_fst),
            Row::StartPermissive,
            named.get(&Row::StartPermissive),
            &mut diags,
        );
        effective.program.interlocks = halt::resolve_interlocks(
            table,
            (&buttons, writes_fst),
            named.get(&Row::Interlock),
            &mut diags,
        );
        names_of_the_whole_table(table, &input.table, &effective, &buttons, &mut diags);
        delays_without_their_input(table, &effective, &input.table, &mut diags);
        rows_without_their_event(&effective, &mut diags);
        halts_for_good(table, &effective, &mut diags);
        guard_leaves_motion(table, &effective, &mut diags);
        untimed::moves_left_unsupervised(table, &effective, &input.table, &mut diags);
        jump_outputs::outputs_a_jump_leaves(table, &input.table, &mut diags);
    }
    match table {
        Some(table) if !diags.has_errors() => Ok(Checked {
            table,
            warnings: diags.into_sorted(),
            settings: effective,
        }),
        _ => Err(diags.into_sorted()),
    }
}

/// Longest output base name, in bytes: with the longest file name after it
/// (`NAME.beremiz/beremiz.xml`) and a temporary file's affixes, every name
/// stays within the 255 bytes file systems allow.
pub const MAX_NAME_BYTES: usize = 200;

/// The output base name for an input path: its file stem, made safe as a
/// folder and file name: control characters become `_`, leading and
/// trailing dots and spaces go (an input named `...csv` must not write into
/// `DIR/..`), and it is cut to [`MAX_NAME_BYTES`]. Empty: `steptable`.
pub fn output_name(path: &Path) -> String {
    let stem = path
        .file_stem()
        .map(|s| s.to_string_lossy().to_string())
        .unwrap_or_default();
    let cleaned: String = stem
        .chars()
        .map(|c| {
            if c.is_control() || c == '/' || c == '\\' {
                '_'
            } else {
                c
            }
        })
        .collect();
    let mut name = cleaned
        .trim_matches(|c: char| c == '.' || c.is_whitespace())
        .to_string();
    if name.len() > MAX_NAME_BYTES {
        let mut cut = MAX_NAME_BYTES;
        while !name.is_char_boundary(cut) {
            cut -= 1;
        }
        name.truncate(cut);
        name = name
            .trim_end_matches(|c: char| c == '.' || c.is_whitespace())
            .to_string();
    }
    if name.is_empty() {
        "steptable".to_string()
    } else {
        name
    }
}

/// Distinct output names for several inputs, returned in the inputs'
/// order: the one rule `convert` and `batch` share, so that a set of inputs
/// gets the same folders whichever command converts it and in whatever
/// order it is given (a shell's glob and a folder walk sort differently).
/// An input whose stem no other input has keeps it; so does the first of
/// inputs sharing a stem (in path order, letters compared without case).
/// The others get `stem-ext` (`line.xlsx` beside `line.csv`), or `stem-2`,
/// `stem-3`, … when that is taken — never a name that is another input's
/// own stem (`line-xlsx.xlsx` keeps `line-xlsx`). Where a name differs from
/// the stem, the commands say so (see [`renamed`]).
pub fn output_names(paths: &[impl AsRef<Path>]) -> Vec<String> {
    let stems: Vec<String> = paths.iter().map(|p| output_name(p.as_ref())).collect();
    let mut order: Vec<usize> = (0..paths.len()).collect();
    let key = |i: &usize| {
        let path = paths[*i].as_ref().to_string_lossy();
        (path.to_lowercase(), path.to_string())
    };
    order.sort_by_key(key);
    // Each input's own stem is claimed first, by the first input to have it.
    let mut taken = std::collections::BTreeSet::new();
    let mut names: Vec<Option<String>> = vec![None; paths.len()];
    for &i in &order {
        if taken.insert(stems[i].to_lowercase()) {
            names[i] = Some(stems[i].clone());
        }
    }
    for &i in &order {
        if names[i].is_some() {
            continue;
        }
        let stem = &stems[i];
        let mut name = match paths[i].as_ref().extension() {
            Some(ext) => format!("{stem}-{}", ext.to_string_lossy().to_lowercase()),
            None => stem.clone(),
        };
        let mut n = 2;
        while taken.contains(&name.to_lowercase()) {
            name = format!("{stem}-{n}");
            n += 1;
        }
        taken.insert(name.to_lowercase());
        names[i] = Some(name);
    }
    names.into_iter().map(Option::unwrap_or_default).collect()
}

/// Whether `name` is not the stem `path` alone would get: another input
/// took it, and the commands say where this one went instead.
pub fn renamed(path: &Path, name: &str) -> bool {
    output_name(path) != name
}

/// Converts one file completely, in memory; outputs are named after its stem.
pub fn convert_path(path: &Path, settings: &Settings) -> Result<Conversion, Failure> {
    convert_path_as(path, &output_name(path), settings)
}

/// Converts one file completely, in memory, naming the outputs `name.*`.
pub fn convert_path_as(
    path: &Path,
    name: &str,
    settings: &Settings,
) -> Result<Conversion, Failure> {
    let checked = check_path(path, settings).map_err(Failure::Input)?;
    generate(name, checked)
}

/// The program of a checked table and its simulation under `sim`, which
/// must run the cycle: outputs and fault tables are judged against that
/// cycle, so a machine that cannot run it is said (E032 with the setting to
/// blame), not converted or analysed.
pub fn healthy_program(
    table: &StepTable,
    settings: &Settings,
    sim: &SimSettings,
) -> Result<(StepProgram, SimReport), Failure> {
    proven_program(table, settings, sim, None, false).map(|p| (p.program, p.proof))
}

/// A program proven by its healthy run, with what that one run can hand
/// on: the fault analysis's yardstick and the report's recording.
pub struct Proven {
    pub program: StepProgram,
    pub proof: SimReport,
    /// The run the fault analysis measures against, when one will run.
    pub healthy: Option<faults::Healthy>,
    /// Every input, output, the active step and the positions, scan by
    /// scan, when `record` was asked.
    pub io_trace: Option<simulate::io::IoTrace>,
}

/// Like [`healthy_program`]; when a fault analysis of up to `faults_at_once`
/// faults will run (it is within its budgets), the proof is its healthy run
/// too ([`faults::healthy_run`]), handed back to be given to it: one
/// simulation of the healthy cycle, not two. Past a budget the analysis is
/// refused, and the proof logs nothing for it. With `record`, that same run
/// is recorded scan by scan (for the report's timeline).
pub fn proven_program(
    table: &StepTable,
    settings: &Settings,
    sim: &SimSettings,
    faults_at_once: Option<usize>,
    record: bool,
) -> Result<Proven, Failure> {
    let program = build_program(table, settings);
    let refused = refused_without_a_run(table, settings, &program);
    if !refused.is_empty() {
        return Err(Failure::Input(refused));
    }
    if let Some(why) = simulate::over_budget(table, &program, sim) {
        return Err(Failure::Input(vec![budget_error(table, why)]));
    }
    let for_faults = faults_at_once.is_some_and(|k| {
        faults::case_count(&program, k) <= faults::MAX_CASES
            && faults::over_budget(table, &program, sim, k).is_none()
    });
    let signals = record.then(|| simulate::io::IoSignals {
        max_scans: Some(emit::report::TIMELINE_SCANS),
        ..simulate::io::IoSignals::every(&program)
    });
    let (simulation, healthy, io_trace) = if for_faults {
        let (healthy, trace) = faults::healthy_run_recording(table, &program, sim, signals);
        // The places are the analysis's; the proof's report has none.
        let proof = SimReport {
            places: Default::default(),
            ..healthy.report.clone()
        };
        (proof, Some(healthy), trace)
    } else if let Some(signals) = signals {
        let run = simulate::Simulator::new(table, &program).run_recorded(sim, Some(signals), false);
        (run.report, None, run.trace)
    } else {
        (simulate::simulate(table, &program, sim), None, None)
    };
    if simulation.passed {
        Ok(Proven {
            program,
            proof: simulation,
            healthy,
            io_trace,
        })
    } else {
        Err(physics::explain(table, settings, &simulation))
    }
}

/// What convert refuses in `program` (built from `table` under `settings`)
/// by arithmetic alone, before any run: a middle stop only luck would
/// reach, a watchdog no PLC timer holds (E032). `check` says them too.
pub fn refused_without_a_run(
    table: &StepTable,
    settings: &Settings,
    program: &StepProgram,
) -> Vec<Diagnostic> {
    let lucky = physics::lucky_middle_stops(table, settings);
    if !lucky.is_empty() {
        return lucky;
    }
    physics::watchdogs_beyond_timers(table, program)
}

/// Error E033 for `table`: the work it asks for is beyond the budget.
pub fn budget_error(table: &StepTable, why: String) -> Diagnostic {
    Diagnostic {
        severity: crate::diag::Severity::Error,
        code: Code::E033OverBudget,
        location: Location {
            file: table.file.clone(),
            sheet: None,
            cell: None,
        },
        message: why,
    }
}

/// The step program of a checked table under `settings`.
pub fn build_program(table: &StepTable, settings: &Settings) -> StepProgram {
    program::build(
        table,
        &settings.program,
        &settings.simulation.machine.valves,
        &settings.simulation.machine.strokes,
    )
}

/// Generates every output of a checked table.
pub fn generate(name: &str, checked: Checked) -> Result<Conversion, Failure> {
    generate_observed(name, checked, &|_, _| {})
}

/// Like [`generate`], calling `progress(done, total)` as the fault analysis
/// (the long part on a large table) runs its cases.
pub fn generate_observed(
    name: &str,
    checked: Checked,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Conversion, Failure> {
    let Checked {
        table,
        mut warnings,
        settings,
    } = checked;
    let settings = &settings;
    let sim_settings = SimSettings {
        record_trace: settings.diagram == emit::diagram::DiagramKind::Time,
        ..settings.simulation.clone()
    };
    let shows_faults = settings.formats.iter().any(|k| k.shows_faults());
    // The report's timeline needs the healthy run scan by scan: then that
    // one run is recorded.
    let record = settings.formats.contains(&OutputKind::Report)
        && table.steps.len() <= emit::report::TIMELINE_STEPS;
    let Proven {
        program,
        proof: simulation,
        healthy,
        io_trace,
    } = proven_program(
        &table,
        settings,
        &sim_settings,
        shows_faults.then_some(1),
        record,
    )?;
    let made_by = crate::provenance::MadeBy::of_run(settings, &table.file);
    let settings_rows = report::settings_rows(settings, &table, &made_by);
    let allocation = allocate(&program, settings, &table.file).map_err(Failure::Input)?;
    let festo = festo_allocation(&program, &allocation);
    let symbols = crate::symbols::SymbolTable::build(&program, &table, &settings.naming);
    let pictures = emit::Pictures::default();
    let input = EmitInput {
        name,
        table: &table,
        allocation: &allocation,
        festo: &festo,
        program: &program,
        symbols: &symbols,
        simulation: Some(&simulation),
        faults: None,
        mitigations: None,
        io_trace: io_trace.as_ref(),
        settings: &settings_rows,
        templates: &settings.templates,
        scan_ms: settings.simulation.scan_ms,
        diagram: settings.diagram,
        pictures: Some(&pictures),
    };
    warnings.extend(findings::of(&input, settings).map_err(Failure::Input)?);
    // Only the fault table and the workbook show the fault analysis; it is
    // most of the work on a large table, so it runs only for them, and
    // beside the other outputs (on a core the analysis leaves idle: its
    // healthy and checkpoint runs are one thread's work). The outputs that
    // show it render as soon as it is done, beside the others still
    // rendering, not after them.
    let (early, late): (Vec<OutputKind>, Vec<OutputKind>) =
        settings.formats.iter().partition(|k| !k.shows_faults());
    if !late.is_empty()
        && let Some(why) = faults::over_budget(&table, &program, &settings.simulation, 1)
    {
        let shown: Vec<&str> = late.iter().map(|k| k.name()).collect();
        let why = format!(
            "{why}, or leave out the outputs that show the fault table (--formats without {})",
            shown.join(", ")
        );
        return Err(Failure::Input(vec![budget_error(&table, why)]));
    }
    let (files, fault_table) =
        beside::render_beside_faults(input, early, late, settings, progress, healthy)?;
    let files = crate::provenance::stamp_all(files, &made_by).map_err(Failure::Internal)?;
    let findings = findings::lines(
        &table,
        &symbols,
        &settings.program.modes,
        &simulation,
        fault_table.as_ref(),
    );
    Ok(Conversion {
        findings,
        made_by,
        name: name.to_string(),
        table,
        allocation,
        program,
        symbols,
        simulation,
        faults: fault_table,
        files,
        warnings,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn output_names_stay_inside_the_output_folder() {
        assert_eq!(output_name(Path::new("...csv")), "steptable");
        assert_eq!(output_name(Path::new("..csv")), "steptable");
        assert_eq!(output_name(Path::new(".hidden.xlsx")), "hidden");
        assert_eq!(output_name(Path::new("a\nb.csv")), "a_b");
        let long = format!("{}.csv", "é".repeat(200));
        let name = output_name(Path::new(&long));
        assert!(name.len() <= MAX_NAME_BYTES && name.chars().all(|c| c == 'é'));
    }

    #[test]
    fn the_fault_analysis_runs_only_for_the_outputs_that_show_it() {
        let convert = |formats: &str| {
            let settings = Settings {
                formats: OutputKind::parse_list(formats).unwrap(),
                ..Settings::new()
            };
            let bytes = b"C1+1\nC2+1\nC1-0\nC2-0\n".to_vec();
            let checked = check_bytes("t.csv", crate::read::Format::Csv, bytes, &settings).unwrap();
            generate("t", checked).unwrap()
        };
        assert!(convert("st,io").faults.is_none());
        let with_table = convert("faults").faults.expect("the fault table shows it");
        assert!(!with_table.cases.is_empty());
        assert!(convert("xlsx").faults.is_some(), "the workbook shows it");
    }

    #[test]
    fn colliding_inputs_get_distinct_names() {
        let names = output_names(&[
            "a/line.xlsx",
            "b/line.xlsx",
            "line.csv",
            "c/LINE.xlsx",
            "other.ods",
        ]);
        assert_eq!(names, ["line", "line-xlsx", "line-csv", "LINE-2", "other"]);
    }

    #[test]
    fn names_depend_on_the_inputs_not_their_order() {
        let inputs = [
            "c/line.xlsx",
            "c/line.csv",
            "c/line-csv.xlsx",
            "c/line-xlsx.xlsx",
        ];
        let named = |order: &[usize]| {
            let paths: Vec<&str> = order.iter().map(|&i| inputs[i]).collect();
            let names = output_names(&paths);
            let mut pairs: Vec<(&str, String)> = paths.into_iter().zip(names).collect();
            pairs.sort();
            pairs
        };
        let first = named(&[0, 1, 2, 3]);
        assert_eq!(
            first,
            [
                ("c/line-csv.xlsx", "line-csv".to_string()),
                ("c/line-xlsx.xlsx", "line-xlsx".to_string()),
                ("c/line.csv", "line".to_string()),
                ("c/line.xlsx", "line-2".to_string()),
            ]
        );
        for order in [[3, 2, 1, 0], [2, 0, 3, 1], [1, 3, 0, 2]] {
            assert_eq!(named(&order), first, "{order:?}");
        }
        assert!(renamed(Path::new("c/line.xlsx"), "line-2"));
        assert!(!renamed(Path::new("c/line.csv"), "line"));
    }
}
