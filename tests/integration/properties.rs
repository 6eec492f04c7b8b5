//! Property tests: invariants over random valid tables.

use proptest::prelude::*;
use steptable::program::Safety;
use steptable::program::{self, ProgramOptions};
use steptable::simulate::{SimSettings, simulate};
use steptable::stroke::Stroke;

/// Per actuator: pmax, extend ms, retract ms.
type Actuators = Vec<(u32, u32, u32)>;
/// Per step: (actuator index, wished target position).
type Wishes = Vec<Vec<(usize, u32)>>;

/// Raw material for a table: actuator count, each one's pmax and stroke
/// times, and up to 37 steps of (actuator, target) wishes.
fn raw_table() -> impl Strategy<Value = (Actuators, Wishes)> {
    let actuators = prop::collection::vec((1u32..=4, 800u32..=3000, 800u32..=3000), 1..=12);
    actuators.prop_flat_map(|acts| {
        let n = acts.len();
        let step = prop::collection::vec((0..n, 0u32..=4), 1..=4);
        (Just(acts), prop::collection::vec(step, 1..=37))
    })
}

/// Turns the raw wishes into a valid table: skips moves that go nowhere or
/// repeat an actuator within a step, then brings everything home, four
/// actuators per step. Returns the rows of cells and the stroke settings.
fn valid_rows(
    acts: &[(u32, u32, u32)],
    raw: &[Vec<(usize, u32)>],
) -> (Vec<Vec<String>>, SimSettings) {
    let mut at = vec![0u32; acts.len()];
    let mut rows: Vec<Vec<String>> = Vec::new();
    for wishes in raw {
        let mut row = Vec::new();
        let mut used = Vec::new();
        for &(a, p) in wishes {
            let target = p % (acts[a].0 + 1);
            if used.contains(&a) || target == at[a] {
                continue;
            }
            let sign = if target > at[a] { '+' } else { '-' };
            row.push(format!("C{}{sign}{target}", a + 1));
            used.push(a);
            at[a] = target;
        }
        if !row.is_empty() {
            rows.push(row);
        }
    }
    let away: Vec<usize> = (0..acts.len()).filter(|a| at[*a] != 0).collect();
    for chunk in away.chunks(4) {
        rows.push(chunk.iter().map(|a| format!("C{}-0", a + 1)).collect());
    }
    let mut settings = SimSettings::default();
    for (i, (_, extend, retract)) in acts.iter().enumerate() {
        settings.machine.strokes.per_actuator.insert(
            i as u32 + 1,
            Stroke {
                extend_ms: *extend,
                retract_ms: *retract,
            },
        );
    }
    (rows, settings)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Every valid random table (up to 12 actuators, 4 positions, 4 branches,
    /// 40 steps) yields a program that completes two identical cycles.
    #[test]
    fn every_valid_table_runs_in_simulation((acts, raw) in raw_table()) {
        let (rows, settings) = valid_rows(&acts, &raw);
        prop_assume!(!rows.is_empty());
        let table = steptable::table::from_rows("random.csv", &rows)
            .map_err(|d| TestCaseError::fail(format!("generator made an invalid table: {d:?}")))?;
        prop_assert!(table.steps.len() <= 40);
        for safety in [Safety::default(), Safety::all()] {
            let options = ProgramOptions { safety, ..ProgramOptions::default() };
            let program = program::build(&table, &options, &settings.machine.valves, &settings.machine.strokes);
            let report = simulate(&table, &program, &settings);
            prop_assert!(report.passed, "{:?}: {}\n{:?}", safety, report.verdict(), rows);
        }
    }
}

/// Per step: optionally a dwell, a wait and an output switch, each with the
/// branch (cell) it goes in.
type Extras = Vec<(
    Option<(usize, u32)>,
    Option<(usize, u8, bool)>,
    Option<(usize, u8, bool)>,
)>;

fn extras() -> impl Strategy<Value = Extras> {
    prop::collection::vec(
        (
            prop::option::of((0usize..4, 1u32..=300)),
            prop::option::of((0usize..4, 0u8..3, any::<bool>())),
            prop::option::of((0usize..4, 0u8..3, any::<bool>())),
        ),
        40,
    )
}

/// Adds dwells, waits and output switches to the cells of a table (`;`
/// after the cell's move, or alone in an empty cell).
fn with_extras(rows: &[Vec<String>], extras: &Extras) -> Vec<Vec<String>> {
    let mut rows = rows.to_vec();
    for (row, (dwell, wait, switch)) in rows.iter_mut().zip(extras) {
        let mut add = |branch: usize, item: String| {
            while row.len() <= branch {
                row.push(String::new());
            }
            if row[branch].is_empty() {
                row[branch] = item;
            } else {
                row[branch] = format!("{}; {item}", row[branch]);
            }
        };
        if let Some((branch, tens)) = dwell {
            add(*branch, format!("T={}ms", tens * 10));
        }
        if let Some((branch, k, value)) = wait {
            add(*branch, format!("I:part{k}={}", u8::from(*value)));
        }
        if let Some((branch, k, on)) = switch {
            add(*branch, format!("Y:lamp{k}{}", if *on { '+' } else { '-' }));
        }
    }
    rows
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// Dwells, waits and output switches anywhere in a valid table, with and
    /// without the operating modes and the safety checks: the program still completes two
    /// identical cycles, and each dwell lengthens its step by at least its time.
    #[test]
    fn dwells_waits_and_outputs_keep_every_table_running(
        (acts, raw) in raw_table(),
        extras in extras(),
        modes in prop_oneof![Just("none"), Just("all"), Just("continuous,stop")],
        safety in prop_oneof![Just(Safety::default()), Just(Safety::all())],
    ) {
        let (rows, settings) = valid_rows(&acts, &raw);
        prop_assume!(!rows.is_empty());
        let rows = with_extras(&rows, &extras);
        let table = steptable::table::from_rows("random.csv", &rows)
            .map_err(|d| TestCaseError::fail(format!("invalid table: {d:?}\n{rows:?}")))?;
        let modes = steptable::program::Modes::parse(modes).unwrap();
        let options = ProgramOptions { modes, safety, ..ProgramOptions::default() };
        let program = program::build(&table, &options, &settings.machine.valves, &settings.machine.strokes);
        let report = simulate(&table, &program, &settings);
        prop_assert!(report.passed, "{}\n{:?}", report.verdict(), rows);
        let cycle = &report.cycles[0];
        for (timing, step) in cycle.steps.iter().zip(&table.steps) {
            let longest = step.dwells.iter().map(|d| d.ms as u64).max().unwrap_or(0);
            prop_assert!(timing.duration_ms >= longest, "{timing:?}");
        }
    }
}

/// A random move as the table writes it.
fn any_move() -> impl Strategy<Value = steptable::cell::CellMove> {
    (1u32..=999, any::<bool>(), prop::option::of(0u32..=63)).prop_map(
        |(actuator, plus, position)| steptable::cell::CellMove {
            actuator,
            sign: if plus {
                steptable::cell::Sign::Plus
            } else {
                steptable::cell::Sign::Minus
            },
            position,
        },
    )
}

/// Text that can never be a move: no `C` followed by a digit, or no sign.
fn garbage() -> impl Strategy<Value = String> {
    prop_oneof![
        "[A-BD-Za-bd-z!?#*/ ]{1,12}",
        "C[0-9]{1,3}",
        "C[0-9]{1,2}[xyz*/]{1,3}",
        "[+\\-][0-9]{1,3}",
    ]
    .prop_filter("must not read as a move", |t| {
        steptable::cell::parse_move(t).is_err() && !t.trim().is_empty()
    })
}

/// A table in the template's layout: a header row `BRANCH 1 …`, then a
/// `STEP k` label before each step's cells. Cell (r, c) of `rows` sits at
/// row r+1, column c+1.
fn with_headers(rows: &[Vec<String>]) -> Vec<Vec<String>> {
    let branches = rows.iter().map(Vec::len).max().unwrap_or(1);
    let mut out = vec![
        std::iter::once(String::new())
            .chain((1..=branches).map(|b| format!("BRANCH {b}")))
            .collect::<Vec<_>>(),
    ];
    for (k, row) in rows.iter().enumerate() {
        out.push(
            std::iter::once(format!("STEP {}", k + 1))
                .chain(row.iter().cloned())
                .collect(),
        );
    }
    out
}

/// Every (row, column) that holds a cell.
fn cells_of(rows: &[Vec<String>]) -> Vec<(usize, usize)> {
    rows.iter()
        .enumerate()
        .flat_map(|(r, row)| (0..row.len()).map(move |c| (r, c)))
        .collect()
}

fn random_table() -> impl Strategy<Value = Vec<Vec<String>>> {
    (any::<u64>(), 1u32..=8, 1u32..=3, 1u32..=4, 4u32..=30).prop_map(
        |(seed, actuators, max_position, branches, steps)| {
            steptable::random_table::random_rows(
                seed,
                steptable::random_table::Shape {
                    actuators,
                    max_position,
                    branches,
                    steps,
                },
            )
        },
    )
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    /// Every move the parser prints, it reads back (also in other spellings).
    #[test]
    fn the_cell_parser_round_trips(m in any_move()) {
        let printed = m.to_string();
        prop_assert_eq!(steptable::cell::parse_move(&printed), Ok(m));
        let spaced = printed.to_lowercase().replace('-', " \u{2212} ").replace('+', " + ");
        prop_assert_eq!(steptable::cell::parse_move(&spaced), Ok(m));
    }

    /// A cell of a valid table changed to garbage is reported at that cell.
    #[test]
    fn garbage_is_reported_at_its_cell(rows in random_table(), pick in any::<prop::sample::Index>(), text in garbage()) {
        let mut rows = rows;
        let cells = cells_of(&rows);
        let (r, c) = cells[pick.index(cells.len())];
        rows[r][c] = text.clone();
        let errors = steptable::table::from_rows("edit.csv", &with_headers(&rows)).expect_err("garbage cannot be valid");
        let here = errors.iter().any(|d| {
            d.location.cell.map(|p| (p.row as usize, p.col as usize)) == Some((r + 1, c + 1))
                && d.code.as_str() == "E010"
        });
        prop_assert!(here, "{text:?} at {r},{c}: {:?}", errors.iter().map(|d| d.to_string()).collect::<Vec<_>>());
    }

    /// A step row written twice: every move of the copy goes nowhere, and
    /// each is reported at its own cell.
    #[test]
    fn a_duplicated_row_is_reported_cell_by_cell(rows in random_table(), pick in any::<prop::sample::Index>()) {
        let mut rows = rows;
        let k = pick.index(rows.len());
        let copy = rows[k].clone();
        rows.insert(k + 1, copy.clone());
        let errors = steptable::table::from_rows("dup.csv", &with_headers(&rows)).expect_err("a repeated step is invalid");
        for c in 0..copy.len() {
            let reported = errors.iter().any(|d| {
                d.location.cell.map(|p| (p.row as usize, p.col as usize)) == Some((k + 2, c + 1))
                    && d.code.as_str() == "E020"
            });
            prop_assert!(reported, "row {} col {c}: {:?}", k + 1, errors.iter().map(|d| d.to_string()).collect::<Vec<_>>());
        }
    }

    /// A deleted move never panics; if the table becomes invalid, a problem
    /// is reported at a move of the same actuator.
    #[test]
    fn a_deleted_move_is_reported_at_its_actuator(rows in random_table(), pick in any::<prop::sample::Index>()) {
        let mut rows = rows;
        let cells = cells_of(&rows);
        let (r, c) = cells[pick.index(cells.len())];
        let removed = std::mem::take(&mut rows[r][c]);
        let actuator = steptable::cell::parse_move(&removed).unwrap().actuator;
        let framed = with_headers(&rows);
        if let Err(errors) = steptable::table::from_rows("del.csv", &framed) {
            let own = errors.iter().any(|d| match d.location.cell {
                Some(p) => framed
                    .get(p.row as usize)
                    .and_then(|row| row.get(p.col as usize))
                    .and_then(|t| steptable::cell::parse_move(t).ok())
                    .is_some_and(|m| m.actuator == actuator)
                    || d.code.as_str() == "E023",
                None => false,
            });
            prop_assert!(own, "C{actuator} removed at {r},{c}: {:?}", errors.iter().map(|d| d.to_string()).collect::<Vec<_>>());
        }
    }
}
