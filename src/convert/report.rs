//! What the report needs that only a conversion knows: the settings in
//! force as rows (the run recorded scan by scan for its timeline is
//! [`crate::simulate::Simulator::run_recorded`]).

use crate::provenance::MadeBy;
use crate::settings::Settings;
use crate::table::StepTable;

/// The settings in force, one row each, for the report.
pub fn settings_rows(
    settings: &Settings,
    table: &StepTable,
    made_by: &MadeBy,
) -> Vec<(String, String)> {
    let sim = &settings.simulation;
    let mut rows = vec![
        ("made by".to_string(), made_by.text().to_string()),
        ("target".to_string(), settings.target.name().to_string()),
        (
            "scan time".to_string(),
            crate::cell::duration_text(sim.scan_ms),
        ),
        (
            "designations".to_string(),
            settings.naming.scheme.name().to_string(),
        ),
        (
            "read from the SETTINGS sheet".to_string(),
            crate::provenance::settings_source(settings),
        ),
    ];
    for actuator in &table.actuators {
        let n = actuator.number;
        let stroke = sim.machine.strokes.of(n);
        let valve = sim.machine.valves.of(n, actuator.max_position);
        let (plus, minus) = valve.move_words();
        rows.push((
            format!("C{n}"),
            format!(
                "valve {valve}, {plus} in {}, {minus} in {}",
                crate::cell::duration_text(stroke.extend_ms),
                crate::cell::duration_text(stroke.retract_ms)
            ),
        ));
    }
    rows
}
