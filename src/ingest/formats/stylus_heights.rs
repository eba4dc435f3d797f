//! Stylus profile exported as heights only: a short header stating the
//! evaluation length and the number of points (and the height unit), then
//! one height per line, one profile per file.
//!
//! ```text
//! Evaluation length: 4.000 mm
//! Number of points: 4001
//! Height unit: um
//! 0.0123
//! ...
//! ```
//!
//! Keys are matched without case, with `:` or `=`: the length as
//! `Evaluation length`, `Measuring length`, `Traverse length` or `Length`
//! (a number and a length unit), the count as `Number of points`,
//! `Points`, `Data count` or `Count`, the height unit as `Height unit`,
//! `Z unit` or `Unit`; an optional `Spacing` (or `Pitch`) with a unit.
//!
//! **Spacing**: the first and last heights lie at the two ends of the
//! evaluation length, so Δx = length / (count − 1); a `Spacing` line, when
//! present, must agree with it (to 1e-6) or the file is refused. The reader
//! writes the positions `x = i·Δx` in the length's unit beside the heights
//! `z`, so the file reads as any x,z profile. The count must equal the
//! number of heights, and every unit must be known: otherwise an error
//! naming the file and line.

use crate::error::{Error, Result};
use crate::ingest::dialect::parse_number;
use crate::ingest::{Channel, Dialect, IngestOptions, MetaEntry, Reader, Section, Text};
use crate::units::{accepted, parse_unit, Quantity, Unit};

/// The heights-only stylus reader.
pub struct StylusHeights;

const LENGTH_KEYS: [&str; 4] = [
    "evaluation length",
    "measuring length",
    "traverse length",
    "length",
];
const COUNT_KEYS: [&str; 4] = ["number of points", "points", "data count", "count"];
const UNIT_KEYS: [&str; 3] = ["height unit", "z unit", "unit"];
const SPACING_KEYS: [&str; 2] = ["spacing", "pitch"];

/// `Key: value` or `Key = value`.
fn key_value(line: &str) -> Option<(String, &str)> {
    let i = line.find([':', '='])?;
    let (k, v) = (line[..i].trim(), line[i + 1..].trim());
    (!k.is_empty()).then(|| (k.to_string(), v))
}

fn is_height(line: &str) -> bool {
    let t = line.trim();
    !t.is_empty() && !t.contains(char::is_whitespace) && parse_number(t, '.').is_some()
}

/// The header: every line before the first height.
struct Header {
    entries: Vec<MetaEntry>,
    /// 1-based line of the first height.
    first_data_line: usize,
}

/// The longest header the sniffer looks through: a large file of another
/// format is then recognised or refused from its first lines, not read whole.
const SNIFF_HEADER_LINES: usize = 40;

/// The header within the first `max_lines` lines; `first_data_line` is past
/// them when no height starts there.
fn header(text: &Text, max_lines: usize) -> Header {
    let mut entries = Vec::new();
    for (i, line) in text.lines().enumerate().take(max_lines) {
        if is_height(line) {
            return Header {
                entries,
                first_data_line: i + 1,
            };
        }
        if let Some((key, value)) = key_value(line) {
            entries.push(MetaEntry {
                key,
                value: value.to_string(),
                line: i + 1,
            });
        } else if !line.trim().is_empty() {
            entries.push(MetaEntry {
                key: line.trim().to_string(),
                value: String::new(),
                line: i + 1,
            });
        }
    }
    Header {
        first_data_line: text.line_count().min(max_lines) + 1,
        entries,
    }
}

fn find<'a>(h: &'a Header, keys: &[&str]) -> Option<&'a MetaEntry> {
    keys.iter()
        .find_map(|k| h.entries.iter().find(|m| m.key.eq_ignore_ascii_case(k)))
}

/// `4.000 mm` as the number and its unit, which must measure `quantity`.
fn number_unit(text: &Text, m: &MetaEntry, quantity: Quantity) -> Result<(f64, Unit)> {
    let mut parts = m.value.split_whitespace();
    let number = parts.next().and_then(|n| parse_number(n, '.'));
    let unit_text = parts.collect::<Vec<_>>().join(" ");
    let Some(v) = number.filter(|v| v.is_finite() && *v > 0.0) else {
        return Err(Error::input(
            text.at(m.line),
            format!("{} '{}': expected a number > 0 and a unit", m.key, m.value),
        ));
    };
    unit(text, m, &unit_text, quantity).map(|u| (v, u))
}

fn unit(text: &Text, m: &MetaEntry, symbol: &str, quantity: Quantity) -> Result<Unit> {
    parse_unit(symbol)
        .filter(|u| u.quantity == quantity)
        .ok_or_else(|| Error::Unit {
            location: text.at(m.line).with_column(&m.key),
            unit: symbol.to_string(),
            expected: format!("a unit of {quantity:?} ({})", accepted(quantity)),
        })
}

fn missing(text: &Text, what: &str) -> Error {
    Error::input(
        text.at(1),
        format!("a heights-only stylus export needs a {what} line in its header"),
    )
}

/// The heights, one per line; anything else is an error naming the line.
fn heights(text: &Text, first: usize) -> Result<Vec<f64>> {
    let mut z = Vec::new();
    for (i, line) in text.lines().enumerate().skip(first - 1) {
        if line.trim().is_empty() {
            continue;
        }
        match parse_number(line.trim(), '.').filter(|_| is_height(line)) {
            Some(v) => z.push(v),
            None => {
                return Err(Error::input(
                    text.at(i + 1),
                    format!(
                        "'{}' is not a height (expected one number per line)",
                        line.trim()
                    ),
                ))
            }
        }
    }
    Ok(z)
}

/// Δx in the length's unit: length / (count − 1), checked against a
/// `Spacing` line.
fn spacing(text: &Text, h: &Header, length: f64, lu: &Unit, count: usize) -> Result<f64> {
    let dx = length / (count - 1) as f64;
    if let Some(m) = find(h, &SPACING_KEYS) {
        let (s, su) = number_unit(text, m, Quantity::Length)?;
        let stated = su.to_si(s) / lu.to_si(1.0);
        if (stated - dx).abs() > 1e-6 * dx {
            return Err(Error::input(
                text.at(m.line),
                format!(
                    "spacing {} disagrees with length / (points − 1) = {dx} {}",
                    m.value, lu.symbol
                ),
            ));
        }
    }
    Ok(dx)
}

impl Reader for StylusHeights {
    fn name(&self) -> &'static str {
        "stylus-heights"
    }
    fn description(&self) -> &'static str {
        "stylus profile as heights only, with evaluation length and number of points in the header (dx = length / (points - 1))"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::Profile)
    }
    fn sniff(&self, text: &Text) -> bool {
        let h = header(text, SNIFF_HEADER_LINES);
        h.first_data_line <= SNIFF_HEADER_LINES
            && find(&h, &LENGTH_KEYS).is_some()
            && find(&h, &COUNT_KEYS).is_some()
            && (h.first_data_line..h.first_data_line + 3)
                .filter(|n| *n <= text.line_count())
                .all(|n| is_height(text.line(n - 1)))
    }
    fn read(
        &self,
        text: &Text,
        _options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let h = header(text, usize::MAX);
        let lm = find(&h, &LENGTH_KEYS).ok_or_else(|| missing(text, "length"))?;
        let (length, lu) = number_unit(text, lm, Quantity::Length)?;
        let cm = find(&h, &COUNT_KEYS).ok_or_else(|| missing(text, "number of points"))?;
        let count = cm
            .value
            .parse::<usize>()
            .ok()
            .filter(|n| *n >= 2)
            .ok_or_else(|| {
                Error::input(
                    text.at(cm.line),
                    format!("{} '{}': expected a whole number ≥ 2", cm.key, cm.value),
                )
            })?;
        let um = find(&h, &UNIT_KEYS).ok_or_else(|| missing(text, "height unit"))?;
        let zu = unit(text, um, &um.value, Quantity::Length)?;
        let z = heights(text, h.first_data_line)?;
        if z.len() != count {
            return Err(Error::input(
                text.at(cm.line),
                format!(
                    "the header states {count} points but the file has {} heights",
                    z.len()
                ),
            ));
        }
        let dx = spacing(text, &h, length, &lu, count)?;
        let x = (0..count).map(|i| i as f64 * dx).collect();
        let length_line = lm.line;
        let first_data_line = h.first_data_line;
        let mut preamble = h.entries;
        preamble.push(MetaEntry {
            key: "tribo.spacing".into(),
            value: format!("{dx} {} = length / (points - 1)", lu.symbol),
            line: length_line,
        });
        let channel = |name: &str, unit: &str, values| Channel {
            name: name.into(),
            raw_unit: unit.into(),
            values,
        };
        let section = Section {
            name: "1".into(),
            metadata: Vec::new(),
            header_line: None,
            first_data_line,
            channels: vec![channel("x", lu.symbol, x), channel("z", zu.symbol, z)],
        };
        Ok((Dialect::whitespace(text), preamble, vec![section]))
    }
}
