//! NIST StRD nonlinear regression suite: every problem from both starts.
//! Target: ≥ 6 correct digits (LRE) on the parameters and ≥ 4 on the
//! standard errors from start 2, ≥ 4 on both from start 1 — or an honest
//! non-converged status. A wrong answer reported as converged fails.
//! The data lives outside the repository (`../shared/data/nist_strd`); when
//! it is absent the suite prints a note and passes, and the embedded
//! fixture (Misra1a) still exercises the solver.

use std::path::PathBuf;

use tribo::fit::nist::{read_nist, run_dir, run_problem};
use tribo::fit::LmParams;

fn shared_dir() -> Option<PathBuf> {
    crate::common::shared("data/nist_strd")
}

#[test]
fn every_nist_problem_meets_its_digits_or_says_it_failed() {
    let Some(dir) = shared_dir() else {
        eprintln!("note: ../shared/data/nist_strd absent; NIST suite skipped");
        return;
    };
    let rows = run_dir(&dir, &LmParams::default()).unwrap();
    assert_eq!(rows.len(), 54, "27 problems x 2 starts");
    eprintln!("{}", tribo::fit::nist::format_table(&rows));
    let mut bad = vec![];
    for r in &rows {
        let need_b = if r.start == 2 { 6.0 } else { 4.0 };
        // The standard errors scale with s = √(RSS/dof); when the residuals
        // sit at the rounding level of the data (Lanczos1: RSS 1.4e-25 for
        // y ≈ 2.5), double precision cannot give s² to 4 digits, and the
        // report says so through `rss_digits`.
        let se_limited = r.rss_digits.is_some_and(|d| d < 4.0);
        if r.status.is_converged() && (r.lre_params < need_b || (r.lre_se < 4.0 && !se_limited)) {
            bad.push(format!(
                "{} start {}: LRE b {:.1} se {:.1} ({})",
                r.name, r.start, r.lre_params, r.lre_se, r.status
            ));
        }
    }
    assert!(bad.is_empty(), "wrong answers reported converged: {bad:#?}");
}

/// The embedded Misra1a (public domain, NIST) keeps a fresh clone testing
/// the solver without the shared data.
#[test]
fn embedded_misra1a_from_both_starts() {
    let path = crate::common::root().join("fixtures/nist/Misra1a.dat");
    let data = read_nist(&path).unwrap();
    for start in [1, 2] {
        let r = run_problem(&data, start, true, &LmParams::default()).unwrap();
        assert!(r.status.is_converged(), "{}", r.status);
        assert!(r.lre_params >= 6.0 && r.lre_se >= 4.0, "{r:?}");
    }
}
