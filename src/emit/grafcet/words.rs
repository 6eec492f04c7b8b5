//! What the GRAFCET writes beside its steps and transitions, in the
//! engineer's designations (from [`crate::symbols`]): receptivities as
//! products of signals (`x11 · ¬x12`, dwells as `t/X3/2s`), and each step's
//! actions as stored set/reset orders (`S y1+`, `R y1-`) split by the
//! table's branches.

use crate::program::{Action, Literal, ProgramStep, Signal, StepKind, StepProgram};
use crate::symbols::SymbolTable;
use crate::table::{Step, StepTable};

/// One factor of a receptivity: its text, drawn with an overline when
/// negated (IEC 60848 writes NOT as a bar over the variable).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Term {
    pub text: String,
    pub negated: bool,
}

/// A receptivity wider than this many characters wraps after a factor.
const LINE_CHARS: usize = 46;

/// The receptivity of `condition` as lines of factors joined by `·`.
/// A dwell's two literals (armed, running) read as one `t/X3/2s`: true
/// once step 3 has been active for 2 s, as IEC 60848 writes a time.
pub fn receptivity(
    condition: &[Literal],
    symbols: &SymbolTable,
    table: &StepTable,
    program: &StepProgram,
) -> Vec<Vec<Term>> {
    let terms: Vec<Term> = condition
        .iter()
        .filter(|l| !matches!(l.signal, Signal::DwellArmed(_)))
        .map(|l| match l.signal {
            Signal::Dwell(n) => Term {
                text: dwell_text(n, table, program, symbols),
                // The timer runs while the dwell lasts: NOT running is the
                // time having elapsed.
                negated: !l.negated,
            },
            signal => Term {
                text: symbols.designation(signal),
                negated: l.negated,
            },
        })
        .collect();
    if terms.is_empty() {
        return vec![vec![Term {
            text: "1".to_string(),
            negated: false,
        }]];
    }
    let mut lines: Vec<Vec<Term>> = vec![Vec::new()];
    let mut width = 0;
    for term in terms {
        let len = term.text.chars().count() + 3;
        if width + len > LINE_CHARS && width > 0 {
            lines.push(Vec::new());
            width = 0;
        }
        width += len;
        lines.last_mut().expect("one line at least").push(term);
    }
    lines
}

/// `t/X3/2s` when dwell `n` starts with its step; `t/x41/500ms` (or
/// `t/(x41·¬r)/2s`) when it starts once the other items of its branch are
/// done: the time runs from the moment its own rung's condition holds, as
/// the program's timer does (IEC 60848's `t1/b/t2`, the delay on `b`).
fn dwell_text(n: u16, table: &StepTable, program: &StepProgram, symbols: &SymbolTable) -> String {
    let Some((step, dwell)) = table
        .steps
        .iter()
        .find_map(|s| s.dwells.iter().find(|d| d.number == n).map(|d| (s, d)))
    else {
        return format!("t/T{n}");
    };
    let trigger: Vec<String> = program
        .rungs
        .iter()
        .find(|r| {
            r.actions
                .iter()
                .any(|a| matches!(a, Action::StartTimer(Signal::Dwell(d), _) if *d == n))
        })
        .map(|rung| {
            rung.condition
                .iter()
                .filter(|l| !matches!(l.signal, Signal::DwellArmed(_)))
                .map(|l| {
                    let name = symbols.designation(l.signal);
                    if l.negated { format!("¬{name}") } else { name }
                })
                .collect()
        })
        .unwrap_or_default();
    let trigger = match trigger.as_slice() {
        [] => format!("X{}", step.number),
        [one] => one.clone(),
        many => format!("({})", many.join("·")),
    };
    format!("t/{trigger}/{}", crate::cell::duration_text(dwell.ms))
}

/// The text of one line of terms, as the SVG and the tests measure it.
pub fn line_text(line: &[Term]) -> String {
    line.iter()
        .map(|t| t.text.as_str())
        .collect::<Vec<_>>()
        .join(" · ")
}

/// The table step a program step fires, if it is one of the table's.
pub fn table_step<'t>(step: &ProgramStep, table: &'t StepTable) -> Option<&'t Step> {
    (step.kind == StepKind::Table)
        .then(|| table.steps.iter().find(|s| s.number == step.number))
        .flatten()
}

/// The branches a table step acts in, in table order: one box each when
/// there are two or more (an AND divergence).
pub fn branches(step: &Step) -> Vec<usize> {
    let mut used: Vec<usize> = step
        .moves
        .iter()
        .map(|m| m.branch)
        .chain(step.dwells.iter().map(|d| d.branch))
        .chain(step.waits.iter().map(|w| w.branch))
        .chain(step.switches.iter().map(|s| s.branch))
        .collect();
    used.sort_unstable();
    used.dedup();
    used
}

/// The branch an action belongs to: the move of its actuator, the switch
/// of its output; `None` for what belongs to the step as a whole.
fn action_branch(action: Action, step: &Step) -> Option<usize> {
    match action.signal() {
        Signal::Coil { actuator, .. } | Signal::SingleCoil { actuator } => step
            .moves
            .iter()
            .find(|m| m.actuator == actuator)
            .map(|m| m.branch),
        Signal::MachineOutput(name) => step
            .switches
            .iter()
            .find(|s| s.output == name)
            .map(|s| s.branch),
        _ => None,
    }
}

/// The stored actions a step shows in `branch` (every branch's when
/// `branch` is `None`): set and reset of coils, machine outputs and alarms,
/// as `S y1+` / `R y1-`. Memories and timers are the program's own
/// bookkeeping; a dwell shows as the receptivity after the step.
pub fn actions(
    program_step: &ProgramStep,
    step: &Step,
    branch: Option<usize>,
    first_branch: bool,
    symbols: &SymbolTable,
) -> Vec<String> {
    program_step
        .actions
        .iter()
        .filter(|a| a.signal().area() == crate::program::Area::Output)
        .filter(|a| match (branch, action_branch(**a, step)) {
            (None, _) => true,
            (Some(b), Some(of)) => b == of,
            // What belongs to no branch is drawn once, in the first box.
            (Some(_), None) => first_branch,
        })
        .filter_map(|a| {
            let letter = match a {
                Action::Set(_) => "S",
                Action::Reset(_) => "R",
                Action::StartTimer(..) => return None,
            };
            Some(format!("{letter} {}", symbols.designation(a.signal())))
        })
        .collect()
}

/// What the mode and safety logic does beside the sequence, one line per
/// kind of rung (`STOP: …`), for the chart's note: it acts on the chart
/// from outside (IEC 60848 forcing), which a chart of steps cannot show.
pub fn mode_note(program: &crate::program::StepProgram, symbols: &SymbolTable) -> Vec<String> {
    use crate::program::RungKind;
    let mut lines: Vec<String> = Vec::new();
    let mut seen: Vec<RungKind> = Vec::new();
    for rung in &program.rungs {
        let shown = matches!(
            rung.kind,
            RungKind::Mode
                | RungKind::EmergencyStop
                | RungKind::StopNow
                | RungKind::Homing
                | RungKind::HaltOff
                | RungKind::Interlock
                | RungKind::Watchdog
                | RungKind::Plausibility
                | RungKind::RunOn
                | RungKind::Manual
        );
        if !shown || seen.contains(&rung.kind) {
            continue;
        }
        seen.push(rung.kind);
        let more = program.rungs.iter().filter(|r| r.kind == rung.kind).count() - 1;
        let tail = if more > 0 {
            format!(" (and {more} more)")
        } else {
            String::new()
        };
        let comment = symbols.explain(&rung.comment);
        // Most comments already begin with what the rung is.
        if comment.starts_with(rung.kind.label()) {
            lines.push(format!("{comment}{tail}"));
        } else {
            lines.push(format!("{}: {comment}{tail}", rung.kind.label()));
        }
    }
    lines
}

/// What the step after a jump's step waits for besides its own condition:
/// that the jump's input does not have the value that takes the jump.
pub fn jump_input(jump: &crate::program::StepJump, symbols: &SymbolTable) -> Option<Term> {
    jump.condition
        .iter()
        .rev()
        .find(|l| matches!(l.signal, Signal::MachineInput(_)))
        .map(|l| Term {
            text: symbols.designation(l.signal),
            negated: !l.negated,
        })
}

/// The characters a panel line shows: the longest of the samples' is 38
/// (`initial step: at rest, waits for START`); a step comment or an
/// actuator name of hundreds would make a panel wider than any page.
pub const PANEL_LINE: usize = 64;

/// A panel's lines cut to [`PANEL_LINE`] by the one cut of every limited
/// comment ([`crate::emit::shorten`]), and the whole lines, one per line of the
/// tooltip, when one was cut.
pub(super) fn panel_lines(lines: Vec<String>) -> (Vec<String>, Option<String>) {
    let cut: Vec<(String, bool)> = lines
        .iter()
        .map(|l| crate::emit::shorten(l, PANEL_LINE))
        .collect();
    let tip = cut.iter().any(|(_, c)| *c).then(|| lines.join("\n"));
    (cut.into_iter().map(|(l, _)| l).collect(), tip)
}
