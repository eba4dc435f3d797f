//! Bytes to lines: encoding detection (UTF-8 with or without BOM, UTF-16
//! with BOM, else Latin-1, or Windows-1252 when bytes 0x80–0x9F say so) and
//! line splitting (LF, CRLF, CR, the doubled CR some instruments write, and
//! files that mix them). Line numbers are 1-based and kept, so
//! every later error can name its line.

use std::borrow::Cow;
use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::error::{Error, Location, Result};

mod index;
use index::{index, Scanned, Starts};

/// How the bytes were decoded.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Encoding {
    /// UTF-8 (also plain ASCII).
    Utf8,
    /// UTF-8 with a byte-order mark.
    Utf8Bom,
    /// UTF-16 little endian, with BOM.
    Utf16Le,
    /// UTF-16 big endian, with BOM.
    Utf16Be,
    /// ISO-8859-1: every byte is one character. Used when the bytes are not
    /// valid UTF-8 (for example a lone 0xB5 micro sign).
    Latin1,
    /// Windows-1252: ISO-8859-1 but for bytes 0x80–0x9F, which are
    /// printable there (`€`, `…`, `–`, curly quotes) and control codes in
    /// ISO-8859-1, where no text export writes them. Used for bytes that
    /// are not UTF-8 and hold one of those.
    Windows1252,
}

/// The line ending found first in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "UPPERCASE")]
pub enum LineEnding {
    /// `\n`
    Lf,
    /// `\r\n`
    Crlf,
    /// `\r`
    Cr,
    /// A single line without ending.
    None,
    /// LF or CRLF, with bare CRs ending some lines too (a recipe line of an
    /// Rtec log): every one of them ends a line.
    Mixed,
}

/// A decoded text file, split into lines. UTF-8 text borrows the bytes it
/// was decoded from (no copy of a large file); other encodings own their
/// decoded text.
#[derive(Debug, Clone)]
pub struct Text<'a> {
    /// The file it came from.
    pub path: PathBuf,
    /// How it was decoded.
    pub encoding: Encoding,
    /// The first line ending seen.
    pub line_ending: LineEnding,
    /// The decoded text, one buffer for the whole file.
    buf: Cow<'a, str>,
    /// Where each line starts in `buf`; line `i + 1` runs from `starts[i]`
    /// to the next line's start, less its ending. Private: readers go
    /// through [`Text::line`] and [`Text::lines`], so that the storage can
    /// change without touching them.
    starts: Starts,
    /// The mapped file the text borrows, when it does byte for byte (plain
    /// UTF-8): lines parsed can be released ([`Text::release_lines`]).
    source: Option<&'a super::source::Source>,
}

impl<'a> Text<'a> {
    /// Decodes `bytes` read from `path`; UTF-8 text is borrowed, not copied.
    pub fn decode(path: &Path, bytes: &'a [u8]) -> Result<Text<'a>> {
        Text::decode_or_binary(path, bytes)?.ok_or_else(|| binary_error(path))
    }

    /// As [`Text::decode`], but `None` when the decoded text holds NUL
    /// bytes (a binary file), so that a caller which treats a binary file as
    /// no data needs no pass of its own to find them. Plain UTF-8 (the
    /// common case, no byte-order mark) is checked, validated and indexed
    /// in one parallel pass ([`index`]); other bytes are decoded first.
    pub fn decode_or_binary(path: &Path, bytes: &'a [u8]) -> Result<Option<Text<'a>>> {
        check_utf16_length(path, bytes)?;
        let bom = bytes.starts_with(&[0xEF, 0xBB, 0xBF])
            || bytes.starts_with(&[0xFF, 0xFE])
            || bytes.starts_with(&[0xFE, 0xFF]);
        if !bom {
            let ending = line_ending(bytes);
            let scanned = index(bytes, ending, true);
            let ending = match scanned {
                Scanned::Mixed(_) => LineEnding::Mixed,
                _ => ending,
            };
            match scanned {
                Scanned::Binary => return Ok(None),
                Scanned::Lines(starts) | Scanned::Mixed(starts) => {
                    // SAFETY: `index` validated every chunk of the bytes
                    // as UTF-8, and a concatenation of valid UTF-8 is valid.
                    let s = unsafe { std::str::from_utf8_unchecked(bytes) };
                    let text =
                        Text::assemble(path, Encoding::Utf8, ending, Cow::Borrowed(s), starts);
                    return Ok(Some(text));
                }
                Scanned::NotUtf8 => {}
            }
        }
        let (encoding, text) = decode_bytes(bytes).ok_or_else(|| utf16_error(path))?;
        Ok(Text::from_decoded(path, encoding, text))
    }

    /// Decodes a file's [`Source`](super::source::Source) (see
    /// [`Text::decode_source_or_binary`]).
    pub fn decode_source(path: &Path, source: &'a super::source::Source) -> Result<Text<'a>> {
        Text::decode_source_or_binary(path, source)?.ok_or_else(|| binary_error(path))
    }

    /// Decodes a file's [`Source`](super::source::Source): as
    /// [`Text::decode_or_binary`], the text remembering the mapped file it
    /// borrows, so that a parser of a long block can release what it has
    /// parsed. The decoding pass releases nothing: the parse that follows
    /// reads every page again, and would only fault them back in.
    pub fn decode_source_or_binary(
        path: &Path,
        source: &'a super::source::Source,
    ) -> Result<Option<Text<'a>>> {
        let mut text = Text::decode_or_binary(path, source.bytes())?;
        if let Some(text) = text.as_mut().filter(|t| t.encoding == Encoding::Utf8) {
            text.source = Some(source);
        }
        Ok(text)
    }

    /// Releases the bytes of lines `lines` (0-based) when the text borrows
    /// a mapped file; they read back unchanged if touched again.
    pub fn release_lines(&self, lines: std::ops::Range<usize>) {
        let Some(source) = self.source else {
            return;
        };
        let at = |i: usize| match i < self.starts.len() {
            true => self.starts.get(i),
            false => self.buf.len(),
        };
        source.release(at(lines.start)..at(lines.end));
    }

    /// As [`Text::decode`], taking the bytes: UTF-8 text (the common case)
    /// becomes the text buffer without a copy, so a large file is held once.
    pub fn decode_owned(path: &Path, bytes: Vec<u8>) -> Result<Text<'static>> {
        check_utf16_length(path, &bytes)?;
        let plain_utf8 = !bytes.starts_with(&[0xEF, 0xBB, 0xBF])
            && !bytes.starts_with(&[0xFF, 0xFE])
            && !bytes.starts_with(&[0xFE, 0xFF]);
        if plain_utf8 {
            match String::from_utf8(bytes) {
                Ok(s) => {
                    return Text::from_decoded(path, Encoding::Utf8, Cow::Owned(s))
                        .ok_or_else(|| binary_error(path))
                }
                Err(e) => return Text::decode(path, e.as_bytes()).map(Text::into_owned),
            }
        }
        Text::decode(path, &bytes).map(Text::into_owned)
    }

    /// This text owning its buffer.
    pub fn into_owned(self) -> Text<'static> {
        Text {
            path: self.path,
            encoding: self.encoding,
            line_ending: self.line_ending,
            buf: Cow::Owned(self.buf.into_owned()),
            starts: self.starts,
            source: None,
        }
    }

    /// Text already decoded, indexed; `None` when it holds NUL bytes.
    fn from_decoded(path: &Path, encoding: Encoding, text: Cow<'a, str>) -> Option<Text<'a>> {
        let ending = line_ending(text.as_bytes());
        match index(text.as_bytes(), ending, false) {
            Scanned::Lines(starts) => Some(Text::assemble(path, encoding, ending, text, starts)),
            Scanned::Mixed(starts) => {
                let ending = LineEnding::Mixed;
                Some(Text::assemble(path, encoding, ending, text, starts))
            }
            Scanned::Binary | Scanned::NotUtf8 => None,
        }
    }

    fn assemble(
        path: &Path,
        encoding: Encoding,
        line_ending: LineEnding,
        buf: Cow<'a, str>,
        starts: Starts,
    ) -> Text<'a> {
        Text {
            path: path.to_path_buf(),
            encoding,
            line_ending,
            buf,
            starts,
            source: None,
        }
    }

    /// A location in this file.
    pub fn at(&self, line: usize) -> Location {
        Location::line(&self.path, line)
    }

    /// The first `n` lines, for sniffing.
    pub fn head(&self, n: usize) -> Vec<&str> {
        self.lines().take(n).collect()
    }

    /// Line `i + 1` (0-based index), without its ending.
    pub fn line(&self, i: usize) -> &str {
        let start = self.starts.get(i);
        let cr = self.line_ending == LineEnding::Cr;
        if i + 1 < self.starts.len() {
            let line = &self.buf[start..self.starts.get(i + 1) - 1]; // less its '\n' or '\r'
                                                                     // Strip every trailing CR: some exports write "\r\r\n".
            return if cr {
                line
            } else {
                line.trim_end_matches('\r')
            };
        }
        // The last line may still carry its ending.
        let line = &self.buf[start..];
        if cr {
            line.strip_suffix('\r').unwrap_or(line)
        } else {
            let line = line.trim_end_matches('\r');
            line.strip_suffix('\n')
                .unwrap_or(line)
                .trim_end_matches('\r')
        }
    }

    /// Number of lines.
    pub fn line_count(&self) -> usize {
        self.starts.len()
    }

    /// Every line in order, without endings.
    pub fn lines(&self) -> impl DoubleEndedIterator<Item = &str> + ExactSizeIterator + '_ {
        (0..self.line_count()).map(|i| self.line(i))
    }
}

fn decode_bytes(bytes: &[u8]) -> Option<(Encoding, Cow<'_, str>)> {
    if let Some(rest) = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]) {
        return Some((Encoding::Utf8Bom, String::from_utf8_lossy(rest)));
    }
    let utf16 = |rest: &[u8], le: bool| {
        let units = rest.chunks_exact(2).map(|c| {
            if le {
                u16::from_le_bytes([c[0], c[1]])
            } else {
                u16::from_be_bytes([c[0], c[1]])
            }
        });
        char::decode_utf16(units)
            .collect::<Result<String, _>>()
            .ok()
    };
    if let Some(rest) = bytes.strip_prefix(&[0xFF, 0xFE]) {
        return utf16(rest, true).map(|s| (Encoding::Utf16Le, Cow::Owned(s)));
    }
    if let Some(rest) = bytes.strip_prefix(&[0xFE, 0xFF]) {
        return utf16(rest, false).map(|s| (Encoding::Utf16Be, Cow::Owned(s)));
    }
    match std::str::from_utf8(bytes) {
        Ok(s) => Some((Encoding::Utf8, Cow::Borrowed(s))),
        Err(_) if bytes.iter().any(|b| (0x80..0xA0).contains(b)) => Some((
            Encoding::Windows1252,
            Cow::Owned(bytes.iter().map(|&b| windows_1252(b)).collect()),
        )),
        Err(_) => Some((
            Encoding::Latin1,
            Cow::Owned(bytes.iter().map(|&b| b as char).collect()),
        )),
    }
}

/// The Windows-1252 character of a byte: ISO-8859-1's but for 0x80–0x9F
/// (the five bytes Windows-1252 leaves undefined keep their code).
fn windows_1252(b: u8) -> char {
    const HIGH: [char; 32] = [
        '€', '\u{81}', '‚', 'ƒ', '„', '…', '†', '‡', 'ˆ', '‰', 'Š', '‹', 'Œ', '\u{8D}', 'Ž',
        '\u{8F}', '\u{90}', '‘', '’', '“', '”', '•', '–', '—', '˜', '™', 'š', '›', 'œ', '\u{9D}',
        'ž', 'Ÿ',
    ];
    match b {
        0x80..=0x9F => HIGH[usize::from(b - 0x80)],
        _ => char::from(b),
    }
}

fn check_utf16_length(path: &Path, bytes: &[u8]) -> Result<()> {
    let utf16 = bytes.starts_with(&[0xFF, 0xFE]) || bytes.starts_with(&[0xFE, 0xFF]);
    if utf16 && bytes.len() % 2 == 1 {
        return Err(Error::input(
            Location::file(path),
            format!(
                "encoding: UTF-16 text (byte-order mark) of odd length ({} bytes): \
                 the file is cut inside a character; expected whole 2-byte units",
                bytes.len()
            ),
        ));
    }
    Ok(())
}

fn utf16_error(path: &Path) -> Error {
    Error::input(
        Location::file(path),
        "encoding: invalid UTF-16 text (an unpaired surrogate)",
    )
}

/// The error of a text that holds NUL bytes.
pub fn binary_error(path: &Path) -> Error {
    Error::input(
        Location::file(path),
        "binary file (NUL bytes); expected a text export",
    )
}

/// The first line ending in `bytes`.
fn line_ending(bytes: &[u8]) -> LineEnding {
    match memchr::memchr(b'\n', bytes) {
        Some(i) if i > 0 && bytes[i - 1] == b'\r' => LineEnding::Crlf,
        Some(_) => LineEnding::Lf,
        None if memchr::memchr(b'\r', bytes).is_some() => LineEnding::Cr,
        None => LineEnding::None,
    }
}

#[cfg(test)]
mod tests;

/// A field or line as quoted in a message: cut to 80 characters, with the
/// full length said, so a huge junk field is never echoed whole.
pub fn quoted(s: &str) -> String {
    let n = s.chars().count();
    if n <= 80 {
        return format!("'{s}'");
    }
    let head: String = s.chars().take(80).collect();
    format!("'{head}…' ({n} characters)")
}

#[cfg(test)]
mod quoted_tests {
    use super::*;

    #[test]
    fn long_tokens_are_cut_and_their_length_said() {
        assert_eq!(quoted("1,5"), "'1,5'");
        let long = "9".repeat(5_000_000);
        let q = quoted(&long);
        assert!(q.len() < 120 && q.ends_with("(5000000 characters)"), "{q}");
    }

    #[test]
    fn odd_utf16_is_an_encoding_error() {
        let mut b = vec![0xFF, 0xFE];
        for c in b"t,F\n0,1\n" {
            b.extend_from_slice(&[*c, 0]);
        }
        b.pop();
        let e = Text::decode(Path::new("x.csv"), &b)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("encoding: UTF-16") && e.contains("odd length"),
            "{e}"
        );
    }
}
