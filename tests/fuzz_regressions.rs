//! Inputs the fuzz harness (`examples/fuzz.rs`) once found defects with,
//! kept in `fixtures/fuzz/`: each now ends in rows or a clean error.

use crate::common;

#[test]
fn every_found_input_now_ends_cleanly() {
    let dir = common::root().join("fixtures/fuzz");
    let mut n = 0;
    for e in std::fs::read_dir(&dir).unwrap() {
        let path = e.unwrap().path();
        if path.extension().is_some_and(|x| x == "md") {
            continue;
        }
        let bytes = std::fs::read(&path).unwrap();
        let finding = tribo::pipeline::fuzz::check_input(&path, &bytes);
        assert!(finding.is_none(), "{}: {finding:?}", path.display());
        n += 1;
    }
    assert!(n >= 1);
}

/// The overflowing Dektak profile is refused by the roughness stage with a
/// numerical error naming it, in `errors.parquet`; the run goes on.
#[test]
fn an_overflowing_profile_is_a_numerical_error_of_its_file() {
    let dir = tempfile::tempdir().unwrap();
    let f = common::root().join("fixtures/fuzz/fc48f2f59c8594af-dektak-1.csv");
    let good = common::root().join("fixtures/roughness/nanovea/test1.txt");
    let out = dir.path().join("out");
    let o = common::tribo(
        dir.path(),
        &[
            "roughness",
            &f.display().to_string(),
            &good.display().to_string(),
            "--out",
            &out.display().to_string(),
        ],
    );
    assert_eq!(o.status.code(), Some(1));
    let (errors, _) = tribo::table::Table::read_parquet(&out.join("errors.parquet")).unwrap();
    assert_eq!(errors.height(), 1);
    assert_eq!(errors.str("kind").unwrap()[0].as_deref(), Some("numerical"));
    let msg = errors.str("message").unwrap()[0].clone().unwrap();
    assert!(
        msg.contains("fc48f2f59c8594af") && msg.contains("Rq is not finite"),
        "{msg}"
    );
    assert_eq!(common::sources(&out, "roughness").len(), 1);
}
