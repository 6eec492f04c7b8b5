//! Which sheet of a workbook is which: the SETTINGS and ADDRESSES sheets
//! by name (in any case, without the spaces around it; a name one letter
//! off is an error, not a sheet skipped), and the sheet holding the step
//! table, asked for or chosen, never silently.

use super::*;
use crate::cell::{header_kind, looks_like_move};
use crate::diag::{Code, Diagnostics, Location};

/// The side sheets (SETTINGS, ADDRESSES) of one workbook.
pub(super) struct SideSheets<'a> {
    pub(super) file: &'a str,
    pub(super) names: &'a [String],
    pub(super) workbook: &'a mut Box<dyn SheetSource>,
    /// How a sheet is read into a grid (the workbook reader's).
    pub(super) read: &'a SheetReader<'a>,
}

impl SideSheets<'_> {
    /// A side sheet is found by its name in any case and without the
    /// spaces around it; one that is hidden is used all the same, and said
    /// so. Two sheets that both match (`SETTINGS` and `Settings `) are an
    /// error naming both: reading one would drop the other's rows without a
    /// word. `code` is the code of that sheet's rows.
    pub(super) fn read(
        &mut self,
        wanted: &str,
        used: &str,
        code: Code,
        diags: &mut Diagnostics,
    ) -> Option<Grid> {
        let names = self.names;
        let matching: Vec<&String> = names.iter().filter(|n| is_side(n, wanted)).collect();
        let name = (*matching.first()?).clone();
        if matching.len() > 1 {
            let quoted: Vec<String> = matching.iter().map(|n| format!("\"{n}\"")).collect();
            let whole_file = Location {
                file: self.file.to_string(),
                sheet: None,
                cell: None,
            };
            diags.error(
                code,
                whole_file,
                format!(
                    "{} sheets are each the {wanted} sheet ({}: names are compared without case and the spaces around them); keep one, or merge their rows into one",
                    matching.len(),
                    quoted.join(", ")
                ),
            );
            return None;
        }
        let grid = (self.read)(self.workbook, &name, diags)?;
        if self.workbook.hidden().contains(&name) {
            diags.warning(
                Code::W004SheetChoice,
                grid.sheet_location(),
                format!("the {wanted} sheet is hidden but {used} are used"),
            );
        }
        Some(grid)
    }
}

/// Whether the sheet `name` is the side sheet `wanted` (SETTINGS,
/// ADDRESSES): the one comparison the reader makes of a side sheet's name.
fn is_side(name: &str, wanted: &str) -> bool {
    let name = name.trim();
    if name.is_ascii() && wanted.is_ascii() {
        return name.eq_ignore_ascii_case(wanted);
    }
    // `Ablauf Ä` as macOS may store it (`A` and a combining mark), in any
    // case.
    let spelt = |t: &str| crate::cell::composed(t.trim().to_string()).to_lowercase();
    spelt(name) == spelt(wanted)
}

/// E046 for a sheet whose name is a side sheet's misspelt (`Setting`,
/// `ADRESSES`) or Excel's name for its copy (`SETTINGS (2)`): only the
/// sheet of that very name is read for settings or pins, so the program
/// would be written without the EMERGENCY STOP, checks or pins it holds.
pub(super) fn misnamed_side_sheets(file: &str, names: &[String], diags: &mut Diagnostics) {
    for name in names.iter() {
        let Some(side) = misnamed_side(name) else {
            continue;
        };
        let sheet = Location {
            file: file.to_string(),
            sheet: Some(name.clone()),
            cell: None,
        };
        diags.error(
            Code::E046MistypedSetting,
            sheet,
            format!(
                "the sheet \"{name}\" is not read: only a sheet named {side} is read for {}; {} (nothing is written, the program would lack what it holds)",
                if side == SETTINGS_SHEET { "settings" } else { "pinned addresses" },
                // Beside the sheet of that name, renaming makes two.
                match names.iter().any(|n| is_side(n, side)) {
                    true => format!("move what it holds to the sheet {side} and delete it"),
                    false => format!("rename it {side}"),
                }
            ),
        );
    }
}

/// The side sheet `name` misspells (`Setting`, `ADRESSES`) or copies
/// (`SETTINGS (2)`), when it is not that sheet itself.
fn misnamed_side(name: &str) -> Option<&'static str> {
    if side_sheet_of(name).is_some() {
        return None;
    }
    let bare = name.trim();
    // Excel names a copied sheet `SETTINGS (2)`.
    let stem = match bare.rsplit_once(" (") {
        Some((stem, n))
            if n.strip_suffix(')')
                .is_some_and(|n| n.parse::<u32>().is_ok()) =>
        {
            stem.trim()
        }
        _ => bare,
    }
    .to_ascii_uppercase();
    [SETTINGS_SHEET, ADDRESSES_SHEET]
        .into_iter()
        .find(|side| crate::cell::edit_distance(&stem, side) <= 1)
}

/// Whether `name` is a side sheet's, or one named like it.
pub(super) fn names_a_side_sheet(name: &str) -> bool {
    side_sheet_of(name).is_some() || misnamed_side(name).is_some()
}

/// The side sheet `name` is, if any: read for its settings or pins, never
/// as the table.
fn side_sheet_of(name: &str) -> Option<&'static str> {
    [SETTINGS_SHEET, ADDRESSES_SHEET]
        .into_iter()
        .find(|side| is_side(name, side))
}

pub(super) type SheetReader<'a> =
    dyn Fn(&mut Box<dyn SheetSource>, &str, &mut Diagnostics) -> Option<Grid> + 'a;

/// The sheet holding the step table: the one asked for (not the SETTINGS or
/// ADDRESSES sheet: E004); else the one named
/// SEQUENTIAL CONTROL DESCRIPTION unless it is hidden; else the visible sheet
/// that best holds a table (BRANCH/STEP headers first, then the most moves;
/// the side sheets are not candidates),
/// and a hidden one only when no visible sheet holds a table. Any choice
/// among several, or of a hidden sheet, is said (W004). The other sheets
/// read on the way go to `others_read`, so that they are not read twice.
pub(super) fn pick_table(
    workbook: &mut Box<dyn SheetSource>,
    names: &[String],
    wanted: Option<&str>,
    whole_file: &Location,
    diags: &mut Diagnostics,
    read_sheet: &SheetReader,
    others_read: &mut Option<Vec<Grid>>,
) -> Option<Grid> {
    let whole_file = whole_file.clone();
    if let Some(wanted) = wanted {
        let name = asked_sheet(names, wanted, &whole_file, diags)?;
        return read_sheet(workbook, name, diags);
    }
    let hidden = workbook.hidden();
    let is_hidden = |name: &str| hidden.iter().any(|h| h == name);
    let named: Vec<&String> = names
        .iter()
        .filter(|n| is_side(n, TABLE_SHEET) && !is_hidden(n))
        .collect();
    if named.len() > 1 {
        ambiguous(TABLE_SHEET, &named, &whole_file, diags);
        return None;
    }
    if let Some(name) = named.first() {
        return read_sheet(workbook, name, diags);
    }
    // A sheet that could not be read may be the one with the table: say why.
    let mut unread = Diagnostics::new();
    let mut candidates: Vec<(TableScore, Grid)> = Vec::new();
    // Sheets of formulas nobody computed, whose first such cell: any may
    // hold the table, and which does cannot be told.
    let mut formulas = Vec::new();
    // The sheets without a table, kept for the caller's look at them.
    let mut no_table = Vec::new();
    // The side sheets are read as such, never as the table.
    for name in names.iter().filter(|n| side_sheet_of(n).is_none()) {
        let mut local = Diagnostics::new();
        match read_sheet(workbook, name, &mut local) {
            Some(grid) => match table_score(&grid, is_hidden(name)) {
                Some(score) => candidates.push((score, grid)),
                None => {
                    formulas.extend(first_uncomputed(&grid));
                    no_table.push(grid);
                }
            },
            None => unread.extend(local),
        }
    }
    if !formulas.is_empty() {
        for (at, formula) in formulas {
            diags.error(
                Code::E016FormulaNotComputed,
                at,
                format!(
                    "the formula {formula} has no computed value, and its sheet holds no move or header steptable can read: the step table may be there, which cannot be told; open and save the workbook in Excel or LibreOffice, or choose the table's sheet with --sheet"
                ),
            );
        }
        return None;
    }
    // The best score wins; the first sheet on a tie.
    let best = candidates
        .iter()
        .enumerate()
        .max_by(|(i, (a, _)), (j, (b, _))| a.cmp(b).then(j.cmp(i)))
        .map(|(i, _)| i);
    let Some(best) = best else {
        diags.extend(unread);
        diags.error(
            Code::E003NoTable,
            whole_file,
            format!(
                "no step table found: no sheet named \"{TABLE_SHEET}\" and no sheet holding moves such as C1+1"
            ),
        );
        return None;
    };
    let (score, grid) = candidates.swap_remove(best);
    // A sheet passed over whose moves may be formulas nobody computed: it
    // may be the table, with more moves than it shows (rt15 F9).
    let passed_over: Vec<_> = candidates
        .iter()
        .filter_map(|(_, other)| {
            first_uncomputed(other).map(|(at, formula)| (at, formula, other.sheet.clone()))
        })
        .collect();
    if !passed_over.is_empty() {
        for (at, formula, sheet) in passed_over {
            diags.error(
                Code::E016FormulaNotComputed,
                at,
                format!(
                    "the formula {formula} has no computed value, and the sheet {} it is on was passed over for {} as the step table: with its formulas' values it may be the table, which cannot be told; open and save the workbook in Excel or LibreOffice, or choose the table's sheet with --sheet",
                    sheet.unwrap_or_default(),
                    grid.sheet.clone().unwrap_or_default()
                ),
            );
        }
        return None;
    }
    let table_sheet = names.iter().find(|n| is_side(n, TABLE_SHEET));
    say_choice(&grid, score, &candidates, table_sheet, diags);
    // Read already: the caller need not read them again.
    let mut others: Vec<Grid> = candidates.into_iter().map(|(_, g)| g).collect();
    others.extend(no_table);
    others.sort_by_key(|g| names.iter().position(|n| g.sheet.as_ref() == Some(n)));
    *others_read = Some(others);
    Some(grid)
}

/// Where `grid`'s first formula without a computed value is, and its text.
fn first_uncomputed(grid: &Grid) -> Option<(Location, String)> {
    grid.cells.iter().find_map(|c| match &c.value {
        CellValue::Uncomputed(f) => Some((grid.location(c.pos), f.clone())),
        _ => None,
    })
}

/// The sheet `--sheet` names (E004 when there is none, or when it is a
/// side sheet).
fn asked_sheet<'n>(
    names: &'n [String],
    wanted: &str,
    whole_file: &Location,
    diags: &mut Diagnostics,
) -> Option<&'n String> {
    let whole_file = whole_file.clone();
    // The exact name first: `Line A` is the sheet `Line A`, even beside a
    // `Line A ` or a `line a`. Else the one sheet that matches without
    // case and the spaces around it; two such sheets are a choice the
    // engineer makes, not steptable.
    let loose: Vec<&String> = names.iter().filter(|n| is_side(n, wanted.trim())).collect();
    if !names.iter().any(|n| n == wanted) && loose.len() > 1 {
        ambiguous(wanted, &loose, &whole_file, diags);
        return None;
    }
    let Some(name) = names
        .iter()
        .find(|n| *n == wanted)
        .or(loose.first().copied())
    else {
        diags.error(
            Code::E004NoSuchSheet,
            whole_file,
            format!(
                "no sheet named \"{wanted}\" (the workbook has: {})",
                names.join(", ")
            ),
        );
        return None;
    };
    // The SETTINGS or ADDRESSES sheet is read as such already: read as
    // the table too, its cells would be both settings and moves, and
    // one reading would call the other's cells unread.
    if let Some(side) = side_sheet_of(name) {
        let tables: Vec<&str> = names
            .iter()
            .filter(|n| side_sheet_of(n).is_none())
            .map(String::as_str)
            .collect();
        diags.error(
            Code::E004NoSuchSheet,
            whole_file,
            format!(
                "\"{name}\" is the {side} sheet, read for the table's {}, not a step table; name the sheet that holds the table with --sheet (the other sheets: {})",
                if side == SETTINGS_SHEET { "settings" } else { "pinned addresses" },
                if tables.is_empty() { "none".to_string() } else { tables.join(", ") }
            ),
        );
        return None;
    }
    Some(name)
}

/// E047: several sheets are each the sheet `wanted` when names are
/// compared without case and the spaces around them, none exactly.
fn ambiguous(wanted: &str, matching: &[&String], whole_file: &Location, diags: &mut Diagnostics) {
    let quoted: Vec<String> = matching.iter().map(|n| format!("\"{n}\"")).collect();
    diags.error(
        Code::E047SheetAmbiguous,
        whole_file.clone(),
        format!(
            "{} sheets are each the sheet \"{wanted}\" ({}: names are compared without case and the spaces around them); name the one that holds the table exactly with --sheet, or rename the other",
            matching.len(),
            quoted.join(", ")
        ),
    );
}

/// W004 when the table's sheet was chosen among several, or is hidden.
fn say_choice(
    grid: &Grid,
    score: TableScore,
    candidates: &[(TableScore, Grid)],
    table_sheet: Option<&String>,
    diags: &mut Diagnostics,
) {
    let others: Vec<String> = candidates
        .iter()
        .map(|(s, g)| {
            let name = g.sheet.clone().unwrap_or_default();
            if s.visible {
                name
            } else {
                format!("{name} (hidden)")
            }
        })
        .collect();
    let chosen = grid.sheet.clone().unwrap_or_default();
    let mut why = Vec::new();
    if let Some(name) = table_sheet {
        why.push(format!("the sheet \"{name}\" is hidden"));
    }
    if !score.visible {
        why.push(format!(
            "\"{chosen}\" is hidden but no visible sheet holds a table"
        ));
    }
    if !others.is_empty() {
        why.push(format!(
            "other sheets also hold moves: {}",
            others.join(", ")
        ));
    }
    if !why.is_empty() {
        diags.warning(
            Code::W004SheetChoice,
            grid.sheet_location(),
            format!(
                "the table was read from sheet \"{chosen}\": {}; choose another with --sheet",
                why.join("; ")
            ),
        );
    }
}

/// How well a sheet holds a step table; `None` when it holds none.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
struct TableScore {
    visible: bool,
    /// BRANCH n / STEP n headers: a legend of example moves has none.
    headers: bool,
    moves: usize,
}

fn table_score(grid: &Grid, hidden: bool) -> Option<TableScore> {
    let mut headers = false;
    let mut moves = 0;
    for cell in &grid.cells {
        if let CellValue::Text(t) = &cell.value {
            headers |= header_kind(t).is_some();
            moves += usize::from(looks_like_move(t));
        }
    }
    (headers || moves > 0).then_some(TableScore {
        visible: !hidden,
        headers,
        moves,
    })
}

/// The two things we need from any calamine reader, object-safe.
pub(super) trait SheetSource {
    fn names(&self) -> Vec<String>;
    /// The names of hidden sheets (also "very hidden" ones).
    fn hidden(&self) -> Vec<String>;
    /// The filled cells of one sheet.
    fn grid(&mut self, file: &str, name: &str) -> Result<Grid, SheetError>;
    /// The sheet's merged cells.
    fn merged(&mut self, _name: &str) -> Vec<Region> {
        Vec::new()
    }
}

/// A rectangle of cells: first and last (row, column), inclusive.
pub(super) type Region = ((u32, u32), (u32, u32));

/// Why a sheet could not be read.
pub(super) enum SheetError {
    /// calamine could not decode it.
    Unreadable(String),
    /// More than [`MAX_FILLED_CELLS`] filled cells.
    TooManyCells,
}
