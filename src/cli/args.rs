//! Options shared by several commands, and their parsers.

use super::*;

#[derive(Args)]
pub(crate) struct SimArgs {
    /// Stroke times per actuator, extend/retract: C2=1.5s/0.8s,C3=2s (default 1s/1s; a swivel drive's and a vacuum gripper's own times, see the guide's valves).
    #[arg(long, value_name = "LIST", value_parser = parse_strokes)]
    pub(crate) stroke: Option<StrokeMap>,
    /// Drift of a 5/3 piston with no coil on, stroke per second: C2=0.1, 2A1=0.1 or clamp=0.1
    /// (the load on an exhausted centre, the creep of a pressurised one; default 0.05).
    #[arg(long, value_name = "LIST", value_parser = parse_loads)]
    pub(crate) load: Option<Keyed<f64>>,
    /// PLC scan time of the simulation and of the generated task.
    #[arg(long, value_name = "TIME", value_parser = parse_scan)]
    pub(crate) scan: Option<u32>,
    /// How long the machine takes to give a waited-for input: part_present=2s (default 0.5s; a jump's input comes as its step starts unless named here).
    #[arg(long, value_name = "LIST", value_parser = parse_input_delays)]
    pub(crate) input_delay: Option<InputDelays>,
}

pub(crate) type InputDelays = std::collections::BTreeMap<crate::cell::Name, u32>;

pub(crate) fn parse_input_delays(text: &str) -> Result<InputDelays, String> {
    no_empty_item(text)?;
    let mut delays = InputDelays::new();
    for item in text.split(',').map(str::trim).filter(|i| !i.is_empty()) {
        let (name, value) = item
            .split_once('=')
            .ok_or_else(|| format!("\"{item}\": expected <input>=<time>, e.g. part_present=2s"))?;
        let name = crate::cell::Name::new(&name.trim().to_ascii_lowercase())
            .map_err(|e| format!("\"{item}\": {e}"))?;
        unit_given(item, value)?;
        let ms = crate::stroke::parse_duration_ms(value)
            .ok_or_else(|| format!("\"{item}\": expected a time such as 2s or 300ms"))?;
        if delays.insert(name, ms).is_some() {
            return Err(format!(
                "\"{item}\": {name} is given twice; give each input once"
            ));
        }
    }
    Ok(delays)
}

/// Per-actuator values by number (`C2=…`) and by the engineer's name
/// (`clamp=…`, resolved once the table's SETTINGS names are read).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Keyed<T> {
    pub(crate) numbered: std::collections::BTreeMap<u32, T>,
    pub(crate) named: std::collections::BTreeMap<String, T>,
}

/// Splits `C1=…,clamp=…` into the items that name an actuator by number,
/// parsed by `numbered` as before, and those that give a name, each value
/// parsed by `one`.
fn parse_keyed<T>(
    text: &str,
    numbered: impl Fn(&str) -> Result<std::collections::BTreeMap<u32, T>, String>,
    one: impl Fn(&str, &str) -> Result<T, String>,
) -> Result<Keyed<T>, String> {
    let mut by_number = Vec::new();
    let mut named = std::collections::BTreeMap::new();
    let mut folded_keys = std::collections::HashSet::new();
    // A terminal may pass `Ö` as O and a combining mark (macOS does): the
    // table's names are read composed.
    let text = crate::cell::composed_str(text);
    for item in text.split(',').map(str::trim).filter(|i| !i.is_empty()) {
        let key = item.split_once('=').map_or(item, |(k, _)| k).trim();
        // `C2 (gripper arm)`, as steptable prints an actuator, is a name.
        let printed = crate::program::bracketed(key).1.is_some();
        let is_name = crate::cell::parse_actuator(key).is_none()
            && (printed
                || crate::symbols::scheme_stem(key).is_some()
                || crate::cell::iso_actuator(key).is_some()
                || engineers_name(key))
            && item.contains('=');
        if !is_name {
            by_number.push(item);
            continue;
        }
        let value = item.split_once('=').map_or("", |(_, v)| v);
        // Kept as written (messages quote it); one name in any case once.
        if !folded_keys.insert(crate::cell::folded(key)) {
            return Err(format!(
                "\"{item}\": {key} is given twice; give each actuator once"
            ));
        }
        named.insert(key.to_string(), one(item, value)?);
    }
    Ok(Keyed {
        numbered: numbered(&by_number.join(","))?,
        named,
    })
}

/// A name such as the SETTINGS actuator table may give, with a letter
/// beyond A-Z (`Ölpumpe`, `Kühler`): the table's names may, and an option
/// names an actuator as the table does.
fn engineers_name(key: &str) -> bool {
    !key.is_ascii()
        && key.starts_with(char::is_alphabetic)
        && key
            .chars()
            .all(|c| c.is_alphanumeric() || matches!(c, '_' | '-' | ' '))
}

pub(crate) type StrokeMap = Keyed<crate::stroke::Stroke>;

pub(crate) fn parse_strokes(text: &str) -> Result<StrokeMap, String> {
    no_empty_item(text)?;
    for item in text.split(',') {
        if let Some((_, times)) = item.split_once('=') {
            for time in times.split('/') {
                unit_given(item.trim(), time)?;
            }
        }
    }
    parse_keyed(text, crate::stroke::parse_strokes, |item, value| {
        // One item alone, with its value under a placeholder number.
        crate::stroke::parse_strokes(&format!("C1={value}"))
            .map(|m| m.into_values().next().unwrap_or_default())
            .map_err(|_| {
                format!("\"{item}\": \"{value}\" is not a stroke time such as 1.5s or 800ms (or extend/retract: 1.5s/0.8s)")
            })
    })
}

pub(crate) fn parse_scan(text: &str) -> Result<u32, String> {
    unit_given(text, text)?;
    crate::stroke::parse_scan(text)
}

/// A time on the command line says its unit: `2` could be seconds or
/// milliseconds, and an option has no cell to warn at (the SETTINGS sheet's
/// W007), so it is refused with both readings. A number not written
/// plainly (`1e1ms`, `0x2s`) is refused saying what is expected, before a
/// parser could blame its range; a word (`fast`) is left to the parser.
pub(crate) fn unit_given(item: &str, time: &str) -> Result<(), String> {
    let time = time.trim();
    if !crate::cell::plain_time(time) && time.chars().any(|c| c.is_ascii_digit()) {
        return Err(format!(
            "\"{item}\": \"{time}\" is not written as a time: expected a plain number and its unit, such as 10ms or 1.5s (no exponent, sign or hex digits)"
        ));
    }
    if crate::cell::without_unit(time) && crate::stroke::parse_duration_ms(time).is_some() {
        return Err(format!(
            "\"{item}\": {time} has no unit: write {time}s or {time}ms"
        ));
    }
    Ok(())
}

impl SimArgs {
    pub(crate) fn apply(&self, settings: &mut Settings) {
        settings.give(Given {
            scan_ms: self.scan,
            loads: self
                .load
                .as_ref()
                .map(|l| l.numbered.clone())
                .unwrap_or_default(),
            named_loads: self
                .load
                .as_ref()
                .map(|l| l.named.clone())
                .unwrap_or_default(),
            strokes: self
                .stroke
                .as_ref()
                .map(|s| s.numbered.clone())
                .unwrap_or_default(),
            named_strokes: self
                .stroke
                .as_ref()
                .map(|s| s.named.clone())
                .unwrap_or_default(),
            ..Given::default()
        });
        if let Some(delays) = &self.input_delay {
            settings.simulation.input_delays = delays.clone();
        }
    }
}

/// What files to write and how they look.
#[derive(Args)]
pub(crate) struct FileArgs {
    /// Horizontal axis of NAME.diagram.svg: step (displacement-step) or time.
    #[arg(long, value_enum, default_value_t = DiagramArg::Step)]
    pub(crate) diagram: DiagramArg,
    #[arg(long, value_name = "LIST", value_parser = parse_formats, help = formats_help())]
    pub(crate) formats: Option<std::collections::BTreeSet<OutputKind>>,
    /// Folder of templates that replace the built-in ones by file name
    /// (start from `steptable templates export DIR`).
    #[arg(long, value_name = "DIR")]
    pub(crate) templates: Option<PathBuf>,
    /// Flush every written file and its folder to the disk before finishing
    /// (slower; for outputs that must survive a power cut).
    #[arg(long)]
    pub(crate) sync: bool,
}

/// The settings of a command that writes files: common flags, simulation
/// flags and file options. `None` (the problem printed) for a broken
/// template folder.
pub(crate) fn output_settings(
    common: &CommonArgs,
    sim: &SimArgs,
    files: &FileArgs,
) -> Option<Settings> {
    let mut settings = common.settings();
    sim.apply(&mut settings);
    match files.apply(&mut settings) {
        Ok(()) => Some(settings),
        Err(err) => {
            eprintln!("{err}");
            None
        }
    }
}

impl FileArgs {
    /// Applies the options; a broken template folder is the user's error.
    pub(crate) fn apply(&self, settings: &mut Settings) -> Result<(), String> {
        settings.diagram = match self.diagram {
            DiagramArg::Step => DiagramKind::Step,
            DiagramArg::Time => DiagramKind::Time,
        };
        if let Some(formats) = &self.formats {
            settings.formats = formats.clone();
        }
        if self.sync {
            settings.durability = crate::write::Durability::Sync;
        }
        if let Some(dir) = &self.templates {
            settings.templates =
                crate::settings::user_templates::load_dir(dir).map_err(|e| e.to_string())?;
        }
        Ok(())
    }
}

#[derive(Clone, Copy, ValueEnum)]
pub(crate) enum DiagramArg {
    Step,
    Time,
}

#[derive(Args)]
pub(crate) struct CommonArgs {
    /// Address dialect: festo (I0.0/O0.0, 16-bit words), iec or openplc (%IX0.0/%QX0.0), siemens (I0.0/Q0.0).
    #[arg(long, ignore_case = true, value_parser = parse_target())]
    pub(crate) target: Option<Target>,
    /// OpenPLC board: only the inputs and outputs it wires are used (implies --target iec).
    #[arg(long, ignore_case = true, value_parser = parse_board())]
    pub(crate) board: Option<Board>,
    /// Operand letters for siemens: en (I/Q) or de (E/A).
    #[arg(long, ignore_case = true, value_parser = parse_mnemonic())]
    pub(crate) mnemonic: Option<Mnemonic>,
    /// Read this sheet instead of "SEQUENTIAL CONTROL DESCRIPTION" or the first sheet with moves.
    #[arg(long, value_name = "NAME")]
    pub(crate) sheet: Option<String>,
    /// How to print problems: human (default) or json (one object per line on stdout).
    #[arg(long, value_enum, default_value_t = MessageFormat::Human)]
    pub(crate) message_format: MessageFormat,
    #[arg(long, value_name = "LIST", value_parser = parse_valves, help = valves_help())]
    pub(crate) valve: Option<Keyed<crate::actuator::ActuatorKind>>,
    #[arg(long, value_name = "LIST", value_parser = parse_safety, help = safety_help())]
    pub(crate) safety: Option<Safety>,
    #[arg(long, value_name = "LIST", value_parser = parse_modes, help = modes_help())]
    pub(crate) modes: Option<Modes>,
    /// Homing stages for RESET, first to last: "C3&C4,C2,C1", an actuator also by its ISO designation (3A1) or name (clamp) (default: the order the cycle itself returns them home).
    #[arg(long, value_name = "ORDER", value_parser = parse_home_order)]
    pub(crate) home_order: Option<HomeOrder>,
    /// Supervision time per table step, in place of the watchdog's from the plant model: 3=5s,5=12s (needs --safety watchdog or criteria).
    #[arg(long, value_name = "LIST", value_parser = parse_supervision)]
    pub(crate) supervision: Option<Supervision>,
    /// How signals are designated in every output: paper (x10, y1+; the default), iso (ISO 1219-2: 1A1, 1B1/1B2, 1M1/1M2) or names (the actuator table's names: clamp_home, clamp_out).
    #[arg(long, ignore_case = true, value_parser = parse_designations())]
    pub(crate) designations: Option<Scheme>,
}

/// `--designations`: the library's parser, with the schemes listed in `--help`.
fn parse_designations() -> impl clap::builder::TypedValueParser<Value = Scheme> {
    clap::builder::PossibleValuesParser::new(Scheme::ALL.map(Scheme::name))
        .try_map(|text| text.parse::<Scheme>())
}

/// `--safety`'s help, listing every check there is.
fn safety_help() -> String {
    format!(
        "Safety checks in the generated program: {} (or all, or none)",
        Safety::NAMES.join(", ")
    )
}

/// `--modes`' help, listing every mode there is.
fn modes_help() -> String {
    format!(
        "Operating modes in the generated program: {} (or all, or none)",
        Modes::NAMES.join(", ")
    )
}

/// Homing stages, each a list of actuator numbers. A type of its own: clap
/// takes a bare `Vec` for a flag given several times, and panicked.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct HomeOrder(pub(crate) Vec<Vec<String>>);

pub(crate) fn parse_modes(text: &str) -> Result<Modes, String> {
    text.parse()
}

/// Supervision times by step. A type of its own: clap takes a bare map
/// apart.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) struct Supervision(pub(crate) std::collections::BTreeMap<usize, u32>);

pub(crate) fn parse_supervision(text: &str) -> Result<Supervision, String> {
    comma_in_a_number(text)?;
    crate::program::parse_supervision(text).map(Supervision)
}

pub(crate) fn parse_home_order(text: &str) -> Result<HomeOrder, String> {
    Modes::parse_home_order(text).map(HomeOrder)
}

/// `--formats` help: every kind the library writes, from its own list.
pub(crate) fn formats_help() -> String {
    let names: Vec<&str> = OutputKind::ALL.iter().map(|k| k.name()).collect();
    let defaults = OutputKind::defaults();
    let asked: Vec<&str> = OutputKind::ALL
        .iter()
        .filter(|k| !defaults.contains(k))
        .map(|k| k.name())
        .collect();
    format!(
        "Files to write, comma-separated: {} (default: every one but {}, written when named or with all)",
        names.join(", "),
        asked.join(", ")
    )
}

/// `--valve` help: every valve type, from the library's list.
pub(crate) fn valves_help() -> String {
    let names: Vec<&str> = crate::actuator::ActuatorKind::ALL
        .iter()
        .map(|v| v.name())
        .collect();
    format!(
        "Valve per actuator: C1=52mono,C2=53closed ({})",
        names.join(", ")
    )
}

pub(crate) fn parse_formats(text: &str) -> Result<std::collections::BTreeSet<OutputKind>, String> {
    OutputKind::parse_list(text)
}

pub(crate) fn parse_valves(text: &str) -> Result<Keyed<crate::actuator::ActuatorKind>, String> {
    no_empty_item(text)?;
    parse_keyed(text, crate::actuator::parse_valves, |item, value| {
        value
            .parse::<crate::actuator::ActuatorKind>()
            .map_err(|e| format!("\"{item}\": {e}"))
    })
}

pub(crate) fn parse_loads(text: &str) -> Result<Keyed<f64>, String> {
    no_empty_item(text)?;
    parse_keyed(text, crate::actuator::parse_loads, |item, value| {
        // One item alone, with its value under a placeholder number.
        crate::actuator::parse_loads(&format!("C1={value}"))
            .map(|m| m.into_values().next().unwrap_or_default())
            .map_err(|why| format!("\"{item}\": {why}"))
    })
}

/// A per-actuator or per-input list with an empty item (`C1=52mono,,C2=52bi`,
/// `,`) has lost a value or has a stray comma: refused, as `--modes` is.
pub(crate) fn no_empty_item(text: &str) -> Result<(), String> {
    if text.split(',').any(|item| item.trim().is_empty()) {
        return Err(format!(
            "\"{}\" has an empty item between its commas; give each item once (e.g. C1=52mono,C2=52bi)",
            text.trim()
        ));
    }
    comma_in_a_number(text)
}

/// `C1=0,8s`: a decimal comma the list's comma parts into `C1=0` and `8s`.
/// Said as that, not as a bad value `0` and an item without `=` (rt24 F8).
fn comma_in_a_number(text: &str) -> Result<(), String> {
    let items: Vec<&str> = text.split(',').map(str::trim).collect();
    let digit_end = |t: &str| t.ends_with(|c: char| c.is_ascii_digit());
    let parted = |before: &str, after: &str| {
        digit_end(before) && !after.contains('=') && after.starts_with(|c: char| c.is_ascii_digit())
    };
    for (k, first) in items.iter().enumerate() {
        if !first.contains('=') {
            continue;
        }
        // The item and every piece the commas split off it (`C1=1`,
        // `5s/0`, `8s` of `C1=1,5s/0,8s`).
        let mut pieces = vec![*first];
        while let Some(next) = items.get(k + pieces.len()) {
            match parted(pieces[pieces.len() - 1], next) {
                true => pieces.push(next),
                false => break,
            }
        }
        if pieces.len() < 2 {
            continue;
        }
        let grouped =
            (pieces[1..].iter()).all(|p| p.chars().take_while(char::is_ascii_digit).count() == 3);
        // Three digits after the comma may group thousands as well: both
        // readings, the thousands first (`1,000ms` is rarely 1 ms).
        let write = match grouped {
            true => format!(
                "write {} for a thousands' comma, or {} for a decimal one",
                pieces.concat(),
                pieces.join(".")
            ),
            false => format!("write a decimal point ({})", pieces.join(".")),
        };
        return Err(format!(
            "\"{}\": the comma parts the list's items, so its number is split; {write}",
            pieces.join(",")
        ));
    }
    Ok(())
}

pub(crate) fn parse_safety(text: &str) -> Result<Safety, String> {
    text.parse()
}

/// `--target`: the library's parser, with the names listed in `--help`.
fn parse_target() -> impl clap::builder::TypedValueParser<Value = Target> {
    clap::builder::PossibleValuesParser::new(Target::NAMES).try_map(|text| text.parse::<Target>())
}

/// `--board`: the library's parser, with the boards listed in `--help`.
fn parse_board() -> impl clap::builder::TypedValueParser<Value = Board> {
    clap::builder::PossibleValuesParser::new(crate::address::BOARDS.map(|b| b.name))
        .try_map(|text| text.parse::<Board>())
}

/// `--mnemonic`: the library's parser, with the names listed in `--help`.
fn parse_mnemonic() -> impl clap::builder::TypedValueParser<Value = Mnemonic> {
    clap::builder::PossibleValuesParser::new(Mnemonic::ALL.map(Mnemonic::name))
        .try_map(|text| text.parse::<Mnemonic>())
}

#[derive(Clone, Copy, PartialEq, Eq, ValueEnum)]
pub(crate) enum MessageFormat {
    Human,
    Json,
}

impl CommonArgs {
    /// Settings from the flags; what they give, a workbook's SETTINGS sheet
    /// does not change.
    pub(crate) fn settings(&self) -> Settings {
        let mut settings = Settings::new();
        settings.give(
            Given {
                target: self.target,
                board: self.board,
                mnemonic: self.mnemonic,
                safety: self.safety,
                modes: self.modes.clone(),
                home_order: self.home_order.as_ref().map(|order| order.0.clone()),
                supervision: self.supervision.as_ref().map(|times| times.0.clone()),
                valves: self
                    .valve
                    .as_ref()
                    .map(|v| v.numbered.clone())
                    .unwrap_or_default(),
                named_valves: self
                    .valve
                    .as_ref()
                    .map(|v| v.named.clone())
                    .unwrap_or_default(),
                designations: self.designations,
                ..Given::default()
            }
            .with_board_target(),
        );
        settings.sheet = self.sheet.clone();
        settings.invocation = super::recorded_invocation();
        settings
    }
}
