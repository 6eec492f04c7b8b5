//! The output workbook (`NAME.steptable.xlsx`) with the four sheets of the
//! published method: the normalised table, input addresses, output addresses
//! and the PLC program, each readable as it is and printable (see [`print`]),
//! then the simulation, its diagram and the fault table ([`report`]). The
//! file is byte-stable: its creation time is fixed, so the same input always
//! gives the same bytes.

mod print;
mod report;

use rust_xlsxwriter::{DocProperties, ExcelDateTime, Workbook, Worksheet, XlsxError};

use super::EmitInput;
use crate::address::Assigned;
use crate::program::{Action, StepKind, paper_sentence};
use crate::program::{Area, Signal};
use crate::sheets::TABLE_SHEET;
use print::{Formats, Page};

pub use print::{outcome_fill, row_points};

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

/// Renders `NAME.steptable.xlsx`.
pub fn render(input: &EmitInput) -> Result<Vec<u8>, XlsxError> {
    let mut workbook = Workbook::new();
    workbook.set_zip_compression_level(1);
    let fixed_time = ExcelDateTime::from_ymd(2020, 1, 1)?;
    workbook.set_properties(
        &DocProperties::new()
            .set_title(format!("steptable: {}", input.name))
            .set_creation_datetime(&fixed_time),
    );
    let f = Formats::new();
    table_sheet(workbook.add_worksheet(), input, &f)?;
    address_sheet(
        workbook.add_worksheet(),
        INPUT_SHEET,
        &input.allocation.inputs,
        input,
        &f,
    )?;
    address_sheet(
        workbook.add_worksheet(),
        OUTPUT_SHEET,
        &input.allocation.outputs,
        input,
        &f,
    )?;
    program_sheet(workbook.add_worksheet(), input, &f)?;
    if let Some(report) = input.simulation {
        report::simulation_sheet(workbook.add_worksheet(), report, input.symbols, &f)?;
        report::diagram_sheet(workbook.add_worksheet(), report, input.symbols, &f)?;
    }
    if let Some(faults) = input.faults {
        report::faults_sheet(workbook.add_worksheet(), faults, input.symbols, &f)?;
    }
    workbook.save_to_buffer()
}

/// The table, normalised, laid out as the paper's Fig. 7.
fn table_sheet(sheet: &mut Worksheet, input: &EmitInput, f: &Formats) -> Result<(), XlsxError> {
    sheet.set_name(TABLE_SHEET)?;
    sheet.write_string_with_format(0, 0, TABLE_SHEET, &f.title)?;
    sheet.write_string(1, 0, input.source())?;
    let header_row = 2;
    sheet.write_blank(header_row, 0, &f.header)?;
    for branch in 0..input.table.branches {
        let col = branch as u16 + 1;
        sheet.write_string_with_format(
            header_row,
            col,
            format!("BRANCH {}", branch + 1),
            &f.header,
        )?;
    }
    let label = f.header.clone().set_background_color("#F2F2F2");
    for (i, step) in input.table.steps.iter().enumerate() {
        let row = header_row + 1 + i as u32;
        sheet.write_string_with_format(row, 0, input.symbols.step_label(step.number), &label)?;
        for branch in 0..input.table.branches {
            sheet.write_string_with_format(
                row,
                branch as u16 + 1,
                step.cell_text(branch),
                &f.cell,
            )?;
        }
    }
    Page {
        repeat: Some((header_row, header_row)),
        widths: vec![12.0; input.table.branches + 1],
        fit_width: true,
    }
    .apply(sheet)?;
    sheet.set_freeze_panes(header_row + 1, 1)?;
    Ok(())
}

/// Column headers in row `row`, boxed and filled.
fn headers(sheet: &mut Worksheet, row: u32, names: &[&str], f: &Formats) -> Result<(), XlsxError> {
    for (col, name) in names.iter().enumerate() {
        sheet.write_string_with_format(row, col as u16, *name, &f.header)?;
    }
    Ok(())
}

/// Rows of text under the headers in row `header`, boxed and wrapped, each
/// row as tall as its longest cell needs (`format` gives row `i`'s cells).
fn write_rows(
    sheet: &mut Worksheet,
    header: u32,
    rows: &[Vec<String>],
    widths: &[f64],
    format: &dyn Fn(usize) -> rust_xlsxwriter::Format,
) -> Result<(), XlsxError> {
    for (i, row) in rows.iter().enumerate() {
        let at = header + 1 + i as u32;
        let format = format(i);
        for (col, text) in row.iter().enumerate() {
            sheet.write_string_with_format(at, col as u16, text, &format)?;
        }
        let texts: Vec<&str> = row.iter().map(String::as_str).collect();
        let points = row_points(&texts, widths);
        if points > 15.0 {
            sheet.set_row_height(at, points)?;
        }
    }
    Ok(())
}

/// A list sheet's filter: on its headers in row `header`, over its rows.
fn filter(
    sheet: &mut Worksheet,
    header: u32,
    rows: usize,
    columns: usize,
) -> Result<(), XlsxError> {
    let last_col = columns.max(1) as u16 - 1;
    sheet.autofilter(header, 0, header + rows as u32, last_col)?;
    Ok(())
}

fn program_sheet(sheet: &mut Worksheet, input: &EmitInput, f: &Formats) -> Result<(), XlsxError> {
    sheet.set_name(PROGRAM_SHEET)?;
    headers(sheet, 0, &["STEP", "PROGRAM", "MEMORIES AND TIMERS"], f)?;
    let rows: Vec<Vec<String>> = program_rows(input).into_iter().map(Vec::from).collect();
    let widest = rows
        .iter()
        .map(|r| r[1].chars().count())
        .max()
        .unwrap_or(10);
    // The sentences wrap in a column at most 90 characters wide, so the
    // three columns print on one landscape page across.
    let widths = [14.0, (widest as f64 * 1.05).clamp(20.0, 90.0), 26.0];
    write_rows(sheet, 0, &rows, &widths, &|_| f.cell.clone())?;
    Page {
        repeat: Some((0, 0)),
        widths: widths.to_vec(),
        fit_width: true,
    }
    .apply(sheet)?;
    sheet.set_freeze_panes(1, 0)?;
    Ok(())
}

fn address_sheet(
    sheet: &mut Worksheet,
    name: &str,
    list: &[Assigned],
    input: &EmitInput,
    f: &Formats,
) -> Result<(), XlsxError> {
    sheet.set_name(name)?;
    headers(sheet, 0, &["ADDRESS", "SYMBOL", "COMMENT"], f)?;
    let rows: Vec<Vec<String>> = list
        .iter()
        .map(|a| {
            vec![
                a.address.display(input.allocation.mnemonic),
                input.symbols.designation(a.signal),
                input.symbols.comment(a.signal),
            ]
        })
        .collect();
    let widths = [11.0, 12.0, 44.0];
    write_rows(sheet, 0, &rows, &widths, &|_| f.cell.clone())?;
    filter(sheet, 0, rows.len(), widths.len())?;
    Page {
        repeat: Some((0, 0)),
        widths: widths.to_vec(),
        fit_width: true,
    }
    .apply(sheet)?;
    sheet.set_freeze_panes(1, 0)?;
    Ok(())
}
