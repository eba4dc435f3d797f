//! The fixed-array chunk index (`FAHD`/`FADB`) of datasets written with
//! HDF5 1.10+'s latest format: one entry per chunk, in row-major order of
//! the chunk grid. Paged data blocks (more than 2^page-bits chunks) are an
//! error that says so.

use super::H5;
use crate::error::Result;

/// A chunk's address, stored size and filter mask; `None` where the chunk
/// was never written.
pub type Entry = Option<(usize, usize, u32)>;

/// The entries of the fixed array whose header is at `addr`, for chunks
/// of `bytes` bytes when not filtered.
pub fn entries(f: &H5, addr: usize, bytes: usize) -> Result<Vec<Entry>> {
    let mut c = f.bytes.le(addr, "HDF5 fixed array header");
    if c.take(4, "signature")? != b"FAHD" {
        return Err(c.bad("signature", 4, "FAHD expected"));
    }
    c.skip(1);
    let client = c.u8("client id")?;
    let entry = c.u8("entry size")? as usize;
    let page_bits = c.u8("page bits")?;
    let n = f.length(&mut c, "number of entries")?;
    let block = f.need(&mut c, "data block address")?;
    f.checksum(addr, c.pos(), "HDF5 fixed array header")?;
    if page_bits < 32 && n > 1usize << page_bits {
        return Err(c.bad(
            "page bits",
            0,
            format!("{n} entries in pages of 2^{page_bits}: paged data blocks are not read"),
        ));
    }
    let filtered = client == 1;
    if client > 1 || entry < f.offset_size + if filtered { 5 } else { 0 } {
        return Err(c.bad(
            "client id",
            0,
            format!("client {client} with entries of {entry} bytes"),
        ));
    }
    let mut d = f.bytes.le(block, "HDF5 fixed array data block");
    if d.take(4, "signature")? != b"FADB" {
        return Err(d.bad("signature", 4, "FADB expected"));
    }
    d.skip(2 + f.offset_size);
    let total = n
        .checked_mul(entry)
        .ok_or_else(|| d.bad("entries", 0, "too many"))?;
    f.bytes
        .slice(d.pos(), total, "HDF5 fixed array data block")?;
    let mut out = Vec::with_capacity(n);
    for _ in 0..n {
        let a = f.addr(&mut d, "chunk address")?;
        let (size, mask) = match filtered {
            true => (
                H5::uint(&mut d, entry - f.offset_size - 4, "chunk size")? as usize,
                d.u32("filter mask")?,
            ),
            false => (bytes, 0),
        };
        out.push(a.map(|a| (a, size, mask)));
    }
    f.checksum(block, d.pos(), "HDF5 fixed array data block")?;
    Ok(out)
}
