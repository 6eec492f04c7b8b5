//! Scenarios from the command line in the engines: `simulate --press
//! START@0.5s --press ESTOP@step2 --press RESET@+1s --press START@step0
//! --press STOP@step1` on every bundled sample, converted with `--modes
//! stop,estop,reset`: the written program runs the very events the command
//! prints, for as long as the command runs, scan for scan as simulated, in
//! matiec (iec), awlsim (siemens) and the FST interpreter (festo); and
//! the Beremiz project folders and CODESYS files of the LD and SFC bodies
//! through Beremiz's generator and matiec.

use crate::engines::{self, awlsim};
use crate::helpers::{sample, steptable};
use crate::sfc::{run_beremiz, xsd_valid};
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "scenario::stop_estop_and_reset_run_as_printed_in_every_engine",
        &[Tool::Shared, Tool::Awlsim],
        stop_estop_and_reset_run_as_printed_in_every_engine,
    ),
    Check::new(
        "scenario::stop_estop_and_reset_run_as_printed_in_the_beremiz_projects",
        &[Tool::Shared, Tool::Xmllint, Tool::BeremizPython],
        stop_estop_and_reset_run_as_printed_in_the_beremiz_projects,
    ),
];

/// Every bundled workbook: each machine's halt settings meet the buttons.
const SAMPLES: [&str; 8] = [
    "paper_example",
    "drilling_station",
    "carwash",
    "mixed_valves",
    "oven",
    "press_station",
    "sorting_station",
    "transfer_line",
];

/// START, the EMERGENCY STOP as step 2 starts (the oven has two steps), RESET a
/// second later, START once the machine is home, and STOP as step 1 of
/// that cycle starts: every button of the three modes, mid-cycle, and
/// each machine's STOP as its halt settings make it (at the cycle's end,
/// or at once).
const EVENTS: [(&str, &str); 5] = [
    ("press", "START@0.5s"),
    ("press", "ESTOP@step2"),
    ("press", "RESET@+1s"),
    ("press", "START@step0"),
    ("press", "STOP@step1"),
];

/// Events as `simulate` reads them: (`press`, `STOP@step2`).
type Events<'a> = &'a [(&'a str, &'a str)];

fn stop_estop_and_reset_run_as_printed_in_every_engine() {
    let dir = tempfile::tempdir().unwrap();
    let python = awlsim::python(&tool(Tool::Awlsim));
    let mut compared = 0;
    for name in SAMPLES {
        let input = sample(&format!("{name}.xlsx"));
        let printed = printed_times(&input);
        for &(target, format) in engines_for(name) {
            let args = ["--target", target, "--modes", "stop,estop,reset"];
            let out = dir.path().join(format);
            let (case, report) =
                engines::convert_and_record(&input, &out, name, &args, format, &EVENTS);
            let label = &case.label;
            // The run the engines replay is the one the command printed.
            let happened: Vec<u64> = report.happened.iter().map(|(t, _)| *t).collect();
            assert_eq!(happened, printed, "{label}: the printed event times");
            let outputs = engines::run_written(&case, format, &python);
            case.check(format, outputs).unwrap();
            // What the engineer sees: the emergency stop switches every
            // coil off, RESET homes the machine, and it stands at rest.
            let scans = &case.trace.scans;
            let estop = happened[1];
            let after = scans.iter().position(|s| s.time_ms > estop).unwrap();
            assert!(
                scans[after].outputs.iter().all(|on| !on),
                "{label}: every output off the scan after the EMERGENCY STOP"
            );
            let last = report.samples.last().unwrap();
            assert_eq!(last.step, 0, "{label}: at rest at the end");
            assert!(
                last.positions.iter().all(|p| p.abs() < 0.05),
                "{label}: home at the end: {:?}",
                last.positions
            );
            compared += 1;
        }
    }
    eprintln!(
        "scenario: {compared} runs (every sample x matiec, awlsim, FST interpreter; the oven in awlsim alone) press START, ESTOP, RESET, START and STOP as `simulate` prints them, scan for scan as simulated"
    );
}

/// The engines a sample converts for: every one, but the oven's ADDRESSES
/// sheet pins S7 addresses, so it converts for the siemens target alone.
fn engines_for(name: &str) -> &'static [(&'static str, &'static str)] {
    const EVERY: &[(&str, &str)] = &[("iec", "st"), ("siemens", "awl"), ("festo", "fst")];
    if name == "oven" { &EVERY[1..2] } else { EVERY }
}

/// The LD and SFC bodies under the three modes' buttons, as their Beremiz
/// project folders hold them (`NAME.ld.beremiz/plc.xml`,
/// `NAME.sfc.beremiz/plc.xml`) and as their CODESYS files do (put back
/// together as a Beremiz project by [`codesys_as_beremiz`]): XSD-valid,
/// turned into ST by Beremiz's generator, compiled by matiec and run on the events `simulate` prints,
/// scan for scan as simulated: the EMERGENCY STOP and RESET mid-cycle on
/// the paper's example and the drilling station, then START for a cycle
/// after homing and STOP in it, and the oven's STOP at
/// rest, whose fan runs on 20 s after its coil went off (a TON of the
/// halt logic in the ladder, of `steptable_post` in the chart).
fn stop_estop_and_reset_run_as_printed_in_the_beremiz_projects() {
    let shared = crate::shared();
    let python = tool(Tool::BeremizPython);
    let xmllint = tool(Tool::Xmllint);
    let dir = tempfile::tempdir().unwrap();
    let oven = [("press", "STOP@15s")];
    let runs: [(&str, &str, Events); 3] = [
        ("paper_example", "stop,estop,reset", &EVENTS),
        ("drilling_station", "stop,estop,reset", &EVENTS),
        ("oven", "stop", &oven),
    ];
    let mut compared = 0;
    for (name, modes, events) in runs {
        let input = sample(&format!("{name}.xlsx"));
        // The oven pins its addresses for its own target.
        let targets = crate::helpers::targets_of(&input);
        let target = if targets.contains(&"iec") {
            "iec"
        } else {
            targets[0]
        };
        let args = ["--target", target, "--modes", modes];
        let out = dir.path().join(name);
        let (case, report) = engines::convert_and_record(
            &input,
            &out,
            name,
            &args,
            "beremiz-ld,beremiz-sfc,codesys-ld,codesys-sfc",
            events,
        );
        assert_eq!(report.happened.len(), events.len(), "{}", case.label);
        for body in ["ld", "sfc"] {
            let xml = case.file(&format!(".{body}.beremiz/plc.xml"));
            xsd_valid(&xmllint, &shared, &xml)
                .unwrap_or_else(|e| panic!("{}: {body} project: XSD: {e}", case.label));
            run_beremiz(&python, &shared, &case, &xml, &format!("{body} project"))
                .unwrap_or_else(|e| panic!("{e}"));
            // The CODESYS file of the same body: XSD-valid in the v2.01
            // namespace, and put back together as a Beremiz project, the
            // same run.
            let text = std::fs::read_to_string(case.file(&format!(".{body}.codesys.xml"))).unwrap();
            let interval = format!("T#{}ms", case.trace.scan_ms);
            let xml = out.join(format!("{body}.codesys.as-beremiz.xml"));
            let swapped = out.join(format!("{body}.codesys.v201.xml"));
            std::fs::write(&swapped, text.replace("tc6_0200", "tc6_0201")).unwrap();
            xsd_valid(&xmllint, &shared, &swapped)
                .unwrap_or_else(|e| panic!("{}: {body} CODESYS: XSD: {e}", case.label));
            std::fs::write(&xml, codesys_as_beremiz(&text, &interval).unwrap()).unwrap();
            run_beremiz(&python, &shared, &case, &xml, &format!("{body} CODESYS"))
                .unwrap_or_else(|e| panic!("{e}"));
            compared += 2;
        }
    }
    eprintln!(
        "scenario: {compared} Beremiz projects and CODESYS files (LD and SFC; paper example and drilling station pressing ESTOP and RESET mid-cycle, START after homing and STOP in that cycle, the oven's STOP and fan run-on) XSD-valid, generated by Beremiz, run in matiec, scan for scan as simulated"
    );
}

/// The times `simulate` prints for the three events, in seconds as
/// printed, read back as milliseconds.
fn printed_times(input: &std::path::Path) -> Vec<u64> {
    let mut command = steptable();
    command
        .arg("simulate")
        .arg(input)
        .args(["--modes", "stop,estop,reset"]);
    for (option, text) in EVENTS {
        command.arg(format!("--{option}")).arg(text);
    }
    let out = command.assert().success().get_output().stdout.clone();
    let out = String::from_utf8(out).unwrap();
    EVENTS
        .iter()
        .map(|(option, text)| {
            let line = out
                .lines()
                .find(|l| l.contains(&format!("--{option} {text}:")))
                .unwrap_or_else(|| panic!("{text} printed: {out}"));
            let seconds: f64 = line.split_whitespace().next().unwrap().parse().unwrap();
            (seconds * 1000.0).round() as u64
        })
        .collect()
}

/// A CODESYS file of a graphical body (`NAME.sfc.codesys.xml`) put back
/// together as a Beremiz project holds it: its POUs as they are, the
/// variables of its global variable lists (`GVL_IO`, `GVL_steptable`) as
/// the resource's globals, and its task's calls, in their order, as the
/// resource's task at the scan time `interval` (`T#10ms`). What runs is
/// then the file's own POUs, variables and call order; what CODESYS itself
/// makes of the chart is not checked (no CODESYS runs here).
pub(crate) fn codesys_as_beremiz(text: &str, interval: &str) -> Result<String, String> {
    let between = |text: &'_ str, from: &str, to: &str| -> Result<String, String> {
        let (_, rest) = text
            .split_once(from)
            .ok_or_else(|| format!("no {from} in the CODESYS file"))?;
        let (inner, _) = rest
            .split_once(to)
            .ok_or_else(|| format!("no {to} after {from} in the CODESYS file"))?;
        Ok(inner.to_string())
    };
    let head = between(text, "", "<instances>")?.replace("tc6_0200", "tc6_0201");
    let task = between(text, "<task ", "</task>")?;
    let calls: Vec<String> = task
        .split("<pouInstance name=\"")
        .skip(1)
        .filter_map(|rest| rest.split('"').next())
        .enumerate()
        .map(|(i, pou)| format!("<pouInstance name=\"call{i}\" typeName=\"{pou}\"/>"))
        .collect();
    let mut globals = String::new();
    for list in ["GVL_IO", "GVL_steptable"] {
        let vars = between(text, &format!("<globalVars name=\"{list}\">"), "<addData>")?;
        globals.push_str(&vars);
    }
    let configuration = between(text, "<configuration name=\"", "\"")?;
    Ok(format!(
        "{head}<instances><configurations><configuration name=\"{configuration}\"><resource name=\"Res0\"><task name=\"task0\" priority=\"0\" interval=\"{interval}\">{}</task><globalVars>{globals}</globalVars></resource></configuration></configurations></instances></project>\n",
        calls.join("")
    ))
}
