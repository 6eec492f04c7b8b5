//! The exact route: the fewest memory operations (proven by the search),
//! then among their placements the smallest equations (the comparison of
//! `choose`), for the fewest memories and for one more. More memories can
//! give smaller equations (Table 5's third sequence: 49 nodes with 3, 48
//! with 4), so the engineer sees the front and picks (`--prefer`).

use super::budget;
use super::choose::{self, Choice};
use super::search;
use super::sequence::{MEMORIES, Sequence};
use super::{Options, SynthError, out_of_time};

/// How the smallest equations were chosen among the minimal modified
/// sequences, and what is proven about them.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Comparison {
    /// Minimal placements of the memory operations found.
    pub placements: usize,
    /// The search stopped listing placements at its limit: the comparison
    /// and its bound cover those listed.
    pub placements_truncated: bool,
    /// Candidates: every polarity of the memories of every placement.
    pub candidates: usize,
    /// Candidates searched or ruled out by their bound.
    pub settled: usize,
    /// No candidate's equations have fewer nodes in all.
    pub lower_bound: usize,
    /// Why the comparison stopped before settling every candidate.
    pub stopped: Option<Stopped>,
}

/// What ended a search early.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stopped {
    TimeLimit,
    Interrupted,
}

impl Stopped {
    /// The budget's reason, if it has passed.
    pub(crate) fn now() -> Option<Stopped> {
        if budget::interrupted() {
            Some(Stopped::Interrupted)
        } else if budget::passed() {
            Some(Stopped::TimeLimit)
        } else {
            None
        }
    }
}

/// Which point of the front to keep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Prefer {
    /// The fewest memories (proven), then its smallest equations.
    #[default]
    Memories,
    /// The smallest equations found on the front, then fewer memories.
    Nodes,
}

/// One point of the front: a memory count, at the fewest inserted
/// operations, and the smallest equations found for it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct FrontPoint {
    pub memories: usize,
    pub insertions: usize,
    pub nodes: usize,
    /// `A1 X1 A0 …`, the sequence that has them.
    pub sequence: String,
    pub comparison: Comparison,
    pub chosen: bool,
}

/// What the exact route found: the front, and the point kept with how it
/// was chosen.
pub(crate) struct Exact {
    pub insertions: usize,
    pub front: Vec<FrontPoint>,
    pub chosen: Choice,
    pub comparison: Comparison,
}

fn compared(found: &search::Minimal, choice: &Choice) -> Comparison {
    Comparison {
        placements: found.solutions.len(),
        placements_truncated: found.truncated,
        candidates: choice.candidates,
        settled: choice.settled,
        lower_bound: choice.lower_bound,
        stopped: if choice.settled < choice.candidates {
            Stopped::now()
        } else {
            None
        },
    }
}

pub(crate) fn route(
    original: &Sequence,
    options: Options,
    progress: &(dyn Fn(usize, usize) + Sync),
) -> Result<Exact, SynthError> {
    let limits = search::Limits::default();
    let Some(minimal) = search::minimal(original, limits) else {
        return Err(if Stopped::now().is_some() {
            out_of_time(original, options)
        } else {
            SynthError::NotFound(
                "no valid sequence with up to 4 memories and 12 inserted operations".to_string(),
            )
        });
    };
    let choice = choose::choose(&minimal.solutions, progress).ok_or_else(|| {
        if Stopped::now().is_some() {
            out_of_time(original, options)
        } else {
            SynthError::NotFound(
                "the equation search reached its limits on every minimal sequence".to_string(),
            )
        }
    })?;
    let mut points = vec![(compared(&minimal, &choice), choice)];
    // One memory more at the same number of operations, if there is room.
    let more = minimal.memories + 1;
    if minimal.memories > 0
        && more <= MEMORIES.len()
        && Stopped::now().is_none()
        && let Some(found) =
            search::placements(original, minimal.insertions, more, limits.max_solutions)
        && let Some(choice) = choose::choose(&found.solutions, progress)
    {
        points.push((compared(&found, &choice), choice));
    }
    let chosen = match options.prefer {
        Prefer::Memories => 0,
        // The smallest; on a tie the fewer memories (the first).
        Prefer::Nodes => (0..points.len())
            .min_by_key(|&i| (points[i].1.nodes, i))
            .unwrap_or(0),
    };
    let front = points
        .iter()
        .enumerate()
        .map(|(i, (comparison, choice))| FrontPoint {
            memories: choice.sequence.memories,
            insertions: minimal.insertions,
            nodes: choice.nodes,
            sequence: choice.sequence.text(),
            comparison: comparison.clone(),
            chosen: i == chosen,
        })
        .collect();
    let (comparison, chosen) = points.swap_remove(chosen);
    Ok(Exact {
        insertions: minimal.insertions,
        front,
        chosen,
        comparison,
    })
}
