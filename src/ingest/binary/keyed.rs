//! Text headers of `key = value` (or `key: value`) lines, optionally in
//! `[Section]`s, that open many SPM files (Nanosurf NID, WSxM, BCR,
//! Agilent MI) before their binary data: each entry keeps its section and
//! byte offset, so that a missing or malformed value is an error naming
//! the file, the section, the key and where the section starts.

use super::{latin1_or_utf8, meta, Bytes};
use crate::error::{Error, Result};
use crate::ingest::MetaEntry;

/// One `key = value` line.
#[derive(Debug, Clone)]
pub struct Entry {
    /// The section (`DataSet-0:1`), empty before the first.
    pub section: String,
    /// The key, trimmed.
    pub key: String,
    /// The value, trimmed.
    pub value: String,
    /// Byte offset of the line in the file.
    pub offset: usize,
}

/// How a header's lines are split.
#[derive(Debug, Clone, Copy)]
pub enum Split {
    /// At the first occurrence of this character.
    At(char),
    /// At a fixed column (Agilent MI: 14 characters of key).
    Column(usize),
}

/// A parsed header and the file it came from.
pub struct Keyed<'a> {
    bytes: Bytes<'a>,
    /// The format's name for messages (`NID header`).
    structure: &'static str,
    /// The entries in file order.
    pub entries: Vec<Entry>,
    sections: Vec<(String, usize)>,
}

impl<'a> Keyed<'a> {
    /// Parses `text` (which starts at byte `start` of the file) line by
    /// line (LF, CR LF or CR): `[Name]` opens a section; other lines are
    /// split as `split` says; lines without a separator are skipped.
    pub fn parse(
        bytes: Bytes<'a>,
        structure: &'static str,
        (text, start): (&[u8], usize),
        split: Split,
    ) -> Keyed<'a> {
        let mut k = Keyed {
            bytes,
            structure,
            entries: Vec::new(),
            sections: Vec::new(),
        };
        let mut section = String::new();
        let mut at = start;
        for raw in text.split(|&b| b == b'\n') {
            let offset = at;
            at += raw.len() + 1;
            let line = latin1_or_utf8(raw.strip_suffix(b"\r").unwrap_or(raw));
            if let Some(name) = line.strip_prefix('[').and_then(|l| l.strip_suffix(']')) {
                section = name.to_string();
                k.sections.push((section.clone(), offset));
                continue;
            }
            let pair = match split {
                Split::At(c) => line.split_once(c),
                Split::Column(n) => line
                    .char_indices()
                    .nth(n)
                    .map(|(i, _)| line.split_at(i))
                    .or(Some((line.as_str(), ""))),
            };
            if let Some((key, value)) = pair.filter(|(key, _)| !key.trim().is_empty()) {
                k.entries.push(Entry {
                    section: section.clone(),
                    key: key.trim().to_string(),
                    value: value.trim().to_string(),
                    offset,
                });
            }
        }
        k
    }

    /// Whether the header has this section.
    pub fn has_section(&self, section: &str) -> bool {
        self.sections.iter().any(|(s, _)| s == section)
    }

    /// Where a section starts (the header's start when it is absent).
    fn section_offset(&self, section: &str) -> usize {
        self.sections
            .iter()
            .find(|(s, _)| s == section)
            .map_or(self.entries.first().map_or(0, |e| e.offset), |(_, o)| *o)
    }

    /// The value of `key` in `section`, if present.
    pub fn get(&self, section: &str, key: &str) -> Option<&str> {
        self.entry(section, key).map(|e| e.value.as_str())
    }

    fn entry(&self, section: &str, key: &str) -> Option<&Entry> {
        self.entries
            .iter()
            .find(|e| e.section == section && e.key == key)
    }

    /// An error about `key` of `section`, at its line (or the section's).
    pub fn error(&self, section: &str, key: &str, message: impl Into<String>) -> Error {
        let at = self
            .entry(section, key)
            .map_or_else(|| self.section_offset(section), |e| e.offset);
        let place = match section {
            "" => format!("{} ({key})", self.structure),
            s => format!("{} [{s}] ({key})", self.structure),
        };
        self.bytes.error(&place, at, message)
    }

    /// The value of `key` in `section`, or an error saying it is missing.
    pub fn text(&self, section: &str, key: &str) -> Result<&str> {
        self.get(section, key)
            .ok_or_else(|| self.error(section, key, "missing"))
    }

    /// The value parsed as `T` (its first word, so that `20 nm` gives 20),
    /// or an error naming what was found.
    pub fn number<T: std::str::FromStr>(&self, section: &str, key: &str) -> Result<T> {
        let v = self.text(section, key)?;
        let word = v.split_whitespace().next().unwrap_or("");
        word.parse()
            .map_err(|_| self.error(section, key, format!("'{v}'; a number expected")))
    }

    /// Every entry of `section` as metadata (`key` alone: sections are
    /// named by the caller where it matters).
    pub fn meta_of(&self, section: &str) -> Vec<MetaEntry> {
        self.entries
            .iter()
            .filter(|e| e.section == section)
            .map(|e| meta(&e.key, &e.value))
            .collect()
    }
}

/// A value and its unit from `20 nm` or `2e-05 m` (the unit empty when
/// absent).
pub fn quantity(value: &str) -> Option<(f64, &str)> {
    let v = value.trim();
    let split = v.find(char::is_whitespace).unwrap_or(v.len());
    let (n, u) = v.split_at(split);
    Some((n.parse().ok()?, u.trim()))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn sections_entries_offsets_and_errors() {
        let text = b"[A]\r\nx = 1\r\nname = two words\n[B]\nx=abc\nno separator\n";
        let b = Bytes::new(Path::new("h.nid"), text);
        let k = Keyed::parse(b, "T header", (text, 0), Split::At('='));
        assert_eq!(k.number::<i32>("A", "x").unwrap(), 1);
        assert_eq!(k.get("A", "name"), Some("two words"));
        assert!(k.has_section("B") && !k.has_section("C"));
        let e = k.number::<f64>("B", "x").unwrap_err().to_string();
        assert!(e.contains("h.nid: byte 33: T header [B] (x)"), "{e}");
        let e = k.text("B", "y").unwrap_err().to_string();
        assert!(e.contains("byte 29: T header [B] (y): missing"), "{e}");
        let fixed = b"xPixels       256\nbufferUnit    um\n";
        let b = Bytes::new(Path::new("m.mi"), fixed);
        let k = Keyed::parse(b, "MI header", (fixed, 0), Split::Column(14));
        assert_eq!(k.get("", "bufferUnit"), Some("um"));
        assert_eq!(quantity("600 nm"), Some((600.0, "nm")));
        assert_eq!(quantity("0.5"), Some((0.5, "")));
    }
}
