//! Stylus profile in the 3-file text export of ACCRETECH Surfcom-style
//! roughness testers: `NAME.tx1` the primary profile, `NAME.tx2` the
//! roughness profile (already filtered by the instrument with the cut-off
//! its conditions state), `NAME.tx3` the measuring conditions.
//!
//! A profile file is two numbers and then the heights, one per line, with
//! no x column and no unit:
//!
//! ```text
//! 10.00000      evaluation length (mm)
//! 28087         number of points
//! -1.6360       heights (µm), one per line
//! ```
//!
//! It is recognised by that structure: a length, a whole count, and exactly
//! that many single numbers after them. The units are the export's: the
//! length in mm and the heights in µm, as the conditions file says
//! (`Unidad salida mm,um`, "output unit"); a conditions file beside the
//! profile that states other length units gives them. Without a
//! conditions file the export's units are used and the preamble says so.
//! Δx = length / (points − 1), the first and last heights at the ends of
//! the evaluation length (as [`super::stylus_heights`]). The conditions
//! (cut-off λc and λs, filter, standard, evaluation length) are the
//! companion's, in the dataset's preamble ([`crate::ingest::companion`]).

use crate::error::{Error, Result};
use crate::ingest::companion;
use crate::ingest::dialect::parse_number;
use crate::ingest::{Channel, Dialect, IngestOptions, MetaEntry, Reader, Section, Text};
use crate::units::{parse_unit, Quantity};

/// The Surfcom `.tx1`/`.tx2` reader.
pub struct SurfcomTx;

/// The export's units: lateral in mm, heights in µm.
const UNITS: (&str, &str) = ("mm", "um");

/// A number alone on a line.
fn single(line: &str, decimal: char) -> Option<f64> {
    let t = line.trim();
    if t.is_empty() || t.contains(char::is_whitespace) {
        return None;
    }
    parse_number(t, decimal).filter(|v| !v.is_nan())
}

/// The decimal mark: the first mark in the first lines (`10.00000` or, in
/// a decimal-comma locale, `10,00000`).
fn decimal_of(text: &Text) -> char {
    (0..text.line_count().min(12))
        .find_map(|i| text.line(i).chars().find(|c| matches!(c, '.' | ',')))
        .unwrap_or('.')
}

/// Lines holding something, from the end (trailing blank lines are no
/// heights).
fn filled_lines(text: &Text) -> usize {
    let blank_tail = text
        .lines()
        .rev()
        .take_while(|l| l.trim().is_empty())
        .count();
    text.line_count() - blank_tail
}

/// The header: (length, count) when the first two lines are a positive
/// length and a whole count ≥ 2.
fn header(text: &Text, decimal: char) -> Option<(f64, usize)> {
    if text.line_count() < 4 {
        return None;
    }
    let length = single(text.line(0), decimal).filter(|l| l.is_finite() && *l > 0.0)?;
    let count = text
        .line(1)
        .trim()
        .parse::<usize>()
        .ok()
        .filter(|n| *n >= 2)?;
    Some((length, count))
}

/// The units the companion conditions file states (`mm,um`), when it does.
fn companion_units(text: &Text) -> Result<Option<(String, String)>> {
    let entries = companion::metadata_for(&text.path)?;
    let Some(m) = entries.iter().find(|m| m.key == "tribo.output_units") else {
        return Ok(None);
    };
    let mut parts = m.value.split([',', ';', '/']).map(str::trim);
    let (x, z) = (parts.next().unwrap_or(""), parts.next().unwrap_or(""));
    let length = |u: &str| parse_unit(u).is_some_and(|u| u.quantity == Quantity::Length);
    match length(x) && length(z) {
        true => Ok(Some((x.to_string(), z.to_string()))),
        false => Err(Error::input(
            text.at(1),
            format!(
                "the measuring conditions beside this profile state its units as '{}' (line {} of the conditions file): expected two length units such as 'mm,um'",
                m.value, m.line
            ),
        )),
    }
}

/// The heights, one per line from line 3, as many as the header states.
fn heights(text: &Text, decimal: char, count: usize) -> Result<Vec<f64>> {
    let n = filled_lines(text);
    let z: Vec<f64> = (2..n)
        .map(|i| {
            single(text.line(i), decimal).ok_or_else(|| {
                Error::input(
                    text.at(i + 1),
                    format!(
                        "expected one height per line, found {}",
                        crate::ingest::text::quoted(text.line(i).trim())
                    ),
                )
            })
        })
        .collect::<Result<_>>()?;
    if z.len() != count {
        return Err(Error::input(
            text.at(2),
            format!(
                "the header states {count} points but the file has {} heights",
                z.len()
            ),
        ));
    }
    Ok(z)
}

impl Reader for SurfcomTx {
    fn name(&self) -> &'static str {
        "surfcom-tx"
    }
    fn description(&self) -> &'static str {
        "stylus profile of a Surfcom-style 3-file text export (.tx1 primary, .tx2 roughness): evaluation length, point count, one height per line; .tx3 conditions read with it"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::Profile)
    }
    fn sniff(&self, text: &Text) -> bool {
        let decimal = decimal_of(text);
        let Some((_, count)) = header(text, decimal) else {
            return false;
        };
        let n = filled_lines(text);
        n == count + 2 && (2..n.min(12)).all(|i| single(text.line(i), decimal).is_some())
    }
    fn read(
        &self,
        text: &Text,
        _options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let decimal = decimal_of(text);
        let (length, count) = header(text, decimal).ok_or_else(|| {
            Error::input(
                text.at(1),
                "expected the evaluation length on line 1 and the number of points on line 2",
            )
        })?;
        let z = heights(text, decimal, count)?;
        let (x_unit, z_unit, said) = match companion_units(text)? {
            Some((x, z)) => (x, z, "as the measuring conditions beside it state"),
            None => (
                UNITS.0.to_string(),
                UNITS.1.to_string(),
                "the export's (no measuring conditions beside it state them)",
            ),
        };
        let dx = length / (count - 1) as f64;
        let preamble = vec![
            MetaEntry {
                key: "Evaluation length".into(),
                value: format!("{length} {x_unit}"),
                line: 1,
            },
            MetaEntry {
                key: "Number of points".into(),
                value: count.to_string(),
                line: 2,
            },
            MetaEntry {
                key: "tribo.units".into(),
                value: format!("x in {x_unit}, heights in {z_unit}: {said}"),
                line: 1,
            },
            MetaEntry {
                key: "tribo.spacing".into(),
                value: format!("{dx} {x_unit} = length / (points - 1)"),
                line: 1,
            },
        ];
        let channel = |name: &str, unit: &str, values| Channel {
            name: name.into(),
            raw_unit: unit.into(),
            values,
        };
        let x = (0..count).map(|i| i as f64 * dx).collect();
        let section = Section {
            name: "1".into(),
            metadata: Vec::new(),
            header_line: None,
            first_data_line: 3,
            channels: vec![channel("x", &x_unit, x), channel("z", &z_unit, z)],
        };
        let dialect = Dialect {
            decimal,
            ..Dialect::whitespace(text)
        };
        Ok((dialect, preamble, vec![section]))
    }
}
