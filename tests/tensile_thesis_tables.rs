//! The per-fibre rows of the thesis's supplementary Tables 5.3–5.8
//! (transcribed in `fixtures/tensile/thesis_tables_5_3_to_5_8.csv`), given to
//! the group summary, must reproduce Table 5.1 (MODELS.md §3).
//!
//! Tolerance: Table 5.1 prints integers (Tables 5.7/5.8 one decimal) that
//! are rounded or truncated (237.75 is printed 237), so a value agrees when
//! it is within one unit of the last printed digit.

use tribo::extract::tensile::summary::fill_ratios;
use tribo::extract::tensile::{groups_table, rows_from_table, summarize, GroupSummary};
use tribo::ingest::csv_table::read_csv_table;

fn groups() -> Vec<GroupSummary> {
    let path = crate::common::root().join("fixtures/tensile/thesis_tables_5_3_to_5_8.csv");
    let t = read_csv_table(&path).unwrap();
    let mut rows = rows_from_table(&t, 0.08).unwrap();
    fill_ratios(&mut rows);
    summarize(&rows)
}

fn find<'a>(g: &'a [GroupSummary], mat: &str, knot: &str, eff: Option<bool>) -> &'a GroupSummary {
    g.iter()
        .find(|s| s.material == mat && s.knot == knot && s.knot_effective == eff)
        .unwrap_or_else(|| panic!("no group {mat} {knot} {eff:?}"))
}

fn close(ours: Option<f64>, printed: f64, unit: f64, what: &str) {
    let v = ours.unwrap_or_else(|| panic!("{what}: missing"));
    assert!(
        (v - printed).abs() <= unit,
        "{what}: ours {v}, Table 5.1 {printed} (± {unit})"
    );
}

/// (material, knot, effective, strength mean ± sd, T mean ± sd, T_u' mean ± sd)
type Row = (
    &'static str,
    &'static str,
    Option<bool>,
    [f64; 2],
    [f64; 2],
    Option<[f64; 2]>,
);

#[test]
fn table_5_1_is_reproduced_from_tables_5_3_to_5_8() {
    let g = groups();
    let table_5_1: [Row; 8] = [
        // controls: Table 5.1 prints T_u as 20 ± 11 and 29 ± 13; Tables 5.7/5.8 give one decimal
        ("raw", "none", None, [219.0, 68.0], [20.5, 11.1], None),
        ("degummed", "none", None, [481.0, 91.0], [29.3, 12.8], None),
        (
            "raw",
            "noose",
            Some(true),
            [229.0, 50.0],
            [45.0, 12.0],
            Some([15.0, 9.0]),
        ),
        (
            "raw",
            "noose",
            Some(false),
            [216.0, 46.0],
            [19.0, 8.0],
            Some([16.0, 7.0]),
        ),
        (
            "raw",
            "overhand_loop",
            Some(false),
            [237.0, 53.0],
            [17.0, f64::NAN],
            Some([16.0, 8.0]),
        ),
        (
            "degummed",
            "noose",
            Some(true),
            [343.0, 104.0],
            [28.0, 9.0],
            None,
        ),
        (
            "degummed",
            "noose",
            Some(false),
            [463.0, 120.0],
            [36.0, 18.0],
            None,
        ),
        (
            "degummed",
            "overhand_loop",
            Some(false),
            [434.0, 146.0],
            [29.0, 17.0],
            Some([27.0, 17.0]),
        ),
    ];
    for (mat, knot, eff, s, t, tu) in table_5_1 {
        let what = format!("{mat} {knot} {eff:?}");
        let grp = find(&g, mat, knot, eff);
        let unit = if knot == "none" { 0.1 } else { 1.0 };
        close(grp.strength.0, s[0], 1.0, &format!("{what} strength mean"));
        close(grp.strength.1, s[1], 1.0, &format!("{what} strength sd"));
        close(grp.toughness.0, t[0], unit, &format!("{what} T mean"));
        if t[1].is_finite() {
            close(grp.toughness.1, t[1], unit, &format!("{what} T sd"));
        }
        if let Some(tu) = tu {
            close(
                grp.after_release.0,
                tu[0],
                1.0,
                &format!("{what} T_u' mean"),
            );
            close(grp.after_release.1, tu[1], 1.0, &format!("{what} T_u' sd"));
        }
    }
    // the example of the issue: raw silk, noose, > 8 %: 229, T_k 45 ± 12, T_u' 15 ± 9, n = 8
    let ex = find(&g, "raw", "noose", Some(true));
    assert_eq!((ex.n, ex.after_release_n), (8, 4));
}

/// Where Table 5.1 disagrees with its own supplementary rows, the rows
/// win; these golden values were computed by hand from the CSV (mean and
/// n − 1 sd, 2 decimals) and document the discrepancies listed in
/// docs/tensile.md.
#[test]
fn known_misprints_of_table_5_1_are_documented() {
    let g = groups();
    // raw O. L. T_k: Table 5.1 prints 17 ± 18; the eight rows give 16.91 ± 8.07
    let ol = find(&g, "raw", "overhand_loop", Some(false));
    close(ol.toughness.1, 8.07, 0.005, "raw O.L. T_k sd");
    // the strength mean uses only the 8 fibres with T_k (237.75), not all 17 (215.2)
    assert_eq!((ol.n, ol.n_incomplete), (8, 9));
    // degummed Noose T_u': Table 5.1 prints 29 ± 17 in both classes (and for
    // O. L.); the rows give 11.23 ± 7.28 (> 8 %) and 28.43 ± 18.91 (< 8 %)
    let hi = find(&g, "degummed", "noose", Some(true));
    close(
        hi.after_release.0,
        11.23,
        0.005,
        "degummed noose >8% T_u' mean",
    );
    close(
        hi.after_release.1,
        7.28,
        0.005,
        "degummed noose >8% T_u' sd",
    );
    let lo = find(&g, "degummed", "noose", Some(false));
    close(
        lo.after_release.0,
        28.43,
        0.005,
        "degummed noose <8% T_u' mean",
    );
    close(
        lo.after_release.1,
        18.91,
        0.005,
        "degummed noose <8% T_u' sd",
    );
}

#[test]
fn comparison_with_controls_follows_the_stated_definitions() {
    let g = groups();
    let ex = find(&g, "raw", "noose", Some(true));
    // mean T_k 361.4/8 = 45.175 J/g over control mean T_u 164.3/8 = 20.5375 J/g
    let ratio = 45.175 / 20.5375;
    // sums of one-decimal values: exact to ~1e-13
    assert!((ex.toughness_ratio_vs_control().unwrap() - ratio).abs() < 1e-12);
    assert!((ex.toughness_increase_pct().unwrap() - (ratio - 1.0) * 100.0).abs() < 1e-9);
    // strength 229 vs control mean 1751/8 = 218.875 MPa: +4.626 %
    let change = (229.0 / 218.875 - 1.0) * 100.0;
    assert!((ex.strength_change_pct().unwrap() - change).abs() < 1e-9);
    // per-fibre ratios: T_k/T_u' for 4 fibres, T_k/T_u of the control for 4
    let per_fibre = [
        52.1 / 23.1,
        39.4 / 7.7,
        27.8 / 7.3,
        41.7 / 22.9,
        67.7 / 32.6,
        53.1 / 19.6,
        37.1 / 8.5,
        42.5 / 8.5,
    ];
    let mean = per_fibre.iter().sum::<f64>() / 8.0;
    assert_eq!(ex.fibre_ratio_n, 8);
    assert!((ex.fibre_ratio.0.unwrap() - mean).abs() < 1e-12);
    // controls are not compared with themselves
    assert_eq!(
        find(&g, "raw", "none", None).toughness_ratio_vs_control(),
        None
    );
    // the table is written with the schema's columns
    let t = groups_table(&g).unwrap();
    tribo::pipeline::registry::schema("tensile_groups")
        .unwrap()
        .check(&t)
        .unwrap();
    // and its row of the group holds the comparison: 8 controls, the
    // per-fibre ratios' sd (numpy `std(ddof=1)`: 1.3435843999413797) and
    // mean increase ((mean − 1) · 100 = 239.40063651816584 %, numpy)
    let row = g.iter().position(|s| std::ptr::eq(s, ex)).unwrap();
    let cell = |c: &str| t.f64(c).unwrap()[row].unwrap();
    assert_eq!(t.i64("control_n").unwrap()[row], Some(8));
    assert!((cell("fibre_ratio_sd") - 1.3435843999413797).abs() < 1e-12);
    assert!((cell("fibre_increase_mean_pct") - 239.40063651816584).abs() < 1e-9);
    assert!((cell("fibre_increase_mean_pct") - (mean - 1.0) * 100.0).abs() < 1e-9);
}
