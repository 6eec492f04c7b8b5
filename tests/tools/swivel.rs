//! The swivel (semi-rotary) drive (`--valve C2=swivel`) in the engines:
//! the distributing station's swivel arm C2 turns between its end stops
//! at 0° (`x20`) and 180° (`x21`) on a 5/2 valve's two coils, beside a
//! vacuum cup C3. The written programs must run in matiec (ST), OpenPLC's
//! upload, awlsim (AWL, both mnemonic sets) and the FST interpreter as
//! steptable simulated them, scan by scan, for every target and with every
//! safety check and mode (the manual jogs among them).

use crate::kinds;
use crate::{Check, Tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "swivel::a_swivel_drive_runs_in_matiec_and_openplc_as_simulated",
        &[Tool::Shared],
        a_swivel_drive_runs_in_matiec_and_openplc_as_simulated,
    ),
    Check::new(
        "swivel::a_swivel_drive_runs_in_awlsim_as_simulated",
        &[Tool::Awlsim],
        a_swivel_drive_runs_in_awlsim_as_simulated,
    ),
    Check::new(
        "swivel::a_swivel_drive_runs_in_the_fst_interpreter_as_simulated",
        &[],
        a_swivel_drive_runs_in_the_fst_interpreter_as_simulated,
    ),
];

const FIXTURE: &str = "distributing_station.csv";
const VALVES: &str = "C2=swivel,C3=vacuum";

fn a_swivel_drive_runs_in_matiec_and_openplc_as_simulated() {
    kinds::in_matiec_and_openplc("swivel", FIXTURE, VALVES);
}

fn a_swivel_drive_runs_in_awlsim_as_simulated() {
    kinds::in_awlsim("swivel", FIXTURE, VALVES);
}

fn a_swivel_drive_runs_in_the_fst_interpreter_as_simulated() {
    kinds::in_fst("swivel", FIXTURE, VALVES);
}
