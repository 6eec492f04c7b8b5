//! Input that could be read two ways, or that would be passed over without a
//! word, is refused or said: a format given twice or beside `all`, a folder
//! among the user's templates, `-j 0`, a pattern matching nothing, the
//! SETTINGS sheet named as the table, two SETTINGS or ADDRESSES sheets; and
//! the folders of inputs that share a name are the same whichever command
//! converts them, and said. Table-driven through the binary: exit code,
//! message, and nothing written.

use std::path::Path;

use crate::helpers::{files_below, sample, steptable, write_xlsx_sheets};

const TABLE: &[&[&str]] = &[
    &["", "BRANCH 1", "BRANCH 2"],
    &["STEP 1", "C1+1", ""],
    &["STEP 2", "", "C2+1"],
    &["STEP 3", "C1-0", "C2-0"],
];

struct Case {
    what: &'static str,
    /// Makes the files under the temporary folder the run reads.
    setup: fn(&Path),
    /// The command line; `DIR` is the temporary folder.
    args: &'static [&'static str],
    exit: i32,
    /// Expected on stderr (human) or on stdout (`--message-format json`).
    said: &'static str,
}

fn paper(dir: &Path) {
    std::fs::copy(sample("paper_example.xlsx"), dir.join("t.xlsx")).unwrap();
}

/// The paper's table, and templates whose folder holds `folder/program.st.j2`.
fn templates_in(dir: &Path, folder: &str) {
    paper(dir);
    let inner = dir.join("tpl").join(folder);
    std::fs::create_dir_all(&inner).unwrap();
    std::fs::write(inner.join("program.st.j2"), "(* mine *)").unwrap();
}

fn two_sheets(dir: &Path, side: &str, second: &str, rows: &[&[&str]]) {
    write_xlsx_sheets(
        &dir.join("t.xlsx"),
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", TABLE),
            (side, rows),
            (second, rows),
        ],
    );
}

#[test]
fn what_could_be_read_two_ways_is_refused_and_nothing_written() {
    let cases = [
        Case {
            what: "a format given twice",
            setup: paper,
            args: &["convert", "DIR/t.xlsx", "--formats", "st,st"],
            exit: 1,
            said: "invalid value 'st,st' for '--formats <LIST>': \"st\" is given twice in \"st,st\"; give each once",
        },
        Case {
            what: "a format given twice in two cases",
            setup: paper,
            args: &["convert", "DIR/t.xlsx", "--formats", "st,ST"],
            exit: 1,
            said: "\"st\" is given twice in \"st,ST\"",
        },
        Case {
            what: "all beside a format",
            setup: paper,
            args: &["batch", "DIR", "--formats", "all,st"],
            exit: 1,
            said: "\"all\" stands alone; \"all,st\" also names others (write all, or the names)",
        },
        Case {
            what: "an empty format",
            setup: paper,
            args: &["convert", "DIR/t.xlsx", "--formats", "st,,awl"],
            exit: 1,
            said: "\"st,,awl\" has an empty item",
        },
        Case {
            what: "a folder named like a template",
            setup: |dir| {
                paper(dir);
                std::fs::create_dir_all(dir.join("tpl/program.st.j2")).unwrap();
            },
            args: &["convert", "DIR/t.xlsx", "--templates", "DIR/tpl"],
            exit: 1,
            said: "tpl/program.st.j2: a folder; templates are read only from",
        },
        Case {
            what: "templates in a folder of the templates",
            setup: |dir| templates_in(dir, "old"),
            args: &["batch", "DIR/t.xlsx", "--templates", "DIR/tpl"],
            exit: 1,
            said: "tpl/old: a folder; templates are read only from",
        },
        Case {
            what: "no job at all",
            setup: paper,
            args: &["batch", "DIR", "-j", "0"],
            exit: 1,
            said: "-j takes 1 to 64 jobs; 0 runs nothing (leave -j out for one job per core)",
        },
        Case {
            what: "a pattern that matches nothing",
            setup: paper,
            args: &["batch", "DIR/*.nomatch"],
            exit: 1,
            said: "*.nomatch: error[E001]: no such file or folder, and no file matches it as a pattern",
        },
        Case {
            what: "a pattern that matches nothing, in JSON",
            setup: paper,
            args: &["batch", "DIR/*.nomatch", "--message-format", "json"],
            exit: 1,
            said: "\"code\":\"E001\"",
        },
        Case {
            what: "the SETTINGS sheet as the table",
            setup: |dir| {
                write_xlsx_sheets(
                    &dir.join("t.xlsx"),
                    &[("TABLE", TABLE), ("SETTINGS", &[&["target", "iec"]])],
                )
            },
            args: &["convert", "DIR/t.xlsx", "--sheet", "settings"],
            exit: 1,
            said: "t.xlsx: error[E004]: \"SETTINGS\" is the SETTINGS sheet, read for the table's settings, not a step table; name the sheet that holds the table with --sheet (the other sheets: TABLE)",
        },
        Case {
            what: "the ADDRESSES sheet as the table",
            setup: |dir| {
                write_xlsx_sheets(
                    &dir.join("t.xlsx"),
                    &[("TABLE", TABLE), ("ADDRESSES", &[&["START", "I0.0"]])],
                )
            },
            args: &["check", "DIR/t.xlsx", "--sheet", "ADDRESSES"],
            exit: 1,
            said: "error[E004]: \"ADDRESSES\" is the ADDRESSES sheet, read for the table's pinned addresses",
        },
        Case {
            what: "two SETTINGS sheets",
            setup: |dir| {
                write_xlsx_sheets(
                    &dir.join("t.xlsx"),
                    &[
                        ("SEQUENTIAL CONTROL DESCRIPTION", TABLE),
                        ("SETTINGS", &[&["target", "iec"]]),
                        ("Settings ", &[&["modes", "stop"]]),
                    ],
                )
            },
            args: &["convert", "DIR/t.xlsx"],
            exit: 1,
            said: "t.xlsx: error[E030]: 2 sheets are each the SETTINGS sheet (\"SETTINGS\", \"Settings \": names are compared without case and the spaces around them); keep one, or merge their rows into one",
        },
        Case {
            what: "two ADDRESSES sheets",
            setup: |dir| two_sheets(dir, "ADDRESSES", "ADDRESSES ", &[&["START", "I0.0"]]),
            args: &["batch", "DIR/t.xlsx"],
            exit: 1,
            said: "t.xlsx: error[E035]: 2 sheets are each the ADDRESSES sheet (\"ADDRESSES\", \"ADDRESSES \"",
        },
    ];
    for case in &cases {
        let dir = tempfile::tempdir().unwrap();
        (case.setup)(dir.path());
        let out = dir.path().join("out");
        let place = dir.path().to_string_lossy().to_string();
        let args: Vec<String> = case.args.iter().map(|a| a.replace("DIR", &place)).collect();
        let mut command = steptable();
        command.args(&args);
        if ["convert", "batch"].contains(&case.args[0]) {
            command.arg("-o").arg(&out);
        }
        let output = command.output().unwrap();
        let said = if case.args.contains(&"json") {
            String::from_utf8_lossy(&output.stdout).to_string()
        } else {
            String::from_utf8_lossy(&output.stderr).to_string()
        };
        assert_eq!(
            output.status.code(),
            Some(case.exit),
            "{}: {said}",
            case.what
        );
        assert!(said.contains(case.said), "{}: {said}", case.what);
        // Nothing of the input's is written (batch's summary aside).
        let written: Vec<_> = files_below(&out)
            .into_iter()
            .filter(|p| !p.ends_with("summary.csv"))
            .collect();
        assert!(written.is_empty(), "{}: {written:?}", case.what);
    }
}

/// A workbook with one SETTINGS sheet still reads it, hidden folders among
/// the templates (a git checkout of them) are not templates, and `-j 1`
/// runs: the refusals above are of the doubtful cases only.
#[test]
fn the_plain_cases_beside_them_still_run() {
    let dir = tempfile::tempdir().unwrap();
    write_xlsx_sheets(
        &dir.path().join("t.xlsx"),
        &[
            ("SEQUENTIAL CONTROL DESCRIPTION", TABLE),
            ("Settings ", &[&["target", "iec"]]),
        ],
    );
    std::fs::create_dir_all(dir.path().join("tpl/.git")).unwrap();
    let out = dir.path().join("out");
    steptable()
        .arg("batch")
        .arg(dir.path().join("t.xlsx"))
        .args(["-j", "1", "--formats", "ST,io", "--templates"])
        .arg(dir.path().join("tpl"))
        .arg("-o")
        .arg(&out)
        .assert()
        .code(0);
    let io = std::fs::read_to_string(out.join("t/t.io.csv")).unwrap();
    assert!(io.contains("%IX0.0"), "the SETTINGS row is read: {io}");
}

/// Inputs sharing a name: the folder each goes to is the same for batch and
/// convert, in any order, never another input's own name, and said — in
/// batch's output and in summary.csv's `folder` column.
#[test]
fn inputs_sharing_a_name_get_the_same_folders_from_batch_and_convert() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("c");
    std::fs::create_dir(&input).unwrap();
    for name in ["line.xlsx", "line-csv.xlsx", "line-xlsx.xlsx"] {
        std::fs::copy(sample("paper_example.xlsx"), input.join(name)).unwrap();
    }
    std::fs::copy(sample("paper_example.csv"), input.join("line.csv")).unwrap();
    let expected = [
        ("line-csv.xlsx", "line-csv"),
        ("line-xlsx.xlsx", "line-xlsx"),
        ("line.csv", "line"),
        ("line.xlsx", "line-2"),
    ];

    let out = dir.path().join("o9");
    let output = steptable()
        .arg("batch")
        .arg(&input)
        .args(["--formats", "io", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(0));
    let stdout = String::from_utf8_lossy(&output.stdout);
    let note = format!(
        "note: {} -> {}/ (another input has the name line)",
        input.join("line.xlsx").display(),
        out.join("line-2").display()
    );
    assert!(stdout.contains(&note), "{stdout}");
    assert_eq!(stdout.matches("note: ").count(), 1, "{stdout}");
    let summary = std::fs::read_to_string(out.join("summary.csv")).unwrap();
    let mut rows = csv::Reader::from_reader(summary.as_bytes());
    assert_eq!(rows.headers().unwrap().get(7), Some("folder"));
    for row in rows.records() {
        let row = row.unwrap();
        let file = Path::new(&row[0]).file_name().unwrap().to_string_lossy();
        let (_, folder) = expected.iter().find(|(f, _)| *f == file).unwrap();
        assert_eq!(&row[7], *folder, "{file}");
        assert!(out.join(folder).join(format!("{folder}.io.csv")).is_file());
    }

    // convert, with the inputs in two other orders: the same folders.
    for order in [[3, 0, 1, 2], [2, 3, 0, 1]] {
        let out = dir.path().join(format!("convert{}", order[0]));
        let output = steptable()
            .arg("convert")
            .args(order.map(|i| input.join(expected[i].0)))
            .args(["--formats", "io", "-o"])
            .arg(&out)
            .output()
            .unwrap();
        assert_eq!(output.status.code(), Some(0));
        let stdout = String::from_utf8_lossy(&output.stdout);
        for (file, folder) in expected {
            let line = stdout
                .lines()
                .find(|l| l.starts_with(&input.join(file).display().to_string()))
                .unwrap_or_else(|| panic!("{file}: {stdout}"));
            assert!(
                line.contains(&format!("-> {}/", out.join(folder).display())),
                "{line}"
            );
        }
    }
}
