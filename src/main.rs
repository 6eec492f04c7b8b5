//! The `steptable` command: the library's command line ([`steptable::cli`]).

/// The system allocator, which ends a user's template that asks for more
/// memory than it may have with exit 1 and its name, not an abort.
#[global_allocator]
static ALLOCATOR: steptable::alloc_guard::Guard = steptable::alloc_guard::Guard;

fn main() {
    std::process::exit(steptable::cli::run());
}
