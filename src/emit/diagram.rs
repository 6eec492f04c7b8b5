//! The displacement-step diagram (VDI 3260 style) every pneumatics engineer
//! draws by hand: one lane per actuator, its position 0…pmax over the step
//! boundaries 1…m+1, from the simulation of the generated program. The
//! `time` variant plots the same positions over simulated time.

use std::fmt::Write;

use crate::simulate::SimReport;
use crate::symbols::SymbolTable;

/// Which horizontal axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum DiagramKind {
    /// Position over step boundaries (displacement-step diagram).
    #[default]
    Step,
    /// Position over simulated time (displacement-time diagram).
    Time,
}

const LEFT: f64 = 110.0;
const RIGHT: f64 = 40.0;
const TOP: f64 = 100.0;
const LANE_UNIT: f64 = 28.0;
const LANE_GAP: f64 = 34.0;
const COLORS: [&str; 6] = [
    "#1f5fa8", "#c0392b", "#1e8449", "#8e44ad", "#b9770e", "#117a65",
];

/// A coordinate as `{:.1}` writes it, without the formatter's exact path,
/// which for most coordinates falls back to big-number arithmetic (a
/// diagram has thousands): the tenths as a whole number. Near a tie, where
/// the product may have rounded the other way, the formatter decides.
pub(crate) struct Tenths(pub(crate) f64);

impl std::fmt::Display for Tenths {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let scaled = self.0.abs() * 10.0;
        let fraction = scaled - scaled.trunc();
        if scaled.is_nan() || scaled >= 1e12 || (fraction - 0.5).abs() < 1e-6 {
            return write!(f, "{:.1}", self.0);
        }
        // Digits by hand: a picture writes thousands of these, and the
        // formatting machinery cost more than the rest of the picture.
        let tenths = scaled.round() as u64;
        let mut text = [0u8; 24];
        let mut at = text.len() - 2;
        text[at..].copy_from_slice(&[b'.', b'0' + (tenths % 10) as u8]);
        let mut whole = tenths / 10;
        loop {
            at -= 1;
            text[at] = b'0' + (whole % 10) as u8;
            whole /= 10;
            if whole == 0 {
                break;
            }
        }
        if self.0.is_sign_negative() {
            at -= 1;
            text[at] = b'-';
        }
        f.write_str(std::str::from_utf8(&text[at..]).map_err(|_| std::fmt::Error)?)
    }
}

pub(crate) fn escape(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            c => escaped.push(c),
        }
    }
    escaped
}

/// Lane geometry: top y and height of each actuator's lane.
fn lanes(report: &SimReport) -> Vec<(f64, f64)> {
    let mut y = TOP;
    report
        .actuators
        .iter()
        .map(|(_, pmax)| {
            let height = LANE_UNIT * (*pmax).max(1) as f64;
            let lane = (y, height);
            y += height + LANE_GAP;
            lane
        })
        .collect()
}

/// Seconds between two grid lines of a time diagram: 1, 2, 5, 10, 20, 50 …,
/// the first that keeps the grid to 60 lines, so a diagram of a long cycle
/// stays a few thousand pixels wide (a 40-minute cycle was 282,510).
fn time_tick(seconds: u64) -> u64 {
    let mut tick = 1;
    for factor in [2, 5, 2].iter().cycle() {
        if seconds.div_ceil(tick) <= 60 {
            return tick;
        }
        tick = tick.saturating_mul(*factor);
    }
    unreachable!("the cycle of factors never ends")
}

/// Renders the diagram as a standalone SVG document in the engineer's
/// notation: each lane labelled as `symbols` names its actuator, with the
/// engineer's name under it (`C1`, `clamp`), and the verdict in the same
/// words as every other finding.
pub fn render_svg(
    name: &str,
    report: &SimReport,
    kind: DiagramKind,
    symbols: &SymbolTable,
) -> String {
    let lanes = lanes(report);
    let sheet = Sheet::new(report, kind, &lanes);
    let mut svg = String::new();
    sheet.header(&mut svg, name, &symbols.explain(&report.verdict()));
    sheet.grid(&mut svg);
    if kind == DiagramKind::Time {
        sheet.step_markers(&mut svg, report);
        sheet.spans(&mut svg, report);
    }
    // Lanes: name, position levels, and the motion.
    for (i, ((number, pmax), lane)) in report.actuators.iter().zip(&lanes).enumerate() {
        sheet.lane(
            &mut svg,
            report,
            i,
            (*pmax).max(1),
            *lane,
            symbols.actuator_parts(*number),
        );
    }
    let _ = writeln!(
        svg,
        r##"<text x="{LEFT}" y="{:.1}" fill="#555" font-size="12">{}</text>"##,
        sheet.bottom - 10.0,
        legend(report, symbols)
    );
    svg.push_str("</svg>\n");
    svg
}

/// What a lane shows, in the words of the kinds the table has: a table of
/// cylinders reads "extends (+)", one with a drive or a gripper names
/// their moves too (`runs forward`, `grips`).
fn legend(report: &SimReport, symbols: &SymbolTable) -> String {
    let mut words: Vec<(&str, &str)> = Vec::new();
    for (number, _) in &report.actuators {
        let moves = symbols.move_words(*number);
        if !words.contains(&moves) {
            words.push(moves);
        }
    }
    let plain = ("extends", "retracts");
    if words.iter().all(|w| *w == plain) {
        return "one lane per cylinder, position 0 (home) to its end; rising = extends (+), falling = retracts (-)".to_string();
    }
    let (plus, minus): (Vec<&str>, Vec<&str>) = words.into_iter().unzip();
    format!(
        "one lane per actuator, position 0 (home) to its end; rising = + ({}), falling = - ({})",
        plus.join(", "),
        minus.join(", ")
    )
}

/// The page a diagram is drawn on: its size, its horizontal axis and the
/// time its axis starts at.
struct Sheet {
    kind: DiagramKind,
    /// The time axis starts at the first START press, as the step timing
    /// of the simulation counts it (step 4 at 2.59 s in the table is drawn
    /// at 2.59 s, not half a second later where power-up was).
    origin: u64,
    bottom: f64,
    width: f64,
    columns: Vec<(f64, String)>,
    x_label: &'static str,
    column_width: f64,
}

impl Sheet {
    fn new(report: &SimReport, kind: DiagramKind, lanes: &[(f64, f64)]) -> Self {
        let origin = report.cycles.first().map_or(0, |c| c.press_ms);
        let bottom = lanes.last().map(|(y, h)| y + h).unwrap_or(TOP) + 50.0;
        let (columns, x_label) = columns(report, kind, origin);
        let span = columns.last().map(|c| c.0).unwrap_or(1.0).max(1.0);
        // One grid column is 72 px per step, 60 px per time tick.
        let column_width = match kind {
            DiagramKind::Step => 72.0,
            DiagramKind::Time => 60.0 / columns.get(1).map(|c| c.0).unwrap_or(1.0).max(1.0),
        };
        let width = (LEFT + RIGHT + span * column_width).max(720.0);
        Sheet {
            kind,
            origin,
            bottom,
            width,
            columns,
            x_label,
            column_width,
        }
    }

    fn x_of(&self, value: f64) -> f64 {
        LEFT + value * self.column_width
    }

    fn header(&self, svg: &mut String, name: &str, verdict: &str) {
        let (width, bottom) = (self.width, self.bottom);
        let _ = writeln!(
            svg,
            r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{bottom:.0}" viewBox="0 0 {width:.0} {bottom:.0}" font-family="Helvetica, Arial, sans-serif" font-size="13">"#
        );
        let _ = writeln!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
        let title = match self.kind {
            DiagramKind::Step => "Displacement-step diagram",
            DiagramKind::Time => "Displacement-time diagram",
        };
        let _ = writeln!(
            svg,
            r#"<text x="{LEFT}" y="28" font-size="17" font-weight="bold">{title}: {}</text>"#,
            escape(name)
        );
        let _ = writeln!(
            svg,
            r##"<text x="{LEFT}" y="50" fill="#555">{}</text>"##,
            escape(&format!("simulated program: {verdict}"))
        );
    }

    /// Vertical grid with labels.
    fn grid(&self, svg: &mut String) {
        for (value, label) in &self.columns {
            let x = self.x_of(*value);
            let _ = writeln!(
                svg,
                r##"<line x1="{x:.1}" y1="{:.1}" x2="{x:.1}" y2="{:.1}" stroke="#bbb" stroke-width="1"/>"##,
                TOP - 12.0,
                self.bottom - 40.0
            );
            let _ = writeln!(
                svg,
                r#"<text x="{x:.1}" y="{:.1}" text-anchor="middle">{}</text>"#,
                TOP - 28.0,
                escape(label)
            );
        }
        let _ = writeln!(
            svg,
            r##"<text x="{:.1}" y="{:.1}" text-anchor="end" fill="#555">{}</text>"##,
            LEFT - 14.0,
            TOP - 28.0,
            self.x_label
        );
    }

    /// Where each step of every cycle fired, as dashed markers.
    fn step_markers(&self, svg: &mut String, report: &SimReport) {
        for (cycle, step) in report
            .cycles
            .iter()
            .flat_map(|c| c.steps.iter().map(move |s| (c, s)))
        {
            let ms = (cycle.press_ms + step.start_ms).saturating_sub(self.origin);
            let x = self.x_of(ms as f64 / 1000.0);
            let _ = writeln!(
                svg,
                r##"<line x1="{x:.1}" y1="{:.1}" x2="{x:.1}" y2="{:.1}" stroke="#e67e22" stroke-dasharray="4 3"/><text x="{x:.1}" y="{:.1}" fill="#e67e22" font-size="11" text-anchor="middle">{}</text>"##,
                TOP - 6.0,
                self.bottom - 40.0,
                self.bottom - 26.0,
                step.step
            );
        }
    }

    /// Dwells and waits on machine inputs, as shaded bands over every lane.
    fn spans(&self, svg: &mut String, report: &SimReport) {
        for span in &report.spans {
            let (x1, x2) = (
                self.x_of(span.from_ms.saturating_sub(self.origin) as f64 / 1000.0),
                self.x_of(span.to_ms.saturating_sub(self.origin) as f64 / 1000.0),
            );
            let color = if span.label.starts_with("I:") {
                "#8e44ad"
            } else {
                "#1e8449"
            };
            let _ = writeln!(
                svg,
                r#"<rect x="{x1:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="{color}" fill-opacity="0.12"/><text x="{:.1}" y="{:.1}" fill="{color}" font-size="11" text-anchor="middle">{}</text>"#,
                TOP - 10.0,
                (x2 - x1).max(1.0),
                self.bottom - 50.0 - TOP,
                (x1 + x2) / 2.0,
                TOP - 13.0,
                escape(&span.label)
            );
        }
    }

    /// One actuator's lane: its name, its position levels and its motion.
    fn lane(
        &self,
        svg: &mut String,
        report: &SimReport,
        i: usize,
        pmax: u32,
        (top, height): (f64, f64),
        (label, own): (String, Option<String>),
    ) {
        let y_of = |position: f64| top + height - position / pmax as f64 * height;
        let color = COLORS[i % COLORS.len()];
        let _ = writeln!(
            svg,
            r#"<text x="12" y="{:.1}" font-size="15" font-weight="bold" fill="{color}">{}</text>"#,
            top + height / 2.0 + 5.0,
            escape(&label)
        );
        if let Some(own) = own {
            let _ = writeln!(
                svg,
                r#"<text x="12" y="{:.1}" font-size="11" fill="{color}">{}</text>"#,
                top + height / 2.0 + 20.0,
                escape(&own)
            );
        }
        for level in 0..=pmax {
            let y = y_of(level as f64);
            let _ = writeln!(
                svg,
                r##"<line x1="{LEFT}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="{}" stroke-width="1"/><text x="{:.1}" y="{:.1}" text-anchor="end" fill="#555" font-size="11">{level}</text>"##,
                self.width - RIGHT,
                if level == 0 { "#888" } else { "#ddd" },
                LEFT - 8.0,
                y + 4.0
            );
        }
        let origin = self.origin;
        let points: Vec<(f64, f64)> = match self.kind {
            DiagramKind::Step => step_levels(report)
                .iter()
                .enumerate()
                .filter_map(|(k, positions)| {
                    positions.get(i).map(|p| (self.x_of(k as f64), y_of(*p)))
                })
                .collect(),
            DiagramKind::Time => report
                .trace
                .iter()
                .filter(|(t, _)| *t >= origin)
                .filter_map(|(t, positions)| {
                    positions
                        .get(i)
                        .map(|p| (self.x_of((t - origin) as f64 / 1000.0), y_of(*p)))
                })
                .collect(),
        };
        svg.push_str(r#"<polyline points=""#);
        for (k, (x, y)) in points.into_iter().enumerate() {
            let gap = if k == 0 { "" } else { " " };
            let _ = write!(svg, "{gap}{},{}", Tenths(x), Tenths(y));
        }
        let _ = writeln!(
            svg,
            r#"" fill="none" stroke="{color}" stroke-width="3" stroke-linejoin="round"/>"#
        );
    }
}

/// The grid columns of the horizontal axis and its label: one per step, or
/// one per time tick.
fn columns(
    report: &SimReport,
    kind: DiagramKind,
    origin: u64,
) -> (Vec<(f64, String)>, &'static str) {
    match kind {
        DiagramKind::Step => {
            let n = report.step_positions.len().max(2);
            let labels = (0..n)
                .map(|i| {
                    let label = if i + 1 == n {
                        format!("{}=1", i + 1)
                    } else {
                        (i + 1).to_string()
                    };
                    (i as f64, label)
                })
                .collect();
            (labels, "step")
        }
        DiagramKind::Time => {
            let end = report
                .trace
                .last()
                .map(|(t, _)| t.saturating_sub(origin))
                .unwrap_or(1000);
            let seconds = end.div_ceil(1000).max(1);
            let tick = time_tick(seconds);
            (
                (0..=seconds.div_ceil(tick))
                    .map(|k| (k as f64 * tick as f64, format!("{} s", k * tick)))
                    .collect(),
                "time",
            )
        }
    }
}

/// The positions at the step boundaries (when each step fired) at the
/// level the sensors report, as the step diagram draws them and the
/// workbook's DIAGRAM sheet lists them.
pub fn step_levels(report: &SimReport) -> Vec<Vec<f64>> {
    report
        .step_positions
        .iter()
        .map(|positions| positions.iter().map(|p| p.round_to_level()).collect())
        .collect()
}

/// Positions at step boundaries are read at sensor level: snap to the level
/// the sensor window reports, so a piston seen 2 % before its end stop is
/// drawn at the end.
trait RoundToLevel {
    fn round_to_level(self) -> f64;
}

impl RoundToLevel for f64 {
    fn round_to_level(self) -> f64 {
        let nearest = self.round();
        if (self - nearest).abs() < 0.15 {
            nearest
        } else {
            self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::simulate::{SimSettings, simulate};
    use crate::table::StepTable;

    /// The paper's own names: `C1`, `x10`, no engineer's names.
    fn plain(table: &StepTable) -> SymbolTable {
        let program = crate::program::build(
            table,
            &Default::default(),
            &Default::default(),
            &Default::default(),
        );
        SymbolTable::build(&program, table, &Default::default())
    }

    /// The healthy run of `table`'s default program, with its position
    /// trace when the time axis needs it.
    fn simulated(table: &StepTable, record_trace: bool) -> SimReport {
        let program = crate::program::build(
            table,
            &Default::default(),
            &Default::default(),
            &Default::default(),
        );
        let settings = SimSettings {
            record_trace,
            ..SimSettings::default()
        };
        simulate(table, &program, &settings)
    }

    /// The grid's labels along the top: `(x, text)` in drawing order.
    fn top_labels(svg: &str) -> Vec<(f64, String)> {
        let y = format!(r#"y="{:.1}" text-anchor="middle">"#, TOP - 28.0);
        svg.lines()
            .filter(|l| l.starts_with("<text x=\"") && l.contains(&y))
            .map(|l| {
                let x = l["<text x=\"".len()..].split('"').next().unwrap();
                let text = l.split(&y).nth(1).unwrap().trim_end_matches("</text>");
                (x.parse().unwrap(), text.to_string())
            })
            .collect()
    }

    /// `Tenths` writes exactly what `{:.1}` writes: ties both ways, values
    /// just beside them, negatives, zeros, and a sweep of a diagram's range.
    #[test]
    fn tenths_are_written_as_the_formatter_writes_them() {
        let mut values = vec![
            0.0,
            -0.0,
            0.05,
            0.15,
            0.25,
            0.35,
            1.45,
            2.5,
            -0.05,
            -1.25,
            0.049_999,
            0.150_001,
            1e11,
            1e13,
            f64::NAN,
            f64::INFINITY,
            -f64::INFINITY,
            123.456,
            99.95,
            99.949_999,
        ];
        let mut x = 0.0_f64;
        while x < 5000.0 {
            values.push(x);
            values.push(-x);
            x += 0.013_7;
        }
        for v in values {
            assert_eq!(Tenths(v).to_string(), format!("{v:.1}"), "{v:e}");
        }
    }

    #[test]
    fn the_time_axis_ticks_one_grid_column_apart_from_the_left_edge() {
        let table = crate::program::tests::paper_table();
        let report = simulated(&table, true);
        let svg = render_svg("paper", &report, DiagramKind::Time, &plain(&table));
        let labels = top_labels(&svg);
        let press = report.cycles[0].press_ms;
        let end_s = (report.trace.last().unwrap().0 - press).div_ceil(1000);
        let tick = time_tick(end_s);
        assert!(labels.len() >= 3, "{labels:?}");
        for (k, (x, text)) in labels.iter().enumerate() {
            assert_eq!(*text, format!("{} s", k as u64 * tick), "{labels:?}");
            assert!((x - (LEFT + 60.0 * k as f64)).abs() < 0.05, "{labels:?}");
        }
        // Step 2 fires where the simulation's step timing says, from the
        // START press; so does every step of the second cycle.
        let cycle = &report.cycles[0];
        let fired = cycle.steps[1].start_ms as f64 / 1000.0;
        let x = LEFT + fired * 60.0 / tick as f64;
        assert!(
            svg.contains(&format!(r#"<line x1="{x:.1}" y1="{:.1}""#, TOP - 6.0)),
            "{x}"
        );
        assert!(report.cycles.len() > 1, "a second cycle to mark");
        for c in &report.cycles {
            for step in &c.steps {
                let s = (c.press_ms - press + step.start_ms) as f64 / 1000.0;
                let x = LEFT + s * 60.0 / tick as f64;
                let marker = format!(r#"<line x1="{x:.1}" y1="{:.1}""#, TOP - 6.0);
                assert!(svg.contains(&marker), "step {} at {s} s", step.step);
            }
        }
    }

    #[test]
    fn a_dwell_is_shaded_where_it_runs_on_the_time_axis() {
        let table = crate::table::from_rows("dwell.csv", &[["C1+1; T=1s"], ["C1-0"]]).unwrap();
        let report = simulated(&table, true);
        let span = &report.spans[0];
        assert_eq!(span.to_ms - span.from_ms, 1000, "{span:?}");
        let press = report.cycles[0].press_ms;
        let tick = time_tick((report.trace.last().unwrap().0 - press).div_ceil(1000)) as f64;
        let x = |ms: u64| LEFT + (ms - press) as f64 / 1000.0 * 60.0 / tick;
        let svg = render_svg("dwell", &report, DiagramKind::Time, &plain(&table));
        let band = format!(
            r#"<rect x="{:.1}" y="{:.1}" width="{:.1}""#,
            x(span.from_ms),
            TOP - 10.0,
            x(span.to_ms) - x(span.from_ms)
        );
        assert!(svg.contains(&band), "{band}\n{svg}");
    }

    #[test]
    fn a_failed_run_is_told_in_the_engineers_designations() {
        let table = crate::program::tests::paper_table();
        let program = crate::program::build(
            &table,
            &Default::default(),
            &Default::default(),
            &Default::default(),
        );
        let dead = crate::program::Signal::Sensor {
            actuator: 1,
            position: 1,
        };
        let settings = SimSettings {
            faults: vec![crate::simulate::Fault {
                signal: dead,
                stuck_at: false,
            }],
            ..SimSettings::default()
        };
        let report = simulate(&table, &program, &settings);
        assert!(report.verdict().contains("x11"), "{}", report.verdict());
        let naming = crate::symbols::Naming {
            scheme: crate::symbols::Scheme::Iso,
            ..Default::default()
        };
        let iso = SymbolTable::build(&program, &table, &naming);
        let svg = render_svg("paper", &report, DiagramKind::Step, &iso);
        let verdict = svg
            .lines()
            .find(|l| l.contains("simulated program"))
            .unwrap();
        assert!(verdict.contains("1B2"), "{verdict}");
        assert!(!verdict.contains("x11"), "{verdict}");
    }

    #[test]
    fn the_step_axis_puts_each_step_a_column_apart() {
        let table = crate::program::tests::paper_table();
        let report = simulated(&table, false);
        let labels = top_labels(&render_svg(
            "paper",
            &report,
            DiagramKind::Step,
            &plain(&table),
        ));
        let texts: Vec<&str> = labels.iter().map(|(_, t)| t.as_str()).collect();
        assert_eq!(texts, ["1", "2", "3", "4", "5", "6", "7", "8", "9=1"]);
        for (k, (x, _)) in labels.iter().enumerate() {
            assert!((x - (LEFT + 72.0 * k as f64)).abs() < 0.05, "{labels:?}");
        }
    }
}
