//! Attributes of an object: compact ones (attribute messages, versions 1
//! to 3) with their values; dense storage is an error that says so.

use super::header::{kind, messages, Message};
use super::types::{dataspace, dtype, value, Dtype, Value};
use super::H5;
use crate::error::Result;
use crate::ingest::binary::latin1_or_utf8;

/// An attribute: name, type, element count and where its data lies.
#[derive(Debug, Clone)]
pub struct Attribute {
    /// Its name.
    pub name: String,
    /// Its datatype.
    pub ty: Dtype,
    /// Elements.
    pub count: usize,
    /// Byte offset of the data.
    pub at: usize,
}

impl Attribute {
    /// The decoded value: one element, or a list of them.
    pub fn value(&self, f: &H5) -> Result<Value> {
        let len = self.count.saturating_mul(self.ty.size);
        let raw = f.bytes.slice(self.at, len, "HDF5 attribute data")?;
        let mut v = Vec::new();
        for i in 0..self.count.min(4096) {
            let s = i * self.ty.size;
            v.push(value(f, &self.ty, &raw[s..], self.at + s)?);
        }
        Ok(match v.len() {
            1 => v.remove(0),
            _ => Value::List(v),
        })
    }
}

/// The attributes of the object at `addr` (compact storage; dense
/// storage is an error that says so).
pub fn attributes(f: &H5, addr: usize) -> Result<Vec<Attribute>> {
    let mut out = Vec::new();
    for m in messages(f, addr)? {
        match m.kind {
            kind::ATTRIBUTE => out.push(attribute(f, m)?),
            kind::ATTRIBUTE_INFO => dense_attributes(f, m)?,
            _ => {}
        }
    }
    Ok(out)
}

fn dense_attributes(f: &H5, m: Message) -> Result<()> {
    let mut c = f.bytes.le(m.at, "HDF5 attribute info message");
    c.skip(1);
    if c.u8("flags")? & 1 != 0 {
        c.skip(2);
    }
    match f.addr(&mut c, "fractal heap address")? {
        None => Ok(()),
        Some(_) => Err(f.bytes.error(
            "HDF5 attribute info message",
            m.at,
            "dense attribute storage (a fractal heap) is not read",
        )),
    }
}

/// An attribute message (versions 1 to 3).
fn attribute(f: &H5, m: Message) -> Result<Attribute> {
    let mut c = f.bytes.le(m.at, "HDF5 attribute message");
    let version = c.u8("version")?;
    let flags = c.u8("flags")?;
    if !(1..=3).contains(&version) {
        return Err(c.bad("version", 2, format!("{version}; 1 to 3 expected")));
    }
    if flags & 3 != 0 {
        return Err(c.bad("flags", 1, "shared datatypes and dataspaces are not read"));
    }
    let name_len = c.u16("name size")? as usize;
    let type_len = c.u16("datatype size")? as usize;
    let space_len = c.u16("dataspace size")? as usize;
    if version == 3 {
        c.skip(1);
    }
    let pad = |n: usize| if version == 1 { n.div_ceil(8) * 8 } else { n };
    let name = latin1_or_utf8(c.take(name_len, "name")?);
    c.skip(pad(name_len) - name_len);
    let type_at = c.pos();
    let ty = dtype(f, &mut c, 0)?;
    c.seek(type_at + pad(type_len));
    let (count, _) = dataspace(f, c.pos())?;
    let at = c.pos() + pad(space_len);
    if at > m.at + m.len {
        return Err(c.bad(
            "dataspace size",
            0,
            "the attribute's parts run past its message",
        ));
    }
    Ok(Attribute {
        name,
        ty,
        count,
        at,
    })
}
