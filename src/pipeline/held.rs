//! Per-file parts held until the set is published, so that the cache can
//! link a table the set publishes as it is instead of copying it
//! ([`super::cache::Cache::hold_parts`]: a one-file run, not a shard's).

use std::path::PathBuf;

use super::cache::Key;
use super::run::Runner;
use crate::error::Result;
use crate::stages::Tables;

impl Runner<'_> {
    /// Keeps a fresh part for [`Runner::store_held`] when the cache holds
    /// parts; a failure is stored at once (it has no table to link).
    pub(super) fn hold(&mut self, key: &Key, part: &Result<Tables>) {
        match part {
            Ok(tables) if self.cache.hold_parts => self.held.push((key.clone(), tables.clone())),
            Err(_) if self.cache.hold_parts => {
                let _ = self.cache.put_part(key, part, &[]);
            }
            _ => {}
        }
    }

    /// Stores the held parts once the set is published: a table published
    /// as it is (the very table, not a copy: [`crate::table::Table::is_same`]) becomes a
    /// hard link to the published file, not a second copy.
    pub(super) fn store_held(&mut self) {
        let out = &self.plan.out_dir;
        for (key, tables) in std::mem::take(&mut self.held) {
            let published: Vec<(&str, PathBuf)> = tables
                .iter()
                .filter_map(|(def, t)| {
                    let made = self.made.iter().find(|p| p.def == *def)?;
                    let same = made.published.is_none() && made.table.get()?.is_same(t);
                    let file = std::fs::canonicalize(out.join(format!("{}.parquet", def.name)));
                    Some((def.name, file.ok().filter(|_| same)?))
                })
                .collect();
            let _ = self.cache.put_part(&key, &Ok(tables), &published);
        }
    }
}
