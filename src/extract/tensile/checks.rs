//! Cross-checks of a tensile record ([`crate::crosscheck`]): ours against
//! the instrument's printed results, the file's redundant channels against
//! each other, and the physical bounds of the results. Each disagreement is
//! a status naming both values; the tolerances are stated here and in
//! `docs/tensile.md` ("Cross-checks").

use crate::crosscheck::bounds::{at_least, at_most, duration};
use crate::crosscheck::channels::{constant, line, rowwise, Relation};
use crate::crosscheck::printed::against_printed;
use crate::crosscheck::{Shown, Tolerance};
use crate::ingest::roles::{tensile_channel, TensileRole};
use crate::ingest::{Channel, Section};
use crate::status::{Note, Status};
use crate::units::Unit;

use super::analyze::FibreFeatures;
use super::class::{MaterialClass, DEFAULT_STRAIN_BOUND};
use super::curve::FibreMeta;
use super::facts::FileFacts;

/// Ours against a printed modulus: instruments fit their own windows
/// (Bluehill's "Automatic Young's", NanoSuite's); the same window agrees
/// within 1 %, the documented different windows within 5 %.
pub const MODULUS: Tolerance = Tolerance::rel(0.05);
/// Strength and maximum force: the same channel's maximum, printed with
/// four to six digits.
pub const STRENGTH: Tolerance = Tolerance::rel(0.005);
/// Strain at maximum force and at break: 1 % and a strain of 0.001 (a
/// printed strain of 3 decimals; a break detected one sample apart).
pub const STRAIN: Tolerance = Tolerance::new(0.01, 0.001);
/// Offset yield: the construction is exact once E is; 2 % covers a
/// different E within [`MODULUS`] on a flat yield.
pub const YIELD: Tolerance = Tolerance::rel(0.02);
/// ∫ σ dε: the same trapezoid sum over the same samples.
pub const ENERGY: Tolerance = Tolerance::rel(0.01);
/// Stress against force / A, and a section stated twice: 1 %.
pub const SECTION: Tolerance = Tolerance::rel(0.01);
/// True against engineering channels row by row: the files round to 4–6
/// significant digits.
pub const TRUE_VALUES: Tolerance = Tolerance::new(2e-3, 1e-5);
/// The longest one test to fracture lasts: ISO 6892-1, ISO 527 and ASTM
/// E8 rates bring any specimen to fracture within hours.
pub const MAX_TEST_S: f64 = 86_400.0;

const MPA: f64 = 1e-6;

fn shown<'a>(name: &'a str, unit: &'static str, scale: f64) -> Shown<'a> {
    Shown { name, unit, scale }
}

/// Every check of one record; `class` is the one the record was analysed
/// with (`None`: tribo's defaults).
pub fn check(
    section: Option<&Section>,
    meta: &FibreMeta,
    facts: &FileFacts,
    f: &FibreFeatures,
) -> Status {
    let mut notes: Vec<Note> = Vec::new();
    notes.extend(printed(facts, f));
    if let Some(s) = section {
        notes.extend(channels(s, meta, facts));
    }
    notes.extend(section_twice(facts));
    notes.extend(bounds(meta.material_class, f));
    let mut status = Status::ok();
    for n in notes {
        status.push(n.code, n.detail);
    }
    status
}

/// Ours against what the instrument printed.
fn printed(facts: &FileFacts, f: &FibreFeatures) -> Vec<Note> {
    let i = &facts.instrument;
    let g = &f.general;
    let max_force = g.max_force_n;
    let window = match &g.modulus_method {
        Some(m) => format!("ours by {m}"),
        None => String::new(),
    };
    let window = window.as_str();
    let pairs = [
        (
            shown("modulus", "GPa", 1e-9),
            g.modulus_pa,
            i.modulus_pa,
            MODULUS,
            window,
        ),
        (
            shown("strength", "MPa", MPA),
            g.max_stress_pa,
            i.strength_pa,
            STRENGTH,
            "",
        ),
        (
            shown("maximum force", "N", 1.0),
            max_force,
            i.max_force_n,
            STRENGTH,
            "",
        ),
        (
            shown("strain at maximum force", "", 1.0),
            g.strain_at_max_stress,
            i.strain_at_max,
            STRAIN,
            "",
        ),
        (
            shown("strain at break", "", 1.0),
            f.strain_at_break,
            i.strain_at_break,
            STRAIN,
            "",
        ),
        (
            shown("offset yield Rp0.2", "MPa", MPA),
            g.yield_stress_pa,
            i.yield_pa,
            YIELD,
            "",
        ),
        (
            shown("upper yield ReH", "MPa", MPA),
            g.upper_yield_pa,
            i.upper_yield_pa,
            YIELD,
            "",
        ),
        (
            shown("energy density", "MJ/m^3", MPA),
            f.energy_density_j_per_m3,
            i.energy_density_j_per_m3,
            ENERGY,
            "",
        ),
    ];
    pairs
        .into_iter()
        .filter_map(|(q, ours, theirs, tol, why)| against_printed(q, ours?, theirs?, tol, why))
        .collect()
}

/// A channel in SI, by its tensile role.
fn channel(s: &Section, role: TensileRole) -> Option<(&Channel, Vec<f64>, Unit)> {
    let (i, u) = tensile_channel(&s.channels, role)?;
    let c = &s.channels[i];
    Some((c, c.values.iter().map(|v| u.to_si(*v)).collect(), u))
}

/// The file's redundant channels against each other.
fn channels(s: &Section, meta: &FibreMeta, facts: &FileFacts) -> Vec<Note> {
    let mut out = Vec::new();
    let stress = channel(s, TensileRole::Stress);
    let force = channel(s, TensileRole::Force);
    if let (Some((sc, sv, _)), Some((fc, fv, _))) = (&stress, &force) {
        out.extend(stress_against_force(sc, sv, fc, fv, meta, facts));
    }
    let strain = channel(s, TensileRole::Strain);
    let ext = channel(s, TensileRole::Extension);
    if let (Some((ec, ev, _)), Some((xc, xv, _))) = (&strain, &ext) {
        out.extend(strain_against_extension(ec, ev, xc, xv));
    }
    if let Some((tc, tv, u)) = channel(s, TensileRole::Time) {
        let (lo, hi) = tv
            .iter()
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
                (a.min(*v), b.max(*v))
            });
        out.extend(duration(
            &tc.name,
            u.symbol,
            hi - lo,
            MAX_TEST_S,
            "one test to fracture",
        ));
    }
    out.extend(true_against_engineering(s));
    out
}

/// The samples above 5 % of the largest magnitude of `v` (noise about zero
/// says nothing of a ratio).
fn loaded(v: &[f64]) -> impl Fn(usize) -> bool + '_ {
    let top = v
        .iter()
        .filter(|x| x.is_finite())
        .fold(0.0_f64, |a, x| a.max(x.abs()));
    move |i| v[i].abs() > 0.05 * top
}

/// σ = F / A: the area the two channels imply against the specimen's.
fn stress_against_force(
    sc: &Channel,
    sv: &[f64],
    fc: &Channel,
    fv: &[f64],
    meta: &FibreMeta,
    facts: &FileFacts,
) -> Option<Note> {
    let keep = loaded(fv);
    let idx: Vec<usize> = (0..fv.len().min(sv.len())).filter(|&i| keep(i)).collect();
    let x: Vec<f64> = idx.iter().map(|&i| fv[i]).collect();
    let y: Vec<f64> = idx.iter().map(|&i| sv[i]).collect();
    let l = line(&x, &y, true)?;
    let law = format!("'{}' = '{}' / A", sc.name, fc.name);
    let rel = Relation {
        law: &law,
        constant: shown("A", "mm^2", 1e6),
        // a 10 nm fibre to a 1 m² slab
        plausible: (1e-16, 1.0),
        tol: SECTION,
    };
    let stated = facts_section(facts)
        .map(|a| (a, "the file"))
        .or_else(|| meta.section().map(|(_, a)| (a, "the specimen's section")));
    constant(&rel, 1.0 / l.slope, l.scatter, stated)
}

/// The section the file itself states: its area, or width × thickness.
fn facts_section(facts: &FileFacts) -> Option<f64> {
    match (facts.diameter_m, facts.width_m, facts.thickness_m) {
        (Some(d), ..) => Some(std::f64::consts::PI * d * d / 4.0),
        (None, Some(w), Some(t)) => Some(w * t),
        _ => facts.area_m2,
    }
}

/// ε = (x − x₀) / L: the gauge length the two channels imply must be one a
/// specimen has. An extensometer's strain beside the crosshead's travel
/// need not be proportional (the machine's compliance), so only a length
/// no gauge has is flagged.
fn strain_against_extension(ec: &Channel, ev: &[f64], xc: &Channel, xv: &[f64]) -> Option<Note> {
    let l = line(xv, ev, false)?;
    let law = format!("'{}' = ('{}' − x0) / L0", ec.name, xc.name);
    let rel = Relation {
        law: &law,
        constant: shown("L0", "mm", 1e3),
        plausible: (1e-3, 2.0),
        tol: Tolerance::rel(f64::INFINITY),
    };
    constant(&rel, 1.0 / l.slope, l.scatter, None)
}

/// True stress = σ (1 + ε) and true strain = ln(1 + ε), row by row, where a
/// file carries both (Instron's SRMD exports).
fn true_against_engineering(s: &Section) -> Vec<Note> {
    let find = |quantity: &str, kind: &str| {
        s.channels.iter().find(|c| {
            let n = c.name.to_lowercase();
            n.contains(quantity) && n.contains(kind)
        })
    };
    let si = |c: &Channel| -> Option<Vec<f64>> {
        let u = crate::units::parse_unit(&c.raw_unit)?;
        Some(c.values.iter().map(|v| u.to_si(*v)).collect())
    };
    let mut out = Vec::new();
    let (Some(e), Some(te)) = (find("strain", "engineering"), find("strain", "true")) else {
        return out;
    };
    let (Some(ev), Some(tev)) = (si(e), si(te)) else {
        return out;
    };
    let computed: Vec<f64> = ev.iter().map(|e| (1.0 + e).ln()).collect();
    let what = format!("'{}' = ln(1 + '{}')", te.name, e.name);
    out.extend(rowwise(&what, &computed, &tev, TRUE_VALUES));
    if let (Some(sg), Some(ts)) = (find("stress", "engineering"), find("stress", "true")) {
        if let (Some(sv), Some(tsv)) = (si(sg), si(ts)) {
            let computed: Vec<f64> = sv.iter().zip(&ev).map(|(s, e)| s * (1.0 + e)).collect();
            let what = format!("'{}' = '{}' (1 + '{}')", ts.name, sg.name, e.name);
            let tol = Tolerance::new(TRUE_VALUES.rel, 1e3);
            out.extend(rowwise(&what, &computed, &tsv, tol));
        }
    }
    out
}

/// A section stated twice in one file (an area beside width × thickness).
fn section_twice(facts: &FileFacts) -> Option<Note> {
    let (w, t, a) = (facts.width_m?, facts.thickness_m?, facts.area_m2?);
    let rel = Relation {
        law: "width × thickness = the stated cross-section",
        constant: shown("width × thickness", "mm^2", 1e6),
        plausible: (0.0, f64::INFINITY),
        tol: SECTION,
    };
    constant(&rel, w * t, 0.0, Some((a, "the file's cross-section")))
}

/// Values physics rules out.
fn bounds(class: Option<MaterialClass>, f: &FibreFeatures) -> Vec<Note> {
    let g = &f.general;
    let positive = "a tensile or compressive stress is given as a positive magnitude";
    let mut out: Vec<Note> = [
        (shown("strength", "MPa", MPA), g.max_stress_pa),
        (shown("offset yield Rp0.2", "MPa", MPA), g.yield_stress_pa),
        (shown("upper yield ReH", "MPa", MPA), g.upper_yield_pa),
        (shown("lower yield ReL", "MPa", MPA), g.lower_yield_pa),
        (shown("modulus", "GPa", 1e-9), g.modulus_pa),
    ]
    .into_iter()
    .filter_map(|(q, v)| at_least(q, v?, 0.0, positive))
    .collect();
    let bound = class.map_or(DEFAULT_STRAIN_BOUND, MaterialClass::strain_bound);
    let why = match class {
        Some(c) => format!("no {c} specimen stretches so far (docs/tensile.md)"),
        None => "no solid specimen stretches so far (docs/tensile.md)".to_string(),
    };
    let strains = [
        ("strain at maximum force", g.strain_at_max_stress),
        ("strain at break", f.strain_at_break),
    ];
    // one note for the record's strain: the largest beyond the bound
    if let Some((name, v)) = strains
        .into_iter()
        .filter_map(|(n, v)| Some((n, v?)))
        .filter(|(_, v)| *v > bound)
        .max_by(|a, b| a.1.total_cmp(&b.1))
    {
        out.extend(at_most(shown(name, "", 1.0), v, bound, &why));
    }
    out
}
