//! Maps whose rows are padded (a row stride larger than its samples) or
//! whose samples are not where a header's count says: decoded row by row
//! through a [`Stream`], into one buffer, without a copy of the rows.

use super::decode::{Conversion, Stream};
use super::Bytes;
use crate::error::Result;
use crate::ingest::grid::GridData;

/// Decodes `ny` rows of `nx` samples, row `r` at `offset + r · stride`
/// (stride in bytes, at least a row's samples). Every row must be in the
/// file: the error names `structure` and the byte where the last row ends.
pub fn decode_rows(
    bytes: &Bytes,
    offset: usize,
    (nx, ny): (usize, usize),
    stride: usize,
    conv: &Conversion,
    structure: &str,
) -> Result<GridData> {
    let row = nx
        .checked_mul(conv.sample.size())
        .filter(|&r| r <= stride)
        .ok_or_else(|| {
            bytes.error(
                structure,
                offset,
                format!("rows of {nx} samples do not fit a stride of {stride} bytes"),
            )
        })?;
    let span = ny
        .checked_sub(1)
        .and_then(|k| k.checked_mul(stride))
        .and_then(|s| s.checked_add(row))
        .ok_or_else(|| bytes.error(structure, offset, "no rows"))?;
    bytes.slice(offset, span, structure)?;
    let mut s = Stream::new(*conv, nx * ny, span);
    for r in 0..ny {
        let at = offset + r * stride;
        s.push(&bytes.data[at..at + row]);
    }
    bytes.release(offset..offset + span);
    Ok(s.finish().expect("every row was in the file"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ingest::binary::decode::Sample;
    use std::path::Path;

    #[test]
    fn padded_rows_skip_their_padding() {
        // 3 × 2 floats, rows padded to 16 bytes.
        let mut raw = Vec::new();
        for r in 0..2 {
            for c in 0..3 {
                raw.extend(((r * 3 + c) as f32).to_le_bytes());
            }
            raw.extend([0xff; 4]);
        }
        let b = Bytes::new(Path::new("t"), &raw);
        let c = Conversion::raw(Sample::F32);
        let g = decode_rows(&b, 0, (3, 2), 16, &c, "rows").unwrap();
        assert_eq!(g.values, [0.0, 1.0, 2.0, 3.0, 4.0, 5.0]);
        // From byte 8 the second row would end at byte 36 of 32.
        let e = decode_rows(&b, 8, (3, 2), 16, &c, "rows").unwrap_err();
        assert!(e.to_string().contains("byte 8: rows"), "{e}");
        assert!(decode_rows(&b, 0, (5, 2), 16, &c, "rows").is_err());
    }
}
