//! Output tables: schemas, units in column names, Parquet round trip, and
//! readers other than ours (pyarrow/pandas, when installed).

use crate::common;

use tribo::pipeline::registry;
use tribo::table::{Table, TableBuilder};

/// Every schema parses, and every column with a physical unit carries it in
/// its name, so that a pandas user sees the unit without the metadata.
#[test]
fn schemas_parse_and_name_their_units() {
    let suffix = |unit: &str| -> Option<&str> {
        Some(match unit {
            "N" => "_N",
            "s" => "_s",
            "m" => "_m",
            "m/s" => "_m_per_s",
            "m^2" => "_m2",
            "Pa" => "_Pa",
            "MPa" => "_MPa",
            "K" => "_K",
            "degC" => "_C",
            "Hz" => "_Hz",
            "J/g" => "_J_per_g",
            "deg" => "_deg",
            _ => return None,
        })
    };
    // Column names fixed by the issue that specifies the table: `load` in
    // alsfm.parquet, kept as the join key in its sibling tables. The unit is
    // in the schema and the metadata.
    let fixed_by_spec = |key: &str| key.starts_with("alsfm") && key.ends_with(".load");
    let mut n = 0;
    let mut missing = Vec::new();
    for def in registry::all() {
        let name = def.name;
        let s = def.schema().unwrap();
        assert_eq!(s.name, name);
        for c in &s.column {
            if let Some(sfx) = suffix(&c.unit) {
                let named = c.name.ends_with(sfx) || c.name.contains(&format!("{sfx}_"));
                let key = format!("{name}.{}", c.name);
                if !named && !fixed_by_spec(&key) {
                    missing.push(format!("{key} [{}]", c.unit));
                }
            }
            assert!(
                !c.meaning.trim().is_empty(),
                "{name}.{} has no meaning",
                c.name
            );
        }
        n += 1;
    }
    assert!(
        missing.is_empty(),
        "columns without their unit in the name: {missing:?}"
    );
    assert!(n >= 5);
}

/// A table survives Parquet: values, nulls (NaN becomes null) and metadata.
#[test]
fn parquet_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let t = TableBuilder::new()
        .str("source", [Some("a"), None, Some("c")])
        .f64("mu", [Some(0.5), Some(f64::NAN), None])
        .i64("n", [Some(1), Some(2), None])
        .bool("ok", [Some(true), Some(false), None])
        .build()
        .unwrap();
    let path = dir.path().join("t.parquet");
    tribo::pipeline::atomic::write_atomic(&path, |w| {
        t.write_parquet_to(w, &[("k".into(), "v".into())])
    })
    .unwrap();
    let (back, kv) = Table::read_parquet(&path).unwrap();
    assert_eq!(
        back.str("source").unwrap(),
        vec![Some("a".into()), None, Some("c".into())]
    );
    assert_eq!(back.f64("mu").unwrap(), vec![Some(0.5), None, None]);
    assert_eq!(back.i64("n").unwrap(), vec![Some(1), Some(2), None]);
    assert_eq!(
        back.bool("ok").unwrap(),
        vec![Some(true), Some(false), None]
    );
    assert!(kv.contains(&("k".into(), "v".into())));
}

/// A failed write leaves neither the target nor a temporary file behind.
#[test]
fn failed_writes_leave_nothing() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("x.parquet");
    let r = tribo::pipeline::atomic::write_atomic(&path, |w| {
        use std::io::Write;
        w.write_all(b"partial").unwrap();
        Err(tribo::Error::Table("simulated failure".into()))
    });
    assert!(r.is_err());
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

/// The demo's tables open in pyarrow and pandas with the schema's columns
/// and our row counts. Skipped when Python or pyarrow is not installed
/// (`.ci/run` installs pyarrow).
#[test]
fn tables_open_in_pandas() {
    let ok = std::process::Command::new("python3")
        .args(["-c", "import pyarrow, pandas"])
        .output();
    if !ok.is_ok_and(|o| o.status.success()) {
        eprintln!("skipped: python3 with pyarrow and pandas not available");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let mut plan =
        tribo::pipeline::Plan::from_file(&common::root().join("pipelines/demo.toml")).unwrap();
    plan.out_dir = dir.path().to_path_buf();
    tribo::pipeline::run(&plan, "test", &|| {}).unwrap();
    for name in [
        "friction",
        "friction_steps",
        "stickslip",
        "traces",
        "errors",
    ] {
        // The traces are a dataset: pyarrow reads the folder as one table.
        let path = registry::find(name).unwrap().path_in(dir.path());
        let ours = common::read_table(&path);
        let script = format!(
            "import pyarrow.parquet as pq, pyarrow.dataset as ds, json, os\n\
             p = {p:?}\n\
             files = sorted(os.path.join(p, f) for f in os.listdir(p)) if os.path.isdir(p) else [p]\n\
             df = ds.dataset(p, format='parquet').to_table().to_pandas()\n\
             md = pq.read_metadata(files[0]).metadata\n\
             print(json.dumps({{'rows': len(df), 'cols': list(df.columns), 'table': md[b'tribo.table'].decode()}}))",
            p = path.display().to_string()
        );
        let o = std::process::Command::new("python3")
            .args(["-c", &script])
            .output()
            .unwrap();
        assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
        assert_eq!(
            v["rows"].as_u64().unwrap() as usize,
            ours.height(),
            "{name}"
        );
        assert_eq!(v["table"], name);
        let cols: Vec<String> = serde_json::from_value(v["cols"].clone()).unwrap();
        let expected: Vec<String> = registry::schema(name)
            .unwrap()
            .column
            .iter()
            .map(|c| c.name.clone())
            .collect();
        assert_eq!(cols, expected, "{name}");
    }
}

/// `docs/statuses.md` lists exactly `ok` and `Code::ALL`, each with its
/// severity, whether the row has a result and its meaning, as the code
/// table says (`TRIBO_BLESS=1` rewrites the list).
#[test]
fn every_status_code_is_documented() {
    use tribo::status::{Code, OK};
    let mut table = String::from(
        "| code | severity | result | meaning |\n|---|---|---|---|\n\
         | `ok` | – | yes | No code: the row's result stands as computed. |\n",
    );
    for c in Code::ALL {
        let meaning: Vec<&str> = c.meaning().split_whitespace().collect();
        table += &format!(
            "| `{}` | {} | {} | {} |\n",
            c.as_str(),
            c.severity().as_str(),
            if c.has_result() { "yes" } else { "no" },
            meaning.join(" ")
        );
    }
    let path = common::root().join("docs/statuses.md");
    let doc = std::fs::read_to_string(&path).unwrap();
    let (begin, end) = ("<!-- codes: begin -->\n", "<!-- codes: end -->");
    let (a, b) = (
        doc.find(begin).unwrap() + begin.len(),
        doc.find(end).unwrap(),
    );
    if std::env::var_os("TRIBO_BLESS").is_some() {
        std::fs::write(&path, format!("{}{table}{}", &doc[..a], &doc[b..])).unwrap();
        return;
    }
    assert_eq!(
        &doc[a..b],
        table,
        "docs/statuses.md is not the code table: TRIBO_BLESS=1 cargo test every_status_code"
    );
    // Every code's text is distinct, and `ok` is none of them.
    let mut texts: Vec<&str> = Code::ALL.iter().map(|c| c.as_str()).collect();
    texts.push(OK);
    let n = texts.len();
    texts.sort_unstable();
    texts.dedup();
    assert_eq!(texts.len(), n);
}
