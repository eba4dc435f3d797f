//! `tribo slurm PIPELINE --shards N`: batch scripts for a Slurm cluster, and
//! with `--submit` their submission.

use std::path::{Path, PathBuf};
use std::process::Command;

use tribo::pipeline::atomic::write_text_atomic;
use tribo::pipeline::exit::Tally;
use tribo::pipeline::slurm::{script_dir, scripts, SlurmOptions};
use tribo::pipeline::Plan;
use tribo::Error;

/// Arguments of `tribo slurm`.
#[derive(clap::Args)]
pub struct SlurmArgs {
    /// Pipeline file (TOML).
    pipeline: PathBuf,
    /// Array tasks: the work is split into this many shards, balanced by
    /// estimated cost.
    #[arg(long)]
    shards: usize,
    /// Output folder, overriding the pipeline's [output] dir.
    #[arg(long)]
    out: Option<PathBuf>,
    /// Slurm partition.
    #[arg(long)]
    partition: Option<String>,
    /// Time limit per task, e.g. 01:00:00.
    #[arg(long)]
    time: Option<String>,
    /// CPUs per task (tribo's worker threads).
    #[arg(long)]
    cpus_per_task: Option<usize>,
    /// Memory per task, e.g. 4G.
    #[arg(long)]
    mem: Option<String>,
    /// Account to charge.
    #[arg(long)]
    account: Option<String>,
    /// Submit the array and the merge job (sbatch) and print their ids.
    #[arg(long)]
    submit: bool,
    /// With --submit: wait until the merge job has finished (sbatch --wait).
    #[arg(long, requires = "submit")]
    wait: bool,
}

fn absolute(p: &Path) -> tribo::Result<PathBuf> {
    std::path::absolute(p).map_err(|e| Error::io(p, e))
}

/// Runs `tribo slurm`.
pub fn run(args: &SlurmArgs) -> tribo::Result<Tally> {
    if args.shards == 0 {
        return Err(Error::Config("--shards must be at least 1".into()));
    }
    // The pipeline is validated here, before anything is queued.
    let plan = Plan::from_file(&args.pipeline)?;
    let out = absolute(args.out.as_ref().unwrap_or(&plan.out_dir))?;
    let tribo = std::env::current_exe().map_err(|e| Error::io(Path::new("tribo"), e))?;
    let options = SlurmOptions {
        shards: args.shards,
        partition: args.partition.clone(),
        time: args.time.clone(),
        cpus_per_task: args.cpus_per_task,
        mem: args.mem.clone(),
        account: args.account.clone(),
    };
    let workdir = absolute(Path::new("."))?;
    let mut run_args = vec![args.pipeline.display().to_string()];
    if let Some(o) = &args.out {
        run_args.extend(["--out".to_string(), o.display().to_string()]);
    }
    let s = scripts(&tribo, &workdir, &run_args, &out, &options);
    let dir = script_dir(&out);
    std::fs::create_dir_all(dir.join("logs")).map_err(|e| Error::io(&dir, e))?;
    for (name, text) in [
        ("array.sbatch", &s.array),
        ("merge.sbatch", &s.merge),
        ("submit.sh", &s.submit),
    ] {
        write_text_atomic(&dir.join(name), text)?;
    }
    eprintln!(
        "wrote {0}/array.sbatch, merge.sbatch and submit.sh; submit with: bash {0}/submit.sh",
        dir.display()
    );
    if !args.submit {
        return Ok(Tally::ok());
    }
    submit(&dir, args.wait)
}

fn sbatch(dir: &Path, args: &[&str]) -> tribo::Result<(String, bool)> {
    let o = Command::new("sbatch")
        .current_dir(dir)
        .args(args)
        .output()
        .map_err(|e| {
            Error::Config(format!(
                "cannot run sbatch ({e}): is Slurm installed here? The scripts are in {}",
                dir.display()
            ))
        })?;
    let id = String::from_utf8_lossy(&o.stdout).trim().to_string();
    if !o.status.success() && id.is_empty() {
        return Err(Error::Config(format!(
            "sbatch {}: {}",
            args.join(" "),
            String::from_utf8_lossy(&o.stderr).trim()
        )));
    }
    Ok((
        id.split(';').next().unwrap_or("").to_string(),
        o.status.success(),
    ))
}

fn submit(dir: &Path, wait: bool) -> tribo::Result<Tally> {
    let (array, _) = sbatch(dir, &["--parsable", "array.sbatch"])?;
    println!("array job {array}");
    let dep = format!("--dependency=afterok:{array}");
    // A failed task cancels the merge instead of leaving it queued forever.
    let mut merge_args = vec!["--parsable", dep.as_str(), "--kill-on-invalid-dep=yes"];
    if wait {
        merge_args.push("--wait");
    }
    merge_args.push("merge.sbatch");
    let (merge, ok) = sbatch(dir, &merge_args)?;
    println!("merge job {merge}");
    if wait && !ok {
        eprintln!(
            "the merge job did not succeed; task logs are in {}/logs",
            dir.display()
        );
        return Ok(Tally::without_result(1));
    }
    Ok(Tally::ok())
}
