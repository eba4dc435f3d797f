//! Publishing a run's set: every table that changed written with its
//! provenance, the others kept, the run's own tables (`files`, `errors`)
//! and the report; then the held parts stored, the state saved and the
//! cache entries nothing uses any more dropped.

use std::collections::BTreeMap;

use super::inputs::files_table;
use super::provenance::Provenance;
use super::publish::OutputSet;
use super::registry::{ERRORS, FILES};
use super::runner::{sorted, Runner};
use super::state::{stamped_file, TableState};
use crate::error::Result;
use crate::schema::TableDef;
use crate::table::Table;

impl Runner<'_> {
    /// Publishes the set, then saves the state and prunes the cache.
    pub(super) fn publish(&mut self, command: &str) -> Result<()> {
        let mut set = OutputSet::begin(&self.plan.out_dir)?;
        self.write_made(&mut set, command)?;
        let own = self.write_own(&mut set, command)?;
        self.write_report(&mut set, own)?;
        set.commit()?;
        self.save_state()
    }

    /// The stages' tables: written, or kept as the last run published
    /// them.
    fn write_made(&mut self, set: &mut OutputSet, command: &str) -> Result<()> {
        let dir = &self.plan.out_dir;
        for p in &self.made {
            let path = p.def.path_in(dir);
            if p.published.is_some() {
                set.keep(p.def)?;
                self.report.kept.push(path);
                continue;
            }
            if let Some(files) = &p.files {
                set.write_dataset(p.def, files)?;
                self.report.outputs.push(path);
                continue;
            }
            let stage = self.plan.stages[p.stage].stage.as_ref();
            let prov = Provenance::of_stage(command, stage, p.inputs.clone(), &self.plan.spec_json);
            set.write_table(p.def, p.table()?, &prov)?;
            self.report.outputs.push(path);
        }
        Ok(())
    }

    /// The run's own tables, `files` and `errors`, with every input of the
    /// set in their provenance.
    fn write_own(&mut self, set: &mut OutputSet, command: &str) -> Result<[Own; 2]> {
        let all = sorted(self.made.iter().flat_map(|p| p.inputs.clone()).collect());
        let prov = Provenance {
            command: command.into(),
            stage: "pipeline".into(),
            inputs: all,
            pipeline: self.plan.spec_json.clone(),
            ..Default::default()
        };
        let own = [
            (&FILES, files_table(&self.report.inputs)?),
            (&ERRORS, self.report.errors_table()?),
        ];
        for (def, table) in &own {
            set.write_table(def, table, &prov)?;
            let path = self.plan.out_dir.join(format!("{}.parquet", def.name));
            self.report.outputs.push(path);
        }
        Ok(own)
    }

    /// The warnings of the set (rows whose status is not `ok`) and, unless
    /// the pipeline says `report = false`, `report.html` from the set's
    /// tables (only those it reads or that have a status: never the traces).
    fn write_report(&mut self, set: &mut OutputSet, own: [Own; 2]) -> Result<()> {
        let mut tables: BTreeMap<String, Table> = own
            .into_iter()
            .map(|(d, t)| (d.name.to_string(), t))
            .collect();
        for p in &self.made {
            if p.def.in_report() || p.def.has_status() {
                tables.insert(p.def.name.to_string(), p.table()?.clone());
            }
        }
        self.report.warnings = crate::report::doubts(&tables)?;
        if self.plan.report {
            super::report::write(set, &self.plan.out_dir, &tables)?;
            let path = self.plan.out_dir.join(super::report::REPORT);
            self.report.outputs.push(path);
        }
        Ok(())
    }

    /// Saves the state of the published set, and drops the cache entries
    /// it does not use.
    fn save_state(&mut self) -> Result<()> {
        let dir = &self.plan.out_dir;
        for p in self.made.iter().filter(|p| p.published.is_none()) {
            let path = stamped_file(dir, p.def);
            if let Some(s) = TableState::of_file(&path, p.key.clone()) {
                self.new.tables.insert(p.def.name.into(), s);
            }
        }
        self.new.save(dir)?;
        let stages = self.new.stages.values().map(|s| s.key.clone()).collect();
        let files = self.new.files.values();
        let routes = files.clone().filter_map(|f| f.route.clone()).collect();
        let parts = files.flat_map(|f| f.parts.values().cloned()).collect();
        self.store
            .cache()
            .retain(&routes, &parts, &stages, &self.units_used);
        Ok(())
    }
}

/// One of the run's own tables.
type Own = (&'static TableDef, Table);
