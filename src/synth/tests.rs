use super::*;

#[test]
fn the_papers_first_sequence_and_its_equations() {
    let s = synthesize(&sequence::parse("A1 A0 B1 B0").unwrap()).unwrap();
    assert_eq!(s.modified.text(), "A1 X1 A0 B1 X0 B0");
    let name = |v: usize| s.modified.signal_name(v).to_string();
    // The paper's equations, up to operand order.
    let paper = sequence::parse_with_memories("A1 X1 A0 B1 X0 B0").unwrap();
    let expected = [
        ("A1", "NOT(OR(b,x))"),
        ("A0", "x"),
        ("B1", "AND(NOT(a),x)"),
        ("B0", "NOT(x)"),
        ("X1", "a"),
        ("X0", "b"),
    ];
    for (token, canonical) in expected {
        let e = s
            .equations
            .iter()
            .find(|e| s.modified.token(e.action) == token)
            .unwrap();
        assert_eq!(
            e.expr.canonical(&name),
            canonical,
            "{token}: {}",
            e.expr.text(&name)
        );
    }
    assert_eq!(paper, s.modified);
    assert_eq!(s.total_nodes(), 13);
}

mod table5 {
    use super::super::*;

    /// DESIGN §7 / the paper's Table 5: (sequence, inserted operations,
    /// memories, bound on the sum of equation nodes, bound on the largest).
    pub(crate) const TABLE5: [(&str, usize, usize, usize, usize); 4] = [
        ("A1 A0 B1 B0", 2, 1, 13, 4),
        ("A0 A1 C1 C0 B1 B0", 4, 2, 23, 5),
        ("A1 A0 A1 A0 A1 A0 B1 B0 C1 C0", 8, 3, 50, 8),
        ("A1 A0 B1 B0 C1 C0 D1 D0 E1 E0 F1 F0", 6, 3, 50, 6),
    ];

    #[test]
    fn pick_and_place_and_memoryless_sequences_run() {
        for (text, memories) in [
            ("B1 D1 B0 C1 B1 D0 B0 C0", None),
            ("B1 D1 B0 A1 D0 A0", None),
            ("A1 B1 A0 B0", Some(0)),
        ] {
            let s = synthesize(&sequence::parse(text).unwrap()).unwrap();
            assert!(s.modified.is_valid(), "{text}");
            if let Some(m) = memories {
                assert_eq!(s.modified.memories, m, "{text}");
                assert_eq!(s.modified.text(), text);
            }
            let v = verify::verify(&s, 2);
            assert!(v.passed, "{text}: {:?}", v.problem);
            assert_eq!(v.observed.len(), 2 * s.modified.actions.len());
        }
    }

    #[test]
    fn gp_reaches_the_proven_minimum_on_the_first_two() {
        for (text, ..) in &TABLE5[..2] {
            let s = synthesize(&sequence::parse(text).unwrap()).unwrap();
            let gp: usize = s
                .equations
                .iter()
                .map(|e| e.gp.as_ref().unwrap().nodes())
                .sum();
            assert_eq!(gp, s.total_nodes(), "{text}");
        }
    }

    #[test]
    fn table5_sequences_reach_the_proven_minimum() {
        for (text, insertions, memories, total, largest) in TABLE5 {
            let start = std::time::Instant::now();
            let s = synthesize(&sequence::parse(text).unwrap()).unwrap();
            eprintln!(
                "{text}: {} | +{} ops, {} memories, {} nodes (largest {}), qm {:?}, {:?}, {} ms",
                s.modified.text(),
                s.insertions,
                s.modified.memories,
                s.total_nodes(),
                s.largest(),
                s.qm_nodes(),
                s.comparison,
                start.elapsed().as_millis()
            );
            assert!(s.modified.is_valid(), "{text}");
            assert_eq!(s.insertions, insertions, "{text}");
            assert_eq!(s.modified.memories, memories, "{text}");
            assert!(s.total_nodes() <= total, "{text}: {}", s.total_nodes());
            assert!(s.largest() <= largest, "{text}: {}", s.largest());
            let v = verify::verify(&s, 2);
            assert!(v.passed, "{text}: {:?}", v.problem);
        }
    }
}

mod ga_table5 {
    use super::super::*;

    #[test]
    fn the_ga_alone_reaches_a_minimal_valid_sequence_with_five_seeds() {
        for (text, insertions, ..) in super::table5::TABLE5 {
            let original = sequence::parse(text).unwrap();
            for seed in 1..=5 {
                let t = std::time::Instant::now();
                let r = ga::run(
                    &original,
                    ga::GaParams {
                        seed,
                        ..ga::GaParams::default()
                    },
                );
                let s = r.sequence.expect("valid");
                eprintln!(
                    "{text} seed {seed}: {} ({} gens, {} ms)",
                    s.text(),
                    r.generations,
                    t.elapsed().as_millis()
                );
                assert_eq!(
                    s.actions.len(),
                    original.actions.len() + insertions,
                    "{text} seed {seed}: {}",
                    s.text()
                );
            }
        }
    }
}

mod modes_table5 {
    use super::super::*;

    /// Each Table 5 program with its modes: nothing moves before START,
    /// STOP ends the cycling at the end of a cycle, the emergency stop
    /// starts nothing new and refuses START, RESET brings everything home
    /// and the next START runs one cycle.
    #[test]
    fn the_programs_obey_start_stop_estop_and_reset() {
        for (text, ..) in super::table5::TABLE5 {
            let s = synthesize(&sequence::parse(text).unwrap()).unwrap();
            let trace = verify::check(&s).unwrap_or_else(|e| panic!("{text}: {e}"));
            assert!(trace.len() > 3 * s.original.actions.len(), "{text}");
        }
    }

    /// The proof fails a program whose START is ignored (held on from
    /// power-up): it moves before the operator presses START.
    #[test]
    fn a_program_without_modes_fails_the_proof() {
        let s = synthesize(&sequence::parse("A1 A0 B1 B0").unwrap()).unwrap();
        let script = verify::script_for(&s);
        let mut free = controller::Program::new(&s);
        let trace = verify::run(
            &s,
            verify::STROKE_MS,
            script.scans,
            &|scan| script.buttons(scan),
            &mut |ends, buttons| {
                Ok(free.scan(
                    ends,
                    controller::Buttons {
                        start: scan_start(buttons),
                        ..controller::Buttons::default()
                    },
                ))
            },
        )
        .unwrap();
        let why = verify::judge(&s, &script, &trace).unwrap_err();
        assert!(why.contains("before START"), "{why}");
    }

    /// START held on every scan: the program then cycles on regardless.
    fn scan_start(_: controller::Buttons) -> bool {
        true
    }
}
