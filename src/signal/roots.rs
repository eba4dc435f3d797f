//! Brent's method for a root of a continuous function bracketed by a sign
//! change (Brent 1973, as scipy's `brentq`): inverse quadratic
//! interpolation or the secant when they stay inside the bracket,
//! bisection otherwise, so it converges at least as surely as bisection.

/// A root of `f` in [a, b], where f(a) and f(b) have opposite signs (or one
/// is zero), to within `xtol + rtol·|x|`; `None` without a sign change or
/// after 200 iterations.
pub fn brent(f: impl Fn(f64) -> f64, a: f64, b: f64, xtol: f64, rtol: f64) -> Option<f64> {
    let (mut a, mut b) = (a, b);
    let (mut fa, mut fb) = (f(a), f(b));
    if fa == 0.0 {
        return Some(a);
    }
    if fb == 0.0 {
        return Some(b);
    }
    if fa.signum() == fb.signum() || fa.is_nan() || fb.is_nan() {
        return None;
    }
    let (mut c, mut fc) = (a, fa);
    let (mut d, mut e) = (b - a, b - a);
    for _ in 0..200 {
        if fb.signum() == fc.signum() {
            (c, fc) = (a, fa);
            d = b - a;
            e = d;
        }
        if fc.abs() < fb.abs() {
            (a, b, c) = (b, c, b);
            (fa, fb, fc) = (fb, fc, fb);
        }
        let tol = 0.5 * (xtol + rtol * b.abs());
        let m = 0.5 * (c - b);
        if m.abs() <= tol || fb == 0.0 {
            return Some(b);
        }
        if e.abs() >= tol && fa.abs() > fb.abs() {
            let s = fb / fa;
            let (mut p, mut q) = if a.to_bits() == c.to_bits() {
                (2.0 * m * s, 1.0 - s)
            } else {
                let (q0, r) = (fa / fc, fb / fc);
                (
                    s * (2.0 * m * q0 * (q0 - r) - (b - a) * (r - 1.0)),
                    (q0 - 1.0) * (r - 1.0) * (s - 1.0),
                )
            };
            if p > 0.0 {
                q = -q;
            } else {
                p = -p;
            }
            if 2.0 * p < (3.0 * m * q - (tol * q).abs()).min((e * q).abs()) {
                e = d;
                d = p / q;
            } else {
                d = m;
                e = m;
            }
        } else {
            d = m;
            e = m;
        }
        (a, fa) = (b, fb);
        b += if d.abs() > tol { d } else { tol.copysign(m) };
        fb = f(b);
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finds_bracketed_roots_and_refuses_unbracketed_ones() {
        let r = brent(|x| x * x - 2.0, 0.0, 2.0, 1e-15, 1e-15).unwrap();
        assert!((r - 2f64.sqrt()).abs() < 1e-14);
        let r = brent(|x| x.cos() - x, 0.0, 1.0, 1e-15, 1e-15).unwrap();
        assert!((r - 0.739_085_133_215_160_6).abs() < 1e-14);
        // A step: bisection-like convergence to the jump.
        let r = brent(|x| if x < 0.3 { -1.0 } else { 1.0 }, 0.0, 1.0, 1e-12, 0.0).unwrap();
        assert!((r - 0.3).abs() < 1e-11);
        assert!(brent(|x| x * x + 1.0, -1.0, 1.0, 1e-12, 0.0).is_none());
    }
}
