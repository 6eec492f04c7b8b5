//! The pipeline's shape, checked on the source: which module may import
//! which (ARCHITECTURE.md, "The rules between modules"). Data flows one way;
//! a new `use` that closes a circle or crosses a forbidden line fails here,
//! naming the file.

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

/// Every `crate::<module>` a module's non-test code names, per file.
fn imports() -> BTreeMap<String, BTreeMap<String, String>> {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let pattern = regex::Regex::new(r"crate::([a-z_]+)").unwrap();
    let mut edges: BTreeMap<String, BTreeMap<String, String>> = BTreeMap::new();
    let mut stack = vec![root.clone()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
                continue;
            }
            let rel = path
                .strip_prefix(&root)
                .unwrap()
                .to_string_lossy()
                .to_string();
            if !rel.ends_with(".rs") || rel.ends_with("tests.rs") || rel.starts_with("cli/") {
                continue;
            }
            let module = rel.split('/').next().unwrap().trim_end_matches(".rs");
            let text = std::fs::read_to_string(&path).unwrap();
            // Unit tests sit at the end of a file and may use anything.
            let code = text.split("#[cfg(test)]").next().unwrap();
            for m in pattern.captures_iter(code) {
                let to = m[1].to_string();
                if to != module {
                    edges
                        .entry(module.to_string())
                        .or_default()
                        .entry(to)
                        .or_insert_with(|| rel.clone());
                }
            }
        }
    }
    edges
}

#[test]
fn modules_import_in_pipeline_order_without_circles() {
    let edges = imports();
    // Depth-first search for a circle, reported as its path.
    fn visit(
        at: &str,
        edges: &BTreeMap<String, BTreeMap<String, String>>,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
    ) {
        if let Some(start) = path.iter().position(|m| m == at) {
            panic!("import circle: {} -> {at}", path[start..].join(" -> "));
        }
        if done.contains(at) {
            return;
        }
        path.push(at.to_string());
        for next in edges.get(at).into_iter().flat_map(|e| e.keys()) {
            visit(next, edges, path, done);
        }
        path.pop();
        done.insert(at.to_string());
    }
    let mut done = BTreeSet::new();
    for module in edges.keys() {
        visit(module, &edges, &mut Vec::new(), &mut done);
    }

    // What each stage never does.
    let forbidden: &[(&str, &[&str], &str)] = &[
        (
            "emit",
            &["write", "convert", "batch", "settings", "read"],
            "emit renders the program into bytes; it never reads or writes files, nor knows the reader",
        ),
        (
            "simulate",
            &["emit", "address", "convert", "settings"],
            "simulate runs the program, never an output language or an address",
        ),
        (
            "faults",
            &["emit", "address", "convert"],
            "faults run the program",
        ),
        (
            "program",
            &["emit", "address", "simulate", "read", "settings", "symbols"],
            "the program knows no output language and no address",
        ),
        (
            "symbols",
            &[
                "emit", "address", "convert", "settings", "simulate", "faults",
            ],
            "the symbol table names the program's signals; every output reads it, it reads none",
        ),
        (
            "address",
            &["table", "read", "emit", "cell"],
            "address lays out the program's signals; it knows no table cells",
        ),
        (
            "synth",
            &["emit", "convert", "settings"],
            "synth finds equations; emit writes them as programs",
        ),
        (
            "table",
            &["program", "address", "emit", "simulate"],
            "the table stage only checks what was read",
        ),
        (
            "read",
            &["table", "program", "address", "emit"],
            "read turns files into grids of cells",
        ),
        (
            "provenance",
            &["convert", "batch", "commands", "write", "cli"],
            "provenance puts one line into bytes in memory; it runs no stage and writes nothing",
        ),
        (
            "convert",
            &["commands", "batch", "cli"],
            "convert is the pipeline in memory; the commands stand above it",
        ),
    ];
    for (module, never, why) in forbidden {
        for target in *never {
            if let Some(file) = edges.get(*module).and_then(|e| e.get(*target)) {
                panic!("src/{file} imports crate::{target}: {why}");
            }
        }
    }
}

#[test]
fn emit_never_touches_the_file_system() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/emit");
    let io = regex::Regex::new(r"std::fs|\bFile::|\bread_dir\b|\bOpenOptions\b").unwrap();
    // Its folders too (emit/grafcet/, emit/report/).
    let mut paths = vec![dir];
    let mut files = Vec::new();
    while let Some(path) = paths.pop() {
        if path.is_dir() {
            paths.extend(std::fs::read_dir(path).unwrap().map(|e| e.unwrap().path()));
        } else {
            files.push(path);
        }
    }
    assert!(
        files.iter().any(|f| f.ends_with("grafcet/mod.rs")),
        "{files:?}"
    );
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap();
        let code = text.split("#[cfg(test)]").next().unwrap();
        if let Some(found) = io.find(code) {
            panic!(
                "{}: {} (emit never reads or writes files)",
                path.display(),
                found.as_str()
            );
        }
    }
}
