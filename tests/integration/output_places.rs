//! Where outputs go (issue 37): a run replaces only what a run wrote, as
//! the folder's `.steptable-manifest` records it; anything else in an
//! output's place is E040, exit 1, with nothing written for that input; a
//! folder walk skips a table only when a manifest vouches for it. Also a
//! folder given where a table file goes (E001), the output budget of a
//! template, and commands and format names that lead to the right one.

use std::path::{Path, PathBuf};

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{files_below, files_with_bytes, sample, steptable};

const MANIFEST: &str = ".steptable-manifest";

fn table(path: &Path) -> PathBuf {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    std::fs::write(path, "C1+1\nC1-0\n").unwrap();
    path.to_path_buf()
}

/// One hostile arrangement of files: what the engineer has, the command,
/// and what must come of it.
struct Case {
    name: &'static str,
    /// Makes the files in the work folder; returns the arguments.
    setup: fn(&Path) -> Vec<String>,
    code: i32,
    /// The error code and the path it names (relative to the work folder).
    error: Option<(&'static str, &'static str)>,
    /// Files (relative) that must be left byte for byte as they were.
    kept: &'static [&'static str],
}

fn s(items: &[&str]) -> Vec<String> {
    items.iter().map(|i| i.to_string()).collect()
}

fn cases() -> Vec<Case> {
    vec![
        Case {
            name: "batch w -o w: the engineer's w/a/a.steptable.xlsx is where a.csv's workbook goes",
            setup: |w| {
                table(&w.join("w/a.csv"));
                std::fs::create_dir_all(w.join("w/a")).unwrap();
                std::fs::copy(sample("paper_example.xlsx"), w.join("w/a/a.steptable.xlsx"))
                    .unwrap();
                s(&["batch", "w", "-o", "w", "-j", "1"])
            },
            code: 1,
            error: Some(("E040", "w/a/a.steptable.xlsx")),
            kept: &["w/a/a.steptable.xlsx"],
        },
        Case {
            name: "batch plant -o plant: tables named like outputs are inputs, never skipped",
            setup: |w| {
                for n in ["press", "drill"] {
                    std::fs::create_dir_all(w.join(format!("plant/{n}"))).unwrap();
                    std::fs::copy(
                        sample("paper_example.xlsx"),
                        w.join(format!("plant/{n}/{n}.steptable.xlsx")),
                    )
                    .unwrap();
                }
                // press.csv's workbook goes where press.steptable.xlsx lies.
                table(&w.join("plant/press.csv"));
                s(&["batch", "plant", "-o", "plant"])
            },
            code: 1,
            error: Some(("E040", "plant/press/press.steptable.xlsx")),
            kept: &[
                "plant/press/press.steptable.xlsx",
                "plant/drill/drill.steptable.xlsx",
            ],
        },
        Case {
            name: "convert out/x/x.steptable.xlsx -o out: a table named like the workbook converts beside it",
            setup: |w| {
                std::fs::create_dir_all(w.join("out/x")).unwrap();
                std::fs::copy(
                    sample("paper_example.xlsx"),
                    w.join("out/x/x.steptable.xlsx"),
                )
                .unwrap();
                s(&["convert", "out/x/x.steptable.xlsx", "-o", "out"])
            },
            code: 0,
            error: None,
            kept: &["out/x/x.steptable.xlsx"],
        },
        Case {
            name: "convert x.csv out/x/x.steptable.xlsx -o out: an input where the other's workbook goes",
            setup: |w| {
                table(&w.join("x.csv"));
                std::fs::create_dir_all(w.join("out/x")).unwrap();
                std::fs::copy(
                    sample("paper_example.xlsx"),
                    w.join("out/x/x.steptable.xlsx"),
                )
                .unwrap();
                s(&["convert", "x.csv", "out/x/x.steptable.xlsx", "-o", "out"])
            },
            code: 1,
            error: Some(("E040", "out/x/x.steptable.xlsx")),
            kept: &["out/x/x.steptable.xlsx"],
        },
        Case {
            name: "convert x.csv -o out: the engineer's own workbook where the output workbook goes",
            setup: |w| {
                table(&w.join("x.csv"));
                std::fs::create_dir_all(w.join("out/x")).unwrap();
                std::fs::write(w.join("out/x/x.steptable.xlsx"), "my notes").unwrap();
                s(&["convert", "x.csv", "-o", "out"])
            },
            code: 1,
            error: Some(("E040", "out/x/x.steptable.xlsx")),
            kept: &["out/x/x.steptable.xlsx"],
        },
        Case {
            name: "convert: a file of the engineer's where an output goes",
            setup: |w| {
                table(&w.join("x.csv"));
                std::fs::create_dir_all(w.join("out/x")).unwrap();
                std::fs::write(w.join("out/x/x.st"), "my own program\n").unwrap();
                s(&["convert", "x.csv", "-o", "out"])
            },
            code: 1,
            error: Some(("E040", "out/x/x.st")),
            kept: &["out/x/x.st"],
        },
        Case {
            name: "batch: the same, through batch",
            setup: |w| {
                table(&w.join("in/x.csv"));
                std::fs::create_dir_all(w.join("out/x")).unwrap();
                std::fs::write(w.join("out/x/x.io.csv"), "my list\n").unwrap();
                s(&["batch", "in", "-o", "out"])
            },
            code: 1,
            error: Some(("E040", "out/x/x.io.csv")),
            kept: &["out/x/x.io.csv"],
        },
        Case {
            name: "an output changed since a run wrote it (the manifest lists it)",
            setup: |w| {
                table(&w.join("x.csv"));
                steptable()
                    .current_dir(w)
                    .args(["convert", "x.csv", "-o", "out"])
                    .assert()
                    .success();
                std::fs::write(w.join("out/x/x.awl"), "// my edits\n").unwrap();
                s(&["convert", "x.csv", "-o", "out"])
            },
            code: 1,
            error: Some(("E040", "out/x/x.awl")),
            kept: &["out/x/x.awl", "out/x/.steptable-manifest", "out/x/x.st"],
        },
        Case {
            name: "an output's file name is a folder on the rerun",
            setup: |w| {
                table(&w.join("x.csv"));
                std::fs::create_dir_all(w.join("out/x/x.st")).unwrap();
                std::fs::write(w.join("out/x/x.st/notes.txt"), "mine\n").unwrap();
                s(&["convert", "x.csv", "-o", "out"])
            },
            code: 1,
            error: Some(("E040", "out/x/x.st")),
            kept: &["out/x/x.st/notes.txt"],
        },
        Case {
            name: "convert -o names an existing file",
            setup: |w| {
                table(&w.join("x.csv"));
                std::fs::write(w.join("notes.txt"), "mine\n").unwrap();
                s(&["convert", "x.csv", "-o", "notes.txt"])
            },
            code: 1,
            error: Some(("E040", "notes.txt")),
            kept: &["notes.txt"],
        },
        Case {
            name: "batch -o names an existing file",
            setup: |w| {
                table(&w.join("x.csv"));
                std::fs::write(w.join("notes.txt"), "mine\n").unwrap();
                s(&["batch", "x.csv", "-o", "notes.txt"])
            },
            code: 1,
            error: Some(("E040", "notes.txt")),
            kept: &["notes.txt"],
        },
        Case {
            name: "a file where the input's output folder goes",
            setup: |w| {
                table(&w.join("x.csv"));
                std::fs::create_dir_all(w.join("out")).unwrap();
                std::fs::write(w.join("out/x"), "mine\n").unwrap();
                s(&["convert", "x.csv", "-o", "out"])
            },
            code: 1,
            error: Some(("E040", "out/x")),
            kept: &["out/x"],
        },
        Case {
            name: "a file where the Beremiz project folder goes",
            setup: |w| {
                table(&w.join("x.csv"));
                std::fs::create_dir_all(w.join("out/x")).unwrap();
                std::fs::write(w.join("out/x/x.beremiz"), "mine\n").unwrap();
                s(&["convert", "x.csv", "-o", "out"])
            },
            code: 1,
            error: Some(("E040", "out/x/x.beremiz")),
            kept: &["out/x/x.beremiz"],
        },
        Case {
            name: "a file of the engineer's named like the manifest",
            setup: |w| {
                table(&w.join("x.csv"));
                std::fs::create_dir_all(w.join("out/x")).unwrap();
                std::fs::write(w.join("out/x/.steptable-manifest"), "mine\n").unwrap();
                s(&["convert", "x.csv", "-o", "out"])
            },
            code: 1,
            error: Some(("E040", "out/x/.steptable-manifest")),
            kept: &["out/x/.steptable-manifest"],
        },
        Case {
            name: "faults -o: the engineer's fault table in its place",
            setup: |w| {
                table(&w.join("x.csv"));
                std::fs::create_dir_all(w.join("out/x")).unwrap();
                std::fs::write(w.join("out/x/x.faults.csv"), "mine\n").unwrap();
                s(&["faults", "x.csv", "-o", "out"])
            },
            code: 1,
            error: Some(("E040", "out/x/x.faults.csv")),
            kept: &["out/x/x.faults.csv"],
        },
        Case {
            name: "an output folder of a version without manifests, with other bytes",
            setup: |w| {
                table(&w.join("x.csv"));
                steptable()
                    .current_dir(w)
                    .args(["convert", "x.csv", "--target", "iec", "-o", "out"])
                    .assert()
                    .success();
                std::fs::remove_file(w.join("out/x/.steptable-manifest")).unwrap();
                s(&["convert", "x.csv", "-o", "out"])
            },
            code: 1,
            error: Some(("E040", "out/x/x.st")),
            kept: &["out/x/x.st", "out/x/x.io.csv"],
        },
        Case {
            name: "a rerun replaces what the first run wrote",
            setup: |w| {
                table(&w.join("x.csv"));
                steptable()
                    .current_dir(w)
                    .args(["convert", "x.csv", "-o", "out"])
                    .assert()
                    .success();
                s(&["convert", "x.csv", "-o", "out"])
            },
            code: 0,
            error: None,
            kept: &[],
        },
        Case {
            name: "an output folder of a version without manifests, byte for byte the same",
            setup: |w| {
                table(&w.join("x.csv"));
                steptable()
                    .current_dir(w)
                    .args(["convert", "x.csv", "-o", "out"])
                    .assert()
                    .success();
                std::fs::remove_file(w.join("out/x/.steptable-manifest")).unwrap();
                s(&["convert", "x.csv", "-o", "out"])
            },
            code: 0,
            error: None,
            kept: &["out/x/x.st"],
        },
    ]
}

/// Every hostile arrangement: its exit code, its error code naming the
/// path in the way, the engineer's files untouched, and — when refused —
/// nothing new written for the refused input (no manifest claims a file).
#[test]
fn every_output_place_that_is_taken_is_refused_and_named() {
    for case in cases() {
        let dir = tempfile::tempdir().unwrap();
        let work = dir.path();
        let args = (case.setup)(work);
        let before = files_with_bytes(work);
        let (exit, said) = crate::helpers::run_in(work, &args);
        assert_eq!(exit, Some(case.code), "{}: {said}", case.name);
        assert!(!said.contains("panicked"), "{}: {said}", case.name);
        if let Some((code, path)) = case.error {
            let expected = format!("{path}: error[{code}]");
            assert!(
                said.contains(&expected),
                "{}: no `{expected}` in {said}",
                case.name
            );
        }
        let after = files_with_bytes(work);
        for kept in case.kept {
            let path = work.join(kept);
            let was = before.iter().find(|(p, _)| *p == path);
            let now = after.iter().find(|(p, _)| *p == path);
            assert_eq!(
                was.map(|w| &w.1),
                now.map(|n| &n.1),
                "{}: {kept}",
                case.name
            );
        }
        if case.code != 0 {
            // What existed is as it was; what is new is only other inputs'.
            for (path, bytes) in &before {
                let now = after.iter().find(|(p, _)| p == path);
                assert_eq!(
                    now.map(|n| &n.1),
                    Some(bytes),
                    "{}: {}",
                    case.name,
                    path.display()
                );
            }
            if let Some((_, taken)) = case.error {
                let folder = work.join(taken).parent().unwrap().to_path_buf();
                let new: Vec<_> = after
                    .iter()
                    .filter(|(p, _)| p.parent() == Some(&folder))
                    .filter(|f| !before.contains(f))
                    .collect();
                assert!(new.is_empty(), "{}: written beside it: {new:?}", case.name);
            }
        }
    }
}

/// A link in an output's place is never ours: refused, and the file it
/// points to is untouched.
#[cfg(unix)]
#[test]
fn a_link_in_an_outputs_place_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path();
    table(&work.join("x.csv"));
    std::fs::write(work.join("mine.st"), "mine\n").unwrap();
    std::fs::create_dir_all(work.join("out/x")).unwrap();
    std::os::unix::fs::symlink(work.join("mine.st"), work.join("out/x/x.st")).unwrap();
    steptable()
        .current_dir(work)
        .args(["convert", "x.csv", "-o", "out"])
        .assert()
        .code(1)
        .stderr(contains("out/x/x.st: error[E040]"));
    assert_eq!(
        std::fs::read_to_string(work.join("mine.st")).unwrap(),
        "mine\n"
    );
    assert_eq!(files_below(&work.join("out")).len(), 1);
}

/// `batch . -o .` reruns: the second run converts the same two tables (the
/// outputs are skipped because the manifests vouch for them, and it says
/// so), and the manifest lists exactly what was written.
#[test]
fn batch_into_its_own_folder_reruns_on_the_same_tables() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path();
    table(&work.join("line.csv"));
    std::fs::copy(sample("paper_example.xlsx"), work.join("paper.xlsx")).unwrap();
    for run in 0..2 {
        let output = steptable()
            .current_dir(work)
            .args(["batch", ".", "-o", ".", "-j", "1"])
            .output()
            .unwrap();
        let stdout = String::from_utf8_lossy(&output.stdout);
        assert!(output.status.success(), "run {run}: {stdout}");
        assert!(
            stdout.contains("2 converted, 0 failed"),
            "run {run}: {stdout}"
        );
        assert_eq!(
            stdout.contains("are outputs of an earlier run"),
            run == 1,
            "run {run}: {stdout}"
        );
    }
    let manifest = std::fs::read_to_string(work.join("line").join(MANIFEST)).unwrap();
    // Each file's line, and under it (indented) how the run made it.
    let listed: Vec<&str> = manifest
        .lines()
        .skip(1)
        .filter(|l| !l.starts_with("  "))
        .map(|l| l.splitn(3, ' ').nth(2).unwrap())
        .collect();
    let mut written: Vec<String> = files_below(&work.join("line"))
        .iter()
        .map(|f| {
            f.strip_prefix(work.join("line"))
                .unwrap()
                .to_string_lossy()
                .to_string()
        })
        .collect();
    written.sort();
    assert_eq!(listed, written);
    let made_by: Vec<&str> = manifest.lines().filter(|l| l.starts_with("  ")).collect();
    assert_eq!(made_by.len(), listed.len(), "{manifest}");
    assert!(
        made_by
            .iter()
            .all(|l| l.contains("from line.csv: steptable batch .; settings: ")),
        "{manifest}"
    );
}

/// A workbook named like an output is a table like any other when no
/// manifest vouches for it (`plant/press/press.xlsx`, and a run's workbook
/// the engineer replaced since): both convert. The run's other outputs in
/// the walk, vouched for byte for byte, are left out and counted.
#[test]
fn tables_named_like_outputs_are_converted() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path();
    std::fs::create_dir_all(work.join("plant/press")).unwrap();
    std::fs::copy(
        sample("paper_example.xlsx"),
        work.join("plant/press/press.steptable.xlsx"),
    )
    .unwrap();
    table(&work.join("src/drill.csv"));
    steptable()
        .current_dir(work)
        .args(["convert", "src/drill.csv", "-o", "plant"])
        .assert()
        .success();
    std::fs::copy(
        sample("paper_example.xlsx"),
        work.join("plant/drill/drill.steptable.xlsx"),
    )
    .unwrap();
    let output = steptable()
        .current_dir(work)
        .args(["batch", "plant", "-o", "out"])
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(output.status.success(), "{stdout}");
    assert!(stdout.contains("2 converted, 0 failed"), "{stdout}");
    // The four CSV lists and the TIA tag table of the run.
    assert!(
        stdout.contains("note: 5 table(s) in the folders are outputs of an earlier run"),
        "{stdout}"
    );
    let summary = std::fs::read_to_string(work.join("out/summary.csv")).unwrap();
    assert!(
        summary.contains("plant/drill/drill.steptable.xlsx,converted"),
        "{summary}"
    );
    assert!(
        summary.contains("plant/press/press.steptable.xlsx,converted"),
        "{summary}"
    );
}

/// A folder where a table file goes is E001 (not E002, "not a workbook"),
/// in every command that reads tables, with the way to convert a folder.
#[test]
fn a_folder_given_as_a_table_is_e001_and_points_to_batch() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("tables.xlsx");
    table(&folder.join("line.csv"));
    for command in ["check", "convert", "simulate", "faults", "synth"] {
        let out = dir.path().join(format!("out-{command}"));
        let mut cmd = steptable();
        cmd.arg(command).arg(&folder);
        if command != "check" && command != "simulate" {
            cmd.arg("-o").arg(&out);
        }
        cmd.assert()
            .code(1)
            .stderr(contains("tables.xlsx: error[E001]: is a folder"))
            .stderr(contains("steptable batch FOLDER -o DIR"));
        assert!(!out.exists(), "{command} wrote {}", out.display());
    }
}

/// A template that writes without end stops at the output budget with an
/// error naming it and the limit: exit 1, nothing written, in seconds.
#[test]
fn a_template_that_writes_without_end_stops_at_the_budget() {
    let dir = tempfile::tempdir().unwrap();
    let templates = dir.path().join("t");
    std::fs::create_dir_all(&templates).unwrap();
    let out = dir.path().join("out");
    let doubling = "{% set ns = namespace(s='x') %}{% for i in range(40) %}{% set ns.s = ns.s ~ ns.s %}{% endfor %}{{ ns.s }}\n";
    for (template, said) in [
        (
            "{% for a in range(100000) %}{% for b in range(1000) %}xxxxxxxxxx{% endfor %}{% endfor %}\n",
            "program.awl.j2: the output passed",
        ),
        // A value built when the template is read (minijinja folds the
        // constant; 100 MB aborted under `ulimit -v`).
        (
            "{{ 'x' * 100000000 }}\n",
            "program.awl.j2: the template asked for a value of",
        ),
        // A value doubled inside the render: bounded at four budgets, where
        // it ended in an abort with a backtrace (under `ulimit -v`) or asked
        // for a terabyte.
        (
            doubling,
            "program.awl.j2: the template asked for a value of",
        ),
    ] {
        std::fs::write(templates.join("program.awl.j2"), template).unwrap();
        let started = std::time::Instant::now();
        steptable()
            .arg("convert")
            .arg(sample("paper_example.xlsx"))
            .arg("--templates")
            .arg(&templates)
            .arg("-o")
            .arg(&out)
            .timeout(std::time::Duration::from_secs(60))
            .assert()
            .code(1)
            .stderr(contains(said))
            .stderr(contains(" MiB"))
            .stderr(contains("panicked").not())
            .stderr(contains("backtrace").not());
        assert!(started.elapsed() < std::time::Duration::from_secs(30));
        assert!(!out.exists(), "nothing written");
    }
}

/// `--formats tags` points to `tia`; `template export` to `templates
/// export`, and `templates` with the workbook's options to `template`;
/// nothing is written by any of them.
#[test]
fn mistaken_names_lead_to_the_command_and_format_meant() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path();
    table(&work.join("x.csv"));
    steptable()
        .current_dir(work)
        .args(["convert", "x.csv", "--formats", "st,tags", "-o", "out"])
        .assert()
        .code(1)
        .stderr(contains("did you mean tia (writes NAME.tags.xlsx)?"));
    steptable()
        .current_dir(work)
        .args(["template", "export", "layouts"])
        .assert()
        .code(1)
        .stderr(contains(
            "did you mean `steptable templates export layouts`?",
        ));
    steptable()
        .current_dir(work)
        .args(["templates", "-o", "t.xlsx"])
        .assert()
        .code(1)
        .stderr(contains("did you mean `steptable template`"));
    assert_eq!(files_below(work), [work.join("x.csv")]);
    // Each command's help says which is which.
    let help = steptable().arg("--help").output().unwrap();
    let help = String::from_utf8_lossy(&help.stdout);
    let line = |name: &str| {
        help.lines()
            .find(|l| l.trim_start().starts_with(&format!("{name} ")))
            .unwrap_or_default()
            .to_string()
    };
    assert!(line("template").contains("not `templates`"), "{help}");
    assert!(line("templates").contains("not `template`"), "{help}");
}

/// The values `--help` lists for `--formats` and `--valve` are the
/// library's own lists, all of them.
#[test]
fn help_lists_every_format_and_valve() {
    use clap::CommandFactory;
    let mut cli = steptable::cli::Cli::command();
    cli.build();
    let help_of = |command: &str, flag: &str| -> String {
        let sub = cli.find_subcommand(command).unwrap();
        let arg = sub.get_arguments().find(|a| a.get_id() == flag).unwrap();
        arg.get_help().unwrap().to_string()
    };
    let listed = |help: &str, after: &str, before: &str| -> Vec<String> {
        let start = help.find(after).unwrap() + after.len();
        let end = start + help[start..].find(before).unwrap();
        help[start..end].split(", ").map(str::to_string).collect()
    };
    let kinds: Vec<String> = steptable::emit::OutputKind::ALL
        .iter()
        .map(|k| k.name().to_string())
        .collect();
    for command in ["convert", "batch"] {
        let help = help_of(command, "formats");
        assert_eq!(
            listed(&help, "comma-separated: ", " (default"),
            kinds,
            "{help}"
        );
    }
    let valves: Vec<String> = steptable::actuator::ActuatorKind::ALL
        .iter()
        .map(|v| v.name().to_string())
        .collect();
    let help = help_of("convert", "valve");
    assert_eq!(listed(&help, "C2=53closed (", ")"), valves, "{help}");
}

/// A linked folder where steptable makes one (`DIR/NAME/`, or
/// `NAME.beremiz/`) is refused, and nothing lands where it points; a link
/// the user names with `-o` is written into (a share, another disk).
#[cfg(unix)]
#[test]
fn a_linked_output_folder_is_refused_but_a_linked_dash_o_is_not() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path();
    table(&work.join("x.csv"));
    std::fs::create_dir_all(work.join("elsewhere")).unwrap();
    std::fs::create_dir_all(work.join("out")).unwrap();
    std::os::unix::fs::symlink(work.join("elsewhere"), work.join("out/x")).unwrap();
    steptable()
        .current_dir(work)
        .args(["convert", "x.csv", "-o", "out"])
        .assert()
        .code(1)
        .stderr(contains("out/x: error[E040]").and(contains("it is a link")));
    assert!(files_below(&work.join("elsewhere")).is_empty());
    // The project folder below the output folder, too.
    std::fs::remove_file(work.join("out/x")).unwrap();
    std::fs::create_dir_all(work.join("out/x")).unwrap();
    std::os::unix::fs::symlink(work.join("elsewhere"), work.join("out/x/x.beremiz")).unwrap();
    steptable()
        .current_dir(work)
        .args(["convert", "x.csv", "-o", "out", "--formats", "beremiz"])
        .assert()
        .code(1)
        .stderr(contains("x.beremiz: error[E040]").and(contains("it is a link")));
    assert!(files_below(&work.join("elsewhere")).is_empty());
    // `-o` naming a link: the user's choice, written into.
    std::os::unix::fs::symlink(work.join("elsewhere"), work.join("linked")).unwrap();
    steptable()
        .current_dir(work)
        .args(["convert", "x.csv", "-o", "linked", "--formats", "st"])
        .assert()
        .success();
    assert!(work.join("elsewhere/x/x.st").is_file());
    // A link in a file's place says it is a link, not that it changed.
    std::fs::write(work.join("mine.st"), "mine\n").unwrap();
    std::fs::remove_file(work.join("elsewhere/x/x.st")).unwrap();
    std::os::unix::fs::symlink(work.join("mine.st"), work.join("elsewhere/x/x.st")).unwrap();
    steptable()
        .current_dir(work)
        .args(["convert", "x.csv", "-o", "linked", "--formats", "st"])
        .assert()
        .code(1)
        .stderr(contains(
            "x.st: error[E040]: (converting x.csv) an output goes here, and this is a link",
        ));
    assert_eq!(
        std::fs::read_to_string(work.join("mine.st")).unwrap(),
        "mine\n"
    );
}
