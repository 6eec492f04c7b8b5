//! The table model: a grid of cells → typed steps and moves, checked against
//! every rule of the method (DESIGN §2). The table is found by its `BRANCH n` /
//! `STEP n` headers anywhere on the sheet, or taken as a bare grid of moves.

use std::collections::BTreeMap;

mod build;
mod check;
mod dialect;
mod frame;
mod machine;

pub use build::{build, build_for, from_rows};
pub use dialect::choose_reading;
pub use machine::{Machine, check_machine, home_order_place};

use crate::cell::{CellItem, Name, Sign};
use crate::diag::CellPos;

/// Largest number of steps accepted.
pub const MAX_STEPS: usize = 10_000;
/// Largest number of branches accepted.
pub const MAX_BRANCHES: usize = 256;
/// Longest text accepted in a cell of the table (a move has a dozen characters).
pub const MAX_CELL_CHARS: usize = 200;

/// One resolved move: actuator `actuator` goes from `from` to `to`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct Move {
    pub actuator: u32,
    pub sign: Sign,
    pub from: u32,
    pub to: u32,
    /// Zero-based branch (column of the table).
    pub branch: usize,
    /// Where the move was written.
    #[serde(skip)]
    pub cell: CellPos,
}

impl Move {
    /// The move in the table's notation, e.g. `C2+3`.
    pub fn notation(&self) -> String {
        format!("C{}{}{}", self.actuator, self.sign.symbol(), self.to)
    }
}

/// Most dwells a table may have: PLCs have 256 timers, one is the watchdog.
pub const MAX_DWELLS: usize = 255;

/// `T=2s` in a branch: once the branch's other items of the step are done,
/// it waits this long.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Dwell {
    /// One-based number of the dwell in the table (its timer's number).
    pub number: u16,
    pub ms: u32,
    pub branch: usize,
    pub cell: CellPos,
}

/// `I:name` / `I:name=0`: the step completes only when the input has `value`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Wait {
    pub input: Name,
    pub value: bool,
    pub branch: usize,
    pub cell: CellPos,
}

/// `Y:name+` / `Y:name-`: a machine output switched on or off when the step starts.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Switch {
    pub output: Name,
    pub on: bool,
    pub branch: usize,
    pub cell: CellPos,
}

/// `J:7 if I:reject` in a branch: once the step is done, the sequence goes
/// on at step `target` (or ends the cycle) when the input has `value`,
/// instead of at the next step. A jump is tested before the next step.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Jump {
    /// The step whose moves come next; `None` ends the cycle.
    pub target: Option<usize>,
    pub input: Name,
    pub value: bool,
    pub branch: usize,
    pub cell: CellPos,
}

impl Jump {
    /// `J:7 if I:reject`.
    pub fn notation(&self) -> String {
        CellItem::Jump {
            target: match self.target {
                Some(n) => crate::cell::JumpTarget::Step(n as u32),
                None => crate::cell::JumpTarget::End,
            },
            input: self.input,
            value: self.value,
        }
        .to_string()
    }

    /// The index among a program's steps of the step this jump fires: its
    /// target's, or for the end the closing step's (`closing`).
    pub fn fires(&self, closing: usize) -> usize {
        self.target.map_or(closing, |n| n - 1)
    }

    /// `step 7` or `the end of the cycle`.
    pub fn target_text(&self) -> String {
        match self.target {
            Some(n) => format!("step {n}"),
            None => "the end of the cycle".to_string(),
        }
    }
}

/// Where every actuator of `steps` stands after each step: index 0 at
/// power-up (all home), index k after step k. Every map names every
/// actuator, so two of them compare with `==`.
pub fn positions_after(steps: &[Step]) -> Vec<BTreeMap<u32, u32>> {
    let home: BTreeMap<u32, u32> = steps
        .iter()
        .flat_map(|s| &s.moves)
        .map(|m| (m.actuator, 0))
        .collect();
    let mut after = Vec::with_capacity(steps.len() + 1);
    after.push(home);
    for step in steps {
        let mut positions = after[after.len() - 1].clone();
        for m in &step.moves {
            positions.insert(m.actuator, m.to);
        }
        after.push(positions);
    }
    after
}

/// One step: all of its moves and switches start together; it completes
/// when every move reached its sensor, every wait holds and every dwell ran.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Step {
    /// One-based step number.
    pub number: usize,
    /// The engineer's comment on the step's label (`clamp part` of `STEP 3
    /// (clamp part)`), carried into every output's step comment.
    pub comment: Option<String>,
    /// Moves in branch order.
    pub moves: Vec<Move>,
    pub dwells: Vec<Dwell>,
    pub waits: Vec<Wait>,
    pub switches: Vec<Switch>,
    /// Where the sequence may go instead of the next step, tested in order.
    pub jumps: Vec<Jump>,
    /// The number its `STEP n` label says and the label's cell (`A7`,
    /// `7:1`), where the row has one: it may differ from `number` (W002).
    pub label: Option<(u32, String)>,
}

/// Where the `STEP n` labels are off (W002), a step number written in a
/// jump or a SETTINGS row may mean step `n` by its place or a row
/// labelled `n` elsewhere (a shifted label, or one two rows carry): when
/// those are two rows, what says so (naming both); none when one row
/// answers to `n` (labels in order, or numbered otherwise throughout: 10,
/// 20, …).
pub fn two_rows_answer(steps: &[Step], n: usize) -> Option<String> {
    let at_place = steps.get(n.checked_sub(1)?)?;
    let other = steps
        .iter()
        .find(|s| s.number != n && s.label.as_ref().is_some_and(|(m, _)| *m as usize == n))?;
    let (_, cell) = other.label.as_ref()?;
    let place = match &at_place.label {
        Some((label, at)) => format!("the row labelled STEP {label} ({at})"),
        None => "a row without a label".to_string(),
    };
    Some(format!(
        "step {n} of the table is {place}, and the row labelled STEP {n} ({cell}) is step {}; steps are numbered by their place, and the labels say otherwise: number the STEP labels 1, 2, 3, … in order so that the number names one row",
        other.number
    ))
}

impl Step {
    /// The step as the table writes it: `C3+2, C2+2` for moves only (as the
    /// paper does), then `; T=2s; I:part_present; Y:vacuum+` for the rest.
    pub fn text(&self) -> String {
        let moves = self
            .moves
            .iter()
            .map(Move::notation)
            .collect::<Vec<_>>()
            .join(", ");
        let mut parts = vec![moves];
        parts.extend(self.other_items(|_| true));
        parts.retain(|p| !p.is_empty());
        parts.join("; ")
    }

    /// Everything written in one branch's cell, as the table writes it.
    pub fn cell_text(&self, branch: usize) -> String {
        let mut parts: Vec<String> = self.branch_moves(branch).map(Move::notation).collect();
        parts.extend(self.other_items(|b| b == branch));
        parts.join("; ")
    }

    /// The switches, waits and dwells of the branches `in_branch` picks, in
    /// the table's notation and that order.
    fn other_items(&self, in_branch: impl Fn(usize) -> bool) -> Vec<String> {
        let switches = self
            .switches
            .iter()
            .filter(|s| in_branch(s.branch))
            .map(|s| {
                CellItem::Switch {
                    output: s.output,
                    on: s.on,
                }
                .to_string()
            });
        let waits = self.waits.iter().filter(|w| in_branch(w.branch)).map(|w| {
            CellItem::Wait {
                input: w.input,
                value: w.value,
            }
            .to_string()
        });
        let dwells = self
            .dwells
            .iter()
            .filter(|d| in_branch(d.branch))
            .map(|d| crate::cell::dwell_text(d.ms));
        let jumps = self
            .jumps
            .iter()
            .filter(|j| in_branch(j.branch))
            .map(Jump::notation);
        switches.chain(waits).chain(dwells).chain(jumps).collect()
    }

    /// The moves of one branch (what its dwell waits for).
    pub fn branch_moves(&self, branch: usize) -> impl Iterator<Item = &Move> {
        self.moves.iter().filter(move |m| m.branch == branch)
    }
}

/// What the table says about one actuator.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Actuator {
    pub number: u32,
    /// Highest position used (`pmax`); 1 for a plain two-position cylinder.
    pub max_position: u32,
}

impl Actuator {
    /// True when the actuator has middle stops (and so a 5/3 valve).
    pub fn has_middle_positions(&self) -> bool {
        self.max_position > 1
    }

    /// True when `position` is between the ends, where the piston must be
    /// stopped on its sensor (a middle stop). The one place this is decided.
    pub fn is_middle(&self, position: u32) -> bool {
        position > 0 && position < self.max_position
    }
}

/// A checked step table.
#[derive(Debug, Clone, PartialEq)]
pub struct StepTable {
    /// File name, for titles and comments.
    pub file: String,
    /// Sheet the table came from (`None` for CSV).
    pub sheet: Option<String>,
    /// Number of branches (columns) of the table.
    pub branches: usize,
    pub steps: Vec<Step>,
    /// Actuators in ascending number.
    pub actuators: Vec<Actuator>,
    /// Machine inputs waited on (`I:name`), in order of first use.
    pub inputs: Vec<Name>,
    /// Machine outputs switched (`Y:name+`), in order of first use.
    pub outputs: Vec<Name>,
}

impl StepTable {
    /// The homing stages RESET uses: `order`, checked to name every actuator
    /// once, or by default the order in which the cycle itself returns them
    /// home: each actuator's last move, earliest first (actuators whose last
    /// move is in the same step go home together).
    pub fn home_stages(&self, order: Option<&[Vec<u32>]>) -> Result<Vec<Vec<u32>>, String> {
        if let Some(order) = order {
            let mut named: Vec<u32> = order.iter().flatten().copied().collect();
            named.sort_unstable();
            if let Some(twice) = named.windows(2).find(|w| w[0] == w[1]) {
                return Err(format!("the home order names C{} twice", twice[0]));
            }
            let all: Vec<u32> = self.actuators.iter().map(|a| a.number).collect();
            if let Some(extra) = named.iter().find(|n| !all.contains(n)) {
                return Err(format!(
                    "the home order names C{extra}, which the table does not move"
                ));
            }
            if let Some(missing) = all.iter().find(|n| !named.contains(n)) {
                return Err(format!("the home order leaves out C{missing}"));
            }
            return Ok(order.to_vec());
        }
        let mut last: BTreeMap<u32, usize> = BTreeMap::new();
        for step in &self.steps {
            for m in &step.moves {
                last.insert(m.actuator, step.number);
            }
        }
        // The cycle's own return order: an actuator's last move is its
        // return home, and the cycle returns them in this order for a
        // reason (the punch lifts before the clamp opens). Homing the other
        // way round would undo the machine's safeguards.
        let mut stages: BTreeMap<usize, Vec<u32>> = BTreeMap::new();
        for (actuator, step) in last {
            stages.entry(step).or_default().push(actuator);
        }
        Ok(stages.into_values().collect())
    }
}

impl StepTable {
    /// Every dwell of the table, in step order.
    pub fn dwells(&self) -> impl Iterator<Item = &Dwell> {
        self.steps.iter().flat_map(|s| &s.dwells)
    }

    pub fn actuator(&self, number: u32) -> Option<&Actuator> {
        self.actuators.iter().find(|a| a.number == number)
    }
}

#[cfg(test)]
mod tests;
