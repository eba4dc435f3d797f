//! `tribo tensile` and `tribo tensile summarize` run as a user would, in a
//! temporary folder, on the fixtures.

use std::path::{Path, PathBuf};
use std::process::Command;

use tribo::table::Table;

fn fixture(name: &str) -> PathBuf {
    crate::common::root().join("fixtures/tensile").join(name)
}

fn tribo(args: &[&str]) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_tribo"))
        .args(args)
        .output()
        .expect("run tribo")
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

fn row_of(t: &Table, id: &str) -> usize {
    t.str("sample_id")
        .unwrap()
        .iter()
        .position(|x| x.as_deref() == Some(id))
        .unwrap_or_else(|| panic!("no row {id}"))
}

#[test]
fn tensile_then_summarize_on_the_fixtures() {
    let dir = tempfile::tempdir().unwrap();
    let out = dir.path().join("out");
    let files = [
        "t150_unknotted.txt",
        "t150_knotted.txt",
        "generic_force_extension.csv",
        "bluehill_truncated.csv",
    ]
    .map(fixture);
    let mut args = vec!["tensile"];
    args.extend(files.iter().map(|p| s(p)));
    let samples = fixture("samples.csv");
    args.extend(["--out", s(&out), "--samples", s(&samples)]);
    let o = tribo(&args);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let (t, meta) = Table::read_parquet(&out.join("tensile.parquet")).unwrap();
    assert_eq!(t.height(), 4);
    assert!(meta
        .iter()
        .any(|(k, v)| k == "tribo.command" && *v == args.join(" ")));
    let k = row_of(&t, "K1");
    assert_eq!(t.str("knot").unwrap()[k].as_deref(), Some("noose"));
    assert_eq!(t.bool("knot_effective").unwrap()[k], Some(true));
    assert_eq!(t.i64("plateau_drops").unwrap()[k], Some(10));
    assert_eq!(
        t.str("release_method").unwrap()[k].as_deref(),
        Some("after_drop")
    );
    let u = row_of(&t, "U1");
    // 70.4 MJ/m³ / 1.4 g/cm³ = 50.2857 J/g (fixture closed form; 1e-6 relative from the file's rounding)
    let tu = t.f64("toughness_J_per_g").unwrap()[u].unwrap();
    assert!((tu / (70.4 / 1.4) - 1.0).abs() < 1e-6, "{tu}");
    // instrument column next to ours
    let w = t.f64("instrument_energy_density_MJ_per_m3").unwrap()[u].unwrap();
    assert!((w - 70.4).abs() < 1e-9);
    // the Bluehill fixture: density 7.85 from the manifest, truncated record
    let b = row_of(&t, "B1");
    assert_eq!(t.bool("fracture_truncated").unwrap()[b], Some(true));
    assert!((t.f64("density_g_per_cm3").unwrap()[b].unwrap() - 7.85).abs() < 1e-12);

    // summarize our own table
    let g_out = dir.path().join("groups");
    let o = tribo(&[
        "tensile",
        "summarize",
        s(&out.join("tensile.parquet")),
        "--out",
        s(&g_out),
    ]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let (g, _) = Table::read_parquet(&g_out.join("tensile_groups.parquet")).unwrap();
    // groups: degummed/none, raw/none, raw/noose/true, steel/none
    assert_eq!(g.height(), 4);
    let knots = g.str("knot").unwrap();
    let i = knots
        .iter()
        .position(|k| k.as_deref() == Some("noose"))
        .unwrap();
    // toughness ratio against the raw control U1: T_k(K1) / T_u(U1)
    let tk = t.f64("toughness_J_per_g").unwrap()[k].unwrap();
    let r = g.f64("toughness_ratio_vs_control").unwrap()[i].unwrap();
    assert!((r - tk / tu).abs() < 1e-12 * r);
}

#[test]
fn summarize_reads_the_thesis_csv() {
    let dir = tempfile::tempdir().unwrap();
    let csv = fixture("thesis_tables_5_3_to_5_8.csv");
    let o = tribo(&["tensile", "summarize", s(&csv), "--out", s(dir.path())]);
    assert_eq!(
        o.status.code(),
        Some(0),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let (g, _) = Table::read_parquet(&dir.path().join("tensile_groups.parquet")).unwrap();
    let mat = g.str("material").unwrap();
    let knot = g.str("knot").unwrap();
    let eff = g.bool("knot_effective").unwrap();
    let i = (0..g.height())
        .find(|&i| {
            mat[i].as_deref() == Some("raw")
                && knot[i].as_deref() == Some("noose")
                && eff[i] == Some(true)
        })
        .unwrap();
    // Table 5.1: 229, T_k 45 ± 12, T_u' 15 ± 9 (rounded: ±0.5 plus the
    // thesis's own rounding, see tests/tensile_thesis_tables.rs)
    let v = |c: &str| g.f64(c).unwrap()[i].unwrap();
    assert!((v("strength_mean_MPa") - 229.0).abs() < 0.5);
    assert!((v("toughness_mean_J_per_g") - 45.0).abs() < 0.5);
    assert!((v("toughness_sd_J_per_g") - 12.0).abs() < 0.5);
    assert!((v("toughness_after_release_mean_J_per_g") - 15.0).abs() < 0.5);
    assert!((v("toughness_after_release_sd_J_per_g") - 9.0).abs() < 0.5);
    assert_eq!(g.i64("n").unwrap()[i], Some(8));
}

#[test]
fn bad_fibres_get_a_status_and_exit_code_1() {
    let dir = tempfile::tempdir().unwrap();
    // a NaN cell, a record that never breaks, and a manifest with a zero
    // diameter, an unknown control, and no row for one file
    let nan = dir.path().join("nan.csv");
    std::fs::write(
        &nan,
        "Strain [%],Stress [MPa]\n0,0\n1,100\n2,NaN\n3,300\n3.1,0\n3.2,0\n",
    )
    .unwrap();
    let nofrac = dir.path().join("nofrac.csv");
    std::fs::write(
        &nofrac,
        "Strain [mm/mm],Stress [GPa]\n0,0\n0.01,0.1\n0.02,0.2\n0.03,0.3\n",
    )
    .unwrap();
    let zero_d = dir.path().join("zero_d.csv");
    std::fs::write(
        &zero_d,
        "Extension [mm],Force [N]\n0,0\n0.1,1\n0.2,2\n0.3,0\n",
    )
    .unwrap();
    let knotted = dir.path().join("knotted.csv");
    std::fs::write(
        &knotted,
        "Strain [mm/mm],Stress [MPa]\n0,0\n0.01,300\n0.2,400\n0.4,500\n0.41,0\n0.42,0\n",
    )
    .unwrap();
    let samples = dir.path().join("samples.csv");
    std::fs::write(
        &samples,
        "file,sample_id,material,knot,diameter_um,fibre_length_mm,end_distance_mm,density_g_per_cm3,control_id\n\
         nofrac.csv,NF,raw,none,,,,,\n\
         zero_d.csv,ZD,raw,none,0,10,,,\n\
         knotted.csv,KN,raw,noose,,25,20,,GHOST\n",
    )
    .unwrap();
    let out = dir.path().join("out");
    let o = tribo(&[
        "tensile",
        s(&nan),
        s(&nofrac),
        s(&zero_d),
        s(&knotted),
        "--out",
        s(&out),
        "--samples",
        s(&samples),
    ]);
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let (t, _) = Table::read_parquet(&out.join("tensile.parquet")).unwrap();
    let status = crate::common::status_texts(&t);
    let st = |id: &str| status[row_of(&t, id)].clone().unwrap();
    assert!(st("nan").contains("no_manifest_row"), "{}", st("nan"));
    assert!(st("nan").contains("non_finite"), "{}", st("nan"));
    assert!(st("NF").contains("no_fracture"), "{}", st("NF"));
    assert!(st("ZD").contains("bad_diameter"), "{}", st("ZD"));
    assert!(st("KN").contains("control_not_found"), "{}", st("KN"));
    // no number where there is no answer
    let tough = t.f64("toughness_J_per_g").unwrap();
    for id in ["nan", "NF", "ZD"] {
        assert_eq!(tough[row_of(&t, id)], None, "{id}");
    }
    assert_eq!(t.f64("toughness_ratio").unwrap()[row_of(&t, "KN")], None);
    // usage errors exit 2
    let o = tribo(&["tensile", s(&nan)]);
    assert_eq!(o.status.code(), Some(2));
}

/// A Bluehill export with one unterminated quote in a data line failed —
/// in errors.parquet and counted as failed on stderr, naming the line —
/// rather than a row whose status hides it.
#[test]
fn a_file_without_a_usable_curve_is_a_failed_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(fixture("bluehill_truncated.csv")).unwrap();
    let broken = text.replacen(
        "\"0.00000\",\"0.00000\",\"0.00000\"",
        "\"0.00000,\"0.00000\",\"0.00000\"",
        1,
    );
    assert_ne!(broken, text);
    let file = dir.path().join("quote.csv");
    std::fs::write(&file, broken).unwrap();
    let ok = fixture("bluehill_truncated.csv");
    let out = dir.path().join("out");
    let o = tribo(&["tensile", s(&file), s(&ok), "--out", s(&out)]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.contains("FAILED") && err.contains("quote.csv"), "{err}");
    // The message names the line and its cause, not a missing column.
    assert!(err.contains("line 12: an unterminated quote"), "{err}");
    assert!(err.contains("1 of 2 files processed, 1 failed"), "{err}");
    let (e, _) = Table::read_parquet(&out.join("errors.parquet")).unwrap();
    let sources = e.str("source").unwrap();
    assert!(
        sources.iter().flatten().any(|s| s.ends_with("quote.csv")),
        "{sources:?}"
    );
    // The other file's row is written.
    let (t, _) = Table::read_parquet(&out.join("tensile.parquet")).unwrap();
    assert_eq!(t.height(), 1);
}
