use super::*;
use crate::diag::Diagnostics;
use crate::read::Grid;

/// A grid from rows of text, top-left at A1; "" is an empty cell.
pub(crate) fn grid(rows: &[&[&str]]) -> Grid {
    Grid::from_text_rows("t.xlsx", Some("S"), rows)
}

fn errors(rows: &[&[&str]]) -> Vec<String> {
    let mut diags = Diagnostics::new();
    assert!(build(&grid(rows), &mut diags).is_none());
    diags
        .into_sorted()
        .into_iter()
        .map(|d| d.to_string())
        .collect()
}

#[test]
fn finds_the_table_by_its_headers_anywhere() {
    let rows: &[&[&str]] = &[
        &["", "My machine", "", ""],
        &["", "", "BRANCH 1", "BRANCH 2"],
        &["", "STEP 1", "C1+1", ""],
        &["", "STEP 2", "C2+", "C1-0"],
        &["", "STEP 3", "", "C2-"],
        &["", "STEP 4", "", ""],
        &["", "note: C-sensors are reed switches", "", ""],
    ];
    let mut diags = Diagnostics::new();
    let table = build(&grid(rows), &mut diags).expect("valid");
    assert_eq!(table.branches, 2);
    assert_eq!(table.steps.len(), 3);
    assert_eq!(table.steps[1].moves[0].notation(), "C2+1");
    assert_eq!(table.steps[1].moves[1].branch, 1);
    assert_eq!(table.actuators.len(), 2);
}

#[test]
fn a_misnumbered_step_label_is_a_warning() {
    let mut diags = Diagnostics::new();
    let rows: &[&[&str]] = &[&["", "BRANCH 1"], &["STEP 1", "C1+1"], &["STEP 3", "C1-0"]];
    assert!(build(&grid(rows), &mut diags).is_some());
    let all = diags.into_sorted();
    assert_eq!(all.len(), 1);
    assert!(
        all[0]
            .to_string()
            .contains("S!A3: warning[W002]: this row is labelled STEP 3 but is step 2")
    );
}

#[test]
fn reads_a_bare_grid() {
    let rows: &[&[&str]] = &[&["Title"], &["C1+1", ""], &["C2+1", "C1-"], &["C2-0", ""]];
    let mut diags = Diagnostics::new();
    let table = build(&grid(rows), &mut diags).expect("valid");
    assert_eq!(table.steps.len(), 3);
    assert_eq!(table.branches, 2);
}

#[test]
fn reports_every_error_with_its_cell() {
    let errs = errors(&[
        &["", "BRANCH 1", "BRANCH 2"],
        // C3, not C2: a refused move of C2 would leave C2's position
        // unknown, and its E022 below unsaid (no cascade).
        &["STEP 1", "C1+1", "C3+x"],
        &["STEP 2", "C1+1", ""],
        &["STEP 3", "C2+1", "C2-0"],
        &["STEP 4", "", ""],
        &["STEP 5", "C1-0", ""],
    ]);
    let joined = errs.join("\n");
    assert!(
        joined.contains("S!C2: error[E010]: \"C3+x\" is not a move"),
        "{joined}"
    );
    assert!(joined.contains("S!B3: error[E020]"), "{joined}");
    assert!(joined.contains("S!C4: error[E021]"), "{joined}");
    assert!(
        joined.contains("S!B5: error[E023]: STEP 4 has no move"),
        "{joined}"
    );
    assert!(
        joined.contains("error[E022]: C2 ends the cycle at position 1"),
        "{joined}"
    );
}

#[test]
fn moves_beside_the_table_are_not_ignored() {
    let errs = errors(&[
        &["", "BRANCH 1", ""],
        &["STEP 1", "C1+1", "C2+1"],
        &["STEP 2", "C1-0", "C2-0"],
    ]);
    assert!(
        errs[0].contains("S!C2") && errs[0].contains("outside the table"),
        "{errs:?}"
    );
}

#[test]
fn plain_signs_resolve_to_the_ends() {
    let mut diags = Diagnostics::new();
    let table = build(&grid(&[&["C1+"], &["C1-"]]), &mut diags).expect("valid");
    assert_eq!(table.actuators[0].max_position, 1);
    assert_eq!(table.steps[0].moves[0].to, 1);
    // C1+ goes to pmax = 3, the highest position written for C1.
    let table = build(
        &grid(&[&["C1+"], &["C1-1"], &["C1+3"], &["C1-"]]),
        &mut diags,
    )
    .expect("valid");
    assert_eq!(table.actuators[0].max_position, 3);
    let tos: Vec<u32> = table.steps.iter().map(|s| s.moves[0].to).collect();
    assert_eq!(tos, [3, 1, 3, 0]);
}

#[test]
fn empty_and_headerless_sheets_are_errors() {
    assert!(errors(&[&["just a note"]])[0].contains("E003"));
    assert!(errors(&[&["", "BRANCH 1"], &["STEP 1", ""]])[0].contains("no moves"));
}
