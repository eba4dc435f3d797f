//! Tests of [`super::radius`]: each source of a track radius, on the
//! stage positions of the real Rtec log.

use super::radius::*;
use super::{Dataset, MetaEntry, Section};
use std::path::Path;

fn section(step: u32, position_mm: Option<f64>) -> Section {
    let metadata = position_mm
        .map(|p| MetaEntry {
            key: RADIAL_POSITION.into(),
            value: format!("{p} mm"),
            line: 2,
        })
        .into_iter()
        .collect();
    Section {
        name: format!("Step {step}"),
        metadata,
        header_line: Some(2),
        first_data_line: 3,
        channels: vec![],
    }
}

fn dataset(name: &str, positions: &[Option<f64>]) -> Dataset {
    Dataset {
        source: name.into(),
        sha256: String::new(),
        format: "rtec",
        dialect: Some(crate::ingest::Dialect {
            encoding: crate::ingest::text::Encoding::Utf8,
            line_ending: crate::ingest::text::LineEnding::Lf,
            delimiter: ',',
            decimal: '.',
            quoted: false,
        }),
        preamble: vec![],
        grids: Vec::new(),
        sections: positions
            .iter()
            .enumerate()
            .map(|(k, p)| section(3 * k as u32 + 4, *p))
            .collect(),
    }
}

fn radii_mm(r: &[Option<TrackRadius>]) -> Vec<Option<(f64, &'static str)>> {
    r.iter()
        .map(|r| r.map(|r| ((r.radius_m * 1e6).round() / 1e3, r.source.as_str())))
        .collect()
}

/// The real Rtec log's stage positions (Y = −9.33 … −18.33 mm, 3 mm
/// apart) around a disc centre at −3.33 mm: 6, 9, 12, 15 mm, from the
/// name's range, a reference radius of 6 mm, the centre, or the table.
#[test]
fn four_tracks_from_each_source() {
    let ps = [Some(-9.33), Some(-12.33), Some(-15.33), Some(-18.33)];
    let name = "013_Rotary_3N_4tests_75-300mm-s_6-15mm-radius_3min-each.csv";
    let want = |src| {
        vec![
            Some((6.0, src)),
            Some((9.0, src)),
            Some((12.0, src)),
            Some((15.0, src)),
        ]
    };
    let ds = dataset(name, &ps);
    let r = track_radii(&ds, &RadiusHints::default()).unwrap();
    assert_eq!(radii_mm(&r), want("file_name_and_stage"));
    let hints = RadiusHints {
        radius_m: Some(6e-3),
        ..Default::default()
    };
    let plain = dataset("log.csv", &ps);
    assert_eq!(
        radii_mm(&track_radii(&plain, &hints).unwrap()),
        want("manifest_and_stage")
    );
    let hints = RadiusHints {
        centre_m: Some(-3.33e-3),
        ..Default::default()
    };
    assert_eq!(
        radii_mm(&track_radii(&plain, &hints).unwrap()),
        want("manifest_centre")
    );
    let steps = parse_steps("4:6 7:9 10:12 13:15").unwrap();
    let hints = RadiusHints {
        steps,
        radius_m: Some(1.0),
        ..Default::default()
    };
    assert_eq!(
        radii_mm(&track_radii(&plain, &hints).unwrap()),
        want("manifest_step")
    );
    let hints = RadiusHints {
        steps: parse_steps("6;9;12;15").unwrap(),
        ..Default::default()
    };
    assert_eq!(
        radii_mm(&track_radii(&plain, &hints).unwrap()),
        want("manifest_step")
    );
    // Nothing gives the radius: none, not a guess.
    assert_eq!(
        radii_mm(&track_radii(&plain, &RadiusHints::default()).unwrap()),
        vec![None; 4]
    );
}

/// A reference radius larger than the positions' span allows a centre
/// on either side: the radius is not known (unless the name's range
/// says which), never one of the two picked.
#[test]
fn an_ambiguous_reference_gives_no_radius() {
    let ps = [Some(0.0), Some(3.0)];
    let hints = RadiusHints {
        radius_m: Some(20e-3),
        ..Default::default()
    };
    let r = track_radii(&dataset("log.csv", &ps), &hints).unwrap();
    assert_eq!(radii_mm(&r), vec![None, None]);
    let r = track_radii(&dataset("log_20-23mm-radius.csv", &ps), &hints).unwrap();
    let s = "manifest_and_stage";
    assert_eq!(radii_mm(&r), vec![Some((20.0, s)), Some((23.0, s))]);
    let r = track_radii(&dataset("log_20-17mm-radius.csv", &ps), &hints).unwrap();
    assert_eq!(radii_mm(&r), vec![Some((20.0, s)), Some((17.0, s))]);
}

/// One track: the manifest's radius, else the name's, which says so.
#[test]
fn one_track() {
    let ps = [Some(-9.33), Some(-9.33)];
    let ds = dataset("pod_10mm-radius.csv", &ps);
    let r = track_radii(&ds, &RadiusHints::default()).unwrap();
    assert_eq!(radii_mm(&r), vec![Some((10.0, "file_name")); 2]);
    assert!(r[0].unwrap().source.from_file_name());
    let hints = RadiusHints {
        radius_m: Some(8e-3),
        ..Default::default()
    };
    assert_eq!(
        radii_mm(&track_radii(&ds, &hints).unwrap()),
        vec![Some((8.0, "manifest")); 2]
    );
    assert_eq!(
        radius_in_name(Path::new("a_radius-7.5mm.csv")),
        Some((7.5e-3, None))
    );
    assert_eq!(radius_in_name(Path::new("75-300mm-s.csv")), None);
}

#[test]
fn step_tables_that_do_not_read() {
    for bad in ["4:6 7", "a b", "4:-1", "", "4:6 x:9"] {
        assert!(parse_steps(bad).is_none(), "{bad}");
    }
    let hints = RadiusHints {
        steps: parse_steps("6 9 12").unwrap(),
        ..Default::default()
    };
    let e = track_radii(&dataset("a.csv", &[None, None]), &hints)
        .unwrap_err()
        .to_string();
    assert!(e.contains("3 radii") && e.contains("2 sections"), "{e}");
}
