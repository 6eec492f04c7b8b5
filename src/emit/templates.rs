//! The minijinja templates every text output is laid out by: the defaults in
//! `templates/`, embedded in the binary, and any a user overrides by file name
//! with `--templates DIR`. Strict about undefined variables, blocks trimmed.
//! Templates only lay out: names, addresses and operators come from Rust.

use std::borrow::Cow;
use std::collections::BTreeMap;
use std::fmt;
use std::path::PathBuf;
use std::sync::Arc;

use minijinja::syntax::SyntaxConfig;
use minijinja::{AutoEscape, Environment, UndefinedBehavior, Value};

/// The default templates, by file name.
pub const DEFAULTS: &[(&str, &str)] = &[
    (
        "program.st.j2",
        include_str!("../../templates/program.st.j2"),
    ),
    (
        "program_body.st.j2",
        include_str!("../../templates/program_body.st.j2"),
    ),
    (
        "program.fst.txt.j2",
        include_str!("../../templates/program.fst.txt.j2"),
    ),
    (
        "plcopen.xml.j2",
        include_str!("../../templates/plcopen.xml.j2"),
    ),
    ("sfc.xml.j2", include_str!("../../templates/sfc.xml.j2")),
    ("ld.xml.j2", include_str!("../../templates/ld.xml.j2")),
    (
        "codesys.xml.j2",
        include_str!("../../templates/codesys.xml.j2"),
    ),
    (
        "codesys_body.xml.j2",
        include_str!("../../templates/codesys_body.xml.j2"),
    ),
    ("gvl.txt.j2", include_str!("../../templates/gvl.txt.j2")),
    (
        "program.awl.j2",
        include_str!("../../templates/program.awl.j2"),
    ),
    (
        "symbols.sdf.j2",
        include_str!("../../templates/symbols.sdf.j2"),
    ),
    (
        "fst-alloc.csv.j2",
        include_str!("../../templates/fst-alloc.csv.j2"),
    ),
    (
        "rockwell.csv.j2",
        include_str!("../../templates/rockwell.csv.j2"),
    ),
    (
        "program.scl.j2",
        include_str!("../../templates/program.scl.j2"),
    ),
    (
        "program.l5x.xml.j2",
        include_str!("../../templates/program.l5x.xml.j2"),
    ),
    (
        "program.exp.j2",
        include_str!("../../templates/program.exp.j2"),
    ),
    (
        "beremiz.xml.j2",
        include_str!("../../templates/beremiz.xml.j2"),
    ),
    (
        "equations.st.j2",
        include_str!("../../templates/equations.st.j2"),
    ),
    (
        "equations.il.j2",
        include_str!("../../templates/equations.il.j2"),
    ),
    (
        "equations_vars.j2",
        include_str!("../../templates/equations_vars.j2"),
    ),
    (
        "equations_config.j2",
        include_str!("../../templates/equations_config.j2"),
    ),
];

/// A template failed to load or render.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TemplateError {
    /// The template file (the user's path for an override).
    pub file: String,
    /// True when the template is the user's, so the user must fix it.
    pub user: bool,
    pub line: Option<usize>,
    pub detail: String,
}

impl fmt::Display for TemplateError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(line) => write!(f, "{}:{line}: {}", self.file, self.detail),
            None => write!(f, "{}: {}", self.file, self.detail),
        }
    }
}

impl std::error::Error for TemplateError {}

/// The set of templates of one run: defaults plus the user's overrides.
#[derive(Clone)]
pub struct Templates {
    /// Shared by every copy of the settings (a batch's conversions), so
    /// that a default template is compiled once per run, when first used.
    env: Arc<Environment<'static>>,
    /// Overridden template name → the user's file.
    overrides: BTreeMap<String, PathBuf>,
    /// Most bytes one render may write (see [`Templates::with_budget`]).
    budget: usize,
}

impl fmt::Debug for Templates {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Templates")
            .field("overrides", &self.overrides)
            .finish()
    }
}

impl PartialEq for Templates {
    fn eq(&self, other: &Self) -> bool {
        self.overrides == other.overrides
    }
}

impl Default for Templates {
    fn default() -> Self {
        Templates::with_overrides(BTreeMap::new()).unwrap_or_else(|_| Templates {
            env: Arc::new(Environment::new()),
            overrides: BTreeMap::new(),
            budget: OUTPUT_BUDGET,
        })
    }
}

fn environment() -> Result<Environment<'static>, minijinja::Error> {
    let mut env = Environment::new();
    env.set_undefined_behavior(UndefinedBehavior::Strict);
    env.set_syntax(
        SyntaxConfig::builder()
            .trim_blocks(true)
            .lstrip_blocks(true)
            .keep_trailing_newline(true)
            .build()?,
    );
    // XML templates escape every value; the others write text as it is.
    env.set_auto_escape_callback(|name| {
        if name.contains(".xml") {
            AutoEscape::Html
        } else {
            AutoEscape::None
        }
    });
    env.add_filter("pad", pad);
    env.add_filter("csv", csv_field);
    // A user's template must end: a loop that runs away runs out of fuel
    // (the defaults use a few million steps on the largest table allowed).
    env.set_fuel(Some(TEMPLATE_FUEL));
    Ok(env)
}

impl Templates {
    /// The defaults with `overrides` (template name → (path, source)) in their place.
    pub(crate) fn with_overrides(
        overrides: BTreeMap<String, (PathBuf, String)>,
    ) -> Result<Self, TemplateError> {
        let mut env = environment().map_err(|e| TemplateError {
            file: "templates".to_string(),
            user: false,
            line: None,
            detail: e.to_string(),
        })?;
        // The defaults compile when first rendered (a conversion renders
        // them side by side; a `--formats st` run needs two); the user's
        // are compiled here, so that a syntax error stops the run before
        // any table is read. An added template comes before the loader.
        env.set_loader(|name| {
            Ok(DEFAULTS
                .iter()
                .find(|(default, _)| *default == name)
                .map(|(_, source)| source.to_string()))
        });
        let mut paths = BTreeMap::new();
        for (name, _) in DEFAULTS {
            let Some((path, text)) = overrides.get(*name) else {
                continue;
            };
            let file = path.display().to_string();
            // Compiling folds constants (`'x' * 100000000` is built here):
            // bounded as a render is.
            let _scope = crate::alloc_guard::Scope::enter(&file, OUTPUT_BUDGET.saturating_mul(4));
            env.add_template_owned(name.to_string(), text.clone())
                .map_err(|e| TemplateError {
                    file: file.clone(),
                    user: true,
                    line: e.line(),
                    detail: e.detail().unwrap_or("syntax error").to_string(),
                })?;
            paths.insert(name.to_string(), PathBuf::from(file));
        }
        Ok(Templates {
            env: Arc::new(env),
            overrides: paths,
            budget: OUTPUT_BUDGET,
        })
    }

    /// The defaults with `sources` (template name, text) in their place, as
    /// if `load_dir` had read them from files of those names: for programs
    /// that hold their templates in memory. An unknown name is an error.
    pub fn from_sources<'a>(
        sources: impl IntoIterator<Item = (&'a str, &'a str)>,
    ) -> Result<Self, TemplateError> {
        let mut overrides = BTreeMap::new();
        for (name, text) in sources {
            if !DEFAULTS.iter().any(|(n, _)| *n == name) {
                return Err(TemplateError {
                    file: name.to_string(),
                    user: true,
                    line: None,
                    detail: "no template has this name".to_string(),
                });
            }
            overrides.insert(name.to_string(), (PathBuf::from(name), text.to_string()));
        }
        Templates::with_overrides(overrides)
    }

    /// The same templates, each render allowed `bytes` of output.
    pub fn with_budget(&self, bytes: usize) -> Templates {
        Templates {
            budget: bytes,
            ..self.clone()
        }
    }

    /// Most bytes one render may write.
    pub fn budget(&self) -> usize {
        self.budget
    }

    /// Renders template `name` with `context`. The output is written into
    /// a buffer that refuses bytes past the budget, so a template that
    /// writes without end stops there, naming itself, before the text is
    /// large enough to exhaust memory.
    pub fn render(&self, name: &str, context: Value) -> Result<String, TemplateError> {
        let (file, user) = match self.overrides.get(name) {
            Some(path) => (path.display().to_string(), true),
            None => (format!("templates/{name}"), false),
        };
        let template = self.env.get_template(name).map_err(|e| TemplateError {
            file: file.clone(),
            user,
            line: None,
            detail: e.to_string(),
        })?;
        let mut sink = Budgeted {
            bytes: Vec::new(),
            budget: self.budget,
            over: false,
        };
        // A user's template may not build values far past its output budget.
        let scope =
            user.then(|| crate::alloc_guard::Scope::enter(&file, self.budget.saturating_mul(4)));
        let rendered = template.render_captured_to(context, &mut sink).map(drop);
        drop(scope);
        if sink.over {
            return Err(TemplateError {
                file,
                user,
                line: None,
                detail: format!(
                    "the output passed {} bytes ({}), the most a template may write for this table; stopped, nothing written",
                    self.budget,
                    mebibytes(self.budget)
                ),
            });
        }
        rendered.map_err(|e| {
            // Name what was undefined: the source text the error points at.
            let source = template.source();
            let detail = e
                .detail()
                .map(str::to_string)
                .unwrap_or_else(|| e.kind().to_string());
            let what = e
                .range()
                .and_then(|r| source.get(r))
                .filter(|s| !detail.contains(*s))
                .map(|s| format!(" (`{s}`)"))
                .unwrap_or_default();
            TemplateError {
                file: file.clone(),
                user,
                line: e.line(),
                detail: format!("{detail}{what}"),
            }
        })?;
        let text = String::from_utf8(sink.bytes).map_err(|e| TemplateError {
            file,
            user,
            line: None,
            detail: format!("output is not UTF-8: {e}"),
        })?;
        Ok(without_trailing_spaces(&text))
    }
}

/// A render's output, refused past `budget` bytes.
struct Budgeted {
    bytes: Vec<u8>,
    budget: usize,
    over: bool,
}

impl std::io::Write for Budgeted {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.bytes.len().saturating_add(buf.len()) > self.budget {
            self.over = true;
            return Err(std::io::Error::other("output budget exceeded"));
        }
        self.bytes.extend_from_slice(buf);
        Ok(buf.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// `16 MiB`, or bytes below one MiB.
fn mebibytes(bytes: usize) -> String {
    if bytes >= 1 << 20 {
        format!("{} MiB", bytes >> 20)
    } else {
        format!("{bytes} bytes")
    }
}

/// The output budget of a render with no table behind it (synthesis, a
/// test): far above any sequence synthesis handles.
pub const OUTPUT_BUDGET: usize = 16 << 20;

/// Output budget per cell of a table (steps × branches): the built-in
/// templates write about 250 bytes per cell (a 1,000-step, 4-branch table's
/// largest file, the AWL, is 0.96 MB; 10,000 × 64 cells, 107 MB), so 16 KiB
/// leaves a user's template sixty times room.
pub const OUTPUT_BUDGET_PER_CELL: usize = 16 << 10;

/// The budget of each rendered file of a table of `steps` × `branches`:
/// [`OUTPUT_BUDGET`] plus [`OUTPUT_BUDGET_PER_CELL`] for every cell.
pub fn output_budget(steps: usize, branches: usize) -> usize {
    steps
        .saturating_mul(branches.max(1))
        .saturating_mul(OUTPUT_BUDGET_PER_CELL)
        .saturating_add(OUTPUT_BUDGET)
}

/// `text` with every line's trailing white space cut and one newline at
/// the end: trailing spaces come from padded empty columns, and no output
/// wants them.
fn without_trailing_spaces(text: &str) -> String {
    let mut out = String::with_capacity(text.len() + 1);
    for line in text.lines() {
        out.push_str(line.trim_end());
        out.push('\n');
    }
    if out.is_empty() {
        out.push('\n');
    }
    out
}

/// How many steps one template may take to render.
pub const TEMPLATE_FUEL: u64 = 200_000_000;

/// Widest column `pad` makes (Rust's formatter refuses widths past 65,535).
const MAX_PAD: usize = 1000;

/// `{{ text | pad(8) }}`: left-justify to a column width (at most 1,000),
/// counting characters. Called for three columns of every AWL line: a
/// string is read where it lies, not copied in, and one as wide as the
/// column already is handed back as it is.
fn pad(value: &Value, width: usize) -> Result<Value, minijinja::Error> {
    // Strict, as for any other use of an undefined value.
    if value.is_undefined() {
        return Err(minijinja::Error::from(minijinja::ErrorKind::UndefinedError));
    }
    let width = width.min(MAX_PAD);
    let text = value
        .as_str()
        .map_or_else(|| value.to_string().into(), Cow::Borrowed);
    let chars = text.chars().count();
    if chars >= width && value.as_str().is_some() && !value.is_safe() {
        return Ok(value.clone());
    }
    let mut padded = String::with_capacity(text.len() + width.saturating_sub(chars));
    padded.push_str(&text);
    padded.extend(std::iter::repeat_n(' ', width.saturating_sub(chars)));
    Ok(Value::from(padded))
}

/// `{{ text | csv }}`: one CSV field, quoted when it must be.
fn csv_field(value: String) -> String {
    if value.contains([',', '"', '\n', '\r', ';']) {
        format!("\"{}\"", value.replace('"', "\"\""))
    } else {
        value
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A render error quotes the template text it points at when its
    /// message does not name it.
    #[test]
    fn a_render_error_quotes_its_source() {
        let empty = || Value::from(BTreeMap::<String, String>::new());
        let undefined = Templates::from_sources([("gvl.txt.j2", "{{ netwerks.x }}")]).unwrap();
        let err = undefined.render("gvl.txt.j2", empty()).unwrap_err();
        assert!(err.detail.contains("(`netwerks.x`)"), "{}", err.detail);
    }

    /// Settings compare and print their templates by the files overriding
    /// the defaults (the environment itself has no equality).
    #[test]
    fn templates_compare_and_print_by_their_overrides() {
        let custom = Templates::from_sources([("gvl.txt.j2", "one")]).unwrap();
        assert_eq!(Templates::default(), Templates::default());
        assert_ne!(custom, Templates::default());
        assert_eq!(
            format!("{custom:?}"),
            "Templates { overrides: {\"gvl.txt.j2\": \"gvl.txt.j2\"} }"
        );
    }

    #[test]
    fn templates_from_memory_replace_the_default_and_refuse_unknown_names() {
        let templates = Templates::from_sources([("gvl.txt.j2", "one {{ 1 + 1 }}")]).unwrap();
        let empty = Value::from(BTreeMap::<String, String>::new());
        assert_eq!(templates.render("gvl.txt.j2", empty).unwrap(), "one 2\n");
        let err = Templates::from_sources([("progam.st.j2", "typo")]).unwrap_err();
        assert!(err.detail.contains("no template has this name"), "{err}");
    }

    /// A render stops once it would write past its budget, naming the
    /// template and the limit; up to the budget it is whole. The budget
    /// grows with the table.
    #[test]
    fn a_render_past_its_budget_stops() {
        let templates = Templates::from_sources([(
            "gvl.txt.j2",
            "{% for i in range(n) %}0123456789{% endfor %}",
        )])
        .unwrap()
        .with_budget(100);
        let render =
            |n: u32| templates.render("gvl.txt.j2", Value::from(BTreeMap::from([("n", n)])));
        assert_eq!(render(10).unwrap().len(), 101);
        let err = render(11).unwrap_err();
        assert!(err.user && err.file == "gvl.txt.j2", "{err}");
        assert!(err.detail.contains("passed 100 bytes"), "{err}");
        assert_eq!(Templates::default().budget(), OUTPUT_BUDGET);
        assert_eq!(output_budget(1000, 4), (16 << 20) + 4000 * (16 << 10));
        assert_eq!(output_budget(usize::MAX, 256), usize::MAX);
    }

    #[test]
    fn lines_lose_their_trailing_spaces_and_end_in_one_newline() {
        assert_eq!(without_trailing_spaces("a  \n\n b\t\r\nc "), "a\n\n b\nc\n");
        assert_eq!(without_trailing_spaces("a\n"), "a\n");
        assert_eq!(without_trailing_spaces(""), "\n");
        assert_eq!(without_trailing_spaces("   "), "\n");
    }

    #[test]
    fn csv_fields_are_quoted_when_needed() {
        assert_eq!(csv_field("x10".into()), "x10");
        assert_eq!(csv_field("a, b".into()), "\"a, b\"");
        assert_eq!(csv_field("say \"hi\"".into()), "\"say \"\"hi\"\"\"");
    }

    /// `pad` counts characters, never cuts, caps the width, pads what is not
    /// a string as it prints, escapes in XML, and refuses what is undefined.
    #[test]
    fn pad_left_justifies_to_a_column() {
        let render = |name: &str, source: &str| {
            let templates = Templates::from_sources([(name, source)]).unwrap();
            templates.render(name, Value::from(BTreeMap::from([("x", "<ü>")])))
        };
        let text = |source: &str| render("gvl.txt.j2", source).unwrap();
        assert_eq!(text("[{{ x | pad(5) }}]"), "[<ü>  ]\n");
        assert_eq!(text("[{{ x | pad(2) }}]"), "[<ü>]\n");
        assert_eq!(text("[{{ 42 | pad(4) }}]"), "[42  ]\n");
        assert_eq!(text("[{{ '' | pad(5000) }}]").len(), 1 + 1000 + 2);
        assert_eq!(
            render(
                "codesys.xml.j2",
                "[{{ x | pad(1) }}][{{ x | safe | pad(1) }}]"
            )
            .unwrap(),
            "[&lt;ü&gt;][&lt;ü&gt;]\n"
        );
        let err = render("gvl.txt.j2", "{{ y | pad(3) }}").unwrap_err();
        assert!(err.detail.contains("undefined"), "{err}");
    }
}
