//! The fault table as CSV (`NAME.faults.csv`), written by `convert` and
//! `faults` alike.

use crate::faults::FaultTable;
use crate::program::Signal;

/// `NAME.faults.csv`: `fault,signals,stuck_at,outcome,appears,detected,step,explanation`,
/// one row per case (pairs have both signals joined with `+`); `appears`
/// is the first moment of the cycle at which the fault gives its outcome,
/// `detected` is `alarm` when an alarm output came on in that run. Each
/// signal is called as `name` says (its designation in the symbol table),
/// in the explanation too (`text` turns the paper's symbols into those).
pub fn render(
    table: &FaultTable,
    name: &dyn Fn(Signal) -> String,
    text: &dyn Fn(&str) -> String,
) -> Result<Vec<u8>, csv::Error> {
    let mut writer = csv::Writer::from_writer(Vec::new());
    writer.write_record(COLUMNS)?;
    for row in rows(table, name, text) {
        writer.write_record(&row)?;
    }
    writer
        .into_inner()
        .map_err(|e| csv::Error::from(std::io::Error::other(e.to_string())))
}

/// The header row.
pub const COLUMNS: [&str; 8] = [
    "fault",
    "signals",
    "stuck_at",
    "outcome",
    "appears",
    "detected",
    "step",
    "explanation",
];

/// Every case as the cells of its row, in the table's order: the CSV and
/// the report's fault table are these rows.
pub fn rows(
    table: &FaultTable,
    name: &dyn Fn(Signal) -> String,
    text: &dyn Fn(&str) -> String,
) -> Vec<[String; 8]> {
    // The workbook's six columns, with the signals and their stuck values
    // after the fault.
    crate::faults::rows(table, name, text)
        .into_iter()
        .zip(&table.cases)
        .map(
            |([fault, outcome, appears, detected, step, explanation], c)| {
                let signals: Vec<String> = c.faults.iter().map(|f| name(f.signal)).collect();
                let stuck: Vec<&str> = c
                    .faults
                    .iter()
                    .map(|f| if f.stuck_at { "1" } else { "0" })
                    .collect();
                [
                    fault,
                    signals.join("+"),
                    stuck.join("+"),
                    outcome,
                    appears,
                    detected,
                    step,
                    explanation,
                ]
            },
        )
        .collect()
}
