//! The documentation is split by reader (README.md, ARCHITECTURE.md,
//! docs/*.md, tests/README.md). These tests keep the split usable: the
//! README stays short and starts with the two commands a newcomer runs,
//! every link between the documents reaches a file and a heading that
//! exist, and the reference lists every code, option and SETTINGS row.

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

use crate::helpers::root;

/// The documents whose links are checked, relative to the repository root.
fn documents() -> Vec<PathBuf> {
    let mut list = vec![
        PathBuf::from("README.md"),
        PathBuf::from("ARCHITECTURE.md"),
        PathBuf::from("tests/README.md"),
    ];
    let mut docs: Vec<PathBuf> = std::fs::read_dir(root().join("docs"))
        .expect("docs folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| p.extension().is_some_and(|e| e == "md"))
        .map(|p| p.strip_prefix(root()).unwrap().to_path_buf())
        .collect();
    docs.sort();
    list.extend(docs);
    list
}

fn read(relative: &Path) -> String {
    std::fs::read_to_string(root().join(relative))
        .unwrap_or_else(|e| panic!("{}: {e}", relative.display()))
}

/// The text outside fenced code blocks, with inline code spans blanked, so
/// that `[--sheet NAME]` in a usage line or `a[i](x)` in code is no link.
fn prose(text: &str) -> String {
    let span = regex::Regex::new(r"`[^`]*`").unwrap();
    let mut fenced = false;
    let mut out = String::new();
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            out.push('\n');
            continue;
        }
        if !fenced {
            out.push_str(&span.replace_all(line, "``"));
        }
        out.push('\n');
    }
    out
}

/// GitHub's anchor for a heading: lower case, code marks and punctuation
/// dropped (letters of any script, digits, `-` and `_` kept), spaces to
/// `-`; a repeated heading gets `-1`, `-2`, … after its first.
fn anchors(text: &str) -> BTreeSet<String> {
    let mut seen = BTreeSet::new();
    let mut fenced = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            fenced = !fenced;
            continue;
        }
        let Some(heading) = line.strip_prefix('#') else {
            continue;
        };
        if fenced {
            continue;
        }
        let title = heading.trim_start_matches('#');
        if !title.starts_with(' ') {
            continue;
        }
        let slug: String = title
            .trim()
            .to_lowercase()
            .chars()
            .filter(|c| c.is_alphanumeric() || matches!(c, ' ' | '-' | '_'))
            .map(|c| if c == ' ' { '-' } else { c })
            .collect();
        let mut anchor = slug.clone();
        let mut n = 0;
        while seen.contains(&anchor) {
            n += 1;
            anchor = format!("{slug}-{n}");
        }
        seen.insert(anchor);
    }
    seen
}

#[test]
fn the_readme_is_short_and_starts_with_the_two_commands() {
    let readme = read(Path::new("README.md"));
    let lines: Vec<&str> = readme.lines().collect();
    assert!(
        lines.len() <= 200,
        "README.md has {} lines; it is the newcomer's page (at most 200): move detail to docs/",
        lines.len()
    );
    // The first code block, within the first lines, is the two commands a
    // newcomer runs on a fresh machine, exactly.
    let open = lines
        .iter()
        .position(|l| l.starts_with("```"))
        .expect("a code block in README.md");
    assert!(
        open < 15,
        "the first code block starts on line {}",
        open + 1
    );
    let block: Vec<&str> = lines[open + 1..]
        .iter()
        .take_while(|l| !l.starts_with("```"))
        .map(|l| l.split('#').next().unwrap().trim())
        .collect();
    assert_eq!(
        block,
        [
            "cargo run --release -- convert samples/paper_example.xlsx",
            "cargo test --locked"
        ],
        "README.md's first block"
    );
    // CI runs exactly the test command the README gives.
    let ci = std::fs::read_to_string(root().join(".ci/run")).unwrap();
    assert!(
        ci.lines().any(|l| l.trim() == "cargo test --locked"),
        ".ci/run no longer runs `cargo test --locked`"
    );
}

#[test]
fn every_link_between_the_documents_resolves() {
    let link = regex::Regex::new(r"\]\(([^)\s]+)\)").unwrap();
    let mut broken = Vec::new();
    let mut count = 0;
    for doc in documents() {
        let text = read(&doc);
        let base = doc.parent().unwrap_or(Path::new(""));
        for target in link.captures_iter(&prose(&text)) {
            let target = &target[1];
            if target.contains("://") || target.starts_with("mailto:") {
                continue;
            }
            count += 1;
            let (file, anchor) = match target.split_once('#') {
                Some((file, anchor)) => (file, Some(anchor)),
                None => (target, None),
            };
            // A bare `#anchor` points into the document itself.
            let path = if file.is_empty() {
                doc.clone()
            } else {
                base.join(file)
            };
            let full = root().join(&path);
            if !full.exists() {
                broken.push(format!("{}: {target}: no such file", doc.display()));
                continue;
            }
            if let Some(anchor) = anchor {
                let headings = anchors(&read(&path));
                if !headings.contains(anchor) {
                    broken.push(format!(
                        "{}: {target}: {} has no heading #{anchor}",
                        doc.display(),
                        path.display()
                    ));
                }
            }
        }
    }
    assert!(broken.is_empty(), "broken links:\n{}", broken.join("\n"));
    assert!(
        count > 50,
        "only {count} links found: is the pattern right?"
    );
}

/// A code block left open swallows the rest of its document into one
/// block of code (headings and links included), which no other check sees.
#[test]
fn every_code_block_is_closed() {
    for doc in documents() {
        let fences = read(&doc)
            .lines()
            .filter(|l| l.trim_start().starts_with("```"))
            .count();
        assert!(
            fences % 2 == 0,
            "{}: a code block is not closed",
            doc.display()
        );
    }
}

#[test]
fn the_anchor_rule_is_githubs() {
    let text = "# Title\n## Jumps on inputs (reject paths, retries, ending early)\n\
                ## The `SETTINGS` sheet\n## Title\n```\n# not a heading\n```\n";
    let found = anchors(text);
    for anchor in [
        "title",
        "jumps-on-inputs-reject-paths-retries-ending-early",
        "the-settings-sheet",
        "title-1",
    ] {
        assert!(found.contains(anchor), "{anchor}: {found:?}");
    }
    assert!(!found.contains("not-a-heading"));
}

/// The reference is where a reader looks a code, an option or a SETTINGS
/// row up: each must be there.
#[test]
fn the_reference_lists_every_code_option_and_settings_row() {
    let reference = read(Path::new("docs/reference.md"));
    let diag = std::fs::read_to_string(root().join("src/diag.rs")).unwrap();
    let codes = regex::Regex::new(r#"=> "([EW]\d{3})""#).unwrap();
    let mut count = 0;
    for code in codes.captures_iter(&diag) {
        count += 1;
        let code = &code[1];
        assert!(
            reference
                .lines()
                .any(|l| l.starts_with(&format!("| {code} |"))),
            "{code} has no row in docs/reference.md"
        );
    }
    assert!(count >= 30, "{count} codes");
    // Every long option of every command, as the binary's help lists it.
    let option = regex::Regex::new(r"(?m)^\s+(?:-\w, )?(--[a-z][a-z-]*)").unwrap();
    let command = regex::Regex::new(r"(?m)^  ([a-z]+)  ").unwrap();
    let help = |args: &[&str]| -> String {
        let out = crate::helpers::steptable()
            .args(args)
            .arg("--help")
            .output()
            .unwrap();
        String::from_utf8(out.stdout).unwrap()
    };
    let mut pending = vec![Vec::<String>::new()];
    let mut options = BTreeSet::new();
    while let Some(path) = pending.pop() {
        let args: Vec<&str> = path.iter().map(String::as_str).collect();
        let text = help(&args);
        for m in option.captures_iter(&text) {
            if !["--help", "--version"].contains(&&m[1]) {
                options.insert(m[1].to_string());
            }
        }
        if let Some(list) = text.split("Commands:").nth(1) {
            let list = list.split("Options:").next().unwrap();
            for m in command.captures_iter(list) {
                if &m[1] != "help" {
                    let mut next = path.clone();
                    next.push(m[1].to_string());
                    pending.push(next);
                }
            }
        }
    }
    assert!(options.len() > 30, "{options:?}");
    for option in &options {
        assert!(
            reference.contains(&format!("`{option}")),
            "{option} is not in docs/reference.md"
        );
    }
    for label in steptable::settings::LABELS {
        assert!(
            reference.contains(&format!("`{label}`")),
            "the SETTINGS row {label} is not in docs/reference.md"
        );
    }
}

/// Every fuzz command of the development notes runs on a fresh clone: a
/// corpus folder it names exists in git or is made on the same line
/// (`mkdir -p`), since libFuzzer refuses a folder that is not there.
#[test]
fn every_fuzz_command_names_folders_a_fresh_clone_has() {
    let notes = read(Path::new("docs/development.md"));
    let mut commands = 0;
    for line in notes.lines().filter(|l| l.contains("fuzz run ")) {
        commands += 1;
        let (made, run) = line.split_once("fuzz run ").unwrap();
        let folders = run.split(" -- ").next().unwrap().split_whitespace().skip(1);
        for folder in folders {
            assert!(
                root().join(folder).is_dir() || made.contains(&format!("mkdir -p {folder}")),
                "docs/development.md: `{line}` names {folder}, which a fresh clone does not have (make it with mkdir -p before the run)"
            );
        }
    }
    assert!(commands >= 6, "the fuzz commands moved: {commands} found");
}

/// The help says the defaults there are (rt8 finding 7): `--formats`
/// leaves the graphical bodies out unless named, and a swivel drive and a
/// gripper have their own stroke times. It said "default all" and "1s/1s".
#[test]
fn the_help_gives_the_real_defaults() {
    let out = crate::helpers::steptable()
        .args(["convert", "--help"])
        .output()
        .unwrap();
    let help = String::from_utf8(out.stdout).unwrap();
    assert!(!help.contains("(default all)"), "{help}");
    assert!(
        help.contains("default: every one but sfc, ld, beremiz-sfc"),
        "{help}"
    );
    assert!(
        help.contains("swivel drive's and a vacuum gripper's own times"),
        "{help}"
    );
}
