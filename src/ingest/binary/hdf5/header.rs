//! Object headers: the messages of an object (version 1, or version 2
//! `OHDR`), with their continuation blocks followed.

use super::H5;
use crate::error::Result;

/// Message types read here.
pub mod kind {
    /// Dataspace.
    pub const DATASPACE: u16 = 0x01;
    /// Link info (new-style groups).
    pub const LINK_INFO: u16 = 0x02;
    /// Datatype.
    pub const DATATYPE: u16 = 0x03;
    /// Link (new-style groups).
    pub const LINK: u16 = 0x06;
    /// Data layout.
    pub const LAYOUT: u16 = 0x08;
    /// Filter pipeline.
    pub const FILTERS: u16 = 0x0B;
    /// Attribute.
    pub const ATTRIBUTE: u16 = 0x0C;
    /// Continuation.
    pub const CONTINUATION: u16 = 0x10;
    /// Symbol table (old-style groups).
    pub const SYMBOL_TABLE: u16 = 0x11;
    /// Attribute info (dense attribute storage).
    pub const ATTRIBUTE_INFO: u16 = 0x15;
}

/// One message: its type and where its body lies in the file.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Message {
    /// Message type.
    pub kind: u16,
    /// Byte offset of its body.
    pub at: usize,
    /// Body length.
    pub len: usize,
}

/// Most continuation blocks followed for one object: a corrupted header
/// whose continuations loop ends here.
const MAX_BLOCKS: usize = 4096;

/// The messages of the object header at `addr`.
pub fn messages(f: &H5, addr: usize) -> Result<Vec<Message>> {
    let sig = f.bytes.slice(addr, 4, "HDF5 object header")?;
    let mut out = Vec::new();
    let v2 = sig == b"OHDR";
    let (first, order) = match v2 {
        true => v2_prefix(f, addr)?,
        false => (v1_prefix(f, addr)?, false),
    };
    let mut blocks = vec![first];
    let mut n = 0;
    while let Some((from, to)) = blocks.pop() {
        n += 1;
        if n > MAX_BLOCKS {
            return Err(f.bytes.error(
                "HDF5 object header",
                addr,
                "too many continuation blocks (a loop?)",
            ));
        }
        let found = if v2 {
            block(f, from, to, Some(order))?
        } else {
            block(f, from, to, None)?
        };
        for m in found {
            if m.kind == kind::CONTINUATION {
                blocks.push(continuation(f, m, v2)?);
            } else {
                out.push(m);
            }
        }
    }
    Ok(out)
}

/// A version-1 header's prefix; its messages' block.
fn v1_prefix(f: &H5, addr: usize) -> Result<(usize, usize)> {
    let mut c = f.bytes.le(addr, "HDF5 object header");
    let version = c.u8("version")?;
    if version != 1 {
        return Err(c.bad("version", 1, format!("{version}; 1 (or OHDR) expected")));
    }
    c.skip(1 + 2 + 4);
    let size = c.u32("header size")? as usize;
    let from = addr + 16;
    f.bytes.slice(from, size, "HDF5 object header (messages)")?;
    Ok((from, from + size))
}

/// A version-2 header's prefix, its checksum checked: its first chunk, and
/// whether its messages carry a creation order.
fn v2_prefix(f: &H5, addr: usize) -> Result<((usize, usize), bool)> {
    let mut c = f.bytes.le(addr + 4, "HDF5 object header");
    let version = c.u8("version")?;
    if version != 2 {
        return Err(c.bad("version", 1, format!("{version}; 2 expected")));
    }
    let flags = c.u8("flags")?;
    if flags & 0x20 != 0 {
        c.skip(16);
    }
    if flags & 0x10 != 0 {
        c.skip(4);
    }
    let size = H5::uint(&mut c, 1 << (flags & 3), "chunk size")?;
    let from = c.pos();
    let to = usize::try_from(size)
        .ok()
        .and_then(|s| from.checked_add(s))
        .ok_or_else(|| c.bad("chunk size", 1, format!("{size} bytes")))?;
    f.checksum(addr, to, "HDF5 object header")?;
    Ok(((from, to), flags & 0x04 != 0))
}

/// The messages of a block, from its first message to its end (a v2
/// chunk's checksum). Version 1: 8-byte headers (u16 type, u16 size,
/// flags, reserved; bodies sized to keep 8-byte alignment). Version 2:
/// 4-byte headers (u8 type, u16 size, flags), 6 with creation order; a gap
/// shorter than a message header may end the chunk.
fn block(f: &H5, from: usize, to: usize, v2: Option<bool>) -> Result<Vec<Message>> {
    let (head, end) = match v2 {
        None => (8, "header"),
        Some(order) => (if order { 6 } else { 4 }, "chunk"),
    };
    let mut out = Vec::new();
    let mut at = from;
    while at + head <= to {
        let mut c = f.bytes.le(at, "HDF5 object header message");
        let kind = match v2 {
            None => c.u16("type")?,
            Some(_) => u16::from(c.u8("type")?),
        };
        let len = c.u16("size")? as usize;
        let body = at + head;
        if body + len > to {
            return Err(c.bad("size", 2, format!("{len} bytes run past the {end}'s end")));
        }
        out.push(Message {
            kind,
            at: body,
            len,
        });
        at = body + len;
    }
    Ok(out)
}

/// A continuation message: the next block of messages.
fn continuation(f: &H5, m: Message, v2: bool) -> Result<(usize, usize)> {
    let mut c = f.bytes.le(m.at, "HDF5 continuation message");
    let addr = f.need(&mut c, "offset")?;
    let len = f.length(&mut c, "length")?;
    f.bytes.slice(addr, len, "HDF5 continuation block")?;
    if !v2 {
        return Ok((addr, addr + len));
    }
    if f.bytes.slice(addr, 4, "HDF5 continuation block")? != b"OCHK" || len < 8 {
        return Err(f
            .bytes
            .error("HDF5 continuation block", addr, "no OCHK signature"));
    }
    f.checksum(addr, addr + len - 4, "HDF5 continuation block")?;
    Ok((addr + 4, addr + len - 4))
}
