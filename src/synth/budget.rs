//! The synthesis's time budget. Both routes are searches whose time grows
//! steeply with the sequence (a repeated two-cylinder cycle of 40 actions
//! ran for minutes), so each hot loop asks [`exceeded`] and gives up once
//! the deadline of the running synthesis has passed; the caller turns that
//! into an answer the engineer can act on. The deadline is per thread: the
//! searches run on the thread that called the synthesis.

use std::cell::Cell;
use std::time::{Duration, Instant};

thread_local! {
    static DEADLINE: Cell<Option<Instant>> = const { Cell::new(None) };
    static PASSED: Cell<bool> = const { Cell::new(false) };
    static CALLS: Cell<u32> = const { Cell::new(0) };
}

/// Holds the deadline while a synthesis runs; clears it when dropped.
pub(crate) struct Budget;

impl Budget {
    pub(crate) fn start(limit: Option<Duration>) -> Budget {
        DEADLINE.set(limit.map(|l| Instant::now() + l));
        PASSED.set(false);
        Budget
    }
}

impl Drop for Budget {
    fn drop(&mut self) {
        DEADLINE.set(None);
        PASSED.set(false);
    }
}

/// Whether the running synthesis is past its deadline. Cheap enough for an
/// inner loop: the clock is read once every 1,024 calls, and once passed
/// the answer stays.
pub(crate) fn exceeded() -> bool {
    if PASSED.get() {
        return true;
    }
    let Some(deadline) = DEADLINE.get() else {
        return false;
    };
    let calls = CALLS.get().wrapping_add(1);
    CALLS.set(calls);
    if calls.is_multiple_of(1024) && Instant::now() >= deadline {
        PASSED.set(true);
    }
    PASSED.get()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn passes_once_the_deadline_is_reached_and_clears_with_the_budget() {
        {
            let _budget = Budget::start(Some(Duration::ZERO));
            assert!((0..2048).any(|_| exceeded()));
            assert!(exceeded(), "stays passed");
        }
        assert!(!(0..2048).any(|_| exceeded()), "no budget, no deadline");
        let _budget = Budget::start(Some(Duration::from_secs(3600)));
        assert!(!(0..4096).any(|_| exceeded()));
    }
}
