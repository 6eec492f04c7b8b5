//! A small evaluator of the Excel formula subset the template's cell
//! validation uses (OR, AND, TRIM, LEFT, MID, UPPER, FIND, ISNUMBER, VALUE,
//! SUBSTITUTE, CLEAN, UNICHAR, string literals, numbers, `&`, `=` and one
//! cell reference), so a test can ask what the written rule says of a cell
//! without Excel.

#[derive(Debug, Clone, PartialEq)]
pub enum V {
    Str(String),
    Num(f64),
    Bool(bool),
    Err,
}

impl V {
    fn text(&self) -> String {
        match self {
            V::Str(s) => s.clone(),
            V::Num(n) => n.to_string(),
            V::Bool(b) => if *b { "TRUE" } else { "FALSE" }.to_string(),
            V::Err => String::new(),
        }
    }
    fn truth(&self) -> bool {
        match self {
            V::Bool(b) => *b,
            V::Num(n) => *n != 0.0,
            _ => false,
        }
    }
    fn num(&self) -> f64 {
        match self {
            V::Num(n) => *n,
            V::Str(s) => s.trim().parse().unwrap_or(f64::NAN),
            _ => f64::NAN,
        }
    }
}

struct Parser<'a> {
    chars: Vec<char>,
    at: usize,
    cell: &'a str,
}

impl Parser<'_> {
    fn peek(&self) -> Option<char> {
        self.chars.get(self.at).copied()
    }
    fn expr(&mut self) -> V {
        let left = self.concat();
        if self.peek() == Some('=') {
            self.at += 1;
            let right = self.concat();
            // Excel compares text without regard to case.
            return V::Bool(left.text().to_uppercase() == right.text().to_uppercase());
        }
        left
    }
    /// `a & b & …`: text joined, binding tighter than `=`.
    fn concat(&mut self) -> V {
        let mut value = self.term();
        while self.peek() == Some('&') {
            self.at += 1;
            let right = self.term();
            value = V::Str(value.text() + &right.text());
        }
        value
    }

    fn term(&mut self) -> V {
        match self.peek() {
            Some('"') => {
                self.at += 1;
                let mut s = String::new();
                loop {
                    let c = self.chars[self.at];
                    self.at += 1;
                    if c == '"' {
                        if self.peek() == Some('"') {
                            s.push('"');
                            self.at += 1;
                            continue;
                        }
                        break;
                    }
                    s.push(c);
                }
                V::Str(s)
            }
            Some(c) if c.is_ascii_digit() => {
                let start = self.at;
                while self.peek().is_some_and(|c| c.is_ascii_digit() || c == '.') {
                    self.at += 1;
                }
                V::Num(
                    self.chars[start..self.at]
                        .iter()
                        .collect::<String>()
                        .parse()
                        .unwrap(),
                )
            }
            _ => {
                let start = self.at;
                while self
                    .peek()
                    .is_some_and(|c| c.is_ascii_alphanumeric() || c == '_' || c == '.')
                {
                    self.at += 1;
                }
                let name: String = self.chars[start..self.at].iter().collect();
                // Functions newer than Excel 2007 are written `_xlfn.NAME`.
                let name = name.trim_start_matches("_xlfn.").to_string();
                if self.peek() != Some('(') {
                    assert_eq!(name, "B4", "only the cell B4 is known");
                    return V::Str(self.cell.to_string());
                }
                self.at += 1;
                let mut args = Vec::new();
                while self.peek() != Some(')') {
                    args.push(self.expr());
                    if self.peek() == Some(',') {
                        self.at += 1;
                    }
                }
                self.at += 1;
                call(&name, &args)
            }
        }
    }
}

fn call(name: &str, a: &[V]) -> V {
    let s = |i: usize| a[i].text();
    match name {
        "OR" => V::Bool(a.iter().any(V::truth)),
        "AND" => V::Bool(a.iter().all(V::truth)),
        "TRIM" => V::Str(
            s(0).split(' ')
                .filter(|w| !w.is_empty())
                .collect::<Vec<_>>()
                .join(" "),
        ),
        "UPPER" => V::Str(s(0).to_uppercase()),
        // The control characters 0 to 31 taken out.
        "CLEAN" => V::Str(s(0).chars().filter(|c| *c as u32 > 31).collect()),
        "UNICHAR" => char::from_u32(a[0].num() as u32).map_or(V::Err, |c| V::Str(c.to_string())),
        "LEFT" => V::Str(s(0).chars().take(a[1].num() as usize).collect()),
        "MID" => V::Str(
            s(0).chars()
                .skip(a[1].num() as usize - 1)
                .take(a[2].num() as usize)
                .collect(),
        ),
        "SUBSTITUTE" => V::Str(s(0).replace(&s(1), &s(2))),
        "FIND" => {
            let hay: Vec<char> = s(1).chars().collect();
            let needle: Vec<char> = s(0).chars().collect();
            if needle.is_empty() {
                return V::Num(1.0);
            }
            (0..hay.len())
                .find(|&i| hay[i..].starts_with(&needle))
                .map_or(V::Err, |i| V::Num(i as f64 + 1.0))
        }
        "ISNUMBER" => V::Bool(matches!(a[0], V::Num(_))),
        "VALUE" => s(0).trim().parse::<f64>().map_or(V::Err, V::Num),
        other => panic!("the evaluator does not know {other}"),
    }
}

/// What `formula` (with its leading `=`) gives for cell B4 holding `cell`.
pub fn evaluate(formula: &str, cell: &str) -> bool {
    let text = formula.trim_start_matches('=');
    let mut p = Parser {
        chars: text.chars().collect(),
        at: 0,
        cell,
    };
    let value = p.expr();
    assert_eq!(p.at, p.chars.len(), "formula not read to its end");
    value.truth()
}
