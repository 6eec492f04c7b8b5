//! The engineer's template workbook: an empty step table laid out as the
//! published method's Fig. 7 (only the move cells can be edited, and they
//! reject text that is not a move), a SETTINGS sheet, a HELP sheet and the
//! paper's example as a sheet to copy from.

use rust_xlsxwriter::{
    DataValidation, DataValidationErrorStyle, DocProperties, ExcelDateTime, Format, FormatBorder,
    Formula, Note, Workbook, Worksheet, XlsxError,
};

use crate::cell::{MAX_ACTUATOR, MAX_POSITION};
use crate::emit::workbook::row_points;
use crate::sheets::{ADDRESSES_SHEET, SETTINGS_SHEET, TABLE_SHEET};
use crate::table::{MAX_BRANCHES, MAX_STEPS};

/// Sheet with the paper's example.
pub const EXAMPLE_SHEET: &str = "EXAMPLE";
/// Sheet with the cell grammar and the rules.
pub const HELP_SHEET: &str = "HELP";

/// The paper's example (Blagojević et al. 2019, Fig. 7).
pub const PAPER_EXAMPLE: [[&str; 3]; 8] = [
    ["C1+1", "", ""],
    ["C2+3", "", ""],
    ["C2-1", "", ""],
    ["C3+2", "C2+2", ""],
    ["C3-0", "C2-1", ""],
    ["C3+1", "C2+2", "C4+1"],
    ["C3-0", "C2-0", "C4-0"],
    ["C1-0", "", ""],
];

/// Characters across the SETTINGS sheet's help column and the HELP sheet's.
const MEANING_WIDTH: f64 = 80.0;
const HELP_WIDTH: f64 = 100.0;

/// Rows and columns of the table: the header row and the first step row.
const HEADER_ROW: u32 = 2;
const FIRST_STEP_ROW: u32 = 3;

struct Formats {
    title: Format,
    header: Format,
    label: Format,
    input: Format,
    wrap: Format,
}

fn formats() -> Formats {
    Formats {
        title: Format::new().set_bold().set_font_size(14),
        header: Format::new()
            .set_bold()
            .set_border(FormatBorder::Thin)
            .set_background_color("#D9E1F2"),
        label: Format::new().set_bold().set_border(FormatBorder::Thin),
        input: Format::new()
            .set_unlocked()
            .set_border(FormatBorder::Thin)
            .set_background_color("#FFFFF0"),
        wrap: Format::new().set_text_wrap(),
    }
}

/// Writes the Fig. 7 layout: title, BRANCH headers, STEP labels.
fn table_layout(
    sheet: &mut Worksheet,
    title: &str,
    branches: u16,
    steps: u32,
    f: &Formats,
) -> Result<(), XlsxError> {
    sheet.write_string_with_format(0, 0, title, &f.title)?;
    sheet.set_column_width(0, 12)?;
    for b in 0..branches {
        sheet.write_string_with_format(
            HEADER_ROW,
            b + 1,
            format!("BRANCH {}", b + 1),
            &f.header,
        )?;
        sheet.set_column_width(b + 1, 13)?;
    }
    for k in 0..steps {
        sheet.write_string_with_format(
            FIRST_STEP_ROW + k,
            0,
            format!("STEP {}", k + 1),
            &f.label,
        )?;
    }
    sheet.set_freeze_panes(FIRST_STEP_ROW, 1)?;
    Ok(())
}

/// The custom validation rule of one move cell (relative to its top-left
/// cell B4), accepting every cell the reader accepts. With the white space
/// the reader ignores left out (`squeezed`): empty, or starting with a `;`
/// (an empty first item; `FIND("", …)` is 1, so a cell of only white space
/// passes here too); a first item that is a move — `C` (also Cyrillic or
/// full-width) then a digit (also subscript, superscript or full-width),
/// with a sign somewhere (+, -, the minus sign, dashes, full-width and
/// raised or lowered signs); or one that starts with a dwell `T=`, a wait
/// `I:`, an output `Y:` or a jump `J:`. The tool's own check is stricter;
/// this catches typing slips while typing.
fn move_rule() -> Formula {
    let squeezed = squeezed();
    let signs: String = MOVE_SIGNS
        .chars()
        .map(|c| format!("ISNUMBER(FIND(\"{c}\",B4))"))
        .collect::<Vec<_>>()
        .join(",");
    let starts = ITEM_STARTS.join("|");
    Formula::new(format!(
        "=OR(TRIM(B4)=\"\",ISNUMBER(FIND(LEFT({squeezed},1),\";\u{FF1B}\")),\
         AND(ISNUMBER(FIND(LEFT({squeezed},1),\"{MOVE_LETTERS}\")),\
         ISNUMBER(FIND(MID({squeezed},2,1),\"0123456789{MOVE_DIGITS}\")),\
         OR({signs})),\
         ISNUMBER(FIND(\"|\"&LEFT(UPPER({squeezed}),2)&\"|\",\"|{starts}|\")))"
    ))
}

/// The cell without the white space the reader ignores (every character
/// `cell::normalize` drops): `CLEAN` takes out the control characters (tab,
/// line breaks), `SUBSTITUTE` each other one by its code (`UNICHAR`), so
/// that no unusual character is written into the formula.
fn squeezed() -> String {
    let mut text = "CLEAN(B4)".to_string();
    for c in IGNORED_SPACES.iter().filter(|c| **c as u32 > 31) {
        text = format!("SUBSTITUTE({text},UNICHAR({}),\"\")", *c as u32);
    }
    text
}

/// Every character the reader ignores in a cell: Unicode's white space
/// (`char::is_whitespace`) and the zero-width ones (a test checks this
/// against `cell::normalize` over every character).
pub const IGNORED_SPACES: [char; 30] = [
    '\t', '\n', '\u{B}', '\u{C}', '\r', ' ', '\u{85}', '\u{A0}', '\u{1680}', '\u{2000}',
    '\u{2001}', '\u{2002}', '\u{2003}', '\u{2004}', '\u{2005}', '\u{2006}', '\u{2007}', '\u{2008}',
    '\u{2009}', '\u{200A}', '\u{2028}', '\u{2029}', '\u{202F}', '\u{205F}', '\u{3000}', '\u{200B}',
    '\u{200C}', '\u{200D}', '\u{2060}', '\u{FEFF}',
];

/// The letters a move cell may start with: C, Cyrillic Es, full-width C.
const MOVE_LETTERS: &str = "Cc\u{0421}\u{0441}\u{FF23}\u{FF43}";
/// Digits other than 0-9 the reader accepts: subscript, superscript and
/// full-width.
const MOVE_DIGITS: &str = "\u{2070}\u{00B9}\u{00B2}\u{00B3}\u{2074}\u{2075}\u{2076}\u{2077}\u{2078}\u{2079}\u{2080}\u{2081}\u{2082}\u{2083}\u{2084}\u{2085}\u{2086}\u{2087}\u{2088}\u{2089}\u{FF10}\u{FF11}\u{FF12}\u{FF13}\u{FF14}\u{FF15}\u{FF16}\u{FF17}\u{FF18}\u{FF19}";
/// Every sign the reader accepts: plus, hyphen-minus, minus sign, the
/// dashes U+2010 to U+2015, full-width, superscript and subscript signs.
const MOVE_SIGNS: &str = "+-\u{2212}\u{2010}\u{2011}\u{2012}\u{2013}\u{2014}\u{2015}\u{FF0B}\u{FF0D}\u{207A}\u{207B}\u{208A}\u{208B}\u{FE62}\u{FE63}";

/// How the items other than moves start: a dwell, a wait, an output, a jump.
const ITEM_STARTS: [&str; 4] = ["T=", "I:", "Y:", "J:"];
/// Builds the template workbook with `branches` × `steps` move cells.
pub fn template_workbook(branches: u16, steps: u32) -> Result<Vec<u8>, XlsxError> {
    let branches = branches.clamp(1, MAX_BRANCHES as u16);
    let steps = steps.clamp(1, MAX_STEPS as u32);
    let f = formats();
    let mut workbook = Workbook::new();
    workbook.set_properties(
        &DocProperties::new()
            .set_title("steptable template")
            .set_creation_datetime(&ExcelDateTime::from_ymd(2020, 1, 1)?),
    );

    // The table to fill in.
    let sheet = workbook.add_worksheet();
    sheet.set_name(TABLE_SHEET)?;
    table_layout(sheet, TABLE_SHEET, branches, steps, &f)?;
    let last_row = FIRST_STEP_ROW + steps - 1;
    for k in 0..steps {
        for b in 0..branches {
            sheet.write_blank(FIRST_STEP_ROW + k, b + 1, &f.input)?;
        }
    }
    let validation = DataValidation::new()
        .allow_custom(move_rule())
        .set_input_title("Move")?
        .set_input_message(
            "C2+1: cylinder 2 out to position 1; C1-0: cylinder 1 home. T=2s: dwell; \
             I:name: wait for an input; Y:name+ / Y:name-: output on / off; J:6 if I:name: \
             jump. Several joined by ; (C3+1; T=2s). Empty: nothing in this branch.",
        )?
        .set_error_title("Not a move")?
        .set_error_message(
            "Expected C<number>+<position> or C<number>-<position>, e.g. C2+1, or T=2s, I:name, Y:name+, J:6 if I:name.",
        )?;
    sheet.add_data_validation(FIRST_STEP_ROW, 1, last_row, branches, &validation)?;
    sheet.write_string(
        last_row + 2,
        0,
        "Fill the yellow cells: one row per step, one column per parallel branch.",
    )?;
    sheet.write_string(
        last_row + 3,
        0,
        "See the HELP sheet; the EXAMPLE sheet holds the paper's example.",
    )?;
    sheet.protect();

    settings_sheet(workbook.add_worksheet(), &f)?;
    addresses_sheet(workbook.add_worksheet(), &f)?;
    help_sheet(workbook.add_worksheet(), &f)?;

    // The paper's example, to look at or copy from.
    let sheet = workbook.add_worksheet();
    sheet.set_name(EXAMPLE_SHEET)?;
    table_layout(
        sheet,
        "EXAMPLE: Blagojević et al. (2019), Fig. 7",
        3,
        PAPER_EXAMPLE.len() as u32,
        &f,
    )?;
    for (k, row) in PAPER_EXAMPLE.iter().enumerate() {
        for (b, text) in row.iter().enumerate() {
            if !text.is_empty() {
                sheet.write_string(FIRST_STEP_ROW + k as u32, b as u16 + 1, *text)?;
            }
        }
    }
    workbook.save_to_buffer()
}

/// Pins to the wiring: empty (any pin would bind every target's notation),
/// with the example in the notes above the header.
fn addresses_sheet(sheet: &mut Worksheet, f: &Formats) -> Result<(), XlsxError> {
    sheet.set_name(ADDRESSES_SHEET)?;
    sheet.write_string_with_format(0, 0, "ADDRESSES", &f.title)?;
    let notes = [
        "Optional: signals wired to given terminals. One row per signal below the header: the signal as the allocation list names it (START, x11, y1+, part_present) and its address in the target's notation.",
        "Example for the siemens target: START | I0.0, x11 | I0.2, y1+ | Q0.1 (festo: I0.0 / O0.1; iec: %IX0.0 / %QX0.1).",
        "Pinned signals keep their address; the others are laid out around them in their usual order.",
    ];
    for (row, note) in notes.iter().enumerate() {
        sheet.write_string(1 + row as u32, 0, *note)?;
    }
    sheet.write_string_with_format(5, 0, "SIGNAL", &f.header)?;
    sheet.write_string_with_format(5, 1, "ADDRESS", &f.header)?;
    sheet.set_column_width(0, 16)?;
    sheet.set_column_width(1, 12)?;
    Ok(())
}

fn settings_sheet(sheet: &mut Worksheet, f: &Formats) -> Result<(), XlsxError> {
    sheet.set_name(SETTINGS_SHEET)?;
    sheet.write_string_with_format(0, 0, "SETTINGS", &f.title)?;
    sheet.write_string(
        1,
        0,
        "Used by steptable convert for this workbook; command-line options override them.",
    )?;
    for (col, header) in [(0, "SETTING"), (1, "VALUE"), (3, "WHAT IT MEANS")] {
        sheet.write_string_with_format(3, col, header, &f.header)?;
    }
    let rows: Vec<SettingRow> = [
        platform_rows().to_vec(),
        safety_rows().to_vec(),
        sequence_rows().to_vec(),
    ]
    .concat();
    for (i, (label, value, meaning, choices)) in rows.iter().enumerate() {
        let row = 4 + i as u32;
        sheet.write_string_with_format(row, 0, *label, &f.label)?;
        sheet.write_string_with_format(row, 1, *value, &f.input)?;
        sheet.write_string_with_format(row, 3, meaning, &f.wrap)?;
        // Tall enough for the wrapped help: neither Excel nor LibreOffice
        // grows a row on opening, and a 15 pt row overlaps the next one.
        sheet.set_row_height(row, row_points(&[meaning.as_str()], &[MEANING_WIDTH]))?;
        sheet.insert_note(row, 1, &Note::new(meaning).set_author("steptable"))?;
        if let Some(choices) = choices {
            let mut validation = DataValidation::new()
                .allow_list_strings(choices)?
                .set_input_title(*label)?;
            // A list may combine choices: warn, but accept other text.
            if *label == "safety" || *label == "modes" {
                validation = validation.set_error_style(DataValidationErrorStyle::Information);
            }
            sheet.add_data_validation(row, 1, row, 1, &validation)?;
        }
    }
    // Below the rows of settings and a blank row.
    let header = 4 + rows.len() as u32 + 2;
    actuator_table(sheet, f, header)?;
    // Wide enough for the longest label (`de-energise on halt`) in bold.
    let widest = rows.iter().map(|r| r.0.chars().count()).max().unwrap_or(10);
    sheet.set_column_width(0, widest as f64 + 3.0)?;
    sheet.set_column_width(1, 14)?;
    sheet.set_column_width(2, 14)?;
    sheet.set_column_width(3, MEANING_WIDTH)?;
    sheet.set_column_width(4, 16)?;
    sheet.protect();
    Ok(())
}

/// One row of the SETTINGS sheet: its label, the template's value, what
/// it means and the values offered (a list to pick from, or free text).
type SettingRow = (
    &'static str,
    &'static str,
    String,
    Option<Vec<&'static str>>,
);

/// Every list from its type's own, so a value added there is offered here
/// (a test compares them).
fn choices(first: &[&'static str], rest: &[&'static str]) -> Vec<&'static str> {
    first.iter().chain(rest).copied().collect()
}

fn owned_row(row: (&'static str, &'static str, &str, Option<&[&'static str]>)) -> SettingRow {
    let (label, value, meaning, choices) = row;
    (
        label,
        value,
        meaning.to_string(),
        choices.map(<[_]>::to_vec),
    )
}

/// Where the program runs: its addresses, board, operand letters and scan.
fn platform_rows() -> [SettingRow; 4] {
    let boards = choices(&["none"], &crate::address::BOARDS.map(|b| b.name));
    let targets = choices(&["default"], &crate::address::Target::NAMES);
    let mnemonics = crate::address::Mnemonic::names();
    let rows: [(&str, &str, &str, Option<&[&str]>); 4] = [
        (
            "target",
            "default",
            "Address style: default (festo, or iec when a board is chosen), festo (I0.0 / O0.0, 16-bit words, the paper's layout), iec or openplc (%IX0.0 / %QX0.0, CODESYS and OpenPLC) or siemens (I0.0 / Q0.0).",
            Some(&targets),
        ),
        (
            "board",
            "none",
            "OpenPLC board the program runs on: none, or rpi, uno, mega, esp32, … Only the inputs and outputs the board wires are used (addresses %IX / %QX); a table that needs more is refused with the counts.",
            Some(&boards),
        ),
        (
            "mnemonic",
            "en",
            "Operand letters for Siemens and STEP 7: en (I, Q; A, AN) or de (E, A; U, UN).",
            Some(&mnemonics),
        ),
        (
            "scan time",
            "10ms",
            "PLC cycle of the generated task and of the simulation, from 1ms to 1s.",
            None,
        ),
    ];
    rows.map(owned_row)
}

/// What the program checks and does when the operator or a fault stops it.
fn safety_rows() -> [SettingRow; 10] {
    let safety = choices(&["none", "all"], &crate::program::Safety::NAMES);
    let modes = choices(&["none", "all"], &crate::program::Modes::NAMES);
    let safety_text = format!(
        "Safety checks built into the program: none, all, or a list of {} (e.g. edge, watchdog).",
        crate::program::Safety::NAMES.join(", ")
    );
    let modes_text = format!(
        "Operating modes in the program: none, all (every mode, step and manual too), or a list of {} (estop brings reset).",
        crate::program::Modes::NAMES.join(", ")
    );
    let rows: [(&str, &str, &str, Option<&[&str]>); 10] = [
        ("safety", "none", &safety_text, Some(&safety)),
        ("modes", "none", &modes_text, Some(&modes)),
        (
            "hold-safe",
            "none",
            "Machine outputs that may stay on when the machine stops on a fault (a vacuum gripper holding its part, a clamp), e.g. vacuum, clamp. Undeclared, a machine output left on in a stopped machine is a hazard in the fault table; coils may stay on.",
            None,
        ),
        (
            "de-energise on halt",
            "none",
            "Outputs the program switches off when a safety check, the emergency stop or an interlock halts the machine (a heater, a motor), e.g. heater, brush. C2 names both coils of C2.",
            None,
        ),
        (
            "start permissive",
            "none",
            "Machine inputs that must be on for a cycle to start (air pressure, a closed guard), e.g. air_ok, guard_closed. Each gets an input address; no step waits for it.",
            None,
        ),
        (
            "hold on estop",
            "none",
            "Outputs the EMERGENCY STOP leaves on (a vacuum gripper keeps its part, a clamp its workpiece), e.g. vacuum. Every other coil and output goes off. Only a machine output that moves nothing: a valve coil or a drive is refused.",
            None,
        ),
        (
            "on stop",
            "none",
            "With modes: stop, what STOP does to each output, e.g. heater off, fan off after 20s, vacuum hold. With this row STOP acts at once, in any state: the cycle is abandoned and every coil and output not named goes off. Without it, STOP lets the cycle finish.",
            None,
        ),
        (
            "on estop",
            "none",
            "What the EMERGENCY STOP does to each output, as for on stop: off (the default), hold, or off after a time (a fan cooling a heater), e.g. fan off after 20s. Hold and off after only for a machine output that moves nothing: a valve coil or a drive is refused.",
            None,
        ),
        (
            "on halt",
            "none",
            "What a halt (a safety check, the emergency stop, an interlock) does to each output: hold (the default: as the sequence left it), off, or off after a time, e.g. heater off, fan off after 20s.",
            None,
        ),
        (
            "interlock",
            "none",
            "Machine inputs that must stay on (a guard door's switch), e.g. guard_closed, or only in some steps: guard_closed in steps 3-5. One going off halts the machine where it is and raises alarm_il; RESET clears it.",
            None,
        ),
    ];
    rows.map(owned_row)
}

/// What the lists call a signal, and the homing and supervision times.
fn sequence_rows() -> [SettingRow; 3] {
    let schemes = crate::symbols::Scheme::ALL.map(crate::symbols::Scheme::name);
    let rows: [(&str, &str, &str, Option<&[&str]>); 3] = [
        (
            "designations",
            "paper",
            "What the lists, comments and fault table call a signal: paper (x10, y1+), iso (ISO 1219-2: 1A1 cylinder, 1B1/1B2 sensors, 1M1/1M2 solenoids) or names (the actuator table's names: clamp_home, clamp_out). Name an actuator in the table below: C1 (clamp).",
            Some(&schemes),
        ),
        (
            "home order",
            "default",
            "Homing stages for RESET, first to last, e.g. C3&C4, C2, C1. default: the order the cycle itself returns the actuators home (each actuator's last move, earliest first; those whose last moves share a step go together).",
            None,
        ),
        (
            "supervision",
            "none",
            "Supervision time per step in place of the watchdog's (twice the step's longest move, plus its dwell, plus 1 s), e.g. 3=5s, 5=12s: longer than the step takes, at most 655.35 s; needs watchdog or criteria among the safety checks. none: every step's from the stroke times.",
            None,
        ),
    ];
    rows.map(owned_row)
}

/// The actuator table's caption: what an empty time cell means, with
/// each kind's own times as the plant and the watchdog take them.
fn actuator_caption() -> String {
    use crate::actuator::ActuatorKind::{Swivel, Vacuum};
    let own = |kind: crate::actuator::ActuatorKind| {
        let s = kind.default_stroke().unwrap_or_default();
        let text = crate::cell::duration_text;
        (text(s.extend_ms), text(s.retract_ms))
    };
    let cylinder = crate::stroke::Stroke::default();
    let (swing_out, swing_back) = own(Swivel);
    let (build_up, release) = own(Vacuum);
    format!(
        "Stroke times (extend / retract; an empty cell takes the kind's own: a cylinder {} / {}, \
         a swivel drive {swing_out} / {swing_back}, a vacuum gripper {build_up} build-up / {release} release), \
         valve type and your name per actuator.",
        crate::cell::duration_text(cylinder.extend_ms),
        crate::cell::duration_text(cylinder.retract_ms),
    )
}

/// The actuator table below the settings, its header on row `header`:
/// stroke times, valve type and the engineer's name of C1 to C8.
fn actuator_table(sheet: &mut Worksheet, f: &Formats, header: u32) -> Result<(), XlsxError> {
    sheet.write_string(header - 1, 0, actuator_caption())?;
    for (col, text) in ["actuator", "extend", "retract", "valve", "name"]
        .iter()
        .enumerate()
    {
        sheet.write_string_with_format(header, col as u16, *text, &f.header)?;
    }
    for i in 0..8u32 {
        let row = header + 1 + i;
        sheet.write_string_with_format(row, 0, format!("C{}", i + 1), &f.input)?;
        // Empty, not 1s: a time written here would be the engineer's and
        // override a swivel drive's or a vacuum gripper's own.
        sheet.write_blank(row, 1, &f.input)?;
        sheet.write_blank(row, 2, &f.input)?;
        sheet.write_blank(row, 3, &f.input)?;
        sheet.write_blank(row, 4, &f.input)?;
    }
    let valves: Vec<&str> = crate::actuator::ActuatorKind::ALL
        .iter()
        .map(|v| v.name())
        .collect();
    sheet.add_data_validation(
        header + 1,
        3,
        header + 8,
        3,
        &DataValidation::new()
            .allow_list_strings(&valves)?
            .set_input_title("valve")?
            .set_input_message(
                "Empty: 52bi (two positions) or 53closed (middle positions). 52mono: one coil, spring return; motor: an electric drive.",
            )?,
    )?;
    sheet.add_data_validation(
        header + 1,
        4,
        header + 8,
        4,
        &DataValidation::new()
            .allow_any_value()
            .set_input_title("name")?
            .set_input_message(
                "Your name of the actuator (clamp): every output carries it; with designations = names it makes the identifiers (clamp_home, clamp_out). The same as C1 (clamp) in the first column.",
            )?,
    )?;
    Ok(())
}

fn help_sheet(sheet: &mut Worksheet, f: &Formats) -> Result<(), XlsxError> {
    sheet.set_name(HELP_SHEET)?;
    sheet.write_string_with_format(0, 0, "HOW TO FILL THE STEP TABLE", &f.title)?;
    let limits = format!(
        "Actuators C1 to C{MAX_ACTUATOR} (need not be contiguous), positions 0 to {MAX_POSITION}, \
         up to {MAX_STEPS} steps and {MAX_BRANCHES} branches."
    );
    let lines: Vec<(&str, String)> = vec![
        ("Rows", "One row per step, top to bottom in the order they run. All moves of a step start together.".into()),
        ("Columns", "One column per branch: a step with moves in three branches moves three actuators at once.".into()),
        ("C2+1", "Cylinder 2 moves in the + direction (extends) to its position 1.".into()),
        ("C1-0", "Cylinder 1 moves in the - direction (retracts) to position 0, its home.".into()),
        ("C3+", "Without a position: + goes to the cylinder's end (its highest position in the table), - goes home.".into()),
        ("Spelling", "Any case, spaces, the Unicode minus or a dash are all accepted: c2 + 1, C2−1, C2–1.".into()),
        ("Empty", "An empty cell means no move in that branch; empty STEP rows after the last move are ignored.".into()),
        ("Rule", "Every actuator starts at position 0 and is back at 0 after the last step.".into()),
        ("Rule", "A + move goes to a higher position than the actuator stands at, a - move to a lower one.".into()),
        ("Rule", "An actuator moves at most once per step; a step between two steps needs at least one item (a move, or only a wait or a dwell).".into()),
        ("Limits", limits),
        ("T=2s", "A dwell: once the cell's other items are done (C3+1; T=2s: once C3 is at position 1) the branch waits 2 s. T=500ms, T=1.5s; 10 ms to 655 s.".into()),
        ("I:name", "Wait until the machine input name (part_present, door_closed) is 1; I:name=0 waits for 0. It gets an address after the sensors.".into()),
        ("Y:name+", "Switch the machine output name (vacuum, conveyor) on; Y:name- switches it off. It stays until switched. It gets an address after the coils.".into()),
        ("J:7 if I:name", "A jump: once the step is done, if the machine input name is 1 (I:name=0: is 0) the sequence goes on at step 7 instead of the next step (a reject path, a retry); J:end if I:name ends the cycle. Every actuator must already stand where the target step starts from (home for end).".into()),
        ("A; B", "Several items in one cell, separated by ;, e.g. Y:vacuum+; T=500ms. A step may hold only a wait or a dwell.".into()),
        ("Names", "Letters, digits and _, starting with a letter, up to 16 characters, no spaces; the first 9 characters must differ (Festo FST keeps 9).".into()),
        ("Modes", "SETTINGS modes adds START/STOP/EMERGENCY STOP/RESET/CONTINUOUS handling and a homing sequence (home order) to every program.".into()),
        ("Middle stops", "An actuator with positions between 0 and its end gets a 5/3 valve; the program switches both coils off at a middle target.".into()),
        ("ADDRESSES", "Optional: pin signals to the terminals they are wired to. One row per signal under SIGNAL | ADDRESS (START | I0.0, y1+ | O0.1), in the target's notation; the other signals are laid out around them. A wrong row is an error at its cell.".into()),
        ("Board", "SETTINGS board (rpi, uno, mega, esp32, …): only the inputs and outputs that OpenPLC board wires are used, packed from %IX0.0 and %QX0.0; a table that needs more is refused with the counts.".into()),
        ("Convert", "steptable convert this-file.xlsx writes the address lists, the programs, the simulation and the fault table.".into()),
    ];
    sheet.write_string_with_format(2, 0, "WRITE", &f.header)?;
    sheet.write_string_with_format(2, 1, "MEANING", &f.header)?;
    for (i, (what, meaning)) in lines.iter().enumerate() {
        let row = 3 + i as u32;
        sheet.write_string_with_format(row, 0, *what, &f.label)?;
        sheet.write_string_with_format(row, 1, meaning, &f.wrap)?;
        sheet.set_row_height(row, row_points(&[meaning], &[HELP_WIDTH]))?;
    }
    sheet.set_column_width(0, 14)?;
    sheet.set_column_width(1, HELP_WIDTH)?;
    Ok(())
}
