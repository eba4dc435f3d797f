//! Runs a validated ALSFM plan: every (β, load) point in parallel (rayon,
//! results in plan order, so the output does not depend on the thread
//! count), each on the cheapest exact path, with the effects the scene asks
//! for. A point that cannot be evaluated (surfaces lock, no contact) is a
//! row with its status, not a failure of the run.

use rayon::prelude::*;

use super::plan::Plan;
use super::rows::*;
use crate::error::{Error, Result};
use crate::models::alsfm::hierarchy::{cascade, wearing_level};
use crate::models::alsfm::numeric_1d::Contact;
use crate::models::alsfm::series::Series;
use crate::models::alsfm::solver::{evaluate, Keep, PointResult};
use crate::models::alsfm::surface::Surface;
use crate::status::{Code, Status};

/// Runs the plan.
pub fn run(plan: &Plan) -> Result<AlsfmOutput> {
    let points: Vec<(f64, f64)> = plan
        .beta_deg
        .iter()
        .flat_map(|b| plan.loads.iter().map(move |l| (*b, *l)))
        .collect();
    let parts: Vec<Result<AlsfmOutput>> = points
        .par_iter()
        .map(|(b, l)| run_point(plan, *b, *l))
        .collect();
    let mut out = AlsfmOutput::default();
    for p in parts {
        out.append(p?);
    }
    Ok(out)
}

/// μ at one level with local coefficient `mu0` and surfaces scaled by `b`.
fn level_mu(plan: &Plan, beta: f64, load: f64, mu0: f64, b: f64) -> Result<PointResult> {
    let (z1, z2): (Surface, Surface) = (plan.lower.scaled(b), plan.upper.scaled(b));
    let c = Contact {
        z1: &z1,
        z2: &z2,
        mu0,
        beta_deg: beta,
        springs: plan.springs,
        load,
    };
    evaluate(&c, &plan.resolution, &Keep::default())
}

fn run_point(plan: &Plan, beta: f64, load: f64) -> Result<AlsfmOutput> {
    let mut out = AlsfmOutput::default();
    let c = Contact {
        z1: &plan.lower,
        z2: &plan.upper,
        mu0: plan.mu0,
        beta_deg: beta,
        springs: plan.springs,
        load,
    };
    let keep = Keep {
        series: plan.outputs.time_series || !plan.outputs.contact_maps.is_empty(),
        record: plan.outputs.contact_maps.clone(),
        force: None,
    };
    let base = evaluate(&c, &plan.resolution, &keep);
    // Hierarchy: level 1 is `base`; outer levels use μ_{i−1} (one
    // evaluation each).
    let levels = plan.hierarchy.as_ref().map_or(1, |h| h.levels);
    let mut point = match &base {
        Ok(r) => PointRow::from_result(beta, load, r),
        Err(e) => PointRow::failed(beta, load, e.status()),
    };
    if let (Some(_), Ok(first)) = (&plan.hierarchy, &base) {
        hierarchy(plan, (beta, load), first, levels, &mut point, &mut out)?;
    }
    if plan.outputs.adhesion {
        out.adhesion
            .push(AdhesionRow::from_point(&point, base.as_ref().ok()));
    }
    if let Ok(r) = &base {
        if let Some(s) = &r.series {
            if plan.outputs.time_series {
                out.series.extend(series_rows(plan, beta, load, s));
            }
            for m in &s.maps {
                out.maps.extend(MapRow::from_map(beta, load, m));
            }
        }
    }
    if plan.outputs.wear {
        out.wear.extend(wear_rows(plan, beta, load, levels)?);
    }
    out.points.push(point);
    Ok(out)
}

/// Hierarchical levels above `first` (level 1): one row per level, and the
/// point's μ from the outermost level, or `locked` at the level that locks.
fn hierarchy(
    plan: &Plan,
    (beta, load): (f64, f64),
    first: &PointResult,
    levels: usize,
    point: &mut PointRow,
    out: &mut AlsfmOutput,
) -> Result<()> {
    let mu1 = first.mu;
    // The outermost level's evaluation, kept for μ_∥ and μ_⊥.
    let mut outer: Option<PointResult> = None;
    let casc = cascade(plan.mu0, levels, |level, prev| {
        if level == 1 {
            return mu1.ok_or_else(|| {
                Error::coded(Code::NoCoefficient, "no coefficient at L <= 0 (adhesion)")
            });
        }
        let r = level_mu(plan, beta, load, prev, 1.0)?;
        let m =
            r.mu.ok_or_else(|| Error::coded(Code::NoCoefficient, "no coefficient at L <= 0"));
        outer = Some(r);
        m
    })?;
    for (i, m) in casc.mu.iter().enumerate() {
        out.hierarchy.push(HierarchyRow {
            beta_deg: beta,
            load,
            level: i as i64,
            mu: Some(*m),
            status: Status::ok(),
        });
    }
    match &casc.locked {
        Some((level, why)) => {
            out.hierarchy.push(HierarchyRow {
                beta_deg: beta,
                load,
                level: *level as i64,
                mu: None,
                status: why.clone(),
            });
            point.mu = None;
            point.mu_parallel = None;
            point.mu_perp = None;
            point.status = at_level(*level, why);
            point.locked_level = Some(*level as i64);
        }
        None => {
            point.mu = casc.mu.last().copied();
            // μ_∥ and μ_⊥ are those of the outermost level's evaluation.
            if let Some(o) = &outer {
                point.mu_parallel = o.mu_parallel;
                point.mu_perp = o.mu_perp;
                point.r_xy = Some(o.r_xy);
            }
        }
    }
    point.levels = levels as i64;
    Ok(())
}

/// A hierarchy's stopping status, its details naming the level.
fn at_level(level: usize, why: &Status) -> Status {
    let mut s = Status::ok();
    for n in why.notes() {
        s.push(n.code, format!("hierarchy level {level}: {}", n.detail));
    }
    s
}

fn series_rows(plan: &Plan, beta: f64, load: f64, s: &Series) -> Vec<SeriesRow> {
    let v = plan.velocity;
    let m = s.instants.len();
    let ds = s.period.map_or(0.0, |p| p / m as f64);
    // One period, or tiled periodically over the requested duration.
    let total = match (plan.duration, s.period) {
        (Some(d), Some(_)) if ds > 0.0 => ((d * v / ds).floor() as usize + 1).max(m),
        (Some(_), None) => 2,
        _ => m,
    };
    (0..total)
        .map(|k| {
            let inst = &s.instants[k % m];
            let dist = if s.period.is_some() {
                k as f64 * ds
            } else {
                plan.duration.unwrap_or(0.0) * v * k as f64
            };
            SeriesRow::new(beta, load, k as i64, dist, dist / v, inst, s.cos_sin)
        })
        .collect()
}

fn wear_rows(plan: &Plan, beta: f64, load: f64, levels: usize) -> Result<Vec<WearRow>> {
    let Some(w) = plan.wear else {
        return Ok(Vec::new());
    };
    let t_w = w.wear_time();
    let hier = plan.hierarchy.as_ref().filter(|h| h.wear);
    let scale = plan.hierarchy.as_ref().map_or(10.0, |h| h.scale);
    // Total wear time: T_w, or the sum over the levels.
    let t_end = match hier {
        None => t_w,
        Some(_) => (0..levels).map(|j| t_w * scale.powi(j as i32)).sum(),
    };
    let n = plan.wear_samples;
    let mut rows = Vec::with_capacity(n);
    for k in 0..n {
        let t = t_end * k as f64 / (n - 1) as f64;
        let (wearing, b) = match hier {
            None => (0, w.reduction(t)),
            Some(_) => wearing_level(t, t_w, scale, levels),
        };
        // μ_n(t): without hierarchical wear every level has the reduction B;
        // with it, levels below the wearing one are flat, the wearing one has
        // B, the outer ones are intact.
        let result = cascade(plan.mu0, levels, |level, prev| {
            let b_level = match hier {
                None => b,
                Some(_) if level < wearing => 0.0,
                Some(_) if level == wearing => b,
                Some(_) => 1.0,
            };
            level_mu(plan, beta, load, prev, b_level)?
                .mu
                .ok_or_else(|| Error::coded(Code::NoCoefficient, "no coefficient at L <= 0"))
        });
        rows.push(match result {
            Ok(c) => match c.locked {
                None => WearRow {
                    beta_deg: beta,
                    load,
                    time_s: t,
                    reduction_b: b,
                    wearing_level: wearing as i64,
                    mu: c.mu.last().copied(),
                    status: Status::ok(),
                },
                Some((level, why)) => WearRow {
                    beta_deg: beta,
                    load,
                    time_s: t,
                    reduction_b: b,
                    wearing_level: wearing as i64,
                    mu: None,
                    status: at_level(level, &why),
                },
            },
            Err(e) => WearRow {
                beta_deg: beta,
                load,
                time_s: t,
                reduction_b: b,
                wearing_level: wearing as i64,
                mu: None,
                status: e.status(),
            },
        });
    }
    Ok(rows)
}
