//! Why tribo has its own solver: argmin's stock Gauss–Newton, run on the
//! NIST StRD problems from start 1, stops with "Solver converged" on answers
//! with fewer than 4 correct digits (ENSO: 3.5 digits; its test is an
//! absolute change of ‖r‖ below √ε) and fails outright on 10 of 27
//! (singular JᵀJ: Eckerle4, MGH09, Nelson, Rat42; iteration limit: BoxBOD,
//! Hahn1, MGH10, MGH17, Rat43, Thurber), where the Levenberg–Marquardt
//! solver gets ≥ 6 digits on every one. Skips (with a note) when the shared
//! NIST data is absent.

use argmin::core::{Executor, Jacobian, Operator, State, TerminationReason};
use argmin::solver::gaussnewton::GaussNewton;
use argmin_math::{ArgminDot, ArgminInv, ArgminTranspose};
use nalgebra::{DMatrix, DVector};
use tribo::fit::nist::{lre, read_nist, run_problem, NistData, NistModel, NistProblem};
use tribo::fit::problem::{jacobian_at, residual_vec};
use tribo::fit::LmParams;

/// A dense matrix with the argmin-math operations Gauss–Newton needs
/// (argmin-math's `vec` backend has no matrix inverse).
#[derive(Clone)]
struct Mat(DMatrix<f64>);

impl ArgminTranspose<Mat> for Mat {
    fn t(self) -> Mat {
        Mat(self.0.transpose())
    }
}
impl ArgminInv<Mat> for Mat {
    fn inv(&self) -> Result<Mat, argmin::core::Error> {
        self.0
            .clone()
            .try_inverse()
            .map(Mat)
            .ok_or_else(|| argmin::core::Error::msg("singular JᵀJ"))
    }
}
impl ArgminDot<Mat, Mat> for Mat {
    fn dot(&self, other: &Mat) -> Mat {
        Mat(&self.0 * &other.0)
    }
}
impl ArgminDot<Vec<f64>, Vec<f64>> for Mat {
    fn dot(&self, v: &Vec<f64>) -> Vec<f64> {
        (&self.0 * DVector::from_column_slice(v))
            .iter()
            .copied()
            .collect()
    }
}

struct GnProblem<'a>(NistProblem<'a>);

impl Operator for GnProblem<'_> {
    type Param = Vec<f64>;
    type Output = Vec<f64>;
    fn apply(&self, b: &Vec<f64>) -> Result<Vec<f64>, argmin::core::Error> {
        Ok(residual_vec(&self.0, b))
    }
}
impl Jacobian for GnProblem<'_> {
    type Param = Vec<f64>;
    type Jacobian = Mat;
    fn jacobian(&self, b: &Vec<f64>) -> Result<Mat, argmin::core::Error> {
        Ok(Mat(jacobian_at(&self.0, b)))
    }
}

fn nist(name: &str) -> Option<NistData> {
    let dir = crate::common::shared("data/nist_strd")?;
    Some(read_nist(&dir.join(format!("{name}.dat"))).unwrap())
}

/// (terminated with "Solver converged", min LRE of the parameters); an
/// argmin error (singular JᵀJ) counts as not converged.
fn gauss_newton(data: &NistData) -> (bool, f64) {
    let model = NistModel::for_dataset(&data.name).unwrap();
    let op = GnProblem(NistProblem {
        data,
        model,
        analytic: true,
    });
    let run = Executor::new(op, GaussNewton::<f64>::new())
        .configure(|s| s.param(data.starts[0].clone()).max_iters(200))
        .ctrlc(false)
        .run();
    match run {
        Err(_) => (false, 0.0),
        Ok(mut res) => {
            let converged =
                res.state.get_termination_reason() == Some(&TerminationReason::SolverConverged);
            let b = res.state.take_best_param().unwrap_or_default();
            let l = b
                .iter()
                .zip(&data.certified)
                .map(|(e, c)| lre(*e, *c))
                .fold(11.0, f64::min);
            (converged, l)
        }
    }
}

#[test]
fn stock_gauss_newton_reports_wrong_answers_converged_where_lm_succeeds() {
    let mut wrong = vec![];
    let mut gn_failed = 0;
    for name in [
        "Bennett5", "BoxBOD", "Chwirut1", "Chwirut2", "DanWood", "ENSO", "Eckerle4", "Gauss1",
        "Gauss2", "Gauss3", "Hahn1", "Kirby2", "Lanczos1", "Lanczos2", "Lanczos3", "MGH09",
        "MGH10", "MGH17", "Misra1a", "Misra1b", "Misra1c", "Misra1d", "Nelson", "Rat42", "Rat43",
        "Roszman1", "Thurber",
    ] {
        let Some(data) = nist(name) else {
            eprintln!("note: ../shared/data/nist_strd absent; test skipped");
            return;
        };
        let (gn_converged, gn_lre) = gauss_newton(&data);
        let lm = run_problem(&data, 1, true, &LmParams::default()).unwrap();
        eprintln!(
            "{name}: GN converged={gn_converged} LRE {gn_lre:.1}; LM {} LRE {:.1}",
            lm.status, lm.lre_params
        );
        gn_failed += usize::from(!gn_converged);
        if gn_converged && gn_lre < 4.0 {
            assert!(
                lm.status.is_converged() && lm.lre_params >= 6.0,
                "{name}: {lm:?}"
            );
            wrong.push(name);
        }
    }
    assert!(
        gn_failed >= 10,
        "Gauss-Newton failed on {gn_failed} problems"
    );
    assert!(
        wrong.contains(&"ENSO"),
        "expected Gauss-Newton to report ENSO converged with < 4 digits: {wrong:?}"
    );
}
