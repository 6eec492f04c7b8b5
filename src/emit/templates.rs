//! The minijinja environment: default templates embedded in the binary, strict
//! about undefined variables, with blocks trimmed so templates read naturally.

use minijinja::syntax::SyntaxConfig;
use minijinja::{Environment, UndefinedBehavior, Value};

/// The default templates, by file name.
pub const DEFAULTS: &[(&str, &str)] = &[
    (
        "program.st.j2",
        include_str!("../../templates/program.st.j2"),
    ),
    (
        "program.fst.txt.j2",
        include_str!("../../templates/program.fst.txt.j2"),
    ),
];

/// A template failed to render.
#[derive(Debug, thiserror::Error)]
#[error("template {name}: {detail}")]
pub struct TemplateError {
    pub name: String,
    pub detail: String,
}

/// Renders one of the default templates with `context`.
pub fn render(name: &str, context: Value) -> Result<String, TemplateError> {
    let source = DEFAULTS
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, s)| *s)
        .ok_or_else(|| TemplateError {
            name: name.to_string(),
            detail: "no such template".to_string(),
        })?;
    let mut env = Environment::new();
    env.set_undefined_behavior(UndefinedBehavior::Strict);
    let syntax = SyntaxConfig::builder()
        .trim_blocks(true)
        .lstrip_blocks(true)
        .keep_trailing_newline(true)
        .build()
        .map_err(|e| TemplateError {
            name: name.to_string(),
            detail: e.to_string(),
        })?;
    env.set_syntax(syntax);
    env.add_filter("pad", pad);
    let to_error = |e: minijinja::Error| TemplateError {
        name: name.to_string(),
        detail: match e.line() {
            Some(line) => format!("line {line}: {e}"),
            None => e.to_string(),
        },
    };
    env.add_template(name, source).map_err(to_error)?;
    let template = env.get_template(name).map_err(to_error)?;
    let text = template.render(context).map_err(to_error)?;
    // Trailing spaces come from padded empty columns; no output language wants them.
    let mut out: String = text
        .lines()
        .map(str::trim_end)
        .collect::<Vec<_>>()
        .join("\n");
    out.push('\n');
    Ok(out)
}

/// `{{ text | pad(8) }}`: left-justify to a column width.
fn pad(value: String, width: usize) -> String {
    format!("{value:<width$}")
}
