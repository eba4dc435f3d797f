//! The HTML of the report. Everything is inline: the CSS below, the
//! figures' SVG; the page loads nothing.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::figures::{texts, FIGURE_TABLES};
use super::summary::doubts;
use crate::error::Result;
use crate::plot::escape;
use crate::table::{ColumnType, Table};

const STYLE: &str = "body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1100px;padding:0 1em;color:#222}\
h1{font-size:1.6em}h2{margin-top:2em;border-bottom:1px solid #ddd}h3{font-size:1.05em}\
table{border-collapse:collapse;font-size:.85em;margin:.5em 0}td,th{border:1px solid #ddd;padding:.25em .5em;text-align:left;vertical-align:top}\
th{background:#f4f4f4}tr.warn td{background:#fff4e0}tr.err td{background:#fde8e8}\
.ok{color:#176b2c}.warn{color:#9a5b00}.err{color:#b01818}\
figure{margin:1em 0}figure svg{max-width:100%;height:auto;border:1px solid #eee}\
code{background:#f4f4f4;padding:0 .2em}.num{text-align:right;font-variant-numeric:tabular-nums}";

/// Tables whose rows are about input files, with the columns shown for
/// each file: (table, [(column, heading)]).
const FILE_TABLES: &[(&str, &[(&str, &str)])] = &[
    (
        "friction",
        &[
            ("section", "section"),
            ("stroke", "stroke"),
            ("mu_static", "μ static"),
            ("mu_dynamic", "μ dynamic"),
            ("mu_instrument", "μ instrument"),
            ("stickslip_events", "stick-slip"),
            ("status", "status"),
        ],
    ),
    (
        "tensile",
        &[
            ("sample_id", "sample"),
            ("strength_MPa", "strength [MPa]"),
            ("strain_at_break", "ε_f"),
            ("modulus_GPa", "E [GPa]"),
            ("yield_stress_MPa", "Rp0.2 [MPa]"),
            ("toughness_J_per_g", "toughness [J/g]"),
            ("status", "status"),
        ],
    ),
    (
        "roughness",
        &[
            ("kind", "kind"),
            ("Ra_m", "Ra [m]"),
            ("Rq_m", "Rq [m]"),
            ("Rz_m", "Rz [m]"),
            ("Rdq_deg", "Rdq [°]"),
            ("Sa_m", "Sa [m]"),
            ("Sq_m", "Sq [m]"),
            ("Sdq_deg", "Sdq [°]"),
            ("fractal_dimension", "D"),
            ("status", "status"),
        ],
    ),
    (
        "wear",
        &[
            ("area_m2", "area [m²]"),
            ("depth_m", "depth [m]"),
            ("width_m", "width [m]"),
            ("volume_m3", "volume [m³]"),
            ("specific_wear_rate_mm3_per_N_m", "k [mm³/(N m)]"),
            ("status", "status"),
        ],
    ),
];

/// Model tables shown under the model stages: (stage, table, columns).
const MODEL_TABLES: &[(&str, &str, &[&str])] = &[
    (
        "coulomb",
        "coulomb",
        &[
            "grouping", "group", "regime", "n", "mu", "mu_se", "tau0_Pa", "r2", "status",
        ],
    ),
    (
        "ice",
        "ice_fit",
        &[
            "group", "bound", "a_m", "a_se_m", "rmse", "misfit", "status",
        ],
    ),
    (
        "spring-block",
        "spring_block_summary",
        &[
            "pattern",
            "pressure_Pa",
            "n",
            "mu_static_mean",
            "mu_static_sd",
            "mu_dynamic_mean",
            "n_failed",
        ],
    ),
    (
        "alsfm",
        "alsfm",
        &["beta_deg", "load", "mu", "r_xy_N", "status"],
    ),
];

/// The anchor of a file's section.
fn anchor(source: &str) -> String {
    let slug: String = source
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() {
                c.to_ascii_lowercase()
            } else {
                '-'
            }
        })
        .collect();
    format!("file-{slug}")
}

/// `ok`, `warn` or `err` for a status text.
fn class_of(status: &str) -> &'static str {
    match super::summary::is_sound(status) {
        true => "ok",
        false => "warn",
    }
}

/// The report of an output set's tables. `title` names the run.
pub fn render(tables: &BTreeMap<String, Table>, title: &str) -> Result<String> {
    let mut h = String::with_capacity(1 << 20);
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width\"><title>tribo report: {t}</title>\
         <style>{STYLE}</style></head><body>\n<h1>tribo report: {t}</h1>\n",
        t = escape(title)
    );
    let files = file_list(tables)?;
    let failed = failures(tables)?;
    overview(&mut h, tables, &files, &failed)?;
    for f in &files {
        file_section(&mut h, tables, f, &failed)?;
    }
    models(&mut h, tables)?;
    h.push_str("</body></html>\n");
    Ok(h)
}

/// Every input file the set mentions, in first-seen order.
fn file_list(tables: &BTreeMap<String, Table>) -> Result<Vec<String>> {
    let mut out: Vec<String> = Vec::new();
    for name in FILE_TABLES.iter().map(|t| t.0).chain(["errors"]) {
        if let Some(t) = tables.get(name) {
            for s in t.str("source")?.into_iter().flatten() {
                let is_file = name != "errors" || !s.ends_with(".parquet");
                if is_file && !out.contains(&s) {
                    out.push(s);
                }
            }
        }
    }
    Ok(out)
}

/// Failures by source: `stage: message`.
fn failures(tables: &BTreeMap<String, Table>) -> Result<BTreeMap<String, Vec<String>>> {
    let mut out: BTreeMap<String, Vec<String>> = BTreeMap::new();
    if let Some(t) = tables.get("errors") {
        let (s, st, m) = (texts(t, "source"), texts(t, "stage"), texts(t, "message"));
        for i in 0..s.len() {
            out.entry(s[i].clone())
                .or_default()
                .push(format!("{}: {}", st[i], m[i]));
        }
    }
    Ok(out)
}

/// The statuses of a file's rows, distinct, not `ok`.
fn file_statuses(tables: &BTreeMap<String, Table>, source: &str) -> Result<Vec<String>> {
    let mut out = Vec::new();
    for (name, _) in FILE_TABLES {
        let Some(t) = tables.get(*name) else { continue };
        let (src, st) = (texts(t, "source"), texts(t, "status"));
        for (s, status) in src.iter().zip(st) {
            if s == source && class_of(&status) != "ok" && !out.contains(&status) {
                out.push(status);
            }
        }
    }
    Ok(out)
}

fn overview(
    h: &mut String,
    tables: &BTreeMap<String, Table>,
    files: &[String],
    failed: &BTreeMap<String, Vec<String>>,
) -> Result<()> {
    let doubts = doubts(tables)?;
    let _ = write!(
        h,
        "<p>{} input files; <span class=\"err\">{} failed</span>; \
         <span class=\"warn\">{} result rows with a warning</span>. Each file links to its figures; \
         rows are highlighted where a status holds a doubt (codes in <code>docs/statuses.md</code>).</p>\n\
         <h2 id=\"files\">Files</h2>\n<table><tr><th>file</th><th>status</th></tr>\n",
        files.len(),
        failed.len(),
        doubts.len()
    );
    for f in files {
        let (class, text) = match failed.get(f) {
            Some(m) => ("err", m.join("<br>")),
            None => {
                let s = file_statuses(tables, f)?;
                match s.is_empty() {
                    true => ("ok", "ok".to_string()),
                    false => (
                        "warn",
                        s.iter().map(|x| escape(x)).collect::<Vec<_>>().join("<br>"),
                    ),
                }
            }
        };
        let text = if class == "err" {
            escape(&text).replace("&lt;br&gt;", "<br>")
        } else {
            text
        };
        let _ = writeln!(
            h,
            "<tr class=\"{class}\"><td><a href=\"#{}\">{}</a></td><td class=\"{class}\">{text}</td></tr>",
            anchor(f),
            escape(f)
        );
    }
    h.push_str("</table>\n");
    let models: Vec<(&str, &str)> = MODEL_TABLES
        .iter()
        .filter(|(_, t, _)| tables.contains_key(*t))
        .map(|(s, t, _)| (*s, *t))
        .collect();
    if !models.is_empty() {
        h.push_str("<p>Models: ");
        let links: Vec<String> = models
            .iter()
            .map(|(m, t)| {
                let n = doubts.iter().filter(|d| d.table == *t).count();
                match n {
                    0 => format!("<a href=\"#model-{m}\">{m}</a>"),
                    n => format!(
                        "<a href=\"#model-{m}\">{m}</a> <span class=\"warn\">({n} with a warning)</span>"
                    ),
                }
            })
            .collect();
        h.push_str(&links.join(" · "));
        h.push_str("</p>\n");
    }
    Ok(())
}

/// The figures of `source` in the figures tables, in table order.
fn figures_of(tables: &BTreeMap<String, Table>, source: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for name in FIGURE_TABLES {
        let Some(t) = tables.get(name) else { continue };
        let (src, title, svg) = (texts(t, "source"), texts(t, "title"), texts(t, "svg"));
        for i in (0..src.len()).filter(|&i| src[i] == source) {
            out.push((title[i].clone(), svg[i].clone()));
        }
    }
    out
}

fn file_section(
    h: &mut String,
    tables: &BTreeMap<String, Table>,
    source: &str,
    failed: &BTreeMap<String, Vec<String>>,
) -> Result<()> {
    let _ = writeln!(
        h,
        "<section id=\"{}\"><h2>{}</h2>",
        anchor(source),
        escape(source)
    );
    if let Some(m) = failed.get(source) {
        for line in m {
            let _ = writeln!(h, "<p class=\"err\">failed: {}</p>", escape(line));
        }
    }
    for (name, cols) in FILE_TABLES {
        let Some(t) = tables.get(*name) else { continue };
        let rows: Vec<usize> = texts(t, "source")
            .iter()
            .enumerate()
            .filter(|(_, s)| *s == source)
            .map(|(i, _)| i)
            .collect();
        if !rows.is_empty() {
            let cols: Vec<(&str, &str)> = cols.to_vec();
            rows_table(h, t, &rows, &cols)?;
        }
    }
    let figs = figures_of(tables, source);
    if figs.is_empty() && !failed.contains_key(source) {
        h.push_str("<p>No figures: the run was made with <code>report = false</code>.</p>\n");
    }
    for (title, svg) in figs {
        let _ = writeln!(
            h,
            "<figure aria-label=\"{}\">{svg}</figure>",
            escape(&title)
        );
    }
    h.push_str("<p><a href=\"#files\">back to the files</a></p></section>\n");
    Ok(())
}

/// A value as shown: numbers to 4 significant digits, null as a dash.
fn cell(t: &Table, col: &str, i: usize) -> Result<(String, bool)> {
    Ok(match t.column_type(col) {
        Some(ColumnType::F64) => (
            t.f64(col)?[i].map_or("–".into(), |v| format!("{v:.4}")),
            true,
        ),
        Some(ColumnType::I64) => (t.i64(col)?[i].map_or("–".into(), |v| v.to_string()), true),
        Some(ColumnType::Bool) => (t.bool(col)?[i].map_or("–".into(), |v| v.to_string()), false),
        Some(_) => (t.str(col)?[i].clone().unwrap_or_else(|| "–".into()), false),
        None => ("".into(), false),
    })
}

fn rows_table(h: &mut String, t: &Table, rows: &[usize], cols: &[(&str, &str)]) -> Result<()> {
    let names = t.column_names();
    let cols: Vec<&(&str, &str)> = cols
        .iter()
        .filter(|(c, _)| names.iter().any(|n| n == c))
        .collect();
    h.push_str("<table><tr>");
    for (_, head) in &cols {
        let _ = write!(h, "<th>{}</th>", escape(head));
    }
    h.push_str("</tr>\n");
    let status = if names.iter().any(|n| n == "status") {
        texts(t, "status")
    } else {
        Vec::new()
    };
    for &i in rows {
        let class = status.get(i).map_or("ok", |s| class_of(s));
        let _ = write!(h, "<tr class=\"{class}\">");
        for (c, _) in &cols {
            let (text, num) = cell(t, c, i)?;
            let cls = if num { " class=\"num\"" } else { "" };
            let _ = write!(h, "<td{cls}>{}</td>", escape(&text));
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n");
    Ok(())
}

fn models(h: &mut String, tables: &BTreeMap<String, Table>) -> Result<()> {
    for (stage, table, cols) in MODEL_TABLES {
        let Some(t) = tables.get(*table) else {
            continue;
        };
        let _ = writeln!(h, "<section id=\"model-{stage}\"><h2>Model: {stage}</h2>");
        let cols: Vec<(&str, &str)> = cols.iter().map(|c| (*c, *c)).collect();
        let rows: Vec<usize> = (0..t.height()).collect();
        rows_table(h, t, &rows, &cols)?;
        for (title, svg) in figures_of(tables, stage) {
            let _ = writeln!(
                h,
                "<figure aria-label=\"{}\">{svg}</figure>",
                escape(&title)
            );
        }
        h.push_str("</section>\n");
    }
    Ok(())
}

/// Whether the report reads the table `name` (the others, such as the
/// traces, are never loaded for it).
pub fn reads(name: &str) -> bool {
    name == "errors"
        || FILE_TABLES.iter().any(|(t, _)| *t == name)
        || MODEL_TABLES.iter().any(|(_, t, _)| *t == name)
        || FIGURE_TABLES.contains(&name)
}
