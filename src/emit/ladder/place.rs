//! The rungs laid out: every element with its integer position and size,
//! every wire with its points (the first at the input, the last at the
//! source's output), the rungs one under the other in scan order.
//!
//! A timer's elements sit between the contacts and the coil column. Beremiz
//! calls a function block when the coil it drives is computed, so each
//! block feeds a coil and runs at that coil's height in the scan: the
//! timer's own rung is contact `run` → TON (IN; PT from the preset
//! variable) → Q → reset coil `run`; a restart is MOVE (EN from the rung,
//! IN the preset as a TIME literal, OUT into the preset variable) → ENO →
//! TON (IN := FALSE) → ENO → the same TON (IN := TRUE) → ENO → set coil
//! `run`. The restart's TON calls take the literal as PT: the MOVE's OUT
//! reaches the preset variable only after them, at the preset's own height.

use serde::Serialize;

use super::{Plan, Timer, Via};
use crate::emit::st::comment_text;

/// Element sizes and spacing, in PLCopen units (Beremiz's defaults for
/// contacts and coils: 21 × 15, a power rail 3 wide).
pub(super) const ELEMENT_W: i64 = 21;
pub(super) const ELEMENT_H: i64 = 15;
/// The height of an element's connection points over its top.
pub(super) const PIN_Y: i64 = 8;
pub(super) const RAIL_W: i64 = 3;
pub(super) const RAIL_X: i64 = 20;
const CONTACT_STEP: i64 = 50;
const ROW: i64 = 40;
pub(super) const COMMENT_H: i64 = 30;
/// A block: its width, its first pin under its top and the pitch of the
/// next; a variable's box (a literal or the preset) and the room between
/// a block and the block or coil after it.
const BLOCK_W: i64 = 60;
const BLOCK_PIN: i64 = 30;
const PIN_PITCH: i64 = 20;
const VAR_W: i64 = 80;
const VAR_H: i64 = 20;
const GAP: i64 = 110;

/// A connection: the element it comes from (and which of a block's
/// outputs), its points, the first at the input, the last at the source's
/// output.
#[derive(Serialize, Clone)]
pub(super) struct Wire {
    from: u64,
    formal: Option<&'static str>,
    points: Vec<(i64, i64)>,
}

impl Wire {
    fn from(source: Source, points: Vec<(i64, i64)>) -> Wire {
        let mut points = points;
        points.push(source.at);
        Wire {
            from: source.id,
            formal: source.formal,
            points,
        }
    }
}

/// Where a wire may start: an element's output.
#[derive(Clone, Copy)]
struct Source {
    id: u64,
    formal: Option<&'static str>,
    at: (i64, i64),
}

#[derive(Serialize)]
pub(super) struct Contact {
    id: u64,
    x: i64,
    y: i64,
    variable: String,
    negated: bool,
    input: Wire,
}

#[derive(Serialize)]
pub(super) struct Coil {
    id: u64,
    x: i64,
    y: i64,
    variable: String,
    /// `set` or `reset`.
    storage: &'static str,
    input: Wire,
}

/// A block's input: its formal parameter, height under the block's top
/// and wire.
#[derive(Serialize)]
pub(super) struct Pin {
    name: &'static str,
    y: i64,
    input: Option<Wire>,
}

#[derive(Serialize)]
pub(super) struct Block {
    id: u64,
    x: i64,
    y: i64,
    width: i64,
    height: i64,
    type_name: &'static str,
    instance: Option<String>,
    inputs: Vec<Pin>,
    outputs: Vec<Pin>,
}

/// An `inVariable` (a literal or a variable read) or an `outVariable`
/// (a variable written), with the wire into it for the latter.
#[derive(Serialize)]
pub(super) struct Var {
    id: u64,
    x: i64,
    y: i64,
    width: i64,
    height: i64,
    expression: String,
    input: Option<Wire>,
}

#[derive(Serialize)]
pub(super) struct Rung {
    comment_id: u64,
    comment: String,
    comment_y: i64,
    left_id: u64,
    left_y: i64,
    /// The rail's output under its top: the rung's line.
    left_out: i64,
    height: i64,
    contacts: Vec<Contact>,
    coils: Vec<Coil>,
    blocks: Vec<Block>,
    in_vars: Vec<Var>,
    out_vars: Vec<Var>,
    right_id: u64,
    right_x: i64,
    right_inputs: Vec<(i64, Wire)>,
}

/// The room a row of a rung takes over and under its line.
fn extent(via: &Via) -> (i64, i64) {
    match via {
        Via::Power => (ROW / 2, ROW / 2),
        Via::Call(_) => (40, 70),
        Via::Restart(..) => (40, 90),
    }
}

/// Places the rungs one under the other; every coil in one column.
pub(super) struct Placer {
    next_id: u64,
    y: i64,
    /// Where the first block of a timer's row stands.
    blocks_x: i64,
    coil_x: i64,
}

impl Placer {
    /// A placer with room for the widest rung's contacts, and for a
    /// timer's blocks if any rung has one.
    pub(super) fn new(plans: &[Plan]) -> Placer {
        let widest = plans.iter().map(|p| p.contacts.len()).max().unwrap_or(0) as i64;
        let contacts_end = RAIL_X + 60 + CONTACT_STEP * widest;
        let timed = plans
            .iter()
            .flat_map(|p| &p.writes)
            .any(|w| w.via != Via::Power);
        let blocks_x = contacts_end + VAR_W + 40;
        Placer {
            next_id: 0,
            y: 20,
            blocks_x,
            coil_x: if timed {
                blocks_x + 3 * BLOCK_W + 2 * (VAR_W + GAP) + 40
            } else {
                contacts_end + 40
            },
        }
    }

    /// The right power rails' column.
    pub(super) fn right_x(&self) -> i64 {
        self.coil_x + ELEMENT_W + 40
    }

    fn id(&mut self) -> u64 {
        self.next_id += 1;
        self.next_id
    }

    pub(super) fn rung(&mut self, plan: Plan) -> Rung {
        let comment_id = self.id();
        let comment_y = self.y;
        let extents: Vec<(i64, i64)> = plan.writes.iter().map(|w| extent(&w.via)).collect();
        let (above, _) = extents.first().copied().unwrap_or((ROW / 2, ROW / 2));
        let line = self.y + COMMENT_H + 10 + above;
        let mut rows = Vec::new();
        let mut y = line;
        for (j, (up, down)) in extents.iter().enumerate() {
            if j > 0 {
                y += extents[j - 1].1 + up;
            }
            rows.push(y);
            let _ = down;
        }
        let left_y = line - above;
        let height = rows
            .last()
            .zip(extents.last())
            .map_or(ROW, |(y, e)| y + e.1 - left_y);
        let left_id = self.id();
        let mut source = Source {
            id: left_id,
            formal: None,
            at: (RAIL_X + RAIL_W, line),
        };
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
                input: Wire::from(source, vec![(x, line)]),
            });
            source = Source {
                id,
                formal: None,
                at: (x + ELEMENT_W, line),
            };
        }
        let timed = plan.writes.iter().any(|w| w.via != Via::Power);
        let mut drawn = Drawn::default();
        let right_x = self.right_x();
        let mut right_inputs = Vec::new();
        for (w, &y) in plan.writes.into_iter().zip(&rows) {
            // A row under the line leaves it just after the contacts in a
            // rung with blocks (the line runs through them), at the coil
            // column otherwise.
            let turn = if timed {
                source.at.0 + 10
            } else {
                self.coil_x - 20
            };
            let route = |to: (i64, i64)| {
                let mut points = vec![to];
                if y != line {
                    points.push((turn, y));
                    points.push((turn, line));
                }
                Wire::from(source, points)
            };
            let (feed, y) = match &w.via {
                Via::Power => (route((self.coil_x, y)), y),
                Via::Call(timer) => self.call(&mut drawn, timer, &w.variable, y, route),
                Via::Restart(timer, ms) => (self.restart(&mut drawn, timer, *ms, y, route), y),
            };
            let id = self.id();
            drawn.coils.push(Coil {
                id,
                x: self.coil_x,
                y: y - PIN_Y,
                variable: w.variable,
                storage: if w.value { "set" } else { "reset" },
                input: feed,
            });
            right_inputs.push((
                y - left_y,
                Wire::from(
                    Source {
                        id,
                        formal: None,
                        at: (self.coil_x + ELEMENT_W, y),
                    },
                    vec![(right_x, y)],
                ),
            ));
        }
        let right_id = self.id();
        self.y = left_y + height + 20;
        Rung {
            comment_id,
            comment: comment_text(&plan.comment),
            comment_y,
            left_id,
            left_y,
            left_out: line - left_y,
            height,
            contacts: contacts.into_iter().chain(drawn.contacts).collect(),
            coils: drawn.coils,
            blocks: drawn.blocks,
            in_vars: drawn.in_vars,
            out_vars: drawn.out_vars,
            right_id,
            right_x,
            right_inputs,
        }
    }
}

/// The elements of one rung besides the contacts of its line.
#[derive(Default)]
struct Drawn {
    contacts: Vec<Contact>,
    coils: Vec<Coil>,
    blocks: Vec<Block>,
    in_vars: Vec<Var>,
    out_vars: Vec<Var>,
}

impl Placer {
    /// A variable read (a literal or the preset) left of the pin at `pin`.
    fn read(&mut self, drawn: &mut Drawn, expression: String, pin: (i64, i64)) -> Wire {
        let id = self.id();
        let x = pin.0 - VAR_W - 20;
        drawn.in_vars.push(Var {
            id,
            x,
            y: pin.1 - VAR_H / 2,
            width: VAR_W,
            height: VAR_H,
            expression,
            input: None,
        });
        Wire::from(
            Source {
                id,
                formal: None,
                at: (x + VAR_W, pin.1),
            },
            vec![pin],
        )
    }

    /// A block at `x` whose first pin is on `y`, with its inputs wired
    /// as given (in pin order) and its outputs named; returns its id.
    fn block(&mut self, drawn: &mut Drawn, kind: BlockKind, x: i64, y: i64) -> u64 {
        let id = self.id();
        let count = kind.inputs.len().max(kind.outputs.len()) as i64;
        let pin = |i: usize| BLOCK_PIN + PIN_PITCH * i as i64;
        drawn.blocks.push(Block {
            id,
            x,
            y: y - BLOCK_PIN,
            width: BLOCK_W,
            height: BLOCK_PIN + PIN_PITCH * count,
            type_name: kind.type_name,
            instance: kind.instance,
            inputs: kind
                .inputs
                .into_iter()
                .enumerate()
                .map(|(i, (name, input))| Pin {
                    name,
                    y: pin(i),
                    input,
                })
                .collect(),
            outputs: kind
                .outputs
                .iter()
                .enumerate()
                .map(|(i, name)| Pin {
                    name,
                    y: pin(i),
                    input: None,
                })
                .collect(),
        });
        id
    }

    /// The timer's own rung: the TON with EN from the rung (the rail), IN
    /// from a contact on the run flag under it, PT the preset variable;
    /// the wire from its Q to the coil and the coil's height (Q's).
    fn call(
        &mut self,
        drawn: &mut Drawn,
        timer: &Timer,
        run: &str,
        y: i64,
        route: impl Fn((i64, i64)) -> Wire,
    ) -> (Wire, i64) {
        let x = self.coil_x - 40 - BLOCK_W;
        let low = y + PIN_PITCH;
        let enable = route((x, y));
        let rail = Source {
            id: enable.from,
            formal: None,
            at: *enable.points.last().expect("a wire has points"),
        };
        let contact_x = RAIL_X + 60;
        let id = self.id();
        drawn.contacts.push(Contact {
            id,
            x: contact_x,
            y: low - PIN_Y,
            variable: run.to_string(),
            negated: false,
            input: Wire::from(
                rail,
                vec![(contact_x, low), (rail.at.0 + 10, low), (rail.at.0 + 10, y)],
            ),
        });
        let input = Wire::from(
            Source {
                id,
                formal: None,
                at: (contact_x + ELEMENT_W, low),
            },
            vec![(x, low)],
        );
        let pt = self.read(drawn, timer.preset.clone(), (x, y + 2 * PIN_PITCH));
        let block = self.block(
            drawn,
            BlockKind {
                type_name: "TON",
                instance: Some(timer.instance.clone()),
                inputs: vec![("EN", Some(enable)), ("IN", Some(input)), ("PT", Some(pt))],
                outputs: &["ENO", "Q", "ET"],
            },
            x,
            y,
        );
        let q = Source {
            id: block,
            formal: Some("Q"),
            at: (x + BLOCK_W, low),
        };
        (Wire::from(q, vec![(self.coil_x, low)]), low)
    }

    /// A restart: MOVE into the preset, the TON with IN off then on, all
    /// chained by EN/ENO from the rung; the wire from the last ENO to the
    /// coil that sets the run flag.
    fn restart(
        &mut self,
        drawn: &mut Drawn,
        timer: &Timer,
        ms: u32,
        y: i64,
        route: impl Fn((i64, i64)) -> Wire,
    ) -> Wire {
        let literal = format!("T#{ms}ms");
        let x = self.blocks_x;
        let preset = self.read(drawn, literal.clone(), (x, y + PIN_PITCH));
        let mov = self.block(
            drawn,
            BlockKind {
                type_name: "MOVE",
                instance: None,
                inputs: vec![("EN", Some(route((x, y)))), ("IN", Some(preset))],
                outputs: &["ENO", "OUT"],
            },
            x,
            y,
        );
        // The preset variable under the MOVE's OUT, before the first TON's
        // literals.
        let out_at = (x + BLOCK_W, y + PIN_PITCH);
        let var_at = (x + BLOCK_W + 20, y + 3 * PIN_PITCH + 10);
        let id = self.id();
        drawn.out_vars.push(Var {
            id,
            x: var_at.0,
            y: var_at.1 - VAR_H / 2,
            width: VAR_W,
            height: VAR_H,
            expression: timer.preset.clone(),
            input: Some(Wire::from(
                Source {
                    id: mov,
                    formal: Some("OUT"),
                    at: out_at,
                },
                vec![var_at, (var_at.0 - 10, var_at.1), (var_at.0 - 10, out_at.1)],
            )),
        });
        let mut enable = Source {
            id: mov,
            formal: Some("ENO"),
            at: (x + BLOCK_W, y),
        };
        let mut bx = x + BLOCK_W + VAR_W + GAP;
        for on in ["FALSE", "TRUE"] {
            let input = self.read(drawn, on.to_string(), (bx, y + PIN_PITCH));
            let pt = self.read(drawn, literal.clone(), (bx, y + 2 * PIN_PITCH));
            let id = self.block(
                drawn,
                BlockKind {
                    type_name: "TON",
                    instance: Some(timer.instance.clone()),
                    inputs: vec![
                        ("EN", Some(Wire::from(enable, vec![(bx, y)]))),
                        ("IN", Some(input)),
                        ("PT", Some(pt)),
                    ],
                    outputs: &["ENO", "Q", "ET"],
                },
                bx,
                y,
            );
            enable = Source {
                id,
                formal: Some("ENO"),
                at: (bx + BLOCK_W, y),
            };
            bx += BLOCK_W + VAR_W + GAP - 40;
        }
        Wire::from(enable, vec![(self.coil_x, y)])
    }
}

/// A block to draw: its type, instance, wired inputs and outputs.
struct BlockKind {
    type_name: &'static str,
    instance: Option<String>,
    inputs: Vec<(&'static str, Option<Wire>)>,
    outputs: &'static [&'static str],
}
