//! Column and unit overrides in a pipeline file make an odd export usable:
//! German column names without units, read through `[[ingest.override]]`.

use crate::common;

use tribo::table::Table;

#[test]
fn overrides_name_columns_and_units() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = String::from("Zeit;Kraft;Last\n");
    for i in 0..400 {
        let t = i as f64 * 0.01;
        let f = if t < 1.0 {
            600.0 * t
        } else if t < 1.1 {
            600.0 - 1000.0 * (t - 1.0)
        } else {
            500.0
        };
        text.push_str(&format!(
            "{};{};{}\n",
            format!("{t:.2}").replace('.', ","),
            format!("{f:.1}").replace('.', ","),
            "1000,0"
        ));
    }
    std::fs::write(dir.path().join("legacy_1.txt"), &text).unwrap();
    std::fs::write(
        dir.path().join("p.toml"),
        r#"
[input]
files = ["legacy_*.txt"]
[output]
dir = "out"
[[ingest.override]]
files = "legacy_*.txt"
columns = { time = "Zeit", friction_force = "Kraft", normal_force = "Last" }
units = { Zeit = "s", Kraft = "mN", Last = "mN" }
"#,
    )
    .unwrap();
    let o = common::tribo(dir.path(), &["run", "p.toml"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (t, _) = Table::read_parquet(&dir.path().join("out/friction.parquet")).unwrap();
    assert_eq!(t.str("status").unwrap()[0].as_deref(), Some("ok"));
    // 600 mN / 1000 mN and 500 mN / 1000 mN, noise-free. The window may
    // start on the last samples of the decay inside the 3 % band (at most
    // +15 mN on a few of ~280 samples: below 2e-4 in μ).
    assert!((t.f64("mu_static").unwrap()[0].unwrap() - 0.6).abs() < 1e-9);
    let mu_d = t.f64("mu_dynamic").unwrap()[0].unwrap();
    assert!((0.5..0.5002).contains(&mu_d), "{mu_d}");
    assert!((t.f64("normal_force_N").unwrap()[0].unwrap() - 1.0).abs() < 1e-12);

    // Without the override, the missing units are a clear error.
    std::fs::write(
        dir.path().join("q.toml"),
        "[input]\nfiles = [\"legacy_*.txt\"]\n[output]\ndir = \"out2\"\n",
    )
    .unwrap();
    let o = common::tribo(dir.path(), &["run", "q.toml"]);
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("legacy_1.txt") && err.contains("no friction_force column"),
        "{err}"
    );
}
