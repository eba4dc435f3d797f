//! A pin-on-disc trace that gives the spindle speed in rpm: the sliding
//! velocity is v = ω r with the manifest's track radius; without a radius
//! the file fails saying what to add.

use crate::common;

use std::path::Path;

/// 20 s at 10 Hz: `Time [s]`, `Speed [rpm]` (60 rpm), `Ff [N]`, `Fn [N]`.
fn write(dir: &Path) {
    let mut s = String::from("Time [s],Speed [rpm],Ff [N],Fn [N]\n");
    for i in 0..200 {
        let t = i as f64 * 0.1;
        let f = if t < 1.0 { 2.0 * t } else { 1.5 };
        s.push_str(&format!("{t:.1},60,{f:.3},5\n"));
    }
    std::fs::write(dir.join("pod.csv"), s).unwrap();
}

fn run(dir: &Path, manifest: &str) -> std::process::Output {
    std::fs::write(dir.join("samples.txt"), manifest).unwrap();
    common::tribo(
        dir,
        &[
            "friction",
            "pod.csv",
            "--out",
            "o",
            "--samples",
            "samples.txt",
        ],
    )
}

/// 60 rpm = 2π rad/s; on a 10 mm track radius v = 2π × 0.01 m/s.
#[test]
fn rpm_with_a_track_radius_gives_the_sliding_velocity() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path());
    let o = run(dir.path(), "file,track_radius_mm\npod.csv,10\n");
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let t = crate::common::read_table(&dir.path().join("o/traces"));
    let v = t.f64("velocity_m_per_s").unwrap();
    let expected = 2.0 * std::f64::consts::PI * 0.01;
    for x in v.iter().take(5) {
        assert!((x.unwrap() - expected).abs() < 1e-12, "{x:?}");
    }
}

#[test]
fn rpm_without_a_track_radius_is_a_file_error() {
    let dir = tempfile::tempdir().unwrap();
    write(dir.path());
    let o = run(dir.path(), "file,sample_id\npod.csv,P\n");
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(
        err.contains("'Speed'") && err.contains("track_radius_mm"),
        "{err}"
    );
}
