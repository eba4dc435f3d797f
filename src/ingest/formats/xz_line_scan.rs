//! A line scan written as two columns of numbers, x and z, with no header
//! and no unit: the text export of a Bruker Dektak (Vision64 OPDx) and of
//! other profilers (`0  1.3718306e-09  `, double blanks, trailing blanks,
//! or a tab or comma between the columns, any line ending).
//!
//! Without a unit the file could be read in any length unit, and a wrong
//! one scales every result by powers of 1000. The reader takes it only
//! when exactly one of m, mm, µm and nm makes the file a plausible line
//! scan ([`plausible`]): a spacing of at least 1 Å and at most 1 mm, a
//! length from 0.1 µm to 200 mm, and heights within 1 cm; x and z in the
//! same unit, as these exports write them. The 3001 points over 5·10⁻⁵ of
//! a Dektak export are then metres (in mm the spacing would be 17 pm). When
//! two units are plausible (a 1.0-long scan of 10 000 points is 1 mm or
//! 1 µm) the reader leaves the file to the generic one, and the roughness
//! stage asks for the units. The unit chosen and why is in the preamble
//! (`tribo.units`).

use crate::error::Result;
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{dialect, Dialect, IngestOptions, MetaEntry, Reader, Section, Text};

/// The headerless x z line-scan reader.
pub struct XzLineScan;

/// The candidate units, name and metres per unit.
const UNITS: [(&str, f64); 4] = [("m", 1.0), ("mm", 1e-3), ("um", 1e-6), ("nm", 1e-9)];

/// What a line scan looks like, in m.
const SPACING: (f64, f64) = (1e-10, 1e-3);
const LENGTH: (f64, f64) = (1e-7, 0.2);
const HEIGHT_RANGE: f64 = 1e-2;

/// Lines sampled from the head of the file.
const HEAD: usize = 50;

/// x, z of a line when it holds exactly two numbers.
fn pair(line: &str, delimiter: char) -> Option<(f64, f64)> {
    match dialect::parse_line(line, delimiter, '.') {
        (Some(row), _) if row.len() == 2 && row.iter().all(|v| v.is_finite()) => {
            Some((row[0], row[1]))
        }
        _ => None,
    }
}

/// What the head and the last line say: (median spacing, length, height
/// range), in the file's unit; `None` unless every line sampled is a pair
/// and x increases.
fn shape(text: &Text) -> Option<(f64, f64, f64)> {
    let filled: Vec<&str> = text
        .lines()
        .filter(|l| !l.trim().is_empty())
        .take(HEAD)
        .collect();
    let last = text.lines().rev().find(|l| !l.trim().is_empty())?;
    let delimiter = [' ', '\t', ',', ';']
        .into_iter()
        .find(|d| filled.iter().all(|l| pair(l, *d).is_some()))?;
    let head: Vec<(f64, f64)> = filled
        .iter()
        .map(|l| pair(l, delimiter))
        .collect::<Option<_>>()?;
    let (x_last, _) = pair(last, delimiter)?;
    if head.len() < 10 || head.windows(2).any(|w| w[1].0 <= w[0].0) || x_last <= head[0].0 {
        return None;
    }
    let mut steps: Vec<f64> = head.windows(2).map(|w| w[1].0 - w[0].0).collect();
    let spacing = crate::signal::stats::median_in_place(&mut steps)?;
    let (lo, hi) = head
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.1), b.max(p.1))
        });
    Some((spacing, x_last - head[0].0, hi - lo))
}

/// The units in which the shape is a plausible line scan.
fn plausible(spacing: f64, length: f64, heights: f64) -> Vec<(&'static str, f64)> {
    let within = |v: f64, (a, b): (f64, f64)| v >= a && v <= b;
    UNITS
        .into_iter()
        .filter(|(_, m)| {
            within(spacing * m, SPACING)
                && within(length * m, LENGTH)
                && heights * m <= HEIGHT_RANGE
        })
        .collect()
}

/// The one unit that makes the file a line scan.
fn unit(text: &Text) -> Option<(&'static str, (f64, f64))> {
    let (spacing, length, heights) = shape(text)?;
    match plausible(spacing, length, heights)[..] {
        [(u, _)] => Some((u, (spacing, length))),
        _ => None,
    }
}

impl Reader for XzLineScan {
    fn name(&self) -> &'static str {
        "xz-line-scan"
    }
    fn description(&self) -> &'static str {
        "headerless two-column x z line scan (Dektak OPDx text export and alike), read only when exactly one length unit makes it a plausible scan"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::Profile)
    }
    fn sniff(&self, text: &Text) -> bool {
        unit(text).is_some()
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, mut preamble, mut sections) = read_delimited(text, options)?;
        let Some((u, (spacing, length))) = unit(text) else {
            return Ok((dialect, preamble, sections));
        };
        for s in &mut sections {
            for (c, name) in s.channels.iter_mut().zip(["x", "z"]) {
                c.name = name.into();
                c.raw_unit = u.into();
            }
        }
        let others: Vec<&str> = UNITS.iter().map(|u| u.0).filter(|o| *o != u).collect();
        preamble.push(MetaEntry {
            key: "tribo.units".into(),
            value: format!(
                "x and z in {u}, which the file does not state: the only length unit in which a spacing \
                 of {spacing:e} and a length of {length:e} make a line scan (in {} they would not); \
                 give --x-unit and --z-unit to read it otherwise",
                others.join(", ")
            ),
            line: 1,
        });
        Ok((dialect, preamble, sections))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A Dektak-like scan of 3001 points over 5e-5 is in metres; a scan
    /// of 10 001 points over 1.0 could be mm or µm and is left alone, and
    /// so is a time series (0.1 s steps over 1200 s).
    #[test]
    fn one_plausible_unit_or_none() {
        assert_eq!(plausible(1.6656e-8, 4.9967e-5, 1.4e-8), [("m", 1.0)]);
        let two: Vec<&str> = plausible(1e-4, 1.0, 0.0036).iter().map(|u| u.0).collect();
        assert_eq!(two, ["mm", "um"]);
        assert!(plausible(0.1, 1200.0, 0.4).len() != 1);
    }
}
