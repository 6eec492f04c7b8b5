//! The rules a table must keep, by code: positions and directions (E020),
//! one move per actuator per step (E021), home at the end (E022), dwells
//! (E026), machine signal names (E015, E025), and the machine the table
//! runs on: valves that can stop at middle positions (E031), a home order
//! that fits the table (E030, W006).

use std::collections::BTreeMap;

use super::frame::Frame;
use super::{Actuator, Dwell, Jump, MAX_DWELLS, Move, Step, StepTable, Switch, Wait};
use crate::actuator::Valves;
use crate::cell::{CellItem, JumpTarget, Name, Sign};
use crate::diag::{CellPos, Code, Diagnostics, Location};
use crate::read::Grid;

/// What a table is checked against besides its own rules: the machine it
/// runs on and the program's options.
#[derive(Debug, Clone, Copy)]
pub struct Machine<'a> {
    pub valves: &'a Valves,
    pub home_order: Option<&'a [Vec<u32>]>,
    /// Where the home order was given: its SETTINGS cell, or `None` for
    /// the command line (`--home-order`).
    pub home_order_at: Option<&'a Location>,
    /// Whether the program has the reset mode, which uses the home order.
    pub reset: bool,
    /// The (lower-case) names of the operating-mode buttons the program has
    /// (`stop`, `estop`, …): taken only when their mode is on.
    pub buttons: &'a [String],
}

/// Checks a built table against the machine it runs on: the valve types,
/// the home order (checked whether or not the reset mode uses it) and the
/// names the operating modes take.
pub fn check_machine(table: &StepTable, machine: &Machine, grid: &Grid, diags: &mut Diagnostics) {
    check_valves(table, machine.valves, grid, diags);
    check_home_order(table, machine, grid, diags);
    check_button_names(table, machine.buttons, grid, diags);
}

/// A machine input or output may be called `stop` unless the program has a
/// STOP button of that name (and likewise for the other buttons): what the
/// buttons add to the one name check ([`crate::names::signal_problem`]),
/// which the table's own build ran without them. Said at the name's first
/// cell, whether a wait, a jump or an output switch.
fn check_button_names(table: &StepTable, buttons: &[String], grid: &Grid, diags: &mut Diagnostics) {
    for name in table.inputs.iter().chain(&table.outputs) {
        let name = name.as_str();
        if crate::names::signal_problem(name, &[]).is_some() {
            continue;
        }
        if let (Some(why), Some(cell)) = (
            crate::names::signal_problem(name, buttons),
            first_use(table, name),
        ) {
            diags.error(Code::E015BadName, grid.location(cell), why);
        }
    }
}

/// The first cell (in step order) that names a machine input or output.
fn first_use(table: &StepTable, name: &str) -> Option<CellPos> {
    table.steps.iter().find_map(|s| {
        let waits = s.waits.iter().filter(|w| w.input.as_str() == name);
        let jumps = s.jumps.iter().filter(|j| j.input.as_str() == name);
        let switches = s.switches.iter().filter(|w| w.output.as_str() == name);
        waits
            .map(|w| w.cell)
            .chain(jumps.map(|j| j.cell))
            .chain(switches.map(|w| w.cell))
            .min()
    })
}

/// Where a message about the home order goes: on its SETTINGS cell, or on
/// the file with the words naming `--home-order` to end the message.
pub fn home_order_place(at: Option<&Location>, file: &str) -> (Location, &'static str) {
    match at {
        Some(at) => (at.clone(), ""),
        None => (
            Location {
                file: file.to_string(),
                sheet: None,
                cell: None,
            },
            " (--home-order)",
        ),
    }
}

/// A home order is checked against the table whether or not it is used,
/// and a home order without the reset mode that uses it is said, so that a
/// forgotten `reset` is not silently a no-op.
fn check_home_order(table: &StepTable, machine: &Machine, grid: &Grid, diags: &mut Diagnostics) {
    let Some(order) = machine.home_order else {
        return;
    };
    let (at, source) = home_order_place(machine.home_order_at, &grid.file);
    if let Err(message) = table.home_stages(Some(order)) {
        diags.error(Code::E030BadSetting, at, format!("{message}{source}"));
    } else if !machine.reset {
        diags.warning(
            Code::W006NoEffect,
            at,
            format!("the home order is used by the reset mode only, which is not on: add reset to the modes, or leave the home order out{source}"),
        );
    }
}

/// A middle position needs a valve with a centre: a 5/2 valve cannot stop a
/// piston between its ends. Names the cell of the first move that asks for it.
fn check_valves(table: &StepTable, valves: &Valves, grid: &Grid, diags: &mut Diagnostics) {
    for actuator in table.actuators.iter().filter(|a| a.has_middle_positions()) {
        let valve = valves.of(actuator.number, actuator.max_position);
        if valve.has_centre() {
            continue;
        }
        let Some(m) = table
            .steps
            .iter()
            .flat_map(|s| &s.moves)
            .find(|m| m.actuator == actuator.number && actuator.is_middle(m.to))
        else {
            continue;
        };
        let centred = crate::actuator::ActuatorKind::centred();
        diags.error(
            Code::E031ValveCannotStop,
            grid.location(m.cell),
            format!(
                "\"{}\" stops C{} at middle position {}, but its valve is {valve}, which cannot stop a piston between its ends (use {})",
                m.notation(),
                actuator.number,
                m.to,
                crate::diag::or_list(&centred)
            ),
        );
    }
}

/// The actuators whose position a refused cell leaves unknown, from the
/// step (index) of that cell on: a move checked against a position the
/// refused `C2+l` would have given is no error of its own (no cascade).
#[derive(Debug, Default)]
pub(super) struct Refused {
    from: BTreeMap<u32, usize>,
    /// A refused move of an actuator nobody can tell (`Cx+1`).
    any_from: Option<usize>,
}

impl Refused {
    pub(super) fn add(&mut self, actuator: Option<u32>, step: usize) {
        let slot = match actuator {
            Some(a) => self.from.entry(a).or_insert(step),
            None => self.any_from.get_or_insert(step),
        };
        *slot = (*slot).min(step);
    }

    /// Whether the position of `actuator` is unknown at step index `step`.
    fn unknown(&self, actuator: u32, step: usize) -> bool {
        self.any_from.is_some_and(|s| s <= step)
            || self.from.get(&actuator).is_some_and(|s| *s <= step)
    }
}

/// Resolves positions and checks the rules of DESIGN §2.
pub(super) fn check(
    grid: &Grid,
    frame: &Frame,
    parsed: Vec<Vec<(CellItem, CellPos, usize)>>,
    refused: &Refused,
    diags: &mut Diagnostics,
) -> Option<StepTable> {
    // pmax(i): the highest position written for Ci; at least 1.
    let mut max_position: BTreeMap<u32, u32> = BTreeMap::new();
    for (item, _, _) in parsed.iter().flatten() {
        if let CellItem::Move(m) = item {
            let entry = max_position.entry(m.actuator).or_insert(1);
            if let Some(p) = m.position {
                *entry = (*entry).max(p);
            }
        }
    }

    let location = |pos: CellPos| -> Location { grid.location(pos) };
    let mut current: BTreeMap<u32, (u32, Option<CellPos>)> =
        max_position.keys().map(|a| (*a, (0, None))).collect();
    let mut names = Names::default();
    let mut dwell_count = 0usize;
    let mut steps = Vec::with_capacity(parsed.len());
    for (index, row) in parsed.into_iter().enumerate() {
        let number = index + 1;
        // The engineer's comment on the step's label (`STEP 3 (clamp part)`).
        let comment = frame.label_cell(grid, index).and_then(|c| match &c.value {
            crate::read::CellValue::Text(t) => crate::cell::step_comment(t),
            _ => None,
        });
        let mut step = Step {
            number,
            comment,
            moves: Vec::with_capacity(row.len()),
            dwells: Vec::new(),
            waits: Vec::new(),
            switches: Vec::new(),
            jumps: Vec::new(),
        };
        let mut seen: BTreeMap<u32, CellPos> = BTreeMap::new();
        for (item, pos, branch) in row {
            let m = match item {
                CellItem::Move(m) => m,
                CellItem::Dwell { ms } => {
                    if step.dwells.iter().any(|d| d.cell == pos) {
                        diags.error(
                            Code::E021TwiceInStep,
                            location(pos),
                            "a cell holds at most one dwell (T=…); add the times up",
                        );
                        continue;
                    }
                    dwell_count += 1;
                    if dwell_count == MAX_DWELLS + 1 {
                        diags.error(
                            Code::E026TooManyDwells,
                            location(pos),
                            format!(
                                "this is dwell number {dwell_count}; a table has at most {MAX_DWELLS} (PLCs have 256 timers)"
                            ),
                        );
                    }
                    step.dwells.push(Dwell {
                        number: dwell_count.min(u16::MAX as usize) as u16,
                        ms,
                        branch,
                        cell: pos,
                    });
                    continue;
                }
                CellItem::Wait { input, value } => {
                    if step.waits.iter().any(|w| w.input == input) {
                        diags.error(
                            Code::E021TwiceInStep,
                            location(pos),
                            format!("STEP {number} already waits for I:{input}; a step waits for an input once"),
                        );
                        continue;
                    }
                    names.use_name(input, NameKind::Input, pos, grid, diags);
                    step.waits.push(Wait {
                        input,
                        value,
                        branch,
                        cell: pos,
                    });
                    continue;
                }
                CellItem::Jump {
                    target,
                    input,
                    value,
                } => {
                    if step.jumps.iter().any(|j| j.input == input) {
                        diags.error(
                            Code::E021TwiceInStep,
                            location(pos),
                            format!("STEP {number} already jumps on I:{input}; a step jumps on an input once"),
                        );
                        continue;
                    }
                    names.use_name(input, NameKind::Input, pos, grid, diags);
                    step.jumps.push(Jump {
                        target: match target {
                            JumpTarget::Step(n) => Some(n as usize),
                            JumpTarget::End => None,
                        },
                        input,
                        value,
                        branch,
                        cell: pos,
                    });
                    continue;
                }
                CellItem::Switch { output, on } => {
                    if step.switches.iter().any(|w| w.output == output) {
                        diags.error(
                            Code::E021TwiceInStep,
                            location(pos),
                            format!("STEP {number} already switches Y:{output}; a step switches an output once"),
                        );
                        continue;
                    }
                    names.use_name(output, NameKind::Output, pos, grid, diags);
                    step.switches.push(Switch {
                        output,
                        on,
                        branch,
                        cell: pos,
                    });
                    continue;
                }
            };
            let pmax = max_position.get(&m.actuator).copied().unwrap_or(1);
            let to = m.position.unwrap_or(match m.sign {
                Sign::Plus => pmax,
                Sign::Minus => 0,
            });
            let written = m.to_string();
            if let Some(first) = seen.get(&m.actuator) {
                diags.error(
                    Code::E021TwiceInStep,
                    location(pos),
                    format!(
                        "\"{written}\": C{} already moves in STEP {number} (cell {}); an actuator moves at most once per step",
                        m.actuator,
                        grid.cell_name(*first)
                    ),
                );
                continue;
            }
            seen.insert(m.actuator, pos);
            let (from, _) = current.get(&m.actuator).copied().unwrap_or((0, None));
            let ok = match m.sign {
                Sign::Plus => to > from,
                Sign::Minus => to < from,
            };
            if !ok && !refused.unknown(m.actuator, index) {
                let (need, verb) = match m.sign {
                    Sign::Plus => ("higher", "a + move extends"),
                    Sign::Minus => ("lower", "a - move retracts"),
                };
                diags.error(
                    Code::E020WrongDirection,
                    location(pos),
                    format!(
                        "\"{written}\": C{} stands at position {from} before STEP {number}; {verb}, so it must go to a {need} position than {from}",
                        m.actuator
                    ),
                );
            }
            current.insert(m.actuator, (to, Some(pos)));
            step.moves.push(Move {
                actuator: m.actuator,
                sign: m.sign,
                from,
                to,
                branch,
                cell: pos,
            });
        }
        steps.push(step);
    }

    for (actuator, (position, last_cell)) in &current {
        if *position != 0 && !refused.unknown(*actuator, usize::MAX) {
            let loc = match last_cell {
                Some(pos) => location(*pos),
                None => grid.sheet_location(),
            };
            diags.error(
                Code::E022NotHome,
                loc,
                format!(
                    "C{actuator} ends the cycle at position {position}, not at home; every actuator must be back at position 0 after the last step (add C{actuator}-0)"
                ),
            );
        }
    }

    check_jumps(&steps, refused, grid, diags);
    Some(StepTable {
        file: grid.file.clone(),
        sheet: grid.sheet.clone(),
        branches: frame.branch_cols.len(),
        steps,
        actuators: max_position
            .into_iter()
            .map(|(number, max_position)| Actuator {
                number,
                max_position,
            })
            .collect(),
        inputs: names.inputs,
        outputs: names.outputs,
    })
}

/// Every jump goes to a step the table has, not to where the sequence goes
/// anyway, and finds every actuator where its target step starts from.
fn check_jumps(steps: &[Step], refused: &Refused, grid: &Grid, diags: &mut Diagnostics) {
    if steps.iter().all(|s| s.jumps.is_empty()) {
        return;
    }
    let after = super::positions_after(steps);
    let count = steps.len();
    for step in steps {
        for jump in &step.jumps {
            let location = grid.location(jump.cell);
            let written = jump.notation();
            let why = match jump.target {
                _ if step.number == count => Some(format!(
                    "the cycle ends after STEP {count}, the last step; a jump belongs in a step before it"
                )),
                Some(n) if n > count => Some(format!("the table has {count} steps")),
                Some(1) => Some(
                    "STEP 1 starts a cycle on START; to end the cycle early, jump to end (J:end if I:…)"
                        .to_string(),
                ),
                Some(n) if n == step.number + 1 => Some(format!(
                    "STEP {n} comes after STEP {} anyway",
                    step.number
                )),
                _ => None,
            };
            let why = why.or_else(|| waited_jump(step, jump));
            if let Some(why) = why {
                diags.error(
                    Code::E028JumpTarget,
                    location,
                    format!("\"{written}\" in STEP {}: {why}", step.number),
                );
                continue;
            }
            // The target step's moves start from the positions after the step
            // before it; the end of the cycle from home.
            let (from, expected) = match jump.target {
                Some(n) => (&after[step.number], &after[n - 1]),
                None => (&after[step.number], &after[0]),
            };
            // Every actuator is in both maps, also one that has not moved yet.
            let away: Vec<String> = from
                .iter()
                .zip(expected.values())
                .filter(|((actuator, at), wanted)| {
                    at != wanted && !refused.unknown(**actuator, usize::MAX)
                })
                .map(|((actuator, at), wanted)| {
                    format!("C{actuator} at {wanted} (it stands at {at})")
                })
                .collect();
            if !away.is_empty() {
                diags.error(
                    Code::E029JumpPositions,
                    location,
                    format!(
                        "\"{written}\" in STEP {}: {} {}; a jump goes only where every actuator already stands (add the moves in a step before it, or jump elsewhere)",
                        step.number,
                        match jump.target {
                            Some(n) => format!("step {n} starts from"),
                            None => "the end of the cycle needs every actuator home:".to_string(),
                        },
                        away.join(", ")
                    ),
                );
            }
        }
    }
}

/// A jump is tested once its step is done, and a step is done only when
/// its waits are met: a jump on an input its own step waits for is then
/// certain (the steps it leaves out never run) or impossible (its path
/// never runs). Both are refused rather than proven on a path that cannot
/// happen.
fn waited_jump(step: &Step, jump: &Jump) -> Option<String> {
    let wait = step.waits.iter().find(|w| w.input == jump.input)?;
    let waited = format!(
        "STEP {} waits for I:{}={}",
        step.number,
        jump.input,
        u8::from(wait.value)
    );
    Some(if wait.value == jump.value {
        let skipped = match jump.target {
            Some(n) if n > step.number + 1 => {
                format!("steps {}–{} never run", step.number + 1, n - 1)
            }
            Some(n) => format!(
                "steps {n}–{} repeat for ever (the cycle never ends)",
                step.number
            ),
            None => format!("the steps after STEP {} never run", step.number),
        };
        format!(
            "{waited}, so once the step is done the jump is always taken and {skipped}; jump on another input, or take the wait out"
        )
    } else {
        format!(
            "{waited}, so I:{} is {} whenever the jump is tested and the jump is never taken; jump on another input, or take the wait out",
            jump.input,
            u8::from(wait.value)
        )
    })
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum NameKind {
    Input,
    Output,
}

/// The machine inputs and outputs named so far, with where each was first used.
#[derive(Default)]
struct Names {
    inputs: Vec<Name>,
    outputs: Vec<Name>,
    first: BTreeMap<Name, (NameKind, CellPos)>,
}

impl Names {
    /// Records a use of a name; a name is an input or an output, not both,
    /// and may not be one the program uses for itself.
    fn use_name(
        &mut self,
        name: Name,
        kind: NameKind,
        pos: CellPos,
        grid: &Grid,
        diags: &mut Diagnostics,
    ) {
        if let Some((first_kind, first_pos)) = self.first.get(&name) {
            if *first_kind != kind {
                let (was, is) = match first_kind {
                    NameKind::Input => ("an input (I:)", "an output (Y:)"),
                    NameKind::Output => ("an output (Y:)", "an input (I:)"),
                };
                diags.error(
                    Code::E025NameClash,
                    grid.location(pos),
                    format!(
                        "{name} is used as {is} here but as {was} in cell {}; give them different names",
                        grid.cell_name(*first_pos)
                    ),
                );
            }
            return;
        }
        if let Some(why) = crate::names::signal_problem(name.as_str(), &[]) {
            diags.error(Code::E015BadName, grid.location(pos), why);
        }
        // Two names FST cannot tell apart are said by the one check over
        // the table and its settings (the symbol table's check).
        self.first.insert(name, (kind, pos));
        match kind {
            NameKind::Input => self.inputs.push(name),
            NameKind::Output => self.outputs.push(name),
        }
    }
}
