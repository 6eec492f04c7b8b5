//! Benchmark (not a test): both synthesis routes on the four sequences of the
//! paper's Table 5 — the median time over five seeds of the exact route and
//! of the GA + GP route, with the sizes each reaches.
//!
//! Then the exact route alone on the long textbook sequences (9 and 10
//! cylinders), median of five runs, with what it proved.
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

const LONG: [&str; 2] = [
    "A1 A0 B1 B0 C1 C0 D1 D0 E1 E0 F1 F0 G1 G0 H1 H0 I1 I0",
    "A1 A0 B1 B0 C1 C0 D1 D0 E1 E0 F1 F0 G1 G0 H1 H0 I1 I0 J1 J0",
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
                ..Options::default()
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
    println!(
        "\nlong sequence | exact: median ms, ops, memories, nodes, candidates compared/all, proven"
    );
    for text in LONG {
        let seq = sequence::parse(text).expect("valid sequence");
        let mut times = Vec::new();
        let mut last = None;
        for _ in 0..5 {
            let start = Instant::now();
            last = Some(
                synth::synthesize_with(
                    &seq,
                    Options {
                        method: Method::Exact,
                        time_limit: None,
                        ..Options::default()
                    },
                )
                .expect("synthesises"),
            );
            times.push(start.elapsed());
        }
        let s = last.expect("ran");
        let c = s.comparison.clone().expect("exact route");
        println!(
            "{text} | {:.0} ms, {}, {}, {}, {}/{}, {}",
            median(times),
            s.insertions,
            s.modified.memories,
            s.total_nodes(),
            c.settled,
            c.candidates,
            s.total_nodes() <= c.lower_bound
        );
    }
}
