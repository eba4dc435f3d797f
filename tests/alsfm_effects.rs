//! Effects: hierarchy (Eq. 2.17 and the locking level), wear reaching T_w
//! (μ → μ0), hierarchical wear, adhesion R_xy against L down to L ≤ 0.
#![deny(clippy::float_cmp)]

use tribo::models::alsfm::closed_form::{mu_across, mu_along, mu_hierarchy_along, WedgeCase};
use tribo::models::alsfm::hierarchy::cascade;
use tribo::models::alsfm::instant::SpringParams;
use tribo::models::alsfm::numeric_1d::Contact;
use tribo::models::alsfm::solver::{evaluate, Keep, Path, Resolution};
use tribo::models::alsfm::surface::Surface;
use tribo::simulate::alsfm::plan::Plan;
use tribo::simulate::alsfm::run;

fn wedge_scene(extra: &str, beta: &str, lower_flat: bool) -> String {
    let lower = if lower_flat {
        "[lower]\nkind = \"flat\"\n".to_string()
    } else {
        "[lower]\nkind = \"wedges\"\nphi_rise_deg = 30.0\nwavelength = 1.0\n".to_string()
    };
    format!(
        "mu0 = 0.3\nbeta_deg = {beta}\nload = 0.5\n{lower}\n[upper]\nkind = \"wedges\"\nphi_rise_deg = 30.0\nwavelength = 1.0\n\n[resolution]\nsprings = 60\n\n{extra}"
    )
}

/// Hierarchy at β = 90° on the numeric 1-D lattice, one evaluation per
/// level, against the power laws of Eq. 2.17 (both rough and one flat),
/// to 1e-9 relative per level.
#[test]
fn hierarchy_numeric_matches_eq_2_17() {
    let phi = 0.35_f64;
    let w = Surface::wedges(phi, 1.0);
    for (z1, case) in [
        (w.clone(), WedgeCase::BothRough),
        (Surface::Flat, WedgeCase::OneFlat),
    ] {
        let c = cascade(0.3, 4, |_, mu| {
            let contact = Contact {
                z1: &z1,
                z2: &w,
                mu0: mu,
                beta_deg: 90.0,
                springs: SpringParams::default(),
                load: 0.2,
            };
            let r = evaluate(
                &contact,
                &Resolution {
                    nx: Some(50),
                    ..Default::default()
                },
                &Keep {
                    force: Some(Path::Numeric1d),
                    ..Default::default()
                },
            )?;
            Ok(r.mu.unwrap())
        })
        .unwrap();
        for (n, mu) in c.mu.iter().enumerate() {
            let want = mu_hierarchy_along(case, 0.3, phi, n as u32).unwrap();
            assert!(
                (mu - want).abs() < 1e-9 * want,
                "{case:?} level {n}: {mu} vs {want}"
            );
        }
    }
}

/// With 30° wedges and μ0 = 0.3, μ_n = 0.3 / cos^n 30°: μ_12 = 1.685 <
/// cot 30° = 1.732 ≤ μ_13, so level 14 locks (MODELS.md §5: μ_{i−1} ≥
/// cot φ). The driver reports it.
#[test]
fn hierarchy_reports_the_locking_level() {
    let text = wedge_scene(
        "[hierarchy]\nlevels = 20\n\n[outputs]\nhierarchy = true\n",
        "90.0",
        false,
    );
    let out = run(&Plan::from_toml(&text).unwrap()).unwrap();
    let p = &out.points[0];
    assert_eq!(p.locked_level, Some(14));
    assert_eq!(p.status.cell(), "locked");
    assert!(p.mu.is_none());
    assert!(p.status.to_string().contains("level 14"), "{}", p.status);
    let last = out.hierarchy.last().unwrap();
    assert!(last.level == 14 && last.status.cell() == "locked" && last.mu.is_none());
    // Below the lock the levels follow Eq. 2.17.
    for r in &out.hierarchy[..14] {
        let want = 0.3 / f64::to_radians(30.0).cos().powi(r.level as i32);
        assert!((r.mu.unwrap() - want).abs() < 1e-12 * want);
    }
}

/// Wear reaching T_w gives μ0 (flat surfaces), and μ falls monotonically
/// with time before (Figs. 2.9, 2.10); also through the numeric path (β =
/// 45°).
#[test]
fn wear_reaches_mu0_at_t_w() {
    let text = wedge_scene(
        "[wear]\nrate = 1e-3\nreference_volume = 0.05\nsamples = 6\n\n[outputs]\nwear = true\n",
        "[0.0, 45.0, 90.0]",
        false,
    );
    let plan = Plan::from_toml(&text).unwrap();
    let out = run(&plan).unwrap();
    let t_w = 0.05 / 1e-3; // V0 / (W v), v = 1 m/s
    for beta in [0.0, 45.0, 90.0] {
        let rows: Vec<_> = out
            .wear
            .iter()
            .filter(|r| (r.beta_deg - beta).abs() < 1e-12)
            .collect();
        assert_eq!(rows.len(), 6);
        let last = rows.last().unwrap();
        assert!((last.time_s - t_w).abs() < 1e-9 && last.reduction_b.abs() < 1e-15);
        assert!(
            (last.mu.unwrap() - 0.3).abs() < 1e-15,
            "beta {beta}: {:?}",
            last.mu
        );
        for pair in rows.windows(2) {
            assert!(pair[1].mu.unwrap() < pair[0].mu.unwrap(), "beta {beta}");
        }
    }
}

/// Wedges wearing against a flat (Case 1): the wear scales their heights
/// by B(t), so every sample of the run, not only its end, must be the
/// closed form at tan φ(t) = B(t) tan 30° (Eq. 2.9): across at β = 0°,
/// along at β = 90°. The lattice and the closed forms are computed apart.
#[test]
fn wear_follows_the_closed_form_at_every_sample() {
    let text = wedge_scene(
        "[wear]\nrate = 1e-3\nreference_volume = 0.05\nsamples = 8\n\n[outputs]\nwear = true\n",
        "[0.0, 90.0]",
        true,
    );
    let out = run(&Plan::from_toml(&text).unwrap()).unwrap();
    let tan0 = 30f64.to_radians().tan();
    let mut n = 0;
    for r in &out.wear {
        let phi = (r.reduction_b * tan0).atan();
        let want = match r.beta_deg < 45.0 {
            true => mu_across(WedgeCase::OneFlat, 0.3, phi).unwrap(),
            false => mu_along(WedgeCase::OneFlat, 0.3, phi).unwrap(),
        };
        let got = r.mu.unwrap();
        assert!(
            (got - want).abs() < 1e-9 * want,
            "β {} B {}: {got} vs {want}",
            r.beta_deg,
            r.reduction_b
        );
        n += 1;
    }
    assert_eq!(n, 16);
}

/// Hierarchical wear (Fig. 2.14): the innermost level wears first (T_1 =
/// T_w), then the next (T_2 = 10 T_w); when level 1 is flat the outer
/// coefficient is the two-level value; at the end μ = μ0.
#[test]
fn hierarchical_wear_cascades_outwards() {
    let text = wedge_scene(
        "[hierarchy]\nlevels = 2\nscale = 10.0\nwear = true\n\n[wear]\nrate = 1e-3\nreference_volume = 0.01\nsamples = 12\n\n[outputs]\nwear = true\nhierarchy = true\n",
        "90.0",
        false,
    );
    let out = run(&Plan::from_toml(&text).unwrap()).unwrap();
    let t1 = 10.0; // 0.01 / 1e-3
    let c = f64::to_radians(30.0).cos();
    // Samples every 11 T_w / 11 = T_w: k = 1 is the end of level 1's wear.
    let r1 = &out.wear[1];
    assert!((r1.time_s - t1).abs() < 1e-9 && r1.wearing_level == 2);
    assert!((r1.mu.unwrap() - 0.3 / c).abs() < 1e-12, "{:?}", r1.mu);
    assert!((out.wear[0].mu.unwrap() - 0.3 / (c * c)).abs() < 1e-12);
    let end = out.wear.last().unwrap();
    assert!((end.mu.unwrap() - 0.3).abs() < 1e-15);
    for pair in out.wear.windows(2) {
        assert!(pair[1].mu.unwrap() <= pair[0].mu.unwrap() + 1e-15);
    }
}

/// Adhesion (Sec. 2.1, Figs. 2.3, 2.4): R_xy against L down to L < 0 with a
/// 1-D sinusoid at β = 0. R_xy stays finite and positive at L = 0 (some
/// springs still compressed), decreases with L, and the tensile fraction
/// grows as L decreases; above the load where all springs are compressed,
/// adhesion changes nothing.
#[test]
fn adhesion_rxy_against_load() {
    let text = "mu0 = 0.3\nbeta_deg = 0.0\nload = { from = 0.2, to = -0.04, count = 13 }\n\
        [lower]\nkind = \"sinusoid\"\namplitude = 0.05\nlambda_x = 1.0\n\
        [upper]\nkind = \"sinusoid\"\namplitude = 0.05\nlambda_x = 1.0\n\
        [adhesion]\n[resolution]\nsprings = 64\n[outputs]\nadhesion = true\n";
    let out = run(&Plan::from_toml(text).unwrap()).unwrap();
    let a = &out.adhesion;
    assert_eq!(a.len(), 13);
    for pair in a.windows(2) {
        assert!(pair[1].r_xy.unwrap() < pair[0].r_xy.unwrap(), "{:?}", pair);
        assert!(pair[1].tension_fraction.unwrap() >= pair[0].tension_fraction.unwrap());
    }
    let zero = a.iter().find(|r| r.load.abs() < 1e-12).unwrap();
    assert!(zero.r_xy.unwrap() > 0.0 && zero.mu_apparent.is_none());
    assert!(a.last().unwrap().r_xy.unwrap() >= 0.0);
    // L = 0.2 ≥ the gap's spread (0.2): no tension, μ_a equals the
    // adhesion-free μ.
    assert!(a[0].tension_fraction.unwrap() < 1e-15);
    let no_adh = run(&Plan::from_toml(
        &text
            .replace("[adhesion]\n", "")
            .replace("to = -0.04, count = 13", "to = 0.2, count = 1"),
    )
    .unwrap())
    .unwrap();
    assert!((no_adh.points[0].mu.unwrap() - a[0].mu_apparent.unwrap()).abs() < 1e-15);
    // Below the full-contact load the adhesive μ_a = R_xy / L exceeds it.
    assert!(a[6].mu_apparent.unwrap() > a[0].mu_apparent.unwrap());
}
