//! The report: every input file has its section and figure, doubts are
//! highlighted, nothing is loaded from outside, and the page renders in
//! headless Chromium without console errors and not blank.

use crate::common::browser::{chromium, headless};
use crate::common::{png, run_demo, tribo};

fn demo() -> (tempfile::TempDir, String) {
    let dir = tempfile::tempdir().unwrap();
    run_demo(dir.path());
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    (dir, html)
}

/// The section of the input file called `name` in the report.
fn section<'a>(html: &'a str, name: &str) -> &'a str {
    let slug: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect();
    let start = html
        .match_indices("<section id=\"file-")
        .map(|(i, _)| i)
        .find(|&i| {
            html[i..]
                .split('"')
                .nth(1)
                .is_some_and(|id| id.ends_with(&slug))
        })
        .unwrap_or_else(|| panic!("no section for {name}"));
    let end = html[start..].find("</section>").unwrap() + start;
    &html[start..end]
}

#[test]
fn every_input_file_has_its_section_and_figures() {
    let (dir, html) = demo();
    let mut n = 0;
    for table in ["friction", "tensile", "roughness"] {
        for source in crate::common::sources(dir.path(), table) {
            let s = section(&html, &source);
            assert!(s.contains("<svg"), "{source}: no figure");
            assert!(html.contains("href=\"#file-"), "no links");
            n += 1;
        }
    }
    assert!(n >= 20, "{n} files");
    // The model stages have theirs.
    for stage in ["coulomb", "ice", "spring-block"] {
        let at = html.find(&format!("id=\"model-{stage}\"")).unwrap();
        assert!(html[at..].contains("<svg"), "{stage}");
    }
}

#[test]
fn doubtful_rows_are_highlighted_and_listed_first() {
    let (_dir, html) = demo();
    // The CETR file whose static peaks sit below the plateau (MODELS.md §1).
    let cetr = "HT-2n-6-4_2_001.csv";
    let files = &html[..html.find("</table>").unwrap()];
    let row = files.lines().find(|l| l.contains(cetr)).unwrap();
    assert!(row.starts_with("<tr class=\"warn\">"), "{row}");
    assert!(row.contains("static_below_dynamic"), "{row}");
    assert!(section(&html, cetr).contains("<tr class=\"warn\">"));
    let sound = files
        .lines()
        .find(|l| l.contains("sled_F1_50g.csv"))
        .unwrap();
    assert!(sound.starts_with("<tr class=\"ok\">"), "{sound}");
}

#[test]
fn the_report_is_self_contained() {
    let (_dir, html) = demo();
    assert!(!html.contains("<script"), "scripts");
    assert!(!html.contains("<link"), "external style sheets");
    for attr in ["src=\"", "href=\"http", "url("] {
        assert!(!html.contains(attr), "external reference: {attr}");
    }
    // Only the SVG namespace names a web address.
    let addresses = html.matches("http").count();
    let namespaces = html.matches("http://www.w3.org/").count();
    assert_eq!(addresses, namespaces);
}

#[test]
fn tribo_report_redoes_the_same_page_from_the_folder() {
    let (dir, html) = demo();
    let out = tribo(dir.path(), &["report", "."]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let again = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    assert_eq!(again, html);
    let empty = tempfile::tempdir().unwrap();
    let out = tribo(empty.path(), &["report", "."]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("no published output set"));
}

#[test]
fn tribo_plot_writes_each_figure_as_svg() {
    let root = crate::common::root().join("fixtures/lab");
    let dir = tempfile::tempdir().unwrap();
    let files = [
        root.join("friction/HT-2n-6-4_2_001.csv"),
        root.join("fibres/t150_knotted.txt"),
        root.join("profiles/dektak-1.csv"),
    ];
    let mut args = vec!["plot".to_string()];
    args.extend(files.iter().map(|f| f.display().to_string()));
    args.extend(["--out".into(), "figs".into()]);
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = tribo(dir.path(), &args);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let svgs = crate::common::files_with_ext(&dir.path().join("figs"), "svg");
    let names: Vec<String> = svgs
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().to_string())
        .collect();
    for want in [
        "HT-2n-6-4_2_001-Step_1-force.svg",
        "HT-2n-6-4_2_001-Step_2-mu.svg",
        "t150_knotted-curve.svg",
        "dektak-1-surface.svg",
        "dektak-1-bearing.svg",
    ] {
        assert!(names.iter().any(|n| n == want), "{want} not in {names:?}");
    }
    for p in &svgs {
        let s = std::fs::read_to_string(p).unwrap();
        assert!(
            s.starts_with("<svg") && s.trim_end().ends_with("</svg>"),
            "{}",
            p.display()
        );
    }
    assert!(
        !dir.path().join("figs/.tribo-plot").exists(),
        "scratch folder left"
    );
}

#[test]
fn a_million_row_trace_gives_a_small_page() {
    let dir = tempfile::tempdir().unwrap();
    let mut csv = String::from("t (s),Fx (N),Fz (N)\n");
    for i in 0..1_000_000u32 {
        let t = i as f64 * 1e-4;
        let f = if t < 1.0 {
            0.6 * t
        } else {
            0.5 + 0.05 * (t * 40.0).sin()
        };
        csv.push_str(&format!("{t:.4},{f:.5},1.0\n"));
    }
    std::fs::write(dir.path().join("long.csv"), csv).unwrap();
    let out = tribo(
        dir.path(),
        &["friction", "long.csv", "--out", "out", "--no-traces"],
    );
    assert!(
        out.status.code().is_some_and(|c| c < 2),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let size = std::fs::metadata(dir.path().join("out/report.html"))
        .unwrap()
        .len();
    assert!(size < 300_000, "report of a 1e6-row trace: {size} bytes");
}

#[test]
fn the_report_renders_in_chromium() {
    let Some(browser) = chromium() else { return };
    let (dir, html) = demo();
    let page = dir.path().join(".tribo/current/report.html");
    let dom = headless(
        &browser,
        &["--enable-logging=stderr", "--v=0", "--dump-dom"],
        &page,
    );
    assert!(
        dom.status.success(),
        "{}",
        String::from_utf8_lossy(&dom.stderr)
    );
    let log = String::from_utf8_lossy(&dom.stderr);
    let console: Vec<&str> = log.lines().filter(|l| l.contains("CONSOLE")).collect();
    assert!(console.is_empty(), "console messages: {console:?}");
    // Every figure survived parsing as SVG in the DOM.
    let dom = String::from_utf8_lossy(&dom.stdout);
    assert_eq!(dom.matches("<svg").count(), html.matches("<svg").count());
    let shot = dir.path().join("shot.png");
    let arg = format!("--screenshot={}", shot.display());
    let out = headless(&browser, &["--window-size=1200,1600", &arg], &page);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let variance = png::grey_variance(&std::fs::read(&shot).unwrap());
    assert!(
        variance > 100.0,
        "the screenshot looks blank (grey variance {variance})"
    );
}

#[test]
fn doubts_are_warnings_on_stderr_and_in_the_summary() {
    let dir = tempfile::tempdir().unwrap();
    let demo = crate::common::root().join("pipelines/demo.toml");
    let out = tribo(
        dir.path(),
        &["run", demo.to_str().unwrap(), "--out", "out", "--json"],
    );
    let err = String::from_utf8_lossy(&out.stderr);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let lines: Vec<&str> = err.lines().filter(|l| l.starts_with("warning: ")).collect();
    assert!(
        lines
            .iter()
            .any(|l| l.contains("friction: ")
                && l.contains("HT-2n-6-4_2_001.csv: static_below_dynamic")),
        "{err}"
    );
    assert!(
        lines
            .iter()
            .any(|l| l.contains("coulomb: ") && l.contains("few_points")),
        "{err}"
    );
    // A model table's row has no file: no empty field between colons.
    assert!(lines.iter().all(|l| !l.contains(": : ")), "{err}");
    let n = json["warnings"].as_u64().unwrap() as usize;
    // The first 20 rows each have a line, the rest are counted on one.
    let more: usize = lines
        .iter()
        .find_map(|l| l.strip_prefix("warning: … and "))
        .map_or(0, |l| l.split(' ').next().unwrap().parse().unwrap());
    let shown = lines
        .iter()
        .filter(|l| !l.starts_with("warning: … and "))
        .count();
    assert!(shown <= 20, "{err}");
    assert_eq!(n, shown + more, "{err}");
    assert!(err.contains(&format!("{n} rows with a warning")), "{err}");
    // Warnings are not failures: the run's exit code is its own.
    assert_eq!(
        out.status.code(),
        Some(json["exit_code"].as_i64().unwrap() as i32)
    );
}
