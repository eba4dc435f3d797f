//! Instron (Bluehill) tensile CSV with a `PARAMETER;INFO` block, as the
//! Soft Robotics Materials Database exports its Instron 5569 tests.
//!
//! Layout: a first line `PARAMETER;INFO;URL` (or `PARAMETER;INFO;;;`), one
//! line per parameter with its unit in the name (`Specimen Thickness
//! (mm);3`, `Specimen Cross-section (cm^2);0.18`, `Standard;ASTM D412`,
//! `Machine;Instron  5569`), a spacer of empty fields (`;;;;`), the channel
//! names with units in parentheses (`Time (s);True Strain;True Stress
//! (MPa);Engineering Strain;Engineering Stress (MPa)`) and the samples.
//! The delimiter is sniffed (semicolon in the real files, comma or tab in
//! others of the family).
//!
//! Each parameter is kept with its name as the key and `value unit` as the
//! value (`Specimen Cross-section` = `0.18 cm^2`).
//!
//! The strain columns carry no unit. The file says which it is by its own
//! redundancy: true strain is ln(1 + engineering strain) row by row, which
//! holds for fractions and not for percent (or the other way round); the
//! unit that makes it hold is given to both columns, with a
//! `tribo.strain_unit` entry saying why. Without both columns the unit
//! stays empty (the user states it in `[ingest] units`).

use crate::error::Result;
use crate::ingest::dialect::split_fields;
use crate::ingest::formats::delimited::read_delimited_rekeyed;
use crate::ingest::header::split_name_unit;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The `PARAMETER;INFO` reader.
pub struct InstronParameters;

/// The delimiter of a `PARAMETER<d>INFO` first line.
fn opening(text: &Text) -> Option<char> {
    let first = text.head(1).first()?.trim().to_uppercase();
    [';', ',', '\t'].into_iter().find(|&d| {
        let f = split_fields(&first, d);
        f.len() >= 2 && f[0].trim() == "PARAMETER" && f[1].trim() == "INFO"
    })
}

impl Reader for InstronParameters {
    fn name(&self) -> &'static str {
        "instron-parameters"
    }
    fn description(&self) -> &'static str {
        "Instron tensile CSV with a PARAMETER;INFO block (units in the names, section in cm^2), then channels with units in parentheses"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::TensileCurve)
    }
    fn sniff(&self, text: &Text) -> bool {
        opening(text).is_some()
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let delimiter = opening(text).unwrap_or(';');
        let (dialect, mut preamble, mut sections) =
            read_delimited_rekeyed(text, options, |line, m| {
                let fields = split_fields(line, delimiter);
                let (name, unit) = split_name_unit(fields.first().map_or("", |f| f.trim()));
                let value = fields.get(1).map_or("", |f| f.trim());
                m.key = name;
                m.value = format!("{value} {unit}").trim().to_string();
                Ok(())
            })?;
        preamble.retain(|m| !m.key.is_empty());
        for s in &mut sections {
            if let Some(note) = strain_unit(s) {
                preamble.push(note);
            }
        }
        Ok((dialect, preamble, sections))
    }
}

/// Gives the unitless true and engineering strain columns of a section the
/// unit under which true = ln(1 + engineering) holds on every row with an
/// engineering strain above 1 % of its largest (within 1e-3 relative, the
/// files' 5–9 significant digits); the note says so.
fn strain_unit(s: &mut Section) -> Option<MetaEntry> {
    let find = |word: &str| {
        s.channels.iter().position(|c| {
            let n = c.name.to_lowercase();
            n.contains("strain") && n.contains(word) && c.raw_unit.is_empty()
        })
    };
    let (e, t) = (find("engineering")?, find("true")?);
    let (eng, tru) = (&s.channels[e].values, &s.channels[t].values);
    let top = eng.iter().copied().fold(0.0_f64, |a, v| a.max(v.abs()));
    let holds = |scale: f64| {
        let mut n = 0;
        let all = eng.iter().zip(tru).all(|(&e, &t)| {
            if !(e.is_finite() && t.is_finite()) || e.abs() <= 0.01 * top {
                return true;
            }
            n += 1;
            let expected = (1.0 + e * scale).ln() / scale;
            (t - expected).abs() <= 1e-3 * expected.abs()
        });
        all && n >= 3
    };
    let unit = [(1.0, "mm/mm"), (0.01, "%")]
        .into_iter()
        .find(|(scale, _)| holds(*scale))?
        .1;
    let names = format!("'{}' and '{}'", s.channels[e].name, s.channels[t].name);
    s.channels[e].raw_unit = unit.into();
    s.channels[t].raw_unit = unit.into();
    Some(MetaEntry {
        key: "tribo.strain_unit".into(),
        value: format!(
            "{names} have no unit: read as {unit}, under which true = ln(1 + engineering) on every row"
        ),
        line: s.header_line.unwrap_or(s.first_data_line),
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn the_strain_unit_follows_from_true_against_engineering() {
        let section = |eng: Vec<f64>, tru: Vec<f64>| Section {
            name: "1".into(),
            metadata: vec![],
            header_line: Some(1),
            first_data_line: 2,
            channels: vec![
                crate::ingest::Channel {
                    name: "True Strain".into(),
                    raw_unit: String::new(),
                    values: tru,
                },
                crate::ingest::Channel {
                    name: "Engineering Strain".into(),
                    raw_unit: String::new(),
                    values: eng,
                },
            ],
        };
        let eng: Vec<f64> = (1..50).map(|i| i as f64 * 0.2).collect();
        let mut s = section(eng.clone(), eng.iter().map(|e| (1.0 + e).ln()).collect());
        assert!(strain_unit(&mut s).is_some());
        assert_eq!(s.channels[0].raw_unit, "mm/mm");
        let pct: Vec<f64> = eng.iter().map(|e| e * 100.0).collect();
        let mut s = section(
            pct.clone(),
            pct.iter().map(|e| 100.0 * (1.0 + e / 100.0).ln()).collect(),
        );
        strain_unit(&mut s).unwrap();
        assert_eq!(s.channels[1].raw_unit, "%");
        // unrelated columns: no unit is invented
        let mut s = section(eng.clone(), eng.clone());
        assert_eq!(strain_unit(&mut s), None);
        assert_eq!(s.channels[0].raw_unit, "");
    }

    #[test]
    fn the_opening_line_names_the_delimiter() {
        let t = |s: &'static str| Text::decode(Path::new("x.csv"), s.as_bytes()).unwrap();
        assert_eq!(opening(&t("PARAMETER;INFO;URL;;\n1;2\n")), Some(';'));
        assert_eq!(opening(&t("Parameter,Info\n1,2\n")), Some(','));
        assert_eq!(opening(&t("Time;Load\n1;2\n")), None);
    }
}
