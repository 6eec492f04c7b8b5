//! Power-up, the operator pressing START, cycles run to their end, and the
//! timing of every step.

use super::*;
use crate::cell::Sign;
use crate::program::{Action, Alarm, Signal, StepKind, StepProgram};
use crate::simulate::plc::{PlcProgram, PlcState};
use crate::table::StepTable;

/// The longest a step may take before the run counts as stalled: well past
/// the slowest stroke, and past the program's own watchdog so that its alarm
/// is seen.
pub(in crate::simulate) fn step_timeout_ms(
    table: &StepTable,
    program: &StepProgram,
    settings: &SimSettings,
) -> u64 {
    let watchdog = program
        .steps
        .iter()
        .flat_map(|s| &s.actions)
        .filter_map(|a| match a {
            Action::StartTimer(_, ms) => Some(*ms as u64 + 1000),
            _ => None,
        })
        .max()
        .unwrap_or(0);
    let longest = table
        .actuators
        .iter()
        .map(|a| {
            let s = settings.stroke(a.number);
            s.extend_ms.max(s.retract_ms)
        })
        .max()
        .unwrap_or(1000) as u64;
    // A step may also dwell and wait for the machine before it completes.
    let dwell = table.dwells().map(|d| d.ms).max().unwrap_or(0) as u64;
    let wait = if table.inputs.is_empty() {
        0
    } else {
        table
            .inputs
            .iter()
            .map(|n| {
                settings
                    .input_delays
                    .get(n)
                    .copied()
                    .unwrap_or(DEFAULT_INPUT_DELAY_MS)
            })
            .max()
            .unwrap_or(0) as u64
    };
    // An output that runs on after a stop, once the watchdog has halted.
    let run_on = program.run_ons.iter().map(|r| r.ms).max().unwrap_or(0) as u64;
    (2 * longest + 500 + dwell + wait).max(watchdog) + run_on
}

/// Whether the table's cycle ends with `output` on: its last switch in
/// the table switches it on.
fn left_on_by_the_cycle(table: &StepTable, output: Signal) -> bool {
    let Signal::MachineOutput(name) = output else {
        return false;
    };
    table
        .steps
        .iter()
        .flat_map(|s| &s.switches)
        .rfind(|w| w.output == name)
        .is_some_and(|w| w.on)
}

impl<'a> Run<'a> {
    /// Power-up: every piston home, the PLC in its initial state.
    pub(in crate::simulate) fn new(
        table: &'a StepTable,
        program: &'a StepProgram,
        code: &'a PlcProgram,
        settings: &SimSettings,
    ) -> Run<'a> {
        let scan_ms = settings.scan_ms.max(1);
        let pistons: Vec<Piston> = table
            .actuators
            .iter()
            .map(|a| {
                Piston::with_valve(
                    a.number,
                    a.max_position,
                    settings.stroke(a.number),
                    scan_ms,
                    settings.valves.of(a.number, a.max_position),
                    settings
                        .loads
                        .get(&a.number)
                        .copied()
                        .unwrap_or(DEFAULT_DRIFT),
                )
            })
            .collect();
        let index_of = pistons
            .iter()
            .enumerate()
            .map(|(i, p)| (p.number, i))
            .collect();
        let settings_scan = SimSettings {
            scan_ms,
            ..settings.clone()
        };
        let mut run = Run {
            program,
            world: World {
                settings: settings_scan,
                pistons,
                index_of,
                start_pressed: false,
                operator: Operator::default(),
                machine: table
                    .inputs
                    .iter()
                    .filter_map(|n| machine::rest_value(table, *n).map(|v| (*n, v)))
                    // A healthy machine holds its start permissives on.
                    .chain(program.permissive.iter().map(|n| (*n, true)))
                    .collect(),
                faults_active: settings.fault_onset_ms == 0,
            },
            plc: PlcState::new(code),
            time_ms: 0,
            problems: Vec::new(),
            active: Vec::new(),
            last_move: vec![None; table.actuators.len()],
            pending: Vec::new(),
            answered: Vec::new(),
            table,
            dwells: Vec::new(),
            spans: Vec::new(),
            trace: Vec::new(),
            coils: Vec::new(),
            io: None,
            event_driven: false,
            quiet: false,
            moving: (0..table.actuators.len()).collect(),
            hazard_seen: false,
            alarm_bits: Vec::new(),
            alarmed: false,
            places: Vec::new(),
            visited: Places::new(),
        };
        run.dwells = table
            .dwells()
            .filter_map(|d| {
                run.plc
                    .index_of(Signal::Dwell(d.number))
                    .map(|at| (at, d.number, None))
            })
            .collect();
        run.places = run
            .world
            .pistons
            .iter()
            .map(|p| p.place(settings.window))
            .collect();
        run.visit();
        run.coils = table
            .actuators
            .iter()
            .map(|a| {
                let at = |s: Signal| run.plc.index_of(s);
                (
                    at(Signal::Coil {
                        actuator: a.number,
                        sign: Sign::Plus,
                    }),
                    at(Signal::Coil {
                        actuator: a.number,
                        sign: Sign::Minus,
                    }),
                    at(Signal::SingleCoil { actuator: a.number }),
                )
            })
            .collect();
        run.alarm_bits = program
            .signals
            .alarms()
            .filter_map(|a| run.plc.index_of(a))
            .collect();
        run
    }
}

pub(in crate::simulate) fn run(
    table: &StepTable,
    program: &StepProgram,
    code: &PlcProgram,
    settings: &SimSettings,
    record: Option<io::IoSignals>,
    stepping: Stepping,
) -> (SimReport, Option<io::IoTrace>) {
    let mut run = Run::new(table, program, code, settings);
    run.event_driven = stepping == Stepping::Events;
    run.io = record.map(|signals| io::IoTrace {
        scan_ms: run.world.settings.scan_ms,
        signals,
        scans: Vec::new(),
    });
    let timeout = step_timeout_ms(table, program, settings);
    let step_count = program.steps.len();
    let mut cycles: Vec<CycleReport> = Vec::new();
    let mut step_positions = vec![run.positions()];
    let mut stalled_at = None;
    let mut first_cycle_end = u64::MAX;

    // Idle before the first press: nothing may happen.
    let mut press_at = IDLE_MS as u64;
    'cycles: for cycle in 0..settings.cycles.max(1) {
        while run.time_ms < press_at {
            run.tick();
            if run.judged() {
                break 'cycles;
            }
            run.pass_quiet_scans(press_at);
        }
        let mut report = CycleReport {
            press_ms: press_at,
            steps: Vec::new(),
            cycle_ms: None,
        };
        let mut fire_times: Vec<u64> = Vec::new();
        let mut last_event = run.time_ms;
        loop {
            // A press the PLC can see: held for two scans at least, however
            // slow the scan.
            let press_ms = START_PRESS_MS.max(2 * run.world.settings.scan_ms) as u64;
            run.world.start_pressed = run.time_ms < press_at + press_ms;
            let before = run.time_ms;
            let fired = run.tick();
            if run.judged() {
                report.steps = timings(program, &fire_times, run.time_ms, press_at, &run.spans);
                cycles.push(report);
                break 'cycles;
            }
            if let Some(index) = fired {
                // A boundary of the diagram: the previous step has ended.
                // (A closing END step is not a boundary: the cycle end is.)
                if cycle == 0 && index > 0 && program.steps[index].kind == StepKind::Table {
                    step_positions.push(run.positions());
                }
                if index == 0 && !fire_times.is_empty() {
                    // Step 1 again before the cycle was seen to end.
                    break;
                }
                fire_times.push(before);
                last_event = run.time_ms;
            }
            // The cycle ends when the machine is at rest: a closing step
            // fires on the home sensors while the last stroke still runs
            // into its end stop, and START must not come before it does.
            let done = fire_times.len() == step_count
                && run.plc.awaited == 0
                && run.all_moves_ended()
                && run.world.pistons.iter().all(plant::Piston::at_rest)
                && run.cycle_complete();
            if done {
                if cycle == 0 {
                    step_positions.push(run.positions());
                }
                report.cycle_ms = Some(run.time_ms - press_at);
                break;
            }
            if run.time_ms - last_event > timeout {
                let waiting = &program.steps[run.plc.awaited];
                // START was pressed and released; it only explains the wait
                // when nothing else is missing.
                // The plant stands still while the sequence waits: what is
                // missing now is what was missing.
                let mut missing_literals = run.missing(run.plc.awaited);
                if missing_literals.len() > 1 {
                    missing_literals.retain(|l| l.signal != Signal::Start);
                }
                let missing: Vec<String> = missing_literals.iter().map(literal_text).collect();
                let alarms: Vec<String> = [Alarm::Sensor, Alarm::Timeout, Alarm::Interlock]
                    .into_iter()
                    .map(Signal::Alarm)
                    .filter(|a| run.plc.bit(*a))
                    .map(|a| a.symbol())
                    .collect();
                let mut message = if fire_times.len() == step_count {
                    format!(
                        "the cycle never ends: the moves of step {} do not finish",
                        program.steps[step_count - 1].number
                    )
                } else {
                    format!(
                        "step {} never fires: waiting for {}",
                        waiting.number,
                        if missing.is_empty() {
                            "its condition".to_string()
                        } else {
                            missing.join(" AND ")
                        }
                    )
                };
                if !alarms.is_empty() {
                    message.push_str(&format!(" (alarm: {})", alarms.join(", ")));
                }
                // Waiting for the next cycle, an output the cycle leaves on
                // (an oven's heater until STOP) is on as in a healthy machine.
                let at_rest = run.plc.awaited == 0;
                let energised: Vec<String> = program
                    .signals
                    .driven()
                    .filter(|s| run.plc.bit(*s) && !program.halt.may_stay_on(*s))
                    .filter(|s| !(at_rest && left_on_by_the_cycle(table, *s)))
                    .map(|s| s.symbol())
                    .collect();
                run.problem(ProblemKind::Stall, waiting.number, message.clone());
                if !energised.is_empty() {
                    run.problem(
                        ProblemKind::Energised,
                        waiting.number,
                        format!(
                            "{message}; the stopped machine keeps {} on (not hold-safe)",
                            energised.join(", ")
                        ),
                    );
                }
                stalled_at = Some(waiting.number);
                report.steps = timings(program, &fire_times, run.time_ms, press_at, &run.spans);
                cycles.push(report);
                break 'cycles;
            }
            // Quiet scans pass at once until START is released or the
            // wait could time out.
            let scan = run.world.settings.scan_ms as u64;
            let release = if run.world.start_pressed {
                press_at + press_ms
            } else {
                u64::MAX
            };
            run.pass_quiet_scans(release.min((last_event + timeout + 1).saturating_sub(scan)));
        }
        report.steps = timings(program, &fire_times, run.time_ms, press_at, &run.spans);
        if cycle == 0 {
            first_cycle_end = run.time_ms;
        }
        // Every actuator home at the end of the cycle.
        if report.cycle_ms.is_some() {
            for p in &run.world.pistons {
                if !p.sensor(0, settings.window) {
                    let step = program.steps[step_count - 1].number;
                    run.problems.push(Problem {
                        kind: ProblemKind::NotHome,
                        time_ms: run.time_ms,
                        step,
                        actuator: Some(p.number),
                        message: format!("C{} is not home at the end of the cycle", p.number),
                    });
                }
            }
        }
        let complete = report.cycle_ms.is_some();
        cycles.push(report);
        if !complete {
            break;
        }
        press_at = run.time_ms + IDLE_MS as u64;
    }
    // A short idle after the last cycle: nothing may move on its own.
    if stalled_at.is_none() && !run.judged() {
        let until = run.time_ms + IDLE_MS as u64;
        run.world.start_pressed = false;
        while run.time_ms < until && !run.judged() {
            run.tick();
            run.pass_quiet_scans(until);
        }
    }

    if let (Some(first), Some(second)) = (cycles.first(), cycles.get(1))
        && first.cycle_ms.is_some()
        && second.cycle_ms.is_some()
    {
        let durations = |c: &CycleReport| c.steps.iter().map(|s| s.duration_ms).collect::<Vec<_>>();
        if durations(first) != durations(second) {
            run.problems.push(Problem {
                kind: ProblemKind::CycleDiffers,
                time_ms: run.time_ms,
                step: 1,
                actuator: None,
                message: "the second cycle's step timing differs from the first".to_string(),
            });
        }
    }
    // Say where each run-through ended: "C2 ran through x22 to x23".
    for problem in &mut run.problems {
        if problem.kind != ProblemKind::RanThrough {
            continue;
        }
        if let Some(piston) = problem
            .actuator
            .and_then(|n| run.world.index_of.get(&n))
            .map(|i| &run.world.pistons[*i])
        {
            let end = match piston.sensor_on(settings.window) {
                Some(position) => Signal::Sensor {
                    actuator: piston.number,
                    position,
                }
                .symbol(),
                None => format!("position {:.2}", piston.position_units()),
            };
            problem.message =
                problem
                    .message
                    .replacen(" in step", &format!(" to {end} in step"), 1);
        }
    }
    let all_cycles_done =
        cycles.len() == settings.cycles.max(1) && cycles.iter().all(|c| c.cycle_ms.is_some());
    run.problems.sort_by_key(|p| p.time_ms);
    let report = SimReport {
        alarmed: run.alarmed,
        passed: run.problems.is_empty() && all_cycles_done,
        cycles,
        problems: run.problems,
        stalled_at,
        step_positions,
        actuators: table
            .actuators
            .iter()
            .map(|a| (a.number, a.max_position))
            .collect(),
        trace: run.trace,
        places: run.visited,
        spans: run
            .spans
            .into_iter()
            .filter(|s| s.from_ms < first_cycle_end)
            .collect(),
    };
    (report, run.io)
}

pub(in crate::simulate) fn timings(
    program: &StepProgram,
    fire_times: &[u64],
    end: u64,
    press_at: u64,
    spans: &[Span],
) -> Vec<StepTiming> {
    fire_times
        .iter()
        .enumerate()
        .map(|(i, t)| {
            let next = fire_times.get(i + 1).copied().unwrap_or(end);
            let step = &program.steps[i];
            let notes: Vec<String> = spans
                .iter()
                .filter(|s| s.from_ms >= *t && s.from_ms < next)
                .map(|s| {
                    if s.label.starts_with("I:") {
                        format!("{} came after {}", s.label, seconds(s.to_ms - t))
                    } else {
                        format!(
                            "{} ran {:.2}–{}",
                            s.label,
                            (s.from_ms - t) as f64 / 1000.0,
                            seconds(s.to_ms - t)
                        )
                    }
                })
                .collect();
            StepTiming {
                step: step.number,
                start_ms: t - press_at,
                duration_ms: next - t,
                // The closing step moves nothing (its row stays blank, as it always has).
                moves: match step.kind {
                    StepKind::Table => step.title.clone(),
                    StepKind::EndOfCycle => String::new(),
                },
                notes: notes.join("; "),
            }
        })
        .collect()
}
