//! The table model: a grid of cells → typed steps and moves, checked against
//! every rule of the method (DESIGN §2). The table is found by its `BRANCH n` /
//! `STEP n` headers anywhere on the sheet, or taken as a bare grid of moves.

use std::collections::BTreeMap;

mod check;
mod dialect;
mod frame;
mod machine;

pub use dialect::choose_reading;
pub use machine::{Machine, check_machine, home_order_place};

use frame::find_frame;

use crate::cell::{
    CellError, CellItem, ItemError, MAX_ACTUATOR, MAX_POSITION, Name, Sign, item_texts,
    move_attempt, not_a_move_hint, parse_items,
};
use crate::diag::{CellPos, Code, Diagnostics, Location};
use crate::read::{CellValue, Grid};

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

/// A table cell found on the sheet, before parsing.
struct RawCell {
    pos: CellPos,
    value: CellValue,
    branch: usize,
}

/// Builds the table from a sheet and checks it. Returns `None` when any error
/// was found (all of them are in `diags`).
pub fn build(grid: &Grid, diags: &mut Diagnostics) -> Option<StepTable> {
    let errors_before = diags.error_count();
    let Some(frame) = find_frame(grid, diags) else {
        if diags.error_count() == errors_before {
            diags.error(
                Code::E003NoTable,
                grid.sheet_location(),
                "no step table found: expected BRANCH n / STEP n headers or cells such as C1+1",
            );
        }
        return None;
    };
    if frame.branch_cols.len() > MAX_BRANCHES || frame.step_rows.len() > MAX_STEPS {
        diags.error(
            Code::E024TableTooLarge,
            grid.sheet_location(),
            format!(
                "table has {} steps × {} branches; the limit is {MAX_STEPS} steps × {MAX_BRANCHES} branches",
                frame.step_rows.len(),
                frame.branch_cols.len()
            ),
        );
        return None;
    }

    // Collect the raw cells of every step row, by row.
    let row_index: BTreeMap<u32, usize> = frame
        .step_rows
        .iter()
        .enumerate()
        .map(|(i, r)| (*r, i))
        .collect();
    let col_index: BTreeMap<u32, usize> = frame
        .branch_cols
        .iter()
        .enumerate()
        .map(|(i, c)| (*c, i))
        .collect();
    let mut rows: Vec<Vec<RawCell>> = (0..frame.step_rows.len()).map(|_| Vec::new()).collect();
    for cell in &grid.cells {
        let Some(&r) = row_index.get(&cell.pos.row) else {
            continue;
        };
        if let Some(&branch) = col_index.get(&cell.pos.col) {
            rows[r].push(RawCell {
                pos: cell.pos,
                value: cell.value.clone(),
                branch,
            });
        }
    }
    frame::report_unused(grid, &frame, diags);

    // Parse every cell.
    let mut parsed: Vec<Vec<(CellItem, CellPos, usize)>> = Vec::with_capacity(rows.len());
    let mut refused = check::Refused::default();
    for (step, row) in rows.iter().enumerate() {
        let mut items = Vec::new();
        for raw in row {
            let mut refuse = |actuator| refused.add(actuator, step);
            for item in parse_cell(grid, raw, diags, &mut refuse) {
                items.push((item, raw.pos, raw.branch));
            }
        }
        parsed.push(items);
    }

    // Steps without moves: trailing labelled rows are unused template rows;
    // any other empty step is an error (we never renumber silently).
    let last_with_moves = rows.iter().rposition(|r| !r.is_empty());
    let Some(last_with_moves) = last_with_moves else {
        diags.error(
            Code::E003NoTable,
            grid.sheet_location(),
            "the step table has no moves: fill at least one cell such as C1+1",
        );
        return None;
    };
    for (i, row) in rows.iter().enumerate().take(last_with_moves) {
        if row.is_empty() {
            let first_col = frame.branch_cols.first().copied().unwrap_or(0);
            let pos = CellPos::new(frame.step_rows[i], first_col);
            let what = if frame.labelled {
                format!("STEP {} has no move", i + 1)
            } else {
                format!("row {} of the table has no move", i + 1)
            };
            diags.error(
                Code::E023EmptyStep,
                grid.location(pos),
                format!("{what}; every step needs at least one move (delete the empty row)"),
            );
        }
    }
    // An unused template row is dropped, but not the engineer's words on
    // its label (`STEP 9 (spare)`): said, so a step meant to be filled
    // is not lost without a word.
    for index in last_with_moves + 1..frame.step_rows.len() {
        if let Some(cell) = frame.label_cell(grid, index)
            && let CellValue::Text(text) = &cell.value
            && crate::cell::step_comment(text).is_some()
        {
            diags.warning(
                Code::W003Ignored,
                grid.location(cell.pos),
                format!("\"{}\" labels a step with no move after the last one; the step and its comment are not used", text.trim()),
            );
        }
    }
    parsed.truncate(last_with_moves + 1);

    let table = check::check(grid, &frame, parsed, &refused, diags);
    if diags.error_count() > errors_before {
        None
    } else {
        table
    }
}

/// The items of a cell; each refused move-like item is told to `refuse`
/// with the actuator it was probably about.
fn parse_cell(
    grid: &Grid,
    raw: &RawCell,
    diags: &mut Diagnostics,
    refuse: &mut dyn FnMut(Option<u32>),
) -> Vec<CellItem> {
    let location = grid.location(raw.pos);
    let text = match &raw.value {
        CellValue::Text(t) => t,
        CellValue::Number(n) => {
            diags.error(
                Code::E010NotAMove,
                location,
                format!("the number {n} is not a move (expected text such as C2+1)"),
            );
            return Vec::new();
        }
        CellValue::Bool(b) => {
            diags.error(
                Code::E010NotAMove,
                location,
                format!(
                    "the value {} is not a move (expected text such as C2+1)",
                    if *b { "TRUE" } else { "FALSE" }
                ),
            );
            return Vec::new();
        }
        CellValue::Date(_) => {
            diags.error(
                Code::E010NotAMove,
                location,
                format!(
                    "{} is not a move: the spreadsheet took what was typed for a date or time; format the cell as text and type the move, e.g. C2+1",
                    raw.value.describe()
                ),
            );
            return Vec::new();
        }
        CellValue::Error(e) => {
            diags.error(
                Code::E010NotAMove,
                location,
                format!("the cell shows the error {e}, not a move"),
            );
            return Vec::new();
        }
        CellValue::Uncomputed(formula) => {
            diags.error(
                Code::E016FormulaNotComputed,
                location,
                format!(
                    "the formula {formula} has no computed value (the file was saved by a program that does not calculate); open and save it in Excel or LibreOffice, or type the move"
                ),
            );
            return Vec::new();
        }
    };
    let chars = text.chars().count();
    if chars > MAX_CELL_CHARS {
        diags.error(
            Code::E013CellTooLong,
            location,
            format!("the cell holds {chars} characters; a move has at most {MAX_CELL_CHARS}"),
        );
        return Vec::new();
    }
    let results = parse_items(text);
    if results.is_empty() {
        diags.error(
            Code::E010NotAMove,
            location.clone(),
            format!(
                "\"{}\" is not a move (expected C<number>+<position>, e.g. C2+1)",
                text.trim()
            ),
        );
    }
    let mut items = Vec::with_capacity(results.len());
    for (part, result) in item_texts(text).into_iter().zip(results) {
        match result {
            Ok(item) => {
                if let CellItem::Dwell { ms } = item
                    && crate::cell::without_unit(part)
                {
                    let number = part.split_once('=').map_or("", |(_, n)| n.trim());
                    let seconds = crate::cell::duration_text(ms);
                    let millis = match number.parse::<u32>() {
                        Ok(n)
                            if (crate::cell::MIN_DWELL_MS..=crate::cell::MAX_DWELL_MS)
                                .contains(&n) =>
                        {
                            format!(", or T={n}ms if milliseconds were meant")
                        }
                        _ => String::new(),
                    };
                    diags.warning(
                        Code::W007Assumed,
                        location.clone(),
                        format!(
                            "\"{}\" has no unit and is read as {} seconds: write T={seconds}{millis}",
                            part.trim(),
                            seconds.trim_end_matches('s'),
                        ),
                    );
                }
                items.push(item)
            }
            Err(error) => {
                if let Some(actuator) = move_attempt(part) {
                    refuse(actuator);
                }
                report_item_error(error, text, part, &location, diags)
            }
        }
    }
    items
}

/// Reports a refused item of the cell `text`: E010 quotes the item
/// (`part`) and says what it was probably meant to be.
fn report_item_error(
    error: ItemError,
    text: &str,
    part: &str,
    location: &Location,
    diags: &mut Diagnostics,
) {
    let location = location.clone();
    match error {
        ItemError::Move(CellError::NotAMove) => diags.error(
            Code::E010NotAMove,
            location,
            format!(
                "\"{}\" is not a move ({})",
                part.trim(),
                not_a_move_hint(part)
            ),
        ),
        ItemError::Move(CellError::BadActuator(n)) => diags.error(
            Code::E011BadActuator,
            location,
            format!(
                "\"{}\": actuator number {n} is out of range (expected 1 to {MAX_ACTUATOR})",
                text.trim()
            ),
        ),
        ItemError::Move(CellError::BadPosition(n)) => diags.error(
            Code::E012BadPosition,
            location,
            format!(
                "\"{}\": position {n} is out of range (expected 0 to {MAX_POSITION})",
                text.trim()
            ),
        ),
        ItemError::BadDwell(message) => diags.error(Code::E014BadDwell, location, message),
        ItemError::BadName(message) => diags.error(Code::E015BadName, location, message),
        ItemError::BadJump(message) => diags.error(Code::E017BadJump, location, message),
    }
}

/// Builds and checks a table from rows of cell text laid out as a bare grid
/// from A1 (empty strings are empty cells), as if read from the CSV file
/// `file`. For tests, benchmarks and generated tables.
pub fn from_rows<R, S>(file: &str, rows: &[R]) -> Result<StepTable, Vec<crate::diag::Diagnostic>>
where
    R: AsRef<[S]>,
    S: AsRef<str>,
{
    let grid = Grid::from_text_rows(file, None, rows);
    let mut diags = Diagnostics::new();
    match build(&grid, &mut diags) {
        Some(table) => Ok(table),
        None => Err(diags.into_sorted()),
    }
}

#[cfg(test)]
mod tests;
