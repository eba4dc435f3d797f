//! A test exported as several files (CETR's linear-wear module writes one
//! file per block of cycles), joined by the manifest's `test_id`: the
//! real CETR exports 001, 002, 003, 010 and 050 of one test, checked
//! against each file's own rows (read independently from the same run).

use crate::common;

use tribo::table::Table;

const FILES: [&str; 5] = [
    "HT-2n-6-4_2_050.csv",
    "HT-2n-6-4_2_002.csv",
    "HT-2n-6-4_2_010.csv",
    "HT-2n-6-4_2_001.csv",
    "HT-2n-6-4_2_003.csv",
];

/// The five CETR files in a temporary folder with a manifest of
/// `sample_id` and, when given, one `test_id`, through the friction stage:
/// its `friction_cycles` and `friction_tests`; `None` without ../shared.
fn run(test_id: Option<&str>) -> Option<(Table, Table)> {
    let dir = common::shared_real("tribometer_cetr_umt")?;
    let out = tempfile::tempdir().unwrap();
    let d = out.path();
    let mut manifest = String::from("file,sample_id,test_id\n");
    for f in FILES {
        std::fs::copy(dir.join(f), d.join(f)).unwrap();
        manifest.push_str(&format!("{f},HT-2n,{}\n", test_id.unwrap_or("")));
    }
    std::fs::write(d.join("samples.csv"), manifest).unwrap();
    let mut args = vec!["friction"];
    args.extend(FILES);
    args.extend(["--out", "o", "--samples", "samples.csv"]);
    let o = common::tribo(d, &args);
    assert!(
        o.status.code().is_some_and(|c| c <= 1),
        "{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let read = |n: &str| Table::read_parquet(&d.join("o").join(n)).unwrap().0;
    Some((
        read("friction_cycles.parquet"),
        read("friction_tests.parquet"),
    ))
}

/// The five files are one series, ordered by the headers' `Run date`
/// (the names given in another order); its cycles are each file's, in
/// that order, numbered 1..n and their sliding distances carried on from
/// file to file; its cycle count and distance are the sums of the files'
/// own rows; its steady μ is the mean of the whole cycles' μ from the
/// cycle it names; the skipped exports are said.
#[test]
fn cetr_exports_sharing_a_test_id_are_one_test() {
    let Some((cycles, tests)) = run(Some("HT-2n-6-4_2")) else {
        return;
    };
    let scope = tests.str("scope").unwrap();
    let series: Vec<usize> = (0..tests.height())
        .filter(|&i| scope[i].as_deref() == Some("series"))
        .collect();
    assert_eq!(series.len(), 1, "{scope:?}");
    let s = series[0];
    let get_i = |c: &str| tests.i64(c).unwrap()[s];
    let get_f = |c: &str| tests.f64(c).unwrap()[s];
    let get_s = |c: &str| tests.str(c).unwrap()[s].clone();
    assert_eq!(get_i("n_files"), Some(5));
    assert_eq!(get_s("series_order").as_deref(), Some("test_started_at"));
    assert_eq!(get_s("test_id").as_deref(), Some("HT-2n-6-4_2"));
    assert!(get_s("source").unwrap().ends_with("_001.csv"));
    let status = get_s("status").unwrap();
    let detail = get_s("status_detail").unwrap_or_default();
    assert!(
        status.contains("series_gap") && detail.contains("4-9, 11-49"),
        "{status}: {detail}"
    );

    // Each file's own rows, in the order of the run dates (= the names).
    let own: Vec<usize> = (0..tests.height()).filter(|&i| i != s).collect();
    assert_eq!(own.len(), 5);
    let sources = tests.str("source").unwrap();
    let n_own: i64 = own
        .iter()
        .map(|&i| tests.i64("n_cycles").unwrap()[i].unwrap())
        .sum();
    assert_eq!(get_i("n_cycles"), Some(n_own));
    let d_own: f64 = own
        .iter()
        .map(|&i| tests.f64("distance_m").unwrap()[i].unwrap())
        .sum();
    assert!((get_f("distance_m").unwrap() / d_own - 1.0).abs() < 1e-12);

    let (src, test_cycle) = (
        cycles.str("source").unwrap(),
        cycles.i64("test_cycle").unwrap(),
    );
    let (d0, d1) = (
        cycles.f64("distance_start_m").unwrap(),
        cycles.f64("distance_end_m").unwrap(),
    );
    let (t0, t1) = (
        cycles.f64("test_distance_start_m").unwrap(),
        cycles.f64("test_distance_end_m").unwrap(),
    );
    let mut order: Vec<usize> = (0..cycles.height()).collect();
    order.sort_by_key(|&i| test_cycle[i]);
    let mut names: Vec<&str> = FILES.to_vec();
    names.sort();
    let (mut carried, mut file_at, mut last_end) = (0.0, 0usize, 0.0);
    for (k, &i) in order.iter().enumerate() {
        assert_eq!(test_cycle[i], Some(k as i64 + 1));
        let name = src[i].as_deref().unwrap();
        if !name.ends_with(names[file_at]) {
            file_at += 1;
            assert!(
                name.ends_with(names[file_at]),
                "{name} after {}",
                names[file_at - 1]
            );
            carried = last_end;
        }
        assert!((t0[i].unwrap() - (d0[i].unwrap() + carried)).abs() < 1e-12);
        assert!((t1[i].unwrap() - (d1[i].unwrap() + carried)).abs() < 1e-12);
        last_end = t1[i].unwrap();
    }
    assert_eq!(file_at, 4);
    assert!(sources.iter().filter(|s| s.is_some()).count() == 6);

    // The steady μ: the mean of the last n_steady whole cycles' μ.
    if let (Some(mu), Some(n)) = (get_f("mu_steady"), get_i("n_steady")) {
        let (m, done) = (cycles.f64("mu").unwrap(), cycles.bool("complete").unwrap());
        let judged: Vec<f64> = order
            .iter()
            .filter(|&&i| done[i] == Some(true))
            .filter_map(|&i| m[i].filter(|v| v.is_finite()))
            .collect();
        assert_eq!(get_i("n_judged"), Some(judged.len() as i64));
        let tail = &judged[judged.len() - n as usize..];
        let mean = tail.iter().sum::<f64>() / tail.len() as f64;
        assert!((mu - mean).abs() < 1e-12, "{mu} vs {mean}");
    } else {
        assert!(status.contains("no_steady_state"), "{status}");
    }
}

/// Without a `test_id` each file is its own test: no series row, and the
/// test's numbering is the file's.
#[test]
fn files_without_a_test_id_stay_apart() {
    let Some((cycles, tests)) = run(None) else {
        return;
    };
    let scope = tests.str("scope").unwrap();
    assert!(scope.iter().all(|s| s.as_deref() != Some("series")));
    assert_eq!(
        cycles.i64("test_cycle").unwrap(),
        cycles.i64("cycle").unwrap()
    );
}
