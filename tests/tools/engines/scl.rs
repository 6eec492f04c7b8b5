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

#[derive(Debug, Clone, PartialEq)]
enum Token {
    Word(String),
    Own(String),
    Tag(String),
    Number(String),
    Time(i64),
    Symbol(&'static str),
}

/// The text as tokens; comments, attributes and REGION names dropped.
fn tokens(text: &str) -> Result<Vec<Token>, String> {
    let chars: Vec<char> = text.chars().collect();
    let mut out = Vec::new();
    let mut i = 0;
    let word_char = |c: char| c.is_ascii_alphanumeric() || c == '_';
    while i < chars.len() {
        let c = chars[i];
        let rest: String = chars[i..chars.len().min(i + 2)].iter().collect();
        if c.is_whitespace() {
            i += 1;
        } else if rest == "//" {
            while i < chars.len() && chars[i] != '\n' {
                i += 1;
            }
        } else if rest == "(*" {
            let end = (i + 2..chars.len().saturating_sub(1))
                .find(|&j| chars[j] == '*' && chars[j + 1] == ')')
                .ok_or("unclosed (* comment")?;
            i = end + 2;
        } else if c == '{' {
            i += chars[i..]
                .iter()
                .position(|&c| c == '}')
                .ok_or("unclosed {")?
                + 1;
        } else if c == '"' {
            let len = chars[i + 1..]
                .iter()
                .position(|&c| c == '"')
                .ok_or("unclosed \"")?;
            out.push(Token::Tag(chars[i + 1..i + 1 + len].iter().collect()));
            i += len + 2;
        } else if c == '#' {
            let len = chars[i + 1..].iter().take_while(|c| word_char(**c)).count();
            if len == 0 {
                return Err("# without a name".to_string());
            }
            out.push(Token::Own(chars[i + 1..i + 1 + len].iter().collect()));
            i += len + 1;
        } else if c.is_ascii_digit() {
            let len = chars[i..]
                .iter()
                .take_while(|c| c.is_ascii_digit() || **c == '.')
                .count();
            out.push(Token::Number(chars[i..i + len].iter().collect()));
            i += len;
        } else if word_char(c) {
            let len = chars[i..].iter().take_while(|c| word_char(**c)).count();
            let word: String = chars[i..i + len].iter().collect();
            i += len;
            if word.eq_ignore_ascii_case("T") && chars.get(i) == Some(&'#') {
                let len = chars[i + 1..].iter().take_while(|c| word_char(**c)).count();
                let literal: String = chars[i + 1..i + 1 + len].iter().collect();
                out.push(Token::Time(time_ms(&literal)?));
                i += len + 1;
            } else if word.eq_ignore_ascii_case("REGION") {
                // The region's name runs to the end of the line.
                while i < chars.len() && chars[i] != '\n' {
                    i += 1;
                }
            } else if !word.eq_ignore_ascii_case("END_REGION") {
                out.push(Token::Word(word.to_ascii_uppercase()));
            }
        } else {
            let symbol = [":=", ":", ";", "(", ")", ",", "."]
                .into_iter()
                .find(|s| chars[i..].starts_with(&s.chars().collect::<Vec<_>>()))
                .ok_or_else(|| format!("unexpected {c:?}"))?;
            out.push(Token::Symbol(symbol));
            i += symbol.len();
        }
    }
    Ok(out)
}

/// Milliseconds of a time literal's body (`2s`, `2200ms`, `1m30s`, `1h`).
fn time_ms(text: &str) -> Result<i64, String> {
    let lower = text.to_ascii_lowercase().replace('_', "");
    let mut rest = lower.as_str();
    let mut total = 0;
    while !rest.is_empty() {
        let digits = rest.chars().take_while(char::is_ascii_digit).count();
        let value: i64 = rest[..digits]
            .parse()
            .map_err(|_| format!("bad time T#{text}"))?;
        rest = &rest[digits..];
        let (unit, factor) = [
            ("ms", 1),
            ("d", 86_400_000),
            ("h", 3_600_000),
            ("m", 60_000),
            ("s", 1000),
        ]
        .into_iter()
        .find(|(u, _)| rest.starts_with(u))
        .ok_or_else(|| format!("bad time unit in T#{text}"))?;
        total += value * factor;
        rest = &rest[unit.len()..];
    }
    Ok(total)
}

#[derive(Debug, Clone)]
enum Expr {
    Const(Value),
    Own(String),
    Tag(String),
    Member(String, String),
    Not(Box<Expr>),
    And(Box<Expr>, Box<Expr>),
    Or(Box<Expr>, Box<Expr>),
}

#[derive(Debug, Clone)]
enum Stmt {
    Assign(Expr, Expr),
    If(Vec<(Expr, Vec<Stmt>)>, Vec<Stmt>),
    Case(Expr, Vec<(i64, Vec<Stmt>)>),
    /// A `TON_TIME` multi-instance called with its inputs.
    Call(String, Vec<(String, Expr)>),
    /// An instance DB called: its function block runs.
    CallDb(String),
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Value {
    Bool(bool),
    Int(i64),
    Time(i64),
}

struct Block {
    statics: Vec<(String, String, Option<Value>)>,
    body: Vec<Stmt>,
}

#[derive(Default)]
struct Source {
    blocks: BTreeMap<String, Block>,
    /// Instance DB → its function block.
    instances: BTreeMap<String, String>,
    main: Option<Vec<Stmt>>,
}

struct Parser {
    tokens: Vec<Token>,
    at: usize,
}

impl Parser {
    fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.at)
    }

    fn next(&mut self) -> Result<Token, String> {
        let t = self.peek().cloned().ok_or("unexpected end of file")?;
        self.at += 1;
        Ok(t)
    }

    fn is_word(&self, word: &str) -> bool {
        self.peek() == Some(&Token::Word(word.to_string()))
    }

    fn expect(&mut self, token: Token) -> Result<(), String> {
        let got = self.next()?;
        if got == token {
            Ok(())
        } else {
            Err(format!(
                "expected {token:?}, found {got:?} (token {})",
                self.at
            ))
        }
    }

    fn word(&mut self, word: &str) -> Result<(), String> {
        self.expect(Token::Word(word.to_string()))
    }

    fn symbol(&mut self, s: &'static str) -> Result<(), String> {
        self.expect(Token::Symbol(s))
    }

    fn tag_name(&mut self) -> Result<String, String> {
        match self.next()? {
            Token::Tag(name) => Ok(name),
            other => Err(format!("expected a \"name\", found {other:?}")),
        }
    }

    /// `VERSION : 0.1`, `NON_RETAIN`: read over.
    fn header(&mut self) -> Result<(), String> {
        loop {
            if self.is_word("VERSION") {
                self.next()?;
                self.symbol(":")?;
                self.next()?;
            } else if self.is_word("NON_RETAIN") {
                self.next()?;
            } else {
                return Ok(());
            }
        }
    }

    fn source(&mut self) -> Result<Source, String> {
        let mut source = Source::default();
        while let Some(token) = self.peek().cloned() {
            match token {
                Token::Word(w) if w == "FUNCTION_BLOCK" => {
                    self.next()?;
                    let name = self.tag_name()?;
                    self.header()?;
                    let statics = self.statics()?;
                    self.word("BEGIN")?;
                    let body = self.statements(&["END_FUNCTION_BLOCK"])?;
                    self.next()?;
                    source.blocks.insert(name, Block { statics, body });
                }
                Token::Word(w) if w == "DATA_BLOCK" => {
                    self.next()?;
                    let name = self.tag_name()?;
                    self.header()?;
                    let fb = self.tag_name()?;
                    self.word("BEGIN")?;
                    self.word("END_DATA_BLOCK")?;
                    source.instances.insert(name, fb);
                }
                Token::Word(w) if w == "ORGANIZATION_BLOCK" => {
                    self.next()?;
                    if self.tag_name()? != "Main" {
                        return Err("the cyclic OB must be \"Main\"".to_string());
                    }
                    self.header()?;
                    self.word("BEGIN")?;
                    source.main = Some(self.statements(&["END_ORGANIZATION_BLOCK"])?);
                    self.next()?;
                }
                other => return Err(format!("expected a block, found {other:?}")),
            }
        }
        Ok(source)
    }

    fn statics(&mut self) -> Result<Vec<(String, String, Option<Value>)>, String> {
        self.word("VAR")?;
        let mut statics = Vec::new();
        while !self.is_word("END_VAR") {
            let Token::Word(name) = self.next()? else {
                return Err("expected a static's name".to_string());
            };
            self.symbol(":")?;
            let Token::Word(data_type) = self.next()? else {
                return Err(format!("{name} has no type"));
            };
            let initial = if self.peek() == Some(&Token::Symbol(":=")) {
                self.next()?;
                match self.expression()? {
                    Expr::Const(v) => Some(v),
                    other => return Err(format!("{name}: start value {other:?}")),
                }
            } else {
                None
            };
            self.symbol(";")?;
            statics.push((name.to_ascii_lowercase(), data_type, initial));
        }
        self.next()?;
        Ok(statics)
    }

    /// Statements up to one of `ends` (left unread).
    fn statements(&mut self, ends: &[&str]) -> Result<Vec<Stmt>, String> {
        let mut list = Vec::new();
        loop {
            match self.peek() {
                Some(Token::Word(w)) if ends.contains(&w.as_str()) => return Ok(list),
                // A CASE label ends the statements of the branch before.
                Some(Token::Number(_)) if ends.contains(&"<label>") => return Ok(list),
                None => return Err(format!("missing {}", ends.join(" or "))),
                _ => list.push(self.statement()?),
            }
        }
    }

    fn statement(&mut self) -> Result<Stmt, String> {
        if self.is_word("IF") {
            self.next()?;
            let mut arms = Vec::new();
            let mut otherwise = Vec::new();
            loop {
                let condition = self.expression()?;
                self.word("THEN")?;
                arms.push((condition, self.statements(&["ELSIF", "ELSE", "END_IF"])?));
                match self.next()? {
                    Token::Word(w) if w == "ELSIF" => continue,
                    Token::Word(w) if w == "ELSE" => {
                        otherwise = self.statements(&["END_IF"])?;
                        self.next()?;
                    }
                    _ => {}
                }
                break;
            }
            self.symbol(";")?;
            return Ok(Stmt::If(arms, otherwise));
        }
        if self.is_word("CASE") {
            self.next()?;
            let selector = self.expression()?;
            self.word("OF")?;
            let mut branches = Vec::new();
            while !self.is_word("END_CASE") {
                let Token::Number(n) = self.next()? else {
                    return Err("expected a CASE label".to_string());
                };
                self.symbol(":")?;
                let n = n.parse().map_err(|_| format!("CASE label {n}"))?;
                branches.push((n, self.statements(&["END_CASE", "<label>"])?));
            }
            self.next()?;
            self.symbol(";")?;
            return Ok(Stmt::Case(selector, branches));
        }
        match self.next()? {
            Token::Own(name) if self.peek() == Some(&Token::Symbol("(")) => {
                self.next()?;
                let mut args = Vec::new();
                while self.peek() != Some(&Token::Symbol(")")) {
                    let Token::Word(param) = self.next()? else {
                        return Err("expected a parameter".to_string());
                    };
                    self.symbol(":=")?;
                    args.push((param, self.expression()?));
                    if self.peek() == Some(&Token::Symbol(",")) {
                        self.next()?;
                    }
                }
                self.next()?;
                self.symbol(";")?;
                Ok(Stmt::Call(name.to_ascii_lowercase(), args))
            }
            Token::Tag(db) if self.peek() == Some(&Token::Symbol("(")) => {
                self.next()?;
                self.symbol(")")?;
                self.symbol(";")?;
                Ok(Stmt::CallDb(db))
            }
            token @ (Token::Own(_) | Token::Tag(_)) => {
                let target = self.operand(token)?;
                self.symbol(":=")?;
                let value = self.expression()?;
                self.symbol(";")?;
                Ok(Stmt::Assign(target, value))
            }
            other => Err(format!(
                "unknown statement at {other:?} (token {})",
                self.at
            )),
        }
    }

    fn operand(&mut self, token: Token) -> Result<Expr, String> {
        Ok(match token {
            Token::Own(name) if self.peek() == Some(&Token::Symbol(".")) => {
                self.next()?;
                let Token::Word(member) = self.next()? else {
                    return Err(format!("#{name}. without a member"));
                };
                Expr::Member(name.to_ascii_lowercase(), member)
            }
            Token::Own(name) => Expr::Own(name.to_ascii_lowercase()),
            Token::Tag(name) => Expr::Tag(name),
            other => return Err(format!("expected an operand, found {other:?}")),
        })
    }

    fn expression(&mut self) -> Result<Expr, String> {
        let mut left = self.conjunction()?;
        while self.is_word("OR") {
            self.next()?;
            left = Expr::Or(Box::new(left), Box::new(self.conjunction()?));
        }
        Ok(left)
    }

    fn conjunction(&mut self) -> Result<Expr, String> {
        let mut left = self.unary()?;
        while self.is_word("AND") {
            self.next()?;
            left = Expr::And(Box::new(left), Box::new(self.unary()?));
        }
        Ok(left)
    }

    fn unary(&mut self) -> Result<Expr, String> {
        match self.next()? {
            Token::Word(w) if w == "NOT" => Ok(Expr::Not(Box::new(self.unary()?))),
            Token::Word(w) if w == "TRUE" => Ok(Expr::Const(Value::Bool(true))),
            Token::Word(w) if w == "FALSE" => Ok(Expr::Const(Value::Bool(false))),
            Token::Number(n) => Ok(Expr::Const(Value::Int(
                n.parse().map_err(|_| format!("number {n}"))?,
            ))),
            Token::Time(ms) => Ok(Expr::Const(Value::Time(ms))),
            Token::Symbol("(") => {
                let e = self.expression()?;
                self.symbol(")")?;
                Ok(e)
            }
            token => self.operand(token),
        }
    }
}

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
