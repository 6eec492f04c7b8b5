//! An interpreter of the Studio 5000 ladder that steptable writes
//! (`NAME.L5X`), built from the text alone: no Logix controller or
//! emulator runs outside Windows, and no open RLL simulator models Logix
//! timers (l5x2c's passes a timer by value and never accumulates). It
//! shares no code with the emitter.
//!
//! The file is read as XML (quick-xml): the controller's tags, the target
//! program's tags, its main routine (`MainRoutineName`, `Type="RLL"`) and
//! every rung's neutral text, which must parse completely:
//! `rung := element* ';'`, `element := INSTR '(' operand {',' operand} ')' |
//! '[' leg {',' leg} ']'`, `leg := element*`.
//!
//! Each scan runs the rungs in order as the Logix instruction reference
//! defines them: the rung-condition starts true; `XIC` / `XIO` pass it on
//! while their bit is 1 / 0; `OTE` writes it, `OTL` / `OTU` set / clear
//! their bit when it is true, `ONS` passes one true scan; `MOV` copies and
//! `RES` clears a timer's ACC, EN, TT and DN when it is true; `TON` times
//! in milliseconds: true after false (EN off) it sets EN and TT and takes
//! the time, true again it adds the time since to ACC and sets DN (ACC held
//! at PRE) once ACC reaches PRE, false it clears ACC, EN, TT and DN.
//! Output instructions pass the condition on; a branch's legs each start
//! from the condition before it, and it ends true if any leg does. `S:FS`
//! is on in the first scan only. Every scan happens at scan number × scan
//! time. Anything else is an error.

use std::collections::BTreeMap;

use quick_xml::events::Event;
use steptable::address::Allocation;
use steptable::simulate::io::IoTrace;

use super::Stepped;

#[derive(Debug, Clone, PartialEq)]
pub enum Element {
    Instruction(String, Vec<String>),
    Branch(Vec<Vec<Element>>),
}

/// One rung's elements; the whole text must be read.
pub fn parse_rung(text: &str) -> Result<Vec<Element>, String> {
    let chars: Vec<char> = text.trim().chars().collect();
    let mut at = 0;
    let elements = elements(&chars, &mut at)?;
    if chars.get(at) != Some(&';') || at + 1 != chars.len() {
        return Err(format!("rung does not end in one ';' at {at}: {text}"));
    }
    Ok(elements)
}

fn elements(chars: &[char], at: &mut usize) -> Result<Vec<Element>, String> {
    let mut list = Vec::new();
    loop {
        match chars.get(*at) {
            Some('[') => {
                let mut legs = Vec::new();
                loop {
                    *at += 1;
                    legs.push(elements(chars, at)?);
                    match chars.get(*at) {
                        Some(',') => continue,
                        Some(']') => break,
                        _ => return Err(format!("unclosed branch at {at}")),
                    }
                }
                *at += 1;
                list.push(Element::Branch(legs));
            }
            Some(c) if c.is_ascii_uppercase() => {
                let len = chars[*at..]
                    .iter()
                    .take_while(|c| c.is_ascii_alphanumeric())
                    .count();
                let name: String = chars[*at..*at + len].iter().collect();
                *at += len;
                if chars.get(*at) != Some(&'(') {
                    return Err(format!("{name} without operands"));
                }
                let close = chars[*at..]
                    .iter()
                    .position(|&c| c == ')')
                    .ok_or("unclosed (")?;
                let inside: String = chars[*at + 1..*at + close].iter().collect();
                let operands: Vec<String> =
                    inside.split(',').map(|o| o.trim().to_string()).collect();
                if operands.iter().any(|o| {
                    o.is_empty()
                        || !o
                            .chars()
                            .all(|c| c.is_ascii_alphanumeric() || "_.:?".contains(c))
                }) {
                    return Err(format!("bad operand in {name}({inside})"));
                }
                *at += close + 1;
                list.push(Element::Instruction(name, operands));
            }
            _ => return Ok(list),
        }
    }
}

#[derive(Debug, Clone)]
pub struct Tag {
    pub name: String,
    pub data_type: String,
    pub description: String,
}

#[derive(Debug, Default)]
pub struct L5x {
    pub controller_tags: Vec<Tag>,
    pub program_tags: Vec<Tag>,
    /// The main routine's rungs: comment and text.
    pub rungs: Vec<(String, String)>,
    pub target_type: String,
    pub software_revision: String,
}

/// Reads the file: tags by scope, the main routine's rungs.
pub fn read(xml: &str) -> Result<L5x, String> {
    let mut reader = quick_xml::Reader::from_str(xml);
    let mut file = L5x::default();
    let mut path: Vec<String> = Vec::new();
    let (mut main_routine, mut routine) = (String::new(), String::new());
    let (mut text, mut comment) = (String::new(), String::new());
    loop {
        let event = reader.read_event().map_err(|e| format!("XML: {e}"))?;
        let (start, empty) = match &event {
            Event::Start(e) => (Some(e.clone()), false),
            Event::Empty(e) => (Some(e.clone()), true),
            _ => (None, false),
        };
        if let Some(e) = start {
            let name = e.name().as_ref().to_string();
            let attr = |key: &str| super::plcxml::attribute(&e, key).unwrap_or_default();
            match name.as_str() {
                "RSLogix5000Content" => {
                    file.target_type = attr("TargetType");
                    file.software_revision = attr("SoftwareRevision");
                }
                "Program" => main_routine = attr("MainRoutineName"),
                "Routine" if attr("Type") != "RLL" => return Err("a routine not in RLL".into()),
                "Routine" => routine = attr("Name"),
                "Tag" => {
                    let tag = Tag {
                        name: attr("Name"),
                        data_type: attr("DataType"),
                        description: String::new(),
                    };
                    if path.iter().any(|p| p == "Program") {
                        file.program_tags.push(tag);
                    } else {
                        file.controller_tags.push(tag);
                    }
                }
                "Rung" => {
                    text.clear();
                    comment.clear();
                }
                _ => {}
            }
            if !empty {
                path.push(name);
            }
            continue;
        }
        match event {
            Event::End(e) => {
                if e.name().as_ref() == "Rung" && routine == main_routine {
                    file.rungs.push((comment.clone(), text.clone()));
                }
                path.pop();
            }
            Event::Text(t) => on_text(
                &path,
                &t.xml10_content(),
                &mut file,
                &mut text,
                &mut comment,
            ),
            Event::CData(t) => on_text(
                &path,
                &t.xml10_content(),
                &mut file,
                &mut text,
                &mut comment,
            ),
            Event::GeneralRef(r) => {
                let c = super::plcxml::entity(&r)?.to_string();
                on_text(&path, &c, &mut file, &mut text, &mut comment);
            }
            Event::Eof => break,
            _ => {}
        }
    }
    if file.rungs.is_empty() {
        return Err(format!("no rung in the main routine {main_routine:?}"));
    }
    Ok(file)
}

/// Text inside an element: a tag's description, a rung's comment or text.
fn on_text(path: &[String], value: &str, file: &mut L5x, text: &mut String, comment: &mut String) {
    let parent = path.len().checked_sub(2).map(|i| path[i].as_str());
    match (parent, path.last().map(String::as_str)) {
        (Some("Tag"), Some("Description")) => {
            let tags = if path.iter().any(|p| p == "Program") {
                &mut file.program_tags
            } else {
                &mut file.controller_tags
            };
            if let Some(tag) = tags.last_mut() {
                tag.description.push_str(value);
            }
        }
        (Some("Rung"), Some("Text")) => text.push_str(value),
        (Some("Rung"), Some("Comment")) => comment.push_str(value),
        _ => {}
    }
}

/// A Logix TIMER.
#[derive(Debug, Default, Clone, Copy)]
struct Timer {
    pre: i64,
    acc: i64,
    en: bool,
    tt: bool,
    dn: bool,
    /// The time TON last looked at the clock.
    stamp: i64,
}

struct Controller {
    bits: BTreeMap<String, bool>,
    timers: BTreeMap<String, Timer>,
    first_scan: bool,
    now: i64,
}

impl Controller {
    fn read(&self, operand: &str) -> Result<bool, String> {
        if operand == "S:FS" {
            return Ok(self.first_scan);
        }
        if let Some((timer, member)) = operand.split_once('.') {
            let t = self
                .timers
                .get(timer)
                .ok_or_else(|| format!("{timer} is no TIMER"))?;
            return match member {
                "DN" => Ok(t.dn),
                "EN" => Ok(t.en),
                "TT" => Ok(t.tt),
                _ => Err(format!("{operand} is no bit")),
            };
        }
        self.bits
            .get(operand)
            .copied()
            .ok_or_else(|| format!("{operand} is no BOOL tag"))
    }

    fn write(&mut self, operand: &str, value: bool) -> Result<(), String> {
        let bit = self
            .bits
            .get_mut(operand)
            .ok_or_else(|| format!("{operand} is no BOOL tag"))?;
        *bit = value;
        Ok(())
    }

    fn timer(&mut self, name: &str) -> Result<&mut Timer, String> {
        self.timers
            .get_mut(name)
            .ok_or_else(|| format!("{name} is no TIMER"))
    }

    /// Runs `list` with rung-condition `condition`; the condition after it.
    fn run(&mut self, list: &[Element], mut condition: bool) -> Result<bool, String> {
        for element in list {
            condition = match element {
                Element::Branch(legs) => {
                    let mut out = false;
                    for leg in legs {
                        out |= self.run(leg, condition)?;
                    }
                    out
                }
                Element::Instruction(name, ops) => self.instruction(name, ops, condition)?,
            };
        }
        Ok(condition)
    }

    fn instruction(&mut self, name: &str, ops: &[String], on: bool) -> Result<bool, String> {
        let one = || match ops {
            [op] => Ok(op.as_str()),
            _ => Err(format!("{name} takes one operand: {ops:?}")),
        };
        match name {
            "XIC" => Ok(on && self.read(one()?)?),
            "XIO" => Ok(on && !self.read(one()?)?),
            "OTE" => self.write(one()?, on).map(|_| on),
            "OTL" | "OTU" => {
                if on {
                    self.write(one()?, name == "OTL")?;
                }
                Ok(on)
            }
            "ONS" => {
                let storage = one()?;
                let before = self.read(storage)?;
                self.write(storage, on)?;
                Ok(on && !before)
            }
            "RES" => {
                let t = self.timer(one()?)?;
                if on {
                    let pre = t.pre;
                    *t = Timer {
                        pre,
                        ..Timer::default()
                    };
                }
                Ok(on)
            }
            "MOV" => {
                let [source, dest] = ops else {
                    return Err(format!("MOV takes two operands: {ops:?}"));
                };
                let value: i64 = source.parse().map_err(|_| format!("MOV from {source}"))?;
                let timer = dest
                    .strip_suffix(".PRE")
                    .ok_or_else(|| format!("MOV to {dest}"))?;
                if on {
                    self.timer(timer)?.pre = value;
                }
                Ok(on)
            }
            "TON" => {
                let [timer, preset, accum] = ops else {
                    return Err(format!("TON takes three operands: {ops:?}"));
                };
                if preset != "?" || accum != "?" {
                    return Err(format!(
                        "TON({timer},{preset},{accum}): the tag holds PRE and ACC"
                    ));
                }
                let now = self.now;
                ton(self.timer(timer)?, on, now);
                Ok(on)
            }
            _ => Err(format!("unknown instruction {name}")),
        }
    }
}

fn ton(t: &mut Timer, on: bool, now: i64) {
    if !on {
        let pre = t.pre;
        *t = Timer {
            pre,
            ..Timer::default()
        };
    } else if !t.en {
        t.en = true;
        t.tt = !t.dn;
        t.stamp = now;
    } else if !t.dn {
        t.acc += now - t.stamp;
        t.stamp = now;
        if t.acc >= t.pre {
            t.acc = t.pre;
            t.dn = true;
            t.tt = false;
        }
    }
}

/// The Rockwell tag import beside the file (`NAME.rockwell.csv`): name,
/// description and type of each TAG row.
pub fn csv_tags(text: &str) -> Result<Vec<Tag>, String> {
    let mut reader = csv::ReaderBuilder::new()
        .has_headers(false)
        .flexible(true)
        .from_reader(text.as_bytes());
    let mut tags = Vec::new();
    for record in reader.records() {
        let record = record.map_err(|e| e.to_string())?;
        if record.get(0) == Some("TAG") {
            tags.push(Tag {
                name: record.get(2).unwrap_or("").to_string(),
                description: record.get(3).unwrap_or("").to_string(),
                data_type: record.get(4).unwrap_or("").to_string(),
            });
        }
    }
    Ok(tags)
}

/// The interpreter's controller with every tag of `file` at 0.
fn controller(file: &L5x) -> Result<Controller, String> {
    let mut plc = Controller {
        bits: BTreeMap::new(),
        timers: BTreeMap::new(),
        first_scan: true,
        now: 0,
    };
    for tag in file.controller_tags.iter().chain(&file.program_tags) {
        let twice = match tag.data_type.as_str() {
            "BOOL" => plc.bits.insert(tag.name.clone(), false).is_some(),
            "TIMER" => plc
                .timers
                .insert(tag.name.clone(), Timer::default())
                .is_some(),
            other => return Err(format!("{}: type {other}", tag.name)),
        };
        if twice {
            return Err(format!("tag {} twice", tag.name));
        }
    }
    Ok(plc)
}

/// Runs the L5X on the recorded inputs: its controller tags must be those
/// of the CSV, which binds them to the allocation's addresses by the
/// address each description begins with; per scan the outputs and the
/// step whose flag (`step_k`) is on.
pub fn run_stepped(
    xml: &str,
    csv: &str,
    trace: &IoTrace,
    allocation: &Allocation,
) -> Result<Stepped, String> {
    let file = read(xml)?;
    let tags = csv_tags(csv)?;
    let key = |t: &Tag| (t.name.clone(), t.data_type.clone(), t.description.clone());
    let (in_file, in_csv): (Vec<_>, Vec<_>) = (
        file.controller_tags.iter().map(key).collect(),
        tags.iter().map(key).collect(),
    );
    if in_file != in_csv {
        return Err(format!(
            "the L5X's controller tags are not those of the Rockwell CSV: {in_file:?} / {in_csv:?}"
        ));
    }
    let tag_of = |signal| {
        let address = allocation
            .address_of(signal)
            .ok_or_else(|| format!("{signal:?} has no address"))?
            .display(allocation.mnemonic);
        tags.iter()
            .find(|t| t.description.starts_with(&format!("{address} ")))
            .map(|t| t.name.clone())
            .ok_or_else(|| format!("no tag at {address}"))
    };
    let signals = &trace.signals;
    let inputs: Vec<String> = signals
        .inputs
        .iter()
        .map(|s| tag_of(*s))
        .collect::<Result<_, _>>()?;
    let outputs: Vec<String> = signals
        .outputs
        .iter()
        .map(|s| tag_of(*s))
        .collect::<Result<_, _>>()?;
    let rungs: Vec<Vec<Element>> = file
        .rungs
        .iter()
        .map(|(_, text)| parse_rung(text))
        .collect::<Result<_, _>>()?;
    let mut plc = controller(&file)?;
    let flags: Vec<(usize, String)> = file
        .program_tags
        .iter()
        .filter_map(|t| Some((t.name.strip_prefix("step_")?.parse().ok()?, t.name.clone())))
        .collect();
    let mut run = Stepped {
        outputs: Vec::new(),
        steps: Vec::new(),
    };
    for (n, scan) in trace.scans.iter().enumerate() {
        plc.now = n as i64 * trace.scan_ms as i64;
        for (tag, value) in inputs.iter().zip(&scan.inputs) {
            plc.write(tag, *value)?;
        }
        for rung in &rungs {
            plc.run(rung, true)?;
        }
        plc.first_scan = false;
        run.outputs
            .push(outputs.iter().map(|t| plc.bits[t]).collect());
        let on: Vec<usize> = flags
            .iter()
            .filter(|(_, f)| plc.bits[f])
            .map(|(k, _)| *k)
            .collect();
        match on[..] {
            [step] => run.steps.push(step),
            _ => {
                return Err(format!(
                    "scan {n}: step flags on: {on:?} (exactly one must be)"
                ));
            }
        }
    }
    Ok(run)
}

/// The rung parser and the interpreter refuse what they do not know.
pub fn unknown_constructs_are_refused() {
    assert!(parse_rung("XIC(a)OTE(b)").is_err());
    assert!(parse_rung("XIC(a)[OTE(b),OTE(c);").is_err());
    assert!(parse_rung("XIC(a b)OTE(c);").is_err());
    assert!(parse_rung("XIC(a)[OTL(b),,OTU(c)];").is_ok());
    let mut plc = Controller {
        bits: [("a".to_string(), true), ("b".to_string(), false)].into(),
        timers: BTreeMap::new(),
        first_scan: false,
        now: 0,
    };
    assert!(
        plc.run(&parse_rung("XIC(a)JSR(b);").unwrap(), true)
            .is_err()
    );
    assert!(
        plc.run(&parse_rung("XIC(a)OTE(c);").unwrap(), true)
            .is_err()
    );
    // A branch is true when a leg is; each leg starts from the same condition.
    plc.run(&parse_rung("[XIO(a),XIC(a)]OTE(b);").unwrap(), true)
        .unwrap();
    assert!(plc.bits["b"]);
    let mut t = Timer {
        pre: 30,
        ..Timer::default()
    };
    for (now, dn) in [(0, false), (10, false), (20, false), (30, true)] {
        ton(&mut t, true, now);
        assert_eq!(t.dn, dn, "at {now} ms");
    }
    ton(&mut t, false, 40);
    assert!(!t.dn && t.acc == 0);
}
