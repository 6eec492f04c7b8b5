//! Proof by simulation that a synthesised controller runs its sequence: the
//! equations are evaluated every PLC scan on the state read at its start;
//! coil equations drive bistable 5/2 valves, memory equations set and reset
//! the memories (reset wins), against the plant of DESIGN §5. A sensor
//! letter `a` is 1 from the moment cylinder A reaches its extended end until
//! it reaches its retracted end, so the state changes only when a move ends.

use super::Synthesis;
use super::sequence::Sequence;
use crate::simulate::plant::Piston;
use crate::stroke::Stroke;

/// The result of simulating a synthesised controller.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Verification {
    pub passed: bool,
    /// The actions observed, as tokens, in order.
    pub observed: Vec<String>,
    /// Time of two complete cycles, in milliseconds.
    pub millis: u64,
    pub problem: Option<String>,
    /// The mode proof (`synth::modes`): the moves it saw, or what went wrong.
    pub modes: Result<usize, String>,
}

/// Runs `cycles` cycles of the controller, 10 ms scans, 1 s strokes.
pub fn verify(synthesis: &Synthesis, cycles: usize) -> Verification {
    Verification {
        modes: super::modes::check(synthesis).map(|trace| trace.len()),
        ..equations(synthesis, cycles)
    }
}

/// The equations alone, cycling from power-up (`modes` left empty).
fn equations(synthesis: &Synthesis, cycles: usize) -> Verification {
    const SCAN_MS: u32 = 10;
    const WINDOW: f64 = 0.02;
    let seq = &synthesis.modified;
    let initial = seq.initial_state();
    let mut pistons = pistons_at_start(seq, Stroke::default(), SCAN_MS);
    let mut state = initial;
    let expected: Vec<String> = (0..cycles)
        .flat_map(|_| seq.actions.iter().map(|a| seq.token(*a)))
        .collect();
    let mut observed: Vec<String> = Vec::new();
    let mut since_event = 0u32;
    let mut time = 0u64;
    let timeout_scans = 3000 / SCAN_MS;
    let value = |action, state: u32| synthesis.drives(action, state);
    while observed.len() < expected.len() {
        // Evaluate every equation on the state read at the start of the scan.
        let mut next = state;
        for (i, piston) in pistons.iter_mut().enumerate() {
            let plus = value(sequence_action(i, true), state);
            let minus = value(sequence_action(i, false), state);
            if piston.drive(plus, minus) {
                return Verification {
                    passed: false,
                    observed,
                    millis: time,
                    problem: Some(format!("the valve of {} sees both coils", seq.var_name(i))),
                    modes: Ok(0),
                };
            }
        }
        for j in 0..seq.memories {
            let var = seq.actuators + j;
            let set = value(sequence_action(var, true), state);
            let reset = value(sequence_action(var, false), state);
            if reset {
                next &= !(1 << var);
            } else if set {
                next |= 1 << var;
            }
        }
        for (i, piston) in pistons.iter_mut().enumerate() {
            piston.advance();
            if piston.sensor(1, WINDOW) && piston.s >= 1.0 {
                next |= 1 << i;
            } else if piston.sensor(0, WINDOW) && piston.s <= 0.0 {
                next &= !(1 << i);
            }
        }
        time += SCAN_MS as u64;
        // Record every variable that changed, in variable order.
        for var in 0..seq.variables() {
            if (state ^ next) >> var & 1 == 1 {
                let token = seq.token(super::sequence::Operation {
                    var,
                    value: (next >> var) & 1 == 1,
                });
                if expected.get(observed.len()) != Some(&token) {
                    observed.push(token.clone());
                    return Verification {
                        passed: false,
                        problem: Some(format!(
                            "expected {} as action {}, but {token} happened",
                            expected
                                .get(observed.len() - 1)
                                .cloned()
                                .unwrap_or_default(),
                            observed.len()
                        )),
                        observed,
                        millis: time,
                        modes: Ok(0),
                    };
                }
                observed.push(token);
                since_event = 0;
            }
        }
        state = next;
        since_event += 1;
        if since_event > timeout_scans {
            return Verification {
                passed: false,
                problem: Some(format!(
                    "nothing happens after {} actions (state {})",
                    observed.len(),
                    seq.state_text(state)
                )),
                observed,
                millis: time,
                modes: Ok(0),
            };
        }
    }
    Verification {
        passed: true,
        observed,
        millis: time,
        problem: None,
        modes: Ok(0),
    }
}

/// One cylinder per actuator, each where the sequence starts it: a cylinder
/// that starts extended is there with its valve that way.
pub(crate) fn pistons_at_start(seq: &Sequence, stroke: Stroke, scan_ms: u32) -> Vec<Piston> {
    let initial = seq.initial_state();
    (0..seq.actuators)
        .map(|i| {
            let mut p = Piston::new(i as u32 + 1, 1, stroke, scan_ms);
            if (initial >> i) & 1 == 1 {
                p.drive(true, false);
                p.s = 1.0;
            }
            p
        })
        .collect()
}

fn sequence_action(var: usize, value: bool) -> super::sequence::Operation {
    super::sequence::Operation { var, value }
}
