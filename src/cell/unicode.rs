//! Unicode spellings of one text: what the reader and the code-page
//! writer both need, in a leaf of its own.

/// Text in Unicode's composed form (NFC): `A` followed by a combining
/// diaeresis, as macOS and some copy-paste write it, becomes `Ä`, the one
/// character every PLC tool and code page knows (as two, Windows-1252 has
/// no place for the mark and a name's length is counted wrong). The same
/// text, only spelt the usual way; ASCII and composed text are not copied.
pub fn composed(text: String) -> String {
    use unicode_normalization::{IsNormalized, UnicodeNormalization, is_nfc_quick};
    if text.is_ascii() || is_nfc_quick(text.chars()) == IsNormalized::Yes {
        return text;
    }
    text.nfc().collect()
}
