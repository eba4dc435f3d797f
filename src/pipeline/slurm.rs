//! Slurm batch scripts for a pipeline: a job array whose tasks each run
//! one shard (`tribo run --shard I/N`, filling the output folder's cache),
//! and a merge job, started only when every task succeeded
//! (`--dependency=afterok`), that assembles the tables and runs the fits.
//! tribo adds no scheduler of its own: Slurm queues, retries and accounts.

use std::path::{Path, PathBuf};

/// What the scripts ask of Slurm, beyond the shard count.
#[derive(Debug, Clone, Default)]
pub struct SlurmOptions {
    /// Array tasks (shards).
    pub shards: usize,
    /// `--partition`.
    pub partition: Option<String>,
    /// `--time` per task, e.g. `01:00:00`.
    pub time: Option<String>,
    /// `--cpus-per-task` (also tribo's `--threads`).
    pub cpus_per_task: Option<usize>,
    /// `--mem` per task, e.g. `4G`.
    pub mem: Option<String>,
    /// `--account`.
    pub account: Option<String>,
}

/// The scripts, as files of `OUT/slurm/`.
pub struct SlurmScripts {
    /// `array.sbatch`: one task per shard.
    pub array: String,
    /// `merge.sbatch`: assembles the tables after the array.
    pub merge: String,
    /// `submit.sh`: submits both, the merge depending on the array.
    pub submit: String,
}

/// The folder the scripts and the task logs go to.
pub fn script_dir(out_dir: &Path) -> PathBuf {
    out_dir.join("slurm")
}

fn quote(p: &Path) -> String {
    let s = p.display().to_string();
    format!("'{}'", s.replace('\'', r"'\''"))
}

fn header(name: &str, log: &str, o: &SlurmOptions) -> String {
    let mut h = format!("#!/bin/bash\n#SBATCH --job-name={name}\n#SBATCH --output={log}\n");
    let mut opt = |k: &str, v: Option<String>| {
        if let Some(v) = v {
            h.push_str(&format!("#SBATCH --{k}={v}\n"));
        }
    };
    opt("partition", o.partition.clone());
    opt("time", o.time.clone());
    opt("cpus-per-task", o.cpus_per_task.map(|c| c.to_string()));
    opt("mem", o.mem.clone());
    opt("account", o.account.clone());
    h
}

/// The scripts that run `tribo run ARGS` in `workdir` (the folder the
/// user ran `tribo slurm` in, so that paths and the tables' `source`
/// columns are those of a run on this machine); task logs go to
/// `out_dir/slurm/logs`.
pub fn scripts(
    tribo: &Path,
    workdir: &Path,
    run_args: &[String],
    out_dir: &Path,
    o: &SlurmOptions,
) -> SlurmScripts {
    let logs = script_dir(out_dir).join("logs");
    let threads = o
        .cpus_per_task
        .map_or(String::new(), |c| format!(" --threads {c}"));
    let args: Vec<String> = run_args.iter().map(|a| quote(Path::new(a))).collect();
    let run = format!(
        "cd {}\nexec {} run {}{threads}",
        quote(workdir),
        quote(tribo),
        args.join(" ")
    );
    let mut array = header(
        "tribo-shard",
        &format!("{}/shard-%A_%a.out", logs.display()),
        o,
    );
    array.push_str(&format!(
        "#SBATCH --array=0-{}\nset -euo pipefail\n\
         # Each task fills its share of the cache; nothing is published yet.\n\
         {run} --shard \"$SLURM_ARRAY_TASK_ID/{}\"\n",
        o.shards.saturating_sub(1),
        o.shards
    ));
    let mut merge = header(
        "tribo-merge",
        &format!("{}/merge-%j.out", logs.display()),
        o,
    );
    merge.push_str(&format!(
        "set -euo pipefail\n\
         # Assembles the tables from the shards' cache, runs the fits, publishes.\n\
         {run} --json\n"
    ));
    let submit = String::from(
        "#!/bin/bash\n# Submits the array, then the merge once every task succeeded.\n\
         set -euo pipefail\ncd \"$(dirname \"$0\")\"\nmkdir -p logs\n\
         array=$(sbatch --parsable array.sbatch)\n\
         merge=$(sbatch --parsable --dependency=afterok:\"${array%%;*}\" --kill-on-invalid-dep=yes \"$@\" merge.sbatch)\n\
         echo \"array job ${array%%;*}, merge job ${merge%%;*}\"\n"
    );
    SlurmScripts {
        array,
        merge,
        submit,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_array_has_one_task_per_shard_and_the_merge_waits_for_it() {
        let o = SlurmOptions {
            shards: 3,
            partition: Some("short".into()),
            cpus_per_task: Some(4),
            ..Default::default()
        };
        let args = ["p.toml".to_string(), "--out".into(), "out".into()];
        let s = scripts(
            Path::new("/opt/tribo"),
            Path::new("/lab"),
            &args,
            Path::new("/lab/out"),
            &o,
        );
        assert!(s.array.contains("#SBATCH --array=0-2\n"));
        assert!(s.array.contains("#SBATCH --partition=short\n"));
        assert!(s.array.contains("#SBATCH --cpus-per-task=4\n"));
        assert!(s
            .array
            .contains("cd '/lab'\nexec '/opt/tribo' run 'p.toml' '--out' 'out' --threads 4 --shard \"$SLURM_ARRAY_TASK_ID/3\""));
        assert!(!s.merge.contains("--shard"));
        assert!(s.submit.contains("--dependency=afterok:"));
        assert!(!s.array.contains("--time"));
    }
}
