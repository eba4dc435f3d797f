//! Reuse across runs: a stage whose key (its parameters and the keys of
//! everything it reads) is the one the last run published, and whose tables
//! are still the files it wrote, is reused without reading them; in a dry
//! run, what would be redone is listed with its reason.

use std::collections::BTreeSet;
use std::sync::OnceLock;

use super::keys::{table_key, Key};
use super::outcome::{Redo, WithoutResult};
use super::runner::{Inputs, Produced, Runner};

impl Runner<'_> {
    /// Why a dry run would read a file.
    pub(super) fn file_reason(&self, path: &str, bytes: &str) -> &'static str {
        match self.old.files.get(path) {
            _ if self.forced => "forced",
            None => "new file",
            Some(old) if *old.bytes != *bytes => "changed file",
            Some(_) => "stage parameters, manifest row, reading options or tribo's build changed",
        }
    }

    /// Reuses stage `i` when the last run published it with this key and
    /// its tables are still the files it wrote.
    pub(super) fn reuse(&mut self, i: usize, key: &Key, inputs: &Inputs) -> bool {
        let stage = self.plan.stages[i].stage.as_ref();
        let Some(old) = self.old.stages.get(stage.name()) else {
            return false;
        };
        let out = &self.plan.out_dir;
        let defs = stage.produces();
        let intact = defs
            .iter()
            .all(|t| self.old.published(out, t, &table_key(key, t.name)));
        if old.key != *key || !intact {
            return false;
        }
        let old = old.clone();
        self.report.stages_reused.push(stage.name().into());
        self.report.notes.extend(old.notes.clone());
        if old.without_result > 0 {
            self.report.without_result.push(WithoutResult {
                stage: stage.name().into(),
                rows: old.without_result,
            });
        }
        for def in defs {
            let t = def.name;
            self.made.push(Produced {
                def,
                stage: i,
                inputs: inputs.clone(),
                key: table_key(key, t),
                table: OnceLock::new(),
                published: Some(def.path_in(out)),
                files: None,
            });
            if let Some(s) = self.old.tables.get(t) {
                self.new.tables.insert(t.into(), s.clone());
            }
        }
        self.new.stages.insert(stage.name().into(), old);
        true
    }

    /// Why a dry run would redo stage `i`.
    pub(super) fn stage_reason(&self, i: usize, key: &Key) -> &'static str {
        match self.old.stages.get(self.plan.stages[i].stage.name()) {
            _ if self.forced => "forced",
            None => "not run before into this folder",
            Some(old) if old.key != *key => "its inputs, parameters or tribo's build changed",
            Some(_) => "its tables were changed or removed",
        }
    }

    /// In a dry run: lists the stage, and stands its tables in for the
    /// stages after it (with the new key, so that they are redone too).
    pub(super) fn would_redo(&mut self, i: usize, key: Key, why: &str, inputs: Inputs) {
        let stage = self.plan.stages[i].stage.as_ref();
        self.report.redo.push(Redo::stage(stage.name(), why));
        for def in stage.produces() {
            self.made.push(Produced {
                def,
                stage: i,
                inputs: inputs.clone(),
                key: table_key(&key, def.name),
                table: OnceLock::new(),
                published: None,
                files: None,
            });
        }
    }

    /// In a dry run: inputs the last run had that are gone.
    pub(super) fn list_deleted(&mut self) {
        let now: BTreeSet<String> = self.plan.files.iter().map(|f| f.source.clone()).collect();
        for path in self.old.files.keys().filter(|p| !now.contains(*p)) {
            self.report
                .redo
                .push(Redo::file(path, "deleted: its rows leave the tables"));
        }
    }
}
