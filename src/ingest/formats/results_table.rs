//! A table of roughness results (`Ra (Promedio Aritmético),3.066 µm`,
//! `Rq,5.903 µm`, …) that a script or another program computed from a
//! profile: recognised so that it is said to be what it is, and not
//! misread as a profile or a trace. It holds no measurement: reading it is
//! an error that says so, which a pipeline reports as a file that is not
//! data ([`crate::ingest::Reading::NotData`]).
//!
//! Recognised by content: lines of `parameter<delimiter>value` pairs
//! (comma, semicolon or tab; quoted or not; any language for the label
//! after the symbol), at least three of whose parameters are ISO 4287 /
//! 13565 / 25178 symbols (Ra, Rq, Rz, Rsk, Rpk, Mr1, Sa, …) with a value
//! that is a number and an optional unit, and no row of several numbers.

use crate::error::{Error, Result};
use crate::ingest::dialect::{parse_number, split_fields};
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The results-table recogniser.
pub struct ResultsTable;

/// Roughness, waviness, primary-profile and areal parameter symbols.
const SYMBOLS: [&str; 34] = [
    "Ra", "Rq", "Rz", "Rp", "Rv", "Rt", "Rc", "Rsk", "Rku", "RSm", "Rdq", "Rmr", "Rpk", "Rk",
    "Rvk", "Mr1", "Mr2", "R3z", "Pa", "Pq", "Pt", "Pp", "Pv", "Wa", "Wq", "Wt", "Sa", "Sq", "Sz",
    "Sp", "Sv", "Ssk", "Sku", "Sdq",
];

/// How many lines are looked at.
const LINES: usize = 60;

/// A `value` cell: a number, and after it at most a unit (`3.066 µm`).
fn value(cell: &str) -> Option<f64> {
    let mut parts = cell.split_whitespace();
    let v = parts.next().and_then(|n| {
        parse_number(n, '.')
            .or_else(|| parse_number(n, ','))
            .filter(|v| !v.is_nan())
    })?;
    let unit = parts.next();
    (parts.next().is_none() && unit.is_none_or(|u| u.chars().count() <= 4)).then_some(v)
}

/// The parameter symbol a label starts with (`Rz/Rt (Altura Total)` →
/// `Rz`), when it is one.
fn symbol(label: &str) -> Option<&'static str> {
    let head = label
        .trim()
        .split([' ', '(', '/', ',', '_'])
        .next()
        .unwrap_or("");
    SYMBOLS.iter().copied().find(|s| *s == head)
}

/// The (line, symbol, value) of the results among the first lines; `None`
/// when the text is not a results table.
fn results(text: &Text) -> Option<Vec<(usize, &'static str, f64)>> {
    let lines: Vec<(usize, &str)> = text
        .lines()
        .enumerate()
        .take(LINES)
        .filter(|(_, l)| !l.trim().is_empty())
        .collect();
    let delimiter = [',', ';', '\t'].into_iter().max_by_key(|d| {
        lines
            .iter()
            .filter(|(_, l)| split_fields(l, *d).len() == 2)
            .count()
    })?;
    let mut found = Vec::new();
    for (i, l) in &lines {
        let cells = split_fields(l, delimiter);
        let numbers = cells
            .iter()
            .filter(|c| parse_number(c, '.').is_some_and(|v| !v.is_nan()));
        if cells.len() > 2 || numbers.count() >= 2 {
            return None; // a row of a table, not a label and its value
        }
        if let [label, v] = &cells[..] {
            if let (Some(s), Some(v)) = (symbol(label), value(v)) {
                found.push((i + 1, s, v));
            }
        }
    }
    (found.len() >= 3).then_some(found)
}

impl Reader for ResultsTable {
    fn name(&self) -> &'static str {
        "results-table"
    }
    fn description(&self) -> &'static str {
        "a table of roughness results (Ra, Rq, Rz, … with their values and units), computed elsewhere from a profile: recognised, and said not to be data"
    }
    fn sniff(&self, text: &Text) -> bool {
        results(text).is_some()
    }
    fn read(
        &self,
        text: &Text,
        _options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let found = results(text).unwrap_or_default();
        let listed: Vec<String> = found
            .iter()
            .take(3)
            .map(|(_, s, v)| format!("{s} = {v}"))
            .collect();
        let line = found.first().map_or(1, |f| f.0);
        Err(Error::input(
            text.at(line),
            format!(
                "a table of roughness results ({}, …: {} parameters), computed from a profile \
                 elsewhere, not a profile or a trace: tribo computes them from the profile itself",
                listed.join(", "),
                found.len()
            ),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    fn text(s: &str) -> Text<'_> {
        Text::decode(Path::new("r.csv"), s.as_bytes()).unwrap()
    }

    /// The script's results table (BOM, Spanish labels, `µm` values, a
    /// second block with quoted labels) is recognised; a profile, a trace
    /// and a key/value preamble are not.
    #[test]
    fn results_tables_and_others() {
        let r = "\u{feff}Parámetro,Valor\nRa (Promedio Aritmético),3.066 µm\nRq (RMS),5.903 µm\n\
                 Rz/Rt (Altura Total),35.612 µm\nRsk (Asimetría),-0.292\n\n\
                 \"Rpk (ISO 13565-2, 16610)\",0.410 µm\nFuente filtrado,primary\n";
        let t = text(r);
        let found = results(&t).unwrap();
        assert_eq!(found[0], (2, "Ra", 3.066));
        assert_eq!(found.len(), 5);
        let e = ResultsTable
            .read(&t, &IngestOptions::default())
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2") && e.contains("Ra = 3.066"), "{e}");
        for other in [
            "x,z\n0,1\n1,2\n2,3\n",
            "Ra,1.0\nRq,2.0\nTime (s),Fx (N)\n0,1\n1,2\n",
            "Sample,A\nLoad,5 N\nSpeed,10 mm/s\n",
        ] {
            assert!(results(&text(other)).is_none(), "{other}");
        }
    }
}
