//! Numeric 1-D ALSFM (thesis Sec. 1.3, Eq. 1.23–1.35; MODELS.md §5 "Numeric
//! set-up"): surfaces z = f(x) extruded along y.
//!
//! Lattice points sit at fixed x_i = (i + ½) Δ over a window W holding whole
//! periods of both surfaces (Δ = W / n, so no point falls on a wedge kink).
//! The upper body is shifted by s_x = s cos β after a sliding distance s. At
//! each instant a point has length l = d + z2(x − s_x) − z1(x) and
//! compression u = l0 − l; the spring attached to the upper body slides on z1
//! with φ = atan z1'(x), the one attached to the lower body slides on z2 with
//! φ = atan z2'(x − s_x); both are positive when the contact resists the
//! motion. The separation d carries the load L (see [`super::separation`]).
//!
//! The configuration repeats after the upper surface's period P2 along x, that
//! is a sliding distance P2 / |cos β|; one period is sampled with `steps`
//! instants (default: one per lattice spacing, so that the upper surface's
//! samples are the same at every instant and only their index rolls). At
//! β = 90° (cos β = 0) or with a flat upper surface nothing changes in time and
//! one instant is evaluated.

use super::instant::{resolve_instant, slope_ok, Instant, Locked, Ratios, SpringParams};
use super::local_law::local_law_unchecked;
use super::series::{common_period, cos_sin_deg, ContactMap, Series};
use super::surface::Surface;
use crate::error::{Error, Result};
use crate::status::Code;

/// A contact to evaluate: two surfaces, the local law and the load.
#[derive(Debug, Clone, Copy)]
pub struct Contact<'a> {
    /// Lower surface z1.
    pub z1: &'a Surface,
    /// Upper surface z2 (the one that slides).
    pub z2: &'a Surface,
    /// μ0, local coefficient, ≥ 0.
    pub mu0: f64,
    /// β, degrees, sliding direction from x.
    pub beta_deg: f64,
    /// Spring parameters.
    pub springs: SpringParams,
    /// L, N per spring (mean axial force).
    pub load: f64,
}

/// Lattice resolution.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Lattice {
    /// Lattice points along x over the window, ≥ 1.
    pub nx: usize,
    /// Lattice points along y over the window (2-D only), ≥ 1.
    pub ny: usize,
    /// Instants per period of relative motion; `None`: one per lattice
    /// spacing along the sliding direction.
    pub steps: Option<usize>,
    /// Instants at which to keep the spring forces (contact maps).
    pub record: Vec<usize>,
}

/// The error for a load that no separation carries.
pub fn no_contact(load: f64) -> Error {
    Error::coded(
        Code::NoContact,
        format!(
            "no contact: load per spring L = {load} is not > 0 and adhesion is off (no spring can \
         carry tension)"
        ),
    )
}

/// Resolves the instants of a series one after another, with reusable
/// scratch, and keeps the contact maps of the instants in `record`.
pub(crate) struct Recorder<'a> {
    springs: SpringParams,
    load: f64,
    record: &'a [usize],
    scratch: Vec<f64>,
    forces: Vec<f64>,
    /// The contact maps kept so far.
    pub maps: Vec<ContactMap>,
}

impl<'a> Recorder<'a> {
    /// For contact `c` on a lattice of `n` points.
    pub fn new(c: &Contact, record: &'a [usize], n: usize) -> Self {
        Recorder {
            springs: c.springs,
            load: c.load,
            record,
            scratch: Vec::with_capacity(n),
            forces: Vec::new(),
            maps: Vec::new(),
        }
    }

    /// Instant `step` from compressions `cbuf` and ratios `hbuf`; its map
    /// (at lattice points `x`, `y`) is kept when asked for.
    pub fn resolve(
        &mut self,
        step: usize,
        cbuf: &[f64],
        hbuf: &[Ratios],
        x: &[f64],
        y: &[f64],
    ) -> Result<Instant> {
        let want = self.record.contains(&step);
        let inst = resolve_instant(
            cbuf,
            hbuf,
            &self.springs,
            self.load,
            &mut self.scratch,
            want.then_some(&mut self.forces),
        )
        .ok_or_else(|| no_contact(self.load))?;
        if want {
            self.maps.push(ContactMap {
                step,
                x: x.to_vec(),
                y: y.to_vec(),
                force: self.forces.clone(),
            });
        }
        Ok(inst)
    }
}

/// Heights and local-law ratios (hx, hy) at the lattice points.
type Sampled = (Vec<f64>, Vec<(f64, f64)>);

/// A surface sampled at the lattice points; the point and slope of the
/// first spring the law locks, as the error.
fn sample_surface(
    c: &Contact,
    surface: &Surface,
    xs: &[f64],
    (cb, sb): (f64, f64),
) -> std::result::Result<Sampled, (f64, f64)> {
    let mut z = Vec::with_capacity(xs.len());
    let mut h = Vec::with_capacity(xs.len());
    for &x in xs {
        let t = surface.gradient(x, 0.0).0;
        let r = local_law_unchecked(c.mu0, t, cb, sb);
        if !slope_ok(c.mu0, t, r.d) {
            return Err((x, t));
        }
        z.push(surface.height(x, 0.0));
        h.push((r.hx, r.hy));
    }
    Ok((z, h))
}

/// The relative motion along x: the upper surface's period (none when it
/// is flat or the motion is across x), the instants per period, the shift
/// per instant, and that shift in whole lattice spacings when it is one.
struct Motion {
    p2: Option<f64>,
    m: usize,
    step_x: f64,
    roll: Option<usize>,
}

fn motion(c: &Contact, lattice: &Lattice, dx: f64, cb: f64) -> Result<Motion> {
    let p2 = match c.z2.period_x() {
        Some(p) if cb != 0.0 && !c.z2.is_flat() => Some(p),
        _ => None,
    };
    let m = match p2 {
        None => 1,
        Some(p) => lattice
            .steps
            .unwrap_or_else(|| ((p / dx).round() as usize).max(1)),
    };
    if m == 0 {
        return Err(Error::Config("steps per period must be >= 1".into()));
    }
    let step_x = p2.map_or(0.0, |p| p / m as f64) * cb.signum();
    let roll = {
        let r = step_x.abs() / dx;
        ((r - r.round()).abs() < 1e-9).then_some(r.round() as usize)
    };
    Ok(Motion {
        p2,
        m,
        step_x,
        roll,
    })
}

/// Runs the 1-D model over one period of relative motion.
pub fn simulate_1d(c: &Contact, lattice: &Lattice) -> Result<Series> {
    if lattice.nx == 0 {
        return Err(Error::Config(
            "the lattice needs at least one point along x".into(),
        ));
    }
    let n = lattice.nx;
    let (cb, sb) = cos_sin_deg(c.beta_deg);
    let w = common_period(c.z1.period_x(), c.z2.period_x(), "x")?.unwrap_or(1.0);
    let dx = w / n as f64;
    let xs: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) * dx).collect();
    let lock = |surface: u8, x: f64, t: f64| {
        Locked {
            surface,
            x,
            y: 0.0,
            tan_phi: t.abs(),
        }
        .to_error(c.mu0, c.beta_deg)
    };
    // Lower surface: fixed, evaluated once; the upper at the lattice points
    // with zero shift, for rolling.
    let (z1, h1) = sample_surface(c, c.z1, &xs, (cb, sb)).map_err(|(x, t)| lock(1, x, t))?;
    let (z2, h2) = sample_surface(c, c.z2, &xs, (cb, sb)).map_err(|(x, t)| lock(2, x, t))?;
    let Motion {
        p2,
        m,
        step_x,
        roll,
    } = motion(c, lattice, dx, cb)?;
    let mut cbuf = vec![0.0; n];
    let mut hbuf: Vec<Ratios> = vec![[0.0; 4]; n];
    let mut rec = Recorder::new(c, &lattice.record, n);
    let ys = vec![0.0; n];
    let mut instants = Vec::with_capacity(m);
    for j in 0..m {
        let sx = step_x * j as f64;
        match roll {
            Some(r) => {
                let k = (j * r) % n;
                for i in 0..n {
                    // x_i − s_x = x_{i ∓ k}: the upper samples roll.
                    let src = if cb >= 0.0 {
                        (i + n - k) % n
                    } else {
                        (i + k) % n
                    };
                    cbuf[i] = c.springs.l0 - (z2[src] - z1[i]);
                    hbuf[i] = [h1[i].0, h1[i].1, h2[src].0, h2[src].1];
                }
            }
            None => {
                for i in 0..n {
                    let xr = xs[i] - sx;
                    let t = c.z2.gradient(xr, 0.0).0;
                    let r = local_law_unchecked(c.mu0, t, cb, sb);
                    if !slope_ok(c.mu0, t, r.d) {
                        return Err(lock(2, xr, t));
                    }
                    cbuf[i] = c.springs.l0 - (c.z2.height(xr, 0.0) - z1[i]);
                    hbuf[i] = [h1[i].0, h1[i].1, r.hx, r.hy];
                }
            }
        }
        instants.push(rec.resolve(j, &cbuf, &hbuf, &xs, &ys)?);
    }
    let period = p2.map(|p| p / cb.abs());
    Ok(Series {
        distance: (0..m)
            .map(|j| period.map_or(0.0, |p| p * j as f64 / m as f64))
            .collect(),
        instants,
        period,
        springs: n,
        cos_sin: (cb, sb),
        whole_periods: true,
        maps: rec.maps,
    })
}
