//! The guide's table of the commissioning inputs' faults (*Faults of the
//! mode inputs, and those no check can catch*) is what `steptable faults
//! --modes all` classifies, for the paper's example and the two
//! stamping-like samples (the press station, the drilling station), and it
//! names every such input the fault table has.

use crate::helpers::{root, sample, steptable};

/// One row of the guide's table: the inputs it speaks of (`jogN+, jogN-`
/// for every jog button), stuck at, the paper's outcome, the samples'.
struct Row {
    inputs: String,
    stuck_at: String,
    paper: String,
    samples: String,
}

impl Row {
    fn covers(&self, signal: &str) -> bool {
        if self.inputs.contains("jogN") {
            signal.starts_with("jog")
        } else {
            self.inputs == format!("`{signal}`")
        }
    }
}

/// The rows of the table under the guide's heading.
fn guide_rows() -> Vec<Row> {
    let guide = std::fs::read_to_string(root().join("docs/guide.md")).unwrap();
    let heading = "#### Faults of the mode inputs, and those no check can catch";
    let from = guide.find(heading).expect("the guide's heading");
    let rows: Vec<Row> = guide[from..]
        .lines()
        .skip_while(|l| !l.starts_with("| input"))
        .skip(2)
        .take_while(|l| l.starts_with('|'))
        .map(|l| {
            let cells: Vec<String> = l.split('|').map(|c| c.trim().to_string()).collect();
            Row {
                inputs: cells[1].clone(),
                stuck_at: cells[2].clone(),
                paper: cells[3].clone(),
                samples: cells[4].clone(),
            }
        })
        .collect();
    assert!(rows.len() >= 8, "the table's rows");
    rows
}

/// `(signal, stuck_at, outcome)` of every single fault of the sample's
/// fault table with every mode, through the binary.
fn fault_rows(name: &str) -> Vec<(String, String, String)> {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("faults")
        .arg(sample(&format!("{name}.xlsx")))
        .args(["--modes", "all", "-o"])
        .arg(dir.path())
        .assert()
        .success();
    let csv = dir.path().join(name).join(format!("{name}.faults.csv"));
    let text = std::fs::read_to_string(csv).unwrap();
    let mut reader = csv::Reader::from_reader(text.as_bytes());
    reader
        .records()
        .map(|r| {
            let r = r.unwrap();
            (r[1].to_string(), r[2].to_string(), r[3].to_string())
        })
        .collect()
}

#[test]
fn the_guides_table_of_mode_input_faults_is_the_fault_tables() {
    let rows = guide_rows();
    let commissioning = |s: &str| s == "STEP_MODE" || s == "STEP_PB" || s == "MAN_MODE";
    for name in ["paper_example", "press_station", "drilling_station"] {
        let faults = fault_rows(name);
        let mut seen = 0;
        for (signal, stuck_at, outcome) in &faults {
            if !commissioning(signal) && !signal.starts_with("jog") {
                continue;
            }
            let row = rows
                .iter()
                .find(|r| r.covers(signal) && r.stuck_at == *stuck_at);
            let row = row.unwrap_or_else(|| panic!("{signal} stuck at {stuck_at}: no row"));
            let said = if name == "paper_example" {
                &row.paper
            } else {
                &row.samples
            };
            assert_eq!(said, outcome, "{name}: {signal} stuck at {stuck_at}");
            seen += 1;
        }
        // STEP_MODE, STEP_PB, MAN_MODE and two jogs per cylinder, each
        // stuck at 1 and at 0.
        let cylinders = if name == "paper_example" { 4 } else { 3 };
        assert_eq!(
            seen,
            2 * (3 + 2 * cylinders),
            "{name}: every input, both ways"
        );
    }
}

/// The table's `STEP_PB` stuck at 1, in single step on the drilling
/// station: the wire's edge fires step 2 (the clamp is out), no press can
/// fire step 3 and, with the watchdog, step 2's wait runs out of time.
#[test]
fn a_step_button_stuck_at_1_fires_one_step_then_the_watchdog_sees_the_wait() {
    let run = steptable()
        .arg("simulate")
        .arg(sample("drilling_station.xlsx"))
        .args(["--modes", "step", "--safety", "watchdog"])
        .args(["--hold", "STEP_MODE@0s", "--press", "START@0.5s"])
        .args(["--press", "STEP_PB@1s", "--stick", "STEP_PB=1@2s"])
        .assert()
        .success();
    let out = String::from_utf8_lossy(&run.get_output().stdout).into_owned();
    let fired: Vec<&str> = out
        .lines()
        .filter(|l| l.split_whitespace().nth(2) == Some("step"))
        .filter_map(|l| l.split_whitespace().nth(3))
        .collect();
    assert_eq!(fired, ["1", "2"], "{out}");
    assert!(out.contains("alarm_wd on"), "{out}");
    assert!(out.lines().last().unwrap().contains("in step 2"), "{out}");
}
