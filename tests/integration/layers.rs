//! The pipeline's shape, checked on the source: which module may import
//! which (ARCHITECTURE.md, "The rules between modules"). Data flows one way;
//! a new `use` that closes a circle or crosses a forbidden line fails here,
//! naming the file.

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// Who imports whom: per importing module, each module it names and the
/// first file that names it.
type Edges = BTreeMap<String, BTreeMap<String, String>>;

/// Every `.rs` file below `dir`.
fn rust_files(dir: &Path) -> Vec<PathBuf> {
    let mut files = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(at) = stack.pop() {
        for entry in std::fs::read_dir(&at).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "rs") {
                files.push(path);
            }
        }
    }
    files
}

/// A file's code without its unit tests, which sit at the end of a file
/// and may use anything.
fn code_of(path: &Path) -> String {
    let text = std::fs::read_to_string(path).unwrap();
    text.split("#[cfg(test)]").next().unwrap().to_string()
}

/// Every `crate::<module>` a module's non-test code names, per file.
fn imports() -> Edges {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let pattern = regex::Regex::new(r"crate::([a-z_]+)").unwrap();
    let mut edges = Edges::new();
    for path in rust_files(&root) {
        let rel = path
            .strip_prefix(&root)
            .unwrap()
            .to_string_lossy()
            .to_string();
        if rel.ends_with("tests.rs") || rel.starts_with("cli/") {
            continue;
        }
        let module = rel.split('/').next().unwrap().trim_end_matches(".rs");
        for m in pattern.captures_iter(&code_of(&path)) {
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
    edges
}

/// Fails, naming the circle's path, when `edges` have one.
fn no_circle(edges: &Edges, within: &str) {
    // Depth-first search for a circle, reported as its path.
    fn visit(
        at: &str,
        edges: &Edges,
        path: &mut Vec<String>,
        done: &mut BTreeSet<String>,
        within: &str,
    ) {
        if let Some(start) = path.iter().position(|m| m == at) {
            panic!(
                "import circle{within}: {} -> {at}",
                path[start..].join(" -> ")
            );
        }
        if done.contains(at) {
            return;
        }
        path.push(at.to_string());
        for next in edges.get(at).into_iter().flat_map(|e| e.keys()) {
            visit(next, edges, path, done, within);
        }
        path.pop();
        done.insert(at.to_string());
    }
    let mut done = BTreeSet::new();
    for module in edges.keys() {
        visit(module, edges, &mut Vec::new(), &mut done, within);
    }
}

#[test]
fn modules_import_in_pipeline_order_without_circles() {
    let edges = imports();
    no_circle(&edges, "");

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
        (
            "actuator",
            &[
                "read", "table", "program", "address", "simulate", "faults", "emit", "settings",
                "convert", "symbols",
            ],
            "the actuator model is a leaf: every stage asks it what a kind is, it asks none",
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
    let files = rust_files(&dir);
    // Its folders too (emit/grafcet/, emit/report/, emit/workbook/).
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

/// Every submodule of `module` another of its submodules names, from the
/// non-test code of the files below `src/<module>/`: `super::x`,
/// `super::{x, y::Z}` (from a file one level down) and `crate::<module>::x`.
fn submodule_imports(module: &str) -> Edges {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("src")
        .join(module);
    let own = regex::Regex::new(&format!(r"crate::{module}::([a-z_]+)")).unwrap();
    let sup = regex::Regex::new(r"\bsuper::([a-z_]+)").unwrap();
    let group = regex::Regex::new(r"\bsuper::\{([^}]*)\}").unwrap();
    let files = rust_files(&dir);
    let submodules: BTreeSet<String> = files
        .iter()
        .map(|f| submodule_of(&dir, f))
        .filter(|m| m != "mod")
        .collect();
    let mut edges = Edges::new();
    for file in &files {
        let from = submodule_of(&dir, file);
        let rel = file
            .strip_prefix(&dir)
            .unwrap()
            .to_string_lossy()
            .to_string();
        if from == "mod" || rel.ends_with("tests.rs") {
            continue;
        }
        let code = code_of(file);
        let mut named: Vec<String> = own.captures_iter(&code).map(|m| m[1].to_string()).collect();
        // `super::` leaves the submodule only from a file directly below
        // the module's folder.
        if !rel.contains('/') {
            named.extend(sup.captures_iter(&code).map(|m| m[1].to_string()));
            for g in group.captures_iter(&code) {
                named.extend(g[1].split(',').filter_map(|item| {
                    let first = item.trim().split("::").next()?.trim();
                    (!first.is_empty()).then(|| first.to_string())
                }));
            }
        }
        for to in named {
            if to != from && submodules.contains(&to) {
                edges
                    .entry(from.clone())
                    .or_default()
                    .entry(to)
                    .or_insert_with(|| rel.clone());
            }
        }
    }
    edges
}

/// `src/synth/verify.rs` and `src/simulate/run/cycle.rs` are submodules
/// `verify` and `run`; `mod.rs` directly below is the module itself.
fn submodule_of(dir: &Path, file: &Path) -> String {
    let rel = file.strip_prefix(dir).unwrap();
    let first = rel
        .components()
        .next()
        .unwrap()
        .as_os_str()
        .to_string_lossy();
    first.trim_end_matches(".rs").to_string()
}

/// The circle `synth::modes` <-> `synth::verify` (the synthesised
/// program's own scan loop and its proof importing each other) must not
/// come back: inside `synth` the submodules import one way.
#[test]
fn synth_submodules_import_without_circles() {
    let edges = submodule_imports("synth");
    no_circle(&edges, " in synth");
    // The proof imports the program it proves, never the other way.
    assert!(edges["verify"].contains_key("controller"), "{edges:?}");
}

/// Synthesis proves its controllers on the shared simulation: it reaches
/// the plant only through `simulate::bench`, so a scan loop or plant model
/// of its own cannot come back unnoticed.
#[test]
fn synth_runs_its_controllers_only_on_the_shared_bench() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("src/synth");
    let own_plant =
        regex::Regex::new(r"simulate::(plant|plc|run|world|scenario)\b|\bPiston\b|\.advance\(\)")
            .unwrap();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if let Some(found) = own_plant.find(&code_of(&path)) {
            panic!(
                "{}: {} (synth runs its controllers on simulate::bench, the plant and scan of every proof)",
                path.display(),
                found.as_str()
            );
        }
    }
}

/// Inside every module the submodules import one way too (a module's
/// `mod.rs` holds them together and is left out): a circle such as
/// `synth::modes` <-> `synth::verify` fails here for any module.
#[test]
fn no_module_has_a_circle_inside() {
    let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
    let mut modules = 0;
    for entry in std::fs::read_dir(src).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            let module = path.file_name().unwrap().to_string_lossy().to_string();
            no_circle(&submodule_imports(&module), &format!(" in {module}"));
            modules += 1;
        }
    }
    assert!(modules >= 10, "{modules} modules found");
}
