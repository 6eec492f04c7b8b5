//! The rows of STEP 7's symbol table (`NAME.sdf`), laid out by
//! `symbols.sdf.j2` from the model the AWL emitter (`awl.rs`) builds: fixed-width
//! quoted fields, the comment at most [`SDF_COMMENT`] characters.

use serde::Serialize;

use super::one_line;

#[derive(Serialize, Clone)]
pub(super) struct Symbol {
    pub(super) symbol: String,
    address: String,
    data_type: &'static str,
    comment: String,
    /// The comment was longer than the symbol table holds (see [`sdf_comment`]).
    #[serde(skip)]
    pub(super) cut: bool,
}

/// The characters a comment of STEP 7's symbol table holds.
pub const SDF_COMMENT: usize = 80;

/// A comment as the symbol table holds it: one line, quoted fields so an
/// engineer's `"` becomes `'`, and at most [`SDF_COMMENT`] characters. A
/// longer one (a long step comment or actuator name) would widen the
/// fixed-width row past what STEP 7 imports, so it is cut to 77
/// characters and `...`, the same every run; the `.awl` keeps it whole.
fn sdf_comment(text: &str) -> (String, bool) {
    super::shorten(&one_line(text).replace('"', "'"), SDF_COMMENT)
}

impl Symbol {
    pub(super) fn new(
        symbol: String,
        address: String,
        data_type: &'static str,
        comment: &str,
    ) -> Symbol {
        let (comment, cut) = sdf_comment(comment);
        Symbol {
            symbol,
            address,
            data_type,
            comment,
            cut,
        }
    }
}
