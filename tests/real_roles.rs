//! Every channel of each real friction export lands in its role, with its
//! unit converted as the instrument means it (skipped when ../shared is
//! absent). Channels that no friction feature uses are listed as such, so
//! a new role or a lost one fails here.

use crate::common;

use std::path::Path;

use tribo::ingest::inspect::inspect;
use tribo::ingest::{read_path, IngestOptions};
use tribo::table::Table;

/// (column, SI unit, role) of the first section of a file.
fn columns(f: &Path) -> Vec<(String, String, Option<&'static str>)> {
    let ds = read_path(f, &IngestOptions::default()).unwrap();
    let i = inspect(&ds, &Default::default());
    i.sections[0]
        .columns
        .iter()
        .map(|c| (c.name.clone(), c.si_unit.clone(), c.role))
        .collect()
}

/// CETR UMT: forces in gram-force (Ff too, though it has no role: it is the
/// instrument's |Fx|), X the stage position, V1 its velocity. Z, Y (other
/// axes), V2, V3 (their velocities) and Ff have no friction role.
#[test]
fn cetr_channels_land_in_their_roles() {
    let Some(dir) = common::shared_real("tribometer_cetr_umt") else {
        return;
    };
    let expected: [(&str, &str, Option<&str>); 11] = [
        ("Fx", "N", Some("friction_force")),
        ("Fz", "N", Some("normal_force")),
        ("Z", "m", None),
        ("Y", "m", None),
        ("X", "m", Some("position")),
        ("V1", "m/s", Some("velocity")),
        ("V2", "m/s", None),
        ("V3", "m/s", None),
        ("T", "s", Some("time")),
        ("Ff", "N", None),
        ("COF", "", Some("instrument_cof")),
    ];
    for f in common::files_with_ext(&dir, "csv") {
        let got = columns(&f);
        let got: Vec<(&str, &str, Option<&str>)> = got
            .iter()
            .map(|(n, u, r)| (n.as_str(), u.as_str(), *r))
            .collect();
        assert_eq!(got, expected, "{}", f.display());
    }
}

/// The pin-on-disc export: time, sliding distance, the instrument's μ and
/// the friction force; `Laps` is a count with no role.
#[test]
fn pin_on_disc_channels_land_in_their_roles() {
    let Some(dir) = common::shared_real("tribometer_pin_on_disc_tsv") else {
        return;
    };
    let expected: [(&str, &str, Option<&str>); 5] = [
        ("Time", "s", Some("time")),
        ("Distance", "m", Some("position")),
        ("Laps", "1", Some("laps")),
        ("mu", "1", Some("instrument_cof")),
        ("FrictionForce", "N", Some("friction_force")),
    ];
    for f in common::files_with_ext(&dir, "csv") {
        let got = columns(&f);
        let got: Vec<(&str, &str, Option<&str>)> = got
            .iter()
            .map(|(n, u, r)| (n.as_str(), u.as_str(), *r))
            .collect();
        assert_eq!(got, expected, "{}", f.display());
    }
}

/// The CETR traces carry position and velocity into the traces table (they
/// were null), in SI: X is 3.949250 mm in the first row; the velocity is
/// the crank's mean sliding speed 4·r·f from the step's header (240 rpm on
/// a 3.9493 mm crank), not the `V1` column's carriage drift (0.055864 mm/s).
#[test]
fn cetr_position_and_velocity_reach_the_traces_table() {
    let Some(dir) = common::shared_real("tribometer_cetr_umt") else {
        return;
    };
    let out = tempfile::tempdir().unwrap();
    let f = dir.join("HT-2n-6-4_2_001.csv");
    let o = common::tribo(out.path(), &["friction", f.to_str().unwrap(), "--out", "o"]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let t = common::read_table(&out.path().join("o/traces"));
    let x = t.f64("position_m").unwrap();
    let v = t.f64("velocity_m_per_s").unwrap();
    assert!((x[0].unwrap() - 3.949250e-3).abs() < 1e-12, "{:?}", x[0]);
    let mean_speed = 4.0 * 3.9493e-3 * 240.0 / 60.0;
    assert!((v[0].unwrap() - mean_speed).abs() < 1e-12, "{:?}", v[0]);
}

/// The pin-on-disc export has no normal force: without a manifest, μ is
/// null with `no_normal_force` and the run exits 1 (rows without a result),
/// never μ = NaN with exit 0.
#[test]
fn pin_on_disc_without_a_load_has_no_mu_and_exits_1() {
    let Some(dir) = common::shared_real("tribometer_pin_on_disc_tsv") else {
        return;
    };
    let out = tempfile::tempdir().unwrap();
    let f = dir.join("c1.csv");
    let o = common::tribo(
        out.path(),
        &["friction", f.to_str().unwrap(), "--out", "o", "--no-traces"],
    );
    assert_eq!(
        o.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let (t, _) = Table::read_parquet(&out.path().join("o/friction.parquet")).unwrap();
    for i in 0..t.height() {
        assert!(t.f64("mu_dynamic").unwrap()[i].is_none());
        assert!(t.f64("mu_static").unwrap()[i].is_none());
        let s = t.str("status").unwrap()[i].clone().unwrap();
        assert!(s.starts_with("no_normal_force"), "{s}");
    }
}

/// (column, SI unit, role) as a test expects it.
type Expected = (&'static str, &'static str, Option<&'static str>);

/// The tensile exports: every channel has its tensile role (Bluehill and
/// T150 name them differently; units in parentheses or on a third header
/// row).
#[test]
fn tensile_channels_land_in_their_roles() {
    let Some(root) = common::shared_real("") else {
        return;
    };
    let cases: [(&str, [Expected; 5]); 2] = [
        (
            "tensile_bluehill/Tens_Yield/Specimen_RawData_1.csv",
            [
                ("Time", "s", Some("time")),
                ("Extension", "m", Some("extension")),
                ("Load", "N", Some("force")),
                ("Tensile strain (Strain 1)", "1", Some("strain")),
                ("Tensile stress", "Pa", Some("stress")),
            ],
        ),
        (
            "nanotensile_t150/B_4_IS_1.txt",
            [
                ("EngineeringStrain", "1", Some("strain")),
                ("EngineeringStress", "Pa", Some("stress")),
                ("LoadOnSpecimen", "N", Some("force")),
                ("_Extension", "m", Some("extension")),
                ("_Time", "s", Some("time")),
            ],
        ),
    ];
    for (file, expected) in cases {
        let got = columns(&root.join(file));
        let got: Vec<(&str, &str, Option<&str>)> = got
            .iter()
            .map(|(n, u, r)| (n.as_str(), u.as_str(), *r))
            .collect();
        assert_eq!(got, expected, "{file}");
    }
}
