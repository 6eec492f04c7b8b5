//! The Ladder body (`--formats ld`, `NAME.ld.xml`) and the editor-load
//! condition of both graphical bodies (SFC and LD): the snapshot of the
//! paper's ladder, integer geometry and wires ending on their connection
//! points for every sample and option set (the checker in
//! `plcopen_geometry.rs`, seen rejecting a moved point and a decimal size),
//! and the hostile inputs of the new output, each through the binary with
//! its exit code, code and cell. The run in Beremiz's generator and matiec
//! is `tests/tools/ladder.rs`.

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{files_below, root, samples, steptable};
use crate::plcopen_geometry::check_file;

/// The option sets the Ladder body is written for (`--safety all` has the
/// watchdog, `--modes all` the oven's run-on: TON blocks).
pub const LADDER_OPTIONS: [&[&str]; 3] = [
    &[],
    &["--modes", "all"],
    &["--modes", "all", "--safety", "all"],
];

/// Converts `input` with `args` into a fresh folder: the written files by
/// name ending, or the stderr of a refusal.
fn convert(input: &std::path::Path, args: &[&str]) -> Result<Vec<(String, String)>, String> {
    let dir = tempfile::tempdir().unwrap();
    let out = steptable()
        .arg("convert")
        .arg(input)
        .args(args)
        .arg("-o")
        .arg(dir.path())
        .output()
        .unwrap();
    if !out.status.success() {
        return Err(String::from_utf8_lossy(&out.stderr).into_owned());
    }
    Ok(files_below(dir.path())
        .into_iter()
        .map(|p| {
            let name = p.file_name().unwrap().to_string_lossy().into_owned();
            (name, std::fs::read_to_string(&p).unwrap_or_default())
        })
        .collect())
}

#[test]
fn the_paper_ladder_is_snapshotted() {
    let files = convert(
        &root().join("samples/paper_example.csv"),
        &["--formats", "ld"],
    )
    .expect("the paper's table has no timer");
    let [(name, text)] = &files[..] else {
        panic!("one file: {files:?}");
    };
    assert_eq!(name, "paper_example.ld.xml");
    insta::assert_snapshot!("paper_example_csv.ld.xml", text);
}

/// Every sample, every option set: both bodies load in the editors as
/// drawn, the timers' blocks too.
#[test]
fn every_sfc_and_ladder_body_has_integer_geometry_and_wires_on_their_points() {
    let mut bodies = 0;
    let mut timed = 0;
    for sample in samples() {
        for options in LADDER_OPTIONS {
            let mut args = options.to_vec();
            args.extend(["--formats", "sfc,ld,st"]);
            let files = convert(&sample, &args)
                .unwrap_or_else(|e| panic!("{} {options:?}: {e}", sample.display()));
            for (name, text) in files.iter().filter(|(n, _)| n.ends_with(".xml")) {
                let wires = check_file(text).unwrap_or_else(|e| panic!("{name} {options:?}: {e}"));
                assert!(wires > 10, "{name}: {wires} wires");
                bodies += 1;
                timed +=
                    usize::from(name.ends_with(".ld.xml") && text.contains("typeName=\"TON\""));
            }
        }
    }
    assert!(
        bodies > 50 && timed > 10,
        "{bodies} bodies, {timed} ladders with timers"
    );
}

/// Each timer E043 refused before is drawn: a dwell, the watchdog (asked
/// for and by a supervision time), a run-on after STOP. The ladder has the
/// TON, its instance among the POU's own variables, the restart's MOVE and
/// two calls, and the geometry the editors need.
#[test]
fn every_kind_of_timer_is_drawn_as_a_ton_block() {
    let cases: [(&str, &str, &[&str]); 4] = [
        (
            "a dwell",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,T=2s\nSTEP 3,C1-0\n",
            &[],
        ),
        (
            "the watchdog",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n",
            &["--safety", "watchdog"],
        ),
        (
            "a supervision time",
            ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n",
            &["--safety", "watchdog", "--supervision", "2=3s"],
        ),
        ("the oven's run-on", "", &["--modes", "all"]),
    ];
    for (what, table, args) in cases {
        let dir = tempfile::tempdir().unwrap();
        let input = if table.is_empty() {
            root().join("samples/oven.xlsx")
        } else {
            let path = dir.path().join("t.csv");
            std::fs::write(&path, table).unwrap();
            path
        };
        let mut all = args.to_vec();
        all.extend(["--formats", "ld"]);
        let files = convert(&input, &all).unwrap_or_else(|e| panic!("{what}: {e}"));
        let [(_, text)] = &files[..] else {
            panic!("{what}: one file: {files:?}");
        };
        check_file(text).unwrap_or_else(|e| panic!("{what}: {e}"));
        let local = text
            .split("<localVars>")
            .nth(1)
            .and_then(|l| l.split("</localVars>").next());
        let local = local.unwrap_or_else(|| panic!("{what}: no TON among the POU's own variables"));
        assert!(local.contains("<derived name=\"TON\"/>"), "{what}: {local}");
        for needle in [
            "typeName=\"MOVE\"",
            "formalParameter=\"ENO\"",
            "<expression>FALSE</expression>",
            "<expression>TRUE</expression>",
        ] {
            assert!(text.contains(needle), "{what}: no {needle}");
        }
        let calls = text.matches("typeName=\"TON\"").count();
        assert!(
            calls >= 3,
            "{what}: {calls} TON blocks (the timer's rung and two per restart)"
        );
    }
}

/// The checker itself: a wire moved off its source's output by one unit,
/// and a decimal width, are what the editors mis-draw; both are caught.
#[test]
fn the_geometry_check_catches_a_moved_point_and_a_decimal_size() {
    let files = convert(
        &root().join("samples/paper_example.csv"),
        &["--formats", "ld,sfc"],
    )
    .unwrap();
    for (name, text) in &files {
        check_file(text).unwrap();
        let anchor = "<position x=\"";
        let at = text.find("<connection ").unwrap();
        let first_point = at + text[at..].find(anchor).unwrap() + anchor.len();
        let moved = format!("{}1{}", &text[..first_point], &text[first_point..]);
        let err = check_file(&moved).expect_err(name);
        assert!(err.contains("starts at"), "{name}: {err}");
        let decimal = text.replacen("width=\"21\"", "width=\"21.5\"", 1).replacen(
            "width=\"70\"",
            "width=\"70.5\"",
            1,
        );
        let err = check_file(&decimal).expect_err(name);
        assert!(err.contains("not an integer"), "{name}: {err}");
    }
}

/// `--formats all` writes every kind, the ladder too: a table with a dwell
/// converts with `all`, its ladder timing the dwell.
#[test]
fn all_formats_include_the_ladder() {
    let files = convert(
        &root().join("samples/sorting_station.xlsx"),
        &["--formats", "all"],
    )
    .unwrap();
    assert!(files.iter().any(|(n, _)| n.ends_with(".sfc.xml")));
    let (_, ld) = files
        .iter()
        .find(|(n, _)| n.ends_with(".ld.xml"))
        .expect("all writes the ladder");
    assert!(ld.contains("typeName=\"TON\""));
}

struct Hostile {
    what: &'static str,
    table: &'static str,
    args: &'static [&'static str],
    /// In stderr, with the code and the cell where there is one.
    says: &'static [&'static str],
}

const HOSTILE: &[Hostile] = &[
    Hostile {
        what: "ld given twice",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n",
        args: &["--formats", "ld,LD"],
        says: &["'--formats <LIST>'", "\"ld\" is given twice"],
    },
    Hostile {
        what: "all beside ld",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n",
        args: &["--formats", "all,ld"],
        says: &["'--formats <LIST>'"],
    },
    Hostile {
        what: "the output misspelt",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n",
        args: &["--formats", "ladder"],
        says: &["\"ladder\" is not an output format", " ld,"],
    },
    Hostile {
        what: "a machine input named as a timer's preset, which the ladder's MOVE writes",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,T=2s\nSTEP 3,I:dwell1_pt\nSTEP 4,C1-0\n",
        args: &["--formats", "ld"],
        says: &["t.csv:4:2: error[E015]", "\"dwell1_pt\" cannot name"],
    },
    Hostile {
        what: "a machine input named as a timer's run flag, the ladder's coil",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,T=2s\nSTEP 3,I:dwell1_run\nSTEP 4,C1-0\n",
        args: &["--formats", "ld"],
        says: &["t.csv:4:2: error[E015]", "\"dwell1_run\" cannot name"],
    },
    Hostile {
        what: "a machine input named as the TON instance",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,T=2s\nSTEP 3,I:dwell1\nSTEP 4,C1-0\n",
        args: &["--formats", "ld"],
        says: &["t.csv:4:2: error[E015]", "\"dwell1\" cannot name"],
    },
    Hostile {
        what: "a machine input named as the block type TON",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,T=2s\nSTEP 3,I:TON\nSTEP 4,C1-0\n",
        args: &["--formats", "ld"],
        says: &[
            "t.csv:4:2: error[E015]",
            "\"ton\" cannot name",
            "standard function, function block",
        ],
    },
    Hostile {
        what: "a machine input named as the block type MOVE",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,T=2s\nSTEP 3,I:MOVE\nSTEP 4,C1-0\n",
        args: &["--formats", "ld"],
        says: &[
            "t.csv:4:2: error[E015]",
            "\"move\" cannot name",
            "standard function",
        ],
    },
    Hostile {
        what: "a machine input named as the ladder's fired bit",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,I:fired\nSTEP 3,C1-0\n",
        args: &["--formats", "ld"],
        says: &["t.csv:3:2: error[E015]", "\"fired\" cannot name"],
    },
    Hostile {
        what: "a machine input named as a step flag of the ladder",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,I:step_2\nSTEP 3,C1-0\n",
        args: &["--formats", "ld"],
        says: &["t.csv:3:2: error[E015]", "\"step_2\" cannot name"],
    },
];

#[test]
fn hostile_ladder_requests_are_refused_at_their_cell_and_write_nothing() {
    for case in HOSTILE {
        let (_dir, out, mut assert) = crate::helpers::convert_csv(case.table, case.args, 1);
        for needle in case.says {
            assert = assert.stderr(contains(*needle));
        }
        assert.stderr(contains("panicked").not());
        assert!(files_below(&out).is_empty(), "{}: wrote files", case.what);
    }
}
