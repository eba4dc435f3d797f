//! Checks shared by the bad-file tests of the binary readers.

use std::path::Path;

use tribo::ingest::{read_bytes, Dataset, IngestOptions};

/// Reads `bytes` as the file `name`, the reader `format` forced.
pub fn read_forced(name: &str, format: &str, bytes: &[u8]) -> tribo::Result<Dataset> {
    let o = IngestOptions {
        format: Some(format.into()),
        ..Default::default()
    };
    read_bytes(Path::new(name), bytes, &o)
}

/// Every cut of `good` (one in `step` byte positions) is an error that
/// names the file and a byte offset (`t.gwy: byte ...`), never a panic
/// and never a map read from the bytes left.
pub fn cuts_name_file_and_offset(name: &str, format: &str, good: &[u8], step: usize) {
    for cut in (1..good.len()).step_by(step) {
        match read_forced(name, format, &good[..cut]) {
            Err(e) => {
                let e = e.to_string();
                assert!(
                    e.starts_with(&format!("{name}: byte ")),
                    "cut at {cut}: {e}"
                );
            }
            Ok(_) => panic!("{name} cut at {cut} of {} read", good.len()),
        }
    }
}

/// `good` with `bytes` written at `at`, read as `name`: the error names
/// `want` and a byte offset.
pub fn altered_names(name: &str, format: &str, good: &[u8], at: usize, bytes: &[u8], want: &str) {
    let mut b = good.to_vec();
    b[at..at + bytes.len()].copy_from_slice(bytes);
    let e = match read_forced(name, format, &b) {
        Err(e) => e.to_string(),
        Ok(_) => panic!("{name} altered at {at} read (expected '{want}')"),
    };
    assert!(e.contains(want) && e.contains("byte "), "{want}: {e}");
}

/// The values of the decoded grid against `want`, to `tol` (NaN where
/// `want` is NaN).
pub fn assert_values(got: &[f64], want: &[f64], tol: f64, what: &str) {
    assert_eq!(got.len(), want.len(), "{what}");
    for (i, (a, b)) in got.iter().zip(want).enumerate() {
        let ok = (a.is_nan() && b.is_nan()) || (a - b).abs() <= tol;
        assert!(ok, "{what}: point {i}: {a:e} vs {b:e}");
    }
}

/// A metadata value of a dataset.
pub fn meta<'a>(ds: &'a Dataset, key: &str) -> Option<&'a str> {
    ds.preamble
        .iter()
        .find(|m| m.key == key)
        .map(|m| m.value.as_str())
}
