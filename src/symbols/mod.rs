//! The program's one naming authority: for every signal and every name an
//! output invents (the step counter, step flags, timer flags and presets),
//! its identifier, its Festo FST symbol, its designation (what the
//! engineer reads in lists and comments: `x10`, `1B1` or `clamp_home`), its
//! comment and its role. Built once per program from the program, the table
//! and the naming settings; every emitter only reads it, so no two outputs
//! can spell a signal differently, and the rules of each target (IEC
//! identifiers, FST's 9 characters, STEP 7 and Rockwell symbols) are
//! checked in one place ([`check`]).

pub mod check;
mod comment;
mod scheme;

use std::collections::BTreeMap;

pub use comment::{FINDING_NAME, shorten};
use comment::{map_words, role};
pub use scheme::{ActuatorName, Naming, Scheme, paper_ident, stem as scheme_stem};

use crate::cell::Sign;
use crate::program::{Action, Signal, StepProgram};
use crate::table::StepTable;

pub use crate::names::{FIRED, STEP_COUNTER};

/// Names of the program's own parts, which [`crate::names`] keeps from
/// every machine signal.
pub const PROGRAM_NAME: &str = "steptable_main";
/// The names OpenPLC Runtime requires (its upload script moves `Config0.c`
/// and `Res0.c`); Beremiz accepts any.
pub const CONFIGURATION_NAME: &str = "Config0";
pub const RESOURCE_NAME: &str = "Res0";
pub const TASK_NAME: &str = "cyclic_task";
pub const INSTANCE_NAME: &str = "main_instance";

/// Everything one signal is called.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Symbol {
    /// The identifier of IEC 61131-3 (ST, PLCopen, CODESYS), of the STEP 7
    /// symbol table and TIA tags, and of the Rockwell tags: legal in all.
    pub ident: String,
    /// The symbolic operand of Festo FST: at most 9 characters.
    pub fst: String,
    /// What the engineer reads in lists, comments, the fault table and the
    /// diagrams: `x10` / `y1+` (the paper's), `1B1` / `1M1` (ISO 1219-2) or
    /// `clamp_home` (the engineer's names).
    pub designation: String,
    /// What the signal is, in words.
    pub comment: String,
    /// The `kind` column of the allocation list.
    pub role: &'static str,
}

/// A name an output gives one of its own parts.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Own {
    pub ident: String,
    pub comment: String,
}

/// The names of one step of the program.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StepNames {
    /// The step's number, as in the table.
    pub number: usize,
    /// The step's label on the sheets: `STEP 3 (clamp part)`, `STEP 9 (END)`.
    pub label: String,
    /// What the step does, with the engineer's comment of its row:
    /// `C1+1 (clamp part)`.
    pub title: String,
    /// The SFC step the program is in while it waits at this program
    /// step: the table step before it, or the initial step.
    pub active: usize,
    /// What that step does (`C1+1 (clamp part)`), or what the initial
    /// step waits for.
    pub active_title: String,
    /// The STEP 7 flag of the step the program is in (`step_0` at rest,
    /// `step_3` while step 3's moves run).
    pub flag: Own,
}

/// The flag and preset a timer is driven by, in the IEC outputs (`dwell1_run`)
/// and in STEP 7 (`dw1_run`, within its symbol length).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TimerNames {
    pub iec_run: Own,
    pub iec_preset: Own,
    pub step7_run: Own,
    pub step7_preset: Own,
}

/// Every name of one program.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct SymbolTable {
    pub scheme: Scheme,
    signals: BTreeMap<Signal, Symbol>,
    /// Each actuator's label (`C1`, `1A1`) and the engineer's name.
    actuators: BTreeMap<u32, (String, Option<String>)>,
    /// Each actuator's kind, for the words of its coils' comments.
    kinds: BTreeMap<u32, crate::actuator::ActuatorKind>,
    steps: Vec<StepNames>,
    timers: BTreeMap<Signal, TimerNames>,
    pub step_counter: Own,
    pub fired: Own,
}

impl SymbolTable {
    /// The names of `program` (of `table`) under `naming`.
    pub fn build(program: &StepProgram, table: &StepTable, naming: &Naming) -> SymbolTable {
        let actuators: BTreeMap<u32, (String, Option<String>)> = table
            .actuators
            .iter()
            .map(|a| (a.number, naming.actuator_parts(a.number)))
            .collect();
        let table_of = signal_symbols(used_signals(program), program, table, naming);
        let timers = timer_names(program, &table_of);
        let steps = step_names(program, table);
        SymbolTable {
            scheme: naming.scheme,
            signals: table_of,
            actuators,
            kinds: program.signals.kinds.clone(),
            steps,
            timers,
            step_counter: Own {
                ident: STEP_COUNTER.to_string(),
                comment: format!(
                    "the active step: {} = initial step (at rest, waiting for START), k = table step k, whose moves run",
                    crate::program::INITIAL_STEP
                ),
            },
            fired: Own {
                ident: FIRED.to_string(),
                comment: "a step fired in this cycle".to_string(),
            },
        }
    }

    /// Everything `signal` is called; `None` only for a signal the program
    /// does not use.
    pub fn get(&self, signal: Signal) -> Option<&Symbol> {
        self.signals.get(&signal)
    }

    /// The identifier of `signal` (`x21`, `y2p`, `clamp_out`).
    pub fn ident(&self, signal: Signal) -> String {
        self.get(signal)
            .map(|s| s.ident.clone())
            .unwrap_or_else(|| scheme::paper_ident(signal))
    }

    /// The Festo FST symbol of `signal`.
    pub fn fst(&self, signal: Signal) -> String {
        self.get(signal)
            .map(|s| s.fst.clone())
            .unwrap_or_else(|| crate::names::fst_stem(&scheme::paper_ident(signal)))
    }

    /// The designation of `signal` (`x21`, `1B2`, `clamp_end`).
    pub fn designation(&self, signal: Signal) -> String {
        self.get(signal)
            .map(|s| s.designation.clone())
            .unwrap_or_else(|| signal.symbol())
    }

    /// What `signal` is, in words.
    pub fn comment(&self, signal: Signal) -> String {
        self.get(signal)
            .map(|s| s.comment.clone())
            .unwrap_or_default()
    }

    /// The role of `signal` (the allocation list's `kind`).
    pub fn role(&self, signal: Signal) -> &'static str {
        role(signal)
    }

    /// Actuator `n` as the outputs name it: `C1`, `C1 (clamp)`, `1A1 (clamp)`.
    pub fn actuator(&self, n: u32) -> String {
        match self.actuator_parts(n) {
            (head, Some(name)) => format!("{head} ({name})"),
            (head, None) => head,
        }
    }

    /// Actuator `n` as a printed finding names it: [`Self::actuator`] with
    /// the engineer's name cut to [`FINDING_NAME`], as [`Self::explain`]
    /// cuts it.
    pub fn actuator_in_finding(&self, n: u32) -> String {
        match self.actuator_parts(n) {
            (head, Some(name)) => format!("{head} ({})", shorten(&name, FINDING_NAME).0),
            (head, None) => head,
        }
    }

    /// Actuator `n` as a diagram labels its lane: `C1` (`1A1` under ISO)
    /// and the engineer's name, if it has one.
    pub fn actuator_parts(&self, n: u32) -> (String, Option<String>) {
        self.actuators
            .get(&n)
            .cloned()
            .unwrap_or_else(|| (format!("C{n}"), None))
    }

    /// The names of the step at `index` among the program's steps.
    pub fn step(&self, index: usize) -> Option<&StepNames> {
        self.steps.get(index)
    }

    /// `text` (a simulation's explanation, written in the paper's symbols)
    /// with each signal's paper symbol replaced by its designation: a whole
    /// word only (`x10`, `y1+`), never part of one (`C1+1` stays).
    pub fn designate(&self, text: &str) -> String {
        if self.scheme == Scheme::Paper {
            return text.to_string();
        }
        let mut by_symbol: BTreeMap<String, &str> = self
            .signals
            .iter()
            .filter(|(s, x)| s.symbol() != x.designation)
            .map(|(s, x)| (s.symbol(), x.designation.as_str()))
            .collect();
        // The actuator too, where its label is not the paper's (`1A1`).
        by_symbol.extend(
            self.actuators
                .iter()
                .filter(|(n, (label, _))| *label != format!("C{n}"))
                .map(|(n, (label, _))| (format!("C{n}"), label.as_str())),
        );
        map_words(text, |token| by_symbol.get(token).copied())
    }

    /// A finding (a fault's explanation, a simulation's verdict or step
    /// notes, written in the paper's symbols) in the engineer's notation:
    /// each signal by its designation ([`Self::designate`]) and each
    /// actuator the engineer named by its name (`C1 had not reached x11` →
    /// `C1 (clamp) had not reached x11`, `1A1 (clamp) … 1B2` under ISO), a
    /// name longer than [`FINDING_NAME`] cut as every limited comment is
    /// ([`shorten`]): a finding names an actuator many times, and the whole
    /// name stands in the lists. A rung's comment (`homing stage 1: C2
    /// home`, `jog C3: … short of x31`) is such a text: the program writes
    /// it in paper symbols, naming no actuator by the engineer's name.
    pub fn explain(&self, text: &str) -> String {
        let text = self.designate(text);
        if self.actuators.values().all(|(_, name)| name.is_none()) {
            return text;
        }
        let named: BTreeMap<&str, String> = self
            .actuators
            .values()
            .filter_map(|(label, name)| {
                let name = shorten(name.as_deref()?, FINDING_NAME).0;
                Some((label.as_str(), format!("{label} ({name})")))
            })
            .collect();
        map_words(&text, |token| named.get(token).map(String::as_str))
    }

    /// The label of the table's step `number` (`STEP 3 (clamp part)`).
    pub fn step_label(&self, number: usize) -> String {
        self.steps
            .iter()
            .find(|s| s.number == number)
            .map_or_else(|| format!("STEP {number}"), |s| s.label.clone())
    }

    /// The run flag and preset names of a timer.
    pub fn timer(&self, timer: Signal) -> Option<&TimerNames> {
        self.timers.get(&timer)
    }

    /// Every signal with its names, in signal order.
    pub fn symbols(&self) -> impl Iterator<Item = (Signal, &Symbol)> {
        self.signals.iter().map(|(s, x)| (*s, x))
    }

    /// The identifiers of the signals that are bits or timers (not the
    /// sequence itself).
    fn signal_identifiers(&self) -> Vec<String> {
        self.signals
            .iter()
            .filter(|(s, _)| **s != Signal::Sequence)
            .map(|(_, x)| x.ident.clone())
            .collect()
    }

    /// Every identifier an IEC output declares: the signals' that are bits
    /// or timers, the step counter, the timers' flags and presets, and the
    /// program's own parts.
    pub fn iec_identifiers(&self) -> Vec<String> {
        let mut ids = self.signal_identifiers();
        ids.push(self.step_counter.ident.clone());
        for t in self.timers.values() {
            ids.push(t.iec_run.ident.clone());
            ids.push(t.iec_preset.ident.clone());
        }
        ids.extend(
            [
                PROGRAM_NAME,
                CONFIGURATION_NAME,
                RESOURCE_NAME,
                TASK_NAME,
                INSTANCE_NAME,
            ]
            .map(String::from),
        );
        ids
    }

    /// Every symbol of the STEP 7 symbol table.
    pub fn step7_identifiers(&self) -> Vec<String> {
        let mut ids = self.signal_identifiers();
        ids.extend(self.steps.iter().map(|s| s.flag.ident.clone()));
        ids.push(self.fired.ident.clone());
        for t in self.timers.values() {
            ids.push(t.step7_run.ident.clone());
            ids.push(t.step7_preset.ident.clone());
        }
        ids
    }

    /// What actuator `actuator`'s one coil does, on and off.
    fn single_coil_words(&self, actuator: u32) -> (&'static str, &'static str) {
        // Only a kind with one coil has a single coil to comment.
        let kind = self.kinds.get(&actuator).copied();
        kind.unwrap_or(crate::actuator::ActuatorKind::Mono52)
            .single_coil_words()
    }

    /// What actuator `actuator` does on its `+` and `-` moves, in its
    /// kind's words (`extends`, `runs forward`, `grips`).
    pub fn move_words(&self, actuator: u32) -> (&'static str, &'static str) {
        self.kinds
            .get(&actuator)
            .map_or(("extends", "retracts"), |k| k.move_words())
    }

    /// What actuator `actuator`'s `+` and `-` coils do.
    fn kind_words(&self, actuator: u32) -> (&'static str, &'static str) {
        self.kinds
            .get(&actuator)
            .map_or(("extend", "retract"), |k| k.coil_words())
    }

    /// A short explanation of an action for a program comment, in the
    /// table's designations (`y1+ on: extend C1 (clamp), C1+1 towards x11`).
    pub fn action_comment(&self, action: Action, moves: &[crate::table::Move]) -> String {
        let name = |s: Signal| self.designation(s);
        let symbol = name(action.signal());
        let sensor = |actuator, position| name(Signal::Sensor { actuator, position });
        match action {
            Action::Set(Signal::Coil { actuator, sign }) => {
                let target = moves
                    .iter()
                    .find(|m| m.actuator == actuator && m.sign == sign)
                    .map(|m| format!(", {} towards {}", m.notation(), sensor(actuator, m.to)))
                    .unwrap_or_default();
                let (plus, minus) = self.kind_words(actuator);
                let verb = if sign == Sign::Plus { plus } else { minus };
                let said = crate::actuator::ActuatorKind::verb_of(verb, &self.actuator(actuator));
                format!("{symbol} on: {said}{target}")
            }
            Action::Reset(Signal::Coil { .. }) => format!("{symbol} off"),
            Action::Set(Signal::SingleCoil { actuator }) => {
                let target = moves
                    .iter()
                    .find(|m| m.actuator == actuator)
                    .map(|m| format!(", {}", m.notation()))
                    .unwrap_or_default();
                let (on, _) = self.single_coil_words(actuator);
                format!("{symbol} on: {on} {}{target}", self.actuator(actuator))
            }
            Action::Reset(Signal::SingleCoil { actuator }) => {
                let target = moves
                    .iter()
                    .find(|m| m.actuator == actuator)
                    .map(|m| format!(", {}", m.notation()))
                    .unwrap_or_default();
                let (_, off) = self.single_coil_words(actuator);
                format!("{symbol} off: {off} {}{target}", self.actuator(actuator))
            }
            Action::Set(Signal::StopAt { actuator, position }) => format!(
                "{symbol}: stop {} at {}",
                self.actuator(actuator),
                sensor(actuator, position)
            ),
            Action::Reset(Signal::StopAt { .. }) => format!("{symbol} off: stop request cleared"),
            Action::StartTimer(s, ms) => format!("start {} for {ms} ms", name(s)),
            Action::Reset(Signal::Sequence) => format!(
                "the sequence goes back to STEP {}",
                crate::program::INITIAL_STEP
            ),
            Action::Set(s) => format!("{} on", name(s)),
            Action::Reset(s) => format!("{} off", name(s)),
        }
    }
}

/// Every signal the program uses: its I/O, memories and timers, and every
/// signal a step or rung reads or writes, so that a lookup never misses (a
/// sensor an action comment points to).
fn used_signals(program: &StepProgram) -> Vec<Signal> {
    let mut used: Vec<Signal> = Vec::new();
    let signals = &program.signals;
    used.extend(&signals.inputs);
    used.extend(signals.valves.iter().map(|v| v.extend()));
    used.extend(signals.valves.iter().filter_map(|v| v.retract()));
    used.extend(&signals.outputs);
    used.extend(&signals.memories);
    used.extend(&program.timers);
    let steps = program.steps.iter().flat_map(|s| {
        let jumps = s.jumps.iter().flat_map(|j| {
            j.condition
                .iter()
                .map(|l| l.signal)
                .chain(j.actions.iter().map(|a| a.signal()))
        });
        s.condition
            .iter()
            .map(|l| l.signal)
            .chain(s.actions.iter().map(|a| a.signal()))
            .chain(jumps)
            .collect::<Vec<_>>()
    });
    let rungs = program.rungs.iter().flat_map(|r| {
        r.condition
            .iter()
            .map(|l| l.signal)
            .chain(r.actions.iter().map(|a| a.signal()))
    });
    used.extend(steps);
    used.extend(rungs);
    used.extend(program.init.iter().map(|a| a.signal()));
    for s in &program.steps {
        for m in &s.moves {
            used.push(program.signals.at(m.actuator, m.to).signal);
        }
    }
    used.push(Signal::Sequence);

    used
}

/// The identifier, designation and comment of every used signal.
fn signal_symbols(
    used: Vec<Signal>,
    program: &StepProgram,
    table: &StepTable,
    naming: &Naming,
) -> BTreeMap<Signal, Symbol> {
    let designate = |s: Signal| naming.designation(s, table);
    let actuator = |n: u32| naming.actuator_words(n);
    let mut table_of = BTreeMap::new();
    for signal in used {
        if table_of.contains_key(&signal) {
            continue;
        }
        let ident = naming.ident(signal, table);
        let designation = designate(signal);
        let words = comment::comment(signal, program, table, &actuator, &designate);
        // The designation leads the comment where the identifier does
        // not show it (ISO 1219 designations are no identifiers).
        let comment = if designation != ident && designation != signal.symbol() {
            format!("{designation}: {words}")
        } else {
            words
        };
        // FST keeps 9 characters: `clamp_jog_out` and `clamp_jog_in` would
        // be one symbol there, so a jog button keeps its paper symbol.
        let fst = match signal {
            Signal::Jog { .. } => paper_ident(signal),
            _ => crate::names::fst_stem(&ident),
        };
        table_of.insert(
            signal,
            Symbol {
                fst,
                ident,
                designation,
                comment,
                role: role(signal),
            },
        );
    }
    table_of
}

/// The run flags and presets of every timer, in the IEC outputs and STEP 7.
fn timer_names(
    program: &StepProgram,
    table_of: &BTreeMap<Signal, Symbol>,
) -> BTreeMap<Signal, TimerNames> {
    let comment_of = |s: Signal| {
        table_of
            .get(&s)
            .map(|x: &Symbol| x.comment.clone())
            .unwrap_or_default()
    };
    let ident_of = |s: Signal| {
        table_of
            .get(&s)
            .map(|x: &Symbol| x.ident.clone())
            .unwrap_or_default()
    };
    program
        .timers
        .iter()
        .map(|&t| {
            let iec_stem = match t {
                Signal::Watchdog => "wd".to_string(),
                other => ident_of(other),
            };
            let step7_stem = match t {
                Signal::Dwell(n) => format!("dw{n}"),
                Signal::RunOn(n) => format!("ro{n}"),
                _ => "wd".to_string(),
            };
            let (what, preset) = match t {
                Signal::Watchdog => (
                    "watchdog".to_string(),
                    "watchdog preset of the running step".to_string(),
                ),
                other => (ident_of(other), format!("{} preset", ident_of(other))),
            };
            let own = |ident: String, comment: String| Own { ident, comment };
            (
                t,
                TimerNames {
                    iec_run: own(format!("{iec_stem}_run"), format!("{} runs", comment_of(t))),
                    iec_preset: own(
                        format!("{iec_stem}_pt"),
                        format!("{} preset", comment_of(t)),
                    ),
                    step7_run: own(format!("{step7_stem}_run"), format!("{what} runs")),
                    step7_preset: own(format!("{step7_stem}_pt"), preset),
                },
            )
        })
        .collect()
}

/// The label, title and active SFC step of every program step.
fn step_names(program: &StepProgram, table: &StepTable) -> Vec<StepNames> {
    let titles: Vec<(String, String)> = program
        .steps
        .iter()
        .map(|s| {
            let comment = table
                .steps
                .iter()
                .find(|t| t.number == s.number && s.kind == crate::program::StepKind::Table)
                .and_then(|t| t.comment.as_deref());
            let label = match (s.kind, comment) {
                (crate::program::StepKind::EndOfCycle, _) => format!("STEP {} (END)", s.number),
                (_, Some(c)) => format!("STEP {} ({c})", s.number),
                (_, None) => format!("STEP {}", s.number),
            };
            let title = match comment {
                Some(c) => format!("{} ({c})", s.title),
                None => s.title.clone(),
            };
            (label, title)
        })
        .collect();
    program
        .steps
        .iter()
        .enumerate()
        .map(|(k, s)| {
            // While the program waits at step k, the SFC step active is
            // the table step before it (or the initial step).
            let active = program.step_in(k);
            let active_title = match k.checked_sub(1).map(|b| (&program.steps[b], b)) {
                Some((before, b)) if before.kind == crate::program::StepKind::Table => {
                    titles[b].1.clone()
                }
                _ => crate::program::INITIAL_TITLE.to_string(),
            };
            StepNames {
                number: s.number,
                label: titles[k].0.clone(),
                title: titles[k].1.clone(),
                flag: Own {
                    ident: format!("step_{active}"),
                    comment: format!("STEP {active} is active: {active_title}"),
                },
                active,
                active_title,
            }
        })
        .collect()
}

#[cfg(test)]
mod tests;
