//! Unicode spellings of one text: what the reader and the code-page
//! writer both need, in a leaf of its own.

/// Text in Unicode's composed form (NFC): `A` followed by a combining
/// diaeresis, as macOS and some copy-paste write it, becomes `Ä`, the one
/// character every PLC tool and code page knows (as two, Windows-1252 has
/// no place for the mark and a name's length is counted wrong). The same
/// text, only spelt the usual way; ASCII and composed text are not copied.
pub fn composed(text: String) -> String {
    match decomposed(&text) {
        true => compose(&text),
        false => text,
    }
}

/// [`composed`] of borrowed text, copied only where it changes.
pub fn composed_str(text: &str) -> std::borrow::Cow<'_, str> {
    match decomposed(text) {
        true => std::borrow::Cow::Owned(compose(text)),
        false => std::borrow::Cow::Borrowed(text),
    }
}

/// Whether `text` may change when composed: never for ASCII or text
/// already composed.
fn decomposed(text: &str) -> bool {
    use unicode_normalization::{IsNormalized, is_nfc_quick};
    !text.is_ascii() && is_nfc_quick(text.chars()) != IsNormalized::Yes
}

fn compose(text: &str) -> String {
    use unicode_normalization::UnicodeNormalization;
    text.nfc().collect()
}

/// A character that takes no room (a zero-width space or joiner, a
/// direction mark, a byte order mark): copy-paste leaves them, and neither
/// eye nor message shows them.
pub fn zero_width(c: char) -> bool {
    matches!(c, '\u{200b}'..='\u{200f}' | '\u{2060}'..='\u{2064}' | '\u{feff}')
}

/// The name spelt in ASCII as a German or French engineer writes it in a
/// PLC (`Ölpumpe` as `Oelpumpe`, `Schieber Ä` as `Schieber Ae`, `é` as
/// `e`), when it differs from `text`: a suggestion, never applied
/// unasked (the name is the engineer's).
pub fn ascii_spelling(text: &str) -> Option<String> {
    use unicode_normalization::UnicodeNormalization;
    let mut out = String::with_capacity(text.len() + 4);
    for c in text.chars() {
        match c {
            'ä' => out.push_str("ae"),
            'ö' => out.push_str("oe"),
            'ü' => out.push_str("ue"),
            'Ä' => out.push_str("Ae"),
            'Ö' => out.push_str("Oe"),
            'Ü' => out.push_str("Ue"),
            'ß' => out.push_str("ss"),
            c => out.extend(
                c.to_string()
                    .nfd()
                    .filter(|d| !unicode_normalization::char::is_combining_mark(*d)),
            ),
        }
    }
    (out != text).then_some(out)
}

/// `text` in one case for comparing names, as Unicode's full case folding
/// has it: `Straße` and `STRASSE`, `ΣΟΦΟΣ` and `σοφος`, `ﬁx` and `FIX` are
/// one name; `kırmızı` and `kirmizi` are two (a dotless ı folds to no i).
/// Composed first, so that a decomposed `Ö` is `Ö`.
pub fn folded(text: &str) -> String {
    let lower = composed_str(text.trim()).to_lowercase();
    let mut out = String::with_capacity(lower.len());
    for c in lower.chars() {
        match c {
            'ß' | 'ẞ' => out.push_str("ss"),
            'ς' => out.push('σ'),
            'ﬀ' => out.push_str("ff"),
            'ﬁ' => out.push_str("fi"),
            'ﬂ' => out.push_str("fl"),
            'ﬃ' => out.push_str("ffi"),
            'ﬄ' => out.push_str("ffl"),
            'ﬅ' | 'ﬆ' => out.push_str("st"),
            c => out.push(c),
        }
    }
    out
}
