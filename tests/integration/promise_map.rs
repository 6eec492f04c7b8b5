//! `tests/README.md` maps every README promise to its test; this keeps the
//! map true.

use clap::CommandFactory;

use crate::helpers::root;

/// The text of a test file named `file.rs` or `tools/file.rs` in the map.
fn test_source(reference: &str) -> Option<String> {
    let path = match reference.strip_prefix("tools/") {
        Some(rest) => root().join("tests/tools").join(rest),
        None => root().join("tests/integration").join(reference),
    };
    std::fs::read_to_string(path).ok()
}

/// Every `file.rs::test` reference in `text`.
fn references(text: &str) -> Vec<(String, String)> {
    let pattern = regex::Regex::new(r"`((?:tools/)?[a-z0-9_]+\.rs)::([a-z0-9_]+)`").unwrap();
    pattern
        .captures_iter(text)
        .map(|c| (c[1].to_string(), c[2].to_string()))
        .collect()
}

#[test]
fn the_map_names_every_flag_code_and_file() {
    let map = std::fs::read_to_string(root().join("tests/README.md")).unwrap();
    // Every long flag of every command.
    let mut flags = Vec::new();
    fn walk(cmd: &clap::Command, flags: &mut Vec<String>) {
        for arg in cmd.get_arguments() {
            if let Some(long) = arg.get_long()
                && !["help", "version"].contains(&long)
            {
                flags.push(format!("`--{long}`"));
            }
        }
        for sub in cmd.get_subcommands() {
            walk(sub, flags);
        }
    }
    walk(&steptable::cli::Cli::command(), &mut flags);
    for flag in &flags {
        let bare = flag.trim_matches('`');
        assert!(
            map.contains(flag.as_str()) || map.contains(&format!(", {bare}")),
            "{bare} is not in tests/README.md"
        );
    }
    // Every code, each with a test that mentions it.
    let diag = std::fs::read_to_string(root().join("src/diag.rs")).unwrap();
    let codes = regex::Regex::new(r#"=> "([EW]\d{3})""#).unwrap();
    let mut count = 0;
    for code in codes.captures_iter(&diag) {
        let code = &code[1];
        count += 1;
        let row = map
            .lines()
            .find(|l| l.starts_with(&format!("| {code} |")))
            .unwrap_or_else(|| panic!("{code} has no row in tests/README.md"));
        let named = references(row);
        assert!(!named.is_empty(), "{code}: no test named");
        assert!(
            named
                .iter()
                .any(|(file, _)| test_source(file).is_some_and(|s| s.contains(code))),
            "{code}: none of the tests named mention it: {row}"
        );
    }
    assert!(count >= 30, "{count} codes");
    // Every output kind.
    for kind in steptable::emit::OutputKind::ALL {
        let suffix = kind.suffix();
        assert!(
            map.contains(&format!("`NAME{suffix}`")) || map.contains(&format!("`NAME{suffix}/")),
            "{suffix} is not in tests/README.md"
        );
    }
    // Every file another command writes, by its name rule.
    for file in steptable::emit::CommandFile::ALL {
        let suffix = file.suffix();
        assert!(
            map.contains(&format!("`NAME{suffix}`")),
            "{suffix} is not in tests/README.md"
        );
    }
    // Every test named exists.
    for (file, test) in references(&map) {
        let source = test_source(&file).unwrap_or_else(|| panic!("{file}: no such test file"));
        assert!(
            source.contains(&format!("fn {test}(")),
            "{file}::{test}: no such test"
        );
    }
}
