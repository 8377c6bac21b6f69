//! Series of runs through `roughcontact study`: the figures' rough-sphere and challenge runs
//! are studies of sweeps in `OUT/studies/`, so that a figure built again resumes where its
//! runs stopped, and a study file can be run by hand across machines (`mpirun -n K
//! roughcontact study FILE`, or a Slurm job array with `--shard`) before the figures read
//! its finished runs (`docs/studies.md`).

use anyhow::{Context as _, Result, bail};
use std::path::{Path, PathBuf};

/// One sweep of a series: its study, its run's directory name and its case keys.
pub struct Sweep {
    pub study: String,
    pub name: String,
    pub keys: toml::Table,
}

/// Writes the study files of `sweeps`, grouped by study (`dir/<study>.toml`, its runs to go
/// in `dir/<study>/runs/`): the keys every run of a study shares form its base case, the
/// others its zipped axes. Returns each study's file, directory and number of runs.
pub fn write(dir: &Path, sweeps: &[Sweep]) -> Result<Vec<(PathBuf, PathBuf, usize)>> {
    let mut studies: Vec<&str> = sweeps.iter().map(|s| s.study.as_str()).collect();
    studies.sort();
    studies.dedup();
    let mut written = Vec::new();
    for study in studies {
        let runs: Vec<&Sweep> = sweeps.iter().filter(|s| s.study == study).collect();
        let first = &runs[0].keys;
        if let Some(odd) = runs.iter().find(|r| !r.keys.keys().eq(first.keys())) {
            bail!(
                "the runs {} and {} of study {study} set different keys",
                runs[0].name,
                odd.name
            );
        }
        let (mut case, mut axes) = (toml::Table::new(), toml::Table::new());
        for (key, value) in first {
            let values: Vec<toml::Value> = runs.iter().map(|r| r.keys[key].clone()).collect();
            if values.iter().all(|v| v == value) {
                case.insert(key.clone(), value.clone());
            } else {
                axes.insert(key.clone(), values.into());
            }
        }
        let mut file = toml::Table::new();
        file.insert("command".into(), "sweep".into());
        file.insert("combine".into(), "zip".into());
        let names: Vec<toml::Value> = runs.iter().map(|r| r.name.clone().into()).collect();
        file.insert("names".into(), names.into());
        file.insert("case".into(), case.into());
        file.insert("axes".into(), axes.into());
        let out = dir.join(study);
        std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
        let path = dir.join(format!("{study}.toml"));
        std::fs::write(&path, toml::to_string(&file)?)
            .with_context(|| format!("writing {}", path.display()))?;
        written.push((path, out, runs.len()));
    }
    Ok(written)
}

/// Runs `sweeps` as the studies [`write()`] writes, as `roughcontact study` would. Returns each
/// sweep's run directory, in order; a failed run is an error.
pub fn run(dir: &Path, sweeps: &[Sweep]) -> Result<Vec<PathBuf>> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    for (file, out, _) in write(dir, sweeps)? {
        runs::study::run(&file, &out, cores, None)?;
    }
    sweeps
        .iter()
        .map(|s| {
            let run = dir.join(&s.study).join("runs").join(&s.name);
            match std::fs::read_to_string(run.join("error.txt")) {
                Ok(error) => bail!("the run {} failed: {error}", run.display()),
                Err(_) => Ok(run),
            }
        })
        .collect()
}

/// The run directory of each of `sweeps` that has finished in `dir` with the keys it has now
/// (as `roughcontact study` would find it, and not run it again), else `None`; nothing is run.
/// For a series drawn beside a figure's own from the runs earlier builds or studies left.
pub fn finished(dir: &Path, sweeps: &[Sweep]) -> Vec<Option<PathBuf>> {
    sweeps
        .iter()
        .map(|s| {
            let run = dir.join(&s.study).join("runs").join(&s.name);
            let keys = std::fs::read_to_string(run.join("run.toml"))
                .ok()
                .and_then(|text| toml::from_str::<toml::Table>(&text).ok())
                .map(|mut keys| {
                    keys.remove("out");
                    keys
                });
            (run.join("summary.json").exists() && keys.as_ref() == Some(&s.keys)).then_some(run)
        })
        .collect()
}

/// A finished or half-finished sweep's `curve.csv`, read a column at a time.
pub struct Curve {
    path: PathBuf,
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Curve {
    /// The curve of the sweep in the run directory `run`.
    pub fn read(run: &Path) -> Result<Curve> {
        let path = run.join("curve.csv");
        let text = std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
        let mut lines = text
            .lines()
            .map(|l| l.split(',').map(str::to_string).collect::<Vec<_>>());
        let header = lines.next().context("an empty curve")?;
        let rows = lines.collect();
        Ok(Curve { path, header, rows })
    }

    /// The number of steps.
    pub fn len(&self) -> usize {
        self.rows.len()
    }

    pub fn is_empty(&self) -> bool {
        self.rows.is_empty()
    }

    /// The column `name` as text.
    pub fn text(&self, name: &str) -> Result<Vec<&str>> {
        let c = self
            .header
            .iter()
            .position(|h| h == name)
            .with_context(|| format!("{} has no column {name}", self.path.display()))?;
        Ok(self.rows.iter().map(|r| r[c].as_str()).collect())
    }

    /// The column `name` as numbers.
    pub fn numbers(&self, name: &str) -> Result<Vec<f64>> {
        self.text(name)?
            .into_iter()
            .map(|v| {
                v.parse::<f64>()
                    .with_context(|| format!("{}: {name} = `{v}`", self.path.display()))
            })
            .collect()
    }

    /// Whether each step converged.
    pub fn converged(&self) -> Result<Vec<bool>> {
        Ok(self.text("converged")?.into_iter().map(|v| v == "true").collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_run_counts_as_finished_only_with_its_summary_and_the_keys_it_has_now() {
        let dir = std::env::temp_dir().join(format!("xtask-series-{}", std::process::id()));
        let keys: toml::Table = toml::from_str("n = 64\nlength = 1e-6\nlaw = \"surface\"").unwrap();
        let sweep = |keys: &toml::Table| Sweep {
            study: "s".into(),
            name: "a".into(),
            keys: keys.clone(),
        };
        let run = dir.join("s/runs/a");
        std::fs::create_dir_all(&run).unwrap();
        let mut written = keys.clone();
        written.insert("out".into(), "elsewhere/a".into());
        std::fs::write(run.join("run.toml"), toml::to_string(&written).unwrap()).unwrap();
        // Half done: no summary yet.
        assert_eq!(finished(&dir, &[sweep(&keys)]), vec![None]);
        std::fs::write(run.join("summary.json"), "{}").unwrap();
        assert_eq!(finished(&dir, &[sweep(&keys)]), vec![Some(run.clone())]);
        // A key changed since: the run no longer answers the sweep.
        let mut changed = keys.clone();
        changed.insert("n".into(), 128.into());
        assert_eq!(finished(&dir, &[sweep(&changed)]), vec![None]);
        std::fs::remove_dir_all(&dir).ok();
    }
}
