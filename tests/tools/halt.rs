//! What the machine does when it must stop or may not start, in the
//! engines: `de-energise on halt` (a heated table whose x11 dies, so that
//! the watchdog halts the machine and the HALT rung switches the heater
//! off), a `start permissive` (air fails at rest, the next START starts
//! nothing) and an `interlock` (the guard opens mid-travel: halt, alarm,
//! heater off) run in matiec (iec), awlsim (siemens) and the FST
//! interpreter (festo) as simulated, scan for scan.

use steptable::convert;
use steptable::program::Signal;
use steptable::simulate::Fault;

use crate::engines::{self, awlsim};
use crate::helpers::{steptable, write_xlsx_sheets};
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "halt::a_halt_switches_the_heater_off_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        a_halt_switches_the_heater_off_in_every_engine,
    ),
    Check::new(
        "halt::an_interlock_over_a_step_range_waits_for_its_steps_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        an_interlock_over_a_step_range_waits_for_its_steps_in_every_engine,
    ),
    Check::new(
        "halt::a_halt_lets_the_fan_run_on_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        a_halt_lets_the_fan_run_on_in_every_engine,
    ),
    Check::new(
        "halt::a_start_permissive_holds_the_next_cycle_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        a_start_permissive_holds_the_next_cycle_in_every_engine,
    ),
    Check::new(
        "halt::an_open_interlock_halts_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        an_open_interlock_halts_in_every_engine,
    ),
    Check::new(
        "halt::the_oven_stops_its_coil_at_once_and_its_fan_after_20s_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        the_oven_stops_its_coil_at_once_and_its_fan_after_20s_in_every_engine,
    ),
    Check::new(
        "halt::an_emergency_stop_keeps_the_gripper_holding_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        an_emergency_stop_keeps_the_gripper_holding_in_every_engine,
    ),
];

/// The bundled oven (Aly 2008): START sounds the horn for 10 s, then the
/// coil and the fan come on and stay on; STOP pressed at rest after the
/// cycle (`on stop | coil off, fan off after 20s`) switches the coil off in
/// that scan and the fan 20 s later, in matiec, awlsim and the FST
/// interpreter as simulated. Its addresses are the paper's Table 3.
fn the_oven_stops_its_coil_at_once_and_its_fan_after_20s_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let input = crate::helpers::sample("oven.xlsx");
    let stop = Fault {
        signal: Signal::Stop,
        stuck_at: false,
    };
    for case in run_everywhere(dir.path(), &input, &["--modes", "stop"], stop, None) {
        // The times at which an output turns to `on`.
        let times = |symbol: &str, on: bool| -> Vec<u64> {
            let values = column(&case, symbol);
            (1..values.len())
                .filter(|&i| values[i - 1] != on && values[i] == on)
                .map(|i| case.trace.scans[i].time_ms)
                .collect()
        };
        let label = &case.label;
        let (horn_on, horn_off) = (times("horn", true), times("horn", false));
        assert_eq!(
            horn_off[0] - horn_on[0],
            10_000,
            "{label}: the horn sounds 10 s"
        );
        assert_eq!(times("coil", true), horn_off[..1], "{label}");
        assert_eq!(times("fan", true), horn_off[..1], "{label}");
        let (coil_off, fan_off) = (times("coil", false), times("fan", false));
        assert_eq!((coil_off.len(), fan_off.len()), (1, 1), "{label}");
        let run_on = fan_off[0] - coil_off[0];
        assert!(
            (20_000..=20_000 + 2 * case.trace.scan_ms as u64).contains(&run_on),
            "{label}: the fan ran on {run_on} ms after the coil went off"
        );
        let pinned: Vec<String> = case
            .allocation
            .inputs
            .iter()
            .chain(&case.allocation.outputs)
            .map(|a| format!("{} {}", a.signal.symbol(), a.address.display(case.mnemonic)))
            .collect();
        assert_eq!(
            pinned,
            [
                "START I0.0",
                "STOP I0.1",
                "horn Q0.0",
                "coil Q0.1",
                "fan Q0.2"
            ],
            "{label}: the paper's Table 3"
        );
    }
    eprintln!(
        "oven: matiec, awlsim and the FST interpreter sound the horn 10 s, and after STOP switch the coil off at once and the fan 20 s later, as simulated"
    );
}

/// `hold on estop | vacuum`: the emergency stop's wire breaks while C1
/// travels out with the vacuum on; every coil goes off but the vacuum
/// stays on, in every engine as simulated.
fn an_emergency_stop_keeps_the_gripper_holding_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("gripper.xlsx");
    let table: &[&[&str]] = &[&["C1+1; Y:vacuum+"], &["C1-0; Y:vacuum-"]];
    let settings: &[&[&str]] = &[&["hold on estop", "vacuum"]];
    write_xlsx_sheets(&input, &[("TABLE", table), ("SETTINGS", settings)]);
    let estop = Fault {
        signal: Signal::EStop,
        stuck_at: false,
    };
    let modes = ["--modes", "estop,reset"];
    for case in run_everywhere(dir.path(), &input, &modes, estop, Some(900)) {
        let column = |symbol: &str| column(&case, symbol).into_iter();
        assert_eq!(column("vacuum").next_back(), Some(true), "{}", case.label);
        assert_eq!(column("y1+").next_back(), Some(false), "{}", case.label);
        assert!(column("y1+").any(|on| on), "{}", case.label);
    }
    eprintln!(
        "estop: matiec, awlsim and the FST interpreter keep the vacuum on through the emergency stop as simulated"
    );
}

/// `interlock | guard_closed` with `de-energise on halt | heater`: the
/// guard opens while C1 travels out with the heater on; the machine halts,
/// `alarm_il` comes on and the heater goes off, in every engine as
/// simulated.
fn an_open_interlock_halts_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("guarded.xlsx");
    let settings: &[&[&str]] = &[
        &["interlock", "guard_closed"],
        &["de-energise on halt", "heater"],
    ];
    write_xlsx_sheets(&input, &[("TABLE", HEATED), ("SETTINGS", settings)]);
    // START is pressed at 500 ms; C1 takes a second to travel out.
    for case in run_everywhere(dir.path(), &input, &[], guard_open(), Some(900)) {
        let alarm = column(&case, "alarm_il");
        assert_eq!(alarm.last(), Some(&true), "{}", case.label);
        let column = heater_column(&case);
        assert!(column.contains(&true), "{}", case.label);
        assert_eq!(column.last(), Some(&false), "{}", case.label);
    }
    eprintln!(
        "interlock: matiec, awlsim and the FST interpreter halt and raise alarm_il as simulated"
    );
}

/// `interlock | guard_closed in step 2`: the guard opens while C1 travels
/// out in step 1; the machine halts only once step 2 has fired, in every
/// engine as simulated.
fn an_interlock_over_a_step_range_waits_for_its_steps_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("zoned.xlsx");
    let settings: &[&[&str]] = &[&["interlock", "guard_closed in step 2"]];
    write_xlsx_sheets(&input, &[("TABLE", HEATED), ("SETTINGS", settings)]);
    // START at 500 ms, C1 out a second later: step 2 would fire at about
    // 1.5 s. The guard opens at 900 ms, outside the zone: no halt, no
    // alarm, and step 2 does not start its move behind the open guard.
    for case in run_everywhere(dir.path(), &input, &[], guard_open(), Some(900)) {
        assert!(
            column(&case, "y1+").iter().any(|on| *on),
            "{}: step 1 ran",
            case.label
        );
        assert!(
            !column(&case, "alarm_il").iter().any(|on| *on),
            "{}",
            case.label
        );
        assert!(
            !column(&case, "y1-").iter().any(|on| *on),
            "{}: step 2 fired",
            case.label
        );
    }
    eprintln!(
        "interlock zone: matiec, awlsim and the FST interpreter do not fire the zone's step behind an open guard, and do not halt outside the zone, as simulated"
    );
}

/// The guard door's switch breaks (reads open).
fn guard_open() -> Fault {
    Fault {
        signal: Signal::MachineInput(steptable::cell::Name::new("guard_closed").unwrap()),
        stuck_at: false,
    }
}

/// C1's out sensor dies: the watchdog halts the machine.
const X11_DEAD: Fault = Fault {
    signal: Signal::Sensor {
        actuator: 1,
        position: 1,
    },
    stuck_at: false,
};

/// C1 carries a part under a heater that is on while C1 is out.
const HEATED: &[&[&str]] = &[&["C1+1; Y:heater+"], &["C1-0; Y:heater-"]];

fn a_halt_switches_the_heater_off_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("heated.xlsx");
    let settings: &[&[&str]] = &[&["de-energise on halt", "heater"]];
    write_xlsx_sheets(&input, &[("TABLE", HEATED), ("SETTINGS", settings)]);
    for case in run_everywhere(
        dir.path(),
        &input,
        &["--safety", "watchdog"],
        X11_DEAD,
        Some(0),
    ) {
        // The heater came on with step 1 and the halt switched it off.
        let column = heater_column(&case);
        assert!(column.contains(&true), "{}", case.label);
        assert_eq!(column.last(), Some(&false), "{}", case.label);
    }
    eprintln!(
        "halt: matiec, awlsim and the FST interpreter switch the heater off on the halt as simulated"
    );
}

/// `on halt | heater off, fan off after 2s`: the watchdog halts a machine
/// whose x11 died; the heater goes off in that scan, the fan 2 s later, in
/// every engine as simulated.
fn a_halt_lets_the_fan_run_on_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("cooled.xlsx");
    let table: &[&[&str]] = &[&["C1+1; Y:heater+; Y:fan+"], &["C1-0; Y:heater-; Y:fan-"]];
    let settings: &[&[&str]] = &[&["on halt", "heater off, fan off after 2s"]];
    write_xlsx_sheets(&input, &[("TABLE", table), ("SETTINGS", settings)]);
    for case in run_everywhere(
        dir.path(),
        &input,
        &["--safety", "watchdog"],
        X11_DEAD,
        Some(0),
    ) {
        let off_at = |symbol: &str| {
            let last_on = column(&case, symbol)
                .iter()
                .rposition(|on| *on)
                .expect("came on");
            case.trace.scans.get(last_on + 1).map(|s| s.time_ms)
        };
        let (heater, fan) = (off_at("heater"), off_at("fan"));
        let (Some(heater), Some(fan)) = (heater, fan) else {
            panic!("{}: heater off at {heater:?}, fan at {fan:?}", case.label);
        };
        assert!(
            (2_000..=2_020).contains(&(fan - heater)),
            "{}: the fan ran on {} ms",
            case.label,
            fan - heater
        );
    }
    eprintln!(
        "halt run-on: matiec, awlsim and the FST interpreter switch the heater off on the halt and the fan 2 s later, as simulated"
    );
}

/// `start permissive | air_ok`: air fails at rest after the first cycle, so
/// the second START starts nothing; every engine agrees, scan for scan.
fn a_start_permissive_holds_the_next_cycle_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join("aired.xlsx");
    let settings: &[&[&str]] = &[&["start permissive", "air_ok"]];
    write_xlsx_sheets(&input, &[("TABLE", HEATED), ("SETTINGS", settings)]);
    let air = Fault {
        signal: Signal::MachineInput(steptable::cell::Name::new("air_ok").unwrap()),
        stuck_at: false,
    };
    for case in run_everywhere(dir.path(), &input, &[], air, None) {
        // One cycle: the heater came on once, and never again.
        let rises = heater_column(&case)
            .windows(2)
            .filter(|w| !w[0] && w[1])
            .count();
        assert_eq!(rises, 1, "{}", case.label);
    }
    eprintln!(
        "permissive: matiec, awlsim and the FST interpreter hold the second cycle as simulated"
    );
}

/// The heater's value at every recorded scan.
fn heater_column(case: &engines::Case) -> Vec<bool> {
    column(case, "heater")
}

/// An output's value at every recorded scan.
fn column(case: &engines::Case, symbol: &str) -> Vec<bool> {
    let at = case
        .trace
        .signals
        .outputs
        .iter()
        .position(|s| s.symbol() == symbol)
        .unwrap_or_else(|| panic!("{symbol} is an output"));
    case.trace.scans.iter().map(|s| s.outputs[at]).collect()
}

/// Converts `input` for each target into `dir/<target>`, simulates it with
/// `fault` appearing at `onset_ms` (by default at rest after the first
/// cycle, as the fault analysis has it), and runs the written file in its
/// engine: the outputs must equal the simulation's at every scan.
fn run_everywhere(
    dir: &std::path::Path,
    input: &std::path::Path,
    extra: &[&str],
    fault: Fault,
    onset_ms: Option<u64>,
) -> Vec<engines::Case> {
    let python = awlsim::python(&tool(Tool::Awlsim));
    let mut cases = Vec::new();
    // A table that pins its addresses is converted for its own target,
    // whose outputs hold every language.
    let pinned = crate::helpers::targets_of(input);
    for (target, format) in [("iec", "st"), ("siemens", "awl"), ("festo", "fst")] {
        let target = if pinned.len() == 1 { pinned[0] } else { target };
        let mut args = vec!["--target", target];
        args.extend_from_slice(extra);
        args.extend(["--formats", format]);
        let out = dir.join(format);
        steptable()
            .arg("convert")
            .arg(input)
            .args(&args)
            .arg("-o")
            .arg(&out)
            .assert()
            .success();
        let mut checked =
            convert::check_path(input, &engines::settings_for(&args)).expect("valid table");
        let onset = onset_ms.unwrap_or_else(|| {
            let program = convert::build_program(&checked.table, &checked.settings);
            let healthy = steptable::simulate::simulate(
                &checked.table,
                &program,
                &checked.settings.simulation,
            );
            let scan = checked.settings.simulation.scan_ms as u64;
            let moments = steptable::faults::moments(&healthy, &checked.table, scan);
            let rest = moments.last().expect("a moment");
            assert_eq!(rest.phase, steptable::faults::Phase::AtRest);
            rest.at_ms
        });
        checked.settings.simulation.faults = vec![fault];
        checked.settings.simulation.fault_onset_ms = onset;
        let name = convert::output_name(input);
        let label = format!("{name} {} with {}", args.join(" "), fault.describe());
        let (case, _) = engines::record_run(
            &label,
            out.join(&name),
            &name,
            &checked.table,
            &checked.settings,
        );
        let outputs = engines::run_written(&case, format, &python);
        case.check(format, outputs).unwrap();
        cases.push(case);
    }
    cases
}
