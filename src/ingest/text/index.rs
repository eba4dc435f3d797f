//! The line index of a text: one parallel pass over chunks cut at
//! character boundaries that checks for NUL bytes, validates UTF-8 and
//! finds where each line starts, giving the index one sequential pass
//! would, whatever the thread count.

use super::LineEnding;

/// Line starts as 32-bit offsets when the text is under 4 GiB (half the
/// memory of a `usize` index on the files that matter), else 64-bit.
#[derive(Debug, Clone)]
pub(super) enum Starts {
    Small(Vec<u32>),
    Large(Vec<usize>),
}

impl Starts {
    pub(super) fn len(&self) -> usize {
        match self {
            Starts::Small(v) => v.len(),
            Starts::Large(v) => v.len(),
        }
    }
    pub(super) fn get(&self, i: usize) -> usize {
        match self {
            Starts::Small(v) => v[i] as usize,
            Starts::Large(v) => v[i],
        }
    }
}

/// Bytes per task of the decoding pass: small enough that a chunk stays in
/// the core's cache across its scans (NUL, UTF-8, line ends).
pub(super) const SCAN_CHUNK: usize = 1 << 20;

/// What the decoding pass found.
pub(super) enum Scanned {
    /// NUL bytes: a binary file.
    Binary,
    /// Bytes that are not UTF-8 (only when asked to check).
    NotUtf8,
    /// Valid text, and where each line starts.
    Lines(Starts),
    /// Valid text whose lines end in LF or CRLF but also in a bare CR
    /// somewhere (an export that wrote one line with a classic Mac ending):
    /// where each line starts, splitting at LF, CRLF and bare CR alike.
    Mixed(Starts),
}

/// The decoding pass over `bytes`: the NUL check, the UTF-8 validation
/// (when `check_utf8`) and the line index, in one pass over chunks cut at
/// character boundaries and scanned on rayon's threads, each chunk's line
/// starts concatenated in file order, so the index is the one a single
/// sequential pass gives whatever the thread count. Line starts are
/// 32-bit offsets when the text is under 4 GiB (half the memory of a
/// `usize` index on the files that matter), built at that width.
///
/// A text whose first line ending is LF or CRLF is also searched for bare
/// CRs (a CR followed by neither CR nor LF); when it has one, its lines are
/// indexed again splitting at every ending ([`Scanned::Mixed`]), so that
/// no line holds another's text after a CR.
pub(super) fn index(bytes: &[u8], ending: LineEnding, check_utf8: bool) -> Scanned {
    let sep = match ending {
        LineEnding::Cr => b'\r',
        _ => b'\n',
    };
    let find_bare_cr = matches!(ending, LineEnding::Lf | LineEnding::Crlf);
    let small = u32::try_from(bytes.len()).is_ok();
    let scanned = match small {
        true => scan::<u32>(bytes, sep, check_utf8, find_bare_cr)
            .map(|(v, mixed)| (Starts::Small(finish(v, bytes, ending)), mixed)),
        false => scan::<usize>(bytes, sep, check_utf8, find_bare_cr)
            .map(|(v, mixed)| (Starts::Large(finish(v, bytes, ending)), mixed)),
    };
    match scanned {
        Ok((starts, false)) => Scanned::Lines(starts),
        Ok((_, true)) => Scanned::Mixed(match small {
            true => Starts::Small(finish(mixed_starts(bytes), bytes, ending)),
            false => Starts::Large(finish(mixed_starts(bytes), bytes, ending)),
        }),
        Err(binary) if binary => Scanned::Binary,
        Err(_) => Scanned::NotUtf8,
    }
}

/// Whether the CR at `i` is a line ending of its own: followed by neither
/// LF (CRLF) nor another CR (the doubled CR of `\r\r\n`), nor the end.
fn bare_cr(bytes: &[u8], i: usize) -> bool {
    !matches!(bytes.get(i + 1), None | Some(b'\n' | b'\r'))
}

/// Line starts of a text with mixed endings: after every LF and every bare
/// CR. Sequential: such files are rare and small (a hand-edited export).
fn mixed_starts<T: Copy + TryFrom<usize>>(bytes: &[u8]) -> Vec<T> {
    let at = |i: usize| T::try_from(i).ok().expect("offset fits the index width");
    let mut starts = vec![at(0)];
    for i in memchr::memchr2_iter(b'\n', b'\r', bytes) {
        if bytes[i] == b'\n' || bare_cr(bytes, i) {
            starts.push(at(i + 1));
        }
    }
    starts
}

/// The chunks' scans of [`index`]: the line starts (with the first line's
/// at 0) and whether a bare CR was found (looked for when `find_bare_cr`),
/// or `Err(true)` for NUL bytes, `Err(false)` for bytes that are not
/// UTF-8. NUL bytes anywhere win over invalid UTF-8 (a binary file is
/// binary whatever its encoding); once either is found, the remaining
/// chunks skip the work that can no longer matter, which changes no
/// result.
fn scan<T: Copy + TryFrom<usize> + Send>(
    bytes: &[u8],
    sep: u8,
    check_utf8: bool,
    find_bare_cr: bool,
) -> std::result::Result<(Vec<T>, bool), bool> {
    use rayon::prelude::*;
    use std::sync::atomic::{AtomicBool, Ordering::Relaxed};
    let at = |i: usize| T::try_from(i).ok().expect("offset fits the index width");
    let (binary, not_utf8) = (AtomicBool::new(false), AtomicBool::new(false));
    let mixed = AtomicBool::new(false);
    let chunk = |(a, b): (usize, usize)| -> Vec<T> {
        let c = &bytes[a..b];
        if binary.load(Relaxed) || memchr::memchr(0, c).is_some() {
            binary.store(true, Relaxed);
            return Vec::new();
        }
        if not_utf8.load(Relaxed) || check_utf8 && std::str::from_utf8(c).is_err() {
            not_utf8.store(true, Relaxed);
            return Vec::new();
        }
        let mut starts = Vec::with_capacity(c.len() / 16);
        let bare = after_each(c, sep, bytes.get(b).copied(), |i| {
            starts.push(at(a + i + 1))
        });
        if find_bare_cr && bare {
            mixed.store(true, Relaxed);
        }
        starts
    };
    let cuts = cuts(bytes);
    let parts: Vec<Vec<T>> = match cuts.len() {
        0 | 1 => cuts.into_iter().map(chunk).collect(),
        _ => cuts.into_par_iter().map(chunk).collect(),
    };
    if binary.into_inner() {
        return Err(true);
    }
    if not_utf8.into_inner() {
        return Err(false);
    }
    let mut starts = Vec::with_capacity(1 + parts.iter().map(Vec::len).sum::<usize>());
    starts.push(at(0));
    for part in parts {
        starts.extend_from_slice(&part);
    }
    Ok((starts, mixed.into_inner()))
}

/// Calls `found(i)` for each `i` where `c[i] == sep`, in order, and
/// returns whether `c` holds a bare CR (one followed by neither LF nor CR;
/// `next` is the byte after `c`). Eight bytes are tested at once (a word
/// whose bytes equal to a byte have their high bit set, exactly: no carry
/// crosses a byte): lines of a numeric export are short, and a search call
/// per line costs more than the test; the CRs are judged from the same
/// words, each against the byte after it.
fn after_each(c: &[u8], sep: u8, next: Option<u8>, mut found: impl FnMut(usize)) -> bool {
    const LOW7: u64 = 0x7f7f_7f7f_7f7f_7f7f;
    const LAST: u64 = 0x80u64 << 56;
    let matches = |word: u64, byte: u8| {
        let x = word ^ u64::from_ne_bytes([byte; 8]);
        !(((x & LOW7) + LOW7) | x) & !LOW7
    };
    let ends = |b: Option<u8>| matches!(b, None | Some(b'\n' | b'\r'));
    let mut words = c.chunks_exact(8);
    // Branch-free: the high bit of each byte that is a bare CR (bytes 0..6
    // against the byte after them in the word; byte 7, carried, against
    // the next word's byte 0).
    let (mut bare, mut carried) = (0u64, 0u64);
    for (w, word) in (&mut words).enumerate() {
        let word = u64::from_le_bytes(word.try_into().expect("eight bytes"));
        let mut hits = matches(word, sep);
        let cr = matches(word, b'\r');
        let lf = if sep == b'\n' {
            hits
        } else {
            matches(word, b'\n')
        };
        let ending = cr | lf;
        bare |= (cr & !(ending >> 8) & !LAST) | (carried >> 56 & !ending);
        carried = cr & LAST;
        while hits != 0 {
            found(8 * w + hits.trailing_zeros() as usize / 8);
            hits &= hits - 1;
        }
    }
    let mut bare = bare != 0;
    let rest = words.remainder();
    bare |= carried != 0 && !ends(rest.first().copied().or(next));
    let done = c.len() - rest.len();
    for (i, &b) in rest.iter().enumerate() {
        if b == sep {
            found(done + i);
        }
        bare |= b == b'\r' && !ends(rest.get(i + 1).copied().or(next));
    }
    bare
}

/// `bytes` cut into chunks of about [`SCAN_CHUNK`] bytes, each cut moved
/// forward to the next byte that starts a character (not a UTF-8
/// continuation byte), so that valid text is cut only between characters.
fn cuts(bytes: &[u8]) -> Vec<(usize, usize)> {
    let mut cuts = Vec::with_capacity(bytes.len() / SCAN_CHUNK + 1);
    let mut a = 0;
    while a < bytes.len() {
        let mut b = (a + SCAN_CHUNK).min(bytes.len());
        while b < bytes.len() && bytes[b] & 0xC0 == 0x80 {
            b += 1;
        }
        cuts.push((a, b));
        a = b;
    }
    cuts
}

/// The line starts less a final empty line (the text ends with its line
/// ending), which is not a line; no line at all for empty text.
pub(super) fn finish<T: Copy>(mut starts: Vec<T>, bytes: &[u8], ending: LineEnding) -> Vec<T>
where
    usize: TryFrom<T>,
{
    let last = match starts.last() {
        Some(&i) if starts.len() > 1 => usize::try_from(i).ok().expect("an offset"),
        _ => 0,
    };
    let tail = &bytes[last..];
    let last_empty =
        tail.is_empty() || (ending != LineEnding::Cr && tail.iter().all(|&b| b == b'\r'));
    if starts.len() > 1 && last_empty || bytes.is_empty() {
        starts.pop();
    }
    starts.shrink_to_fit();
    starts
}
#[cfg(test)]
mod tests {
    use super::*;

    /// The word-at-a-time search finds exactly the separator's positions,
    /// for every byte value as separator and neighbour, at every alignment.
    #[test]
    fn word_search_finds_every_separator() {
        let bytes: Vec<u8> = (0..600u32).map(|i| (i * 37 % 256) as u8).collect();
        for sep in [b'\n', b'\r', 0, 0x80, 0xff, 0x7f, 0x01] {
            for start in 0..9 {
                let c = &bytes[start..];
                let mut got = Vec::new();
                let bare = after_each(c, sep, None, |i| got.push(i));
                let want: Vec<usize> = (0..c.len()).filter(|&i| c[i] == sep).collect();
                assert_eq!(got, want, "separator {sep}, from {start}");
                assert_eq!(
                    bare,
                    (0..c.len()).any(|i| super::bare_cr(c, i) && c[i] == b'\r')
                );
            }
        }
        // CR, LF and other bytes in every order, across word boundaries,
        // with and without a byte after the slice.
        let mix: Vec<u8> = (0..300u32)
            .map(|i| b"\r\na\r\r\nb"[(i * i % 7) as usize])
            .collect();
        for start in 0..9 {
            for end in mix.len() - 9..mix.len() {
                let c = &mix[start..end];
                let want = (start..end).any(|i| mix[i] == b'\r' && super::bare_cr(&mix, i));
                let mut n = 0;
                assert_eq!(
                    after_each(c, b'\n', mix.get(end).copied(), |_| n += 1),
                    want
                );
                assert_eq!(n, c.iter().filter(|&&b| b == b'\n').count());
            }
        }
    }
}
