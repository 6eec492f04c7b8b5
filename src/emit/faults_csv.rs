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
    writer.write_record([
        "fault",
        "signals",
        "stuck_at",
        "outcome",
        "appears",
        "detected",
        "step",
        "explanation",
    ])?;
    for c in &table.cases {
        let signals: Vec<String> = c.faults.iter().map(|f| name(f.signal)).collect();
        let stuck: Vec<&str> = c
            .faults
            .iter()
            .map(|f| if f.stuck_at { "1" } else { "0" })
            .collect();
        writer.write_record([
            c.fault_text_as(name),
            signals.join("+"),
            stuck.join("+"),
            c.outcome.label().to_string(),
            c.appears(table.moments.len()),
            c.detected_text().to_string(),
            c.step.map(|s| s.to_string()).unwrap_or_default(),
            text(&c.explanation),
        ])?;
    }
    writer
        .into_inner()
        .map_err(|e| csv::Error::from(std::io::Error::other(e.to_string())))
}
