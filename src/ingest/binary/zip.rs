//! A zip container read in place (X3P, and any zip-based format): the
//! central directory, then each entry as a stream, stored or deflated,
//! checked against its CRC-32 and size when it has been read to its end.
//!
//! Written here rather than taken from the `zip` crate: the formats need
//! only stored and deflated entries, and the crate's ~15 s of extra build
//! (zip, typed-path, zeroize, ...) on 2 cores buys nothing over ~200 lines
//! on `flate2`, which polars already builds. Zip64 sizes and offsets are
//! read; encrypted entries and other methods are errors that say so.

use std::io::Read;

use super::Bytes;
use crate::error::Result;

/// One entry of the central directory.
#[derive(Debug, Clone, PartialEq)]
pub struct Entry {
    /// Its path in the archive (`main.xml`, `bindata/data.bin`).
    pub name: String,
    method: u16,
    flags: u16,
    crc: u32,
    /// Compressed size (bytes).
    pub compressed: u64,
    /// Size once decompressed (bytes).
    pub size: u64,
    /// Where its local header is in the file.
    pub local: u64,
}

/// A zip archive's directory.
#[derive(Debug, Clone)]
pub struct Zip {
    /// The entries, in the directory's order.
    pub entries: Vec<Entry>,
}

const EOCD: u32 = 0x0605_4b50;
const EOCD64: u32 = 0x0606_4b50;
const LOCATOR64: u32 = 0x0706_4b50;
const CENTRAL: u32 = 0x0201_4b50;
const LOCAL: u32 = 0x0403_4b50;

/// Whether the bytes start like a zip archive (a local file header).
pub fn is_zip(data: &[u8]) -> bool {
    data.starts_with(b"PK\x03\x04")
}

impl Zip {
    /// Reads the central directory.
    pub fn open(bytes: &Bytes) -> Result<Zip> {
        let data = bytes.data;
        // The end record is in the last 22 + 65535 (comment) bytes.
        let from = data.len().saturating_sub(22 + 65_535);
        let at = (from..data.len().saturating_sub(21))
            .rev()
            .find(|&i| data[i..i + 4] == EOCD.to_le_bytes())
            .ok_or_else(|| {
                bytes.error(
                    "zip end of central directory",
                    data.len(),
                    "not found at the end of the file (a truncated or not a zip archive)",
                )
            })?;
        let mut c = bytes.le(at + 10, "zip end of central directory");
        let mut count = c.u16("entries")? as u64;
        let mut cd_size = c.u32("directory size")? as u64;
        let mut cd_at = c.u32("directory offset")? as u64;
        let mut cd_end = at as u64;
        if count == 0xFFFF || cd_size == 0xFFFF_FFFF || cd_at == 0xFFFF_FFFF {
            (count, cd_size, cd_at, cd_end) = zip64_end(bytes, at)?;
        }
        // An archive after a prefix (ZON's preview image, VK6's header)
        // counts its offsets from its own start: where the directory ends
        // less its size and its stated offset (as Python's zipfile finds it).
        let base = cd_end
            .checked_sub(cd_size)
            .and_then(|d| d.checked_sub(cd_at))
            .unwrap_or(0);
        let cd_at = usize::try_from(cd_at + base).unwrap_or(usize::MAX);
        bytes.slice(
            cd_at,
            usize::try_from(cd_size).unwrap_or(usize::MAX),
            "zip central directory",
        )?;
        let mut c = bytes.le(cd_at, "zip central directory entry");
        let mut entries = Vec::new();
        for _ in 0..count {
            entries.push(central_entry(bytes, &mut c, base)?);
        }
        Ok(Zip { entries })
    }

    /// The entry with this exact path.
    pub fn find(&self, name: &str) -> Option<&Entry> {
        self.entries.iter().find(|e| e.name == name)
    }

    /// Reads an entry through `f`, a stream of its decompressed bytes;
    /// a stream read to its end is checked against the entry's CRC-32 and
    /// size (an error of the read).
    pub fn open_entry<'b>(&self, bytes: &Bytes<'b>, e: &Entry) -> Result<EntryReader<'b>> {
        let structure = format!("zip entry '{}'", e.name);
        if e.flags & 1 != 0 {
            return Err(bytes.error(&structure, e.local as usize, "is encrypted"));
        }
        let local = usize::try_from(e.local).unwrap_or(usize::MAX);
        let mut c = bytes.le(local, "zip local file header");
        if c.u32("signature")? != LOCAL {
            return Err(bytes.error(&structure, local, "no local file header here"));
        }
        c.skip(22);
        let name_len = c.u16("name length")? as usize;
        let extra_len = c.u16("extra length")? as usize;
        let start = c.pos() + name_len + extra_len;
        let len = usize::try_from(e.compressed).unwrap_or(usize::MAX);
        let raw = bytes.slice(start, len, &structure)?;
        let source = Releasing {
            bytes: *bytes,
            data: raw,
            pos: 0,
            base: start,
            released: 0,
        };
        let inner = match e.method {
            0 => Inner::Stored(source),
            8 => Inner::Deflate(Box::new(flate2::read::DeflateDecoder::new(source))),
            m => {
                return Err(bytes.error(
                    &structure,
                    local,
                    format!("compression method {m}; only stored (0) and deflate (8) are read"),
                ))
            }
        };
        Ok(EntryReader {
            inner,
            crc: flate2::Crc::new(),
            entry: e.clone(),
            start,
        })
    }

    /// An entry's whole content, for small entries (XML, checksums):
    /// at most `limit` bytes.
    pub fn read_small(&self, bytes: &Bytes, e: &Entry, limit: u64) -> Result<Vec<u8>> {
        let structure = format!("zip entry '{}'", e.name);
        if e.size > limit {
            return Err(bytes.error(
                &structure,
                e.local as usize,
                format!("is {} bytes; at most {limit} expected", e.size),
            ));
        }
        let mut r = self.open_entry(bytes, e)?;
        let mut out = Vec::with_capacity(e.size as usize);
        r.read_to_end(&mut out)
            .map_err(|err| bytes.error(&structure, r.start, err.to_string()))?;
        Ok(out)
    }
}

/// The zip64 end record's count, size and offset of the directory, and
/// where the record is (the directory ends there).
fn zip64_end(bytes: &Bytes, eocd: usize) -> Result<(u64, u64, u64, u64)> {
    let loc = eocd.checked_sub(20).ok_or_else(|| {
        bytes.error(
            "zip64 end locator",
            eocd,
            "no room for it before the end record",
        )
    })?;
    let mut c = bytes.le(loc, "zip64 end locator");
    if c.u32("signature")? != LOCATOR64 {
        return Err(bytes.error("zip64 end locator", loc, "not found"));
    }
    c.skip(4);
    let stated = c.u64("end record offset")?;
    // At its stated offset, or (an archive after a prefix) just before the
    // locator, where a record without extensible data ends.
    let signed = |at: usize| bytes.data.get(at..at + 4) == Some(&EOCD64.to_le_bytes()[..]);
    let at = [
        usize::try_from(stated).unwrap_or(usize::MAX),
        loc.saturating_sub(56),
    ]
    .into_iter()
    .find(|&at| signed(at))
    .ok_or_else(|| bytes.error("zip64 end of central directory", loc, "not found"))?;
    let mut c = bytes.le(at + 32, "zip64 end of central directory");
    let count = c.u64("entries")?;
    let size = c.u64("directory size")?;
    let offset = c.u64("directory offset")?;
    Ok((count, size, offset, at as u64))
}

fn central_entry(bytes: &Bytes, c: &mut super::Cursor, base: u64) -> Result<Entry> {
    let at = c.pos();
    if c.u32("signature")? != CENTRAL {
        return Err(bytes.error("zip central directory entry", at, "bad signature"));
    }
    c.skip(4);
    let flags = c.u16("flags")?;
    let method = c.u16("method")?;
    c.skip(4);
    let crc = c.u32("crc-32")?;
    let mut compressed = c.u32("compressed size")? as u64;
    let mut size = c.u32("size")? as u64;
    let name_len = c.u16("name length")? as usize;
    let extra_len = c.u16("extra length")? as usize;
    let comment_len = c.u16("comment length")? as usize;
    c.skip(8);
    let mut local = c.u32("local header offset")? as u64;
    let name = String::from_utf8_lossy(c.take(name_len, "name")?).into_owned();
    let extra = c.take(extra_len, "extra field")?;
    c.take(comment_len, "comment")?;
    // Zip64: the fields stored as 0xFFFFFFFF follow in the extra block 1.
    let mut x = extra;
    while x.len() >= 4 {
        let id = u16::from_le_bytes([x[0], x[1]]);
        let n = (u16::from_le_bytes([x[2], x[3]]) as usize).min(x.len() - 4);
        if id == 1 {
            let mut f = x[4..4 + n]
                .chunks_exact(8)
                .map(|b| u64::from_le_bytes(b.try_into().expect("chunks_exact gives 8 bytes")));
            for v in [&mut size, &mut compressed, &mut local] {
                if *v == 0xFFFF_FFFF {
                    *v = f.next().ok_or_else(|| {
                        bytes.error("zip64 extra field", at, format!("'{name}' lacks a size"))
                    })?;
                }
            }
        }
        x = &x[4 + n..];
    }
    Ok(Entry {
        name,
        method,
        flags,
        crc,
        compressed,
        size,
        local: local.saturating_add(base),
    })
}

/// The compressed bytes of an entry, read in place; pages of a mapped
/// file are released every 4 MiB behind the reader.
struct Releasing<'b> {
    bytes: Bytes<'b>,
    data: &'b [u8],
    pos: usize,
    base: usize,
    released: usize,
}

impl Read for Releasing<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let k = buf.len().min(self.data.len() - self.pos);
        buf[..k].copy_from_slice(&self.data[self.pos..self.pos + k]);
        self.pos += k;
        if self.pos - self.released >= 4 << 20 || (k == 0 && self.pos > self.released) {
            let b = self.base;
            self.bytes.release(b + self.released..b + self.pos);
            self.released = self.pos;
        }
        Ok(k)
    }
}

enum Inner<'b> {
    Stored(Releasing<'b>),
    Deflate(Box<flate2::read::DeflateDecoder<Releasing<'b>>>),
}

/// An entry's decompressed bytes as a stream (see [`Zip::open_entry`]).
pub struct EntryReader<'b> {
    inner: Inner<'b>,
    crc: flate2::Crc,
    entry: Entry,
    /// Where the entry's data starts in the file.
    pub start: usize,
}

impl Read for EntryReader<'_> {
    fn read(&mut self, buf: &mut [u8]) -> std::io::Result<usize> {
        let k = match &mut self.inner {
            Inner::Stored(r) => r.read(buf)?,
            Inner::Deflate(r) => r.read(buf)?,
        };
        self.crc.update(&buf[..k]);
        if k == 0 || self.crc.amount() as u64 > self.entry.size {
            let e = &self.entry;
            let bad = |m: String| std::io::Error::new(std::io::ErrorKind::InvalidData, m);
            if self.crc.amount() as u64 != e.size {
                return Err(bad(format!(
                    "decompresses to {} bytes; the directory says {}",
                    self.crc.amount(),
                    e.size
                )));
            }
            if self.crc.sum() != e.crc {
                return Err(bad(format!(
                    "CRC-32 {:08x}; the directory says {:08x} (corrupted)",
                    self.crc.sum(),
                    e.crc
                )));
            }
        }
        Ok(k)
    }
}

/// A zip archive of `files` (name, content), stored or deflated: what the
/// tests write their X3P (and other zip-based) fixtures with.
pub fn write(files: &[(&str, &[u8])], deflate: bool) -> Vec<u8> {
    use std::io::Write;
    let mut out = Vec::new();
    let mut central = Vec::new();
    for (name, content) in files {
        let mut crc = flate2::Crc::new();
        crc.update(content);
        let body = match deflate {
            true => {
                let mut e =
                    flate2::write::DeflateEncoder::new(Vec::new(), flate2::Compression::fast());
                e.write_all(content).expect("writing to memory");
                e.finish().expect("writing to memory")
            }
            false => content.to_vec(),
        };
        let method: u16 = if deflate { 8 } else { 0 };
        let fields = |sig: u32| {
            let mut h = sig.to_le_bytes().to_vec();
            h.extend_from_slice(&20u16.to_le_bytes());
            if sig == CENTRAL {
                h.extend_from_slice(&20u16.to_le_bytes());
            }
            h.extend_from_slice(&0u16.to_le_bytes());
            h.extend_from_slice(&method.to_le_bytes());
            h.extend_from_slice(&[0; 4]);
            h.extend_from_slice(&crc.sum().to_le_bytes());
            h.extend_from_slice(&(body.len() as u32).to_le_bytes());
            h.extend_from_slice(&(content.len() as u32).to_le_bytes());
            h.extend_from_slice(&(name.len() as u16).to_le_bytes());
            h.extend_from_slice(&0u16.to_le_bytes());
            h
        };
        let offset = out.len() as u32;
        out.extend(fields(LOCAL));
        out.extend_from_slice(name.as_bytes());
        out.extend_from_slice(&body);
        central.extend(fields(CENTRAL));
        // Comment length, disk, internal and external attributes.
        central.extend_from_slice(&[0; 10]);
        central.extend_from_slice(&offset.to_le_bytes());
        central.extend_from_slice(name.as_bytes());
    }
    let cd_at = out.len() as u32;
    out.extend_from_slice(&central);
    out.extend_from_slice(&EOCD.to_le_bytes());
    out.extend_from_slice(&[0; 4]);
    let n = (files.len() as u16).to_le_bytes();
    out.extend_from_slice(&n);
    out.extend_from_slice(&n);
    out.extend_from_slice(&(central.len() as u32).to_le_bytes());
    out.extend_from_slice(&cd_at.to_le_bytes());
    out.extend_from_slice(&0u16.to_le_bytes());
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::Path;

    #[test]
    fn stored_and_deflated_entries_read_back_and_corruption_is_caught() {
        let body: Vec<u8> = (0..100_000u32)
            .flat_map(|i| (i % 251).to_le_bytes())
            .collect();
        for deflate in [false, true] {
            let z = write(&[("a/main.xml", b"<x/>"), ("bin/data.bin", &body)], deflate);
            let b = Bytes::new(Path::new("t.zip"), &z);
            let zip = Zip::open(&b).unwrap();
            assert_eq!(zip.entries.len(), 2);
            let e = zip.find("bin/data.bin").unwrap();
            assert_eq!(zip.read_small(&b, e, u64::MAX).unwrap(), body);
            // One byte of the data changed: the CRC (or the inflater) says so.
            let mut bad = z.clone();
            let at = e.local as usize + 30 + e.name.len() + 1000;
            bad[at] ^= 0x55;
            let b = Bytes::new(Path::new("t.zip"), &bad);
            let zip = Zip::open(&b).unwrap();
            let err = zip
                .read_small(&b, zip.find("bin/data.bin").unwrap(), u64::MAX)
                .unwrap_err()
                .to_string();
            assert!(err.contains("zip entry 'bin/data.bin'"), "{err}");
            // Cut short: no end record.
            let cut = &z[..z.len() / 2];
            let err = Zip::open(&Bytes::new(Path::new("t.zip"), cut))
                .unwrap_err()
                .to_string();
            assert!(err.contains("end of central directory"), "{err}");
        }
    }

    /// An archive after a prefix (ZON, VK6) keeps offsets from its own
    /// start: its entries are found where they are in the file.
    #[test]
    fn an_archive_after_a_prefix_reads_its_entries() {
        let z = write(&[("a", b"first"), ("b", b"second entry")], false);
        let mut f = b"KPK1 and a preview of any length".to_vec();
        f.extend(&z);
        let b = Bytes::new(Path::new("t.zon"), &f);
        let zip = Zip::open(&b).unwrap();
        let e = zip.find("b").unwrap();
        assert_eq!(zip.read_small(&b, e, 100).unwrap(), b"second entry");
    }
}
