//! The laid-out chart drawn as SVG.

use super::*;

/// Draws a laid-out chart.
pub fn svg_of(chart: &Chart) -> String {
    let (w, h) = (chart.width, chart.height);
    let mut svg = format!(
        r##"<svg xmlns="http://www.w3.org/2000/svg" class="grafcet" width="{w:.0}" height="{h:.0}" viewBox="0 0 {w:.0} {h:.0}" font-family="Helvetica, Arial, sans-serif" font-size="12">
<defs><marker id="gr-arrow" viewBox="0 0 10 10" refX="9" refY="5" markerWidth="7" markerHeight="7" orient="auto"><path d="M0,0 L10,5 L0,10 z" fill="#222"/></marker></defs>
<rect width="100%" height="100%" fill="white"/>
"##
    );
    for shape in &chart.shapes {
        draw(&mut svg, shape);
    }
    svg.push_str("</svg>\n");
    svg
}

fn draw(svg: &mut String, shape: &Shape) {
    let esc = crate::emit::diagram::escape;
    match shape {
        Shape::Step { x, y, id, double } => {
            let left = x - BOX / 2.0;
            let _ = write!(
                svg,
                r##"<g class="step" data-step="{}"><rect x="{left:.1}" y="{y:.1}" width="{BOX}" height="{BOX}" fill="white" stroke="#222" stroke-width="1.5"/>"##,
                esc(id)
            );
            if *double {
                let _ = write!(
                    svg,
                    r##"<rect x="{:.1}" y="{:.1}" width="{}" height="{}" fill="none" stroke="#222" stroke-width="1.2"/>"##,
                    left + 4.0,
                    y + 4.0,
                    BOX - 8.0,
                    BOX - 8.0
                );
            }
            let _ = writeln!(
                svg,
                r#"<text x="{x:.1}" y="{:.1}" text-anchor="middle" font-weight="bold">{}</text></g>"#,
                y + BOX / 2.0 + 4.0,
                esc(id)
            );
        }
        Shape::Panel {
            x,
            y,
            w,
            h,
            class,
            lines,
            tip,
        } => {
            let fill = if *class == "note" { "#fff8dc" } else { "white" };
            let _ = write!(svg, r#"<g class="{class}">"#);
            if let Some(tip) = tip {
                let _ = write!(svg, "<title>{}</title>", esc(tip));
            }
            let _ = write!(
                svg,
                r##"<rect x="{x:.1}" y="{y:.1}" width="{w:.1}" height="{h:.1}" fill="{fill}" stroke="#444"/>"##
            );
            for (k, line) in lines.iter().enumerate() {
                let _ = write!(
                    svg,
                    r#"<text x="{:.1}" y="{:.1}">{}</text>"#,
                    x + 6.0,
                    y + 16.0 + k as f64 * LINE,
                    esc(line)
                );
            }
            svg.push_str("</g>\n");
        }
        Shape::Transition { x, y, id, lines } => draw_transition(svg, *x, *y, id, lines),
        Shape::Path {
            points,
            double,
            arrow,
        } => draw_path(svg, points, *double, *arrow),
        Shape::Label { x, y, text, size } => {
            let weight = if *size > FONT {
                r#" font-weight="bold""#
            } else {
                ""
            };
            let _ = writeln!(
                svg,
                r#"<text class="label" x="{x:.1}" y="{y:.1}" font-size="{size}"{weight}>{}</text>"#,
                esc(text)
            );
        }
    }
}

/// A transition: its bar and its condition, one term line after another
/// (a negated term overlined).
fn draw_transition(svg: &mut String, x: f64, y: f64, id: &str, lines: &[Vec<Term>]) {
    let esc = crate::emit::diagram::escape;
    let _ = write!(
        svg,
        r##"<g class="transition" data-transition="{id}"><line x1="{:.1}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#222" stroke-width="3"/>"##,
        x - 12.0,
        x + 12.0
    );
    for (k, line) in lines.iter().enumerate() {
        let _ = write!(
            svg,
            r#"<text x="{:.1}" y="{:.1}">"#,
            x + 22.0,
            y + 4.0 + k as f64 * LINE
        );
        for (n, term) in line.iter().enumerate() {
            if n > 0 {
                svg.push_str(" · ");
            }
            if term.negated {
                let _ = write!(
                    svg,
                    r#"<tspan text-decoration="overline">{}</tspan>"#,
                    esc(&term.text)
                );
            } else {
                svg.push_str(&esc(&term.text));
            }
        }
        svg.push_str("</text>");
    }
    svg.push_str("</g>\n");
}

/// A connection: a double line for a simultaneous branch, else a polyline
/// (with an arrow where it goes up).
fn draw_path(svg: &mut String, points: &[(f64, f64)], double: bool, arrow: bool) {
    let d: Vec<String> = points
        .iter()
        .map(|(x, y)| format!("{},{}", Tenths(*x), Tenths(*y)))
        .collect();
    let d = d.join(" ");
    if double {
        let (a, b) = (points[0], points[points.len() - 1]);
        let _ = writeln!(
            svg,
            r##"<g class="and"><line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#222"/><line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}" stroke="#222"/></g>"##,
            a.0,
            a.1 - 2.0,
            b.0,
            b.1 - 2.0,
            a.0,
            a.1 + 2.0,
            b.0,
            b.1 + 2.0
        );
    } else {
        let marker = if arrow {
            r#" marker-end="url(#gr-arrow)""#
        } else {
            ""
        };
        let _ = writeln!(
            svg,
            r##"<polyline points="{d}" fill="none" stroke="#222"{marker}/>"##
        );
    }
}
