//! The SCL subset's tokens and parser, for the interpreter beside it
//! (`scl/mod.rs` says what the subset is). Comments, `{ … }` attributes and
//! REGION names are dropped; anything the subset lacks is an error.

use std::collections::BTreeMap;

#[derive(Debug, Clone, PartialEq)]
pub(super) enum Token {
    Word(String),
    Own(String),
    Tag(String),
    Number(String),
    Time(i64),
    Symbol(&'static str),
}

/// The text as tokens; comments, attributes and REGION names dropped.
pub(super) fn tokens(text: &str) -> Result<Vec<Token>, String> {
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
pub(super) fn time_ms(text: &str) -> Result<i64, String> {
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
pub(super) enum Expr {
    Const(Value),
    Own(String),
    Tag(String),
    Member(String, String),
    Not(Box<Expr>),
    And(Box<Expr>, Box<Expr>),
    Or(Box<Expr>, Box<Expr>),
}

#[derive(Debug, Clone)]
pub(super) enum Stmt {
    Assign(Expr, Expr),
    If(Vec<(Expr, Vec<Stmt>)>, Vec<Stmt>),
    Case(Expr, Vec<(i64, Vec<Stmt>)>),
    /// A `TON_TIME` multi-instance called with its inputs.
    Call(String, Vec<(String, Expr)>),
    /// An instance DB called: its function block runs.
    CallDb(String),
}

#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Value {
    Bool(bool),
    Int(i64),
    Time(i64),
}

pub(super) struct Block {
    pub(super) statics: Vec<(String, String, Option<Value>)>,
    pub(super) body: Vec<Stmt>,
}

#[derive(Default)]
pub(super) struct Source {
    pub(super) blocks: BTreeMap<String, Block>,
    /// Instance DB → its function block.
    pub(super) instances: BTreeMap<String, String>,
    pub(super) main: Option<Vec<Stmt>>,
}

pub(super) struct Parser {
    pub(super) tokens: Vec<Token>,
    pub(super) at: usize,
}

impl Parser {
    pub(super) fn peek(&self) -> Option<&Token> {
        self.tokens.get(self.at)
    }

    pub(super) fn next(&mut self) -> Result<Token, String> {
        let t = self.peek().cloned().ok_or("unexpected end of file")?;
        self.at += 1;
        Ok(t)
    }

    pub(super) fn is_word(&self, word: &str) -> bool {
        self.peek() == Some(&Token::Word(word.to_string()))
    }

    pub(super) fn expect(&mut self, token: Token) -> Result<(), String> {
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

    pub(super) fn word(&mut self, word: &str) -> Result<(), String> {
        self.expect(Token::Word(word.to_string()))
    }

    pub(super) fn symbol(&mut self, s: &'static str) -> Result<(), String> {
        self.expect(Token::Symbol(s))
    }

    pub(super) fn tag_name(&mut self) -> Result<String, String> {
        match self.next()? {
            Token::Tag(name) => Ok(name),
            other => Err(format!("expected a \"name\", found {other:?}")),
        }
    }

    /// `VERSION : 0.1`, `NON_RETAIN`: read over.
    pub(super) fn header(&mut self) -> Result<(), String> {
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

    pub(super) fn source(&mut self) -> Result<Source, String> {
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

    pub(super) fn statics(&mut self) -> Result<Vec<(String, String, Option<Value>)>, String> {
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
    pub(super) fn statements(&mut self, ends: &[&str]) -> Result<Vec<Stmt>, String> {
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

    pub(super) fn statement(&mut self) -> Result<Stmt, String> {
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

    pub(super) fn operand(&mut self, token: Token) -> Result<Expr, String> {
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

    pub(super) fn expression(&mut self) -> Result<Expr, String> {
        let mut left = self.conjunction()?;
        while self.is_word("OR") {
            self.next()?;
            left = Expr::Or(Box::new(left), Box::new(self.conjunction()?));
        }
        Ok(left)
    }

    pub(super) fn conjunction(&mut self) -> Result<Expr, String> {
        let mut left = self.unary()?;
        while self.is_word("AND") {
            self.next()?;
            left = Expr::And(Box::new(left), Box::new(self.unary()?));
        }
        Ok(left)
    }

    pub(super) fn unary(&mut self) -> Result<Expr, String> {
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
