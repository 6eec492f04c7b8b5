//! The GRAFCET (IEC 60848) of the step program, as an SVG picture drawn by
//! steptable's own top-to-bottom layout: the initial step 0 in a double
//! box, every step with its stored actions beside it, every transition with
//! its receptivity, a table step acting in several branches as an AND
//! divergence and convergence (double lines) with one step per branch,
//! jumps as a selection divergence whose transitions end in an arrow to
//! their target step, the end of the cycle as the line back to step 0, and
//! the mode and safety logic in a note. Step numbers are the SFC numbers of
//! every other output ([`crate::program::StepProgram::step_entered`]).
//!
//! Every box and label is placed on a grid of rows, one below the other, so
//! none overlaps another whatever the table; text widths are estimated from
//! the character count at a generous width per character.

mod svg;
mod words;

use std::fmt::Write;

pub use svg::svg_of;
pub use words::Term;
use words::{actions, branches, line_text, mode_note, panel_lines, receptivity, table_step};

use super::EmitInput;
use super::diagram::Tenths;
use crate::program::{INITIAL_STEP, StepKind};

/// The centre line of the sequence.
const MAIN_X: f64 = 96.0;
/// The line back to step 0 runs down the left edge.
const LOOP_X: f64 = 30.0;
const BOX: f64 = 36.0;
const LINE: f64 = 16.0;
const FONT: f64 = 12.0;
/// Width per character at 12 px, wider than Helvetica's and DejaVu's
/// average so that an estimated box holds its text in any sans font.
const CHAR_W: f64 = 7.4;

/// What the picture is made of, so that tests and the report can measure
/// it as well as draw it.
#[derive(Debug, Clone, PartialEq)]
pub enum Shape {
    /// A step box (`double` for the initial step), its id (`3`, `4.2`).
    Step {
        x: f64,
        y: f64,
        id: String,
        double: bool,
    },
    /// A rectangle with text lines: the actions of a step, or the note.
    Panel {
        x: f64,
        y: f64,
        w: f64,
        h: f64,
        class: &'static str,
        lines: Vec<String>,
        /// The whole text of lines cut to [`words::PANEL_LINE`], for a tooltip.
        tip: Option<String>,
    },
    /// A transition bar at (x, y), its receptivity to its right, and
    /// which transition it is (`t3`, `t3j1` for a jump).
    Transition {
        x: f64,
        y: f64,
        id: String,
        lines: Vec<Vec<Term>>,
    },
    /// A link or a double (AND) line.
    Path {
        points: Vec<(f64, f64)>,
        double: bool,
        arrow: bool,
    },
    /// A free label (a jump's target, the title).
    Label {
        x: f64,
        y: f64,
        text: String,
        size: f64,
    },
}

/// An axis-aligned box, `(left, top, right, bottom)`.
pub type Bounds = (f64, f64, f64, f64);

/// How wide `chars` characters at `size` px are taken to be.
pub fn text_width(text: &str, size: f64) -> f64 {
    text.chars().count() as f64 * CHAR_W * size / FONT
}

impl Shape {
    /// The boxes this shape covers that nothing else may overlap: a step's
    /// box, a panel, a transition's receptivity text, a label.
    pub fn bounds(&self) -> Vec<Bounds> {
        match self {
            Shape::Step { x, y, .. } => vec![(x - BOX / 2.0, *y, x + BOX / 2.0, y + BOX)],
            Shape::Panel { x, y, w, h, .. } => vec![(*x, *y, x + w, y + h)],
            Shape::Transition { x, y, lines, .. } => {
                let left = x + 22.0;
                let width = lines
                    .iter()
                    .map(|l| text_width(&line_text(l), FONT))
                    .fold(0.0, f64::max);
                let top = y - FONT * 0.5;
                vec![(left, top, left + width, top + lines.len() as f64 * LINE)]
            }
            Shape::Path { .. } => Vec::new(),
            Shape::Label { x, y, text, size } => {
                vec![(
                    *x,
                    y - size * 0.85,
                    x + text_width(text, *size),
                    y + size * 0.3,
                )]
            }
        }
    }
}

/// The laid-out chart.
#[derive(Debug, Clone)]
pub struct Chart {
    pub shapes: Vec<Shape>,
    pub width: f64,
    pub height: f64,
}

/// Lays the GRAFCET of `input`'s program out.
pub fn chart(input: &EmitInput) -> Chart {
    let mut layout = Layout::default();
    layout.label(
        LOOP_X - 14.0,
        26.0,
        format!("GRAFCET: {}", super::one_line(input.name)),
        16.0,
    );
    layout.y = 44.0;
    let note = mode_note(input.program, input.symbols);
    if !note.is_empty() {
        let mut lines = vec!["Modes and safety (act on the chart from outside):".to_string()];
        lines.extend(note);
        layout.panel(LOOP_X - 14.0, layout.y, "note", lines);
        layout.y += 16.0;
    }
    let entry = layout.y + 14.0;
    layout.y = entry + 20.0;
    layout.step_row(
        INITIAL_STEP.to_string(),
        &[(None, vec![crate::program::INITIAL_TITLE.to_string()])],
        true,
    );
    let program = input.program;
    for (index, step) in program.steps.iter().enumerate() {
        layout.transition(input, index);
        if step.kind == StepKind::EndOfCycle {
            layout.back_to_start(entry);
            continue;
        }
        let Some(row) = table_step(step, input.table) else {
            continue;
        };
        let number = program.step_entered(index);
        let title = input.symbols.step(index).map(|n| n.title.clone());
        let mut caption: Vec<String> = title.into_iter().collect();
        for (from, jump) in jumps_into(input, index) {
            caption.push(format!("also from step {from}: {}", jump));
        }
        let used = branches(row);
        let boxes: Vec<(Option<String>, Vec<String>)> = if used.len() < 2 {
            let mut lines = caption;
            lines.extend(actions(step, row, None, true, input.symbols));
            vec![(None, lines)]
        } else {
            used.iter()
                .enumerate()
                .map(|(k, b)| {
                    let mut lines = if k == 0 { caption.clone() } else { Vec::new() };
                    lines.extend(actions(step, row, Some(*b), k == 0, input.symbols));
                    (Some(format!("{number}.{}", b + 1)), lines)
                })
                .collect()
        };
        layout.parallel_steps(number, boxes);
    }
    layout.finish()
}

/// The jumps that enter `program.steps[index]`'s step from elsewhere: the
/// step they leave and their notation.
fn jumps_into(input: &EmitInput, index: usize) -> Vec<(usize, String)> {
    let program = input.program;
    program
        .steps
        .iter()
        .enumerate()
        .flat_map(|(at, s)| s.jumps.iter().map(move |j| (at, j)))
        .filter(|(_, j)| j.fires == index)
        .map(|(at, j)| (program.step_in(at), j.title.clone()))
        .collect()
}

#[derive(Default)]
struct Layout {
    shapes: Vec<Shape>,
    y: f64,
    /// Where the links leave the boxes of the last step row.
    sources: Vec<f64>,
    right: f64,
}

impl Layout {
    fn push(&mut self, shape: Shape) {
        for (_, _, right, _) in shape.bounds() {
            self.right = self.right.max(right);
        }
        self.shapes.push(shape);
    }

    fn label(&mut self, x: f64, y: f64, text: String, size: f64) {
        self.push(Shape::Label { x, y, text, size });
    }

    fn link(&mut self, points: Vec<(f64, f64)>, arrow: bool) {
        self.push(Shape::Path {
            points,
            double: false,
            arrow,
        });
    }

    /// A panel of text lines with its top left at (x, y); the row grows
    /// below it.
    fn panel(&mut self, x: f64, y: f64, class: &'static str, lines: Vec<String>) -> f64 {
        // A long step comment or actuator name would stretch the panel
        // over the page: it is cut, and the whole text is the tooltip.
        let (lines, tip) = panel_lines(lines);
        let w = lines
            .iter()
            .map(|l| text_width(l, FONT))
            .fold(0.0, f64::max)
            + 12.0;
        let h = (lines.len() as f64 * LINE + 8.0).max(BOX);
        self.push(Shape::Panel {
            x,
            y,
            w,
            h,
            class,
            lines,
            tip,
        });
        self.y = self.y.max(y + h);
        w
    }

    /// One step (or an AND divergence of one step per branch) at the
    /// current row: each box with its actions panel to its right.
    fn step_row(&mut self, id: String, boxes: &[(Option<String>, Vec<String>)], double: bool) {
        let top = self.y;
        let mut x = MAIN_X;
        let mut sources = Vec::new();
        let mut bottom = top + BOX;
        for (k, (own, lines)) in boxes.iter().enumerate() {
            let id = own.clone().unwrap_or_else(|| id.clone());
            self.push(Shape::Step {
                x,
                y: top,
                id,
                double: double && k == 0,
            });
            sources.push(x);
            let mut width = 0.0;
            if !lines.is_empty() {
                let left = x + BOX / 2.0 + 14.0;
                self.link(
                    vec![(x + BOX / 2.0, top + BOX / 2.0), (left, top + BOX / 2.0)],
                    false,
                );
                let saved = self.y;
                width = self.panel(left, top, "actions", lines.clone()) + 14.0;
                bottom = bottom.max(self.y);
                self.y = saved;
            }
            x += BOX + width + 40.0;
        }
        self.y = bottom;
        self.sources = sources;
    }

    fn parallel_steps(&mut self, number: usize, boxes: Vec<(Option<String>, Vec<String>)>) {
        if boxes.len() < 2 {
            self.link(vec![(MAIN_X, self.y), (MAIN_X, self.y + 18.0)], false);
            self.y += 18.0;
            return self.step_row(number.to_string(), &boxes, false);
        }
        // The AND divergence: a double line over every branch's step.
        let at = self.y + 12.0;
        self.link(vec![(MAIN_X, self.y), (MAIN_X, at)], false);
        let row_y = at + 14.0;
        let start = self.shapes.len();
        self.y = row_y;
        self.step_row(number.to_string(), &boxes, false);
        let xs = self.sources.clone();
        let last = xs.last().copied().unwrap_or(MAIN_X);
        self.shapes.insert(
            start,
            Shape::Path {
                points: vec![(MAIN_X - 20.0, at), (last + 20.0, at)],
                double: true,
                arrow: false,
            },
        );
        for x in xs {
            self.link(vec![(x, at + 3.0), (x, row_y)], false);
        }
    }

    /// The transition `program.steps[index]` below the step it leaves, with
    /// its jumps beside it as a selection divergence.
    fn transition(&mut self, input: &EmitInput, index: usize) {
        let step = &input.program.steps[index];
        // An AND convergence closes parallel steps before their transition.
        if self.sources.len() > 1 {
            let at = self.y + 12.0;
            for x in self.sources.clone() {
                self.link(vec![(x, self.y), (x, at - 3.0)], false);
            }
            let last = *self.sources.last().expect("two sources");
            self.push(Shape::Path {
                points: vec![(MAIN_X - 20.0, at), (last + 20.0, at)],
                double: true,
                arrow: false,
            });
            self.y = at + 3.0;
        }
        let mut main = receptivity(&step.condition, input.symbols, input.table, input.program);
        // The program tests its jumps first: the sequence goes on only when
        // no jump's input holds, which makes the alternatives exclusive.
        for jump in &step.jumps {
            if let Some(term) = words::jump_input(jump, input.symbols) {
                main.last_mut().expect("one line at least").push(term);
            }
        }
        let jumps: Vec<(String, Vec<Vec<Term>>, usize)> = step
            .jumps
            .iter()
            .enumerate()
            .map(|(k, j)| {
                let mut cond = receptivity(&j.condition, input.symbols, input.table, input.program);
                // A later jump is tested only when no earlier one fired.
                for earlier in &step.jumps[..k] {
                    if let Some(term) = words::jump_input(earlier, input.symbols) {
                        cond.last_mut().expect("one line at least").push(term);
                    }
                }
                (
                    format!("t{index}j{}", k + 1),
                    cond,
                    input.program.step_entered(j.fires),
                )
            })
            .collect();
        let mut x = MAIN_X;
        let mut columns = Vec::new();
        let widest = |lines: &Vec<Vec<Term>>| {
            lines
                .iter()
                .map(|l| text_width(&line_text(l), FONT))
                .fold(0.0, f64::max)
        };
        columns.push((x, format!("t{index}"), main.clone(), None));
        let mut width = widest(&main);
        for (id, lines, target) in jumps {
            x += 22.0 + width + 40.0;
            width = widest(&lines);
            columns.push((x, id, lines, Some(target)));
        }
        let rows = columns.iter().map(|c| c.2.len()).max().unwrap_or(1) as f64;
        let top = self.y;
        if columns.len() > 1 {
            // The selection divergence: a single line over the alternatives.
            let last = columns.last().expect("jumps").0;
            self.link(vec![(MAIN_X, top), (MAIN_X, top + 8.0)], false);
            self.link(vec![(MAIN_X, top + 8.0), (last, top + 8.0)], false);
        }
        let bar = top + 22.0;
        for (x, id, lines, target) in columns {
            let from = if x == MAIN_X { top } else { top + 8.0 };
            self.link(vec![(x, from), (x, bar + rows * LINE)], false);
            self.push(Shape::Transition {
                x,
                y: bar,
                id,
                lines,
            });
            if let Some(target) = target {
                let end = bar + rows * LINE + 14.0;
                self.link(vec![(x, bar + rows * LINE), (x, end)], true);
                self.label(x - 8.0, end + 14.0, format!("→ step {target}"), FONT);
            }
        }
        self.y = bar + rows * LINE;
        if !step.jumps.is_empty() {
            // Room for the jumps' arrows and targets below the bars.
            self.link(vec![(MAIN_X, self.y), (MAIN_X, self.y + 32.0)], false);
            self.y += 32.0;
        }
        self.sources = vec![MAIN_X];
    }

    /// The closing transition leads back to step 0: down, left along the
    /// edge, up, and into step 0 from above.
    fn back_to_start(&mut self, entry: f64) {
        let down = self.y + 16.0;
        self.link(
            vec![
                (MAIN_X, self.y),
                (MAIN_X, down),
                (LOOP_X, down),
                (LOOP_X, entry),
                (MAIN_X, entry),
                (MAIN_X, entry + 20.0),
            ],
            true,
        );
        self.y = down;
        self.sources.clear();
    }

    fn finish(self) -> Chart {
        Chart {
            width: (self.right + 24.0).max(320.0).ceil(),
            height: (self.y + 24.0).ceil(),
            shapes: self.shapes,
        }
    }
}

/// The GRAFCET as a standalone SVG document.
pub fn render_svg(input: &EmitInput) -> String {
    svg_of(&chart(input))
}
