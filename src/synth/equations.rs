//! Logic equations: expression trees over sensor and memory letters with AND,
//! OR, NOT, XOR; an exact search for the smallest tree that matches a truth
//! table column on its visited rows (so minimality is proven, not hoped for);
//! and Quine–McCluskey with don't-cares as the two-level baseline.
//!
//! Size convention: every node of the tree counts — each leaf, each NOT and
//! each binary operator. `NOT (b OR x)` has 4 nodes.

/// A logic expression.
#[derive(Debug, Clone, PartialEq, Eq, Hash)]
pub enum Expr {
    Var(usize),
    Not(Box<Expr>),
    And(Box<Expr>, Box<Expr>),
    Or(Box<Expr>, Box<Expr>),
    Xor(Box<Expr>, Box<Expr>),
}

impl Expr {
    /// Tree nodes: leaves, NOTs and binary operators.
    pub fn nodes(&self) -> usize {
        match self {
            Expr::Var(_) => 1,
            Expr::Not(e) => 1 + e.nodes(),
            Expr::And(a, b) | Expr::Or(a, b) | Expr::Xor(a, b) => 1 + a.nodes() + b.nodes(),
        }
    }

    pub fn eval(&self, state: u32) -> bool {
        match self {
            Expr::Var(v) => (state >> v) & 1 == 1,
            Expr::Not(e) => !e.eval(state),
            Expr::And(a, b) => a.eval(state) && b.eval(state),
            Expr::Or(a, b) => a.eval(state) || b.eval(state),
            Expr::Xor(a, b) => a.eval(state) != b.eval(state),
        }
    }

    /// Text in the grammar `expr := ident | NOT expr | expr AND expr | expr OR
    /// expr | expr XOR expr | ( expr )`, with `name` giving each variable's
    /// identifier: `NOT (b OR x)`, `NOT a AND x`.
    pub fn text(&self, name: &dyn Fn(usize) -> String) -> String {
        self.render(name, "NOT ", " AND ", " OR ", " XOR ")
    }

    /// The same expression with the operands of AND, OR and XOR in a fixed
    /// order, to compare expressions up to operand order.
    pub fn canonical(&self, name: &dyn Fn(usize) -> String) -> String {
        match self {
            Expr::Var(v) => name(*v),
            Expr::Not(e) => format!("NOT({})", e.canonical(name)),
            Expr::And(a, b) | Expr::Or(a, b) | Expr::Xor(a, b) => {
                let op = match self {
                    Expr::And(..) => "AND",
                    Expr::Or(..) => "OR",
                    _ => "XOR",
                };
                let mut parts = [a.canonical(name), b.canonical(name)];
                parts.sort();
                format!("{op}({},{})", parts[0], parts[1])
            }
        }
    }

    /// The same with other operator spellings (for IL comments, ST, …).
    pub fn render(
        &self,
        name: &dyn Fn(usize) -> String,
        not: &str,
        and: &str,
        or: &str,
        xor: &str,
    ) -> String {
        let operand = |e: &Expr| match e {
            Expr::Var(_) | Expr::Not(_) => e.render(name, not, and, or, xor),
            _ => format!("({})", e.render(name, not, and, or, xor)),
        };
        match self {
            Expr::Var(v) => name(*v),
            Expr::Not(e) => match **e {
                Expr::Var(_) | Expr::Not(_) => {
                    format!("{not}{}", e.render(name, not, and, or, xor))
                }
                _ => format!("{not}({})", e.render(name, not, and, or, xor)),
            },
            Expr::And(a, b) => format!("{}{and}{}", operand(a), operand(b)),
            Expr::Or(a, b) => format!("{}{or}{}", operand(a), operand(b)),
            Expr::Xor(a, b) => format!("{}{xor}{}", operand(a), operand(b)),
        }
    }
}

#[derive(Debug, Clone, Copy)]
enum Op {
    Var(usize),
    Not(u32),
    And(u32, u32),
    Or(u32, u32),
    Xor(u32, u32),
}

/// Limits of the exact search, so that a huge column cannot hang it.
#[derive(Debug, Clone, Copy)]
pub struct SearchLimits {
    pub max_nodes: usize,
    /// Pairs of subexpressions combined, at most.
    pub max_work: u64,
}

impl Default for SearchLimits {
    fn default() -> Self {
        SearchLimits {
            max_nodes: 13,
            max_work: 200_000_000,
        }
    }
}

/// The smallest expression that is 1 on every `on` state and 0 on every
/// `off` state (other states do not matter), found by enumerating every
/// distinct function on those rows by tree size. `None` if the limits are
/// reached first. Among equal sizes, NOT comes before AND, AND before OR,
/// OR before XOR, and smaller left operands first.
pub fn minimal(on: &[u32], off: &[u32], variables: usize, limits: SearchLimits) -> Option<Expr> {
    match smallest(on, off, variables, limits) {
        Smallest::Found(expr) => Some(expr),
        Smallest::Larger | Smallest::GaveUp => None,
    }
}

/// What the exact search of one column found.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Smallest {
    /// The smallest tree.
    Found(Expr),
    /// Proven: every tree that fits has more than `max_nodes` nodes.
    Larger,
    /// The work limit or the synthesis's time ran out first: nothing proven.
    GaveUp,
}

/// [`minimal`], saying why it found nothing.
pub fn smallest(on: &[u32], off: &[u32], variables: usize, limits: SearchLimits) -> Smallest {
    let rows: Vec<u32> = on.iter().chain(off).copied().collect();
    if rows.len() > 63 || on.is_empty() && off.is_empty() {
        return Smallest::GaveUp;
    }
    // At most 63 rows: a mask never has every bit set (MaskSet's empty mark).
    let full: u64 = (1u64 << rows.len()) - 1;
    let target: u64 = (0..on.len()).fold(0, |m, i| m | (1 << i));
    let mut arena: Vec<Op> = Vec::new();
    let mut seen = Seen::new(rows.len());
    let mut levels: Vec<Vec<(u64, u32)>> = vec![Vec::new()];
    let mut found: Option<u32> = None;
    let mut push = |level: &mut Vec<(u64, u32)>, arena: &mut Vec<Op>, mask: u64, op: Op| -> bool {
        if !seen.insert(mask) {
            return false;
        }
        arena.push(op);
        let id = arena.len() as u32 - 1;
        level.push((mask, id));
        mask == target
    };
    // Size 1: the variables.
    let mut level = Vec::new();
    for v in 0..variables {
        let mask = rows
            .iter()
            .enumerate()
            .filter(|(_, s)| (**s >> v) & 1 == 1)
            .fold(0u64, |m, (i, _)| m | (1 << i));
        if push(&mut level, &mut arena, mask, Op::Var(v)) && found.is_none() {
            found = Some(arena.len() as u32 - 1);
        }
    }
    levels.push(level);
    let mut work: u64 = 0;
    let mut size = 1;
    while found.is_none() {
        size += 1;
        if size > limits.max_nodes {
            return Smallest::Larger;
        }
        let mut level = Vec::new();
        // NOT of size-1 trees.
        for &(mask, id) in &levels[size - 1] {
            if push(&mut level, &mut arena, !mask & full, Op::Not(id)) {
                found = Some(arena.len() as u32 - 1);
                break;
            }
        }
        // Binary operators: left size i, right size size-1-i.
        'ops: for op in 0..3 {
            if found.is_some() {
                break;
            }
            for left in 1..size - 1 {
                let right = size - 1 - left;
                if left > right {
                    break;
                }
                for (li, &(lm, lid)) in levels[left].iter().enumerate() {
                    let start = if left == right { li } else { 0 };
                    work += (levels[right].len() - start) as u64;
                    if work > limits.max_work || super::budget::exceeded() {
                        return Smallest::GaveUp;
                    }
                    for &(rm, rid) in &levels[right][start..] {
                        let (mask, node) = match op {
                            0 => (lm & rm, Op::And(lid, rid)),
                            1 => (lm | rm, Op::Or(lid, rid)),
                            _ => (lm ^ rm, Op::Xor(lid, rid)),
                        };
                        if push(&mut level, &mut arena, mask, node) {
                            found = Some(arena.len() as u32 - 1);
                            break 'ops;
                        }
                    }
                }
            }
        }
        levels.push(level);
    }
    match found {
        Some(id) => Smallest::Found(build(&arena, id)),
        None => Smallest::GaveUp,
    }
}

fn build(arena: &[Op], id: u32) -> Expr {
    match arena[id as usize] {
        Op::Var(v) => Expr::Var(v),
        Op::Not(a) => Expr::Not(Box::new(build(arena, a))),
        Op::And(a, b) => Expr::And(Box::new(build(arena, a)), Box::new(build(arena, b))),
        Op::Or(a, b) => Expr::Or(Box::new(build(arena, a)), Box::new(build(arena, b))),
        Op::Xor(a, b) => Expr::Xor(Box::new(build(arena, a)), Box::new(build(arena, b))),
    }
}

/// The functions (masks over the care rows) already built: a bit set when
/// the rows are few enough, an open-addressing hash set otherwise (the
/// standard set's hashing was most of the search's time).
enum Seen {
    Bits(Vec<u64>),
    Hash(MaskSet),
}

impl Seen {
    fn new(rows: usize) -> Self {
        if rows <= 20 {
            Seen::Bits(vec![0; (1usize << rows).div_ceil(64)])
        } else {
            Seen::Hash(MaskSet::new())
        }
    }

    /// Adds `mask`; false if it was there already.
    fn insert(&mut self, mask: u64) -> bool {
        match self {
            Seen::Bits(bits) => {
                let (word, bit) = ((mask / 64) as usize, mask % 64);
                let new = (bits[word] >> bit) & 1 == 0;
                bits[word] |= 1 << bit;
                new
            }
            Seen::Hash(set) => set.insert(mask),
        }
    }
}

/// A set of masks of at most 63 rows, so `u64::MAX` never occurs and marks
/// an empty slot; linear probing, Fibonacci hashing, at most half full.
struct MaskSet {
    slots: Vec<u64>,
    len: usize,
    shift: u32,
}

impl MaskSet {
    const EMPTY: u64 = u64::MAX;

    fn new() -> Self {
        MaskSet {
            slots: vec![Self::EMPTY; 1 << 12],
            len: 0,
            shift: 64 - 12,
        }
    }

    fn insert(&mut self, mask: u64) -> bool {
        if 2 * (self.len + 1) > self.slots.len() {
            self.grow();
        }
        let last = self.slots.len() - 1;
        let mut i = (mask.wrapping_mul(0x9E37_79B9_7F4A_7C15) >> self.shift) as usize;
        loop {
            match self.slots[i] {
                Self::EMPTY => {
                    self.slots[i] = mask;
                    self.len += 1;
                    return true;
                }
                m if m == mask => return false,
                _ => i = (i + 1) & last,
            }
        }
    }

    fn grow(&mut self) {
        let doubled = vec![Self::EMPTY; 2 * self.slots.len()];
        let old = std::mem::replace(&mut self.slots, doubled);
        self.shift -= 1;
        self.len = 0;
        for mask in old.into_iter().filter(|m| *m != Self::EMPTY) {
            self.insert(mask);
        }
    }
}

/// Every prime implicant of the function that is 0 on `off` and 1 or
/// don't-care elsewhere, as (value bits, care mask), in the order of the
/// tabular method (fewest don't-cares first, then by value and mask). Each
/// cube is an implicant when both its halves are (one table of bits over
/// every cube: 2^(2n) bits, 2 MB at 12 variables), and prime when no cube
/// one don't-care larger is.
fn prime_implicants(off: &[u32], variables: usize) -> Vec<(u32, u32)> {
    let n = variables;
    let all = (1u32 << n) - 1;
    let index = |value: u32, free: u32| (value as usize) | ((free as usize) << n);
    let mut implicant = vec![0u64; (1usize << (2 * n)).div_ceil(64)];
    let get = |bits: &[u64], i: usize| (bits[i / 64] >> (i % 64)) & 1 == 1;
    let mut is_off = vec![false; 1 << n];
    for row in off {
        is_off[*row as usize & all as usize] = true;
    }
    let mut primes_free: Vec<(u32, u32)> = Vec::new();
    for free in 0..=all {
        let fixed = all & !free;
        let low = free & free.wrapping_neg();
        // Every value over the fixed bits: the submasks of `fixed`.
        let mut value = fixed;
        loop {
            let yes = if free == 0 {
                !is_off[value as usize]
            } else {
                let half = free & !low;
                get(&implicant, index(value, half)) && get(&implicant, index(value | low, half))
            };
            if yes {
                let i = index(value, free);
                implicant[i / 64] |= 1 << (i % 64);
                primes_free.push((value, free));
            }
            if value == 0 {
                break;
            }
            value = (value - 1) & fixed;
        }
    }
    // Prime: no fixed bit can be freed.
    let mut primes: Vec<(u32, u32)> = primes_free
        .into_iter()
        .filter(|&(value, free)| {
            (0..n)
                .map(|b| 1u32 << b)
                .all(|b| free & b != 0 || !get(&implicant, index(value & !b, free | b)))
        })
        .map(|(value, free)| (value, all & !free))
        .collect();
    primes
        .sort_unstable_by_key(|&(value, mask)| (std::cmp::Reverse(mask.count_ones()), value, mask));
    primes
}

/// A product term: for each variable, `Some(value)` if it appears.
type Term = Vec<Option<bool>>;

/// Quine–McCluskey over the full table of `variables` variables, states not
/// in `on` or `off` being don't-cares, with a minimum cover (fewest terms,
/// then fewest literals). Returns the sum of products as an expression, or
/// `None` beyond 12 variables (4,096 rows).
pub fn quine_mccluskey(on: &[u32], off: &[u32], variables: usize) -> Option<Expr> {
    if variables == 0 || variables > 12 || on.is_empty() {
        return None;
    }
    let primes = prime_implicants(off, variables);
    // Only primes that cover some ON row matter.
    let mut primes = primes;
    let covers = |p: &(u32, u32), r: u32| (r & p.1) == (p.0 & p.1);
    primes.retain(|p| on.iter().any(|r| covers(p, *r)));
    primes.sort_unstable_by_key(|p| {
        (
            std::cmp::Reverse(on.iter().filter(|r| covers(p, **r)).count()),
            p.1.count_ones(),
            p.0,
        )
    });
    let mut best: Option<Vec<usize>> = None;
    let cost = |set: &[usize]| -> (usize, u32) {
        (
            set.len(),
            set.iter().map(|i| primes[*i].1.count_ones()).sum(),
        )
    };
    fn cover(
        on: &[u32],
        primes: &[(u32, u32)],
        chosen: &mut Vec<usize>,
        best: &mut Option<Vec<usize>>,
        cost: &dyn Fn(&[usize]) -> (usize, u32),
    ) {
        let covers = |p: &(u32, u32), r: u32| (r & p.1) == (p.0 & p.1);
        let Some(first) = on
            .iter()
            .find(|r| !chosen.iter().any(|i| covers(&primes[*i], **r)))
        else {
            if best.as_ref().is_none_or(|b| cost(chosen) < cost(b)) {
                *best = Some(chosen.clone());
            }
            return;
        };
        if best.as_ref().is_some_and(|b| chosen.len() + 1 > b.len()) {
            return;
        }
        for (i, p) in primes.iter().enumerate() {
            if covers(p, *first) {
                chosen.push(i);
                cover(on, primes, chosen, best, cost);
                chosen.pop();
            }
        }
    }
    cover(on, &primes, &mut Vec::new(), &mut best, &cost);
    let chosen = best?;
    let terms: Vec<Term> = chosen
        .iter()
        .map(|i| {
            let (value, mask) = primes[*i];
            (0..variables)
                .map(|v| ((mask >> v) & 1 == 1).then_some((value >> v) & 1 == 1))
                .collect()
        })
        .collect();
    let term_expr = |t: &Term| -> Option<Expr> {
        t.iter()
            .enumerate()
            .filter_map(|(v, lit)| {
                lit.map(|value| {
                    if value {
                        Expr::Var(v)
                    } else {
                        Expr::Not(Box::new(Expr::Var(v)))
                    }
                })
            })
            .reduce(|a, b| Expr::And(Box::new(a), Box::new(b)))
    };
    terms
        .iter()
        .filter_map(term_expr)
        .reduce(|a, b| Expr::Or(Box::new(a), Box::new(b)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn name(v: usize) -> String {
        ["a", "b", "x"][v].to_string()
    }

    #[test]
    fn finds_the_smallest_tree() {
        // on: a=0 b=0 x=0 ; off: x=1 rows and b=1 rows
        // bit 0 = a, bit 1 = b, bit 2 = x
        let on = [0b000, 0b001];
        let off = [0b100, 0b101, 0b010, 0b011];
        let e = minimal(&on, &off, 3, SearchLimits::default()).unwrap();
        assert_eq!(e.nodes(), 4);
        assert_eq!(e.text(&name), "NOT (b OR x)");
        for s in on {
            assert!(e.eval(s));
        }
        for s in off {
            assert!(!e.eval(s));
        }
    }

    #[test]
    fn qm_matches_on_and_off() {
        let on = [0b000, 0b010];
        let off = [0b100, 0b001];
        let e = quine_mccluskey(&on, &off, 3).unwrap();
        assert!(on.iter().all(|s| e.eval(*s)) && off.iter().all(|s| !e.eval(*s)));
    }
}
