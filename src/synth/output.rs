//! The synthesis report (`NAME.synth.txt`, `NAME.synth.json`), the equations
//! as an IEC program (`NAME.equations.st`, `NAME.equations.il`) and the
//! EQUATIONS sheet of `NAME.xlsx`.

use rust_xlsxwriter::{DocProperties, ExcelDateTime, Format, Workbook, XlsxError};
use serde_json::json;

use super::verify::Verification;
use super::{Comparison, Equation, Method, Stopped, Synthesis};

/// The size convention, stated next to every number.
pub const CONVENTION: &str =
    "nodes = tree nodes: every leaf, every NOT and every binary operator (NOT (b OR x) = 4)";

fn name_of(s: &Synthesis) -> impl Fn(usize) -> String + '_ {
    move |v| s.modified.signal_name(v).to_string()
}

/// `A1  = NOT (b OR x)`: an equation as the report and the IL comments show it.
pub fn equation_line(s: &Synthesis, e: &Equation) -> String {
    format!(
        "{:<3} = {}",
        s.modified.token(e.action),
        e.expr.text(&name_of(s))
    )
}

/// The report as text.
pub fn report_text(s: &Synthesis, v: &Verification) -> String {
    let mut out = String::new();
    sequence_section(&mut out, s);
    truth_table_section(&mut out, s);
    equations_section(&mut out, s);
    verification_section(&mut out, s, v);
    out
}

/// The sequence, its signal clashes, and the modified sequence with how it
/// was found.
fn sequence_section(out: &mut String, s: &Synthesis) {
    let seq = &s.modified;
    out.push_str(&format!("sequence:          {}\n", s.original.text()));
    if s.clashes.is_empty() {
        out.push_str("signal clashes:    none (no memory needed)\n");
    } else {
        for c in &s.clashes {
            out.push_str(&format!("{c}\n"));
        }
    }
    if s.method == super::Method::Ga {
        out.push_str(&format!(
            "modified sequence: {}\n  {} inserted operation(s), {} memory(ies), found by the GA{}\n",
            seq.text(),
            s.insertions,
            seq.memories,
            s.minimum.gap(s.insertions, seq.memories)
        ));
    } else {
        out.push_str(&format!(
            "modified sequence: {}\n  {}\n",
            seq.text(),
            match s.front.first() {
                Some(fewest) if fewest.memories < seq.memories => format!(
                    "{} inserted operation(s), the proven minimum (exhaustive search); {} memory(ies), one more than the proven minimum of {}, for smaller equations (--prefer nodes)",
                    s.insertions, seq.memories, fewest.memories
                ),
                _ => format!(
                    "{} inserted operation(s), {} memory(ies): the proven minimum (exhaustive search)",
                    s.insertions, seq.memories
                ),
            }
        ));
    }
    if let Some(ga) = &s.ga {
        match &ga.sequence {
            Some(found) => out.push_str(&format!(
                "  the paper's GA: {} ({} inserted operation(s), {} memory(ies), {} generations, {} ms){}\n",
                found.text(),
                found.actions.len() - s.original.actions.len(),
                found.memories,
                ga.generations,
                ga.millis,
                s.minimum
                    .gap(found.actions.len() - s.original.actions.len(), found.memories)
            )),
            None => out.push_str(&format!(
                "  the paper's GA: no valid sequence in {} generations\n",
                ga.generations
            )),
        }
    }
}

/// The signal names and the truth table.
fn truth_table_section(out: &mut String, s: &Synthesis) {
    let seq = &s.modified;
    out.push_str("\nnames (as written; the programs' signals):\n");
    for line in seq.name_lines() {
        out.push_str(&format!("  {line}\n"));
    }
    out.push_str("\ntruth table (rows: the state before each action, in sequence order; 1, 0, x = don't care):\n");
    let vars: Vec<String> = (0..seq.variables())
        .map(|v| seq.signal_name(v).to_string())
        .collect();
    let cols: Vec<String> = s.table.columns.iter().map(|a| seq.token(*a)).collect();
    out.push_str(&format!(
        "  {}  | {}   next\n",
        vars.join(" "),
        cols.join(" ")
    ));
    for (k, (state, cells)) in s.table.rows.iter().zip(&s.table.cells).enumerate() {
        let bits: Vec<String> = (0..seq.variables())
            .map(|v| ((state >> v) & 1).to_string())
            .collect();
        let row: Vec<String> = cells
            .iter()
            .zip(&cols)
            .map(|(c, name)| format!("{:<width$}", c.symbol(), width = name.len()))
            .collect();
        out.push_str(&format!(
            "  {}  | {}   {}\n",
            bits.join(" "),
            row.join(" "),
            seq.token(seq.actions[k])
        ));
    }
}

/// Each equation with its size, the totals and the front.
fn equations_section(out: &mut String, s: &Synthesis) {
    out.push_str(&format!(
        "\nequations (each the proven smallest tree; {CONVENTION}):\n"
    ));
    for e in &s.equations {
        out.push_str(&format!(
            "  {:<40} {:>2} nodes   QM: {}{}\n",
            equation_line(s, e),
            e.expr.nodes(),
            e.qm.as_ref()
                .map(|q| format!("{} ({} nodes)", q.text(&name_of(s)), q.nodes()))
                .unwrap_or_else(|| "not computed".to_string()),
            match (&s.ga, &e.gp) {
                (None, _) => String::new(),
                (Some(_), Some(gp)) =>
                    format!("   GP: {} ({} nodes)", gp.text(&name_of(s)), gp.nodes()),
                (Some(_), None) => "   GP: no fitting tree".to_string(),
            }
        ));
    }
    out.push_str(&format!(
        "  total {} nodes, largest equation {} nodes; Quine-McCluskey two-level: {}\n",
        s.total_nodes(),
        s.largest(),
        s.qm_nodes()
            .map(|n| format!("{n} nodes"))
            .unwrap_or_else(|| "not computed".to_string())
    ));
    if let Some(c) = &s.comparison {
        out.push_str(&format!("  {}\n", comparison_text(c, s.total_nodes())));
    }
    if s.front.len() > 1 {
        out.push_str(&format!(
            "\nfront (fewer memories against smaller equations, at {} inserted operations; > marks the one kept, --prefer memories|nodes):\n",
            s.insertions
        ));
        for p in &s.front {
            out.push_str(&format!(
                "  {} {} memories: {} nodes, {}\n    {}\n",
                if p.chosen { ">" } else { " " },
                p.memories,
                p.nodes,
                comparison_text(&p.comparison, p.nodes),
                p.sequence
            ));
        }
    }
}

/// The simulation and modes verdicts, the GP total and the time taken.
fn verification_section(out: &mut String, s: &Synthesis, v: &Verification) {
    out.push_str(&format!(
        "\nsimulation: {} ({} actions in {:.2} s of simulated time{})\n",
        if v.passed { "passed" } else { "FAILED" },
        v.observed.len(),
        v.millis as f64 / 1000.0,
        v.problem
            .as_ref()
            .map(|p| format!("; {p}"))
            .unwrap_or_default()
    ));
    out.push_str(&match &v.modes {
        Ok(moves) => format!(
            "modes: passed (START, STOP at the end of the cycle, ESTOP refusing START until RESET, RESET home, one more cycle: {moves} moves as the program's inputs START, STOP, ESTOP, RESET_PB would give them)\n"
        ),
        Err(why) => format!("modes: FAILED ({why})\n"),
    });
    let gp_total: Option<usize> = s.ga.as_ref().and_then(|_| {
        s.equations
            .iter()
            .map(|e| e.gp.as_ref().map(|g| g.nodes()))
            .sum()
    });
    if let Some(gp) = gp_total {
        out.push_str(&format!(
            "GP total: {gp} nodes ({} the proven minimum of {})\n",
            if gp == s.total_nodes() {
                "equal to"
            } else {
                "above"
            },
            s.total_nodes()
        ));
    }
    // Every part that ran, and the whole: the parts are not the whole
    // (checks, the truth table, the report).
    let exact = if s.method == Method::Ga {
        "minimal equations"
    } else {
        "exact route"
    };
    out.push_str(&format!(
        "time: {} ms in all ({exact} {} ms",
        s.total_millis, s.millis
    ));
    if let Some(ms) = s.ga_gp_millis {
        out.push_str(&format!(", GA + GP {ms} ms"));
    }
    out.push_str(")\n");
}

/// What is proven about the total: the smallest of every candidate, or the
/// best found with the bound no candidate beats.
pub fn comparison_text(c: &Comparison, nodes: usize) -> String {
    let listed = if c.placements_truncated {
        format!(", the first {} the search listed", thousands(c.placements))
    } else {
        String::new()
    };
    let candidates = format!(
        "{} candidates ({} placement(s) of the memory operations{listed}, each memory either way round)",
        thousands(c.candidates),
        thousands(c.placements)
    );
    let why = match c.stopped {
        Some(Stopped::Interrupted) => "when Ctrl-C stopped the search",
        _ => "before the time limit (--time-limit)",
    };
    if c.settled == c.candidates {
        format!("the smallest total of all {candidates}")
    } else if nodes <= c.lower_bound {
        format!(
            "the smallest total possible: {} of {candidates} compared {why}, and none of the others can have fewer nodes",
            thousands(c.settled)
        )
    } else {
        format!(
            "best found: {} of {candidates} compared {why}; no candidate has fewer than {} nodes",
            thousands(c.settled),
            c.lower_bound
        )
    }
}

/// 1,760.
fn thousands(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::new();
    for (i, d) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i).is_multiple_of(3) {
            out.push(',');
        }
        out.push(d);
    }
    out
}

/// The report as JSON.
pub fn report_json(s: &Synthesis, v: &Verification, seed: u64) -> String {
    let seq = &s.modified;
    let memories: Vec<String> = seq.memory_names.iter().map(|c| c.to_string()).collect();
    let columns: Vec<String> = s.table.columns.iter().map(|a| seq.token(*a)).collect();
    let variables: Vec<String> = (0..seq.variables())
        .map(|v| seq.signal_name(v).to_string())
        .collect();
    let rows: Vec<serde_json::Value> = s
        .table
        .rows
        .iter()
        .zip(&s.table.cells)
        .enumerate()
        .map(|(k, (state, cells))| {
            json!({
                "state": (0..seq.variables()).map(|v| (state >> v) & 1).collect::<Vec<_>>(),
                "next": seq.token(seq.actions[k]),
                "cells": cells.iter().map(|c| c.symbol().to_string()).collect::<Vec<_>>(),
            })
        })
        .collect();
    let equations: serde_json::Map<String, serde_json::Value> = s
        .equations
        .iter()
        .map(|e| (seq.token(e.action), json!(e.expr.text(&name_of(s)))))
        .collect();
    let nodes: serde_json::Map<String, serde_json::Value> = s
        .equations
        .iter()
        .map(|e| (seq.token(e.action), json!(e.expr.nodes())))
        .collect();
    let value = json!({
        "sequence": s.original.actions.iter().map(|a| s.original.token(*a)).collect::<Vec<_>>(),
        "clashes": s.clashes.iter().map(|c| json!({
            "state": c.state_text,
            "actions": c.actions.iter().map(|(_, t)| t.clone()).collect::<Vec<_>>(),
        })).collect::<Vec<_>>(),
        "modified_sequence": seq.actions.iter().map(|a| seq.token(*a)).collect::<Vec<_>>(),
        "inserted_operations": s.insertions,
        "comparison": s.comparison.as_ref().map(|c| json!({
            "placements": c.placements,
            "placements_truncated": c.placements_truncated,
            "candidates": c.candidates,
            "compared": c.settled,
            "nodes_lower_bound": c.lower_bound,
            "nodes_proven_smallest": s.total_nodes() <= c.lower_bound,
            "stopped": c.stopped.map(|why| match why {
                Stopped::TimeLimit => "time limit",
                Stopped::Interrupted => "interrupted",
            }),
        })),
        "memories": memories,
        "front": s.front.iter().map(|p| json!({
            "memories": p.memories,
            "inserted_operations": p.insertions,
            "nodes": p.nodes,
            "nodes_lower_bound": p.comparison.lower_bound,
            "nodes_proven_smallest": p.nodes <= p.comparison.lower_bound,
            "modified_sequence": p.sequence.split(' ').collect::<Vec<_>>(),
            "chosen": p.chosen,
        })).collect::<Vec<_>>(),
        "truth_table": {"variables": variables, "columns": columns, "rows": rows},
        "equations": equations,
        "nodes": {"per_equation": nodes, "total": s.total_nodes(), "largest": s.largest(),
                  "qm_total": s.qm_nodes(), "convention": CONVENTION},
        "method": match s.method {
            super::Method::Exact => "exact",
            super::Method::Ga => "ga",
            super::Method::Both => "both",
        },
        "seed": s.ga.as_ref().map(|_| seed),
        "millis": s.total_millis,
        "ga": s.ga.as_ref().map(|g| json!({
            "modified_sequence": g.sequence.as_ref().map(|q| q.actions.iter().map(|a| q.token(*a)).collect::<Vec<_>>()),
            "generations": g.generations,
            "millis": g.millis,
        })),
        "gp_equations": s.ga.as_ref().map(|_| s.equations.iter().map(|e| (seq.token(e.action), json!(e.gp.as_ref().map(|g| g.text(&name_of(s)))))).collect::<serde_json::Map<_, _>>()),
        "simulation": {"passed": v.passed, "problem": v.problem,
                       "modes": {"passed": v.modes.is_ok(), "problem": v.modes.as_ref().err()}},
    });
    serde_json::to_string_pretty(&value).unwrap_or_default() + "\n"
}

/// `NAME.xlsx` with the EQUATIONS sheet and the truth table.
pub fn workbook(s: &Synthesis, v: &Verification) -> Result<Vec<u8>, XlsxError> {
    let seq = &s.modified;
    let mut workbook = Workbook::new();
    workbook.set_properties(
        &DocProperties::new().set_creation_datetime(&ExcelDateTime::from_ymd(2020, 1, 1)?),
    );
    let bold = Format::new().set_bold();
    let sheet = workbook.add_worksheet();
    sheet.set_name("EQUATIONS")?;
    sheet.write_string_with_format(0, 0, "EQUATIONS", &bold)?;
    sheet.write_string(
        1,
        0,
        format!("sequence {} -> {}", s.original.text(), seq.text()),
    )?;
    sheet.write_string(2, 0, CONVENTION)?;
    for (col, h) in ["ACTION", "EQUATION", "NODES", "QM (two-level)", "QM NODES"]
        .iter()
        .enumerate()
    {
        sheet.write_string_with_format(4, col as u16, *h, &bold)?;
    }
    for (i, e) in s.equations.iter().enumerate() {
        let row = 5 + i as u32;
        sheet.write_string(row, 0, seq.token(e.action))?;
        sheet.write_string(row, 1, e.expr.text(&name_of(s)))?;
        sheet.write_number(row, 2, e.expr.nodes() as f64)?;
        if let Some(q) = &e.qm {
            sheet.write_string(row, 3, q.text(&name_of(s)))?;
            sheet.write_number(row, 4, q.nodes() as f64)?;
        }
    }
    let row = 6 + s.equations.len() as u32;
    sheet.write_string(row, 0, "TOTAL")?;
    sheet.write_number(row, 2, s.total_nodes() as f64)?;
    if let Some(q) = s.qm_nodes() {
        sheet.write_number(row, 4, q as f64)?;
    }
    sheet.write_string(
        row + 1,
        0,
        format!("simulation: {}", if v.passed { "passed" } else { "FAILED" }),
    )?;
    sheet.set_column_width(0, 10)?;
    sheet.set_column_width(1, 36)?;
    sheet.set_column_width(3, 36)?;

    let sheet = workbook.add_worksheet();
    sheet.set_name("TRUTH TABLE")?;
    let mut col = 0u16;
    for v in 0..seq.variables() {
        sheet.write_string_with_format(0, col, seq.signal_name(v).to_string(), &bold)?;
        col += 1;
    }
    for a in &s.table.columns {
        sheet.write_string_with_format(0, col, seq.token(*a), &bold)?;
        col += 1;
    }
    sheet.write_string_with_format(0, col, "next", &bold)?;
    for (k, (state, cells)) in s.table.rows.iter().zip(&s.table.cells).enumerate() {
        let row = 1 + k as u32;
        let mut col = 0u16;
        for v in 0..seq.variables() {
            sheet.write_number(row, col, ((state >> v) & 1) as f64)?;
            col += 1;
        }
        for c in cells {
            sheet.write_string(row, col, c.symbol().to_string())?;
            col += 1;
        }
        sheet.write_string(row, col, seq.token(seq.actions[k]))?;
    }
    workbook.save_to_buffer()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn comparison(settled: usize, lower_bound: usize, stopped: Option<Stopped>) -> Comparison {
        Comparison {
            placements: 110,
            placements_truncated: false,
            candidates: 1760,
            settled,
            lower_bound,
            stopped,
        }
    }

    /// The report claims the smallest total only when it is proven, and
    /// otherwise says how far the comparison got and the bound.
    #[test]
    fn the_total_is_called_smallest_only_when_proven() {
        let all = comparison_text(&comparison(1760, 95, None), 95);
        assert!(all.starts_with("the smallest total of all 1,760 candidates (110 placement(s)"));
        let cut = comparison_text(&comparison(367, 88, Some(Stopped::TimeLimit)), 95);
        assert_eq!(
            cut,
            "best found: 367 of 1,760 candidates (110 placement(s) of the memory operations, each memory either way round) compared before the time limit (--time-limit); no candidate has fewer than 88 nodes"
        );
        let stopped = comparison_text(&comparison(5, 88, Some(Stopped::Interrupted)), 95);
        assert!(
            stopped.contains("when Ctrl-C stopped the search"),
            "{stopped}"
        );
        let bounded = comparison_text(&comparison(900, 95, Some(Stopped::TimeLimit)), 95);
        assert!(
            bounded.starts_with("the smallest total possible: 900 of 1,760"),
            "{bounded}"
        );
        assert_eq!(thousands(47232), "47,232");
        assert_eq!(thousands(999), "999");
    }
}
