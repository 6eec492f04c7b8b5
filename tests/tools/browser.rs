//! The pictures and the report as a real browser draws them: headless
//! Chromium (Debian's package) lays the GRAFCET out with its own fonts and
//! measures every box and label, so an overlap the character estimate of
//! `tests/integration/grafcet.rs` missed is still caught.

use std::path::Path;

use crate::helpers::{samples, steptable};
use crate::{Check, Tool, tool};

pub const CHECKS: &[Check] = &[
    Check::new(
        "browser::the_grafcet_renders_without_overlaps_in_chromium",
        &[Tool::Chromium],
        the_grafcet_renders_without_overlaps_in_chromium,
    ),
    Check::new(
        "browser::every_report_opens_in_chromium_without_errors_or_requests",
        &[Tool::Chromium],
        every_report_opens_in_chromium_without_errors_or_requests,
    ),
    Check::new(
        "browser::a_scenario_page_opens_in_chromium_without_errors_or_requests",
        &[Tool::Chromium],
        a_scenario_page_opens_in_chromium_without_errors_or_requests,
    ),
];

/// The page's DOM after its scripts ran, as headless Chromium dumps it,
/// and what Chromium logged (console messages among it).
pub fn dump_dom(page: &Path, profile: &Path) -> (String, String) {
    let out = std::process::Command::new(tool(Tool::Chromium))
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--disable-quic",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
            "--enable-logging=stderr",
            "--v=0",
            "--dump-dom",
        ])
        .arg(format!("--user-data-dir={}", profile.display()))
        .arg(format!("file://{}", page.display()))
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    (
        String::from_utf8_lossy(&out.stdout).to_string(),
        String::from_utf8_lossy(&out.stderr).to_string(),
    )
}

/// Measures the boxes and texts of every SVG on the page and writes the
/// overlaps it finds into `#overlaps`, one a line, and `done` after them.
pub const MEASURE: &str = r#"<script>
(function () {
  var out = [];
  document.querySelectorAll('svg.grafcet').forEach(function (svg) {
    var items = [];
    svg.querySelectorAll('g.step > rect:first-of-type, g.actions > rect, g.note > rect, g.transition > text, text.label').forEach(function (el) {
      var b = el.getBBox();
      items.push({ el: el, b: b, name: el.parentNode.getAttribute('data-step') || el.parentNode.getAttribute('data-transition') || el.textContent });
    });
    svg.querySelectorAll('g.actions, g.note').forEach(function (g) {
      var r = g.querySelector('rect').getBBox();
      g.querySelectorAll('text').forEach(function (t) {
        var b = t.getBBox();
        if (b.x < r.x || b.y < r.y || b.x + b.width > r.x + r.width || b.y + b.height > r.y + r.height)
          out.push('outside its panel: ' + t.textContent);
      });
    });
    for (var i = 0; i < items.length; i++) for (var j = i + 1; j < items.length; j++) {
      var a = items[i].b, c = items[j].b;
      if (a.x < c.x + c.width && c.x < a.x + a.width && a.y < c.y + c.height && c.y < a.y + a.height)
        out.push(items[i].name + ' overlaps ' + items[j].name);
    }
    out.push('drawn: ' + svg.querySelectorAll('g.step').length + ' steps, ' + svg.querySelectorAll('g.transition').length + ' transitions');
  });
  var pre = document.createElement('pre');
  pre.id = 'overlaps';
  pre.textContent = out.join('\n') + '\ndone';
  document.body.appendChild(pre);
})();
</script>"#;

/// Converts a sample into `dir/STEM` with `options`: its stem and folder.
fn convert(path: &Path, dir: &Path, options: &[&str]) -> (String, std::path::PathBuf) {
    let stem = path.file_stem().unwrap().to_string_lossy().to_string();
    let out = dir.join(&stem);
    steptable()
        .arg("convert")
        .arg(path)
        .args(options)
        .arg("-o")
        .arg(&out)
        .assert()
        .success();
    (stem, out)
}

fn the_grafcet_renders_without_overlaps_in_chromium() {
    let dir = tempfile::tempdir().unwrap();
    for path in samples() {
        let (stem, out) = convert(
            &path,
            dir.path(),
            &["--formats", "grafcet", "--modes", "all"],
        );
        let svg =
            std::fs::read_to_string(out.join(&stem).join(format!("{stem}.grafcet.svg"))).unwrap();
        let page = dir.path().join(format!("{stem}.html"));
        std::fs::write(
            &page,
            format!("<!DOCTYPE html><html><body>{svg}{MEASURE}</body></html>"),
        )
        .unwrap();
        let (dom, _) = dump_dom(&page, &dir.path().join("profile"));
        let found = dom
            .split("<pre id=\"overlaps\">")
            .nth(1)
            .and_then(|rest| rest.split("</pre>").next())
            .unwrap_or_else(|| panic!("{stem}: the measuring script did not run"));
        let lines: Vec<&str> = found.lines().collect();
        assert_eq!(lines.last(), Some(&"done"), "{stem}: {found}");
        let problems: Vec<&&str> = lines
            .iter()
            .filter(|l| !l.starts_with("drawn:") && **l != "done")
            .collect();
        assert!(problems.is_empty(), "{stem}: {problems:#?}");
        let steps = svg.matches("<g class=\"step\"").count();
        assert!(
            lines.iter().any(|l| *l
                == format!(
                    "drawn: {steps} steps, {} transitions",
                    svg.matches("<g class=\"transition\"").count()
                )),
            "{stem}: {found}"
        );
    }
}

/// Lists the resources the page fetched into `#requests`, `done` last.
const REQUESTS: &str = "<script>(function () { var p = document.createElement('pre'); p.id = 'requests'; p.textContent = performance.getEntriesByType('resource').map(function (e) { return e.name + '\\n'; }).join('') + 'done'; document.body.appendChild(p); })();</script>";

/// Opens a copy of `written` with a probe after the page's own script in
/// Chromium and checks what every page of steptable keeps: the script ran
/// (it marks the page and shows the controls), the console logged no
/// error, and the page fetched nothing beyond itself (every resource it
/// fetched, a style's font or image too, as the browser's resource timing
/// lists them). Returns the DOM; `what` names the page in a failure.
fn open_probed(written: &Path, dir: &Path, what: &str) -> String {
    let page = dir.join(format!("{what}.probed.html"));
    let html = std::fs::read_to_string(written).unwrap();
    std::fs::write(
        &page,
        html.replace("</body>", &format!("{REQUESTS}</body>")),
    )
    .unwrap();
    let (dom, log) = dump_dom(&page, &dir.join("profile"));
    assert!(
        dom.contains("data-js=\"on\""),
        "{what}: the script did not run\n{log}"
    );
    let errors: Vec<&str> = log
        .lines()
        .filter(|l| l.contains("CONSOLE") || l.contains("Uncaught"))
        .collect();
    assert!(errors.is_empty(), "{what}: {errors:#?}");
    assert!(
        !dom.contains("<div class=\"controls\" hidden"),
        "{what}: the controls stay hidden"
    );
    let requests = dom
        .split("<pre id=\"requests\">")
        .nth(1)
        .and_then(|r| r.split("</pre>").next())
        .unwrap_or_else(|| panic!("{what}: the probe did not run"));
    assert_eq!(
        requests, "done",
        "{what}: the page asked for more than itself"
    );
    dom
}

/// Every sample's report in Chromium opens as every page must
/// ([`open_probed`]), with every section in the DOM.
fn every_report_opens_in_chromium_without_errors_or_requests() {
    let dir = tempfile::tempdir().unwrap();
    for path in samples() {
        let (stem, out) = convert(&path, dir.path(), &["--formats", "report"]);
        let written = out.join(&stem).join(format!("{stem}.report.html"));
        let dom = open_probed(&written, dir.path(), &stem);
        for (id, _) in steptable::emit::report::SECTIONS {
            assert!(
                dom.contains(&format!("<section id=\"{id}\">")),
                "{stem}: {id}"
            );
        }
        // The fault table's mitigation column, filled for each hazard
        // (what it says is checked against `faults --safety` in
        // tests/integration/mitigation.rs).
        assert!(
            dom.contains("<th>mitigation</th>"),
            "{stem}: no mitigation column"
        );
        let hazard_rows = dom.matches("<tr class=\"hazard\"").count();
        let mitigated = [
            "caught by --safety",
            "still a hazard if it appears",
            "not caught by --safety",
        ]
        .iter()
        .any(|m| dom.contains(m));
        assert!(
            hazard_rows == 0 || mitigated,
            "{stem}: hazards without a mitigation"
        );
    }
}

/// `simulate --press … --report DIR` on the paper's example: the page opens
/// as every page must ([`open_probed`]), with a mark per event.
fn a_scenario_page_opens_in_chromium_without_errors_or_requests() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("r");
    steptable()
        .arg("simulate")
        .arg(crate::helpers::sample("paper_example.xlsx"))
        .args(["--modes", "estop,reset", "--press", "ESTOP@step3"])
        .args(["--press", "RESET@+1s", "--report"])
        .arg(&out)
        .assert()
        .success();
    let written = out.join("paper_example/paper_example.scenario.report.html");
    let dom = open_probed(&written, dir.path(), "scenario");
    assert_eq!(
        dom.matches("class=\"mark\"").count(),
        2,
        "one mark per event"
    );
}
