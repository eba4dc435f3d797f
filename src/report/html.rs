//! The HTML of the report. Everything is inline: the CSS below, the
//! figures' SVG; the page loads nothing.

use std::collections::{BTreeMap, BTreeSet};
use std::fmt::Write as _;

use super::figure_files::FigureFiles;
use super::figures::texts;
use super::index::{by_source, rows_by_source, BySource, Shown};
use super::overview::{self, Input};
use super::pages::{self, anchor, Split, FILES_PER_PAGE};
use super::summary::doubts;
use crate::error::Result;
use crate::plot::escape;
use crate::schema::{Show, TableDef};
use crate::table::Table;

/// Columns shown, as (column, heading).
type Columns = &'static [(&'static str, &'static str)];

/// The tables whose rows are about input files, with the columns shown
/// for each file.
fn file_tables<'a>(
    defs: &'a [&'static TableDef],
) -> impl Iterator<Item = (&'static TableDef, Columns)> + 'a {
    defs.iter().filter_map(|d| match d.show {
        Show::PerFile(cols) => Some((*d, cols)),
        _ => None,
    })
}

/// The model tables: (model, table, columns).
fn model_tables<'a>(
    defs: &'a [&'static TableDef],
) -> impl Iterator<Item = (&'static str, &'static TableDef, Columns)> + 'a {
    defs.iter().filter_map(|d| match d.show {
        Show::Model { model, columns } => Some((model, *d, columns)),
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
.ok{color:#176b2c}.warn{color:#9a5b00}.err{color:#b01818}.skip{color:#666}\
figure{margin:1em 0}figure svg{max-width:100%;height:auto;border:1px solid #eee}\
code{background:#f4f4f4;padding:0 .2em}.num{text-align:right;font-variant-numeric:tabular-nums}";

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
    /// The figure tables among `tables`, each by source.
    figures: BTreeMap<&'a str, BySource<'a>>,
    /// The figure tables read from files, a page's sources at a time.
    kept: FigureFiles<'a>,
    failed: BTreeMap<String, Vec<String>>,
}

/// How a page shows the figures of the tables read from files.
enum Kept<'b> {
    /// Read for the page's sources: each table's figures by source.
    Read(&'b BTreeMap<&'b str, BySource<'b>>),
    /// Only the files they are in named: a page's outline, which changes
    /// whenever the page does, made without reading a figure.
    Named,
}

/// A rendered report: its first page (`report.html`, the overview of
/// every input and the models) and, when the files' sections are split,
/// each page of them made when asked for ([`Report::page`]): the pages
/// of a large archive are written one at a time, never all held at once.
pub struct Report<'a> {
    /// `report.html`.
    pub index: String,
    page: Page<'a>,
    split: Split,
    title: String,
}

impl Report<'_> {
    /// The number of pages of file sections (0: on the first page).
    pub fn pages(&self) -> usize {
        self.split.count()
    }

    /// The name of the `i`-th page in [`super::PAGES_DIR`].
    pub fn page_name(&self, i: usize) -> String {
        pages::name(i)
    }

    /// The `i`-th page of file sections: its name in
    /// [`super::PAGES_DIR`] and its HTML, with links to the first page
    /// and to the pages before and after it. Reads the figures of its
    /// files that are kept in files.
    pub fn page(&self, i: usize) -> Result<(String, String)> {
        let read = self.page.kept.read(self.split.page(i))?;
        let figures = by_source(read.iter().map(|(n, t)| (*n, t)))?;
        Ok(self.page_html(i, &Kept::Read(&figures)))
    }

    /// The `i`-th page as [`Report::page`] makes it, with the figures
    /// kept in files named instead of shown: equal outlines, equal pages.
    pub fn outline(&self, i: usize) -> String {
        self.page_html(i, &Kept::Named).1
    }

    fn page_html(&self, i: usize, kept: &Kept) -> (String, String) {
        let files = self.split.page(i);
        let (first, last) = (files.first(), files.last());
        let part = format!(
            ", files {} to {}",
            first.map_or("", |f| f),
            last.map_or("", |f| f)
        );
        let mut h = head(&self.title, &part);
        let mut nav = vec!["<a href=\"../report.html#files\">all files</a>".to_string()];
        if i > 0 {
            let before = pages::name(i - 1);
            nav.push(format!("<a href=\"{before}\">previous page</a>"));
        }
        if i + 1 < self.pages() {
            let after = pages::name(i + 1);
            nav.push(format!("<a href=\"{after}\">next page</a>"));
        }
        // Not "of N": a page would then change whenever one is added.
        let nav = format!("<p>Page {}: {}</p>\n", i + 1, nav.join(" · "));
        h.push_str(&nav);
        for f in files {
            file_section(&mut h, &self.page, f, "../report.html", kept);
        }
        h.push_str(&nav);
        h.push_str("</body></html>\n");
        (self.page_name(i), h)
    }
}

/// The report of `tables` with [`FILES_PER_PAGE`] file sections a page.
pub fn render<'a>(
    tables: &'a BTreeMap<String, Table>,
    defs: &'a [&'static TableDef],
    title: &str,
    kept: FigureFiles<'a>,
) -> Result<Report<'a>> {
    render_paged(tables, defs, title, FILES_PER_PAGE, kept)
}

/// The report of an output set's tables, shown as their declarations
/// `defs` say. `title` names the run. Up to `per_page` file sections are
/// on the first page; more are split over pages of `per_page` each. The
/// figure tables `kept` holds are read from their files, a page at a time.
pub fn render_paged<'a>(
    tables: &'a BTreeMap<String, Table>,
    defs: &'a [&'static TableDef],
    title: &str,
    per_page: usize,
    kept: FigureFiles<'a>,
) -> Result<Report<'a>> {
    let mut shown_files = Vec::new();
    for (def, cols) in file_tables(defs) {
        if let Some(t) = tables.get(def.name) {
            let shown = Shown::of(t, def.schema()?, cols)?;
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
        figures: by_source(
            shown_as(defs, Show::Figures).filter_map(|n| Some((n, tables.get(n)?))),
        )?,
        kept,
        failed: failures(tables, defs),
    };
    let mentioned = file_list(tables, defs)?;
    let inputs = overview::inputs(tables, defs, &mentioned);
    // Sections in input order: the files with rows or failures.
    let with_rows: BTreeSet<&String> = mentioned.iter().collect();
    let listed: BTreeSet<&String> = inputs.iter().map(|i| &i.file).collect();
    let files: Vec<String> = inputs
        .iter()
        .map(|i| &i.file)
        .filter(|f| with_rows.contains(f))
        .chain(mentioned.iter().filter(|f| !listed.contains(f)))
        .cloned()
        .collect();
    let split = Split::of(files, per_page);
    let mut h = head(title, "");
    overview(&mut h, &page, &inputs, &split)?;
    let read = page.kept.read(split.on_first())?;
    let figures = by_source(read.iter().map(|(n, t)| (*n, t)))?;
    let kept = Kept::Read(&figures);
    for f in split.on_first() {
        file_section(&mut h, &page, f, "", &kept);
    }
    models(&mut h, &page, &kept)?;
    h.push_str("</body></html>\n");
    Ok(Report {
        index: h,
        page,
        split,
        title: title.to_string(),
    })
}

/// The start of a page: its title, the style, its heading.
fn head(title: &str, part: &str) -> String {
    let mut h = String::with_capacity(1 << 20);
    let _ = write!(
        h,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\">\
         <meta name=\"viewport\" content=\"width=device-width\"><title>tribo report: {t}{p}</title>\
         <style>{STYLE}</style></head><body>\n<h1>tribo report: {t}{p}</h1>\n",
        t = escape(title),
        p = escape(part),
    );
    h
}

/// Every input file the set mentions, in first-seen order.
fn file_list(tables: &BTreeMap<String, Table>, defs: &[&'static TableDef]) -> Result<Vec<String>> {
    let mut seen = std::collections::BTreeSet::new();
    let mut out: Vec<String> = Vec::new();
    let errors: Vec<&str> = shown_as(defs, Show::Errors).collect();
    for name in file_tables(defs)
        .map(|t| t.0.name)
        .chain(errors.iter().copied())
    {
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

/// The statuses of a file's rows that are not sound, distinct, and the
/// class of the most severe.
fn file_statuses(page: &Page, source: &str) -> (&'static str, Vec<String>) {
    let (mut class, mut out) = ("ok", Vec::new());
    for ft in &page.file_tables {
        for &i in ft.rows.get(source).map_or(&[][..], |r| r.as_slice()) {
            let status = &ft.shown.status[i];
            if status.is_sound() {
                continue;
            }
            if status.class() == "err" {
                class = "err";
            } else if class == "ok" {
                class = "warn";
            }
            if !out.contains(&status.text) {
                out.push(status.text.clone());
            }
        }
    }
    (class, out)
}

/// The first table: every input with what became of it; a file with a
/// section links to it (on its page when the sections are split).
fn overview(h: &mut String, page: &Page, inputs: &[Input], split: &Split) -> Result<()> {
    let doubts = doubts(page.tables)?;
    let _ = write!(
        h,
        "<p>{} Each file links to its figures; \
         rows are highlighted where a status holds a doubt (codes in <code>docs/statuses.md</code>).</p>\n\
         <h2 id=\"files\">Files</h2>\n<table><tr><th>file</th><th>read as</th><th>stages</th>\
         <th>status</th></tr>\n",
        overview::counts(inputs, page.failed.len(), doubts.len())?,
    );
    for input in inputs {
        let f = &input.file;
        let (class, lines) = overview::status_of(input, page.failed.get(f), file_statuses(page, f));
        let link = split.link(f);
        overview::row(h, input, class, &lines, link.as_deref());
    }
    h.push_str("</table>\n");
    model_links(h, page, &doubts);
    Ok(())
}

/// Links to the model stages, with their rows' warnings counted.
fn model_links(h: &mut String, page: &Page, doubts: &[super::Doubt]) {
    let links: Vec<String> = model_tables(page.defs)
        .filter(|(_, t, _)| page.tables.contains_key(t.name))
        .map(
            |(m, t, _)| match doubts.iter().filter(|d| d.table == t.name).count() {
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

/// Writes the figures of `source`, table by table in declaration order;
/// returns how many (a file named in an outline counts as one).
fn figures(h: &mut String, page: &Page, source: &str, kept: &Kept) -> usize {
    let mut n = 0;
    for name in shown_as(page.defs, Show::Figures) {
        let by = match (page.kept.holds(name), kept) {
            (true, Kept::Named) => {
                n += usize::from(page.kept.name(h, name, source));
                continue;
            }
            (true, Kept::Read(read)) => read.get(name),
            (false, _) => page.figures.get(name),
        };
        let figs = by
            .and_then(|b| b.get(source))
            .map_or(&[][..], |f| f.as_slice());
        for (title, svg) in figs {
            let _ = writeln!(h, "<figure aria-label=\"{}\">{svg}</figure>", escape(title));
        }
        n += figs.len();
    }
    n
}

/// A file's section; `back` is the path of the first page from the
/// section's page (empty on the first page itself).
fn file_section(h: &mut String, page: &Page, source: &str, back: &str, kept: &Kept) {
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
    if figures(h, page, source, kept) == 0 && !page.failed.contains_key(source) {
        h.push_str("<p>No figures: the run was made with <code>report = false</code>.</p>\n");
    }
    let _ = writeln!(
        h,
        "<p><a href=\"{back}#files\">back to the files</a></p></section>"
    );
}

fn rows_table(h: &mut String, shown: &Shown, rows: &[usize]) {
    h.push_str("<table><tr>");
    for head in &shown.heads {
        let _ = write!(h, "<th>{}</th>", escape(head));
    }
    h.push_str("</tr>\n");
    for &i in rows {
        let _ = write!(h, "<tr class=\"{}\">", shown.status[i].class());
        for (cells, num) in shown.cells.iter().zip(&shown.numeric) {
            let cls = if *num { " class=\"num\"" } else { "" };
            let _ = write!(h, "<td{cls}>{}</td>", escape(&cells[i]));
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</table>\n");
}

fn models(h: &mut String, page: &Page, kept: &Kept) -> Result<()> {
    for (stage, def, cols) in model_tables(page.defs) {
        let Some(t) = page.tables.get(def.name) else {
            continue;
        };
        let _ = writeln!(h, "<section id=\"model-{stage}\"><h2>Model: {stage}</h2>");
        let rows: Vec<usize> = (0..t.height()).collect();
        rows_table(h, &Shown::of(t, def.schema()?, cols)?, &rows);
        figures(h, page, stage, kept);
        h.push_str("</section>\n");
    }
    Ok(())
}
