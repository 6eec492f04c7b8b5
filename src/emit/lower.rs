//! The step program lowered once into what every sequence language renders:
//! per SFC step the transitions that leave it (its jumps first, in the order
//! they are tested, then the step's own), each with its condition, the
//! actions of the step it enters, where the sequence then waits and the
//! comments; the rungs that run after the sequence; and the step-flag
//! encoding (one flag per step, one "fired" bit) of the languages that keep
//! the step in bits. ST, FST, AWL, the SFC and the LD bodies all walk this
//! model, so that a step's numbering, the order its transitions are tested
//! in and their comments cannot differ between them.

use crate::program::{Action, Literal, StepKind, StepProgram};
use crate::symbols::SymbolTable;
use crate::table::Move;

/// One transition leaving a step: it fires when its condition holds, runs
/// its actions and makes the sequence wait at program step `next`.
#[derive(Debug, Clone, Copy)]
pub struct Transition<'p> {
    /// Raw text (each language escapes it): the jump (`J:7 if I:reject: on
    /// to STEP 7 in place of STEP 3`) or the step entered and what it does.
    pub comment: &'p str,
    pub condition: &'p [Literal],
    /// The actions of the step entered, in order.
    pub actions: &'p [Action],
    /// The moves of the step whose actions run, for the actions' comments.
    pub moves: &'p [Move],
    /// The SFC step entered (0 at the end of the cycle).
    pub enters: usize,
    /// Index of the program step awaited once it fired.
    pub next: usize,
    /// A jump (`J:` cell) rather than the step's own transition.
    pub jump: bool,
}

/// One step of the sequence as the program waits in it.
#[derive(Debug, Clone)]
pub struct Step<'p> {
    /// Index into the program's steps of the transition awaited here.
    pub index: usize,
    /// The SFC step the program is in: 0 at rest, k while table step k's
    /// moves run.
    pub active: usize,
    /// What that step does, with the engineer's comment (raw text).
    pub active_title: String,
    /// The step's own transition: the step it enters, or the end of the cycle.
    pub entry: String,
    /// The jumps' comments, in the order of [`Step::transitions`].
    jump_comments: Vec<String>,
    /// Whether the step's own transition closes the cycle.
    pub closing: bool,
    program: &'p StepProgram,
}

impl<'p> Step<'p> {
    /// The transitions leaving this step in the order they are tested (the
    /// first that holds fires, at most one per scan): jumps first, then the
    /// step's own, which is always last.
    pub fn transitions(&self) -> Vec<Transition<'_>> {
        let program = self.program;
        let step = &program.steps[self.index];
        let count = program.steps.len();
        let mut all: Vec<Transition> = step
            .jumps
            .iter()
            .zip(&self.jump_comments)
            .map(|(j, comment)| Transition {
                comment,
                condition: &j.condition,
                actions: &j.actions,
                moves: &program.steps[j.fires].moves,
                enters: program.step_entered(j.fires),
                next: j.next,
                jump: true,
            })
            .collect();
        all.push(Transition {
            comment: &self.entry,
            condition: &step.condition,
            actions: &step.actions,
            moves: &step.moves,
            enters: program.step_entered(self.index),
            next: (self.index + 1) % count,
            jump: false,
        });
        all
    }

    /// The heading of a transition's rung or network (raw text): the step
    /// with what it does, then the step entered (`STEP 3: C2-0; J:6 if
    /// I:reject; on to STEP 4: C3+1`); a jump's, the step and the jump
    /// alone, since the step's cell names its jumps already.
    pub fn heading(&self, t: &Transition) -> String {
        match t.jump {
            true => format!("STEP {}: {}", self.active, t.comment),
            false => format!("STEP {}: {}; {}", self.active, self.active_title, t.comment),
        }
    }

    /// The jumps alone, in the order they are tested.
    pub fn jumps(&self) -> Vec<Transition<'_>> {
        let mut all = self.transitions();
        all.pop();
        all
    }

    /// The step's own transition, tested after its jumps.
    pub fn own(&self) -> Transition<'_> {
        let mut all = self.transitions();
        all.pop().expect("a step always has its own transition")
    }
}

/// The step program lowered for the sequence languages.
#[derive(Debug, Clone)]
pub struct Lowered<'p> {
    pub steps: Vec<Step<'p>>,
    /// The step flag of each step, by program step index (`step_0` while
    /// the program waits at the first transition).
    pub flags: Vec<String>,
    /// The bit that lets at most one transition fire per scan, in the
    /// languages that test every transition in one pass (AWL, LD).
    pub fired: String,
}

impl<'p> Lowered<'p> {
    /// The flag of the step the program is in while it waits at program
    /// step `index`.
    pub fn flag(&self, index: usize) -> &str {
        &self.flags[index]
    }
}

/// Lowers `program` with the names of `symbols`.
pub fn lower<'p>(program: &'p StepProgram, symbols: &SymbolTable) -> Lowered<'p> {
    let steps = program
        .steps
        .iter()
        .enumerate()
        .map(|(i, s)| Step {
            index: i,
            active: program.step_in(i),
            active_title: symbols
                .step(i)
                .map_or_else(|| program.title_in(i), |n| n.active_title.clone()),
            entry: super::entry_comment(program, symbols, i),
            jump_comments: s
                .jumps
                .iter()
                .map(|j| super::jump_comment(program, i, j))
                .collect(),
            closing: s.kind == StepKind::EndOfCycle,
            program,
        })
        .collect();
    let flags = (0..program.steps.len())
        .map(|k| {
            symbols.step(k).map_or_else(
                || format!("step_{}", program.step_in(k)),
                |s| s.flag.ident.clone(),
            )
        })
        .collect();
    Lowered {
        steps,
        flags,
        fired: symbols.fired.ident.clone(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::actuator::Valves;
    use crate::program::{ProgramOptions, build};
    use crate::stroke::Strokes;

    #[test]
    fn paper_steps_leave_in_sfc_order() {
        let table = crate::program::tests::paper_table();
        let program = build(
            &table,
            &ProgramOptions::default(),
            &Valves::default(),
            &Strokes::default(),
        );
        let symbols = crate::symbols::SymbolTable::build(&program, &table, &Default::default());
        let lowered = lower(&program, &symbols);
        let walk: Vec<(usize, usize, usize)> = lowered
            .steps
            .iter()
            .map(|s| (s.active, s.own().enters, s.own().next))
            .collect();
        assert_eq!(
            walk,
            [
                (0, 1, 1),
                (1, 2, 2),
                (2, 3, 3),
                (3, 4, 4),
                (4, 5, 5),
                (5, 6, 6),
                (6, 7, 7),
                (7, 8, 8),
                (8, 0, 0)
            ]
        );
        assert!(lowered.steps[8].closing && !lowered.steps[7].closing);
        assert_eq!(lowered.flag(0), "step_0");
        assert_eq!(lowered.flag(8), "step_8");
    }
}
