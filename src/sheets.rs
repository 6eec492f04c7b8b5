//! The sheet names steptable's workbooks share: the reader looks for them,
//! the template workbook and the output workbook write them. A leaf module,
//! so that the output side names a sheet without knowing the reader. The
//! labels of the SETTINGS rows are here too: the table stage names one
//! written beside a table.

/// The sheet name of the published method's table.
pub const TABLE_SHEET: &str = "SEQUENTIAL CONTROL DESCRIPTION";
/// The sheet name of the engineer's settings, when a workbook has one.
pub const SETTINGS_SHEET: &str = "SETTINGS";
/// The sheet name of the signals pinned to the wiring's addresses.
pub const ADDRESSES_SHEET: &str = "ADDRESSES";

/// The labels of the SETTINGS sheet's rows, as written there.
pub const SETTING_LABELS: [&str; 17] = [
    "target",
    "board",
    "on stop",
    "on estop",
    "on halt",
    "hold-safe",
    "de-energise on halt",
    "start permissive",
    "interlock",
    "hold on estop",
    "mnemonic",
    "scan time",
    "safety",
    "modes",
    "home order",
    "designations",
    "supervision",
];

/// `mode`, `hold safe`, `on-halt`, `supervison`: a label steptable knows,
/// misspelt — the same letters, or one letter off (two in a label of eight
/// letters or more). Looser likenesses (`notes` and `modes`) are only
/// named (by the SETTINGS reader): a note row must not stop a conversion.
pub fn mistyped_setting_label(label: &str) -> Option<&'static str> {
    let word = label_letters(label).to_lowercase();
    if word.is_empty() {
        return None;
    }
    SETTING_LABELS
        .into_iter()
        .map(|known| {
            let known_letters = label_letters(known);
            let distance = crate::cell::edit_distance(&word, &known_letters);
            let allowed = if known_letters.chars().count() >= 8 {
                2
            } else {
                1
            };
            (distance, allowed, known)
        })
        .filter(|(distance, allowed, _)| distance <= allowed)
        .min()
        .map(|(_, _, known)| known)
}

/// The letters of a label (`hold-safe` is `holdsafe`).
fn label_letters(text: &str) -> String {
    text.chars().filter(|c| c.is_alphabetic()).collect()
}

/// A text that holds a setting's label and its value together (`target:
/// iec`, `scan time = 20ms`): the label it starts with.
pub fn setting_in_one_cell(text: &str) -> Option<&'static str> {
    let lower = text.trim().to_ascii_lowercase();
    SETTING_LABELS.into_iter().find(|label| {
        lower.strip_prefix(label).is_some_and(|rest| {
            rest.starts_with([':', '=', ' ', '\t'])
                && !rest
                    .trim_matches(|c: char| c == ':' || c == '=' || c.is_whitespace())
                    .is_empty()
        })
    })
}
