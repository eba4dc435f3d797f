//! Small writers of SPM and profiler formats (Igor IBW v5, Nanosurf NID,
//! Agilent MI, BCR/BCRF, WSxM, FRT), after their public descriptions and
//! the readers of SurfaceTopography and Gwyddion: the fixtures of the
//! round-trip and variant tests. Rows are written as those readers orient
//! them (see each reader's doc), so that a surface written and read gives
//! back the same grid.

use crate::common::writers::Surface;

/// The surface's values in file order: row by row, the last row first
/// when `flip`.
fn rows(s: &Surface, flip: bool) -> impl Iterator<Item = f64> + '_ {
    (0..s.ny).flat_map(move |j| {
        let r = if flip { s.ny - 1 - j } else { j };
        s.z[r * s.nx..(r + 1) * s.nx].iter().copied()
    })
}

/// An IBW v5 wave of `layers` (name, values of a surface shaped like `s`)
/// in f32, data unit `unit`, lateral unit `m`.
pub fn ibw(s: &Surface, layers: &[(&str, &Surface)], unit: &str, big: bool) -> Vec<u8> {
    let put16 = |o: &mut Vec<u8>, v: i16| {
        o.extend(if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        })
    };
    let put32 = |o: &mut Vec<u8>, v: i32| {
        o.extend(if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        })
    };
    let putf = |o: &mut Vec<u8>, v: f64| {
        o.extend(if big {
            v.to_be_bytes()
        } else {
            v.to_le_bytes()
        })
    };
    let n = s.nx * s.ny * layers.len();
    let note = b"MicroscopeModel:MFP3D\rDate:2021-03-04\rTime:1:02:03 PM\rScanSize: 1e-05".to_vec();
    let mut labels = vec![0u8; 32 * (layers.len() + 1)];
    for (k, (name, _)) in layers.iter().enumerate() {
        labels[32 * (k + 1)..32 * (k + 1) + name.len()].copy_from_slice(name.as_bytes());
    }
    let mut b = Vec::new();
    put16(&mut b, 5);
    put16(&mut b, 0); // checksum, set below
    put32(&mut b, 320 + 4 * n as i32);
    put32(&mut b, 0);
    put32(&mut b, note.len() as i32);
    for size in [0, 0, 0, 0, 0, 0, 0, labels.len() as i32, 0, 0, 0, 0] {
        put32(&mut b, size);
    }
    // WaveHeader5.
    b.extend([0u8; 12]);
    put32(&mut b, n as i32);
    put16(&mut b, 2); // f32
    b.extend([0u8; 10]);
    let mut name = [0u8; 32];
    name[..5].copy_from_slice(b"Image");
    b.extend(name);
    b.extend([0u8; 8]);
    for d in [s.nx, s.ny, layers.len(), 0] {
        put32(&mut b, d as i32);
    }
    for v in [s.dx, s.dy, 1.0, 1.0, 0.0, 0.0, 0.0, 0.0] {
        putf(&mut b, v);
    }
    let mut units = [0u8; 20];
    units[..unit.len()].copy_from_slice(unit.as_bytes());
    units[4] = b'm';
    units[8] = b'm';
    b.extend(units);
    b.resize(384, 0);
    let sum = b.chunks(2).fold(0u16, |a, w| {
        a.wrapping_add(if big {
            u16::from_be_bytes([w[0], w[1]])
        } else {
            u16::from_le_bytes([w[0], w[1]])
        })
    });
    let fix = 0u16.wrapping_sub(sum);
    b[2..4].copy_from_slice(&if big {
        fix.to_be_bytes()
    } else {
        fix.to_le_bytes()
    });
    for (_, l) in layers {
        for v in rows(l, true) {
            b.extend(if big {
                (v as f32).to_be_bytes()
            } else {
                (v as f32).to_le_bytes()
            });
        }
    }
    b.extend(note);
    b.extend(labels);
    b
}

/// A NID file of one group of `channels` (Dim2Name, unit, metres per
/// unit, surface) as 32-bit signed Intel (or 16-bit) integers over
/// ±range/2 about 0; returns the file and each channel's step (m).
pub fn nid(
    s: &Surface,
    channels: &[(&str, &str, f64, &Surface)],
    bits: u32,
) -> (Vec<u8>, Vec<f64>) {
    let mut h = String::from("[DataSet]\r\nVersion=2\r\nGroupCount=1\r\nGr0-Name=Scan forward\r\n");
    h += &format!("Gr0-ID=0\r\nGr0-Count={}\r\n", channels.len());
    for k in 0..channels.len() {
        h += &format!("Gr0-Ch{k}=DataSet-0:{k}\r\n");
    }
    h += "\r\n[DataSet-Info]\r\nDate=05-06-2023\r\nTime=07:08:09\r\nHead type=FlexAFM\r\n";
    let mut data = Vec::new();
    let mut steps = Vec::new();
    for (k, (name, unit, per, surf)) in channels.iter().enumerate() {
        let peak = surf.z.iter().fold(0f64, |m, v| m.max(v.abs())) / per;
        let range = 2.5 * peak.max(1e-30);
        let q = range / 2f64.powi(bits as i32);
        steps.push(q * per);
        h += &format!(
            "\r\n[DataSet-0:{k}]\r\nPoints={}\r\nLines={}\r\nFrame=Scan forward\r\nDim0Unit=m\r\nDim0Range={:e}\r\nDim1Unit=m\r\nDim1Range={:e}\r\nDim2Name={name}\r\nDim2Unit={unit}\r\nDim2Range={range:e}\r\nDim2Min={:e}\r\nSaveMode=Binary\r\nSaveBits={bits}\r\nSaveSign=Signed\r\nSaveOrder=Intel\r\n",
            s.nx, s.ny, s.nx as f64 * s.dx, s.ny as f64 * s.dy, -range / 2.0
        );
        for v in rows(surf, true) {
            let raw = (v / per / q).round();
            match bits {
                16 => data.extend((raw as i16).to_le_bytes()),
                _ => data.extend((raw as i32).to_le_bytes()),
            }
        }
    }
    let mut b = h.into_bytes();
    b.extend(b"\r\n#!");
    b.extend(data);
    (b, steps)
}

/// A 14-column MI header line.
fn mi_line(key: &str, value: &str) -> String {
    format!("{key:<14}{value}\n")
}

/// An MI image: heights (µm buffer) and one more buffer in V, as 16-bit
/// (`BINARY`) or 32-bit (`BINARY_32`) integers; returns the file and the
/// height step (m).
pub fn mi(s: &Surface, bits32: bool, scan_up: bool) -> (Vec<u8>, f64) {
    let mut h = mi_line("fileType", "Image");
    h += &mi_line("dateAcquired", "Wed Mar 04 05:06:07 2020");
    h += &mi_line("xPixels", &s.nx.to_string());
    h += &mi_line("yPixels", &s.ny.to_string());
    h += &mi_line("xLength", &format!("{:e}", s.nx as f64 * s.dx));
    h += &mi_line("yLength", &format!("{:e}", s.ny as f64 * s.dy));
    h += &mi_line("scanUp", if scan_up { "TRUE" } else { "FALSE" });
    let peak_um = s.z.iter().fold(0f64, |m, v| m.max(v.abs())) * 1e6;
    let range = 1.5 * peak_um;
    for (label, unit, r) in [("Topography", "um", range), ("Deflection", "V", 10.0)] {
        h += &mi_line("bufferLabel", label);
        h += &mi_line("direction", "Trace");
        h += &mi_line("bufferRange", &format!("{r:e}"));
        h += &mi_line("bufferUnit", unit);
    }
    h += &mi_line("data", if bits32 { "BINARY_32" } else { "BINARY" });
    let full = if bits32 { 2147483648.0 } else { 32768.0 };
    let mut b = h.into_bytes();
    for k in 0..2 {
        for v in rows(s, scan_up) {
            let raw = if k == 0 {
                (v * 1e6 / range * full).round()
            } else {
                7.0
            };
            match bits32 {
                true => b.extend((raw as i32).to_le_bytes()),
                false => b.extend((raw as i16).to_le_bytes()),
            }
        }
    }
    (b, range / full * 1e-6)
}

/// A BCR (16-bit, 1 nm per count) or BCRF (f32 µm) file with a header of
/// 2048 characters, Latin-1 or UTF-16 LE; `void` indices are written as
/// the void value.
pub fn bcr(s: &Surface, float: bool, unicode: bool, void: &[usize]) -> Vec<u8> {
    let kind = match (float, unicode) {
        (false, false) => "bcrstm",
        (true, false) => "bcrf",
        (false, true) => "bcrstm_unicode",
        (true, true) => "bcrf_unicode",
    };
    let (zunit, voidv) = if float {
        ("um", "3.402823E+38")
    } else {
        ("nm", "32767")
    };
    let mut h = format!(
        "fileformat = {kind}\n%\nheadersize = 2048\nxpixels = {}\nypixels = {}\nxlength = {}\nylength = {}\nxunit = nm\nyunit = nm\nzunit = {zunit}\nbit2nm = 1\nintelmode = 1\nvoidpixels = {voidv}\n",
        s.nx, s.ny, s.nx as f64 * s.dx * 1e9, s.ny as f64 * s.dy * 1e9
    );
    while h.len() < 2048 {
        h.push('\0');
    }
    let mut b: Vec<u8> = match unicode {
        true => h.encode_utf16().flat_map(|u| u.to_le_bytes()).collect(),
        false => h.into_bytes(),
    };
    for (i, v) in rows(s, false).enumerate() {
        let bad = void.contains(&i);
        match float {
            true => b.extend(if bad { f32::MAX } else { (v * 1e6) as f32 }.to_le_bytes()),
            false => b.extend(if bad { 32767 } else { (v * 1e9).round() as i16 }.to_le_bytes()),
        }
    }
    b
}

/// A WSxM image of `short` (raw counts about the middle of the range)
/// or `double` (nm) data.
pub fn wsxm(s: &Surface, double: bool) -> Vec<u8> {
    let z_nm: Vec<f64> = rows(s, false).map(|v| v * 1e9).collect();
    let (lo, hi) = z_nm
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(*v), b.max(*v)));
    // 16-bit: counts over ±30000 across the range.
    let q = (hi - lo) / 60000.0;
    let raw: Vec<f64> = match double {
        true => z_nm.clone(),
        false => z_nm
            .iter()
            .map(|v| ((v - (lo + hi) / 2.0) / q).round())
            .collect(),
    };
    let (rmin, rmax) = raw
        .iter()
        .fold((f64::MAX, f64::MIN), |(a, b), v| (a.min(*v), b.max(*v)));
    let amp = if double {
        rmax - rmin
    } else {
        (rmax - rmin) * q
    };
    let body = format!(
        "\r\n[Control]\r\n\r\n    X Amplitude: {} nm\r\n    Y Amplitude: {} nm\r\n\r\n[General Info]\r\n\r\n    Acquisition channel: Topography\r\n    Acquisition time: 03/11/2011, 20:23:46.484\r\n    Head type: AFM\r\n    Image Data Type: {}\r\n    Number of columns: {}\r\n    Number of rows: {}\r\n    Z Amplitude: {amp} nm\r\n\r\n[Miscellaneous]\r\n\r\n    Maximum: {rmax}\r\n    Minimum: {rmin}\r\n\r\n[Header end]\r\n",
        s.nx as f64 * s.dx * 1e9,
        s.ny as f64 * s.dy * 1e9,
        if double { "double" } else { "short" },
        s.nx,
        s.ny
    );
    let head = "WSxM file copyright UAM\r\nSxM Image file\r\nImage header size: ";
    let size = head.len() + 6 + body.len();
    let mut b = format!("{head}{size:06}{body}").into_bytes();
    for v in raw {
        match double {
            true => b.extend(v.to_le_bytes()),
            false => b.extend((v as i16).to_le_bytes()),
        }
    }
    b
}

/// An FRT file (version 1.00 or 1.01) of 16-bit counts of `step` m;
/// `invalid` indices written as the marker 1; returns the file.
pub fn frt(s: &Surface, v101: bool, step: f64, invalid: &[usize]) -> Vec<u8> {
    let mut b = b"FRTM_GLIDERV".to_vec();
    b.extend(if v101 { b"1.01" } else { b"1.00" });
    let mut blocks: Vec<(u16, Vec<u8>)> = Vec::new();
    blocks.push((0x65, b"a comment\0".to_vec()));
    let mut size = Vec::new();
    for v in [s.nx as u32, s.ny as u32, 16] {
        size.extend(v.to_le_bytes());
    }
    blocks.push((0x66, size));
    let mut scan = Vec::new();
    for v in [s.nx as f64 * s.dx, s.ny as f64 * s.dy, 0.0, 0.0, 1.0] {
        scan.extend(v.to_le_bytes());
    }
    scan.extend(0u32.to_le_bytes());
    blocks.push((0x67, scan));
    let mut scale = 5u32.to_le_bytes().to_vec();
    scale.extend(step.to_le_bytes());
    blocks.push((0x6c, scale));
    let lo = s.z.iter().fold(f64::MAX, |a, v| a.min(*v));
    let data = rows(s, false)
        .enumerate()
        .flat_map(|(i, v)| {
            let raw = if invalid.contains(&i) {
                1
            } else {
                ((v - lo) / step).round() as u16 + 2
            };
            raw.to_le_bytes()
        })
        .collect();
    blocks.push((0x0b, data));
    b.extend((blocks.len() as u16).to_le_bytes());
    for (id, content) in blocks {
        b.extend(id.to_le_bytes());
        match v101 {
            true => b.extend((content.len() as u64).to_le_bytes()),
            false => b.extend((content.len() as u32).to_le_bytes()),
        }
        b.extend(content);
    }
    b
}
