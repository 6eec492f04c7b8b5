//! What the report needs that only a conversion knows: the run recorded
//! scan by scan (the timeline), and the settings in force as rows.

use crate::program::StepProgram;
use crate::provenance::MadeBy;
use crate::settings::Settings;
use crate::simulate::io::{IoSignals, IoTrace};
use crate::simulate::{SimReport, SimSettings, Simulator};
use crate::table::StepTable;

/// The healthy run, recorded: runs the program as
/// [`crate::simulate::simulate`] does and also keeps every input, output
/// and the active step at every scan, and the positions.
pub fn recorded_run(
    table: &StepTable,
    program: &StepProgram,
    sim: &SimSettings,
    signals: IoSignals,
) -> (SimReport, IoTrace) {
    let sim = SimSettings {
        record_trace: true,
        ..sim.clone()
    };
    Simulator::new(table, program).run_recording(&sim, signals)
}

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
        rows.push((
            format!("C{n}"),
            format!(
                "valve {}, extends in {}, retracts in {}",
                sim.machine.valves.of(n, actuator.max_position),
                crate::cell::duration_text(stroke.extend_ms),
                crate::cell::duration_text(stroke.retract_ms)
            ),
        ));
    }
    rows
}
