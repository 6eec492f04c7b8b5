//! The Beremiz project folders of the graphical bodies (`--formats
//! beremiz-sfc,beremiz-ld`: `NAME.sfc.beremiz/`, `NAME.ld.beremiz/`, issue
//! 39 item 3) and their CODESYS files (`codesys-sfc`, `codesys-ld`: the
//! POUs proven in Beremiz byte for byte, `GVL_IO`, the task's calls): each folder's `plc.xml` is the chart's or the ladder's file
//! byte for byte, its `beremiz.xml` the ST project's, the ST project is
//! unchanged beside them, and neither folder is written unless asked for
//! (or with `all`); the hostile requests, each through the binary with its
//! exit code, code and cell or path. Their run in Beremiz's generator and
//! matiec is `tests/tools/scenario.rs`.

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{files_below, root, steptable};

fn read(dir: &std::path::Path, name: &str) -> Vec<u8> {
    std::fs::read(dir.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"))
}

#[test]
fn the_body_projects_hold_the_chart_and_the_ladder_as_written() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(root().join("samples/sorting_station.xlsx"))
        .args(["--modes", "all", "--formats"])
        .arg("beremiz,beremiz-sfc,beremiz-ld,sfc,ld,plcopen")
        .arg("-o")
        .arg(dir.path())
        .assert()
        .success()
        .stdout(contains("sorting_station.sfc.beremiz/plc.xml"))
        .stdout(contains("sorting_station.ld.beremiz/beremiz.xml"));
    let out = dir.path().join("sorting_station");
    let sfc = read(&out, "sorting_station.sfc.xml");
    let ld = read(&out, "sorting_station.ld.xml");
    assert_eq!(read(&out, "sorting_station.sfc.beremiz/plc.xml"), sfc);
    assert_eq!(read(&out, "sorting_station.ld.beremiz/plc.xml"), ld);
    assert!(String::from_utf8_lossy(&sfc).contains("<SFC>"));
    assert!(String::from_utf8_lossy(&ld).contains("<LD>"));
    // The ST project stays as it was: the PLCopen file's ST body.
    assert_eq!(
        read(&out, "sorting_station.beremiz/plc.xml"),
        read(&out, "sorting_station.plcopen.xml")
    );
    let project = read(&out, "sorting_station.beremiz/beremiz.xml");
    for body in ["sfc", "ld"] {
        let name = format!("sorting_station.{body}.beremiz/beremiz.xml");
        assert_eq!(read(&out, &name), project, "{name}");
    }
}

/// The text between `from` and the next `to` in `text`.
fn between<'t>(text: &'t str, from: &str, to: &str) -> &'t str {
    let (_, rest) = text.split_once(from).unwrap_or_else(|| panic!("no {from}"));
    rest.split_once(to).unwrap_or_else(|| panic!("no {to}")).0
}

/// The CODESYS files of the bodies carry the POUs proven in Beremiz and
/// matiec byte for byte, the ST export's `GVL_IO`, and a task calling the
/// chart's timer program, the chart and its rung program in that order.
#[test]
fn the_codesys_bodies_hold_the_proven_pous() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(root().join("samples/sorting_station.xlsx"))
        .args(["--modes", "all", "--safety", "all", "--formats"])
        .arg("sfc,ld,codesys,codesys-sfc,codesys-ld")
        .arg("-o")
        .arg(dir.path())
        .assert()
        .success();
    let out = dir.path().join("sorting_station");
    let text = |name: &str| String::from_utf8(read(&out, name)).unwrap();
    let st = text("sorting_station.codesys.xml");
    let gvl_io = between(&st, "<globalVars name=\"GVL_IO\">", "<addData>");
    for (body, calls) in [
        (
            "sfc",
            &["steptable_pre", "steptable_main", "steptable_post"][..],
        ),
        ("ld", &["steptable_main"][..]),
    ] {
        let beremiz = text(&format!("sorting_station.{body}.xml"));
        let codesys = text(&format!("sorting_station.{body}.codesys.xml"));
        assert!(codesys.contains("xmlns=\"http://www.plcopen.org/xml/tc6_0200\""));
        assert_eq!(
            between(&codesys, "<pous>", "</pous>"),
            between(&beremiz, "<pous>", "</pous>"),
            "{body}: the POUs"
        );
        assert_eq!(
            between(&codesys, "<globalVars name=\"GVL_IO\">", "<addData>"),
            gvl_io,
            "{body}: GVL_IO"
        );
        let task = between(&codesys, "<task name=\"MainTask\"", "</task>");
        let called: Vec<&str> = task
            .split("<pouInstance name=\"")
            .skip(1)
            .map(|r| r.split('"').next().unwrap())
            .collect();
        assert_eq!(called, calls, "{body}: the task's calls");
        let state = between(&codesys, "<globalVars name=\"GVL_steptable\">", "<addData>");
        assert!(
            state.contains("<variable name=\"halt\">"),
            "{body}: {state}"
        );
    }
}

#[test]
fn the_body_projects_are_written_when_asked_for_or_with_all() {
    let has = |args: &[&str]| -> [bool; 4] {
        let dir = tempfile::tempdir().unwrap();
        steptable()
            .arg("convert")
            .arg(root().join("samples/paper_example.xlsx"))
            .args(args)
            .arg("-o")
            .arg(dir.path())
            .assert()
            .success();
        let place = |s: &str| dir.path().join(format!("paper_example/paper_example{s}"));
        [
            ".sfc.beremiz",
            ".ld.beremiz",
            ".sfc.codesys.xml",
            ".ld.codesys.xml",
        ]
        .map(|s| place(s).exists())
    };
    assert_eq!(has(&[]), [false; 4]);
    assert_eq!(has(&["--formats", "st,beremiz,codesys"]), [false; 4]);
    assert_eq!(has(&["--formats", "all"]), [true; 4]);
    assert_eq!(
        has(&["--formats", "beremiz-ld"]),
        [false, true, false, false]
    );
    assert_eq!(
        has(&["--formats", "codesys-sfc"]),
        [false, false, true, false]
    );
}

struct Hostile {
    what: &'static str,
    table: &'static str,
    args: &'static [&'static str],
    /// In stderr, with the code and the cell where there is one.
    says: &'static [&'static str],
}

const TWO_STEPS: &str = ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,C1-0\n";

const HOSTILE: &[Hostile] = &[
    Hostile {
        what: "beremiz-sfc given twice",
        table: TWO_STEPS,
        args: &["--formats", "beremiz-sfc,BEREMIZ-SFC"],
        says: &["'--formats <LIST>'", "\"beremiz-sfc\" is given twice"],
    },
    Hostile {
        what: "all beside beremiz-ld",
        table: TWO_STEPS,
        args: &["--formats", "all,beremiz-ld"],
        says: &["'--formats <LIST>'"],
    },
    Hostile {
        what: "the folder's kind misspelt",
        table: TWO_STEPS,
        args: &["--formats", "beremiz_ld"],
        says: &[
            "\"beremiz_ld\" is not an output format",
            "did you mean beremiz-ld (writes NAME.ld.beremiz)?",
        ],
    },
    Hostile {
        what: "the folder's name as a kind",
        table: TWO_STEPS,
        args: &["--formats", "sfc.beremiz"],
        says: &["\"sfc.beremiz\" is not an output format", "beremiz-sfc"],
    },
    Hostile {
        what: "codesys-ld given twice",
        table: TWO_STEPS,
        args: &["--formats", "codesys-ld,CODESYS-LD"],
        says: &["'--formats <LIST>'", "\"codesys-ld\" is given twice"],
    },
    Hostile {
        what: "the CODESYS body misspelt",
        table: TWO_STEPS,
        args: &["--formats", "codesys_sfc"],
        says: &[
            "\"codesys_sfc\" is not an output format",
            "did you mean codesys-sfc (writes NAME.sfc.codesys.xml)?",
        ],
    },
    Hostile {
        what: "a machine input named as CODESYS's I/O list (names are not case sensitive there)",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,I:GVL_IO\nSTEP 3,C1-0\n",
        args: &["--formats", "codesys-sfc"],
        says: &["t.csv:3:2: error[E015]", "\"gvl_io\" cannot name"],
    },
    Hostile {
        what: "a machine input named as the body's state list",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,I:gvl_steptable\nSTEP 3,C1-0\n",
        args: &["--formats", "codesys-ld"],
        says: &["t.csv:3:2: error[E015]", "\"gvl_steptable\" cannot name"],
    },
    Hostile {
        what: "a machine input named as CODESYS's task",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,I:MainTask\nSTEP 3,C1-0\n",
        args: &["--formats", "codesys-sfc"],
        says: &["t.csv:3:2: error[E015]", "\"maintask\" cannot name"],
    },
    Hostile {
        what: "a machine input named as the chart's timer program",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,T=2s\nSTEP 3,I:steptable_pre\nSTEP 4,C1-0\n",
        args: &["--formats", "beremiz-sfc"],
        says: &["t.csv:4:2: error[E015]", "\"steptable_pre\" cannot name"],
    },
    Hostile {
        what: "a machine input named as the chart's rung program's instance",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,T=2s\nSTEP 3,I:post_instance\nSTEP 4,C1-0\n",
        args: &["--formats", "beremiz-sfc"],
        says: &["t.csv:4:2: error[E015]", "\"post_instance\" cannot name"],
    },
    Hostile {
        what: "a machine input named as a step flag of the ladder project",
        table: ",BRANCH 1\nSTEP 1,C1+1\nSTEP 2,I:step_2\nSTEP 3,C1-0\n",
        args: &["--formats", "beremiz-ld"],
        says: &["t.csv:3:2: error[E015]", "\"step_2\" cannot name"],
    },
];

#[test]
fn hostile_body_project_requests_are_refused_and_write_nothing() {
    for case in HOSTILE {
        let (_dir, out, mut assert) = crate::helpers::convert_csv(case.table, case.args, 1);
        for needle in case.says {
            assert = assert.stderr(contains(*needle));
        }
        assert.stderr(contains("panicked").not());
        assert!(files_below(&out).is_empty(), "{}: wrote files", case.what);
    }
}

/// What is in the way of a body project's folder: a file of the user's
/// inside it, a file of its name, a link of its name. Each is E040 naming
/// the path, exit 1, and what was there stays as it was.
#[test]
fn a_body_project_folder_never_overwrites_what_is_in_its_way() {
    type Place = fn(&std::path::Path) -> std::path::PathBuf;
    let rows: [(&str, &str, Place, &str); 4] = [
        (
            "beremiz-sfc",
            "a file of the user's as plc.xml",
            |t| {
                let dir = t.join("t.sfc.beremiz");
                std::fs::create_dir_all(&dir).unwrap();
                std::fs::write(dir.join("plc.xml"), "mine").unwrap();
                dir.join("plc.xml")
            },
            "no steptable run recorded writing this file",
        ),
        (
            "codesys-ld",
            "a file of the user's as the CODESYS body",
            |t| {
                std::fs::write(t.join("t.ld.codesys.xml"), "mine").unwrap();
                t.join("t.ld.codesys.xml")
            },
            "no steptable run recorded writing this file",
        ),
        (
            "beremiz-ld",
            "a file where the folder goes",
            |t| {
                std::fs::write(t.join("t.ld.beremiz"), "mine").unwrap();
                t.join("t.ld.beremiz")
            },
            "is a file, and outputs go into a folder of this name",
        ),
        (
            "beremiz-ld",
            "a link where the folder goes",
            |t| {
                let elsewhere = t.parent().unwrap().join("elsewhere");
                std::fs::create_dir_all(&elsewhere).unwrap();
                std::os::unix::fs::symlink(&elsewhere, t.join("t.ld.beremiz")).unwrap();
                t.join("t.ld.beremiz")
            },
            "it is a link",
        ),
    ];
    for (kind, what, place, says) in rows {
        let dir = tempfile::tempdir().unwrap();
        let input = dir.path().join("t.csv");
        std::fs::write(&input, TWO_STEPS).unwrap();
        let folder = dir.path().join("out/t");
        std::fs::create_dir_all(&folder).unwrap();
        let path = place(&folder);
        steptable()
            .arg("convert")
            .arg(&input)
            .args(["--formats", kind, "-o"])
            .arg(dir.path().join("out"))
            .assert()
            .code(1)
            .stderr(contains(format!("{}: error[E040]", path.display())))
            .stderr(contains(says))
            .stderr(contains("panicked").not());
        assert!(
            !folder.join("t.steptable-manifest").exists()
                && !folder.join(".steptable-manifest").exists(),
            "{what}: a manifest was written"
        );
        if !path.is_symlink() && path.is_file() {
            assert_eq!(std::fs::read_to_string(&path).unwrap(), "mine", "{what}");
        }
        assert!(
            !dir.path().join("elsewhere/plc.xml").exists(),
            "{what}: written through the link"
        );
    }
}
