//! The cell parser: any text must parse or be refused, never panic, and a
//! parsed move must print as text that parses to the same move.
#![no_main]

use libfuzzer_sys::fuzz_target;
use steptable::cell;

fuzz_target!(|text: &str| {
    let _ = cell::looks_like_move(text);
    if let Ok(parsed) = cell::parse_move(text) {
        let printed = parsed.to_string();
        assert_eq!(
            cell::parse_move(&printed),
            Ok(parsed),
            "{text:?} printed as {printed:?}"
        );
    }
});
