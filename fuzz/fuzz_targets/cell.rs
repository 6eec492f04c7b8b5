//! The cell grammar: any text must parse or be refused, never panic, and
//! every move, dwell, wait or output it parses must print as text that
//! parses back to the same item.
#![no_main]

use libfuzzer_sys::fuzz_target;
use steptable::cell;

fuzz_target!(|text: &str| {
    let _ = cell::looks_like_item(text);
    if let Ok(parsed) = cell::parse_move(text) {
        let printed = parsed.to_string();
        assert_eq!(
            cell::parse_move(&printed),
            Ok(parsed),
            "{text:?} printed as {printed:?}"
        );
    }
    for item in cell::parse_items(text).into_iter().flatten() {
        let printed = item.to_string();
        assert_eq!(
            cell::parse_item(&printed),
            Ok(item),
            "{text:?} printed as {printed:?}"
        );
    }
});
