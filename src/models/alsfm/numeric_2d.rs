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
//!
//! Speed: when the shift per instant is a whole number of lattice cells in
//! x and y (the default instants at β = 0 or 90°, or any commensurate
//! direction), the upper surface is sampled once on the lattice and each
//! instant reads its samples by a rolled index instead of evaluating the
//! surface again; the coordinates then differ from x − s_x only by rounding
//! (results agree to 1e-12, tested). A sinusoid shifted by a fraction of a
//! cell is evaluated from per-column and per-row parts (O(n_x + n_y)
//! trigonometric calls per instant), and every spring's law in the closed
//! form of [`tangent_plane_ratios`] (two roots and a division, branch-free).
//! The reference path ([`simulate_2d_with`] with `sample_once = false`)
//! evaluates every point and takes the law by the thesis' rotation form.
//! Instants are independent and are resolved in parallel, each into its own
//! slot, so the series does not depend on the thread count.

use rayon::prelude::*;

use super::instant::{resolve_instant, slope_ok, Instant, Locked, Ratios};
use super::local_law::{local_law_2d, tangent_plane_ratios};
use super::numeric_1d::{no_contact, Contact, Lattice};
use super::series::{common_period, cos_sin_deg, ContactMap, Series};
use crate::error::{Error, Result};

/// Largest number of instants per average in 2-D.
pub const MAX_STEPS_2D: usize = 4096;

/// Lattice points, spacing and the sliding direction.
struct Grid {
    nx: usize,
    ny: usize,
    dx: f64,
    dy: f64,
    xs: Vec<f64>,
    ys: Vec<f64>,
    cb: f64,
    sb: f64,
}

impl Grid {
    fn new(c: &Contact, nx: usize, ny: usize) -> Result<Self> {
        let (cb, sb) = cos_sin_deg(c.beta_deg);
        let wx = common_period(c.z1.period_x(), c.z2.period_x(), "x")?.unwrap_or(1.0);
        let wy = common_period(c.z1.period_y(), c.z2.period_y(), "y")?.unwrap_or(wx);
        let (dx, dy) = (wx / nx as f64, wy / ny as f64);
        let (mut xs, mut ys) = (Vec::with_capacity(nx * ny), Vec::with_capacity(nx * ny));
        for j in 0..ny {
            for i in 0..nx {
                xs.push((i as f64 + 0.5) * dx);
                ys.push((j as f64 + 0.5) * dy);
            }
        }
        Ok(Grid {
            nx,
            ny,
            dx,
            dy,
            xs,
            ys,
            cb,
            sb,
        })
    }
}

/// The error of a spring on `surface` at (x, y) with gradient `g`.
fn locked(c: &Contact, surface: u8, x: f64, y: f64, g: (f64, f64)) -> Error {
    Locked {
        surface,
        x,
        y,
        tan_phi: g.0.hypot(g.1),
    }
    .to_error(c.mu0, c.beta_deg)
}

/// Reaction ratios of the local law on a surface with gradient `g`, `None`
/// where the surfaces lock (D ≤ 0 or μ0 tan φ ≥ 1).
fn ratios(c: &Contact, g: (f64, f64), cb: f64, sb: f64) -> Option<(f64, f64)> {
    let (hx, hy, ok) = tangent_plane_ratios(c.mu0, g.0, g.1, cb, sb);
    ok.then_some((hx, hy))
}

/// [`ratios`] by the thesis' own steps (local frame, law, rotation back;
/// [`local_law_2d`]): the reference path's law, independent of the closed
/// form.
fn ratios_by_rotation(c: &Contact, g: (f64, f64), cb: f64, sb: f64) -> Option<(f64, f64)> {
    local_law_2d(c.mu0, g.0, g.1, cb, sb).filter(|_| slope_ok(c.mu0, g.0.hypot(g.1), 1.0))
}

/// How a spring's ratios are computed from its gradient.
type Law = fn(&Contact, (f64, f64), f64, f64) -> Option<(f64, f64)>;

/// Heights and ratios of a surface at the lattice points (ratios `None`
/// where it locks).
fn sample(
    c: &Contact,
    z: &super::surface::Surface,
    grid: &Grid,
    law: Law,
) -> (Vec<f64>, Vec<Option<(f64, f64)>>) {
    (0..grid.xs.len())
        .map(|k| {
            let (x, y) = (grid.xs[k], grid.ys[k]);
            (z.height(x, y), law(c, z.gradient(x, y), grid.cb, grid.sb))
        })
        .unzip()
}

/// The upper surface at each instant: sampled once and rolled by whole
/// cells, or evaluated at the shifted points.
enum Upper {
    Sampled {
        z: Vec<f64>,
        h: Vec<Option<(f64, f64)>>,
        /// Cells the upper body moves per instant along x and y.
        cells: (i64, i64),
    },
    /// A sinusoid: per-instant factors of each column and row.
    Separable,
    Analytic,
}

impl Upper {
    /// Sampled when the shift per instant, `step_len` (cos β, sin β), is a
    /// whole number of cells (to 1e-13 of a cell).
    fn new(c: &Contact, grid: &Grid, step_len: f64, sample_once: bool) -> Self {
        let (ax, ay) = (step_len * grid.cb / grid.dx, step_len * grid.sb / grid.dy);
        let whole = |a: f64| (a - a.round()).abs() <= 1e-13;
        if !sample_once {
            return Upper::Analytic;
        }
        if !whole(ax) || !whole(ay) {
            return match c.z2.axis_parts(0, 0.0) {
                Some(_) => Upper::Separable,
                None => Upper::Analytic,
            };
        }
        let (z, h) = sample(c, c.z2, grid, ratios);
        Upper::Sampled {
            z,
            h,
            cells: (ax.round() as i64, ay.round() as i64),
        }
    }
}

/// Everything an instant reads.
struct Setup<'a> {
    c: &'a Contact<'a>,
    /// The local law: closed form, or the rotation form on the reference
    /// path.
    law: Law,
    grid: Grid,
    z1: Vec<f64>,
    h1: Vec<(f64, f64)>,
    upper: Upper,
}

impl Setup<'_> {
    /// Compressions and ratios of every spring at `step`, shift (sx, sy).
    fn fill(&self, step: usize, (sx, sy): (f64, f64), b: &mut Buffers) -> Result<()> {
        if let Upper::Separable = self.upper {
            return self.fill_separable((sx, sy), b);
        }
        let (c, g) = (self.c, &self.grid);
        let analytic = |k: usize| -> Result<(f64, (f64, f64))> {
            let (xr, yr) = (g.xs[k] - sx, g.ys[k] - sy);
            let gr = c.z2.gradient(xr, yr);
            let r = (self.law)(c, gr, g.cb, g.sb).ok_or_else(|| locked(c, 2, xr, yr, gr))?;
            Ok((c.z2.height(xr, yr), r))
        };
        for k in 0..b.cbuf.len() {
            let (z2, r) = match &self.upper {
                Upper::Separable | Upper::Analytic => analytic(k)?,
                Upper::Sampled { z, h, cells } => {
                    let (i, j) = ((k % g.nx) as i64, (k / g.nx) as i64);
                    let si = (i - cells.0 * step as i64).rem_euclid(g.nx as i64) as usize;
                    let sj = (j - cells.1 * step as i64).rem_euclid(g.ny as i64) as usize;
                    let src = sj * g.nx + si;
                    match h[src] {
                        Some(r) => (z[src], r),
                        None => analytic(k)?,
                    }
                }
            };
            b.cbuf[k] = c.springs.l0 - (z2 - self.z1[k]);
            b.hbuf[k] = [self.h1[k].0, self.h1[k].1, r.0, r.1];
        }
        Ok(())
    }

    /// [`Self::fill`] for a sinusoid shifted by a fraction of a cell: the
    /// per-column and per-row parts of its height and gradient
    /// ([`Surface::axis_parts`], O(n_x + n_y) trigonometric calls), then
    /// per spring three products and the closed-form local law, a
    /// branch-free loop over each row. The products are those of
    /// [`Surface::height`] and [`Surface::gradient`], so the compressions and
    /// ratios equal the per-point evaluation to the bit.
    ///
    /// [`Surface::axis_parts`]: super::surface::Surface::axis_parts
    /// [`Surface::height`]: super::surface::Surface::height
    /// [`Surface::gradient`]: super::surface::Surface::gradient
    fn fill_separable(&self, (sx, sy): (f64, f64), b: &mut Buffers) -> Result<()> {
        let (c, g) = (self.c, &self.grid);
        let parts = |axis: usize, v: f64| c.z2.axis_parts(axis, v).unwrap_or_default();
        b.cols.clear();
        b.cols.extend((0..g.nx).map(|i| parts(0, g.xs[i] - sx)));
        b.rows.clear();
        b.rows
            .extend((0..g.ny).map(|j| parts(1, g.ys[j * g.nx] - sy)));
        let (mu0, l0, cb, sb) = (c.mu0, c.springs.l0, g.cb, g.sb);
        let mut all_ok = true;
        for (j, r) in b.rows.iter().enumerate() {
            let row = j * g.nx..(j + 1) * g.nx;
            let out = b.cbuf[row.clone()].iter_mut().zip(&mut b.hbuf[row.clone()]);
            let lower = self.z1[row.clone()].iter().zip(&self.h1[row]);
            for (((cv, hv), (z1, h1)), col) in out.zip(lower).zip(&b.cols) {
                let (z2, gx, gy) = (col[0] * r[0], col[1] * r[1], col[2] * r[2]);
                let (hx, hy, ok) = tangent_plane_ratios(mu0, gx, gy, cb, sb);
                all_ok &= ok;
                *cv = l0 - (z2 - z1);
                *hv = [h1.0, h1.1, hx, hy];
            }
        }
        if all_ok {
            return Ok(());
        }
        // The first locked spring, named as the per-point evaluation names it.
        for k in 0..b.cbuf.len() {
            let (xr, yr) = (g.xs[k] - sx, g.ys[k] - sy);
            let gr = c.z2.gradient(xr, yr);
            if ratios(c, gr, cb, sb).is_none() {
                return Err(locked(c, 2, xr, yr, gr));
            }
        }
        Ok(())
    }
}

/// Per-thread buffers of one instant.
struct Buffers {
    cbuf: Vec<f64>,
    hbuf: Vec<Ratios>,
    scratch: Vec<f64>,
    forces: Vec<f64>,
    /// Parts of a separable upper surface per column and row.
    cols: Vec<[f64; 3]>,
    rows: Vec<[f64; 3]>,
}

/// Runs the 2-D model over one period of relative motion.
pub fn simulate_2d(c: &Contact, lattice: &Lattice) -> Result<Series> {
    simulate_2d_with(c, lattice, true)
}

/// [`simulate_2d`], with `sample_once = false` evaluating the upper surface
/// at every instant even when the motion is commensurate, and the local law
/// by the thesis' rotation form instead of the closed form (the reference
/// for the sampled and per-row paths).
pub fn simulate_2d_with(c: &Contact, lattice: &Lattice, sample_once: bool) -> Result<Series> {
    let (nx, ny) = (lattice.nx, lattice.ny);
    if nx == 0 || ny == 0 {
        return Err(Error::Config(format!(
            "the 2-D lattice needs at least one point along x and y, got {nx} x {ny}"
        )));
    }
    let grid = Grid::new(c, nx, ny)?;
    let law: Law = if sample_once {
        ratios
    } else {
        ratios_by_rotation
    };
    let (z1, h1) = sample(c, c.z1, &grid, law);
    let h1 = h1
        .into_iter()
        .enumerate()
        .map(|(k, r)| {
            let (x, y) = (grid.xs[k], grid.ys[k]);
            r.ok_or_else(|| locked(c, 1, x, y, c.z1.gradient(x, y)))
        })
        .collect::<Result<Vec<_>>>()?;
    let (cb, sb) = (grid.cb, grid.sb);
    let (distance, whole) = motion_period(c, cb, sb);
    let m = match distance {
        None => 1,
        Some(p) => lattice.steps.unwrap_or_else(|| {
            ((p / grid.dx.min(grid.dy)).round() as usize).clamp(1, MAX_STEPS_2D)
        }),
    };
    if m == 0 {
        return Err(Error::Config("steps per period must be >= 1".into()));
    }
    let dist: Vec<f64> = (0..m)
        .map(|step| distance.map_or(0.0, |p| p * step as f64 / m as f64))
        .collect();
    let step_len = distance.map_or(0.0, |p| p / m as f64);
    let upper = Upper::new(c, &grid, step_len, sample_once);
    let setup = Setup {
        c,
        law,
        grid,
        z1,
        h1,
        upper,
    };
    let results = resolve_all(&setup, &dist, &lattice.record);
    let (mut instants, mut maps) = (Vec::with_capacity(m), Vec::new());
    for r in results {
        let (inst, map) = r?;
        instants.push(inst);
        maps.extend(map);
    }
    Ok(Series {
        distance: dist,
        instants,
        period: distance,
        springs: nx * ny,
        cos_sin: (cb, sb),
        whole_periods: whole,
        maps,
    })
}

type Resolved = Result<(Instant, Option<ContactMap>)>;

/// Every instant, in parallel, each into its own slot (in step order).
fn resolve_all(setup: &Setup, dist: &[f64], record: &[usize]) -> Vec<Resolved> {
    let n = setup.grid.xs.len();
    let (c, g) = (setup.c, &setup.grid);
    (0..dist.len())
        .into_par_iter()
        .map_init(
            || Buffers {
                cbuf: vec![0.0; n],
                hbuf: vec![[0.0; 4]; n],
                scratch: Vec::with_capacity(n),
                forces: Vec::new(),
                cols: Vec::with_capacity(g.nx),
                rows: Vec::with_capacity(g.ny),
            },
            |b, step| {
                let s = dist[step];
                setup.fill(step, (s * g.cb, s * g.sb), b)?;
                let want = record.contains(&step);
                let inst = resolve_instant(
                    &b.cbuf,
                    &b.hbuf,
                    &c.springs,
                    c.load,
                    &mut b.scratch,
                    want.then_some(&mut b.forces),
                )
                .ok_or_else(|| no_contact(c.load))?;
                let map = want.then(|| ContactMap {
                    step,
                    x: g.xs.clone(),
                    y: g.ys.clone(),
                    force: b.forces.clone(),
                });
                Ok((inst, map))
            },
        )
        .collect()
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
