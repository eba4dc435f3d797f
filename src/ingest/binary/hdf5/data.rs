//! Datasets: datatype, shape and layout, and their values read into one
//! `f64` buffer. Contiguous and compact data are converted in place
//! ([`decode`]); chunked data one chunk at a time (inflated, unshuffled),
//! so that no more than one decompressed chunk is held beside the values.

use std::io::Read;

use super::group::v1_node;
use super::header::{kind, messages, Message};
use super::types::{dataspace, dtype, Dtype, Kind};
use super::H5;
use crate::error::Result;
use crate::ingest::binary::decode::{decode, inflated_at_most, Conversion, Sample};
use crate::ingest::grid::{count_nan, GridData};

/// A dataset: where its header is, its type, shape and storage.
#[derive(Debug, Clone)]
pub struct Dataset {
    /// Its object header.
    pub addr: usize,
    /// Element type.
    pub ty: Dtype,
    /// Dimensions, slowest first.
    pub dims: Vec<usize>,
    layout: Layout,
    filters: Vec<(u16, Vec<u32>)>,
}

#[derive(Debug, Clone)]
enum Layout {
    Compact(usize, usize),
    Contiguous(Option<usize>),
    Chunked(Vec<usize>, Index, usize),
}

#[derive(Debug, Clone)]
enum Index {
    BTree(Option<usize>),
    Single(Option<usize>, Option<(usize, u32)>),
    Implicit(Option<usize>),
    Fixed(Option<usize>),
}

/// A chunk: its first element's position (row, column), address, stored
/// size and filter mask.
type Chunk = ((usize, usize), usize, usize, u32);

const LAYOUT: &str = "HDF5 data layout message";

/// The dataset whose object header is at `addr`; `None` for an object
/// that is not one (a group).
pub fn dataset(f: &H5, addr: usize) -> Result<Option<Dataset>> {
    let msgs = messages(f, addr)?;
    let find = |k: u16| msgs.iter().find(|m| m.kind == k).copied();
    let (Some(t), Some(s), Some(l)) = (
        find(kind::DATATYPE),
        find(kind::DATASPACE),
        find(kind::LAYOUT),
    ) else {
        return Ok(None);
    };
    let ty = dtype(f, &mut f.bytes.le(t.at, "HDF5 datatype message"), 0)?;
    let (_, dims) = dataspace(f, s.at)?;
    let filters = match find(kind::FILTERS) {
        Some(m) => filters(f, m)?,
        None => Vec::new(),
    };
    Ok(Some(Dataset {
        addr,
        ty,
        dims,
        layout: layout(f, l)?,
        filters,
    }))
}

fn layout(f: &H5, m: Message) -> Result<Layout> {
    let mut c = f.bytes.le(m.at, LAYOUT);
    let version = c.u8("version")?;
    // Version 5 (HDF5 2.0) is laid out as version 4.
    if !(3..=5).contains(&version) {
        return Err(c.bad("version", 1, format!("{version}; 3 to 5 expected")));
    }
    let class = c.u8("layout class")?;
    match class {
        0 => {
            let n = c.u16("compact size")? as usize;
            Ok(Layout::Compact(c.pos(), n))
        }
        1 => Ok(Layout::Contiguous(f.addr(&mut c, "data address")?)),
        2 if version == 3 => {
            let rank = c.u8("dimensionality")? as usize;
            let tree = f.addr(&mut c, "B-tree address")?;
            let dims = (0..rank)
                .map(|_| c.u32("chunk dimension").map(|d| d as usize))
                .collect::<Result<Vec<_>>>()?;
            Ok(Layout::Chunked(dims, Index::BTree(tree), m.at))
        }
        2 => chunked_v4(f, &mut c, m.at),
        k => Err(c.bad("layout class", 1, format!("class {k}; 0, 1 or 2 expected"))),
    }
}

fn chunked_v4(f: &H5, c: &mut crate::ingest::binary::Cursor, at: usize) -> Result<Layout> {
    let flags = c.u8("flags")?;
    let rank = c.u8("dimensionality")? as usize;
    let width = c.u8("dimension size")? as usize;
    if !(1..=8).contains(&width) {
        return Err(c.bad("dimension size", 1, format!("{width} bytes")));
    }
    let dims = (0..rank)
        .map(|_| H5::uint(c, width, "chunk dimension").map(|d| d as usize))
        .collect::<Result<Vec<_>>>()?;
    let index = match c.u8("chunk index type")? {
        1 => {
            let filtered = match flags & 2 != 0 {
                true => Some((f.length(c, "filtered size")?, c.u32("filter mask")?)),
                false => None,
            };
            Index::Single(f.addr(c, "chunk address")?, filtered)
        }
        2 => Index::Implicit(f.addr(c, "chunk address")?),
        3 => {
            c.skip(1);
            Index::Fixed(f.addr(c, "fixed array address")?)
        }
        k => {
            let name = match k {
                4 => "an extensible array",
                5 => "a version-2 B-tree",
                _ => "unknown",
            };
            return Err(c.bad(
                "chunk index type",
                1,
                format!("index type {k} ({name}) is not read"),
            ));
        }
    };
    Ok(Layout::Chunked(dims, index, at))
}

fn filters(f: &H5, m: Message) -> Result<Vec<(u16, Vec<u32>)>> {
    let mut c = f.bytes.le(m.at, "HDF5 filter pipeline message");
    let version = c.u8("version")?;
    let n = c.u8("number of filters")?;
    if version == 1 {
        c.skip(6);
    }
    let mut out = Vec::new();
    for _ in 0..n {
        let id = c.u16("filter id")?;
        let name_len = match version == 1 || id >= 256 {
            true => c.u16("name length")? as usize,
            false => 0,
        };
        c.skip(2);
        let nv = c.u16("number of values")? as usize;
        c.skip(if version == 1 {
            name_len.div_ceil(8) * 8
        } else {
            name_len
        });
        let values = (0..nv)
            .map(|_| c.u32("client data"))
            .collect::<Result<Vec<_>>>()?;
        if version == 1 && nv % 2 == 1 {
            c.skip(4);
        }
        if !matches!(id, 1..=3) {
            return Err(c.bad(
                "filter id",
                0,
                format!("filter {id} is not read (deflate, shuffle and Fletcher-32 are)"),
            ));
        }
        out.push((id, values));
    }
    Ok(out)
}

/// The raw sample type of a numeric dataset, and whether it is big-endian.
pub fn sample(ty: &Dtype) -> Option<(Sample, bool)> {
    Some(match (&ty.kind, ty.size) {
        (Kind::Float { big }, 4) => (Sample::F32, *big),
        (Kind::Float { big }, 8) => (Sample::F64, *big),
        (Kind::Int { signed, big }, n) => (
            match (signed, n) {
                (false, 1) => Sample::U8,
                (true, 1) => Sample::I8,
                (false, 2) => Sample::U16,
                (true, 2) => Sample::I16,
                (false, 4) => Sample::U32,
                (true, 4) => Sample::I32,
                (false, 8) => Sample::U64,
                (true, 8) => Sample::I64,
                _ => return None,
            },
            *big,
        ),
        _ => return None,
    })
}

impl Dataset {
    /// Rows and columns: a 2-D dataset's (d0, d1), a 1-D one's (1, d0).
    pub fn shape(&self) -> Option<(usize, usize)> {
        match self.dims.as_slice() {
            [n] => Some((1, *n)),
            [r, c] => Some((*r, *c)),
            _ => None,
        }
    }

    /// The values, converted by `conv` (whose sample type is the
    /// dataset's), row-major; chunks never written are NaN.
    pub fn read(&self, f: &H5, conv: &Conversion, structure: &str) -> Result<GridData> {
        let (rows, cols) = self.shape().ok_or_else(|| {
            f.bytes.error(
                structure,
                self.addr,
                format!("{} dimensions; 1 or 2 expected", self.dims.len()),
            )
        })?;
        let n = rows * cols;
        match &self.layout {
            Layout::Compact(at, len) if *len >= n.saturating_mul(self.ty.size) => {
                decode(&f.bytes, *at, n, conv, structure)
            }
            Layout::Compact(at, _) => {
                Err(f
                    .bytes
                    .error(structure, *at, "compact data shorter than the dataspace"))
            }
            Layout::Contiguous(Some(at)) => decode(&f.bytes, *at, n, conv, structure),
            Layout::Contiguous(None) => {
                Err(f.bytes.error(structure, self.addr, "no data was written"))
            }
            Layout::Chunked(chunk, index, at) => {
                // Chunks inflate at most 1032-fold: more values than the
                // file's bytes could give are a corrupted dataspace.
                if n.saturating_mul(self.ty.size) > inflated_at_most(f.bytes.len()) {
                    return Err(f.bytes.error(
                        structure,
                        self.addr,
                        format!(
                            "{rows} × {cols} values cannot come from a file of {} bytes",
                            f.bytes.len()
                        ),
                    ));
                }
                let (cr, cc) = self.chunk_shape(f, chunk, *at)?;
                let chunks = self.chunks(f, index, (cr, cc), *at)?;
                self.read_chunks(f, &chunks, (cr, cc), conv, structure)
            }
        }
    }

    fn chunk_shape(&self, f: &H5, chunk: &[usize], at: usize) -> Result<(usize, usize)> {
        let s = match (chunk, self.dims.len()) {
            ([c, e], 1) if *e == self.ty.size => (1, *c),
            ([r, c, e], 2) if *e == self.ty.size => (*r, *c),
            _ => (0, 0),
        };
        let bytes =
            s.0.checked_mul(s.1)
                .and_then(|n| n.checked_mul(self.ty.size));
        if s.0 == 0 || s.1 == 0 || bytes.is_none_or(|b| b > 1 << 32) {
            return Err(f.bytes.error(
                LAYOUT,
                at,
                format!(
                    "chunk {chunk:?} does not fit dimensions {:?} of {}-byte elements",
                    self.dims, self.ty.size
                ),
            ));
        }
        Ok(s)
    }

    fn chunks(&self, f: &H5, index: &Index, cs: (usize, usize), at: usize) -> Result<Vec<Chunk>> {
        let (rows, cols) = self.shape().unwrap_or((0, 0));
        let bytes = cs.0 * cs.1 * self.ty.size;
        let grid = (rows.div_ceil(cs.0), cols.div_ceil(cs.1));
        let place = |i: usize| ((i / grid.1) * cs.0, (i % grid.1) * cs.1);
        Ok(match index {
            Index::BTree(None)
            | Index::Single(None, _)
            | Index::Implicit(None)
            | Index::Fixed(None) => Vec::new(),
            Index::BTree(Some(a)) => {
                let mut out = Vec::new();
                chunk_tree(f, *a, self.dims.len() + 1, &mut Vec::new(), &mut out)?;
                out
            }
            Index::Single(Some(a), filtered) => {
                let (size, mask) = filtered.unwrap_or((bytes, 0));
                vec![((0, 0), *a, size, mask)]
            }
            Index::Implicit(Some(a)) => (0..grid.0 * grid.1)
                .map(|i| {
                    Ok((
                        place(i),
                        a.checked_add(i * bytes)
                            .ok_or_else(|| f.bytes.error(LAYOUT, at, "chunk address overflows"))?,
                        bytes,
                        0,
                    ))
                })
                .collect::<Result<_>>()?,
            Index::Fixed(Some(a)) => super::fixed::entries(f, *a, bytes)?
                .into_iter()
                .enumerate()
                .filter_map(|(i, e)| e.map(|(addr, size, mask)| (place(i), addr, size, mask)))
                .collect(),
        })
    }

    fn read_chunks(
        &self,
        f: &H5,
        chunks: &[Chunk],
        cs: (usize, usize),
        conv: &Conversion,
        structure: &str,
    ) -> Result<GridData> {
        let (rows, cols) = self.shape().unwrap_or((0, 0));
        let size = self.ty.size;
        let mut values = vec![f64::NAN; rows * cols];
        let mut buf = Vec::with_capacity(cs.0 * cs.1 * size);
        for &((r0, c0), addr, stored, mask) in chunks {
            if r0 >= rows || c0 >= cols || r0 % cs.0 != 0 || c0 % cs.1 != 0 {
                return Err(f.bytes.error(
                    structure,
                    addr,
                    format!("a chunk at ({r0}, {c0}), outside the {rows} × {cols} grid"),
                ));
            }
            self.unfilter(
                f,
                (addr, stored, mask),
                cs.0 * cs.1 * size,
                &mut buf,
                structure,
            )?;
            let w = cs.1.min(cols - c0);
            for r in 0..cs.0.min(rows - r0) {
                let from = r * cs.1 * size;
                let out = (r0 + r) * cols + c0;
                conv.convert(&buf[from..from + w * size], &mut values[out..out + w]);
            }
        }
        let n_invalid = count_nan(&values);
        Ok(GridData { values, n_invalid })
    }

    /// A chunk's bytes, its filters undone in reverse order, into `buf`
    /// (exactly `want` bytes).
    fn unfilter(
        &self,
        f: &H5,
        (addr, stored, mask): (usize, usize, u32),
        want: usize,
        buf: &mut Vec<u8>,
        structure: &str,
    ) -> Result<()> {
        let raw = f.bytes.slice(addr, stored, structure)?;
        buf.clear();
        buf.extend_from_slice(raw);
        for (i, (id, values)) in self.filters.iter().enumerate().rev() {
            if mask >> i & 1 == 1 {
                continue;
            }
            match id {
                1 => {
                    let mut out = Vec::with_capacity(want);
                    flate2::read::ZlibDecoder::new(buf.as_slice())
                        .take(want as u64 + 1)
                        .read_to_end(&mut out)
                        .map_err(|e| {
                            f.bytes.error(
                                structure,
                                addr,
                                format!("deflated chunk cannot be decoded: {e}"),
                            )
                        })?;
                    *buf = out;
                }
                2 => unshuffle(buf, values.first().map_or(self.ty.size, |&s| s as usize)),
                _ => buf.truncate(buf.len().saturating_sub(4)),
            }
        }
        if buf.len() != want {
            return Err(f.bytes.error(
                structure,
                addr,
                format!("chunk holds {} bytes; {want} expected", buf.len()),
            ));
        }
        Ok(())
    }
}

/// Undoes HDF5's shuffle: byte k of every element was stored together.
fn unshuffle(buf: &mut [u8], size: usize) {
    if size <= 1 {
        return;
    }
    let n = buf.len() / size;
    let src = buf[..n * size].to_vec();
    for (k, plane) in src.chunks_exact(n).enumerate().take(size) {
        for (i, &b) in plane.iter().enumerate() {
            buf[i * size + k] = b;
        }
    }
}

/// The chunks under a v1 B-tree node of type 1 (raw data chunks).
fn chunk_tree(
    f: &H5,
    addr: usize,
    rank: usize,
    seen: &mut Vec<usize>,
    out: &mut Vec<Chunk>,
) -> Result<()> {
    let (mut c, level, used) = v1_node(f, addr, 1, "HDF5 chunk B-tree node", seen, 65_536)?;
    for _ in 0..used {
        let size = c.u32("chunk size")? as usize;
        let mask = c.u32("filter mask")?;
        let offs = (0..rank)
            .map(|_| c.u64("chunk offset").map(|o| o as usize))
            .collect::<Result<Vec<_>>>()?;
        let child = f.need(&mut c, "child address")?;
        let place = match offs.as_slice() {
            [col, _] => (0, *col),
            [row, col, _] => (*row, *col),
            _ => (usize::MAX, usize::MAX),
        };
        match level {
            0 => out.push((place, child, size, mask)),
            _ => chunk_tree(f, child, rank, seen, out)?,
        }
    }
    Ok(())
}
