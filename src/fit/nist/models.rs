//! The NIST StRD nonlinear models, written by hand from each file's
//! `Model:` line, with analytic gradients ∂f/∂bₖ (checked against central
//! differences in the tests).

use std::f64::consts::PI;

/// A model function of the NIST suite.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NistModel {
    /// y = b1 (b2 + x)^(−1/b3)
    Bennett5,
    /// y = b1 (1 − exp(−b2 x)) (BoxBOD, Misra1a)
    ExpRise,
    /// y = exp(−b1 x) / (b2 + b3 x) (Chwirut1, Chwirut2)
    Chwirut,
    /// y = b1 x^b2
    DanWood,
    /// y = b1 + b2 cos(2πx/12) + b3 sin(2πx/12) + b5 cos(2πx/b4) + b6 sin(2πx/b4) + b8 cos(2πx/b7) + b9 sin(2πx/b7)
    Enso,
    /// y = (b1/b2) exp(−½((x − b3)/b2)²)
    Eckerle4,
    /// y = b1 exp(−b2 x) + b3 exp(−(x − b4)²/b5²) + b6 exp(−(x − b7)²/b8²) (Gauss1–3)
    Gauss,
    /// y = (b1 + b2 x + b3 x² + b4 x³) / (1 + b5 x + b6 x² + b7 x³) (Hahn1, Thurber)
    Rational33,
    /// y = (b1 + b2 x + b3 x²) / (1 + b4 x + b5 x²)
    Kirby2,
    /// y = b1 exp(−b2 x) + b3 exp(−b4 x) + b5 exp(−b6 x) (Lanczos1–3)
    Lanczos,
    /// y = b1 (x² + x b2) / (x² + x b3 + b4)
    Mgh09,
    /// y = b1 exp(b2 / (x + b3))
    Mgh10,
    /// y = b1 + b2 exp(−x b4) + b3 exp(−x b5)
    Mgh17,
    /// y = b1 (1 − (1 + b2 x/2)^(−2))
    Misra1b,
    /// y = b1 (1 − (1 + 2 b2 x)^(−1/2))
    Misra1c,
    /// y = b1 b2 x (1 + b2 x)^(−1)
    Misra1d,
    /// log y = b1 − b2 x1 exp(−b3 x2)
    Nelson,
    /// y = b1 / (1 + exp(b2 − b3 x))
    Rat42,
    /// y = b1 / (1 + exp(b2 − b3 x))^(1/b4)
    Rat43,
    /// y = b1 − b2 x − arctan(b3/(x − b4))/π
    Roszman1,
}

impl NistModel {
    /// The model of a NIST dataset, by its name.
    pub fn for_dataset(name: &str) -> Option<NistModel> {
        use NistModel::*;
        Some(match name {
            "Bennett5" => Bennett5,
            "BoxBOD" | "Misra1a" => ExpRise,
            "Chwirut1" | "Chwirut2" => Chwirut,
            "DanWood" => DanWood,
            "ENSO" => Enso,
            "Eckerle4" => Eckerle4,
            "Gauss1" | "Gauss2" | "Gauss3" => Gauss,
            "Hahn1" | "Thurber" => Rational33,
            "Kirby2" => Kirby2,
            "Lanczos1" | "Lanczos2" | "Lanczos3" => Lanczos,
            "MGH09" => Mgh09,
            "MGH10" => Mgh10,
            "MGH17" => Mgh17,
            "Misra1b" => Misra1b,
            "Misra1c" => Misra1c,
            "Misra1d" => Misra1d,
            "Nelson" => Nelson,
            "Rat42" => Rat42,
            "Rat43" => Rat43,
            "Roszman1" => Roszman1,
            _ => return None,
        })
    }

    /// Whether the response is fitted on a log scale (Nelson: log y).
    pub fn log_response(self) -> bool {
        self == NistModel::Nelson
    }

    /// f(b; x) and, if `g` is given, ∂f/∂bₖ into `g`.
    pub fn eval(self, b: &[f64], xs: &[f64], g: Option<&mut [f64]>) -> f64 {
        use NistModel::*;
        let x = xs[0];
        let mut tmp = [0.0; 9];
        let d = &mut tmp[..b.len()];
        let f = match self {
            Bennett5 => {
                let u = b[1] + x;
                let p = u.powf(-1.0 / b[2]);
                d[0] = p;
                d[1] = -b[0] / b[2] * p / u;
                d[2] = b[0] * p * u.ln() / (b[2] * b[2]);
                b[0] * p
            }
            ExpRise => {
                let e = (-b[1] * x).exp();
                d[0] = 1.0 - e;
                d[1] = b[0] * x * e;
                b[0] * (1.0 - e)
            }
            Chwirut => {
                let e = (-b[0] * x).exp();
                let den = b[1] + b[2] * x;
                d[0] = -x * e / den;
                d[1] = -e / (den * den);
                d[2] = -x * e / (den * den);
                e / den
            }
            DanWood => {
                let p = x.powf(b[1]);
                d[0] = p;
                d[1] = b[0] * p * x.ln();
                b[0] * p
            }
            Enso => {
                let t0 = 2.0 * PI * x / 12.0;
                let t4 = 2.0 * PI * x / b[3];
                let t7 = 2.0 * PI * x / b[6];
                d[0] = 1.0;
                d[1] = t0.cos();
                d[2] = t0.sin();
                d[4] = t4.cos();
                d[5] = t4.sin();
                d[7] = t7.cos();
                d[8] = t7.sin();
                d[3] = (-b[4] * t4.sin() + b[5] * t4.cos()) * (-t4 / b[3]);
                d[6] = (-b[7] * t7.sin() + b[8] * t7.cos()) * (-t7 / b[6]);
                b[0] + b[1] * d[1]
                    + b[2] * d[2]
                    + b[4] * d[4]
                    + b[5] * d[5]
                    + b[7] * d[7]
                    + b[8] * d[8]
            }
            Eckerle4 => {
                let z = (x - b[2]) / b[1];
                let gz = (-0.5 * z * z).exp();
                d[0] = gz / b[1];
                d[1] = b[0] * gz * (z * z - 1.0) / (b[1] * b[1]);
                d[2] = b[0] * gz * z / (b[1] * b[1]);
                b[0] / b[1] * gz
            }
            Gauss => {
                let e = (-b[1] * x).exp();
                let g1 = (-(x - b[3]).powi(2) / (b[4] * b[4])).exp();
                let g2 = (-(x - b[6]).powi(2) / (b[7] * b[7])).exp();
                d[0] = e;
                d[1] = -b[0] * x * e;
                d[2] = g1;
                d[3] = b[2] * g1 * 2.0 * (x - b[3]) / (b[4] * b[4]);
                d[4] = b[2] * g1 * 2.0 * (x - b[3]).powi(2) / b[4].powi(3);
                d[5] = g2;
                d[6] = b[5] * g2 * 2.0 * (x - b[6]) / (b[7] * b[7]);
                d[7] = b[5] * g2 * 2.0 * (x - b[6]).powi(2) / b[7].powi(3);
                b[0] * e + b[2] * g1 + b[5] * g2
            }
            Rational33 => {
                let (x2, x3) = (x * x, x * x * x);
                let num = b[0] + b[1] * x + b[2] * x2 + b[3] * x3;
                let den = 1.0 + b[4] * x + b[5] * x2 + b[6] * x3;
                for (k, p) in [1.0, x, x2, x3].iter().enumerate() {
                    d[k] = p / den;
                }
                for (k, p) in [x, x2, x3].iter().enumerate() {
                    d[4 + k] = -num * p / (den * den);
                }
                num / den
            }
            Kirby2 => {
                let x2 = x * x;
                let num = b[0] + b[1] * x + b[2] * x2;
                let den = 1.0 + b[3] * x + b[4] * x2;
                d[0] = 1.0 / den;
                d[1] = x / den;
                d[2] = x2 / den;
                d[3] = -num * x / (den * den);
                d[4] = -num * x2 / (den * den);
                num / den
            }
            Lanczos => {
                let mut f = 0.0;
                for k in 0..3 {
                    let e = (-b[2 * k + 1] * x).exp();
                    d[2 * k] = e;
                    d[2 * k + 1] = -b[2 * k] * x * e;
                    f += b[2 * k] * e;
                }
                f
            }
            Mgh09 => {
                let num = x * x + x * b[1];
                let den = x * x + x * b[2] + b[3];
                d[0] = num / den;
                d[1] = b[0] * x / den;
                d[2] = -b[0] * num * x / (den * den);
                d[3] = -b[0] * num / (den * den);
                b[0] * num / den
            }
            Mgh10 => {
                let u = x + b[2];
                let e = (b[1] / u).exp();
                d[0] = e;
                d[1] = b[0] * e / u;
                d[2] = -b[0] * e * b[1] / (u * u);
                b[0] * e
            }
            Mgh17 => {
                let e4 = (-x * b[3]).exp();
                let e5 = (-x * b[4]).exp();
                d[0] = 1.0;
                d[1] = e4;
                d[2] = e5;
                d[3] = -b[1] * x * e4;
                d[4] = -b[2] * x * e5;
                b[0] + b[1] * e4 + b[2] * e5
            }
            Misra1b => {
                let u = 1.0 + b[1] * x / 2.0;
                d[0] = 1.0 - u.powi(-2);
                d[1] = b[0] * x * u.powi(-3);
                b[0] * d[0]
            }
            Misra1c => {
                let u = 1.0 + 2.0 * b[1] * x;
                d[0] = 1.0 - u.powf(-0.5);
                d[1] = b[0] * x * u.powf(-1.5);
                b[0] * d[0]
            }
            Misra1d => {
                let u = 1.0 + b[1] * x;
                d[0] = b[1] * x / u;
                d[1] = b[0] * x / (u * u);
                b[0] * d[0]
            }
            Nelson => {
                let x2 = xs[1];
                let e = (-b[2] * x2).exp();
                d[0] = 1.0;
                d[1] = -x * e;
                d[2] = b[1] * x * x2 * e;
                b[0] - b[1] * x * e
            }
            Rat42 => {
                let e = (b[1] - b[2] * x).exp();
                let u = 1.0 + e;
                d[0] = 1.0 / u;
                d[1] = -b[0] * e / (u * u);
                d[2] = b[0] * x * e / (u * u);
                b[0] / u
            }
            Rat43 => {
                let e = (b[1] - b[2] * x).exp();
                let u = 1.0 + e;
                let p = u.powf(-1.0 / b[3]);
                d[0] = p;
                d[1] = -b[0] / b[3] * p / u * e;
                d[2] = b[0] / b[3] * p / u * e * x;
                d[3] = b[0] * p * u.ln() / (b[3] * b[3]);
                b[0] * p
            }
            Roszman1 => {
                let u = x - b[3];
                let w = b[2] / u;
                let k = 1.0 / (PI * (1.0 + w * w));
                d[0] = 1.0;
                d[1] = -x;
                d[2] = -k / u;
                d[3] = -k * b[2] / (u * u);
                b[0] - b[1] * x - w.atan() / PI
            }
        };
        if let Some(g) = g {
            g.copy_from_slice(d);
        }
        f
    }
}
