//! Output languages. Each emitter turns the one step program (plus the table,
//! the allocation and the symbol table) into the bytes of one file. What an
//! address or an operator is, is decided here in Rust, what a name or a
//! comment is in [`crate::symbols`]; templates in `templates/` only lay out.

pub mod awl;
pub mod codesys_body;
pub mod diagram;
pub mod equations;
pub mod faults_csv;
pub mod fst;
pub mod grafcet;
pub mod io_csv;
mod kind;
pub mod l5x;
pub mod ladder;
pub mod lower;
mod render;
pub mod report;
pub mod s5time;
pub mod scl;
pub mod sdf;
pub mod sfc;
pub mod st;
pub mod tables;
pub mod templates;
pub mod workbook;

pub use kind::{CommandFile, OutputKind};
pub use render::{EmitError, Renderer, render, render_each};

use crate::address::Allocation;
use crate::faults::FaultTable;
use crate::program::StepProgram;
use crate::simulate::SimReport;
use crate::symbols::SymbolTable;
use crate::table::StepTable;
use templates::Templates;

/// One generated file, in memory.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct OutputFile {
    /// File name without folder, e.g. `paper.st`.
    pub name: String,
    pub bytes: Vec<u8>,
}

/// Everything an emitter may read.
#[derive(Debug, Clone, Copy)]
pub struct EmitInput<'a> {
    /// Base name of the outputs (the input file's stem).
    pub name: &'a str,
    pub table: &'a StepTable,
    pub allocation: &'a Allocation,
    /// The same signals on Festo operands, which the FST files use whatever
    /// the target: allocated once, by the caller, not by each emitter.
    pub festo: &'a Allocation,
    pub program: &'a StepProgram,
    /// Every name the outputs give a signal or a part of their own: the
    /// emitters read names and comments only from here.
    pub symbols: &'a SymbolTable,
    /// The simulation of the program, for the SIMULATION sheet.
    pub simulation: Option<&'a SimReport>,
    /// The fault table, for the FAULTS sheet.
    pub faults: Option<&'a FaultTable>,
    /// The verified mitigation of each hazard of `faults`, in its cases'
    /// order (`None` for a case that is no hazard), for the report.
    pub mitigations: Option<&'a [Option<crate::faults::mitigation::Mitigation>]>,
    /// Every scan of the simulation's inputs, outputs and step, for the
    /// report's timeline (recorded only when the report is written).
    pub io_trace: Option<&'a crate::simulate::io::IoTrace>,
    /// The settings in force, as `(setting, value)` rows for the report.
    pub settings: &'a [(String, String)],
    /// The templates text outputs are laid out by.
    pub templates: &'a Templates,
    /// The PLC scan time, which is also the generated task's cycle.
    pub scan_ms: u32,
    /// The horizontal axis of the diagram.
    pub diagram: diagram::DiagramKind,
    /// The pictures drawn so far for this conversion, when the outputs
    /// share them: the report shows the GRAFCET and the diagrams that
    /// `NAME.grafcet.svg` and `NAME.diagram.svg` are.
    pub pictures: Option<&'a Pictures>,
}

/// The pictures two outputs show, each drawn once per conversion by
/// whichever output needs it first (the outputs render side by side):
/// the GRAFCET and the displacement diagram along either axis; and the
/// report's page up to its fault table, drawn beside the fault analysis
/// so that the report waits for the hazards' mitigations alone.
#[derive(Debug, Default)]
pub struct Pictures {
    grafcet: std::sync::OnceLock<String>,
    step: std::sync::OnceLock<String>,
    time: std::sync::OnceLock<String>,
    report_head: std::sync::OnceLock<Result<String, String>>,
}

impl EmitInput<'_> {
    /// The GRAFCET as SVG ([`grafcet::render_svg`]).
    pub fn grafcet_svg(&self) -> std::borrow::Cow<'_, str> {
        let draw = || grafcet::render_svg(self);
        match self.pictures {
            Some(p) => p.grafcet.get_or_init(draw).as_str().into(),
            None => draw().into(),
        }
    }

    /// The report's page up to its fault table ([`report::head`]).
    pub fn report_head(&self) -> Result<std::borrow::Cow<'_, str>, String> {
        let draw = || report::head(self);
        match self.pictures {
            Some(p) => match p.report_head.get_or_init(draw) {
                Ok(head) => Ok(head.as_str().into()),
                Err(why) => Err(why.clone()),
            },
            None => draw().map(Into::into),
        }
    }

    /// The displacement diagram of `simulation` along `kind`'s axis as SVG
    /// ([`diagram::render_svg`]).
    pub fn diagram_svg(
        &self,
        simulation: &SimReport,
        kind: diagram::DiagramKind,
    ) -> std::borrow::Cow<'_, str> {
        let draw = || diagram::render_svg(self.name, simulation, kind, self.symbols);
        let drawn = self.pictures.map(|p| match kind {
            diagram::DiagramKind::Step => &p.step,
            diagram::DiagramKind::Time => &p.time,
        });
        match drawn {
            Some(drawn) => drawn.get_or_init(draw).as_str().into(),
            None => draw().into(),
        }
    }
}

impl EmitInput<'_> {
    /// `paper.xlsx, sheet SEQUENTIAL CONTROL DESCRIPTION` — where the table
    /// came from. Only the file name, not its folder, so that outputs do not
    /// depend on where the command was run.
    pub fn source(&self) -> String {
        let file = std::path::Path::new(&self.table.file)
            .file_name()
            .map(|n| n.to_string_lossy().to_string())
            .unwrap_or_else(|| self.table.file.clone());
        match &self.table.sheet {
            Some(sheet) => format!("{file}, sheet {sheet}"),
            None => file,
        }
    }
}

/// What the step number of a program means, for its header, in lines of
/// at most 72 characters: `what` is how the language shows it
/// (`active_step`, `the step flag on`).
pub fn step_numbering_note(what: &str) -> Vec<String> {
    let initial = crate::program::INITIAL_STEP;
    let text = format!(
        "Steps are numbered as in SFC: {what} is {initial} at rest (the initial step, waiting for START) and k while table step k's moves run. Each step waits until it is done (its moves' sensors on, its waits and dwells over), then runs the actions of the step it enters; after the last step the sequence is back in step {initial}."
    );
    let mut lines: Vec<String> = Vec::new();
    for word in text.split(' ') {
        match lines.last_mut() {
            Some(line) if line.len() + 1 + word.len() <= 72 => {
                line.push(' ');
                line.push_str(word);
            }
            _ => lines.push(word.to_string()),
        }
    }
    lines
}

/// The comment on the transition `program.steps[index]`: the step it
/// enters and what that step does (with the engineer's comment of its
/// row), or the end of the cycle.
pub fn entry_comment(
    program: &crate::program::StepProgram,
    symbols: &crate::symbols::SymbolTable,
    index: usize,
) -> String {
    let enters = program.step_entered(index);
    match (program.steps.get(index), symbols.step(index)) {
        (Some(step), Some(names)) if step.kind == crate::program::StepKind::Table => {
            format!("on to STEP {enters}: {}", names.title)
        }
        _ => format!("end of cycle: back to STEP {enters}"),
    }
}

/// The comment on a jump tested while the program waits at
/// `program.steps[index]`: the step it enters in place of the next one.
pub fn jump_comment(
    program: &crate::program::StepProgram,
    index: usize,
    jump: &crate::program::StepJump,
) -> String {
    format!(
        "{}: on to STEP {} in place of STEP {}",
        jump.title,
        program.step_entered(jump.fires),
        program.step_entered(index)
    )
}

pub use crate::symbols::shorten;

/// Text on one line: control characters (a newline in a file name) become spaces.
pub fn one_line(text: &str) -> String {
    text.chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect()
}

/// `text` in the Windows-1252 code page the Windows tools of
/// [`OutputKind::windows_ansi`] read their files in, one byte a character
/// (so fixed-width rows stay fixed); a character the code page lacks is
/// `?` (said before, by [`code_page_lacks`]).
pub fn windows_1252(text: &str) -> Vec<u8> {
    // `A` and a combining mark (a file name macOS wrote) as the one `Ä`
    // the code page has.
    let text = &*crate::cell::composed_str(text);
    let mut out = Vec::with_capacity(text.len());
    let mut buffer = [0u8; 4];
    for c in text.chars() {
        if c.is_ascii() {
            out.push(c as u8);
            continue;
        }
        let (bytes, _, lacked) = encoding_rs::WINDOWS_1252.encode(c.encode_utf8(&mut buffer));
        match (lacked, bytes.as_ref()) {
            (false, [byte]) => out.push(*byte),
            _ => out.push(b'?'),
        }
    }
    out
}

/// The characters of `text` the Windows-1252 code page lacks, each once.
pub fn code_page_lacks(text: &str) -> Vec<char> {
    let text = &*crate::cell::composed_str(text);
    let mut lacked: Vec<char> = Vec::new();
    let mut buffer = [0u8; 4];
    for c in text.chars().filter(|c| !c.is_ascii()) {
        let (_, _, missing) = encoding_rs::WINDOWS_1252.encode(c.encode_utf8(&mut buffer));
        if missing && !lacked.contains(&c) {
            lacked.push(c);
        }
    }
    lacked
}

/// Text with Windows line ends, for the lists Windows tools import (STEP 7
/// symbol tables, Studio 5000 and FST lists, CoDeSys V2.3 exports).
pub fn crlf(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + text.len() / 20);
    for line in text.split_inclusive('\n') {
        match line.strip_suffix('\n') {
            Some(body) => {
                out.push_str(body.strip_suffix('\r').unwrap_or(body));
                out.push_str("\r\n");
            }
            None => out.push_str(line),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    #[test]
    fn crlf_ends_every_line_once() {
        assert_eq!(super::crlf("a\nb\r\nc"), "a\r\nb\r\nc");
        assert_eq!(super::crlf("a\n\n"), "a\r\n\r\n");
    }

    #[test]
    fn a_long_comment_is_cut_to_the_limit_with_three_dots() {
        assert_eq!(super::shorten("clamp", 5), ("clamp".to_string(), false));
        assert_eq!(super::shorten("clamps", 5), ("cl...".to_string(), true));
        // Characters, not bytes: an umlaut is one.
        let (cut, was) = super::shorten("Überwachung der Presse", 8);
        assert_eq!((cut.as_str(), was), ("Überw...", true));
        assert_eq!(cut.chars().count(), 8);
    }
}
