//! The paper's genetic programming for the equations (DESIGN §7): a (μ+λ)
//! strategy over expression trees of AND, OR, NOT, XOR and the sensor and
//! memory letters; grow initialisation with at most 20 nodes; offspring by
//! subtree mutation or by subtree search (a fully fit subtree of the parent
//! replaces it); no crossover. Fitness to maximise: Nc + 1/Ni (rows matched,
//! tree nodes). Trees are evaluated on all truth-table rows at once, as bit
//! masks over the rows that matter. Seeded with PCG.

use rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg64;

use super::equations::Expr;

/// GP parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct GpParams {
    pub mu: usize,
    /// (μ+λ)/μ.
    pub ratio: usize,
    pub generations: usize,
    /// Most nodes of a tree at creation.
    pub max_initial_nodes: usize,
    pub seed: u64,
}

impl Default for GpParams {
    fn default() -> Self {
        GpParams {
            mu: 500,
            ratio: 4,
            generations: 60,
            max_initial_nodes: 20,
            seed: 1,
        }
    }
}

struct Rng(Pcg64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        (self.0.next_u64() % n.max(1) as u64) as usize
    }
}

/// Grows a random tree of at most `depth` levels.
fn grow(rng: &mut Rng, variables: usize, depth: usize) -> Expr {
    let leaf = depth <= 1 || rng.below(3) == 0;
    if leaf {
        return Expr::Var(rng.below(variables));
    }
    let sub = |rng: &mut Rng| Box::new(grow(rng, variables, depth - 1));
    match rng.below(4) {
        0 => Expr::Not(sub(rng)),
        1 => Expr::And(sub(rng), sub(rng)),
        2 => Expr::Or(sub(rng), sub(rng)),
        _ => Expr::Xor(sub(rng), sub(rng)),
    }
}

/// The tree's value on every row, as a mask.
fn mask(e: &Expr, var_masks: &[u64], full: u64) -> u64 {
    match e {
        Expr::Var(v) => var_masks[*v],
        Expr::Not(a) => !mask(a, var_masks, full) & full,
        Expr::And(a, b) => mask(a, var_masks, full) & mask(b, var_masks, full),
        Expr::Or(a, b) => mask(a, var_masks, full) | mask(b, var_masks, full),
        Expr::Xor(a, b) => mask(a, var_masks, full) ^ mask(b, var_masks, full),
    }
}

/// Every subtree, preorder.
fn subtrees(e: &Expr) -> Vec<&Expr> {
    let mut all = vec![e];
    match e {
        Expr::Var(_) => {}
        Expr::Not(a) => all.extend(subtrees(a)),
        Expr::And(a, b) | Expr::Or(a, b) | Expr::Xor(a, b) => {
            all.extend(subtrees(a));
            all.extend(subtrees(b));
        }
    }
    all
}

/// A copy of `e` with its `index`-th subtree (preorder) replaced.
fn replace(e: &Expr, index: &mut usize, with: &Expr) -> Expr {
    if *index == 0 {
        *index = usize::MAX;
        return with.clone();
    }
    *index = index.saturating_sub(1);
    match e {
        Expr::Var(v) => Expr::Var(*v),
        Expr::Not(a) => Expr::Not(Box::new(replace(a, index, with))),
        Expr::And(a, b) => {
            let a = replace(a, index, with);
            Expr::And(Box::new(a), Box::new(replace(b, index, with)))
        }
        Expr::Or(a, b) => {
            let a = replace(a, index, with);
            Expr::Or(Box::new(a), Box::new(replace(b, index, with)))
        }
        Expr::Xor(a, b) => {
            let a = replace(a, index, with);
            Expr::Xor(Box::new(a), Box::new(replace(b, index, with)))
        }
    }
}

/// The GP's best tree for a column that must be 1 on `on` and 0 on `off`,
/// if it found one matching every row. `start`, a tree that fits (the
/// two-level form), joins the first population, so that the GP only has to
/// shrink it where random trees alone find nothing that fits.
pub fn run(
    on: &[u32],
    off: &[u32],
    variables: usize,
    params: GpParams,
    start: Option<&Expr>,
) -> Option<Expr> {
    let rows: Vec<u32> = on.iter().chain(off).copied().collect();
    if rows.is_empty() || rows.len() > 63 || variables == 0 {
        return None;
    }
    let full = (1u64 << rows.len()) - 1;
    let target = (1u64 << on.len()) - 1;
    let var_masks: Vec<u64> = (0..variables)
        .map(|v| {
            rows.iter()
                .enumerate()
                .filter(|(_, s)| (**s >> v) & 1 == 1)
                .fold(0, |m, (i, _)| m | (1 << i))
        })
        .collect();
    let matched =
        |e: &Expr| rows.len() - ((mask(e, &var_masks, full) ^ target).count_ones() as usize);
    let score = |e: &Expr| matched(e) as f64 + 1.0 / e.nodes() as f64;
    let fully_fit = |e: &Expr| matched(e) == rows.len();
    let mut rng = Rng(Pcg64::seed_from_u64(params.seed));
    let mu = params.mu.max(2);
    let lambda = mu * (params.ratio.max(2) - 1);
    let mut population: Vec<(f64, Expr)> = Vec::with_capacity(mu + lambda);
    if let Some(tree) = start {
        population.push((score(tree), tree.clone()));
    }
    while population.len() < mu {
        let depth = 1 + rng.below(5);
        let tree = grow(&mut rng, variables, depth);
        if tree.nodes() <= params.max_initial_nodes {
            population.push((score(&tree), tree));
        }
    }
    let mut best = f64::MIN;
    let mut stalled = 0;
    for _ in 0..params.generations {
        if super::budget::exceeded() {
            break;
        }
        let mut offspring = Vec::with_capacity(lambda);
        for _ in 0..lambda {
            if super::budget::exceeded() {
                break;
            }
            let parent = &population[rng.below(mu)].1;
            let parts = subtrees(parent);
            let child = if rng.below(4) == 0 {
                // Subtree search: the smallest fully fit subtree, if any.
                match parts
                    .iter()
                    .filter(|s| fully_fit(s))
                    .min_by_key(|s| s.nodes())
                {
                    Some(s) => (*s).clone(),
                    None => parent.clone(),
                }
            } else {
                // Subtree mutation: a random subtree regrown.
                let mut index = rng.below(parts.len());
                let depth = 1 + rng.below(3);
                let new = grow(&mut rng, variables, depth);
                replace(parent, &mut index, &new)
            };
            offspring.push((score(&child), child));
        }
        population.extend(offspring);
        population.sort_by(|a, b| b.0.total_cmp(&a.0));
        population.dedup_by(|a, b| a.1 == b.1);
        population.truncate(mu);
        while population.len() < mu {
            let depth = 1 + rng.below(5);
            let tree = grow(&mut rng, variables, depth);
            population.push((score(&tree), tree));
        }
        if population[0].0 > best + 1e-12 {
            best = population[0].0;
            stalled = 0;
        } else {
            stalled += 1;
            if stalled > 15 && fully_fit(&population[0].1) {
                break;
            }
        }
    }
    let winner = population.into_iter().next()?.1;
    fully_fit(&winner).then_some(winner)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_a_small_fitting_tree() {
        // bit 0 = a, bit 1 = b, bit 2 = x: 1 where b = 0 and x = 0.
        let on = [0b000, 0b001];
        let off = [0b100, 0b101, 0b010, 0b011];
        let e = run(&on, &off, 3, GpParams::default(), None).unwrap();
        assert!(on.iter().all(|s| e.eval(*s)) && off.iter().all(|s| !e.eval(*s)));
        assert_eq!(e.nodes(), 4);
    }

    /// A column no random tree of the first population fits: with the
    /// two-level form in it, the GP answers and only shrinks from there.
    #[test]
    fn a_fitting_start_tree_means_an_answer() {
        // 1 only where a, b, c, d are all 1 (a four-input AND, 7 nodes).
        let on = [0b1111];
        let off: Vec<u32> = (0..15).collect();
        let tiny = GpParams {
            mu: 2,
            ratio: 2,
            generations: 1,
            max_initial_nodes: 1,
            seed: 3,
        };
        assert_eq!(
            run(&on, &off, 4, tiny, None),
            None,
            "single leaves never fit"
        );
        let v = |i| Box::new(Expr::Var(i));
        let start = Expr::And(
            Box::new(Expr::And(v(0), v(1))),
            Box::new(Expr::And(v(2), v(3))),
        );
        let e = run(&on, &off, 4, tiny, Some(&start)).unwrap();
        assert!(e.eval(0b1111) && off.iter().all(|s| !e.eval(*s)));
        assert!(e.nodes() <= start.nodes());
    }
}
