//! MTS 793 / MultiPurpose TestWare (MPT) text export, any locale.
//!
//! Layout (the real export `Mat-O-Lab/CSVToCSVW examples/example4.csv`, a
//! German concrete-cylinder compression test):
//!
//! ```text
//! MTS793|MPT|DEU|x|x|,|.|:|49|1|1|A          banner: language, decimal mark, thousands, time separator
//!
//! Bediener Information<TAB>…<TAB>Zeit:<TAB>78,494141<TAB>s<TAB>22.07.2014 07:20:41
//! Probenbezeichnung :<TAB>Maack X.x Drucklversuch Probe 11 B
//! Durchmesser :<TAB>100,1                     operator entries, no units
//! Bediener Information Ende
//!
//! Datenerfassung<TAB>…<TAB>Zeit:<TAB>544,35547<TAB>s<TAB>…   one acquisition (a section)
//! Datum<TAB>Laufzeit<TAB>Ch 1 Kraft Sollwert<TAB>Ch 1 Kraft<TAB>Ch 1 Weg<TAB>…
//! d<TAB>s<TAB>kN<TAB>kN<TAB>mm<TAB>…          unit row
//! 41842<TAB>79,004883<TAB>-1,2784081<TAB>…
//! ```
//!
//! The banner states the decimal mark (field 6) and thousands separator
//! (field 7): they are taken from it, not sniffed. Each acquisition block
//! (`Datenerfassung`, `Data Acquisition`: whatever its title, a line above
//! a name row, a unit row and numeric rows) is a section named after its
//! title; the lines outside the blocks are the preamble, `key : value` or
//! `key<TAB>value` with the colon dropped (`Durchmesser` = `100,1`, as
//! written: the operator's entries carry no unit).

use crate::error::{Error, Result};
use crate::ingest::columns::{parse_block, RowShape};
use crate::ingest::dialect::{parse_line, split_fields};
use crate::ingest::{Channel, Dialect, IngestOptions, MetaEntry, Reader, Section, Text};
use crate::units::parse_unit;

/// The MTS 793 reader.
pub struct Mts793;

/// The banner's fields, when line 1 is an MTS 793 banner.
fn banner(text: &Text) -> Option<Vec<String>> {
    let first = text.head(1).first()?.trim().to_string();
    let fields: Vec<String> = first.split('|').map(|f| f.trim().to_string()).collect();
    (fields.len() >= 7 && fields[0].to_ascii_uppercase().starts_with("MTS")).then_some(fields)
}

/// The decimal mark the banner states (`,` or `.`), else sniffed from the
/// data rows.
fn decimal_mark(text: &Text, options: &IngestOptions) -> char {
    let stated = banner(text).and_then(|b| b[5].chars().next());
    options
        .decimal
        .or(stated.filter(|c| matches!(c, ',' | '.')))
        .unwrap_or_else(|| crate::ingest::dialect::sniff(text.lines()).1)
}

/// A metadata line as key and value: `Masse :<TAB>5646,2`,
/// `Bemerkungen<TAB>Kraftgeregelt 3,9 kN/s`; a title line keeps its fields
/// after the first as the value.
fn meta(line: &str, number: usize) -> Option<MetaEntry> {
    let fields: Vec<String> = split_fields(line, '\t')
        .iter()
        .map(|f| f.trim().to_string())
        .filter(|f| !f.is_empty())
        .collect();
    let (key, rest) = fields.split_first()?;
    Some(MetaEntry {
        key: key.trim_end_matches(':').trim().to_string(),
        value: rest.join(" "),
        line: number,
    })
}

/// Whether a row is the unit row: most of its cells are units tribo knows
/// (the date column's `d` is not one).
fn unit_row(cells: &[String]) -> bool {
    let filled: Vec<&String> = cells.iter().filter(|c| !c.trim().is_empty()).collect();
    let known = filled.iter().filter(|c| parse_unit(c).is_some()).count();
    !filled.is_empty() && 2 * known >= filled.len()
}

/// The acquisition blocks: for each, the 0-based lines of its first row and
/// of the line after its last (the name and unit rows are the two above).
fn blocks(text: &Text, decimal: char) -> Vec<(usize, usize)> {
    let n = text.line_count();
    let numeric = |i: usize| {
        i < n && matches!(parse_line(text.line(i), '\t', decimal), (Some(r), _) if !r.is_empty())
    };
    let mut out = Vec::new();
    let mut i = 2;
    while i < n {
        let units = split_fields(text.line(i - 1), '\t');
        if numeric(i) && !numeric(i - 1) && !numeric(i - 2) && unit_row(&units) {
            let mut end = i;
            while numeric(end) {
                end += 1;
            }
            out.push((i, end));
            i = end;
        }
        i += 1;
    }
    out
}

impl Reader for Mts793 {
    fn name(&self) -> &'static str {
        "mts-793"
    }
    fn description(&self) -> &'static str {
        "MTS 793 / MultiPurpose TestWare text export (banner with the locale's decimal mark, operator entries, acquisition blocks with a unit row)"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::TensileCurve)
    }
    fn sniff(&self, text: &Text) -> bool {
        banner(text).is_some_and(|b| b[0].to_ascii_uppercase().starts_with("MTS79"))
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let decimal = decimal_mark(text, options);
        let mut preamble = Vec::new();
        let mut sections = Vec::new();
        let mut used = 0;
        for (start, end) in blocks(text, decimal) {
            let names = split_fields(text.line(start - 2), '\t');
            let units = split_fields(text.line(start - 1), '\t');
            let width = names
                .iter()
                .rposition(|c| !c.trim().is_empty())
                .map_or(0, |k| k + 1);
            let shape = RowShape {
                delimiter: '\t',
                decimal,
                width,
            };
            let (columns, stop) = parse_block(text, start, shape);
            if stop < end {
                return Err(Error::input(
                    text.at(stop + 1),
                    format!("expected {width} numbers as named on line {}", start - 1),
                ));
            }
            let title = start.checked_sub(3).and_then(|t| meta(text.line(t), t + 1));
            let top = title.as_ref().map_or(start - 2, |t| t.line - 1);
            let lines: Vec<MetaEntry> = (used..top)
                .filter_map(|j| meta(text.line(j), j + 1))
                .collect();
            preamble.extend(lines);
            let channels = columns
                .into_iter()
                .enumerate()
                .map(|(k, values)| Channel {
                    name: names.get(k).map_or(String::new(), |s| s.trim().to_string()),
                    raw_unit: units.get(k).map_or(String::new(), |s| s.trim().to_string()),
                    values,
                })
                .collect();
            sections.push(Section {
                name: match &title {
                    Some(t) => format!("{} {}", t.key, sections.len() + 1),
                    None => (sections.len() + 1).to_string(),
                },
                metadata: title.into_iter().collect(),
                header_line: Some(start - 1),
                first_data_line: start + 1,
                channels,
            });
            used = end;
        }
        if sections.is_empty() {
            return Err(Error::input(
                text.at(1),
                "MTS 793 export without an acquisition block (a name row, a unit row and numeric rows)",
            ));
        }
        preamble.extend((used..text.line_count()).filter_map(|j| meta(text.line(j), j + 1)));
        let dialect = Dialect {
            encoding: text.encoding,
            line_ending: text.line_ending,
            delimiter: '\t',
            decimal,
            quoted: false,
        };
        Ok((dialect, preamble, sections))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn operator_entries_lose_their_colon() {
        let m = meta("Durchmesser :\t100,1", 9).unwrap();
        assert_eq!((m.key.as_str(), m.value.as_str()), ("Durchmesser", "100,1"));
        let m = meta("Bemerkungen\tKraftgeregelt 3,9 kN/s", 7).unwrap();
        assert_eq!(m.value, "Kraftgeregelt 3,9 kN/s");
        assert_eq!(meta("\t\t", 1), None);
    }
}
