//! The vacuum gripper (`--valve C2=vacuum`) in the engines: a pick and
//! place whose gripper C2 holds the part on its vacuum switch `x21` and
//! reads "released" as that switch off. The written programs must run in
//! matiec (ST), OpenPLC's upload, awlsim (AWL, both mnemonic sets) and the
//! FST interpreter as steptable simulated them, scan by scan, for every
//! target and with every safety check and mode.

use crate::kinds;
use crate::{Check, Tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "vacuum::a_vacuum_gripper_runs_in_matiec_and_openplc_as_simulated",
        &[Tool::Shared],
        a_vacuum_gripper_runs_in_matiec_and_openplc_as_simulated,
    ),
    Check::new(
        "vacuum::a_vacuum_gripper_runs_in_awlsim_as_simulated",
        &[Tool::Awlsim],
        a_vacuum_gripper_runs_in_awlsim_as_simulated,
    ),
    Check::new(
        "vacuum::a_vacuum_gripper_runs_in_the_fst_interpreter_as_simulated",
        &[],
        a_vacuum_gripper_runs_in_the_fst_interpreter_as_simulated,
    ),
];

const FIXTURE: &str = "pick_and_place.csv";
const VALVES: &str = "C2=vacuum";

fn a_vacuum_gripper_runs_in_matiec_and_openplc_as_simulated() {
    kinds::in_matiec_and_openplc("vacuum", FIXTURE, VALVES);
}

fn a_vacuum_gripper_runs_in_awlsim_as_simulated() {
    kinds::in_awlsim("vacuum", FIXTURE, VALVES);
}

fn a_vacuum_gripper_runs_in_the_fst_interpreter_as_simulated() {
    kinds::in_fst("vacuum", FIXTURE, VALVES);
}
