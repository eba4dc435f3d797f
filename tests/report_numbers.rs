//! The report's numbers: every float column of every table, in the unit
//! its schema gives it with one prefix for the column, reads back as the
//! value it shows (no nonzero value shown as zero), on the demo and on the
//! real exports of other labs.

use std::path::Path;

use tribo::pipeline::registry;
use tribo::report::numbers::{format_column, NONE};
use tribo::table::{ColumnType, Table};

use crate::common::{files_with_ext, run_demo};

/// Checks every float column of every table in `out` as the report formats
/// it; returns how many nonzero values were checked.
fn check_tables(out: &Path) -> usize {
    let mut checked = 0;
    for path in files_with_ext(out, "parquet") {
        let stem = path.file_stem().unwrap().to_string_lossy().to_string();
        let Some(def) = registry::find(&stem) else {
            continue;
        };
        let schema = def.schema().unwrap();
        let (t, _) = Table::read_parquet(&path).unwrap();
        for spec in &schema.column {
            if t.column_type(&spec.name) != Some(ColumnType::F64) {
                continue;
            }
            let values = t.f64(&spec.name).unwrap();
            let n = format_column(&values, &spec.unit);
            let at = format!("{stem}.{} [{}]", spec.name, n.unit);
            assert!(!n.unit.contains(['[', ']']), "{at}");
            for (v, cell) in values.iter().zip(&n.cells) {
                let Some(v) = v.filter(|v| v.is_finite()) else {
                    assert_eq!(cell, NONE, "{at}");
                    continue;
                };
                // A cell is a plain number: the unit (one prefix) is the
                // column's, never the cell's.
                let shown: f64 = cell
                    .parse()
                    .unwrap_or_else(|_| panic!("{at}: {cell:?} is not a number"));
                if v == 0.0 {
                    assert_eq!(shown, 0.0, "{at}");
                    continue;
                }
                assert!(shown != 0.0, "{at}: {v} shown as {cell}");
                let back = shown * n.scale;
                assert!(
                    (back - v).abs() <= 0.05 * v.abs(),
                    "{at}: {v} shown as {cell}"
                );
                checked += 1;
            }
        }
    }
    checked
}

/// The page's tables: each numeric cell a plain number or a dash, each
/// heading with one unit at most.
fn check_page(html: &str) {
    let mut cells = 0;
    for cell in html.split("<td class=\"num\">").skip(1) {
        let cell = &cell[..cell.find("</td>").unwrap()];
        assert!(cell == NONE || cell.parse::<f64>().is_ok(), "cell {cell:?}");
        cells += 1;
    }
    assert!(cells > 0, "no numbers on the page");
    for head in html.split("<th>").skip(1) {
        let head = &head[..head.find("</th>").unwrap()];
        assert!(head.matches(" [").count() <= 1, "heading {head:?}");
    }
}

#[test]
fn every_number_of_the_demo_reads_back_in_its_columns_unit() {
    let dir = tempfile::tempdir().unwrap();
    run_demo(dir.path());
    let n = check_tables(dir.path());
    assert!(n > 1000, "{n} values");
    let html = std::fs::read_to_string(dir.path().join("report.html")).unwrap();
    check_page(&html);
    // Roughness in µm or nm, strengths in MPa or GPa: a prefix per column.
    let rq = html.split("<th>Rq [").nth(1).expect("Rq heading");
    assert!(
        rq.starts_with("µm]") || rq.starts_with("nm]"),
        "{}",
        &rq[..8]
    );
    assert!(html.contains("<th>strength [MPa]</th>") || html.contains("<th>strength [GPa]</th>"));
}

#[test]
fn every_number_of_the_real_exports_reads_back_in_its_columns_unit() {
    let dir = tempfile::tempdir().unwrap();
    let Some(out) = crate::common::run_real_exports(&["real"], dir.path()) else {
        return;
    };
    let n = check_tables(&out);
    assert!(n > 50, "{n} values");
    check_page(&std::fs::read_to_string(out.join("report.html")).unwrap());
}
