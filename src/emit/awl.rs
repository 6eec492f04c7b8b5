//! STEP 7 statement list source (`NAME.awl`, organisation block OB 1) and its
//! symbol table (`NAME.sdf`). One NETWORK per transition: a step flag marks
//! the step the program is in (`step_0` at rest, `step_k` while table step
//! k's moves run, as in SFC), and a `fired` flag lets at most one step fire
//! per cycle, as the step program says. English (`A`, `AN`, `JCN`, `I`, `Q`)
//! or German (`U`, `UN`, `SPBN`, `E`, `A`) mnemonics follow `--mnemonic`.

use super::s5time::{s5_ms, s5time};
use minijinja::Value;
use minijinja::value::Serde;
use serde::Serialize;

use super::sdf::Symbol;
use super::{EmitInput, one_line, templates};
use crate::address::Mnemonic;
use crate::program::{Action, INITIAL_STEP, Literal};
use crate::program::{Area, Signal};

/// The AWL words of one mnemonic set.
struct Words {
    and: &'static str,
    and_not: &'static str,
    jump_if_not: &'static str,
    /// The on-delay timer: `SD` in English, `SE` in German (English `SE`
    /// is the extended pulse, a different timer).
    on_delay: &'static str,
    input: &'static str,
    output: &'static str,
}

fn words(mnemonic: Mnemonic) -> Words {
    match mnemonic {
        Mnemonic::En => Words {
            and: "A",
            and_not: "AN",
            jump_if_not: "JCN",
            on_delay: "SD",
            input: "I",
            output: "Q",
        },
        Mnemonic::De => Words {
            and: "U",
            and_not: "UN",
            jump_if_not: "SPBN",
            on_delay: "SE",
            input: "E",
            output: "A",
        },
    }
}

#[derive(Serialize)]
struct Line {
    label: String,
    op: String,
    operand: String,
    comment: String,
}

struct Network {
    title: String,
    lines: Vec<Line>,
}

/// The characters a network's TITLE is cut to: an assumption on the short
/// side, as no source confirms STEP 7's limit (awlsim 0.77.1 sets none, nor
/// Siemens' "Programming with STEP 7", A5E02789666-01); the whole title
/// follows as a `//` line of the network comment.
pub const NETWORK_TITLE: usize = 64;

/// A network as the template lays it out: its title cut to
/// [`NETWORK_TITLE`], and `full`, the whole title, only when it was cut.
impl Serialize for Network {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeStruct;
        let (title, cut) = super::shorten(&self.title, NETWORK_TITLE);
        let mut network = serializer.serialize_struct("Network", 3)?;
        network.serialize_field("title", &title)?;
        if cut {
            network.serialize_field("full", &self.title)?;
        }
        network.serialize_field("lines", &self.lines)?;
        network.end()
    }
}

/// The symbols whose comments `NAME.sdf` cuts to [`super::sdf::SDF_COMMENT`]
/// characters, for the warning that says so.
pub fn shortened_comments(input: &EmitInput) -> Vec<String> {
    build(input)
        .symbols
        .into_iter()
        .filter(|s| s.cut)
        .map(|s| s.symbol)
        .collect()
}

#[derive(Serialize)]
struct Context {
    title: String,
    version: &'static str,
    source: String,
    mnemonics: &'static str,
    step_flags: String,
    /// What the step flags mean, for the header.
    step_note: Vec<String>,
    networks: Vec<Network>,
    symbols: Vec<Symbol>,
}

/// Where everything lives in the CPU: I/O and the program's memories from the
/// allocation, then the AWL-only bits (step flags, `fired`, watchdog flags)
/// from the next free memory byte on.
struct Layout {
    words: Words,
    step_flags: Vec<(u32, u32)>,
    fired: (u32, u32),
    timers: Vec<TimerBits>,
}

/// An S5 on-delay timer driven the way the step program means a timer: the
/// step that starts it restarts it in that very cycle (so its time runs from
/// there, as the step program's does), it runs while `run` is set, and
/// `preset` holds its time.
struct TimerBits {
    signal: Signal,
    /// The symbols of its run flag and preset (`dw3_run`, `dw3_pt`).
    run_name: crate::symbols::Own,
    preset_name: crate::symbols::Own,
    run: (u32, u32),
    preset_word: u32,
}

/// A name for a timer part the symbol table lacks (it never does: it
/// names every timer of the program).
fn own_default(what: &str) -> crate::symbols::Own {
    crate::symbols::Own {
        ident: format!("timer_{what}"),
        comment: String::new(),
    }
}

impl Layout {
    fn new(input: &EmitInput) -> Self {
        let memory_bytes = input
            .allocation
            .memories
            .iter()
            .map(|m| m.address.byte_bit().0 + 1)
            .max()
            .unwrap_or(0);
        let mut next = memory_bytes * 8;
        let mut take = || {
            let bit = (next / 8, next % 8);
            next += 1;
            bit
        };
        let step_flags = input.program.steps.iter().map(|_| take()).collect();
        let fired = take();
        let bits: Vec<(u32, u32)> = input.program.timers.iter().map(|_| take()).collect();
        let first_word = next.div_ceil(16) * 2;
        let timers = input
            .program
            .timers
            .iter()
            .zip(bits)
            .enumerate()
            .map(|(i, (&signal, run))| TimerBits {
                signal,
                run_name: input
                    .symbols
                    .timer(signal)
                    .map(|t| t.step7_run.clone())
                    .unwrap_or_else(|| own_default("run")),
                preset_name: input
                    .symbols
                    .timer(signal)
                    .map(|t| t.step7_preset.clone())
                    .unwrap_or_else(|| own_default("pt")),
                run,
                preset_word: first_word + 2 * i as u32,
            })
            .collect();
        Layout {
            words: words(input.allocation.mnemonic),
            step_flags,
            fired,
            timers,
        }
    }

    fn timer(&self, signal: Signal) -> Option<&TimerBits> {
        self.timers.iter().find(|t| t.signal == signal)
    }

    fn m((byte, bit): (u32, u32)) -> String {
        format!("M {byte}.{bit}")
    }

    /// The operand of a signal.
    fn operand(&self, input: &EmitInput, signal: Signal) -> String {
        if let Some(timer) = self.timer(signal) {
            return Layout::m(timer.run);
        }
        match input.allocation.address_of(signal) {
            Some(address) => {
                let (byte, bit) = address.byte_bit();
                match address.area {
                    Area::Input => format!("{} {byte}.{bit}", self.words.input),
                    Area::Output => format!("{} {byte}.{bit}", self.words.output),
                    Area::Memory => format!("M {byte}.{bit}"),
                    Area::Timer => format!("T {}", address.unit),
                }
            }
            None => "?".to_string(),
        }
    }
}

/// The S5 timer of a timer signal.
fn timer_operand(input: &EmitInput, signal: Signal) -> String {
    input
        .allocation
        .timers
        .iter()
        .find(|t| t.signal == signal)
        .map(|t| format!("T {}", t.address.unit))
        .unwrap_or_else(|| "T 0".to_string())
}

/// Jump labels have at most four characters in STEP 7.
fn label(n: usize) -> String {
    const DIGITS: &[u8] = b"0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ";
    let mut n = n;
    let mut text = Vec::new();
    for _ in 0..3 {
        text.push(DIGITS[n % 36]);
        n /= 36;
    }
    text.reverse();
    format!("L{}", String::from_utf8(text).unwrap_or_default())
}

fn line(op: &str, operand: impl Into<String>, comment: impl Into<String>) -> Line {
    Line {
        label: String::new(),
        op: op.to_string(),
        operand: operand.into(),
        comment: one_line(&comment.into()),
    }
}

/// What the networks of OB 1 are built from: the layout, the lowered steps
/// and the count of jump labels handed out so far.
struct Networks<'a> {
    input: &'a EmitInput<'a>,
    layout: &'a Layout,
    lowered: &'a super::lower::Lowered<'a>,
    labels: usize,
    networks: Vec<Network>,
}

impl Networks<'_> {
    /// The flag of the step the program is in while it waits at
    /// `program.steps[k]`: `step_0` at rest, `step_3` while step 3's moves run.
    fn flag(&self, k: usize) -> String {
        self.lowered.flag(k).to_string()
    }

    fn next_label(&mut self) -> String {
        let skip = label(self.labels);
        self.labels += 1;
        skip
    }

    fn condition(&self, lines: &mut Vec<Line>, literals: &[Literal]) {
        let w = &self.layout.words;
        for l in literals {
            let op = if l.negated { w.and_not } else { w.and };
            lines.push(line(
                op,
                self.layout.operand(self.input, l.signal),
                self.input.symbols.ident(l.signal),
            ));
        }
    }

    fn actions(&self, lines: &mut Vec<Line>, list: &[Action], moves: &[crate::table::Move]) {
        let (input, layout) = (self.input, self.layout);
        let w = &layout.words;
        for a in list {
            let comment = input.symbols.action_comment(*a, moves);
            match *a {
                Action::Reset(Signal::Sequence) => {
                    // Back to the initial step: every step flag off, its own on.
                    for (k, bit) in layout.step_flags.iter().enumerate() {
                        lines.push(line("R", Layout::m(*bit), self.flag(k)));
                    }
                    lines.push(line(
                        "S",
                        Layout::m(layout.step_flags[0]),
                        format!("{}: back to STEP {INITIAL_STEP}", self.flag(0)),
                    ));
                }
                Action::Set(s) => lines.push(line("S", layout.operand(input, s), comment)),
                Action::Reset(s) => lines.push(line("R", layout.operand(input, s), comment)),
                Action::StartTimer(s, ms) => {
                    let Some(t) = layout.timer(s) else { continue };
                    let word = format!("MW {}", t.preset_word);
                    let timer = timer_operand(input, s);
                    // The comment says what the preset holds, where it
                    // differs from the table's time (W008 said so too).
                    let comment = match s5_ms(ms) {
                        held if held != ms => format!("{comment} (S5TIME holds {held} ms)"),
                        _ => comment,
                    };
                    lines.push(line("L", s5time(ms), comment));
                    lines.push(line("T", word.clone(), t.preset_name.ident.clone()));
                    lines.push(line("S", Layout::m(t.run), t.run_name.ident.clone()));
                    // A falling then a rising edge: the timer starts anew now.
                    lines.push(line("CLR", "", ""));
                    lines.push(line(w.on_delay, timer.clone(), "stop the timer"));
                    lines.push(line("SET", "", ""));
                    lines.push(line("L", word, t.preset_name.ident.clone()));
                    lines.push(line(w.on_delay, timer, "and start it from now"));
                    lines.push(line("SET", "", ""));
                }
            }
        }
    }

    /// With no step flag set (first cycle after a cold start) the sequence
    /// is in the initial step; then no step has fired yet in this cycle.
    fn start(&mut self) {
        let layout = self.layout;
        let w = &layout.words;
        let mut init = Vec::new();
        for (k, bit) in layout.step_flags.iter().enumerate() {
            init.push(line(w.and_not, Layout::m(*bit), self.flag(k)));
        }
        init.push(line("S", Layout::m(layout.step_flags[0]), self.flag(0)));
        self.actions(&mut init, &self.input.program.init, &[]);
        self.networks.push(Network {
            title: format!("start: no step flag set, so the sequence is in STEP {INITIAL_STEP}"),
            lines: init,
        });
        self.networks.push(Network {
            title: "no step has fired yet in this cycle".to_string(),
            lines: vec![
                line("SET", "", ""),
                line("R", Layout::m(layout.fired), self.lowered.fired.as_str()),
            ],
        });
    }

    fn timers(&mut self) {
        let (input, layout) = (self.input, self.layout);
        let w = &layout.words;
        for t in &layout.timers {
            let timer = timer_operand(input, t.signal);
            let run = &t.run_name.ident;
            let preset = &t.preset_name.ident;
            let name = input.symbols.ident(t.signal);
            self.networks.push(Network {
                title: format!(
                    "{} timer: on-delay while {run}; when it has elapsed, {run} goes off",
                    if t.signal == Signal::Watchdog {
                        "watchdog".to_string()
                    } else {
                        name.clone()
                    }
                ),
                lines: vec![
                    line(w.and, Layout::m(t.run), run.clone()),
                    line("L", format!("MW {}", t.preset_word), preset.clone()),
                    line(w.on_delay, timer.clone(), name.clone()),
                    line(w.and, timer, format!("{name} elapsed")),
                    line("R", Layout::m(t.run), run.clone()),
                ],
            });
        }
    }

    /// One transition per network: the step's jumps first, then the step.
    fn transitions(&mut self) {
        let lowered = self.lowered;
        for step in &lowered.steps {
            for t in step.transitions() {
                let title = one_line(&step.heading(&t));
                self.transition(step.index, t.condition, t.actions, t.moves, t.next, title);
            }
        }
    }

    fn transition(
        &mut self,
        k: usize,
        condition_of: &[Literal],
        fired_actions: &[Action],
        moves: &[crate::table::Move],
        next: usize,
        title: String,
    ) {
        let layout = self.layout;
        let w = &layout.words;
        let fired = self.lowered.fired.as_str();
        let mut lines = vec![
            line(w.and, Layout::m(layout.step_flags[k]), self.flag(k)),
            line(w.and_not, Layout::m(layout.fired), fired),
        ];
        self.condition(&mut lines, condition_of);
        let skip = self.next_label();
        lines.push(line(w.jump_if_not, skip.clone(), "condition not met"));
        lines.push(line("SET", "", ""));
        self.actions(&mut lines, fired_actions, moves);
        lines.push(line("R", Layout::m(layout.step_flags[k]), self.flag(k)));
        lines.push(line(
            "S",
            Layout::m(layout.step_flags[next]),
            self.flag(next),
        ));
        lines.push(line("S", Layout::m(layout.fired), fired));
        lines.push(nop(&skip));
        self.networks.push(Network { title, lines });
    }

    fn rungs(&mut self) {
        let w = &self.layout.words;
        for rung in &self.input.program.rungs {
            let mut lines = Vec::new();
            if rung.condition.is_empty() {
                // Nothing to test: the actions always run.
                lines.push(line("SET", "", ""));
                self.actions(&mut lines, &rung.actions, &[]);
                self.networks.push(Network {
                    title: one_line(&self.input.symbols.explain(&rung.comment)),
                    lines,
                });
                continue;
            }
            self.condition(&mut lines, &rung.condition);
            let skip = self.next_label();
            lines.push(line(w.jump_if_not, skip.clone(), ""));
            lines.push(line("SET", "", ""));
            self.actions(&mut lines, &rung.actions, &[]);
            lines.push(nop(&skip));
            self.networks.push(Network {
                title: one_line(&self.input.symbols.explain(&rung.comment)),
                lines,
            });
        }
    }
}

/// The jump target that ends a network's conditional part.
fn nop(skip: &str) -> Line {
    Line {
        label: format!("{skip}:"),
        op: "NOP".to_string(),
        operand: "0".to_string(),
        comment: String::new(),
    }
}

/// An operand as the symbol table column holds it.
fn sdf_address(operand: &str) -> String {
    let (letter, number) = operand.split_once(' ').unwrap_or((operand, ""));
    format!("{letter:<4}{number:>7}")
}

/// The symbol table: I/O, memories, timer, and the AWL-only bits.
fn symbol_table(
    input: &EmitInput,
    layout: &Layout,
    lowered: &super::lower::Lowered,
) -> Vec<Symbol> {
    let symbols = input.symbols;
    let mut table: Vec<Symbol> = input
        .allocation
        .inputs
        .iter()
        .chain(&input.allocation.outputs)
        .chain(&input.allocation.memories)
        .map(|a| {
            Symbol::new(
                symbols.ident(a.signal),
                sdf_address(&layout.operand(input, a.signal)),
                "BOOL",
                &symbols.comment(a.signal),
            )
        })
        .collect();
    for (k, bit) in layout.step_flags.iter().enumerate() {
        let names = symbols.step(k);
        table.push(Symbol::new(
            lowered.flag(k).to_string(),
            sdf_address(&Layout::m(*bit)),
            "BOOL",
            &names.map(|n| n.flag.comment.clone()).unwrap_or_default(),
        ));
    }
    table.push(Symbol::new(
        lowered.fired.clone(),
        sdf_address(&Layout::m(layout.fired)),
        "BOOL",
        &symbols.fired.comment,
    ));
    for t in &layout.timers {
        table.push(Symbol::new(
            t.run_name.ident.clone(),
            sdf_address(&Layout::m(t.run)),
            "BOOL",
            &t.run_name.comment,
        ));
        table.push(Symbol::new(
            t.preset_name.ident.clone(),
            sdf_address(&format!("MW {}", t.preset_word)),
            "S5TIME",
            &t.preset_name.comment,
        ));
        table.push(Symbol::new(
            symbols.ident(t.signal),
            sdf_address(&timer_operand(input, t.signal)),
            "TIMER",
            &symbols.comment(t.signal),
        ));
    }
    table
}

fn build(input: &EmitInput) -> Context {
    let layout = Layout::new(input);
    let lowered = super::lower::lower(input.program, input.symbols);
    let mut networks = Networks {
        input,
        layout: &layout,
        lowered: &lowered,
        labels: 0,
        networks: Vec::new(),
    };
    networks.start();
    networks.timers();
    networks.transitions();
    networks.rungs();
    let networks = networks.networks;
    let first_flag = layout.step_flags.first().copied().unwrap_or((0, 0));
    let last_flag = layout.step_flags.last().copied().unwrap_or((0, 0));
    Context {
        title: one_line(input.name),
        version: env!("CARGO_PKG_VERSION"),
        source: one_line(&input.source()),
        mnemonics: match input.allocation.mnemonic {
            Mnemonic::En => "English (A, AN, JCN; I, Q)",
            Mnemonic::De => "German (U, UN, SPBN; E, A)",
        },
        step_flags: format!("{} to {}", Layout::m(first_flag), Layout::m(last_flag)),
        step_note: super::step_numbering_note("the number of the step flag that is on (step_k)")
            .iter()
            .map(|l| one_line(l))
            .collect(),
        networks,
        symbols: symbol_table(input, &layout, &lowered),
    }
}

/// The networks and symbols both STEP 7 files lay out: build it once per
/// conversion and hand it to [`render_awl`] and [`render_sdf`].
pub fn model(input: &EmitInput) -> Value {
    Value::from(Serde(&build(input)))
}

/// Renders `NAME.awl` from the [`model`].
pub fn render_awl(input: &EmitInput, model: &Value) -> Result<String, templates::TemplateError> {
    input.templates.render("program.awl.j2", model.clone())
}

/// Renders `NAME.sdf` from the [`model`].
pub fn render_sdf(input: &EmitInput, model: &Value) -> Result<String, templates::TemplateError> {
    input.templates.render("symbols.sdf.j2", model.clone())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn labels_fit_four_characters() {
        assert_eq!(label(0), "L000");
        assert_eq!(label(46655), "LZZZ");
        assert!((0..5000).map(label).all(|l| l.len() == 4));
    }
}
