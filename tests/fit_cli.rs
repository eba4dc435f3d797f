//! The fit and simulate commands run end to end in a temporary folder and
//! write schema-valid tables.

use std::process::Command;

use tribo::table::{Table, TableBuilder};

fn tribo() -> Command {
    Command::new(env!("CARGO_BIN_EXE_tribo"))
}

#[test]
fn fit_coulomb_writes_its_tables() {
    let dir = tempfile::tempdir().unwrap();
    let n: Vec<f64> = (0..8).map(|i| 1.0 + (i % 4) as f64).collect();
    let t = TableBuilder::new()
        .str(
            "sample_id",
            (0..8).map(|i| Some(if i < 4 { "S1" } else { "S2" })),
        )
        .str("pattern", (0..8).map(|_| Some("F")))
        .f64_values("apparent_area_m2", (0..8).map(|_| 4e-4))
        .f64_values("area_fraction", (0..8).map(|_| 1.0))
        .f64_values("normal_force_N", n.clone())
        .f64_values("static_force_N", n.iter().map(|n| 0.05 + 0.4 * n))
        .f64_values("dynamic_force_N", n.iter().map(|n| 0.04 + 0.3 * n))
        .build()
        .unwrap();
    let input = dir.path().join("friction.parquet");
    t.write_parquet_to(std::fs::File::create(&input).unwrap(), &[])
        .unwrap();
    let st = tribo()
        .args(["fit", "coulomb"])
        .arg(&input)
        .arg("--out")
        .arg(dir.path())
        .status()
        .unwrap();
    assert!(st.success(), "{st:?}");
    let (c, meta) = Table::read_parquet(&dir.path().join("coulomb.parquet")).unwrap();
    assert!(meta.iter().any(|(k, v)| k == "tribo.command"
        && *v
            == format!(
                "fit coulomb {} --out {}",
                input.display(),
                dir.path().display()
            )));
    // 2 samples + 1 pattern, x 2 regimes.
    assert_eq!(c.height(), 6);
    let mu = c.f64("mu").unwrap();
    assert!(mu
        .iter()
        .flatten()
        .all(|m| (m - 0.4).abs() < 1e-12 || (m - 0.3).abs() < 1e-12));
    assert!(dir.path().join("coulomb_summary.parquet").exists());
}

#[test]
fn simulate_ice_writes_the_grid() {
    let dir = tempfile::tempdir().unwrap();
    let st = tribo()
        .args([
            "simulate",
            "ice",
            "--v",
            "0.025",
            "1",
            "5",
            "--t=-10",
            "--a=1e-4",
            "--phi=7.3",
        ])
        .arg("--out")
        .arg(dir.path())
        .status()
        .unwrap();
    assert!(st.success());
    let (g, _) = Table::read_parquet(&dir.path().join("ice_grid.parquet")).unwrap();
    assert_eq!(g.height(), 5);
}

#[test]
fn fit_nist_prints_the_table_for_the_embedded_problem() {
    let out = tribo()
        .args(["fit", "nist"])
        .arg(crate::common::root().join("fixtures/nist"))
        .output()
        .unwrap();
    assert!(out.status.success());
    let s = String::from_utf8(out.stdout).unwrap();
    assert!(
        s.contains("Misra1a") && s.contains("start 2: 1/1 converged"),
        "{s}"
    );
}
