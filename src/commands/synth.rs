//! `synth`: minimal logic equations for a single-branch sequence, given as
//! a step table or as text (`--sequence "A1 A0 B1 B0"`), written as the
//! report, its JSON, the two programs and a workbook into `DIR/NAME/`.
//!
//! A table's outputs are named after the table (`line.csv` → `line/`), as
//! convert names them. A sequence's are named after the sequence itself
//! ([`sequence_name`]: `A1 A0 B1 B0` → `A1A0B1B0/`), so that synthesising
//! another sequence never replaces the first one's files; and should a
//! folder of that name hold another sequence's synthesis all the same (a
//! name cut short, or a table named so), the run is refused with E040.

use std::path::{Path, PathBuf};

use super::CommandError;
use crate::diag::{Code, Diagnostic, Location, Severity};
use crate::emit::templates::Templates;
use crate::emit::{CommandFile, OutputFile};
use crate::provenance::{self, MadeBy};
use crate::settings::Settings;
use crate::synth::{self, SynthError, output as synth_out, sequence::Sequence};
use crate::write::{self, WriteError};

/// What to synthesise.
#[derive(Debug, Clone, Copy)]
pub enum SynthSource<'a> {
    /// A single-branch step table, read from this sheet or the default one.
    Table {
        path: &'a Path,
        sheet: Option<&'a str>,
    },
    /// A sequence as text: `A1 A0 B1 B0`, `A+ A- B+ B-`, `C1+1 C1-0`.
    Sequence(&'a str),
}

/// What a synthesis found and wrote.
#[derive(Debug)]
pub struct SynthRun {
    pub warnings: Vec<Diagnostic>,
    /// The report (`NAME.synth.txt`), to show.
    pub report: String,
    /// The folder the files go into.
    pub folder: PathBuf,
    /// The paths written, or why they could not be (the synthesis stands:
    /// the caller still shows the report).
    pub written: Result<Vec<PathBuf>, WriteError>,
}

/// Longest sequence name before it is cut and given a hash of the whole
/// sequence: within convert's longest base name.
const MAX_SEQUENCE_NAME: usize = 180;

/// The folder and base name of a sequence's outputs: its actions as the
/// report writes them, without spaces (`A1A0B1B0`; `C1+1C1-0` for a table's
/// moves), letters, digits, `+` and `-` only, which every file system takes.
/// `A+ A- B+ B-` is the same sequence as `A1 A0 B1 B0` and gets its name.
/// A name longer than 180 bytes is cut there and ends in `-` and a hash of
/// the whole sequence (FNV-1a, 16 hex digits).
pub fn sequence_name(sequence: &Sequence) -> String {
    let name: String = sequence
        .actions
        .iter()
        .map(|a| sequence.token(*a))
        .collect();
    if name.len() <= MAX_SEQUENCE_NAME {
        return name;
    }
    let hash = crate::manifest::Stamp::of(sequence.text().as_bytes()).hash;
    let mut cut = MAX_SEQUENCE_NAME;
    while !name.is_char_boundary(cut) {
        cut -= 1;
    }
    format!("{}-{hash:016x}", &name[..cut])
}

/// Synthesises `source` with `options`, proves the controller, and writes
/// its files into `out/NAME/` with the templates `templates`. `invocation`
/// is the command line the files record; `progress(done, total)` is told
/// how the comparison of equations advances.
pub fn run(
    source: SynthSource,
    options: synth::Options,
    templates: &Templates,
    out: &Path,
    invocation: Option<&str>,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<SynthRun, CommandError> {
    let (sequence, name, inputs, warnings, file) = read(source)?;
    let refused = |code: Code, message: String| {
        CommandError::Input(vec![whole_file(&file, code, message)]).after(&warnings)
    };
    // The one name check, as for a table's signals: a name whose signals
    // the programs cannot declare (`R`: `r` is an IL operator) is E015.
    let problems = sequence.name_problems();
    if !problems.is_empty() {
        let problems = problems
            .into_iter()
            .map(|why| whole_file(&file, Code::E015BadName, why));
        return Err(CommandError::Input(
            warnings.iter().cloned().chain(problems).collect(),
        ));
    }
    let seed = options.ga.seed;
    let synthesis = synth::synthesize_observed(&sequence, options, progress).map_err(|err| {
        let code = match err {
            SynthError::Unsuitable(_) => Code::E034NotSynthesisable,
            SynthError::NotFound(_) | SynthError::OutOfTime(_) => Code::E033OverBudget,
        };
        refused(code, err.to_string())
    })?;
    let verification = synth::verify::verify(&synthesis, 2);
    // A program that fails its proof is not written.
    if !verification.passed {
        return Err(CommandError::Internal(format!(
            "the synthesised controller fails its simulation ({}); please report this sequence",
            verification.problem.as_deref().unwrap_or_default()
        )));
    }
    if let Err(why) = &verification.modes {
        return Err(CommandError::Internal(format!(
            "the synthesised program fails its mode proof ({why}); please report this sequence"
        )));
    }
    let report = synth_out::report_text(&synthesis, &verification);
    let workbook = synth_out::workbook(&synthesis, &verification)
        .map_err(|e| CommandError::Internal(format!("workbook: {e}")))?;
    let st = crate::emit::equations::structured_text(templates, &synthesis, &name)
        .map_err(CommandError::Template)?;
    let il = crate::emit::equations::instruction_list(templates, &synthesis, &name)
        .map_err(CommandError::Template)?;
    let files = [
        (CommandFile::SynthReport, report.clone().into_bytes()),
        (
            CommandFile::SynthJson,
            synth_out::report_json(&synthesis, &verification, seed).into_bytes(),
        ),
        (CommandFile::EquationsSt, st.into_bytes()),
        (CommandFile::EquationsIl, il.into_bytes()),
        (CommandFile::SynthWorkbook, workbook),
    ];
    let made_from = match source {
        SynthSource::Sequence(_) => format!("the sequence {}", sequence.text()),
        SynthSource::Table { path, .. } => path
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_else(|| file.clone()),
    };
    let made_by = MadeBy::new(
        invocation,
        &made_from,
        "the command line, defaults for the rest",
    );
    let files = files
        .into_iter()
        .map(|(kind, bytes)| OutputFile {
            name: kind.file_name(&name),
            bytes,
        })
        .collect();
    let files = provenance::stamp_all(files, &made_by).map_err(CommandError::Internal)?;
    let folder = out.join(&name);
    let written = match source {
        SynthSource::Sequence(_) => another_sequence(&folder, &name, &sequence),
        SynthSource::Table { .. } => None,
    };
    let written = match written {
        Some(taken) => Err(WriteError::Taken(vec![taken])),
        None => write::write_outputs(
            &folder,
            &files,
            &write::Inputs::new(&inputs),
            write::Durability::Rename,
            Some(made_by.text()),
        ),
    };
    Ok(SynthRun {
        warnings,
        report,
        folder,
        written,
    })
}

/// The sequence, its outputs' name, the inputs never to overwrite, the
/// table's warnings and the name problems are said about.
type Read = (Sequence, String, Vec<PathBuf>, Vec<Diagnostic>, String);

fn read(source: SynthSource) -> Result<Read, CommandError> {
    match source {
        SynthSource::Sequence(text) => {
            let file = "--sequence".to_string();
            let sequence = synth::sequence::parse(text).map_err(|why| {
                CommandError::Input(vec![whole_file(&file, Code::E034NotSynthesisable, why)])
            })?;
            let name = sequence_name(&sequence);
            Ok((sequence, name, Vec::new(), Vec::new(), file))
        }
        SynthSource::Table { path, sheet } => {
            let mut settings = Settings::new();
            settings.sheet = sheet.map(str::to_string);
            let mut checked =
                crate::convert::check_path(path, &settings).map_err(CommandError::Input)?;
            let (refused, unused) =
                sheet_settings_synth_drops(&checked.settings, &checked.table.file);
            // convert's advice about a cell synth reports itself (a home
            // order without reset: "add reset to the modes") does not apply.
            let said = |d: &Diagnostic| {
                d.code == Code::W006NoEffect
                    && unused
                        .iter()
                        .chain(&refused)
                        .any(|u| u.location == d.location)
            };
            checked.warnings.retain(|d| !said(d));
            checked.warnings.extend(unused);
            if !refused.is_empty() {
                return Err(CommandError::Input(refused).after(&checked.warnings));
            }
            let sequence = synth::from_table(&checked.table)
                .map_err(|d| CommandError::Input(vec![d]).after(&checked.warnings))?;
            Ok((
                sequence,
                crate::convert::output_name(path),
                vec![path.to_path_buf()],
                checked.warnings,
                crate::read::display_name(path),
            ))
        }
    }
}

/// What the workbook's SETTINGS and ADDRESSES sheets say that synthesis
/// does not build: its equations have no operating modes, safety checks,
/// interlocks or halt rows of the engineer's, and use their own addresses
/// and timing. A row that keeps people or the machine safe (modes, safety,
/// the interlock, the permissive, the halt and stop rows) is refused (E034
/// at its cell: a "proven" controller without it would mislead); any other
/// cell is W006 at the cell. Nothing is dropped in silence.
fn sheet_settings_synth_drops(
    settings: &Settings,
    file: &str,
) -> (Vec<Diagnostic>, Vec<Diagnostic>) {
    let (mut refused, mut unused) = (Vec::new(), Vec::new());
    let convert = "convert the table for a program that has it";
    for (label, at) in &settings.cells {
        let safety = matches!(*label, "modes" | "safety");
        let diagnostic = |severity, code, why: &str| Diagnostic {
            severity,
            code,
            location: at.clone(),
            message: format!("{label}: synth {why}"),
        };
        if safety {
            refused.push(diagnostic(
                Severity::Error,
                Code::E034NotSynthesisable,
                &format!("does not build this into its equations; {convert}, or remove the row to synthesise"),
            ));
        } else {
            unused.push(diagnostic(
                Severity::Warning,
                Code::W006NoEffect,
                "does not use this setting (its equations take their own addresses and timing); it was not read",
            ));
        }
    }
    for (row, list) in &settings.named {
        refused.push(Diagnostic {
            severity: Severity::Error,
            code: Code::E034NotSynthesisable,
            location: list.at.clone(),
            message: format!(
                "{}: synth does not build this into its equations; {convert}, or remove the row to synthesise",
                row.label()
            ),
        });
    }
    // The equations name signals by the paper's symbols (c1_home, yc1_p):
    // the engineer's names of the actuators are in none of them.
    for (n, name) in &settings.naming.actuators {
        unused.push(Diagnostic {
            severity: Severity::Warning,
            code: Code::W006NoEffect,
            location: name.at.clone(),
            message: format!(
                "C{n} ({}): synth does not use the actuators' names (its equations name signals by the paper's symbols); it was not read",
                name.text
            ),
        });
    }
    for pin in &settings.pins {
        unused.push(Diagnostic {
            severity: Severity::Warning,
            code: Code::W006NoEffect,
            location: pin.signal_at.clone(),
            message: format!(
                "{} {}: synth does not use pinned addresses (its equations name signals, not addresses); it was not read",
                pin.signal, pin.address
            ),
        });
    }
    let sim = &settings.simulation;
    // The equations pulse a coil and count on the valve to keep the
    // position: a spring return, a 5/3 centre, a drive or a gripper would
    // not do what the proof shows.
    for (n, kind) in &sim.machine.valves.per_actuator {
        let keeps = kind.coils() == crate::actuator::CoilSet::Double && !kind.has_centre();
        if !keeps {
            refused.push(Diagnostic {
                severity: Severity::Error,
                code: Code::E034NotSynthesisable,
                location: Location {
                    file: file.to_string(),
                    sheet: Some("SETTINGS".to_string()),
                    cell: None,
                },
                message: format!(
                    "C{n} is a {} on valve type {kind}: synth's equations drive two-position actuators whose valve keeps its position with no coil on (52bi, swivel) only; {convert}",
                    kind.noun()
                ),
            });
        }
    }
    if !(sim.machine.strokes.per_actuator.is_empty()
        && sim.machine.valves.per_actuator.is_empty()
        && sim.machine.loads.is_empty())
    {
        unused.push(Diagnostic {
            severity: Severity::Warning,
            code: Code::W006NoEffect,
            location: Location {
                file: file.to_string(),
                sheet: Some("SETTINGS".to_string()),
                cell: None,
            },
            message: "synth does not use the actuator table (its proof uses its own valve and stroke model); it was not read".to_string(),
        });
    }
    (refused, unused)
}

/// An error of `code` about `file` as a whole.
fn whole_file(file: &str, code: Code, message: String) -> Diagnostic {
    Diagnostic {
        severity: Severity::Error,
        code,
        location: Location {
            file: file.to_string(),
            sheet: None,
            cell: None,
        },
        message,
    }
}

/// E040 when `folder` holds the synthesis of a sequence other than
/// `sequence` (its `NAME.synth.json` says which): a run for one sequence
/// never replaces another's outputs.
fn another_sequence(folder: &Path, name: &str, sequence: &Sequence) -> Option<Diagnostic> {
    let path = folder.join(CommandFile::SynthJson.file_name(name));
    let text = std::fs::read_to_string(&path).ok()?;
    let json: serde_json::Value = serde_json::from_str(&text).ok()?;
    let theirs: Vec<&str> = json
        .get("sequence")?
        .as_array()?
        .iter()
        .filter_map(|t| t.as_str())
        .collect();
    let ours: Vec<String> = sequence
        .actions
        .iter()
        .map(|a| sequence.token(*a))
        .collect();
    if theirs == ours {
        return None;
    }
    Some(whole_file(
        &crate::read::display_name(&path),
        Code::E040OutputTaken,
        format!(
            "holds the synthesis of another sequence ({}), and this one ({}) would replace it; nothing written: move that folder, or choose another output folder with -o",
            theirs.join(" "),
            ours.join(" ")
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_sequence_is_named_after_its_actions_and_a_long_one_is_cut_with_a_hash() {
        let name = |text: &str| sequence_name(&synth::sequence::parse(text).unwrap());
        assert_eq!(name("A1 A0 B1 B0"), "A1A0B1B0");
        assert_eq!(name("a+ a- b+, b-"), "A1A0B1B0");
        assert_eq!(name("C1+1 C1-0 C2+1 C2-0"), "C1+1C1-0C2+1C2-0");
        let long = "A1 A0 ".repeat(60);
        let longer = format!("{long}B1 B0");
        let (a, b) = (name(&long), name(&longer));
        assert!(a.len() <= crate::convert::MAX_NAME_BYTES, "{a}");
        assert_ne!(a, b, "two long sequences with one start keep apart");
        assert!(
            a.chars()
                .all(|c| c.is_ascii_alphanumeric() || "+-".contains(c)),
            "{a}"
        );
    }
}
