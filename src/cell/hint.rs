//! What a table item that is not a move was probably meant to be: a dwell,
//! wait or output written without its `=` or `:`, items split by `,`
//! instead of `;`, a letter typed for a digit (`C2+l`), or the letter
//! notation of `synth --sequence`. E010 says it in the engineer's terms, and
//! the table check knows which actuator a refused move was about.

use super::{normalize, parse_dwell, parse_item, parse_move};

/// Edit distance by characters, a swap of two neighbours counting one
/// (`clmap` for `clamp`): the one measure of "did you mean" (labels,
/// formats, actuator names).
pub fn edit_distance(a: &str, b: &str) -> usize {
    let a: Vec<char> = a.chars().collect();
    let b: Vec<char> = b.chars().collect();
    // d[i][j]: the distance of a's first i and b's first j characters.
    let mut d = vec![vec![0usize; b.len() + 1]; a.len() + 1];
    for (i, row) in d.iter_mut().enumerate() {
        row[0] = i;
    }
    for (j, cell) in d[0].iter_mut().enumerate() {
        *cell = j;
    }
    for i in 1..=a.len() {
        for j in 1..=b.len() {
            let cost = usize::from(a[i - 1] != b[j - 1]);
            let mut best = (d[i - 1][j] + 1)
                .min(d[i][j - 1] + 1)
                .min(d[i - 1][j - 1] + cost);
            if i > 1 && j > 1 && a[i - 1] == b[j - 2] && a[i - 2] == b[j - 1] {
                best = best.min(d[i - 2][j - 2] + 1);
            }
            d[i][j] = best;
        }
    }
    d[a.len()][b.len()]
}

/// Why `item` is not a move, shaped by what it looks like: "did you mean
/// C2+1? …", or the grammar when nothing fits better.
pub fn not_a_move_hint(item: &str) -> String {
    let text = item.trim();
    let norm = normalize(text);
    if let Some(items) = split_by(text, &[',', '\u{FF0C}']) {
        return format!("separate items with `;`, not `,`: {}", items.join("; "));
    }
    if let Some(items) = split_by(text, &['\n', '\r']) {
        return format!(
            "separate items with `;`, not line breaks: {}",
            items.join("; ")
        );
    }
    if let Some(items) = split_by(text, &[' ', '\t', '\u{3000}']) {
        return format!("separate items with `;`, not spaces: {}", items.join("; "));
    }
    if digits_split(text).is_some() {
        return split_number_hint(text).unwrap_or_default();
    }
    if let Some(fixed) = digit_for_letter(&norm) {
        return format!("did you mean {fixed}? A letter stands where a digit belongs");
    }
    if let Some(rest) = norm.strip_prefix('T') {
        let rest = rest
            .trim_start_matches([':', '-', '.'])
            .to_ascii_lowercase();
        if parse_dwell(&rest).is_some() {
            return format!("did you mean T={rest}? A dwell is written T=<time>, e.g. T=2s");
        }
    }
    if let Some(fixed) = missing_colon(text) {
        let how = match fixed.as_bytes()[0] {
            b'I' => "A wait is written I:<input>, e.g. I:part_present",
            b'Y' => "An output is switched with Y:<output>+ or Y:<output>-",
            _ => "A jump is written J:<step> if I:<input>",
        };
        return format!("did you mean {fixed}? {how}");
    }
    if is_letter_notation(&norm) {
        return "a table writes moves as C<number>+<position>, e.g. C1+1 and C1-0; letter notation (A+, A1, B0) is for synth --sequence".to_string();
    }
    "expected C<number>+<position>, e.g. C2+1".to_string()
}

/// The actuators a refused item was about: one `Some(n)` for each Cn it
/// names (`C2+l`, `C2+99`, `C2+1,C3+1`, `C1~0`, `T=1s C1-0`), one `None`
/// for a move of an actuator nobody can tell (`Cx+1`), none when it is no
/// move at all (a dwell typo). A move checked against the position such an
/// item would have given is no error of its own.
pub fn move_attempts(item: &str) -> Vec<Option<u32>> {
    // `C1 0+1`: C1 as written, C10 with the space taken out; either may
    // be the actuator meant.
    if let Some(joined) = joined_digits(item) {
        let mut both: Vec<Option<u32>> = actuators_named(item).into_iter().map(Some).collect();
        if let Ok(m) = parse_move(&joined)
            && !both.contains(&Some(m.actuator))
        {
            both.push(Some(m.actuator));
        }
        return both;
    }
    let norm = normalize(item);
    if let Some(fixed) = digit_for_letter(&norm) {
        return vec![parse_move(&fixed).ok().map(|m| m.actuator)];
    }
    let named = actuators_named(item);
    if !named.is_empty() {
        return named.into_iter().map(Some).collect();
    }
    match norm.strip_prefix('C') {
        Some(rest) if rest.contains(['+', '-']) => vec![None],
        _ => Vec::new(),
    }
}

/// Each `C<number>` in `text` that starts a word (`C2` in `T=1s C2-0`, not
/// in `PC2`).
fn actuators_named(text: &str) -> Vec<u32> {
    let chars: Vec<char> = text.chars().collect();
    let mut named = Vec::new();
    for (i, c) in chars.iter().enumerate() {
        let starts_word = i == 0 || !chars[i - 1].is_alphanumeric() && chars[i - 1] != '_';
        if !starts_word || !matches!(c, 'C' | 'c') {
            continue;
        }
        let digits: String = chars[i + 1..]
            .iter()
            .take_while(|d| d.is_ascii_digit())
            .collect();
        if let Ok(n) = digits.parse::<u32>()
            && !named.contains(&n)
        {
            named.push(n);
        }
    }
    named
}

/// `C1+1, T=1s` or `C1+1 T=1s`: items that each parse, split by one of
/// `separators`.
fn split_by(text: &str, separators: &[char]) -> Option<Vec<String>> {
    let parts: Vec<String> = text
        .split(separators)
        .map(|p| p.trim().to_string())
        .filter(|p| !p.is_empty())
        .collect();
    (parts.len() > 1 && parts.iter().all(|p| parse_item(p).is_ok())).then_some(parts)
}

/// `C4+1 0`, `C1 2+1`: a move whose number a space splits, with the
/// space dropped.
fn digits_split(text: &str) -> Option<String> {
    let joined = joined_digits(text.trim())?;
    parse_item(&joined).is_ok().then_some(joined)
}

/// `text` with the white space between two digits taken out (`C1 0+1` as
/// `C10+1`), when there is any: one pass. A space beside a decimal
/// separator splits a number too (`T=1, 5s`, `T=1 .5s`, `T=. 5s`): taken
/// out, it is `T=1,5s` or two items, which is not ours to guess.
fn joined_digits(text: &str) -> Option<String> {
    let mut joined = String::with_capacity(text.len());
    let mut pending = String::new();
    // The last two characters that were no space, the latest first.
    let (mut last, mut before_last): (Option<char>, Option<char>) = (None, None);
    let mut split = false;
    for c in text.chars() {
        // A zero-width space or joiner is dropped as white space is.
        let spacer = c.is_whitespace() || super::zero_width(c);
        if spacer {
            pending.push(c);
            continue;
        }
        // A decimal separator with a digit on its other side (`1. 5`,
        // `1 .5`, `. 5`, `1. s`) is part of the number the space splits.
        let number_at = |d: Option<char>| d.is_some_and(digit_like);
        let split_here = match last {
            Some(l) if digit_like(l) => digit_like(c) || decimal_separator(c),
            Some(l) if decimal_separator(l) => digit_like(c) || number_at(before_last),
            _ => false,
        };
        let between = !pending.is_empty() && split_here;
        match between {
            true => split = true,
            false => joined.push_str(&pending),
        }
        pending.clear();
        joined.push(c);
        before_last = last;
        last = Some(c);
    }
    joined.push_str(&pending);
    split.then_some(joined)
}

fn decimal_separator(c: char) -> bool {
    matches!(c, '.' | ',')
}

/// A digit as the cell reader takes it: ASCII, or a sub-, superscript or
/// full-width digit copy-paste left (`C₂-₁`, `C1 ０`).
fn digit_like(c: char) -> bool {
    let mut buffer = [0u8; 4];
    if c.is_ascii() {
        return c.is_ascii_digit();
    }
    let read = normalize(c.encode_utf8(&mut buffer));
    !read.is_empty() && read.chars().all(|d| d.is_ascii_digit())
}

/// What to write for an item whose number a space splits, as a hint: the
/// item with the space taken out, or two items.
pub fn split_number_hint(text: &str) -> Option<String> {
    let joined = joined_digits(text.trim())?;
    // `I:y=1 0`: joined, no input's value (0 or 1) either (rt27 F5).
    let value = joined.rsplit_once('=').map_or("", |(_, v)| v.trim());
    if joined.to_ascii_uppercase().contains("I:")
        && value.len() > 1
        && value.chars().all(|c| c.is_ascii_digit())
    {
        return Some(
            "a space splits a number, and an input's value is 0 or 1: write one, or separate two items with `;`".to_string(),
        );
    }
    Some(format!(
        "a space splits a number: write {joined} if that is meant, or separate two items with `;`"
    ))
}

/// Whether white space splits a number of `text`: it stands between two
/// digits, or beside the decimal separator between them.
pub fn split_number(text: &str) -> bool {
    joined_digits(text).is_some()
}

/// `C2+l`, `CI+1`, `C1+O` read with 1 and 0 for the look-alike letters,
/// when that makes a move.
fn digit_for_letter(norm: &str) -> Option<String> {
    let rest = norm.strip_prefix('C')?;
    let fixed: String = rest
        .chars()
        .map(|c| match c {
            'L' | 'I' | '|' => '1',
            'O' => '0',
            other => other,
        })
        .collect();
    let fixed = format!("C{fixed}");
    (fixed != norm && parse_move(&fixed).is_ok()).then_some(fixed)
}

/// `I part`, `Y vac+`, `J 6 if I:x`: a wait, output or jump without its
/// colon, when the colon makes it one.
fn missing_colon(text: &str) -> Option<String> {
    let mut chars = text.chars();
    let letter = chars.next()?.to_ascii_uppercase();
    if !matches!(letter, 'I' | 'Y' | 'J') {
        return None;
    }
    let rest = chars.as_str();
    // A separator, not a colon, after the letter (`Idle` is a word).
    if !rest.starts_with(|c: char| c.is_whitespace() || matches!(c, '=' | '.' | '-')) {
        return None;
    }
    let rest = rest.trim_start().trim_start_matches(['=', '.', '-']).trim();
    let fixed = format!("{letter}:{rest}");
    parse_item(&fixed).is_ok().then_some(fixed)
}

/// `A+`, `A1`, `B0`: one letter and a direction, as `synth --sequence`
/// writes a move.
fn is_letter_notation(norm: &str) -> bool {
    let mut chars = norm.chars();
    matches!(
        (chars.next(), chars.next(), chars.next()),
        (Some('A'..='Z'), Some('0' | '1' | '+' | '-'), None)
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_typo_gets_its_own_hint() {
        for (item, hint) in [
            ("C2+l", "did you mean C2+1?"),
            ("CI+1", "did you mean C1+1?"),
            ("C1+O", "did you mean C1+0?"),
            ("T 1s", "did you mean T=1s? A dwell"),
            ("T:1.5s", "did you mean T=1.5s?"),
            ("I part", "did you mean I:part? A wait"),
            ("Y vac+", "did you mean Y:vac+? An output"),
            ("C1+1, T=1s", "separate items with `;`, not `,`: C1+1; T=1s"),
            ("A+", "a table writes moves as C<number>+<position>"),
            ("b0", "a table writes moves as C<number>+<position>"),
            ("C2+x", "expected C<number>+<position>, e.g. C2+1"),
            ("=C1+1", "expected C<number>+<position>"),
            ("T=1,5s", "expected C<number>+<position>"),
            ("Idle", "expected C<number>+<position>"),
        ] {
            let got = not_a_move_hint(item);
            assert!(got.starts_with(hint), "{item}: {got}");
        }
    }

    #[test]
    fn a_refused_move_names_its_actuators() {
        assert_eq!(move_attempts("C2+l"), [Some(2)]);
        assert_eq!(move_attempts("CI+1"), [Some(1)]);
        assert_eq!(move_attempts("C2+99"), [Some(2)]);
        assert_eq!(move_attempts("Cx+1"), [None]);
        assert_eq!(move_attempts("C2+1,C3+1"), [Some(2), Some(3)]);
        assert_eq!(move_attempts("C2+1 C3+1"), [Some(2), Some(3)]);
        assert_eq!(move_attempts("C1~0"), [Some(1)]);
        assert_eq!(move_attempts("T=1s C1-0"), [Some(1)]);
        assert_eq!(move_attempts("C1â€“0"), [Some(1)]);
        assert!(move_attempts("T 1s").is_empty());
        assert!(move_attempts("I part").is_empty());
        assert!(move_attempts("I:PC2").is_empty());
    }
}
