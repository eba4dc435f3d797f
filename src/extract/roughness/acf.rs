//! The autocorrelation function of a map or profile and the spatial
//! parameters read from it: Sal and Str (ISO 25178-2, MODELS.md §10).
//!
//! # ACF
//! f(t) = R(t) / R(0) with R(t) = Σ h(r) h(r + t) / N(t), the sum over the
//! N(t) pairs of measured points at lag t (the unbiased, linear estimator:
//! each lag is divided by its own number of pairs, so neither the edges
//! wrap around nor the large lags shrink; surfalize's estimator, and with
//! points not measured the pairs simply fewer). Computed by FFT on the map
//! zero-padded to twice its size (to a power of two); N(t) is
//! (n_x − |t_x|)(n_y − |t_y|) without gaps, and the autocorrelation of the
//! mask with them. A surface stated periodic uses the circular estimator
//! (all n pairs at every lag, lags up to half the size).
//!
//! # Sal, Str
//! Along a ray from the origin at angle θ, the decay length r(θ) is the
//! first distance where f (bilinear between lags) falls to s = 0.2 (ISO
//! 25178-3 default), located by bisection after steps of half a sample.
//! Rays every 0.25° over [0°, 180°) (f is even); the extremes are refined
//! by a parabola through the three rays around them. Sal = min r(θ); Str =
//! min r / max r when f decays in every direction within the measured lags,
//! else undefined (the slowest decay lies outside the data, as along the
//! lay of a 1-D texture: surfalize's `nan` choice); Sal is undefined when f
//! decays in no direction.

use rayon::prelude::*;

use crate::signal::fft2::{irfft2_rows, rfft2, HalfSpectrum};

/// ISO 25178-3 default threshold s of Sal and Str.
pub const DEFAULT_THRESHOLD: f64 = 0.2;

/// Angular step of the rays (degrees).
const RAY_STEP_DEG: f64 = 0.25;

/// A normalised ACF on the lags |ix| ≤ lx, |iy| ≤ ly (in samples).
#[derive(Debug, Clone)]
pub struct Acf {
    /// Largest lag along x (samples).
    pub lx: usize,
    /// Largest lag along y (samples); 0 for a profile.
    pub ly: usize,
    /// Spacing along x (m).
    pub dx: f64,
    /// Spacing along y (m).
    pub dy: f64,
    /// Row-major, (2 ly + 1) × (2 lx + 1), lag (0, 0) at the centre; NaN
    /// where no pair of measured points exists.
    values: Vec<f64>,
}

impl Acf {
    /// f at the lag (ix, iy) in samples, |ix| ≤ lx, |iy| ≤ ly.
    pub fn at(&self, ix: isize, iy: isize) -> f64 {
        let w = 2 * self.lx + 1;
        self.values[(iy + self.ly as isize) as usize * w + (ix + self.lx as isize) as usize]
    }

    /// f at the lag (tx, ty) in metres, bilinear between lags; `None`
    /// outside the lags held or where a corner is undefined.
    pub fn bilinear(&self, tx: f64, ty: f64) -> Option<f64> {
        let (fx, fy) = (tx / self.dx, if self.ly == 0 { 0.0 } else { ty / self.dy });
        let (lx, ly) = (self.lx as f64, self.ly as f64);
        if fx.abs() > lx || fy.abs() > ly {
            return None;
        }
        let (x0, y0) = (
            fx.floor().min(lx - 1.0).max(-lx),
            fy.floor().min(ly - 1.0).max(-ly),
        );
        let (ax, ay) = (fx - x0, fy - y0);
        let (i, j) = (x0 as isize, y0 as isize);
        let v = if self.ly == 0 {
            self.at(i, 0) * (1.0 - ax) + self.at(i + 1, 0) * ax
        } else {
            let f00 = self.at(i, j);
            let f10 = self.at(i + 1, j);
            let f01 = self.at(i, j + 1);
            let f11 = self.at(i + 1, j + 1);
            (f00 * (1.0 - ax) + f10 * ax) * (1.0 - ay) + (f01 * (1.0 - ax) + f11 * ax) * ay
        };
        (!v.is_nan()).then_some(v)
    }

    /// f along x at lags 0..=k (samples).
    pub fn along_x(&self, k: usize) -> Vec<f64> {
        (0..=k.min(self.lx))
            .map(|i| self.at(i as isize, 0))
            .collect()
    }

    /// f averaged over rings of width `w` (m) about the origin (ring k
    /// holds the lags with radius in [(k − ½) w, (k + ½) w)), out to `rmax`
    /// (m): (mean radius, mean f) of each non-empty ring.
    pub fn radial(&self, rmax: f64, w: f64) -> Vec<(f64, f64)> {
        // A lag exactly on a ring's edge or on r_max (a 3-4-5 lag at
        // r_max = 50 Δ), and r_max on a ring's centre, are computed a few
        // ulps to either side: taken a hair longer, each goes where exact
        // arithmetic puts it, whatever the spacing (without, ~10 % of such
        // lags fell out of the last ring for random spacings, and at some
        // spacings the last ring itself).
        let tie = 1.0 + 1e-12;
        let rings = (rmax * tie / w).floor() as usize + 1;
        let mut sums = vec![(0.0, 0.0, 0usize); rings];
        for iy in -(self.ly as isize)..=self.ly as isize {
            for ix in -(self.lx as isize)..=self.lx as isize {
                let r = ((ix as f64 * self.dx).powi(2) + (iy as f64 * self.dy).powi(2)).sqrt();
                let f = self.at(ix, iy);
                let k = (r * tie / w + 0.5).floor() as usize;
                if k < rings && !f.is_nan() && r <= rmax * tie {
                    sums[k] = (sums[k].0 + r, sums[k].1 + f, sums[k].2 + 1);
                }
            }
        }
        sums.into_iter()
            .filter(|s| s.2 > 0)
            .map(|s| (s.0 / s.2 as f64, s.1 / s.2 as f64))
            .collect()
    }
}

/// The half spectrum's power abs(F)², as a spectrum again (imaginary 0).
fn power(mut s: HalfSpectrum) -> HalfSpectrum {
    s.data
        .par_iter_mut()
        .for_each(|v| *v = (v.0 * v.0 + v.1 * v.1, 0.0));
    s
}

/// The circular autocorrelation Σ h(r) h(r + t) of a row-major map padded
/// to p × q, at the lags |iy| ≤ ly, |ix| ≤ lx, centred.
fn correlate(
    h: &[f64],
    nx: usize,
    ny: usize,
    (p, q): (usize, usize),
    (lx, ly): (usize, usize),
) -> Vec<f64> {
    let rows: Vec<usize> = (-(ly as isize)..=ly as isize)
        .map(|iy| iy.rem_euclid(p as isize) as usize)
        .collect();
    let mut out = irfft2_rows(power(rfft2(h, nx, ny, p, q)), &rows);
    // Compact each row in place to the lags −lx..=lx (stride 2 lx + 1): when
    // that is ≤ q, row i's new place overlaps only rows ≤ i, already moved;
    // a periodic map's lags (q + 1 of them for even q) need more room.
    let w = 2 * lx + 1;
    if w > q {
        out.resize(rows.len() * w.max(q), 0.0);
        let src = out.clone();
        for i in 0..rows.len() {
            for j in 0..w {
                let ix = j as isize - lx as isize;
                out[i * w + j] = src[i * q + ix.rem_euclid(q as isize) as usize];
            }
        }
        out.truncate(rows.len() * w);
        return out;
    }
    let mut tmp = vec![0.0; q];
    for i in 0..rows.len() {
        tmp.copy_from_slice(&out[i * q..(i + 1) * q]);
        for j in 0..w {
            let ix = j as isize - lx as isize;
            out[i * w + j] = tmp[ix.rem_euclid(q as isize) as usize];
        }
    }
    out.truncate(rows.len() * w);
    out
}

/// The normalised ACF of a row-major `ny × nx` map (a profile: `ny = 1`),
/// NaN for a point not measured; `None` when the measured heights have no
/// variance.
pub fn acf(z: &[f64], nx: usize, ny: usize, dx: f64, dy: f64, periodic: bool) -> Option<Acf> {
    let gaps = z.iter().any(|v| v.is_nan());
    let h: Vec<f64> = z
        .iter()
        .map(|&v| if v.is_nan() { 0.0 } else { v })
        .collect();
    let (pq, lags) = match periodic {
        true => ((ny, nx), (nx / 2, ny / 2)),
        false => {
            let pad = |n: usize| (2 * n - 1).next_power_of_two();
            ((pad(ny).max(1), pad(nx)), (nx - 1, ny - 1))
        }
    };
    let r = correlate(&h, nx, ny, pq, lags);
    let (lx, ly) = lags;
    let w = 2 * lx + 1;
    let counts: Vec<f64> = match (gaps, periodic) {
        (true, _) => {
            let m: Vec<f64> = z.iter().map(|v| f64::from(u8::from(!v.is_nan()))).collect();
            correlate(&m, nx, ny, pq, lags)
                .into_iter()
                .map(|c| c.round())
                .collect()
        }
        (false, true) => vec![(nx * ny) as f64; r.len()],
        (false, false) => (0..r.len())
            .map(|k| {
                let (iy, ix) = (
                    (k / w) as isize - ly as isize,
                    (k % w) as isize - lx as isize,
                );
                ((nx as isize - ix.abs()) * (ny as isize - iy.abs())) as f64
            })
            .collect(),
    };
    let mut values: Vec<f64> = r
        .iter()
        .zip(&counts)
        .map(|(&v, &c)| if c > 0.0 { v / c } else { f64::NAN })
        .collect();
    let r0 = values[ly * w + lx];
    if r0.is_nan() || r0 <= 0.0 {
        return None;
    }
    values.iter_mut().for_each(|v| *v /= r0);
    Some(Acf {
        lx,
        ly,
        dx,
        dy,
        values,
    })
}

/// Decay lengths of an areal ACF.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Decay {
    /// Sal (m): the fastest decay to s; `None` when f decays in no
    /// direction within the lags held.
    pub sal: Option<f64>,
    /// Str = Sal / slowest decay, in (0, 1]; `None` when f does not decay
    /// in some direction within the lags held.
    pub str_ratio: Option<f64>,
    /// Direction of the fastest decay (degrees from x, counter-clockwise,
    /// in [0, 180)).
    pub fastest_deg: Option<f64>,
    /// Rays (of 720) along which f did not decay to s.
    pub undecayed_rays: usize,
}

/// r(θ): the first distance along the ray at `theta` (radians) where f
/// falls to `s`; `None` when the ray leaves the lags held first.
fn decay_along(acf: &Acf, theta: f64, s: f64) -> Option<f64> {
    let (c, sn) = (theta.cos(), theta.sin());
    // Half a pixel along the ray. With unequal spacings, half a pixel in
    // index space: half the smaller spacing made a ray across a map of
    // 1e-7 × 0.08 m pixels take ~1e10 steps (found by the fuzz harness).
    let h = match acf.ly == 0 || acf.dx.to_bits() == acf.dy.to_bits() {
        true => 0.5 * acf.dx,
        false => 0.5 / ((c / acf.dx).powi(2) + (sn / acf.dy).powi(2)).sqrt(),
    };
    // A spacing so small or large that the step is not a finite positive
    // number (1e-310 m overflows 1/dx) leaves no ray to walk.
    if !(h > 0.0 && h.is_finite()) {
        return None;
    }
    let f = |t: f64| acf.bilinear(t * c, t * sn);
    // Half a pixel a step crosses the lags within 2 (lx + ly) + 2 steps;
    // the bound holds when rounding would stall t (found by the fuzz
    // harness: a step that rounds to nothing looped forever).
    let mut t = 0.0;
    for _ in 0..2 * (acf.lx + acf.ly) + 4 {
        let next = t + h;
        match f(next) {
            None => return None,
            Some(v) if v <= s => {
                let (mut a, mut b) = (t, next);
                for _ in 0..40 {
                    let m = 0.5 * (a + b);
                    match f(m) {
                        Some(v) if v > s => a = m,
                        _ => b = m,
                    }
                }
                return Some(0.5 * (a + b));
            }
            Some(_) => t = next,
        }
    }
    None
}

/// The vertex of the parabola through (−1, a), (0, b), (1, c): its offset
/// in [−1, 1] and its value.
fn vertex(a: f64, b: f64, c: f64) -> (f64, f64) {
    let d = a - 2.0 * b + c;
    if d == 0.0 {
        return (0.0, b);
    }
    let u = (0.5 * (a - c) / d).clamp(-1.0, 1.0);
    (u, b - 0.25 * (a - c) * u)
}

/// Sal, Str and the direction of the fastest decay of an areal ACF at
/// threshold `s`.
pub fn decay(acf: &Acf, s: f64) -> Decay {
    let n = (180.0 / RAY_STEP_DEG).round() as usize;
    let step = RAY_STEP_DEG.to_radians();
    let r: Vec<Option<f64>> = (0..n)
        .into_par_iter()
        .map(|k| decay_along(acf, k as f64 * step, s))
        .collect();
    let undecayed = r.iter().filter(|v| v.is_none()).count();
    let decayed: Vec<(usize, f64)> = r
        .iter()
        .enumerate()
        .filter_map(|(k, v)| v.map(|v| (k, v)))
        .collect();
    let Some(&(kmin, _)) = decayed.iter().min_by(|a, b| a.1.total_cmp(&b.1)) else {
        return Decay {
            sal: None,
            str_ratio: None,
            fastest_deg: None,
            undecayed_rays: undecayed,
        };
    };
    // Refine an extreme with its two neighbouring rays (the circle wraps).
    let refine = |k: usize| {
        let at = |j: isize| r[j.rem_euclid(n as isize) as usize];
        match (at(k as isize - 1), at(k as isize), at(k as isize + 1)) {
            (Some(a), Some(b), Some(c)) => vertex(a, b, c),
            (_, b, _) => (0.0, b.unwrap_or(f64::NAN)),
        }
    };
    let (u, sal) = refine(kmin);
    let fastest = ((kmin as f64 + u) * RAY_STEP_DEG).rem_euclid(180.0);
    let str_ratio = (undecayed == 0).then(|| {
        let kmax = decayed
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map_or(0, |v| v.0);
        let (_, longest) = refine(kmax);
        (sal / longest).min(1.0)
    });
    Decay {
        sal: Some(sal),
        str_ratio,
        fastest_deg: Some(fastest),
        undecayed_rays: undecayed,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// Lags on a ring's edge or on r_max are ringed as in integers, for
    /// any spacing: the last ring's mean lag (ring 50 of width Δ out to
    /// 50 Δ: 49.5 ≤ √(i² + j²) ≤ 50, the 3-4-5 lags included) is the
    /// exact one, counted in integers, for 300 spacings.
    #[test]
    fn ring_edges_hold_for_any_spacing() {
        let n = 50isize;
        let exact: Vec<f64> = (-n..=n)
            .flat_map(|i| (-n..=n).map(move |j| i * i + j * j))
            .filter(|&r2| 4 * r2 >= 99 * 99 && r2 <= n * n)
            .map(|r2| (r2 as f64).sqrt())
            .collect();
        let mean = exact.iter().sum::<f64>() / exact.len() as f64;
        let (lx, ly) = (n as usize, n as usize);
        let f = vec![1.0; (2 * lx + 1) * (2 * ly + 1)];
        for k in 0..300 {
            let d = 1e-7 * (1.0 + 0.0137 * k as f64);
            let a = Acf {
                values: f.clone(),
                lx,
                ly,
                dx: d,
                dy: d,
            };
            let rings = a.radial(n as f64 * d, d);
            let last = rings.last().unwrap().0;
            assert!(
                (last / (mean * d) - 1.0).abs() < 1e-12,
                "Δ {d}: {last} vs {}",
                mean * d
            );
        }
    }

    /// Spacings whose half-pixel step overflows or rounds to nothing end
    /// each ray (no decay found) instead of walking it forever; a sane
    /// spacing on the same map still decays.
    #[test]
    fn degenerate_spacings_end_every_ray() {
        let (nx, ny) = (16usize, 12usize);
        let z: Vec<f64> = (0..nx * ny).map(|i| ((i * 37 % 11) as f64) - 5.0).collect();
        for (dx, dy) in [
            (1e-310, 1.0),
            (1.0, 1e-310),
            (1e-310, 1e300),
            (1e300, 1e-300),
        ] {
            let a = acf(&z, nx, ny, dx, dy, false).unwrap();
            let d = decay(&a, 0.2);
            assert!(d.sal.is_none_or(f64::is_finite), "{dx} {dy}: {:?}", d.sal);
        }
        let a = acf(&z, nx, ny, 1e-6, 2e-6, false).unwrap();
        assert!(decay(&a, 0.2).sal.is_some_and(|s| s > 0.0 && s.is_finite()));
    }

    #[test]
    fn acf_of_a_periodic_sine_is_the_cosine() {
        // z = sin(2π x / λ) on whole periods, periodic: f(t) = cos(2π t/λ)
        // exactly (circular estimator over whole periods).
        let (n, per) = (256usize, 32usize);
        let z: Vec<f64> = (0..n)
            .map(|i| (2.0 * PI * i as f64 / per as f64).sin())
            .collect();
        let a = acf(&z, n, 1, 1.0, 1.0, true).unwrap();
        for k in 0..=n / 2 {
            let want = (2.0 * PI * k as f64 / per as f64).cos();
            assert!((a.at(k as isize, 0) - want).abs() < 1e-12, "lag {k}");
        }
    }

    #[test]
    fn linear_estimator_divides_each_lag_by_its_pairs() {
        // Direct sums against the FFT, with and without points not
        // measured, on a small map.
        let (nx, ny) = (9usize, 7usize);
        let mut z: Vec<f64> = (0..nx * ny).map(|i| ((i * 37 % 13) as f64) - 6.0).collect();
        for gaps in [false, true] {
            if gaps {
                z[10] = f64::NAN;
                z[33] = f64::NAN;
            }
            let a = acf(&z, nx, ny, 1.0, 2.0, false).unwrap();
            let direct = |ix: isize, iy: isize| {
                let (mut s, mut k) = (0.0, 0);
                for r in 0..ny as isize {
                    for c in 0..nx as isize {
                        let (r2, c2) = (r + iy, c + ix);
                        if r2 < 0 || c2 < 0 || r2 >= ny as isize || c2 >= nx as isize {
                            continue;
                        }
                        let (u, v) = (
                            z[(r * nx as isize + c) as usize],
                            z[(r2 * nx as isize + c2) as usize],
                        );
                        if !(u.is_nan() || v.is_nan()) {
                            s += u * v;
                            k += 1;
                        }
                    }
                }
                s / k as f64
            };
            let r0 = direct(0, 0);
            for iy in -(ny as isize - 1)..ny as isize {
                for ix in -(nx as isize - 1)..nx as isize {
                    let want = direct(ix, iy) / r0;
                    assert!(
                        (a.at(ix, iy) - want).abs() < 1e-12,
                        "({ix}, {iy}) gaps {gaps}"
                    );
                }
            }
        }
    }
}
