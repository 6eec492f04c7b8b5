//! The move-cell grammar: `C<actuator><sign><position>`, written the way engineers
//! actually type it (any case, spaces, Unicode minus and dashes, sub- and
//! superscript digits from copy-paste, a Cyrillic `С` from a Serbian keyboard).

use std::fmt;

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

/// True when the text looks like an attempt at a move (`C` followed by a digit
/// after normalisation). Used to find a bare grid of moves without headers.
pub fn looks_like_move(text: &str) -> bool {
    let norm = normalize(text);
    let mut chars = norm.chars();
    chars.next() == Some('C') && chars.next().is_some_and(|c| c.is_ascii_digit())
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mv(a: u32, sign: Sign, p: Option<u32>) -> CellMove {
        CellMove {
            actuator: a,
            sign,
            position: p,
        }
    }

    #[test]
    fn accepts_what_engineers_type() {
        let expected = mv(2, Sign::Minus, Some(1));
        for text in [
            "C2-1",
            "c2-1",
            "C2 - 1",
            " C2-1 ",
            "C2\u{2212}1",
            "C2\u{2013}1",
            "C2\u{2014}1",
            "C\u{2082}-\u{2081}",
            "\u{0421}2-1",
            "C2\u{00A0}-1",
            "C\u{FF12}\u{FF0D}1",
        ] {
            assert_eq!(parse_move(text), Ok(expected), "{text:?}");
        }
        assert_eq!(parse_move("C12+3"), Ok(mv(12, Sign::Plus, Some(3))));
        assert_eq!(parse_move("C1+"), Ok(mv(1, Sign::Plus, None)));
        assert_eq!(parse_move("c3 -"), Ok(mv(3, Sign::Minus, None)));
        assert_eq!(parse_move("C01+01"), Ok(mv(1, Sign::Plus, Some(1))));
    }

    #[test]
    fn rejects_what_is_not_a_move() {
        for text in [
            "C2+x", "C+1", "2+1", "C2", "C2*1", "A1", "C2+1+", "C2+-1", "START", "-",
        ] {
            assert_eq!(parse_move(text), Err(CellError::NotAMove), "{text:?}");
        }
        assert_eq!(parse_move("C0+1"), Err(CellError::BadActuator("0".into())));
        assert!(matches!(
            parse_move("C99999999999+1"),
            Err(CellError::BadActuator(_))
        ));
        assert!(matches!(
            parse_move("C1+64"),
            Err(CellError::BadPosition(_))
        ));
    }

    #[test]
    fn printing_round_trips() {
        for m in [
            mv(1, Sign::Plus, Some(1)),
            mv(12, Sign::Minus, Some(0)),
            mv(3, Sign::Plus, None),
        ] {
            assert_eq!(parse_move(&m.to_string()), Ok(m));
        }
    }

    #[test]
    fn recognises_attempts_at_moves() {
        assert!(looks_like_move("C2+x"));
        assert!(looks_like_move("c 1"));
        assert!(!looks_like_move("Cylinder sequence"));
        assert!(!looks_like_move("BRANCH 1"));
    }
}
