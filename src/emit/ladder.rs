//! The step program as a Ladder (LD) body in PLCopen XML (`NAME.ld.xml`),
//! rendered from the shared lowering, with the full geometry Beremiz and
//! the OpenPLC Editor v3 need to open it (integer sizes on every element,
//! every wire with its points, the first at the input and the last at the
//! source's output).
//!
//! The sequence keeps a BOOL flag per step (`step_0` at rest, `step_k`
//! while table step k's moves run) and the `fired` bit, as the STEP 7 and
//! Studio 5000 ladders do. Beremiz turns each coil into its own
//! `IF rung THEN v := TRUE/FALSE` and reads the rung's contacts again for
//! every coil, in the order of the coils' height: a coil that writes one
//! of its rung's contacts the other way cuts the power of every coil after
//! it. So a rung has at most one such coil, drawn last, and a transition
//! is two rungs: the first (flag, not fired, condition) runs the actions
//! of the step entered and sets its flag; the second sees the two flags
//! on together, which only that first rung leaves, sets `fired` and
//! clears the step left.
//!
//! Beremiz orders the coils by their height, so the rungs are placed top to
//! bottom in scan order. Timers have no rung here: a program with one is
//! refused before rendering (E043), since it needs a TON restarted in the
//! scan its step fires, which coils alone cannot draw.

use minijinja::Value;
use minijinja::value::Serde;
use serde::Serialize;

use super::lower::{Lowered, lower};
use super::st::comment_text;
use super::{EmitInput, templates};
use crate::program::{Action, INITIAL_STEP, Literal, Signal};

/// Element sizes and spacing, in PLCopen units (Beremiz's defaults for
/// contacts and coils: 21 × 15, a power rail 3 wide).
const ELEMENT_W: i64 = 21;
const ELEMENT_H: i64 = 15;
/// The height of an element's connection points over its top.
const PIN_Y: i64 = 8;
const RAIL_W: i64 = 3;
const RAIL_X: i64 = 20;
const CONTACT_STEP: i64 = 50;
const ROW: i64 = 40;
const COMMENT_H: i64 = 30;

/// A connection: the element it comes from and its points, the first at
/// the input, the last at the source's output.
#[derive(Serialize, Clone)]
struct Wire {
    from: u64,
    points: Vec<(i64, i64)>,
}

#[derive(Serialize)]
struct Contact {
    id: u64,
    x: i64,
    y: i64,
    variable: String,
    negated: bool,
    input: Wire,
}

#[derive(Serialize)]
struct Coil {
    id: u64,
    x: i64,
    y: i64,
    variable: String,
    /// `set` or `reset`.
    storage: &'static str,
    input: Wire,
}

#[derive(Serialize)]
struct Rung {
    comment_id: u64,
    comment: String,
    comment_y: i64,
    left_id: u64,
    left_y: i64,
    height: i64,
    contacts: Vec<Contact>,
    coils: Vec<Coil>,
    right_id: u64,
    right_x: i64,
    right_inputs: Vec<(i64, Wire)>,
}

/// One coil before it is placed: the variable and the value it writes.
#[derive(Clone, PartialEq, Eq)]
struct Write {
    variable: String,
    value: bool,
}

/// A rung before it is placed.
struct Plan {
    comment: String,
    contacts: Vec<(String, bool)>,
    writes: Vec<Write>,
}

impl Plan {
    /// Whether `w` switches one of the rung's own contacts off.
    fn cuts(&self, w: &Write) -> bool {
        self.contacts
            .iter()
            .any(|(v, negated)| *v == w.variable && w.value == *negated)
    }

    /// The coils in the order Beremiz must run them: those that leave the
    /// rung's power as it is first, in the program's order, then the one
    /// that cuts it. Two that cut it cannot be one rung.
    fn ordered(mut self) -> Result<Plan, String> {
        let (cut, keep): (Vec<Write>, Vec<Write>) =
            self.writes.iter().cloned().partition(|w| self.cuts(w));
        if cut.len() > 1 {
            return Err(format!(
                "the rung \"{}\" switches {} of its own contacts off: Ladder cannot draw it as one rung",
                self.comment,
                cut.len()
            ));
        }
        self.writes = keep.into_iter().chain(cut).collect();
        Ok(self)
    }
}

struct Names<'a> {
    input: &'a EmitInput<'a>,
    lowered: Lowered<'a>,
}

impl Names<'_> {
    fn contact(&self, l: &Literal) -> (String, bool) {
        (self.input.symbols.ident(l.signal), l.negated)
    }

    fn writes(&self, actions: &[Action], out: &mut Vec<Write>) -> Result<(), String> {
        for action in actions {
            match *action {
                Action::Reset(Signal::Sequence) => {
                    out.extend(self.lowered.flags.iter().map(|f| Write {
                        variable: f.clone(),
                        value: false,
                    }));
                    out.push(Write {
                        variable: self.lowered.flag(INITIAL_STEP).to_string(),
                        value: true,
                    });
                }
                Action::StartTimer(timer, _) => {
                    return Err(format!(
                        "{} is a timer: the Ladder body has none",
                        self.input.symbols.ident(timer)
                    ));
                }
                Action::Set(s) | Action::Reset(s) => out.push(Write {
                    variable: self.input.symbols.ident(s),
                    value: action.value(),
                }),
            }
        }
        Ok(())
    }

    /// Every rung, in scan order.
    fn plans(&self) -> Result<Vec<Plan>, String> {
        let lowered = &self.lowered;
        let fired = lowered.fired.clone();
        let mut plans = vec![Plan {
            comment: "no step has fired yet in this scan".to_string(),
            contacts: Vec::new(),
            writes: vec![Write {
                variable: fired.clone(),
                value: false,
            }],
        }];
        for step in &lowered.steps {
            let flag = lowered.flag(step.index).to_string();
            for t in step.transitions() {
                let next = lowered.flag(t.next).to_string();
                let title = format!("STEP {}: {}", step.active, step.active_title);
                let mut contacts = vec![(flag.clone(), false), (fired.clone(), true)];
                contacts.extend(t.condition.iter().map(|l| self.contact(l)));
                let mut writes = Vec::new();
                self.writes(t.actions, &mut writes)?;
                writes.push(Write {
                    variable: next.clone(),
                    value: true,
                });
                let same = next == flag;
                if same {
                    writes.push(Write {
                        variable: fired.clone(),
                        value: true,
                    });
                }
                plans.push(Plan {
                    comment: format!("{title}; {}", t.comment),
                    contacts,
                    writes,
                });
                if !same {
                    plans.push(Plan {
                        comment: format!(
                            "{title}: left for STEP {} (both flags on only after the rung above fired)",
                            t.enters
                        ),
                        contacts: vec![(flag.clone(), false), (next, false)],
                        writes: vec![
                            Write {
                                variable: fired.clone(),
                                value: true,
                            },
                            Write {
                                variable: flag.clone(),
                                value: false,
                            },
                        ],
                    });
                }
            }
        }
        for r in &self.input.program.rungs {
            let mut writes = Vec::new();
            self.writes(&r.actions, &mut writes)?;
            plans.push(Plan {
                comment: r.comment.clone(),
                contacts: r.condition.iter().map(|l| self.contact(l)).collect(),
                writes,
            });
        }
        plans.into_iter().map(Plan::ordered).collect()
    }
}

/// Places the rungs one under the other; every coil in one column.
struct Placer {
    next_id: u64,
    y: i64,
    coil_x: i64,
}

impl Placer {
    fn id(&mut self) -> u64 {
        self.next_id += 1;
        self.next_id
    }

    fn rung(&mut self, plan: Plan) -> Rung {
        let comment_id = self.id();
        let comment_y = self.y;
        let line = self.y + COMMENT_H + 30;
        let rows = plan.writes.len().max(1) as i64;
        let left_id = self.id();
        let left_out = (RAIL_X + RAIL_W, line);
        let mut source = (left_id, left_out);
        let mut contacts = Vec::new();
        for (i, (variable, negated)) in plan.contacts.into_iter().enumerate() {
            let id = self.id();
            let x = RAIL_X + 60 + CONTACT_STEP * i as i64;
            contacts.push(Contact {
                id,
                x,
                y: line - PIN_Y,
                variable,
                negated,
                input: Wire {
                    from: source.0,
                    points: vec![(x, line), source.1],
                },
            });
            source = (id, (x + ELEMENT_W, line));
        }
        let right_x = self.coil_x + ELEMENT_W + 40;
        let mut coils = Vec::new();
        let mut right_inputs = Vec::new();
        for (j, w) in plan.writes.into_iter().enumerate() {
            let id = self.id();
            let y = line + ROW * j as i64;
            let mut points = vec![(self.coil_x, y)];
            if j > 0 {
                points.push((self.coil_x - 20, y));
                points.push((self.coil_x - 20, line));
            }
            points.push(source.1);
            coils.push(Coil {
                id,
                x: self.coil_x,
                y: y - PIN_Y,
                variable: w.variable,
                storage: if w.value { "set" } else { "reset" },
                input: Wire {
                    from: source.0,
                    points,
                },
            });
            right_inputs.push((
                y - (line - 20),
                Wire {
                    from: id,
                    points: vec![(right_x, y), (self.coil_x + ELEMENT_W, y)],
                },
            ));
        }
        let right_id = self.id();
        let height = ROW * rows;
        self.y = line - 20 + height + 20;
        Rung {
            comment_id,
            comment: comment_text(&plan.comment),
            comment_y,
            left_id,
            left_y: line - 20,
            height,
            contacts,
            coils,
            right_id,
            right_x,
            right_inputs,
        }
    }
}

#[derive(Serialize)]
struct Flag {
    ident: String,
    initial: bool,
    comment: String,
}

#[derive(Serialize)]
struct Ladder {
    rungs: Vec<Rung>,
    flags: Vec<Flag>,
    step_counter: String,
    element_w: i64,
    element_h: i64,
    pin_y: i64,
    rail_w: i64,
    rail_x: i64,
    comment_w: i64,
    comment_h: i64,
}

/// The rungs of the Ladder body, laid out, or why the program cannot be one.
fn ladder(input: &EmitInput) -> Result<Ladder, String> {
    let names = Names {
        input,
        lowered: lower(input.program, input.symbols),
    };
    let plans = names.plans()?;
    let widest = plans.iter().map(|p| p.contacts.len()).max().unwrap_or(0) as i64;
    let mut placer = Placer {
        next_id: 0,
        y: 20,
        coil_x: RAIL_X + 60 + CONTACT_STEP * widest + 40,
    };
    let rungs: Vec<Rung> = plans.into_iter().map(|p| placer.rung(p)).collect();
    let symbols = input.symbols;
    let mut flags: Vec<Flag> = (0..names.lowered.steps.len())
        .map(|k| Flag {
            ident: names.lowered.flag(k).to_string(),
            initial: names.lowered.steps[k].active == INITIAL_STEP,
            comment: comment_text(
                &symbols
                    .step(k)
                    .map(|s| s.flag.comment.clone())
                    .unwrap_or_default(),
            ),
        })
        .collect();
    flags.push(Flag {
        ident: names.lowered.fired.clone(),
        initial: false,
        comment: comment_text(&symbols.fired.comment),
    });
    Ok(Ladder {
        rungs,
        flags,
        step_counter: symbols.step_counter.ident.clone(),
        element_w: ELEMENT_W,
        element_h: ELEMENT_H,
        pin_y: PIN_Y,
        rail_w: RAIL_W,
        rail_x: RAIL_X,
        comment_w: placer.coil_x + ELEMENT_W + 40 - RAIL_X,
        comment_h: COMMENT_H,
    })
}

/// Renders `NAME.ld.xml`: the IEC context (variables, configuration) and
/// the rungs.
pub fn render(input: &EmitInput) -> Result<String, templates::TemplateError> {
    let (iec, _) = super::st::parts(input, input.scan_ms)?;
    // Refused before rendering (E043): reaching this is a bug, not the
    // engineer's to fix.
    let ladder = ladder(input).map_err(|detail| templates::TemplateError {
        file: "ld.xml.j2".to_string(),
        user: false,
        line: None,
        detail,
    })?;
    #[derive(Serialize)]
    struct Context<'c> {
        iec: &'c super::st::Context,
        ld: &'c Ladder,
    }
    input.templates.render(
        "ld.xml.j2",
        Value::from(Serde(&Context {
            iec: &iec,
            ld: &ladder,
        })),
    )
}
