//! Every function, function block and type of the IEC libraries matiec and
//! OpenPLC compile against is refused as a machine signal name (E015): a
//! signal named like one would not compile. And every letter synth takes
//! gives programs matiec compiles; the letters it refuses are the ones
//! that would not (R and S, IL operators).

use steptable::names::reserved_name;

use crate::engines::matiec;
use crate::helpers::steptable;
use crate::{Check, Tool, shared};

pub const CHECKS: &[Check] = &[
    Check::new(
        "names::every_iec_library_name_is_reserved",
        &[Tool::Shared],
        every_iec_library_name_is_reserved,
    ),
    Check::new(
        "names::every_letter_synth_takes_compiles_in_matiec",
        &[Tool::Shared],
        every_letter_synth_takes_compiles_in_matiec,
    ),
    Check::new(
        "names::instruction_list_operators_name_table_signals_in_st",
        &[Tool::Shared],
        instruction_list_operators_name_table_signals_in_st,
    ),
];

/// A table's programs are Structured Text, where matiec takes IL's
/// operators (`r`, `s`, `ld`, `in`, `pt`) as names: the table accepts them
/// (synth, which writes IL, refuses its letters R and S), and the `.st`
/// compiles.
fn instruction_list_operators_name_table_signals_in_st() {
    let shared = shared();
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("il.csv");
    std::fs::write(
        &input,
        ",BRANCH 1\nSTEP 1,C1+1; I:r\nSTEP 2,Y:s+; I:ld\nSTEP 3,C1-0; I:in\nSTEP 4,Y:s-; I:pt\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    let output = steptable()
        .arg("convert")
        .arg(&input)
        .args(["--formats", "st", "-o"])
        .arg(&out)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let st = out.join("il").join("il.st");
    let text = std::fs::read_to_string(&st).unwrap();
    assert!(
        text.contains("r AT %IX") && text.contains("s AT %QX"),
        "{text}"
    );
    let work = dir.path().join("c");
    std::fs::create_dir_all(&work).unwrap();
    matiec::compile(&shared, &st, &work).unwrap_or_else(|e| panic!("{e}"));
}

/// Each letter as an actuator (with K, or J beside K), and the memories a
/// sequence of W, X, Y, Z, V, U takes instead (T, Q, P: S and R skipped):
/// synth refuses (E015) or writes ST and IL that matiec compiles.
fn every_letter_synth_takes_compiles_in_matiec() {
    let shared = shared();
    let dir = tempfile::tempdir().unwrap();
    let mut sequences: Vec<String> = ('A'..='Z')
        .map(|l| {
            let other = if l == 'K' { 'J' } else { 'K' };
            format!("{l}1 {l}0 {other}1 {other}0")
        })
        .collect();
    sequences.push("W1 W0 X1 X0 Y1 Y0 Z1 Z0 V1 V0 U1 U0".to_string());
    let mut refused = Vec::new();
    for (k, text) in sequences.iter().enumerate() {
        let out = dir.path().join(format!("s{k}"));
        let output = steptable()
            .args(["synth", "--sequence", text, "--method", "exact", "-o"])
            .arg(&out)
            .output()
            .unwrap();
        let stderr = String::from_utf8_lossy(&output.stderr);
        if output.status.code() == Some(1) && stderr.contains("error[E015]") {
            refused.push(text[..1].to_string());
            continue;
        }
        assert!(output.status.success(), "{text}: {stderr}");
        for file in [".equations.st", ".equations.il"] {
            let work = dir.path().join(format!("c{k}-{file}"));
            std::fs::create_dir_all(&work).unwrap();
            let path = crate::helpers::synthesised(&out, text, file);
            matiec::compile(&shared, &path, &work).unwrap_or_else(|e| panic!("{text}: {e}"));
        }
    }
    assert_eq!(refused, ["R", "S"]);
}

fn every_iec_library_name_is_reserved() {
    let shared = shared();
    let mut names = std::collections::BTreeSet::new();
    for lib in ["tools/matiec/lib", "tools/openplc/lib"] {
        let files = std::fs::read_dir(shared.join(lib)).unwrap().flatten();
        for entry in files.filter(|e| e.path().extension().is_some_and(|x| x == "txt")) {
            let text = std::fs::read_to_string(entry.path()).unwrap_or_default();
            for line in text.lines() {
                let mut words = line.split_whitespace();
                if let (Some("FUNCTION" | "FUNCTION_BLOCK"), Some(name)) =
                    (words.next(), words.next())
                {
                    names.insert(name.trim_end_matches(':').to_ascii_lowercase());
                }
            }
        }
    }
    assert!(names.len() > 1000, "{}", names.len());
    let accepted: Vec<&String> = names
        .iter()
        .filter(|n| reserved_name(n).is_none())
        .collect();
    assert!(accepted.is_empty(), "accepted: {accepted:?}");
}
