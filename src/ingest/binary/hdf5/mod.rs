//! A read-only subset of HDF5, enough for instrument files built on it
//! (Zygo DATX): superblock versions 0–3 (after a user block too), object
//! headers v1 and v2 with their continuation blocks, old-style groups
//! (symbol table, v1 B-tree, local heap) and new-style compact links,
//! datatypes (integers, floats, strings, compounds, variable-length
//! strings and sequences through the global heap, enums, arrays),
//! attributes, and datasets stored compact, contiguous or chunked (v1
//! B-tree, single-chunk, implicit and fixed-array indexes; deflate,
//! shuffle and Fletcher-32 filters).
//!
//! Written from the HDF5 File Format Specification (version 3.0) rather
//! than taken from a crate: the pure-Rust crates either do not decode
//! compound attributes holding variable-length strings and sequences
//! (DATX's unit converters), or are >100 000 lines (docs/formats.md,
//! "Crates"). Dense (fractal-heap) link and attribute storage, extensible
//! array and v2 B-tree chunk indexes, and filters other than the three
//! above are errors that name them. Every read is bounds-checked and every
//! failure an [`crate::error::Error::Structure`] with its byte offset;
//! checksums of v2 structures are verified.

pub mod attr;
pub mod data;
pub mod fixed;
pub mod group;
pub mod header;
pub mod types;

use super::Bytes;
use crate::error::Result;

/// The HDF5 signature.
pub const SIGNATURE: &[u8; 8] = b"\x89HDF\r\n\x1a\n";

/// Where the superblock is: at 0, or after a user block of 512, 1024,
/// 2048, ... bytes.
pub fn find_signature(data: &[u8]) -> Option<usize> {
    let mut at = 0usize;
    while at.checked_add(8).is_some_and(|e| e <= data.len()) {
        if &data[at..at + 8] == SIGNATURE {
            return Some(at);
        }
        at = if at == 0 { 512 } else { at.checked_mul(2)? };
    }
    None
}

/// An HDF5 file: its bytes and what the superblock says about addresses.
#[derive(Clone, Copy)]
pub struct H5<'a> {
    /// The file's bytes.
    pub bytes: Bytes<'a>,
    /// Where addresses count from (the superblock's position).
    base: usize,
    /// Bytes of an address.
    pub offset_size: usize,
    /// Bytes of a length.
    pub length_size: usize,
    /// The root group's object header (absolute).
    pub root: usize,
    /// Superblock version.
    pub version: u8,
}

impl<'a> H5<'a> {
    /// Reads the superblock.
    pub fn open(bytes: Bytes<'a>) -> Result<H5<'a>> {
        let base = find_signature(bytes.data).ok_or_else(|| {
            bytes.error(
                "HDF5 superblock",
                0,
                "no HDF5 signature at byte 0, 512, 1024, ...",
            )
        })?;
        let mut c = bytes.le(base + 8, "HDF5 superblock");
        let version = c.u8("version")?;
        let mut f = H5 {
            bytes,
            base,
            offset_size: 8,
            length_size: 8,
            root: 0,
            version,
        };
        match version {
            0 | 1 => {
                c.skip(4);
                f.sizes(&mut c)?;
                c.skip(1 + 4 + 4 + if version == 1 { 4 } else { 0 });
                c.skip(2 * f.offset_size); // base, free space
                f.end(&mut c)?;
                c.skip(2 * f.offset_size); // driver, root entry's name offset
                f.root = f.need(&mut c, "root group object header")?;
            }
            2 | 3 => {
                f.sizes(&mut c)?;
                c.skip(1 + 2 * f.offset_size); // flags, base, extension
                f.end(&mut c)?;
                f.root = f.need(&mut c, "root group object header")?;
                let end = c.pos();
                f.checksum(base, end, "HDF5 superblock")?;
            }
            v => return Err(c.bad("version", 1, format!("{v}; 0 to 3 expected"))),
        }
        Ok(f)
    }

    /// Checks the end-of-file address against the file's length: a
    /// truncated file is refused here, before any of its parts is read.
    fn end(&self, c: &mut super::Cursor) -> Result<()> {
        let end = Self::uint(c, self.offset_size, "end of file address")?;
        // Stored as the relative end plus the base address: the file's
        // whole length, user block included (as h5py's files hold it).
        let have = self.bytes.len() as u64;
        if end > have {
            return Err(c.bad(
                "end of file address",
                self.offset_size,
                format!("the file should have {end} bytes, it has {have} (truncated?)"),
            ));
        }
        Ok(())
    }

    fn sizes(&mut self, c: &mut super::Cursor) -> Result<()> {
        self.offset_size = c.u8("size of offsets")? as usize;
        self.length_size = c.u8("size of lengths")? as usize;
        for (what, n) in [
            ("size of offsets", self.offset_size),
            ("size of lengths", self.length_size),
        ] {
            if !matches!(n, 2 | 4 | 8) {
                return Err(c.bad(what, 1, format!("{n}; 2, 4 or 8 expected")));
            }
        }
        Ok(())
    }

    /// An unsigned little-endian number of `n` bytes.
    pub fn uint(c: &mut super::Cursor, n: usize, field: &str) -> Result<u64> {
        let b = c.take(n, field)?;
        Ok(b.iter().rev().fold(0u64, |a, &x| (a << 8) | x as u64))
    }

    /// A length.
    pub fn length(&self, c: &mut super::Cursor, field: &str) -> Result<usize> {
        let v = Self::uint(c, self.length_size, field)?;
        usize::try_from(v).map_err(|_| c.bad(field, self.length_size, format!("{v} is too large")))
    }

    /// An address, absolute; `None` for the undefined address (all ones).
    pub fn addr(&self, c: &mut super::Cursor, field: &str) -> Result<Option<usize>> {
        let v = Self::uint(c, self.offset_size, field)?;
        if self.offset_size < 8 && v == (1u64 << (8 * self.offset_size)) - 1 || v == u64::MAX {
            return Ok(None);
        }
        let abs = usize::try_from(v)
            .ok()
            .and_then(|v| v.checked_add(self.base))
            .filter(|&a| a < self.bytes.len());
        match abs {
            Some(a) => Ok(Some(a)),
            None => Err(c.bad(
                field,
                self.offset_size,
                format!(
                    "address {v} is past the end of the file ({} bytes; truncated?)",
                    self.bytes.len()
                ),
            )),
        }
    }

    /// An address that must be defined.
    pub fn need(&self, c: &mut super::Cursor, field: &str) -> Result<usize> {
        self.addr(c, field)?
            .ok_or_else(|| c.bad(field, self.offset_size, "undefined address"))
    }

    /// Checks the Jenkins lookup3 checksum stored after `from..to`.
    pub fn checksum(&self, from: usize, to: usize, structure: &str) -> Result<()> {
        let body = self.bytes.slice(from, to.saturating_sub(from), structure)?;
        let mut c = self.bytes.le(to, structure);
        let stored = c.u32("checksum")?;
        let computed = lookup3(body);
        if stored != computed {
            return Err(self.bytes.error(
                structure,
                from,
                format!("checksum {stored:#010x} stored, {computed:#010x} computed (corrupted?)"),
            ));
        }
        Ok(())
    }

    /// The object header at the end of `path` (`Data/Surface/x`), from
    /// the root group.
    pub fn find(&self, path: &str) -> Result<Option<usize>> {
        let mut at = self.root;
        for part in path.split('/').filter(|p| !p.is_empty()) {
            let links = group::links(self, at)?;
            match links.into_iter().find(|(n, _)| n == part) {
                Some((_, a)) => at = a,
                None => return Ok(None),
            }
        }
        Ok(Some(at))
    }
}

/// Bob Jenkins' lookup3 `hashlittle` with seed 0: HDF5's checksum of its
/// version-2 structures.
pub fn lookup3(key: &[u8]) -> u32 {
    let mut a = 0xdead_beefu32.wrapping_add(key.len() as u32);
    let (mut b, mut c) = (a, a);
    let word = |k: &[u8]| {
        let mut w = [0u8; 4];
        w[..k.len()].copy_from_slice(k);
        u32::from_le_bytes(w)
    };
    let mut k = key;
    while k.len() > 12 {
        a = a.wrapping_add(word(&k[0..4]));
        b = b.wrapping_add(word(&k[4..8]));
        c = c.wrapping_add(word(&k[8..12]));
        (a, b, c) = mix(a, b, c);
        k = &k[12..];
    }
    if k.is_empty() {
        return c;
    }
    let mut tail = [0u8; 12];
    tail[..k.len()].copy_from_slice(k);
    a = a.wrapping_add(word(&tail[0..4]));
    b = b.wrapping_add(word(&tail[4..8]));
    c = c.wrapping_add(word(&tail[8..12]));
    final_mix(a, b, c)
}

fn mix(mut a: u32, mut b: u32, mut c: u32) -> (u32, u32, u32) {
    a = a.wrapping_sub(c) ^ c.rotate_left(4);
    c = c.wrapping_add(b);
    b = b.wrapping_sub(a) ^ a.rotate_left(6);
    a = a.wrapping_add(c);
    c = c.wrapping_sub(b) ^ b.rotate_left(8);
    b = b.wrapping_add(a);
    a = a.wrapping_sub(c) ^ c.rotate_left(16);
    c = c.wrapping_add(b);
    b = b.wrapping_sub(a) ^ a.rotate_left(19);
    a = a.wrapping_add(c);
    c = c.wrapping_sub(b) ^ b.rotate_left(4);
    b = b.wrapping_add(a);
    (a, b, c)
}

fn final_mix(mut a: u32, mut b: u32, mut c: u32) -> u32 {
    c ^= b;
    c = c.wrapping_sub(b.rotate_left(14));
    a ^= c;
    a = a.wrapping_sub(c.rotate_left(11));
    b ^= a;
    b = b.wrapping_sub(a.rotate_left(25));
    c ^= b;
    c = c.wrapping_sub(b.rotate_left(16));
    a ^= c;
    a = a.wrapping_sub(c.rotate_left(4));
    b ^= a;
    b = b.wrapping_sub(a.rotate_left(14));
    c ^= b;
    c = c.wrapping_sub(b.rotate_left(24));
    c
}

#[cfg(test)]
mod tests {
    /// Bob Jenkins' published values of `hashlittle(key, 0)`.
    #[test]
    fn lookup3_known_values() {
        assert_eq!(super::lookup3(b""), 0xdead_beef);
        assert_eq!(
            super::lookup3(b"Four score and seven years ago"),
            0x1777_0551
        );
    }

    #[test]
    fn signature_after_a_user_block() {
        let mut b = vec![0u8; 2048 + 8];
        b[1024..1032].copy_from_slice(super::SIGNATURE);
        assert_eq!(super::find_signature(&b), Some(1024));
        assert_eq!(super::find_signature(&b[..1030]), None);
    }
}
