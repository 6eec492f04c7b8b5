//! `de-energise on halt` in the engines: a heated table whose x11 dies, so
//! that the watchdog halts the machine and the HALT rung switches the
//! heater off, runs in matiec (iec), awlsim (siemens) and the FST
//! interpreter (festo) as simulated, scan for scan, through the halt.

use steptable::convert;
use steptable::program::Signal;
use steptable::simulate::Fault;

use crate::engines::{self, awlsim, fst, matiec};
use crate::helpers::{steptable, write_xlsx_sheets};
use crate::{Check, Tool, shared, tool};

pub const CHECKS: &[Check] = &[Check::new(
    "halt::a_halt_switches_the_heater_off_in_every_engine",
    &[Tool::Shared, Tool::Awlsim],
    a_halt_switches_the_heater_off_in_every_engine,
)];

fn a_halt_switches_the_heater_off_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("heated.xlsx");
    let table: &[&[&str]] = &[&["C1+1; Y:heater+"], &["C1-0; Y:heater-"]];
    let settings: &[&[&str]] = &[&["de-energise on halt", "heater"]];
    write_xlsx_sheets(&input, &[("TABLE", table), ("SETTINGS", settings)]);
    let python = awlsim::python(&tool(Tool::Awlsim));
    for (target, format) in [("iec", "st"), ("siemens", "awl"), ("festo", "fst")] {
        let args = [
            "--target",
            target,
            "--safety",
            "watchdog",
            "--formats",
            format,
        ];
        let out = dir.path().join(target);
        steptable()
            .arg("convert")
            .arg(&input)
            .args(args)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        let mut checked =
            convert::check_path(&input, &engines::settings_for(&args)).expect("valid table");
        let x11 = Signal::Sensor {
            actuator: 1,
            position: 1,
        };
        checked.settings.simulation.faults = vec![Fault {
            signal: x11,
            stuck_at: false,
        }];
        let label = format!("heated.xlsx {} with x11 dead", args.join(" "));
        let (case, report) = engines::record_run(
            &label,
            out.join("heated"),
            "heated",
            &checked.table,
            &checked.settings,
        );
        assert!(
            report.verdict().contains("alarm_wd"),
            "{label}: {}",
            report.verdict()
        );
        // The heater came on with step 1 and the halt switched it off.
        let heater = case
            .trace
            .signals
            .outputs
            .iter()
            .position(|s| s.symbol() == "heater")
            .expect("the heater is an output");
        let column: Vec<bool> = case.trace.scans.iter().map(|s| s.outputs[heater]).collect();
        assert!(column.contains(&true), "{label}");
        assert_eq!(column.last(), Some(&false), "{label}");
        let outputs = match format {
            "st" => matiec::run(&shared(), &case.file(".st"), &case.trace, &case.allocation),
            "awl" => awlsim::run(
                &python,
                &case.file(".awl"),
                case.mnemonic,
                &case.trace,
                &case.allocation,
            ),
            _ => {
                let text = std::fs::read_to_string(case.file(".fst.txt")).unwrap();
                fst::run(&text, &case.trace, &case.festo)
            }
        };
        case.check(format, outputs).unwrap();
    }
    eprintln!(
        "halt: matiec, awlsim and the FST interpreter switch the heater off on the halt as simulated"
    );
}
