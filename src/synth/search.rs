//! Exhaustive search for the fewest memory operations that make a sequence
//! valid: iterative deepening over the number of inserted operations, then
//! over the number of memories, so the first solutions found are provably
//! minimal. Symmetry breaking: memories are introduced in order X, Y, Z, W,
//! and each memory's first operation sets it (a memory whose first
//! operation resets it is the same memory with its value inverted).

use super::sequence::{MEMORIES, Operation, Sequence, apply};

/// Search limits: the most memories and inserted operations tried, and how
/// many minimal solutions are kept for choosing the smallest equations.
#[derive(Debug, Clone, Copy)]
pub struct Limits {
    pub max_memories: usize,
    pub max_insertions: usize,
    pub max_solutions: usize,
}

impl Default for Limits {
    fn default() -> Self {
        Limits {
            max_memories: MEMORIES.len(),
            max_insertions: 12,
            max_solutions: 4000,
        }
    }
}

/// All minimal modified sequences (fewest insertions, then fewest
/// memories), up to `limits.max_solutions`, and whether that cap cut the list.
#[derive(Debug, Clone)]
pub struct Minimal {
    pub insertions: usize,
    pub memories: usize,
    pub solutions: Vec<Sequence>,
    pub truncated: bool,
}

struct Dfs<'a> {
    sequence: &'a Sequence,
    original: &'a [Operation],
    actuators: usize,
    memories: usize,
    budget: usize,
    initial: u32,
    /// Operations the gaps after each gap must hold at least.
    needed_after: Vec<usize>,
    seen: Vec<u64>,
    actions: Vec<Operation>,
    solutions: Vec<Sequence>,
    max_solutions: usize,
}

impl Dfs<'_> {
    fn seen(&self, state: u32) -> bool {
        (self.seen[(state / 64) as usize] >> (state % 64)) & 1 == 1
    }

    fn mark(&mut self, state: u32, on: bool) {
        let word = &mut self.seen[(state / 64) as usize];
        if on {
            *word |= 1 << (state % 64);
        } else {
            *word &= !(1 << (state % 64));
        }
    }

    /// In the gap before original action `pos` (or the closing gap when
    /// `pos` is past the end), with `inserted` operations so far.
    fn gap(&mut self, pos: usize, state: u32, inserted: usize, used: usize) {
        if self.solutions.len() >= self.max_solutions || super::budget::exceeded() {
            return;
        }
        // Memories toggled an odd number of times must each be toggled again.
        let odd = (0..used)
            .filter(|j| (state >> (self.actuators + j)) & 1 == 1)
            .count();
        let left = self.budget - inserted;
        if odd > left || (left - odd) % 2 == 1 || self.needed_after[pos] > left {
            return;
        }
        if pos == self.original.len() {
            if inserted == self.budget && state == self.initial {
                self.solutions
                    .push(self.sequence.with_memories(used, self.actions.clone()));
            }
        } else {
            self.place(pos, state, inserted, used);
        }
        if inserted < self.budget {
            for j in 0..(used + 1).min(self.memories) {
                let var = self.actuators + j;
                let action = Operation {
                    var,
                    value: (state >> var) & 1 == 0,
                };
                if self.seen(state) {
                    break;
                }
                self.mark(state, true);
                self.actions.push(action);
                self.gap(pos, apply(state, action), inserted + 1, used.max(j + 1));
                self.actions.pop();
                self.mark(state, false);
            }
        }
    }

    fn place(&mut self, pos: usize, state: u32, inserted: usize, used: usize) {
        let action = self.original[pos];
        if self.seen(state) || (state >> action.var) & 1 == u32::from(action.value) {
            return;
        }
        self.mark(state, true);
        self.actions.push(action);
        self.gap(pos + 1, apply(state, action), inserted, used);
        self.actions.pop();
        self.mark(state, false);
    }
}

/// Finds the minimal modified sequences of `original` (which has no memories).
/// `None` when none exists within the limits.
pub fn minimal(original: &Sequence, limits: Limits) -> Option<Minimal> {
    if original.actions.is_empty()
        || original.memories > 0
        || original.actuators + limits.max_memories > 20
    {
        return None;
    }
    let (fewest_insertions, fewest_memories) = lower_bounds(original);
    let needed_after = needed_after(original);
    for budget in (fewest_insertions..=limits.max_insertions).step_by(2) {
        for memories in fewest_memories..=limits.max_memories.min(budget / 2) {
            if budget > 0 && memories == 0 {
                continue;
            }
            let found = search(
                original,
                budget,
                memories,
                &needed_after,
                limits.max_solutions,
            );
            if found.is_some() {
                return found;
            }
        }
    }
    None
}

/// The valid modified sequences of `original` with exactly `insertions`
/// inserted operations of exactly `memories` memories, up to
/// `max_solutions`; `None` when there is none (or the time ran out first).
pub fn placements(
    original: &Sequence,
    insertions: usize,
    memories: usize,
    max_solutions: usize,
) -> Option<Minimal> {
    if original.memories > 0
        || original.actuators + memories > 20
        || memories > MEMORIES.len()
        || insertions % 2 == 1
    {
        return None;
    }
    search(
        original,
        insertions,
        memories,
        &needed_after(original),
        max_solutions,
    )
}

fn search(
    original: &Sequence,
    budget: usize,
    memories: usize,
    needed_after: &[usize],
    max_solutions: usize,
) -> Option<Minimal> {
    let mut dfs = Dfs {
        sequence: original,
        original: &original.actions,
        actuators: original.actuators,
        memories,
        budget,
        initial: original.initial_state(),
        needed_after: needed_after.to_vec(),
        seen: vec![0; (1usize << (original.actuators + memories)).div_ceil(64)],
        actions: Vec::new(),
        solutions: Vec::new(),
        max_solutions,
    };
    dfs.place(0, dfs.initial, 0, 0);
    // A solution with fewer memories than allowed is found (or not) at a
    // smaller `memories`: keep exactly this count.
    dfs.solutions.retain(|s| s.memories == memories);
    if dfs.solutions.is_empty() {
        return None;
    }
    // Cut by the list's limit or by the time limit.
    let truncated = dfs.solutions.len() >= max_solutions || super::budget::passed();
    Some(Minimal {
        insertions: budget,
        memories,
        solutions: dfs.solutions,
        truncated,
    })
}

/// The stretches of the cycle in which a memory must change, as (first
/// gap, last gap), gap g lying before action g (gap n = gap 0, the closing
/// one), unrolled: last < first + n; and the fewest memories.
fn stretches(original: &Sequence) -> (Vec<(usize, usize)>, usize) {
    let states = original.pre_states();
    let n = states.len();
    let mut stretches: Vec<(usize, usize)> = Vec::new();
    let mut memories = 0;
    for (p, state) in states.iter().enumerate() {
        let visits: Vec<usize> = (0..n).filter(|q| states[*q] == *state).collect();
        if visits[0] != p || visits.len() < 2 {
            continue;
        }
        memories = memories.max(visits.len().next_power_of_two().trailing_zeros() as usize);
        for (i, &from) in visits.iter().enumerate() {
            let to = visits.get(i + 1).copied().unwrap_or(visits[0] + n);
            stretches.push((from + 1, to));
        }
    }
    (stretches, memories)
}

/// For each gap g, the fewest operations the gaps after it must hold: the
/// stretches that lie wholly after g, cut greedily by their ends.
fn needed_after(original: &Sequence) -> Vec<usize> {
    let n = original.actions.len();
    let (mut stretches, _) = stretches(original);
    stretches.retain(|s| s.1 <= n);
    stretches.sort_by_key(|s| s.1);
    (0..=n)
        .map(|g| {
            let mut cut: Option<usize> = None;
            let mut count = 0;
            for &(a, b) in stretches.iter().filter(|s| s.0 > g) {
                if cut.is_none_or(|c| c < a) {
                    cut = Some(b);
                    count += 1;
                }
            }
            count
        })
        .collect()
}

/// Fewest inserted operations and memories any valid modified sequence
/// needs, so that the search does not prove smaller counts impossible one by
/// one. A state met k times before actions needs k memory codes (at least
/// ⌈log2 k⌉ memories), and between two of its visits in a row a memory must
/// change: the fewest gaps that cut every such stretch of the cycle, rounded
/// up to even (every memory ends where it started).
pub fn lower_bounds(original: &Sequence) -> (usize, usize) {
    let n = original.actions.len();
    let (stretches, memories) = stretches(original);
    if stretches.is_empty() {
        return (0, 0);
    }
    // Fewest points cutting every stretch of a circle: some cut lies in the
    // first stretch, so try each of its gaps first and cover the rest
    // greedily by their ends, which is optimal on a line.
    let (first, last) = stretches[0];
    let cuts = (first..=last)
        .map(|start| {
            // Unroll the circle from just after `start`.
            let mut rest: Vec<(usize, usize)> = stretches
                .iter()
                .filter_map(|&(a, b)| {
                    let shift = |g: usize| (g + 2 * n - start - 1) % n;
                    let (a, b) = (shift(a), shift(a) + (b - a));
                    // Contains `start` (at n - 1 once unrolled): cut already.
                    (b < n - 1).then_some((a, b))
                })
                .collect();
            rest.sort_by_key(|r| r.1);
            let mut count = 1;
            let mut cut: Option<usize> = None;
            for (a, b) in rest {
                if cut.is_none_or(|c| c < a) {
                    cut = Some(b);
                    count += 1;
                }
            }
            count
        })
        .min()
        .unwrap_or(0);
    let insertions = cuts.max(2 * memories);
    (insertions + insertions % 2, memories)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::sequence::parse;

    #[test]
    fn the_classic_needs_one_memory_and_two_operations() {
        let m = minimal(&parse("A1 A0 B1 B0").unwrap(), Limits::default()).unwrap();
        assert_eq!((m.insertions, m.memories), (2, 1));
        assert!(m.solutions.iter().all(Sequence::is_valid));
        assert!(m.solutions.iter().any(|s| s.text() == "A1 X1 A0 B1 X0 B0"));
    }

    #[test]
    fn the_lower_bounds_never_exceed_the_minimum() {
        for (text, insertions, memories) in [
            ("A1 A0 B1 B0", 2, 1),
            ("A0 A1 C1 C0 B1 B0", 4, 2),
            ("A1 A0 A1 A0 A1 A0 B1 B0 C1 C0", 8, 3),
            ("A1 A0 B1 B0 C1 C0 D1 D0 E1 E0 F1 F0", 6, 3),
            ("A1 B1 A0 B0", 0, 0),
            ("B1 D1 B0 C1 B1 D0 B0 C0", 0, 0),
        ] {
            let original = parse(text).unwrap();
            let (fewest_insertions, fewest_memories) = lower_bounds(&original);
            assert!(
                fewest_insertions <= insertions,
                "{text}: {fewest_insertions}"
            );
            assert!(fewest_memories <= memories, "{text}: {fewest_memories}");
            let m = minimal(&original, Limits::default()).unwrap();
            assert_eq!((m.insertions, m.memories), (insertions, memories), "{text}");
        }
        // Six visits of the home state need six cuts and three memories: the
        // bound is the answer, so nothing below it is searched.
        let six = parse("A1 A0 B1 B0 C1 C0 D1 D0 E1 E0 F1 F0").unwrap();
        assert_eq!(lower_bounds(&six), (6, 3));
    }

    #[test]
    fn a_valid_sequence_needs_nothing() {
        let m = minimal(&parse("A1 B1 A0 B0").unwrap(), Limits::default()).unwrap();
        assert_eq!((m.insertions, m.memories), (0, 0));
    }
}
