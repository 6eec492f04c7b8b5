//! The outputs rendered beside the fault analysis: those that need no
//! fault table at once (with the report's page up to its fault table), the
//! others as soon as it is done, and the report's fault table once the
//! mitigations of its hazards are verified.

use super::{Failure, Settings};
use crate::emit::{self, EmitInput, OutputKind};
use crate::faults;

/// Renders the outputs that need no fault table at once and, beside them,
/// runs the fault analysis and then renders the outputs that show it;
/// every file in the order of its kind.
pub(super) fn render_beside_faults(
    input: EmitInput,
    early: Vec<OutputKind>,
    late: Vec<OutputKind>,
    settings: &Settings,
    progress: &(dyn Fn(usize, usize) + Sync),
    healthy: Option<faults::Healthy>,
) -> Result<(Vec<emit::OutputFile>, Option<faults::FaultTable>), Failure> {
    let (table, program) = (input.table, input.program);
    // The mitigations' trial programs are expected to run healthy as this
    // one does: a copy of its run is their yardstick.
    let wants_report = late.contains(&OutputKind::Report);
    let expected = healthy.as_ref().filter(|_| wants_report).cloned();
    let ((fault_table, late), early) = rayon::join(
        || {
            let fault_table = (!late.is_empty()).then(|| {
                faults::analyse_from(
                    table,
                    program,
                    &settings.simulation,
                    1,
                    faults::FaultRuns::Resumed,
                    progress,
                    healthy,
                )
            });
            // The report names, per hazard, what catches it: verified by
            // running the hazards again under each check the program lacks,
            // most of the report's cost on a long line. The report alone
            // waits for that: the other outputs that show the fault table
            // render beside it.
            let (report, others): (Vec<OutputKind>, Vec<OutputKind>) =
                late.into_iter().partition(|k| *k == OutputKind::Report);
            let shown = EmitInput {
                faults: fault_table.as_ref(),
                ..input
            };
            let (mitigations, others) = rayon::join(
                || {
                    fault_table
                        .as_ref()
                        .filter(|_| !report.is_empty())
                        .map(|f| {
                            faults::mitigation::mitigations(
                                table,
                                &settings.program,
                                &settings.simulation,
                                f,
                                expected.as_ref(),
                                &|p| super::allocate(p, settings, &table.file).is_ok(),
                            )
                        })
                },
                || emit::render_each(others, shown),
            );
            let report = emit::render_each(
                report,
                EmitInput {
                    mitigations: mitigations.as_deref(),
                    ..shown
                },
            );
            let late = others.and_then(|mut others| {
                others.extend(report?);
                Ok(others)
            });
            (fault_table, late)
        },
        || {
            // The report's page up to its fault table needs no fault
            // analysis: drawn here, the report then waits for the
            // mitigations alone.
            if wants_report {
                let _ = input.report_head();
            }
            emit::render_each(early, input)
        },
    );
    let emitted = |e| match e {
        emit::EmitError::Template(e) => Failure::Template(e),
        emit::EmitError::Internal(why) => Failure::Internal(why),
    };
    let mut kinds = early.map_err(emitted)?;
    kinds.extend(late.map_err(emitted)?);
    kinds.sort_by_key(|(kind, _)| *kind);
    let files = kinds.into_iter().flat_map(|(_, files)| files).collect();
    Ok((files, fault_table))
}
