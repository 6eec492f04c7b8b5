//! The move-cell grammar: `C<actuator><sign><position>`, written the way engineers
//! actually type it (any case, spaces, Unicode minus and dashes, sub- and
//! superscript digits from copy-paste, a Cyrillic `С` from a Serbian keyboard).

use std::fmt;

mod hint;
mod label;
mod name;
mod unicode;
pub use hint::{edit_distance, move_attempts, not_a_move_hint, split_number, split_number_hint};
pub use label::{
    Header, actuator_comment, actuator_name, decimals, header_kind, looks_like_item,
    looks_like_move, parse_actuator, step_comment, visible_text,
};
use name::raw_name_problem;
pub use name::{MAX_NAME_CHARS, Name};
pub use unicode::{ascii_spelling, composed, composed_str, folded, zero_width};

/// Largest actuator number accepted (`C999`).
pub const MAX_ACTUATOR: u32 = 999;
/// Largest position number accepted (`C1+63`).
pub const MAX_POSITION: u32 = 63;

/// Direction of a move: `+` extends (towards higher positions), `-` retracts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash, serde::Serialize)]
pub enum Sign {
    #[serde(rename = "+")]
    Plus,
    #[serde(rename = "-")]
    Minus,
}

impl Sign {
    pub fn symbol(self) -> char {
        match self {
            Sign::Plus => '+',
            Sign::Minus => '-',
        }
    }

    pub fn opposite(self) -> Sign {
        match self {
            Sign::Plus => Sign::Minus,
            Sign::Minus => Sign::Plus,
        }
    }
}

/// A move as written in a cell. `position` is `None` for `Ci+` / `Ci-`, which
/// mean the final end / home and are resolved once the whole table is known.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct CellMove {
    pub actuator: u32,
    pub sign: Sign,
    pub position: Option<u32>,
}

impl fmt::Display for CellMove {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "C{}{}", self.actuator, self.sign.symbol())?;
        if let Some(p) = self.position {
            write!(f, "{p}")?;
        }
        Ok(())
    }
}

/// Why a cell is not a valid move.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum CellError {
    /// Not of the form `C<number><sign><position>` at all.
    NotAMove,
    /// `C0…` or an actuator number above [`MAX_ACTUATOR`].
    BadActuator(String),
    /// A position number above [`MAX_POSITION`].
    BadPosition(String),
}

/// Maps the look-alike characters of copy-pasted and hand-typed cells to ASCII
/// and drops every kind of white space. Returns upper case.
pub fn normalize(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for ch in text.chars() {
        if ch.is_whitespace() || matches!(ch, '\u{200B}'..='\u{200D}' | '\u{2060}' | '\u{FEFF}') {
            continue;
        }
        let mapped = match ch {
            '\u{2212}'
            | '\u{2010}'..='\u{2015}'
            | '\u{FE63}'
            | '\u{FF0D}'
            | '\u{207B}'
            | '\u{208B}' => '-',
            '\u{FF0B}' | '\u{207A}' | '\u{208A}' | '\u{FE62}' => '+',
            '\u{2080}'..='\u{2089}' => digit(ch as u32 - 0x2080),
            '\u{2070}' => '0',
            '\u{00B9}' => '1',
            '\u{00B2}' => '2',
            '\u{00B3}' => '3',
            '\u{2074}'..='\u{2079}' => digit(ch as u32 - 0x2070),
            '\u{FF10}'..='\u{FF19}' => digit(ch as u32 - 0xFF10),
            // Cyrillic and full-width C
            '\u{0421}' | '\u{0441}' | '\u{FF23}' | '\u{FF43}' => 'C',
            other => other.to_ascii_uppercase(),
        };
        out.push(mapped);
    }
    out
}

fn digit(n: u32) -> char {
    char::from_digit(n, 10).unwrap_or('?')
}

/// Parses one move cell. Empty text is not a move; callers skip empty cells first.
pub fn parse_move(text: &str) -> Result<CellMove, CellError> {
    // `C4+1 0`: two numbers, or one mistyped; which is not ours to guess.
    if hint::split_number(text) {
        return Err(CellError::NotAMove);
    }
    let norm = normalize(text);
    let rest = norm.strip_prefix('C').ok_or(CellError::NotAMove)?;
    let digits_end = rest
        .find(|c: char| !c.is_ascii_digit())
        .unwrap_or(rest.len());
    if digits_end == 0 {
        return Err(CellError::NotAMove);
    }
    let (actuator_text, rest) = rest.split_at(digits_end);
    let mut chars = rest.chars();
    let sign = match chars.next() {
        Some('+') => Sign::Plus,
        Some('-') => Sign::Minus,
        _ => return Err(CellError::NotAMove),
    };
    let position_text = chars.as_str();
    if !position_text.chars().all(|c| c.is_ascii_digit()) {
        return Err(CellError::NotAMove);
    }
    let actuator = match actuator_text.parse::<u32>() {
        Ok(n) if (1..=MAX_ACTUATOR).contains(&n) => n,
        _ => return Err(CellError::BadActuator(actuator_text.to_string())),
    };
    let position = if position_text.is_empty() {
        None
    } else {
        match position_text.parse::<u32>() {
            Ok(n) if n <= MAX_POSITION => Some(n),
            _ => return Err(CellError::BadPosition(position_text.to_string())),
        }
    };
    Ok(CellMove {
        actuator,
        sign,
        position,
    })
}

/// Shortest and longest dwell accepted: FST counts timers in hundredths of a
/// second in a 16-bit word, so 655.35 s is the most every target can hold.
pub const MIN_DWELL_MS: u32 = 10;
pub const MAX_DWELL_MS: u32 = 655_350;

/// One thing a branch cell asks for; a cell holds one or more, split by `;`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CellItem {
    /// `C2+1`.
    Move(CellMove),
    /// `T=2s`: the branch waits this long after its other items.
    Dwell { ms: u32 },
    /// `I:part_present` / `I:name=0`: the step completes only when the
    /// machine input has this value.
    Wait { input: Name, value: bool },
    /// `Y:vacuum+` / `Y:vacuum-`: switch a machine output on or off.
    Switch { output: Name, on: bool },
    /// `J:7 if I:reject`, `J:end if I:abort`: once the step is done, the
    /// sequence goes on at another step (or ends the cycle) when the
    /// machine input has this value, instead of at the next step.
    Jump {
        target: JumpTarget,
        input: Name,
        value: bool,
    },
}

/// Where a jump goes: a step of the table, or the end of the cycle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum JumpTarget {
    Step(u32),
    End,
}

impl fmt::Display for JumpTarget {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            JumpTarget::Step(n) => write!(f, "{n}"),
            JumpTarget::End => f.write_str("end"),
        }
    }
}

impl fmt::Display for CellItem {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            CellItem::Move(m) => write!(f, "{m}"),
            CellItem::Dwell { ms } => f.write_str(&dwell_text(*ms)),
            CellItem::Wait { input, value } => {
                if *value {
                    write!(f, "I:{input}")
                } else {
                    write!(f, "I:{input}=0")
                }
            }
            CellItem::Switch { output, on } => {
                write!(f, "Y:{output}{}", if *on { '+' } else { '-' })
            }
            CellItem::Jump {
                target,
                input,
                value,
            } => {
                write!(f, "J:{target} if ")?;
                CellItem::Wait {
                    input: *input,
                    value: *value,
                }
                .fmt(f)
            }
        }
    }
}

/// `T=2s`, `T=500ms`, `T=1.25s`: the shortest exact spelling.
pub fn dwell_text(ms: u32) -> String {
    format!("T={}", duration_text(ms))
}

/// `2s`, `500ms`, `1.25s`: the shortest exact spelling of a duration.
pub fn duration_text(ms: u32) -> String {
    if ms.is_multiple_of(1000) {
        format!("{}s", ms / 1000)
    } else if ms < 1000 {
        format!("{ms}ms")
    } else {
        let text = format!("{:.3}", ms as f64 / 1000.0);
        format!("{}s", text.trim_end_matches('0'))
    }
}

/// Why an item of a cell is not valid.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum ItemError {
    Move(CellError),
    /// `T=` with a duration that is malformed or out of range.
    BadDwell(String),
    /// `I:` / `Y:` with a bad name or value.
    BadName(String),
    /// `J:` that is not `J:<step> if I:<name>` or `J:end if I:<name>`.
    BadJump(String),
}

/// Parses one `;`-separated item.
pub fn parse_item(text: &str) -> Result<CellItem, ItemError> {
    // `T = 1 5 s`, `J:1 0 if I:x`: two numbers, or one mistyped, in any
    // item (white space is dropped everywhere else).
    if hint::split_number(text) {
        return Err(ItemError::Move(CellError::NotAMove));
    }
    let norm = normalize(text);
    if (norm.starts_with("I:") || norm.starts_with("Y:")) && name_has_space(text) {
        return Err(ItemError::BadName(format!(
            "\"{}\": a name has no spaces (write part_present, not part present)",
            text.trim()
        )));
    }
    if norm.starts_with("I:") || norm.starts_with("Y:") {
        raw_name_problem(text).map_or(Ok(()), |why| Err(ItemError::BadName(why)))?;
    }
    if let Some(rest) = norm.strip_prefix("T=") {
        let ms = parse_dwell(rest).ok_or_else(|| {
            if thousands_comma(rest) {
                return ItemError::BadDwell(format!(
                    "dwell {}",
                    thousands_comma_words(text.trim())
                ));
            }
            ItemError::BadDwell(format!(
                "\"{}\" is not a dwell (expected T=2s or T=500ms, from {MIN_DWELL_MS} ms to {} s)",
                text.trim(),
                f64::from(MAX_DWELL_MS) / 1000.0
            ))
        })?;
        return Ok(CellItem::Dwell { ms });
    }
    if let Some(rest) = norm.strip_prefix("J:") {
        return parse_jump(text, rest);
    }
    if let Some(rest) = norm.strip_prefix("I:") {
        let rest = rest.to_ascii_lowercase();
        let (name, value) = match rest.split_once('=') {
            None => (rest.as_str(), true),
            Some((name, "1")) => (name, true),
            Some((name, "0")) => (name, false),
            Some(_) => {
                return Err(ItemError::BadName(format!(
                    "\"{}\": a wait is I:name, I:name=1 or I:name=0",
                    text.trim()
                )));
            }
        };
        let input =
            Name::new(name).map_err(|e| ItemError::BadName(format!("\"{}\": {e}", text.trim())))?;
        return Ok(CellItem::Wait { input, value });
    }
    if let Some(rest) = norm.strip_prefix("Y:") {
        let rest = rest.to_ascii_lowercase();
        let (name, on) = if let Some(name) = rest.strip_suffix('+') {
            (name, true)
        } else if let Some(name) = rest.strip_suffix('-') {
            (name, false)
        } else {
            return Err(ItemError::BadName(format!(
                "\"{}\": an output is switched with Y:name+ (on) or Y:name- (off)",
                text.trim()
            )));
        };
        let output =
            Name::new(name).map_err(|e| ItemError::BadName(format!("\"{}\": {e}", text.trim())))?;
        return Ok(CellItem::Switch { output, on });
    }
    parse_move(text)
        .map(CellItem::Move)
        .map_err(ItemError::Move)
}

/// `J:7 if I:reject` after its `J:` (normalised: `7IFI:REJECT`).
fn parse_jump(text: &str, rest: &str) -> Result<CellItem, ItemError> {
    let bad = |why: &str| {
        ItemError::BadJump(format!(
            "\"{}\": {why} (a jump is J:<step> if I:<input>, J:<step> if I:<input>=0 or J:end if I:<input>)",
            text.trim()
        ))
    };
    let (target, condition) = rest
        .split_once("IF")
        .ok_or_else(|| bad("the jump says no input (if I:…)"))?;
    let target = match target {
        "END" => JumpTarget::End,
        digits if !digits.is_empty() && digits.bytes().all(|b| b.is_ascii_digit()) => {
            match digits.parse::<u32>() {
                // The table checks that the step exists.
                Ok(n) if n >= 1 => JumpTarget::Step(n),
                _ => return Err(bad("no such step number")),
            }
        }
        _ => return Err(bad("the target is a step number or end")),
    };
    // `J:e nd if …`: the spaces normalising drops would join a word split
    // in two (rt23 F6).
    let raw = text.split_once(':').map_or("", |(_, r)| r);
    let Some(keyword) = raw.to_ascii_lowercase().find("if") else {
        return Err(bad("a space splits its word if"));
    };
    let written = &raw[..keyword];
    if written.trim().contains(char::is_whitespace) {
        return Err(bad(&format!(
            "a space splits its target \"{}\" (write end or the step's number)",
            written.trim()
        )));
    }
    if !condition.starts_with("I:") {
        return Err(bad("the condition is a machine input, I:<name>"));
    }
    // The condition is read as a wait is, spaces in the name included; the
    // first `if` is the keyword (a step number or `end` holds none).
    let lower = text.to_ascii_lowercase();
    let after_if = lower.find("if").map_or("", |i| &text[i + 2..]);
    match parse_item(after_if)? {
        CellItem::Wait { input, value } => Ok(CellItem::Jump {
            target,
            input,
            value,
        }),
        _ => Err(bad("the condition is a machine input, I:<name>")),
    }
}

/// Whether the name in `I:name=0` / `Y:name+` has white space inside it,
/// which normalising would otherwise silently close up.
fn name_has_space(text: &str) -> bool {
    let after_colon = text.split_once(':').map_or("", |(_, rest)| rest);
    let name = after_colon.split('=').next().unwrap_or("");
    let name = name
        .trim()
        .trim_end_matches(|c: char| !c.is_alphanumeric() && c != '_');
    name.trim().contains(char::is_whitespace)
}

/// `2s`, `500ms`, `1.5s`, `1,5s` (a bare number is seconds).
fn parse_dwell(text: &str) -> Option<u32> {
    parse_duration_in(text, MIN_DWELL_MS..=MAX_DWELL_MS)
}

/// A duration written without its unit (`T=500`, `1000`), which the
/// duration parser reads as seconds and a PLC programmer used to
/// milliseconds may not have meant: the one test of W007.
pub fn without_unit(text: &str) -> bool {
    text.trim().ends_with(|c: char| c.is_ascii_digit())
}

/// The actuator an ISO designation names: `1A1` (any case) is actuator 1.
pub fn iso_actuator(text: &str) -> Option<u32> {
    let lower = text.trim().to_ascii_lowercase();
    let digits = lower.strip_suffix("a1")?;
    if digits.is_empty() || !digits.chars().all(|c| c.is_ascii_digit()) || digits.starts_with('0') {
        return None;
    }
    digits.parse().ok()
}

/// Whether `text` is written as a time at all: a plain decimal number
/// (`10`, `1.5`, `1,5`) and at most a unit (`s`, `ms`). An exponent, a
/// sign or a hex number (`1e1ms`, `-5ms`, `0x10ms`) is not, whatever its
/// value, so the message says what to write instead of blaming the range.
pub fn plain_time(text: &str) -> bool {
    if split_number(text) {
        return false;
    }
    let t: String = text
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_ascii_lowercase();
    let number = t
        .strip_suffix("ms")
        .or_else(|| t.strip_suffix('s'))
        .unwrap_or(&t);
    let (whole, fraction) = number.split_once(['.', ',']).unwrap_or((number, ""));
    !(whole.is_empty() && fraction.is_empty())
        && whole
            .chars()
            .chain(fraction.chars())
            .all(|c| c.is_ascii_digit())
}

/// W007's words for a time typed without its unit (`1000`): what it is
/// read as, and both spellings that say it.
pub fn read_as_seconds(text: &str) -> String {
    format!(
        "\"{text}\" has no unit and is read as {text} seconds: write {text}s, or {text}ms if milliseconds were meant"
    )
}

/// Whether a time's comma may group thousands as well as mark decimals:
/// three digits after it (`1,000ms`, `0,500s`). `1,000ms` is 1000 ms to
/// one engineer and 1 ms to another, so no time cell reads it; `1,5s`
/// can only be a decimal comma and is 1.5 s everywhere.
pub fn thousands_comma(text: &str) -> bool {
    let t: String = text.chars().filter(|c| !c.is_whitespace()).collect();
    let t = t.to_ascii_lowercase();
    let number = t
        .strip_suffix("ms")
        .or_else(|| t.strip_suffix('s'))
        .unwrap_or(&t);
    number.split_once(',').is_some_and(|(whole, after)| {
        !whole.is_empty()
            && whole.chars().all(|c| c.is_ascii_digit())
            && after.len() == 3
            && after.chars().all(|c| c.is_ascii_digit())
    })
}

/// The words for a time [`thousands_comma`] refuses: both readings, and
/// how to write either.
pub fn thousands_comma_words(text: &str) -> String {
    let text = text.trim();
    format!(
        "\"{text}\" has a comma that may separate thousands ({}) or be a decimal comma ({}): write the time without it, with a point for decimals (1.5s, 1000ms)",
        text.replace(',', ""),
        text.replace(',', ".")
    )
}

/// The one duration parser (dwells, stroke and scan times, input delays):
/// `2s`, `500ms`, `1.5s`, `1,5s`, a bare number in seconds, at most three
/// decimals, in exact decimal arithmetic; `None` outside `range` (ms), and
/// for a comma that may separate thousands ([`thousands_comma`]).
pub fn parse_duration_in(text: &str, range: std::ops::RangeInclusive<u32>) -> Option<u32> {
    if thousands_comma(text) {
        return None;
    }
    let lower = text.to_ascii_lowercase();
    let (number, scale) = if let Some(n) = lower.strip_suffix("ms") {
        (n, 1u64)
    } else if let Some(n) = lower.strip_suffix('s') {
        (n, 1000)
    } else {
        (lower.as_str(), 1000)
    };
    let number = number.replace(',', ".");
    let (whole, fraction) = number.split_once('.').unwrap_or((&number, ""));
    if whole.is_empty() && fraction.is_empty() {
        return None;
    }
    if !whole
        .chars()
        .chain(fraction.chars())
        .all(|c| c.is_ascii_digit())
        || whole.len() > 7
        || fraction.len() > 3
    {
        return None;
    }
    // Exact decimal arithmetic: 0.1 s is 100 ms, not 99.
    let whole: u64 = if whole.is_empty() {
        0
    } else {
        whole.parse().ok()?
    };
    let padded = format!("{fraction:0<3}");
    let thousandths: u64 = padded.parse().ok()?;
    let ms = (whole * 1000 + thousandths) * scale;
    if !ms.is_multiple_of(1000) && scale == 1 && !fraction.is_empty() {
        // `1.5ms`: below the timers' resolution.
        return None;
    }
    let ms = ms / 1000;
    (*range.start() as u64..=*range.end() as u64)
        .contains(&ms)
        .then_some(ms as u32)
}

/// Splits a cell on `;` (also the full-width `；`) and parses each part.
/// Empty parts (a trailing `;`) are ignored.
pub fn parse_items(text: &str) -> Vec<Result<CellItem, ItemError>> {
    item_texts(text).into_iter().map(parse_item).collect()
}

/// The parts of a cell that [`parse_items`] parses, in order.
pub fn item_texts(text: &str) -> Vec<&str> {
    text.split([';', '\u{FF1B}'])
        .filter(|part| !normalize(part).is_empty())
        .collect()
}

#[cfg(test)]
mod tests;
