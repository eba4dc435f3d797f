//! Publishing a run's output set at once.
//!
//! Tables are written into a staging folder `OUT/.tribo/sets/<id>/`; the
//! set is published by one atomic rename of the symbolic link
//! `OUT/.tribo/current` to it. Each `OUT/<table>.parquet` is a link to
//! `.tribo/current/<table>.parquet`, so a reader opening it sees the
//! previous complete set or the new one, never a mixture, whenever a run
//! is killed. Tables a rerun keeps are hard links into the new set (no
//! copy). Staging sets and temporary files of killed runs are removed by
//! the next run, never those of a run still alive ([`super::owner`]: each
//! temporary name tells its host and pid); temporary files are created
//! exclusively, with unpredictable names, so a planted link is never
//! followed. An output folder copied with its links followed (a copy to a
//! share, a zip) has real files where the links were: it is repaired (the
//! copied `current` set is moved aside, the links made again).

use std::collections::HashSet;
use std::fs::{self, File};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use rayon::prelude::*;

use super::atomic::{write_atomic, write_docs, Doc};
use super::dataset::{self, DataFile, Manifest};
use super::owner::{is_leftover, temp_name};
use crate::error::{Error, Result};
use crate::schema::TableDef;
use crate::table::Table;

/// A table's provenance as key-value pairs, shared by a stage's tables.
pub type KeyValues = Arc<[(String, String)]>;

/// A table to write into a set, with its provenance's key-value pairs.
pub type ToWrite = (&'static TableDef, Table, KeyValues);

/// Writes `table` as `<name>.parquet` in `staging`, with its provenance's
/// key-value pairs (`tribo.table` set to its name) and each column's unit
/// and meaning; returns the file's name.
fn write_table_file(
    staging: &Path,
    def: &TableDef,
    table: &Table,
    kv: &[(String, String)],
) -> Result<String> {
    let name = def.name;
    let schema = def.schema()?;
    let path = staging.join(format!("{name}.parquet"));
    let mut kv = kv.to_vec();
    for (k, v) in &mut kv {
        if k == "tribo.table" {
            *v = name.to_string();
        }
    }
    let columns = schema.field_metadata();
    write_atomic(&path, |w| table.write_parquet_with(w, &kv, &columns))?;
    Ok(format!("{name}.parquet"))
}

/// The output set being written; [`OutputSet::commit`] publishes it.
pub struct OutputSet {
    out: PathBuf,
    staging: PathBuf,
    /// A `current` that was not a link (a copied folder), moved aside.
    aside: Option<PathBuf>,
    /// File names in the set (`friction.parquet`, `report.html`,
    /// `traces.dataset.json`).
    files: Vec<String>,
    /// Each dataset's folder as this set leaves it.
    datasets: Vec<Folder>,
}

/// A dataset's folder: the files the set lists, and those it held before
/// when known (it was as the last run left it, [`super::swept`]: the files
/// of the last set), else `None` (it is listed).
struct Folder {
    dir: PathBuf,
    listed: Vec<String>,
    before: Option<Vec<String>>,
}

impl Folder {
    /// Removes the files the set does not list: by name when the folder's
    /// files are known, else by a listing (which also removes what killed
    /// runs left).
    fn prune(&self) {
        match &self.before {
            Some(before) => {
                let listed: HashSet<&str> = self.listed.iter().map(String::as_str).collect();
                for name in before.iter().filter(|n| !listed.contains(n.as_str())) {
                    let _ = fs::remove_file(self.dir.join(name));
                }
            }
            None => dataset::prune(&self.dir, &self.listed.iter().map(String::as_str).collect()),
        }
    }
}

fn tribo_dir(out: &Path) -> PathBuf {
    out.join(".tribo")
}

impl OutputSet {
    /// Starts a set in `out`, removing staging sets of killed runs. The
    /// caller holds the folder's lock.
    pub fn begin(out: &Path) -> Result<OutputSet> {
        let sets = tribo_dir(out).join("sets");
        fs::create_dir_all(&sets).map_err(|e| Error::io(&sets, e))?;
        let aside = move_aside_copied_current(out)?;
        let current = fs::read_link(tribo_dir(out).join("current")).ok();
        for e in fs::read_dir(&sets)
            .map_err(|e| Error::io(&sets, e))?
            .flatten()
        {
            let name = e.file_name();
            let published = current
                .as_ref()
                .is_some_and(|c| c.file_name() == Some(&name));
            // A staging set (`.tmp`) is removed when its run is gone; a
            // finished set that is not current was left by a run killed
            // as it published (only the lock's holder publishes).
            let name = name.to_string_lossy();
            let leftover = match name.ends_with(".tmp") {
                true => is_leftover(&name, true),
                false => true,
            };
            if !published && leftover {
                let _ = fs::remove_dir_all(e.path());
            }
        }
        remove_temp_files(out);
        let staging = sets.join(temp_name("set"));
        fs::create_dir(&staging).map_err(|e| Error::io(&staging, e))?;
        Ok(OutputSet {
            out: out.to_path_buf(),
            staging,
            aside,
            files: Vec::new(),
            datasets: Vec::new(),
        })
    }

    /// Writes tables into the set, in parallel (the largest, such as
    /// `friction` and `files` over a large archive, take about as long
    /// each): each with its provenance's key-value pairs (made once for the
    /// tables of one stage) and each column's unit and meaning. The tables
    /// were checked against their schemas where they were made.
    pub fn write_tables(&mut self, tables: &[ToWrite]) -> Result<()> {
        let written: Vec<Result<String>> = tables
            .par_iter()
            .map(|(def, table, kv)| write_table_file(&self.staging, def, table, kv))
            .collect();
        for file in written {
            self.files.push(file?);
        }
        Ok(())
    }

    /// Writes a document (the report) into the set as `file`.
    pub fn write_document(&mut self, file: &str, content: &[u8]) -> Result<()> {
        let path = self.staging.join(file);
        write_atomic(&path, |w| {
            w.write_all(content).map_err(|e| Error::io(&path, e))
        })?;
        self.files.push(file.to_string());
        Ok(())
    }

    /// Writes `n` documents into the set's folder `folder` (the report's
    /// pages), each made by `doc` as it is written, in parallel; the folder
    /// is linked from `OUT/<folder>`. A document kept, or that the published
    /// folder holds byte for byte, is linked from there instead of written
    /// again. Returns the folder in the set.
    pub fn write_folder(
        &mut self,
        folder: &str,
        n: usize,
        doc: impl Fn(usize) -> Result<Doc> + Sync,
    ) -> Result<PathBuf> {
        let dir = self.staging.join(folder);
        let published = fs::canonicalize(self.out.join(folder)).ok();
        write_docs(&dir, n, doc, published.as_deref())?;
        self.files.push(folder.to_string());
        Ok(dir)
    }

    /// Keeps the published folder `OUT/<folder>` in the new set as it is
    /// (each of its files linked), when there is one.
    pub fn keep_folder(&mut self, folder: &str) -> Result<()> {
        let Ok(from) = fs::canonicalize(self.out.join(folder)) else {
            return Ok(());
        };
        let to = self.staging.join(folder);
        fs::create_dir_all(&to).map_err(|e| Error::io(&to, e))?;
        for e in fs::read_dir(&from)
            .map_err(|e| Error::io(&from, e))?
            .flatten()
        {
            let target = to.join(e.file_name());
            if fs::hard_link(e.path(), &target).is_err() {
                fs::copy(e.path(), &target).map_err(|err| Error::io(&target, err))?;
            }
        }
        self.files.push(folder.to_string());
        Ok(())
    }

    /// Writes the dataset `def` into the set: its files linked into its
    /// folder (those not there yet, or made in this run), its manifest
    /// into the set. The files the set does not list leave the folder once
    /// it is published. `held`: the folder is as the last run left it (its
    /// files are the published manifest's, and it is not listed).
    /// `source`: the cache's file of each of `files`.
    pub fn write_dataset(
        &mut self,
        def: &TableDef,
        files: &[DataFile],
        held: bool,
        source: impl Fn(&DataFile) -> PathBuf,
    ) -> Result<()> {
        let published = dataset::manifest_path(&self.out, def.name);
        let before = held
            .then(|| dataset::read_manifest(&published).ok())
            .flatten()
            .map(|m| m.files);
        dataset::link_files(&self.out, def, files, before.as_deref(), source)?;
        let manifest = Manifest {
            table: def.name.into(),
            files: files.iter().map(|f| f.name.clone()).collect(),
        };
        let file = format!("{}{}", def.name, dataset::MANIFEST);
        // Written as it is serialized, not made into one string first: the
        // list grows with the inputs.
        let path = self.staging.join(&file);
        write_atomic(&path, |w| {
            serde_json::to_writer(w, &manifest).map_err(|e| Error::io(&path, e.into()))
        })?;
        self.files.push(file);
        self.datasets.push(Folder {
            dir: def.path_in(&self.out),
            listed: manifest.files,
            before,
        });
        Ok(())
    }

    /// Keeps the published table `def` in the new set, as it is (a
    /// dataset: its manifest, and the files it lists; `held`: its folder
    /// is as the last run left it, holding just those, and is not read).
    pub fn keep(&mut self, def: &TableDef, held: bool) -> Result<()> {
        let file = match def.is_dataset() {
            true => format!("{}{}", def.name, dataset::MANIFEST),
            false => format!("{}.parquet", def.name),
        };
        let to = self.keep_file(&file)?;
        if def.is_dataset() {
            let listed = match held {
                true => Vec::new(),
                false => dataset::read_manifest(&to)?.files,
            };
            self.datasets.push(Folder {
                dir: def.path_in(&self.out),
                before: held.then(|| listed.clone()),
                listed,
            });
        }
        Ok(())
    }

    /// Keeps the published file `file` (`OUT/<file>`) in the new set, as
    /// it is (a link to the same file); returns its path in the set.
    pub fn keep_file(&mut self, file: &str) -> Result<PathBuf> {
        let from =
            fs::canonicalize(self.out.join(file)).map_err(|e| Error::io(self.out.join(file), e))?;
        let to = self.staging.join(file);
        if fs::hard_link(&from, &to).is_err() {
            fs::copy(&from, &to).map_err(|e| Error::io(&to, e))?;
        }
        self.files.push(file.to_string());
        Ok(to)
    }

    /// Publishes the set: one rename makes it current; then each table's
    /// link in `OUT/` is made (once) and links to tables no longer in the
    /// set are removed, with the previous set. Returns the datasets'
    /// folders, as the set leaves them.
    pub fn commit(self) -> Result<Vec<PathBuf>> {
        let dir = tribo_dir(&self.out);
        sync_dir(&self.staging);
        // Its final name: no longer a staging set.
        let name = format!("set-{:016x}", rand::random::<u64>());
        let done = dir.join("sets").join(&name);
        fs::rename(&self.staging, &done).map_err(|e| Error::io(&done, e))?;
        let target = Path::new("sets").join(name);
        let previous = fs::read_link(dir.join("current")).ok();
        replace_with_link(&dir.join("current"), &target)?;
        sync_dir(&dir);
        for file in &self.files {
            let link = self.out.join(file);
            let to = Path::new(".tribo").join("current").join(file);
            if fs::read_link(&link).ok().as_deref() != Some(to.as_path()) {
                remove_copied_folder(&link)?;
                replace_with_link(&link, &to)?;
            }
        }
        self.drop_stale_links();
        for folder in &self.datasets {
            folder.prune();
        }
        if let Some(p) = previous.filter(|p| *p != target) {
            let _ = fs::remove_dir_all(dir.join(p));
        }
        if let Some(p) = &self.aside {
            let _ = fs::remove_dir_all(p).or_else(|_| fs::remove_file(p));
        }
        Ok(self.datasets.into_iter().map(|f| f.dir).collect())
    }

    /// Links in `OUT/` into the current set whose table it no longer has.
    fn drop_stale_links(&self) {
        let Ok(entries) = fs::read_dir(&self.out) else {
            return;
        };
        for e in entries.flatten() {
            let p = e.path();
            let ours = fs::read_link(&p).is_ok_and(|t| t.starts_with(".tribo/current"));
            if ours && !p.exists() {
                let _ = fs::remove_file(&p);
                // A dataset no longer published: its folder goes too.
                let name = e.file_name().to_string_lossy().to_string();
                if let Some(table) = name.strip_suffix(dataset::MANIFEST) {
                    dataset::remove(&self.out.join(table));
                }
            }
        }
    }
}

/// Removes `OUT/<folder>` when it is a folder where the set's link should
/// be: a copy of a published folder (the output folder copied with its
/// links followed). Anything else in it (not a page of the report) means
/// it is not tribo's: the run stops and says so.
fn remove_copied_folder(link: &Path) -> Result<()> {
    let is_dir = fs::symlink_metadata(link).is_ok_and(|m| m.is_dir());
    if !is_dir {
        return Ok(());
    }
    let ours = fs::read_dir(link)
        .map_err(|e| Error::io(link, e))?
        .all(|e| {
            e.is_ok_and(|e| {
                let name = e.file_name().to_string_lossy().to_string();
                name.starts_with("files-") && name.ends_with(".html")
            })
        });
    if !ours {
        return Err(Error::Config(format!(
            "{}: a folder tribo did not write stands where the output set's link goes; \
             move it out of the output folder and run again",
            link.display()
        )));
    }
    fs::remove_dir_all(link).map_err(|e| Error::io(link, e))
}

/// Makes `path` a symbolic link to `target`, atomically (a new link under
/// a unique name, renamed over `path`).
pub(super) fn replace_with_link(path: &Path, target: &Path) -> Result<()> {
    let dir = path.parent().unwrap_or(Path::new("."));
    let tmp = dir.join(temp_name(".link"));
    symlink(target, &tmp).map_err(|e| Error::io(&tmp, e))?;
    fs::rename(&tmp, path).map_err(|e| {
        let _ = fs::remove_file(&tmp);
        Error::io(path, e)
    })
}

#[cfg(unix)]
fn symlink(target: &Path, link: &Path) -> std::io::Result<()> {
    std::os::unix::fs::symlink(target, link)
}

#[cfg(not(unix))]
fn symlink(target: &Path, link: &Path) -> std::io::Result<()> {
    std::os::windows::fs::symlink_file(target, link)
}

fn sync_dir(dir: &Path) {
    if let Ok(f) = File::open(dir) {
        let _ = f.sync_all();
    }
}

/// Temporary files left in `OUT/` and `OUT/.tribo/` by killed runs.
fn remove_temp_files(out: &Path) {
    for dir in [out.to_path_buf(), tribo_dir(out)] {
        let Ok(entries) = fs::read_dir(&dir) else {
            continue;
        };
        for e in entries.flatten() {
            let name = e.file_name().to_string_lossy().to_string();
            if name.starts_with('.') && name.ends_with(".tmp") && is_leftover(&name, true) {
                let _ = fs::remove_file(e.path());
            }
        }
    }
}

/// `OUT/.tribo/current` should be a link to the published set. In a
/// folder copied with its links followed (`cp -rL`, a zip, a sync tool) it
/// is a copy of that set: it is moved aside (removed once the new set is
/// published; the tables in `OUT/` stay readable until then). Returns
/// where it went. An error only when it cannot be moved.
fn move_aside_copied_current(out: &Path) -> Result<Option<PathBuf>> {
    let current = tribo_dir(out).join("current");
    let Ok(meta) = fs::symlink_metadata(&current) else {
        return Ok(None);
    };
    if meta.file_type().is_symlink() {
        return Ok(None);
    }
    let aside = tribo_dir(out).join("sets").join(temp_name("copied"));
    match fs::rename(&current, &aside) {
        Ok(()) => Ok(Some(aside)),
        Err(e) => Err(Error::Config(format!(
            "{} should be a link to the published set, but is a {} (was the folder \
             copied with its links followed?) and could not be moved aside: {e}; \
             remove it (the tables in {} stay) and run again",
            current.display(),
            match meta.is_dir() {
                true => "folder",
                false => "file",
            },
            out.display()
        ))),
    }
}
