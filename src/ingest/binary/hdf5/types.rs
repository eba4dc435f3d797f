//! Datatypes, dataspaces, attributes and the values they hold, with
//! variable-length strings and sequences read from the global heap.

use super::H5;
use crate::error::Result;
use crate::ingest::binary::{latin1_or_utf8, Cursor};

/// A datatype: the size of one element and its class.
#[derive(Debug, Clone, PartialEq)]
pub struct Dtype {
    /// Bytes of one element.
    pub size: usize,
    /// What the bytes are.
    pub kind: Kind,
}

/// Datatype classes.
#[derive(Debug, Clone, PartialEq)]
pub enum Kind {
    /// Integer of `size` bytes.
    Int {
        /// Two's complement.
        signed: bool,
        /// Big-endian.
        big: bool,
    },
    /// IEEE float of 4 or 8 bytes.
    Float {
        /// Big-endian.
        big: bool,
    },
    /// Fixed-length string.
    Str,
    /// Variable-length string (global heap).
    VlenStr,
    /// Variable-length sequence of a base type (global heap).
    VlenSeq(Box<Dtype>),
    /// Compound: named members at byte offsets.
    Compound(Vec<(String, usize, Dtype)>),
    /// Enumeration: a base integer type and the names of its values.
    Enum(Box<Dtype>, Vec<(String, Vec<u8>)>),
    /// Fixed-size array of a base type.
    Array(usize, Box<Dtype>),
    /// A class not decoded (time, bitfield, opaque, reference, ...).
    Other(u8),
}

/// A decoded value.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// A number.
    Num(f64),
    /// Text.
    Text(String),
    /// Several values (an array, a sequence, an attribute of many).
    List(Vec<Value>),
    /// A compound's members.
    Fields(Vec<(String, Value)>),
    /// A value of a class not decoded.
    Unread,
}

impl Value {
    /// The first number in the value.
    pub fn number(&self) -> Option<f64> {
        match self {
            Value::Num(x) => Some(*x),
            Value::Text(t) => t.trim().parse().ok(),
            Value::List(v) => v.first().and_then(Value::number),
            _ => None,
        }
    }

    /// The first text in the value.
    pub fn text(&self) -> Option<&str> {
        match self {
            Value::Text(t) => Some(t),
            Value::List(v) => v.first().and_then(Value::text),
            _ => None,
        }
    }

    /// A compound member (of the first element of a list).
    pub fn field(&self, name: &str) -> Option<&Value> {
        match self {
            Value::Fields(v) => v.iter().find(|(n, _)| n == name).map(|(_, v)| v),
            Value::List(v) => v.first().and_then(|x| x.field(name)),
            _ => None,
        }
    }

    /// The value as one line of text.
    pub fn display(&self) -> String {
        match self {
            Value::Num(x) if *x != 0.0 && !(1e-4..1e9).contains(&x.abs()) => format!("{x:e}"),
            Value::Num(x) => x.to_string(),
            Value::Text(t) => t.clone(),
            Value::List(v) if v.len() == 1 => v[0].display(),
            Value::List(v) => {
                let s: Vec<String> = v.iter().map(Value::display).collect();
                format!("[{}]", s.join(", "))
            }
            Value::Fields(v) => {
                let s: Vec<String> = v
                    .iter()
                    .map(|(n, x)| format!("{n}: {}", x.display()))
                    .collect();
                format!("{{{}}}", s.join(", "))
            }
            Value::Unread => "?".into(),
        }
    }
}

/// Deepest nesting of datatypes (compounds of arrays of ...).
const MAX_NESTING: usize = 16;

/// Parses a datatype at the cursor, leaving it after the datatype.
pub fn dtype(f: &H5, c: &mut Cursor, depth: usize) -> Result<Dtype> {
    let cv = c.u8("datatype class")?;
    let (class, version) = (cv & 0x0f, cv >> 4);
    let b = c.take(3, "datatype bit field")?;
    let bits = u32::from_le_bytes([b[0], b[1], b[2], 0]);
    let size = c.u32("datatype size")? as usize;
    if depth > MAX_NESTING {
        return Err(c.bad("datatype class", 8, "datatypes nested too deep"));
    }
    let kind = match class {
        0 => {
            c.skip(4);
            match size {
                1 | 2 | 4 | 8 => Kind::Int {
                    signed: bits & 8 != 0,
                    big: bits & 1 != 0,
                },
                _ => Kind::Other(0),
            }
        }
        1 => {
            c.skip(12);
            match (size, bits & 0x41) {
                (4 | 8, 0) => Kind::Float { big: false },
                (4 | 8, 1) => Kind::Float { big: true },
                _ => Kind::Other(1),
            }
        }
        3 => Kind::Str,
        6 => compound(f, c, (bits & 0xffff) as usize, (version, size), depth)?,
        8 => enumeration(f, c, (bits & 0xffff) as usize, version, depth)?,
        9 => match (bits & 0x0f, dtype(f, c, depth + 1)?) {
            (1, _) => Kind::VlenStr,
            (_, base) => Kind::VlenSeq(Box::new(base)),
        },
        10 => array(f, c, version, depth)?,
        2 | 4 | 5 | 7 => {
            c.skip(match class {
                2 => 2,
                4 => 4,
                5 => (bits & 0xff) as usize,
                _ => 0,
            });
            Kind::Other(class)
        }
        k => return Err(c.bad("datatype class", 8, format!("class {k}; 0 to 10 expected"))),
    };
    Ok(Dtype { size, kind })
}

/// A NUL-terminated name; padded to a multiple of 8 bytes when `pad`.
fn name(c: &mut Cursor, pad: bool) -> Result<String> {
    let start = c.pos();
    let mut b = Vec::new();
    loop {
        match c.u8("name")? {
            0 => break,
            x => b.push(x),
        }
    }
    if pad {
        let used = c.pos() - start;
        c.skip((8 - used % 8) % 8);
    }
    Ok(latin1_or_utf8(&b))
}

fn compound(f: &H5, c: &mut Cursor, n: usize, vs: (u8, usize), depth: usize) -> Result<Kind> {
    let (version, size) = vs;
    let offset_bytes = match size {
        0..=0xff => 1,
        0x100..=0xffff => 2,
        0x1_0000..=0xff_ffff => 3,
        _ => 4,
    };
    let mut fields = Vec::new();
    for _ in 0..n {
        let name = name(c, version < 3)?;
        let at = match version {
            1 | 2 => c.u32("member offset")? as usize,
            _ => H5::uint(c, offset_bytes, "member offset")? as usize,
        };
        if version == 1 {
            c.skip(28);
        }
        let ty = dtype(f, c, depth + 1)?;
        if at.checked_add(ty.size).is_none_or(|e| e > size) {
            return Err(c.bad(
                "member offset",
                0,
                format!("member '{name}' lies past the compound's {size} bytes"),
            ));
        }
        fields.push((name, at, ty));
    }
    Ok(Kind::Compound(fields))
}

fn enumeration(f: &H5, c: &mut Cursor, n: usize, version: u8, depth: usize) -> Result<Kind> {
    let base = dtype(f, c, depth + 1)?;
    let mut names = Vec::new();
    for _ in 0..n {
        names.push(name(c, version < 3)?);
    }
    let mut out = Vec::new();
    for nm in names {
        out.push((nm, c.take(base.size, "enumeration value")?.to_vec()));
    }
    Ok(Kind::Enum(Box::new(base), out))
}

fn array(f: &H5, c: &mut Cursor, version: u8, depth: usize) -> Result<Kind> {
    let rank = c.u8("array rank")? as usize;
    if version < 3 {
        c.skip(3);
    }
    let mut n = 1usize;
    for _ in 0..rank {
        let d = c.u32("array dimension")? as usize;
        n = n
            .checked_mul(d)
            .ok_or_else(|| c.bad("array dimension", 4, "too many elements"))?;
    }
    if version < 3 {
        c.skip(4 * rank);
    }
    Ok(Kind::Array(n, Box::new(dtype(f, c, depth + 1)?)))
}

/// Element count of the dataspace at `at` (0 for a null one) and its
/// dimensions (none for a scalar).
pub fn dataspace(f: &H5, at: usize) -> Result<(usize, Vec<usize>)> {
    let mut c = f.bytes.le(at, "HDF5 dataspace");
    let version = c.u8("version")?;
    let rank = c.u8("rank")? as usize;
    let _flags = c.u8("flags")?;
    let null = match version {
        1 => {
            c.skip(5);
            false
        }
        2 => c.u8("type")? == 2,
        v => return Err(c.bad("version", 1, format!("{v}; 1 or 2 expected"))),
    };
    if rank > 32 {
        return Err(c.bad("rank", 1, format!("{rank}; at most 32")));
    }
    let mut dims = Vec::new();
    let mut n = 1usize;
    for _ in 0..rank {
        let d = f.length(&mut c, "dimension")?;
        n = n
            .checked_mul(d)
            .ok_or_else(|| c.bad("dimension", f.length_size, "too many elements"))?;
        dims.push(d);
    }
    Ok((if null { 0 } else { n }, dims))
}

/// An object of the global heap: the collection at `coll`, object `index`.
fn global<'a>(f: &H5<'a>, coll: usize, index: u32) -> Result<&'a [u8]> {
    let mut c = f.bytes.le(coll, "HDF5 global heap");
    if c.take(4, "signature")? != b"GCOL" {
        return Err(c.bad("signature", 4, "GCOL expected"));
    }
    c.skip(4);
    let size = f.length(&mut c, "collection size")?;
    let end = coll.saturating_add(size).min(f.bytes.len());
    while c.pos() + 8 + f.length_size <= end {
        let i = c.u16("object index")?;
        c.skip(6);
        let n = f.length(&mut c, "object size")?;
        if i == 0 {
            break;
        }
        let obj = c.take(n, "object data")?;
        if u32::from(i) == index {
            return Ok(obj);
        }
        c.skip((8 - n % 8) % 8);
    }
    Err(f.bytes.error(
        "HDF5 global heap",
        coll,
        format!("no object {index} in the collection"),
    ))
}

/// Decodes one element of `ty` from `raw` (whose bytes begin at file
/// offset `at`, for errors).
pub fn value(f: &H5, ty: &Dtype, raw: &[u8], at: usize) -> Result<Value> {
    nested(f, ty, raw, at, 0)
}

/// As [`value`], `depth` sequences deep: a sequence of sequences (of
/// sequences ...) could make a small file decode for ever, and is not
/// decoded past two levels.
fn nested(f: &H5, ty: &Dtype, raw: &[u8], at: usize, depth: usize) -> Result<Value> {
    let raw = raw.get(..ty.size).ok_or_else(|| {
        f.bytes.error(
            "HDF5 value",
            at,
            format!("{} bytes; {} expected", raw.len(), ty.size),
        )
    })?;
    Ok(match &ty.kind {
        Kind::Int { signed, big } => Value::Num(int(raw, *signed, *big) as f64),
        Kind::Float { big } => Value::Num(float(raw, *big)),
        Kind::Str => Value::Text(latin1_or_utf8(raw)),
        Kind::VlenStr => Value::Text(latin1_or_utf8(vlen(f, raw, at)?.1)),
        Kind::VlenSeq(base) if depth >= 2 || base.size == 0 => Value::Unread,
        Kind::Array(n, base)
            if base.size == 0 || n.checked_mul(base.size).is_none_or(|k| k > raw.len()) =>
        {
            return Err(f.bytes.error(
                "HDF5 array value",
                at,
                format!(
                    "{n} elements of {} bytes do not fit its {} bytes",
                    base.size,
                    raw.len()
                ),
            ));
        }
        Kind::VlenSeq(base) => {
            let (n, obj) = vlen(f, raw, at)?;
            let need = n.checked_mul(base.size).filter(|&k| k <= obj.len());
            let Some(_) = need else {
                return Err(f.bytes.error(
                    "HDF5 sequence",
                    at,
                    format!("{n} elements do not fit its heap object"),
                ));
            };
            let items = (0..n).map(|i| nested(f, base, &obj[i * base.size..], at, depth + 1));
            Value::List(items.collect::<Result<_>>()?)
        }
        Kind::Compound(fields) => Value::Fields(
            fields
                .iter()
                .map(|(n, o, t)| Ok((n.clone(), nested(f, t, &raw[*o..], at + o, depth)?)))
                .collect::<Result<_>>()?,
        ),
        Kind::Enum(base, names) => match names
            .iter()
            .find(|(_, v)| v.as_slice() == &raw[..base.size.min(raw.len())])
        {
            Some((n, _)) => Value::Text(n.clone()),
            None => nested(f, base, raw, at, depth)?,
        },
        Kind::Array(n, base) => Value::List(
            (0..*n)
                .map(|i| nested(f, base, &raw[i * base.size..], at + i * base.size, depth))
                .collect::<Result<_>>()?,
        ),
        Kind::Other(_) => Value::Unread,
    })
}

/// A variable-length element (length, heap collection address, object
/// index): its length and its heap object.
fn vlen<'a>(f: &H5<'a>, raw: &[u8], at: usize) -> Result<(usize, &'a [u8])> {
    let o = f.offset_size;
    let bad = |m: String| f.bytes.error("HDF5 variable-length element", at, m);
    if raw.len() < 8 + o {
        return Err(bad(format!("{} bytes; {} expected", raw.len(), 8 + o)));
    }
    let n = int(&raw[..4], false, false) as usize;
    let coll = int(&raw[4..4 + o], false, false) as u64;
    let index = int(&raw[4 + o..8 + o], false, false) as u32;
    if n == 0 {
        return Ok((0, &[]));
    }
    let addr = usize::try_from(coll)
        .ok()
        .and_then(|a| a.checked_add(f.base))
        .filter(|&a| a < f.bytes.len())
        .ok_or_else(|| bad(format!("heap collection at {coll}, past the file's end")))?;
    Ok((n, global(f, addr, index)?))
}

fn int(raw: &[u8], signed: bool, big: bool) -> i128 {
    let n = raw.len();
    let mut v: u64 = 0;
    for i in 0..n {
        let byte = if big { raw[i] } else { raw[n - 1 - i] };
        v = (v << 8) | byte as u64;
    }
    if signed && n < 8 && v >> (8 * n - 1) & 1 == 1 {
        return v as i128 - (1i128 << (8 * n));
    }
    if signed {
        v as i64 as i128
    } else {
        v as i128
    }
}

fn float(raw: &[u8], big: bool) -> f64 {
    let bits = int(raw, false, big) as u64;
    match raw.len() {
        4 => f32::from_bits(bits as u32) as f64,
        _ => f64::from_bits(bits),
    }
}
