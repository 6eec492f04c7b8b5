//! The labels around the moves: `BRANCH 1` / `STEP 3 (clamp)` headers and
//! their comments, actuator names (`C2 (clamp)`), and the text a cell
//! shows once its invisible characters are gone.

use super::*;

/// A header cell of the published layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Header {
    Branch(u32),
    Step(u32),
}

/// Recognises `BRANCH 1` / `STEP 1` in any case and spacing, also with a
/// comment after the number (`STEP 3 (clamp)`, `STEP 3: clamp`, `BRANCH 2 -
/// gripper`): engineers name their steps, and a label we do not recognise
/// loses its row.
pub fn header_kind(text: &str) -> Option<Header> {
    // `STEP 1 0`: step 10, or step 1 with a note 0? Not ours to guess.
    let word_end = text
        .trim_start()
        .find(|c: char| !c.is_alphabetic())
        .unwrap_or(0);
    let number: String = text.trim_start()[word_end..]
        .chars()
        .take_while(|c| c.is_whitespace() || c.is_ascii_digit())
        .collect();
    if super::split_number(&number) {
        return None;
    }
    let squeezed: String = text.chars().filter(|c| !c.is_whitespace()).collect();
    if let Some(header) = bare_header(&squeezed) {
        return Some(header);
    }
    // `STEP 3 (clamp)`: the word, the number, then a separator and a comment.
    let trimmed = text.trim();
    let digits_end = trimmed
        .char_indices()
        .skip_while(|(_, c)| c.is_alphabetic() || c.is_whitespace())
        .find(|(_, c)| !c.is_ascii_digit())
        .map(|(i, _)| i)?;
    let (head, comment) = trimmed.split_at(digits_end);
    let separator = comment.chars().next()?;
    // A comment that reads as a move is a cell the label swallowed
    // (`STEP 1,C1+1` read with the wrong CSV delimiter).
    let rest = comment.trim_start_matches(|c: char| !c.is_alphanumeric());
    if separator.is_alphanumeric() || separator == '_' || looks_like_item(rest) {
        return None;
    }
    let squeezed: String = head.chars().filter(|c| !c.is_whitespace()).collect();
    bare_header(&squeezed)
}

/// The comment a `STEP n` label carries (`clamp part` of `STEP 3 (clamp
/// part)`, `eject` of `STEP 4: eject`): what follows the number, without
/// its separator and a closing bracket; `None` for a bare label.
pub fn step_comment(text: &str) -> Option<String> {
    if !matches!(header_kind(text), Some(Header::Step(_))) {
        return None;
    }
    let trimmed = text.trim();
    let after = trimmed
        .char_indices()
        .skip_while(|(_, c)| c.is_alphabetic() || c.is_whitespace())
        .find(|(_, c)| !c.is_ascii_digit())
        .map(|(i, _)| &trimmed[i..])?;
    // `STEP 2.5`: a number's decimals, not a comment `5` (W002 names the
    // label as written).
    let after = match decimals(after) {
        Some(rest) => rest,
        None => after,
    };
    label_comment(after)
}

/// What follows the decimals of a label's number (`.5 (lift)` after `STEP
/// 2`), when they are there.
pub fn decimals(after: &str) -> Option<&str> {
    let rest = after.strip_prefix(['.', ','])?;
    let digits = rest.chars().take_while(char::is_ascii_digit).count();
    (digits > 0).then(|| &rest[digits..])
}

/// The comment after a label's number (`(clamp part)`, `: eject`, `- lift`)
/// without its separator: brackets only where they enclose the whole
/// comment (`(clamp) extra` keeps both, `((x))` keeps the inner pair), a
/// dash only where a space follows it (`-5 bar` and `-> z` are the
/// comment); `None` when nothing is left.
fn label_comment(after: &str) -> Option<String> {
    let after = after.trim();
    let comment = if let Some(inner) = enclosed(after) {
        inner
    } else if let Some(rest) = after.strip_prefix([':', '.', ',', ';', '=']) {
        rest
    } else {
        let dash = after.strip_prefix(['-', '–', '—']);
        match dash {
            Some(rest) if rest.starts_with(char::is_whitespace) => rest,
            _ => after,
        }
    };
    let comment = visible_text(comment);
    let comment = comment.trim();
    (!comment.is_empty()).then(|| comment.to_string())
}

/// What a pair of brackets encloses when the first `(` of `text` closes
/// at its last character.
fn enclosed(text: &str) -> Option<&str> {
    let inner = text.strip_prefix('(')?.strip_suffix(')')?;
    let mut depth = 0usize;
    for c in inner.chars() {
        match c {
            '(' => depth += 1,
            ')' if depth == 0 => return None,
            ')' => depth -= 1,
            _ => {}
        }
    }
    Some(inner)
}

/// Free text (a comment, an actuator's name) as the engineer sees it: a
/// vertical tab, form feed or Unicode line or paragraph separator (Word's
/// soft line break pasted into a cell, stored as `_x000B_`) is a line
/// break; other control characters and Unicode noncharacters show as
/// nothing and are left out, so that no written file (XML, SVG, a PLC
/// comment) carries a character its format forbids. The table's own cells
/// keep them, and a move with one is refused (E010).
pub fn visible_text(raw: &str) -> String {
    if !raw.chars().any(is_invisible) {
        return raw.to_string();
    }
    raw.chars()
        .filter_map(|c| match c {
            '\u{b}' | '\u{c}' | '\u{2028}' | '\u{2029}' => Some('\n'),
            c if is_invisible(c) => None,
            c => Some(c),
        })
        .collect()
}

fn is_invisible(c: char) -> bool {
    let noncharacter = matches!(c as u32, 0xFDD0..=0xFDEF) || (c as u32) & 0xFFFE == 0xFFFE;
    (c.is_control() && !matches!(c, '\t' | '\n' | '\r'))
        || noncharacter
        || matches!(c, '\u{2028}' | '\u{2029}')
}

/// `BRANCH1` / `STEP1` with nothing else, any case.
fn bare_header(squeezed: &str) -> Option<Header> {
    let split = squeezed.find(|c: char| c.is_ascii_digit())?;
    let (word, number) = squeezed.split_at(split);
    if !number.chars().all(|c| c.is_ascii_digit()) {
        return None;
    }
    let number: u32 = number.parse().ok()?;
    if word.eq_ignore_ascii_case("BRANCH") {
        Some(Header::Branch(number))
    } else if word.eq_ignore_ascii_case("STEP") {
        Some(Header::Step(number))
    } else {
        None
    }
}

/// An actuator named exactly (`C2`, `c2`, `C 2`, nothing after it), as a
/// command-line option or a home order names one; `None` when out of range.
/// The one parser of `C<n>` outside the cell grammar.
pub fn parse_actuator(text: &str) -> Option<u32> {
    let number = actuator_name(text)?;
    (normalize(text) == format!("C{number}")).then_some(number)
}

/// An actuator named in a settings row or option: `C2`, `c 2`, also with a
/// comment after it (`C2 (clamp)`, `C2: gripper`, `C2 lift`). `None` when
/// the text names no actuator in range.
pub fn actuator_name(text: &str) -> Option<u32> {
    let mut chars = text.trim().chars().peekable();
    let one = |c: char| normalize(c.encode_utf8(&mut [0; 4]));
    if one(chars.next()?) != "C" {
        return None;
    }
    while chars.peek().is_some_and(|c| c.is_whitespace()) {
        chars.next();
    }
    let mut number = String::new();
    while let Some(&c) = chars.peek() {
        let n = one(c);
        if n.len() == 1 && n.as_bytes()[0].is_ascii_digit() {
            number.push_str(&n);
            chars.next();
        } else {
            break;
        }
    }
    if chars
        .peek()
        .is_some_and(|c| c.is_alphanumeric() || *c == '_')
    {
        return None;
    }
    // `C1 0`: C10, or C1 named 0? Not ours to guess.
    if super::split_number(text) {
        return None;
    }
    number
        .parse()
        .ok()
        .filter(|n| (1..=MAX_ACTUATOR).contains(n))
}

/// The comment after an actuator's number in a settings row (`clamp` of
/// `C1 (clamp)`, `gripper` of `C2: gripper`, `lift` of `C2 lift`); `None`
/// for a bare `C2` or a text that names no actuator.
pub fn actuator_comment(text: &str) -> Option<String> {
    actuator_name(text)?;
    let trimmed = text.trim();
    // Past the `C`, the spaces and the digits (in any width the name allows).
    let after = trimmed
        .char_indices()
        .skip(1)
        .skip_while(|(_, c)| c.is_whitespace())
        .find(|(_, c)| {
            let n = normalize(c.encode_utf8(&mut [0; 4]));
            !(n.len() == 1 && n.as_bytes()[0].is_ascii_digit())
        })
        .map(|(i, _)| &trimmed[i..])?;
    label_comment(after)
}

/// True when the text looks like an attempt at a move (`C` followed by a digit
/// after normalisation). Used to find a bare grid of moves without headers.
pub fn looks_like_move(text: &str) -> bool {
    let norm = normalize(text);
    let mut chars = norm.chars();
    chars.next() == Some('C') && chars.next().is_some_and(|c| c.is_ascii_digit())
}

/// True when the text looks like an attempt at any cell item: a move, or
/// `T=`, `I:`, `Y:` (possibly after other items and a `;`).
pub fn looks_like_item(text: &str) -> bool {
    let norm = normalize(text);
    looks_like_move(text)
        || norm.starts_with("T=")
        || norm.starts_with("I:")
        || norm.starts_with("Y:")
        || norm.starts_with("J:")
}
