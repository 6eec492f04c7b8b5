//! Random valid step tables from a seed, for benchmarks and tests: realistic
//! in shape (parallel branches, middle positions, everything back home at the
//! end) and the same on every machine for the same seed.

/// SplitMix64: tiny, fast, and fully specified, so a seed means the same
/// table everywhere.
#[derive(Debug, Clone)]
pub struct SplitMix64(u64);

impl SplitMix64 {
    pub fn new(seed: u64) -> Self {
        SplitMix64(seed)
    }

    pub fn next_u64(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A number in `low..=high`.
    pub fn range(&mut self, low: u32, high: u32) -> u32 {
        low + (self.next_u64() % (high - low + 1) as u64) as u32
    }
}

/// The shape of the tables to generate.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shape {
    pub actuators: u32,
    /// Highest position any actuator may have (1 = two-position cylinders only).
    pub max_position: u32,
    /// Most moves in one step.
    pub branches: u32,
    /// Number of steps, including the closing steps that bring everything home.
    pub steps: u32,
}

/// Rows of move cells (a bare grid) for a valid table of the given shape.
/// Every step moves at least one actuator; the last steps bring every
/// actuator home, `branches` at a time.
pub fn random_rows(seed: u64, shape: Shape) -> Vec<Vec<String>> {
    let mut rng = SplitMix64::new(seed);
    let n = shape.actuators.max(1) as usize;
    let branches = shape.branches.max(1) as usize;
    let pmax: Vec<u32> = (0..n)
        .map(|_| rng.range(1, shape.max_position.max(1)))
        .collect();
    let mut at = vec![0u32; n];
    let mut rows: Vec<Vec<String>> = Vec::new();
    let closing = |at: &[u32]| at.iter().filter(|p| **p != 0).count().div_ceil(branches);
    while rows.len() + closing(&at) < shape.steps as usize {
        let wanted = rng.range(1, branches as u32) as usize;
        let mut row = Vec::new();
        let mut used = Vec::new();
        for _ in 0..wanted * 8 {
            if row.len() == wanted {
                break;
            }
            let a = rng.range(0, n as u32 - 1) as usize;
            if used.contains(&a) {
                continue;
            }
            let target = rng.range(0, pmax[a]);
            if target == at[a] {
                continue;
            }
            // Keep the closing steps within the step budget.
            let away_after = at
                .iter()
                .enumerate()
                .filter(|(i, p)| if *i == a { target != 0 } else { **p != 0 })
                .count();
            if rows.len() + 1 + away_after.div_ceil(branches) > shape.steps as usize {
                continue;
            }
            let sign = if target > at[a] { '+' } else { '-' };
            row.push(format!("C{}{sign}{target}", a + 1));
            used.push(a);
            at[a] = target;
        }
        if row.is_empty() {
            // Nothing fits the step budget (or the dice kept missing): close.
            break;
        }
        rows.push(row);
    }
    if rows.is_empty() {
        // Every table has at least one step: move the first actuator out.
        rows.push(vec![format!("C1+{}", pmax[0])]);
        at[0] = pmax[0];
    }
    let away: Vec<usize> = (0..n).filter(|a| at[*a] != 0).collect();
    for chunk in away.chunks(branches) {
        rows.push(chunk.iter().map(|a| format!("C{}-0", a + 1)).collect());
    }
    rows
}

/// Adds jumps on inputs (`J:4 if I:jmp0`, `J:end if I:jmp1=0`) where the
/// table allows them, to half the tables, with dice of their own (seeded
/// from `seed`, so the caller's other draws stay as they were).
pub fn add_jumps(seed: u64, rows: &mut [Vec<String>]) {
    let mut rng = SplitMix64::new(seed ^ 0x7a11);
    let Ok(table) = crate::table::from_rows("random.csv", rows) else {
        return;
    };
    let choices = jump_choices(&table);
    if choices.is_empty() || rng.range(0, 1) == 0 {
        return;
    }
    for n in 0..rng.range(1, 2) {
        let (k, target) = choices[rng.range(0, choices.len() as u32 - 1) as usize];
        let target = target.map_or("end".to_string(), |t| t.to_string());
        let value = if rng.range(0, 1) == 0 { "" } else { "=0" };
        rows[k - 1].push(format!("J:{target} if I:jmp{n}{value}"));
    }
}

/// The jumps a checked table allows (`J:t if I:…` in step k): from a step
/// before the last to a step t ≥ 2 other than the next one where every
/// actuator stands after step k as after step t−1, or to the end (`None`)
/// where every actuator is home after step k. As `(k, t)`, one-based.
pub fn jump_choices(table: &crate::table::StepTable) -> Vec<(usize, Option<usize>)> {
    let after = crate::table::positions_after(&table.steps);
    let count = table.steps.len();
    let mut choices = Vec::new();
    for k in 1..count {
        if after[k] == after[0] {
            choices.push((k, None));
        }
        for t in 2..=count {
            if t != k + 1 && after[k] == after[t - 1] {
                choices.push((k, Some(t)));
            }
        }
    }
    choices
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn even_a_one_step_budget_gives_a_table() {
        for seed in 0..20 {
            let rows = random_rows(
                seed,
                Shape {
                    actuators: 1,
                    max_position: 1,
                    branches: 1,
                    steps: 1,
                },
            );
            assert!(crate::table::from_rows("r.csv", &rows).is_ok(), "{rows:?}");
        }
    }

    #[test]
    fn generated_tables_are_valid_and_sized() {
        for seed in 0..50 {
            let shape = Shape {
                actuators: 12,
                max_position: 4,
                branches: 4,
                steps: 40,
            };
            let rows = random_rows(seed, shape);
            assert!(rows.len() <= 40, "{}", rows.len());
            let table = crate::table::from_rows("r.csv", &rows).expect("valid");
            assert!(table.steps.iter().all(|s| s.moves.len() <= 4));
        }
        assert_eq!(
            random_rows(
                7,
                Shape {
                    actuators: 3,
                    max_position: 2,
                    branches: 2,
                    steps: 10
                }
            ),
            random_rows(
                7,
                Shape {
                    actuators: 3,
                    max_position: 2,
                    branches: 2,
                    steps: 10
                }
            )
        );
    }
}
