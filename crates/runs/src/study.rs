//! `study`: a base case and axes to vary, expanded into runs (each a `solve` or a `sweep` in a
//! run directory of its own, named by its parameters), run side by side and resumed where they
//! stopped, their summaries merged into one table with a summary of each group.

use crate::solve::{self, SolveArgs};
use crate::sweep::{self, SweepArgs};
use anyhow::{Context, Result, bail};
use clap::{Args, Parser};
use indicatif::{ProgressBar, ProgressStyle};
use serde_json::Value;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::{Duration, Instant};

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

/// One run of a study: its index in the expansion, its axis values and its directory name.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    pub index: usize,
    pub values: Vec<(String, toml::Value)>,
    pub name: String,
}

/// A study file, read.
#[derive(Debug)]
pub struct Study {
    pub command: String,
    pub case: toml::Table,
    pub axes: Vec<(String, Vec<toml::Value>)>,
    pub runs: Vec<Run>,
}

/// A value as it appears in a run's name and in the table: TOML's own spelling (strings
/// unquoted).
fn spelt(v: &toml::Value) -> String {
    match v {
        toml::Value::String(s) => s.clone(),
        // Rust's shortest round-trip digits, with an exponent for the very small or large.
        toml::Value::Float(x) if *x != 0.0 && !(1e-3..1e6).contains(&x.abs()) => format!("{x:e}"),
        toml::Value::Float(x) => format!("{x:?}"),
        other => other.to_string(),
    }
}

/// A run directory's name from its values: `key=value` joined by `_`, any character that a
/// file name should not hold replaced by `-`.
fn run_name(values: &[(String, toml::Value)]) -> String {
    let name = values
        .iter()
        .map(|(k, v)| format!("{k}={}", spelt(v)))
        .collect::<Vec<_>>()
        .join("_");
    let clean = clean_name(&name);
    if clean.is_empty() { "base".into() } else { clean }
}

/// `name` with any character a file name should not hold replaced by `-`.
fn clean_name(name: &str) -> String {
    name.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "=._+-".contains(c) {
                c
            } else {
                '-'
            }
        })
        .collect()
}

impl Study {
    /// Reads a study file; paths in its case are taken relative to the file's folder.
    pub fn read(path: &Path) -> Result<Study> {
        let text = std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
        Study::parse(&text, path)
    }

    fn parse(text: &str, path: &Path) -> Result<Study> {
        let name = path.display();
        let mut table: toml::Table = toml::from_str(text).with_context(|| format!("parsing {name}"))?;
        let dir = path.parent().unwrap_or(Path::new(""));
        let command = match table.remove("command") {
            Some(toml::Value::String(c)) if c == "solve" || c == "sweep" => c,
            Some(other) => bail!("{name}: `command` is \"solve\" or \"sweep\", got {other}"),
            None => bail!("{name}: say what each run is: command = \"solve\" or \"sweep\""),
        };
        let mut case = match table.remove("case") {
            Some(toml::Value::Table(t)) => t,
            Some(toml::Value::String(file)) => {
                let file = dir.join(file);
                let text =
                    std::fs::read_to_string(&file).with_context(|| format!("reading {}", file.display()))?;
                let mut t: toml::Table =
                    toml::from_str(&text).with_context(|| format!("parsing {}", file.display()))?;
                beside(&mut t, file.parent().unwrap_or(Path::new("")));
                t
            }
            Some(other) => bail!("{name}: `case` is a table of case keys or a case file's path, got {other}"),
            None => toml::Table::new(),
        };
        beside(&mut case, dir);
        let zip = match table.remove("combine") {
            None => false,
            Some(toml::Value::String(c)) if c == "product" => false,
            Some(toml::Value::String(c)) if c == "zip" => true,
            Some(other) => bail!("{name}: `combine` is \"product\" or \"zip\", got {other}"),
        };
        let axes: Vec<(String, Vec<toml::Value>)> = match table.remove("axes") {
            Some(toml::Value::Table(t)) => t
                .into_iter()
                .map(|(k, v)| match v {
                    toml::Value::Array(values) if !values.is_empty() => Ok((k, values)),
                    other => bail!("{name}: axis `{k}` must be a non-empty list of values, got {other}"),
                })
                .collect::<Result<_>>()?,
            Some(other) => bail!("{name}: `axes` is a table of lists, got {other}"),
            None => Vec::new(),
        };
        let names = match table.remove("names") {
            None => None,
            Some(toml::Value::Array(v)) => Some(
                v.into_iter()
                    .map(|n| match n {
                        toml::Value::String(n) if !n.is_empty() && n != "." && n != ".." => Ok(n),
                        other => {
                            bail!("{name}: `names` are the runs' directory names (strings), got {other}")
                        }
                    })
                    .collect::<Result<Vec<String>>>()?,
            ),
            Some(other) => bail!("{name}: `names` is a list of the runs' directory names, got {other}"),
        };
        if let Some(k) = table.keys().next() {
            bail!("{name}: unknown key `{k}`; a study has command, case, axes, combine and names");
        }
        for (k, _) in &axes {
            if k == "out" {
                bail!("{name}: `out` cannot be an axis: each run has its own directory");
            }
        }
        bound_runs(&axes, zip).with_context(|| format!("{name}: the axes"))?;
        let mut runs = expand(&axes, zip).with_context(|| format!("{name}: the axes"))?;
        if let Some(names) = names {
            if names.len() != runs.len() {
                bail!("{name}: {} names for {} runs", names.len(), runs.len());
            }
            if let Some(bad) = names.iter().find(|n| **n != clean_name(n)) {
                bail!("{name}: the run name `{bad}` is not a plain file name (letters, digits, = . _ + -)");
            }
            for (run, n) in runs.iter_mut().zip(names) {
                run.name = n;
            }
            unique(&runs)?;
        }
        let study = Study {
            command,
            case,
            axes,
            runs,
        };
        study.check_runs().with_context(|| format!("{name}"))?;
        Ok(study)
    }

    /// Checks every run's case before the first runs: unknown keys, values of the wrong type
    /// and keys that do not apply are refused naming the run and the key, so that a study
    /// does not run each run into the same error.
    fn check_runs(&self) -> Result<()> {
        for run in &self.runs {
            let mut t = self.case.clone();
            for (k, v) in &run.values {
                t.insert(k.clone(), v.clone());
            }
            let checked = if self.command == "sweep" {
                case::from_table::<case::Case, case::SweepPath>("the case", t).map(|(c, _)| c)
            } else {
                case::from_table::<case::Case, case::SolveControl>("the case", t).map(|(c, _)| c)
            }
            .and_then(|mut c| {
                c.fill_defaults("");
                c.check_applicable()
            });
            if let Err(e) = checked {
                let axis = |k: &str| self.axes.iter().any(|(a, _)| a == k);
                let message = format!("{e:#}");
                let culprit = run
                    .values
                    .iter()
                    .find(|(k, _)| message.contains(&format!("`{k}`")));
                let named = culprit
                    .filter(|(k, _)| axis(k))
                    .map_or(String::new(), |(k, v)| format!(" (axis `{k}` = {})", spelt(v)));
                bail!("run {}{named}: {message}", run.name);
            }
        }
        Ok(())
    }

    /// A run's case file: the base case, the run's values, its output directory.
    fn run_case(&self, run: &Run, out: &Path) -> Result<String> {
        let mut t = self.case.clone();
        for (k, v) in &run.values {
            t.insert(k.clone(), v.clone());
        }
        t.insert("out".into(), toml::Value::String(out.display().to_string()));
        Ok(toml::to_string(&t)?)
    }
}

/// Whether a run's case (`run.toml`) is the one the study gives it now: the same keys and
/// values but for its output directory and the folders of the files it names, which differ
/// between machines and checkouts.
fn same_run(old: &str, new: &str) -> bool {
    let table = |t: &str| {
        sweep::without_out(t).map(|mut t| {
            for key in FILE_KEYS {
                if let Some(toml::Value::String(p)) = t.get_mut(key) {
                    *p = Path::new(p.as_str())
                        .file_name()
                        .map_or_else(String::new, |f| f.to_string_lossy().into_owned());
                }
            }
            t
        })
    };
    matches!((table(old), table(new)), (Some(a), Some(b)) if a == b)
}

/// The case keys that name files.
const FILE_KEYS: [&str; 2] = ["surface", "start_from"];

/// Case keys that name files, made absolute against the folder of the file that gave them.
fn beside(case: &mut toml::Table, dir: &Path) {
    for key in FILE_KEYS {
        if let Some(toml::Value::String(p)) = case.get_mut(key)
            && Path::new(p).is_relative()
        {
            *p = dir.join(&*p).display().to_string();
        }
    }
}

/// The runs of the axes (in alphabetical order): every combination, the last axis varying
/// fastest (product), or the lists side by side (zip; they must be equally long).
fn expand(axes: &[(String, Vec<toml::Value>)], zip: bool) -> Result<Vec<Run>> {
    let combos: Vec<Vec<(String, toml::Value)>> = if zip {
        let len = axes.first().map_or(1, |(_, v)| v.len());
        if let Some((k, v)) = axes.iter().find(|(_, v)| v.len() != len) {
            bail!(
                "combine = \"zip\" needs lists of one length: `{k}` has {}, not {len}",
                v.len()
            );
        }
        (0..len)
            .map(|i| axes.iter().map(|(k, v)| (k.clone(), v[i].clone())).collect())
            .collect()
    } else {
        let mut combos = vec![Vec::new()];
        for (k, values) in axes {
            combos = combos
                .into_iter()
                .flat_map(|c| {
                    values.iter().map(move |v| {
                        let mut c = c.clone();
                        c.push((k.clone(), v.clone()));
                        c
                    })
                })
                .collect();
        }
        combos
    };
    let runs: Vec<Run> = combos
        .into_iter()
        .enumerate()
        .map(|(index, values)| Run {
            index,
            name: run_name(&values),
            values,
        })
        .collect();
    unique(&runs)?;
    Ok(runs)
}

/// The bytes a run of a study takes before it runs, per axis (its values and name), and its
/// row of the merged tables: for refusing an axis product the machine cannot list.
const RUN_BYTES: f64 = 256.0;
const RUN_BYTES_PER_AXIS: f64 = 160.0;

/// Refuses axes whose runs cannot be listed, with the count and the memory it would take,
/// before any run is made.
fn bound_runs(axes: &[(String, Vec<toml::Value>)], zip: bool) -> Result<()> {
    let count = if zip {
        axes.first().map_or(1.0, |(_, v)| v.len() as f64)
    } else {
        axes.iter().map(|(_, v)| v.len() as f64).product()
    };
    case::memory::check(
        &format!("a study of {count:.3e} runs"),
        count * (RUN_BYTES + RUN_BYTES_PER_AXIS * axes.len() as f64),
    )
}

/// Refuses runs that would share a directory.
fn unique(runs: &[Run]) -> Result<()> {
    let mut sorted: Vec<&Run> = runs.iter().collect();
    sorted.sort_by(|a, b| a.name.cmp(&b.name));
    if let Some(w) = sorted.windows(2).find(|w| w[0].name == w[1].name) {
        let values = |r: &Run| {
            r.values
                .iter()
                .map(|(k, v)| format!("`{k}` = {v}"))
                .collect::<Vec<_>>()
                .join(", ")
        };
        bail!(
            "two runs would share the directory {} ({} and {}): an axis repeats a value, or two values \
             spell one name; give each run a name (`names`)",
            w[0].name,
            values(w[0]),
            values(w[1])
        );
    }
    Ok(())
}

/// `I/N` with 1 <= I <= N.
fn parse_shard(s: &str) -> Result<(usize, usize)> {
    let parsed = s
        .split_once('/')
        .and_then(|(i, n)| Some((i.trim().parse::<usize>().ok()?, n.trim().parse::<usize>().ok()?)));
    match parsed {
        Some((i, n)) if n >= 1 && (1..=n).contains(&i) => Ok((i, n)),
        _ => bail!("--shard is I/N with 1 <= I <= N (e.g. 2/8), got {s}"),
    }
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

/// Each of the runs `names` with the steps its curve has so far and where its running step
/// stands.
fn standing(runs_dir: &Path, names: &[&str]) -> String {
    names
        .iter()
        .map(|n| {
            let dir = runs_dir.join(n);
            let rows = std::fs::read_to_string(dir.join("curve.csv"))
                .map_or(0, |t| t.lines().count().saturating_sub(1));
            match crate::run::read_progress(&dir) {
                Some(progress) => format!("{n} ({rows} steps done; {})", progress.trim()),
                None => format!("{n} ({rows} steps done)"),
            }
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The finished runs' summaries as one table (study.csv: a row a run in the study's order,
/// its axis values, its status and error, and every number, flag and word of the top level of
/// its summary.json except wall times, so that the table does not depend on how the runs were
/// spread); with the counts of failed and missing runs.
fn merge(study: &Study, runs_dir: &Path) -> Result<(String, Counts)> {
    let mut rows: Vec<(String, Option<String>, BTreeMap<String, String>)> = Vec::new();
    let (mut failed, mut missing, mut elsewhere) = (0, 0, 0);
    let mut columns = std::collections::BTreeSet::new();
    for run in &study.runs {
        let dir = runs_dir.join(&run.name);
        let summary = dir.join("summary.json");
        let mut fields = BTreeMap::new();
        let (status, error) = if let Ok(text) = std::fs::read_to_string(&summary) {
            let value: Value =
                serde_json::from_str(&text).with_context(|| format!("reading {}", summary.display()))?;
            if let Value::Object(m) = value {
                for (k, v) in m {
                    let cell = match v {
                        Value::Number(x) => x.to_string(),
                        Value::Bool(b) => b.to_string(),
                        Value::String(s) => s,
                        _ => continue,
                    };
                    if k.ends_with("wall_time_s") {
                        continue;
                    }
                    columns.insert(k.clone());
                    fields.insert(k, cell);
                }
            }
            ("finished".to_string(), None)
        } else if crate::run::busy(&dir) {
            elsewhere += 1;
            ("under way elsewhere".to_string(), None)
        } else if let Ok(e) = std::fs::read_to_string(dir.join("error.txt")) {
            failed += 1;
            ("failed".to_string(), Some(e))
        } else {
            missing += 1;
            ("not run".to_string(), None)
        };
        rows.push((status, error, fields));
    }
    let mut header = vec!["run".to_string()];
    header.extend(study.axes.iter().map(|(k, _)| k.clone()));
    header.extend(["status".to_string(), "error".to_string()]);
    header.extend(columns.iter().cloned());
    let mut csv = csv::Writer::from_writer(Vec::new());
    csv.write_record(&header)?;
    for (run, (status, error, fields)) in study.runs.iter().zip(rows) {
        let mut record = vec![run.name.clone()];
        record.extend(run.values.iter().map(|(_, v)| spelt(v)));
        record.extend([status, error.unwrap_or_default()]);
        record.extend(columns.iter().map(|c| fields.get(c).cloned().unwrap_or_default()));
        csv.write_record(&record)?;
    }
    let bytes = csv
        .into_inner()
        .map_err(|e| anyhow::anyhow!("writing the table: {e}"))?;
    Ok((
        String::from_utf8(bytes)?,
        Counts {
            failed,
            missing,
            elsewhere,
        },
    ))
}

/// How many runs of a merged table are not finished.
struct Counts {
    failed: usize,
    missing: usize,
    /// Under way in another process (its lock held).
    elsewhere: usize,
}

/// A CSV table's header and rows (RFC 4180 quoting: cells may hold commas, quotes and line
/// breaks).
fn read_table(table: &str) -> Result<(Vec<String>, Vec<Vec<String>>)> {
    let mut reader = csv::ReaderBuilder::new().from_reader(table.as_bytes());
    let header = reader.headers()?.iter().map(str::to_string).collect();
    let rows = reader
        .records()
        .map(|r| Ok(r?.iter().map(str::to_string).collect()))
        .collect::<Result<_>>()?;
    Ok((header, rows))
}

/// One CSV line of `cells`, quoted where they need it.
fn csv_line(cells: &[String]) -> Result<String> {
    let mut csv = csv::WriterBuilder::new().from_writer(Vec::new());
    csv.write_record(cells)?;
    let bytes = csv
        .into_inner()
        .map_err(|e| anyhow::anyhow!("writing the table: {e}"))?;
    Ok(String::from_utf8(bytes)?)
}

/// study-groups.csv: the finished runs grouped by every axis but `over`, and for every
/// numeric column its mean, standard error (sample standard deviation over sqrt(count)) and
/// count over the group.
fn group(table: &str, study: &Study, over: &str) -> Result<String> {
    let (header, rows) = read_table(table)?;
    let column = |name: &str| {
        header
            .iter()
            .position(|h| h == name)
            .with_context(|| format!("study.csv has no column `{name}`"))
    };
    let keys: Vec<usize> = study
        .axes
        .iter()
        .filter(|(k, _)| k != over)
        .map(|(k, _)| column(k))
        .collect::<Result<_>>()?;
    let first_result = column("error")? + 1;
    let finished: Vec<&Vec<String>> = rows
        .iter()
        .filter(|r| r[first_result - 2] == "finished")
        .collect();
    let numeric: Vec<usize> = (first_result..header.len())
        .filter(|&c| {
            finished.iter().any(|r| !r[c].is_empty())
                && finished
                    .iter()
                    .all(|r| r[c].is_empty() || r[c].parse::<f64>().is_ok())
        })
        .collect();
    let mut groups: Vec<(Vec<String>, Vec<&Vec<String>>)> = Vec::new();
    for r in &finished {
        let key: Vec<String> = keys.iter().map(|&k| r[k].clone()).collect();
        match groups.iter_mut().find(|(k, _)| *k == key) {
            Some((_, members)) => members.push(r),
            None => groups.push((key, vec![r])),
        }
    }
    let mut csv = keys.iter().map(|&k| header[k].clone()).collect::<Vec<_>>();
    csv.push("runs".into());
    for &c in &numeric {
        csv.extend([
            format!("{}_mean", header[c]),
            format!("{}_stderr", header[c]),
            format!("{}_count", header[c]),
        ]);
    }
    let mut out = csv_line(&csv)?;
    for (key, members) in groups {
        let mut line: Vec<String> = key;
        line.push(members.len().to_string());
        for &c in &numeric {
            let xs: Vec<f64> = members.iter().filter_map(|r| r[c].parse::<f64>().ok()).collect();
            let n = xs.len() as f64;
            let mean = xs.iter().sum::<f64>() / n;
            let stderr = if xs.len() > 1 {
                (xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt() / n.sqrt()
            } else {
                f64::NAN
            };
            line.extend([format!("{mean:e}"), format!("{stderr:e}"), xs.len().to_string()]);
        }
        out += &csv_line(&line)?;
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn study(text: &str) -> Result<Study> {
        Study::parse(text, Path::new("/studies/s.toml"))
    }

    /// A run under way shows its finished steps and, once its sweep has written it, where its
    /// running step stands; a finished step clears that.
    #[test]
    fn runs_under_way_show_where_their_step_stands() {
        let runs = std::env::temp_dir().join(format!("roughcontact-standing-{}", std::process::id()));
        let dir = crate::run::RunDir::open(&runs.join("a"), crate::run::Reuse::Refuse).unwrap();
        std::fs::write(dir.path().join("curve.csv"), "step\n0\n1\n").unwrap();
        assert_eq!(standing(&runs, &["a"]), "a (2 steps done)");
        dir.write_progress(Some("step 3/11: iteration 40, residual 1.00e-2"));
        assert_eq!(
            standing(&runs, &["a"]),
            "a (2 steps done; step 3/11: iteration 40, residual 1.00e-2)"
        );
        dir.write_progress(None);
        assert_eq!(standing(&runs, &["a"]), "a (2 steps done)");
        drop(dir);
        std::fs::remove_dir_all(&runs).unwrap();
    }

    #[test]
    fn wall_times_read_with_their_units() {
        for (text, seconds) in [("90", 90.0), ("90s", 90.0), ("30m", 1800.0), ("1.5h", 5400.0)] {
            assert_eq!(
                parse_duration(text),
                Ok(Duration::from_secs_f64(seconds)),
                "{text}"
            );
        }
        for bad in ["", "h", "-1m", "2d", "inf", "1 hour"] {
            assert!(parse_duration(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn axes_expand_into_named_runs() {
        let s = study(
            "command = \"sweep\"\ncase = { modulus = 1e9, rms_height = 1e-8, start_from = \"a\" }\n[axes]\nseed = [1, 2]\nlaw = [\"point\", \"surface\"]\n",
        )
        .unwrap();
        let names: Vec<&str> = s.runs.iter().map(|r| r.name.as_str()).collect();
        // The axes in alphabetical order, the last varying fastest.
        let expected = [
            "law=point_seed=1",
            "law=point_seed=2",
            "law=surface_seed=1",
            "law=surface_seed=2",
        ];
        assert_eq!(names, expected);
        assert_eq!(s.case["start_from"].as_str(), Some("/studies/a"));
        let zipped =
            study("command = \"solve\"\ncombine = \"zip\"\ncase = { rms_height = 1e-8, law = \"point\" }\n[axes]\nseed = [1, 2]\nz0 = [1e-9, 2e-9]\n")
                .unwrap();
        assert_eq!(zipped.runs.len(), 2);
        assert_eq!(zipped.runs[1].name, "seed=2_z0=2e-9");
    }

    #[test]
    fn bad_studies_are_refused() {
        for (text, message) in [
            ("[axes]\nseed = [1]\n", "command = \"solve\" or \"sweep\""),
            ("command = \"run\"\n", "`command` is"),
            ("command = \"solve\"\n[axes]\nseed = 1\n", "non-empty list"),
            ("command = \"solve\"\n[axes]\nseed = []\n", "non-empty list"),
            (
                "command = \"solve\"\ncombine = \"zip\"\n[axes]\nseed = [1, 2]\nz0 = [1.0]\n",
                "one length",
            ),
            (
                "command = \"solve\"\n[axes]\nseed = [1, 1]\n",
                "share the directory",
            ),
            ("command = \"solve\"\nbogus = 1\n", "unknown key `bogus`"),
        ] {
            let e = format!("{:#}", study(text).unwrap_err());
            assert!(e.contains(message), "{text}: {e}");
        }
        assert!(parse_shard("0/2").is_err() && parse_shard("3/2").is_err() && parse_shard("x").is_err());
        assert_eq!(parse_shard("2/3").unwrap(), (2, 3));
    }

    /// Any value an axis could list, the plausible and the awkward.
    fn axis_value() -> impl proptest::strategy::Strategy<Value = toml::Value> {
        use proptest::prelude::*;
        prop_oneof![
            prop_oneof![
                Just(f64::NAN),
                Just(-1.0),
                Just(0.0),
                Just(1e-9),
                Just(0.5),
                Just(48.5),
                any::<f64>()
            ]
            .prop_map(toml::Value::Float),
            prop_oneof![Just(-3i64), Just(0), Just(1), Just(32), Just(i64::MAX)]
                .prop_map(toml::Value::Integer),
            prop_oneof![Just("two"), Just("point"), Just("free"), Just("")]
                .prop_map(|s| toml::Value::String(s.into())),
            any::<bool>().prop_map(toml::Value::Boolean),
            Just(toml::Value::Array(vec![toml::Value::Integer(1)])),
        ]
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig { cases: 200, failure_persistence: None, ..Default::default() })]

        /// Any axes over a generated surface's case: the study is refused naming an axis or a
        /// key, or every run's case reads, types and applies (so no run fails on them).
        #[test]
        fn any_axes_are_checked_before_a_run(
            axes in proptest::collection::vec(
                (proptest::sample::select(vec!["seed", "n", "hurst", "law", "z0", "modulus", "exact_sphere", "surface", "bogus", "mean_pressure", "tolerance", "domain"]),
                 proptest::collection::vec(axis_value(), 1..3)),
                1..3,
            ),
            command in proptest::sample::select(vec!["solve", "sweep"]),
        ) {
            let mut text = format!("command = \"{command}\"\n[case]\nlength = 1e-6\nrms_height = 1e-8\nmodulus = 1e9\n[axes]\n");
            let mut seen = Vec::new();
            for (k, values) in &axes {
                if seen.contains(k) {
                    continue;
                }
                seen.push(*k);
                text += &format!("{k} = {}\n", toml::Value::Array(values.clone()));
            }
            let parsed = std::panic::catch_unwind(|| study(&text));
            proptest::prop_assert!(parsed.is_ok(), "panicked on {text}");
            match parsed.unwrap() {
                Ok(s) => {
                    for run in &s.runs {
                        let mut t = s.case.clone();
                        t.extend(run.values.iter().cloned());
                        let read = if command == "sweep" {
                            case::from_table::<case::Case, case::SweepPath>("run", t).map(|(c, _)| c)
                        } else {
                            case::from_table::<case::Case, case::SolveControl>("run", t).map(|(c, _)| c)
                        };
                        let applies = read.and_then(|mut c| {
                            c.fill_defaults("");
                            c.check_applicable()
                        });
                        proptest::prop_assert!(applies.is_ok(), "{text}: run {} passed the check: {:?}", run.name, applies.err());
                    }
                }
                Err(e) => {
                    let message = format!("{e:#}");
                    proptest::prop_assert!(
                        seen.iter().any(|k| message.contains(&format!("`{k}`")) || message.contains(&format!("--{}", k.replace('_', "-")))),
                        "{text}: the error names no axis: {message}"
                    );
                }
            }
        }
    }

    #[test]
    fn groups_have_means_and_standard_errors() {
        let s = study(
            "command = \"solve\"\ncase = { rms_height = 1e-8 }\n[axes]\nmodulus = [1, 2]\nseed = [1, 2, 3]\n",
        )
        .unwrap();
        let table = "run,modulus,seed,status,error,load,law\n\
                     a,1,1,finished,,1.0,x\na,1,2,finished,,2.0,x\na,1,3,finished,,3.0,x\n\
                     b,2,1,finished,,5.0,x\nb,2,2,failed,\"bad, input\",,\nb,2,3,finished,,7.0,x\n";
        let g = group(table, &s, "seed").unwrap();
        let lines: Vec<&str> = g.lines().collect();
        assert_eq!(lines[0], "modulus,runs,load_mean,load_stderr,load_count");
        let one: Vec<&str> = lines[1].split(',').collect();
        assert_eq!([one[0], one[1], one[2], one[4]], ["1", "3", "2e0", "3"]);
        let stderr: f64 = one[3].parse().unwrap();
        assert!((stderr - (1.0f64 / 3.0).sqrt()).abs() < 1e-15, "{stderr}");
        assert_eq!(lines[2], "2,2,6e0,1e0,2");
        let (_, quoted) = read_table("a,b,c\na,\"b, \"\"c\"\"\nd\",e\n").unwrap();
        assert_eq!(quoted, [["a", "b, \"c\"\nd", "e"]]);
    }
}

/// MPI ranks sharing a study's runs (feature `mpi`, under `mpirun -n K`): rank 0 hands out
/// the runs one at a time to whichever rank asks (its own included) and merges at the end; a
/// rank asks again when its run is done.
#[cfg(feature = "mpi")]
mod ranks {
    use super::{Outcome, Run, Study, execute};
    use mpi::traits::*;
    use std::path::Path;
    use std::sync::mpsc;
    use std::time::{Duration, Instant};

    const ASK: i32 = 1;
    const GIVE: i32 = 2;
    /// The answer that there is nothing left.
    const DONE: u64 = u64::MAX;

    pub struct Ranks {
        _universe: mpi::environment::Universe,
        world: mpi::topology::SimpleCommunicator,
    }

    impl Ranks {
        /// MPI, when this process is one of several ranks (`None` alone: the study runs as
        /// on one machine).
        pub fn start() -> Option<Ranks> {
            let universe = mpi::initialize()?;
            let world = universe.world();
            (world.size() > 1).then_some(Ranks {
                _universe: universe,
                world,
            })
        }

        /// Runs `runs` across the ranks, `threads` threads each; whether this is rank 0 (which
        /// then merges).
        pub fn share(
            &self,
            study: &Study,
            runs: &[&Run],
            runs_dir: &Path,
            threads: usize,
            starts_until: Option<Instant>,
        ) -> bool {
            crate::set_quiet(true);
            let root = self.world.process_at_rank(0);
            if self.world.rank() != 0 {
                loop {
                    root.send_with_tag(&0u64, ASK);
                    let (k, _) = root.receive_with_tag::<u64>(GIVE);
                    if k == DONE {
                        return false;
                    }
                    let run = runs[k as usize];
                    if let Outcome::Failed(e) = execute(study, run, &runs_dir.join(&run.name), threads) {
                        crate::note_err(format_args!("run {} failed: {e}", run.name));
                    }
                }
            }
            // Rank 0: its own runs on a thread that never calls MPI; this one answers the others.
            let mut next = 0usize;
            let mut hand_out = || {
                let k = next;
                next += 1;
                let late = starts_until.is_some_and(|t| Instant::now() >= t);
                (k < runs.len() && !late).then_some(k)
            };
            let (give, take) = mpsc::channel::<Option<usize>>();
            let (finished, done) = mpsc::channel::<()>();
            std::thread::scope(|s| {
                s.spawn(move || {
                    while let Ok(Some(k)) = take.recv() {
                        let run = runs[k];
                        if let Outcome::Failed(e) = execute(study, run, &runs_dir.join(&run.name), threads) {
                            crate::note_err(format_args!("run {} failed: {e}", run.name));
                        }
                        if finished.send(()).is_err() {
                            break;
                        }
                    }
                });
                let (mut busy, mut local_done, mut others) = (false, false, self.world.size() - 1);
                while others > 0 || !local_done || busy {
                    let mut idle = true;
                    if !busy && !local_done {
                        let k = hand_out();
                        local_done = k.is_none();
                        busy = k.is_some();
                        let _ = give.send(k);
                        idle = false;
                    }
                    if busy && done.try_recv().is_ok() {
                        busy = false;
                        idle = false;
                    }
                    if let Some(status) = self.world.any_process().immediate_probe_with_tag(ASK) {
                        let from = self.world.process_at_rank(status.source_rank());
                        let _ = from.receive_with_tag::<u64>(ASK);
                        let k = hand_out().map_or(DONE, |k| k as u64);
                        others -= usize::from(k == DONE) as i32;
                        from.send_with_tag(&k, GIVE);
                        idle = false;
                    }
                    if idle {
                        std::thread::sleep(Duration::from_millis(2));
                    }
                }
            });
            crate::set_quiet(false);
            true
        }
    }
}
