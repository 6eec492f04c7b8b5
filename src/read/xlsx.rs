//! A guard in front of calamine's `.xlsx` reader: calamine reserves room for
//! as many shared strings as `sharedStrings.xml` says it holds
//! (`uniqueCount`), before reading them, so a 1 KB file claiming four
//! billion strings made it ask for 96 GB and the process aborted. A string
//! takes at least five bytes (`<si/>`), so the count is checked against the
//! part's size.

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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reads_the_count_from_the_first_element() {
        let xml = br#"<?xml version="1.0"?><sst xmlns="x" count="2" uniqueCount="4000000000"><si><t>a</t></si></sst>"#;
        assert_eq!(unique_count(xml), Some(4_000_000_000));
        assert_eq!(unique_count(b"<sst><si/></sst>"), None);
    }
}
