//! Every input a fuzz target found a problem with (tests/fuzz-regressions/)
//! is checked and converted: a clean error or a clean conversion, never a
//! crash, a printed panic or a half-written output.

use crate::helpers::{files_below, root, steptable};

#[test]
fn fuzz_findings_end_in_a_clean_error() {
    let dir = root().join("tests/fuzz-regressions");
    let inputs: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|e| e != "md"))
        .collect();
    assert!(!inputs.is_empty());
    for input in inputs {
        let out = tempfile::tempdir().unwrap();
        for command in ["check", "convert"] {
            let mut run = steptable();
            run.arg(command).arg(&input);
            if command == "convert" {
                run.arg("-o").arg(out.path());
            }
            let output = run.output().unwrap();
            let stderr = String::from_utf8_lossy(&output.stderr);
            let code = output.status.code();
            assert!(
                matches!(code, Some(0) | Some(1)),
                "{} {command}: exit {code:?}\n{stderr}",
                input.display()
            );
            assert!(
                !stderr.contains("panicked") && !stderr.contains("backtrace"),
                "{} {command}: {stderr}",
                input.display()
            );
            if code == Some(1) {
                assert!(stderr.contains("error["), "{stderr}");
                assert!(files_below(out.path()).is_empty());
            }
        }
    }
}

#[test]
fn the_ole_sector_table_finding_is_a_damaged_workbook() {
    steptable()
        .arg("check")
        .arg(root().join("tests/fuzz-regressions/workbook-ole-sector-size.xls"))
        .assert()
        .code(1)
        .stderr(predicates::str::contains(
            "error[E002]: the workbook is damaged and could not be decoded",
        ));
}

#[test]
fn a_looping_sector_chain_is_refused_at_once() {
    steptable()
        .arg("check")
        .arg(root().join("tests/fuzz-regressions/workbook-ole-fat-loop.xls"))
        .timeout(std::time::Duration::from_secs(20))
        .assert()
        .code(1)
        .stderr(predicates::str::contains(
            "the workbook is damaged and could not be decoded (the sector chain through sector",
        ));
}

#[test]
fn an_xls_whose_dimensions_wrap_is_refused_not_aborted() {
    steptable()
        .arg("check")
        .arg(root().join("tests/fuzz-regressions/workbook-xls-dimensions.xls"))
        .assert()
        .code(1)
        .stderr(predicates::str::contains(
            "the workbook is damaged and could not be decoded (a sheet's dimensions end before they start)",
        ));
}

#[test]
fn an_xls_with_cells_far_apart_is_refused_before_it_is_laid_out() {
    steptable()
        .arg("check")
        .arg(root().join("tests/fuzz-regressions/workbook-xls-cell-spread.xls"))
        .timeout(std::time::Duration::from_secs(20))
        .assert()
        .code(1)
        .stderr(predicates::str::contains(
            "error[E024]: a sheet's cells spread over a rectangle of 142857507 cells; at most 3000000 are read",
        ));
}

#[test]
fn a_cylinder_with_35_positions_converts_with_every_check() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(root().join("tests/fuzz-regressions/pipeline-many-positions.csv"))
        .args(["--safety", "all", "--modes", "all", "-o"])
        .arg(dir.path())
        .assert()
        .success();
}
