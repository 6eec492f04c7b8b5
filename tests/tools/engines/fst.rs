//! An interpreter of the Festo FST statement list that steptable writes
//! (`NAME.fst.txt`), built from the text alone: no FST engine exists outside
//! Festo's Windows software. It shares no code with the emitter.
//!
//! The subset it runs, as FST defines it:
//! - programs `P0` (steps) and `P1` (no steps, every rule every cycle), each
//!   beginning at a comment line `" ===== program Pn =====`;
//! - `STEP label`, `IF`, `AND`, `N operand` (negation), `NOP` (always true),
//!   `THEN`, `SET`, `RESET`, `LOAD Vn` / `TO TPn` (timer preset in 1/100 s),
//!   `JMP TO label`;
//! - operands `I w.b`, `O w.b`, `F w.b`, `T n` (on while the timer runs),
//!   `P n` (`SET Pn` starts program n at its first step, `RESET Pn` stops it).
//!
//! A cycle advances the timers, runs P0's active step, then every rule of P1
//! in order. A step's sentences (`IF … THEN …`) run in order as FST's STL
//! defines them: one whose condition holds runs its actions, and `JMP TO`
//! leaves the step at once; one whose condition fails passes to the next
//! sentence, except the last, which repeats the step in the next cycle; once
//! the last sentence has run, the next step is active (and tested in the
//! next cycle). Anything else is an error.

use std::collections::BTreeMap;

use steptable::address::Allocation;
use steptable::simulate::io::IoTrace;

use super::Stepped;

#[derive(Debug, Clone, PartialEq)]
enum Action {
    Set(String),
    Reset(String),
    Load(u64),
    To(String),
    Jump(String),
}

#[derive(Debug, Clone, Default)]
struct Rule {
    /// `(negated, operand)`; `NOP` is no literal.
    condition: Vec<(bool, String)>,
    actions: Vec<Action>,
}

#[derive(Debug, Clone)]
struct Step {
    label: String,
    /// Its sentences, in order.
    rules: Vec<Rule>,
}

#[derive(Debug, Default)]
struct Program {
    steps: Vec<Step>,
    rules: Vec<Rule>,
}

/// Parses the statement list; an unknown construct is an error naming its line.
fn parse(text: &str) -> Result<BTreeMap<u32, Program>, String> {
    let mut programs: BTreeMap<u32, Program> = BTreeMap::new();
    let mut current: Option<u32> = None;
    // Whether the rule being read is still in its condition.
    let mut in_condition = false;
    for (n, raw) in text.lines().enumerate() {
        let at = |msg: &str| format!("line {}: {msg}: {raw}", n + 1);
        if let Some(comment) = raw.trim_start().strip_prefix('"') {
            if let Some(rest) = comment.trim().strip_prefix("===== program P") {
                let number = rest.trim_end_matches('=').trim();
                let number = number.parse().map_err(|_| at("bad program header"))?;
                programs.insert(number, Program::default());
                current = Some(number);
            }
            continue;
        }
        let code = raw.split('"').next().unwrap_or("");
        let words: Vec<&str> = code.split_whitespace().collect();
        if words.is_empty() {
            continue;
        }
        let program = programs
            .get_mut(&current.ok_or_else(|| at("statement before any program"))?)
            .expect("current program");
        let mut words = words.as_slice();
        match words[0] {
            "STEP" => {
                let label = words.get(1).ok_or_else(|| at("STEP without label"))?;
                program.steps.push(Step {
                    label: label.to_string(),
                    rules: Vec::new(),
                });
                in_condition = false;
                continue;
            }
            "IF" => {
                match program.steps.last_mut() {
                    None => program.rules.push(Rule::default()),
                    Some(step) => step.rules.push(Rule::default()),
                }
                in_condition = true;
                if words[1..] != ["NOP"] {
                    push_literal(program, &words[1..]).map_err(&at)?;
                }
                continue;
            }
            "AND" => {
                if !in_condition {
                    return Err(at("AND outside a condition"));
                }
                push_literal(program, &words[1..]).map_err(&at)?;
                continue;
            }
            "THEN" => {
                if !in_condition {
                    return Err(at("THEN without IF"));
                }
                in_condition = false;
                words = &words[1..];
            }
            _ if in_condition => return Err(at("unknown condition statement")),
            _ => {}
        }
        let action = match words {
            ["SET", op] => Action::Set(op.to_string()),
            ["RESET", op] => Action::Reset(op.to_string()),
            ["LOAD", v] if v.starts_with('V') => {
                Action::Load(v[1..].parse().map_err(|_| at("bad constant"))?)
            }
            ["TO", tp] if tp.starts_with("TP") => Action::To(tp.to_string()),
            ["JMP", "TO", label] => Action::Jump(label.to_string()),
            ["NOP"] => continue,
            _ => return Err(at("unknown statement")),
        };
        let r = rule(program).ok_or_else(|| at("action outside a rule"))?;
        r.actions.push(action);
    }
    Ok(programs)
}

/// The rule being read: the last step's, or in a program without steps the
/// last rule.
fn rule(program: &mut Program) -> Option<&mut Rule> {
    if program.rules.is_empty() {
        program.steps.last_mut().and_then(|s| s.rules.last_mut())
    } else {
        program.rules.last_mut()
    }
}

/// Adds the literal `words` (`N I0.1`, `F0.4`) to the rule being read.
fn push_literal(program: &mut Program, words: &[&str]) -> Result<(), &'static str> {
    let literal = literal(words).ok_or("bad condition")?;
    rule(program).ok_or("no rule")?.condition.push(literal);
    Ok(())
}

fn literal(words: &[&str]) -> Option<(bool, String)> {
    match words {
        ["N", op] => Some((true, op.to_string())),
        [op] if *op != "N" => Some((false, op.to_string())),
        _ => None,
    }
}

/// The machine state the statement list runs on.
struct Plc {
    bits: BTreeMap<String, bool>,
    /// Timer n: elapsed and preset milliseconds while it runs.
    timers: BTreeMap<String, (u64, u64)>,
    presets: BTreeMap<String, u64>,
    accumulator: u64,
    /// Per program: running, and the index of its active step.
    state: BTreeMap<u32, (bool, usize)>,
}

impl Plc {
    fn read(&self, operand: &str) -> bool {
        if operand.starts_with('T') {
            return self.timers.contains_key(operand);
        }
        self.bits.get(operand).copied().unwrap_or(false)
    }

    fn holds(&self, rule: &Rule) -> bool {
        rule.condition.iter().all(|(neg, op)| self.read(op) != *neg)
    }

    /// Runs a rule's actions; a jump target for P0 if one was given.
    fn act(&mut self, rule: &Rule) -> Result<Option<String>, String> {
        let mut jump = None;
        for action in &rule.actions {
            match action {
                Action::Set(op) | Action::Reset(op) => {
                    let on = matches!(action, Action::Set(_));
                    if let Some(n) = op.strip_prefix('P') {
                        let n: u32 = n.parse().map_err(|_| format!("bad program {op}"))?;
                        self.state.insert(n, (on, 0));
                    } else if op.starts_with('T') && !op.starts_with("TP") {
                        if on {
                            let preset = self.presets.get(&format!("TP{}", &op[1..])).copied();
                            let preset =
                                preset.ok_or_else(|| format!("{op} started with no preset"))?;
                            self.timers.insert(op.clone(), (0, preset * 10));
                        } else {
                            self.timers.remove(op);
                        }
                    } else if op.starts_with(['O', 'F']) {
                        self.bits.insert(op.clone(), on);
                    } else {
                        return Err(format!("cannot set or reset {op}"));
                    }
                }
                Action::Load(v) => self.accumulator = *v,
                Action::To(tp) => {
                    self.presets.insert(tp.clone(), self.accumulator);
                }
                Action::Jump(label) => jump = Some(label.clone()),
            }
        }
        Ok(jump)
    }
}

/// Runs `text` on the recorded inputs (operands from the Festo allocation);
/// the outputs of every scan.
pub fn run(text: &str, trace: &IoTrace, festo: &Allocation) -> Result<Vec<Vec<bool>>, String> {
    execute(text, trace, festo).map(|(outputs, _)| outputs)
}

/// Like [`run`], with the step P0 is in at the end of every scan (its
/// label). `STEP INIT`, which runs once as P0 starts (setting P1 going and
/// the memories' first values), is part of the initial step 0.
pub fn run_stepped(text: &str, trace: &IoTrace, festo: &Allocation) -> Result<Stepped, String> {
    let (outputs, labels) = execute(text, trace, festo)?;
    let steps = labels
        .iter()
        .map(|label| match label.as_str() {
            "INIT" => Ok(steptable::program::INITIAL_STEP),
            other => other
                .parse()
                .map_err(|_| format!("STEP {other} is not a step number")),
        })
        .collect::<Result<_, _>>()?;
    Ok(Stepped { outputs, steps })
}

/// The outputs and P0's active step label of every scan.
fn execute(
    text: &str,
    trace: &IoTrace,
    festo: &Allocation,
) -> Result<(Vec<Vec<bool>>, Vec<String>), String> {
    let programs = parse(text)?;
    let operand = |s| {
        festo
            .address_of(s)
            .map(|a| a.display(festo.mnemonic))
            .ok_or_else(|| format!("{s:?} has no Festo address"))
    };
    let inputs: Vec<String> = trace
        .signals
        .inputs
        .iter()
        .map(|s| operand(*s))
        .collect::<Result<_, _>>()?;
    let outputs: Vec<String> = trace
        .signals
        .outputs
        .iter()
        .map(|s| operand(*s))
        .collect::<Result<_, _>>()?;
    let mut plc = Plc {
        bits: BTreeMap::new(),
        timers: BTreeMap::new(),
        presets: BTreeMap::new(),
        accumulator: 0,
        // P0 runs from power-up; the others when started.
        state: programs.keys().map(|&n| (n, (n == 0, 0))).collect(),
    };
    let mut result = Vec::with_capacity(trace.scans.len());
    let mut labels = Vec::with_capacity(trace.scans.len());
    for scan in &trace.scans {
        for (op, value) in inputs.iter().zip(&scan.inputs) {
            plc.bits.insert(op.clone(), *value);
        }
        let ms = trace.scan_ms as u64;
        plc.timers.retain(|_, (elapsed, preset)| {
            *elapsed += ms;
            *elapsed < *preset
        });
        for (&number, program) in &programs {
            let (running, active) = plc.state[&number];
            if !running {
                continue;
            }
            if program.steps.is_empty() {
                for rule in &program.rules {
                    if plc.holds(rule) {
                        plc.act(rule)?;
                    }
                }
                continue;
            }
            let step = &program.steps[active];
            let last = step.rules.len().saturating_sub(1);
            for (i, sentence) in step.rules.iter().enumerate() {
                if !plc.holds(sentence) {
                    // The last sentence failing repeats the step; another
                    // passes to the next sentence.
                    continue;
                }
                let jump = plc.act(sentence)?;
                // The step's own actions may have restarted or stopped it.
                if plc.state[&number] != (running, active) {
                    break;
                }
                let next = match jump {
                    Some(label) => program
                        .steps
                        .iter()
                        .position(|s| s.label == label)
                        .ok_or_else(|| format!("JMP TO {label}: no such step"))?,
                    None if i < last => continue,
                    None if active + 1 < program.steps.len() => active + 1,
                    None => {
                        return Err(format!(
                            "STEP {} falls off the end of P{number}",
                            step.label
                        ));
                    }
                };
                plc.state.insert(number, (true, next));
                break;
            }
        }
        result.push(outputs.iter().map(|o| plc.read(o)).collect());
        let p0 = programs
            .get(&0)
            .zip(plc.state.get(&0))
            .and_then(|(program, (_, active))| program.steps.get(*active));
        labels.push(p0.map_or_else(String::new, |step| step.label.clone()));
    }
    Ok((result, labels))
}

/// The interpreter refuses what it does not know rather than guessing.
pub fn unknown_statements_are_refused() {
    assert!(parse("\" ===== program P0 =====\nSTEP 1\n  IF I0.1\n  OR I0.2\n").is_err());
    assert!(parse("STEP 1\n").is_err());
}
