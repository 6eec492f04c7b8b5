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
//! bottom in scan order. A timer is a TON block, as the ST program's: one
//! rung per timer at the top of the scan calls it with its run flag and
//! clears the flag when the time is up (`t(IN := t_run, PT := t_pt)`); a
//! rung that starts it restarts it in that very scan, so that its time
//! runs from the scan its step fired, as in the simulation: a MOVE writes
//! the preset, and two calls of the same TON, IN off then on, chained
//! through EN/ENO, set its run flag (see `place.rs`).

use minijinja::Value;
use minijinja::value::Serde;
use serde::Serialize;

mod place;

use super::lower::{Lowered, lower};
use super::st::{Internal, Spelling, comment_text};
use super::{EmitInput, templates};
use crate::program::{Action, INITIAL_STEP, Literal, Signal};
use place::{COMMENT_H, ELEMENT_H, ELEMENT_W, PIN_Y, Placer, RAIL_W, RAIL_X, Rung};

/// A timer as its rungs name it: the TON instance, its run flag and its
/// preset variable (the ST program's names).
#[derive(Clone, PartialEq, Eq)]
struct Timer {
    instance: String,
    preset: String,
}

/// What drives a coil besides the rung's contacts.
#[derive(Clone, PartialEq, Eq)]
enum Via {
    /// Straight from the rung's power.
    Power,
    /// The timer's own rung: the TON called in every scan (EN from the
    /// rail: a restart leaves EN off in the instance, and matiec keeps an
    /// FB's EN until a call gives it again), IN from a contact on the run
    /// flag, PT its preset variable; its Q drives the coil.
    Call(Timer),
    /// The timer restarted with `ms` (a MOVE into its preset, the TON
    /// called with IN off then on, chained by EN/ENO): the coil sets its
    /// run flag.
    Restart(Timer, u32),
}

/// One coil before it is placed: the variable and the value it writes.
#[derive(Clone, PartialEq, Eq)]
struct Write {
    variable: String,
    value: bool,
    via: Via,
}

impl Write {
    fn coil(variable: impl Into<String>, value: bool) -> Write {
        Write {
            variable: variable.into(),
            value,
            via: Via::Power,
        }
    }
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
    /// A signal as a variable: a timer reads as its run flag, as in ST.
    fn variable(&self, s: Signal) -> String {
        Spelling::Iec.signal(self.input.symbols, s)
    }

    fn contact(&self, l: &Literal) -> (String, bool) {
        (self.variable(l.signal), l.negated)
    }

    fn timer(&self, timer: Signal) -> Result<Timer, String> {
        let names = self.input.symbols.timer(timer).ok_or_else(|| {
            format!(
                "{} has no run flag and preset",
                self.input.symbols.ident(timer)
            )
        })?;
        Ok(Timer {
            instance: self.input.symbols.ident(timer),
            preset: names.iec_preset.ident.clone(),
        })
    }

    fn writes(&self, actions: &[Action], out: &mut Vec<Write>) -> Result<(), String> {
        for action in actions {
            match *action {
                Action::Reset(Signal::Sequence) => {
                    out.extend(self.lowered.flags.iter().map(|f| Write::coil(f, false)));
                    out.push(Write::coil(self.lowered.flag(INITIAL_STEP), true));
                }
                Action::StartTimer(timer, ms) => out.push(Write {
                    variable: self.variable(timer),
                    value: true,
                    via: Via::Restart(self.timer(timer)?, ms),
                }),
                Action::Set(s) | Action::Reset(s) => {
                    out.push(Write::coil(self.variable(s), action.value()))
                }
            }
        }
        Ok(())
    }

    /// Every rung, in scan order.
    fn plans(&self) -> Result<Vec<Plan>, String> {
        let lowered = &self.lowered;
        let fired = lowered.fired.clone();
        let mut plans = self.timer_calls()?;
        plans.push(Plan {
            comment: "no step has fired yet in this scan".to_string(),
            contacts: Vec::new(),
            writes: vec![Write::coil(&fired, false)],
        });
        for step in &lowered.steps {
            let flag = lowered.flag(step.index).to_string();
            for t in step.transitions() {
                let next = lowered.flag(t.next).to_string();
                let title = format!("STEP {}: {}", step.active, step.active_title);
                let mut contacts = vec![(flag.clone(), false), (fired.clone(), true)];
                contacts.extend(t.condition.iter().map(|l| self.contact(l)));
                let mut writes = Vec::new();
                self.writes(t.actions, &mut writes)?;
                writes.push(Write::coil(&next, true));
                let same = next == flag;
                let comment = step.heading(&t);
                if same {
                    plans.extend(self.retry(comment, contacts, writes));
                    continue;
                }
                plans.push(Plan {
                    comment,
                    contacts,
                    writes,
                });
                plans.push(Plan {
                    comment: format!(
                        "{title}: left for STEP {} (both flags on only after the rung above fired)",
                        t.enters
                    ),
                    contacts: vec![(flag.clone(), false), (next, false)],
                    writes: vec![Write::coil(&fired, true), Write::coil(&flag, false)],
                });
            }
        }
        for r in &self.input.program.rungs {
            let mut writes = Vec::new();
            self.writes(&r.actions, &mut writes)?;
            plans.push(Plan {
                // In the engineer's designations, as in every other body.
                comment: self.input.symbols.explain(&r.comment),
                contacts: r.condition.iter().map(|l| self.contact(l)).collect(),
                writes,
            });
        }
        plans.into_iter().map(Plan::ordered).collect()
    }

    /// A jump back into its own step (a retry): there is no second flag
    /// to clear, so one rung sets `fired`, which switches its own `NOT
    /// fired` contact off. A restart of the timer the step waits on (its
    /// dwell) switches another one off, and Beremiz runs one such coil per
    /// rung: the restarts go to a second rung that sees the step's flag
    /// and `fired` on under the same condition. Only the first rung leaves
    /// them so: an entry from another step restarts that very timer in the
    /// scan it fires, which holds the condition off, and any other
    /// transition clears this step's flag.
    fn retry(
        &self,
        comment: String,
        contacts: Vec<(String, bool)>,
        writes: Vec<Write>,
    ) -> Vec<Plan> {
        let fired = &self.lowered.fired;
        let mut first = Plan {
            comment,
            contacts,
            writes: Vec::new(),
        };
        let (restarts, mut kept): (Vec<Write>, Vec<Write>) =
            writes.into_iter().partition(|w| first.cuts(w));
        kept.push(Write::coil(fired, true));
        first.writes = kept;
        if restarts.is_empty() {
            return vec![first];
        }
        // The same contacts with `fired` on in place of off (the second).
        let mut contacts = first.contacts.clone();
        contacts[1] = (fired.clone(), false);
        let second = Plan {
            comment: format!(
                "{}: restarts its timer (the rung above fired)",
                first.comment
            ),
            contacts,
            writes: restarts,
        };
        vec![first, second]
    }

    /// The timers' rungs, first in the scan as the ST program calls them:
    /// the TON runs while its run flag is on, and its Q clears the flag.
    fn timer_calls(&self) -> Result<Vec<Plan>, String> {
        let program = self.input.program;
        program
            .timers
            .iter()
            .map(|&t| {
                let timer = self.timer(t)?;
                let run = self.variable(t);
                Ok(Plan {
                    comment: format!(
                        "{} runs while {run} is set and clears it when its preset has elapsed",
                        timer.instance
                    ),
                    // The run flag's contact feeds the TON's IN, not the
                    // rung: the TON is called in every scan.
                    contacts: Vec::new(),
                    writes: vec![Write {
                        variable: run,
                        value: false,
                        via: Via::Call(timer),
                    }],
                })
            })
            .collect()
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
    /// The TON instances, the POU's own variables.
    instances: Vec<String>,
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
    let mut placer = Placer::new(&plans);
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
    let instances = input
        .program
        .timers
        .iter()
        .map(|&t| symbols.ident(t))
        .collect();
    Ok(Ladder {
        rungs,
        instances,
        flags,
        step_counter: symbols.step_counter.ident.clone(),
        element_w: ELEMENT_W,
        element_h: ELEMENT_H,
        pin_y: PIN_Y,
        rail_w: RAIL_W,
        rail_x: RAIL_X,
        comment_w: placer.right_x() - RAIL_X,
        comment_h: COMMENT_H,
    })
}

/// The ladder's variables besides its I/O and its TON instances (which are
/// the POU's own), as a global variable list declares them: the ST
/// program's memories, run flags and presets, then the step flags and
/// `fired`. `internals` are the ST program's.
pub(super) fn globals(
    input: &EmitInput,
    internals: Vec<Internal>,
) -> Result<Vec<Internal>, String> {
    let ladder = ladder(input)?;
    let flags = ladder.flags.into_iter().map(|f| Internal {
        ident: f.ident,
        data_type: "BOOL",
        derived: false,
        initial: Some(if f.initial { "TRUE" } else { "FALSE" }.to_string()),
        comment: f.comment,
    });
    Ok(internals
        .into_iter()
        .filter(|v| v.ident != ladder.step_counter && v.data_type != "TON")
        .chain(flags)
        .collect())
}

/// Renders `NAME.ld.xml`: the IEC context (variables, configuration) and
/// the rungs.
pub fn render(input: &EmitInput) -> Result<String, templates::TemplateError> {
    let (iec, _) = super::st::parts(input, input.scan_ms)?;
    // A rung that would switch two of its own contacts off is not the
    // engineer's to fix: reaching this is a bug.
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
