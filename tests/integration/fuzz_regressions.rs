//! Every input a fuzz target found a problem with (tests/fuzz-regressions/)
//! is checked and converted: a clean error or a clean conversion, never a
//! crash, a printed panic or a half-written output.

use crate::helpers::{files_below, root, steptable};

/// The stored inputs with the outcome the README's table gives each: an
/// error code, or `converts`.
fn expectations(dir: &std::path::Path) -> Vec<(String, String)> {
    std::fs::read_to_string(dir.join("README.md"))
        .unwrap()
        .lines()
        .filter_map(|line| {
            let cells: Vec<&str> = line.split('|').map(str::trim).collect();
            let file = cells.get(1)?.strip_prefix('`')?.strip_suffix('`')?;
            Some((file.to_string(), cells.get(2)?.to_string()))
        })
        .collect()
}

#[test]
fn fuzz_findings_end_as_their_table_says() {
    let dir = root().join("tests/fuzz-regressions");
    let expected = expectations(&dir);
    let mut inputs: Vec<String> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().to_string())
        .filter(|name| name != "README.md")
        .collect();
    inputs.sort();
    let mut listed: Vec<String> = expected.iter().map(|(f, _)| f.clone()).collect();
    listed.sort();
    assert_eq!(
        inputs, listed,
        "every stored input has one row in README.md"
    );
    for (file, outcome) in expected {
        let input = dir.join(&file);
        let out = tempfile::tempdir().unwrap();
        for command in ["check", "convert"] {
            let mut run = steptable();
            run.arg(command).arg(&input);
            if command == "convert" {
                run.arg("-o").arg(out.path());
            }
            let output = run.output().unwrap();
            let stderr = String::from_utf8_lossy(&output.stderr);
            assert!(
                !stderr.contains("panicked") && !stderr.contains("backtrace"),
                "{file} {command}: {stderr}"
            );
            if outcome == "converts" {
                assert_eq!(output.status.code(), Some(0), "{file} {command}: {stderr}");
                if command == "convert" {
                    assert_eq!(
                        files_below(out.path()).len(),
                        crate::helpers::all_files(),
                        "{file}"
                    );
                }
            } else {
                assert_eq!(output.status.code(), Some(1), "{file} {command}: {stderr}");
                assert!(
                    stderr.contains(&format!("error[{outcome}]")),
                    "{file} {command}: expected {outcome}: {stderr}"
                );
                assert!(files_below(out.path()).is_empty(), "{file}");
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
