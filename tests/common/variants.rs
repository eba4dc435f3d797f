//! Generated variants of a text export: the same content written with
//! another line ending or encoding, and what a reader makes of it, as a
//! signature two variants must share.

use std::path::Path;

use tribo::ingest::inspect::inspect;
use tribo::ingest::{read_path, Dataset, IngestOptions};

/// How lines end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Ending {
    /// `\n`
    Lf,
    /// `\r\n`
    Crlf,
    /// `\r` (classic Mac)
    Cr,
    /// A bare `\r` after the first line, `\r\n` after the others (the real
    /// Rtec log).
    FirstCr,
}

/// How characters become bytes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Enc {
    /// UTF-8 without byte-order mark.
    Utf8,
    /// UTF-8 with a byte-order mark.
    Utf8Bom,
    /// UTF-16 little endian with a byte-order mark.
    Utf16Le,
    /// UTF-16 big endian with a byte-order mark.
    Utf16Be,
    /// ISO-8859-1 (every character below U+0100).
    Latin1,
}

/// Every line ending.
pub const ENDINGS: [Ending; 4] = [Ending::Lf, Ending::Crlf, Ending::Cr, Ending::FirstCr];
/// Every encoding.
pub const ENCODINGS: [Enc; 5] = [
    Enc::Utf8,
    Enc::Utf8Bom,
    Enc::Utf16Le,
    Enc::Utf16Be,
    Enc::Latin1,
];

/// `text` (lines joined by `\n`) with `ending` and `enc`.
pub fn render(text: &str, ending: Ending, enc: Enc) -> Vec<u8> {
    let lines: Vec<&str> = text.lines().collect();
    let mut s = String::new();
    for (i, l) in lines.iter().enumerate() {
        s.push_str(l);
        s.push_str(match (ending, i) {
            (Ending::Lf, _) => "\n",
            (Ending::Crlf, _) => "\r\n",
            (Ending::Cr, _) | (Ending::FirstCr, 0) => "\r",
            (Ending::FirstCr, _) => "\r\n",
        });
    }
    match enc {
        Enc::Utf8 => s.into_bytes(),
        Enc::Utf8Bom => [&[0xEF, 0xBB, 0xBF][..], s.as_bytes()].concat(),
        Enc::Utf16Le => [
            vec![0xFF, 0xFE],
            s.encode_utf16().flat_map(u16::to_le_bytes).collect(),
        ]
        .concat(),
        Enc::Utf16Be => [
            vec![0xFE, 0xFF],
            s.encode_utf16().flat_map(u16::to_be_bytes).collect(),
        ]
        .concat(),
        Enc::Latin1 => s
            .chars()
            .map(|c| u8::try_from(u32::from(c)).expect("a Latin-1 character"))
            .collect(),
    }
}

/// Writes `bytes` as `dir/name` and reads it.
pub fn read_written(dir: &Path, name: &str, bytes: &[u8]) -> Dataset {
    let p = dir.join(name);
    std::fs::write(&p, bytes).unwrap();
    read_path(&p, &IngestOptions::default()).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// One column as a reader gives it: name, SI unit, role, values (bits).
pub type Column = (String, String, Option<&'static str>, Vec<u64>);

/// Each section's name and columns (sorted by name, so that a variant
/// with another column order has the same signature).
pub fn signature(ds: &Dataset) -> Vec<(String, Vec<Column>)> {
    let info = inspect(ds, &Default::default());
    info.sections
        .iter()
        .zip(&ds.sections)
        .map(|(i, s)| {
            let mut cols: Vec<Column> = i
                .columns
                .iter()
                .zip(&s.channels)
                .map(|(c, ch)| {
                    let bits = ch.values.iter().map(|v| v.to_bits()).collect();
                    (c.name.clone(), c.si_unit.clone(), c.role, bits)
                })
                .collect();
            cols.sort_by(|a, b| a.0.cmp(&b.0));
            (s.name.clone(), cols)
        })
        .collect()
}

/// Asserts two signatures are equal, saying where they first differ.
pub fn assert_same(want: &[(String, Vec<Column>)], got: &[(String, Vec<Column>)], what: &str) {
    assert_eq!(want.len(), got.len(), "{what}: sections");
    for ((wn, wc), (gn, gc)) in want.iter().zip(got) {
        assert_eq!(wn, gn, "{what}: section name");
        let names = |c: &[Column]| {
            c.iter()
                .map(|c| (c.0.clone(), c.1.clone(), c.2))
                .collect::<Vec<_>>()
        };
        assert_eq!(names(wc), names(gc), "{what}: {wn} columns");
        for (w, g) in wc.iter().zip(gc) {
            assert!(w.3 == g.3, "{what}: {wn} column '{}' values differ", w.0);
        }
    }
}

/// The columns of `text` (a delimited table, first line the header) in
/// the order `order` gives (indices into the original columns).
pub fn reorder(lines: &[String], delimiter: char, order: &[usize]) -> Vec<String> {
    lines
        .iter()
        .map(|l| {
            let f: Vec<&str> = l.split(delimiter).collect();
            let trailing = l.ends_with(delimiter);
            let mut out: Vec<&str> = order
                .iter()
                .map(|&k| f.get(k).copied().unwrap_or(""))
                .collect();
            if trailing {
                out.push("");
            }
            out.join(&delimiter.to_string())
        })
        .collect()
}
