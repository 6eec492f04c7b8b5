//! Sequences of two-position actuators: in letter notation (`A1 A0 B1 B0`,
//! `A+ A-`) or as a step table writes them (`C1+1 C1-0`). Each actuator
//! keeps the name it was written with (`A`, `C1`, `W`); its sensor is the
//! name in lower case (`a`, `c1`: 1 while extended). The auxiliary memories
//! take letters no actuator uses (X, Y, Z, W first). A state is a bit set over
//! all variables; a sequence is valid for a combinational controller when
//! every state before an action is distinct, no action changes nothing, and
//! the cycle ends in its start state.

use std::fmt;

/// Memory letters, in the order a search introduces memories (X first, as in
/// the textbooks and the paper's first example); letters an actuator uses
/// are skipped.
pub const MEMORIES: [char; 4] = ['X', 'Y', 'Z', 'W'];
/// Further memory letters, for sequences whose actuators use some of X…W;
/// enough that [`MAX_ACTUATORS`] actuators leave four after the name check
/// has taken out S and R.
const MORE_MEMORY_LETTERS: [char; 22] = [
    'V', 'U', 'T', 'S', 'R', 'Q', 'P', 'M', 'N', 'L', 'K', 'J', 'H', 'G', 'F', 'E', 'D', 'C', 'B',
    'A', 'O', 'I',
];
/// Most actuators a sequence may have.
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
    /// Each actuator's name as written (`A`, `C1`), in variable order.
    pub actuator_names: Vec<String>,
    pub memories: usize,
    /// The letter of each memory (`X`, `Y`, …), in variable order.
    pub memory_names: Vec<char>,
    pub actions: Vec<Operation>,
}

impl Sequence {
    /// Upper-case name of a variable: the actuator's (`A`, `C1`) or the
    /// memory's letter.
    pub fn var_name(&self, var: usize) -> String {
        if var < self.actuators {
            self.actuator_names
                .get(var)
                .cloned()
                .unwrap_or_else(|| "?".to_string())
        } else {
            self.memory_names
                .get(var - self.actuators)
                .map_or_else(|| "?".to_string(), char::to_string)
        }
    }

    /// Lower-case name: the sensor (`a`, `c1`) or the memory's state.
    pub fn signal_name(&self, var: usize) -> String {
        self.var_name(var).to_ascii_lowercase()
    }

    /// The program's output for an action: the valve coil `ya_p` / `ya_m`
    /// (`yc1_p`), or the memory's `x_set` / `x_reset`. IEC names are not
    /// case-sensitive, so a coil cannot be called `A1`.
    pub fn output_name(&self, action: Operation) -> String {
        let state = self.signal_name(action.var);
        match (self.is_memory(action.var), action.value) {
            (true, true) => format!("{state}_set"),
            (true, false) => format!("{state}_reset"),
            (false, true) => format!("y{state}_p"),
            (false, false) => format!("y{state}_m"),
        }
    }

    /// The program's end-switch inputs of an actuator: retracted, extended.
    pub fn input_names(&self, var: usize) -> [String; 2] {
        let state = self.signal_name(var);
        [format!("{state}_home"), format!("{state}_end")]
    }

    /// What each name stands for in the programs: `C1: sensor c1 (inputs
    /// c1_home, c1_end), coils yc1_p (C1+1) and yc1_m (C1-0)`, `X: memory x
    /// (x_set on X1, x_reset on X0)`.
    pub fn name_lines(&self) -> Vec<String> {
        (0..self.variables())
            .map(|v| {
                let [set, reset] = [true, false].map(|value| Operation { var: v, value });
                let (name, signal) = (self.var_name(v), self.signal_name(v));
                let (set_name, reset_name) = (self.output_name(set), self.output_name(reset));
                let (set_token, reset_token) = (self.token(set), self.token(reset));
                if self.is_memory(v) {
                    format!(
                        "{name}: memory {signal} ({set_name} on {set_token}, {reset_name} on {reset_token})"
                    )
                } else {
                    let [home, end] = self.input_names(v);
                    format!(
                        "{name}: sensor {signal} (inputs {home}, {end}), coils {set_name} ({set_token}) and {reset_name} ({reset_token})"
                    )
                }
            })
            .collect()
    }

    /// The letters the memories of this sequence's modified sequences take:
    /// X, Y, Z, W unless an actuator has that name.
    pub fn memory_letters(&self) -> Vec<char> {
        // S and R are among the spare letters: the name check keeps the IL
        // operators out, once (the GA decodes a sequence per individual).
        static ALLOWED: std::sync::OnceLock<Vec<char>> = std::sync::OnceLock::new();
        let allowed = ALLOWED.get_or_init(|| {
            MEMORIES
                .iter()
                .chain(&MORE_MEMORY_LETTERS)
                .copied()
                .filter(|m| {
                    let name = m.to_string();
                    crate::names::synth_problem(&name, &memory_identifiers(&name)).is_none()
                })
                .collect()
        });
        allowed
            .iter()
            .copied()
            .filter(|m| !self.actuator_names.iter().any(|n| n == &m.to_string()))
            .take(MEMORIES.len())
            .collect()
    }

    /// Why the names of this sequence's actuators cannot be the programs'
    /// (`R`: its sensor `r` is an IL operator), one line per name.
    pub fn name_problems(&self) -> Vec<String> {
        self.actuator_names
            .iter()
            .filter_map(|name| {
                let state = name.to_ascii_lowercase();
                let ids = [
                    state.clone(),
                    format!("{state}_home"),
                    format!("{state}_end"),
                    format!("y{state}_p"),
                    format!("y{state}_m"),
                ];
                crate::names::synth_problem(name, &ids)
            })
            .collect()
    }

    /// This sequence (without memories) with `actions` over its actuators and
    /// `memories` memories.
    pub fn with_memories(&self, memories: usize, actions: Vec<Operation>) -> Sequence {
        Sequence {
            actuators: self.actuators,
            actuator_names: self.actuator_names.clone(),
            memories,
            memory_names: self.memory_letters()[..memories.min(MEMORIES.len())].to_vec(),
            actions,
        }
    }

    pub fn variables(&self) -> usize {
        self.actuators + self.memories
    }

    /// `A1`, `X0`; a name ending in a digit as a step table writes the move
    /// (`C1+1`, `C1-0`).
    pub fn token(&self, action: Operation) -> String {
        let name = self.var_name(action.var);
        let value = u8::from(action.value);
        if name.ends_with(|c: char| c.is_ascii_digit()) {
            format!("{name}{}{value}", if action.value { '+' } else { '-' })
        } else {
            format!("{name}{value}")
        }
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
        // `A1 A0 A1 A0`: the same action each time, so the sensors alone
        // know what to do next; what they cannot tell is which half of the
        // cycle it is, and so where the cycle (and a STOP) ends.
        let first = self.actions.first().map(|(_, t)| t);
        if self.actions.iter().all(|(_, t)| Some(t) == first) {
            return write!(
                f,
                "state met again: {} comes before {}; the action is the same, but only a memory tells the cycle's repeats apart, and so where the cycle ends",
                self.state_text,
                actions.join(" and ")
            );
        }
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

/// Parses an original sequence: `A1 A0 B1 B0`, `A+ A- B+ B-` or `C1+1 C1-0
/// C2+1 C2-0`. Every name is an actuator's (W…Z too) and keeps its spelling;
/// actuators are ordered by name. Returns the sequence or what is wrong.
pub fn parse(text: &str) -> Result<Sequence, String> {
    read(text, false)
}

/// Parses a sequence with memories (`A1 X1 A0 B1 X0 B0`): W, X, Y, Z are
/// memories, other letters actuators.
pub fn parse_with_memories(text: &str) -> Result<Sequence, String> {
    read(text, true)
}

/// The identifiers a memory named `name` gives the programs: its state and
/// its set and reset outputs.
fn memory_identifiers(name: &str) -> [String; 3] {
    let state = name.to_ascii_lowercase();
    [
        state.clone(),
        format!("{state}_set"),
        format!("{state}_reset"),
    ]
}

/// A name: actuators before memories, then by letters, then by number.
fn name_order(name: &str) -> (String, u32) {
    let letters: String = name
        .chars()
        .take_while(|c| c.is_ascii_alphabetic())
        .collect();
    let number = name[letters.len()..].parse().unwrap_or(0);
    (letters, number)
}

fn read(text: &str, memories_allowed: bool) -> Result<Sequence, String> {
    let tokens: Vec<&str> = text
        .split(|c: char| c.is_whitespace() || c == ',' || c == ';')
        .filter(|t| !t.is_empty())
        .collect();
    if tokens.is_empty() {
        return Err("the sequence is empty".to_string());
    }
    let mut raw: Vec<(String, bool)> = Vec::new();
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
                    (format!("C{}", m.actuator), value)
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
            (first.to_string(), value)
        } else {
            return Err(format!(
                "\"{token}\" is not an action (expected e.g. A1, A0, A+ or A-)"
            ));
        };
        raw.push(parsed);
    }
    let is_memory = |name: &str| {
        memories_allowed && name.len() == 1 && name.chars().all(|c| MEMORIES.contains(&c))
    };
    let mut actuator_names: Vec<String> = Vec::new();
    let mut memory_names: Vec<char> = Vec::new();
    for (name, _) in &raw {
        if is_memory(name) {
            let letter = name.chars().next().unwrap_or('X');
            if !memory_names.contains(&letter) {
                memory_names.push(letter);
            }
        } else if !actuator_names.contains(name) {
            actuator_names.push(name.clone());
        }
    }
    if actuator_names.len() > MAX_ACTUATORS {
        return Err(format!(
            "synthesis handles at most {MAX_ACTUATORS} actuators; this sequence has {}",
            actuator_names.len()
        ));
    }
    actuator_names.sort_by_key(|n| name_order(n));
    memory_names.sort_by_key(|m| MEMORIES.iter().position(|x| x == m));
    let actuators = actuator_names.len();
    let actions = raw
        .iter()
        .map(|(name, value)| Operation {
            var: if is_memory(name) {
                actuators
                    + memory_names
                        .iter()
                        .position(|m| name.starts_with(*m))
                        .unwrap_or(0)
            } else {
                actuator_names.iter().position(|n| n == name).unwrap_or(0)
            },
            value: *value,
        })
        .collect();
    Ok(Sequence {
        actuators,
        actuator_names,
        memories: memory_names.len(),
        memory_names,
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
        let c = parse("C1+1 C1-0 C2+1 C2-0").unwrap();
        assert_eq!((c.actuators, &c.actions), (a.actuators, &a.actions));
        assert_eq!(a.text(), "A1 A0 B1 B0");
        assert_eq!(c.text(), "C1+1 C1-0 C2+1 C2-0");
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
        assert!(parse_with_memories("A1 X1 A0 B1 X0 B0").unwrap().is_valid());
        assert!(parse("A1 B1 A0 B0").unwrap().is_valid());
    }

    #[test]
    fn memories_skip_the_letters_il_reserves() {
        let s = parse("W1 W0 X1 X0 Y1 Y0 Z1 Z0 V1 V0 U1 U0 T1 T0").unwrap();
        // S and R follow T among the spare letters; Q, P, M, N come instead.
        assert_eq!(s.memory_letters(), ['Q', 'P', 'M', 'N']);
        assert_eq!(s.name_problems(), Vec::<String>::new());
        let r = parse("R1 R0 S1 S0").unwrap();
        assert_eq!(r.name_problems().len(), 2, "{:?}", r.name_problems());
    }
}
