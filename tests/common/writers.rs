//! Small writers of binary surface formats, after their specifications:
//! the fixtures of the round-trip and variant tests (a file written here
//! and read by tribo gives back what was written).

use tribo::ingest::binary::zip;

/// A test surface: z(c, r) in metres on an nx × ny grid.
pub struct Surface {
    pub nx: usize,
    pub ny: usize,
    pub dx: f64,
    pub dy: f64,
    pub z: Vec<f64>,
}

impl Surface {
    /// z = a sin(2π c / px) + b cos(2π r / py) + tilt·c, periods in
    /// points (whole periods give closed-form moments).
    pub fn waves(nx: usize, ny: usize, dx: f64, dy: f64, a: f64, b: f64) -> Surface {
        let tau = std::f64::consts::TAU;
        let z = (0..ny)
            .flat_map(|r| {
                (0..nx).map(move |c| {
                    a * (tau * c as f64 / 16.0).sin() + b * (tau * r as f64 / 8.0).cos()
                })
            })
            .collect();
        Surface { nx, ny, dx, dy, z }
    }
}

/// RMS about the mean over finite values (Sq with a mean detrend), and
/// their count.
pub fn sq_finite(v: &[f64]) -> (f64, usize) {
    let f: Vec<f64> = v.iter().copied().filter(|x| x.is_finite()).collect();
    let m = f.iter().sum::<f64>() / f.len() as f64;
    let s = f.iter().map(|x| (x - m).powi(2)).sum::<f64>() / f.len() as f64;
    (s.sqrt(), f.len())
}

/// X3P data types.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum X3pType {
    I,
    L,
    F,
    D,
}

/// Options of an X3P file.
pub struct X3p<'a> {
    pub kind: X3pType,
    /// Folder of main.xml and the data inside the zip ("" for none).
    pub folder: &'a str,
    pub deflate: bool,
    /// z increment for integer types (m per count).
    pub z_increment: f64,
    pub origin: (f64, f64),
    /// Valid-points mask (true = measured), written as valid.bin.
    pub mask: Option<Vec<bool>>,
    /// Points listed in the XML instead of a binary file.
    pub inline: bool,
}

impl Default for X3p<'_> {
    fn default() -> Self {
        X3p {
            kind: X3pType::D,
            folder: "",
            deflate: true,
            z_increment: 1e-9,
            origin: (0.0, 0.0),
            mask: None,
            inline: false,
        }
    }
}

/// An X3P archive of `s` (ISO 5436-2 layout: Record1..4).
pub fn x3p(s: &Surface, o: &X3p) -> Vec<u8> {
    x3p_edited(s, o, &|x| x)
}

/// As [`x3p`], with `main.xml` passed through `edit` (bad-file tests).
pub fn x3p_edited(s: &Surface, o: &X3p, edit: &dyn Fn(String) -> String) -> Vec<u8> {
    let (dt, inc) = match o.kind {
        X3pType::I => ("I", format!("<Increment>{:e}</Increment>", o.z_increment)),
        X3pType::L => ("L", format!("<Increment>{:e}</Increment>", o.z_increment)),
        X3pType::F => ("F", String::new()),
        X3pType::D => ("D", "<Increment>1</Increment>".into()),
    };
    let quant = |z: f64| (z / o.z_increment).round();
    let mut bin = Vec::new();
    for &z in &s.z {
        match o.kind {
            X3pType::I => bin.extend((quant(z) as i16).to_le_bytes()),
            X3pType::L => bin.extend((quant(z) as i32).to_le_bytes()),
            X3pType::F => bin.extend((z as f32).to_le_bytes()),
            X3pType::D => bin.extend(z.to_le_bytes()),
        }
    }
    let feature = if s.ny == 1 { "PRF" } else { "SUR" };
    let record3 = match o.inline {
        true => {
            let data: String =
                s.z.iter()
                    .map(|z| format!("<Datum>{z:e}</Datum>"))
                    .collect();
            format!("<DataList>{data}</DataList>")
        }
        false => {
            let valid = match o.mask {
                Some(_) => "<ValidPointsLink>bindata/valid.bin</ValidPointsLink>",
                None => "",
            };
            format!(
                "<DataLink><PointDataLink>bindata/data.bin</PointDataLink>\
                 <MD5ChecksumPointData>00</MD5ChecksumPointData>{valid}</DataLink>"
            )
        }
    };
    let xml = format!(
        r#"<?xml version="1.0" encoding="UTF-8"?>
<p:ISO5436_2 xmlns:p="http://www.opengps.eu/2008/ISO5436_2">
<Record1><Revision>ISO5436 - 2000</Revision><FeatureType>{feature}</FeatureType>
<Axes>
<CX><AxisType>I</AxisType><DataType>D</DataType><Increment>{:e}</Increment><Offset>{:e}</Offset></CX>
<CY><AxisType>I</AxisType><DataType>D</DataType><Increment>{:e}</Increment><Offset>{:e}</Offset></CY>
<CZ><AxisType>A</AxisType><DataType>{dt}</DataType>{inc}<Offset>0</Offset></CZ>
</Axes></Record1>
<Record2><Date>2024-03-01T10:20:30+01:00</Date><Creator>tribo tests</Creator>
<Instrument><Manufacturer>Acme &amp; Co</Manufacturer><Model>Profilometer 3000</Model><Serial>42</Serial><Version>1.0</Version></Instrument>
<CalibrationDate>2024-01-01T00:00:00</CalibrationDate>
<ProbingSystem><Type>NonContacting</Type><Identification>50x objective</Identification></ProbingSystem>
<Comment>written by the test writer</Comment></Record2>
<Record3><MatrixDimension><SizeX>{}</SizeX><SizeY>{}</SizeY><SizeZ>1</SizeZ></MatrixDimension>
{record3}</Record3>
<Record4><ChecksumFile>md5checksum.hex</ChecksumFile></Record4>
</p:ISO5436_2>"#,
        s.dx, o.origin.0, s.dy, o.origin.1, s.nx, s.ny
    );
    let xml = edit(xml);
    let mut mask_bytes = vec![0u8; s.z.len().div_ceil(8)];
    if let Some(m) = &o.mask {
        for (i, _) in m.iter().enumerate().filter(|(_, v)| **v) {
            mask_bytes[i / 8] |= 1 << (i % 8);
        }
    }
    let p = |name: &str| format!("{}{name}", o.folder);
    let (main, data, valid, md5) = (
        p("main.xml"),
        p("bindata/data.bin"),
        p("bindata/valid.bin"),
        p("md5checksum.hex"),
    );
    let mut files: Vec<(&str, &[u8])> = vec![(&main, xml.as_bytes()), (&md5, b"00 *main.xml\n")];
    if !o.inline {
        files.push((&data, &bin));
    }
    if o.mask.is_some() {
        files.push((&valid, &mask_bytes));
    }
    zip::write(&files, o.deflate)
}

/// Options of a SUR file.
pub struct Sur {
    pub bits: u16,
    pub compressed: bool,
    /// zlib streams of a compressed file.
    pub streams: usize,
    /// Points not measured (written as zmin − 2).
    pub invalid: Vec<usize>,
    /// Step units of x, y and z.
    pub units: [&'static str; 3],
    /// Metres per count of z.
    pub dz_m: f64,
    pub z_offset_m: f64,
}

impl Default for Sur {
    fn default() -> Self {
        Sur {
            bits: 32,
            compressed: false,
            streams: 1,
            invalid: Vec::new(),
            units: ["um", "um", "um"],
            dz_m: 1e-10,
            z_offset_m: 0.0,
        }
    }
}

fn unit_m(u: &str) -> f64 {
    match u {
        "m" => 1.0,
        "mm" => 1e-3,
        "um" | "µm" => 1e-6,
        "nm" => 1e-9,
        _ => panic!("unit {u}"),
    }
}

/// One SUR object (header and points) of `s`; `objects` is written in the
/// header's object count, `name` as the z axis name.
pub fn sur_object(s: &Surface, o: &Sur, objects: u16, name: &str) -> Vec<u8> {
    let put = |h: &mut Vec<u8>, at: usize, b: &[u8]| h[at..at + b.len()].copy_from_slice(b);
    let text = |t: &str, n: usize| {
        let mut b = t.as_bytes().to_vec();
        b.resize(n, b' ');
        b
    };
    let (sx, sy, sz) = (unit_m(o.units[0]), unit_m(o.units[1]), unit_m(o.units[2]));
    let dz = o.dz_m / sz;
    let raw: Vec<i64> =
        s.z.iter()
            .map(|z| ((z - o.z_offset_m) / o.dz_m).round() as i64)
            .collect();
    let zmin = raw.iter().copied().min().unwrap_or(0);
    let mut h = vec![0u8; 512];
    put(
        &mut h,
        0,
        if o.compressed {
            b"DSCOMPRESSED"
        } else {
            b"DIGITAL SURF"
        },
    );
    put(&mut h, 14, &objects.to_le_bytes());
    put(&mut h, 16, &1u16.to_le_bytes());
    put(
        &mut h,
        18,
        &(if s.ny == 1 { 1u16 } else { 2 }).to_le_bytes(),
    );
    put(&mut h, 20, &text("test object", 30));
    put(&mut h, 86, &(!o.invalid.is_empty() as u16).to_le_bytes());
    put(&mut h, 98, &o.bits.to_le_bytes());
    put(&mut h, 100, &(zmin as i32).to_le_bytes());
    put(
        &mut h,
        104,
        &(raw.iter().copied().max().unwrap_or(0) as i32).to_le_bytes(),
    );
    put(&mut h, 108, &(s.nx as i32).to_le_bytes());
    put(&mut h, 112, &(s.ny as i32).to_le_bytes());
    put(&mut h, 116, &((s.nx * s.ny) as i32).to_le_bytes());
    put(&mut h, 120, &((s.dx / sx) as f32).to_le_bytes());
    put(&mut h, 124, &((s.dy / sy) as f32).to_le_bytes());
    put(&mut h, 128, &(dz as f32).to_le_bytes());
    for (i, n) in ["X", "Y", name].iter().enumerate() {
        put(&mut h, 132 + 16 * i, &text(n, 16));
    }
    for (i, u) in o.units.iter().chain(o.units.iter()).enumerate() {
        put(&mut h, 180 + 16 * i, &text(u, 16));
    }
    for (i, v) in [30u16, 15, 9, 24, 12, 2023].iter().enumerate() {
        put(&mut h, 306 + 2 * i, &v.to_le_bytes());
    }
    put(&mut h, 474, &((o.z_offset_m / sz) as f32).to_le_bytes());
    let mut points = Vec::new();
    for (i, &r) in raw.iter().enumerate() {
        let r = if o.invalid.contains(&i) { zmin - 2 } else { r };
        match o.bits {
            16 => points.extend((r as i16).to_le_bytes()),
            _ => points.extend((r as i32).to_le_bytes()),
        }
    }
    let body = match o.compressed {
        false => points,
        true => {
            use std::io::Write;
            let per = points.len().div_ceil(o.streams).div_ceil(4) * 4;
            let parts: Vec<&[u8]> = points.chunks(per.max(4)).collect();
            let mut dir = (parts.len() as u32).to_le_bytes().to_vec();
            let mut zipped = Vec::new();
            for p in &parts {
                let mut e =
                    flate2::write::ZlibEncoder::new(Vec::new(), flate2::Compression::fast());
                e.write_all(p).unwrap();
                let z = e.finish().unwrap();
                dir.extend((p.len() as u32).to_le_bytes());
                dir.extend((z.len() as u32).to_le_bytes());
                zipped.extend(z);
            }
            dir.extend(zipped);
            put(&mut h, 324, &(dir.len() as u32).to_le_bytes());
            dir
        }
    };
    h.extend(body);
    h
}

/// A SUR file of one object.
pub fn sur(s: &Surface, o: &Sur) -> Vec<u8> {
    sur_object(s, o, 1, "Z")
}
