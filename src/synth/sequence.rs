//! Sequences in letter notation (`A1 A0 B1 B0`): actuators A, B, … with
//! sensors a, b, … (1 when extended) and auxiliary memories W, X, Y, Z. A
//! state is a bit set over all variables; a sequence is valid for a
//! combinational controller when every state before an action is distinct,
//! no action changes nothing, and the cycle ends in its start state.

use std::fmt;

/// Memory names, in the order a search introduces memories (X first, as in
/// the textbooks and the paper's first example).
pub const MEMORIES: [char; 4] = ['X', 'Y', 'Z', 'W'];
/// Most actuators a sequence may have (letters A…L, clear of W…Z).
pub const MAX_ACTUATORS: usize = 12;

/// One operation of a sequence: variable `var` (actuators first, then
/// memories) goes to `value` (`A+`, `m1-`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Operation {
    pub var: usize,
    pub value: bool,
}

/// A sequence of actions over `actuators` actuators and `memories` memories.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub struct Sequence {
    pub actuators: usize,
    pub memories: usize,
    /// The letter of each memory (`X`, `Y`, …), in variable order.
    pub memory_names: Vec<char>,
    pub actions: Vec<Operation>,
}

impl Sequence {
    /// Upper-case name of a variable: `A`, `B`, … or the memory's letter.
    pub fn var_name(&self, var: usize) -> char {
        if var < self.actuators {
            (b'A' + var as u8) as char
        } else {
            self.memory_names
                .get(var - self.actuators)
                .copied()
                .unwrap_or('?')
        }
    }

    /// Lower-case name: the sensor letter or the memory's state.
    pub fn signal_name(&self, var: usize) -> char {
        self.var_name(var).to_ascii_lowercase()
    }

    pub fn variables(&self) -> usize {
        self.actuators + self.memories
    }

    /// `A1`, `X0`.
    pub fn token(&self, action: Operation) -> String {
        format!("{}{}", self.var_name(action.var), u8::from(action.value))
    }

    pub fn is_memory(&self, var: usize) -> bool {
        var >= self.actuators
    }

    /// Each variable starts at the complement of its first operation.
    pub fn initial_state(&self) -> u32 {
        let mut state = 0u32;
        for var in 0..self.variables() {
            if let Some(first) = self.actions.iter().find(|a| a.var == var)
                && !first.value
            {
                state |= 1 << var;
            }
        }
        state
    }

    /// The state before each action, in order.
    pub fn pre_states(&self) -> Vec<u32> {
        let mut state = self.initial_state();
        let mut states = Vec::with_capacity(self.actions.len());
        for a in &self.actions {
            states.push(state);
            state = apply(state, *a);
        }
        states
    }

    /// Every problem that keeps a combinational controller from running this
    /// sequence; empty when it is valid.
    pub fn problems(&self) -> Vec<String> {
        let mut problems = Vec::new();
        let mut state = self.initial_state();
        for (i, a) in self.actions.iter().enumerate() {
            if (state >> a.var) & 1 == u32::from(a.value) {
                problems.push(format!(
                    "action {} ({}) changes nothing",
                    i + 1,
                    self.token(*a)
                ));
            }
            state = apply(state, *a);
        }
        if state != self.initial_state() {
            problems.push("the cycle does not end in its start state".to_string());
        }
        for clash in self.clashes() {
            problems.push(clash.to_string());
        }
        problems
    }

    pub fn is_valid(&self) -> bool {
        self.problems().is_empty()
    }

    /// States met more than once before an action, and the actions after them.
    pub fn clashes(&self) -> Vec<Clash> {
        let states = self.pre_states();
        let mut clashes: Vec<Clash> = Vec::new();
        for (i, s) in states.iter().enumerate() {
            if clashes.iter().any(|c| c.state == *s) {
                continue;
            }
            let positions: Vec<usize> = (i..states.len()).filter(|j| states[*j] == *s).collect();
            if positions.len() > 1 {
                clashes.push(Clash {
                    state: *s,
                    state_text: self.state_text(*s),
                    actions: positions
                        .iter()
                        .map(|p| (p + 1, self.token(self.actions[*p])))
                        .collect(),
                });
            }
        }
        clashes
    }

    /// `a=0 b=1 x=0`.
    pub fn state_text(&self, state: u32) -> String {
        (0..self.variables())
            .map(|v| format!("{}={}", self.signal_name(v), (state >> v) & 1))
            .collect::<Vec<_>>()
            .join(" ")
    }

    /// The actions as text: `A1 X1 A0 B1 X0 B0`.
    pub fn text(&self) -> String {
        self.actions
            .iter()
            .map(|a| self.token(*a))
            .collect::<Vec<_>>()
            .join(" ")
    }
}

/// A state met before more than one action.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Clash {
    pub state: u32,
    pub state_text: String,
    /// (one-based position, token) of each action that follows it.
    pub actions: Vec<(usize, String)>,
}

impl fmt::Display for Clash {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let actions: Vec<String> = self
            .actions
            .iter()
            .map(|(p, t)| format!("{t} (action {p})"))
            .collect();
        write!(
            f,
            "signal clash: {} comes before {}",
            self.state_text,
            actions.join(" and ")
        )
    }
}

pub fn apply(state: u32, action: Operation) -> u32 {
    if action.value {
        state | (1 << action.var)
    } else {
        state & !(1 << action.var)
    }
}

/// Parses `A1 A0 B1 B0`, `A+ A- B+ B-` or `C1+1 C1-0 C2+1 C2-0`. Letters W…Z
/// are memories. Returns the sequence or what is wrong with the text.
pub fn parse(text: &str) -> Result<Sequence, String> {
    let tokens: Vec<&str> = text
        .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
        .filter(|t| !t.is_empty())
        .collect();
    if tokens.is_empty() {
        return Err("the sequence is empty".to_string());
    }
    let mut raw: Vec<(Result<usize, char>, bool)> = Vec::new();
    for token in &tokens {
        let norm = crate::cell::normalize(token);
        let mut chars = norm.chars();
        let first = chars.next().unwrap_or(' ');
        let rest: String = chars.collect();
        // C1+1 (a step-table move) has a sign after the number; C1 is
        // cylinder C's action in letter notation.
        let table_move = first == 'C'
            && rest.starts_with(|c: char| c.is_ascii_digit())
            && rest.contains(['+', '-']);
        let parsed = if table_move {
            // C1+1 / C1-0 from a step table: a two-position actuator.
            match crate::cell::parse_move(&norm) {
                Ok(m) if m.position.is_none_or(|p| p <= 1) => {
                    let value = m.sign == crate::cell::Sign::Plus;
                    if m.position.is_some_and(|p| u32::from(value) != p) {
                        return Err(format!(
                            "\"{token}\": a + move must end at 1 and a - move at 0"
                        ));
                    }
                    (Ok(m.actuator as usize - 1), value)
                }
                Ok(_) => {
                    return Err(format!(
                        "\"{token}\": synthesis handles two-position actuators only (positions 0 and 1); use convert for middle positions"
                    ));
                }
                Err(_) => return Err(format!("\"{token}\" is not an action")),
            }
        } else if first.is_ascii_alphabetic() {
            let value = match rest.as_str() {
                "1" | "+" => true,
                "0" | "-" => false,
                _ => {
                    return Err(format!(
                        "\"{token}\" is not an action (expected e.g. A1, A0, A+ or A-)"
                    ));
                }
            };
            if MEMORIES.contains(&first) {
                (Err(first), value)
            } else {
                (Ok((first as u8 - b'A') as usize), value)
            }
        } else {
            return Err(format!(
                "\"{token}\" is not an action (expected e.g. A1, A0, A+ or A-)"
            ));
        };
        raw.push(parsed);
    }
    // Actuators keep their letters; memories are numbered in order of use.
    let actuators = raw
        .iter()
        .filter_map(|(v, _)| v.ok())
        .max()
        .map_or(0, |m| m + 1);
    if actuators > MAX_ACTUATORS {
        return Err(format!(
            "synthesis handles at most {MAX_ACTUATORS} actuators (A to {})",
            (b'A' + MAX_ACTUATORS as u8 - 1) as char
        ));
    }
    let mut memory_order: Vec<char> = Vec::new();
    for (v, _) in &raw {
        if let Err(m) = v
            && !memory_order.contains(m)
        {
            memory_order.push(*m);
        }
    }
    memory_order.sort_by_key(|m| MEMORIES.iter().position(|x| x == m));
    let actions = raw
        .iter()
        .map(|(v, value)| Operation {
            var: match v {
                Ok(a) => *a,
                Err(m) => actuators + memory_order.iter().position(|x| x == m).unwrap_or(0),
            },
            value: *value,
        })
        .collect();
    Ok(Sequence {
        actuators,
        memories: memory_order.len(),
        memory_names: memory_order,
        actions,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn notations_agree() {
        let a = parse("A1 A0 B1 B0").unwrap();
        assert_eq!(parse("A+ A- B+ B-").unwrap(), a);
        assert_eq!(parse("C1+1 C1-0 C2+1 C2-0").unwrap(), a);
        assert_eq!(a.text(), "A1 A0 B1 B0");
        assert!(parse("C1+2 C1-0").unwrap_err().contains("two-position"));
        assert!(parse("A2").is_err());
    }

    #[test]
    fn the_classic_clash_is_found() {
        let s = parse("A1 A0 B1 B0").unwrap();
        let clashes = s.clashes();
        assert_eq!(clashes.len(), 1);
        assert_eq!(clashes[0].state_text, "a=0 b=0");
        assert_eq!(
            clashes[0].actions,
            [(1, "A1".to_string()), (3, "B1".to_string())]
        );
        assert!(parse("A1 X1 A0 B1 X0 B0").unwrap().is_valid());
        assert!(parse("A1 B1 A0 B0").unwrap().is_valid());
    }
}
