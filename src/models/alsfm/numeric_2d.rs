//! Numeric 2-D ALSFM (thesis Sec. 1.4, Eq. 1.36–1.42; MODELS.md §5):
//! surfaces z = f(x, y).
//!
//! Lattice points sit at (x_i, y_j) = ((i + ½) Δx, (j + ½) Δy) over a window
//! holding whole periods of both surfaces in x and y. After a sliding
//! distance s the upper body is shifted by (s cos β, s sin β). Each spring
//! uses the tangent plane of the surface it slides on: tan φ = |∇z|, the
//! steepest direction α_P = atan2(∂z/∂y, ∂z/∂x), the local law with
//! β' = β − α_P and the rotation back by α_P
//! ([`super::local_law::local_law_2d`]). Everything else is as in 1-D.
//!
//! Period of the relative motion: P2x / |cos β| when only x matters,
//! P2y / |sin β| when only y matters; otherwise the smallest s with
//! s |cos β| = a P2x and s |sin β| = b P2y for whole a, b ≤ 16. When there is
//! none (an irrational direction), 16 such spans are averaged and
//! `whole_periods` is false.

use super::instant::{slope_ok, Locked, Ratios};
use super::local_law::local_law_2d;
use super::numeric_1d::{Contact, Lattice, Recorder};
use super::series::{common_period, cos_sin_deg, Series};
use crate::error::{Error, Result};

/// Largest number of instants per average in 2-D.
pub const MAX_STEPS_2D: usize = 4096;

/// Runs the 2-D model over one period of relative motion.
pub fn simulate_2d(c: &Contact, lattice: &Lattice) -> Result<Series> {
    let (nx, ny) = (lattice.nx, lattice.ny);
    if nx == 0 || ny == 0 {
        return Err(Error::Config(format!(
            "the 2-D lattice needs at least one point along x and y, got {nx} x {ny}"
        )));
    }
    let (cb, sb) = cos_sin_deg(c.beta_deg);
    let wx = common_period(c.z1.period_x(), c.z2.period_x(), "x")?.unwrap_or(1.0);
    let wy = common_period(c.z1.period_y(), c.z2.period_y(), "y")?.unwrap_or(wx);
    let (dx, dy) = (wx / nx as f64, wy / ny as f64);
    let n = nx * ny;
    let mut xs = Vec::with_capacity(n);
    let mut ys = Vec::with_capacity(n);
    for j in 0..ny {
        for i in 0..nx {
            xs.push((i as f64 + 0.5) * dx);
            ys.push((j as f64 + 0.5) * dy);
        }
    }
    let locked = |surface: u8, x: f64, y: f64, g: (f64, f64)| {
        Locked {
            surface,
            x,
            y,
            tan_phi: g.0.hypot(g.1),
        }
        .to_error(c.mu0, c.beta_deg)
    };
    let mut z1 = Vec::with_capacity(n);
    let mut h1 = Vec::with_capacity(n);
    for k in 0..n {
        let g = c.z1.gradient(xs[k], ys[k]);
        let r = local_law_2d(c.mu0, g.0, g.1, cb, sb)
            .filter(|_| slope_ok(c.mu0, g.0.hypot(g.1), 1.0))
            .ok_or_else(|| locked(1, xs[k], ys[k], g))?;
        z1.push(c.z1.height(xs[k], ys[k]));
        h1.push(r);
    }
    let (distance, whole) = motion_period(c, cb, sb);
    let m = match distance {
        None => 1,
        Some(p) => lattice
            .steps
            .unwrap_or_else(|| ((p / dx.min(dy)).round() as usize).clamp(1, MAX_STEPS_2D)),
    };
    if m == 0 {
        return Err(Error::Config("steps per period must be >= 1".into()));
    }
    let mut cbuf = vec![0.0; n];
    let mut hbuf: Vec<Ratios> = vec![[0.0; 4]; n];
    let mut rec = Recorder::new(c, &lattice.record, n);
    let mut instants = Vec::with_capacity(m);
    let mut dist = Vec::with_capacity(m);
    for step in 0..m {
        let s = distance.map_or(0.0, |p| p * step as f64 / m as f64);
        dist.push(s);
        let (sx, sy) = (s * cb, s * sb);
        for k in 0..n {
            let (xr, yr) = (xs[k] - sx, ys[k] - sy);
            let g = c.z2.gradient(xr, yr);
            let r = local_law_2d(c.mu0, g.0, g.1, cb, sb)
                .filter(|_| slope_ok(c.mu0, g.0.hypot(g.1), 1.0))
                .ok_or_else(|| locked(2, xr, yr, g))?;
            cbuf[k] = c.springs.l0 - (c.z2.height(xr, yr) - z1[k]);
            hbuf[k] = [h1[k].0, h1[k].1, r.0, r.1];
        }
        instants.push(rec.resolve(step, &cbuf, &hbuf, &xs, &ys)?);
    }
    Ok(Series {
        distance: dist,
        instants,
        period: distance,
        springs: n,
        cos_sin: (cb, sb),
        whole_periods: whole,
        maps: rec.maps,
    })
}

/// Sliding distance over which the configuration repeats, and whether it is
/// an exact period.
fn motion_period(c: &Contact, cb: f64, sb: f64) -> (Option<f64>, bool) {
    if c.z2.is_flat() {
        return (None, true);
    }
    let px = c.z2.period_x().filter(|_| cb != 0.0);
    let py =
        c.z2.period_y()
            .filter(|_| sb != 0.0 && !c.z2.is_y_invariant());
    match (px, py) {
        (None, None) => (None, true),
        (Some(p), None) => (Some(p / cb.abs()), true),
        (None, Some(p)) => (Some(p / sb.abs()), true),
        (Some(px), Some(py)) => {
            let (ux, uy) = (px / cb.abs(), py / sb.abs());
            for a in 1..=16u32 {
                let s = ux * a as f64;
                let b = (s / uy).round();
                if b >= 1.0 && (b * uy - s).abs() <= 1e-9 * s {
                    return (Some(s), true);
                }
            }
            (Some(16.0 * ux.max(uy)), false)
        }
    }
}
