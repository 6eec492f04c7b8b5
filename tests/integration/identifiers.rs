//! Issue 38's one naming authority, checked on what is written: every
//! identifier each file of every sample and target declares comes from the
//! program's symbol table, is legal for its target and unique there after
//! case folding (IEC, Rockwell) or truncation (FST keeps 9 characters).

use std::collections::BTreeSet;

use steptable::address::Target;
use steptable::convert::{Conversion, convert_path};
use steptable::settings::Settings;
use steptable::symbols::{Scheme, check::identifier_problem};

use crate::helpers::samples;

/// The text of the file whose name ends in `suffix`.
fn file<'a>(c: &'a Conversion, suffix: &str) -> &'a str {
    c.files
        .iter()
        .find(|f| f.name.ends_with(suffix))
        .and_then(|f| std::str::from_utf8(&f.bytes).ok())
        .unwrap_or_else(|| panic!("{suffix} of {}", c.name))
}

/// Each of `ids` is in `table`, legal by `legal`, and unique after `fold`.
fn check(
    what: &str,
    ids: &[String],
    table: &BTreeSet<String>,
    legal: impl Fn(&str) -> Option<String>,
    fold: impl Fn(&str) -> String,
) {
    assert!(!ids.is_empty(), "{what}: no identifier found");
    let mut seen = BTreeSet::new();
    for id in ids {
        assert!(table.contains(id), "{what}: {id} is not the symbol table's");
        assert_eq!(legal(id), None, "{what}: {id}");
        assert!(seen.insert(fold(id)), "{what}: {id} is declared twice");
    }
}

/// The identifiers a Structured Text file declares in its VAR blocks.
fn st_declarations(text: &str) -> Vec<String> {
    let mut ids = Vec::new();
    let mut in_var = false;
    for line in text.lines() {
        let line = line.trim();
        if line.starts_with("VAR") {
            in_var = true;
        } else if line.starts_with("END_VAR") {
            in_var = false;
        } else if in_var && let Some((name, _)) = line.split_once(':') {
            let name = name.split_whitespace().next().unwrap_or("");
            if !name.is_empty() && !name.starts_with("(*") {
                ids.push(name.to_string());
            }
        }
    }
    ids
}

#[test]
fn every_identifier_written_comes_from_the_symbol_table() {
    // The samples, and a table whose actuators have the engineer's names.
    let mut tables = samples();
    tables.push(crate::helpers::root().join("tests/fixtures/named_station.xlsx"));
    for sample in tables {
        for (target, scheme) in [
            (Target::Festo, Scheme::Paper),
            (Target::Iec, Scheme::Iso),
            (Target::Siemens, Scheme::Names),
        ] {
            let mut settings = Settings::new();
            settings.target = target;
            settings.naming.scheme = scheme;
            let c = convert_path(&sample, &settings).expect("a sample converts");
            let what = |kind: &str| format!("{} {} {kind}", c.name, target.name());
            let iec: BTreeSet<String> = c.symbols.iec_identifiers().into_iter().collect();
            let step7: BTreeSet<String> = c.symbols.step7_identifiers().into_iter().collect();
            let fst: BTreeSet<String> = c.symbols.symbols().map(|(_, s)| s.fst.clone()).collect();
            let lower = |id: &str| id.to_ascii_lowercase();
            check(
                &what("st"),
                &st_declarations(file(&c, ".st")),
                &iec,
                identifier_problem,
                lower,
            );
            check(
                &what("gvl"),
                &st_declarations(file(&c, ".gvl.txt")),
                &iec,
                identifier_problem,
                lower,
            );
            // The STEP 7 symbol table: a quoted, padded first field.
            let sdf: Vec<String> = file(&c, ".sdf")
                .lines()
                .filter_map(|l| l.split('"').nth(1))
                .map(|s| s.trim().to_string())
                .collect();
            let step7_rule = |id: &str| {
                (id.len() > 24)
                    .then(|| format!("{id} is longer than STEP 7's 24 characters"))
                    .or_else(|| identifier_problem(id))
            };
            check(&what("sdf"), &sdf, &step7, step7_rule, lower);
            // Rockwell tags: the third field of each TAG row.
            let tags: Vec<String> = file(&c, ".rockwell.csv")
                .lines()
                .filter(|l| l.starts_with("TAG,"))
                .filter_map(|l| l.split(',').nth(2))
                .map(str::to_string)
                .collect();
            let rockwell_rule = |id: &str| {
                (id.len() > 40)
                    .then(|| format!("{id} is longer than a Rockwell tag's 40 characters"))
                    .or_else(|| identifier_problem(id))
            };
            check(&what("rockwell"), &tags, &iec, rockwell_rule, lower);
            // FST's allocation list: the symbolic operand, 9 characters,
            // unique in any case.
            let symbols: Vec<String> = file(&c, ".fst-alloc.csv")
                .lines()
                .skip(1)
                .filter_map(|l| l.split(',').nth(1))
                .map(str::to_string)
                .collect();
            let fst_rule = |id: &str| {
                (id.chars().count() > 9)
                    .then(|| format!("{id} is longer than FST's 9 characters"))
                    .or_else(|| identifier_problem(id))
            };
            check(&what("fst-alloc"), &symbols, &fst, fst_rule, lower);
        }
    }
}
