//! What a simulation found: problems, step timings, the verdict, and the
//! text `simulate` prints of them.

/// What went wrong in a run.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum ProblemKind {
    /// The sequence waits for ever (a safe stall unless something else happened).
    Stall,
    /// A move passed its target sensor.
    RanThrough,
    /// An actuator moved although no step was moving it (or the wrong way).
    OutsideStep,
    /// A valve saw both coils.
    CoilConflict,
    /// A step fired before the previous step's moves physically finished.
    Premature,
    /// A cycle started without a START press.
    UnexpectedStart,
    /// In single step, a step fired without a STEP_PB press.
    UnexpectedStep,
    /// The cycle ended with an actuator away from home.
    NotHome,
    /// The second cycle differs from the first.
    CycleDiffers,
    /// A cycle that was to take a jump ran the other path (a dead reject
    /// sensor: the bad part goes on as a good one).
    PathLost,
    /// The actuators stand (or move) in a combination of positions the
    /// healthy cycle never has: on a real machine, a possible collision.
    /// Only checked against a recorded healthy run (the fault analysis).
    Collision,
    /// The machine has stopped (the sequence waits for ever) with an
    /// output on that may not stay on: a heater, a motor, a spray valve
    /// (see [`HaltPolicy`](crate::program::HaltPolicy)).
    Energised,
}

impl ProblemKind {
    /// Whether this problem can hurt someone or something (DESIGN §6): a move
    /// that starts too early, motion no step commands, both coils, a start
    /// without START. A run-through is a move that goes on in the direction
    /// its own step commanded to the cylinder's next sensor or end stop
    /// because its target sensor is dead: it fails the run, and the sequence
    /// then stalls, but it is not motion outside the step.
    pub fn is_hazard(self) -> bool {
        !matches!(
            self,
            ProblemKind::Stall
                | ProblemKind::CycleDiffers
                | ProblemKind::RanThrough
                | ProblemKind::NotHome
        )
    }
}

/// One problem, when it happened and in which step.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Problem {
    pub kind: ProblemKind,
    pub time_ms: u64,
    /// The SFC step the machine is in when the problem is found (0 at
    /// rest, k while table step k's moves run; a step started too early is
    /// the step entered).
    pub step: usize,
    /// The actuator it concerns, where it concerns one (a run-through).
    pub actuator: Option<u32>,
    pub message: String,
}

/// Timing of one step in one cycle.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StepTiming {
    pub step: usize,
    /// When the step fired, from the START press of its cycle.
    pub start_ms: u64,
    /// Until the next step fired (or, for the last step, until its moves ended).
    pub duration_ms: u64,
    /// What the step does, in the table's notation.
    pub moves: String,
    /// Dwells and waits of the step, as they happened: `T=2s from 1.21 s`,
    /// `I:part_present after 0.50 s`.
    pub notes: String,
}

/// A span of time in the run (absolute milliseconds) with a label: a dwell
/// running or a step waiting for a machine input. Drawn on the time diagram.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Span {
    pub from_ms: u64,
    pub to_ms: u64,
    pub label: String,
}

/// The operator's buttons and switches at one moment.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Operator {
    pub start: bool,
    pub continuous: bool,
    /// STOP pressed (the normally closed input reads 0).
    pub stop: bool,
    /// EMERGENCY STOP pressed (the normally closed input reads 0).
    pub estop: bool,
    pub reset: bool,
    /// The STEP_MODE switch on (single step).
    pub step_mode: bool,
    /// STEP_PB pressed.
    pub step: bool,
    /// The MAN_MODE selector at 1 (manual).
    pub manual: bool,
    /// The jog buttons held.
    pub jogs: Jogs,
}

/// The jog buttons an operator holds: at most [`Jogs::HANDS`] at once (a
/// scenario naming more is refused), so that the operator stays a value.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Jogs([Option<crate::program::Signal>; Jogs::HANDS]);

impl Jogs {
    /// How many jog buttons a scenario may hold in all.
    pub const HANDS: usize = 4;
    pub const NONE: Jogs = Jogs([None; Jogs::HANDS]);

    /// Whether `jog` is held.
    pub fn held(self, jog: crate::program::Signal) -> bool {
        self.0.contains(&Some(jog))
    }

    /// `jog` held too; `None` when every hand is full.
    pub fn with(self, jog: crate::program::Signal) -> Option<Jogs> {
        if self.held(jog) {
            return Some(self);
        }
        let mut jogs = self;
        *jogs.0.iter_mut().find(|j| j.is_none())? = Some(jog);
        Some(jogs)
    }

    /// `jog` let go of.
    pub fn without(self, jog: crate::program::Signal) -> Jogs {
        let mut jogs = self;
        for j in &mut jogs.0 {
            if *j == Some(jog) {
                *j = None;
            }
        }
        jogs
    }
}

/// One complete or interrupted cycle.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CycleReport {
    /// Absolute time of the START press.
    pub press_ms: u64,
    pub steps: Vec<StepTiming>,
    /// From the START press to the end of the last move, when the cycle completed.
    pub cycle_ms: Option<u64>,
    /// The jump the machine took in this cycle: its step and notation.
    pub jump: Option<(usize, String)>,
    /// The jumps tested and not taken in this cycle: the step they leave
    /// (one-based) and their notation, each once, in the order tested.
    pub declined: Vec<(usize, String)>,
}

/// The result of a simulation run.
#[derive(Debug, Clone, PartialEq)]
pub struct SimReport {
    pub passed: bool,
    pub cycles: Vec<CycleReport>,
    pub problems: Vec<Problem>,
    /// The SFC step the machine stalled in (0 at rest, k while table step
    /// k's moves run: it waits for the transition after step k), if it did.
    pub stalled_at: Option<usize>,
    /// Positions in sensor units of every actuator (table order) at each step
    /// boundary of the first cycle: before step 1, …, after the last step.
    pub step_positions: Vec<Vec<f64>>,
    /// Actuator numbers, in the order of every position vector.
    pub actuators: Vec<(u32, u32)>,
    /// `(time_ms, positions)` at every scan, when recorded.
    pub trace: Vec<(u64, Vec<f64>)>,
    /// Dwells and waits of the first cycle, in absolute time.
    pub spans: Vec<Span>,
    /// Every combination of actuator places reached, when recorded.
    pub places: super::Places,
    /// An alarm output of a safety check came on during the run: the
    /// machine told its operator something is wrong.
    pub alarmed: bool,
}

impl SimReport {
    /// One line: `passed: cycle 8.46 s` or the reason it failed.
    pub fn verdict(&self) -> String {
        if self.passed {
            let ms = self
                .cycles
                .first()
                .and_then(|c| c.cycle_ms)
                .unwrap_or_default();
            format!("passed: cycle time {}", seconds(ms))
        } else {
            format!("FAILED: {}", self.reason())
        }
    }

    /// Why the run failed: a stall with the run-throughs that explain it, or
    /// else the first problem.
    pub fn reason(&self) -> String {
        let stall = self.problems.iter().find(|p| p.kind == ProblemKind::Stall);
        let Some(first) = stall.or(self.problems.first()) else {
            return "no problem recorded".to_string();
        };
        let mut text = first.message.clone();
        if first.kind == ProblemKind::Stall {
            for p in self
                .problems
                .iter()
                .filter(|p| p.kind == ProblemKind::RanThrough)
            {
                text.push_str("; ");
                text.push_str(&p.message);
            }
        }
        text
    }

    /// Whether any hazard happened.
    pub fn hazard(&self) -> Option<&Problem> {
        self.problems.iter().find(|p| p.kind.is_hazard())
    }
}

/// `1.23 s`.
pub fn seconds(ms: u64) -> String {
    format!("{:.2} s", ms as f64 / 1000.0)
}

/// The per-step timing of the first cycle as an aligned text table, and a line
/// about the second cycle.
pub fn step_table(report: &SimReport) -> String {
    let mut lines = vec![format!(
        "  {:<6} {:>9} {:>9}  moves",
        "step", "start", "duration"
    )];
    if let Some(cycle) = report.cycles.first() {
        for s in &cycle.steps {
            let mut line = format!(
                "  {:<6} {:>9} {:>9}  {}",
                s.step,
                seconds(s.start_ms),
                seconds(s.duration_ms),
                s.moves
            );
            if !s.notes.is_empty() {
                line.push_str(&format!("  ({})", s.notes));
            }
            lines.push(line);
        }
    }
    match (report.cycles.first(), report.cycles.get(1)) {
        (Some(first), Some(second))
            if first.cycle_ms.is_some() && first.cycle_ms == second.cycle_ms =>
        {
            lines.push(format!(
                "  second START: identical cycle of {}",
                seconds(second.cycle_ms.unwrap_or_default())
            ));
        }
        _ => {}
    }
    // Each jump both ways: the plain cycles leave every jump they test
    // (said once: a jump cycle's list would grow with the square of the
    // jumps), the jump cycles take one each.
    let not_taken = |cycle: &CycleReport| {
        let jumps: Vec<String> = cycle
            .declined
            .iter()
            .map(|(step, jump)| format!("{jump} after step {step}"))
            .collect();
        if jumps.is_empty() {
            String::new()
        } else {
            format!("; not taken: {}", jumps.join(", "))
        }
    };
    let plain: Vec<String> = report
        .cycles
        .iter()
        .enumerate()
        .filter(|(_, c)| c.jump.is_none() && !c.declined.is_empty())
        .map(|(n, _)| (n + 1).to_string())
        .collect();
    if let Some(first) = report.cycles.iter().find(|c| c.jump.is_none())
        && !plain.is_empty()
    {
        lines.push(format!(
            "  cycle{} {} (take no jump){}",
            if plain.len() > 1 { "s" } else { "" },
            plain.join(", "),
            not_taken(first)
        ));
    }
    for (n, cycle) in report.cycles.iter().enumerate() {
        let Some((step, jump)) = &cycle.jump else {
            continue;
        };
        let fired: Vec<String> = cycle.steps.iter().map(|s| s.step.to_string()).collect();
        lines.push(format!(
            "  cycle {} (takes {jump} after step {step}): steps {}{}",
            n + 1,
            fired.join(", "),
            cycle
                .cycle_ms
                .map_or(String::new(), |ms| format!(", cycle of {}", seconds(ms))),
        ));
    }
    for p in &report.problems {
        lines.push(format!("  at {}: {}", seconds(p.time_ms), p.message));
    }
    lines.join("\n")
}
