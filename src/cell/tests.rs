use super::*;

fn mv(a: u32, sign: Sign, p: Option<u32>) -> CellMove {
    CellMove {
        actuator: a,
        sign,
        position: p,
    }
}

#[test]
fn headers_may_carry_a_comment() {
    assert_eq!(header_kind("STEP 3 (clamp)"), Some(Header::Step(3)));
    assert_eq!(header_kind("step 12: eject"), Some(Header::Step(12)));
    assert_eq!(header_kind(" Branch 2 - gripper"), Some(Header::Branch(2)));
    assert_eq!(header_kind("BRANCH 1"), Some(Header::Branch(1)));
    assert_eq!(header_kind("S T E P 1 0"), Some(Header::Step(10)));
    for not in [
        "STEP", "STEP 3a", "BRANH 1", "STEPS 2", "STEP x", "3 STEP", "",
    ] {
        assert_eq!(header_kind(not), None, "{not}");
    }
}

#[test]
fn a_space_before_the_sign_of_an_output_is_not_inside_its_name() {
    assert!(!name_has_space("Y:vacuum +"));
    assert!(!name_has_space("I:part_present = 1"));
    assert!(name_has_space("Y:vac uum+"));
    assert_eq!(format!("{:?}", Name::new("vacuum").unwrap()), "\"vacuum\"");
}

#[test]
fn every_digit_a_keyboard_or_a_font_makes_reads_as_a_digit() {
    // Subscripts, superscripts (¹²³ live apart from ⁰⁴⁻⁹), full-width.
    assert_eq!(normalize("₀₁₂₃₄₅₆₇₈₉"), "0123456789");
    assert_eq!(normalize("⁰¹²³⁴⁵⁶⁷⁸⁹"), "0123456789");
    assert_eq!(normalize("０１２３４５６７８９"), "0123456789");
    // Signs and the letter C as other scripts and fonts write them.
    assert_eq!(normalize("c 2 − 1"), "C2-1");
    assert_eq!(normalize("С１＋₂"), "C1+2");
    assert_eq!(normalize("Ｃ3⁻0\u{200B}"), "C3-0");
}

#[test]
fn actuator_names_may_carry_a_comment() {
    for (text, n) in [
        ("C1", 1),
        ("c 12", 12),
        ("C1 (clamp)", 1),
        ("C3: lift", 3),
        ("C2 gripper", 2),
        ("\u{FF23}\u{FF12}", 2),
    ] {
        assert_eq!(actuator_name(text), Some(n), "{text}");
    }
    for text in ["C", "C0", "C1000", "C1a", "X1", "CLAMP", "1", ""] {
        assert_eq!(actuator_name(text), None, "{text}");
        assert_eq!(parse_actuator(text), None, "{text}");
    }
    // An option names the actuator and nothing else.
    for (text, n) in [("C2", 2), ("c 12", 12), (" C999 ", 999)] {
        assert_eq!(parse_actuator(text), Some(n), "{text}");
    }
    for text in ["C2 (clamp)", "C2: gripper", "C2 lift"] {
        assert_eq!(parse_actuator(text), None, "{text}");
    }
}

#[test]
fn accepts_what_engineers_type() {
    let expected = mv(2, Sign::Minus, Some(1));
    for text in [
        "C2-1",
        "c2-1",
        "C2 - 1",
        " C2-1 ",
        "C2\u{2212}1",
        "C2\u{2013}1",
        "C2\u{2014}1",
        "C\u{2082}-\u{2081}",
        "\u{0421}2-1",
        "C2\u{00A0}-1",
        "C\u{FF12}\u{FF0D}1",
    ] {
        assert_eq!(parse_move(text), Ok(expected), "{text:?}");
    }
    assert_eq!(parse_move("C12+3"), Ok(mv(12, Sign::Plus, Some(3))));
    assert_eq!(parse_move("C1+"), Ok(mv(1, Sign::Plus, None)));
    assert_eq!(parse_move("c3 -"), Ok(mv(3, Sign::Minus, None)));
    assert_eq!(parse_move("C01+01"), Ok(mv(1, Sign::Plus, Some(1))));
}

#[test]
fn rejects_what_is_not_a_move() {
    for text in [
        "C2+x", "C+1", "2+1", "C2", "C2*1", "A1", "C2+1+", "C2+-1", "START", "-",
    ] {
        assert_eq!(parse_move(text), Err(CellError::NotAMove), "{text:?}");
    }
    assert_eq!(parse_move("C0+1"), Err(CellError::BadActuator("0".into())));
    assert!(matches!(
        parse_move("C99999999999+1"),
        Err(CellError::BadActuator(_))
    ));
    assert!(matches!(
        parse_move("C1+64"),
        Err(CellError::BadPosition(_))
    ));
}

#[test]
fn printing_round_trips() {
    for m in [
        mv(1, Sign::Plus, Some(1)),
        mv(12, Sign::Minus, Some(0)),
        mv(3, Sign::Plus, None),
    ] {
        assert_eq!(parse_move(&m.to_string()), Ok(m));
    }
}

fn name(text: &str) -> Name {
    Name::new(text).expect("valid name")
}

#[test]
fn parses_dwells_waits_and_outputs() {
    let dwell = |ms| Ok(CellItem::Dwell { ms });
    assert_eq!(parse_item("T=2s"), dwell(2000));
    assert_eq!(parse_item("t = 500 ms"), dwell(500));
    assert_eq!(parse_item("T=1.5s"), dwell(1500));
    assert_eq!(parse_item("T=0,1s"), dwell(100));
    assert_eq!(parse_item("T=3"), dwell(3000));
    // Whole milliseconds are the timers' resolution: 20.0 ms is 20.
    assert_eq!(parse_item("T=20.0ms"), dwell(20));
    // Up to three decimals and seven whole digits are read.
    assert_eq!(parse_item("T=1.005s"), dwell(1005));
    assert_eq!(parse_item("T=0000010s"), dwell(10_000));
    for bad in [
        "T=",
        "T=12.5ms",
        // Long enough to overflow the arithmetic if it were not refused.
        "T=99999999999999999s",
        "T=0s",
        "T=5ms",
        "T=656s",
        "T=1.5ms",
        "T=2h",
        "T=-1s",
        "T=1.2345s",
    ] {
        assert!(
            matches!(parse_item(bad), Err(ItemError::BadDwell(_))),
            "{bad}"
        );
    }
    assert_eq!(
        parse_item("I:Part_Present"),
        Ok(CellItem::Wait {
            input: name("part_present"),
            value: true
        })
    );
    assert_eq!(
        parse_item("i: door = 0"),
        Ok(CellItem::Wait {
            input: name("door"),
            value: false
        })
    );
    assert_eq!(
        parse_item("Y:vacuum\u{2212}"),
        Ok(CellItem::Switch {
            output: name("vacuum"),
            on: false
        })
    );
    for bad in [
        "I:",
        "I:2door",
        "I:a__b",
        "I:door=2",
        "Y:vacuum",
        "Y:+",
        "I:seventeen_chars_x",
    ] {
        assert!(
            matches!(parse_item(bad), Err(ItemError::BadName(_))),
            "{bad}"
        );
    }
    let items: Vec<_> = parse_items("C1+1; Y:vacuum+ ;T=2s;").into_iter().collect();
    assert_eq!(items.len(), 3);
    assert!(items.iter().all(Result::is_ok));
}

#[test]
fn items_print_as_they_parse() {
    for text in [
        "T=2s",
        "T=500ms",
        "T=1.25s",
        "I:part_present",
        "I:door=0",
        "Y:vacuum+",
        "Y:motor-",
        "C2+1",
        "J:7 if I:reject",
        "J:end if I:abort=0",
    ] {
        let item = parse_item(text).expect(text);
        assert_eq!(item.to_string(), text);
    }
}

#[test]
fn recognises_attempts_at_moves() {
    assert!(looks_like_move("C2+x"));
    assert!(looks_like_move("c 1"));
    assert!(!looks_like_move("Cylinder sequence"));
    assert!(!looks_like_move("BRANCH 1"));
}

#[test]
fn jumps_read_as_engineers_type_them() {
    let jump = |target, input: &str, value| CellItem::Jump {
        target,
        input: Name::new(input).unwrap(),
        value,
    };
    for (text, expected) in [
        ("J:7 if I:reject", jump(JumpTarget::Step(7), "reject", true)),
        (
            "j:7 IF i:Reject=1",
            jump(JumpTarget::Step(7), "reject", true),
        ),
        (
            "J:12if I:shift_ok=0",
            jump(JumpTarget::Step(12), "shift_ok", false),
        ),
        ("J: end if I:abort", jump(JumpTarget::End, "abort", true)),
        ("J:END IF I:iffy", jump(JumpTarget::End, "iffy", true)),
    ] {
        assert_eq!(parse_item(text), Ok(expected), "{text}");
    }
    for bad in [
        "J:7",
        "J:7 if",
        "J:x if I:reject",
        "J:0 if I:reject",
        "J:7 if Y:reject+",
        "J:7 when I:reject",
        "J:7 if I:reject=2",
        "J:7 if I:re ject",
        "J:99999999999 if I:reject",
    ] {
        assert!(
            matches!(
                parse_item(bad),
                Err(ItemError::BadJump(_) | ItemError::BadName(_))
            ),
            "{bad}: {:?}",
            parse_item(bad)
        );
    }
    assert!(looks_like_item("J:7 if I:reject"));
}

#[test]
fn label_comments_are_read_without_their_separators() {
    assert_eq!(
        step_comment("STEP 3 (clamp part)").as_deref(),
        Some("clamp part")
    );
    assert_eq!(step_comment("step 4: eject").as_deref(), Some("eject"));
    assert_eq!(step_comment("STEP 2 - lift").as_deref(), Some("lift"));
    assert_eq!(step_comment("STEP 2"), None);
    assert_eq!(step_comment("C1+1"), None);
    assert_eq!(actuator_comment("C1 (clamp)").as_deref(), Some("clamp"));
    assert_eq!(
        actuator_comment("C12: gripper arm").as_deref(),
        Some("gripper arm")
    );
    assert_eq!(actuator_comment("C2 lift").as_deref(), Some("lift"));
    // Only what the engineer used as a separator goes: brackets that
    // enclose the whole comment, one colon, a dash before a space.
    for (label, comment) in [
        ("STEP 3 ((x))", "(x)"),
        ("STEP 4: (y)", "(y)"),
        ("STEP 5 (clamp) extra", "(clamp) extra"),
        ("STEP 1 -5 bar", "-5 bar"),
        ("STEP 5 (-- dashes --)", "-- dashes --"),
        ("STEP 7 -> z", "-> z"),
        ("STEP 2 – lift", "lift"),
        ("STEP 6 (a) (b)", "(a) (b)"),
        ("STEP 8 (open (", "(open ("),
    ] {
        assert_eq!(step_comment(label).as_deref(), Some(comment), "{label}");
    }
    assert_eq!(
        actuator_comment("C3 (lift) extra").as_deref(),
        Some("(lift) extra")
    );
    assert_eq!(
        actuator_comment("C4 (mark) (x)").as_deref(),
        Some("(mark) (x)")
    );
    assert_eq!(actuator_comment("C2"), None);
    assert_eq!(actuator_comment("clamp"), None);
}

#[test]
fn invisible_characters_of_a_comment_become_what_they_show() {
    assert_eq!(visible_text("clamp\u{b}part"), "clamp\npart");
    assert_eq!(visible_text("a\u{7}b\u{1b}c\u{fffe}d\u{ffff}"), "abcd");
    assert_eq!(visible_text("tab\there\r\nok"), "tab\there\r\nok");
    assert_eq!(
        step_comment("STEP 2 (bell\u{7} and escape\u{1b})").as_deref(),
        Some("bell and escape")
    );
    assert_eq!(
        actuator_comment("C2 (lift\u{b}unit)").as_deref(),
        Some("lift\nunit")
    );
}
