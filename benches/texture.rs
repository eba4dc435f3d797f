//! The ISO 25178-2 texture parameters of a 2048 × 2048 map
//! (`TRIBO_BENCH_SIDE` to change the side) side by side with surfalize, and
//! the radially averaged PSD with SurfaceTopography, on the same SUR file
//! (`benches/peers/surfalize_texture.py`: a seeded self-affine map written
//! by surfalize's own SUR writer). In one run:
//!
//! - in process, per parameter group (read, plane levelling, amplitude and
//!   heights, Sdq, Sdr, Sal/Str from the ACF, Std, the material-ratio family
//!   with the volumes, the PSD): tribo's library functions against the
//!   peers' calls timed inside Python (start-up excluded), each the median
//!   of `TRIBO_BENCH_RUNS` runs (default 3), with the ratio peer / tribo and
//!   the largest relative difference of the group's values (Sdq with forward
//!   differences, surfalize's scheme);
//! - whole processes (wall and CPU seconds, peak memory): `tribo roughness
//!   FILE --detrend line` (all tables, the fractal dimension and the
//!   report besides) and with `--no-spectra`, against the surfalize peer.
//!
//! The peers run in the Python of `TRIBO_PEER_PYTHON`, else the virtual
//! environment `scripts/python-tests.sh` makes in the target folder, else
//! `python3`; without surfalize the benchmark says so and stops.
//!
//! cargo bench --bench texture

mod common;

use std::collections::BTreeMap;
use std::path::Path;
use std::process::Command;
use std::time::Instant;

use common::{load_average, measure, measure_in, peer, peer_python, python_has, repeats, tribo};
use tribo::extract::roughness::acf::{acf, decay};
use tribo::extract::roughness::amplitude::{amplitude, rms_gradient};
use tribo::extract::roughness::chain::{map_chain, Chained};
use tribo::extract::roughness::heights::map_heights;
use tribo::extract::roughness::hybrid::{sdr, texture_direction};
use tribo::extract::roughness::input::{surfaces_from_dataset, AxisUnits, Surface};
use tribo::extract::roughness::material::{rk_family, volume, MaterialCurve, RkLine};
use tribo::extract::roughness::psd::{map_psd, Spectrum};
use tribo::extract::roughness::{AreaMap, DerivativeScheme, RoughnessParams};
use tribo::ingest::{read_path, IngestOptions};

/// Parameter values in surfalize's units (µm, percent), by name.
type Values = BTreeMap<String, f64>;

const UM: f64 = 1e6;

/// The median seconds of [`repeats`] runs of `f`, and its last value.
fn median_of<T>(mut f: impl FnMut() -> T) -> (f64, T) {
    let mut secs = Vec::new();
    let mut last = None;
    for _ in 0..repeats() {
        let t = Instant::now();
        last = Some(f());
        secs.push(t.elapsed().as_secs_f64());
    }
    secs.sort_by(f64::total_cmp);
    (secs[secs.len() / 2], last.expect("at least one run"))
}

fn named(pairs: &[(&str, f64)]) -> Values {
    pairs.iter().map(|&(k, v)| (k.to_string(), v)).collect()
}

fn read_map(path: &Path) -> AreaMap {
    let ds = read_path(path, &IngestOptions::default()).expect("read the SUR file");
    let mut s = surfaces_from_dataset(&ds, &AxisUnits::default()).expect("a surface");
    match s.remove(0) {
        Surface::Map(m) => m,
        Surface::Profile(_) => panic!("the SUR file is not a map"),
    }
}

fn functional(c: &Chained) -> Values {
    let curve = MaterialCurve::new(&c.z).expect("measured heights");
    let rk = rk_family(&curve, RkLine::LeastSquares);
    let v = volume(&curve, 0.1, 0.8);
    named(&[
        ("Sk", rk.rk * UM),
        ("Spk", rk.rpk * UM),
        ("Svk", rk.rvk * UM),
        ("Smr1", rk.mr1 * 100.0),
        ("Smr2", rk.mr2 * 100.0),
        ("Sxp", (curve.height(0.025) - curve.height(0.5)) * UM),
        ("Vmp", v.vmp * UM),
        ("Vmc", v.vmc * UM),
        ("Vvc", v.vvc * UM),
        ("Vvv", v.vvv * UM),
    ])
}

/// tribo's groups in this process: (group, median seconds, values).
fn ours(path: &Path) -> (Vec<(&'static str, f64, Values)>, Spectrum) {
    let (t_read, map) = median_of(|| read_map(path));
    let params = RoughnessParams::default();
    let (t_form, c) = median_of(|| map_chain(&map, &params).expect("plane levelling"));
    let (nx, ny, dx, dy) = (c.nx, c.ny, c.dx, c.dy);
    let z = &c.z;
    let mut out = vec![
        ("read", t_read, Values::new()),
        ("form", t_form, Values::new()),
    ];
    let (t, v) = median_of(|| {
        let a = amplitude(z, c.scale);
        let h = map_heights(z);
        named(&[
            ("Sa", a.ra * UM),
            ("Sq", a.rq * UM),
            ("Ssk", a.rsk.unwrap_or(f64::NAN)),
            ("Sku", a.rku.unwrap_or(f64::NAN)),
            ("Sp", h.peak * UM),
            ("Sv", h.valley * UM),
            ("Sz", h.total * UM),
        ])
    });
    out.push(("amplitude", t, v));
    let (t, v) = median_of(|| {
        let s = rms_gradient(z, nx, ny, dx, dy, DerivativeScheme::Forward);
        named(&[("Sdq", s.unwrap_or(f64::NAN))])
    });
    out.push(("slope", t, v));
    let (t, v) =
        median_of(|| named(&[("Sdr", sdr(z, nx, ny, dx, dy).unwrap_or(f64::NAN) * 100.0)]));
    out.push(("area", t, v));
    let (t, v) = median_of(|| {
        let a = acf(z, nx, ny, dx, dy, false).expect("an ACF");
        let d = decay(&a, 0.2);
        named(&[
            ("Sal", d.sal.unwrap_or(f64::NAN) * UM),
            ("Str", d.str_ratio.unwrap_or(f64::NAN)),
        ])
    });
    out.push(("acf", t, v));
    let (t, v) = median_of(|| {
        named(&[(
            "Std",
            texture_direction(z, nx, ny, dx, dy).unwrap_or(f64::NAN),
        )])
    });
    out.push(("direction", t, v));
    let (t, v) = median_of(|| functional(&c));
    out.push(("functional", t, v));
    let (t, psd) = median_of(|| map_psd(z, nx, ny, dx, dy, false));
    out.push(("psd", t, Values::new()));
    (out, psd)
}

/// The peer's JSON lines: per group the median seconds, and the values.
fn peer_lines(path: &Path) -> (BTreeMap<String, f64>, serde_json::Value) {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let lines: Vec<serde_json::Value> = text
        .lines()
        .filter_map(|l| serde_json::from_str(l).ok())
        .collect();
    let mut secs: BTreeMap<String, Vec<f64>> = BTreeMap::new();
    for l in &lines {
        for (k, v) in l["seconds"].as_object().into_iter().flatten() {
            secs.entry(k.clone())
                .or_default()
                .push(v.as_f64().unwrap_or(f64::NAN));
        }
    }
    let medians = secs
        .into_iter()
        .map(|(k, mut v)| {
            v.sort_by(f64::total_cmp);
            (k, v[v.len() / 2])
        })
        .collect();
    let values = lines
        .last()
        .map_or(serde_json::Value::Null, |l| l["values"].clone());
    (medians, values)
}

/// The largest relative difference of `ours` from the peer's values of the
/// same names (Std left out: on an isotropic map its angle is arbitrary).
fn largest_difference(ours: &Values, theirs: &serde_json::Value) -> Option<(String, f64)> {
    ours.iter()
        .filter(|(k, _)| k.as_str() != "Std")
        .filter_map(|(k, &v)| {
            let r = theirs[k.as_str()].as_f64()?;
            Some((k.clone(), (v - r).abs() / r.abs().max(f64::MIN_POSITIVE)))
        })
        .max_by(|a, b| a.1.total_cmp(&b.1))
}

fn psd_difference(ours: &Spectrum, theirs: &serde_json::Value) -> Option<f64> {
    let q = theirs["q"].as_array()?;
    let c = theirs["C"].as_array()?;
    if q.len() != ours.q.len() {
        println!(
            "  PSD: {} bins here, {} in SurfaceTopography",
            ours.q.len(),
            q.len()
        );
        return None;
    }
    Some(
        ours.c
            .iter()
            .zip(c)
            .filter_map(|(a, b)| Some((a - b.as_f64()?).abs() / a.abs()))
            .fold(0.0, f64::max),
    )
}

fn main() {
    let side: usize = std::env::var("TRIBO_BENCH_SIDE")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(2048);
    println!("load average at start: {}", load_average());
    let py = peer_python();
    if !python_has(&py, "numpy, surfalize") {
        println!(
            "no surfalize: nothing to compare with (TRIBO_PEER_PYTHON, or scripts/python-tests.sh)"
        );
        return;
    }
    let dir = std::env::temp_dir().join("tribo_bench_texture");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("bench dir");
    let sur = dir.join("map.sur");
    let s = sur.to_str().expect("UTF-8 temp path");
    let script = peer("surfalize_texture.py");
    let made = Command::new(&py)
        .args([&script, "generate", s, &side.to_string()])
        .status();
    assert!(
        made.is_ok_and(|st| st.success()),
        "the peer could not write {s}"
    );
    let mb = std::fs::metadata(&sur).map_or(0, |m| m.len()) as f64 / 1e6;
    println!(
        "== {side} x {side} map, SUR file {mb:.1} MB; medians of {} runs ==",
        repeats()
    );

    let (groups, psd) = ours(&sur);
    let jl = dir.join("peer.jsonl");
    let j = jl.to_str().expect("UTF-8 temp path");
    let peer_whole = measure(&py, &[&script, "params", s, j]);
    let (mut theirs, values) = peer_lines(&jl);
    let mut psd_values = serde_json::Value::Null;
    if python_has(&py, "SurfaceTopography") {
        let sl = dir.join("st.jsonl");
        let sj = sl.to_str().expect("UTF-8 temp path");
        if measure(&py, &[&script, "psd", s, sj]).is_some() {
            let (st, v) = peer_lines(&sl);
            theirs.extend(st);
            psd_values = v;
        }
    }
    println!("in process (seconds; peer / tribo; largest relative difference of the values):");
    println!("| group | tribo | peer | ratio | difference |");
    println!("|---|---|---|---|---|");
    let (mut sum_ours, mut sum_theirs) = (0.0, 0.0);
    for (g, t, v) in &groups {
        let peer_t = theirs.get(*g).copied();
        let diff = match *g {
            "psd" => psd_difference(&psd, &psd_values).map(|d| format!("C(q) {d:.1e}")),
            _ => largest_difference(v, &values).map(|(k, d)| format!("{k} {d:.1e}")),
        };
        if let Some(p) = peer_t {
            (sum_ours, sum_theirs) = (sum_ours + t, sum_theirs + p);
        }
        println!(
            "| {g} | {t:.3} | {} | {} | {} |",
            peer_t.map_or("-".into(), |p| format!("{p:.3}")),
            peer_t.map_or("-".into(), |p| format!("{:.1}", p / t)),
            diff.unwrap_or_default()
        );
    }
    println!(
        "| all groups | {sum_ours:.3} | {sum_theirs:.3} | {:.1} | |",
        sum_theirs / sum_ours
    );

    let out = dir.join("out");
    let o = out.to_str().expect("UTF-8 temp path");
    let full = ["roughness", s, "--out", o, "--detrend", "line"];
    let lean = [
        "roughness",
        s,
        "--out",
        o,
        "--detrend",
        "line",
        "--no-spectra",
    ];
    println!("whole processes (wall s, CPU s, peak RSS MB, peer wall / this wall):");
    let peer_whole = peer_whole.expect("the surfalize peer ran");
    for (name, args) in [
        ("tribo roughness", &full[..]),
        ("tribo roughness --no-spectra", &lean[..]),
    ] {
        if let Some(m) = measure_in(tribo(), args, Some(&out)) {
            println!(
                "{name:<34} {:>7.2} {:>7.2} {:>7.0}  {:.1}",
                m.secs,
                m.cpu_secs,
                m.rss_mb,
                peer_whole.secs / m.secs
            );
        }
    }
    println!(
        "{:<34} {:>7.2} {:>7.2} {:>7.0}",
        "surfalize peer", peer_whole.secs, peer_whole.cpu_secs, peer_whole.rss_mb
    );
    println!("load average at end: {}", load_average());
    let _ = std::fs::remove_dir_all(&dir);
}
