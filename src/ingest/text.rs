//! Bytes to lines: encoding detection (UTF-8 with or without BOM, UTF-16
//! with BOM, else Latin-1) and line splitting (LF, CRLF, CR, and the
//! doubled CR some instruments write). Line numbers are 1-based and kept, so
//! every later error can name its line.

use std::path::{Path, PathBuf};

use serde::Serialize;

use crate::error::{Error, Location, Result};

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
}

/// A decoded text file, split into lines.
#[derive(Debug, Clone)]
pub struct Text {
    /// The file it came from.
    pub path: PathBuf,
    /// How it was decoded.
    pub encoding: Encoding,
    /// The first line ending seen.
    pub line_ending: LineEnding,
    /// The lines without their endings; `lines[i]` is line `i + 1`. Private:
    /// readers go through [`Text::line`] and [`Text::lines`], so that the
    /// storage can change without touching them.
    lines: Vec<String>,
}

impl Text {
    /// Decodes `bytes` read from `path`.
    pub fn decode(path: &Path, bytes: &[u8]) -> Result<Text> {
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
        let (encoding, text) = decode_bytes(bytes).ok_or_else(|| {
            Error::input(
                Location::file(path),
                "encoding: invalid UTF-16 text (an unpaired surrogate)",
            )
        })?;
        if text.contains('\0') {
            return Err(Error::input(
                Location::file(path),
                "binary file (NUL bytes); expected a text export",
            ));
        }
        let line_ending = match text.find('\n') {
            Some(i) if text[..i].ends_with('\r') => LineEnding::Crlf,
            Some(_) => LineEnding::Lf,
            None if text.contains('\r') => LineEnding::Cr,
            None => LineEnding::None,
        };
        let lines = split_lines(&text, line_ending);
        Ok(Text {
            path: path.to_path_buf(),
            encoding,
            line_ending,
            lines,
        })
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
        &self.lines[i]
    }

    /// Number of lines.
    pub fn line_count(&self) -> usize {
        self.lines.len()
    }

    /// Every line in order, without endings.
    pub fn lines(&self) -> impl DoubleEndedIterator<Item = &str> + ExactSizeIterator + '_ {
        self.lines.iter().map(String::as_str)
    }
}

fn decode_bytes(bytes: &[u8]) -> Option<(Encoding, String)> {
    if let Some(rest) = bytes.strip_prefix(&[0xEF, 0xBB, 0xBF]) {
        return Some((
            Encoding::Utf8Bom,
            String::from_utf8_lossy(rest).into_owned(),
        ));
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
        return utf16(rest, true).map(|s| (Encoding::Utf16Le, s));
    }
    if let Some(rest) = bytes.strip_prefix(&[0xFE, 0xFF]) {
        return utf16(rest, false).map(|s| (Encoding::Utf16Be, s));
    }
    match std::str::from_utf8(bytes) {
        Ok(s) => Some((Encoding::Utf8, s.to_string())),
        Err(_) => Some((Encoding::Latin1, bytes.iter().map(|&b| b as char).collect())),
    }
}

fn split_lines(text: &str, ending: LineEnding) -> Vec<String> {
    let mut lines: Vec<String> = if ending == LineEnding::Cr {
        text.split('\r').map(str::to_string).collect()
    } else {
        // Strip every trailing CR: some exports write "\r\r\n".
        text.split('\n')
            .map(|l| l.trim_end_matches('\r').to_string())
            .collect()
    };
    if lines.last().is_some_and(|l| l.is_empty()) {
        lines.pop();
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn detects_bom_crlf_and_latin1() {
        let t = Text::decode(Path::new("a"), b"\xEF\xBB\xBFt;F\r\n1;2\r\n").unwrap();
        assert_eq!(t.encoding, Encoding::Utf8Bom);
        assert_eq!(t.line_ending, LineEnding::Crlf);
        assert_eq!(t.lines, vec!["t;F", "1;2"]);
        let t = Text::decode(Path::new("a"), b"x [\xB5m]\r\r\n1\n").unwrap();
        assert_eq!(t.encoding, Encoding::Latin1);
        assert_eq!(t.lines, vec!["x [µm]", "1"]);
        let t = Text::decode(Path::new("a"), b"\xFF\xFEa\x00\n\x00").unwrap();
        assert_eq!(t.encoding, Encoding::Utf16Le);
        assert_eq!(t.lines, vec!["a"]);
    }

    #[test]
    fn binary_is_refused() {
        let e = Text::decode(Path::new("x.bin"), b"PAR1\0\0\x01").unwrap_err();
        assert!(e.to_string().contains("x.bin") && e.to_string().contains("binary"));
    }
}

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
