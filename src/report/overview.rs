//! The report's first table: every input file of the run (the `files`
//! table), with what became of it and, for a processed file, the statuses
//! of its rows; a set without a `files` table lists the files its tables
//! mention.

use std::collections::BTreeMap;
use std::fmt::Write as _;

use super::figures::texts;
use crate::error::Result;
use crate::plot::escape;
use crate::schema::{Show, TableDef};
use crate::table::Table;

/// One input file as the first table shows it.
pub(super) struct Input {
    pub file: String,
    /// Reader and kind, `format / kind`.
    pub read_as: String,
    /// The stages that took it.
    pub stages: String,
    /// `processed`, `failed`, `companion`, `not_taken`; empty when the set
    /// has no `files` table.
    pub outcome: String,
    pub reason: String,
    pub companion_of: String,
}

/// The inputs of the set's `files` table, else one per file in
/// `mentioned`.
pub(super) fn inputs(
    tables: &BTreeMap<String, Table>,
    defs: &[&'static TableDef],
    mentioned: &[String],
) -> Vec<Input> {
    let files = defs
        .iter()
        .find(|d| d.show == Show::Files)
        .and_then(|d| tables.get(d.name));
    let Some(t) = files else {
        return mentioned
            .iter()
            .map(|f| Input {
                file: f.clone(),
                read_as: String::new(),
                stages: String::new(),
                outcome: String::new(),
                reason: String::new(),
                companion_of: String::new(),
            })
            .collect();
    };
    let col = |c: &str| texts(t, c);
    let (file, format, kind, stages) = (col("source"), col("format"), col("kind"), col("stages"));
    let (outcome, reason, companion) = (col("outcome"), col("reason"), col("companion_of"));
    (0..t.height())
        .map(|i| Input {
            file: file[i].clone(),
            read_as: [&format[i], &kind[i]]
                .iter()
                .filter(|s| !s.is_empty())
                .map(|s| s.as_str())
                .collect::<Vec<_>>()
                .join(" / "),
            stages: stages[i].replace(',', ", "),
            outcome: outcome[i].clone(),
            reason: reason[i].clone(),
            companion_of: companion[i].clone(),
        })
        .collect()
}

/// What the first table says of one input: its row's class and lines.
/// `failed`: its failures; `statuses`: its rows' doubtful statuses.
pub(super) fn status_of(
    input: &Input,
    failed: Option<&Vec<String>>,
    (class, statuses): (&'static str, Vec<String>),
) -> (&'static str, Vec<String>) {
    match (input.outcome.as_str(), failed) {
        ("not_taken", _) => ("skip", vec![format!("not taken: {}", input.reason)]),
        ("companion", _) => ("ok", vec![format!("read with {}", input.companion_of)]),
        (_, Some(m)) => ("err", m.clone()),
        ("failed", None) => ("err", vec![input.reason.clone()]),
        _ if statuses.is_empty() => ("ok", vec!["ok".to_string()]),
        _ => (class, statuses),
    }
}

/// One row of the first table; the file links to its section when it has
/// one.
pub(super) fn row(
    h: &mut String,
    input: &Input,
    class: &str,
    lines: &[String],
    link: Option<&str>,
) {
    let name = match link {
        Some(href) => format!("<a href=\"{href}\">{}</a>", escape(&input.file)),
        None => escape(&input.file),
    };
    let text: Vec<String> = lines.iter().map(|x| escape(x)).collect();
    let _ = writeln!(
        h,
        "<tr class=\"{class}\"><td>{name}</td><td>{}</td><td>{}</td><td class=\"{class}\">{}</td></tr>",
        escape(&input.read_as),
        escape(&input.stages),
        text.join("<br>")
    );
}

/// The counts above the first table.
pub(super) fn counts(inputs: &[Input], failed: usize, warnings: usize) -> Result<String> {
    let not_taken = inputs.iter().filter(|i| i.outcome == "not_taken").count();
    let mut s = format!(
        "{} input files; <span class=\"err\">{failed} failed</span>; ",
        inputs.len()
    );
    if not_taken > 0 {
        let _ = write!(
            s,
            "<span class=\"skip\">{not_taken} taken by no stage</span>; "
        );
    }
    let _ = write!(
        s,
        "<span class=\"warn\">{warnings} result rows with a warning</span>."
    );
    Ok(s)
}
