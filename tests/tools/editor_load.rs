//! The editor-load test of issue 39, as far as a machine without a display
//! allows: every sample's Beremiz project folders of the graphical bodies
//! (`NAME.sfc.beremiz/`, `NAME.ld.beremiz/`, with `--modes all --safety
//! all`, the most elements) are opened with Beremiz's own project model
//! (`PLCControler.OpenXMLFile`, as the IDE opens a project), and each
//! graphical POU is read as the SFC and LD editors read it when they open
//! it (`GetEditedElementInstancesInfos`, which `editors/Viewer.py` draws
//! from), by `tests/engines/beremiz_editor_load.py`: every element of the
//! file must arrive, with an integer size and position, and every wire
//! must start on its own input and end on the connector the editor's
//! loader (`Viewer.CreateWires`) would connect it to, an output of its
//! source. Not proven: that wxPython draws it (no window is opened), and
//! the OpenPLC Editor (a fork of Beremiz's editor) is not run. A project
//! with a step's action connector moved must be caught.

use std::path::Path;
use std::process::Command;

use crate::{Check, Tool, shared, tool};

pub const CHECKS: &[Check] = &[Check::new(
    "editor_load::every_body_project_loads_in_beremiz_s_model_with_its_wires_on_their_connectors",
    &[Tool::Shared, Tool::BeremizPython],
    every_body_project_loads_in_beremiz_s_model_with_its_wires_on_their_connectors,
)];

/// Runs the loader on `xml`: its report, or why it failed.
fn load(python: &Path, shared: &Path, xml: &Path) -> Result<String, String> {
    let out = Command::new(python)
        .arg(crate::helpers::root().join("tests/engines/beremiz_editor_load.py"))
        .arg(shared.join("tools/plcopen2st.py"))
        .arg(xml)
        .output()
        .map_err(|e| e.to_string())?;
    let text = String::from_utf8_lossy(&out.stdout).into_owned();
    if out.status.success() {
        Ok(text)
    } else {
        Err(format!(
            "{}: {text}{}",
            xml.display(),
            String::from_utf8_lossy(&out.stderr)
        ))
    }
}

/// The elements of the file's graphical body: every `localId` but the
/// actions inside an action block (which are no elements of their own).
fn elements_in(xml: &str) -> usize {
    xml.lines()
        .filter(|l| l.contains(" localId=\"") && !l.trim_start().starts_with("<action "))
        .count()
}

/// The elements the model handed the editor: the sum of the counts on the
/// graphical POUs' lines (`pou steptable_main LD: 75 coil, 22 comment, …`).
fn elements_loaded(report: &str) -> usize {
    report
        .lines()
        .filter_map(|l| l.strip_prefix("pou ")?.split_once(": ").map(|(_, c)| c))
        .flat_map(|counts| counts.split(", "))
        .filter_map(|c| c.split(' ').next()?.parse::<usize>().ok())
        .sum()
}

fn every_body_project_loads_in_beremiz_s_model_with_its_wires_on_their_connectors() {
    let shared = shared();
    let python = tool(Tool::BeremizPython);
    let dir = tempfile::tempdir().unwrap();
    let mut loaded = 0;
    for sample in crate::helpers::samples() {
        let targets = crate::helpers::targets_of(&sample);
        let target = if targets.contains(&"iec") {
            "iec"
        } else {
            targets[0]
        };
        let out = dir.path().join(sample.file_name().unwrap());
        crate::helpers::steptable()
            .arg("convert")
            .arg(&sample)
            .args(["--target", target, "--modes", "all", "--safety", "all"])
            .args(["--formats", "beremiz-sfc,beremiz-ld", "-o"])
            .arg(&out)
            .assert()
            .success();
        let name = steptable::convert::output_name(&sample);
        for body in ["sfc", "ld"] {
            let xml = out
                .join(&name)
                .join(format!("{name}.{body}.beremiz/plc.xml"));
            let report = load(&python, &shared, &xml).unwrap_or_else(|e| panic!("{e}"));
            let text = std::fs::read_to_string(&xml).unwrap();
            assert_eq!(
                elements_loaded(&report),
                elements_in(&text),
                "{}: every element arrives: {report}",
                xml.display()
            );
            assert!(report.contains("wire-errors 0"), "{report}");
            loaded += 1;
        }
    }
    // Broken on purpose: the steps' action connector moved 5 units up, so
    // the action blocks' wires end beside it.
    let xml = dir.path().join("moved.xml");
    let last = std::fs::read_to_string(
        dir.path()
            .join("paper_example.xlsx/paper_example/paper_example.sfc.beremiz/plc.xml"),
    )
    .unwrap();
    let moved = last.replace(
        "<connectionPointOutAction formalParameter=\"\">\n                <relPosition x=\"70\" y=\"15\"/>",
        "<connectionPointOutAction formalParameter=\"\">\n                <relPosition x=\"70\" y=\"10\"/>",
    );
    assert_ne!(moved, last);
    std::fs::write(&xml, moved).unwrap();
    let err = load(&python, &shared, &xml).expect_err("a moved connector must be caught");
    assert!(err.contains("is not on an output of step"), "{err}");
    eprintln!(
        "editor_load: {loaded} project folders (every sample, SFC and LD, --modes all --safety all) load in Beremiz's model with every element placed and every wire on its connectors; a moved action connector caught"
    );
}
