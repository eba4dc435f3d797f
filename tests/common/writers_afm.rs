//! Small writers of AFM and SPM formats (Gwyddion GWY, Nanoscope, Igor
//! IBW, Nanosurf NID, Agilent MI, WSxM), after their public descriptions:
//! the fixtures of the round-trip and variant tests.

use crate::common::writers::Surface;

/// A GWY component value.
pub enum G {
    I(i32),
    D(f64),
    S(String),
    B(bool),
    O(&'static str, Vec<(String, G)>),
    Ds(Vec<f64>),
}

fn cstr(out: &mut Vec<u8>, s: &str) {
    out.extend(s.as_bytes());
    out.push(0);
}

/// A serialised GWY object.
pub fn gwy_object(name: &str, items: &[(String, G)]) -> Vec<u8> {
    let mut body = Vec::new();
    for (k, v) in items {
        cstr(&mut body, k);
        match v {
            G::I(i) => {
                body.push(b'i');
                body.extend(i.to_le_bytes());
            }
            G::D(d) => {
                body.push(b'd');
                body.extend(d.to_le_bytes());
            }
            G::S(s) => {
                body.push(b's');
                cstr(&mut body, s);
            }
            G::B(b) => {
                body.push(b'b');
                body.push(*b as u8);
            }
            G::O(n, it) => {
                body.push(b'o');
                body.extend(gwy_object(n, it));
            }
            G::Ds(v) => {
                body.push(b'D');
                body.extend((v.len() as u32).to_le_bytes());
                v.iter().for_each(|x| body.extend(x.to_le_bytes()));
            }
        }
    }
    let mut out = Vec::new();
    cstr(&mut out, name);
    out.extend((body.len() as u32).to_le_bytes());
    out.extend(body);
    out
}

/// One GWY image channel.
pub struct GwyChannel<'a> {
    pub title: &'a str,
    pub surface: &'a Surface,
    /// Lateral unit and metres per unit.
    pub xy: (&'a str, f64),
    /// Value unit and (for a length) metres per unit.
    pub z: (&'a str, f64),
    /// Points not measured (a mask of 1).
    pub mask: Option<Vec<bool>>,
}

fn gwy_field(s: &Surface, xy: (&str, f64), z: (&str, f64), data: Vec<f64>) -> G {
    let unit = |u: &str| G::O("GwySIUnit", vec![("unitstr".into(), G::S(u.into()))]);
    G::O(
        "GwyDataField",
        vec![
            ("xres".into(), G::I(s.nx as i32)),
            ("yres".into(), G::I(s.ny as i32)),
            ("xreal".into(), G::D(s.nx as f64 * s.dx / xy.1)),
            ("yreal".into(), G::D(s.ny as f64 * s.dy / xy.1)),
            ("xoff".into(), G::D(0.0)),
            ("yoff".into(), G::D(0.0)),
            ("si_unit_xy".into(), unit(xy.0)),
            ("si_unit_z".into(), unit(z.0)),
            ("data".into(), G::Ds(data)),
        ],
    )
}

/// A GWY file of `channels` (`/0/data`, `/1/data`, ...) and a metadata
/// container for the first.
pub fn gwy(channels: &[GwyChannel]) -> Vec<u8> {
    let mut items = Vec::new();
    for (i, c) in channels.iter().enumerate() {
        let s = c.surface;
        let z: Vec<f64> = s.z.iter().map(|v| v / c.z.1).collect();
        items.push((format!("/{i}/data/title"), G::S(c.title.into())));
        items.push((format!("/{i}/data"), gwy_field(s, c.xy, c.z, z)));
        items.push((format!("/{i}/data/visible"), G::B(true)));
        if let Some(m) = &c.mask {
            let m = m.iter().map(|&b| b as u8 as f64).collect();
            items.push((format!("/{i}/mask"), gwy_field(s, c.xy, ("", 1.0), m)));
        }
    }
    let meta = vec![("Date".to_string(), G::S("2024-05-06 07:08:09".into()))];
    items.push(("/0/meta".into(), G::O("GwyContainer", meta)));
    let mut out = b"GWYP".to_vec();
    out.extend(gwy_object("GwyContainer", &items));
    out
}
