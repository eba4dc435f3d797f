//! Memory as a limit: a file whose reading and analysis would need more
//! memory than the machine has left fails with a clear error before it is
//! read, instead of the allocation aborting the whole run and every other
//! file's results with it (issue: a 2.1 GB trace aborted at 9.3 GB).
//!
//! The need is estimated as [`PEAK_PER_FILE_BYTE`] times the file's size
//! (the peak measured at 1e7 rows is 1.24× without the traces table and
//! 2.48× with it, 2.8× for a 10 M-point profile, `docs/speed.md`); the
//! limit is
//! `TRIBO_MEMORY_LIMIT` (`8G`, `512M`, bytes) or else the kernel's
//! `MemAvailable`. Files are read two or more at a time, so this guards
//! against one file too large, not against several large ones together.

use std::path::Path;

use crate::error::{Error, Location, Result};

/// Peak resident memory of reading and analysing a file, per byte of it,
/// with a margin over the measured 2.48 (traces table on) and 2.8 (a long
/// profile).
pub const PEAK_PER_FILE_BYTE: u64 = 3;

/// A size such as `8G`, `512M`, `64K` or a number of bytes.
pub fn parse_size(s: &str) -> Option<u64> {
    let s = s.trim();
    let (num, mult) = match s.char_indices().last()? {
        (i, 'K' | 'k') => (&s[..i], 1u64 << 10),
        (i, 'M' | 'm') => (&s[..i], 1 << 20),
        (i, 'G' | 'g') => (&s[..i], 1 << 30),
        (i, 'T' | 't') => (&s[..i], 1 << 40),
        _ => (s, 1),
    };
    let v: f64 = num.trim().parse().ok()?;
    (v.is_finite() && v >= 0.0).then_some((v * mult as f64) as u64)
}

/// The memory a file may use: `TRIBO_MEMORY_LIMIT`, else `MemAvailable`;
/// `None` where neither is known (no check).
fn limit() -> Option<(u64, &'static str)> {
    if let Some(v) = std::env::var("TRIBO_MEMORY_LIMIT")
        .ok()
        .and_then(|v| parse_size(&v))
    {
        return Some((v, "TRIBO_MEMORY_LIMIT"));
    }
    let info = std::fs::read_to_string("/proc/meminfo").ok()?;
    let line = info.lines().find(|l| l.starts_with("MemAvailable:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some((kb * 1024, "available memory"))
}

fn gb(b: u64) -> String {
    match b < 1_000_000_000 {
        true => format!("{:.1} MB", b as f64 / 1e6),
        false => format!("{:.2} GB", b as f64 / 1e9),
    }
}

/// Fails a file of `size` bytes that would not fit in the memory left.
pub fn check(path: &Path, size: u64) -> Result<()> {
    let Some((limit, what)) = limit() else {
        return Ok(());
    };
    let need = size.saturating_mul(PEAK_PER_FILE_BYTE);
    if need <= limit {
        return Ok(());
    }
    Err(Error::input(
        Location::file(path),
        format!(
            "the file is {}; reading and analysing it needs about {} ({PEAK_PER_FILE_BYTE}× \
             its size) and the {what} is {}: split the file, or run where more memory is \
             free (TRIBO_MEMORY_LIMIT sets the limit)",
            gb(size),
            gb(need),
            gb(limit)
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_read_with_their_unit() {
        assert_eq!(parse_size("512"), Some(512));
        assert_eq!(parse_size("64K"), Some(65_536));
        assert_eq!(parse_size("1.5G"), Some(1_610_612_736));
        assert_eq!(parse_size(" 8g "), Some(8 << 30));
        assert_eq!(parse_size("lots"), None);
        assert_eq!(parse_size("-1M"), None);
    }
}
