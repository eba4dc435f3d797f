//! Bruker Dektak stylus profilometer CSV export.
//!
//! Layout: a "Scan Parameters" block (scan type, stylus, length, duration,
//! resolution, force, range, cursor positions), an "Analytical Results"
//! block (`Function,R.Cur Pos,R.Cur Width,M.Cur Pos,M.Cur Width,Result`: the
//! instrument's own Ra, Rq, Skew, … between the cursors), then "Scan Data"
//! with the header `Lateral um,Raw Micrometer` and rows `x,z,,`. Latin-1
//! encoded (the micro sign is byte 0xB5). Lateral positions are printed with
//! one decimal while the step is 0.156 µm, so they look slightly non-uniform.
//!
//! The reader keeps both blocks verbatim in the preamble and names the
//! channels `Lateral` (um) and `Raw` (um). [`analytical_results`] parses the
//! results block into SI numbers.

use crate::error::Result;
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};
use crate::units::parse_unit;

/// The Dektak reader.
pub struct Dektak;

impl Reader for Dektak {
    fn name(&self) -> &'static str {
        "dektak"
    }
    fn description(&self) -> &'static str {
        "Bruker Dektak stylus profilometer CSV (Scan Parameters, Analytical Results, Lateral um / Raw Micrometer)"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::Profile)
    }
    fn sniff(&self, text: &Text) -> bool {
        text.head(1)
            .first()
            .is_some_and(|l| l.trim().starts_with("Scan Parameters"))
            && text
                .lines()
                .take(200)
                .any(|l| l.trim_start().starts_with("Lateral"))
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, preamble, mut sections) = read_delimited(text, options)?;
        for s in &mut sections {
            for c in &mut s.channels {
                // "Lateral um", "Raw Micrometer": the unit is the last word.
                if c.raw_unit.is_empty() {
                    if let Some((name, unit)) = c.name.rsplit_once(' ') {
                        if parse_unit(unit).is_some() {
                            let (n, u) = (name.trim().to_string(), unit.trim().to_string());
                            c.name = n;
                            c.raw_unit = u;
                        }
                    }
                }
            }
        }
        Ok((dialect, preamble, sections))
    }
}

/// One line of the Dektak "Analytical Results" block, in SI.
#[derive(Debug, Clone, PartialEq)]
pub struct DektakResult {
    /// The function (`Ra`, `Rq`, `Skew`, …).
    pub function: String,
    /// R cursor position (m).
    pub r_cursor: f64,
    /// M cursor position (m).
    pub m_cursor: f64,
    /// The result, in SI when it has a length unit (m), else as printed.
    pub value: f64,
    /// The unit printed with the result (empty when dimensionless).
    pub raw_unit: String,
}

fn value_with_unit(s: &str) -> Option<(f64, String)> {
    let s = s.trim();
    let (num, unit) = s.split_once(' ').unwrap_or((s, ""));
    let v: f64 = num.trim().parse().ok()?;
    let unit = unit.trim();
    if unit.is_empty() {
        return Some((v, String::new()));
    }
    let u = parse_unit(unit)?;
    Some((u.to_si(v), unit.to_string()))
}

/// Parses the "Analytical Results" lines of a Dektak preamble (the entries
/// after the `Function` header line whose value has five comma-separated
/// fields). Lines that do not parse are skipped.
pub fn analytical_results(preamble: &[MetaEntry]) -> Vec<DektakResult> {
    let Some(start) = preamble.iter().position(|m| m.key == "Function") else {
        return Vec::new();
    };
    preamble[start + 1..]
        .iter()
        .filter_map(|m| {
            let f: Vec<&str> = m.value.split(',').collect();
            if f.len() != 5 {
                return None;
            }
            let (r, _) = value_with_unit(f[0])?;
            let (mc, _) = value_with_unit(f[2])?;
            let (value, raw_unit) = value_with_unit(f[4])?;
            Some(DektakResult {
                function: m.key.clone(),
                r_cursor: r,
                m_cursor: mc,
                value,
                raw_unit,
            })
        })
        .collect()
}
