//! The run order of a pipeline's stages, derived from what each needs:
//! per-file stages first, then every table stage after the stages whose
//! tables it reads, keeping the listed order where the needs allow.

use std::collections::BTreeMap;

use super::plan::PlannedStage;
use crate::error::{Error, Result};
use crate::stages::Consumes;

/// Indices of `stages` in run order. A table that two stages produce, a
/// required table that no stage produces and no file gives, and a cycle
/// are configuration errors.
pub fn run_order(stages: &[PlannedStage]) -> Result<Vec<usize>> {
    let producers = producers(stages)?;
    let mut deps: Vec<Vec<usize>> = Vec::with_capacity(stages.len());
    for s in stages {
        let mut d = Vec::new();
        if let Consumes::Tables(needs) = s.stage.consumes() {
            for need in needs {
                if s.table_files.contains_key(need.table.name) {
                    continue;
                }
                match producers.get(need.table.name) {
                    Some(&p) => d.push(p),
                    None if need.required => {
                        return Err(Error::Config(format!(
                            "stage '{0}' needs the table '{1}': add the stage that writes it to \
                             stages, or give [{0}] inputs = {{ {1} = \"path/{1}.parquet\" }}",
                            s.stage.name(),
                            need.table.name
                        )))
                    }
                    None => {}
                }
            }
        }
        deps.push(d);
    }
    let mut order: Vec<usize> = (0..stages.len())
        .filter(|&i| matches!(stages[i].stage.consumes(), Consumes::Files(_)))
        .collect();
    while order.len() < stages.len() {
        let next = (0..stages.len())
            .find(|i| !order.contains(i) && deps[*i].iter().all(|d| order.contains(d)))
            .ok_or_else(|| {
                let left: Vec<_> = (0..stages.len())
                    .filter(|i| !order.contains(i))
                    .map(|i| stages[i].stage.name())
                    .collect();
                Error::Config(format!("stages {left:?} need each other's tables"))
            })?;
        order.push(next);
    }
    Ok(order)
}

/// Table name → the stage that writes it.
fn producers(stages: &[PlannedStage]) -> Result<BTreeMap<&'static str, usize>> {
    let mut out: BTreeMap<&'static str, usize> = BTreeMap::new();
    for (i, s) in stages.iter().enumerate() {
        for t in s.stage.produces().into_iter().map(|d| d.name) {
            if let Some(&j) = out.get(t) {
                return Err(Error::Config(format!(
                    "stages '{}' and '{}' both write the table '{t}'",
                    stages[j].stage.name(),
                    s.stage.name()
                )));
            }
            out.insert(t, i);
        }
    }
    Ok(out)
}
