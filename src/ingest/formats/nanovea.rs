//! Nanovea (ST-400 optical profilometer) x,y,z point export: comma-separated
//! rows `x,y,z` without a header, grouped by y (one group per scan line, x
//! increasing), groups separated by blank lines. The file states no units;
//! the Nanovea export writes x and y in mm and z in µm, which this reader
//! assigns (override with `units` in the options). The groups are merged
//! into one section with channels `x`, `y`, `z`.

use crate::error::{Error, Result};
use crate::ingest::dialect::{parse_row, split_fields};
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Channel, Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The Nanovea x,y,z reader.
pub struct Nanovea;

fn triple(line: &str) -> Option<Vec<f64>> {
    parse_row(&split_fields(line, ','), '.')
        .filter(|r| r.len() == 3 && r.iter().all(|v| v.is_finite()))
}

/// A scan line of the file: its first and last line (1-based) and points.
struct ScanLine {
    first: usize,
    last: usize,
    points: usize,
}

/// Every non-blank line must be an x,y,z point, and the last scan line as
/// long as the first: an export cut short (a partial last line, or a last
/// scan line with fewer points) is an error naming the line, never a map
/// with its last row silently dropped.
fn check_whole_lines(text: &Text) -> Result<()> {
    let mut scans: Vec<ScanLine> = Vec::new();
    let mut open = false;
    for (i, line) in text.lines().enumerate() {
        if line.trim().is_empty() {
            open = false;
            continue;
        }
        if triple(line).is_none() {
            return Err(Error::input(
                text.at(i + 1),
                format!(
                    "'{}' is not an x,y,z point (expected three numbers); the map is                      truncated or damaged here: re-export it, or crop it to whole scan lines",
                    line.trim()
                ),
            ));
        }
        match scans.last_mut() {
            Some(s) if open => {
                s.last = i + 1;
                s.points += 1;
            }
            _ => scans.push(ScanLine {
                first: i + 1,
                last: i + 1,
                points: 1,
            }),
        }
        open = true;
    }
    if let [first, .., last] = scans.as_slice() {
        if last.points < first.points {
            return Err(Error::input(
                text.at(last.last),
                format!(
                    "truncated map: the last scan line (lines {}–{}) has {} points where the                      first has {}; re-export the map, or crop it to whole scan lines",
                    last.first, last.last, last.points, first.points
                ),
            ));
        }
    }
    Ok(())
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
        check_whole_lines(text)?;
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    /// `rows` scan lines of `per` points, two blank lines between them (the
    /// Nanovea layout), then `tail` appended verbatim.
    fn map_text(rows: usize, per: usize, tail: &str) -> Text<'static> {
        let mut s = String::new();
        for r in 0..rows {
            for c in 0..per {
                s.push_str(&format!(
                    "{:.4},{:.4},{}.0\n",
                    c as f64 * 0.005,
                    r as f64 * 0.005,
                    c + r
                ));
            }
            s.push_str("\n\n");
        }
        s.push_str(tail);
        Text::decode_owned(Path::new("m.txt"), s.into_bytes()).unwrap()
    }

    fn read(t: &Text) -> Result<Vec<Section>> {
        Nanovea.read(t, &IngestOptions::default()).map(|r| r.2)
    }

    #[test]
    fn whole_map_is_read() {
        let s = read(&map_text(10, 12, "")).unwrap();
        assert_eq!(s[0].rows(), 120);
    }

    #[test]
    fn a_partial_last_line_is_an_error_naming_it() {
        // 10 lines of 12 points and 2 blanks each: the partial point is on
        // line 10 · 14 + 1 = 141.
        let e = read(&map_text(10, 12, "0.0000,0.0500\n")).unwrap_err();
        let m = e.to_string();
        assert!(m.contains("141") && m.contains("not an x,y,z point"), "{m}");
    }

    #[test]
    fn a_short_last_scan_line_is_a_truncated_map_naming_the_line() {
        let e = read(&map_text(10, 12, "0.0000,0.0500,1.0\n0.0050,0.0500,1.0\n")).unwrap_err();
        let m = e.to_string();
        assert!(
            m.contains("truncated map")
                && m.contains("lines 141–142")
                && m.contains("has 2 points"),
            "{m}"
        );
    }
}
