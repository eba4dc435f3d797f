//! Zwick/Roell testXpert text export (tab-separated, quoted, German or
//! English).
//!
//! testXpert writes its export from a user-edited template, so the family
//! has two layouts, both read here:
//!
//! - **parameter lines**: one `"key"<TAB>value<TAB>"unit"` line per result
//!   or specimen parameter (`"E-Modul"  1127.12  "N/mm²"`, `"Probenbreite
//!   b0"  11.4  "mm"`, `"Messlänge"  "nicht bekannt"` when unknown), then a
//!   quoted header row and a unit row (`"Prüfzeit" "Standardweg"
//!   "Standardkraft" "Dehnung"` / `"s" "mm" "N" "%"`) and the samples
//!   (the real export `Mat-O-Lab/CSVToCSVW examples/example.csv`);
//! - **results table**: a few `"Key"<TAB>"Value"` lines, then a results
//!   block opened by `"Ergebnisse:"` — a row of result names (`Nr`,
//!   `Probenkennung`, `a0`, `b0`, `S0`, `E`, `Rp0,2`, `Fm`, `Rm`, …), a row
//!   of their units and one row of values per specimen — then the series
//!   `"Serie:"<TAB>"Probe 1"` with the channel names, a unit row and the
//!   samples.
//!
//! Numbers may have decimal commas (German locale) or points; the file is
//! usually ISO-8859-1/Windows-1252 with CRLF or LF. The channel block is
//! read by the generic block engine. Every parameter line and every value
//! of the first specimen's results row is kept in the preamble with its key
//! as written and `value unit` as the value, the decimal comma turned into
//! a point (`E-Modul` = `1127.12 N/mm²`, `Rm` = `448.9 MPa`); an unknown
//! value (`nicht bekannt`, `unknown`) is kept as written, so it never reads
//! as a number.

use crate::error::Result;
use crate::ingest::dialect::{parse_number, split_fields};
use crate::ingest::formats::delimited::read_delimited_rekeyed;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The testXpert reader.
pub struct ZwickTestXpert;

/// Channel names testXpert gives its standard channels (German and
/// English exports), lower-cased.
const CHANNELS: [&str; 12] = [
    "standardkraft",
    "standardweg",
    "prüfzeit",
    "traverse",
    "dehnung",
    "nominelle dehnung",
    "standard force",
    "standard travel",
    "test time",
    "crosshead",
    "grip to grip separation",
    "nominal strain",
];

fn unquote(field: &str) -> String {
    field.trim().trim_matches('"').trim().to_string()
}

/// A parameter line `"key"<TAB>value[<TAB>"unit"]`: the key quoted and not
/// a number, the value a number (either decimal mark) or quoted text, at
/// most three fields. Returns (key, value, unit).
fn parameter_line(line: &str) -> Option<(String, String, String)> {
    let fields = split_fields(line, '\t');
    if !(2..=3).contains(&fields.len()) || !line.trim_start().starts_with('"') {
        return None;
    }
    let key = unquote(&fields[0]);
    let value = unquote(&fields[1]);
    let numeric = |s: &str| {
        parse_number(s, '.')
            .or_else(|| parse_number(s, ','))
            .is_some()
    };
    if key.is_empty() || numeric(&key) || value.is_empty() {
        return None;
    }
    let unit = fields.get(2).map(|u| unquote(u)).unwrap_or_default();
    Some((key, point_decimal(&value), unit))
}

/// Whether a line is a quoted header row naming testXpert's channels.
fn is_channel_header(line: &str) -> bool {
    let fields = split_fields(line, '\t');
    fields.len() >= 2
        && fields
            .iter()
            .any(|f| CHANNELS.contains(&unquote(f).to_lowercase().as_str()))
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

/// `448,9` → `448.9`, `8.978,8` → `8978.8`; a value with a letter in it
/// (an id, `nicht bekannt`, `1.5e-3` stays as is when it has no comma).
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
        "Zwick testXpert text export (tab-separated, quoted; parameter lines or a results table, then channels with a unit row; German or English, either decimal mark)"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::TensileCurve)
    }
    fn sniff(&self, text: &Text) -> bool {
        let head = text.head(60);
        // The banner is a field of its own (`"testXpert II"<TAB>…`), not
        // the word in prose (a README that names the software).
        let banner = head
            .iter()
            .any(|l| unquote(l.split(['\t', ';']).next().unwrap_or("")).starts_with("testXpert"));
        let results_table = head.iter().any(|l| unquote(l) == "Ergebnisse:")
            && head.iter().any(|l| l.starts_with("\"Serie"));
        let parameters = head.iter().filter(|l| parameter_line(l).is_some()).count();
        let header = head.iter().any(|l| is_channel_header(l));
        banner || results_table || (parameters >= 3 && header)
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, mut preamble, sections) =
            read_delimited_rekeyed(text, options, |line, m| {
                if let Some((key, value, unit)) = parameter_line(line) {
                    m.key = key;
                    m.value = format!("{value} {unit}").trim().to_string();
                }
                Ok(())
            })?;
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

    #[test]
    fn parameter_lines_split_into_key_value_unit() {
        let p = |l: &str| parameter_line(l).unwrap();
        assert_eq!(
            p("\"E-Modul\"\t1127.12\t\"N/mm²\""),
            ("E-Modul".into(), "1127.12".into(), "N/mm²".into())
        );
        assert_eq!(
            p("\"E-Modul\"\t1127,12\t\"N/mm²\""),
            ("E-Modul".into(), "1127.12".into(), "N/mm²".into())
        );
        assert_eq!(
            p("\"Messlänge\"\t\"nicht bekannt\""),
            ("Messlänge".into(), "nicht bekannt".into(), "".into())
        );
        assert_eq!(parameter_line("0.02\t6.89e-005\t0.218"), None);
        assert_eq!(parameter_line("\"s\"\t\"mm\"\t\"N\"\t\"%\""), None);
        assert!(is_channel_header(
            "\"Prüfzeit\"\t\"Standardweg\"\t\"Standardkraft\""
        ));
        assert!(is_channel_header("\"Test time\"\t\"Standard force\""));
        assert!(!is_channel_header("\"Time\"\t\"Load\""));
    }
}
