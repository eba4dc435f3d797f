//! NumPy `.npy` (format versions 1, 2 and 3): the magic `\x93NUMPY`, a
//! header (a Python dict literal: `descr`, `fortran_order`, `shape`), then
//! the array. One dimension is a profile, two a map with rows along y
//! (`a[r, c]` at x = c·Δx, y = r·Δy: the image convention; a Fortran-order
//! array is read column by column). The file states no spacing and no
//! unit: the roughness stage asks for `--spacing` and `--z-unit`. NaN
//! (and ±inf) values are points not measured.

use crate::error::Result;
use crate::ingest::binary::decode::{decode_grid, Conversion, Order, Sample};
use crate::ingest::binary::{meta, Bytes};
use crate::ingest::grid::Grid;
use crate::ingest::{Decoded, IngestOptions, Reader};

/// The registry entry.
pub struct Npy;

const MAGIC: &[u8] = b"\x93NUMPY";
const STRUCTURE: &str = "NPY header";

impl Reader for Npy {
    fn name(&self) -> &'static str {
        "npy"
    }
    fn description(&self) -> &'static str {
        "NumPy .npy array (1-D profile or 2-D map; spacing and unit given by the user)"
    }
    fn sniff_bytes(&self, data: &[u8]) -> bool {
        data.starts_with(MAGIC)
    }
    fn read_bytes(&self, bytes: &Bytes, _options: &IngestOptions) -> Option<Result<Decoded>> {
        Some(read(bytes))
    }
}

/// The value of `key` in the header dict, as written (up to the next
/// top-level comma or the closing brace).
fn field<'a>(h: &'a str, key: &str) -> Option<&'a str> {
    let at = h
        .find(&format!("'{key}'"))
        .or_else(|| h.find(&format!("\"{key}\"")))?;
    let rest = h[at + key.len() + 2..]
        .trim_start()
        .strip_prefix(':')?
        .trim_start();
    let mut depth = 0;
    for (i, ch) in rest.char_indices() {
        match ch {
            '(' | '[' => depth += 1,
            ')' | ']' => depth -= 1,
            ',' | '}' if depth == 0 => return Some(rest[..i].trim()),
            _ => {}
        }
    }
    None
}

/// The byte order (big-endian or not) and sample type of a `descr` such
/// as `<f8`, or what is wrong with it.
fn sample_type(descr: &str) -> std::result::Result<(bool, Sample), String> {
    // The byte order is the first character (a mutated header may start
    // with a multi-byte one).
    let (order, kind) = descr.split_at(descr.chars().next().map_or(0, char::len_utf8));
    let big = match order {
        ">" => true,
        "<" | "|" | "=" => false,
        _ => return Err(format!("descr '{descr}': a byte order (<, >, |) expected")),
    };
    let sample = match kind {
        "f8" => Sample::F64,
        "f4" => Sample::F32,
        "i1" => Sample::I8,
        "u1" => Sample::U8,
        "i2" => Sample::I16,
        "u2" => Sample::U16,
        "i4" => Sample::I32,
        "u4" => Sample::U32,
        "i8" => Sample::I64,
        "u8" => Sample::U64,
        k => {
            return Err(format!(
                "descr '{descr}': type '{k}'; integers and f4/f8 are read"
            ))
        }
    };
    Ok((big, sample))
}

fn read(bytes: &Bytes) -> Result<Decoded> {
    let mut c = bytes.le(0, STRUCTURE);
    if c.take(6, "magic")? != MAGIC {
        return Err(c.bad("magic", 6, "not a NumPy file"));
    }
    let major = c.u8("major version")?;
    c.u8("minor version")?;
    let len = match major {
        1 => c.u16("header length")? as usize,
        2 | 3 => c.u32("header length")? as usize,
        v => {
            return Err(c.bad(
                "major version",
                1,
                format!("{v}; versions 1, 2 and 3 are read"),
            ))
        }
    };
    let start = c.pos();
    let h = String::from_utf8_lossy(c.take(len, "header")?).into_owned();
    let bad = |m: String| bytes.error(STRUCTURE, start, m);
    let descr = field(&h, "descr")
        .map(|d| d.trim_matches(|c| c == '\'' || c == '"'))
        .ok_or_else(|| bad(format!("no 'descr' in {h:?}")))?;
    let fortran = match field(&h, "fortran_order") {
        Some("True") => true,
        Some("False") => false,
        f => return Err(bad(format!("fortran_order {f:?}; True or False expected"))),
    };
    let shape: Vec<usize> = field(&h, "shape")
        .map(|s| s.trim_matches(['(', ')']))
        .ok_or_else(|| bad("no 'shape'".into()))?
        .split(',')
        .filter(|t| !t.trim().is_empty())
        .map(|t| {
            t.trim()
                .parse::<usize>()
                .map_err(|_| bad(format!("shape entry '{t}'")))
        })
        .collect::<Result<_>>()?;
    let (big, sample) = sample_type(descr).map_err(bad)?;
    let (nx, ny) = match shape[..] {
        [n] => (n, 1),
        [r, c] => (c, r),
        _ => {
            return Err(bad(format!(
                "shape {shape:?}; one or two dimensions are read"
            )))
        }
    };
    if nx == 0 || ny == 0 {
        return Err(bad(format!("shape {shape:?} holds no value")));
    }
    let mut conv = Conversion::raw(sample);
    if big {
        conv = conv.big_endian();
    }
    let order = Order {
        column_major: fortran && ny > 1,
        flip_y: false,
    };
    let data = decode_grid(bytes, c.pos(), (nx, ny), &conv, "NPY array", order)?;
    let mut g = Grid::heights("array", nx, ny, f64::NAN, f64::NAN);
    g.unit = String::new();
    g.data = Some(data);
    Ok(Decoded {
        preamble: vec![
            meta("descr", descr),
            meta("shape", format!("{shape:?}")),
            meta("fortran_order", fortran),
        ],
        sections: Vec::new(),
        grids: vec![g],
    })
}
