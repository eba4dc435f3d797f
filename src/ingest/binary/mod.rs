//! What binary and structured readers share: the file's bytes with their
//! path ([`Bytes`]), a bounds-checked [`Cursor`] over fixed-layout headers,
//! sample decoding into one `f64` buffer ([`decode`]), a zip container
//! ([`zip`]) and a small XML tree ([`xml`]).
//!
//! Every failure is an [`Error::Structure`] naming the file, the structure
//! that failed and the byte offset: a truncated, corrupted or unknown
//! version of a file is never a panic, and never a map read from the wrong
//! bytes.

pub mod decode;
pub mod hdf5;
pub mod keyed;
pub mod rows;
pub mod units;
pub mod xml;
pub mod zip;

use std::path::Path;

use super::grid::Grid;
use super::source::Source;
use super::{apply_units, named_reader, Dataset, IngestOptions, MetaEntry, Section};
use crate::error::{Error, Result};

/// What a binary reader gives: the file's metadata, its channels on a grid,
/// and tables where the format holds some.
#[derive(Debug, Clone, Default)]
pub struct Decoded {
    /// File-level metadata.
    pub preamble: Vec<MetaEntry>,
    /// Tables, if any.
    pub sections: Vec<Section>,
    /// Channels on a grid: every channel the file holds, the selected one
    /// decoded ([`select_channel`]).
    pub grids: Vec<Grid>,
}

/// Reads a file with a binary reader: the one named in the options, or
/// the first whose `sniff_bytes` recognises it. `None` when the named
/// reader reads text, or no binary reader recognises the bytes.
pub fn read(bytes: &Bytes, options: &IngestOptions) -> Result<Option<Dataset>> {
    let named = named_reader(options)?;
    let sniffed = || {
        super::READERS
            .iter()
            .copied()
            .find(|r| r.sniff_bytes(bytes.data))
    };
    let Some(reader) = named.or_else(|| options.format.is_none().then(sniffed).flatten()) else {
        return Ok(None);
    };
    let Some(decoded) = reader.read_bytes(bytes, options) else {
        return Ok(None);
    };
    let Decoded {
        preamble,
        mut sections,
        grids,
    } = decoded?;
    apply_units(bytes.path, &mut sections, options)?;
    Ok(Some(Dataset {
        source: bytes.path.to_path_buf(),
        sha256: String::new(), // set by `hashed`, beside which the read ran
        format: reader.name(),
        dialect: None,
        preamble,
        sections,
        grids,
    }))
}

/// A binary file's bytes, as read or mapped.
#[derive(Clone, Copy)]
pub struct Bytes<'a> {
    /// The file, for messages.
    pub path: &'a Path,
    /// Its bytes.
    pub data: &'a [u8],
    source: Option<&'a Source>,
}

impl<'a> Bytes<'a> {
    /// Bytes from a [`Source`]: a mapped file's decoded pages can be
    /// released ([`Bytes::release`]).
    pub fn from_source(path: &'a Path, source: &'a Source) -> Bytes<'a> {
        Bytes {
            path,
            data: source.bytes(),
            source: Some(source),
        }
    }

    /// Bytes already in memory.
    pub fn new(path: &'a Path, data: &'a [u8]) -> Bytes<'a> {
        Bytes {
            path,
            data,
            source: None,
        }
    }

    /// Length in bytes.
    pub fn len(&self) -> usize {
        self.data.len()
    }

    /// Whether the file is empty.
    pub fn is_empty(&self) -> bool {
        self.data.is_empty()
    }

    /// An [`Error::Structure`] in this file.
    pub fn error(&self, structure: &str, offset: usize, message: impl Into<String>) -> Error {
        Error::Structure {
            path: self.path.to_path_buf(),
            structure: structure.to_string(),
            offset: offset as u64,
            message: message.into(),
        }
    }

    /// `len` bytes from `offset`, or an error saying where the file ends.
    pub fn slice(&self, offset: usize, len: usize, structure: &str) -> Result<&'a [u8]> {
        match offset.checked_add(len) {
            Some(end) if end <= self.data.len() => Ok(&self.data[offset..end]),
            _ => Err(self.error(
                structure,
                offset,
                format!(
                    "needs {len} bytes from here, but the file ends at byte {} (truncated?)",
                    self.data.len()
                ),
            )),
        }
    }

    /// A little-endian cursor at `offset` for `structure`.
    pub fn le(&self, offset: usize, structure: &'a str) -> Cursor<'a> {
        Cursor {
            bytes: *self,
            pos: offset,
            structure,
            big: false,
        }
    }

    /// A big-endian cursor at `offset` for `structure`.
    pub fn be(&self, offset: usize, structure: &'a str) -> Cursor<'a> {
        Cursor {
            big: true,
            ..self.le(offset, structure)
        }
    }

    /// Hands the pages of `range` back to the kernel when the file is
    /// mapped (see [`Source::release`]): what a decoder has converted is
    /// not kept resident beside the values.
    pub fn release(&self, range: std::ops::Range<usize>) {
        if let Some(s) = self.source {
            s.release(range);
        }
    }
}

/// A position in a fixed-layout structure: each read is bounds-checked and
/// names its field in the error.
#[derive(Clone, Copy)]
pub struct Cursor<'a> {
    bytes: Bytes<'a>,
    pos: usize,
    structure: &'a str,
    big: bool,
}

macro_rules! read_num {
    ($($name:ident: $t:ty),*) => {$(
        #[doc = concat!("Reads a `", stringify!($t), "` in the cursor's byte order.")]
        pub fn $name(&mut self, field: &str) -> Result<$t> {
            let b = self.take(std::mem::size_of::<$t>(), field)?;
            let a = b.try_into().expect("take gives the length asked");
            Ok(if self.big { <$t>::from_be_bytes(a) } else { <$t>::from_le_bytes(a) })
        }
    )*};
}

impl<'a> Cursor<'a> {
    read_num!(u8: u8, i8: i8, u16: u16, i16: i16, u32: u32, i32: i32, u64: u64, i64: i64, f32: f32, f64: f64);

    /// Byte offset in the file.
    pub fn pos(&self) -> usize {
        self.pos
    }

    /// Moves to `offset`.
    pub fn seek(&mut self, offset: usize) {
        self.pos = offset;
    }

    /// Skips `n` bytes (checked when they are read past).
    pub fn skip(&mut self, n: usize) {
        self.pos = self.pos.saturating_add(n);
    }

    /// `n` bytes.
    pub fn take(&mut self, n: usize, field: &str) -> Result<&'a [u8]> {
        let data = self.bytes.data;
        match self.pos.checked_add(n) {
            Some(end) if end <= data.len() => {
                let s = &data[self.pos..end];
                self.pos = end;
                Ok(s)
            }
            _ => Err(self.bytes.error(
                &format!("{} ({field})", self.structure),
                self.pos,
                format!(
                    "needs {n} bytes from here, but the file ends at byte {} (truncated?)",
                    data.len()
                ),
            )),
        }
    }

    /// A fixed-width text field: up to the first NUL, trimmed; Latin-1
    /// where it is not UTF-8 (instrument software writes both).
    pub fn text(&mut self, n: usize, field: &str) -> Result<String> {
        Ok(latin1_or_utf8(self.take(n, field)?))
    }

    /// An error at the cursor's position.
    pub fn error(&self, message: impl Into<String>) -> Error {
        self.bytes.error(self.structure, self.pos, message)
    }

    /// An error about `field` read just before the cursor (`size` bytes).
    pub fn bad(&self, field: &str, size: usize, message: impl std::fmt::Display) -> Error {
        self.bytes.error(
            &format!("{} ({field})", self.structure),
            self.pos.saturating_sub(size),
            message.to_string(),
        )
    }
}

/// Text up to the first NUL, trimmed: UTF-8 when valid, else Latin-1.
pub fn latin1_or_utf8(b: &[u8]) -> String {
    let end = b.iter().position(|&c| c == 0).unwrap_or(b.len());
    let b = &b[..end];
    match std::str::from_utf8(b) {
        Ok(s) => s.trim().to_string(),
        Err(_) => b
            .iter()
            .map(|&c| c as char)
            .collect::<String>()
            .trim()
            .to_string(),
    }
}

/// A metadata entry of a binary file (no line: `line` is 0).
pub fn meta(key: &str, value: impl ToString) -> MetaEntry {
    MetaEntry {
        key: key.to_string(),
        value: value.to_string(),
        line: 0,
    }
}

/// The keys binary readers give the metadata every format has in some
/// form, so that `inspect` and the tables name them alike; each reader
/// keeps its format's own fields beside them, under their own names.
pub mod keys {
    /// Instrument (maker, model, software as the file names it).
    pub const INSTRUMENT: &str = "instrument";
    /// Acquisition date and time, ISO 8601 (`2018-12-05T12:53:14`).
    pub const DATE: &str = "acquisition_date";
    /// Lateral unit as written in the file.
    pub const LATERAL_UNIT: &str = "lateral_unit";
    /// Height unit as written in the file.
    pub const HEIGHT_UNIT: &str = "height_unit";
    /// Lateral scale factors (spacing per pixel, in the lateral unit).
    pub const LATERAL_SCALE: &str = "lateral_scale";
    /// Height scale factor (height per raw count, in the height unit).
    pub const HEIGHT_SCALE: &str = "height_scale";
    /// Objective (optical instruments).
    pub const OBJECTIVE: &str = "objective";
    /// Tip or stylus (AFM, stylus profilers).
    pub const TIP: &str = "tip";
}

/// An ISO 8601 date and time from its parts, when they make one.
pub fn iso_date(y: i64, mo: i64, d: i64, h: i64, mi: i64, s: i64) -> Option<String> {
    let leap = y % 4 == 0 && (y % 100 != 0 || y % 400 == 0);
    let days = match mo {
        2 if leap => 29,
        2 => 28,
        4 | 6 | 9 | 11 => 30,
        _ => 31,
    };
    let ok = (1900..=2200).contains(&y)
        && (1..=12).contains(&mo)
        && (1..=days).contains(&d)
        && (0..24).contains(&h)
        && (0..60).contains(&mi)
        && (0..=60).contains(&s);
    ok.then(|| format!("{y:04}-{mo:02}-{d:02}T{h:02}:{mi:02}:{s:02}"))
}

/// A Unix time as ISO 8601 (UTC), for plausible times.
pub fn unix_date(t: i32) -> Option<String> {
    if t <= 0 {
        return None;
    }
    let days = (t as i64).div_euclid(86_400);
    let s = (t as i64).rem_euclid(86_400);
    // Civil date from days since 1970-01-01 (H. Hinnant's algorithm).
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z - era * 146_097;
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let mo = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + (mo <= 2) as i64;
    iso_date(y, mo, d, s / 3600, s / 60 % 60, s % 60).map(|d| d + "Z")
}

/// Which of a file's channels to decode: the one named in the options
/// (case-insensitive), else the first height channel, else the first.
/// A name that is not in the file is an error listing the channels.
pub fn select_channel(bytes: &Bytes, grids: &[Grid], options: &IngestOptions) -> Result<usize> {
    if let Some(want) = &options.channel {
        return grids
            .iter()
            .position(|g| g.name.eq_ignore_ascii_case(want.trim()))
            .ok_or_else(|| {
                let names: Vec<String> = grids.iter().map(|g| format!("'{}'", g.name)).collect();
                Error::input(
                    crate::error::Location::file(bytes.path),
                    format!(
                        "no channel '{want}' in this file; its channels are {}",
                        names.join(", ")
                    ),
                )
            });
    }
    Ok(grids.iter().position(|g| g.height).unwrap_or(0))
}

/// Checks a grid's size and spacing as read from a header: sides ≥ 1, a
/// product that fits in memory's addressing, spacings finite and > 0.
pub fn check_grid(bytes: &Bytes, structure: &str, offset: usize, g: &Grid) -> Result<()> {
    let n = g.nx.checked_mul(g.ny);
    if g.nx == 0 || g.ny == 0 || n.is_none_or(|n| n > (1 << 34)) {
        return Err(bytes.error(
            structure,
            offset,
            format!("a grid of {} × {} points; expected sides ≥ 1", g.nx, g.ny),
        ));
    }
    for (axis, d) in [("x", g.dx), ("y", g.dy)] {
        if !(d.is_finite() && d > 0.0) {
            return Err(bytes.error(
                structure,
                offset,
                format!("spacing along {axis} is {d} m; expected a finite value > 0"),
            ));
        }
    }
    Ok(())
}

/// As [`check_grid`], for a file whose lateral unit may be unknown: a
/// NaN spacing (to be given by the user, `--spacing`) passes; the sides
/// and any spacing the file gives are checked.
pub fn check_grid_or_unspaced(
    bytes: &Bytes,
    structure: &str,
    offset: usize,
    g: &Grid,
) -> Result<()> {
    let mut probe = g.clone();
    for d in [&mut probe.dx, &mut probe.dy] {
        if d.is_nan() {
            *d = 1.0;
        }
    }
    check_grid(bytes, structure, offset, &probe)
}

#[cfg(test)]
mod tests {
    #[test]
    fn unix_dates() {
        assert_eq!(super::unix_date(0), None);
        assert_eq!(
            super::unix_date(951_782_400).as_deref(),
            Some("2000-02-29T00:00:00Z")
        );
        assert_eq!(
            super::unix_date(1_700_000_000).as_deref(),
            Some("2023-11-14T22:13:20Z")
        );
        assert_eq!(super::iso_date(2023, 2, 29, 0, 0, 0), None);
        assert_eq!(
            super::iso_date(2024, 2, 29, 1, 2, 3).as_deref(),
            Some("2024-02-29T01:02:03")
        );
    }
}
