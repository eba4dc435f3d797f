//! What a person sees in the report's figures, measured by the browser
//! that draws them (text is laid out by the browser, not by tribo): no
//! legend over data, no legend entry outside its box or the figure, no two
//! legend entries that look alike, and no two texts on top of each other.
//! `report_visual.js` walks every figure after layout and writes what it
//! found into the page, which `--dump-dom` hands back.

use std::path::Path;

use serde_json::Value;

use crate::common::browser::{chromium, headless};

/// The script that measures the figures.
const CHECK: &str = include_str!("report_visual.js");

/// What the script found for each figure with axes, checked; returns how
/// many figures were measured.
fn check_report(browser: &Path, report: &Path) -> usize {
    let (n, problems) = measure(browser, report);
    assert!(
        problems.is_empty(),
        "{}:\n{}",
        report.display(),
        problems.join("\n")
    );
    n
}

/// The figures measured in `report` and what is wrong with them.
fn measure(browser: &Path, report: &Path) -> (usize, Vec<String>) {
    let html = std::fs::read_to_string(report).unwrap();
    let page = report.with_file_name("visual-check.html");
    let script = format!("<script>{CHECK}</script></body>");
    std::fs::write(&page, html.replacen("</body>", &script, 1)).unwrap();
    let out = headless(browser, &["--window-size=1200,1600", "--dump-dom"], &page);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let dom = String::from_utf8_lossy(&out.stdout);
    let start = dom
        .find("<pre id=\"visual-check\">")
        .expect("the script ran")
        + 23;
    let end = start + dom[start..].find("</pre>").unwrap();
    let json = dom[start..end]
        .replace("&quot;", "\"")
        .replace("&lt;", "<")
        .replace("&gt;", ">")
        .replace("&amp;", "&");
    let figures: Vec<Value> = serde_json::from_str(&json).unwrap();
    let mut problems = Vec::new();
    for f in &figures {
        let name = f["name"].as_str().unwrap().replace('\n', " ");
        if f["covered"].as_u64() != Some(0) {
            problems.push(format!(
                "{name}: the legend covers {} drawn points",
                f["covered"]
            ));
        }
        for key in ["overflow", "overlaps"] {
            if let Some(v) = f[key].as_array().filter(|v| !v.is_empty()) {
                problems.push(format!("{name}: {key}: {v:?}"));
            }
        }
        let looks: Vec<&str> = f["styles"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(Value::as_str)
            .collect();
        let mut unique = looks.clone();
        unique.sort();
        unique.dedup();
        if unique.len() != looks.len() {
            problems.push(format!("{name}: legend entries that look alike: {looks:?}"));
        }
    }
    (figures.len(), problems)
}

#[test]
fn the_demo_figures_have_no_legend_over_data_and_no_text_over_text() {
    let Some(browser) = chromium() else { return };
    let dir = tempfile::tempdir().unwrap();
    crate::common::run_demo(dir.path());
    let n = check_report(&browser, &dir.path().join(".tribo/current/report.html"));
    assert!(n >= 50, "{n} figures measured");
}

#[test]
fn the_real_exports_figures_have_no_legend_over_data_and_no_text_over_text() {
    let Some(browser) = chromium() else { return };
    let dir = tempfile::tempdir().unwrap();
    let Some(out) = crate::common::run_real_exports(&["real", "real2"], dir.path()) else {
        return;
    };
    let n = check_report(&browser, &out.join("report.html"));
    assert!(n >= 30, "{n} figures measured");
}

/// The check fails where it should: a figure drawn as plotters draws one
/// (mesh lines, a data line, then the legend's box and entries) with its
/// legend across the line, two entries alike, and two labels overlapping.
#[test]
fn the_check_finds_a_legend_over_data_look_alike_entries_and_overlapping_text() {
    let Some(browser) = chromium() else { return };
    let dir = tempfile::tempdir().unwrap();
    let svg = r##"<svg width="400" height="200" viewBox="0 0 400 200" xmlns="http://www.w3.org/2000/svg">
<text x="150" y="15">bad figure</text>
<line x1="80" y1="20" x2="80" y2="180" stroke="#F0F0F0"/>
<line x1="380" y1="20" x2="380" y2="180" stroke="#F0F0F0"/>
<polyline fill="none" stroke="#000000" points="80,100 380,100"/>
<rect x="200" y="80" width="100" height="45" opacity="0.85" fill="#FFFFFF"/>
<rect x="200" y="80" width="100" height="45" opacity="1" fill="none" stroke="#C8C8C8"/>
<polyline fill="none" stroke="#0072B2" stroke-width="2" points="206,92 222,92"/>
<text x="228" y="96" font-size="10">one</text>
<polyline fill="none" stroke="#0072B2" stroke-width="2" points="206,110 222,110"/>
<text x="228" y="114" font-size="10">two</text>
<text x="20" y="190" font-size="12">overlapping</text>
<text x="24" y="190" font-size="12">labels</text>
</svg>"##;
    let report = dir.path().join("bad.html");
    let page = format!("<html><body><section id=\"bad\">{svg}</section></body></html>");
    std::fs::write(&report, page).unwrap();
    let (n, problems) = measure(&browser, &report);
    assert_eq!(n, 1);
    let text = problems.join("\n");
    assert!(text.contains("the legend covers"), "{text}");
    assert!(text.contains("legend entries that look alike"), "{text}");
    assert!(
        text.contains("overlaps") && text.contains("overlapping | labels"),
        "{text}"
    );
}
