//! Shards: one of N runs that each fill part of the cache (a Slurm job
//! array's tasks). Work units — input files of the per-file stages (the
//! files a manifest gives one `test_id` together), and the
//! simulation stages that read no table of the run — are split by an
//! estimated cost (longest first, each to the least-loaded shard), the
//! same way on every shard, so that the shards cover every unit exactly
//! once whatever machine runs them. A later run without a shard assembles
//! the tables from the cache and runs the fits.

use std::collections::BTreeSet;

use crate::error::{Error, Result};
use crate::pipeline::plan::Plan;
use crate::stages::Consumes;

/// Shard `index` of `count` (0-based).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Shard {
    /// This shard, `0..count`.
    pub index: usize,
    /// How many shards.
    pub count: usize,
}

impl Shard {
    /// Parses `I/N` (0-based, as Slurm array task ids from 0).
    pub fn parse(s: &str) -> Result<Shard> {
        let bad = || {
            Error::Config(format!(
                "--shard {s}: expected I/N with 0 <= I < N, e.g. 0/3"
            ))
        };
        let (i, n) = s.split_once('/').ok_or_else(bad)?;
        let index: usize = i.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Shard { index, count })
    }

    /// The shard of a Slurm array task: `SLURM_ARRAY_TASK_ID` (counted from
    /// `SLURM_ARRAY_TASK_MIN`) of `SLURM_ARRAY_TASK_COUNT`; `None` outside
    /// an array job.
    pub fn from_env(get: impl Fn(&str) -> Option<String>) -> Result<Option<Shard>> {
        let num = |k: &str| get(k).and_then(|v| v.trim().parse::<usize>().ok());
        let (Some(id), Some(count)) = (num("SLURM_ARRAY_TASK_ID"), num("SLURM_ARRAY_TASK_COUNT"))
        else {
            return Ok(None);
        };
        let min = num("SLURM_ARRAY_TASK_MIN").unwrap_or(0);
        Shard::parse(&format!("{}/{count}", id.saturating_sub(min))).map(Some)
    }
}

/// The units of `costs` that `shard` takes: longest first, each to the
/// shard with the least cost so far (ties to the lowest shard), so that
/// shards finish together.
pub fn assign(costs: &[f64], shard: Shard) -> BTreeSet<usize> {
    let mut order: Vec<usize> = (0..costs.len()).collect();
    order.sort_by(|&a, &b| costs[b].total_cmp(&costs[a]).then(a.cmp(&b)));
    let mut load = vec![0.0_f64; shard.count];
    let mut mine = BTreeSet::new();
    for u in order {
        let (s, _) = load
            .iter()
            .enumerate()
            .min_by(|(i, a), (j, b)| a.total_cmp(b).then(i.cmp(j)))
            .unwrap_or((0, &0.0));
        load[s] += costs[u].max(0.0);
        if s == shard.index {
            mine.insert(u);
        }
    }
    mine
}

/// Estimated seconds of a file's per-file work: its size at the speed of
/// reading and extracting (about 25 MB/s), at least a few milliseconds.
pub fn file_cost(bytes: u64) -> f64 {
    (bytes as f64 / 25e6).max(0.005)
}

/// Estimated seconds of a simulation stage: its work units (runs, lattice
/// points) at about half a second each.
pub fn stage_cost(units: usize) -> f64 {
    0.5 * units.max(1) as f64
}

/// A shard's work: input files (indices into the plan's files), the
/// simulation stages that read no table of the run, and runs of studies
/// (stage, run).
pub(crate) struct ShardUnits {
    pub(crate) files: BTreeSet<usize>,
    pub(crate) stages: BTreeSet<usize>,
    pub(crate) units: BTreeSet<(usize, usize)>,
}

/// Splits the plan's work units between shards by their estimated cost.
pub(crate) fn shard_units(plan: &Plan, shard: Shard) -> ShardUnits {
    let produced: BTreeSet<&str> = plan
        .stages
        .iter()
        .flat_map(|s| s.stage.produces())
        .map(|d| d.name)
        .collect();
    let ids: Vec<Option<&str>> = plan
        .files
        .iter()
        .map(|f| {
            let row = plan.manifest().and_then(|m| m.find(&f.path));
            row.and_then(|r| r.fields.get("test_id"))
                .map(String::as_str)
        })
        .collect();
    let groups = series_groups(&ids);
    let mut items: Vec<Item> = (0..groups.len()).map(Item::Files).collect();
    let mut costs: Vec<f64> = groups
        .iter()
        .map(|g| {
            g.iter()
                .map(|&f| file_cost(std::fs::metadata(&plan.files[f].path).map_or(0, |m| m.len())))
                .sum()
        })
        .collect();
    for (i, ps) in plan.stages.iter().enumerate() {
        let Consumes::Tables(needs) = ps.stage.consumes() else {
            continue;
        };
        let units = ps.stage.unit_costs();
        if !units.is_empty() {
            items.extend((0..units.len()).map(|u| Item::Unit(i, u)));
            costs.extend(units);
        } else if needs.iter().all(|n| !produced.contains(n.table.name)) {
            items.push(Item::Stage(i));
            costs.push(stage_cost(ps.stage.units()));
        }
    }
    let mut mine = ShardUnits {
        files: BTreeSet::new(),
        stages: BTreeSet::new(),
        units: BTreeSet::new(),
    };
    for k in assign(&costs, shard) {
        match items[k] {
            Item::Files(g) => {
                mine.files.extend(groups[g].iter().copied());
                true
            }
            Item::Stage(s) => mine.stages.insert(s),
            Item::Unit(s, u) => mine.units.insert((s, u)),
        };
    }
    mine
}

/// The input files (indices) in groups that go to one shard together:
/// the files the manifest gives one `test_id` (a test exported as several
/// files is analysed as one series), every other file alone; in the order
/// of each group's first file.
fn series_groups(ids: &[Option<&str>]) -> Vec<Vec<usize>> {
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut by_id: std::collections::BTreeMap<&str, usize> = Default::default();
    for (f, id) in ids.iter().enumerate() {
        match id.map(|id| *by_id.entry(id).or_insert(groups.len())) {
            Some(g) if g < groups.len() => groups[g].push(f),
            _ => groups.push(vec![f]),
        }
    }
    groups
}

/// A unit of work.
#[derive(Clone, Copy)]
enum Item {
    /// A group of input files ([`series_groups`]).
    Files(usize),
    Stage(usize),
    Unit(usize, usize),
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The files of one test stay together, in file order, and files of
    /// no test are each their own unit.
    #[test]
    fn a_series_of_files_is_one_unit() {
        let ids = [
            Some("T1"),
            None,
            Some("T2"),
            Some("T1"),
            None,
            Some("T2"),
            Some("T1"),
        ];
        assert_eq!(
            series_groups(&ids),
            vec![vec![0, 3, 6], vec![1], vec![2, 5], vec![4]]
        );
        assert!(series_groups(&[]).is_empty());
    }

    #[test]
    fn every_unit_goes_to_exactly_one_shard_and_loads_balance() {
        let costs: Vec<f64> = (0..50).map(|i| ((i * 37) % 11) as f64 + 1.0).collect();
        for n in 1..=5 {
            let parts: Vec<BTreeSet<usize>> = (0..n)
                .map(|i| assign(&costs, Shard { index: i, count: n }))
                .collect();
            let total: usize = parts.iter().map(BTreeSet::len).sum();
            assert_eq!(total, costs.len());
            let union: BTreeSet<usize> = parts.iter().flatten().copied().collect();
            assert_eq!(union.len(), costs.len());
            let loads: Vec<f64> = parts
                .iter()
                .map(|p| p.iter().map(|&u| costs[u]).sum())
                .collect();
            let (lo, hi) = loads
                .iter()
                .fold((f64::MAX, 0.0_f64), |(l, h), &x| (l.min(x), h.max(x)));
            // Longest-first greedy: within the largest unit (11).
            assert!(hi - lo <= 11.0, "{loads:?}");
        }
    }

    #[test]
    fn shards_parse_and_come_from_slurm() {
        assert_eq!(Shard::parse("2/3").unwrap(), Shard { index: 2, count: 3 });
        for bad in ["3/3", "1", "a/2", "0/0", "-1/2"] {
            assert!(Shard::parse(bad).is_err(), "{bad}");
        }
        let env = |k: &str| match k {
            "SLURM_ARRAY_TASK_ID" => Some("5".to_string()),
            "SLURM_ARRAY_TASK_COUNT" => Some("3".to_string()),
            "SLURM_ARRAY_TASK_MIN" => Some("4".to_string()),
            _ => None,
        };
        assert_eq!(
            Shard::from_env(env).unwrap(),
            Some(Shard { index: 1, count: 3 })
        );
        assert_eq!(Shard::from_env(|_| None).unwrap(), None);
    }
}
