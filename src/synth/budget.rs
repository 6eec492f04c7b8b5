//! The synthesis's time budget. Both routes are searches whose time grows
//! steeply with the sequence (a repeated two-cylinder cycle of 40 actions
//! ran for minutes), so each hot loop asks [`exceeded`] and gives up once
//! the deadline of the running synthesis has passed; the caller turns that
//! into an answer the engineer can act on. The deadline is per thread: the
//! searches run on the thread that called the synthesis.

use std::cell::Cell;
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

thread_local! {
    static DEADLINE: Cell<Option<Instant>> = const { Cell::new(None) };
    static PASSED: Cell<bool> = const { Cell::new(false) };
    static CALLS: Cell<u32> = const { Cell::new(0) };
}

/// Set by [`interrupt`] (the command's Ctrl-C handler): every running
/// synthesis stops as at its deadline and keeps what it has.
static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Stops every running synthesis as if its time were up.
pub fn interrupt() {
    INTERRUPTED.store(true, Ordering::Relaxed);
}

/// Whether [`interrupt`] was called.
pub fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}

/// Holds the deadline while a synthesis runs; puts back the thread's
/// previous deadline when dropped (a worker thread of the synthesis may be
/// the thread that started it).
pub(crate) struct Budget {
    previous: (Option<Instant>, bool),
}

impl Budget {
    pub(crate) fn start(limit: Option<Duration>) -> Budget {
        Budget::until(limit.map(|l| Instant::now() + l))
    }

    /// The same deadline on another thread.
    pub(crate) fn until(deadline: Option<Instant>) -> Budget {
        let previous = (DEADLINE.replace(deadline), PASSED.replace(false));
        Budget { previous }
    }
}

impl Drop for Budget {
    fn drop(&mut self) {
        DEADLINE.set(self.previous.0);
        PASSED.set(self.previous.1);
    }
}

/// The running synthesis's deadline on this thread, for its workers.
pub(crate) fn deadline() -> Option<Instant> {
    DEADLINE.get()
}

/// Whether the running synthesis is past its deadline or interrupted, the
/// clock read now.
pub(crate) fn passed() -> bool {
    let passed =
        PASSED.get() || interrupted() || DEADLINE.get().is_some_and(|d| Instant::now() >= d);
    PASSED.set(passed);
    passed
}

/// Whether the running synthesis is past its deadline or interrupted.
/// Cheap enough for an inner loop: the clock is read once every 1,024
/// calls, and once passed the answer stays.
pub(crate) fn exceeded() -> bool {
    if PASSED.get() {
        return true;
    }
    let calls = CALLS.get().wrapping_add(1);
    CALLS.set(calls);
    if !calls.is_multiple_of(1024) {
        return false;
    }
    let passed = interrupted() || DEADLINE.get().is_some_and(|d| Instant::now() >= d);
    PASSED.set(passed);
    passed
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
