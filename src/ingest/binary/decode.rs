//! Raw samples to one `f64` buffer: value = raw · scale + offset, with the
//! format's not-measured marker (and any non-finite float) as NaN, counted.
//!
//! [`decode`] converts samples lying in the file's bytes on all threads,
//! block by block, handing each converted block of a mapped file back to
//! the kernel, so that the file is not resident beside the heights.
//! [`Stream`] converts samples arriving in pieces (a decompressed entry),
//! so that the decompressed bytes are never held whole.

use rayon::prelude::*;

use super::Bytes;
use crate::error::Result;
use crate::ingest::grid::GridData;

/// The type of a raw sample.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Sample {
    /// Unsigned 8-bit integer.
    U8,
    /// Signed 8-bit integer.
    I8,
    /// Unsigned 16-bit integer.
    U16,
    /// Signed 16-bit integer.
    I16,
    /// Unsigned 32-bit integer.
    U32,
    /// Signed 32-bit integer.
    I32,
    /// Unsigned 64-bit integer.
    U64,
    /// Signed 64-bit integer.
    I64,
    /// IEEE 754 single precision.
    F32,
    /// IEEE 754 double precision.
    F64,
}

impl Sample {
    /// Bytes per sample.
    pub fn size(self) -> usize {
        match self {
            Sample::U8 | Sample::I8 => 1,
            Sample::U16 | Sample::I16 => 2,
            Sample::U32 | Sample::I32 | Sample::F32 => 4,
            Sample::U64 | Sample::I64 | Sample::F64 => 8,
        }
    }
}

/// Which raw values mark a point as not measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Invalid {
    /// None (non-finite floats still are).
    None,
    /// Raw values equal to this one.
    Equal(f64),
    /// Raw values at or above this one (a format that marks the top of
    /// its integer range).
    AtLeast(f64),
}

/// How raw samples become values.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Conversion {
    /// The sample type.
    pub sample: Sample,
    /// Big-endian bytes.
    pub big_endian: bool,
    /// Multiplies the raw value.
    pub scale: f64,
    /// Added after scaling.
    pub offset: f64,
    /// The not-measured marker, compared with the raw value.
    pub invalid: Invalid,
}

impl Conversion {
    /// Raw values as they are, little-endian, without a marker.
    pub fn raw(sample: Sample) -> Conversion {
        Conversion {
            sample,
            big_endian: false,
            scale: 1.0,
            offset: 0.0,
            invalid: Invalid::None,
        }
    }

    /// The same, scaled: value = raw · scale + offset.
    pub fn scaled(self, scale: f64, offset: f64) -> Conversion {
        Conversion {
            scale,
            offset,
            ..self
        }
    }

    /// The same, big-endian.
    pub fn big_endian(self) -> Conversion {
        Conversion {
            big_endian: true,
            ..self
        }
    }

    /// The same, with a not-measured marker.
    pub fn invalid(self, invalid: Invalid) -> Conversion {
        Conversion { invalid, ..self }
    }

    /// Converts `raw` (whole samples) into `out`; returns the NaN count.
    pub fn convert(&self, raw: &[u8], out: &mut [f64]) -> usize {
        macro_rules! run {
            ($t:ty) => {{
                const N: usize = std::mem::size_of::<$t>();
                let mut bad = 0;
                for (o, b) in out.iter_mut().zip(raw.chunks_exact(N)) {
                    let a: [u8; N] = b.try_into().expect("chunks_exact");
                    let r = match self.big_endian {
                        true => <$t>::from_be_bytes(a),
                        false => <$t>::from_le_bytes(a),
                    } as f64;
                    let v = match (self.invalid, r.is_finite()) {
                        (_, false) => f64::NAN,
                        // Markers are exact raw values (never zero): bit equality.
                        (Invalid::Equal(m), _) if r.to_bits() == m.to_bits() => f64::NAN,
                        (Invalid::AtLeast(m), _) if r >= m => f64::NAN,
                        _ => r * self.scale + self.offset,
                    };
                    bad += v.is_nan() as usize;
                    *o = v;
                }
                bad
            }};
        }
        match self.sample {
            Sample::U8 => run!(u8),
            Sample::I8 => run!(i8),
            Sample::U16 => run!(u16),
            Sample::I16 => run!(i16),
            Sample::U32 => run!(u32),
            Sample::I32 => run!(i32),
            Sample::U64 => run!(u64),
            Sample::I64 => run!(i64),
            Sample::F32 => run!(f32),
            Sample::F64 => run!(f64),
        }
    }
}

/// Samples converted per block before its bytes are released.
const BLOCK: usize = 1 << 20;
/// Samples per task within a block.
const TASK: usize = 1 << 14;

/// Decodes `n` samples at byte `offset` of the file into one buffer. The
/// bytes must be there: a file that ends first is an error naming
/// `structure` and where the data starts.
pub fn decode(
    bytes: &Bytes,
    offset: usize,
    n: usize,
    conv: &Conversion,
    structure: &str,
) -> Result<GridData> {
    let size = conv.sample.size();
    let len = n.checked_mul(size).ok_or_else(|| {
        bytes.error(
            structure,
            offset,
            format!("{n} samples overflow the address space"),
        )
    })?;
    let raw = bytes.slice(offset, len, structure)?;
    let mut values = vec![0.0f64; n];
    let mut n_invalid = 0;
    for (b, out) in values.chunks_mut(BLOCK).enumerate() {
        let start = b * BLOCK * size;
        let inp = &raw[start..start + out.len() * size];
        n_invalid += out
            .par_chunks_mut(TASK)
            .zip(inp.par_chunks(TASK * size))
            .map(|(o, i)| conv.convert(i, o))
            .sum::<usize>();
        bytes.release(offset + start..offset + start + inp.len());
    }
    Ok(GridData { values, n_invalid })
}

/// How a grid's samples lie in the file, relative to its rows (row r
/// holds the nx values at y index r).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Order {
    /// The file holds columns: the ny values at x index 0, then at 1, ...
    pub column_major: bool,
    /// The file's first row (or the first value of each column) is the
    /// grid's last row.
    pub flip_y: bool,
}

/// As [`decode`], for an nx × ny grid laid out in the file as `order`
/// says; the values come out row-major, row 0 first.
pub fn decode_grid(
    bytes: &Bytes,
    offset: usize,
    (nx, ny): (usize, usize),
    conv: &Conversion,
    structure: &str,
    order: Order,
) -> Result<GridData> {
    let n = nx.checked_mul(ny).ok_or_else(|| {
        bytes.error(
            structure,
            offset,
            format!("{nx} × {ny} overflows the address space"),
        )
    })?;
    if order == Order::default() {
        return decode(bytes, offset, n, conv, structure);
    }
    let size = conv.sample.size();
    let raw = bytes.slice(offset, n.saturating_mul(size), structure)?;
    let mut values = vec![0.0f64; n];
    let n_invalid = values
        .par_chunks_mut(nx.max(1))
        .enumerate()
        .map_init(Vec::new, |row, (r, out)| {
            let s = if order.flip_y { ny - 1 - r } else { r };
            row.clear();
            for c in 0..nx {
                let i = match order.column_major {
                    true => c * ny + s,
                    false => s * nx + c,
                };
                row.extend_from_slice(&raw[i * size..(i + 1) * size]);
            }
            conv.convert(row, out)
        })
        .sum();
    bytes.release(offset..offset + raw.len());
    Ok(GridData { values, n_invalid })
}

/// Samples arriving in pieces of any length (a decompressed stream).
pub struct Stream {
    conv: Conversion,
    expected: usize,
    values: Vec<f64>,
    n_invalid: usize,
    /// Bytes of a sample split between two pieces.
    carry: Vec<u8>,
}

/// Most bytes a deflate (or zlib) stream of `packed` bytes can decompress
/// to (deflate's ratio is at most 1032:1): a header's count of points
/// beyond it cannot be in the stream, and is not allocated.
pub fn inflated_at_most(packed: usize) -> usize {
    packed.saturating_mul(1032).saturating_add(64)
}

impl Stream {
    /// Expects `n` samples, with room for at most `bytes_at_most` bytes of
    /// them reserved ([`inflated_at_most`]): a corrupted count of points
    /// does not allocate what the stream cannot hold.
    pub fn new(conv: Conversion, n: usize, bytes_at_most: usize) -> Stream {
        Stream {
            conv,
            expected: n,
            values: Vec::with_capacity(n.min(bytes_at_most / conv.sample.size())),
            n_invalid: 0,
            carry: Vec::with_capacity(8),
        }
    }

    /// Samples decoded so far.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Whether none was decoded yet.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// Whether all expected samples are in.
    pub fn is_full(&self) -> bool {
        self.values.len() >= self.expected
    }

    /// Takes the next piece; bytes past the expected samples are ignored
    /// (the caller checks the stream's own length).
    pub fn push(&mut self, mut piece: &[u8]) {
        let size = self.conv.sample.size();
        if !self.carry.is_empty() {
            let need = (size - self.carry.len()).min(piece.len());
            self.carry.extend_from_slice(&piece[..need]);
            piece = &piece[need..];
            if self.carry.len() == size {
                let carry = std::mem::take(&mut self.carry);
                self.put(&carry);
                self.carry = carry;
                self.carry.clear();
            }
        }
        let whole = piece.len() / size * size;
        self.put(&piece[..whole]);
        self.carry.extend_from_slice(&piece[whole..]);
    }

    fn put(&mut self, raw: &[u8]) {
        let size = self.conv.sample.size();
        let room = self.expected - self.values.len().min(self.expected);
        let k = (raw.len() / size).min(room);
        let at = self.values.len();
        self.values.resize(at + k, 0.0);
        self.n_invalid += self.conv.convert(&raw[..k * size], &mut self.values[at..]);
    }

    /// The values, or `None` when fewer than expected arrived.
    pub fn finish(self) -> Option<GridData> {
        (self.values.len() == self.expected).then_some(GridData {
            values: self.values,
            n_invalid: self.n_invalid,
        })
    }
}

/// Reads `n` samples (of which the stream can hold at most
/// `bytes_at_most` bytes) from `reader` through a [`Stream`], in pieces of
/// 256 KiB. A read error or a stream that ends early is an error naming
/// `structure` at `offset` (where its data starts in the file).
pub fn decode_stream(
    bytes: &Bytes,
    mut reader: impl std::io::Read,
    (n, bytes_at_most): (usize, usize),
    conv: &Conversion,
    structure: &str,
    offset: usize,
) -> Result<GridData> {
    let mut s = Stream::new(*conv, n, bytes_at_most);
    let mut buf = vec![0u8; 256 << 10];
    while !s.is_full() {
        let k = match reader.read(&mut buf) {
            Ok(0) => break,
            Ok(k) => k,
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => continue,
            Err(e) => {
                return Err(bytes.error(structure, offset, format!("cannot be decoded: {e}")))
            }
        };
        s.push(&buf[..k]);
    }
    // Read to the end, so that a checked stream (a zip entry's CRC-32)
    // checks itself; bytes past the samples are not used.
    loop {
        match reader.read(&mut buf) {
            Ok(0) => break,
            Ok(_) => {}
            Err(e) if e.kind() == std::io::ErrorKind::Interrupted => {}
            Err(e) => {
                return Err(bytes.error(structure, offset, format!("cannot be decoded: {e}")))
            }
        }
    }
    let got = s.len();
    s.finish().ok_or_else(|| {
        bytes.error(
            structure,
            offset,
            format!(
                "holds {got} samples of {} bytes; {n} expected (truncated?)",
                conv.sample.size()
            ),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn integers_scale_and_mark_invalid_points() {
        let raw: Vec<u8> = [-3i16, 0, 7, i16::MAX, 12]
            .iter()
            .flat_map(|v| v.to_le_bytes())
            .collect();
        let b = Bytes::new(Path::new("t"), &raw);
        let c = Conversion::raw(Sample::I16)
            .scaled(0.5, 1.0)
            .invalid(Invalid::Equal(i16::MAX as f64));
        let g = decode(&b, 0, 5, &c, "data").unwrap();
        assert_eq!(g.n_invalid, 1);
        assert_eq!(&g.values[..3], &[-0.5, 1.0, 4.5]);
        assert!(g.values[3].is_nan());
        assert_eq!(g.values[4].to_bits(), 7f64.to_bits());
        let e = decode(&b, 4, 5, &c, "SUR data").unwrap_err().to_string();
        assert!(
            e.contains("byte 4: SUR data") && e.contains("ends at byte 10"),
            "{e}"
        );
    }

    /// Column-major and flipped layouts give the grid row-major, row 0
    /// first: value 10·c + r at column c, row r.
    #[test]
    fn column_major_and_flipped_layouts() {
        let (nx, ny) = (4usize, 3usize);
        let want: Vec<f64> = (0..ny)
            .flat_map(|r| (0..nx).map(move |c| (10 * c + r) as f64))
            .collect();
        for (column_major, flip_y) in [(false, false), (false, true), (true, false), (true, true)] {
            let order = Order {
                column_major,
                flip_y,
            };
            let at = |c: usize, r: usize| {
                let r = if flip_y { ny - 1 - r } else { r };
                if column_major {
                    c * ny + r
                } else {
                    r * nx + c
                }
            };
            let mut file = vec![0i16; nx * ny];
            for r in 0..ny {
                for c in 0..nx {
                    file[at(c, r)] = (10 * c + r) as i16;
                }
            }
            let raw: Vec<u8> = file.iter().flat_map(|v| v.to_le_bytes()).collect();
            let b = Bytes::new(Path::new("t"), &raw);
            let g =
                decode_grid(&b, 0, (nx, ny), &Conversion::raw(Sample::I16), "d", order).unwrap();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&g.values), bits(&want), "{order:?}");
        }
    }

    #[test]
    fn big_endian_floats_and_non_finite_values() {
        let raw: Vec<u8> = [1.5f32, f32::INFINITY, f32::NAN, -2.0]
            .iter()
            .flat_map(|v| v.to_be_bytes())
            .collect();
        let b = Bytes::new(Path::new("t"), &raw);
        let c = Conversion::raw(Sample::F32).big_endian();
        let g = decode(&b, 0, 4, &c, "data").unwrap();
        assert_eq!(g.n_invalid, 2);
        assert_eq!((g.values[0], g.values[3]), (1.5, -2.0));
    }

    /// A stream cut at every byte boundary gives the same values as one
    /// decode of the whole buffer, across blocks and tasks.
    #[test]
    fn stream_in_pieces_equals_whole_decode() {
        let n = 3 * TASK + 17;
        let raw: Vec<u8> = (0..n)
            .flat_map(|i| ((i as i32 * 7919) % 65_521 - 30_000).to_le_bytes())
            .collect();
        let b = Bytes::new(Path::new("t"), &raw);
        let c = Conversion::raw(Sample::I32)
            .scaled(1e-9, -2e-6)
            .invalid(Invalid::AtLeast(35_000.0));
        let whole = decode(&b, 0, n, &c, "data").unwrap();
        assert!(whole.n_invalid > 0);
        for piece in [1, 3, 4, 5, 4099] {
            let mut s = Stream::new(c, n, usize::MAX);
            for p in raw.chunks(piece) {
                s.push(p);
            }
            let got = s.finish().unwrap();
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&got.values), bits(&whole.values), "pieces of {piece}");
            assert_eq!(got.n_invalid, whole.n_invalid);
        }
        let mut short = Stream::new(c, n, 16);
        short.push(&raw[..raw.len() - 1]);
        assert!(short.finish().is_none());
    }
}
