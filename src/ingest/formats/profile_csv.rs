//! Quoted decimal-comma profile export: a header `"Distance","Profile"` and
//! rows such as `"0,00050","0,03"`, the layout of the `trib` R package's
//! profilometer import. The file states no units; the layout's are those
//! that package reads it in (its plots: "Distance mm", "Profile um"; its
//! track area: mm·µm / 1000 = mm²). A column without a unit given in the
//! options is read in them, with an [`ASSUMED_UNIT`] entry saying so: the
//! analyses mark their rows `assumed_unit` unless the user gave the unit
//! (`--x-unit`, `--z-unit`, or `x_unit`/`z_unit` in a pipeline file).

use crate::error::Result;
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text, ASSUMED_UNIT};

/// The layout's units, by column.
const LAYOUT_UNITS: [(&str, &str); 2] = [("Distance", "mm"), ("Profile", "um")];

/// The quoted `"Distance","Profile"` reader.
pub struct ProfileCsv;

impl Reader for ProfileCsv {
    fn name(&self) -> &'static str {
        "profile-csv"
    }
    fn description(&self) -> &'static str {
        "quoted decimal-comma stylus profile (\"Distance\",\"Profile\"), read in mm and um"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::Profile)
    }
    fn sniff(&self, text: &Text) -> bool {
        text.head(1).first().is_some_and(|l| {
            let l = l.trim().replace(' ', "");
            l == "\"Distance\",\"Profile\"" || l == "\"Distance\";\"Profile\""
        })
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, mut preamble, mut sections) = read_delimited(text, options)?;
        for s in &mut sections {
            for c in &mut s.channels {
                let layout = LAYOUT_UNITS.iter().find(|(name, _)| *name == c.name);
                let Some((name, unit)) = layout else { continue };
                if c.raw_unit.is_empty() && !options.units.contains_key(*name) {
                    c.raw_unit = unit.to_string();
                    preamble.push(MetaEntry {
                        key: ASSUMED_UNIT.into(),
                        value: format!("{name} as {unit}"),
                        line: s.header_line.unwrap_or(1),
                    });
                }
            }
        }
        Ok((dialect, preamble, sections))
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use crate::ingest::{read_bytes, IngestOptions, ASSUMED_UNIT};

    /// The layout's units fill only the columns without one: a unit the
    /// options give for a column is that column's, and not assumed.
    #[test]
    fn layout_units_fill_only_the_columns_the_options_leave() {
        let text = b"\"Distance\",\"Profile\"\n\"0,001\",\"0,1\"\n\"0,002\",\"0,3\"\n";
        let units = |o: &IngestOptions| {
            let ds = read_bytes(Path::new("p.csv"), text, o).unwrap();
            assert_eq!(ds.format, "profile-csv");
            let raw: Vec<String> = ds.sections[0]
                .channels
                .iter()
                .map(|c| c.raw_unit.clone())
                .collect();
            let said: Vec<String> = ds
                .preamble
                .iter()
                .filter(|m| m.key == ASSUMED_UNIT)
                .map(|m| m.value.clone())
                .collect();
            (raw, said)
        };
        let (raw, said) = units(&IngestOptions::default());
        assert_eq!(raw, ["mm", "um"]);
        assert_eq!(said, ["Distance as mm", "Profile as um"]);
        let mut o = IngestOptions::default();
        o.units.insert("Distance".into(), "um".into());
        let (raw, said) = units(&o);
        assert_eq!(raw, ["um", "um"]);
        assert_eq!(said, ["Profile as um"]);
    }
}
