//! An interpreter of the TIA Portal SCL that steptable writes (`NAME.scl`),
//! built from the text alone: TIA Portal and PLCSIM are Windows software
//! no test can run. It shares no code with the emitter.
//!
//! What it runs, as SCL defines it:
//! - blocks `FUNCTION_BLOCK "fb"` (with `VAR … END_VAR` statics: `Bool`,
//!   `Int`, `Time`, `TON_TIME`, each with an optional start value),
//!   `DATA_BLOCK "db"` naming its function block (an instance DB), and
//!   `ORGANIZATION_BLOCK "Main"`, the cyclic OB, which is what a scan runs;
//!   `{ … }` attributes and `VERSION : 0.1` are read over;
//! - statements `x := e;`, `IF … THEN … ELSIF … ELSE … END_IF;`,
//!   `CASE x OF n: … END_CASE;`, calls `#t(IN := e, PT := e);` of a
//!   `TON_TIME` multi-instance and `"db"();` of an instance DB, `REGION`s;
//! - expressions of `NOT`, `AND`, `OR`, `TRUE`, `FALSE`, integers, time
//!   literals (`T#2s`, `T#2200ms`, `T#1m30s`), `#static`, `"tag"` (a PLC
//!   tag of `NAME.tags.xlsx`, which gives its address) and `#t.Q`.
//!
//! `TON_TIME` is the IEC on-delay: IN rising starts it at the time of the
//! scan, Q is on while IN is and the time since the start has reached PT,
//! IN off resets it. Every scan happens at scan number × scan time.
//! Anything else is an error.

use std::collections::BTreeMap;
use std::path::Path;

use steptable::address::{Allocation, Mnemonic};
use steptable::program::Area;
use steptable::simulate::io::IoTrace;

use super::Stepped;

mod parse;

use parse::{Expr, Parser, Source, Stmt, Value, time_ms, tokens};

/// An IEC on-delay timer's memory.
#[derive(Default, Clone, Copy)]
struct Ton {
    input: bool,
    start: i64,
    q: bool,
}

struct Machine<'a> {
    source: &'a Source,
    /// Every PLC tag of the tag table, by name.
    tags: BTreeMap<String, bool>,
    /// Per instance DB: its statics and its timers.
    statics: BTreeMap<String, BTreeMap<String, Value>>,
    timers: BTreeMap<String, BTreeMap<String, Ton>>,
    now: i64,
}

impl Machine<'_> {
    fn eval(&self, db: &str, e: &Expr) -> Result<Value, String> {
        Ok(match e {
            Expr::Const(v) => *v,
            Expr::Own(name) => *self
                .statics
                .get(db)
                .and_then(|s| s.get(name))
                .ok_or_else(|| format!("#{name} is not declared"))?,
            Expr::Tag(name) => Value::Bool(
                *self
                    .tags
                    .get(name)
                    .ok_or_else(|| format!("\"{name}\" is not in the tag table"))?,
            ),
            Expr::Member(name, member) if member == "Q" => Value::Bool(
                self.timers
                    .get(db)
                    .and_then(|t| t.get(name))
                    .ok_or_else(|| format!("#{name} is not a TON_TIME"))?
                    .q,
            ),
            Expr::Member(name, member) => return Err(format!("#{name}.{member}")),
            Expr::Not(a) => Value::Bool(!self.bool(db, a)?),
            Expr::And(a, b) => Value::Bool(self.bool(db, a)? & self.bool(db, b)?),
            Expr::Or(a, b) => Value::Bool(self.bool(db, a)? | self.bool(db, b)?),
        })
    }

    fn bool(&self, db: &str, e: &Expr) -> Result<bool, String> {
        match self.eval(db, e)? {
            Value::Bool(b) => Ok(b),
            other => Err(format!("{e:?} is {other:?}, not Bool")),
        }
    }

    fn run(&mut self, db: &str, list: &[Stmt]) -> Result<(), String> {
        for stmt in list {
            match stmt {
                Stmt::Assign(target, value) => {
                    let value = self.eval(db, value)?;
                    match target {
                        Expr::Tag(name) => match (self.tags.get_mut(name), value) {
                            (Some(tag), Value::Bool(b)) => *tag = b,
                            _ => return Err(format!("\"{name}\" := {value:?}")),
                        },
                        Expr::Own(name) => {
                            let slot = self
                                .statics
                                .get_mut(db)
                                .and_then(|s| s.get_mut(name))
                                .ok_or_else(|| format!("#{name} is not declared"))?;
                            if std::mem::discriminant(slot) != std::mem::discriminant(&value) {
                                return Err(format!("#{name} := {value:?}: wrong type"));
                            }
                            *slot = value;
                        }
                        other => return Err(format!("cannot assign {other:?}")),
                    }
                }
                Stmt::If(arms, otherwise) => {
                    let mut chosen = otherwise;
                    for (condition, body) in arms {
                        if self.bool(db, condition)? {
                            chosen = body;
                            break;
                        }
                    }
                    self.run(db, chosen)?;
                }
                Stmt::Case(selector, branches) => {
                    let Value::Int(n) = self.eval(db, selector)? else {
                        return Err("CASE on a non-Int".to_string());
                    };
                    if let Some((_, body)) = branches.iter().find(|(label, _)| *label == n) {
                        self.run(db, body)?;
                    }
                }
                Stmt::Call(name, args) => self.call_timer(db, name, args)?,
                Stmt::CallDb(instance) => {
                    let fb = self
                        .source
                        .instances
                        .get(instance)
                        .ok_or_else(|| format!("\"{instance}\" is no instance DB"))?;
                    let block = &self.source.blocks[fb];
                    self.run(instance, &block.body)?;
                }
            }
        }
        Ok(())
    }

    fn call_timer(&mut self, db: &str, name: &str, args: &[(String, Expr)]) -> Result<(), String> {
        let (mut input, mut preset) = (None, None);
        for (param, e) in args {
            match (param.as_str(), self.eval(db, e)?) {
                ("IN", Value::Bool(b)) => input = Some(b),
                ("PT", Value::Time(ms)) => preset = Some(ms),
                (p, v) => return Err(format!("#{name}({p} := {v:?})")),
            }
        }
        let (input, preset) = input
            .zip(preset)
            .ok_or(format!("#{name} needs IN and PT"))?;
        let now = self.now;
        let timer = self
            .timers
            .get_mut(db)
            .and_then(|t| t.get_mut(name))
            .ok_or_else(|| format!("#{name} is not a TON_TIME"))?;
        if input && !timer.input {
            timer.start = now;
        }
        timer.input = input;
        timer.q = input && now - timer.start >= preset;
        Ok(())
    }
}

/// The PLC tags of a TIA tag table export (`NAME.tags.xlsx`): name by
/// logical address (`%I0.1`).
pub fn tag_table(path: &Path) -> Result<BTreeMap<String, String>, String> {
    use calamine::{Reader, Xlsx, open_workbook};
    let mut book: Xlsx<_> = open_workbook(path).map_err(|e| format!("{e}"))?;
    let sheet = book
        .worksheet_range("PLC Tags")
        .map_err(|e| format!("PLC Tags: {e}"))?;
    let mut rows = sheet.rows();
    let header: Vec<String> = rows
        .next()
        .ok_or("empty tag table")?
        .iter()
        .map(|c| c.to_string())
        .collect();
    let column = |name: &str| {
        header
            .iter()
            .position(|h| h == name)
            .ok_or(format!("no {name} column"))
    };
    let (name, address) = (column("Name")?, column("Logical Address")?);
    Ok(rows
        .map(|r| (r[address].to_string(), r[name].to_string()))
        .collect())
}

/// Runs `scl` on the recorded inputs, its tags bound by the tag table's
/// addresses; per scan the outputs and the value of the step counter (the
/// variable the first CASE switches on).
pub fn run_stepped(
    scl: &Path,
    tags: &Path,
    trace: &IoTrace,
    allocation: &Allocation,
) -> Result<Stepped, String> {
    let text = std::fs::read_to_string(scl).map_err(|e| e.to_string())?;
    let table = tag_table(tags)?;
    run_text(&text, &table, trace, allocation)
}

/// The tag of a signal: the tag table's name at its address.
fn tag_of(
    table: &BTreeMap<String, String>,
    allocation: &Allocation,
    signal: steptable::program::Signal,
) -> Result<String, String> {
    let address = allocation
        .address_of(signal)
        .ok_or_else(|| format!("{signal:?} has no address"))?;
    let (byte, bit) = address.byte_bit();
    let letter = match (address.area, allocation.mnemonic) {
        (Area::Input, Mnemonic::En) => "I",
        (Area::Input, Mnemonic::De) => "E",
        (_, Mnemonic::En) => "Q",
        (_, Mnemonic::De) => "A",
    };
    let logical = format!("%{letter}{byte}.{bit}");
    table
        .get(&logical)
        .cloned()
        .ok_or_else(|| format!("no tag at {logical}"))
}

/// [`run_stepped`] on the text of a file.
pub fn run_text(
    text: &str,
    table: &BTreeMap<String, String>,
    trace: &IoTrace,
    allocation: &Allocation,
) -> Result<Stepped, String> {
    let source = Parser {
        tokens: tokens(text)?,
        at: 0,
    }
    .source()?;
    let main = source
        .main
        .as_ref()
        .ok_or("no ORGANIZATION_BLOCK \"Main\"")?;
    let step_var = first_case(&source).ok_or("no CASE over the step")?;
    let inputs: Vec<String> = trace
        .signals
        .inputs
        .iter()
        .map(|s| tag_of(table, allocation, *s))
        .collect::<Result<_, _>>()?;
    let outputs: Vec<String> = trace
        .signals
        .outputs
        .iter()
        .map(|s| tag_of(table, allocation, *s))
        .collect::<Result<_, _>>()?;
    let mut machine = Machine {
        source: &source,
        tags: table.values().map(|n| (n.clone(), false)).collect(),
        statics: BTreeMap::new(),
        timers: BTreeMap::new(),
        now: 0,
    };
    for (db, fb) in &source.instances {
        let block = source
            .blocks
            .get(fb)
            .ok_or_else(|| format!("no FUNCTION_BLOCK \"{fb}\""))?;
        let (mut statics, mut timers) = (BTreeMap::new(), BTreeMap::new());
        for (name, data_type, initial) in &block.statics {
            let default = match data_type.as_str() {
                "BOOL" => Value::Bool(false),
                "INT" => Value::Int(0),
                "TIME" => Value::Time(0),
                "TON_TIME" => {
                    timers.insert(name.clone(), Ton::default());
                    continue;
                }
                other => return Err(format!("#{name}: type {other}")),
            };
            statics.insert(name.clone(), initial.unwrap_or(default));
        }
        machine.statics.insert(db.clone(), statics);
        machine.timers.insert(db.clone(), timers);
    }
    let mut run = Stepped {
        outputs: Vec::new(),
        steps: Vec::new(),
    };
    for (n, scan) in trace.scans.iter().enumerate() {
        machine.now = n as i64 * trace.scan_ms as i64;
        for (tag, value) in inputs.iter().zip(&scan.inputs) {
            machine.tags.insert(tag.clone(), *value);
        }
        machine.run("", main)?;
        run.outputs
            .push(outputs.iter().map(|t| machine.tags[t]).collect());
        let step = machine
            .statics
            .values()
            .find_map(|s| s.get(&step_var))
            .ok_or("the step counter is not a static")?;
        match step {
            Value::Int(k) if *k >= 0 => run.steps.push(*k as usize),
            other => return Err(format!("step counter {other:?}")),
        }
    }
    Ok(run)
}

/// The static the first CASE of a function block switches on.
fn first_case(source: &Source) -> Option<String> {
    source
        .blocks
        .values()
        .flat_map(|b| &b.body)
        .find_map(|s| match s {
            Stmt::Case(Expr::Own(name), _) => Some(name.clone()),
            _ => None,
        })
}

/// The interpreter refuses what it does not know rather than guessing.
pub fn unknown_constructs_are_refused() {
    let parse = |text: &str| {
        Parser {
            tokens: tokens(text)?,
            at: 0,
        }
        .source()
    };
    assert!(
        parse("FUNCTION_BLOCK \"f\" VAR END_VAR BEGIN WHILE TRUE DO END_WHILE; END_FUNCTION_BLOCK")
            .is_err()
    );
    assert!(
        parse("FUNCTION_BLOCK \"f\" VAR x : Bool; END_VAR BEGIN #x := TRUE END_FUNCTION_BLOCK")
            .is_err()
    );
    assert!(parse("ORGANIZATION_BLOCK \"OB2\" BEGIN END_ORGANIZATION_BLOCK").is_err());
    assert!(time_ms("2x").is_err());
    assert_eq!(time_ms("1m30s").unwrap(), 90_000);
    assert_eq!(time_ms("2200ms").unwrap(), 2200);
    assert_eq!(time_ms("2S").unwrap(), 2000);
}
