//! `study`: a base case and axes to vary, expanded into runs (each a `solve` or a `sweep` in a
//! run directory of its own, named by its parameters), run side by side and resumed where they
//! stopped, their summaries merged into one table with a summary of each group.

use crate::solve::{self, SolveArgs};
use crate::sweep::{self, SweepArgs};
use anyhow::{Context, Result, bail};
use clap::{Args, Parser};
use indicatif::{ProgressBar, ProgressStyle};
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

mod plan;
#[cfg(feature = "mpi")]
mod ranks;
mod table;
#[cfg(test)]
mod tests;

use plan::{Run, Study, parse_shard, same_run};
use table::{Counts, group, merge, standing};

#[derive(Args, Debug)]
pub struct StudyArgs {
    /// Study file (TOML): `command` ("solve" or "sweep"), the base case as a `[case]` table of
    /// case keys (or `case = "FILE"`), the axes as an `[axes]` table of lists (`seed = [1, 2]`),
    /// `combine` ("product", the default: every combination; or "zip": the lists side by side),
    /// and optionally `names`, the runs' directory names in order [default: key=value joined].
    study: PathBuf,
    /// Study directory: runs/ and the merged tables [default: run/study/ and the study file's
    /// name without its extension, under the working directory: never beside the study file,
    /// which may sit in a checkout's data/].
    #[arg(long)]
    out: Option<PathBuf>,
    /// Runs side by side on this machine, each with its share of the cores (shared among the
    /// runs left to do; or --threads each).
    #[arg(long, default_value_t = 1)]
    jobs: usize,
    /// Start no run once this much wall time has passed since the study began (a number with
    /// the unit s, m or h: `90m`, `1.5h`); the runs under way finish and the rest are left for
    /// the next call, which resumes. For a batch job's time limit, less a run's length.
    #[arg(long, value_name = "TIME", value_parser = parse_duration)]
    start_within: Option<Duration>,
    /// Only this shard of the runs, I/N (1 <= I <= N): run k belongs to shard (k mod N) + 1.
    /// For job arrays (Slurm); `--merge` then combines the shards' runs.
    #[arg(long, value_name = "I/N")]
    shard: Option<String>,
    /// Run nothing: merge the finished runs into the tables (after sharded runs).
    #[arg(long)]
    merge: bool,
    /// Summarise over this axis: each group of runs equal in the other axes gets the mean,
    /// standard error and count of every number in study-groups.csv [default: the first axis
    /// named `seed`, if any].
    #[arg(long, value_name = "AXIS")]
    group_over: Option<String>,
    /// List the runs and their directories, and exit.
    #[arg(long)]
    dry_run: bool,
}

/// What became of a run.
enum Outcome {
    Done,
    Failed(String),
    /// Under way in another process.
    Elsewhere,
}

/// Runs one run in `dir` on a pool of `threads` threads: resumes a half-finished sweep, skips a
/// finished run, and turns an error (or a panic) into [`Outcome::Failed`] (written to
/// `error.txt`), so that no run takes the study down.
fn execute(study: &Study, run: &Run, dir: &Path, threads: usize) -> Outcome {
    let attempt =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| attempt(study, run, dir, threads)));
    let outcome = attempt.unwrap_or_else(|panic| {
        let what = panic
            .downcast_ref::<String>()
            .cloned()
            .or_else(|| panic.downcast_ref::<&str>().map(|s| s.to_string()))
            .unwrap_or_default();
        Err(anyhow::anyhow!("the run panicked: {what}"))
    });
    match outcome {
        Ok(()) => Outcome::Done,
        // Another process runs it (a second study on the same directory): its outcome is that
        // process's, and nothing is written here.
        Err(e) if e.downcast_ref::<crate::run::Busy>().is_some() => Outcome::Elsewhere,
        Err(e) => {
            let message = format!("{e:#}");
            let _ =
                std::fs::create_dir_all(dir).and_then(|_| std::fs::write(dir.join("error.txt"), &message));
            Outcome::Failed(message)
        }
    }
}

/// Whether `run` in `dir` finished with the case it has now (then it is not run again).
fn finished(study: &Study, run: &Run, dir: &Path) -> bool {
    study.run_case(run, dir).is_ok_and(|case| {
        dir.join("summary.json").exists()
            && std::fs::read_to_string(dir.join("run.toml")).is_ok_and(|old| same_run(&old, &case))
    })
}

fn attempt(study: &Study, run: &Run, dir: &Path, threads: usize) -> Result<()> {
    if finished(study, run, dir) {
        return Ok(());
    }
    let case = study.run_case(run, dir)?;
    let config = dir.join("run.toml");
    let same = std::fs::read_to_string(&config).is_ok_and(|old| same_run(&old, &case));
    std::fs::create_dir_all(dir).with_context(|| format!("creating {}", dir.display()))?;
    let _ = std::fs::remove_file(dir.join("error.txt"));
    std::fs::write(&config, case).with_context(|| format!("writing {}", config.display()))?;
    let config = config.display().to_string();
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build()?;
    pool.install(|| {
        if study.command == "sweep" {
            // A run of another case, or copied without its saved state (its small files
            // only), starts over.
            let again = if same && dir.join("curve.csv").exists() && dir.join("state").exists() {
                "--resume"
            } else {
                "--overwrite"
            };
            let args = ["sweep", "--config", &config, again, "--keep-going", "--no-png"];
            sweep::sweep(Wrapped::<SweepArgs>::try_parse_from(args)?.args)
        } else {
            let args = [
                "solve",
                "--config",
                &config,
                "--overwrite",
                "--keep-going",
                "--no-png",
            ];
            solve::solve(Wrapped::<SolveArgs>::try_parse_from(args)?.args)
        }
    })
}

/// A command's arguments parsed as the command line would.
#[derive(Parser)]
struct Wrapped<A: Args> {
    #[command(flatten)]
    args: A,
}

/// Runs the study file `study` into `out`, `jobs` runs side by side on `threads` threads each
/// (`None`: the cores shared among the runs left), and merges its tables: `roughcontact study
/// STUDY --out OUT --jobs J`, from a program.
pub fn run(study: &Path, out: &Path, jobs: usize, threads: Option<usize>) -> Result<()> {
    let args = StudyArgs {
        study: study.to_path_buf(),
        out: Some(out.to_path_buf()),
        jobs,
        start_within: None,
        shard: None,
        merge: false,
        group_over: None,
        dry_run: false,
    };
    self::study(args, threads)
}

pub fn study(a: StudyArgs, threads: Option<usize>) -> Result<()> {
    let study = Study::read(&a.study)?;
    let starts_until = a.start_within.map(|d| Instant::now() + d);
    let root = match &a.out {
        Some(out) => out.clone(),
        None => {
            let stem = a.study.file_stem().context("a study file's name is needed")?;
            Path::new("run/study").join(stem)
        }
    };
    let runs_dir = root.join("runs");
    if a.dry_run {
        for r in &study.runs {
            crate::outln!("{}", runs_dir.join(&r.name).display());
        }
        return Ok(());
    }
    // Each job is a thread with a pool of its own.
    case::memory::check_threads("--jobs", a.jobs)?;
    if a.merge && a.start_within.is_some() {
        bail!("--merge runs nothing: --start-within has nothing to limit");
    }
    let group_over = match &a.group_over {
        Some(g) if !study.axes.iter().any(|(k, _)| k == g) => {
            bail!(
                "--group-over {g}: the study has no such axis (its axes: {})",
                axis_names(&study)
            )
        }
        Some(g) => Some(g.clone()),
        None => study
            .axes
            .iter()
            .find(|(k, _)| k == "seed")
            .map(|(k, _)| k.clone()),
    };
    let (shard, shards) = match &a.shard {
        Some(s) => parse_shard(s)?,
        None => (1, 1),
    };
    if !a.merge {
        let mine: Vec<&Run> = study
            .runs
            .iter()
            .filter(|r| r.index % shards == shard - 1)
            .collect();
        let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
        // Under mpirun, whether this is rank 0 (which merges); alone, None.
        #[cfg(feature = "mpi")]
        let ranked = match ranks::Ranks::start() {
            Some(ranks) => {
                if a.jobs != 1 {
                    bail!(
                        "under mpirun each rank runs one run at a time: start more ranks instead of --jobs"
                    );
                }
                // The cores of a machine shared among the ranks on it (Open MPI and MPICH say how many).
                let local = ["OMPI_COMM_WORLD_LOCAL_SIZE", "MPI_LOCALNRANKS"]
                    .iter()
                    .find_map(|v| std::env::var(v).ok()?.parse::<usize>().ok())
                    .unwrap_or(1);
                Some(ranks.share(
                    &study,
                    &mine,
                    &runs_dir,
                    threads.unwrap_or((cores / local).max(1)),
                    starts_until,
                ))
            }
            None => None,
        };
        #[cfg(not(feature = "mpi"))]
        let ranked: Option<bool> = None;
        match ranked {
            Some(false) => return Ok(()),
            Some(true) => {}
            None => {
                // The cores go to the runs left: the last run of a resumed study gets them all.
                let left = mine
                    .iter()
                    .filter(|r| !finished(&study, r, &runs_dir.join(&r.name)))
                    .count();
                let jobs = a.jobs.min(left).max(1);
                run_all(
                    &study,
                    &mine,
                    &runs_dir,
                    jobs,
                    threads.unwrap_or((cores / jobs).max(1)),
                    starts_until,
                )
            }
        }
    }
    let (
        rows,
        Counts {
            failed,
            missing,
            elsewhere,
        },
    ) = merge(&study, &runs_dir)?;
    let table = root.join("study.csv");
    std::fs::create_dir_all(&root).with_context(|| format!("creating {}", root.display()))?;
    std::fs::write(&table, &rows).with_context(|| format!("writing {}", table.display()))?;
    if let Some(g) = &group_over {
        let groups = group(&rows, &study, g)?;
        let path = root.join("study-groups.csv");
        std::fs::write(&path, groups).with_context(|| format!("writing {}", path.display()))?;
    }
    let late = match (a.start_within, starts_until) {
        (Some(d), Some(t)) if missing > 0 && Instant::now() >= t => format!(
            " (none started after --start-within {}s: the same command resumes)",
            d.as_secs_f64()
        ),
        _ => String::new(),
    };
    crate::outln!(
        "{} runs: {} finished, {failed} failed, {missing} not run{late}{}; wrote {}{}",
        study.runs.len(),
        study.runs.len() - failed - missing - elsewhere,
        if elsewhere > 0 {
            format!(", {elsewhere} under way in another process (merge again when it ends: --merge)")
        } else {
            String::new()
        },
        table.display(),
        group_over.map_or(String::new(), |g| format!(" and study-groups.csv (over {g})"))
    );
    Ok(())
}

/// A wall time from `90`, `90s`, `30m` or `1.5h` (seconds without a unit).
fn parse_duration(text: &str) -> Result<Duration, String> {
    let t = text.trim();
    let (number, seconds) = match t.char_indices().last() {
        Some((i, 's')) => (&t[..i], 1.0),
        Some((i, 'm')) => (&t[..i], 60.0),
        Some((i, 'h')) => (&t[..i], 3600.0),
        _ => (t, 1.0),
    };
    match number.trim().parse::<f64>() {
        Ok(x) if x.is_finite() && x >= 0.0 => Ok(Duration::from_secs_f64(x * seconds)),
        _ => Err(format!(
            "`{text}` is not a wall time: a number >= 0 with the unit s, m or h (`90m`, `1.5h`)"
        )),
    }
}

fn axis_names(study: &Study) -> String {
    study
        .axes
        .iter()
        .map(|(k, _)| k.as_str())
        .collect::<Vec<_>>()
        .join(", ")
}

/// Runs `runs`, `jobs` at a time, each on `threads` threads, none started after
/// `starts_until`, with one progress bar that names the runs under way and their finished
/// steps (without a terminal, a line a minute).
fn run_all(
    study: &Study,
    runs: &[&Run],
    runs_dir: &Path,
    jobs: usize,
    threads: usize,
    starts_until: Option<Instant>,
) {
    crate::set_quiet(true);
    let bar = ProgressBar::new(runs.len() as u64).with_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} runs, {elapsed} elapsed, ~{eta} left  {msg}")
            .expect("valid template"),
    );
    let next = AtomicUsize::new(0);
    let under_way = Mutex::new(Vec::<&str>::new());
    std::thread::scope(|s| {
        let workers: Vec<_> = (0..jobs.min(runs.len()))
            .map(|_| {
                s.spawn(|| {
                    loop {
                        if starts_until.is_some_and(|t| Instant::now() >= t) {
                            break;
                        }
                        let k = next.fetch_add(1, Ordering::SeqCst);
                        let Some(run) = runs.get(k) else { break };
                        under_way.lock().expect("not poisoned").push(&run.name);
                        let outcome = execute(study, run, &runs_dir.join(&run.name), threads);
                        under_way.lock().expect("not poisoned").retain(|n| *n != run.name);
                        match outcome {
                            Outcome::Failed(e) => {
                                bar.suspend(|| crate::note_err(format_args!("run {} failed: {e}", run.name)))
                            }
                            Outcome::Elsewhere => bar.suspend(|| {
                                crate::note_err(format_args!(
                                    "run {} is under way in another process: left to it",
                                    run.name
                                ))
                            }),
                            Outcome::Done => {}
                        }
                        bar.inc(1);
                    }
                })
            })
            .collect();
        let (tick, every) = (Duration::from_millis(200), if bar.is_hidden() { 300 } else { 10 });
        let mut ticks = 0usize;
        while !workers.iter().all(|w| w.is_finished()) {
            std::thread::sleep(tick);
            ticks += 1;
            if ticks.is_multiple_of(every) {
                let names = under_way.lock().expect("not poisoned").clone();
                let status = standing(runs_dir, &names);
                if bar.is_hidden() {
                    crate::note_err(format_args!(
                        "{}/{} runs finished; under way: {status}",
                        bar.position(),
                        runs.len()
                    ));
                } else {
                    bar.set_message(status);
                }
            }
        }
    });
    bar.finish_and_clear();
    crate::set_quiet(false);
}
