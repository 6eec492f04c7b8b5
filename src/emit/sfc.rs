//! The sequence as an SFC chart in PLCopen XML (`NAME.sfc.xml`), laid out
//! top to bottom with full geometry, which Beremiz turns into the textual
//! SFC matiec compiles.
//!
//! Three programs run in one task, in this order, so that a scan does what
//! the step program's does: `steptable_pre` calls the timers, the chart
//! `steptable_main` fires at most one transition (the first that holds, as
//! the ST's `IF … ELSIF`: explicit priorities for Beremiz and matiec, and
//! the same order left to right for CODESYS, which has no priorities),
//! `steptable_post` runs the rungs. The variables are the resource's
//! globals. Each step's actions run once, as it is entered, in a `P` action
//! of its own (never shared: a shared pulse action misses a step in
//! Beremiz, and an `S` coil action is re-asserted by matiec on every scan
//! the step is active, which would undo a rung's reset of that coil; `P`,
//! not `P1`, which CODESYS lacks). Its body tests the step's flag and that
//! `active_step` is not yet k: CODESYS and IEC 61131-3 ed. 2 run an action
//! once more after it ends (after the step is left, or in the next cycle),
//! which must do nothing. The entry action ends `active_step := k`,
//! so `active_step` is the step program's step as in the ST; a rung that
//! sends the sequence back (`active_step := 0`) is followed, on the next
//! scan, by the transitions every step has at the highest priority: on to
//! step 1 when step 0's own condition holds, else back to step 0.

use minijinja::Value;
use minijinja::value::Serde;
use serde::Serialize;

use super::lower::{Lowered, Transition};
use super::st::{Spelling, Statement, comment_text, condition, statements};
use super::{EmitInput, templates};
use crate::program::{Action, INITIAL_STEP, Signal};

/// Vertical and horizontal spacing of the chart, in PLCopen units.
const STEP_W: i64 = 70;
const STEP_H: i64 = 30;
const BRANCH_GAP: i64 = 320;
const LEFT: i64 = 40;

/// A connection: the element it comes from and its points, the first at
/// the input, the last at the source's output (as the editors draw it).
#[derive(Serialize)]
struct Wire {
    from: u64,
    points: Vec<(i64, i64)>,
}

#[derive(Serialize)]
#[serde(tag = "kind")]
enum Element {
    Step {
        id: u64,
        name: String,
        initial: bool,
        x: i64,
        y: i64,
        input: Option<Wire>,
        comment: String,
    },
    Actions {
        id: u64,
        x: i64,
        y: i64,
        input: Wire,
        action: String,
    },
    Divergence {
        id: u64,
        x: i64,
        y: i64,
        width: i64,
        /// Where the step's wire comes in, from the bar's left end.
        input_x: i64,
        input: Wire,
        outputs: Vec<i64>,
    },
    Transition {
        id: u64,
        x: i64,
        y: i64,
        priority: usize,
        condition: String,
        input: Wire,
        comment: String,
    },
    Jump {
        id: u64,
        x: i64,
        y: i64,
        target: String,
        input: Wire,
    },
}

/// The action a step runs as it is entered: per step it may come from, the
/// actions of the transition that brought it there.
#[derive(Serialize)]
struct Entry {
    name: String,
    /// The SFC step's name, whose flag guards the action.
    flag: String,
    step: usize,
    /// One case per distinct action list; `from` empty: always.
    cases: Vec<EntryCase>,
}

#[derive(Serialize)]
struct EntryCase {
    from: Vec<usize>,
    actions: Vec<Statement>,
}

#[derive(Serialize)]
struct Chart {
    elements: Vec<Element>,
    entries: Vec<Entry>,
    step_var: String,
}

/// One outgoing transition as the chart draws it.
struct Leaving {
    condition: String,
    comment: String,
    enters: usize,
    /// Drawn straight down to the next step rather than as a jump.
    down: bool,
}

struct Layout<'l, 'p> {
    input: &'l EmitInput<'l>,
    lowered: &'l Lowered<'p>,
    elements: Vec<Element>,
    next_id: u64,
}

impl Layout<'_, '_> {
    fn id(&mut self) -> u64 {
        self.next_id += 1;
        self.next_id
    }

    /// The SFC step's name: the step flag of the languages with flags.
    fn name(&self, step: usize) -> String {
        self.lowered
            .steps
            .iter()
            .position(|s| s.active == step)
            .map(|k| self.lowered.flag(k).to_string())
            .unwrap_or_else(|| format!("step_{step}"))
    }

    /// Transitions leaving a step in the order they are tested: the return
    /// after a rung sent the sequence back, the jumps, the step's own.
    fn leaving(&self, k: usize, resets: bool) -> Vec<Leaving> {
        let symbols = self.input.symbols;
        let step = &self.lowered.steps[k];
        let var = &symbols.step_counter.ident;
        let mut all = Vec::new();
        if resets && step.active != INITIAL_STEP {
            let first = self.lowered.steps[0].own();
            let text = condition(symbols, first.condition, Spelling::Iec);
            all.push(Leaving {
                condition: if first.condition.is_empty() {
                    format!("{var} = {INITIAL_STEP}")
                } else {
                    format!("{var} = {INITIAL_STEP} AND {text}")
                },
                comment: format!(
                    "sent back to STEP {INITIAL_STEP} by a rung, and STEP {INITIAL_STEP} is done"
                ),
                enters: first.enters,
                down: false,
            });
            all.push(Leaving {
                condition: format!("{var} = {INITIAL_STEP}"),
                comment: format!("sent back to STEP {INITIAL_STEP} by a rung"),
                enters: INITIAL_STEP,
                down: false,
            });
        }
        for t in step.transitions() {
            all.push(Leaving {
                condition: condition(symbols, t.condition, Spelling::Iec),
                comment: comment_text(t.comment),
                enters: t.enters,
                down: !t.jump && !step.closing,
            });
        }
        all
    }

    /// Draws the step waiting at `k` at height `y`, its column at `x`, and
    /// what leaves it; returns the wire into the next step and its height.
    fn step(
        &mut self,
        k: usize,
        (x, y): (i64, i64),
        input: Option<Wire>,
        resets: bool,
    ) -> (Option<Wire>, i64) {
        let active = self.lowered.steps[k].active;
        let step_id = self.id();
        self.elements.push(Element::Step {
            id: step_id,
            name: self.name(active),
            initial: active == INITIAL_STEP,
            x,
            y,
            input,
            comment: comment_text(&self.lowered.steps[k].active_title),
        });
        let actions_id = self.id();
        self.elements.push(Element::Actions {
            id: actions_id,
            x: x + STEP_W + 40,
            y,
            input: Wire {
                from: step_id,
                points: vec![(x + STEP_W + 40, y + 15), (x + STEP_W, y + 15)],
            },
            action: entry_name(&self.name(active)),
        });
        let cx = x + STEP_W / 2;
        let leaving = self.leaving(k, resets);
        // Left to right in the order they are tested, as CODESYS tests an
        // alternative branch (it has no priorities): the step's own
        // transition, tested last, stays in the main column and the others
        // branch off to its left.
        let own = leaving.len() - 1;
        let column = |i: usize| i as i64 - own as i64;
        let (ty, source, source_y) = if own > 0 {
            let div = self.id();
            let width = BRANCH_GAP * own as i64;
            self.elements.push(Element::Divergence {
                id: div,
                x: cx - width,
                y: y + STEP_H + 20,
                width,
                input_x: width,
                input: Wire {
                    from: step_id,
                    points: vec![(cx, y + STEP_H + 20), (cx, y + STEP_H)],
                },
                outputs: (0..leaving.len()).map(|i| BRANCH_GAP * i as i64).collect(),
            });
            (y + STEP_H + 50, div, y + STEP_H + 21)
        } else {
            (y + STEP_H + 30, step_id, y + STEP_H)
        };
        let mut down = None;
        for (i, t) in leaving.into_iter().enumerate() {
            let bx = cx + BRANCH_GAP * column(i);
            let tid = self.id();
            self.elements.push(Element::Transition {
                id: tid,
                x: bx - 10,
                y: ty,
                priority: i + 1,
                condition: t.condition,
                input: Wire {
                    from: source,
                    points: vec![(bx, ty), (bx, source_y)],
                },
                comment: t.comment,
            });
            if t.down {
                down = Some(Wire {
                    from: tid,
                    points: vec![(bx, ty + 42), (bx, ty + 2)],
                });
            } else {
                let jid = self.id();
                let target = self.name(t.enters);
                self.elements.push(Element::Jump {
                    id: jid,
                    x: bx - 10,
                    y: ty + 30,
                    target,
                    input: Wire {
                        from: tid,
                        points: vec![(bx, ty + 30), (bx, ty + 2)],
                    },
                });
            }
        }
        (down, ty + 42)
    }
}

fn entry_name(step: &str) -> String {
    format!("{step}_entry")
}

/// Whether a rung sends the sequence back to step 0.
fn rungs_reset(input: &EmitInput) -> bool {
    input
        .program
        .rungs
        .iter()
        .any(|r| r.actions.contains(&Action::Reset(Signal::Sequence)))
}

/// The entry action of every step: the actions of the transitions that
/// enter it, grouped by the step they come from.
fn entries(
    input: &EmitInput,
    lowered: &Lowered,
    resets: bool,
    name: impl Fn(usize) -> String,
) -> Vec<Entry> {
    let symbols = input.symbols;
    let mut entries: Vec<Entry> = Vec::new();
    for step in &lowered.steps {
        let e = step.active;
        let mut cases: Vec<(Vec<usize>, Transition)> = Vec::new();
        for from in &lowered.steps {
            for t in from.transitions() {
                if t.enters != e {
                    continue;
                }
                match cases.iter_mut().find(|(_, c)| c.actions == t.actions) {
                    Some((sources, _)) => sources.push(from.active),
                    None => cases.push((vec![from.active], t)),
                }
            }
        }
        // Entered from one kind of transition only: no test needed, unless
        // a rung's return to step 0 enters it with nothing to do.
        let plain = cases.len() == 1 && !(resets && e == INITIAL_STEP);
        entries.push(Entry {
            name: entry_name(&name(e)),
            flag: name(e),
            step: e,
            cases: cases
                .into_iter()
                .map(|(from, t)| EntryCase {
                    from: if plain { Vec::new() } else { from },
                    actions: statements(symbols, t.actions, t.moves, Spelling::Iec),
                })
                .collect(),
        });
    }
    entries
}

/// The data `sfc.xml.j2` lays out: the IEC context (variables,
/// configuration), the timers and rungs, and the chart.
pub fn render(input: &EmitInput) -> Result<String, templates::TemplateError> {
    let (iec, around) = super::st::parts(input, input.scan_ms)?;
    let lowered = super::lower::lower(input.program, input.symbols);
    let resets = rungs_reset(input);
    let mut layout = Layout {
        input,
        lowered: &lowered,
        elements: Vec::new(),
        next_id: 0,
    };
    // The main column leaves room on its left for the most branches a
    // step has.
    let branches = (0..lowered.steps.len())
        .map(|k| layout.leaving(k, resets).len() as i64 - 1)
        .max()
        .unwrap_or(0);
    let x = LEFT + BRANCH_GAP * branches;
    let mut wire = None;
    let mut y = 20;
    for k in 0..lowered.steps.len() {
        let (next, next_y) = layout.step(k, (x, y), wire.take(), resets);
        wire = next;
        y = next_y;
    }
    let entries = entries(input, &lowered, resets, |e| layout.name(e));
    let chart = Chart {
        elements: layout.elements,
        entries,
        step_var: input.symbols.step_counter.ident.clone(),
    };
    #[derive(Serialize)]
    struct Context<'c> {
        iec: &'c super::st::Context,
        around: &'c super::st::Around,
        chart: &'c Chart,
    }
    input.templates.render(
        "sfc.xml.j2",
        Value::from(Serde(&Context {
            iec: &iec,
            around: &around,
            chart: &chart,
        })),
    )
}
