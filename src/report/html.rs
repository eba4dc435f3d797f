//! The HTML of the report. Everything is inline: the CSS below, the
//! figures' SVG; the page loads nothing.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::figures::texts;
use super::index::{figures_by_source, rows_by_source, Shown};
use super::summary::doubts;
use crate::error::Result;
use crate::plot::escape;
use crate::schema::{Show, TableDef};
use crate::table::Table;

/// The tables whose rows are about input files, with the columns shown
/// for each file: (table, [(column, heading)]).
fn file_tables<'a>(
    defs: &'a [&'static TableDef],
) -> impl Iterator<Item = (&'static str, &'static [(&'static str, &'static str)])> + 'a {
    defs.iter().filter_map(|d| match d.show {
        Show::PerFile(cols) => Some((d.name, cols)),
        _ => None,
    })
}

/// The model tables: (model, table, columns).
fn model_tables<'a>(
    defs: &'a [&'static TableDef],
) -> impl Iterator<Item = (&'static str, &'static str, &'static [&'static str])> + 'a {
    defs.iter().filter_map(|d| match d.show {
        Show::Model { model, columns } => Some((model, d.name, columns)),
        _ => None,
    })
}

/// The names of the tables shown as `show`.
fn shown_as<'a>(
    defs: &'a [&'static TableDef],
    show: Show,
) -> impl Iterator<Item = &'static str> + 'a {
    defs.iter().filter(move |d| d.show == show).map(|d| d.name)
}

const STYLE: &str = "body{font-family:system-ui,sans-serif;margin:2em auto;max-width:1100px;padding:0 1em;color:#222}\
h1{font-size:1.6em}h2{margin-top:2em;border-bottom:1px solid #ddd}h3{font-size:1.05em}\
table{border-collapse:collapse;font-size:.85em;margin:.5em 0}td,th{border:1px solid #ddd;padding:.25em .5em;text-align:left;vertical-align:top}\
th{background:#f4f4f4}tr.warn td{background:#fff4e0}tr.err td{background:#fde8e8}\
.ok{color:#176b2c}.warn{color:#9a5b00}.err{color:#b01818}\
figure{margin:1em 0}figure svg{max-width:100%;height:auto;border:1px solid #eee}\
code{background:#f4f4f4;padding:0 .2em}.num{text-align:right;font-variant-numeric:tabular-nums}";

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

/// A file table prepared once: its shown columns and its rows by source.
struct FileTable {
    shown: Shown,
    rows: BTreeMap<String, Vec<usize>>,
}

/// What the page is made of, gathered once.
struct Page<'a> {
    tables: &'a BTreeMap<String, Table>,
    defs: &'a [&'static TableDef],
    file_tables: Vec<FileTable>,
    figures: BTreeMap<String, Vec<(String, String)>>,
    failed: BTreeMap<String, Vec<String>>,
}

/// The report of an output set's tables, shown as their declarations
/// `defs` say. `title` names the run.
pub fn render(
    tables: &BTreeMap<String, Table>,
    defs: &[&'static TableDef],
    title: &str,
) -> Result<String> {
    let mut h = String::with_capacity(1 << 20);
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width\"><title>tribo report: {t}</title>\
         <style>{STYLE}</style></head><body>\n<h1>tribo report: {t}</h1>\n",
        t = escape(title)
    );
    let mut shown_files = Vec::new();
    for (name, cols) in file_tables(defs) {
        if let Some(t) = tables.get(name) {
            let shown = Shown::of(t, cols)?;
            shown_files.push(FileTable {
                shown,
                rows: rows_by_source(t),
            });
        }
    }
    let page = Page {
        tables,
        defs,
        file_tables: shown_files,
        figures: figures_by_source(tables, shown_as(defs, Show::Figures)),
        failed: failures(tables, defs),
    };
    let files = file_list(tables, defs)?;
    overview(&mut h, &page, &files)?;
    for f in &files {
        file_section(&mut h, &page, f);
    }
    models(&mut h, &page)?;
    h.push_str("</body></html>\n");
    Ok(h)
}

/// Every input file the set mentions, in first-seen order.
fn file_list(tables: &BTreeMap<String, Table>, defs: &[&'static TableDef]) -> Result<Vec<String>> {
    let mut seen = std::collections::BTreeSet::new();
    let mut out: Vec<String> = Vec::new();
    let errors: Vec<&str> = shown_as(defs, Show::Errors).collect();
    for name in file_tables(defs).map(|t| t.0).chain(errors.iter().copied()) {
        if let Some(t) = tables.get(name) {
            for s in t.str("source")?.into_iter().flatten() {
                let is_file = !errors.contains(&name) || !s.ends_with(".parquet");
                if is_file && seen.insert(s.clone()) {
                    out.push(s);
                }
            }
        }
    }
    Ok(out)
}

/// Failures by source: `stage: message`.
fn failures(
    tables: &BTreeMap<String, Table>,
    defs: &[&'static TableDef],
) -> BTreeMap<String, Vec<String>> {
    let mut out: BTreeMap<String, Vec<String>> = BTreeMap::new();
    for t in shown_as(defs, Show::Errors).filter_map(|n| tables.get(n)) {
        let (s, st, m) = (texts(t, "source"), texts(t, "stage"), texts(t, "message"));
        for i in 0..s.len() {
            out.entry(s[i].clone())
                .or_default()
                .push(format!("{}: {}", st[i], m[i]));
        }
    }
    out
}

/// The statuses of a file's rows, distinct, not sound.
fn file_statuses(page: &Page, source: &str) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for ft in &page.file_tables {
        for &i in ft.rows.get(source).map_or(&[][..], |r| r.as_slice()) {
            let status = &ft.shown.status[i];
            if class_of(status) != "ok" && !out.contains(status) {
                out.push(status.clone());
            }
        }
    }
    out
}

fn overview(h: &mut String, page: &Page, files: &[String]) -> Result<()> {
    let doubts = doubts(page.tables)?;
    let _ = write!(
        h,
        "<p>{} input files; <span class=\"err\">{} failed</span>; \
         <span class=\"warn\">{} result rows with a warning</span>. Each file links to its figures; \
         rows are highlighted where a status holds a doubt (codes in <code>docs/statuses.md</code>).</p>\n\
         <h2 id=\"files\">Files</h2>\n<table><tr><th>file</th><th>status</th></tr>\n",
        files.len(),
        page.failed.len(),
        doubts.len()
    );
    for f in files {
        let (class, lines) = match page.failed.get(f) {
            Some(m) => ("err", m.clone()),
            None => match file_statuses(page, f) {
                s if s.is_empty() => ("ok", vec!["ok".to_string()]),
                s => ("warn", s),
            },
        };
        let text: Vec<String> = lines.iter().map(|x| escape(x)).collect();
        let _ = writeln!(
            h,
            "<tr class=\"{class}\"><td><a href=\"#{}\">{}</a></td><td class=\"{class}\">{}</td></tr>",
            anchor(f),
            escape(f),
            text.join("<br>")
        );
    }
    h.push_str("</table>\n");
    model_links(h, page, &doubts);
    Ok(())
}

/// Links to the model stages, with their rows' warnings counted.
fn model_links(h: &mut String, page: &Page, doubts: &[super::Doubt]) {
    let links: Vec<String> = model_tables(page.defs)
        .filter(|(_, t, _)| page.tables.contains_key(*t))
        .map(
            |(m, t, _)| match doubts.iter().filter(|d| d.table == t).count() {
                0 => format!("<a href=\"#model-{m}\">{m}</a>"),
                n => format!(
                "<a href=\"#model-{m}\">{m}</a> <span class=\"warn\">({n} with a warning)</span>"
            ),
            },
        )
        .collect();
    if !links.is_empty() {
        let _ = writeln!(h, "<p>Models: {}</p>", links.join(" · "));
    }
}

fn figures(h: &mut String, page: &Page, source: &str) -> usize {
    let figs = page.figures.get(source).map_or(&[][..], |f| f.as_slice());
    for (title, svg) in figs {
        let _ = writeln!(h, "<figure aria-label=\"{}\">{svg}</figure>", escape(title));
    }
    figs.len()
}

fn file_section(h: &mut String, page: &Page, source: &str) {
    let _ = writeln!(
        h,
        "<section id=\"{}\"><h2>{}</h2>",
        anchor(source),
        escape(source)
    );
    if let Some(m) = page.failed.get(source) {
        for line in m {
            let _ = writeln!(h, "<p class=\"err\">failed: {}</p>", escape(line));
        }
    }
    for ft in &page.file_tables {
        if let Some(rows) = ft.rows.get(source) {
            rows_table(h, &ft.shown, rows);
        }
    }
    if figures(h, page, source) == 0 && !page.failed.contains_key(source) {
        h.push_str("<p>No figures: the run was made with <code>report = false</code>.</p>\n");
    }
    h.push_str("<p><a href=\"#files\">back to the files</a></p></section>\n");
}

fn rows_table(h: &mut String, shown: &Shown, rows: &[usize]) {
    h.push_str("<table><tr>");
    for head in &shown.heads {
        let _ = write!(h, "<th>{}</th>", escape(head));
    }
    h.push_str("</tr>\n");
    for &i in rows {
        let _ = write!(h, "<tr class=\"{}\">", class_of(&shown.status[i]));
        for (cells, num) in shown.cells.iter().zip(&shown.numeric) {
            let cls = if *num { " class=\"num\"" } else { "" };
            let _ = write!(h, "<td{cls}>{}</td>", escape(&cells[i]));
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n");
}

fn models(h: &mut String, page: &Page) -> Result<()> {
    for (stage, table, cols) in model_tables(page.defs) {
        let Some(t) = page.tables.get(table) else {
            continue;
        };
        let _ = writeln!(h, "<section id=\"model-{stage}\"><h2>Model: {stage}</h2>");
        let cols: Vec<(&str, &str)> = cols.iter().map(|c| (*c, *c)).collect();
        let rows: Vec<usize> = (0..t.height()).collect();
        rows_table(h, &Shown::of(t, &cols)?, &rows);
        figures(h, page, stage);
        h.push_str("</section>\n");
    }
    Ok(())
}
