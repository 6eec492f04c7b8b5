//! The one way into emit: an output kind and the input give its files.

use minijinja::Value;

use super::st::IecFile;
use super::templates::TemplateError;
use super::{EmitInput, OutputFile, OutputKind};

/// Why an output could not be rendered.
#[derive(Debug)]
pub enum EmitError {
    /// A template failed: the user's (fix it) or a default one (a bug).
    Template(TemplateError),
    /// A bug: a writer failed on bytes in memory, or an input was missing.
    Internal(String),
}

fn internal(what: &str, e: impl std::fmt::Display) -> EmitError {
    EmitError::Internal(format!("{what}: {e}"))
}

/// Renders the files of one conversion. The IEC files share one model (with
/// the ST body) and the STEP 7 files another: each is built on first use and
/// reused, as are the PLCopen bytes a Beremiz project holds.
pub struct Renderer<'a> {
    input: EmitInput<'a>,
    iec: Option<Value>,
    awl: Option<Value>,
    plcopen: Option<Vec<u8>>,
}

/// Every file of `kinds`, in the order of [`OutputKind::ALL`].
pub fn render(
    kinds: impl IntoIterator<Item = OutputKind>,
    input: EmitInput<'_>,
) -> Result<Vec<OutputFile>, EmitError> {
    Ok(render_each(kinds, input)?
        .into_iter()
        .flat_map(|(_, files)| files)
        .collect())
}

/// Like [`render`], each kind with its files, so that kinds rendered apart
/// (some before the fault analysis has ended) can be put back in order.
pub fn render_each(
    kinds: impl IntoIterator<Item = OutputKind>,
    input: EmitInput<'_>,
) -> Result<Vec<(OutputKind, Vec<OutputFile>)>, EmitError> {
    use rayon::prelude::*;
    // Every text this table gives has a budget that grows with the table.
    let budgeted = input.templates.with_budget(super::templates::output_budget(
        input.table.steps.len(),
        input.table.branches,
    ));
    let input = EmitInput {
        templates: &budgeted,
        ..input
    };
    let mut kinds: Vec<OutputKind> = kinds.into_iter().collect();
    kinds.sort_unstable();
    kinds.dedup();
    // Kinds that share a model render one after the other with one
    // renderer; the groups render side by side.
    let mut groups: Vec<Vec<OutputKind>> = Vec::new();
    for kind in kinds {
        let family = shared_model(kind);
        match groups
            .iter_mut()
            .find(|g| family.is_some() && shared_model(g[0]) == family)
        {
            Some(group) => group.push(kind),
            None => groups.push(vec![kind]),
        }
    }
    let rendered: Vec<Result<Vec<_>, (OutputKind, EmitError)>> = groups
        .into_par_iter()
        .map(|group| {
            let mut renderer = Renderer::new(input);
            group
                .into_iter()
                .map(|kind| Ok((kind, renderer.render(kind).map_err(|e| (kind, e))?)))
                .collect()
        })
        .collect();
    // The failure of the first kind that failed, as one at a time would
    // have met it (a group stops at its first).
    let mut files = Vec::new();
    let mut failed: Option<(OutputKind, EmitError)> = None;
    for group in rendered {
        match group {
            Ok(group) => files.extend(group),
            Err(e) => {
                if failed.as_ref().is_none_or(|(kind, _)| e.0 < *kind) {
                    failed = Some(e);
                }
            }
        }
    }
    if let Some((_, e)) = failed {
        return Err(e);
    }
    files.sort_by_key(|(kind, _)| *kind);
    Ok(files)
}

/// Which model a kind's renderer builds and keeps for the kinds after it
/// (the IEC model, the STEP 7 model), if any.
fn shared_model(kind: OutputKind) -> Option<u8> {
    match kind {
        OutputKind::StructuredText
        | OutputKind::PlcOpen
        | OutputKind::Codesys
        | OutputKind::Gvl
        | OutputKind::CodesysV2
        | OutputKind::Beremiz => Some(0),
        OutputKind::Awl | OutputKind::SymbolTable => Some(1),
        _ => None,
    }
}

impl<'a> Renderer<'a> {
    pub fn new(input: EmitInput<'a>) -> Self {
        Renderer {
            input,
            iec: None,
            awl: None,
            plcopen: None,
        }
    }

    /// The files of one kind: one file, or a Beremiz project's two.
    pub fn render(&mut self, kind: OutputKind) -> Result<Vec<OutputFile>, EmitError> {
        let input = self.input;
        let name = input.name;
        let file = |bytes| OutputFile {
            name: format!("{name}{}", kind.suffix()),
            bytes,
        };
        let bytes = match kind {
            OutputKind::Workbook => {
                super::workbook::render(&input).map_err(|e| internal("workbook", e))?
            }
            OutputKind::Fst => text(kind, super::fst::render(&input))?,
            OutputKind::Allocation => {
                super::io_csv::render(&input).map_err(|e| internal("allocation list", e))?
            }
            OutputKind::Diagram => {
                let simulation = input
                    .simulation
                    .ok_or_else(|| internal("diagram", "not simulated"))?;
                input
                    .diagram_svg(simulation, input.diagram)
                    .into_owned()
                    .into_bytes()
            }
            OutputKind::Faults => {
                let faults = input
                    .faults
                    .ok_or_else(|| internal("fault table", "not analysed"))?;
                super::faults_csv::render(faults, &|s| self.input.symbols.designation(s), &|t| {
                    self.input.symbols.explain(t)
                })
                .map_err(|e| internal("fault table", e))?
            }
            OutputKind::TiaTags => {
                super::tables::render_tia_tags(&input).map_err(|e| internal("TIA tag table", e))?
            }
            OutputKind::Awl => {
                let model = self.awl_model();
                text(kind, super::awl::render_awl(&input, &model))?
            }
            OutputKind::SymbolTable => {
                let model = self.awl_model();
                text(kind, super::awl::render_sdf(&input, &model))?
            }
            OutputKind::FstAllocation => text(kind, super::tables::render_fst_alloc(&input))?,
            OutputKind::Rockwell => text(kind, super::tables::render_rockwell(&input))?,
            OutputKind::Scl => text(kind, super::scl::render(&input))?,
            OutputKind::L5x => text(kind, super::l5x::render(&input))?,
            OutputKind::Beremiz | OutputKind::BeremizSfc | OutputKind::BeremizLd => {
                return self.beremiz(kind);
            }
            OutputKind::Grafcet => input.grafcet_svg().into_owned().into_bytes(),
            OutputKind::Report => super::report::render(&input)
                .map_err(|e| internal("report", e))?
                .into_bytes(),
            OutputKind::StructuredText => self.iec(kind, IecFile::StructuredText)?,
            OutputKind::PlcOpen => {
                let bytes = self.iec(kind, IecFile::PlcOpen)?;
                self.plcopen = Some(bytes.clone());
                bytes
            }
            OutputKind::Codesys => self.iec(kind, IecFile::Codesys)?,
            OutputKind::Gvl => self.iec(kind, IecFile::GlobalVariables)?,
            OutputKind::CodesysV2 => self.iec(kind, IecFile::CodesysV2)?,
            OutputKind::Sfc => text(kind, super::sfc::render(&input))?,
            OutputKind::Ladder => text(kind, super::ladder::render(&input))?,
            OutputKind::CodesysSfc => {
                text(kind, super::codesys_body::render(&input, OutputKind::Sfc))?
            }
            OutputKind::CodesysLd => text(
                kind,
                super::codesys_body::render(&input, OutputKind::Ladder),
            )?,
        };
        Ok(vec![file(bytes)])
    }

    fn awl_model(&mut self) -> Value {
        let input = self.input;
        self.awl
            .get_or_insert_with(|| super::awl::model(&input))
            .clone()
    }

    fn iec(&mut self, kind: OutputKind, file: IecFile) -> Result<Vec<u8>, EmitError> {
        let input = self.input;
        let model = match &self.iec {
            Some(model) => model.clone(),
            None => {
                let model = super::st::model(&input, input.scan_ms).map_err(EmitError::Template)?;
                self.iec.insert(model).clone()
            }
        };
        text(kind, super::st::render(&input, &model, file))
    }

    /// A project folder Beremiz and the OpenPLC Editor open as it is: as
    /// `plc.xml` the PLCopen XML (the same bytes as `NAME.plcopen.xml`), or
    /// for the graphical bodies their file's bytes (`NAME.sfc.xml`,
    /// `NAME.ld.xml`), and `beremiz.xml`.
    fn beremiz(&mut self, kind: OutputKind) -> Result<Vec<OutputFile>, EmitError> {
        let folder = format!("{}{}", self.input.name, kind.suffix());
        let plc = match (kind.body(), self.plcopen.clone()) {
            (Some(body), _) => {
                let mut files = self.render(body)?;
                files.pop().map(|f| f.bytes).unwrap_or_default()
            }
            (None, Some(bytes)) => bytes,
            (None, None) => self.iec(OutputKind::PlcOpen, IecFile::PlcOpen)?,
        };
        let project = self.iec(OutputKind::Beremiz, IecFile::BeremizProject)?;
        Ok(vec![
            OutputFile {
                name: format!("{folder}/plc.xml"),
                bytes: plc,
            },
            OutputFile {
                name: format!("{folder}/beremiz.xml"),
                bytes: project,
            },
        ])
    }
}

/// A rendered text as bytes, with CRLF line ends where the kind wants them.
fn text(kind: OutputKind, result: Result<String, TemplateError>) -> Result<Vec<u8>, EmitError> {
    let text = result.map_err(EmitError::Template)?;
    let text = match kind.windows_lines() {
        true => super::crlf(&text),
        false => text,
    };
    Ok(match kind.windows_ansi() {
        true => super::windows_1252(&text),
        false => text.into_bytes(),
    })
}
