//! Nanovea (ST-400 optical profilometer) x,y,z point export: comma-separated
//! rows `x,y,z` without a header, grouped by y (one group per scan line, x
//! increasing), groups separated by blank lines. The file states no units;
//! the Nanovea export writes x and y in mm and z in µm, which this reader
//! assigns (override with `units` in the options). The groups are merged
//! into one section with channels `x`, `y`, `z`.

use crate::error::Result;
use crate::ingest::dialect::{parse_row, split_fields};
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Channel, Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The Nanovea x,y,z reader.
pub struct Nanovea;

fn triple(line: &str) -> Option<Vec<f64>> {
    parse_row(&split_fields(line, ','), '.')
        .filter(|r| r.len() == 3 && r.iter().all(|v| v.is_finite()))
}

impl Reader for Nanovea {
    fn name(&self) -> &'static str {
        "nanovea"
    }
    fn description(&self) -> &'static str {
        "Nanovea optical profilometer x,y,z points (mm, mm, um), scan lines separated by blank lines"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::ArealMap)
    }
    fn sniff(&self, text: &Text) -> bool {
        // Numeric x,y,z rows with a constant y up to the first blank line,
        // then another group with a different y.
        let lines = text.head(100_000);
        let Some(blank) = lines.iter().take(100_000).position(|l| l.trim().is_empty()) else {
            return false;
        };
        if blank < 3 {
            return false;
        }
        let rows: Option<Vec<Vec<f64>>> = lines[..blank].iter().map(|l| triple(l)).collect();
        let Some(rows) = rows else { return false };
        let y0 = rows[0][1];
        if rows.iter().any(|r| (r[1] - y0).abs() > 0.0) {
            return false;
        }
        lines[blank..]
            .iter()
            .find(|l| !l.trim().is_empty())
            .and_then(|l| triple(l))
            .is_some_and(|r| (r[1] - y0).abs() > 0.0)
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, preamble, sections) = read_delimited(text, options)?;
        let mut cols: [Vec<f64>; 3] = Default::default();
        for s in &sections {
            for (k, c) in s.channels.iter().take(3).enumerate() {
                cols[k].extend_from_slice(&c.values);
            }
        }
        let first_data_line = sections.first().map_or(1, |s| s.first_data_line);
        let [x, y, z] = cols;
        let channel = |name: &str, unit: &str, values: Vec<f64>| Channel {
            name: name.into(),
            raw_unit: unit.into(),
            values,
        };
        let merged = Section {
            name: "1".into(),
            metadata: Vec::new(),
            header_line: None,
            first_data_line,
            channels: vec![
                channel("x", "mm", x),
                channel("y", "mm", y),
                channel("z", "um", z),
            ],
        };
        Ok((dialect, preamble, vec![merged]))
    }
}
