//! Benchmark (not a test): the exact synthesis route on the four sequences of
//! the paper's Table 5 — median time of five runs, and the sizes it proves.
//! (The paper's GA + GP route is not implemented yet.)
//!
//! Run with `cargo bench --bench synth`.

use std::time::{Duration, Instant};

use steptable::synth::{self, sequence, verify};

const TABLE5: [&str; 4] = [
    "A1 A0 B1 B0",
    "A0 A1 C1 C0 B1 B0",
    "A1 A0 A1 A0 A1 A0 B1 B0 C1 C0",
    "A1 A0 B1 B0 C1 C0 D1 D0 E1 E0 F1 F0",
];

fn main() {
    println!(
        "sequence | exact route median of 5 | inserted ops | memories | nodes (sum / largest) | QM nodes | simulation"
    );
    for text in TABLE5 {
        let seq = sequence::parse(text).expect("valid sequence");
        let mut times: Vec<Duration> = Vec::new();
        let mut last = None;
        for _ in 0..5 {
            let start = Instant::now();
            last = Some(synth::synthesize(&seq).expect("synthesises"));
            times.push(start.elapsed());
        }
        times.sort();
        let s = last.expect("ran");
        let v = verify::verify(&s, 2);
        println!(
            "{text} | {:.1} ms | {} | {} | {} / {} | {} | {}",
            times[2].as_secs_f64() * 1e3,
            s.insertions,
            s.modified.memories,
            s.total_nodes(),
            s.largest(),
            s.qm_nodes().map_or("-".to_string(), |n| n.to_string()),
            if v.passed { "passed" } else { "FAILED" }
        );
    }
}
