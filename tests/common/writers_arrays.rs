//! Small writers of array formats (netCDF 3, NumPy .npy, ISO 25178-71
//! SDF), after their specifications: the fixtures of the round-trip and
//! variant tests.

use crate::common::writers::Surface;

/// A netCDF variable type and how heights are stored in it.
#[derive(Clone, Copy, PartialEq)]
pub enum NcType {
    Double,
    Float,
    /// NC_SHORT with `scale_factor` and `add_offset`.
    Short,
}

/// What a netCDF test file holds.
pub struct Nc<'a> {
    /// 1 (classic), 2 (64-bit offset) or 5 (CDF-5).
    pub version: u8,
    /// `heights(x, y)` (SurfaceTopography) rather than `heights(y, x)`.
    pub xy: bool,
    pub kind: NcType,
    /// Unit of heights and axes (`nm`, `µm`, `Å`).
    pub unit: &'a str,
    /// Axes by a `length` attribute (else by coordinate values).
    pub length_attr: bool,
    /// Points (row-major index) written as `_FillValue`.
    pub fill: Vec<usize>,
    /// Points (row-major index) marked in a `mask` variable.
    pub mask: Vec<usize>,
    /// A second channel `phase` (unit `deg`) before the heights.
    pub phase: bool,
}

impl Default for Nc<'_> {
    fn default() -> Self {
        Nc {
            version: 1,
            xy: true,
            kind: NcType::Double,
            unit: "nm",
            length_attr: true,
            fill: vec![],
            mask: vec![],
            phase: false,
        }
    }
}

const FILL: f64 = -9999.0;
const SHORT_SCALE: f64 = 0.01;
const SHORT_OFFSET: f64 = 5.0;

/// Metres per unit of the writers' units.
pub fn metres(unit: &str) -> f64 {
    match unit {
        "nm" => 1e-9,
        "µm" | "um" => 1e-6,
        "Å" => 1e-10,
        "mm" => 1e-3,
        _ => 1.0,
    }
}

/// Attribute values.
enum A<'a> {
    T(&'a str),
    D(f64),
    S(i16),
}

struct NcVar<'a> {
    name: &'a str,
    dims: Vec<u32>,
    attrs: Vec<(&'a str, A<'a>)>,
    kind: u32,
    data: Vec<u8>,
}

struct W {
    out: Vec<u8>,
    wide_count: bool,
}

impl W {
    fn count(&mut self, n: usize) {
        match self.wide_count {
            true => self.out.extend((n as u64).to_be_bytes()),
            false => self.out.extend((n as u32).to_be_bytes()),
        }
    }
    fn pad(&mut self) {
        while self.out.len() % 4 != 0 {
            self.out.push(0);
        }
    }
    fn name(&mut self, s: &str) {
        self.count(s.len());
        self.out.extend(s.as_bytes());
        self.pad();
    }
    fn attrs(&mut self, attrs: &[(&str, A)]) {
        if attrs.is_empty() {
            self.out.extend(0u32.to_be_bytes());
            self.count(0);
            return;
        }
        self.out.extend(12u32.to_be_bytes());
        self.count(attrs.len());
        for (k, v) in attrs {
            self.name(k);
            match v {
                A::T(t) => {
                    self.out.extend(2u32.to_be_bytes());
                    self.count(t.len());
                    self.out.extend(t.as_bytes());
                }
                A::D(d) => {
                    self.out.extend(6u32.to_be_bytes());
                    self.count(1);
                    self.out.extend(d.to_be_bytes());
                }
                A::S(s) => {
                    self.out.extend(3u32.to_be_bytes());
                    self.count(1);
                    self.out.extend(s.to_be_bytes());
                }
            }
            self.pad();
        }
    }
}

fn be_f64(v: impl Iterator<Item = f64>) -> Vec<u8> {
    v.flat_map(f64::to_be_bytes).collect()
}

/// The heights of `s` as a netCDF 3 file, laid out as `o` says.
pub fn netcdf(s: &Surface, o: &Nc) -> Vec<u8> {
    let u = metres(o.unit);
    let (nx, ny) = (s.nx, s.ny);
    // Row-major (y, x) index i → the file's order.
    let order: Vec<usize> = match o.xy {
        true => (0..nx)
            .flat_map(|c| (0..ny).map(move |r| r * nx + c))
            .collect(),
        false => (0..nx * ny).collect(),
    };
    let dims = if o.xy { vec![0, 1] } else { vec![1, 0] };
    let z = |i: usize| match o.fill.contains(&i) {
        true => None,
        false => Some(s.z[i] / u),
    };
    let (kind, data, mut attrs) = match o.kind {
        NcType::Double => (
            6,
            be_f64(order.iter().map(|&i| z(i).unwrap_or(FILL))),
            vec![("_FillValue", A::D(FILL))],
        ),
        // No _FillValue: the type's default fill (NC_FILL_FLOAT) marks them.
        NcType::Float => (
            5,
            order
                .iter()
                .flat_map(|&i| {
                    z(i).map_or(f32::from_bits(0x7cf0_0000), |v| v as f32)
                        .to_be_bytes()
                })
                .collect(),
            vec![],
        ),
        NcType::Short => (
            3,
            order
                .iter()
                .flat_map(|&i| {
                    let raw = z(i).map_or(-32767, |v| {
                        ((v - SHORT_OFFSET) / SHORT_SCALE).round() as i16
                    });
                    raw.to_be_bytes()
                })
                .collect(),
            vec![
                ("scale_factor", A::D(SHORT_SCALE)),
                ("add_offset", A::D(SHORT_OFFSET)),
                ("_FillValue", A::S(-32767)),
            ],
        ),
    };
    attrs.push(("unit", A::T(o.unit)));
    finish(s, o, kind, data, attrs, dims, &order)
}

fn finish<'a>(
    s: &Surface,
    o: &'a Nc,
    kind: u32,
    data: Vec<u8>,
    attrs: Vec<(&'a str, A<'a>)>,
    dims: Vec<u32>,
    order: &[usize],
) -> Vec<u8> {
    let u = metres(o.unit);
    let axis = |name: &'a str, n: usize, d: f64| NcVar {
        name,
        dims: vec![if name == "x" { 0 } else { 1 }],
        attrs: match o.length_attr {
            true => vec![("length", A::D(n as f64 * d / u)), ("unit", A::T(o.unit))],
            false => vec![("unit", A::T(o.unit))],
        },
        kind: 6,
        data: be_f64((0..n).map(|k| (k as f64 + 0.5) * d / u)),
    };
    let mut vars = vec![axis("x", s.nx, s.dx), axis("y", s.ny, s.dy)];
    if o.phase {
        vars.push(NcVar {
            name: "phase",
            dims: dims.clone(),
            attrs: vec![("units", A::T("deg"))],
            kind: 6,
            data: be_f64(order.iter().map(|&i| i as f64)),
        });
    }
    vars.push(NcVar {
        name: "heights",
        dims: dims.clone(),
        attrs,
        kind,
        data,
    });
    if !o.mask.is_empty() {
        let m = order.iter().map(|i| o.mask.contains(i) as u8).collect();
        vars.push(NcVar {
            name: "mask",
            dims,
            attrs: vec![],
            kind: 7,
            data: m,
        });
    }
    let header = |begins: &[usize]| {
        let mut w = W {
            out: b"CDF".to_vec(),
            wide_count: o.version == 5,
        };
        w.out.push(o.version);
        w.count(0);
        w.out.extend(10u32.to_be_bytes());
        w.count(2);
        for (n, len) in [("x", s.nx), ("y", s.ny)] {
            w.name(n);
            w.count(len);
        }
        w.attrs(&[("title", A::T("test surface"))]);
        w.out.extend(11u32.to_be_bytes());
        w.count(vars.len());
        for (v, &b) in vars.iter().zip(begins) {
            w.name(v.name);
            w.count(v.dims.len());
            for &d in &v.dims {
                w.count(d as usize);
            }
            w.attrs(&v.attrs);
            w.out.extend(v.kind.to_be_bytes());
            w.count(v.data.len().div_ceil(4) * 4);
            match o.version {
                1 => w.out.extend((b as u32).to_be_bytes()),
                _ => w.out.extend((b as u64).to_be_bytes()),
            }
        }
        w.out
    };
    let mut at = header(&vec![0; vars.len()]).len();
    let mut begins = Vec::new();
    for v in &vars {
        begins.push(at);
        at += v.data.len().div_ceil(4) * 4;
    }
    let mut out = header(&begins);
    for v in &vars {
        out.extend(&v.data);
        while out.len() % 4 != 0 {
            out.push(0);
        }
    }
    out
}

/// A NumPy array file: `descr` (`<f8`, `>f4`, `<i4`, ...), `shape`, the
/// values in C or Fortran order, header version 1, 2 or 3.
pub fn npy(values: &[f64], shape: &[usize], descr: &str, fortran: bool, version: u8) -> Vec<u8> {
    let shape_s = match shape {
        [n] => format!("({n},)"),
        s => format!(
            "({})",
            s.iter()
                .map(|n| n.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ),
    };
    let fo = if fortran { "True" } else { "False" };
    let mut h = format!("{{'descr': '{descr}', 'fortran_order': {fo}, 'shape': {shape_s}, }}");
    let pre = if version == 1 { 10 } else { 12 };
    while (pre + h.len() + 1) % 64 != 0 {
        h.push(' ');
    }
    h.push('\n');
    let mut out = b"\x93NUMPY".to_vec();
    out.extend([version, 0]);
    match version {
        1 => out.extend((h.len() as u16).to_le_bytes()),
        _ => out.extend((h.len() as u32).to_le_bytes()),
    }
    out.extend(h.as_bytes());
    let index: Vec<usize> = match (fortran, shape) {
        (true, [r, c]) => (0..*c)
            .flat_map(|j| (0..*r).map(move |i| i * c + j))
            .collect(),
        _ => (0..values.len()).collect(),
    };
    let big = descr.starts_with('>');
    for i in index {
        let v = values[i];
        let b: Vec<u8> = match (&descr[1..], big) {
            ("f8", false) => v.to_le_bytes().to_vec(),
            ("f8", true) => v.to_be_bytes().to_vec(),
            ("f4", false) => (v as f32).to_le_bytes().to_vec(),
            ("f4", true) => (v as f32).to_be_bytes().to_vec(),
            ("i4", false) => (v as i32).to_le_bytes().to_vec(),
            ("i2", true) => (v as i16).to_be_bytes().to_vec(),
            ("u1", _) => vec![v as u8],
            (d, _) => panic!("writer: descr {d}"),
        };
        out.extend(b);
    }
    out
}

/// An ASCII SDF (`aISO-1.0`) of `s` in units of `zscale` m, `BAD` at the
/// points `bad`, lines ended by `eol`.
pub fn sdf_ascii(s: &Surface, zscale: f64, bad: &[usize], eol: &str) -> Vec<u8> {
    let mut t = String::new();
    let head = [
        "aISO-1.0".to_string(),
        "ManufacID = TEST".into(),
        "CreateDate = 010120240000".into(),
        "ModDate = 010120240000".into(),
        format!("NumPoints = {}", s.nx),
        format!("NumProfiles = {}", s.ny),
        format!("Xscale = {:e}", s.dx),
        format!("Yscale = {:e}", s.dy),
        format!("Zscale = {zscale:e}"),
        "Zresolution = -1".into(),
        "Compression = 0".into(),
        "DataType = 7".into(),
        "CheckType = 0".into(),
        "*".into(),
    ];
    for l in head {
        t += &l;
        t += eol;
    }
    for r in 0..s.ny {
        let row: Vec<String> = (0..s.nx)
            .map(|c| r * s.nx + c)
            .map(|i| match bad.contains(&i) {
                true => "BAD".into(),
                false => format!("{:.9e}", s.z[i] / zscale),
            })
            .collect();
        t += &row.join(" ");
        t += eol;
    }
    t += &format!("*{eol}{eol}< OperatorName > Test < /OperatorName >{eol}*{eol}");
    t.into_bytes()
}

/// A binary SDF (`bISO-1.0`): DataType 3 (f32), 5 (i16), 6 (i32) or 7
/// (f64); `bad` points as the type's minimum (integers) or NaN.
pub fn sdf_binary(s: &Surface, zscale: f64, data_type: u8, bad: &[usize]) -> Vec<u8> {
    let mut out = b"bISO-1.0".to_vec();
    out.extend(b"TEST      ");
    out.extend(b"010120240000010120240000");
    out.extend((s.nx as u16).to_le_bytes());
    out.extend((s.ny as u16).to_le_bytes());
    for v in [s.dx, s.dy, zscale, -1.0] {
        out.extend(v.to_le_bytes());
    }
    out.extend([0, data_type, 0]);
    for (i, z) in s.z.iter().enumerate() {
        let (v, b) = (z / zscale, bad.contains(&i));
        match data_type {
            3 => out.extend((if b { f32::NAN } else { v as f32 }).to_le_bytes()),
            5 => out.extend((if b { i16::MIN } else { v.round() as i16 }).to_le_bytes()),
            6 => out.extend((if b { i32::MIN } else { v.round() as i32 }).to_le_bytes()),
            _ => out.extend((if b { f64::NAN } else { v }).to_le_bytes()),
        }
    }
    out
}
