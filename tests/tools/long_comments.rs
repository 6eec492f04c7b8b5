//! A 300-character step comment and actuator name (hostile: far past what
//! STEP 7 keeps of a network title) are cut where a target limits them,
//! by the one cut (`emit::shorten`), and the program still runs: awlsim
//! runs the `.awl` as the simulation does, every network TITLE holds at
//! most 64 characters and the whole comment follows as a `//` line.

use crate::engines::{self, awlsim};
use crate::helpers::{long_table, long_text};
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[Check::new(
    "long_comments::a_300_character_comment_runs_in_awlsim_with_titles_cut",
    &[Tool::Awlsim],
    a_300_character_comment_runs_in_awlsim_with_titles_cut,
)];

fn a_300_character_comment_runs_in_awlsim_with_titles_cut() {
    let python = awlsim::python(&tool(Tool::Awlsim));
    let dir = tempfile::tempdir().unwrap();
    let input = long_table(dir.path());
    let case = engines::prepare(&input, &["--formats", "awl,sdf"], &dir.path().join("out"));
    let awl = std::fs::read_to_string(case.file(".awl")).unwrap();
    let titles: Vec<&str> = awl
        .lines()
        .filter_map(|l| l.strip_prefix("TITLE = "))
        .collect();
    assert!(titles.iter().all(|t| t.chars().count() <= 64), "{titles:?}");
    assert!(titles.iter().any(|t| t.ends_with("...")), "{titles:?}");
    let whole = long_text("clamp the part");
    assert!(
        awl.lines()
            .any(|l| l.starts_with("// ") && l.contains(&whole)),
        "the whole comment is kept"
    );
    case.check_stepped(
        "awlsim",
        awlsim::run_stepped(
            &python,
            &case.file(".awl"),
            case.mnemonic,
            &case.trace,
            &case.allocation,
        ),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    eprintln!("awlsim: the .awl with 300-character comments runs, traces equal");
}
