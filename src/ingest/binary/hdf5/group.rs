//! Groups: the links (name → object header) of an old-style group
//! (symbol table: v1 B-tree of symbol nodes, names in a local heap) or of
//! a new-style one (link messages in its header). Dense link storage
//! (a fractal heap, groups of many links written by HDF5 1.8+ with the
//! latest format) is an error that says so.

use super::header::{kind, messages, Message};
use super::H5;
use crate::error::Result;
use crate::ingest::binary::Cursor;

/// Deepest B-tree followed: a corrupted tree that loops ends here.
const MAX_DEPTH: usize = 32;

/// The hard links of the group whose object header is at `addr`, in the
/// file's order: (name, object header address).
pub fn links(f: &H5, addr: usize) -> Result<Vec<(String, usize)>> {
    let msgs = messages(f, addr)?;
    let mut out = Vec::new();
    for m in &msgs {
        match m.kind {
            kind::SYMBOL_TABLE => symbol_table(f, *m, &mut out)?,
            kind::LINK => {
                if let Some(l) = link(f, *m)? {
                    out.push(l);
                }
            }
            kind::LINK_INFO => dense_links(f, *m)?,
            _ => {}
        }
    }
    Ok(out)
}

/// Refuses a link info message that points at a fractal heap.
fn dense_links(f: &H5, m: Message) -> Result<()> {
    let mut c = f.bytes.le(m.at, "HDF5 link info message");
    c.skip(1);
    let flags = c.u8("flags")?;
    if flags & 1 != 0 {
        c.skip(8);
    }
    match f.addr(&mut c, "fractal heap address")? {
        None => Ok(()),
        Some(_) => Err(f.bytes.error(
            "HDF5 link info message",
            m.at,
            "dense link storage (a fractal heap) is not read",
        )),
    }
}

/// A link message: its name and, for a hard link, the object's address.
fn link(f: &H5, m: Message) -> Result<Option<(String, usize)>> {
    let mut c = f.bytes.le(m.at, "HDF5 link message");
    let version = c.u8("version")?;
    if version != 1 {
        return Err(c.bad("version", 1, format!("{version}; 1 expected")));
    }
    let flags = c.u8("flags")?;
    let ty = if flags & 0x08 != 0 {
        c.u8("link type")?
    } else {
        0
    };
    if flags & 0x04 != 0 {
        c.skip(8);
    }
    if flags & 0x10 != 0 {
        c.skip(1);
    }
    let n = H5::uint(&mut c, 1 << (flags & 3), "name length")? as usize;
    let name = String::from_utf8_lossy(c.take(n, "name")?).into_owned();
    if ty != 0 {
        return Ok(None); // soft and external links lead outside what is read
    }
    Ok(Some((name, f.need(&mut c, "object address")?)))
}

/// The entries of an old-style group: its B-tree's symbol nodes, names
/// from its local heap.
fn symbol_table(f: &H5, m: Message, out: &mut Vec<(String, usize)>) -> Result<()> {
    let mut c = f.bytes.le(m.at, "HDF5 symbol table message");
    let tree = f.need(&mut c, "B-tree address")?;
    let heap = f.need(&mut c, "local heap address")?;
    let mut h = f.bytes.le(heap, "HDF5 local heap");
    if h.take(4, "signature")? != b"HEAP" {
        return Err(h.bad("signature", 4, "HEAP expected"));
    }
    h.skip(4);
    let size = f.length(&mut h, "data segment size")?;
    f.length(&mut h, "free list offset")?;
    let data = f.need(&mut h, "data segment address")?;
    let names = f.bytes.slice(data, size, "HDF5 local heap data")?;
    let mut nodes = Vec::new();
    group_tree(f, tree, &mut vec![], &mut nodes)?;
    for node in nodes {
        symbol_node(f, node, names, out)?;
    }
    Ok(())
}

/// A v1 B-tree node (`TREE`) of type `ty`: its level and entries used,
/// and the cursor at its first key. `seen` holds the nodes visited (at
/// most `max_nodes`), so that a corrupted tree pointing back into itself
/// is an error rather than an endless walk; depth and level are bounded.
pub(super) fn v1_node<'a>(
    f: &H5<'a>,
    addr: usize,
    ty: u8,
    what: &'a str,
    seen: &mut Vec<usize>,
    max_nodes: usize,
) -> Result<(Cursor<'a>, u8, u16)> {
    let depth = seen.len();
    let mut c = f.bytes.le(addr, what);
    if seen.contains(&addr) || seen.len() > max_nodes {
        return Err(c.error("B-tree node visited twice (a loop?)"));
    }
    seen.push(addr);
    if c.take(4, "signature")? != b"TREE" {
        return Err(c.bad("signature", 4, "TREE expected"));
    }
    let found = c.u8("node type")?;
    let level = c.u8("node level")?;
    let used = c.u16("entries used")?;
    if found != ty || depth > MAX_DEPTH || (level as usize) > MAX_DEPTH {
        return Err(c.bad(
            "node type",
            4,
            format!("type {found}, level {level} at depth {depth}; type {ty} expected"),
        ));
    }
    c.skip(2 * f.offset_size);
    Ok((c, level, used))
}

/// The symbol-node addresses under a group B-tree node (type 0).
fn group_tree(f: &H5, addr: usize, seen: &mut Vec<usize>, out: &mut Vec<usize>) -> Result<()> {
    let (mut c, level, used) = v1_node(f, addr, 0, "HDF5 group B-tree node", seen, 4096)?;
    for _ in 0..used {
        c.skip(f.length_size);
        let child = f.need(&mut c, "child address")?;
        match level {
            0 => out.push(child),
            _ => group_tree(f, child, seen, out)?,
        }
    }
    Ok(())
}

/// The entries of a symbol node (`SNOD`).
fn symbol_node(f: &H5, addr: usize, names: &[u8], out: &mut Vec<(String, usize)>) -> Result<()> {
    let mut c = f.bytes.le(addr, "HDF5 symbol table node");
    if c.take(4, "signature")? != b"SNOD" {
        return Err(c.bad("signature", 4, "SNOD expected"));
    }
    c.skip(2);
    let n = c.u16("number of symbols")?;
    for _ in 0..n {
        let at = H5::uint(&mut c, f.offset_size, "link name offset")?;
        let object = f.need(&mut c, "object header address")?;
        c.skip(4 + 4 + 16);
        let name = usize::try_from(at)
            .ok()
            .and_then(|a| names.get(a..))
            .map(|s| &s[..s.iter().position(|&b| b == 0).unwrap_or(s.len())])
            .ok_or_else(|| {
                c.bad(
                    "link name offset",
                    2 * f.offset_size + 24,
                    format!("{at} is past the local heap"),
                )
            })?;
        out.push((String::from_utf8_lossy(name).into_owned(), object));
    }
    Ok(())
}
