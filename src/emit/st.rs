//! IEC 61131-3 Structured Text (`NAME.st`) that matiec — the compiler behind
//! OpenPLC and Beremiz — accepts as it is: located variables in their own VAR
//! block, `(* *)` comments only, and a CONFIGURATION with a cyclic task.
//!
//! The same model (variables and the rendered ST body) feeds the PLCopen XML,
//! the CODESYS XML and the CODESYS global variable list.

use minijinja::Value;
use minijinja::value::Serde;
use serde::Serialize;

use super::{EmitInput, templates};
use crate::address::Assigned;
use crate::program::{Action, INITIAL_STEP, Literal, condition_text};
use crate::program::{Area, Signal};
use crate::symbols::{
    CONFIGURATION_NAME, INSTANCE_NAME, PROGRAM_NAME, RESOURCE_NAME, SymbolTable, TASK_NAME,
};

#[derive(Serialize)]
struct Var {
    ident: String,
    iec_address: String,
    address: String,
    comment: String,
}

#[derive(Serialize)]
pub(super) struct Internal {
    pub(super) ident: String,
    pub(super) data_type: &'static str,
    /// A function block type (`TON`) rather than an elementary one.
    pub(super) derived: bool,
    /// Initial value, if the declaration has one.
    pub(super) initial: Option<String>,
    pub(super) comment: String,
}

/// A timer: a TON instance driven by a run flag and a preset variable, so
/// that "start" and "running" mean what the step program says.
#[derive(Serialize, Clone)]
pub(super) struct Timer {
    pub(super) ident: String,
    pub(super) run: String,
    pub(super) preset: String,
}

#[derive(Serialize, Clone)]
pub(super) struct Statement {
    code: String,
    comment: String,
}

/// One branch of the `CASE`: the SFC step the program is in, and the
/// transitions that leave it with the actions of the step each enters.
#[derive(Serialize)]
pub(super) struct StepContext {
    /// The step the program is in (`active_step`): 0 at rest, else the
    /// table step whose moves run.
    active: usize,
    active_title: String,
    /// The step entered and what it does, for the transition's comment.
    entry: String,
    condition: String,
    actions: Vec<Statement>,
    /// The step entered: the next table step, 0 after the last.
    enters: usize,
    /// Tested first: `IF jump THEN … ELSIF step THEN …`.
    jumps: Vec<JumpContext>,
}

/// A jump of a step (`J:7 if I:reject`): its target is entered in place of
/// the next step.
#[derive(Serialize)]
pub(super) struct JumpContext {
    comment: String,
    condition: String,
    actions: Vec<Statement>,
    enters: usize,
}

#[derive(Serialize, Clone)]
pub(super) struct RungContext {
    comment: String,
    condition: String,
    actions: Vec<Statement>,
}

#[derive(Serialize)]
struct BodyContext {
    step_var: String,
    timers: Vec<Timer>,
    steps: Vec<StepContext>,
    rungs: Vec<RungContext>,
}

/// Everything the IEC templates (`.st`, PLCopen, CODESYS, GVL) lay out.
#[derive(Serialize)]
pub(super) struct Context {
    title: String,
    version: &'static str,
    source: String,
    target: String,
    timestamp: &'static str,
    program_name: &'static str,
    /// What `active_step` means, for the header.
    step_note: Vec<String>,
    /// Inputs and outputs, with addresses.
    located: Vec<Var>,
    /// Internal variables: step counter, memories, timer flags and instances.
    internals: Vec<Internal>,
    /// The program body, rendered from `program_body.st.j2`.
    body: String,
    configuration_name: &'static str,
    resource_name: &'static str,
    task_name: &'static str,
    instance_name: &'static str,
    task_interval: String,
    /// The task interval as CODESYS writes it (`PT0.01S`).
    task_interval_xsd: String,
    /// CODESYS object ids of the program and the global variable list:
    /// stable for a name, so that a re-import replaces the same objects.
    program_object_id: String,
    gvl_object_id: String,
}

/// A GUID derived from `text` (FNV-1a, 128 bits, formatted as a version 4
/// UUID): the same text gives the same id on every run.
pub fn object_id(text: &str) -> String {
    let mut hash: u128 = 0x6c62_272e_07bb_0142_62b8_2175_6295_c58d;
    for byte in text.bytes() {
        hash ^= byte as u128;
        hash = hash.wrapping_mul(0x0000_0000_0100_0000_0000_0000_0000_013b);
    }
    let b = hash.to_be_bytes();
    let hex = |range: std::ops::Range<usize>| {
        b[range]
            .iter()
            .map(|x| format!("{x:02x}"))
            .collect::<String>()
    };
    let version = format!("4{}", &hex(6..8)[1..]);
    let variant = format!("{:x}{}", 8 | (b[8] >> 4 & 3), &hex(8..10)[1..]);
    format!(
        "{}-{}-{version}-{variant}-{}",
        hex(0..4),
        hex(4..6),
        hex(10..16)
    )
}

/// `PT0.01S` for 10 ms: an XML Schema duration.
fn xsd_duration(ms: u32) -> String {
    let seconds = format!("{}.{:03}", ms / 1000, ms % 1000);
    let seconds = seconds.trim_end_matches('0').trim_end_matches('.');
    format!("PT{seconds}S")
}

/// The fixed creation time of generated files: outputs are byte-stable.
pub const TIMESTAMP: &str = "2020-01-01T00:00:00";

/// Text made safe inside `(* … *)`: ST comments do not nest.
pub(super) fn comment_text(text: &str) -> String {
    super::one_line(text)
        .replace("(*", "( *")
        .replace("*)", "* )")
}

/// The run flag and preset variable of a timer (`wd_run`, `wd_pt` for the
/// watchdog), as the symbol table names them.
fn timer_run(symbols: &SymbolTable, timer: Signal) -> String {
    symbols
        .timer(timer)
        .map(|t| t.iec_run.ident.clone())
        .unwrap_or_default()
}

fn timer_preset(symbols: &SymbolTable, timer: Signal) -> String {
    symbols
        .timer(timer)
        .map(|t| t.iec_preset.ident.clone())
        .unwrap_or_default()
}

/// How a language writes the program's names: IEC ST bare; TIA Portal's
/// SCL the tag table's tags (inputs, outputs) in double quotes and the
/// block's own variables with `#`. Everything else ST and SCL share.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Spelling {
    Iec,
    Scl,
}

impl Spelling {
    /// A variable of the program or block itself.
    pub(super) fn own(self, ident: &str) -> String {
        match self {
            Spelling::Iec => ident.to_string(),
            Spelling::Scl => format!("#{ident}"),
        }
    }

    /// A signal: an input or output is a tag, anything else the block's own;
    /// a timer reads as its run flag.
    pub(super) fn signal(self, symbols: &SymbolTable, signal: Signal) -> String {
        match (self, signal.area()) {
            (_, Area::Timer) => self.own(&timer_run(symbols, signal)),
            (Spelling::Scl, Area::Input | Area::Output) => {
                format!("\"{}\"", symbols.ident(signal))
            }
            _ => self.own(&symbols.ident(signal)),
        }
    }
}

/// A condition as an ST expression; one with no literal always holds
/// (`IF THEN` with nothing between is a syntax error in matiec).
pub(super) fn condition(symbols: &SymbolTable, literals: &[Literal], sp: Spelling) -> String {
    if literals.is_empty() {
        return "TRUE".to_string();
    }
    condition_text(literals, |s| sp.signal(symbols, s), "AND", "NOT ")
}

fn statement(symbols: &SymbolTable, action: Action, sp: Spelling) -> String {
    match action {
        Action::Reset(Signal::Sequence) => {
            format!("{} := {INITIAL_STEP};", sp.own(&symbols.step_counter.ident))
        }
        // Called with IN off then on, the TON restarts now: its time runs
        // from this scan, as the step program's timer does (a TON first
        // called with IN on in the next scan would end one scan late).
        Action::StartTimer(timer, ms) => format!(
            "{pt} := T#{ms}ms; {run} := TRUE; {t}(IN := FALSE, PT := {pt}); {t}(IN := TRUE, PT := {pt});",
            pt = sp.own(&timer_preset(symbols, timer)),
            run = sp.own(&timer_run(symbols, timer)),
            t = sp.own(&symbols.ident(timer))
        ),
        Action::Set(s) | Action::Reset(s) => {
            let value = if action.value() { "TRUE" } else { "FALSE" };
            format!("{} := {value};", sp.signal(symbols, s))
        }
    }
}

pub(super) fn statements(
    symbols: &SymbolTable,
    actions: &[Action],
    moves: &[crate::table::Move],
    sp: Spelling,
) -> Vec<Statement> {
    actions
        .iter()
        .map(|a| Statement {
            code: statement(symbols, *a, sp),
            comment: comment_text(&symbols.action_comment(*a, moves)),
        })
        .collect()
}

fn located(a: &Assigned, input: &EmitInput) -> Var {
    Var {
        ident: input.symbols.ident(a.signal),
        iec_address: a.address.iec(),
        address: a.address.display(input.allocation.mnemonic),
        comment: comment_text(&input.symbols.comment(a.signal)),
    }
}

/// Builds the context shared by every IEC output.
fn context(input: &EmitInput, scan_millis: u32) -> Result<Context, templates::TemplateError> {
    Ok(parts(input, scan_millis)?.0)
}

/// What the ST body runs besides the sequence, for the bodies that keep the
/// sequence elsewhere (the SFC chart): the timers, called before it, and
/// the rungs, run after it.
#[derive(Serialize, Clone)]
pub(super) struct Around {
    pub(super) timers: Vec<Timer>,
    pub(super) rungs: Vec<RungContext>,
}

/// The `CASE` branches and the rungs after it, spelled for ST or SCL.
pub(super) fn sequence(input: &EmitInput, sp: Spelling) -> (Vec<StepContext>, Vec<RungContext>) {
    let program = input.program;
    let symbols = input.symbols;
    let lowered = super::lower::lower(program, symbols);
    let steps = lowered
        .steps
        .iter()
        .map(|s| {
            let own = s.own();
            StepContext {
                jumps: s
                    .jumps()
                    .iter()
                    .map(|j| JumpContext {
                        comment: comment_text(j.comment),
                        condition: condition(symbols, j.condition, sp),
                        actions: statements(symbols, j.actions, j.moves, sp),
                        enters: j.enters,
                    })
                    .collect(),
                active: s.active,
                active_title: comment_text(&s.active_title),
                entry: comment_text(own.comment),
                condition: condition(symbols, own.condition, sp),
                actions: statements(symbols, own.actions, own.moves, sp),
                enters: own.enters,
            }
        })
        .collect();
    let rungs: Vec<RungContext> = program
        .rungs
        .iter()
        .map(|r| RungContext {
            // The program's own rungs name signals as the symbol table does.
            comment: comment_text(&symbols.explain(&r.comment)),
            condition: condition(symbols, &r.condition, sp),
            actions: statements(symbols, &r.actions, &[], sp),
        })
        .collect();
    (steps, rungs)
}

/// The program's own variables (step counter, memories, timer flags,
/// presets and instances) and its timers, named as ST and SCL name them.
pub(super) fn internals(input: &EmitInput) -> (Vec<Internal>, Vec<Timer>) {
    let alloc = input.allocation;
    let program = input.program;
    let symbols = input.symbols;
    let initially_on = |s: Signal| program.init.contains(&Action::Set(s));
    let mut internals = vec![Internal {
        ident: symbols.step_counter.ident.clone(),
        data_type: "INT",
        derived: false,
        initial: Some(INITIAL_STEP.to_string()),
        comment: comment_text(&symbols.step_counter.comment),
    }];
    internals.extend(alloc.memories.iter().map(|m| {
        Internal {
            ident: symbols.ident(m.signal),
            data_type: "BOOL",
            derived: false,
            initial: Some(
                if initially_on(m.signal) {
                    "TRUE"
                } else {
                    "FALSE"
                }
                .to_string(),
            ),
            comment: comment_text(&symbols.comment(m.signal)),
        }
    }));
    let mut timers = Vec::new();
    for &timer in &program.timers {
        let Some(names) = symbols.timer(timer) else {
            continue;
        };
        internals.push(Internal {
            ident: names.iec_run.ident.clone(),
            data_type: "BOOL",
            derived: false,
            initial: Some("FALSE".to_string()),
            comment: comment_text(&names.iec_run.comment),
        });
        internals.push(Internal {
            ident: names.iec_preset.ident.clone(),
            data_type: "TIME",
            derived: false,
            initial: Some("T#0ms".to_string()),
            comment: comment_text(&names.iec_preset.comment),
        });
        timers.push(Timer {
            ident: symbols.ident(timer),
            run: names.iec_run.ident.clone(),
            preset: names.iec_preset.ident.clone(),
        });
    }
    for timer in &timers {
        internals.push(Internal {
            ident: timer.ident.clone(),
            data_type: "TON",
            derived: true,
            initial: None,
            comment: String::new(),
        });
    }
    (internals, timers)
}

/// The context shared by every IEC output, and the timers and rungs of its body.
pub(super) fn parts(
    input: &EmitInput,
    scan_millis: u32,
) -> Result<(Context, Around), templates::TemplateError> {
    let alloc = input.allocation;
    let symbols = input.symbols;
    let (steps, rungs) = sequence(input, Spelling::Iec);
    let (internals, timers) = internals(input);
    let around = Around {
        timers: timers.clone(),
        rungs: rungs.clone(),
    };
    let body = input.templates.render(
        "program_body.st.j2",
        Value::from(Serde(&BodyContext {
            step_var: symbols.step_counter.ident.clone(),
            timers,
            steps,
            rungs,
        })),
    )?;
    Ok((
        Context {
            title: comment_text(input.name),
            version: env!("CARGO_PKG_VERSION"),
            source: comment_text(&input.source()),
            target: alloc.target.name().to_string(),
            timestamp: TIMESTAMP,
            program_name: PROGRAM_NAME,
            step_note: super::step_numbering_note(&symbols.step_counter.ident)
                .iter()
                .map(|l| comment_text(l))
                .collect(),
            located: alloc
                .inputs
                .iter()
                .chain(&alloc.outputs)
                .map(|a| located(a, input))
                .collect(),
            internals,
            body,
            // OpenPLC's upload moves exactly Config0.c and Res0.c, the files
            // matiec names after the configuration and its resource.
            configuration_name: CONFIGURATION_NAME,
            resource_name: RESOURCE_NAME,
            task_name: TASK_NAME,
            instance_name: INSTANCE_NAME,
            task_interval: format!("T#{scan_millis}ms"),
            task_interval_xsd: xsd_duration(scan_millis),
            program_object_id: object_id(&format!("{}/{PROGRAM_NAME}", input.name)),
            gvl_object_id: object_id(&format!("{}/GVL_IO", input.name)),
        },
        around,
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn object_ids_are_stable_guids() {
        let id = object_id("paper_example/steptable_main");
        assert_eq!(id, object_id("paper_example/steptable_main"));
        assert_ne!(id, object_id("paper_example/GVL_IO"));
        let parts: Vec<&str> = id.split('-').collect();
        assert_eq!(
            parts.iter().map(|p| p.len()).collect::<Vec<_>>(),
            [8, 4, 4, 4, 12]
        );
        assert!(parts[2].starts_with('4'));
        assert!(matches!(
            parts[3].chars().next(),
            Some('8' | '9' | 'a' | 'b')
        ));
        assert!(id.chars().all(|c| c == '-' || c.is_ascii_hexdigit()));
    }

    #[test]
    fn intervals_as_xml_durations() {
        assert_eq!(xsd_duration(10), "PT0.01S");
        assert_eq!(xsd_duration(5), "PT0.005S");
        assert_eq!(xsd_duration(1000), "PT1S");
        assert_eq!(xsd_duration(1250), "PT1.25S");
    }
}

/// Which IEC file to render.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum IecFile {
    /// `NAME.st` (program and configuration).
    StructuredText,
    /// `NAME.plcopen.xml`, PLCopen TC6 XML v2.01.
    PlcOpen,
    /// `NAME.codesys.xml`, PLCopen XML as CODESYS imports it.
    Codesys,
    /// `NAME.gvl.txt`, a CODESYS global variable list.
    GlobalVariables,
    /// `NAME.exp`, a CoDeSys V2.3 export (global variable list and program).
    CodesysV2,
    /// `NAME.beremiz/beremiz.xml`, the project file beside `plc.xml`.
    BeremizProject,
}

/// The data every IEC template lays out, with the program body rendered once:
/// build it once per conversion and hand it to [`render`] for each file.
pub fn model(input: &EmitInput, scan_millis: u32) -> Result<Value, templates::TemplateError> {
    Ok(Value::from(Serde(&context(input, scan_millis)?)))
}

/// Renders one IEC file from the [`model`].
pub fn render(
    input: &EmitInput,
    model: &Value,
    file: IecFile,
) -> Result<String, templates::TemplateError> {
    let template = match file {
        IecFile::StructuredText => "program.st.j2",
        IecFile::PlcOpen => "plcopen.xml.j2",
        IecFile::Codesys => "codesys.xml.j2",
        IecFile::GlobalVariables => "gvl.txt.j2",
        IecFile::CodesysV2 => "program.exp.j2",
        IecFile::BeremizProject => "beremiz.xml.j2",
    };
    input.templates.render(template, model.clone())
}
