//! A row's status as a table holds it: three columns, written and read
//! here only (`docs/statuses.md`). `status` is a dictionary column of the
//! most severe code or `ok` (so that `value_counts()` or `GROUP BY status`
//! gives one line per code), `status_codes` the list of every code of the
//! row, and `status_detail` the codes with their details and numbers.

use super::{Table, TableBuilder};
use crate::error::{Error, Result};
use crate::status::{Code, Status};

/// The names of the three status columns, in table order.
pub const STATUS_COLUMNS: [&str; 3] = ["status", "status_codes", "status_detail"];

impl TableBuilder {
    /// The rows' statuses as the columns `status`, `status_codes` and
    /// `status_detail` (a schema's `type = "status"` entry).
    pub fn status<'a>(self, statuses: impl IntoIterator<Item = &'a Status>) -> Self {
        let statuses: Vec<&Status> = statuses.into_iter().collect();
        let mut runs: Vec<(Option<&str>, usize)> = Vec::new();
        for s in &statuses {
            match runs.last_mut() {
                Some((Some(c), n)) if *c == s.cell() => *n += 1,
                _ => runs.push((Some(s.cell()), 1)),
            }
        }
        self.cat_runs(STATUS_COLUMNS[0], runs)
            .str_list(
                STATUS_COLUMNS[1],
                statuses
                    .iter()
                    .map(|s| s.codes().into_iter().map(Code::as_str)),
            )
            .str(STATUS_COLUMNS[2], statuses.iter().map(|s| s.detail()))
    }
}

impl Table {
    /// Each row's codes, from `status_codes`. A code this version does not
    /// know is an error naming it.
    pub fn status_codes(&self) -> Result<Vec<Vec<Code>>> {
        self.fold_status_codes(Vec::new(), |codes, c| codes.push(c))
    }

    /// Each row's codes folded by `f` from `init` ([`Table::status_codes`]
    /// without a list per row).
    pub fn fold_status_codes<T: Clone>(
        &self,
        init: T,
        mut f: impl FnMut(&mut T, Code),
    ) -> Result<Vec<T>> {
        self.str_list_fold(STATUS_COLUMNS[1], init, |acc, c| {
            let code = Code::parse(c).ok_or_else(|| {
                Error::Table(format!("unknown status code '{c}' in status_codes"))
            })?;
            f(acc, code);
            Ok(())
        })
    }

    /// How many rows have no result: a code of theirs says so.
    pub fn rows_without_result(&self) -> Result<usize> {
        Ok(self
            .status_codes()?
            .iter()
            .filter(|codes| codes.iter().any(|c| !c.has_result()))
            .count())
    }

    /// Each row's status, from `status_codes` and `status_detail`.
    pub fn statuses(&self) -> Result<Vec<Status>> {
        let detail = self.str(STATUS_COLUMNS[2])?;
        Ok(self
            .status_codes()?
            .iter()
            .zip(detail)
            .map(|(codes, d)| Status::from_cells(codes, d.as_deref()))
            .collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The three columns hold the worst code (a dictionary), every code
    /// and the detail; written to Parquet and read back they give the
    /// statuses again.
    #[test]
    fn status_columns_round_trip_through_parquet() {
        let mut doubtful = Status::of(Code::PeakAtStart, "t = 0.01 s");
        doubtful.push(Code::NoNormalForce, "no column; no manifest value");
        let rows = [Status::ok(), doubtful.clone(), Status::ok()];
        let t = TableBuilder::new()
            .i64("n", [Some(1), Some(2), Some(3)])
            .status(&rows)
            .build()
            .unwrap();
        assert_eq!(t.column_type("status"), Some(super::super::ColumnType::Cat));
        let status = t.str("status").unwrap();
        assert_eq!(
            status,
            [Some("ok"), Some("no_normal_force"), Some("ok")].map(|s| s.map(String::from))
        );
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("t.parquet");
        t.write_parquet_to(std::fs::File::create(&path).unwrap(), &[])
            .unwrap();
        let (back, _) = Table::read_parquet(&path).unwrap();
        assert_eq!(
            back.column_names(),
            ["n", "status", "status_codes", "status_detail"]
        );
        assert_eq!(
            back.str_list("status_codes").unwrap()[1],
            Some(vec![
                "peak_at_start".to_string(),
                "no_normal_force".to_string()
            ])
        );
        assert_eq!(back.str_list("status_codes").unwrap()[0], Some(vec![]));
        assert_eq!(back.statuses().unwrap(), rows);
        let joined = Table::concat([back.clone(), back]).unwrap().unwrap();
        assert_eq!(joined.statuses().unwrap().len(), 6);
    }

    #[test]
    fn codes_are_folded_in_place_and_an_unknown_one_is_an_error_naming_it() {
        let rows = [
            vec!["peak_at_start", "no_normal_force"],
            vec![],
            vec!["nonsense"],
        ];
        let t = TableBuilder::new()
            .str_list("status_codes", rows.clone())
            .build()
            .unwrap();
        let e = t.status_codes().unwrap_err().to_string();
        assert!(e.contains("unknown status code 'nonsense'"), "{e}");
        let known = TableBuilder::new()
            .str_list("status_codes", rows[..2].to_vec())
            .build()
            .unwrap();
        let counts = known.fold_status_codes(0, |n, _| *n += 1).unwrap();
        assert_eq!(counts, [2, 0]);
        assert_eq!(
            known.status_codes().unwrap(),
            [vec![Code::PeakAtStart, Code::NoNormalForce], vec![]]
        );
    }
}
