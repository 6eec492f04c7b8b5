//! Benchmark (not a test): both synthesis routes on the four sequences of the
//! paper's Table 5 — the median time over five seeds of the exact route and
//! of the GA + GP route, with the sizes each reaches.
//!
//! Run with `cargo bench --bench synth`.

use std::time::{Duration, Instant};

use steptable::synth::{self, Method, Options, ga, gp, sequence, verify};

const TABLE5: [&str; 4] = [
    "A1 A0 B1 B0",
    "A0 A1 C1 C0 B1 B0",
    "A1 A0 A1 A0 A1 A0 B1 B0 C1 C0",
    "A1 A0 B1 B0 C1 C0 D1 D0 E1 E0 F1 F0",
];

fn median(mut v: Vec<Duration>) -> f64 {
    v.sort();
    v[v.len() / 2].as_secs_f64() * 1e3
}

fn main() {
    println!(
        "sequence | exact: ms, ops, memories, nodes sum/largest | GA+GP: ms, ops, memories, GP nodes sum | QM nodes | simulation"
    );
    for text in TABLE5 {
        let seq = sequence::parse(text).expect("valid sequence");
        let (mut exact_times, mut ga_times) = (Vec::new(), Vec::new());
        let (mut exact, mut ga_run) = (None, None);
        for seed in 1..=5u64 {
            let start = Instant::now();
            exact = Some(
                synth::synthesize_with(
                    &seq,
                    Options {
                        method: Method::Exact,
                        ..Options::default()
                    },
                )
                .expect("synthesises"),
            );
            exact_times.push(start.elapsed());
            let options = Options {
                method: Method::Ga,
                ga: ga::GaParams {
                    seed,
                    ..ga::GaParams::default()
                },
                gp: gp::GpParams {
                    seed,
                    ..gp::GpParams::default()
                },
                time_limit: None,
            };
            let start = Instant::now();
            ga_run = synth::synthesize_with(&seq, options).ok();
            ga_times.push(start.elapsed());
        }
        let e = exact.expect("ran");
        let v = verify::verify(&e, 2);
        let ga_text = match &ga_run {
            Some(g) => {
                let gp: Option<usize> = g
                    .equations
                    .iter()
                    .map(|q| q.gp.as_ref().map(|t| t.nodes()))
                    .sum();
                format!(
                    "{:.0} ms, {}, {}, {}",
                    median(ga_times),
                    g.insertions,
                    g.modified.memories,
                    gp.map_or("-".to_string(), |n| n.to_string())
                )
            }
            None => "no valid sequence".to_string(),
        };
        println!(
            "{text} | {:.1} ms, {}, {}, {}/{} | {ga_text} | {} | {}",
            median(exact_times),
            e.insertions,
            e.modified.memories,
            e.total_nodes(),
            e.largest(),
            e.qm_nodes().map_or("-".to_string(), |n| n.to_string()),
            if v.passed { "passed" } else { "FAILED" }
        );
    }
}
