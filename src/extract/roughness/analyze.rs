//! One profile or map through the chain ([`super::chain`]: window →
//! S-filter → form → L-filter) and every parameter on the result, with the
//! notes that say what could not be computed or is doubtful.

use super::acf::{acf, decay, Acf};
use super::amplitude::{amplitude, rms_gradient, rms_slope, slope_angle_deg, Amplitude};
use super::bearing::{bearing_curve, contact_length, ContactEstimate};
use super::chain::{map_chain, profile_chain, Chained};
use super::fractal::{map_dimension, profile_dimension, FractalEstimate, FractalFailure};
use super::heights::{map_heights, profile_heights, Heights};
use super::hybrid::{sdr, texture_direction};
use super::map::AreaMap;
use super::material::{rk_family, volume, MaterialCurve};
use super::params::RoughnessParams;
use super::psd::{map_psd, profile_psd, Spectrum};
use super::reliability::{reliability_cutoff, Cutoff};
use super::report::{AcfPoint, Functional, Reliability, Spatial};
use super::spacing::rsm;
use super::surface::Profile;
use crate::error::Result;
use crate::status::{Code, Status};

pub use super::report::{RoughnessReport, SurfaceKind};

/// Most points of each ACF curve in the `acf` table.
const ACF_POINTS: usize = 1000;

fn fractal_note(
    r: Result<FractalEstimate, FractalFailure>,
    min_r2: f64,
    notes: &mut Status,
) -> Option<FractalEstimate> {
    match r {
        Ok(e) => {
            if e.dimension.is_none() {
                notes.push(
                    Code::FractalUndefined,
                    format!("fitted Hurst exponent {:.3} outside (0, 1]", e.hurst),
                );
            } else if e.r_squared < min_r2 {
                notes.push(
                    Code::PoorFit,
                    format!(
                        "fractal fit r² = {:.3} < {min_r2}: the surface is not self-affine over \
                         the fitted scales",
                        e.r_squared
                    ),
                );
            }
            Some(e)
        }
        Err(FractalFailure::TooFewScales) => {
            notes.push(
                Code::FractalUndefined,
                "fewer than 3 scales in the lag range",
            );
            None
        }
        Err(FractalFailure::Degenerate) => {
            notes.push(Code::FractalUndefined, "zero structure function");
            None
        }
    }
}

/// Points of an ACF curve: every `step`-th lag up to half the length.
fn acf_curves(a: &Acf, areal: bool) -> Vec<AcfPoint> {
    let line = |n: usize, d: f64, dir: &'static str, get: &dyn Fn(usize) -> f64| {
        let half = n / 2;
        let step = half.div_ceil(ACF_POINTS).max(1);
        (0..=half)
            .step_by(step)
            .map(|k| AcfPoint {
                direction: dir,
                lag: k as f64 * d,
                value: get(k),
            })
            .collect::<Vec<_>>()
    };
    let mut out = line(a.lx, a.dx, "x", &|k| a.at(k as isize, 0));
    if areal {
        out.extend(line(a.ly, a.dy, "y", &|k| a.at(0, k as isize)));
        let rmax = (a.lx as f64 * a.dx).min(a.ly as f64 * a.dy) / 2.0;
        let ring = (rmax / ACF_POINTS as f64).max(a.dx.min(a.dy));
        out.extend(a.radial(rmax, ring).into_iter().map(|(r, v)| AcfPoint {
            direction: "radial",
            lag: r,
            value: v,
        }));
    }
    out
}

/// The material ratio curve of the measured heights and the functional
/// parameters read from it.
fn functional(z: &[f64], params: &RoughnessParams) -> Option<(Functional, MaterialCurve)> {
    let curve = MaterialCurve::new(z)?;
    let (p, q) = params.volume_ratios;
    let f = Functional {
        rk: rk_family(&curve, params.rk_line),
        smr: curve.ratio(params.material_height),
        smc: curve.height(params.material_ratio),
        sxp: curve.height(0.025) - curve.height(0.5),
        volume: volume(&curve, p, q),
    };
    Some((f, curve))
}

/// Everything read from the chained heights apart from amplitude and
/// slope, computed side by side (each in its own fixed order).
struct Readings {
    fractal: Option<Result<FractalEstimate, FractalFailure>>,
    functional: Option<(Functional, MaterialCurve)>,
    psd: Spectrum,
    acf: Option<Acf>,
    spatial: Spatial,
    cutoff: Option<Cutoff>,
}

fn readings(c: &Chained, kind: SurfaceKind, flat: bool, params: &RoughnessParams) -> Readings {
    let (z, nx, ny, dx, dy) = (&c.z, c.nx, c.ny, c.dx, c.dy);
    let areal = kind == SurfaceKind::Areal;
    let spectra = params.spectra && !flat;
    let ((fractal, functional), ((psd, acf), (spatial, cutoff))) = rayon::join(
        || {
            rayon::join(
                || {
                    (!flat).then(|| match areal {
                        true => map_dimension(z, nx, ny, dx, dy, &params.fractal),
                        false => profile_dimension(z, dx, &params.fractal),
                    })
                },
                || functional(z, params),
            )
        },
        || {
            rayon::join(
                || {
                    rayon::join(
                        || match (spectra, areal) {
                            (false, _) => Spectrum::default(),
                            (true, true) => map_psd(z, nx, ny, dx, dy, params.periodic),
                            (true, false) => profile_psd(z, dx, params.periodic),
                        },
                        || {
                            let wanted = spectra || (areal && !flat);
                            wanted
                                .then(|| acf(z, nx, ny, dx, dy, params.periodic))
                                .flatten()
                        },
                    )
                },
                || {
                    rayon::join(
                        || match areal {
                            true => Spatial {
                                sdr: sdr(z, nx, ny, dx, dy),
                                std_deg: (!flat)
                                    .then(|| texture_direction(z, nx, ny, dx, dy))
                                    .flatten(),
                                ..Spatial::default()
                            },
                            false => Spatial::default(),
                        },
                        || {
                            params
                                .tip_radius
                                .map(|r| reliability_cutoff(z, nx, ny, dx, dy, r))
                        },
                    )
                },
            )
        },
    );
    Readings {
        fractal,
        functional,
        psd,
        acf,
        spatial,
        cutoff,
    }
}

/// The notes on spatial parameters the data cannot support.
fn spatial_notes(s: &Spatial, kind: SurfaceKind, undecayed: usize, notes: &mut Status) {
    if kind == SurfaceKind::Areal {
        if s.sal.is_none() {
            notes.push(
                Code::ParameterUndefined,
                "Sal, Str: the ACF does not fall to s in any direction within the map \
                 (correlation longer than the map)",
            );
        } else if s.str_ratio.is_none() {
            notes.push(
                Code::ParameterUndefined,
                format!(
                    "Str: the ACF does not fall to s along {undecayed} of 720 directions within \
                     the map (a lay longer than the map); ISO allows 0 or undefined: null"
                ),
            );
        }
    } else if s.rsm.is_none() {
        notes.push(
            Code::ParameterUndefined,
            "RSm: no whole profile element (peak and valley beyond 10 % of Rz)",
        );
    }
}

/// The note on scales below the tip's reliability cut-off.
fn reliability_note(
    c: &Chained,
    params: &RoughnessParams,
    cut: Option<Cutoff>,
    fractal: Option<&FractalEstimate>,
    notes: &mut Status,
) {
    let (Some(r), Some(cut)) = (params.tip_radius, cut) else {
        return;
    };
    let Some(l) = cut.length() else {
        return;
    };
    // The slopes (and Sdr) reach down to two samples, or to λs when an
    // S-filter removed the shorter scales.
    let finest = params.short_cutoff.unwrap_or(0.0).max(2.0 * c.dx);
    let mut affected = Vec::new();
    if l > finest {
        affected.push("Rdq/Sdq, Sdr");
    }
    if fractal.is_some_and(|f| l > f.scales.0) {
        affected.push("the fractal fit");
    }
    if matches!(cut, Cutoff::Everything(_)) {
        affected = vec!["every scale measured"];
    }
    if !affected.is_empty() {
        notes.push(
            Code::BelowReliabilityCutoff,
            format!(
                "a tip of radius {r:.3e} m cannot follow scales below {l:.3e} m; {} use them \
                 (and the PSD there: its `reliable` column)",
                affected.join(", ")
            ),
        );
    }
}

/// Amplitude, slope and heights of the chained heights, side by side.
fn amplitude_slope_heights(
    c: &Chained,
    areal: bool,
    params: &RoughnessParams,
) -> (Amplitude, (Option<f64>, Heights)) {
    let z = &c.z;
    rayon::join(
        || amplitude(z, c.scale),
        || {
            rayon::join(
                || match areal {
                    true => rms_gradient(z, c.nx, c.ny, c.dx, c.dy, params.derivative),
                    false => rms_slope(z, c.dx, params.derivative),
                },
                // ISO 4288: the sampling length is the filter's cut-off.
                || match areal {
                    true => map_heights(z),
                    false => profile_heights(z, c.dx, params.filter.map(|f| f.cutoff)),
                },
            )
        },
    )
}

/// The notes on points not measured and on a flat surface.
fn coverage_notes(n: usize, n_invalid: usize, flat: bool, params: &RoughnessParams) -> Status {
    let mut notes = Status::ok();
    let share = n_invalid as f64 / n as f64;
    if share > params.max_invalid_fraction {
        notes.push(
            Code::TooManyInvalid,
            format!(
                "{n_invalid} of {n} points ({:.1} %) are not measured; at most {:.1} % allowed",
                100.0 * share,
                100.0 * params.max_invalid_fraction
            ),
        );
    }
    if flat {
        notes.push(
            Code::Flat,
            "Rq = 0, so skewness, kurtosis, fractal dimension, spectra and spatial \
             parameters are undefined",
        );
    }
    notes
}

/// Sal and Str from the ACF (maps), RSm (profiles), with their notes.
fn complete_spatial(
    c: &Chained,
    kind: SurfaceKind,
    flat: bool,
    (heights, acf): (&Heights, Option<&Acf>),
    mut spatial: Spatial,
    params: &RoughnessParams,
    notes: &mut Status,
) -> Spatial {
    let mut undecayed = 0;
    if let (SurfaceKind::Areal, Some(a)) = (kind, acf) {
        let d = decay(a, params.acf_threshold);
        (spatial.sal, spatial.str_ratio, undecayed) = (d.sal, d.str_ratio, d.undecayed_rays);
    }
    if kind == SurfaceKind::Profile && !flat {
        let rz = heights.rz_iso.unwrap_or(heights.total);
        let lr = params.filter.map_or(c.nx as f64 * c.dx / 5.0, |f| f.cutoff);
        spatial.rsm = rsm(&c.z, c.dx, 0.1 * rz, 0.01 * lr);
    }
    if !flat {
        spatial_notes(&spatial, kind, undecayed, notes);
    }
    spatial
}

/// The notes on gaps filled for the PSD and a robust filter that did not
/// settle.
fn transform_notes(n_invalid: usize, psd: &Spectrum, c: &Chained, notes: &mut Status) {
    if n_invalid > 0 && !psd.q.is_empty() {
        notes.push(
            Code::GapsFilled,
            format!(
                "PSD: {n_invalid} points not measured set to the mean line, the spectrum \
                 scaled by n/n_measured"
            ),
        );
    }
    if let Some(run) = c.robust.filter(|run| !run.converged) {
        notes.push(
            Code::NumericalFailure,
            format!(
                "the robust filter's weights did not settle in {} iterations",
                run.iterations
            ),
        );
    }
}

/// The bearing curve and the contact estimate, both read off the material
/// curve; a contact asked for on a surface without RMS slope is noted.
fn bearing_and_contact(
    curve: Option<&MaterialCurve>,
    slope: Option<f64>,
    params: &RoughnessParams,
    notes: &mut Status,
) -> (Vec<(f64, f64)>, Option<ContactEstimate>) {
    let bearing = curve.map_or_else(Vec::new, |c| {
        bearing_curve(c.sorted(), params.bearing_points)
    });
    let contact = params.contact.and_then(|ct| {
        let est = curve
            .zip(slope)
            .and_then(|(c, s)| contact_length(c.sorted(), s, &ct));
        if est.is_none() {
            notes.push(Code::ContactUndefined, "zero RMS slope");
        }
        est
    });
    (bearing, contact)
}

fn finish(
    source: &str,
    kind: SurfaceKind,
    c: Chained,
    window: Option<(f64, f64)>,
    params: &RoughnessParams,
) -> RoughnessReport {
    let z = &c.z;
    let areal = kind == SurfaceKind::Areal;
    let (amp, (slope, heights)) = amplitude_slope_heights(&c, areal, params);
    let n_invalid = super::mask::count_invalid(z);
    let mut notes = coverage_notes(z.len(), n_invalid, amp.flat, params);
    let mut r = readings(&c, kind, amp.flat, params);
    let fractal = r
        .fractal
        .take()
        .and_then(|e| fractal_note(e, params.fractal_min_r_squared, &mut notes));
    if slope.is_none() {
        notes.push(
            Code::SlopeUndefined,
            "too few points for the derivative scheme",
        );
    }
    let spatial = complete_spatial(
        &c,
        kind,
        amp.flat,
        (&heights, r.acf.as_ref()),
        r.spatial,
        params,
        &mut notes,
    );
    transform_notes(n_invalid, &r.psd, &c, &mut notes);
    reliability_note(&c, params, r.cutoff, fractal.as_ref(), &mut notes);
    let (functional, curve) = match r.functional.take() {
        Some((f, curve)) => ((!amp.flat).then_some(f), Some(curve)),
        None => (None, None),
    };
    let (bearing, contact) = bearing_and_contact(curve.as_ref(), slope, params, &mut notes);
    RoughnessReport {
        source: source.to_string(),
        kind,
        n_points: z.len(),
        n_invalid,
        length: (c.nx - 1) as f64 * c.dx,
        window,
        ra: amp.ra,
        rq: amp.rq,
        rms_slope: slope,
        rdq_deg: slope.map(slope_angle_deg),
        rsk: amp.rsk,
        rku: amp.rku,
        heights,
        fractal,
        bearing,
        functional,
        spatial,
        psd: r.psd,
        acf: r
            .acf
            .as_ref()
            .filter(|_| params.spectra)
            .map_or_else(Vec::new, |a| acf_curves(a, areal)),
        reliability: params
            .tip_radius
            .zip(r.cutoff)
            .map(|(tip_radius, cutoff)| Reliability { tip_radius, cutoff }),
        form_radius: c.form_radius,
        robust: c.robust,
        contact,
        notes,
    }
}

/// Roughness of a profile.
///
/// Errors: [`crate::Error::Config`] for invalid parameters,
/// [`crate::Error::Input`] when the window holds too few points,
/// [`crate::Error::NotApplicable`] when the (windowed) profile is shorter
/// than the filter cut-off, too few points remain after discarding the
/// filter's ends, or a form cannot be fitted.
pub fn analyze_profile(p: &Profile, params: &RoughnessParams) -> Result<RoughnessReport> {
    params.validate()?;
    let c = profile_chain(p, params)?;
    Ok(finish(
        &p.source,
        SurfaceKind::Profile,
        c,
        params.window,
        params,
    ))
}

/// Roughness of an areal map (S-parameters) inside the windows along x and y.
pub fn analyze_map(m: &AreaMap, params: &RoughnessParams) -> Result<RoughnessReport> {
    params.validate()?;
    let c = map_chain(m, params)?;
    Ok(finish(
        &m.source,
        SurfaceKind::Areal,
        c,
        params.window,
        params,
    ))
}
