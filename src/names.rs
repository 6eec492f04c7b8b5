//! Names a machine signal may not have: keywords of the target languages,
//! the IEC 61131-3 standard library, addresses of STEP 7 and FST, and the
//! names the generated program uses for itself.

/// The step counter of the Structured Text programs (`step` is a keyword).
pub const STEP_COUNTER: &str = "active_step";
/// The STEP 7 memory that lets at most one step fire per cycle.
pub const FIRED: &str = "fired";
/// The cyclic OB the TIA Portal SCL source replaces and calls the step
/// program from, and the instance DB of that program: names of the CPU, as
/// every PLC tag is, so no tag may have them.
pub const TIA_CYCLIC_OB: &str = "Main";
pub const TIA_INSTANCE_DB: &str = "steptable_main_DB";
/// The program and routine of the Studio 5000 export.
pub const LOGIX_PROGRAM: &str = "MainProgram";
pub const LOGIX_ROUTINE: &str = "MainRoutine";
/// Festo FST keeps this many characters of a symbolic operand: the shortest
/// limit of any target.
pub const FST_SYMBOL_CHARS: usize = 9;

/// What FST keeps of a name: its first [`FST_SYMBOL_CHARS`] characters.
pub fn fst_stem(name: &str) -> String {
    name.chars().take(FST_SYMBOL_CHARS).collect()
}

/// Instruction-list operators and the function-block inputs IL names as
/// operators (`S1`, `IN`, `PT`): matiec refuses a variable of one of these
/// names in IL (checked one by one), so no signal of synth's IL may have
/// them. The table's programs have no IL: there they are names like any.
#[rustfmt::skip]
pub const IL_OPERATORS: &[&str] = &[
    "LD", "LDN", "ST", "STN", "S", "R", "S1", "R1", "AND", "ANDN", "OR", "ORN", "XOR", "XORN",
    "NOT", "ADD", "SUB", "MUL", "DIV", "MOD", "GT", "GE", "EQ", "NE", "LE", "LT", "JMP", "JMPC",
    "JMPCN", "CAL", "CALC", "CALCN", "RET", "RETC", "RETCN", "IN", "PT", "CLK", "CU", "CD", "PV",
];

/// The identifiers the synthesised programs (`NAME.equations.st`/`.il`)
/// declare for themselves, beside each variable's `a`, `a_home`, `a_end`,
/// `ya_p`, `ya_m` (or `x`, `x_set`, `x_reset`) and the IL scratch `t1`, `t2`…;
/// a unit test reads them back from the template.
#[rustfmt::skip]
pub const SYNTH_OWN: &[&str] = &[
    "start", "stop", "estop", "reset_pb", "home", "start_edge", "start_last", "resetting",
    "normal", "halted", "homing", "running", "stopping", "away", "cycle_end", "stopped", "enable",
    "cyclic_task", "main_instance", "synth_main", "synth_il",
];

/// Why a machine input or output may not have this (lower-case) name in a
/// program with the operating-mode buttons `buttons` (lower case: `stop`,
/// `estop`, `cont`, `reset_pb`): the one check every place a name enters
/// goes through (table cells, SETTINGS rows). The name is refused when it
/// is reserved or reads as a button in any case; where a Festo FST file is
/// written (`fst`), also when the 9 characters FST keeps of it do.
pub fn signal_problem(name: &str, buttons: &[String], fst: bool) -> Option<String> {
    let name = name.to_ascii_lowercase();
    let stem = fst_stem(&name);
    if let Some(reason) = reserved_name(&name) {
        return Some(format!("\"{name}\" cannot name a machine signal: {reason}"));
    }
    if fst && let Some(reason) = reserved_name(&stem) {
        return Some(format!(
            "\"{name}\" cannot name a machine signal where a Festo FST file is written: FST keeps its first {FST_SYMBOL_CHARS} characters, \"{stem}\", and {reason}"
        ));
    }
    // The button of that very name before one that is only the same to
    // FST (`clamp_jog_in` is the retract jog, not `clamp_jog_out`).
    if let Some(button) = buttons.iter().find(|b| b.eq_ignore_ascii_case(&name)) {
        return Some(format!(
            "\"{name}\" cannot name a machine signal while the program has the operating-mode button {} (IEC names ignore case): rename the signal, or leave that mode out",
            button.to_ascii_uppercase()
        ));
    }
    let button = buttons.iter().find(|b| fst && same_in_fst(b, &name))?;
    Some(format!(
        "\"{name}\" cannot name a machine signal while the program has the operating-mode button {} where a Festo FST file is written: FST keeps the first {FST_SYMBOL_CHARS} characters of both, \"{stem}\"; rename the signal, leave that mode out, or leave the FST files out (--formats)",
        button.to_ascii_uppercase()
    ))
}

/// The name an operator calls a button by beside its symbol, which
/// `simulate --press` answers to: RESET for RESET_PB (whose symbol avoids
/// an FST keyword), STEP for STEP_PB, EMERGENCY_STOP for ESTOP.
pub const BUTTON_ALIASES: [(&str, &str); 4] = [
    ("RESET_PB", "RESET"),
    ("STEP_PB", "STEP"),
    ("ESTOP", "EMERGENCY_STOP"),
    ("MAN_MODE", "MANUAL"),
];

/// The alias of the button whose symbol is `symbol`, if it has one.
pub fn button_alias(symbol: &str) -> Option<&'static str> {
    BUTTON_ALIASES
        .iter()
        .find(|(s, _)| s.eq_ignore_ascii_case(symbol))
        .map(|(_, alias)| *alias)
}

/// Whether two names are one symbol to Festo FST, which keeps only their
/// first [`FST_SYMBOL_CHARS`] characters (and ignores case).
pub fn same_in_fst(a: &str, b: &str) -> bool {
    fst_stem(&a.to_ascii_lowercase()) == fst_stem(&b.to_ascii_lowercase())
}

/// Why an actuator or memory of a synthesised program may not have this
/// name (`R`, `C1`): one of the identifiers it gives (`r`, `r_home`,
/// `yr_p`, …) is a keyword, an IL operator, a standard function or one of
/// the synthesised program's own names.
pub fn synth_problem(name: &str, identifiers: &[String]) -> Option<String> {
    identifiers.iter().find_map(|id| {
        let lower = id.to_ascii_lowercase();
        let upper = lower.to_ascii_uppercase();
        let why = if IL_OPERATORS.contains(&upper.as_str()) {
            "an instruction-list operator (matiec would read it as one)"
        } else if is_standard_library_name(&upper) {
            "a standard function, function block or data type of IEC 61131-3"
        } else if KEYWORDS.contains(&upper.as_str()) {
            "a keyword of a PLC language"
        } else if SYNTH_OWN.contains(&lower.as_str())
            || lower
                .strip_prefix('t')
                .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
        {
            "a name the synthesised program uses for itself"
        } else {
            return None;
        };
        Some(format!(
            "{name} cannot name an actuator for synthesis: its signal {lower} is {why}; use another letter"
        ))
    })
}

/// IEC 61131-3 keywords (and the common vendor ones) no identifier may be.
#[rustfmt::skip]
pub const KEYWORDS: &[&str] = &[
    "ABS", "ACTION", "AND", "ANY", "ARRAY", "AT", "BOOL", "BY", "BYTE", "CASE", "CONFIGURATION",
    "CONSTANT", "DATE", "DINT", "DO", "DT", "DWORD", "ELSE", "ELSIF", "END_ACTION", "END_CASE",
    "END_CONFIGURATION", "END_FOR", "END_FUNCTION", "END_FUNCTION_BLOCK", "END_IF",
    "END_PROGRAM", "END_REPEAT", "END_RESOURCE", "END_STEP", "END_STRUCT", "END_TRANSITION",
    "END_TYPE", "END_VAR", "END_WHILE", "EN", "ENO", "EXIT", "FALSE", "FOR", "FROM",
    "FUNCTION", "FUNCTION_BLOCK", "IF", "INITIAL_STEP", "INT", "INTERVAL", "LINT", "LREAL",
    "MOD", "NOT", "OF", "ON", "OR", "PRIORITY", "PROGRAM", "READ_ONLY", "READ_WRITE", "REAL",
    "REPEAT", "RESOURCE", "RETAIN", "RETURN", "SINT", "STEP", "STRING", "STRUCT", "TASK",
    "THEN", "TIME", "TO", "TOD", "TRANSITION", "TRUE", "TYPE", "UDINT", "UINT", "ULINT",
    "UNTIL", "USINT", "VAR", "VAR_ACCESS", "VAR_EXTERNAL", "VAR_GLOBAL", "VAR_INPUT",
    "VAR_IN_OUT", "VAR_OUTPUT", "VAR_TEMP", "WHILE", "WITH", "WORD", "XOR", "NOP", "JMP",
    "SET", "RESET", "THEN", "TON", "TOF", "TP", "LOAD", "ELSE", "OTHRW", "CMP", "PSE",
    // matiec's and OpenPLC v3's own (the edition 2 words it parses).
    "CONTINUE", "VAR_CONFIG", "R_EDGE", "F_EDGE", "NON_RETAIN", "REF", "REF_TO", "NULL",
    // Edition 3's object-oriented words, which OpenPLC v4's STruC++ and
    // CODESYS reserve.
    "THIS", "SUPER", "METHOD", "END_METHOD", "INTERFACE", "END_INTERFACE", "PROPERTY",
    "END_PROPERTY", "PUBLIC", "PRIVATE", "PROTECTED", "INTERNAL", "EXTENDS", "IMPLEMENTS",
    "ABSTRACT", "FINAL", "OVERRIDE", "NAMESPACE", "END_NAMESPACE", "USING", "VAR_STAT",
    "CLASS", "END_CLASS", "CHAR", "WCHAR", "WSTRING", "LWORD", "LTIME", "LDATE", "LTOD", "LDT",
    "DATE_AND_TIME", "TIME_OF_DAY", "REFERENCE", "POINTER",
];

/// Why a machine input or output may not have this (lower-case) name, if
/// it may not: a keyword of a target language, or a name of the generated
/// program's own (sensors `x…`, coils `y…`, memories, timers, steps).
pub fn reserved_name(name: &str) -> Option<String> {
    let upper = name.to_ascii_uppercase();
    // The library first: `ton`, `abs`, `int` are in both lists, and the
    // engineer is told what they are (a block, a function, a type).
    // Instruction-list operators (`r`, `s`, `ld`) are refused only for
    // synth's IL output ([`synth_problem`]): the table's programs are ST,
    // where matiec accepts them.
    if is_standard_library_name(&upper) {
        return Some(
            "it is a standard function, function block or data type of IEC 61131-3 (matiec, OpenPLC and CODESYS would take it for that)"
                .to_string(),
        );
    }
    if KEYWORDS.contains(&upper.as_str()) {
        return Some("it is a keyword of a PLC language".to_string());
    }
    // The words of the SETTINGS lists (`hold-safe | none`, `safety | all`,
    // `target | default`): a signal so named could not be told from them.
    if ["all", "none", "default"].contains(&name) {
        return Some(
            "it is a word of the SETTINGS rows and options (all, none, default), which could not tell the signal from it"
                .to_string(),
        );
    }
    const OWN: &[&str] = &[
        // The mode buttons (stop, estop, reset_pb, cont, step_mode,
        // step_pb) are taken only when their mode is on: the table check
        // knows which are.
        "start",
        "start_mem",
        "halt",
        "alarm_pl",
        "alarm_wd",
        "alarm_il",
        "watchdog",
        "wd_armed",
        "wd_run",
        "wd_pt",
        "wd_restart",
        "cycle_req",
        "busy",
        "auto_run",
        "step_ok",
        "step_mem",
        "reset_mem",
        "man_mem",
        "jog_ok",
        "homing",
        FIRED,
        STEP_COUNTER,
        "sequence",
        // The program, task and instance of the Structured Text (matiec
        // refuses a variable named like its program).
        "steptable_main",
        "cyclic_task",
        "main_instance",
        // OpenPLC's upload needs the configuration and resource so named
        // (its script moves Config0.c and Res0.c).
        "config0",
        "res0",
        // The programs the SFC chart runs before and after it, and their
        // instances (its steps `step_k` and actions `step_k_entry` are
        // numbered names below).
        "steptable_pre",
        "steptable_post",
        "pre_instance",
        "post_instance",
        // The objects of the CODESYS files (CODESYS names are not case
        // sensitive): a variable named like a global variable list or the
        // task would be ambiguous there.
        "gvl_io",
        "gvl_steptable",
        "maintask",
        // The blocks of the TIA Portal SCL source and the program and
        // routine of the Studio 5000 export (TIA_CYCLIC_OB, …, lower case).
        "main",
        "steptable_main_db",
        "mainprogram",
        "mainroutine",
    ];
    // Followed by a digit these read as the program's own names or as an
    // address of STEP 7 (I0, MW2, DB1, T3, Z4) or FST (FW1, TP0, R3, V10).
    let numbered = [
        "x", "y", "m", "t", "jogged", "dwell", "dw", "runon", "ro", "zone", "home", "step_",
        "crit", "miss", "p", "f", "i", "o", "q", "e", "a", "l", "c", "z", "r", "v", "db", "di",
        "fb", "fc", "ob", "sfb", "sfc", "mb", "mw", "md", "ib", "iw", "id", "qb", "qw", "qd", "eb",
        "ew", "ed", "ab", "aw", "ad", "pib", "piw", "pid", "pqb", "pqw", "pqd", "peb", "pew",
        "ped", "pab", "paw", "pad", "dbx", "dbb", "dbw", "dbd", "fw", "ow", "tp", "tw", "cp", "cw",
        "lb", "lw", "ld",
    ];
    let after_prefix_is_number = |prefix: &str| {
        name.strip_prefix(prefix)
            .and_then(|rest| rest.chars().next())
            .is_some_and(|c| c.is_ascii_digit())
    };
    if OWN.contains(&name) || numbered.iter().any(|p| after_prefix_is_number(p)) {
        return Some(
            "the generated program uses it (sensors x…, coils y…, memories, timers, steps and addresses such as I0 or T1)"
                .to_string(),
        );
    }
    None
}

/// Elementary and generic data types of IEC 61131-3.
const TYPES: &[&str] = &[
    "BOOL",
    "SINT",
    "INT",
    "DINT",
    "LINT",
    "USINT",
    "UINT",
    "UDINT",
    "ULINT",
    "REAL",
    "LREAL",
    "TIME",
    "LTIME",
    "DATE",
    "TIME_OF_DAY",
    "TOD",
    "DATE_AND_TIME",
    "DT",
    "STRING",
    "WSTRING",
    "CHAR",
    "WCHAR",
    "BYTE",
    "WORD",
    "DWORD",
    "LWORD",
    "ANY",
    "ANY_DERIVED",
    "ANY_ELEMENTARY",
    "ANY_MAGNITUDE",
    "ANY_NUM",
    "ANY_REAL",
    "ANY_INT",
    "ANY_BIT",
    "ANY_STRING",
    "ANY_DATE",
    "ANY_NBIT",
    "ANY_SINT",
    "ANY_UINT",
];

/// Standard functions and function blocks (IEC 61131-3 and the libraries
/// matiec and OpenPLC ship), without their typed variants (`ADD_INT`).
const LIBRARY: &[&str] = &[
    "ABS",
    "ACOS",
    "ADD",
    "AND",
    "ASIN",
    "ATAN",
    "CONCAT",
    "COS",
    "CTD",
    "CTU",
    "CTUD",
    "DELETE",
    "DERIVATIVE",
    "DIV",
    "DIVTIME",
    "EQ",
    "EXP",
    "EXPT",
    "FIND",
    "F_TRIG",
    "GE",
    "GT",
    "HYSTERESIS",
    "INSERT",
    "INTEGRAL",
    "LE",
    "LEFT",
    "LEN",
    "LIMIT",
    "LN",
    "LOG",
    "LT",
    "MAX",
    "MID",
    "MIN",
    "MOD",
    "MOVE",
    "MUL",
    "MULTIME",
    "MUX",
    "NE",
    "NOT",
    "OR",
    "PID",
    "RAMP",
    "REPLACE",
    "RIGHT",
    "ROL",
    "ROR",
    "RS",
    "RTC",
    "R_TRIG",
    "SEL",
    "SEMA",
    "SHL",
    "SHR",
    "SIN",
    "SQRT",
    "SR",
    "SUB",
    "TAN",
    "TOF",
    "TON",
    "TP",
    "TRUNC",
    "XOR",
    "ROTARY_SWITCH",
    "TCP_CLOSE",
    "TCP_CONNECT",
    "TCP_RECEIVE",
    "TCP_SEND",
    "ADD_DT_TIME",
    "ADD_TOD_TIME",
    "CONCAT_DATE_TOD",
    "SUB_DATE_DATE",
    "SUB_DT_DT",
    "SUB_DT_TIME",
    "SUB_TOD_TIME",
    "SUB_TOD_TOD",
    "CONCAT_DT_TOD",
    "SLM_04THM_CONFIG",
    "SLM_ANALOG_IN_4",
    "SLM_ANALOG_IN_8",
    "SLM_ANALOG_OUT_4",
    "SLM_ANALOG_OUT_8",
    "SLM_DISCRETE_IN_16",
    "SLM_DISCRETE_IN_8",
    "SLM_DISCRETE_OUT_15",
    "SLM_DISCRETE_OUT_16",
    "SLM_DISCRETE_OUT_8",
    "SLM_INIT",
    "SLM_TEMPERATURE_4",
    "SM_16DIN",
    "SM_16RELAY",
    "SM_4REL4IN",
    "SM_8DIN",
    "SM_8MOSFET",
    "SM_8RELAY",
    "SM_BAS",
    "SM_HOME",
    "SM_INDUSTRIAL",
    "SM_RTD",
];

/// Whether an (upper-case) name is a standard function, function block or
/// type: one of them, a typed variant (`ADD_INT`, `CTU_DINT`), or a
/// conversion (`INT_TO_REAL`, `BYTE_BCD_TO_UINT`, `TRUNC_INT`).
fn is_standard_library_name(name: &str) -> bool {
    if TYPES.contains(&name) || LIBRARY.contains(&name) {
        return true;
    }
    // Typed variants, once or twice (`MUX_DINT_BOOL`).
    let typed = TYPES.iter().any(|t| {
        name.strip_suffix(t)
            .and_then(|base| base.strip_suffix('_'))
            .is_some_and(is_standard_library_name)
    });
    if typed {
        return true;
    }
    let side = |text: &str| {
        text == "BCD"
            || TYPES.contains(&text)
            || text
                .strip_suffix("_BCD")
                .is_some_and(|t| TYPES.contains(&t))
            || text
                .strip_prefix("BCD_")
                .is_some_and(|t| TYPES.contains(&t))
    };
    name.match_indices("_TO_")
        .any(|(at, _)| side(&name[..at]) && side(&name[at + 4..]))
        || name.strip_prefix("TO_").is_some_and(side)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// rt7 F18.5: `ton` is refused as the timer block it is, not as a
    /// keyword; `if` stays a keyword.
    #[test]
    fn a_reserved_name_is_refused_for_what_it_is() {
        for block in ["ton", "tof", "tp", "abs", "int"] {
            let why = reserved_name(block).unwrap();
            assert!(
                why.contains("standard function, function block or data type"),
                "{block}: {why}"
            );
        }
        assert!(reserved_name("if").unwrap().contains("keyword"));
    }

    #[test]
    fn standard_functions_blocks_and_types_are_refused() {
        for name in [
            "max",
            "min",
            "left",
            "right",
            "limit",
            "move",
            "sel",
            "len",
            "ctu",
            "r_trig",
            "lword",
            "mux",
            "abs",
            "sqrt",
            "concat",
            "mid",
            "find",
            "insert",
            "delete",
            "replace",
            "trunc",
            "ton",
            "tof",
            "tp",
            "rs",
            "sr",
            "f_trig",
            "ctd",
            "ctud",
            "rtc",
            "sema",
            "pid",
            "ramp",
            "integral",
            "derivative",
            "hysteresis",
            "expt",
            "shl",
            "rol",
            "wstring",
            "add_int",
            "ctu_dint",
            "int_to_real",
            "byte_bcd_to_uint",
            "uint_to_bcd_word",
            "date_and_time_to_time_of_day",
            "sub_dt_dt",
            "mux_dint",
            "time_of_day",
            "any_num",
            "bcd_to_int",
            "to_bcd",
        ] {
            assert!(reserved_name(name).is_some(), "{name}");
        }
        for name in [
            "vacuum",
            "heater",
            "fan",
            "clamp",
            "part_present",
            "maxi",
            "left_door",
            // A conversion's name needs a type on both sides of `_to_`.
            "part_to_bin",
            "part_to_int",
            "int_to_bin",
        ] {
            assert_eq!(reserved_name(name), None, "{name}");
        }
    }

    #[test]
    fn il_operators_are_names_outside_il_and_mode_buttons_are_refused_in_any_case() {
        // matiec accepts these in ST; only synth's IL refuses them (`r1`,
        // `s1` stay refused as FST registers).
        for name in [
            "ld", "st", "s", "r", "in", "pt", "clk", "cal", "ret", "jmpc",
        ] {
            assert_eq!(signal_problem(name, &[], true), None, "{name}");
            assert!(synth_problem(name, &[name.to_string()]).is_some(), "{name}");
        }
        let buttons = ["estop".to_string(), "stop".to_string()];
        assert!(
            signal_problem("estop", &buttons, true)
                .unwrap()
                .contains("ESTOP")
        );
        assert!(signal_problem("EStop", &buttons, true).is_some());
        assert_eq!(signal_problem("estop", &[], true), None);
        assert_eq!(signal_problem("stop_lamp", &buttons, true), None);
        assert_eq!(signal_problem("vacuum", &buttons, true), None);
    }

    #[test]
    fn synthesis_names_clash_with_il_and_the_programs_own() {
        let ids = |n: &str| vec![n.to_string(), format!("{n}_home"), format!("y{n}_p")];
        for letter in ["r", "s"] {
            assert!(synth_problem(letter, &ids(letter)).is_some(), "{letter}");
        }
        for letter in ["a", "b", "q", "t", "c1", "x"] {
            assert_eq!(synth_problem(letter, &ids(letter)), None, "{letter}");
        }
        assert!(synth_problem("home", &["home".to_string()]).is_some());
    }

    #[test]
    fn the_synthesised_programs_own_names_are_all_listed() {
        let vars = include_str!("../templates/equations_vars.j2");
        let declared: Vec<&str> = vars
            .lines()
            .filter(|l| !l.contains("{{"))
            .filter_map(|l| l.trim().split_once(" : BOOL"))
            .map(|(name, _)| name)
            .collect();
        assert!(declared.len() > 10, "{declared:?}");
        for name in declared {
            assert!(SYNTH_OWN.contains(&name), "{name}");
        }
    }

    #[test]
    fn the_blocks_of_the_scl_and_l5x_files_are_refused_in_any_case() {
        for name in [TIA_CYCLIC_OB, TIA_INSTANCE_DB, LOGIX_PROGRAM, LOGIX_ROUTINE] {
            assert!(
                reserved_name(&name.to_ascii_lowercase()).is_some(),
                "{name}"
            );
        }
        assert!(reserved_name("mains").is_none());
    }

    #[test]
    fn addresses_of_step7_and_fst_are_refused() {
        for name in ["mw10", "db1", "z3", "c1", "fw2", "tp0", "r3", "v10", "dbx0"] {
            assert!(reserved_name(name).is_some(), "{name}");
        }
    }
}
