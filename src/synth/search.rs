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
    original: &'a [Operation],
    actuators: usize,
    memories: usize,
    budget: usize,
    initial: u32,
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
        if odd > left || (left - odd) % 2 == 1 {
            return;
        }
        if pos == self.original.len() {
            if inserted == self.budget && state == self.initial {
                self.solutions.push(Sequence {
                    actuators: self.actuators,
                    memories: used,
                    memory_names: MEMORIES[..used].to_vec(),
                    actions: self.actions.clone(),
                });
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
    if original.actions.is_empty() || original.memories > 0 {
        return None;
    }
    let variables = original.actuators + limits.max_memories;
    if variables > 20 {
        return None;
    }
    let initial = original.initial_state();
    for budget in (0..=limits.max_insertions).step_by(2) {
        for memories in 0..=limits.max_memories.min(budget / 2) {
            if budget > 0 && memories == 0 {
                continue;
            }
            let mut dfs = Dfs {
                original: &original.actions,
                actuators: original.actuators,
                memories,
                budget,
                initial,
                seen: vec![0; (1usize << (original.actuators + memories)).div_ceil(64)],
                actions: Vec::new(),
                solutions: Vec::new(),
                max_solutions: limits.max_solutions,
            };
            dfs.place(0, initial, 0, 0);
            // A solution with fewer memories than allowed was already found
            // (or not) at a smaller `memories`: keep exactly this count.
            dfs.solutions.retain(|s| s.memories == memories);
            if !dfs.solutions.is_empty() {
                let truncated = dfs.solutions.len() >= limits.max_solutions;
                return Some(Minimal {
                    insertions: budget,
                    memories,
                    solutions: dfs.solutions,
                    truncated,
                });
            }
        }
    }
    None
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
    fn a_valid_sequence_needs_nothing() {
        let m = minimal(&parse("A1 B1 A0 B0").unwrap(), Limits::default()).unwrap();
        assert_eq!((m.insertions, m.memories), (0, 0));
    }
}
