//! Separation of the two bodies for a given normal load (MODELS.md §5, "Load
//! and separation"; with adhesion, Sec. 2.1 and Eq. 2.1).
//!
//! Spring i has compression u_i = c_i − d, where c_i = l0 − (z2 − z1)_i is its
//! compression at zero separation and d the separation. Its force is
//! F_i = k_c u_i when u_i > 0, and, only with adhesion, k_t u_i when u_i < 0
//! (tension, negative). The separation solves mean_i F_i = L, where L is the
//! load per spring (N). The mean force is continuous, piecewise linear and
//! non-increasing in d, so the exact root is found from the c_i ordered
//! from the largest: with the m largest compressed,
//! d_m = (k_c P_m + k_t (T − P_m) − n L) / (k_c m + k_t (n − m)),
//! P_m their sum and T the sum of all, valid when d_m lies between the m-th
//! and the (m+1)-th largest c. [`solve_separation`] finds that m by
//! selection (quickselect on the answer: expected O(n), no full sort);
//! [`solve_separation_sorted`] by a full sort and a scan (O(n log n), the
//! reference it is tested against); [`solve_separation_bisect`] is the
//! bisection fallback, used when the exact solution does not reproduce the
//! load.
//!
//! | symbol | argument | unit |
//! |---|---|---|
//! | c_i | `c` | m, compression at d = 0 |
//! | k_c | `k_c` | N/m, stiffness in compression, > 0 |
//! | k_t | `k_t` | N/m, stiffness in tension, ≥ 0 (0: no adhesion) |
//! | L | `load` | N per spring, mean spring force |

/// The solved separation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Separation {
    /// d, m.
    pub d: f64,
    /// Whether the exact (sorting) solution was used; false for bisection.
    pub exact: bool,
}

/// Mean spring force at separation `d`.
pub fn mean_force(c: &[f64], d: f64, k_c: f64, k_t: f64) -> f64 {
    c.iter()
        .map(|ci| {
            let u = ci - d;
            if u > 0.0 {
                k_c * u
            } else {
                k_t * u
            }
        })
        .sum::<f64>()
        / c.len() as f64
}

/// Exact separation by selection, with the bisection fallback when the
/// residual exceeds 1e-9 of the force scale. `scratch` is reused between
/// calls to avoid allocation. Returns `None` when no separation gives the
/// load: without adhesion, L ≤ 0 (no contact).
///
/// The mean force at a pivot p, with the springs of c ≥ p compressed,
/// tells on which side of p the root lies (the force does not increase
/// with d): below or at p, every spring with c ≥ p is compressed (or at
/// zero force); above it, none with c ≤ p is. Each round partitions the
/// undecided springs around their median (`select_nth_unstable_by`) and
/// keeps one side, so the work halves: expected O(n) per instant instead of
/// the O(n log n) sort. The result equals [`solve_separation_sorted`]'s to
/// round-off of the sums, which are taken in another order (tested to
/// 1e-12).
pub fn solve_separation(
    c: &[f64],
    k_c: f64,
    k_t: f64,
    load: f64,
    scratch: &mut Vec<f64>,
) -> Option<Separation> {
    let n = c.len();
    if n == 0 || !load.is_finite() || (k_t <= 0.0 && load <= 0.0) {
        return None;
    }
    scratch.clear();
    scratch.extend_from_slice(c);
    let total: f64 = c.iter().sum();
    let nl = n as f64 * load;
    let (mut lo, mut hi) = (0usize, n);
    // Sum of scratch[..lo]: the springs known to be compressed.
    let mut top = 0.0;
    while lo < hi {
        let mid = lo + (hi - lo) / 2;
        let slice = &mut scratch[lo..hi];
        slice.select_nth_unstable_by(mid - lo, |a, b| b.total_cmp(a));
        let p = slice[mid - lo];
        let upper: f64 = slice[..=mid - lo].iter().sum();
        let m = (mid + 1) as f64;
        let compressed = top + upper;
        let force = k_c * (compressed - m * p) + k_t * ((total - compressed) - (n as f64 - m) * p);
        if force <= nl {
            // The root is at or below p: all of scratch[..=mid] compressed.
            top = compressed;
            lo = mid + 1;
        } else {
            // Above p: none of scratch[mid..] is compressed.
            hi = mid;
        }
    }
    let m = lo;
    let denom = k_c * m as f64 + k_t * (n - m) as f64;
    let (cmin, cmax) = c
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        });
    let scale = k_c * (cmax - cmin).abs().max(load.abs() / k_c);
    if denom > 0.0 {
        let d = (k_c * top + k_t * (total - top) - nl) / denom;
        if (mean_force(c, d, k_c, k_t) - load).abs() <= 1e-9 * scale.max(f64::MIN_POSITIVE) {
            return Some(Separation { d, exact: true });
        }
    }
    solve_separation_bisect(c, k_c, k_t, load)
}

/// Exact separation by sorting (descending c) and prefix sums, with the
/// bisection fallback when the residual exceeds 1e-9 of the force scale:
/// the reference for [`solve_separation`] (O(n log n)).
pub fn solve_separation_sorted(
    c: &[f64],
    k_c: f64,
    k_t: f64,
    load: f64,
    scratch: &mut Vec<f64>,
) -> Option<Separation> {
    let n = c.len();
    if n == 0 || !load.is_finite() || (k_t <= 0.0 && load <= 0.0) {
        return None;
    }
    scratch.clear();
    scratch.extend_from_slice(c);
    scratch.sort_unstable_by(|a, b| b.total_cmp(a));
    let total: f64 = scratch.iter().sum();
    let nl = n as f64 * load;
    let mut prefix = 0.0;
    let mut found = None;
    // m springs (the m largest c) are compressed, the others in tension
    // (k_t) or slack (k_t = 0).
    for m in 0..=n {
        if m > 0 {
            prefix += scratch[m - 1];
        }
        let denom = k_c * m as f64 + k_t * (n - m) as f64;
        if denom <= 0.0 {
            continue;
        }
        let d = (k_c * prefix + k_t * (total - prefix) - nl) / denom;
        let upper = if m == 0 {
            f64::INFINITY
        } else {
            scratch[m - 1]
        };
        let lower = if m == n {
            f64::NEG_INFINITY
        } else {
            scratch[m]
        };
        if d <= upper && d >= lower {
            found = Some(d);
            break;
        }
    }
    let scale = k_c * (scratch[0] - scratch[n - 1]).abs().max(load.abs() / k_c);
    if let Some(d) = found {
        if (mean_force(c, d, k_c, k_t) - load).abs() <= 1e-9 * scale.max(f64::MIN_POSITIVE) {
            return Some(Separation { d, exact: true });
        }
    }
    solve_separation_bisect(c, k_c, k_t, load)
}

/// Separation by bisection on the monotone mean force (fallback, and an
/// independent check of [`solve_separation`]). Stops when the bracket no
/// longer shrinks (machine precision).
pub fn solve_separation_bisect(c: &[f64], k_c: f64, k_t: f64, load: f64) -> Option<Separation> {
    if c.is_empty() || !load.is_finite() || (k_t <= 0.0 && load <= 0.0) {
        return None;
    }
    let (lo_c, hi_c) = c
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(*v), b.max(*v))
        });
    // At d = hi_c the mean force is ≤ 0 and at d = lo_c it is ≥ 0; widen by
    // the load over the smallest stiffness that acts at that end.
    let mut lo = lo_c - load.abs() / k_c - 1.0;
    let mut hi = hi_c
        + if k_t > 0.0 {
            load.abs() / k_t + 1.0
        } else {
            0.0
        };
    if mean_force(c, lo, k_c, k_t) < load || mean_force(c, hi, k_c, k_t) > load {
        return None;
    }
    for _ in 0..2000 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if mean_force(c, mid, k_c, k_t) > load {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(Separation {
        d: 0.5 * (lo + hi),
        exact: false,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Two springs c = (1, 0), k = 1, L = 0.25: only the first is compressed,
    /// d = 0.5 (mean force (1 − d)/2 = 0.25). By hand.
    #[test]
    fn two_springs_by_hand() {
        let mut s = Vec::new();
        let r = solve_separation(&[1.0, 0.0], 1.0, 0.0, 0.25, &mut s).unwrap();
        assert!((r.d - 0.5).abs() < 1e-15 && r.exact);
        // L = 1: both compressed, (1 − d − d)/2 = 1 → d = −0.5.
        let r = solve_separation(&[1.0, 0.0], 1.0, 0.0, 1.0, &mut s).unwrap();
        assert!((r.d + 0.5).abs() < 1e-15);
        // With adhesion k_t = 0.5 and L = 0: (1 − d) + 0.5 (0 − d) = 0 → d = 2/3.
        let r = solve_separation(&[1.0, 0.0], 1.0, 0.5, 0.0, &mut s).unwrap();
        assert!((r.d - 2.0 / 3.0).abs() < 1e-15);
    }

    /// No adhesion and L ≤ 0: no contact, no separation.
    #[test]
    fn no_contact_without_load() {
        let mut s = Vec::new();
        assert!(solve_separation(&[1.0, 0.0], 1.0, 0.0, 0.0, &mut s).is_none());
        assert!(solve_separation(&[1.0, 0.0], 1.0, 0.0, -1.0, &mut s).is_none());
        assert!(solve_separation(&[1.0, 0.0], 1.0, 0.5, -1.0, &mut s).is_some());
    }

    proptest! {
        /// Selection and the full sort give the same separation on random
        /// compressions (with many ties: values drawn from a few levels, as
        /// on a periodic surface) to 1e-12 of the spread of c: the same
        /// formula, with sums taken in another order.
        #[test]
        fn selection_equals_the_sorted_solution(
            c in proptest::collection::vec(-1.0f64..1.0, 1..300),
            levels in proptest::collection::vec(-1.0f64..1.0, 1..6),
            tie in proptest::bool::ANY,
            load in -0.5f64..2.0,
            kt in prop_oneof![Just(0.0f64), 0.1f64..2.0],
        ) {
            let c: Vec<f64> = if tie {
                c.iter().map(|v| levels[((v + 1.0) * 100.0) as usize % levels.len()]).collect()
            } else {
                c
            };
            let (mut s1, mut s2) = (Vec::new(), Vec::new());
            let a = solve_separation(&c, 1.3, kt, load, &mut s1);
            let b = solve_separation_sorted(&c, 1.3, kt, load, &mut s2);
            prop_assert_eq!(a.is_some(), b.is_some());
            if let (Some(a), Some(b)) = (a, b) {
                prop_assert_eq!(a.exact, b.exact);
                prop_assert!((a.d - b.d).abs() <= 1e-12 * (1.0 + b.d.abs()), "{} vs {}", a.d, b.d);
            }
        }

        /// The sorted solution reproduces the load and agrees with bisection
        /// (to 1e-9 of the spread of c, far above bisection's last bit).
        #[test]
        fn sorting_agrees_with_bisection(
            c in proptest::collection::vec(-1.0f64..1.0, 1..40),
            load in -0.5f64..2.0,
            kt in prop_oneof![Just(0.0f64), 0.1f64..2.0],
        ) {
            let mut s = Vec::new();
            let a = solve_separation(&c, 1.3, kt, load, &mut s);
            let b = solve_separation_bisect(&c, 1.3, kt, load);
            prop_assert_eq!(a.is_some(), b.is_some());
            if let (Some(a), Some(b)) = (a, b) {
                prop_assert!((mean_force(&c, a.d, 1.3, kt) - load).abs() < 1e-9);
                prop_assert!((a.d - b.d).abs() < 1e-9, "{} vs {}", a.d, b.d);
            }
        }
    }
}
