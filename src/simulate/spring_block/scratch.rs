//! Scratch arrays of one classical RK4 step over the moving blocks,
//! allocated once per run.

/// Stage positions of all blocks and, per moving block (by its place in the
/// moving list), the velocity at the step's start, the stage velocity, the
/// last stage derivatives and the weighted sums of the derivatives.
#[derive(Debug, Clone)]
pub(crate) struct Rk4Scratch {
    /// Stage positions (equal to the state's positions between steps) \[m\].
    pub px: Vec<f64>,
    pub py: Vec<f64>,
    /// Velocity at the step's start [m/s].
    pub ovx: Vec<f64>,
    pub ovy: Vec<f64>,
    /// Stage velocity [m/s].
    pub svx: Vec<f64>,
    pub svy: Vec<f64>,
    /// Last stage derivative of position (a velocity) and of velocity.
    pub kxx: Vec<f64>,
    pub kxy: Vec<f64>,
    pub kvx: Vec<f64>,
    pub kvy: Vec<f64>,
    /// k1 + 2 k2 + 2 k3 + k4 of position and of velocity.
    pub sxx: Vec<f64>,
    pub sxy: Vec<f64>,
    pub svsx: Vec<f64>,
    pub svsy: Vec<f64>,
}

impl Rk4Scratch {
    /// Scratch for `n` blocks at positions (ux, uy).
    pub fn new(ux: &[f64], uy: &[f64]) -> Self {
        let n = ux.len();
        let z = || vec![0.0; n];
        Rk4Scratch {
            px: ux.to_vec(),
            py: uy.to_vec(),
            ovx: z(),
            ovy: z(),
            svx: z(),
            svy: z(),
            kxx: z(),
            kxy: z(),
            kvx: z(),
            kvy: z(),
            sxx: z(),
            sxy: z(),
            svsx: z(),
            svsy: z(),
        }
    }

    /// Stage 1 of moving block number `m`: velocity (wx, wy), acceleration
    /// (ax, ay) at the step's start.
    #[inline(always)]
    pub fn first_stage(&mut self, m: usize, (wx, wy): (f64, f64), (ax, ay): (f64, f64)) {
        self.ovx[m] = wx;
        self.ovy[m] = wy;
        self.kxx[m] = wx;
        self.kxy[m] = wy;
        self.kvx[m] = ax;
        self.kvy[m] = ay;
        self.sxx[m] = wx;
        self.sxy[m] = wy;
        self.svsx[m] = ax;
        self.svsy[m] = ay;
    }

    /// A later stage of moving block `m`, added with weight `w`.
    #[inline(always)]
    pub fn later_stage(&mut self, m: usize, w: f64, (wx, wy): (f64, f64), (ax, ay): (f64, f64)) {
        self.kxx[m] = wx;
        self.kxy[m] = wy;
        self.kvx[m] = ax;
        self.kvy[m] = ay;
        self.sxx[m] += w * wx;
        self.sxy[m] += w * wy;
        self.svsx[m] += w * ax;
        self.svsy[m] += w * ay;
    }
}
