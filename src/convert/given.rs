//! What the settings give, checked against the table before anything is
//! built: settings for actuators or inputs the table lacks, loads that do
//! nothing, cells the command line overrides, options naming actuators by
//! name, and the one check of every name over the table and its settings.

use std::collections::BTreeMap;

use crate::diag::{Code, Diagnostics, Location};
use crate::read;
use crate::settings::Settings;
use crate::settings::halt::Row;
use crate::table::StepTable;

/// A valve type, stroke, load or input delay for an actuator or input the
/// table does not have does nothing: a typo (C8 for C3) would leave the
/// real actuator on its default valve without a word. Each is E030 at the
/// SETTINGS cell that names it, or naming the command-line option; a
/// SETTINGS row giving only the default stroke (the old template's C1 to
/// C8) loses nothing and is W003 ([`super::placeholder_rows`]).
pub(super) fn settings_without_their_actuator(
    table: &StepTable,
    settings: &Settings,
    sheet: Option<(&read::Grid, &crate::settings::Given)>,
    file: &str,
    diags: &mut Diagnostics,
) {
    let has: Vec<String> = table
        .actuators
        .iter()
        .map(|a| format!("C{}", a.number))
        .collect();
    let has = if has.is_empty() {
        "it has none".to_string()
    } else {
        format!("it has {}", has.join(", "))
    };
    let option = Location {
        file: file.to_string(),
        sheet: None,
        cell: None,
    };
    // The template's actuator table lists C1 to C8 at the default 1s / 1s:
    // a row saying only the default loses nothing.
    let keys = |given: &crate::settings::Given, all: bool| -> Vec<(u32, &'static str)> {
        let mut keys: Vec<(u32, &'static str)> = Vec::new();
        keys.extend(given.valves.keys().map(|n| (*n, "valve")));
        keys.extend(
            given
                .strokes
                .iter()
                .filter(|(_, s)| all || **s != crate::stroke::Stroke::default())
                .map(|(n, _)| (*n, "stroke")),
        );
        keys.extend(given.loads.keys().map(|n| (*n, "load")));
        keys.retain(|(n, _)| table.actuator(*n).is_none());
        keys
    };
    for (n, what) in keys(&settings.given, true) {
        diags.error(
            Code::E030BadSetting,
            option.clone(),
            format!("--{what} C{n}=…: the table has no actuator C{n} ({has}); the setting would do nothing"),
        );
    }
    if let Some((grid, given)) = sheet {
        super::placeholder_rows::placeholder_rows(table, grid, given, &has, diags);
        let mut named: Vec<u32> = keys(given, false).into_iter().map(|(n, _)| n).collect();
        named.sort_unstable();
        named.dedup();
        for n in named {
            let cell = grid.cells.iter().find(|c| match &c.value {
                read::CellValue::Text(t) => {
                    let head = t.split(['(', ' ']).next().unwrap_or("");
                    crate::cell::actuator_name(head) == Some(n)
                }
                _ => false,
            });
            let at = match cell {
                Some(cell) => grid.location(cell.pos),
                None => grid.location(crate::diag::CellPos::new(0, 0)),
            };
            diags.error(
                Code::E030BadSetting,
                at,
                format!("the actuator table names C{n}, which the table does not have ({has}); its settings would do nothing"),
            );
        }
    }
}

/// A load only moves a piston whose valve lets it (an exhausted or a
/// pressurised centre); given for another valve it would be dropped
/// without a word: W006 at the file, naming the actuator and its valve.
pub(super) fn loads_without_effect(
    table: &StepTable,
    settings: &Settings,
    sheet: Option<&crate::settings::Given>,
    grid: &read::Grid,
    diags: &mut Diagnostics,
) {
    let valves = &settings.simulation.machine.valves;
    for (&n, load) in &settings.simulation.machine.loads {
        let Some(actuator) = table.actuator(n) else {
            continue; // E030 already
        };
        let valve = valves.of(n, actuator.max_position);
        if !valve.load_drifts() {
            let cell = sheet.and_then(|s| s.actuator_cells.get(&(n, "load")));
            let (source, at) = match cell {
                Some(at) if !settings.given.loads.contains_key(&n) => {
                    ("the actuator table's load", at.clone())
                }
                _ => ("--load", grid.sheet_location()),
            };
            diags.warning(
                Code::W006NoEffect,
                at,
                format!(
                    "{source} C{n}={load}: {} (a load drifts only a piston on a 53exhaust or 53pressure valve's centre); the load does nothing",
                    valve.load_held(n)
                ),
            );
        }
    }
}

/// The command line wins over the SETTINGS sheet, but not silently: each
/// cell it overrides is W006 at that cell, naming the option (a batch may
/// give one option to workbooks whose sheets differ).
pub(super) fn overridden_by_the_command_line(
    line: &crate::settings::Given,
    sheet: &crate::settings::Given,
    naming: &crate::symbols::Naming,
    diags: &mut Diagnostics,
) {
    for (label, at) in &sheet.cells {
        if line.gives(label) {
            // A board sets OpenPLC's addresses: --board, not a --target the
            // engineer never gave, overrides the cell (rt25 F6).
            let option = match (*label, line.board) {
                ("target", Some(_)) => "--board (OpenPLC's addresses)".to_string(),
                _ => crate::settings::option_for(label),
            };
            diags.warning(
                Code::W006NoEffect,
                at.clone(),
                format!(
                    "{label}: {option} on the command line wins over this cell; it was not used"
                ),
            );
        }
    }
    for ((actuator, what), at) in &sheet.actuator_cells {
        let n = *actuator;
        // An option may name the actuator (`--valve clamp=52bi`).
        let is_n = |name: &String| naming.actuator_called(name) == Some(n);
        let (option, given) = match *what {
            "valve" => (
                "valve",
                line.valves.contains_key(&n) || line.named_valves.keys().any(is_n),
            ),
            "load" => (
                "load",
                line.loads.contains_key(&n) || line.named_loads.keys().any(is_n),
            ),
            _ => (
                "stroke",
                line.strokes.contains_key(&n) || line.named_strokes.keys().any(is_n),
            ),
        };
        if given {
            diags.warning(
                Code::W006NoEffect,
                at.clone(),
                format!("{what} of C{n}: --{option} on the command line wins over this cell; it was not used"),
            );
        }
    }
}

/// The valve types, stroke times and loads the command line gives by an
/// actuator's name or ISO designation (`--valve clamp=52mono`, `--load
/// 1A1=0.1`), put in force for the actuator the naming authority reads it
/// as; a name no actuator of the table has, or an actuator given by name
/// and by number, is E030.
pub(super) fn by_name(
    table: &StepTable,
    settings: &mut Settings,
    file: &str,
    diags: &mut Diagnostics,
) {
    let at = Location {
        file: file.to_string(),
        sheet: None,
        cell: None,
    };
    let naming = settings.naming.clone();
    let named: Vec<String> = naming
        .actuators
        .iter()
        .map(|(n, a)| format!("C{n} ({})", a.text))
        .collect();
    let numbers: Vec<u32> = table.actuators.iter().map(|a| a.number).collect();
    let mut resolve = |option: &str, name: &str, numbered: bool| -> Option<u32> {
        let like = naming
            .actuator_like(name, &numbers)
            .map(|name| format!("; did you mean {name}?"))
            .unwrap_or_default();
        let why = match naming.actuator_called(name) {
            Some(n) if table.actuator(n).is_none() => {
                format!(
                    "{name} is C{n}, which the table does not have; the setting would do nothing"
                )
            }
            Some(n) if numbered => {
                format!("{name} is C{n}, which is given by number too; give each actuator once")
            }
            Some(n) => return Some(n),
            None if named.is_empty() => format!(
                "no actuator is named {name}: the SETTINGS actuator table names none (a row such as C1 (clamp) names one){like}"
            ),
            None => format!(
                "no actuator is named {name} (the actuator table names {}){like}",
                named.join(", ")
            ),
        };
        diags.error(
            Code::E030BadSetting,
            at.clone(),
            format!("--{option} {name}=…: {why}"),
        );
        None
    };
    let given = settings.given.clone();
    for (name, valve) in &given.named_valves {
        let n = naming.actuator_called(name);
        let numbered = n.is_some_and(|n| given.valves.contains_key(&n));
        if let Some(n) = resolve("valve", name, numbered) {
            settings
                .simulation
                .machine
                .valves
                .per_actuator
                .insert(n, *valve);
        }
    }
    for (name, stroke) in &given.named_strokes {
        let n = naming.actuator_called(name);
        let numbered = n.is_some_and(|n| given.strokes.contains_key(&n));
        if let Some(n) = resolve("stroke", name, numbered) {
            settings
                .simulation
                .machine
                .strokes
                .per_actuator
                .insert(n, *stroke);
        }
    }
    for (name, load) in &given.named_loads {
        let n = naming.actuator_called(name);
        let numbered = n.is_some_and(|n| given.loads.contains_key(&n));
        if let Some(n) = resolve("load", name, numbered) {
            settings.simulation.machine.loads.insert(n, *load);
        }
    }
    // One actuator under two names in one option (`arm=swivel,2A1=vacuum`):
    // neither value may win unsaid.
    let options = [
        ("valve", given.named_valves.keys().collect::<Vec<_>>()),
        ("stroke", given.named_strokes.keys().collect()),
        ("load", given.named_loads.keys().collect()),
    ];
    for (option, names) in options {
        let mut first: BTreeMap<u32, &String> = BTreeMap::new();
        for name in names {
            let Some(n) = naming.actuator_called(name) else {
                continue;
            };
            if let Some(earlier) = first.insert(n, name) {
                diags.error(
                    Code::E030BadSetting,
                    at.clone(),
                    format!(
                        "--{option} {name}=…: {name} is C{n}, which --{option} gives as {earlier} too; give each actuator once"
                    ),
                );
            }
        }
    }
}

/// The one check of every name against every other, over the table and
/// its settings (see [`crate::symbols::check`]), the program's operating
/// -mode buttons (`buttons`, lower case) among them: table cells first, then
/// the SETTINGS rows and the actuator names in sheet order, so that an
/// error falls on the later of two names.
pub(super) fn names_of_the_whole_table(
    table: &StepTable,
    grid: &read::Grid,
    settings: &Settings,
    buttons: &[String],
    diags: &mut Diagnostics,
) {
    use crate::symbols::check;
    let mut entries = check::table_entries(table, grid);
    let mut later = Vec::new();
    if let Some(row) = settings.named.get(&Row::StartPermissive) {
        later.extend(check::row_entries(
            Row::StartPermissive.label(),
            &settings.program.permissive,
            &row.at,
        ));
    }
    if let Some(row) = settings.named.get(&Row::Interlock) {
        let inputs: Vec<crate::cell::Name> = settings
            .program
            .interlocks
            .iter()
            .map(|i| i.input)
            .collect();
        later.extend(check::row_entries(Row::Interlock.label(), &inputs, &row.at));
    }
    let jogs = jog_buttons(table, settings);
    later.extend(check::actuator_entries(
        table,
        &settings.naming,
        &jogs,
        buttons,
        diags,
    ));
    later.sort_by_key(|e| check::sheet_order(&e.at));
    entries.extend(later);
    use crate::emit::OutputKind;
    let asked = |kinds: &[OutputKind]| kinds.iter().any(|k| settings.formats.contains(k));
    let step7 = [OutputKind::Awl, OutputKind::SymbolTable];
    let rockwell = [OutputKind::Rockwell, OutputKind::L5x];
    let limits = check::Limits {
        fst: settings.writes_fst(),
        longest: if asked(&step7) {
            Some((
                24,
                "characters of a symbol STEP 7's symbol table (.sdf, .awl)",
            ))
        } else if asked(&rockwell) {
            Some((40, "characters of a tag Studio 5000 (.L5X, .rockwell.csv)"))
        } else {
            None
        },
    };
    check::check_entries(&entries, &limits, diags);
}

/// Supervision times (`--supervision`, SETTINGS `supervision`) checked
/// against the table: each names a step the table has, the watchdog they
/// set is on, and none is shorter than its step takes in a healthy machine
/// (its longest move from the stroke times, plus its dwell), where the
/// alarm would come every cycle. Each is E030 at the SETTINGS cell, or
/// naming the option.
pub(super) fn supervision_times(
    table: &StepTable,
    settings: &Settings,
    file: &str,
    diags: &mut Diagnostics,
) {
    let times = &settings.program.supervision;
    if times.is_empty() {
        return;
    }
    let (at, source) = match settings.cells.get("supervision") {
        Some(at) => (at.clone(), "supervision".to_string()),
        None => (
            Location {
                file: file.to_string(),
                sheet: None,
                cell: None,
            },
            "--supervision".to_string(),
        ),
    };
    let mut refuse = |message: String| {
        diags.error(
            Code::E030BadSetting,
            at.clone(),
            format!("{source}: {message}"),
        );
    };
    if !settings.program.safety.watchdog {
        refuse(format!(
            "a supervision time sets the step watchdog, which {} leaves out; add watchdog or criteria to the safety checks",
            settings.origin("safety")
        ));
    }
    let strokes = &settings.simulation.machine.strokes;
    for (&number, &ms) in times {
        let Some(step) = table.steps.iter().find(|s| s.number == number) else {
            refuse(format!(
                "step {number} is not a step of the table (it has steps 1 to {})",
                table.steps.len()
            ));
            continue;
        };
        if let Some(why) = crate::table::two_rows_answer(&table.steps, number) {
            refuse(format!("step {number}: {why}"));
            continue;
        }
        let (longest, dwell) = crate::program::expected_step_ms(table, step, strokes);
        let text = |ms: u64| crate::cell::duration_text(ms.min(u64::from(u32::MAX)) as u32);
        let takes = longest + dwell;
        if u64::from(ms) <= takes {
            refuse(format!(
                "step {number}'s {} is not longer than the {} the step takes in a healthy machine (its longest move, plus its dwell): the alarm would come every cycle",
                crate::cell::duration_text(ms),
                text(takes)
            ));
            continue;
        }
        // The proof answers a wait after its input's delay: no alarm there.
        let delay_of = |w: &crate::table::Wait| settings.simulation.input_delay_ms(&w.input);
        let waits = step
            .waits
            .iter()
            .map(|w| (&w.input, u64::from(delay_of(w))));
        let Some((input, delay)) = waits.max_by_key(|(_, delay)| *delay) else {
            continue;
        };
        let waited = longest.max(delay) + dwell;
        if u64::from(ms) <= waited {
            refuse(format!(
                "step {number}'s {} is not longer than the {} the step takes in the program's proof, which answers its wait for I:{input} after {} (--input-delay), plus its dwell: the proof would raise the alarm; give step {number} a longer time, or I:{input} a shorter delay with --input-delay {input}=…",
                crate::cell::duration_text(ms),
                text(waited),
                text(delay)
            ));
        }
    }
}

/// A delay for an input the table does not have would be dropped without
/// a word (a batch may give one for some of its tables): W006.
pub(super) fn delays_without_their_input(
    table: &StepTable,
    effective: &Settings,
    grid: &read::Grid,
    diags: &mut Diagnostics,
) {
    for name in effective.simulation.input_delays.keys() {
        if !table.inputs.contains(name) {
            let inputs: Vec<&str> = table.inputs.iter().map(|n| n.as_str()).collect();
            diags.warning(
                Code::W006NoEffect,
                grid.sheet_location(),
                format!(
                    "--input-delay {name}=…: {name} is no machine input of this table ({}); nothing is delayed",
                    if inputs.is_empty() {
                        "it waits for none".to_string()
                    } else {
                        format!("its inputs: {}", inputs.join(", "))
                    }
                ),
            );
        }
    }
}

/// Manual mode on a table that moves no actuator has nothing to jog: the
/// MAN_MODE selector would only end cycles. The mode is left out of the
/// program (so `--modes all` serves such a table too) and W006 says so, at
/// the `modes` cell or naming `--modes`.
pub(super) fn manual_without_actuators(
    table: &StepTable,
    settings: &mut Settings,
    file: &str,
    diags: &mut Diagnostics,
) {
    if !settings.program.modes.manual || !table.actuators.is_empty() {
        return;
    }
    settings.program.modes.manual = false;
    let (at, source) = match settings.cells.get("modes") {
        Some(at) => (at.clone(), "modes"),
        None => (
            Location {
                file: file.to_string(),
                sheet: None,
                cell: None,
            },
            "--modes",
        ),
    };
    diags.warning(
        Code::W006NoEffect,
        at,
        format!(
            "{source}: manual mode jogs actuators, and the table moves none (no C1+1 cell); it is left out of the program"
        ),
    );
}

/// Manual mode's jog buttons (none without the mode).
fn jog_buttons(table: &StepTable, settings: &Settings) -> Vec<crate::program::Signal> {
    if !settings.program.modes.manual {
        return Vec::new();
    }
    let valves = &settings.simulation.machine.valves;
    let kinds = table
        .actuators
        .iter()
        .map(|a| (a.number, valves.of(a.number, a.max_position)))
        .collect();
    crate::program::jog_buttons(&kinds)
}

/// The names manual mode's jog buttons take (`jog1p`, `jog1m`, and under
/// any scheme the engineer's `clamp_jog_out`), lower-case: none without
/// the mode.
pub(super) fn jog_names(table: &StepTable, settings: &Settings) -> Vec<String> {
    jog_buttons(table, settings)
        .into_iter()
        .flat_map(|jog| {
            let own = settings.naming.own_alias(jog, table);
            std::iter::once(crate::symbols::paper_ident(jog)).chain(own)
        })
        .map(|name| name.to_ascii_lowercase())
        .collect()
}
