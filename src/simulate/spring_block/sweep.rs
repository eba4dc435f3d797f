//! Pressure × repetition sweeps in parallel (rayon), with per-run seeds
//! derived from the scene seed, the pressure index and the run index, so the
//! result is bit-identical whatever the number of threads.

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;

use super::run::{simulate_run, RunReport, RunSpec};
use super::scene::ScenePlan;
use crate::error::Result;
use crate::models::spring_block::Lattice;

/// One finished run of a sweep.
#[derive(Debug, Clone, serde::Serialize, serde::Deserialize)]
pub struct SweepRun {
    /// Index into the plan's pressures.
    pub pressure_index: usize,
    /// p \[Pa\].
    pub pressure: f64,
    /// Repetition index.
    pub run: usize,
    /// The run's seed (63 bits, so it fits a signed column).
    pub seed: u64,
    /// α \[rad\].
    pub angle: f64,
    /// The run's result.
    pub report: RunReport,
}

/// SplitMix64 finaliser: a bijective mix of 64 bits.
fn mix(mut z: u64) -> u64 {
    z = z.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// Seed of run `run` at pressure index `pressure_index` of a scene seeded
/// `seed`: distinct inputs give independent-looking 63-bit seeds.
pub fn derive_seed(seed: u64, pressure_index: usize, run: usize) -> u64 {
    mix(mix(mix(seed) ^ pressure_index as u64) ^ ((run as u64) << 1 | 1)) >> 1
}

/// α of a run, uniform in the plan's range, from stream 1 of the run's
/// ChaCha8 generator (stream 0 draws the friction coefficients).
pub fn draw_angle(seed: u64, range: (f64, f64)) -> f64 {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(1);
    let u: f64 = rng.random();
    range.0 + (range.1 - range.0) * u
}

/// Runs every (pressure, repetition) of the plan on the current rayon pool.
/// `progress` is called once per finished run (from worker threads).
/// Returns the runs in (pressure, repetition) order.
pub fn run_sweep(plan: &ScenePlan, progress: &(dyn Fn() + Sync)) -> Result<Vec<SweepRun>> {
    let lattice = Lattice::new(&plan.params);
    sweep_jobs(plan)
        .par_iter()
        .map(|&(k, r)| {
            let run = run_one(plan, &lattice, k, r)?;
            progress();
            Ok(run)
        })
        .collect()
}

/// The (pressure index, repetition) of every run of a sweep, in order.
pub fn sweep_jobs(plan: &ScenePlan) -> Vec<(usize, usize)> {
    (0..plan.pressures.len())
        .flat_map(|k| (0..plan.repetitions).map(move |r| (k, r)))
        .collect()
}

/// Run `r` at pressure index `k` of a sweep: its seed and angle derive from
/// the scene's seed, so a run gives the same result wherever it runs.
pub fn run_one(plan: &ScenePlan, lattice: &Lattice, k: usize, r: usize) -> Result<SweepRun> {
    let seed = derive_seed(plan.seed, k, r);
    let angle = draw_angle(seed, plan.angle_range);
    let spec = RunSpec {
        pressure: plan.pressures[k],
        angle,
        seed,
    };
    let report = simulate_run(
        &plan.params,
        lattice,
        &plan.mask,
        &plan.integrator,
        &plan.control,
        &spec,
    )?;
    Ok(SweepRun {
        pressure_index: k,
        pressure: plan.pressures[k],
        run: r,
        seed,
        angle,
        report,
    })
}
