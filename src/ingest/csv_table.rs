//! Small CSV tables (manifests, per-fibre spreadsheets) read into a
//! [`Table`]: comma-separated, first row the header, `"…"` quoting with `""`
//! escapes, CRLF or LF, an optional UTF-8 BOM. Each column's type is
//! inferred: `f64` when every non-empty cell is a number, `bool` when every
//! non-empty cell is true/false, `str` otherwise. Empty cells and `-`, `NA`,
//! `NaN` are missing values.

use std::path::Path;

use crate::error::{Error, Location, Result};
use crate::table::{Table, TableBuilder};

/// A data row with its 1-based line number.
pub type NumberedRow = (usize, Vec<String>);

/// Splits one CSV line into fields (quotes removed, `""` → `"`).
pub fn split_line(line: &str) -> Vec<String> {
    super::dialect::split_fields(line, ',')
}

fn is_missing(s: &str) -> bool {
    matches!(s, "" | "-" | "NA" | "N/A" | "NaN" | "nan" | "null")
}

fn parse_bool(s: &str) -> Option<bool> {
    match s.to_ascii_lowercase().as_str() {
        "true" | "yes" => Some(true),
        "false" | "no" => Some(false),
        _ => None,
    }
}

/// Rows of a CSV file: header and cells (trimmed), with their 1-based line
/// numbers. Blank lines are skipped.
pub fn read_rows(path: &Path) -> Result<(Vec<String>, Vec<NumberedRow>)> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    rows_of(path, bytes)
}

/// [`read_rows`] of a file already in memory.
fn rows_of(path: &Path, bytes: Vec<u8>) -> Result<(Vec<String>, Vec<NumberedRow>)> {
    let text = String::from_utf8(bytes).map_err(|e| {
        Error::input(
            Location::file(path),
            format!("not UTF-8 text ({e}); expected a UTF-8 CSV"),
        )
    })?;
    let text = text.strip_prefix('\u{feff}').unwrap_or(&text);
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim_end_matches('\r')))
        .filter(|(_, l)| !l.trim().is_empty());
    let (_, head) = lines
        .next()
        .ok_or_else(|| Error::input(Location::file(path), "empty file; expected a header row"))?;
    let header: Vec<String> = split_line(head)
        .iter()
        .map(|s| s.trim().to_string())
        .collect();
    let mut rows = Vec::new();
    for (no, l) in lines {
        let cells: Vec<String> = split_line(l).iter().map(|s| s.trim().to_string()).collect();
        if cells.len() != header.len() {
            return Err(Error::input(
                Location::line(path, no),
                format!(
                    "{} fields, expected {} as in the header",
                    cells.len(),
                    header.len()
                ),
            ));
        }
        rows.push((no, cells));
    }
    Ok((header, rows))
}

/// Reads a table file: Parquet when the extension is `.parquet`, else CSV
/// with inferred column types ([`read_csv_table`]). Labs keep per-sample
/// tables in spreadsheets; every stage that takes a table accepts both.
pub fn read_table_file(path: &Path) -> Result<Table> {
    if path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("parquet"))
    {
        Ok(Table::read_parquet(path)?.0)
    } else {
        read_csv_table(path)
    }
}

/// Reads a CSV file into a table with inferred column types.
pub fn read_csv_table(path: &Path) -> Result<Table> {
    let bytes = std::fs::read(path).map_err(|e| Error::io(path, e))?;
    csv_table_of(path, bytes)
}

/// [`read_csv_table`] of a file already in memory (`path` names it in
/// errors).
pub fn csv_table_of(path: &Path, bytes: Vec<u8>) -> Result<Table> {
    let (header, rows) = rows_of(path, bytes)?;
    let mut b = TableBuilder::new();
    for (j, name) in header.iter().enumerate() {
        let cells: Vec<&str> = rows.iter().map(|(_, r)| r[j].as_str()).collect();
        let present = || cells.iter().filter(|c| !is_missing(c));
        if present().all(|c| c.parse::<f64>().is_ok()) && present().next().is_some() {
            b = b.f64(
                name,
                cells
                    .iter()
                    .map(|c| (!is_missing(c)).then(|| c.parse().ok()).flatten()),
            );
        } else if present().all(|c| parse_bool(c).is_some()) && present().next().is_some() {
            b = b.bool(name, cells.iter().map(|c| parse_bool(c)));
        } else {
            b = b.str(name, cells.iter().map(|c| (!is_missing(c)).then_some(*c)));
        }
    }
    b.build()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quotes_and_escapes_are_handled() {
        assert_eq!(
            split_line(r#"a,"b,c","d""e",,"#),
            vec!["a", "b,c", "d\"e", "", ""]
        );
    }

    #[test]
    fn column_types_are_inferred() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("t.csv");
        std::fs::write(
            &p,
            "\u{feff}id,x,flag\r\na,1.5,true\r\nb,-,false\r\nc,2,\r\n",
        )
        .unwrap();
        let t = read_csv_table(&p).unwrap();
        assert_eq!(t.str("id").unwrap()[2].as_deref(), Some("c"));
        assert_eq!(t.f64("x").unwrap(), vec![Some(1.5), None, Some(2.0)]);
        assert_eq!(t.bool("flag").unwrap(), vec![Some(true), Some(false), None]);
        std::fs::write(&p, "a,b\n1\n").unwrap();
        let e = read_csv_table(&p).unwrap_err().to_string();
        assert!(
            e.contains("line 2") && e.contains("1 fields, expected 2"),
            "{e}"
        );
    }
}
