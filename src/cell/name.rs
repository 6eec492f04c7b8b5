//! The name of a machine input or output (`I:part_present`,
//! `Y:vacuum+`): what a PLC may show, checked as the engineer typed it.

use std::fmt;

use super::{ascii_spelling, zero_width};

/// Longest name of a machine input or output (`I:part_present`).
pub const MAX_NAME_CHARS: usize = 16;
/// The name of a machine input or output: lower-case ASCII letters, digits
/// and `_`, starting with a letter, at most [`MAX_NAME_CHARS`]. Stored inline
/// so that signals stay `Copy`.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Name {
    len: u8,
    bytes: [u8; MAX_NAME_CHARS],
}

impl Name {
    /// Checks and stores a name (already lower case).
    pub fn new(text: &str) -> Result<Name, String> {
        let valid_chars = text
            .bytes()
            .all(|b| b.is_ascii_lowercase() || b.is_ascii_digit() || b == b'_');
        if text.is_empty() {
            return Err("the name is missing".to_string());
        }
        // `tür`: ü is a letter, but not one a PLC name may hold.
        if let Some(c) = text.chars().find(|c| c.is_alphanumeric() && !c.is_ascii()) {
            let spelt = ascii_spelling(text)
                .filter(|s| Name::new(s).is_ok())
                .map(|s| format!(" (write it \"{s}\")"))
                .unwrap_or_default();
            return Err(format!(
                "\"{text}\" is not a name: \"{c}\" is no letter a-z, and a PLC name holds only those, digits and _{spelt}"
            ));
        }
        if !valid_chars || !text.as_bytes()[0].is_ascii_lowercase() {
            return Err(format!(
                "\"{text}\" is not a name: use letters, digits and _, starting with a letter"
            ));
        }
        if text.contains("__") || text.ends_with('_') {
            return Err(format!(
                "\"{text}\" is not a name: IEC 61131-3 forbids a double or trailing _"
            ));
        }
        if text.len() > MAX_NAME_CHARS {
            return Err(format!(
                "\"{text}\" is longer than {MAX_NAME_CHARS} characters"
            ));
        }
        let mut bytes = [0u8; MAX_NAME_CHARS];
        bytes[..text.len()].copy_from_slice(text.as_bytes());
        Ok(Name {
            len: text.len() as u8,
            bytes,
        })
    }

    pub fn as_str(&self) -> &str {
        // Only ASCII is ever stored.
        std::str::from_utf8(&self.bytes[..self.len as usize]).unwrap_or("")
    }
}

impl fmt::Display for Name {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

impl fmt::Debug for Name {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}", self.as_str())
    }
}

/// Why the name of a wait or output is no name as the engineer typed it,
/// before the item is read as a move is (`part²` would read as `part2`, a
/// zero-width space would vanish): a name is what the PLC shows, so it is
/// refused rather than rewritten.
pub(super) fn raw_name_problem(text: &str) -> Option<String> {
    let (_, after) = text.trim().split_once([':', '\u{FF1A}'])?;
    let name = after.split(['=', '\u{FF1D}']).next().unwrap_or("");
    let item = text.trim();
    if let Some(c) = name.chars().find(|c| zero_width(*c)) {
        return Some(format!(
            "\"{}\": the name holds the invisible character U+{:04X}: delete it",
            item.replace(c, ""),
            c as u32
        ));
    }
    // A sign at its end may be any plus or minus the move reader takes.
    let name = name.trim().trim_end_matches(|c: char| !c.is_alphanumeric());
    if !name.chars().any(|c| c.is_alphanumeric() && !c.is_ascii()) {
        return None;
    }
    Name::new(&name.to_lowercase())
        .err()
        .map(|e| format!("\"{item}\": {e}"))
}
