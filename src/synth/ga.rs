//! The paper's genetic algorithm for memory insertion (Ganesh & Gurunathan
//! 2017; DESIGN §7): a (μ+λ) evolution strategy over chromosomes whose genes
//! are the original actions — which never move ("gene silencing" only switches
//! the inserted genes on and off) — and slots for memory operations between
//! them. Fitness to minimise: `max(Nf) + Sms/max(Si) − C`, where Nf counts the
//! actions that share a truth-table row, Sms is the modified length, Si the
//! chromosome length and C = 1 for a valid cycle; valid iff f < 1.
//! Seeded with PCG, so a seed gives the same answer on every machine.

use rand_core::{RngCore, SeedableRng};
use rand_pcg::Pcg64;

use super::sequence::{MEMORIES, Operation, Sequence, apply};

/// GA parameters (the paper: μ 50–5000, (μ+λ)/μ 2–6).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GaParams {
    pub mu: usize,
    /// (μ+λ)/μ.
    pub ratio: usize,
    pub generations: usize,
    /// Memory-operation slots after each original action.
    pub slots: usize,
    pub seed: u64,
}

impl Default for GaParams {
    fn default() -> Self {
        GaParams {
            mu: 500,
            ratio: 4,
            generations: 400,
            slots: 2,
            seed: 1,
        }
    }
}

/// A memory-operation slot: silent, or memory `m` set/reset.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Gene {
    Silent,
    Op(u8, bool),
}

#[derive(Debug, Clone)]
struct Individual {
    genes: Vec<Gene>,
    fitness: f64,
}

/// What the GA found.
#[derive(Debug, Clone)]
pub struct GaResult {
    /// The best valid modified sequence, if one was found.
    pub sequence: Option<Sequence>,
    pub fitness: f64,
    pub generations: usize,
}

fn decode(original: &Sequence, genes: &[Gene], slots: usize) -> Sequence {
    let mut used: Vec<u8> = Vec::new();
    for g in genes {
        if let Gene::Op(m, _) = g
            && !used.contains(m)
        {
            used.push(*m);
        }
    }
    used.sort_unstable();
    let mut actions = Vec::with_capacity(original.actions.len() + genes.len());
    for (i, a) in original.actions.iter().enumerate() {
        actions.push(*a);
        for g in &genes[i * slots..(i + 1) * slots] {
            if let Gene::Op(m, value) = g {
                let index = used.iter().position(|u| u == m).unwrap_or(0);
                actions.push(Operation {
                    var: original.actuators + index,
                    value: *value,
                });
            }
        }
    }
    original.with_memories(used.len(), actions)
}

/// The paper's fitness of a decoded sequence (lower is better).
pub fn fitness(sequence: &Sequence, max_length: usize) -> f64 {
    let initial = sequence.initial_state();
    let mut state = initial;
    let mut counts: std::collections::HashMap<u32, usize> = std::collections::HashMap::new();
    let mut null_action = false;
    for a in &sequence.actions {
        *counts.entry(state).or_default() += 1;
        if (state >> a.var) & 1 == u32::from(a.value) {
            null_action = true;
        }
        state = apply(state, *a);
    }
    let max_nf = counts.values().copied().max().unwrap_or(1) as f64;
    let cyclic = if state == initial && !null_action {
        1.0
    } else {
        0.0
    };
    max_nf + sequence.actions.len() as f64 / max_length as f64 - cyclic
}

struct Rng(Pcg64);

impl Rng {
    fn below(&mut self, n: usize) -> usize {
        (self.0.next_u64() % n.max(1) as u64) as usize
    }
    fn chance(&mut self, p: f64) -> bool {
        (self.0.next_u64() as f64 / u64::MAX as f64) < p
    }
}

/// Runs the GA on `original` (a sequence without memories).
pub fn run(original: &Sequence, params: GaParams) -> GaResult {
    let n = original.actions.len();
    let slots = params.slots.max(1);
    let length = n * slots;
    let max_length = n + length;
    let memories = MEMORIES.len() as u8;
    let mut rng = Rng(Pcg64::seed_from_u64(params.seed));
    let random_gene = |rng: &mut Rng| {
        if rng.chance(0.8) {
            Gene::Silent
        } else {
            Gene::Op(rng.below(memories as usize) as u8, rng.chance(0.5))
        }
    };
    let evaluate = |genes: Vec<Gene>| {
        let fitness = fitness(&decode(original, &genes, slots), max_length);
        Individual { genes, fitness }
    };
    let mu = params.mu.max(2);
    let lambda = mu * (params.ratio.max(2) - 1);
    let mut population: Vec<Individual> = (0..mu)
        .map(|_| evaluate((0..length).map(|_| random_gene(&mut rng)).collect()))
        .collect();
    // One valid individual built by construction, so that the GA never
    // ends without an answer where one is easy to give; the search then
    // only has to shorten it.
    if let Some(genes) = gray_code_genes(original, slots) {
        population[0] = evaluate(genes);
    }
    let mut generation = 0;
    let mut best_seen = f64::MAX;
    let mut stalled = 0;
    while generation < params.generations && !super::budget::exceeded() {
        generation += 1;
        let mut offspring = Vec::with_capacity(lambda);
        for _ in 0..lambda {
            if super::budget::exceeded() {
                break;
            }
            let mother = &population[rng.below(mu)];
            let mut genes = mother.genes.clone();
            if rng.chance(0.5) {
                // One-point crossover on a common cut: both parents have the
                // same slots, so the tails swap slot for slot.
                let father = &population[rng.below(mu)];
                let cut = rng.below(length + 1);
                genes[cut..].copy_from_slice(&father.genes[cut..]);
            }
            // Mutation: change one or two slots (silence, or another operation).
            for _ in 0..=rng.below(2) {
                let i = rng.below(length);
                genes[i] = if matches!(genes[i], Gene::Op(..)) && rng.chance(0.5) {
                    Gene::Silent
                } else {
                    Gene::Op(rng.below(memories as usize) as u8, rng.chance(0.5))
                };
            }
            offspring.push(evaluate(genes));
        }
        // (μ+λ): the best μ of parents and offspring survive.
        population.extend(offspring);
        population.sort_by(|a, b| a.fitness.total_cmp(&b.fitness));
        population.truncate(mu);
        let best = population[0].fitness;
        if best < best_seen - 1e-12 {
            best_seen = best;
            stalled = 0;
        } else {
            stalled += 1;
        }
        if best < 1.0 && stalled > 60 {
            break;
        }
    }
    let best = &population[0];
    let decoded = decode(original, &best.genes, slots);
    GaResult {
        sequence: (best.fitness < 1.0 && decoded.is_valid()).then_some(decoded),
        fitness: best.fitness,
        generations: generation,
    }
}

/// A valid chromosome by construction: the actions are cut into groups in
/// which no actuator moves twice (within a group every state before an
/// action differs, as each action moves another actuator), and the
/// memories count the groups in a cyclic Gray code, switched between
/// groups, so that no two groups share a memory state. An odd number of
/// groups skips one code with two switches in one gap (the skipped code
/// is then the state between them, which no group has). `None` when the
/// groups need more than the four memories or two slots per gap.
fn gray_code_genes(original: &Sequence, slots: usize) -> Option<Vec<Gene>> {
    let n = original.actions.len();
    // The index of the last action of each group.
    let mut ends = Vec::new();
    let mut moved: Vec<usize> = Vec::new();
    for (i, a) in original.actions.iter().enumerate() {
        if moved.contains(&a.var) {
            ends.push(i - 1);
            moved.clear();
        }
        moved.push(a.var);
    }
    ends.push(n - 1);
    let groups = ends.len();
    if groups == 1 {
        return Some(vec![Gene::Silent; n * slots]);
    }
    let count = groups + groups % 2;
    let bits = (usize::BITS - (count - 1).leading_zeros()) as usize;
    if bits > MEMORIES.len() || slots < 2 {
        return None;
    }
    // A cyclic Gray code of `count` words: the first half of the reflected
    // code on bits-1 bits, then the same half reversed with the top bit set.
    let half: Vec<u32> = (0..count as u32 / 2).map(|k| k ^ (k >> 1)).collect();
    let top = if bits == 0 { 0 } else { 1 << (bits - 1) };
    let mut codes: Vec<u32> = half.clone();
    codes.extend(half.iter().rev().map(|c| c | top));
    if count > groups {
        // Skip the second code: the first gap switches two memories.
        codes.remove(1);
    }
    let mut genes = vec![Gene::Silent; n * slots];
    for (g, &end) in ends.iter().enumerate() {
        let (from, to) = (codes[g], codes[(g + 1) % groups]);
        let changed = from ^ to;
        // Switch in the order the code passes through them: the skipped
        // code's bit first.
        let order: Vec<u32> = if count > groups && g == 0 {
            let skipped = half.get(1).copied().unwrap_or(0);
            let first = skipped ^ from;
            vec![first, changed ^ first]
        } else {
            (0..bits as u32)
                .map(|b| 1 << b)
                .filter(|b| changed & b != 0)
                .collect()
        };
        for (slot, bit) in (end * slots..).zip(order.into_iter().filter(|b| *b != 0)) {
            let memory = bit.trailing_zeros() as u8;
            genes[slot] = Gene::Op(memory, to & bit != 0);
        }
    }
    Some(genes)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::synth::sequence::parse;

    #[test]
    fn fitness_follows_the_paper() {
        let valid = crate::synth::sequence::parse_with_memories("A1 X1 A0 B1 X0 B0").unwrap();
        let f = fitness(&valid, 12);
        assert!((f - 0.5).abs() < 1e-9, "{f}");
        let clash = parse("A1 A0 B1 B0").unwrap();
        assert!(fitness(&clash, 12) >= 1.0);
    }

    /// The constructive individual is valid for long sequences that the
    /// random population never solved (A1 A0 … J1 J0: eleven groups), with
    /// an odd and an even number of groups, so the GA always answers.
    #[test]
    fn a_constructed_individual_keeps_the_ga_from_failing() {
        let letters = "ABCDEFGHIJ";
        for count in [2, 3, 4, 7, 10] {
            let text: Vec<String> = letters[..count]
                .chars()
                .flat_map(|c| [format!("{c}1"), format!("{c}0")])
                .collect();
            let original = parse(&text.join(" ")).unwrap();
            let genes = gray_code_genes(&original, 2).expect("at most 16 groups");
            let built = decode(&original, &genes, 2);
            assert!(
                built.is_valid(),
                "{count}: {} {:?}",
                built.text(),
                built.problems()
            );
            for seed in 1..=8 {
                let r = run(
                    &original,
                    GaParams {
                        mu: 20,
                        generations: 5,
                        seed,
                        ..GaParams::default()
                    },
                );
                let found = r.sequence.expect("the GA answers");
                assert!(found.is_valid(), "{count}, seed {seed}: {}", found.text());
            }
        }
        // Nineteen groups need five memories: no construction.
        let text: Vec<String> = "ABCDEFGHI"
            .chars()
            .flat_map(|c| [format!("{c}1"), format!("{c}0")])
            .collect();
        let twice = format!("{0} {0}", text.join(" "));
        assert_eq!(gray_code_genes(&parse(&twice).unwrap(), 2), None);
    }

    #[test]
    fn the_ga_reaches_the_minimum_on_the_classic() {
        let original = parse("A1 A0 B1 B0").unwrap();
        for seed in 1..=5 {
            let r = run(
                &original,
                GaParams {
                    seed,
                    ..GaParams::default()
                },
            );
            let s = r.sequence.expect("valid");
            assert_eq!(s.actions.len(), 6, "seed {seed}: {}", s.text());
        }
    }
}
