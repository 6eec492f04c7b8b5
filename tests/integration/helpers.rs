//! Helpers: run the binary, make workbooks, read workbooks back.

use std::path::{Path, PathBuf};

use assert_cmd::Command;
use calamine::{Data, Reader, open_workbook_auto};
use rust_xlsxwriter::Workbook;

/// The repository root (where `samples/` is).
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

pub fn sample(name: &str) -> PathBuf {
    root().join("samples").join(name)
}

/// Every bundled sample.
pub fn samples() -> Vec<PathBuf> {
    let mut list: Vec<PathBuf> = std::fs::read_dir(root().join("samples"))
        .expect("samples folder")
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            matches!(
                p.extension().and_then(|e| e.to_str()),
                Some("xlsx" | "xls" | "ods" | "csv")
            )
        })
        .collect();
    list.sort();
    list
}

/// The targets a sample converts for: the one its ADDRESSES sheet pins
/// addresses in (the oven's are STEP 7's), or every target.
pub fn targets_of(path: &Path) -> Vec<&'static str> {
    let settings = steptable::settings::Settings::new();
    let checked = steptable::convert::check_path(path, &settings)
        .unwrap_or_else(|e| panic!("{}: {e:?}", path.display()));
    if checked.settings.pins.is_empty() {
        vec!["festo", "iec", "siemens"]
    } else {
        vec![checked.settings.target.name()]
    }
}

pub fn steptable() -> Command {
    Command::cargo_bin("steptable").expect("binary built")
}

/// Writes an .xlsx with one sheet holding `rows` from A1 (empty strings skipped).
pub fn write_xlsx(path: &Path, sheet: &str, rows: &[&[&str]]) {
    let mut workbook = Workbook::new();
    let ws = workbook.add_worksheet();
    ws.set_name(sheet).expect("sheet name");
    for (r, row) in rows.iter().enumerate() {
        for (c, text) in row.iter().enumerate() {
            if !text.is_empty() {
                ws.write_string(r as u32, c as u16, *text).expect("write");
            }
        }
    }
    workbook.save(path).expect("save");
}

/// A sheet as rows of text (numbers printed as calamine prints them).
pub fn read_sheet(path: &Path, sheet: &str) -> Vec<Vec<String>> {
    let mut workbook = open_workbook_auto(path).expect("open workbook");
    let range = workbook.worksheet_range(sheet).expect("sheet");
    let (r0, c0) = range.start().unwrap_or((0, 0));
    let (r1, c1) = range.end().unwrap_or((0, 0));
    let mut rows = vec![vec![String::new(); c1 as usize + 1]; r1 as usize + 1];
    for (r, c, v) in range.used_cells() {
        let text = match v {
            Data::String(s) => s.clone(),
            Data::Empty => String::new(),
            other => other.to_string(),
        };
        rows[r0 as usize + r][c0 as usize + c] = text;
    }
    rows
}

/// All files below a folder (empty if it does not exist).
pub fn files_below(dir: &Path) -> Vec<PathBuf> {
    let mut found = Vec::new();
    if let Ok(entries) = std::fs::read_dir(dir) {
        for entry in entries.flatten() {
            let path = entry.path();
            if path.is_dir() {
                found.extend(files_below(&path));
            } else if entry.file_name() != steptable::manifest::FILE_NAME {
                // The record of what a run wrote is no output (its own
                // tests, `output_places.rs`, look for it by name).
                found.push(path);
            }
        }
    }
    found.sort();
    found
}

/// Writes an .xlsx with several sheets, each holding rows from A1.
pub fn write_xlsx_sheets(path: &Path, sheets: &[(&str, &[&[&str]])]) {
    let mut workbook = Workbook::new();
    for (name, rows) in sheets {
        let ws = workbook.add_worksheet();
        ws.set_name(*name).expect("sheet name");
        for (r, row) in rows.iter().enumerate() {
            for (c, text) in row.iter().enumerate() {
                if !text.is_empty() {
                    ws.write_string(r as u32, c as u16, *text).expect("write");
                }
            }
        }
    }
    workbook.save(path).expect("save");
}

/// The text of one part of an .xlsx (a zip), such as `xl/worksheets/sheet1.xml`.
/// The (address, symbol) pairs of a written `NAME.io.csv`.
pub fn io_rows(csv: &str) -> Vec<(String, String)> {
    csv.lines()
        .skip(1)
        .map(|l| {
            let mut f = l.split(',');
            (f.next().unwrap().to_string(), f.next().unwrap().to_string())
        })
        .collect()
}

/// A command's stdout with each line's runs of spaces squeezed to one: a
/// printed table's columns without their padding.
pub fn squeezed_stdout(assert: &assert_cmd::assert::Assert) -> String {
    String::from_utf8_lossy(&assert.get_output().stdout)
        .lines()
        .map(|l| l.split_whitespace().collect::<Vec<_>>().join(" "))
        .collect::<Vec<_>>()
        .join("\n")
}

/// The first line of `text` that starts with `start` (the whole text in
/// the panic when none does): a row of a printed table, by its first column.
pub fn line_with(text: &str, start: &str) -> String {
    text.lines()
        .find(|l| l.starts_with(start))
        .unwrap_or_else(|| panic!("no line starting {start:?} in:\n{text}"))
        .to_string()
}

/// How long step `step` lasted in a `simulate` report (squeezed by
/// [`squeezed_stdout`]), in seconds.
pub fn step_seconds(said: &str, step: u32) -> f64 {
    let line = line_with(said, &format!("{step} "));
    let seconds = line.split(' ').nth(3).expect("a duration");
    seconds.parse().unwrap_or_else(|_| panic!("{line}"))
}

/// `simulate` of a workbook of a table (sheet `TABLE`) and its SETTINGS
/// rows, with `args`: its stdout squeezed, its stderr, its exit code.
pub fn simulate_sheets(
    table: &[&[&str]],
    settings: &[&[&str]],
    args: &[&str],
) -> (String, String, Option<i32>) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("h.xlsx");
    write_xlsx_sheets(&path, &[("TABLE", table), ("SETTINGS", settings)]);
    let assert = steptable().arg("simulate").arg(&path).args(args).assert();
    let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
    let code = assert.get_output().status.code();
    (squeezed_stdout(&assert), stderr, code)
}

pub fn xlsx_part(path: &Path, part: &str) -> String {
    use std::io::Read;
    let file = std::fs::File::open(path).expect("open");
    let mut archive = zip::ZipArchive::new(file).expect("zip");
    let mut entry = archive.by_name(part).expect("part");
    let mut text = String::new();
    entry.read_to_string(&mut text).expect("read part");
    text
}

/// How many files one conversion with the default formats writes.
pub fn all_files() -> usize {
    steptable::emit::OutputKind::defaults()
        .iter()
        .map(|k| k.file_count())
        .sum()
}

/// The program files a conversion of `input` writes (ST, FST, I/O list,
/// AWL, PLCopen), without the lines that name the source file: what two
/// workbooks holding the same table must agree on.
pub fn program_texts(input: &Path, out: &Path, sheet: Option<&str>) -> Vec<String> {
    let mut cmd = steptable();
    cmd.arg("convert")
        .arg(input)
        .args(["--formats", "st,fst,io,awl,plcopen"]);
    if let Some(sheet) = sheet {
        cmd.args(["--sheet", sheet]);
    }
    cmd.arg("-o").arg(out).assert().success();
    let stem = input.file_stem().unwrap();
    files_below(&out.join(stem))
        .iter()
        .map(|p| {
            let text = std::fs::read_to_string(p).unwrap();
            text.lines()
                .filter(|l| {
                    !l.contains("Source:")
                        && !l.contains(&format!("from {}", stem.to_string_lossy()))
                })
                .collect::<Vec<_>>()
                .join("\n")
        })
        .collect()
}

/// `f` over `items` on two threads (the CI machine's cores), keeping what it
/// returns, in no particular order.
pub fn on_threads<T: Sync, R: Send>(items: &[T], f: impl Fn(&T) -> Option<R> + Sync) -> Vec<R> {
    let next = std::sync::atomic::AtomicUsize::new(0);
    let found = std::sync::Mutex::new(Vec::new());
    std::thread::scope(|scope| {
        for _ in 0..2 {
            scope.spawn(|| {
                loop {
                    let i = next.fetch_add(1, std::sync::atomic::Ordering::SeqCst);
                    let Some(item) = items.get(i) else { break };
                    if let Some(r) = f(item) {
                        found.lock().unwrap_or_else(|e| e.into_inner()).push(r);
                    }
                }
            });
        }
    });
    found.into_inner().unwrap_or_else(|e| e.into_inner())
}

/// One table through the library with the options a test names, so that
/// tests say what they vary and nothing else:
/// `Build::paper().modes("all").program()`.
pub struct Build {
    pub table: steptable::table::StepTable,
    pub settings: steptable::settings::Settings,
}

impl Build {
    /// The paper's example (DESIGN §4), as a bare grid.
    pub fn paper() -> Self {
        Build::rows("paper.csv", &steptable::template_workbook::PAPER_EXAMPLE)
    }

    /// A table from rows of cell text laid out from A1.
    pub fn rows<R: AsRef<[S]>, S: AsRef<str>>(file: &str, rows: &[R]) -> Self {
        let table = steptable::table::from_rows(file, rows).expect("a valid table");
        Build {
            table,
            settings: steptable::settings::Settings::new(),
        }
    }

    /// A workbook, read and checked (its SETTINGS sheet applied).
    pub fn path(path: &Path) -> Self {
        let settings = steptable::settings::Settings::new();
        let checked = steptable::convert::check_path(path, &settings).expect("a valid sample");
        Build {
            table: checked.table,
            settings: checked.settings,
        }
    }

    pub fn modes(mut self, modes: &str) -> Self {
        self.settings.program.modes = modes.parse().expect("valid modes");
        self
    }

    pub fn safety(mut self, safety: steptable::program::Safety) -> Self {
        self.settings.program.safety = safety;
        self
    }

    pub fn simulation(mut self, simulation: steptable::simulate::SimSettings) -> Self {
        self.settings.simulation = simulation;
        self
    }

    pub fn program(&self) -> steptable::program::StepProgram {
        steptable::convert::build_program(&self.table, &self.settings)
    }

    pub fn faults(&self) -> steptable::faults::FaultTable {
        let program = self.program();
        steptable::faults::analyse(&self.table, &program, &self.settings.simulation, 1)
    }
}

/// Ctrl-C to a running steptable, as a terminal sends it; its output when it
/// has ended.
#[cfg(unix)]
pub fn interrupt(child: std::process::Child) -> std::process::Output {
    std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    child.wait_with_output().unwrap()
}

/// The file `NAME{suffix}` that `synth --sequence TEXT -o out` writes:
/// `out/NAME/NAME{suffix}`, NAME the sequence's own name
/// (`steptable::commands::synth::sequence_name`: `A1 A0` → `A1A0`).
pub fn synthesised(out: &Path, sequence: &str, suffix: &str) -> PathBuf {
    let parsed = steptable::synth::sequence::parse(sequence).expect("a sequence");
    let name = steptable::commands::synth::sequence_name(&parsed);
    out.join(&name).join(format!("{name}{suffix}"))
}

/// Every file below `dir`, the manifests too, with its bytes: what a run
/// that must write nothing must leave as it was.
pub fn files_with_bytes(dir: &Path) -> Vec<(PathBuf, Vec<u8>)> {
    let mut found = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(dir) = stack.pop() {
        for entry in std::fs::read_dir(&dir).into_iter().flatten().flatten() {
            let path = entry.path();
            let meta = std::fs::symlink_metadata(&path).unwrap();
            if meta.is_dir() {
                stack.push(path);
            } else {
                let bytes = std::fs::read(&path).unwrap_or_default();
                found.push((path, bytes));
            }
        }
    }
    found.sort();
    found
}

/// Runs steptable in `work` with `args`: its exit code, and stdout then
/// stderr as one text (what a user sees).
pub fn run_in(work: &Path, args: &[String]) -> (Option<i32>, String) {
    let output = steptable().current_dir(work).args(args).output().unwrap();
    let said = format!(
        "{}{}",
        String::from_utf8_lossy(&output.stdout),
        String::from_utf8_lossy(&output.stderr)
    );
    (output.status.code(), said)
}

/// One hostile input of a table-driven test: the table (sheet `TABLE`, one
/// column per branch), the SETTINGS rows, the options, and what stderr
/// must say (`TABLE!A2: error[E015]`, or an option's message).
pub struct Refused {
    pub what: &'static str,
    pub table: &'static [&'static [&'static str]],
    pub settings: &'static [&'static [&'static str]],
    pub args: &'static [&'static str],
    pub code_at: &'static str,
}

/// A table (sheet `TABLE`) and its SETTINGS rows written to a workbook and
/// converted with `args` (and `--formats st`): the run, asserted to exit
/// with `exit`, and the output folder it was given (inside the returned
/// temporary folder).
pub fn convert_sheets(
    table: &[&[&str]],
    settings: &[&[&str]],
    args: &[&str],
    exit: i32,
) -> (tempfile::TempDir, PathBuf, assert_cmd::assert::Assert) {
    let mut sheets: Vec<(&str, &[&[&str]])> = vec![("TABLE", table)];
    if !settings.is_empty() {
        sheets.push(("SETTINGS", settings));
    }
    // `--formats` of the case's own (a case about FST's names) stands.
    let own = args.contains(&"--formats");
    let formats: &[&str] = if own { &[] } else { &["--formats", "st"] };
    let args: Vec<&str> = args.iter().chain(formats).copied().collect();
    convert_workbook(&sheets, &args, exit)
}

/// A workbook of `sheets` written as `h.xlsx` and converted with `args`,
/// as [`convert_sheets`] converts one.
pub fn convert_workbook(
    sheets: &[(&str, &[&[&str]])],
    args: &[&str],
    exit: i32,
) -> (tempfile::TempDir, PathBuf, assert_cmd::assert::Assert) {
    convert_written("h.xlsx", |path| write_xlsx_sheets(path, sheets), args, exit)
}

/// A table written as `t.csv` (messages name its cells `t.csv:3:2`) and
/// converted with `args`, as [`convert_sheets`] converts a workbook.
pub fn convert_csv(
    table: &str,
    args: &[&str],
    exit: i32,
) -> (tempfile::TempDir, PathBuf, assert_cmd::assert::Assert) {
    let write = |path: &Path| std::fs::write(path, table).unwrap();
    convert_written("t.csv", write, args, exit)
}

/// The one runner of both: `file` written by `write` into a new temporary
/// folder, then `convert FILE ARGS -o out`.
fn convert_written(
    file: &str,
    write: impl FnOnce(&Path),
    args: &[&str],
    exit: i32,
) -> (tempfile::TempDir, PathBuf, assert_cmd::assert::Assert) {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join(file);
    write(&path);
    let out = dir.path().join("out");
    let assert = steptable()
        .arg("convert")
        .arg(&path)
        .args(args)
        .arg("-o")
        .arg(&out)
        .assert()
        .code(exit);
    (dir, out, assert)
}

/// Each row through `convert`: exit 1, its code at its cell, nothing
/// written.
pub fn assert_refused(cases: &[Refused]) {
    for case in cases {
        let (_dir, out, assert) = convert_sheets(case.table, case.settings, case.args, 1);
        let stderr = String::from_utf8_lossy(&assert.get_output().stderr).into_owned();
        assert!(
            stderr.contains(case.code_at),
            "{}: expected {}, got {stderr}",
            case.what,
            case.code_at
        );
        assert!(!out.exists(), "{}: refused but wrote files", case.what);
    }
}

/// 300 characters, the same every run.
pub fn long_text(what: &str) -> String {
    let mut text = format!("{what} ");
    while text.chars().count() < 300 {
        text.push_str("and then some more words ");
    }
    // Ends in a letter, not a space a cell would lose.
    text.chars().take(299).chain(['.']).collect()
}

/// A two-step table whose step 1 comment and C1's name are 300 characters.
pub fn long_table(dir: &Path) -> PathBuf {
    let path = dir.join("long.xlsx");
    let step = format!("STEP 1 ({})", long_text("clamp the part"));
    let name = format!("C1 ({})", long_text("clamp"));
    let table: &[&[&str]] = &[&["", "BRANCH 1"], &[&step, "C1+1"], &["STEP 2", "C1-0"]];
    let settings: &[&[&str]] = &[&["actuator"], &[&name]];
    write_xlsx_sheets(
        &path,
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", table),
            ("SETTINGS", settings),
        ],
    );
    path
}

/// The manual-mode scenario both the simulation test and its engine
/// replay run (`tests/fixtures/manual_scenario.txt`): `(option, text)`.
pub fn manual_events() -> Vec<(String, String)> {
    let path = root().join("tests/fixtures/manual_scenario.txt");
    let text = std::fs::read_to_string(path).expect("the manual scenario");
    text.lines()
        .filter(|l| !l.trim().is_empty() && !l.starts_with('#'))
        .map(|l| {
            let (option, event) = l.split_once(' ').expect("OPTION TEXT");
            (option.to_string(), event.to_string())
        })
        .collect()
}

/// A labelled table moving C1 out, C2 out, C1 home, C2 home: the one the
/// hostile rows of an actuator kind (C2 a gripper, a swivel drive) refuse
/// their settings on.
pub const TWO_ACTUATORS: &[&[&str]] = &[
    &["", "BRANCH 1"],
    &["STEP 1", "C1+1"],
    &["STEP 2", "C2+1"],
    &["STEP 3", "C1-0"],
    &["STEP 4", "C2-0"],
];
