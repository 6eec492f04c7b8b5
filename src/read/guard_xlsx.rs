//! Guards in front of calamine's `.xlsx` reader. Calamine reserves room for
//! as many shared strings as `sharedStrings.xml` says it holds
//! (`uniqueCount`), before reading them, so a 1 KB file claiming four
//! billion strings made it ask for 96 GB and the process aborted. A string
//! takes at least five bytes (`<si/>`), so the count is checked against the
//! part's size. And calamine decodes each string whole: 245 KB holding one
//! 250 MB string took 739 MB, so the text of every part is measured as it
//! streams past, against Excel's own limit for a cell.

use std::io::{Cursor, Read};

use quick_xml::Reader;
use quick_xml::events::Event;

/// Why the `.xlsx` file is not decoded, if it is not. What this pass cannot
/// read is left to calamine to report.
pub fn impossible_string_count(bytes: &[u8]) -> Option<String> {
    let mut archive = zip::ZipArchive::new(Cursor::new(bytes)).ok()?;
    let names: Vec<String> = archive
        .file_names()
        .flatten()
        .filter(|n| n.to_ascii_lowercase().ends_with("sharedstrings.xml"))
        .map(|n| n.to_string())
        .collect();
    for name in names {
        let Ok(entry) = archive.by_name(&name) else {
            continue;
        };
        let size = entry.size();
        // The count is on the first element: the first 64 KiB hold it.
        let mut head = Vec::new();
        if entry.take(64 * 1024).read_to_end(&mut head).is_err() {
            continue;
        }
        let Some(count) = unique_count(&head) else {
            continue;
        };
        if count > size / 5 + 1 {
            return Some(format!(
                "{name} claims {count} shared strings in {size} bytes"
            ));
        }
    }
    None
}

/// Excel's limit for the text of one cell; formulas are shorter still.
pub const MAX_TEXT_CHARS: u64 = 32_767;

/// The part and length of a text longer than [`MAX_TEXT_CHARS`] in the
/// shared strings or a worksheet, measured while the part streams past.
pub fn overlong_text(bytes: &[u8]) -> Option<String> {
    let mut archive = zip::ZipArchive::new(Cursor::new(bytes)).ok()?;
    let names: Vec<String> = archive
        .file_names()
        .flatten()
        .filter(|n| {
            let lower = n.to_ascii_lowercase();
            lower.ends_with(".xml")
                && (lower.ends_with("sharedstrings.xml") || lower.contains("worksheets/"))
        })
        .map(|n| n.to_string())
        .collect();
    for name in names {
        let Ok(entry) = archive.by_name(&name) else {
            continue;
        };
        if let Some(chars) = first_text_over(entry, MAX_TEXT_CHARS) {
            return Some(format!(
                "{name} holds a text of more than {chars} characters; a cell holds at most {MAX_TEXT_CHARS}"
            ));
        }
    }
    None
}

/// Counts the characters of each run of text between two tags (an entity
/// such as `&amp;` is one character) and stops at the first run longer than
/// `limit`, returning how far it counted. Reads in blocks, so memory stays
/// flat whatever the text's length; an unreadable part is left to calamine.
fn first_text_over(mut part: impl Read, limit: u64) -> Option<u64> {
    let mut block = [0u8; 64 * 1024];
    let (mut in_tag, mut in_entity, mut run) = (false, false, 0u64);
    loop {
        let n = part.read(&mut block).ok()?;
        if n == 0 {
            return None;
        }
        for &b in &block[..n] {
            match b {
                b'<' => {
                    in_tag = true;
                    run = 0;
                }
                b'>' => in_tag = false,
                _ if in_tag => {}
                b'&' => {
                    in_entity = true;
                    run += 1;
                }
                b';' if in_entity => in_entity = false,
                _ if in_entity => {}
                // A UTF-8 continuation byte is part of the character before.
                _ if b & 0xC0 == 0x80 => {}
                _ => run += 1,
            }
            if run > limit {
                return Some(run);
            }
        }
    }
}

/// The `uniqueCount` of the `sst` element, read as calamine reads it.
fn unique_count(xml: &[u8]) -> Option<u64> {
    let mut reader = Reader::from_reader(xml);
    let mut buf = Vec::new();
    loop {
        match reader.read_event_into(&mut buf).ok()? {
            Event::Start(e) | Event::Empty(e) if e.local_name().as_ref() == "sst" => {
                let value = e
                    .attributes()
                    .flatten()
                    .find(|a| a.key.as_ref() == "uniqueCount")?
                    .value
                    .to_string();
                return value.parse().ok();
            }
            Event::Eof => return None,
            _ => {}
        }
        buf.clear();
    }
}

/// Whether the workbook asks to be calculated again when opened
/// (`<calcPr fullCalcOnLoad="1"/>`): a program that does not calculate
/// saves a placeholder (0) as a formula's value and says so; Excel and
/// LibreOffice show the computed value, never the placeholder. (A writer
/// that gives a formula its result, and asks all the same, is believed.)
pub fn values_to_recalculate(bytes: &[u8]) -> bool {
    let Some(mut archive) = zip::ZipArchive::new(Cursor::new(bytes)).ok() else {
        return false;
    };
    let Ok(part) = archive.by_name("xl/workbook.xml") else {
        return false;
    };
    // The calculation settings are small and near the end of a small part.
    let mut text = Vec::new();
    if part.take(4 << 20).read_to_end(&mut text).is_err() {
        return false;
    }
    let mut reader = Reader::from_reader(text.as_slice());
    let mut buf = Vec::new();
    loop {
        match reader.read_event_into(&mut buf) {
            Ok(Event::Empty(e) | Event::Start(e)) if e.local_name().into_inner() == "calcPr" => {
                return e.attributes().flatten().any(|a| {
                    a.key.local_name().into_inner() == "fullCalcOnLoad"
                        && matches!(&*a.value, "1" | "true")
                });
            }
            Ok(Event::Eof) | Err(_) => return false,
            _ => {}
        }
        buf.clear();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_count_from_the_first_element() {
        let xml = br#"<?xml version="1.0"?><sst xmlns="x" count="2" uniqueCount="4000000000"><si><t>a</t></si></sst>"#;
        assert_eq!(unique_count(xml), Some(4_000_000_000));
        assert_eq!(unique_count(b"<sst><si/></sst>"), None);
    }

    #[test]
    fn measures_text_runs_in_characters_between_tags() {
        let text = |body: &str| format!("<sst><si><t>{body}</t></si><si><t>x</t></si></sst>");
        // 4 characters: an entity and a two-byte letter count once each.
        assert_eq!(first_text_over(text("ab&amp;ü").as_bytes(), 3), Some(4));
        assert_eq!(first_text_over(text("ab&amp;ü").as_bytes(), 4), None);
        // Tags and attributes are not text.
        let long_attribute = format!(r#"<c r="A1" s="{}"/>"#, "9".repeat(100));
        assert_eq!(first_text_over(long_attribute.as_bytes(), 10), None);
        // Found across the reader's blocks.
        let long = text(&"é".repeat(70_000));
        assert!(first_text_over(long.as_bytes(), MAX_TEXT_CHARS).is_some());
        assert!(first_text_over(text(&"é".repeat(32_767)).as_bytes(), MAX_TEXT_CHARS).is_none());
    }
}
