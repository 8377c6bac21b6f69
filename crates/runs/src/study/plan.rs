//! A study's plan: its file read, its axes expanded into runs, each run named and its case
//! made.

use crate::sweep;
use anyhow::{Context, Result, bail};
use std::path::Path;

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
pub(super) fn spelt(v: &toml::Value) -> String {
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
pub(super) fn run_name(values: &[(String, toml::Value)]) -> String {
    let name = values
        .iter()
        .map(|(k, v)| format!("{k}={}", spelt(v)))
        .collect::<Vec<_>>()
        .join("_");
    let clean = clean_name(&name);
    if clean.is_empty() { "base".into() } else { clean }
}

/// `name` with any character a file name should not hold replaced by `-`.
pub(super) fn clean_name(name: &str) -> String {
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

    pub(super) fn parse(text: &str, path: &Path) -> Result<Study> {
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
    pub(super) fn run_case(&self, run: &Run, out: &Path) -> Result<String> {
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
pub(super) fn same_run(old: &str, new: &str) -> bool {
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
pub(super) const FILE_KEYS: [&str; 2] = ["surface", "start_from"];

/// Case keys that name files, made absolute against the folder of the file that gave them.
pub(super) fn beside(case: &mut toml::Table, dir: &Path) {
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
pub(super) fn expand(axes: &[(String, Vec<toml::Value>)], zip: bool) -> Result<Vec<Run>> {
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
pub(super) const RUN_BYTES: f64 = 256.0;
pub(super) const RUN_BYTES_PER_AXIS: f64 = 160.0;

/// Refuses axes whose runs cannot be listed, with the count and the memory it would take,
/// before any run is made.
pub(super) fn bound_runs(axes: &[(String, Vec<toml::Value>)], zip: bool) -> Result<()> {
    let count = if zip {
        axes.first().map_or(1.0, |(_, v)| v.len() as f64)
    } else {
        axes.iter().map(|(_, v)| v.len() as f64).product()
    };
    case::memory::check(
        &format!("a study of {count:.3e} runs"),
        count * (RUN_BYTES + RUN_BYTES_PER_AXIS * axes.len() as f64),
    )?;
    Ok(())
}

/// Refuses runs that would share a directory.
pub(super) fn unique(runs: &[Run]) -> Result<()> {
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
pub(super) fn parse_shard(s: &str) -> Result<(usize, usize)> {
    let parsed = s
        .split_once('/')
        .and_then(|(i, n)| Some((i.trim().parse::<usize>().ok()?, n.trim().parse::<usize>().ok()?)));
    match parsed {
        Some((i, n)) if n >= 1 && (1..=n).contains(&i) => Ok((i, n)),
        _ => bail!("--shard is I/N with 1 <= I <= N (e.g. 2/8), got {s}"),
    }
}
