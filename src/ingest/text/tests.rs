//! Tests of the decoding and line index of [`super`].

use super::index::SCAN_CHUNK;
use super::*;

#[test]
fn detects_bom_crlf_and_latin1() {
    let t = Text::decode(Path::new("a"), b"\xEF\xBB\xBFt;F\r\n1;2\r\n").unwrap();
    assert_eq!(t.encoding, Encoding::Utf8Bom);
    assert_eq!(t.line_ending, LineEnding::Crlf);
    assert_eq!(t.lines().collect::<Vec<_>>(), vec!["t;F", "1;2"]);
    let t = Text::decode(Path::new("a"), b"x [\xB5m]\r\r\n1\n").unwrap();
    assert_eq!(t.encoding, Encoding::Latin1);
    assert_eq!(t.lines().collect::<Vec<_>>(), vec!["x [µm]", "1"]);
    let t = Text::decode(Path::new("a"), b"\xFF\xFEa\x00\n\x00").unwrap();
    assert_eq!(t.encoding, Encoding::Utf16Le);
    assert_eq!(t.lines().collect::<Vec<_>>(), vec!["a"]);
}

/// The single sequential pass the parallel index replaced: its oracle
/// for the line starts (the final-line rule, `index::finish`, is shared).
fn sequential_starts(bytes: &[u8], ending: LineEnding) -> Vec<usize> {
    let sep = if ending == LineEnding::Cr {
        b'\r'
    } else {
        b'\n'
    };
    let mut starts = vec![0];
    starts.extend(memchr::memchr_iter(sep, bytes).map(|i| i + 1));
    super::index::finish(starts, bytes, ending)
}

fn starts_of(t: &Text) -> Vec<usize> {
    (0..t.line_count()).map(|i| t.starts.get(i)).collect()
}

/// Texts of several scan chunks, cut inside two-byte characters, with
/// every line ending, give the index of one sequential pass; NUL or
/// invalid UTF-8 in the last chunk are found as in the first.
#[test]
fn parallel_index_is_the_sequential_one() {
    let line = "µµµµµµµµ"; // 16 bytes + its ending: cuts fall inside a 'µ'
    let n = 3 * SCAN_CHUNK / 17 + 5;
    for (end, tail) in [("\n", ""), ("\r\n", "\r\r"), ("\r", "x"), ("\r\r\n", "")] {
        let inside = |b: &String| (1..4).any(|k| b.as_bytes()[k * SCAN_CHUNK] & 0xC0 == 0x80);
        let body = (0..8)
            .map(|pad| {
                format!(
                    "{}{}{tail}",
                    "a".repeat(pad),
                    format!("{line}{end}").repeat(n)
                )
            })
            .find(inside)
            .expect("a padding that cuts a character");
        let bytes = body.as_bytes();
        let t = Text::decode(Path::new("a"), bytes).unwrap();
        assert_eq!(t.encoding, Encoding::Utf8);
        assert_eq!(
            starts_of(&t),
            sequential_starts(bytes, t.line_ending),
            "{end:?}"
        );
        assert_eq!(t.lines().last(), Some(if tail == "x" { "x" } else { line }));
    }
    let mut bytes = format!("{line}\n").repeat(n).into_bytes();
    bytes.extend_from_slice(b"1,\xB5m\n");
    let t = Text::decode(Path::new("a"), &bytes).unwrap();
    assert_eq!(t.encoding, Encoding::Latin1);
    assert_eq!(
        starts_of(&t),
        sequential_starts(t.buf.as_bytes(), LineEnding::Lf)
    );
    bytes.push(0);
    assert!(Text::decode_or_binary(Path::new("a"), &bytes)
        .unwrap()
        .is_none());
    assert!(Text::decode(Path::new("a"), b"").unwrap().line_count() == 0);
}

/// Lines ending in LF or CRLF, with a bare CR ending one of them (the
/// recipe line of a real Rtec log), split at every ending, in a small
/// text and in one of several scan chunks whose only bare CR is in the
/// last chunk; the doubled CR of `\r\r\n` stays one ending.
#[test]
fn mixed_endings_split_at_every_ending() {
    let t = Text::decode(Path::new("a"), b"k1, k2\rv1,v2,\r\n1,2\n3,4\r\r\n5,6").unwrap();
    assert_eq!(t.line_ending, LineEnding::Mixed);
    let lines: Vec<&str> = t.lines().collect();
    assert_eq!(lines, ["k1, k2", "v1,v2,", "1,2", "3,4", "5,6"]);
    let mut body = "1,2\r\n".repeat(3 * SCAN_CHUNK / 5);
    body.push_str("x\ry\r\n");
    let t = Text::decode(Path::new("a"), body.as_bytes()).unwrap();
    assert_eq!(t.line_ending, LineEnding::Mixed);
    let want: Vec<&str> = body.split(['\n', '\r']).filter(|l| !l.is_empty()).collect();
    assert_eq!(t.lines().collect::<Vec<_>>(), want);
    // Latin-1 text (decoded, then indexed) is split the same way.
    let t = Text::decode(Path::new("a"), b"\xB5m\rz\n1\n").unwrap();
    assert_eq!(
        (t.encoding, t.line_ending),
        (Encoding::Latin1, LineEnding::Mixed)
    );
    assert_eq!(t.lines().collect::<Vec<_>>(), ["µm", "z", "1"]);
}

/// Bytes 0x80–0x9F are Windows-1252's printable characters (control
/// codes in ISO-8859-1, which no export writes); without them the text
/// is ISO-8859-1.
#[test]
fn windows_1252_when_its_bytes_say_so() {
    let t = Text::decode(Path::new("a"), b"\x80;\x96;\xB5m;\x93q\x94\n").unwrap();
    assert_eq!(t.encoding, Encoding::Windows1252);
    assert_eq!(t.line(0), "€;–;µm;“q”");
    let t = Text::decode(Path::new("a"), b"\xE9\xB5\n").unwrap();
    assert_eq!((t.encoding, t.line(0)), (Encoding::Latin1, "éµ"));
}

#[test]
fn binary_is_refused() {
    let e = Text::decode(Path::new("x.bin"), b"PAR1\0\0\x01").unwrap_err();
    assert!(e.to_string().contains("x.bin") && e.to_string().contains("binary"));
}
