//! The analysis chain: window → detrend → Gaussian filter → parameters.

use super::amplitude::{amplitude, rms_gradient, rms_slope, slope_angle_deg};
use super::bearing::{bearing_curve, contact_length, select_heights, ContactEstimate};
use super::form::{detrend_map, detrend_profile_at};
use super::fractal::{map_dimension, profile_dimension, FractalEstimate, FractalFailure};
use super::heights::{map_heights, profile_heights, Heights};
use super::params::RoughnessParams;
use super::surface::{AreaMap, Profile, MIN_POINTS};
use crate::error::{Error, Result};
use crate::signal::gaussian_filter::{mean_surface, roughness};
use crate::status::{Code, Status};
use rayon::prelude::*;

/// Whether a report is about a profile (R-parameters) or a map
/// (S-parameters, same formulas over the area).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SurfaceKind {
    /// A stylus profile z(x).
    Profile,
    /// An areal map z(x, y).
    Areal,
}

impl SurfaceKind {
    /// `profile` or `areal`.
    pub fn as_str(self) -> &'static str {
        match self {
            SurfaceKind::Profile => "profile",
            SurfaceKind::Areal => "areal",
        }
    }
}

/// Roughness of one profile or map.
#[derive(Debug, Clone, PartialEq)]
pub struct RoughnessReport {
    /// Input label.
    pub source: String,
    /// Profile or areal.
    pub kind: SurfaceKind,
    /// Points evaluated (after window and end discarding), measured or not.
    pub n_points: usize,
    /// Of those, points not measured (NaN in the file, or left undefined by
    /// a filter across a wide gap, [`super::mask`]).
    pub n_invalid: usize,
    /// Evaluated length along x (m).
    pub length: f64,
    /// Ra (Sa) (m).
    pub ra: f64,
    /// Rq (Sq) (m).
    pub rq: f64,
    /// RMS slope Rdq (Sdq) as a slope (dimensionless).
    pub rms_slope: Option<f64>,
    /// Rdq as an angle, atan(rms_slope) (degrees).
    pub rdq_deg: Option<f64>,
    /// Rsk (Ssk); `None` when flat.
    pub rsk: Option<f64>,
    /// Rku (Sku); `None` when flat.
    pub rku: Option<f64>,
    /// Rp, Rv, Rt, Rz (Sp, Sv, Sz for maps), MODELS.md §9.
    pub heights: Heights,
    /// Fractal estimate, when one could be made.
    pub fractal: Option<FractalEstimate>,
    /// Bearing curve (material ratio, height in m).
    pub bearing: Vec<(f64, f64)>,
    /// Contact length (Eq. 3.14–3.15) when requested and defined.
    pub contact: Option<ContactEstimate>,
    /// Notes on values left out; empty when everything was computed.
    pub notes: Status,
}

impl RoughnessReport {
    /// `ok`, or the notes joined by `; `.
    pub fn status(&self) -> String {
        self.notes.to_string()
    }
}

fn fractal_note(
    r: Result<FractalEstimate, FractalFailure>,
    notes: &mut Status,
) -> Option<FractalEstimate> {
    match r {
        Ok(e) => {
            if e.dimension.is_none() {
                notes.push(
                    Code::FractalUndefined,
                    format!("fitted Hurst exponent {:.3} outside (0, 1]", e.hurst),
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

/// Shared tail: amplitude, slope, fractal, bearing, contact.
struct Evaluated {
    amp: super::amplitude::Amplitude,
    slope: Option<f64>,
    heights: Heights,
}

/// The largest |z| (the scale of round-off in the amplitude sums), on all
/// threads: a maximum does not depend on the order it is taken in.
fn largest_magnitude(z: &[f64]) -> f64 {
    crate::signal::scan::finite_range(z).map_or(0.0, |(lo, hi)| lo.abs().max(hi.abs()))
}

fn finish(
    source: &str,
    kind: SurfaceKind,
    z: &[f64],
    length: f64,
    ev: Evaluated,
    fractal: impl FnOnce() -> Result<FractalEstimate, FractalFailure> + Send,
    params: &RoughnessParams,
) -> RoughnessReport {
    let mut notes = Status::ok();
    let n_invalid = super::mask::count_invalid(z);
    let share = n_invalid as f64 / z.len() as f64;
    if share > params.max_invalid_fraction {
        notes.push(
            Code::TooManyInvalid,
            format!(
                "{n_invalid} of {} points ({:.1} %) are not measured; at most {:.1} % allowed",
                z.len(),
                100.0 * share,
                100.0 * params.max_invalid_fraction
            ),
        );
    }
    if ev.amp.flat {
        notes.push(
            Code::Flat,
            "Rq = 0, so skewness, kurtosis and fractal dimension are undefined",
        );
    }
    let ratios: Vec<f64> = params
        .contact
        .iter()
        .map(|c| c.nominal_pressure / c.hardness)
        .collect();
    // The fractal estimate and the bearing ranks read the heights apart;
    // the ranks are those of the measured heights.
    let (estimate, sorted) = rayon::join(
        || (!ev.amp.flat).then(fractal),
        || match n_invalid {
            0 => select_heights(z, params.bearing_points, &ratios),
            _ => select_heights(
                &super::mask::measured_heights(z),
                params.bearing_points,
                &ratios,
            ),
        },
    );
    let fractal = estimate.and_then(|e| fractal_note(e, &mut notes));
    if ev.slope.is_none() {
        notes.push(
            Code::SlopeUndefined,
            "too few points for the derivative scheme",
        );
    }
    let bearing = bearing_curve(&sorted, params.bearing_points);
    let contact = params.contact.and_then(|c| {
        let r = ev.slope.and_then(|s| contact_length(&sorted, s, &c));
        if r.is_none() {
            notes.push(Code::ContactUndefined, "zero RMS slope");
        }
        r
    });
    RoughnessReport {
        source: source.to_string(),
        kind,
        n_points: z.len(),
        n_invalid,
        length,
        ra: ev.amp.ra,
        rq: ev.amp.rq,
        rms_slope: ev.slope,
        rdq_deg: ev.slope.map(slope_angle_deg),
        rsk: ev.amp.rsk,
        rku: ev.amp.rku,
        heights: ev.heights,
        fractal,
        bearing,
        contact,
        notes,
    }
}

/// At least [`MIN_POINTS`] of `z` measured, else an error naming `source`
/// and `where_`.
fn enough_measured(source: &str, z: &[f64], where_: &str) -> Result<()> {
    let n = z.len() - super::mask::count_invalid(z);
    if n < MIN_POINTS {
        return Err(Error::NotApplicable(format!(
            "{source}: {n} of {} points {where_} are measured (the others are not: NaN in \
             the file, or a gap wider than the filter can bridge); at least {MIN_POINTS} \
             are needed",
            z.len()
        )));
    }
    Ok(())
}

/// Roughness of a profile.
///
/// Errors: [`Error::Config`] for invalid parameters, [`Error::Input`] when
/// the window holds too few points, [`Error::NotApplicable`] when the
/// (windowed) profile is shorter than the filter cut-off or too few points
/// remain after discarding the filter's ends.
pub fn analyze_profile(p: &Profile, params: &RoughnessParams) -> Result<RoughnessReport> {
    params.validate()?;
    let (lo, hi) = p.window_range(params.window)?;
    let mut z: Vec<f64> = p.z[lo..hi].par_iter().copied().collect();
    enough_measured(&p.source, &z, "in the evaluation window")?;
    let scale = largest_magnitude(&z);
    let positions = p.positions.as_ref().map(|x| &x[lo..hi]);
    detrend_profile_at(&mut z, positions, params.detrend);
    if let Some(f) = &params.filter {
        let (r, _) = roughness(&z, p.dx, f)?;
        if r.len() < MIN_POINTS {
            return Err(Error::NotApplicable(format!(
                "{}: {} points remain after discarding λc/2 at each end; at least \
                 {MIN_POINTS} are needed (shorter λc or Renormalize ends)",
                p.source,
                r.len()
            )));
        }
        enough_measured(&p.source, &r, "after the filter")?;
        z = r;
    }
    // Three independent readings of the profile, each in its own order:
    // side by side, with the same bits.
    let (amp, (slope, heights)) = rayon::join(
        || amplitude(&z, scale),
        || {
            rayon::join(
                || rms_slope(&z, p.dx, params.derivative),
                // ISO 4288: the sampling length is the filter's cut-off.
                || profile_heights(&z, p.dx, params.filter.map(|f| f.cutoff)),
            )
        },
    );
    let length = (z.len() - 1) as f64 * p.dx;
    let fp = params.fractal;
    let dx = p.dx;
    let zr = &z;
    Ok(finish(
        &p.source,
        SurfaceKind::Profile,
        &z,
        length,
        Evaluated {
            amp,
            slope,
            heights,
        },
        || profile_dimension(zr, dx, &fp),
        params,
    ))
}

/// Roughness of an areal map (S-parameters) inside the windows along x and y.
pub fn analyze_map(m: &AreaMap, params: &RoughnessParams) -> Result<RoughnessReport> {
    params.validate()?;
    let w = m.windowed(params.window, params.window_y)?;
    let (mut nx, mut ny, mut z) = (w.nx, w.ny, w.z);
    enough_measured(&m.source, &z, "in the evaluation window")?;
    let scale = largest_magnitude(&z);
    detrend_map(&mut z, nx, ny, params.detrend);
    if let Some(f) = &params.filter {
        let lx = (nx - 1) as f64 * m.dx;
        let ly = (ny - 1) as f64 * m.dy;
        if lx.min(ly) < f.cutoff {
            return Err(Error::NotApplicable(format!(
                "{}: map of {lx:.6e} × {ly:.6e} m is smaller than the cut-off λc = {:.6e} m",
                m.source, f.cutoff
            )));
        }
        let mean = mean_surface(&z, nx, ny, m.dx, m.dy, f)?;
        let (drop_x, drop_y) = (f.discard_count(m.dx), f.discard_count(m.dy));
        let (nx2, ny2) = (nx.saturating_sub(2 * drop_x), ny.saturating_sub(2 * drop_y));
        if nx2 < MIN_POINTS || ny2 < MIN_POINTS {
            return Err(Error::NotApplicable(format!(
                "{}: {nx2} × {ny2} points remain after discarding λc/2 at each edge; \
                 at least {MIN_POINTS} per side are needed",
                m.source
            )));
        }
        let mut r = Vec::with_capacity(nx2 * ny2);
        for row in drop_y..drop_y + ny2 {
            for c in drop_x..drop_x + nx2 {
                r.push(z[row * nx + c] - mean[row * nx + c]);
            }
        }
        enough_measured(&m.source, &r, "after the filter")?;
        z = r;
        nx = nx2;
        ny = ny2;
    }
    let amp = amplitude(&z, scale);
    let slope = rms_gradient(&z, nx, ny, m.dx, m.dy, params.derivative);
    let heights = map_heights(&z);
    let length = (nx - 1) as f64 * m.dx;
    let fp = params.fractal;
    let (dx, dy) = (m.dx, m.dy);
    let zr = &z;
    Ok(finish(
        &m.source,
        SurfaceKind::Areal,
        &z,
        length,
        Evaluated {
            amp,
            slope,
            heights,
        },
        || map_dimension(zr, nx, ny, dx, dy, &fp),
        params,
    ))
}
