//! Property tests: invariants over random valid tables.

use proptest::prelude::*;
use steptable::address::{Allocation, Mnemonic, Safety, Target};
use steptable::program::{self, ProgramOptions};
use steptable::simulate::{SimSettings, simulate};
use steptable::timing::Stroke;

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
        settings.strokes.per_actuator.insert(
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
            let alloc = Allocation::with_safety(&table, Target::Festo, Mnemonic::En, safety);
            let options = ProgramOptions { safety, ..ProgramOptions::default() };
            let program = program::build(&table, &alloc, options, &settings.strokes);
            let report = simulate(&table, &program, &settings);
            prop_assert!(report.passed, "{:?}: {}\n{:?}", safety, report.verdict(), rows);
        }
    }
}
