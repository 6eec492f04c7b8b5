//! Logic synthesis for single-branch sequences of two-position actuators
//! (Ganesh & Gurunathan 2017; DESIGN §7): find where auxiliary memories must
//! be set and reset so that the sensor state alone decides the next action,
//! fill the truth table, and find the smallest equation for every valve coil
//! and memory. This route is exact: the number of inserted operations, the
//! number of memories and every equation's size are proven minimal by
//! exhaustive search; the controller is then proven by simulation.
//!
//! The paper's own route — a genetic algorithm for the memories, genetic
//! programming for the equations — runs beside it and is reported against
//! the proven minimum.

mod budget;
pub mod choose;
pub mod controller;
pub mod equations;
mod exact;
pub mod ga;
pub mod gp;
pub mod output;
pub mod search;
pub mod sequence;
pub mod verify;

use std::time::Instant;

pub use budget::interrupt;
pub use exact::{Comparison, FrontPoint, Prefer, Stopped};

use equations::Expr;
use sequence::{Clash, Operation, Sequence};

/// One cell of the truth table.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Cell {
    One,
    Zero,
    DontCare,
}

impl Cell {
    pub fn symbol(self) -> char {
        match self {
            Cell::One => '1',
            Cell::Zero => '0',
            Cell::DontCare => 'x',
        }
    }
}

/// The truth table: one row per visited state in sequence order (the state
/// before each action), one column per action. Unvisited states are
/// don't-cares and have no row.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TruthTable {
    pub rows: Vec<u32>,
    pub columns: Vec<Operation>,
    /// `cells[row][column]`.
    pub cells: Vec<Vec<Cell>>,
}

impl TruthTable {
    /// Fills the table by the rules of DESIGN §7: where an action is next its
    /// column is 1 and its complement's 0; below a 0 (cyclically, in sequence
    /// order) 0 until the next 1; below a 1 don't-care until the next 0.
    pub fn of(sequence: &Sequence) -> TruthTable {
        let rows = sequence.pre_states();
        let mut columns: Vec<Operation> = Vec::new();
        for a in &sequence.actions {
            if !columns.contains(a) {
                columns.push(*a);
            }
        }
        let n = rows.len();
        let mut cells = vec![vec![Cell::DontCare; columns.len()]; n];
        for (c, column) in columns.iter().enumerate() {
            let defined: Vec<Option<Cell>> = sequence
                .actions
                .iter()
                .map(|a| {
                    if a == column {
                        Some(Cell::One)
                    } else if a.var == column.var {
                        Some(Cell::Zero)
                    } else {
                        None
                    }
                })
                .collect();
            for k in 0..n {
                cells[k][c] = match defined[k] {
                    Some(cell) => cell,
                    None => {
                        // The nearest defined row above, cyclically.
                        let above = (1..n).map(|d| defined[(k + n - d) % n]).find_map(|x| x);
                        match above {
                            Some(Cell::Zero) => Cell::Zero,
                            _ => Cell::DontCare,
                        }
                    }
                };
            }
        }
        TruthTable {
            rows,
            columns,
            cells,
        }
    }

    /// States where column `c` must be 1, and where it must be 0.
    pub fn on_off(&self, c: usize) -> (Vec<u32>, Vec<u32>) {
        let pick = |want: Cell| {
            self.rows
                .iter()
                .zip(&self.cells)
                .filter(|(_, cells)| cells[c] == want)
                .map(|(s, _)| *s)
                .collect()
        };
        (pick(Cell::One), pick(Cell::Zero))
    }
}

/// One action's equation.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Equation {
    pub action: Operation,
    /// The proven smallest tree.
    pub expr: Expr,
    /// The Quine–McCluskey two-level form over the full table, if computed.
    pub qm: Option<Expr>,
    /// The genetic programming's tree, when the GP ran and found one.
    pub gp: Option<Expr>,
}

/// Which route inserts the memories.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// The exhaustive search only.
    Exact,
    /// The paper's GA only (and GP for the equations).
    Ga,
    /// Both; the better (the exact one, or a GA answer as good) is kept.
    Both,
}

/// Synthesis options.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Options {
    pub method: Method,
    pub ga: ga::GaParams,
    pub gp: gp::GpParams,
    /// The longest the synthesis may run; `None` for no limit.
    pub time_limit: Option<std::time::Duration>,
    /// Which point of the front (memories against equation size) to keep.
    pub prefer: Prefer,
}

/// The default time limit: a few seconds, in which the textbook sequences
/// are answered in full (10 cylinders and 20 actions included); past it the
/// comparison of equations keeps its best so far.
pub const DEFAULT_TIME_LIMIT: std::time::Duration = std::time::Duration::from_secs(5);

impl Default for Options {
    fn default() -> Self {
        Options {
            method: Method::Both,
            ga: ga::GaParams::default(),
            gp: gp::GpParams::default(),
            time_limit: Some(DEFAULT_TIME_LIMIT),
            prefer: Prefer::Memories,
        }
    }
}

/// The fewest inserted operations and memories any valid modified sequence
/// has: proven by the exhaustive search, or (when it could not end in time)
/// only lower bounds.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Minimum {
    pub insertions: usize,
    pub memories: usize,
    pub proven: bool,
}

impl Minimum {
    /// How `insertions` operations of `memories` memories compare with the
    /// minimum: ": as short as the proven minimum", ": 2 inserted
    /// operation(s) more than the proven minimum of 10", …
    pub fn gap(&self, insertions: usize, memories: usize) -> String {
        if !self.proven {
            return format!(
                " (the minimum, not proven in the time given, is at least {} inserted operation(s) of {} memory(ies))",
                self.insertions, self.memories
            );
        }
        let mut more = Vec::new();
        if insertions > self.insertions {
            more.push(format!(
                "{} inserted operation(s) more than the proven minimum of {}",
                insertions - self.insertions,
                self.insertions
            ));
        }
        if memories > self.memories {
            more.push(format!(
                "{} memory(ies) more than the proven minimum of {}",
                memories - self.memories,
                self.memories
            ));
        }
        if more.is_empty() {
            ": as short as the proven minimum".to_string()
        } else {
            format!(": {}", more.join(" and "))
        }
    }
}

/// What the GA found, for the report.
#[derive(Debug, Clone, PartialEq)]
pub struct GaSummary {
    pub sequence: Option<Sequence>,
    pub generations: usize,
    pub millis: u128,
}

/// Everything the synthesis found.
#[derive(Debug, Clone)]
pub struct Synthesis {
    pub original: Sequence,
    pub clashes: Vec<Clash>,
    /// The modified sequence with the memory operations inserted.
    pub modified: Sequence,
    /// Inserted operations of `modified`.
    pub insertions: usize,
    /// The fewest inserted operations and memories (with `--method ga` found
    /// by the exhaustive search beside the GA, if it ends in time).
    pub minimum: Minimum,
    /// How the exact route chose among the minimal sequences.
    pub comparison: Option<Comparison>,
    /// The exact route's front: for the fewest memories and one more (at the
    /// fewest inserted operations), the smallest equations found; one is
    /// marked chosen.
    pub front: Vec<FrontPoint>,
    pub table: TruthTable,
    pub equations: Vec<Equation>,
    /// Time of the exact route: its sequence search (not run by `--method
    /// ga`) and the minimal equations (always run).
    pub millis: u128,
    /// Time of the whole synthesis, every route and the checks included.
    pub total_millis: u128,
    /// The method used.
    pub method: Method,
    /// The GA's answer, when it ran.
    pub ga: Option<GaSummary>,
    /// Time of the GA and GP, when they ran.
    pub ga_gp_millis: Option<u128>,
}

impl Synthesis {
    /// Sum of equation tree nodes.
    pub fn total_nodes(&self) -> usize {
        self.equations.iter().map(|e| e.expr.nodes()).sum()
    }

    /// Whether the equation of `action` is 1 in `state` (false for an
    /// action without a column).
    pub fn drives(&self, action: Operation, state: u32) -> bool {
        self.table
            .columns
            .iter()
            .position(|c| *c == action)
            .and_then(|c| self.equations.get(c))
            .is_some_and(|e| e.expr.eval(state))
    }

    /// Nodes of the largest equation.
    pub fn largest(&self) -> usize {
        self.equations
            .iter()
            .map(|e| e.expr.nodes())
            .max()
            .unwrap_or(0)
    }

    /// Sum of QM two-level sizes (same node convention), if all were computed.
    pub fn qm_nodes(&self) -> Option<usize> {
        self.equations
            .iter()
            .map(|e| e.qm.as_ref().map(Expr::nodes))
            .sum()
    }
}

/// Why synthesis could not be done.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum SynthError {
    /// The input is not a single-branch two-position sequence, or similar.
    Unsuitable(String),
    /// No valid modified sequence within the search limits.
    NotFound(String),
    /// The time limit passed before the search ended.
    OutOfTime(String),
}

impl std::fmt::Display for SynthError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            SynthError::Unsuitable(why)
            | SynthError::NotFound(why)
            | SynthError::OutOfTime(why) => f.write_str(why),
        }
    }
}

/// The sequence of a checked step table, its actuators named as the table
/// names them (C1, C2, …). Refused (E034) at the cell to blame, with the
/// reason, for parallel branches, middle positions, dwells, waits, outputs
/// or jumps.
pub fn from_table(table: &crate::table::StepTable) -> Result<Sequence, crate::diag::Diagnostic> {
    let refuse = |cell: Option<crate::diag::CellPos>, why: String| crate::diag::Diagnostic {
        severity: crate::diag::Severity::Error,
        code: crate::diag::Code::E034NotSynthesisable,
        location: crate::diag::Location {
            file: table.file.clone(),
            sheet: table.sheet.clone(),
            cell,
        },
        message: why,
    };
    if let Some(step) = table.steps.iter().find(|s| s.moves.len() > 1) {
        return Err(refuse(
            step.moves.get(1).map(|m| m.cell),
            format!(
                "STEP {} moves {} actuators at once: synthesis handles single-branch sequences only; use convert for parallel branches",
                step.number,
                step.moves.len()
            ),
        ));
    }
    if let Some(step) = table.steps.iter().find(|s| {
        s.moves.len() != 1
            || !s.dwells.is_empty()
            || !s.waits.is_empty()
            || !s.switches.is_empty()
            || !s.jumps.is_empty()
    }) {
        // The first item that is not a move; its cell also holds the move.
        let cell = step
            .dwells
            .iter()
            .map(|d| d.cell)
            .chain(step.waits.iter().map(|w| w.cell))
            .chain(step.switches.iter().map(|w| w.cell))
            .chain(step.jumps.iter().map(|j| j.cell))
            .min();
        return Err(refuse(
            cell,
            format!(
                "STEP {} ({}) is not one cylinder move: synthesis handles sequences of moves only, without dwells, waits, machine outputs or jumps; use convert for those",
                step.number,
                step.text()
            ),
        ));
    }
    if let Some(a) = table.actuators.iter().find(|a| a.max_position > 1) {
        let cell = table
            .steps
            .iter()
            .flat_map(|s| &s.moves)
            .find(|m| m.actuator == a.number && a.is_middle(m.to))
            .map(|m| m.cell);
        return Err(refuse(
            cell,
            format!(
                "C{} has middle positions: synthesis handles two-position actuators only; use convert for middle stops",
                a.number
            ),
        ));
    }
    let text: Vec<String> = table
        .steps
        .iter()
        .flat_map(|s| &s.moves)
        .map(|m| format!("C{}{}{}", m.actuator, m.sign.symbol(), m.to))
        .collect();
    sequence::parse(&text.join(" ")).map_err(|why| refuse(None, why))
}

/// Synthesises a controller for `original` with the default options (both
/// routes, the paper's parameters, seed 1).
pub fn synthesize(original: &Sequence) -> Result<Synthesis, SynthError> {
    synthesize_with(original, Options::default())
}

/// Synthesises a controller for `original` (a sequence without memories),
/// within `options.time_limit`.
pub fn synthesize_with(original: &Sequence, options: Options) -> Result<Synthesis, SynthError> {
    synthesize_observed(original, options, &|_, _| {})
}

/// [`synthesize_with`], telling `progress` how many of the candidates for
/// the smallest equations are settled (from any thread). Past the time limit
/// (or after [`interrupt`]) the search for the memories ends in
/// [`SynthError::OutOfTime`]; the comparison of equations keeps its best so
/// far and says what is proven.
pub fn synthesize_observed(
    original: &Sequence,
    options: Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Synthesis, SynthError> {
    let started = Instant::now();
    let _budget = budget::Budget::start(options.time_limit);
    let mut synthesis = synthesize_within(original, options, progress)?;
    synthesis.total_millis = started.elapsed().as_millis();
    Ok(synthesis)
}

/// The error of a search that found nothing before the time limit or Ctrl-C.
pub(crate) fn out_of_time(original: &Sequence, options: Options) -> SynthError {
    let why = match (Stopped::now(), options.time_limit) {
        (Some(Stopped::Interrupted), _) => "the search was interrupted".to_string(),
        (_, Some(limit)) => format!(
            "the search ran past its time limit of {} s",
            limit.as_secs_f64()
        ),
        (_, None) => "the search stopped".to_string(),
    };
    SynthError::OutOfTime(format!(
        "{why} before it found the fewest memory operations ({} actions of {} actuators; the time grows steeply with the length and with repeated states): raise --time-limit, or shorten the sequence",
        original.actions.len(),
        original.actuators
    ))
}

/// A sequence synthesis refuses: one with memories already, an action
/// that changes nothing, a cycle that does not end where it started.
fn unsuitable(original: &Sequence) -> Result<(), SynthError> {
    if original.memories > 0 {
        return Err(SynthError::Unsuitable(
            "give the original sequence without memories (W, X, Y, Z): they are what synthesis finds".to_string(),
        ));
    }
    let mut problems = Vec::new();
    let mut state = original.initial_state();
    for (i, a) in original.actions.iter().enumerate() {
        if (state >> a.var) & 1 == u32::from(a.value) {
            problems.push(format!(
                "action {} ({}) changes nothing",
                i + 1,
                original.token(*a)
            ));
        }
        state = sequence::apply(state, *a);
    }
    if state != original.initial_state() {
        problems.push("the cycle does not end with every actuator where it started".to_string());
    }
    if !problems.is_empty() {
        return Err(SynthError::Unsuitable(problems.join("; ")));
    }
    Ok(())
}

/// The fewest insertions and memories: the exact front's, else a search's,
/// else the lower bounds (not proven).
fn minimum(original: &Sequence, front: &[FrontPoint]) -> Minimum {
    match front.first() {
        Some(fewest) => Minimum {
            insertions: fewest.insertions,
            memories: fewest.memories,
            proven: true,
        },
        None => match search::minimal(original, search::Limits::default()) {
            Some(m) => Minimum {
                insertions: m.insertions,
                memories: m.memories,
                proven: true,
            },
            None => {
                let (insertions, memories) = search::lower_bounds(original);
                Minimum {
                    insertions,
                    memories,
                    proven: false,
                }
            }
        },
    }
}

fn synthesize_within(
    original: &Sequence,
    options: Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Synthesis, SynthError> {
    unsuitable(original)?;
    let clashes = original.clashes();
    let ga_start = Instant::now();
    let ga_summary = (options.method != Method::Exact).then(|| {
        let result = ga::run(original, options.ga);
        GaSummary {
            sequence: result.sequence,
            generations: result.generations,
            millis: 0,
        }
    });
    let ga_millis = ga_start.elapsed().as_millis();
    let exact_start = Instant::now();
    let (modified, insertions, comparison, front, equations) = if options.method == Method::Ga {
        let Some(s) = ga_summary.as_ref().and_then(|g| g.sequence.clone()) else {
            return Err(SynthError::NotFound(format!(
                "the GA found no valid sequence in {} generations (try more, another --seed, or --method exact)",
                options.ga.generations
            )));
        };
        let insertions = s.actions.len() - original.actions.len();
        let trees = choose::smallest_equations(&s).ok_or_else(|| {
            SynthError::NotFound("the equation search reached its limits".to_string())
        })?;
        (s, insertions, None, Vec::new(), trees)
    } else {
        let exact = exact::route(original, options, progress)?;
        (
            exact.chosen.sequence,
            exact.insertions,
            Some(exact.comparison),
            exact.front,
            exact.chosen.equations,
        )
    };
    let minimum = minimum(original, &front);
    let table = TruthTable::of(&modified);
    let mut equations: Vec<Equation> = table
        .columns
        .iter()
        .enumerate()
        .zip(equations)
        .map(|((c, action), expr)| {
            let (on, off) = table.on_off(c);
            Equation {
                action: *action,
                expr,
                qm: equations::quine_mccluskey(&on, &off, modified.variables()),
                gp: None,
            }
        })
        .collect();
    let millis = exact_start.elapsed().as_millis();
    let mut ga_gp_millis = None;
    if options.method != Method::Exact {
        let gp_start = Instant::now();
        for (c, equation) in equations.iter_mut().enumerate() {
            let (on, off) = table.on_off(c);
            let params = gp::GpParams {
                seed: options.gp.seed.wrapping_add(c as u64),
                ..options.gp
            };
            equation.gp = gp::run(
                &on,
                &off,
                modified.variables(),
                params,
                equation.qm.as_ref(),
            );
        }
        ga_gp_millis = Some(ga_millis + gp_start.elapsed().as_millis());
    }
    Ok(Synthesis {
        original: original.clone(),
        clashes,
        modified,
        insertions,
        minimum,
        comparison,
        front,
        table,
        equations,
        millis,
        total_millis: 0,
        method: options.method,
        ga: ga_summary.map(|g| GaSummary {
            millis: ga_millis,
            ..g
        }),
        ga_gp_millis,
    })
}

#[cfg(test)]
mod tests;
