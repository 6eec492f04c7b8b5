//! The condition under which Beremiz and the OpenPLC Editor v3 open a
//! graphical PLCopen body as it was drawn: every element has integer
//! `width` and `height` and an integer position, and every wire
//! (`connection` with its `position` points) starts at the input it ends
//! in and ends at an output of the element it names. Without the points the
//! editor routes the wire to the wrong leg, without positions it draws only
//! the left rail; its maintainer calls such files corrupted and declined to
//! lay them out (OpenPLC Editor issue #37,
//! https://github.com/thiagoralves/OpenPLC_Editor/issues/37).

use std::collections::BTreeMap;

use quick_xml::Reader;
use quick_xml::events::{BytesStart, Event};

/// One XML element: its name, attributes and children.
#[derive(Debug, Default)]
pub struct Node {
    pub name: String,
    pub attrs: BTreeMap<String, String>,
    pub children: Vec<Node>,
}

fn node(start: &BytesStart) -> Node {
    Node {
        name: start.local_name().as_ref().to_string(),
        attrs: start
            .attributes()
            .flatten()
            .map(|a| {
                (
                    a.key.local_name().as_ref().to_string(),
                    a.value.into_owned(),
                )
            })
            .collect(),
        children: Vec::new(),
    }
}

/// The document's root element.
pub fn parse(text: &str) -> Node {
    let mut reader = Reader::from_str(text);
    let mut stack = vec![Node::default()];
    loop {
        match reader.read_event().expect("well-formed XML") {
            Event::Start(s) => stack.push(node(&s)),
            Event::Empty(s) => stack.last_mut().unwrap().children.push(node(&s)),
            Event::End(_) => {
                let done = stack.pop().unwrap();
                stack.last_mut().unwrap().children.push(done);
            }
            Event::Eof => break,
            _ => {}
        }
    }
    stack.pop().unwrap().children.pop().expect("a root element")
}

impl Node {
    pub fn child(&self, name: &str) -> Option<&Node> {
        self.children.iter().find(|c| c.name == name)
    }

    fn all<'n>(&'n self, name: &'n str) -> impl Iterator<Item = &'n Node> + 'n {
        self.children.iter().filter(move |c| c.name == name)
    }

    /// Every element named `name` below this one.
    pub fn descendants<'n>(&'n self, name: &str, out: &mut Vec<&'n Node>) {
        for c in &self.children {
            if c.name == name {
                out.push(c);
            }
            c.descendants(name, out);
        }
    }
}

fn int(node: &Node, attr: &str, what: &str) -> Result<i64, String> {
    let text = node
        .attrs
        .get(attr)
        .ok_or_else(|| format!("{what}: no {attr}"))?;
    text.parse()
        .map_err(|_| format!("{what}: {attr}=\"{text}\" is not an integer"))
}

fn point(node: &Node, what: &str) -> Result<(i64, i64), String> {
    Ok((int(node, "x", what)?, int(node, "y", what)?))
}

/// The connection points an element offers to wires that leave it.
const OUTPUTS: [&str; 2] = ["connectionPointOut", "connectionPointOutAction"];

/// An element's connection points named `names`, and a block's (inside
/// its `inputVariables` or `outputVariables`, each with its formal
/// parameter).
fn pins<'n>(e: &'n Node, names: &[&str], block: &str) -> Vec<(Option<String>, &'n Node)> {
    let mut found: Vec<(Option<String>, &Node)> = names
        .iter()
        .flat_map(|name| e.children.iter().filter(move |c| c.name == *name))
        .map(|c| (None, c))
        .collect();
    for variables in e.children.iter().filter(|c| c.name == block) {
        for v in variables.children.iter().filter(|c| c.name == "variable") {
            for c in v
                .children
                .iter()
                .filter(|c| names.contains(&c.name.as_str()))
            {
                found.push((v.attrs.get("formalParameter").cloned(), c));
            }
        }
    }
    found
}

/// An output's formal parameter (a block's) and where it is.
type Output = (Option<String>, (i64, i64));

/// Checks one graphical body (`<SFC>`, `<LD>`, `<FBD>`); returns how many
/// wires were checked, or the first fault, named by element.
pub fn check_body(body: &Node) -> Result<usize, String> {
    let mut outputs: BTreeMap<String, Vec<Output>> = BTreeMap::new();
    let mut placed = BTreeMap::new();
    for e in &body.children {
        let Some(id) = e.attrs.get("localId") else {
            continue;
        };
        let what = format!("{} {id}", e.name);
        int(e, "width", &what)?;
        int(e, "height", &what)?;
        let at = point(
            e.child("position").ok_or(format!("{what}: no position"))?,
            &what,
        )?;
        let mut outs = Vec::new();
        for (formal, out) in pins(e, &OUTPUTS, "outputVariables") {
            let rel = point(
                out.child("relPosition")
                    .ok_or(format!("{what}: no relPosition"))?,
                &what,
            )?;
            outs.push((formal, (at.0 + rel.0, at.1 + rel.1)));
        }
        outputs.insert(id.clone(), outs);
        placed.insert(id.clone(), at);
    }
    if placed.is_empty() {
        return Err("the body has no element".to_string());
    }
    let mut wires = 0;
    for e in &body.children {
        let Some(id) = e.attrs.get("localId") else {
            continue;
        };
        let what = format!("{} {id}", e.name);
        let at = placed[id];
        for (_, input) in pins(e, &["connectionPointIn"], "inputVariables") {
            let rel = point(
                input
                    .child("relPosition")
                    .ok_or(format!("{what}: no relPosition"))?,
                &what,
            )?;
            let pin = (at.0 + rel.0, at.1 + rel.1);
            for wire in input.all("connection") {
                let from = &wire.attrs["refLocalId"];
                let points: Vec<(i64, i64)> = wire
                    .all("position")
                    .map(|p| point(p, &what))
                    .collect::<Result<_, _>>()?;
                let (Some(first), Some(last)) = (points.first(), points.last()) else {
                    return Err(format!("{what}: a wire from {from} without points"));
                };
                if *first != pin {
                    return Err(format!(
                        "{what}: the wire from {from} starts at {first:?}, not at the input {pin:?}"
                    ));
                }
                let outs: Vec<(i64, i64)> = outputs
                    .get(from)
                    .ok_or(format!(
                        "{what}: a wire from {from}, which is not in the body"
                    ))?
                    .iter()
                    .filter(|(formal, _)| {
                        // A wire from a block names the output it leaves.
                        wire.attrs
                            .get("formalParameter")
                            .is_none_or(|f| formal.as_ref() == Some(f))
                    })
                    .map(|(_, p)| *p)
                    .collect();
                if !outs.contains(last) {
                    return Err(format!(
                        "{what}: the wire from {from} ends at {last:?}, not at one of its outputs {outs:?}"
                    ));
                }
                wires += 1;
            }
        }
    }
    Ok(wires)
}

/// Checks every graphical body of a PLCopen file, its actions' too.
pub fn check_file(text: &str) -> Result<usize, String> {
    let root = parse(text);
    let mut bodies = Vec::new();
    for kind in ["SFC", "LD", "FBD"] {
        root.descendants(kind, &mut bodies);
    }
    if bodies.is_empty() {
        return Err("no graphical body".to_string());
    }
    bodies.into_iter().map(check_body).sum()
}
