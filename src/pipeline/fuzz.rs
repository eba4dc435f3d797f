//! What the fuzz harness (`examples/fuzz.rs`) and its regression test check
//! for one input: reading, routing and every per-file stage that takes the
//! file, as a run would, must end in rows or a clean error — never a
//! panic, a table that breaks its schema (which once failed whole
//! batches), or a non-finite number in a table.

use std::collections::BTreeMap;
use std::panic::{catch_unwind, AssertUnwindSafe};
use std::path::Path;
use std::sync::OnceLock;
use std::time::Duration;

use crate::ingest::source::Source;
use crate::ingest::{read_data, IngestOptions, Reading};
use crate::stages::{self, Consumes, FileInput, PlanContext, StagePlan};
use crate::table::ColumnType;

/// A defect found by the harness.
#[derive(Debug)]
pub enum Finding {
    /// A panic, with its message.
    Panic(String),
    /// A table that does not fit its schema, or holds a non-finite number.
    BrokenTable(String),
    /// An input that took too long.
    Slow(Duration),
}

/// The per-file stages with default settings.
fn file_stages() -> &'static [Box<dyn StagePlan>] {
    static PLANS: OnceLock<Vec<Box<dyn StagePlan>>> = OnceLock::new();
    PLANS.get_or_init(|| {
        let ctx = PlanContext {
            base: ".".into(),
            traces: true,
            figures: true,
        };
        stages::STAGES
            .iter()
            .filter_map(|s| s.plan(toml::Table::new(), &ctx).ok())
            .filter(|p| matches!(p.consumes(), Consumes::Files(_)))
            .collect()
    })
}

/// Checks one input; `None` when it ends in rows or a clean error.
pub fn check_input(path: &Path, bytes: &[u8]) -> Option<Finding> {
    match catch_unwind(AssertUnwindSafe(|| run_once(path, bytes))) {
        Ok(f) => f,
        Err(p) => {
            let msg = p
                .downcast_ref::<String>()
                .cloned()
                .or_else(|| p.downcast_ref::<&str>().map(|s| s.to_string()))
                .unwrap_or_default();
            Some(Finding::Panic(msg))
        }
    }
}

fn run_once(path: &Path, bytes: &[u8]) -> Option<Finding> {
    let source = Source::Read(bytes.to_vec());
    let (_, Ok(Reading::Data(ds))) = read_data(path, &source, None, &IngestOptions::default())
    else {
        return None;
    };
    let columns = BTreeMap::new();
    let (kind, _) = super::route::kind_of(&ds, &columns);
    let input = || FileInput {
        path,
        dataset: std::borrow::Cow::Borrowed(&ds),
        columns: &columns,
        manifest: None,
    };
    for plan in file_stages() {
        // As the stage's own command routes it (a one-stage pipeline).
        let takes = !super::route::takers([plan.as_ref()], &[], kind).is_empty();
        let Some(Ok(tables)) = takes.then(|| plan.run_file(input())) else {
            continue;
        };
        for (def, t) in &tables {
            let name = def.name;
            let broken = def.check(t).err();
            if let Some(e) = broken {
                return Some(Finding::BrokenTable(format!("{}: {e}", plan.name())));
            }
            for c in t.column_names() {
                if t.column_type(&c) != Some(ColumnType::F64) {
                    continue;
                }
                let bad = t
                    .f64(&c)
                    .ok()?
                    .into_iter()
                    .flatten()
                    .any(|v| !v.is_finite());
                if bad {
                    return Some(Finding::BrokenTable(format!(
                        "{name}.{c}: a non-finite value"
                    )));
                }
            }
        }
    }
    None
}
