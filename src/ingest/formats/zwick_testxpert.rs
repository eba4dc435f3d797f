//! Zwick/Roell testXpert II text export (tab-separated, quoted, German).
//!
//! Layout: a few `"Key"<TAB>"Value"` lines (Prüfvorschrift, Werkstoff, …),
//! a results block opened by `"Ergebnisse:"` — a row of result names
//! (`Nr`, `Probenkennung`, `a0`, `b0`, `S0`, `E`, `Rp0,2`, `Fm`, `Rm`, `A`,
//! …), a row of their units and one row of values per specimen — then the
//! series `"Serie:"<TAB>"Probe 1"` with the channel names (`Standardweg`,
//! `Standardkraft`, `Dehnung`, `Prüfzeit`), a unit row and the samples.
//! Every field is quoted, numbers have decimal commas, the file is usually
//! Windows-1252 with CRLF.
//!
//! The channel block is read by the generic delimited reader. Each value of
//! the first specimen's results row is added to the preamble with the result
//! name as its key and `value unit` as its value, the decimal comma turned
//! into a point (`Rm` = `448.9 MPa`), beside the verbatim lines.

use crate::error::Result;
use crate::ingest::dialect::split_fields;
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The testXpert reader.
pub struct ZwickTestXpert;

fn unquote(field: &str) -> String {
    field.trim().trim_matches('"').trim().to_string()
}

/// The results block: names, units and the first specimen's values.
struct Results {
    names: Vec<String>,
    units: Vec<String>,
    values: Vec<String>,
    /// 1-based line of the values.
    line: usize,
}

fn results_block(text: &Text) -> Option<Results> {
    let lines: Vec<&str> = text.lines().collect();
    let start = lines
        .iter()
        .position(|l| unquote(l).trim_end_matches(':') == "Ergebnisse")?;
    let row = |i: usize| -> Option<Vec<String>> {
        let l = lines.get(i)?;
        (!l.trim().is_empty()).then(|| split_fields(l, '\t').iter().map(|f| unquote(f)).collect())
    };
    Some(Results {
        names: row(start + 1)?,
        units: row(start + 2)?,
        values: row(start + 3)?,
        line: start + 4,
    })
}

/// `448,9` → `448.9`; a value with a letter in it (an id) is kept as is.
fn point_decimal(v: &str) -> String {
    if v.chars().any(|c| c.is_alphabetic()) || !v.contains(',') {
        v.to_string()
    } else {
        v.replace('.', "").replace(',', ".")
    }
}

impl Reader for ZwickTestXpert {
    fn name(&self) -> &'static str {
        "zwick-testxpert"
    }
    fn description(&self) -> &'static str {
        "Zwick testXpert II text export (tab-separated, quoted, German, results block, decimal commas)"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::TensileCurve)
    }
    fn sniff(&self, text: &Text) -> bool {
        let head = text.head(40);
        let tabbed = head.iter().filter(|l| l.contains("\"\t\"")).count() >= 3;
        tabbed
            && (head.iter().any(|l| l.contains("testXpert"))
                || (head.iter().any(|l| unquote(l) == "Ergebnisse:")
                    && head.iter().any(|l| l.starts_with("\"Serie"))))
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, mut preamble, sections) = read_delimited(text, options)?;
        if let Some(Results {
            names,
            units,
            values,
            line,
        }) = results_block(text)
        {
            for (i, name) in names.iter().enumerate() {
                let Some(v) = values.get(i).filter(|v| !v.is_empty()) else {
                    continue;
                };
                let unit = units.get(i).map(String::as_str).unwrap_or("");
                preamble.push(MetaEntry {
                    key: name.clone(),
                    value: format!("{} {unit}", point_decimal(v)).trim().to_string(),
                    line,
                });
            }
        }
        Ok((dialect, preamble, sections))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn decimal_commas_become_points_and_ids_stay() {
        assert_eq!(point_decimal("448,9"), "448.9");
        assert_eq!(point_decimal("8.978,8"), "8978.8");
        assert_eq!(point_decimal("Z-017"), "Z-017");
        assert_eq!(point_decimal("1.5"), "1.5");
    }
}
