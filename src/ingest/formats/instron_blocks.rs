//! Instron (Bluehill 2) raw-data CSV with a metadata block.
//!
//! Layout: header lines of up to four parts, `Type : Name,value,unit`, where
//! the type is the block (`General`, `Specimen`, `Results`, …): for example
//! `Specimen : Specimen label,"AL-03"`, `Specimen : Area,0.2500,cm^2`,
//! `Results : Tensile stress at Maximum Load,339.5,MPa`; a blank line; the
//! channel names (`Time,Extension,Load`); a unit row in parentheses
//! (`(s),(mm),(kN)`); the samples. The section may be given only as its
//! area, often in cm².
//!
//! Each header line is kept with the name as its key and `value unit` as its
//! value (`Area` = `0.2500 cm^2`), as the Bluehill results block is. The
//! lines tribo takes (the section, the gauge length and the printed
//! results, [`USED`]) must carry a unit tribo knows of the right quantity:
//! anything else is an error naming the file and line, found when the file
//! is opened rather than as a missing section later.

use crate::error::{Error, Result};
use crate::ingest::dialect::split_fields;
use crate::ingest::formats::delimited::read_delimited_rekeyed;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};
use crate::units::{accepted, parse_unit, Quantity};

/// The Instron metadata-block reader.
pub struct InstronBlocks;

/// Header names tribo takes, with the quantity their unit must measure.
pub const USED: [(&str, Quantity); 9] = [
    ("Area", Quantity::Area),
    ("Width", Quantity::Length),
    ("Thickness", Quantity::Length),
    ("Diameter", Quantity::Length),
    ("Gauge length", Quantity::Length),
    ("Tensile stress at Maximum Load", Quantity::Stress),
    ("Tensile strain at Maximum Load", Quantity::Dimensionless),
    ("Modulus (Automatic)", Quantity::Stress),
    ("Tensile stress at Yield (Offset 0.2 %)", Quantity::Stress),
];

/// `Type : Name,value,unit` split into (type, name, value, unit).
fn header_line(line: &str) -> Option<(String, String, String, String)> {
    let (kind, rest) = line.split_once(" : ")?;
    let kind = kind.trim();
    if kind.is_empty() || kind.contains(',') || kind.split_whitespace().count() > 2 {
        return None;
    }
    let fields = split_fields(rest, ',');
    let field = |i: usize| {
        fields
            .get(i)
            .map(|f| f.trim().trim_matches('"').trim().to_string())
            .unwrap_or_default()
    };
    Some((kind.to_string(), field(0), field(1), field(2)))
}

/// The unit of a used header line must be known and of its quantity.
fn check_unit(text: &Text, m: &MetaEntry, unit: &str) -> Result<()> {
    let Some((_, quantity)) = USED.iter().find(|(k, _)| *k == m.key) else {
        return Ok(());
    };
    match parse_unit(unit) {
        Some(u) if u.quantity == *quantity => Ok(()),
        _ => Err(Error::Unit {
            location: text.at(m.line).with_column(&m.key),
            unit: unit.to_string(),
            expected: format!("a unit of {:?} ({})", quantity, accepted(*quantity)),
        }),
    }
}

impl Reader for InstronBlocks {
    fn name(&self) -> &'static str {
        "instron-blocks"
    }
    fn description(&self) -> &'static str {
        "Instron raw-data CSV with `Type : Name,value,unit` metadata blocks (section as an area, e.g. cm^2)"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::TensileCurve)
    }
    fn sniff(&self, text: &Text) -> bool {
        let head = text.head(60);
        let blocks = head
            .iter()
            .take_while(|l| !l.trim().is_empty())
            .filter(|l| header_line(l).is_some())
            .count();
        blocks >= 2 && head.iter().any(|l| l.trim_start().starts_with("Time,"))
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        read_delimited_rekeyed(text, options, |line, m| {
            let Some((_, name, value, unit)) = header_line(line) else {
                return Ok(());
            };
            m.key = name;
            m.value = format!("{value} {unit}").trim().to_string();
            check_unit(text, m, &unit)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn header_lines_split_into_their_parts() {
        assert_eq!(
            header_line("Specimen : Area,0.2500,cm^2"),
            Some((
                "Specimen".into(),
                "Area".into(),
                "0.2500".into(),
                "cm^2".into()
            ))
        );
        let (_, n, v, u) = header_line("Specimen : Specimen label,\"AL-03\",").unwrap();
        assert_eq!(
            (n.as_str(), v.as_str(), u.as_str()),
            ("Specimen label", "AL-03", "")
        );
        // a time with colons is a value, not a block separator
        let (_, n, v, _) = header_line("General : Start date,Tue 04 Jun 2019 10:39:12,").unwrap();
        assert_eq!(
            (n.as_str(), v.as_str()),
            ("Start date", "Tue 04 Jun 2019 10:39:12")
        );
        assert_eq!(header_line("0.20,0.01000,0.35000"), None);
        assert_eq!(header_line("Time,Extension,Load"), None);
    }
}
