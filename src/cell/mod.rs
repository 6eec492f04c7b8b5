//! The move-cell grammar: `C<actuator><sign><position>`, written the way engineers
//! actually type it (any case, spaces, Unicode minus and dashes, sub- and
//! superscript digits from copy-paste, a Cyrillic `С` from a Serbian keyboard).

use std::fmt;

mod hint;
pub use hint::{edit_distance, move_attempt, not_a_move_hint};

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

/// Longest name of a machine input or output (`I:part_present`).
pub const MAX_NAME_CHARS: usize = 16;
/// Shortest and longest dwell accepted: FST counts timers in hundredths of a
/// second in a 16-bit word, so 655.35 s is the most every target can hold.
pub const MIN_DWELL_MS: u32 = 10;
pub const MAX_DWELL_MS: u32 = 655_350;

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
    let norm = normalize(text);
    if (norm.starts_with("I:") || norm.starts_with("Y:")) && name_has_space(text) {
        return Err(ItemError::BadName(format!(
            "\"{}\": a name has no spaces (write part_present, not part present)",
            text.trim()
        )));
    }
    if let Some(rest) = norm.strip_prefix("T=") {
        let ms = parse_dwell(rest).ok_or_else(|| {
            ItemError::BadDwell(format!(
                "\"{}\" is not a dwell (expected T=2s or T=500ms, from {MIN_DWELL_MS} ms to {} s)",
                text.trim(),
                MAX_DWELL_MS / 1000
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

/// The one duration parser (dwells, stroke and scan times, input delays):
/// `2s`, `500ms`, `1.5s`, `1,5s`, a bare number in seconds, at most three
/// decimals, in exact decimal arithmetic; `None` outside `range` (ms).
pub fn parse_duration_in(text: &str, range: std::ops::RangeInclusive<u32>) -> Option<u32> {
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
    label_comment(after)
}

/// The comment after a label's number (`(clamp part)`, `: eject`), without
/// its separator and a closing bracket; `None` when nothing is left.
fn label_comment(after: &str) -> Option<String> {
    let bracketed = after.trim_start().starts_with('(');
    let comment = after.trim_start_matches(|c: char| {
        c.is_whitespace() || matches!(c, ':' | '-' | '–' | '—' | '(' | '.' | ',' | ';' | '=')
    });
    let comment = if bracketed {
        comment.trim_end().strip_suffix(')').unwrap_or(comment)
    } else {
        comment
    };
    let comment = visible_text(comment);
    let comment = comment.trim();
    (!comment.is_empty()).then(|| comment.to_string())
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

#[cfg(test)]
mod tests;
