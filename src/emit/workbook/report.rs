//! The sheets of what steptable found out about the program: SIMULATION
//! (verdict and step timing), DIAGRAM (the displacement-step diagram as
//! native charts) and FAULTS (what each failed sensor does, hazards first).

use rust_xlsxwriter::{Chart, ChartType, Worksheet, XlsxError};

use super::print::{Formats, Page};
use super::{DIAGRAM_SHEET, FAULTS_SHEET, SIMULATION_SHEET, filter, headers, write_rows};
use crate::emit::diagram::step_levels;
use crate::faults::FaultTable;
use crate::program::Signal;
use crate::simulate::SimReport;
use crate::symbols::SymbolTable;

pub(super) fn simulation_sheet(
    sheet: &mut Worksheet,
    report: &SimReport,
    symbols: &SymbolTable,
    f: &Formats,
) -> Result<(), XlsxError> {
    sheet.set_name(SIMULATION_SHEET)?;
    sheet.write_string_with_format(0, 0, "SIMULATION", &f.title)?;
    sheet.write_string(1, 0, symbols.explain(&report.verdict()))?;
    sheet.write_string(
        2,
        0,
        format!(
            "{} cycle(s) from START; step timing of the first cycle:",
            report.cycles.len()
        ),
    )?;
    let header = 4;
    let steps = report
        .cycles
        .first()
        .map(|c| c.steps.as_slice())
        .unwrap_or(&[]);
    let notes = steps.iter().any(|s| !s.notes.is_empty());
    let mut names = vec!["STEP", "START (s)", "DURATION (s)", "MOVES"];
    let mut widths = vec![12.0, 11.0, 13.0, 30.0];
    if notes {
        names.push("DWELLS AND WAITS");
        widths.push(40.0);
    }
    headers(sheet, header, &names, f)?;
    let rows: Vec<Vec<String>> = steps
        .iter()
        .map(|step| {
            let mut row = vec![
                symbols.step_label(step.step),
                String::new(),
                String::new(),
                step.moves.clone(),
            ];
            if notes {
                row.push(symbols.explain(&step.notes));
            }
            row
        })
        .collect();
    write_rows(sheet, header, &rows, &widths, &|_| f.cell.clone())?;
    // The times stay numbers, so they can be summed and filtered.
    for (i, step) in steps.iter().enumerate() {
        let row = header + 1 + i as u32;
        sheet.write_number_with_format(row, 1, step.start_ms as f64 / 1000.0, &f.cell)?;
        sheet.write_number_with_format(row, 2, step.duration_ms as f64 / 1000.0, &f.cell)?;
    }
    filter(sheet, header, rows.len(), widths.len())?;
    Page {
        repeat: Some((header, header)),
        widths,
        fit_width: true,
    }
    .apply(sheet)?;
    sheet.set_freeze_panes(header + 1, 0)?;
    Ok(())
}

pub(super) fn faults_sheet(
    sheet: &mut Worksheet,
    faults: &FaultTable,
    symbols: &SymbolTable,
    f: &Formats,
) -> Result<(), XlsxError> {
    sheet.set_name(FAULTS_SHEET)?;
    sheet.write_string_with_format(0, 0, "SENSOR FAULTS", &f.title)?;
    sheet.write_string(1, 0, faults.summary())?;
    let header = 3;
    let names = [
        "FAULT",
        "OUTCOME",
        "APPEARS",
        "DETECTED",
        "STEP",
        "EXPLANATION",
    ];
    headers(sheet, header, &names, f)?;
    let name = |s: Signal| symbols.designation(s);
    let text = |t: &str| symbols.explain(t);
    let rows = crate::faults::rows(faults, &name, &text);
    // Hazards first, then safe stalls, then faults without effect; in the
    // fault table's order within each.
    let mut order: Vec<usize> = (0..rows.len()).collect();
    order.sort_by_key(|&i| std::cmp::Reverse(faults.cases[i].outcome));
    let sorted: Vec<Vec<String>> = order.iter().map(|&i| rows[i].to_vec()).collect();
    let widths = [28.0, 11.0, 24.0, 10.0, 6.0, 56.0];
    let fill = |i: usize| f.outcome(faults.cases[order[i]].outcome);
    write_rows(sheet, header, &sorted, &widths, &fill)?;
    filter(sheet, header, sorted.len(), widths.len())?;
    Page {
        repeat: Some((header, header)),
        widths: widths.to_vec(),
        fit_width: true,
    }
    .apply(sheet)?;
    sheet.set_freeze_panes(header + 1, 0)?;
    Ok(())
}

/// Pixels of one row at the default height (15 points).
const ROW_PIXELS: u32 = 20;

/// Pixels of a portrait A4 page's printed area at 100 %, less a margin for
/// the header and footer LibreOffice takes from it: a chart that would
/// cross this starts a new page.
const PAGE_PIXELS: u32 = 820;

/// Width in pixels of each chart: 7 of the sheet's columns, inside a
/// portrait A4 page as LibreOffice prints it (560 pixels over columns of
/// its default width printed two pages wide).
const CHART_WIDTH: u32 = 480;

/// Columns given the table's width, under the charts too, so that Excel
/// and LibreOffice (whose default column is wider) agree on them.
const DIAGRAM_COLUMNS: usize = 8;

/// Height in pixels of one actuator's chart: a lane of 40 pixels per
/// position besides the axes, so 0, 1 and a middle position all show.
fn chart_height(pmax: u32) -> u32 {
    110 + 40 * pmax.max(1)
}

/// The displacement-step diagram as native Excel charts, stacked like the
/// lanes of the hand-drawn diagram, one page after another without cutting
/// a chart; under them the positions at the step boundaries they plot: the
/// sensor level each actuator stands at when a step fires (as the SVG
/// draws it), not the piston a scan before its end stop.
pub(super) fn diagram_sheet(
    sheet: &mut Worksheet,
    report: &SimReport,
    symbols: &SymbolTable,
    f: &Formats,
) -> Result<(), XlsxError> {
    sheet.set_name(DIAGRAM_SHEET)?;
    sheet.write_string_with_format(0, 0, "DISPLACEMENT-STEP DIAGRAM", &f.title)?;
    sheet.write_string(
        1,
        0,
        "Position of each cylinder (0 = home) at the step boundaries, from the simulation.",
    )?;
    let mut breaks = Vec::new();
    let mut page_top = 0u32;
    let mut row = 3u32;
    let mut place = |rows: u32, breaks: &mut Vec<u32>| {
        if (row + rows - page_top) * ROW_PIXELS > PAGE_PIXELS && row > page_top {
            breaks.push(row);
            page_top = row;
        }
        let at = row;
        row += rows + 1;
        at
    };
    let levels = step_levels(report);
    let boundaries = levels.len() as u32;
    let mut chart_rows = Vec::new();
    for (_, pmax) in &report.actuators {
        chart_rows.push(place(chart_height(*pmax).div_ceil(ROW_PIXELS), &mut breaks));
    }
    let header = place(boundaries + 1, &mut breaks);
    let last_row = header + boundaries;
    let mut names = vec!["STEP".to_string()];
    names.extend(report.actuators.iter().map(|(n, _)| symbols.actuator(*n)));
    let names: Vec<&str> = names.iter().map(String::as_str).collect();
    headers(sheet, header, &names, f)?;
    for (k, positions) in levels.iter().enumerate() {
        let at = header + 1 + k as u32;
        sheet.write_number_with_format(at, 0, (k + 1) as f64, &f.cell)?;
        for (i, p) in positions.iter().enumerate() {
            sheet.write_number_with_format(
                at,
                i as u16 + 1,
                (p * 100.0).round() / 100.0,
                &f.cell,
            )?;
        }
    }
    for (i, (number, pmax)) in report.actuators.iter().enumerate() {
        let col = i as u16 + 1;
        let mut chart = Chart::new(ChartType::ScatterStraightWithMarkers);
        chart
            .add_series()
            .set_name(names[col as usize])
            .set_categories((DIAGRAM_SHEET, header + 1, 0, last_row, 0))
            .set_values((DIAGRAM_SHEET, header + 1, col, last_row, col));
        chart.legend().set_hidden();
        chart
            .x_axis()
            .set_name("step")
            .set_min(1)
            .set_max(boundaries.max(2) as f64)
            .set_major_unit(1);
        // The lane's name stands where the hand-drawn diagram has it: left
        // of its positions.
        chart
            .y_axis()
            .set_name(symbols.actuator(*number).as_str())
            .set_min(0)
            .set_max((*pmax).max(1) as f64)
            .set_major_unit(1)
            .set_major_gridlines(true);
        chart.set_width(CHART_WIDTH).set_height(chart_height(*pmax));
        sheet.insert_chart(chart_rows[i], 0, &chart)?;
    }
    sheet.set_page_breaks(&breaks)?;
    let columns = report.actuators.len() + 1;
    Page {
        repeat: None,
        widths: vec![8.0; columns.max(DIAGRAM_COLUMNS)],
        // Fit to width only where the table is wider than the page: Excel
        // ignores the page breaks that keep charts whole on a fitted sheet.
        fit_width: columns as f64 * 8.0 > super::print::PORTRAIT_CHARS,
    }
    .apply(sheet)?;
    Ok(())
}
