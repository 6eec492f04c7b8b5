//! The rules a table must keep, by code: positions and directions (E020),
//! one move per actuator per step (E021), home at the end (E022), dwells
//! (E026), jumps, machine signal names (E015, E025). The rules on the
//! machine the table runs on are in [`super::machine`].

use std::collections::BTreeMap;

use super::frame::Frame;
use super::{Actuator, Dwell, Jump, MAX_DWELLS, Move, Step, StepTable, Switch, Wait};
use crate::actuator::Valves;
use crate::cell::{CellItem, JumpTarget, Name, Sign};
use crate::diag::{CellPos, Code, Diagnostics, Location};
use crate::read::Grid;

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
    (refused, valves, fst): (&Refused, &Valves, bool),
    diags: &mut Diagnostics,
) -> Option<StepTable> {
    let mut rules = Rules::new(grid, refused, diags, &parsed);
    rules.names.fst = fst;
    let mut steps = Vec::with_capacity(parsed.len());
    for (index, row) in parsed.into_iter().enumerate() {
        steps.push(rules.step(frame, index, row));
    }
    let actuators: Vec<Actuator> = (rules.max_position.iter())
        .map(|(&number, &max_position)| Actuator {
            number,
            max_position,
        })
        .collect();
    // A position its kind cannot hold is said with every other error; its
    // actuator is then not told to come home from there (E022).
    let cannot_hold =
        super::machine::check_positions(&actuators, &steps, valves, grid, rules.diags);
    rules.home(&cannot_hold);
    let Rules { names, diags, .. } = rules;
    for (step, label) in steps.iter_mut().zip(frame.step_labels(grid)) {
        step.label = label.map(|(n, pos)| (n, grid.cell_name(pos)));
    }
    check_jumps(&steps, refused, grid, diags);
    Some(StepTable {
        file: grid.file.clone(),
        sheet: grid.sheet.clone(),
        branches: frame.branch_cols.len(),
        steps,
        actuators,
        inputs: names.inputs,
        outputs: names.outputs,
    })
}

/// The table's rules as its cells are read in step order, one validator
/// per kind of cell item, each with the codes it reports; the state they
/// share is where every actuator stands and which names are taken.
struct Rules<'a> {
    grid: &'a Grid,
    refused: &'a Refused,
    diags: &'a mut Diagnostics,
    /// pmax(i): the highest position written for Ci; at least 1.
    max_position: BTreeMap<u32, u32>,
    /// Where each actuator stands and the cell that last moved it.
    current: BTreeMap<u32, (u32, Option<CellPos>)>,
    names: Names,
    dwell_count: usize,
}

impl<'a> Rules<'a> {
    fn new(
        grid: &'a Grid,
        refused: &'a Refused,
        diags: &'a mut Diagnostics,
        parsed: &[Vec<(CellItem, CellPos, usize)>],
    ) -> Self {
        let mut max_position: BTreeMap<u32, u32> = BTreeMap::new();
        for (item, _, _) in parsed.iter().flatten() {
            if let CellItem::Move(m) = item {
                let entry = max_position.entry(m.actuator).or_insert(1);
                if let Some(p) = m.position {
                    *entry = (*entry).max(p);
                }
            }
        }
        let current = max_position.keys().map(|a| (*a, (0, None))).collect();
        Rules {
            grid,
            refused,
            diags,
            max_position,
            current,
            names: Names::default(),
            dwell_count: 0,
        }
    }

    fn location(&self, pos: CellPos) -> Location {
        self.grid.location(pos)
    }

    /// One step of the table, each of its cell items checked.
    fn step(&mut self, frame: &Frame, index: usize, row: Vec<(CellItem, CellPos, usize)>) -> Step {
        let number = index + 1;
        // The engineer's comment on the step's label (`STEP 3 (clamp part)`).
        let comment = frame
            .label_cell(self.grid, index)
            .and_then(|c| match &c.value {
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
            label: None,
        };
        let mut seen: BTreeMap<u32, CellPos> = BTreeMap::new();
        for (item, pos, branch) in row {
            match item {
                CellItem::Move(m) => self.movement(&mut step, &mut seen, index, m, pos, branch),
                CellItem::Dwell { ms } => self.dwell(&mut step, ms, pos, branch),
                CellItem::Wait { input, value } => self.wait(&mut step, input, value, pos, branch),
                CellItem::Jump {
                    target,
                    input,
                    value,
                } => self.jump(&mut step, target, input, value, pos, branch),
                CellItem::Switch { output, on } => self.switch(&mut step, output, on, pos, branch),
            }
        }
        step
    }

    /// E021 (two dwells in a cell), E026 (too many dwells).
    fn dwell(&mut self, step: &mut Step, ms: u32, pos: CellPos, branch: usize) {
        if step.dwells.iter().any(|d| d.cell == pos) {
            self.diags.error(
                Code::E021TwiceInStep,
                self.location(pos),
                "a cell holds at most one dwell (T=…); add the times up",
            );
            return;
        }
        self.dwell_count += 1;
        let dwell_count = self.dwell_count;
        if dwell_count == MAX_DWELLS + 1 {
            self.diags.error(
                Code::E026TooManyDwells,
                self.location(pos),
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
    }

    /// E021 when a step names a machine signal `twice` for one purpose
    /// (`message`); else the name is taken as an input or output. Whether
    /// the item is read.
    fn first_use(
        &mut self,
        twice: bool,
        name: Name,
        kind: NameKind,
        pos: CellPos,
        message: impl FnOnce() -> String,
    ) -> bool {
        if twice {
            self.diags
                .error(Code::E021TwiceInStep, self.location(pos), message());
            return false;
        }
        self.names.use_name(name, kind, pos, self.grid, self.diags);
        true
    }

    /// E021 (a step waits for an input twice), and the input's name.
    fn wait(&mut self, step: &mut Step, input: Name, value: bool, pos: CellPos, branch: usize) {
        let twice = step.waits.iter().any(|w| w.input == input);
        let number = step.number;
        if !self.first_use(twice, input, NameKind::Input, pos, || {
            format!("STEP {number} already waits for I:{input}; a step waits for an input once")
        }) {
            return;
        }
        step.waits.push(Wait {
            input,
            value,
            branch,
            cell: pos,
        });
    }

    /// E021 (a step jumps on an input twice), and the input's name.
    fn jump(
        &mut self,
        step: &mut Step,
        target: JumpTarget,
        input: Name,
        value: bool,
        pos: CellPos,
        branch: usize,
    ) {
        let twice = step.jumps.iter().any(|j| j.input == input);
        let number = step.number;
        if !self.first_use(twice, input, NameKind::Input, pos, || {
            format!("STEP {number} already jumps on I:{input}; a step jumps on an input once")
        }) {
            return;
        }
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
    }

    /// E021 (a step switches an output twice), and the output's name.
    fn switch(&mut self, step: &mut Step, output: Name, on: bool, pos: CellPos, branch: usize) {
        let twice = step.switches.iter().any(|w| w.output == output);
        let number = step.number;
        if !self.first_use(twice, output, NameKind::Output, pos, || {
            format!("STEP {number} already switches Y:{output}; a step switches an output once")
        }) {
            return;
        }
        step.switches.push(Switch {
            output,
            on,
            branch,
            cell: pos,
        });
    }

    /// E021 (an actuator moves twice in a step), E020 (a move against
    /// where the actuator stands).
    fn movement(
        &mut self,
        step: &mut Step,
        seen: &mut BTreeMap<u32, CellPos>,
        index: usize,
        m: crate::cell::CellMove,
        pos: CellPos,
        branch: usize,
    ) {
        let number = step.number;
        let pmax = self.max_position.get(&m.actuator).copied().unwrap_or(1);
        let to = m.position.unwrap_or(match m.sign {
            Sign::Plus => pmax,
            Sign::Minus => 0,
        });
        let written = m.to_string();
        if let Some(first) = seen.get(&m.actuator) {
            self.diags.error(
                Code::E021TwiceInStep,
                self.location(pos),
                format!(
                    "\"{written}\": C{} already moves in STEP {number} (cell {}); an actuator moves at most once per step",
                    m.actuator,
                    self.grid.cell_name(*first)
                ),
            );
            return;
        }
        seen.insert(m.actuator, pos);
        let (from, _) = self.current.get(&m.actuator).copied().unwrap_or((0, None));
        let ok = match m.sign {
            Sign::Plus => to > from,
            Sign::Minus => to < from,
        };
        if !ok && !self.refused.unknown(m.actuator, index) {
            let (need, verb) = match m.sign {
                Sign::Plus => ("higher", "a + move extends"),
                Sign::Minus => ("lower", "a - move retracts"),
            };
            self.diags.error(
                Code::E020WrongDirection,
                self.location(pos),
                format!(
                    "\"{written}\": C{} stands at position {from} before STEP {number}; {verb}, so it must go to a {need} position than {from}",
                    m.actuator
                ),
            );
        }
        self.current.insert(m.actuator, (to, Some(pos)));
        step.moves.push(Move {
            actuator: m.actuator,
            sign: m.sign,
            from,
            to,
            branch,
            cell: pos,
        });
    }

    /// E022: every actuator back at position 0 after the last step, but
    /// for those whose position no kind of theirs can hold (E045).
    fn home(&mut self, cannot_hold: &[u32]) {
        for (actuator, (position, last_cell)) in &self.current {
            if *position != 0
                && !self.refused.unknown(*actuator, usize::MAX)
                && !cannot_hold.contains(actuator)
            {
                let loc = match last_cell {
                    Some(pos) => self.grid.location(*pos),
                    None => self.grid.sheet_location(),
                };
                self.diags.error(
                    Code::E022NotHome,
                    loc,
                    format!(
                        "C{actuator} ends the cycle at position {position}, not at home; every actuator must be back at position 0 after the last step (add C{actuator}-0)"
                    ),
                );
            }
        }
    }
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
            let why = why
                .or_else(|| waited_jump(step, jump))
                .or_else(|| jump.target.and_then(|n| super::two_rows_answer(steps, n)));
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
    /// A Festo FST file is written: the 9 characters it keeps of a name
    /// count too.
    fst: bool,
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
        if let Some(why) = crate::names::signal_problem(name.as_str(), &[], self.fst) {
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
