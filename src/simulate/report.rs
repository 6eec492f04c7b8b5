//! Text reports of a simulation, as `simulate` prints them.

use super::{SimReport, seconds};

/// The per-step timing of the first cycle as an aligned text table, and a line
/// about the second cycle.
pub fn step_table(report: &SimReport) -> String {
    let mut lines = vec![format!(
        "  {:<6} {:>9} {:>9}  moves",
        "step", "start", "duration"
    )];
    if let Some(cycle) = report.cycles.first() {
        for s in &cycle.steps {
            let mut line = format!(
                "  {:<6} {:>9} {:>9}  {}",
                s.step,
                seconds(s.start_ms),
                seconds(s.duration_ms),
                s.moves
            );
            if !s.notes.is_empty() {
                line.push_str(&format!("  ({})", s.notes));
            }
            lines.push(line);
        }
    }
    match (report.cycles.first(), report.cycles.get(1)) {
        (Some(first), Some(second))
            if first.cycle_ms.is_some() && first.cycle_ms == second.cycle_ms =>
        {
            lines.push(format!(
                "  second START: identical cycle of {}",
                seconds(second.cycle_ms.unwrap_or_default())
            ));
        }
        _ => {}
    }
    for p in &report.problems {
        lines.push(format!("  at {}: {}", seconds(p.time_ms), p.message));
    }
    lines.join("\n")
}
