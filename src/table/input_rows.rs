//! The rows a result is computed from (a fit's points, a group's
//! members), named for people and with the warnings of their own
//! statuses: a result over doubtful rows says so (`doubtful_points`,
//! [`Status::inherit`]).
//!
//! [`Status::inherit`]: crate::status::Status::inherit

use super::status_columns::STATUS_COLUMNS;
use super::{ColumnType, Table};
use crate::error::Result;
use crate::status::{Code, InputRow};

impl Table {
    /// Each row as an input of a result computed from the table: its label
    /// and its warnings (none for a table without statuses, one written by
    /// hand). The label is the file's name (from `source`), with the
    /// section when a file has several, and the stroke or step within it;
    /// a table without `source` names the row by its place.
    pub fn input_rows(&self) -> Result<Vec<InputRow>> {
        input_rows(self)
    }
}

/// Each row's warnings ([`Code::is_doubt`], in the order found).
fn row_warnings(t: &Table) -> Result<Vec<Vec<Code>>> {
    if t.column_type(STATUS_COLUMNS[1]) != Some(ColumnType::StrList) {
        return Ok(vec![Vec::new(); t.height()]);
    }
    Ok(t.status_codes()?
        .into_iter()
        .map(|codes| codes.into_iter().filter(|c| c.is_doubt()).collect())
        .collect())
}

fn input_rows(t: &Table) -> Result<Vec<InputRow>> {
    let text = |name: &str| -> Result<Option<Vec<Option<String>>>> {
        match t.column_type(name) {
            Some(ColumnType::Str | ColumnType::Cat) => t.str(name).map(Some),
            _ => Ok(None),
        }
    };
    let (source, section) = (text("source")?, text("section")?);
    let within = ["stroke", "step"]
        .into_iter()
        .find(|c| t.column_type(c) == Some(ColumnType::I64))
        .map(|c| t.i64(c).map(|v| (c, v)))
        .transpose()?;
    let warnings = row_warnings(t)?;
    Ok(warnings
        .into_iter()
        .enumerate()
        .map(|(i, codes)| {
            let cell = |c: &Option<Vec<Option<String>>>| c.as_ref().and_then(|c| c[i].clone());
            let mut label = match cell(&source) {
                Some(s) => s.rsplit(['/', '\\']).next().unwrap_or(&s).to_string(),
                None => format!("row {}", i + 1),
            };
            if let Some(s) = cell(&section).filter(|s| s != "1") {
                label.push_str(&format!(" section {s}"));
            }
            if let Some((name, Some(k))) = within.as_ref().map(|(n, v)| (n, v[i])) {
                label.push_str(&format!(" {name} {k}"));
            }
            InputRow { label, codes }
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use crate::status::{Code, Status};
    use crate::table::TableBuilder;

    /// Labels name the file, a section other than the first, and the
    /// stroke; only warnings are kept (an info code is not a doubt).
    #[test]
    fn rows_are_named_by_file_section_and_stroke_with_their_warnings() {
        let statuses = [
            Status::of(Code::StaticBelowDynamic, "μ_s < μ_d"),
            Status::ok(),
            Status::of(Code::LoadRamp, "ramp"),
        ];
        let t = TableBuilder::new()
            .str(
                "source",
                [Some("lab/a.csv"), Some("lab\\b.csv"), Some("c.csv")],
            )
            .str("section", [Some("1"), Some("Step 2"), Some("1")])
            .i64("stroke", [Some(1), Some(3), None])
            .status(statuses.iter())
            .build()
            .unwrap();
        let rows = t.input_rows().unwrap();
        let labels: Vec<&str> = rows.iter().map(|r| r.label.as_str()).collect();
        assert_eq!(
            labels,
            ["a.csv stroke 1", "b.csv section Step 2 stroke 3", "c.csv"]
        );
        let codes: Vec<&[Code]> = rows.iter().map(|r| r.codes.as_slice()).collect();
        assert_eq!(codes, [&[Code::StaticBelowDynamic][..], &[], &[]]);
    }

    /// A table written by hand (no statuses, no source) names rows by place.
    #[test]
    fn a_table_without_statuses_has_no_doubts() {
        let t = TableBuilder::new()
            .f64_values("normal_force_N", [1.0, 2.0])
            .build()
            .unwrap();
        let rows = t.input_rows().unwrap();
        assert_eq!(rows[1].label, "row 2");
        assert!(rows.iter().all(|r| r.codes.is_empty()));
    }
}
