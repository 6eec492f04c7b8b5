//! A bound on the memory a user's template may take while it renders.
//!
//! The output budget stops a template that writes too much, but a value
//! built inside a render (a string doubled in a loop: `{% set ns.s = ns.s ~
//! ns.s %}`) grows before anything is written, and minijinja bounds no
//! concatenation: forty doublings ask for a terabyte, and a refused
//! allocation aborts the process with a backtrace. The binary's allocator
//! ([`Guard`], registered in `main.rs`) watches the threads rendering a
//! user's template or compiling it ([`Scope`]: compiling folds constant
//! expressions such as `'x' * 100000000`): an allocation past the scope's limit, or
//! one the system refuses, ends the run with exit 1 and a message naming
//! the template, instead of the abort. Nothing was written for it (outputs
//! are written after every file is rendered). Outside a scope the allocator
//! is the system's, one relaxed atomic load per allocation more.

use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;
use std::io::Write;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Scopes open on any thread: zero almost always, and then nothing is looked up.
static OPEN: AtomicUsize = AtomicUsize::new(0);

thread_local! {
    /// This thread's scope: the largest allocation allowed, and the
    /// template's file name (bytes owned by the [`Scope`]).
    static SCOPE: Cell<Option<(usize, *const u8, usize)>> = const { Cell::new(None) };
}

/// While alive, allocations on this thread are bounded by `limit`, in the
/// name of `file`.
pub struct Scope {
    _file: Box<str>,
    previous: Option<(usize, *const u8, usize)>,
}

impl Scope {
    pub fn enter(file: &str, limit: usize) -> Scope {
        let file: Box<str> = file.into();
        let previous = SCOPE.with(|s| s.replace(Some((limit, file.as_ptr(), file.len()))));
        OPEN.fetch_add(1, Ordering::SeqCst);
        Scope {
            _file: file,
            previous,
        }
    }
}

impl Drop for Scope {
    fn drop(&mut self) {
        SCOPE.with(|s| s.set(self.previous));
        OPEN.fetch_sub(1, Ordering::SeqCst);
    }
}

/// The scope of this thread, if any scope is open anywhere.
fn scope() -> Option<(usize, *const u8, usize)> {
    if OPEN.load(Ordering::Relaxed) == 0 {
        return None;
    }
    SCOPE.try_with(Cell::get).ok().flatten()
}

/// Ends the process: the template asked for more memory than it may have.
/// Writes without allocating (the message is pieces of bytes), and leaves
/// the scope first so that nothing below comes back here.
fn refuse(size: usize, (limit, name, len): (usize, *const u8, usize)) -> ! {
    let _ = SCOPE.try_with(|s| s.set(None));
    // SAFETY: the bytes belong to the Scope that set them, alive while its
    // thread renders, which is the thread here.
    let name = unsafe { std::slice::from_raw_parts(name, len) };
    let mut err = std::io::stderr().lock();
    let mut number = [0u8; 20];
    let _ = err.write_all(name);
    let _ = err.write_all(b": the template asked for a value of ");
    let _ = err.write_all(digits(size >> 20, &mut number));
    let _ = err.write_all(b" MiB (the most is ");
    let _ = err.write_all(digits(limit >> 20, &mut number));
    let _ = err.write_all(b" MiB, four times its output budget); stopped, nothing written\n");
    let _ = err.flush();
    std::process::exit(1)
}

/// `n` in decimal, in `buf`.
fn digits(mut n: usize, buf: &mut [u8; 20]) -> &[u8] {
    let mut at = buf.len();
    loop {
        at -= 1;
        buf[at] = b'0' + (n % 10) as u8;
        n /= 10;
        if n == 0 {
            return &buf[at..];
        }
    }
}

/// The system allocator, bounded inside a [`Scope`].
pub struct Guard;

// SAFETY: every call goes to `System` unchanged, or ends the process.
unsafe impl GlobalAlloc for Guard {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        check(layout.size());
        let p = unsafe { System.alloc(layout) };
        refused(p, layout.size())
    }

    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        check(layout.size());
        let p = unsafe { System.alloc_zeroed(layout) };
        refused(p, layout.size())
    }

    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        unsafe { System.dealloc(ptr, layout) }
    }

    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        check(new_size);
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        refused(p, new_size)
    }
}

fn check(size: usize) {
    if let Some(scope) = scope()
        && size > scope.0
    {
        refuse(size, scope);
    }
}

fn refused(p: *mut u8, size: usize) -> *mut u8 {
    if p.is_null()
        && let Some(scope) = scope()
    {
        refuse(size, scope);
    }
    p
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn digits_are_written_without_allocating() {
        let mut buf = [0u8; 20];
        assert_eq!(digits(0, &mut buf), b"0");
        assert_eq!(digits(1024, &mut buf), b"1024");
        assert_eq!(
            digits(usize::MAX, &mut buf),
            usize::MAX.to_string().as_bytes()
        );
    }

    #[test]
    fn scopes_nest_and_close() {
        assert_eq!(scope(), None);
        {
            let _outer = Scope::enter("a.j2", 10);
            assert_eq!(scope().map(|s| s.0), Some(10));
            {
                let _inner = Scope::enter("b.j2", 20);
                assert_eq!(scope().map(|s| (s.0, s.2)), Some((20, 4)));
            }
            assert_eq!(scope().map(|s| s.0), Some(10));
        }
        assert_eq!(scope(), None);
    }
}
