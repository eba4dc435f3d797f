//! Text height maps in the layout SurfaceTopography's plain-text reader
//! (`IO/Text.py`, MIT) takes: Gwyddion and SPIP text exports, in English or
//! German, UTF-8 or UTF-16 with a byte-order mark.
//!
//! Layout: header lines (usually behind `#`) with the scan size and units,
//! then one row of heights per y, one column per x, separated by blanks or
//! tabs:
//!
//! ```text
//! # Kanal: Height          (Channel)
//! # Breite: 12.34 µm       (Width, or x-length)
//! # Höhe: 5678.9 nm        (Height, or y-length)
//! # Value units: m         (or z-unit)
//! 1 1.5 3 …
//! ```
//!
//! The header keys are written back in English (`Breite` → `Width`, `Höhe`
//! → `Height`, `Kanal` → `Channel`, `x-length` → `Width`, `z-unit` →
//! `Value units`) so that the map reads as any z matrix
//! ([`crate::extract::roughness::input`]): Δx = Width / columns, Δy =
//! Height / rows (Gwyddion's and SurfaceTopography's convention). A size
//! written without a unit takes `x-unit` / `y-unit`, else the value unit
//! (as SurfaceTopography does). Every size must be a length with a unit tribo
//! knows, and the value unit a length: otherwise an error naming the file
//! and line, when the file is opened. Each column of heights carries the
//! value unit.

use crate::error::{Error, Result};
use crate::ingest::dialect::parse_number;
use crate::ingest::formats::delimited::read_delimited;
use crate::ingest::{Dialect, IngestOptions, MetaEntry, Reader, Section, Text};
use crate::units::{accepted, parse_unit, Quantity};

/// The SurfaceTopography / Gwyddion text-map reader.
pub struct SurfaceText;

/// Header keys as written (lower case) and the English key they become.
const KEYS: [(&str, &str); 11] = [
    ("channel", "Channel"),
    ("kanal", "Channel"),
    ("width", "Width"),
    ("breite", "Width"),
    ("x-length", "Width"),
    ("height", "Height"),
    ("höhe", "Height"),
    ("y-length", "Height"),
    ("value units", "Value units"),
    ("z-unit", "Value units"),
    ("x-unit", "x-unit"),
];

/// `# Key: value` / `Key = value` as the English key and the value.
fn header_key(line: &str) -> Option<(&'static str, String)> {
    let l = line.trim().trim_start_matches('#').trim();
    let i = l.find([':', '='])?;
    let key = l[..i].trim().to_lowercase();
    let value = l[i + 1..].trim().to_string();
    let english = KEYS.iter().find(|(k, _)| *k == key).map(|(_, e)| *e);
    english
        .or_else(|| (key == "y-unit").then_some("y-unit"))
        .map(|e| (e, value))
}

/// The header: lines before the first row of numbers.
fn head_lines<'t>(text: &'t Text) -> Vec<&'t str> {
    text.lines()
        .take(60)
        .take_while(|l| {
            let mut fields = l.split_whitespace().peekable();
            fields.peek().is_none() || !fields.all(|f| parse_number(f, '.').is_some())
        })
        .collect()
}

/// The header lines as metadata, SurfaceTopography's keys in English.
fn header_entries(text: &Text, delimiter: char) -> Vec<MetaEntry> {
    let head = head_lines(text);
    head.iter()
        .enumerate()
        .filter_map(|(i, l)| match header_key(l) {
            Some((key, value)) => Some(MetaEntry {
                key: key.to_string(),
                value,
                line: i + 1,
            }),
            None => MetaEntry::parse(l, i + 1, delimiter),
        })
        .collect()
}

fn unit_error(text: &Text, m: &MetaEntry, unit: &str, what: &str) -> Error {
    Error::Unit {
        location: text.at(m.line).with_column(&m.key),
        unit: unit.to_string(),
        expected: format!(
            "a length unit for the {what} ({})",
            accepted(Quantity::Length)
        ),
    }
}

/// Checks the value unit and completes and checks the sizes.
fn normalise(text: &Text, preamble: &mut [MetaEntry]) -> Result<String> {
    let get = |p: &[MetaEntry], k: &str| p.iter().find(|m| m.key == k).cloned();
    let z = get(preamble, "Value units").ok_or_else(|| {
        Error::input(
            text.at(1),
            "the map's header states no value unit ('Value units' or 'z-unit')",
        )
    })?;
    if !parse_unit(&z.value).is_some_and(|u| u.quantity == Quantity::Length) {
        return Err(unit_error(text, &z, &z.value, "heights"));
    }
    for (size, axis) in [("Width", "x-unit"), ("Height", "y-unit")] {
        let fallback = get(preamble, axis).map_or(z.value.clone(), |m| m.value);
        let Some(m) = preamble.iter_mut().find(|m| m.key == size) else {
            continue;
        };
        let mut parts = m.value.split_whitespace();
        let number = parts.next().and_then(|n| parse_number(n, '.'));
        let mut unit = parts.collect::<Vec<_>>().join(" ");
        if number.is_none() {
            return Err(Error::input(
                text.at(m.line),
                format!(
                    "scan {size} '{}': expected a length such as '10 µm'",
                    m.value
                ),
            ));
        }
        if unit.is_empty() {
            unit = fallback.clone();
            m.value = format!("{} {unit}", m.value);
        }
        if !parse_unit(&unit).is_some_and(|u| u.quantity == Quantity::Length) {
            return Err(unit_error(text, m, &unit, &format!("scan {size}")));
        }
    }
    Ok(z.value)
}

impl Reader for SurfaceText {
    fn name(&self) -> &'static str {
        "surface-text"
    }
    fn description(&self) -> &'static str {
        "text height map with a Gwyddion/SurfaceTopography header (Width/Breite, Height/Höhe, Value units), English or German, UTF-8 or UTF-16"
    }
    fn kind(&self) -> Option<crate::ingest::kind::DataKind> {
        Some(crate::ingest::kind::DataKind::ArealMap)
    }
    fn sniff(&self, text: &Text) -> bool {
        let head = head_lines(text);
        let keys: Vec<&str> = head
            .iter()
            .filter_map(|l| header_key(l))
            .map(|k| k.0)
            .collect();
        let rows = text
            .lines()
            .skip(head.len())
            .take(1)
            .next()
            .map_or(0, |l| l.split_whitespace().count());
        keys.contains(&"Value units")
            && (keys.contains(&"Width") || keys.contains(&"Height"))
            && rows > 3
    }
    fn read(
        &self,
        text: &Text,
        options: &IngestOptions,
    ) -> Result<(Dialect, Vec<MetaEntry>, Vec<Section>)> {
        let (dialect, _, mut sections) = read_delimited(text, options)?;
        let mut preamble = header_entries(text, dialect.delimiter);
        // The map has no header row: with blanks as the delimiter, the last
        // `#` line above the numbers can look like one (`# Value units: m`
        // is four words over four columns).
        for s in &mut sections {
            if s.header_line
                .is_some_and(|n| preamble.iter().any(|m| m.line == n))
            {
                s.header_line = None;
                for (k, c) in s.channels.iter_mut().enumerate() {
                    c.name = format!("column_{}", k + 1);
                }
            }
        }
        let z_unit = normalise(text, &mut preamble)?;
        if let Some(s) = sections.first() {
            preamble.push(MetaEntry {
                key: "tribo.spacing".into(),
                value: format!(
                    "dx = Width / {} columns, dy = Height / {} rows (Gwyddion's convention)",
                    s.channels.len(),
                    s.rows()
                ),
                line: s.first_data_line,
            });
        }
        for s in &mut sections {
            for c in &mut s.channels {
                c.raw_unit = z_unit.clone();
            }
        }
        Ok((dialect, preamble, sections))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn german_and_english_keys_become_english() {
        assert_eq!(
            header_key("# Breite: 12.34 µm"),
            Some(("Width", "12.34 µm".into()))
        );
        assert_eq!(header_key("# Höhe: 5678.9 nm").unwrap().0, "Height");
        assert_eq!(header_key("# Kanal: My Channel").unwrap().0, "Channel");
        assert_eq!(header_key("x-length = 2000").unwrap().0, "Width");
        assert_eq!(
            header_key("z-unit = nm"),
            Some(("Value units", "nm".into()))
        );
        assert_eq!(header_key("# Datum: 2024"), None);
    }
}
