//! Which minimal modified sequence has the smallest equations. Every
//! placement of the memory operations, in every polarity of its memories, is
//! a candidate, and each candidate's equations are searched exactly, so the
//! comparison is what costs: thousands of candidates of dozens of columns.
//! Three things keep it short and honest:
//!
//! - a lower bound per column that holds in every polarity: a tree that
//!   tells the column's on rows from its off rows reads at least the fewest
//!   variables that tell every such pair apart, and a tree of k leaves has
//!   at least 2k − 1 nodes. Candidates are taken in the order of their
//!   bound; one whose bound is above the best so far is never searched, and
//!   once that holds for all that are left the best is proven the smallest;
//! - each column's search gets only the room the bounds of the other
//!   columns leave, and what a search proved about a column is remembered;
//! - every core.
//!
//! Past the deadline (or on Ctrl-C) the best so far is kept, with the lower
//! bound no candidate can beat.

use std::collections::HashMap;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

use super::TruthTable;
use super::budget;
use super::equations::{self, Expr, SearchLimits, Smallest};
use super::sequence::Sequence;

/// The candidate with the smallest equations found, and what is proven.
#[derive(Debug, Clone)]
pub struct Choice {
    pub sequence: Sequence,
    /// Its equations, one per column of its truth table, each the smallest.
    pub equations: Vec<Expr>,
    pub nodes: usize,
    /// Candidates: placements times polarities.
    pub candidates: usize,
    /// Candidates searched or ruled out by their bound.
    pub settled: usize,
    /// No candidate has equations of fewer nodes in all.
    pub lower_bound: usize,
}

impl Choice {
    /// Whether `nodes` is proven the smallest over every candidate.
    pub fn proven(&self) -> bool {
        self.nodes == self.lower_bound
    }
}

/// The sequence with the memories in `flip` inverted.
pub fn polarity(sequence: &Sequence, flip: u32) -> Sequence {
    let mut s = sequence.clone();
    for a in &mut s.actions {
        if a.var >= s.actuators && (flip >> (a.var - s.actuators)) & 1 == 1 {
            a.value = !a.value;
        }
    }
    s
}

/// For every column of `sequence`'s truth table, the fewest nodes a tree
/// for it can have in any polarity of the memories.
pub fn column_bounds(sequence: &Sequence) -> Vec<usize> {
    let table = TruthTable::of(sequence);
    (0..table.columns.len())
        .map(|c| {
            let (on, off) = table.on_off(c);
            2 * fewest_variables(&on, &off, sequence.variables()).max(1) - 1
        })
        .collect()
}

/// The fewest variables that tell every on row from every off row.
fn fewest_variables(on: &[u32], off: &[u32], variables: usize) -> usize {
    let mut differences: Vec<u32> = on
        .iter()
        .flat_map(|a| off.iter().map(move |b| a ^ b))
        .collect();
    differences.sort_unstable();
    differences.dedup();
    // A difference that contains another is told apart whenever that one is.
    let minimal: Vec<u32> = differences
        .iter()
        .copied()
        .filter(|d| !differences.iter().any(|e| e != d && e & d == *e))
        .collect();
    (0..=variables)
        .find(|&k| subsets(variables, k).any(|s| minimal.iter().all(|d| d & s != 0)))
        .unwrap_or(variables)
}

/// Every set of `k` of `n` variables, as bit masks (Gosper's hack).
fn subsets(n: usize, k: usize) -> impl Iterator<Item = u32> {
    let end = 1u32 << n;
    let first = if k == 0 { 0 } else { (1u32 << k) - 1 };
    std::iter::successors(Some(first), move |&s| {
        if s == 0 {
            return None;
        }
        let low = s & s.wrapping_neg();
        let ripple = s + low;
        Some((((ripple ^ s) >> 2) / low) | ripple)
    })
    .take_while(move |&s| s < end)
}

/// What is known of one column: its smallest tree, or a bound below.
#[derive(Clone)]
enum Known {
    Tree(Expr),
    AtLeast(usize),
}

/// Columns by their sorted on and off rows.
type Memo = HashMap<(Vec<u32>, Vec<u32>), Known>;

/// Orders equal totals: the smaller largest equation, then memories set
/// first where possible (the usual reading), then the text.
type Key = (usize, usize, usize, String);

fn key(candidate: &Sequence, equations: &[Expr]) -> Key {
    let resets_first = (candidate.actuators..candidate.variables())
        .filter(|v| {
            candidate
                .actions
                .iter()
                .find(|a| a.var == *v)
                .is_some_and(|a| !a.value)
        })
        .count();
    (
        equations.iter().map(Expr::nodes).sum(),
        equations.iter().map(Expr::nodes).max().unwrap_or(0),
        resets_first,
        candidate.text(),
    )
}

/// The smallest equations of `candidate` when their total can be at most
/// `bound`; `Err(lower)` with a bound on its total when it cannot or the
/// search gave up.
fn evaluate(
    candidate: &Sequence,
    bounds: &[usize],
    bound: usize,
    memo: &mut Memo,
) -> Result<Vec<Expr>, usize> {
    let table = TruthTable::of(candidate);
    let columns: Vec<(Vec<u32>, Vec<u32>)> = (0..table.columns.len())
        .map(|c| {
            let (mut on, mut off) = table.on_off(c);
            on.sort_unstable();
            off.sort_unstable();
            (on, off)
        })
        .collect();
    let mut lower: Vec<usize> = columns
        .iter()
        .zip(bounds)
        .map(|(column, b)| match memo.get(column) {
            Some(Known::Tree(e)) => e.nodes(),
            Some(Known::AtLeast(n)) => (*n).max(*b),
            None => *b,
        })
        .collect();
    let mut trees: Vec<Option<Expr>> = columns
        .iter()
        .map(|column| match memo.get(column) {
            Some(Known::Tree(e)) => Some(e.clone()),
            _ => None,
        })
        .collect();
    // The cheapest columns first: their exact sizes tighten the room the
    // expensive ones get.
    let mut order: Vec<usize> = (0..columns.len()).collect();
    order.sort_by_key(|&c| lower[c]);
    for c in order {
        let total: usize = lower.iter().sum();
        if total > bound {
            return Err(total);
        }
        if trees[c].is_some() {
            continue;
        }
        let room = bound.saturating_sub(total - lower[c]);
        let limits = SearchLimits {
            max_nodes: SearchLimits::default().max_nodes.min(room),
            ..SearchLimits::default()
        };
        let (on, off) = &columns[c];
        match equations::smallest(on, off, candidate.variables(), limits) {
            Smallest::Found(expr) => {
                lower[c] = expr.nodes();
                memo.insert(columns[c].clone(), Known::Tree(expr.clone()));
                trees[c] = Some(expr);
            }
            Smallest::Larger => {
                lower[c] = lower[c].max(limits.max_nodes + 1);
                if limits.max_nodes == room {
                    memo.insert(columns[c].clone(), Known::AtLeast(lower[c]));
                }
                return Err(lower.iter().sum());
            }
            Smallest::GaveUp => return Err(lower.iter().sum()),
        }
    }
    Ok(trees.into_iter().flatten().collect())
}

/// The smallest tree of every column of `sequence`'s truth table, in column
/// order; `None` when a column has none within the search's limits (or the
/// synthesis's time ran out).
pub fn smallest_equations(sequence: &Sequence) -> Option<Vec<Expr>> {
    evaluate(
        sequence,
        &column_bounds(sequence),
        usize::MAX,
        &mut Memo::new(),
    )
    .ok()
}

/// The candidate with the smallest equations among every polarity of every
/// placement, searched until the synthesis's deadline; `progress` is told
/// the candidates settled of all. `None` when no candidate's equations could
/// be found.
pub fn choose(placements: &[Sequence], progress: &(dyn Fn(usize, usize) + Sync)) -> Option<Choice> {
    let mut ranked: Vec<(usize, Vec<usize>, &Sequence)> = placements
        .iter()
        .map(|p| {
            let bounds = column_bounds(p);
            (bounds.iter().sum(), bounds, p)
        })
        .collect();
    ranked.sort_by_key(|r| r.0);
    let flips = |p: &Sequence| 1usize << p.memories;
    let work: Vec<(usize, u32)> = ranked
        .iter()
        .enumerate()
        .flat_map(|(i, (_, _, p))| (0..flips(p) as u32).map(move |f| (i, f)))
        .collect();
    let candidates = work.len();
    // The best lower bound of each candidate, tightened as it is settled.
    let lower: Vec<AtomicUsize> = work
        .iter()
        .map(|(i, _)| AtomicUsize::new(ranked[*i].0))
        .collect();
    let best: Mutex<Option<(Key, Sequence, Vec<Expr>)>> = Mutex::new(None);
    let best_total = AtomicUsize::new(usize::MAX);
    let next = AtomicUsize::new(0);
    let settled = AtomicUsize::new(0);
    let deadline = budget::deadline();
    let worker = || {
        let _budget = budget::Budget::until(deadline);
        let mut memo = Memo::new();
        loop {
            let index = next.fetch_add(1, Ordering::Relaxed);
            if index >= candidates || budget::passed() {
                return;
            }
            let (i, flip) = work[index];
            let (placement_bound, bounds, placement) = &ranked[i];
            let bound = best_total.load(Ordering::Relaxed);
            if *placement_bound > bound {
                // Taken in the order of their bound: none left can win.
                for l in &lower[index..] {
                    l.fetch_max(bound + 1, Ordering::Relaxed);
                }
                settled.fetch_add(candidates - index, Ordering::Relaxed);
                next.store(candidates, Ordering::Relaxed);
                return;
            }
            let candidate = polarity(placement, flip);
            match evaluate(&candidate, bounds, bound, &mut memo) {
                Ok(trees) => {
                    let key = key(&candidate, &trees);
                    lower[index].store(key.0, Ordering::Relaxed);
                    let mut best = best.lock().unwrap_or_else(|e| e.into_inner());
                    if best.as_ref().is_none_or(|(k, ..)| key < *k) {
                        best_total.fetch_min(key.0, Ordering::Relaxed);
                        *best = Some((key, candidate, trees));
                    }
                }
                Err(_) if budget::exceeded() => return,
                Err(at_least) => {
                    lower[index].fetch_max(at_least, Ordering::Relaxed);
                }
            }
            progress(settled.fetch_add(1, Ordering::Relaxed) + 1, candidates);
        }
    };
    rayon::scope(|scope| {
        for _ in 0..rayon::current_num_threads() {
            scope.spawn(|_| worker());
        }
    });
    let mut best = best.into_inner().unwrap_or_else(|e| e.into_inner());
    if best.is_none() && settled.load(Ordering::Relaxed) < candidates {
        // Stopped before any candidate was done (a short limit on a busy
        // machine): the one with the lowest bound, searched to the end, so
        // that found memories always give an answer.
        let _unlimited = budget::Budget::until(None);
        let (i, flip) = work[0];
        let candidate = polarity(ranked[i].2, flip);
        if let Some(trees) = smallest_equations(&candidate) {
            let key = key(&candidate, &trees);
            lower[0].store(key.0, Ordering::Relaxed);
            settled.fetch_add(1, Ordering::Relaxed);
            best = Some((key, candidate, trees));
        }
    }
    let (key, sequence, equations) = best?;
    let lower_bound = lower
        .iter()
        .map(|l| l.load(Ordering::Relaxed))
        .min()
        .unwrap_or(key.0)
        .min(key.0);
    Some(Choice {
        sequence,
        equations,
        nodes: key.0,
        candidates,
        settled: settled.load(Ordering::Relaxed).min(candidates),
        lower_bound,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::sequence::{parse, parse_with_memories};

    #[test]
    fn a_column_bound_counts_the_variables_every_tree_must_read() {
        // A1 X1 A0 B1 X0 B0: A1 = NOT (b OR x) must read b and x (3 nodes
        // at least, 4 in fact); A0 = x reads one.
        let s = parse_with_memories("A1 X1 A0 B1 X0 B0").unwrap();
        let bounds = column_bounds(&s);
        let table = TruthTable::of(&s);
        for (c, bound) in bounds.iter().enumerate() {
            let (on, off) = table.on_off(c);
            let exact = equations::minimal(&on, &off, s.variables(), SearchLimits::default())
                .unwrap()
                .nodes();
            assert!(*bound <= exact, "column {c}: {bound} > {exact}");
        }
        assert_eq!(bounds[0], 3, "A1 reads b and x");
        assert_eq!(bounds[2], 1, "A0 = x");
    }

    /// The bounds only skip what cannot win: the choice is the smallest
    /// total of every candidate, searched one by one without them.
    #[test]
    fn the_choice_is_the_smallest_of_every_candidate() {
        for text in ["A0 A1 C1 C0 B1 B0", "A1 A0 A1 A0 A1 A0 B1 B0 C1 C0"] {
            let original = parse(text).unwrap();
            let minimal =
                crate::synth::search::minimal(&original, crate::synth::search::Limits::default())
                    .unwrap();
            let every: Vec<usize> = minimal
                .solutions
                .iter()
                .flat_map(|p| (0..1u32 << p.memories).map(move |f| polarity(p, f)))
                .map(|candidate| {
                    let table = TruthTable::of(&candidate);
                    (0..table.columns.len())
                        .map(|c| {
                            let (on, off) = table.on_off(c);
                            equations::minimal(
                                &on,
                                &off,
                                candidate.variables(),
                                SearchLimits::default(),
                            )
                            .unwrap()
                            .nodes()
                        })
                        .sum()
                })
                .collect();
            let choice = choose(&minimal.solutions, &|_, _| {}).unwrap();
            assert_eq!(choice.candidates, every.len(), "{text}");
            assert_eq!(choice.settled, every.len(), "{text}");
            assert_eq!(Some(&choice.nodes), every.iter().min(), "{text}");
            assert!(choice.proven(), "{text}");
            let sizes: usize = choice.equations.iter().map(Expr::nodes).sum();
            assert_eq!(sizes, choice.nodes, "{text}");
        }
    }

    /// A limit that passes before any candidate is done still gives an
    /// answer (the candidate with the lowest bound), not called proven.
    #[test]
    fn a_limit_past_before_any_candidate_still_answers() {
        let original = parse("A1 A0 A1 A0 A1 A0 B1 B0 C1 C0").unwrap();
        let minimal =
            crate::synth::search::minimal(&original, crate::synth::search::Limits::default())
                .unwrap();
        let _budget = budget::Budget::start(Some(std::time::Duration::ZERO));
        let choice = choose(&minimal.solutions, &|_, _| {}).unwrap();
        assert_eq!((choice.settled, choice.candidates), (1, 304));
        assert!(choice.sequence.is_valid());
        assert!(choice.lower_bound < choice.nodes, "{choice:?}");
        assert!(!choice.proven());
    }

    #[test]
    fn subsets_are_every_choice_of_k() {
        assert_eq!(subsets(4, 2).count(), 6);
        assert_eq!(subsets(4, 0).collect::<Vec<_>>(), vec![0]);
        assert!(subsets(5, 3).all(|s| s.count_ones() == 3 && s < 32));
    }
}
