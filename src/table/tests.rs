//! Tests of the table layer: string runs and dictionary columns.

use super::*;

fn categories(t: &Table, name: &str) -> Vec<String> {
    t.categories(name)
        .unwrap_or_else(|| panic!("{name} is not a dictionary column"))
}

fn strings(v: &[Option<&str>]) -> Vec<Option<String>> {
    v.iter().map(|s| s.map(str::to_string)).collect()
}

/// A string column from runs has a row per run length, nulls included.
#[test]
fn string_runs_keep_null_runs() {
    let t = TableBuilder::new()
        .str_runs("s", [(Some("a"), 2), (None, 3), (Some("b"), 1)])
        .build()
        .unwrap();
    let want = [Some("a"), Some("a"), None, None, None, Some("b")];
    assert_eq!(t.str("s").unwrap(), strings(&want));
}

/// A dictionary column from runs reads back from both writers as a
/// dictionary column with its values, and joins parts with different
/// categories into one dictionary in first-seen order.
#[test]
fn dictionary_column_round_trips_and_joins() {
    let a = TableBuilder::new()
        .cat_runs(
            "source",
            [(Some("b.csv"), 2), (None, 1), (Some("a.csv"), 3)],
        )
        .i64_runs("n", [(Some(1), 6)])
        .build()
        .unwrap();
    let b = TableBuilder::new()
        .cat_runs("source", [(Some("c.csv"), 1), (Some("a.csv"), 2)])
        .i64_runs("n", [(Some(2), 3)])
        .build()
        .unwrap();
    assert_eq!(a.column_type("source"), Some(ColumnType::Cat));
    assert_eq!(categories(&a, "source"), ["b.csv", "a.csv"]);
    let dir = tempfile::tempdir().unwrap();
    let (pa, pb) = (dir.path().join("a.parquet"), dir.path().join("b.parquet"));
    let units = [("source".to_string(), vec![("unit".into(), "".into())])];
    a.write_parquet_with(File::create(&pa).unwrap(), &[], &units)
        .unwrap();
    b.write_scratch_parquet(File::create(&pb).unwrap()).unwrap();
    let (ra, _) = Table::read_parquet(&pa).unwrap();
    let (rb, _) = Table::read_parquet(&pb).unwrap();
    let want_a = [
        Some("b.csv"),
        Some("b.csv"),
        None,
        Some("a.csv"),
        Some("a.csv"),
        Some("a.csv"),
    ];
    let want_b = [Some("c.csv"), Some("a.csv"), Some("a.csv")];
    assert_eq!(ra.column_type("source"), Some(ColumnType::Cat));
    assert_eq!(ra.str("source").unwrap(), strings(&want_a));
    assert_eq!(rb.str("source").unwrap(), strings(&want_b));

    let joined = Table::concat([ra, rb]).unwrap().unwrap();
    assert_eq!(joined.column_names(), ["source", "n"]);
    assert_eq!(categories(&joined, "source"), ["b.csv", "a.csv", "c.csv"]);
    let want: Vec<Option<&str>> = want_a.iter().chain(&want_b).copied().collect();
    assert_eq!(joined.str("source").unwrap(), strings(&want));
    let n = [1, 1, 1, 1, 1, 1, 2, 2, 2].map(Some);
    assert_eq!(joined.i64("n").unwrap(), n);
    assert_eq!(joined.null_count("source").unwrap(), 1);

    // Read as a dataset's files, in parallel: the same table.
    let stacked = Table::read_stacked(&[pa, pb]).unwrap().unwrap();
    assert_eq!(categories(&stacked, "source"), ["b.csv", "a.csv", "c.csv"]);
    assert_eq!(stacked.str("source").unwrap(), strings(&want));
    assert_eq!(stacked.i64("n").unwrap(), n);
    assert!(Table::read_stacked(&[]).unwrap().is_none());
}

/// Thousands of small files read from rayon's threads, as a run reads a
/// dataset's: each is decoded on the thread that reads it (polars' own
/// parallel decoding, entered there, nested reads until the stack
/// overflowed).
#[test]
fn many_small_files_are_read_from_rayon_threads() {
    use rayon::prelude::*;
    let dir = tempfile::tempdir().unwrap();
    let paths: Vec<_> = (0..3000)
        .map(|i| {
            let t = TableBuilder::new()
                .str("svg", [Some("x".repeat(4000 + i))])
                .i64("i", [Some(i as i64)])
                .build()
                .unwrap();
            let p = dir.path().join(format!("{i}.parquet"));
            t.write_scratch_parquet(File::create(&p).unwrap()).unwrap();
            p
        })
        .collect();
    let heights: Vec<usize> = (0..4)
        .into_par_iter()
        .map(|_| Table::read_stacked(&paths).unwrap().unwrap().height())
        .collect();
    assert_eq!(heights, [3000; 4]);
    let t = Table::read_stacked(&paths).unwrap().unwrap();
    let i: Vec<Option<i64>> = (0..3000).map(Some).collect();
    assert_eq!(t.i64("i").unwrap(), i);
}

/// A table passed on unchanged is the same table, whatever polars made of
/// its columns: empty joins of zero-length slices and all-null columns are
/// constant columns, which hold no memory to compare. An equal table built
/// apart is not the same.
#[test]
fn a_table_passed_on_is_the_same_one() {
    let built = || {
        TableBuilder::new()
            .f64("mu", [Some(0.1), None, Some(0.3)])
            .f64_null("none", 3)
            .str("s", [Some("a"), None, Some("c")])
            .build()
            .unwrap()
    };
    let t = built();
    let empty = Table::concat([t.slice(0, 0), t.slice(3, 0)])
        .unwrap()
        .unwrap();
    let nulls = Table::concat([t.slice(1, 1), t.slice(1, 1)])
        .unwrap()
        .unwrap();
    for table in [&t, &empty, &nulls] {
        assert!(table.clone().is_same(table), "{:?}", table.df);
    }
    assert!(!built().is_same(&t));
    assert!(!empty.is_same(&t.slice(0, 1)));
}

/// Rows gathered by ranges are those of the ranges' slices stacked, in
/// the ranges' order (dictionary columns read as their strings); ranges
/// that follow each other are one slice; a range past the end is an error.
#[test]
fn rows_of_ranges_are_their_slices_stacked() {
    let names = ["a", "b", "c", "d", "e", "f"];
    let t = TableBuilder::new()
        .f64_values("x", (0..6).map(f64::from))
        .cat_runs("s", names.iter().map(|n| (Some(*n), 1)))
        .build()
        .unwrap();
    let ranges = [(4, 2), (0, 1), (1, 1), (3, 1)];
    let got = t.rows_of(&ranges).unwrap();
    let slices = ranges.iter().map(|&(at, n)| t.slice(at, n));
    let want = Table::concat(slices).unwrap().unwrap();
    assert_eq!(got.f64("x").unwrap(), want.f64("x").unwrap());
    assert_eq!(got.str("s").unwrap(), want.str("s").unwrap());
    assert_eq!(
        got.f64("x").unwrap(),
        [4.0, 5.0, 0.0, 1.0, 3.0].map(Some).to_vec()
    );
    let one = t.rows_of(&[(1, 2), (3, 1)]).unwrap();
    assert_eq!(one.f64("x").unwrap(), [1.0, 2.0, 3.0].map(Some).to_vec());
    assert!(t.rows_of(&[(0, 1), (5, 2)]).is_err());
    assert_eq!(t.rows_of(&[]).unwrap().height(), 0);
}

/// One table's categories after `concat` are its rows' own, in first-seen
/// order: a slice of a table whose categories came in another order (or
/// hold values the slice lacks) joins to the same table as a fresh one.
#[test]
fn one_table_joins_to_first_seen_categories() {
    let t = TableBuilder::new()
        .cat_runs("status", [(Some("x"), 1), (Some("b"), 2), (Some("a"), 1)])
        .build()
        .unwrap();
    let joined = Table::concat([t.slice(1, 3)]).unwrap().unwrap();
    assert_eq!(categories(&joined, "status"), ["b", "a"]);
    let fresh = TableBuilder::new()
        .cat_runs("status", [(Some("b"), 2), (Some("a"), 1)])
        .build()
        .unwrap();
    assert_eq!(joined.df, fresh.df);
    assert_eq!(joined.df.schema(), fresh.df.schema());
}
