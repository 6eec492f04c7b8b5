//! The output workbook (`NAME.xlsx`) with the four sheets of the published
//! method: the normalised table, input addresses, output addresses and the PLC
//! program, each readable as it is. The file is byte-stable: its creation time
//! is fixed, so the same input always gives the same bytes.

use rust_xlsxwriter::{
    Chart, ChartType, DocProperties, ExcelDateTime, Format, Workbook, Worksheet, XlsxError,
};

use super::EmitInput;
use crate::address::Assigned;
use crate::faults::FaultTable;
use crate::program::{Action, StepKind, paper_sentence};
use crate::program::{Area, Signal};
use crate::sheets::TABLE_SHEET;
use crate::simulate::SimReport;

pub const INPUT_SHEET: &str = "INPUT ADDRESSES";
pub const OUTPUT_SHEET: &str = "OUTPUT ADDRESSES";
pub const PROGRAM_SHEET: &str = "PLC PROGRAM";
pub const SIMULATION_SHEET: &str = "SIMULATION";
pub const FAULTS_SHEET: &str = "FAULTS";
pub const DIAGRAM_SHEET: &str = "DIAGRAM";

/// The rows of the PLC PROGRAM sheet: `[label, sentence, memories and timers]`.
/// Each row is labelled with the step the program is in while it waits (as
/// in SFC: STEP 0 at rest, STEP k while table step k's moves run, the FST
/// file's labels); its sentence holds that step's completion and the output
/// actions of the step it enters, in the paper's notation, ending in `GOTO
/// STEP n` where the sequence does not simply go on to the next row (a jump,
/// the end of the cycle). The third column holds what it does to memories
/// (the middle-stop requests) and timers.
pub fn program_rows(input: &EmitInput) -> Vec<[String; 3]> {
    let program = input.program;
    let is_output = |a: &Action| a.signal().area() == Area::Output;
    let name = |s: Signal| input.symbols.designation(s);
    let mut rows = Vec::new();
    let split = |actions: &[Action]| -> (Vec<Action>, String) {
        let (outputs, memories): (Vec<Action>, Vec<Action>) =
            actions.iter().partition(|a| is_output(a));
        let requests = memories
            .iter()
            .map(|a| match a {
                Action::StartTimer(s, ms) => format!("START {} ({ms} ms)", name(*s)),
                _ => format!("{} {}", a.verb(), name(a.signal())),
            })
            .collect::<Vec<_>>()
            .join(" ");
        (outputs, requests)
    };
    for (i, step) in program.steps.iter().enumerate() {
        let label = input.symbols.step_label(program.step_in(i));
        // A jump is tested before its step: `IF … THEN … GOTO STEP 6`.
        for jump in &step.jumps {
            let (outputs, requests) = split(&jump.actions);
            rows.push([
                format!("{label} ({})", jump.title),
                format!(
                    "{} GOTO STEP {}",
                    paper_sentence(&jump.condition, &outputs, name),
                    program.step_entered(jump.fires)
                ),
                requests,
            ]);
        }
        let (outputs, requests) = split(&step.actions);
        let mut sentence = paper_sentence(&step.condition, &outputs, name);
        if step.kind == StepKind::EndOfCycle {
            sentence.push_str(&format!(" GOTO STEP {}", program.step_entered(i)));
        }
        rows.push([label, sentence, requests]);
    }
    for rung in &input.program.rungs {
        rows.push([
            rung.kind.label().to_string(),
            paper_sentence(&rung.condition, &rung.actions, name),
            String::new(),
        ]);
    }
    rows
}

/// Renders `NAME.xlsx`.
pub fn render(input: &EmitInput) -> Result<Vec<u8>, XlsxError> {
    let mut workbook = Workbook::new();
    workbook.set_zip_compression_level(1);
    let fixed_time = ExcelDateTime::from_ymd(2020, 1, 1)?;
    workbook.set_properties(
        &DocProperties::new()
            .set_title(format!("steptable: {}", input.name))
            .set_creation_datetime(&fixed_time),
    );
    let bold = Format::new().set_bold();
    let title = Format::new().set_bold().set_font_size(14);

    // The table, normalised, laid out as the paper's Fig. 7.
    let sheet = workbook.add_worksheet();
    sheet.set_name(TABLE_SHEET)?;
    sheet.write_string_with_format(0, 0, TABLE_SHEET, &title)?;
    sheet.write_string(1, 0, input.source())?;
    let header_row = 2;
    for branch in 0..input.table.branches {
        let col = branch as u16 + 1;
        sheet.write_string_with_format(header_row, col, format!("BRANCH {}", branch + 1), &bold)?;
        sheet.set_column_width(col, 12)?;
    }
    sheet.set_column_width(0, 12)?;
    for (i, step) in input.table.steps.iter().enumerate() {
        let row = header_row + 1 + i as u32;
        sheet.write_string_with_format(row, 0, input.symbols.step_label(step.number), &bold)?;
        for branch in 0..input.table.branches {
            let text = step.cell_text(branch);
            if !text.is_empty() {
                sheet.write_string(row, branch as u16 + 1, text)?;
            }
        }
    }
    sheet.set_freeze_panes(header_row + 1, 1)?;

    address_sheet(
        workbook.add_worksheet(),
        INPUT_SHEET,
        &input.allocation.inputs,
        input,
        &bold,
    )?;
    address_sheet(
        workbook.add_worksheet(),
        OUTPUT_SHEET,
        &input.allocation.outputs,
        input,
        &bold,
    )?;

    let sheet = workbook.add_worksheet();
    sheet.set_name(PROGRAM_SHEET)?;
    for (col, header) in ["STEP", "PROGRAM", "MEMORIES AND TIMERS"]
        .iter()
        .enumerate()
    {
        sheet.write_string_with_format(0, col as u16, *header, &bold)?;
    }
    let rows = program_rows(input);
    let widest = rows.iter().map(|r| r[1].len()).max().unwrap_or(10);
    for (i, row) in rows.iter().enumerate() {
        for (col, text) in row.iter().enumerate() {
            if !text.is_empty() {
                sheet.write_string(i as u32 + 1, col as u16, text)?;
            }
        }
    }
    sheet.set_column_width(0, 14)?;
    sheet.set_column_width(1, (widest as f64 * 1.05).clamp(20.0, 120.0))?;
    sheet.set_column_width(2, 24)?;
    sheet.set_freeze_panes(1, 0)?;

    if let Some(report) = input.simulation {
        // The SIMULATION sheet, then the DIAGRAM sheet.
        for sheet in [simulation_sheet, diagram_sheet] {
            sheet(
                workbook.add_worksheet(),
                report,
                input.symbols,
                &bold,
                &title,
            )?;
        }
    }
    if let Some(faults) = input.faults {
        faults_sheet(
            workbook.add_worksheet(),
            faults,
            input.symbols,
            &bold,
            &title,
        )?;
    }

    workbook.save_to_buffer()
}

fn simulation_sheet(
    sheet: &mut Worksheet,
    report: &SimReport,
    symbols: &crate::symbols::SymbolTable,
    bold: &Format,
    title: &Format,
) -> Result<(), XlsxError> {
    sheet.set_name(SIMULATION_SHEET)?;
    sheet.write_string_with_format(0, 0, "SIMULATION", title)?;
    sheet.write_string(1, 0, report.verdict())?;
    sheet.write_string(
        2,
        0,
        format!(
            "{} cycle(s) from START; step timing of the first cycle:",
            report.cycles.len()
        ),
    )?;
    let header = 4;
    for (col, text) in ["STEP", "START (s)", "DURATION (s)", "MOVES"]
        .iter()
        .enumerate()
    {
        sheet.write_string_with_format(header, col as u16, *text, bold)?;
    }
    if let Some(cycle) = report.cycles.first() {
        for (i, step) in cycle.steps.iter().enumerate() {
            let row = header + 1 + i as u32;
            sheet.write_string(row, 0, symbols.step_label(step.step))?;
            sheet.write_number(row, 1, step.start_ms as f64 / 1000.0)?;
            sheet.write_number(row, 2, step.duration_ms as f64 / 1000.0)?;
            sheet.write_string(row, 3, &step.moves)?;
            if !step.notes.is_empty() {
                sheet.write_string(row, 4, &step.notes)?;
            }
        }
        if cycle.steps.iter().any(|s| !s.notes.is_empty()) {
            sheet.write_string_with_format(header, 4, "DWELLS AND WAITS", bold)?;
            sheet.set_column_width(4, 40)?;
        }
    }
    sheet.set_column_width(0, 12)?;
    sheet.set_column_width(1, 12)?;
    sheet.set_column_width(2, 14)?;
    sheet.set_column_width(3, 30)?;
    sheet.set_freeze_panes(header + 1, 0)?;
    Ok(())
}

fn address_sheet(
    sheet: &mut Worksheet,
    name: &str,
    list: &[Assigned],
    input: &EmitInput,
    bold: &Format,
) -> Result<(), XlsxError> {
    sheet.set_name(name)?;
    for (col, header) in ["ADDRESS", "SYMBOL", "COMMENT"].iter().enumerate() {
        sheet.write_string_with_format(0, col as u16, *header, bold)?;
    }
    for (i, a) in list.iter().enumerate() {
        let row = i as u32 + 1;
        sheet.write_string(row, 0, a.address.display(input.allocation.mnemonic))?;
        sheet.write_string(row, 1, input.symbols.designation(a.signal))?;
        sheet.write_string(row, 2, input.symbols.comment(a.signal))?;
    }
    sheet.set_column_width(0, 10)?;
    sheet.set_column_width(1, 10)?;
    sheet.set_column_width(2, 36)?;
    sheet.set_freeze_panes(1, 0)?;
    Ok(())
}

fn faults_sheet(
    sheet: &mut Worksheet,
    faults: &FaultTable,
    symbols: &crate::symbols::SymbolTable,
    bold: &Format,
    title: &Format,
) -> Result<(), XlsxError> {
    sheet.set_name(FAULTS_SHEET)?;
    sheet.write_string_with_format(0, 0, "SENSOR FAULTS", title)?;
    sheet.write_string(1, 0, faults.summary())?;
    let header = 3;
    for (col, text) in [
        "FAULT",
        "OUTCOME",
        "APPEARS",
        "DETECTED",
        "STEP",
        "EXPLANATION",
    ]
    .iter()
    .enumerate()
    {
        sheet.write_string_with_format(header, col as u16, *text, bold)?;
    }
    let name = |s: Signal| symbols.designation(s);
    let text = |t: &str| symbols.designate(t);
    for (i, row) in crate::faults::rows(faults, &name, &text).iter().enumerate() {
        for (col, text) in row.iter().enumerate() {
            if !text.is_empty() {
                sheet.write_string(header + 1 + i as u32, col as u16, text)?;
            }
        }
    }
    sheet.set_column_width(0, 38)?;
    sheet.set_column_width(1, 11)?;
    sheet.set_column_width(2, 34)?;
    sheet.set_column_width(3, 9)?;
    sheet.set_column_width(4, 6)?;
    sheet.set_column_width(5, 90)?;
    sheet.set_freeze_panes(header + 1, 0)?;
    Ok(())
}

/// Pixels of one row at the default height.
const ROW_PIXELS: u32 = 20;

/// Height in pixels of one actuator's chart: taller with more positions.
fn chart_height(pmax: u32) -> u32 {
    90 + 45 * pmax.max(1)
}

/// The displacement-step diagram as native Excel charts: the positions at the
/// step boundaries in a small table, and one line chart per actuator, stacked
/// like the lanes of the hand-drawn diagram.
fn diagram_sheet(
    sheet: &mut Worksheet,
    report: &SimReport,
    symbols: &crate::symbols::SymbolTable,
    bold: &Format,
    title: &Format,
) -> Result<(), XlsxError> {
    sheet.set_name(DIAGRAM_SHEET)?;
    sheet.write_string_with_format(0, 0, "DISPLACEMENT-STEP DIAGRAM", title)?;
    sheet.write_string(
        1,
        0,
        "Position of each cylinder (0 = home) at the step boundaries, from the simulation.",
    )?;
    let header = 3u32;
    sheet.write_string_with_format(header, 0, "STEP", bold)?;
    let boundaries = report.step_positions.len();
    for (k, positions) in report.step_positions.iter().enumerate() {
        let row = header + 1 + k as u32;
        sheet.write_number(row, 0, (k + 1) as f64)?;
        for (i, p) in positions.iter().enumerate() {
            sheet.write_number(row, i as u16 + 1, (p * 100.0).round() / 100.0)?;
        }
    }
    let last_row = header + boundaries as u32;
    let chart_col = report.actuators.len() as u16 + 2;
    // Charts stack downwards, each starting below the one above it: rows
    // are 20 pixels high (15 points, the sheet's default), plus one spare.
    let mut chart_row = 1u32;
    for (i, (number, pmax)) in report.actuators.iter().enumerate() {
        let col = i as u16 + 1;
        let label = symbols.actuator(*number);
        sheet.write_string_with_format(header, col, &label, bold)?;
        let mut chart = Chart::new(ChartType::ScatterStraightWithMarkers);
        chart
            .add_series()
            .set_name(label.as_str())
            .set_categories((DIAGRAM_SHEET, header + 1, 0, last_row, 0))
            .set_values((DIAGRAM_SHEET, header + 1, col, last_row, col));
        chart.title().set_name(label.as_str());
        chart.legend().set_hidden();
        chart
            .x_axis()
            .set_name("step")
            .set_min(1)
            .set_max(boundaries.max(2) as f64)
            .set_major_unit(1);
        chart
            .y_axis()
            .set_name("position")
            .set_min(0)
            .set_max((*pmax).max(1) as f64)
            .set_major_unit(1);
        let height = chart_height(*pmax);
        chart.set_width(560).set_height(height);
        sheet.insert_chart(chart_row, chart_col, &chart)?;
        chart_row += height.div_ceil(ROW_PIXELS) + 1;
    }
    Ok(())
}
