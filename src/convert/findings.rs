//! What a conversion found, in the few lines `convert` prints under each
//! input: the simulation's verdict and cycle time, the fault table's
//! hazards with the first one's cause, the order RESET homes in, and — for
//! a program without operating modes — that it has no STOP or EMERGENCY
//! STOP and which option adds them. The engineer should not have to open
//! seventeen files to learn what steptable already knows.

use crate::address::Allocation;
use crate::diag::Diagnostic;
use crate::emit::{EmitInput, OutputKind};
use crate::faults::{FaultTable, Outcome};
use crate::program::{Modes, StepProgram};
use crate::settings::Settings;
use crate::simulate::SimReport;
use crate::symbols::SymbolTable;
use crate::table::StepTable;

/// The lines, most important first, without the input's name; each signal
/// and actuator named as the symbol table names it (`1B2`, `C1 (clamp)`).
pub fn lines(
    table: &StepTable,
    symbols: &SymbolTable,
    modes: &Modes,
    simulation: &SimReport,
    faults: Option<&FaultTable>,
) -> Vec<String> {
    let mut lines = vec![symbols.explain(&format!("simulation {}", simulation.verdict()))];
    if let Some(faults) = faults {
        lines.push(hazards(faults, symbols));
    }
    if modes.reset
        && let Ok(stages) = modes.home_stages(table)
    {
        lines.push(if stages.is_empty() {
            "RESET abandons the cycle; no actuator to home, the machine is ready at once"
                .to_string()
        } else {
            format!("RESET homes {}", stages_text(&stages, symbols))
        });
    }
    let missing: Vec<&str> = [(modes.stop, "STOP"), (modes.estop, "EMERGENCY STOP")]
        .into_iter()
        .filter_map(|(has, name)| (!has).then_some(name))
        .collect();
    if !missing.is_empty() {
        lines.push(format!(
            "note: the program has no {} button (--modes all, or a `modes` row on SETTINGS, adds STOP, EMERGENCY STOP, RESET and continuous operation)",
            missing.join(" or ")
        ));
    }
    lines
}

/// `fault table: 3 hazard(s) among 24 fault case(s); first: x22 open
/// circuit (stuck at 0) in step 5: …`, or that there is none.
fn hazards(faults: &FaultTable, symbols: &SymbolTable) -> String {
    let count = faults.count(Outcome::Hazard);
    let cases = faults.cases.len();
    let Some(first) = faults.cases.iter().find(|c| c.outcome == Outcome::Hazard) else {
        return format!("fault table: no hazard among {cases} fault case(s)");
    };
    let step = first
        .step
        .map(|s| format!(" in step {s}"))
        .unwrap_or_default();
    format!(
        "fault table: {count} hazard(s) among {cases} fault case(s); first: {}{step}: {}",
        first.fault_text_as(&|s| symbols.designation(s)),
        symbols.explain(&first.explanation)
    )
}

/// `C2, C3 & C4, then C1`: stages in order, actuators of a stage together.
fn stages_text(stages: &[Vec<u32>], symbols: &SymbolTable) -> String {
    let stage = |s: &Vec<u32>| {
        let names: Vec<String> = s.iter().map(|n| symbols.actuator_in_finding(*n)).collect();
        match names.split_last() {
            Some((last, rest)) if !rest.is_empty() => format!("{} & {last}", rest.join(", ")),
            _ => names.join(""),
        }
    };
    let texts: Vec<String> = stages.iter().map(stage).collect();
    match texts.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{}, then {last}", rest.join(", then ")),
        _ => texts.join(""),
    }
}

/// W008 when `NAME.sdf` cuts comments to the width STEP 7's symbol table
/// holds (a long step comment or actuator name), naming the symbols, so
/// the engineer knows where the symbol table says less than the `.awl`.
pub(super) fn shortened_sdf_comments(
    input: &crate::emit::EmitInput,
) -> Option<crate::diag::Diagnostic> {
    let cut = crate::emit::awl::shortened_comments(input);
    let (first, _) = cut.split_first()?;
    let more = match cut.len() {
        1 => String::new(),
        n => format!(" and {} more ({})", n - 1, cut[1..].join(", ")),
    };
    Some(shortened(
        input,
        format!(
            "{}.sdf: the comment of {first}{more} is longer than the {} characters a STEP 7 symbol table holds; it is cut there and ends in \"...\" (the .awl keeps it whole); shorten the step comment or actuator name to keep it",
            input.name,
            crate::emit::sdf::SDF_COMMENT
        ),
    ))
}

/// W008 at the input as a whole: an output holds less than it says.
fn shortened(input: &crate::emit::EmitInput, message: String) -> crate::diag::Diagnostic {
    crate::diag::Diagnostic {
        severity: crate::diag::Severity::Warning,
        code: crate::diag::Code::W008Shortened,
        location: crate::diag::Location {
            file: input.table.file.clone(),
            sheet: None,
            cell: None,
        },
        message,
    }
}

/// W008 when a timer's time is finer than the AWL's S5TIME or FST's
/// hundredths hold (`T=15ms`), and one of those files is asked for: its
/// preset there is longer, rounded up, than what the simulation proved and
/// the other programs load.
pub(super) fn rounded_presets(
    input: &crate::emit::EmitInput,
    settings: &crate::settings::Settings,
) -> Option<crate::diag::Diagnostic> {
    use crate::emit::OutputKind;
    use crate::program::Action;
    let awl = settings.formats.contains(&OutputKind::Awl);
    let fst = settings.formats.contains(&OutputKind::Fst);
    let program = input.program;
    let actions = (program.init.iter())
        .chain(program.steps.iter().flat_map(|s| &s.actions))
        .chain(program.rungs.iter().flat_map(|r| &r.actions));
    let mut said: Vec<String> = Vec::new();
    for action in actions {
        let Action::StartTimer(timer, ms) = *action else {
            continue;
        };
        let mut held = Vec::new();
        if awl && crate::emit::s5time::s5_ms(ms) != ms {
            held.push(format!(
                "{}.awl {} ms",
                input.name,
                crate::emit::s5time::s5_ms(ms)
            ));
        }
        if fst && crate::emit::fst::fst_ms(ms) != ms {
            held.push(format!(
                "{}.fst.txt {} ms",
                input.name,
                crate::emit::fst::fst_ms(ms)
            ));
        }
        let line = format!(
            "{} for {ms} ms ({})",
            input.symbols.ident(timer),
            held.join(", ")
        );
        if !held.is_empty() && !said.contains(&line) {
            said.push(line);
        }
    }
    let (first, rest) = said.split_first()?;
    let more = match rest.len() {
        0 => String::new(),
        _ => format!("; {}", rest.join("; ")),
    };
    Some(shortened(
        input,
        format!(
            "{first}{more}: STEP 7's S5TIME and FST's presets count in steps of 10 ms or more, so the time is rounded up there; the simulation and the other programs use it as written (write a multiple of 10 ms to have one time everywhere)"
        ),
    ))
}

/// W008 when a name or comment of the engineer's holds characters the
/// Windows-1252 code page lacks, and a file written in it is asked for
/// (`.sdf`, FST, CoDeSys V2.3): there they are `?`.
pub(super) fn code_page_losses(
    input: &crate::emit::EmitInput,
    settings: &crate::settings::Settings,
) -> Option<crate::diag::Diagnostic> {
    let files: Vec<String> = settings
        .formats
        .iter()
        .filter(|k| k.windows_ansi())
        .map(|k| k.file_name(input.name))
        .collect();
    if files.is_empty() {
        return None;
    }
    let symbols = input.symbols;
    let steps = (0..input.program.steps.len()).filter_map(|i| symbols.step(i));
    let texts = symbols
        .symbols()
        .flat_map(|(_, s)| [&s.ident, &s.designation, &s.comment])
        .chain(steps.flat_map(|s| [&s.title, &s.active_title]));
    let mut lacked: Vec<char> = crate::emit::code_page_lacks(input.name);
    for text in texts {
        for c in crate::emit::code_page_lacks(text) {
            if !lacked.contains(&c) {
                lacked.push(c);
            }
        }
    }
    if lacked.is_empty() {
        return None;
    }
    let chars: String = lacked.iter().map(|c| format!("{} ", shown(*c))).collect();
    Some(shortened(
        input,
        format!(
            "{}: these files are written in the Windows-1252 code page the Windows tools read them in, which lacks {}(from a name or comment of yours): there each is written as ?; the other outputs keep them",
            files.join(", "),
            chars
        ),
    ))
}

/// One character for a message: quoted where it shows on its own, by its
/// code point where it does not (a combining mark left over a quote, a
/// zero-width or other invisible character).
fn shown(c: char) -> String {
    let invisible = unicode_normalization::char::is_combining_mark(c)
        || c.is_control()
        || c.is_whitespace()
        || crate::cell::zero_width(c);
    match invisible {
        true => format!("U+{:04X}", u32::from(c)),
        false => format!("\"{c}\""),
    }
}

/// E048 at each jump back into its own step whose re-entry does something
/// (restarts a dwell or the watchdog, sets a coil again), when an SFC
/// chart is asked for: the chart's step stays active through such a jump
/// and does not run its entry again, so its program would not run as the
/// simulation (the ST, AWL, Ladder and the others do).
pub(super) fn retry_in_chart(
    input: &crate::emit::EmitInput,
    settings: &crate::settings::Settings,
) -> Vec<crate::diag::Diagnostic> {
    use crate::emit::OutputKind;
    let charts: Vec<&str> = [
        OutputKind::Sfc,
        OutputKind::BeremizSfc,
        OutputKind::CodesysSfc,
    ]
    .into_iter()
    .filter(|k| settings.formats.contains(k))
    .map(|k| k.name())
    .collect();
    if charts.is_empty() {
        return Vec::new();
    }
    let program = input.program;
    let retries = program.steps.iter().enumerate().flat_map(|(i, step)| {
        step.jumps
            .iter()
            .filter(move |j| j.next == i && !j.actions.is_empty())
    });
    let table = input.table;
    let jumps = table.steps.iter().flat_map(|s| &s.jumps);
    retries
        .map(|retry| {
            let cell = jumps.clone().find(|j| j.notation() == retry.title).map(|j| j.cell);
            crate::diag::Diagnostic {
                severity: crate::diag::Severity::Error,
                code: crate::diag::Code::E048RetryInChart,
                location: crate::diag::Location {
                    file: table.file.clone(),
                    sheet: table.sheet.clone(),
                    cell,
                },
                message: format!(
                    "\"{}\" jumps back into its own step, whose entry restarts its dwell or sets its coils again: an SFC step that stays active does not run its entry again, so the chart ({}) cannot run this table as the program does; leave out the chart (the ST program, AWL and the Ladder body run the retry), or jump to a step of its own",
                    retry.title,
                    charts.join(", ")
                ),
            }
        })
        .collect()
}

/// W011 when the SFC chart (`NAME.sfc.xml`, `NAME.sfc.beremiz/`) has
/// timers and the program is for OpenPLC (`--target iec` or `openplc`,
/// `--board`): the chart's timers are TON blocks among the resource's
/// globals, which the matiec of OpenPLC Runtime v3 cannot build (its upload
/// fails: `macro "__SET_VAR" requires 4 arguments`), while the ST program
/// and the Ladder body keep their timers in the program and pass.
pub(super) fn openplc_chart(
    input: &crate::emit::EmitInput,
    settings: &crate::settings::Settings,
) -> Option<crate::diag::Diagnostic> {
    use crate::emit::OutputKind;
    let charts: Vec<String> = [
        (OutputKind::Sfc, ".sfc.xml"),
        (OutputKind::BeremizSfc, ".sfc.beremiz/"),
    ]
    .into_iter()
    .filter(|(kind, _)| settings.formats.contains(kind))
    .map(|(_, ending)| format!("{}{ending}", input.name))
    .collect();
    let timers = input.program.timers.len();
    if charts.is_empty() || timers == 0 || settings.target != crate::address::Target::Iec {
        return None;
    }
    let for_board = settings
        .board
        .map(|b| format!(" ({})", b.label))
        .unwrap_or_default();
    Some(crate::diag::Diagnostic {
        severity: crate::diag::Severity::Warning,
        code: crate::diag::Code::W011RefusedByTool,
        location: crate::diag::Location {
            file: input.table.file.clone(),
            sheet: None,
            cell: None,
        },
        message: format!(
            "{}: OpenPLC Runtime v3{for_board} will not take this SFC chart: its upload refuses the chart's {timers} timer(s) (dwell, watchdog, run-on), which a chart declares as global TON blocks (\"macro __SET_VAR requires 4 arguments\"); for OpenPLC, upload the ST program ({}.st) or the Ladder body ({}.ld.beremiz/, --formats beremiz-ld), which it accepts",
            charts.join(" and "),
            input.name,
            input.name,
        ),
    })
}

/// What the outputs asked for lose of the table as written (W008: a comment
/// cut, a code page without a character, a preset rounded), and, as the
/// error, a chart one of them cannot draw. `convert` and `check` say the same.
pub(super) fn of(
    input: &EmitInput,
    settings: &Settings,
) -> Result<Vec<Diagnostic>, Vec<Diagnostic>> {
    let refused = retry_in_chart(input, settings);
    if !refused.is_empty() {
        return Err(refused);
    }
    let mut warnings = Vec::new();
    if settings.formats.contains(&OutputKind::SymbolTable) {
        warnings.extend(shortened_sdf_comments(input));
    }
    warnings.extend(openplc_chart(input, settings));
    warnings.extend(code_page_losses(input, settings));
    warnings.extend(rounded_presets(input, settings));
    Ok(warnings)
}

/// [`of`] the outputs `settings` asks for, named `name`, before any
/// run: what `check` says of them.
pub fn output_findings(
    name: &str,
    table: &StepTable,
    settings: &Settings,
    program: &StepProgram,
    allocation: &Allocation,
) -> Result<Vec<Diagnostic>, Vec<Diagnostic>> {
    let festo = super::festo_allocation(program, allocation);
    let symbols = crate::symbols::SymbolTable::build(program, table, &settings.naming);
    let input = EmitInput {
        name,
        table,
        allocation,
        festo: &festo,
        program,
        symbols: &symbols,
        simulation: None,
        faults: None,
        mitigations: None,
        io_trace: None,
        settings: &[],
        templates: &settings.templates,
        scan_ms: settings.simulation.scan_ms,
        diagram: settings.diagram,
        pictures: None,
    };
    of(&input, settings)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn paper_symbols() -> SymbolTable {
        let table = crate::program::tests::paper_table();
        let program = crate::program::build(
            &table,
            &crate::program::ProgramOptions::default(),
            &crate::actuator::Valves::default(),
            &crate::stroke::Strokes::default(),
        );
        SymbolTable::build(&program, &table, &Default::default())
    }

    #[test]
    fn stages_read_in_order() {
        let symbols = paper_symbols();
        let text = |stages: &[Vec<u32>]| stages_text(stages, &symbols);
        assert_eq!(text(&[vec![2, 3, 4], vec![1]]), "C2, C3 & C4, then C1");
        assert_eq!(text(&[vec![1]]), "C1");
        assert_eq!(text(&[vec![2], vec![1], vec![3]]), "C2, then C1, then C3");
    }
}
