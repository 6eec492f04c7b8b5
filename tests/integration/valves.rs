//! Valve types per actuator: a sample mixing single-solenoid, bistable and
//! closed-centre valves, and the impossible combination.

use predicates::prelude::*;
use predicates::str::contains;

use crate::helpers::{files_below, sample, steptable};

#[test]
fn the_mixed_valve_sample_converts_and_runs() {
    let dir = tempfile::tempdir().unwrap();
    steptable()
        .arg("convert")
        .arg(sample("mixed_valves.xlsx"))
        .args(["--formats", "io,st,xlsx", "-o"])
        .arg(dir.path())
        .assert()
        .success()
        .stdout(contains("3 actuators, 8 inputs, 5 outputs"));
    let io = std::fs::read_to_string(dir.path().join("mixed_valves/mixed_valves.io.csv")).unwrap();
    // One coil for the 52mono actuator, in its + place; its - place stays free.
    assert!(io.contains("O0.1,y1,coil,1,,+,"), "{io}");
    assert!(!io.contains("y1-") && !io.contains("O1.1,"), "{io}");
    assert!(io.contains("O1.2,y2-,coil,2,,-,"), "{io}");
    let st = std::fs::read_to_string(dir.path().join("mixed_valves/mixed_valves.st")).unwrap();
    assert!(
        st.contains("y1 := TRUE; (* y1 on: extend C1, C1+1 *)"),
        "{st}"
    );
    assert!(
        st.contains("y1 := FALSE; (* y1 off: the spring retracts C1, C1-0 *)"),
        "{st}"
    );
    steptable()
        .arg("simulate")
        .arg(sample("mixed_valves.xlsx"))
        .assert()
        .success()
        .stdout(contains("passed"));
}

#[test]
fn a_middle_stop_on_a_5_2_valve_is_refused_at_its_cell() {
    for valve in ["52bi", "52mono"] {
        steptable()
            .arg("check")
            .arg(sample("mixed_valves.xlsx"))
            .args(["--valve", &format!("C3={valve}")])
            .assert()
            .code(1)
            .stderr(contains("SEQUENTIAL CONTROL DESCRIPTION!C4: error[E031]: \"C3+1\" stops C3 at middle position 1"))
            .stderr(contains(valve));
    }
}

/// An exhausted centre does not hold a middle stop: under a load the piston
/// drifts off its sensor and the sequence waits for it.
#[test]
fn an_exhausted_centre_drifts_off_the_middle_sensor() {
    steptable()
        .arg("simulate")
        .arg(sample("mixed_valves.xlsx"))
        .args(["--valve", "C3=53exhaust", "--load", "C3=0.5"])
        .assert()
        .code(1)
        .stdout(contains("step 2 never fires: waiting for x31"));
    // With no load it holds like a closed centre.
    steptable()
        .arg("simulate")
        .arg(sample("mixed_valves.xlsx"))
        .args(["--valve", "C3=53exhaust", "--load", "C3=0"])
        .assert()
        .success()
        .stdout(contains("passed").and(contains("identical cycle")));
}

/// A machine set up so that no program can run its cycle — a valve that
/// cannot hold its load, a stroke that passes a middle sensor between two
/// scans, a scan too slow for the strokes — is the engineer's setting to
/// change, not a bug in steptable: exit 1, E032 naming the setting whose
/// default lets the cycle run, nothing written.
#[test]
fn a_machine_that_cannot_run_the_cycle_is_refused_with_the_setting_to_blame() {
    // A middle sensor the PLC might not see in time is refused before the
    // simulation, at the move's cell (`machine_limits.rs` has the rule).
    let cases: &[(&str, &[&str], &str)] = &[
        (
            "mixed_valves.xlsx",
            &["--valve", "C3=53exhaust", "--load", "C3=0.5"],
            "error[E032]: the machine as set up cannot run this cycle: ",
        ),
        (
            "mixed_valves.xlsx",
            &["--valve", "C3=53exhaust", "--load", "C3=0.5"],
            "it runs with C3 on its default valve (53closed)",
        ),
        (
            "paper_example.xlsx",
            &["--stroke", "C2=10ms"],
            "error[E032]: C2 stops at its middle position 1 in step 3, but its sensor x21 is in view for only 0.4 ms of a 10 ms stroke back",
        ),
        (
            "mixed_valves.xlsx",
            &["--scan", "200ms"],
            "C3 stops at its middle position 1 in step 1, but its sensor x31 is in view for only 60.0 ms of a 1500 ms stroke out, less than two 200 ms scans",
        ),
    ];
    for (file, flags, says) in cases {
        let dir = tempfile::tempdir().unwrap();
        steptable()
            .arg("convert")
            .arg(sample(file))
            .args(*flags)
            .arg("-o")
            .arg(dir.path())
            .assert()
            .code(1)
            .stderr(
                contains("error[E032]: ")
                    .and(contains(*says))
                    .and(contains("bug").not()),
            );
        assert!(files_below(dir.path()).is_empty(), "{file} {flags:?}");
    }
}

/// A slow scan still sees START: the simulated press lasts two scans.
#[test]
fn a_slow_scan_sees_the_start_press() {
    steptable()
        .arg("simulate")
        .arg(sample("drilling_station.xlsx"))
        .args(["--scan", "200ms"])
        .assert()
        .success()
        .stdout(contains("passed"));
}
