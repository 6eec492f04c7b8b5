//! Snapshots of every generated text file, for every sample and target. A
//! change to any output shows up as a reviewable diff (`cargo insta review`).

use steptable::address::{Mnemonic, Target};
use steptable::convert::convert_path;
use steptable::settings::Settings;

use crate::helpers::samples;

/// Every text output, by the end of its name.
const TEXT_OUTPUTS: [&str; 13] = [
    ".st",
    ".fst.txt",
    ".io.csv",
    ".plcopen.xml",
    ".codesys.xml",
    ".gvl.txt",
    ".awl",
    ".sdf",
    ".fst-alloc.csv",
    ".rockwell.csv",
    ".exp",
    ".scl",
    ".L5X",
];

#[test]
fn every_sample_and_target() {
    for path in samples() {
        let targets = crate::helpers::targets_of(&path);
        for (target, mnemonic, label) in [
            (Target::Festo, Mnemonic::En, "festo"),
            (Target::Iec, Mnemonic::En, "iec"),
            (Target::Siemens, Mnemonic::En, "siemens"),
            (Target::Siemens, Mnemonic::De, "siemens-de"),
        ] {
            if !targets.contains(&target.name()) {
                continue;
            }
            let mut settings = Settings::new();
            settings.target = target;
            settings.mnemonic = mnemonic;
            let conversion = match convert_path(&path, &settings) {
                Ok(c) => c,
                Err(e) => panic!("{}: {e:?}", path.display()),
            };
            let file = path
                .file_name()
                .unwrap()
                .to_string_lossy()
                .replace('.', "_");
            for output in &conversion.files {
                let Some(ext) = TEXT_OUTPUTS.into_iter().find(|e| output.name.ends_with(e)) else {
                    continue;
                };
                // FST files always use Festo operands: one snapshot is enough.
                // The exports for other tools: Festo and German Siemens.
                let festo_only = [".fst.txt", ".fst-alloc.csv"].contains(&ext);
                let export = ![".st", ".fst.txt", ".io.csv"].contains(&ext);
                if (festo_only && label != targets[0])
                    || (export && !["festo", "siemens-de"].contains(&label))
                {
                    continue;
                }
                let text = String::from_utf8(output.bytes.clone()).expect("text output");
                insta::assert_snapshot!(format!("{file}-{label}{ext}"), text);
            }
        }
    }
}

/// The programs with every safety check, for the Festo and IEC targets.
#[test]
fn every_sample_with_all_safety_checks() {
    for path in samples() {
        let targets = crate::helpers::targets_of(&path);
        for (target, label) in [
            (Target::Festo, "festo"),
            (Target::Iec, "iec"),
            (Target::Siemens, "siemens"),
        ] {
            // Siemens for the samples that pin its addresses only.
            if !targets.contains(&label) || (targets.len() > 1 && label == "siemens") {
                continue;
            }
            let mut settings = Settings::new();
            settings.target = target;
            settings.program.safety = steptable::program::Safety::all();
            let conversion = match convert_path(&path, &settings) {
                Ok(c) => c,
                Err(e) => panic!("{}: {e:?}", path.display()),
            };
            let file = path
                .file_name()
                .unwrap()
                .to_string_lossy()
                .replace('.', "_");
            for output in &conversion.files {
                let Some(ext) = [".st", ".fst.txt", ".io.csv"]
                    .into_iter()
                    .find(|e| output.name.ends_with(e))
                else {
                    continue;
                };
                if ext == ".fst.txt" && label != targets[0] {
                    continue;
                }
                let text = String::from_utf8(output.bytes.clone()).expect("text output");
                insta::assert_snapshot!(format!("{file}-{label}-safety{ext}"), text);
            }
        }
    }
}

/// The programs with every operating mode (STOP, EMERGENCY STOP, RESET with
/// homing, continuous operation), in every language that carries them.
#[test]
fn paper_and_press_station_with_every_operating_mode() {
    for name in ["paper_example.xlsx", "press_station.xlsx"] {
        let path = crate::helpers::sample(name);
        let mut settings = Settings::new();
        settings.program.modes = steptable::program::Modes::parse("all").unwrap();
        let conversion = match convert_path(&path, &settings) {
            Ok(c) => c,
            Err(e) => panic!("{}: {e:?}", path.display()),
        };
        let file = name.replace('.', "_");
        for output in &conversion.files {
            let Some(ext) = [".st", ".fst.txt", ".awl", ".io.csv", ".scl", ".L5X"]
                .into_iter()
                .find(|e| output.name.ends_with(e))
            else {
                continue;
            };
            let text = String::from_utf8(output.bytes.clone()).expect("text output");
            insta::assert_snapshot!(format!("{file}-modes{ext}"), text);
        }
    }
}

/// Single step (`--modes step`): the STEP_MODE and STEP_PB inputs, the
/// `step_ok` permit in every table step's condition, and its rungs, in the
/// program model and in ST, FST and AWL.
#[test]
fn paper_in_single_step() {
    let path = crate::helpers::sample("paper_example.xlsx");
    let mut settings = Settings::new();
    settings.program.modes = steptable::program::Modes::parse("step").unwrap();
    let conversion = convert_path(&path, &settings).expect("sample converts");
    insta::assert_snapshot!(
        "paper_example_xlsx-step.program",
        program_text(&conversion.program)
    );
    for output in &conversion.files {
        let Some(ext) = [".st", ".fst.txt", ".awl"]
            .into_iter()
            .find(|e| output.name.ends_with(e))
        else {
            continue;
        };
        let text = String::from_utf8(output.bytes.clone()).expect("text output");
        insta::assert_snapshot!(format!("paper_example_xlsx-step{ext}"), text);
    }
}

/// The paper's example with the criteria analysis (`--safety criteria`,
/// and step 2 supervised 2.5 s): the awaited memories each transition
/// moves, the rungs that light the `miss` outputs, in the program model
/// and in ST, FST, AWL, SCL and the I/O list.
#[test]
fn paper_with_criteria_analysis() {
    let path = crate::helpers::sample("paper_example.xlsx");
    let mut settings = Settings::new();
    settings.program.safety = "criteria".parse().unwrap();
    settings.program.supervision = [(2, 2_500)].into();
    let conversion = convert_path(&path, &settings).expect("sample converts");
    insta::assert_snapshot!(
        "paper_example_xlsx-criteria.program",
        program_text(&conversion.program)
    );
    for output in &conversion.files {
        let Some(ext) = [".st", ".fst.txt", ".awl", ".scl", ".io.csv"]
            .into_iter()
            .find(|e| output.name.ends_with(e))
        else {
            continue;
        };
        let text = String::from_utf8(output.bytes.clone()).expect("text output");
        insta::assert_snapshot!(format!("paper_example_xlsx-criteria{ext}"), text);
    }
}

/// The step program itself, in the paper's notation: the one model every
/// output is rendered from. A change in it shows here before it shows in
/// eleven output files.
fn program_text(program: &steptable::program::StepProgram) -> String {
    use steptable::program::{Signal, paper_sentence};
    let mut lines = Vec::new();
    let init: Vec<String> = program
        .init
        .iter()
        .map(|a| format!("{} {}", a.verb(), a.signal().symbol()))
        .collect();
    let none = |list: Vec<String>| {
        if list.is_empty() {
            "(none)".to_string()
        } else {
            list.join(", ")
        }
    };
    lines.push(format!("INIT {}", none(init)));
    for step in &program.steps {
        lines.push(format!(
            "STEP {} ({}): {}",
            step.number,
            step.title,
            paper_sentence(&step.condition, &step.actions, Signal::symbol)
        ));
    }
    for rung in &program.rungs {
        lines.push(format!(
            "RUNG {}: {}",
            rung.kind.label(),
            paper_sentence(&rung.condition, &rung.actions, Signal::symbol)
        ));
    }
    let timers: Vec<String> = program.timers.iter().map(|t| t.symbol()).collect();
    lines.push(format!("TIMERS {}", none(timers)));
    lines.join("\n") + "\n"
}

#[test]
fn step_programs_and_template_contexts() {
    use steptable::emit::{self, EmitInput};
    for (name, modes, safety) in [
        ("paper_example.xlsx", "none", "none"),
        ("paper_example.xlsx", "all", "all"),
        ("press_station.xlsx", "all", "none"),
        ("mixed_valves.xlsx", "none", "all"),
    ] {
        let path = crate::helpers::sample(name);
        let mut settings = Settings::new();
        settings.program.modes = modes.parse().unwrap();
        settings.program.safety = safety.parse().unwrap();
        let c = convert_path(&path, &settings).expect("sample converts");
        let label = format!("{}-modes-{modes}-safety-{safety}", name.replace('.', "_"));
        insta::assert_snapshot!(format!("{label}.program"), program_text(&c.program));

        // What the templates see: the IEC and STEP 7 models, as JSON.
        let festo = steptable::address::Allocation::new(&c.program, Target::Festo, Mnemonic::En);
        let input = EmitInput {
            name: &c.name,
            table: &c.table,
            allocation: &c.allocation,
            festo: &festo,
            program: &c.program,
            symbols: &c.symbols,
            simulation: Some(&c.simulation),
            faults: c.faults.as_ref(),
            mitigations: None,
            io_trace: None,
            settings: &[],
            templates: &settings.templates,
            scan_ms: settings.simulation.scan_ms,
            diagram: settings.diagram,
            pictures: None,
        };
        let iec = emit::st::model(&input, settings.simulation.scan_ms).expect("model");
        let awl = emit::awl::model(&input);
        for (kind, model) in [("iec", iec), ("awl", awl)] {
            let json = serde_json::to_string_pretty(&model).expect("a model is JSON");
            insta::assert_snapshot!(format!("{label}.{kind}-context.json"), json);
        }
    }
}
