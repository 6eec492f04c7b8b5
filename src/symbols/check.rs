//! The rules every name meets in every target, checked once over the whole
//! table and its settings: each name a cell or a SETTINGS row brings in
//! (machine inputs and outputs, start permissives, interlocks, actuator
//! names and, under the engineer's names, the identifiers they give) against
//! every other. IEC 61131-3 and Rockwell tags ignore case and Festo FST keeps
//! only 9 characters, so two names that are one there are one signal to that
//! target: an error at the later one's cell, naming the earlier one.

use crate::cell::Sign;
use crate::diag::{Code, Diagnostics, Location};
use crate::names::{FST_SYMBOL_CHARS, fst_stem, reserved_name};
use crate::read::Grid;
use crate::table::StepTable;

use super::scheme::{Naming, Scheme};

/// Why `id` is not an identifier of IEC 61131-3 (and so of Rockwell tags
/// and STEP 7 symbols, which accept more): a letter, then letters, digits
/// and single underscores, not ending in one.
pub fn identifier_problem(id: &str) -> Option<String> {
    let mut chars = id.chars();
    if !chars.next().is_some_and(|c| c.is_ascii_alphabetic()) {
        return Some(format!("{id} does not begin with a letter"));
    }
    if !chars.all(|c| c.is_ascii_alphanumeric() || c == '_') {
        return Some(format!(
            "{id} holds a character other than a letter, digit or _"
        ));
    }
    if id.contains("__") || id.ends_with('_') {
        return Some(format!("{id} has a double or trailing underscore"));
    }
    None
}

/// One name the table or its settings bring in.
#[derive(Debug, Clone)]
pub struct Entry {
    /// The name as the program spells it.
    pub name: String,
    /// Where it was written.
    pub at: Location,
    /// Says where it was written, in a message (`in cell B3`, `in the
    /// interlock row`, `for C1`).
    pub origin: String,
    /// The prefix of a message at this entry (`interlock: `).
    pub label: String,
    /// The actuator whose name gives it, if any.
    pub actuator: Option<u32>,
    /// Whether it names a signal (an actuator's bare name names none, so
    /// what FST keeps of it does not matter).
    pub symbol: bool,
    /// Whether it is an operating-mode button's name (a jog button's):
    /// a machine signal meets those in [`crate::names::signal_problem`],
    /// so here it is held only against the other actuators' names.
    pub button: bool,
}

/// The machine inputs and outputs of `table`, each at the first cell
/// (row by row, left to right) that names it.
pub fn table_entries(table: &StepTable, grid: &Grid) -> Vec<Entry> {
    let mut uses: Vec<(crate::diag::CellPos, String)> = Vec::new();
    for step in &table.steps {
        uses.extend(step.waits.iter().map(|w| (w.cell, w.input.to_string())));
        uses.extend(step.jumps.iter().map(|j| (j.cell, j.input.to_string())));
        uses.extend(step.switches.iter().map(|s| (s.cell, s.output.to_string())));
    }
    uses.sort_by_key(|(pos, _)| (pos.row, pos.col));
    let mut entries: Vec<Entry> = Vec::new();
    for (pos, name) in uses {
        if entries.iter().any(|e| e.name == name) {
            continue;
        }
        entries.push(Entry {
            origin: format!("in cell {}", grid.cell_name(pos)),
            at: grid.location(pos),
            label: String::new(),
            actuator: None,
            symbol: true,
            button: false,
            name,
        });
    }
    entries
}

/// `SETTINGS!B5`: a cell in a message.
fn place(at: &Location) -> String {
    match (&at.sheet, at.cell) {
        (Some(sheet), Some(cell)) => format!("{sheet}!{}", cell.a1()),
        (None, Some(cell)) => format!("{}:{}", cell.row + 1, cell.col + 1),
        (Some(sheet), None) => sheet.clone(),
        (None, None) => "the command line".to_string(),
    }
}

/// The inputs a SETTINGS row (`label`: `start permissive`, `interlock`)
/// names, at its cell.
pub fn row_entries(label: &str, names: &[crate::cell::Name], at: &Location) -> Vec<Entry> {
    names
        .iter()
        .map(|n| Entry {
            name: n.to_string(),
            at: at.clone(),
            origin: format!("in the {label} row, {}", place(at)),
            label: format!("{label}: "),
            actuator: None,
            symbol: true,
            button: false,
        })
        .collect()
}

/// Sheet order of a SETTINGS cell, so that of two rows the lower one is
/// the later.
pub fn sheet_order(at: &Location) -> (u32, u32) {
    at.cell.map_or((0, 0), |c| (c.row, c.col))
}

/// The identifiers the engineer's names give (`clamp_home`, `clamp_out`,
/// and the jog buttons `jogs` of manual mode: `clamp_jog_out`), and each
/// name itself, at the actuator table's cell; a name that gives no
/// identifier under the names scheme is E015 there.
pub fn actuator_entries(
    table: &StepTable,
    naming: &Naming,
    jogs: &[crate::program::Signal],
    buttons: &[String],
    diags: &mut Diagnostics,
) -> Vec<Entry> {
    let mut entries = Vec::new();
    for (&n, name) in &naming.actuators {
        let Some(actuator) = table.actuator(n) else {
            // A name the engineer typed that no output can carry: said,
            // so that a name on the wrong row is not lost without a word.
            diags.warning(
                Code::W006NoEffect,
                name.at.clone(),
                format!(
                    "C{n} is named \"{}\", but the table does not move C{n}; the name is not used",
                    name.text
                ),
            );
            continue;
        };
        let label = format!("C{n} ({}): ", name.text);
        if let Some(why) = reads_as_another(&name.text, n, buttons) {
            diags.error(
                Code::E015BadName,
                name.at.clone(),
                format!("{label}\"{}\" cannot name an actuator: {why}", name.text),
            );
            continue;
        }
        let Some(stem) = name.stem() else {
            without_identifier(naming, n, name, &label, &mut entries, diags);
            continue;
        };
        let origin = format!("for C{n} at {}", place(&name.at));
        let entry = |text: String, symbol: bool| Entry {
            name: text,
            at: name.at.clone(),
            origin: origin.clone(),
            label: label.clone(),
            actuator: Some(n),
            symbol,
            button: false,
        };
        // The name itself may not read as a reserved word or another
        // actuator's (`C1 (C2)`, `C1 (y1)`, `C1 (none)`): a row naming it
        // would mean two things.
        if let Some(why) = reserved_name(&stem) {
            diags.error(
                Code::E015BadName,
                name.at.clone(),
                format!("{label}\"{}\" cannot name an actuator: {why}", name.text),
            );
            continue;
        }
        entries.push(entry(stem.clone(), false));
        // The names a row may use for its signals (`clamp_home`, `clamp_out`)
        // are names under every scheme; under `names` they are identifiers
        // too, so FST's 9 characters and the identifier rules apply.
        let names = naming.scheme == Scheme::Names;
        let mut signals: Vec<crate::program::Signal> = (0..=actuator.max_position)
            .map(|position| crate::program::Signal::Sensor {
                actuator: n,
                position,
            })
            .collect();
        signals.extend(
            [Sign::Plus, Sign::Minus]
                .map(|sign| crate::program::Signal::Coil { actuator: n, sign }),
        );
        for signal in signals {
            let Some(id) = naming.own_alias(signal, table) else {
                continue;
            };
            if names && let Some(why) = identifier_problem(&id).or_else(|| reserved_name(&id)) {
                diags.error(
                    Code::E015BadName,
                    name.at.clone(),
                    format!("{label}its signal {id} cannot be an identifier: {why}"),
                );
            }
            entries.push(entry(id, names));
        }
        // A jog button keeps its paper symbol in FST (`jog1p`), so only
        // its whole name can meet another's: `c_jog_out` is C1 (c)'s jog
        // and C2 (c_jog)'s coil.
        let own_jogs = jogs.iter().filter(
            |jog| matches!(jog, crate::program::Signal::Jog { actuator, .. } if *actuator == n),
        );
        for &jog in own_jogs {
            if let Some(id) = naming.own_alias(jog, table) {
                entries.push(Entry {
                    origin: format!("for C{n}'s jog button at {}", place(&name.at)),
                    label: format!("{label}its jog button "),
                    button: true,
                    ..entry(id, false)
                });
            }
        }
    }
    entries
}

/// Why the name `text` of actuator `n` would read as something else where
/// a row or an option names an actuator or a signal: as an actuator the
/// table reader takes it for (`С2` with a Cyrillic С, `c 2`, `C₂`), as an
/// ISO 1219 designation other than its own `nA1` (`2A1`, `1M1`, `1B2`:
/// rows take those too), or as one of the program's operating-mode
/// buttons (`estop`, `jog1p`).
fn reads_as_another(text: &str, n: u32, buttons: &[String]) -> Option<String> {
    // `1A1 (x)`: an actuator as steptable prints it, which the lists and
    // the home order read (`--valve "1A1 (x)=52mono"` would be C1's).
    let (head, inner) = crate::program::bracketed(text);
    if inner.is_some()
        && let Some(other) =
            crate::cell::parse_actuator(head).or_else(|| crate::cell::iso_actuator(head))
    {
        return Some(format!(
            "it reads as actuator C{other} as steptable prints one ({head} (name)), which the options and the home order take"
        ));
    }
    let folded = crate::cell::normalize(text);
    if let Some(other) = folded
        .strip_prefix('C')
        .filter(|d| !d.is_empty() && d.chars().all(|c| c.is_ascii_digit()))
    {
        return Some(format!(
            "it reads as actuator C{} (the table reads a Cyrillic or full-width C, spaces and small digits as C and 0-9)",
            other.trim_start_matches('0')
        ));
    }
    let iso = iso_designation(&folded);
    if let Some(circuit) = iso
        && folded != format!("{n}A1")
    {
        return Some(format!(
            "it reads as an ISO 1219 designation ({circuit}A1 is C{circuit}, {circuit}B1 and {circuit}B2 its sensors, {circuit}M1 and {circuit}M2 its solenoids), which rows and options take too"
        ));
    }
    let lower = text.trim().to_ascii_lowercase();
    buttons.iter().find(|b| **b == lower).map(|b| {
        format!(
            "it is the program's operating-mode button {}",
            b.to_ascii_uppercase()
        )
    })
}

/// `2A1`, `1M2`, `10B3` (upper case, no spaces): the circuit number.
fn iso_designation(folded: &str) -> Option<u32> {
    let letter_at = folded.find(|c: char| !c.is_ascii_digit())?;
    let (circuit, rest) = folded.split_at(letter_at);
    let mut chars = rest.chars();
    let letter = chars.next()?;
    let number = chars.as_str();
    let digits = |t: &str| !t.is_empty() && t.chars().all(|c| c.is_ascii_digit());
    let iso = digits(circuit) && matches!(letter, 'A' | 'B' | 'M') && digits(number);
    iso.then(|| circuit.parse().ok()).flatten()
}

/// What the files asked for hold of a symbol: Festo FST tells apart only
/// the first 9 characters; STEP 7's symbol table holds 24, Studio 5000's
/// tags 40 (the shortest that binds, and its tool).
#[derive(Debug, Clone, Copy, Default)]
pub struct Limits {
    pub fst: bool,
    pub longest: Option<(usize, &'static str)>,
}

/// Every entry against every earlier one: the same name after case folding
/// (two actuators with one name, an input named like an actuator), or the
/// same first 9 characters in Festo FST when an FST file is written
/// (`fst`: a STEP 7 or IEC program tells them apart). An error at the
/// later entry.
pub fn check_entries(entries: &[Entry], limits: &Limits, diags: &mut Diagnostics) {
    let fst = limits.fst;
    let mut said: Vec<(Location, String)> = Vec::new();
    for (i, entry) in entries.iter().enumerate() {
        // Longer than a file asked for holds: cut there, it would be
        // another name, or two names one.
        if let Some((longest, tool)) = limits.longest
            && entry.symbol
            && entry.name.chars().count() > longest
            && !said.contains(&(entry.at.clone(), String::new()))
        {
            said.push((entry.at.clone(), String::new()));
            diags.error(
                Code::E015BadName,
                entry.at.clone(),
                format!(
                    "{}{} has {} characters, more than the {longest} {tool} holds; give {} a shorter name, choose --designations paper or iso, or leave that file out (--formats)",
                    entry.label,
                    entry.name,
                    entry.name.chars().count(),
                    if entry.actuator.is_some() { "the actuator" } else { "it" }
                ),
            );
            continue;
        }
        // Unicode's case folding: `Kühler` and `KÜHLER`, `Straße` and
        // `STRASSE` are one name.
        let lower = crate::cell::folded(&entry.name);
        for earlier in &entries[..i] {
            let same_actuator = entry.actuator.is_some() && entry.actuator == earlier.actuator;
            let other = crate::cell::folded(&earlier.name);
            // A machine signal named like a button is E015 where it is
            // written (names::signal_problem), said once.
            let signal_and_button = (entry.button && earlier.actuator.is_none())
                || (earlier.button && entry.actuator.is_none());
            if signal_and_button {
                continue;
            }
            let message = if lower == other {
                // One input in two rows (a permissive that is an
                // interlock too) is one signal.
                if same_actuator || (entry.actuator.is_none() && earlier.actuator.is_none()) {
                    continue;
                }
                format!(
                    "{}{} is named {} too; give them different names",
                    entry.label, entry.name, earlier.origin
                )
            } else if fst && entry.symbol && earlier.symbol && fst_stem(&lower) == fst_stem(&other)
            {
                format!(
                    "{}{} and {} begin with the same {FST_SYMBOL_CHARS} characters, which is all Festo FST keeps of a symbol ({} is named {}){}",
                    entry.label,
                    entry.name,
                    earlier.name,
                    earlier.name,
                    earlier.origin,
                    if entry.actuator.is_some() {
                        "; give the actuator a shorter name, or choose --designations paper or iso"
                    } else {
                        ""
                    }
                )
            } else {
                continue;
            };
            // One error per place and name pair; one per actuator name,
            // whose signals would all say the same.
            let key = match entry.actuator {
                Some(_) => (entry.at.clone(), String::new()),
                None => (entry.at.clone(), entry.name.clone()),
            };
            if !said.contains(&key) {
                said.push(key);
                diags.error(Code::E025NameClash, entry.at.clone(), message);
            }
            break;
        }
    }
}

/// An actuator's name that gives no identifier (`Ölpumpe`, `2nd clamp`):
/// under `names` E015, saying why and how to write it; under the other
/// schemes rows and comments still name the actuator by it, so it is an
/// entry that two actuators may not share.
fn without_identifier(
    naming: &Naming,
    n: u32,
    name: &super::scheme::ActuatorName,
    label: &str,
    entries: &mut Vec<Entry>,
    diags: &mut Diagnostics,
) {
    if naming.scheme != Scheme::Names {
        entries.push(Entry {
            name: name.text.trim().to_string(),
            at: name.at.clone(),
            origin: format!("for C{n} at {}", place(&name.at)),
            label: label.to_string(),
            actuator: Some(n),
            symbol: false,
            button: false,
        });
        return;
    }
    diags.error(
        Code::E015BadName,
        name.at.clone(),
        format!(
            "{label}\"{}\" gives no identifier under --designations names: {}; {}or choose another scheme",
            name.text,
            why_no_identifier(&name.text),
            match ascii_spelling(&name.text) {
                Some(ascii) => format!("write it \"{ascii}\", "),
                None => "rename it, ".to_string(),
            }
        ),
    );
}

/// Why a name makes no identifier: a letter beyond A-Z (PLC identifiers
/// are ASCII), or no letter A-Z to begin with.
fn why_no_identifier(text: &str) -> String {
    match text.chars().find(|c| c.is_alphanumeric() && !c.is_ascii()) {
        Some(c) => {
            format!("\"{c}\" is no letter A-Z, and PLC identifiers hold only those, digits and _")
        }
        None => "an identifier begins with a letter A-Z".to_string(),
    }
}

/// The name spelt in ASCII (`Ölpumpe` as `Oelpumpe`), when that gives an
/// identifier: a suggestion, never applied unasked.
fn ascii_spelling(text: &str) -> Option<String> {
    crate::cell::ascii_spelling(text).filter(|out| super::scheme::stem(out).is_some())
}
