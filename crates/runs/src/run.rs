//! A run directory: everything `solve` and `sweep` write (the resolved case, the summary, the
//! fields, a sweep's curve and saved states) and what a resumed sweep reads back, in one place.
//!
//! Layout: `case.toml` (the resolved case), `summary.json`, the fields of the solution as
//! `.npy` (SI units, listed in the summary), and for a sweep `curve.csv` (a row a step),
//! `state/` (the last step's fields, to resume from) and with `--save-states`
//! `states/step-NNNN/` (every step's), and while a sweep runs inside a study `progress.txt`
//! (where its running step's solve stands, [`RunDir::write_progress`]). A saved state's
//! `manifest.json` holds its approach and a fingerprint of each field, so that a state mixed
//! from two steps is refused.
//!
//! One run at a time: a run holds an exclusive lock on `.lock` in its directory (released by
//! the system when the process ends, also when it is killed), and a directory that holds
//! another run's files is refused unless the run resumes it or overwrites it.

use anyhow::{Context, Result, bail};
use case::{Built, fingerprint};
use ndarray::Array2;
use serde::Serialize;
use serde_json::Value;
use solver::{AdhesiveState, Branch, ContactState, CyclePoint, SweepPoint};
use std::fs::{File, OpenOptions, TryLockError};
use std::io::Write;
use std::path::{Path, PathBuf};

/// Where the running step of the sweep in `dir` stands, if it has written so
/// ([`RunDir::write_progress`]).
pub fn read_progress(dir: &Path) -> Option<String> {
    std::fs::read_to_string(dir.join(PROGRESS)).ok()
}

/// The columns of `curve.csv`.
const HEADER: &str = "step,approach,load,mean_pressure,contact_area_fraction,attractive_area_fraction,\
attached_area_fraction,central_gap,branch,iterations,inner_iterations,converged,residual,wall_time_s,\
retries,plastic_area_fraction,permanent_set_volume,plastic_work,time,elastic_energy,viscous_work";

/// The files and directories a run writes: what makes a directory "another run's", and what
/// `--overwrite` removes (nothing else in the directory is touched).
const RUN_FILES: [&str; 24] = [
    "case.toml",
    "summary.json",
    "curve.csv",
    "load_approach.png",
    "pressure.png",
    "pressure.npy",
    "compressive_pressure.npy",
    "adhesive_pressure.npy",
    "gap.npy",
    "displacement.npy",
    "plastic.npy",
    "state",
    "state.new",
    "state.old",
    "states",
    "tangential.csv",
    "shear_x.npy",
    "shear_y.npy",
    "slip_x.npy",
    "slip_y.npy",
    crate::tangential::STATE,
    "tangential_state.new",
    "tangential_state.old",
    PROGRESS,
];

/// Where a sweep's running step stands, for a study's progress line.
const PROGRESS: &str = "progress.txt";

/// A run directory locked by another running process.
#[derive(Debug)]
pub struct Busy(pub PathBuf);

impl std::fmt::Display for Busy {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{} is in use by another running solve or sweep; wait for it to end or give another --out",
            self.0.display()
        )
    }
}

impl std::error::Error for Busy {}

/// Whether another running process holds the lock of the run directory `path`.
pub fn busy(path: &Path) -> bool {
    OpenOptions::new()
        .write(true)
        .open(path.join(".lock"))
        .is_ok_and(|f| matches!(f.try_lock(), Err(TryLockError::WouldBlock)))
}

/// How a run may use a directory that already holds another run.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Reuse {
    /// Refuse it.
    Refuse,
    /// Continue it (`--resume`): its files are kept. What it continues, which the directory
    /// must hold: a sweep (`curve.csv`) or a solve's tangential path.
    Resume(Continued),
    /// Remove its files first (`--overwrite`).
    Overwrite,
}

/// What `--resume` continues.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Continued {
    /// A sweep.
    Sweep,
    /// A solve's tangential path.
    TangentialPath,
}

impl Continued {
    /// Whether `dir` holds one to continue.
    fn held_by(self, dir: &Path) -> bool {
        match self {
            Continued::Sweep => dir.join("curve.csv").exists(),
            Continued::TangentialPath => saved(&dir.join(crate::tangential::STATE)).is_some(),
        }
    }

    fn name(self) -> &'static str {
        match self {
            Continued::Sweep => "sweep",
            Continued::TangentialPath => "tangential path",
        }
    }
}

/// A run's output directory, locked for the lifetime of the value.
pub struct RunDir {
    path: PathBuf,
    _lock: File,
}

impl RunDir {
    /// Creates `path` (and its parents) for a run's output and locks it; a directory locked by
    /// a running process, or holding another run's files (unless `reuse` says what to do with
    /// them), is refused.
    pub fn open(path: &Path, reuse: Reuse) -> Result<RunDir> {
        std::fs::create_dir_all(path).with_context(|| format!("creating {}", path.display()))?;
        let lock_path = path.join(".lock");
        let lock = OpenOptions::new()
            .create(true)
            .truncate(false)
            .write(true)
            .open(&lock_path)
            .with_context(|| format!("opening {}", lock_path.display()))?;
        match lock.try_lock() {
            Ok(()) => {}
            Err(TryLockError::WouldBlock) => return Err(Busy(path.to_path_buf()).into()),
            Err(TryLockError::Error(e)) => {
                return Err(e).with_context(|| format!("locking {}", lock_path.display()));
            }
        }
        let found: Vec<&str> = RUN_FILES.into_iter().filter(|f| path.join(f).exists()).collect();
        match reuse {
            _ if found.is_empty() => {}
            // Only a sweep or a tangential path is continued, each by its own command: another
            // run would be overwritten under its name.
            Reuse::Resume(what) if !what.held_by(path) => bail!(
                "--resume: {} holds no {} to continue ({}): give another --out, or --overwrite to \
                 replace what it holds",
                path.display(),
                what.name(),
                found.join(", ")
            ),
            Reuse::Resume(_) => {}
            Reuse::Refuse => bail!(
                "{} already holds a run ({}); give --overwrite to replace it (or, for a sweep, --resume \
                 to continue it), or another --out",
                path.display(),
                found.join(", ")
            ),
            Reuse::Overwrite => {
                for f in found {
                    let p = path.join(f);
                    let removed = if p.is_dir() {
                        std::fs::remove_dir_all(&p)
                    } else {
                        std::fs::remove_file(&p)
                    };
                    removed.with_context(|| format!("--overwrite: removing {}", p.display()))?;
                }
            }
        }
        Ok(RunDir {
            path: path.to_path_buf(),
            _lock: lock,
        })
    }

    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Writes `text` as where the running step's solve stands (its iteration and residual),
    /// which a study shows beside the run's finished steps ([`read_progress`]); `None` removes
    /// it. A progress line that cannot be written is left out: it is no result.
    pub fn write_progress(&self, text: Option<&str>) {
        let path = self.path.join(PROGRESS);
        let _ = match text {
            Some(text) => crate::output::text(&path, text),
            None => std::fs::remove_file(path).map_err(Into::into),
        };
    }

    /// Writes the resolved case (TOML) the run was made with.
    pub fn write_case(&self, resolved: &str) -> Result<()> {
        crate::output::text(
            &self.path.join("case.toml"),
            &format!("{}\n", resolved.trim_end()),
        )
    }

    /// The resolved case a previous run left here, if any.
    pub fn case(&self) -> Option<String> {
        std::fs::read_to_string(self.path.join("case.toml")).ok()
    }

    /// Writes `name.npy`.
    pub fn write_field(&self, name: &str, field: &Array2<f64>) -> Result<()> {
        crate::output::field(&self.path, name, field)
    }

    /// Writes the fields of an adhesive solution: the total, compressive and adhesive
    /// pressures, the gap and the displacement.
    pub fn write_adhesive_fields(&self, state: &AdhesiveState) -> Result<()> {
        self.write_field("pressure", &state.total_pressure())?;
        self.write_field("compressive_pressure", &state.contact.pressure)?;
        self.write_field("adhesive_pressure", &state.adhesive_pressure)?;
        self.write_field("gap", &state.contact.gap)?;
        self.write_field("displacement", &state.contact.displacement)?;
        self.write_plastic(&state.contact)
    }

    /// Writes the permanent set as `plastic.npy` \[m\], once the surface has a hardness.
    pub fn write_plastic(&self, state: &solver::ContactState) -> Result<()> {
        match &state.permanent_set {
            Some(set) => self.write_field("plastic", set),
            None => Ok(()),
        }
    }

    /// Writes `summary.json`: the version, the case, the surface's hash, the grid, and the
    /// fields of `results` (a JSON object).
    pub fn write_summary(&self, case: &impl Serialize, built: &Built, results: Value) -> Result<()> {
        let d = built.problem.domain();
        let mut summary = serde_json::json!({
            "version": env!("CARGO_PKG_VERSION"),
            "case": case,
            "surface_hash": built.surface_hash,
            "grid": { "nx": d.nx, "ny": d.ny, "dx": d.dx, "dy": d.dy, "periodic": d.periodic },
        });
        if let (Value::Object(all), Value::Object(results)) = (&mut summary, results) {
            all.extend(results);
        }
        crate::output::text(
            &self.path.join("summary.json"),
            &(serde_json::to_string_pretty(&summary)? + "\n"),
        )
    }

    /// Starts an empty `curve.csv` (its header only).
    pub fn start_curve(&self) -> Result<()> {
        crate::output::text(&self.curve_path(), &format!("{HEADER}\n"))
    }

    /// Keeps the first `rows` steps of `curve.csv`.
    pub fn truncate_curve(&self, rows: usize) -> Result<()> {
        let path = self.curve_path();
        let text = std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
        let kept: String = text.split_inclusive('\n').take(rows + 1).collect();
        crate::output::text(&path, &kept)
    }

    /// Whether a previous sweep left a curve here.
    pub fn has_curve(&self) -> bool {
        self.curve_path().exists()
    }

    /// The steps of `curve.csv`, as much as a summary and a plot need. A curve written before
    /// the plastic columns, the time column or the energy columns is rewritten with them
    /// (zeros, no time, energies unknown: NaN), so that the rows a resumed sweep appends match
    /// it.
    pub fn read_curve(&self) -> Result<Vec<CyclePoint>> {
        let path = self.curve_path();
        let text = std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
        let columns = text.lines().next().map_or(0, |h| h.split(',').count());
        // Curves written before the plastic columns, the time column or the energy columns.
        let missing = match HEADER.split(',').count().checked_sub(columns) {
            Some(6) => Some(",0,0e0,0e0,,,"),
            Some(3) => Some(",,,"),
            Some(2) => Some(",,"),
            _ => None,
        };
        if let Some(missing) = missing {
            let body: String = text.lines().skip(1).map(|l| format!("{l}{missing}\n")).collect();
            let upgraded = format!("{HEADER}\n{body}");
            let rows = parse_curve(&upgraded)?;
            crate::output::text(&path, &upgraded)?;
            return Ok(rows);
        }
        parse_curve(&text)
    }

    /// `curve.csv` opened to append rows.
    pub fn curve_writer(&self) -> Result<CurveWriter> {
        let path = self.curve_path();
        let file = OpenOptions::new()
            .append(true)
            .open(&path)
            .with_context(|| format!("opening {}", path.display()))?;
        Ok(CurveWriter(file))
    }

    fn curve_path(&self) -> PathBuf {
        self.path.join("curve.csv")
    }

    /// Saves step `k`'s state as the one to resume from (`state/`), and also as
    /// `states/step-NNNN/` when `keep`.
    pub fn save_state(&self, k: usize, state: &AdhesiveState, keep: bool) -> Result<()> {
        if keep {
            write_state(&self.step_dir(k), state)?;
        }
        write_state(&self.path.join("state"), state)
    }

    fn step_dir(&self, k: usize) -> PathBuf {
        self.path.join("states").join(format!("step-{k:04}"))
    }

    /// The state to resume from after `step` (its approach `approach` [m]): `state/` if it is
    /// that step's, else that step's own from `--save-states`. A sweep stopped between writing
    /// a step's state and its row of curve.csv (or a curve.csv cut by hand) would otherwise
    /// resume from a state the path has not reached yet.
    pub fn resume_state(&self, step: usize, approach: f64) -> Result<AdhesiveState> {
        let last = self.path.join("state");
        let state = read_state(&last)?;
        if state.contact.approach == approach {
            return Ok(state);
        }
        let kept = self.step_dir(step);
        if kept.join(MANIFEST).exists() {
            let state = read_state(&kept)?;
            if state.contact.approach == approach {
                return Ok(state);
            }
        }
        bail!(
            "--resume: the saved state in {} is at approach {:e} m, but curve.csv's last step ({step}) is at \
             {approach:e} m; rerun without --resume (with --save-states a sweep keeps every step's state)",
            last.display(),
            state.contact.approach
        )
    }
}

/// Appends the rows of `curve.csv`, each flushed as it is written (a killed sweep loses at
/// most the step it was solving).
pub struct CurveWriter(File);

impl CurveWriter {
    /// Appends step `k`'s row.
    pub fn append(&mut self, k: usize, p: &SweepPoint) -> Result<()> {
        let r = &p.report;
        let line = format!(
            "{},{:e},{:e},{:e},{},{},{},{:e},{},{},{},{},{:e},{:.3},{},{},{:e},{:e},{},{:e},{:e}\n",
            k,
            r.approach,
            r.load,
            r.mean_pressure,
            r.contact_area_fraction,
            r.attractive_area_fraction,
            r.attached_area_fraction,
            r.central_gap,
            p.branch.name(),
            r.iterations.count(),
            r.iterations.inner().map_or(String::new(), |i| i.to_string()),
            r.converged(),
            r.residual,
            r.wall_time_s,
            p.retries,
            r.yielding.plastic_area_fraction,
            r.yielding.permanent_set_volume,
            r.yielding.plastic_work,
            p.time.map_or(String::new(), |t| format!("{t:e}")),
            r.elastic_energy,
            r.viscous_work,
        );
        self.0.write_all(line.as_bytes())?;
        self.0.flush()?;
        Ok(())
    }
}

fn parse_curve(text: &str) -> Result<Vec<CyclePoint>> {
    let mut rows = Vec::new();
    for (k, line) in text.lines().skip(1).enumerate() {
        let f: Vec<&str> = line.split(',').collect();
        if f.len() != HEADER.split(',').count() {
            bail!("curve.csv line {} is incomplete: {line}", k + 2);
        }
        let num = |i: usize| -> Result<f64> {
            f[i].parse::<f64>()
                .with_context(|| format!("curve.csv line {}: bad number {}", k + 2, f[i]))
        };
        rows.push(CyclePoint {
            approach: num(1)?,
            load: num(2)?,
            contact_area_fraction: num(4)?,
            attached_area_fraction: num(6)?,
            branch: if f[8] == "unloading" {
                Branch::Unloading
            } else {
                Branch::Loading
            },
            converged: f[11] == "true",
            plastic_work: num(17)?,
            time: if f[18].is_empty() { None } else { Some(num(18)?) },
            elastic_energy: if f[19].is_empty() { f64::NAN } else { num(19)? },
            viscous_work: if f[20].is_empty() { f64::NAN } else { num(20)? },
        });
    }
    Ok(rows)
}

/// Writes a state into `dir` whole or not at all ([`write_fields`]).
fn write_state(dir: &Path, state: &AdhesiveState) -> Result<()> {
    let mut manifest = serde_json::json!({ "approach": state.contact.approach });
    if let Some(h) = &state.contact.history {
        manifest["time"] = h.time.into();
    }
    write_fields(dir, &state_fields(state), manifest)
}

/// Writes `fields` (`name.npy`) and `manifest` with a fingerprint of each field added, into
/// `dir` whole or not at all: into a sibling `<name>.new` first (its manifest last), then
/// swapped in by renames, so that a run killed at any moment leaves either the old set or the
/// new one (or, between the two renames, only `<name>.new`, which [`saved`] and
/// [`read_state`] take).
pub fn write_fields(dir: &Path, fields: &[(String, &Array2<f64>)], mut manifest: Value) -> Result<()> {
    let sibling = |ext: &str| {
        let mut name = dir.file_name().unwrap_or_default().to_os_string();
        name.push(ext);
        dir.with_file_name(name)
    };
    let (new, old) = (sibling(".new"), sibling(".old"));
    for d in [&new, &old] {
        if d.exists() {
            std::fs::remove_dir_all(d).with_context(|| format!("removing {}", d.display()))?;
        }
    }
    std::fs::create_dir_all(&new).with_context(|| format!("creating {}", new.display()))?;
    let mut prints = serde_json::Map::new();
    for (name, field) in fields {
        crate::output::field(&new, name, field)?;
        prints.insert(name.clone(), Value::String(fingerprint(field)));
    }
    manifest["fields"] = Value::Object(prints);
    crate::output::text(
        &new.join(MANIFEST),
        &(serde_json::to_string_pretty(&manifest)? + "\n"),
    )?;
    let rename = |from: &Path, to: &Path| {
        std::fs::rename(from, to).with_context(|| format!("renaming {} to {}", from.display(), to.display()))
    };
    if dir.exists() {
        rename(dir, &old)?;
    }
    rename(&new, dir)?;
    if old.exists() {
        std::fs::remove_dir_all(&old).with_context(|| format!("removing {}", old.display()))?;
    }
    Ok(())
}

/// A saved state's manifest: its approach [m] and a fingerprint of each field.
const MANIFEST: &str = "manifest.json";

/// The fields a saved state holds, by file name: the permanent set (`plastic`) once the
/// surface has a hardness, a viscoelastic body's branch stresses (`branch_stress_K` \[Pa\],
/// its time in the manifest).
fn state_fields(state: &AdhesiveState) -> Vec<(String, &Array2<f64>)> {
    let mut fields = vec![
        ("compressive_pressure".to_string(), &state.contact.pressure),
        ("adhesive_pressure".to_string(), &state.adhesive_pressure),
        ("gap".to_string(), &state.contact.gap),
        ("displacement".to_string(), &state.contact.displacement),
    ];
    fields.extend(
        state
            .contact
            .permanent_set
            .as_ref()
            .map(|s| ("plastic".to_string(), s)),
    );
    if let Some(h) = &state.contact.history {
        fields.extend(
            h.branches
                .iter()
                .enumerate()
                .map(|(k, b)| (format!("branch_stress_{k}"), b)),
        );
    }
    fields
}

/// A state saved by a sweep (`state/` or `states/step-NNNN/`, or the sweep's directory for
/// its `state/`): for `--start-from` and `--resume`. Its fields must be the ones its manifest
/// fingerprints: a state torn between two steps is refused.
pub fn read_state(dir: &Path) -> Result<AdhesiveState> {
    let has = |d: &Path| d.join(MANIFEST).exists();
    let dir = [dir.to_path_buf(), dir.join("state"), dir.join("state.new")]
        .into_iter()
        .chain(dir.file_name().map(|n| {
            let mut n = n.to_os_string();
            n.push(".new");
            dir.with_file_name(n)
        }))
        .find(|d| has(d))
        .with_context(|| {
            if dir.exists() {
                format!(
                    "{} holds no saved state: give a sweep's directory, its state/ or one of its \
                     states/step-NNNN (with --save-states)",
                    dir.display()
                )
            } else {
                format!(
                    "{} does not exist: give a sweep's directory or one of its saved states",
                    dir.display()
                )
            }
        })?;
    let saved = read_fields(&dir)?;
    let (manifest, read) = (&saved.manifest, |name: &str| saved.read(name));
    let manifest_path = dir.join(MANIFEST);
    let approach = manifest["approach"]
        .as_f64()
        .with_context(|| format!("{}: no approach", manifest_path.display()))?;
    let state = AdhesiveState {
        contact: ContactState {
            pressure: read("compressive_pressure")?,
            gap: read("gap")?,
            displacement: read("displacement")?,
            approach,
            permanent_set: match manifest["fields"].get("plastic") {
                Some(_) => Some(read("plastic")?),
                None => None,
            },
            history: match manifest["time"].as_f64() {
                Some(time) => {
                    if manifest["fields"].get("branch_0").is_some() {
                        bail!(
                            "{}: saved by an earlier version, which kept the branches' \
                             displacements; this one keeps their stresses: rerun the sweep",
                            manifest_path.display()
                        );
                    }
                    let count = (0..)
                        .take_while(|k| manifest["fields"].get(format!("branch_stress_{k}")).is_some())
                        .count();
                    let branches = (0..count)
                        .map(|k| read(&format!("branch_stress_{k}")))
                        .collect::<Result<_>>()?;
                    Some(solver::History { time, branches })
                }
                None => None,
            },
        },
        adhesive_pressure: read("adhesive_pressure")?,
    };
    let shape = state.contact.gap.dim();
    if state_fields(&state).iter().any(|(_, f)| f.dim() != shape) {
        bail!("{}: the fields' shapes differ", dir.display());
    }
    Ok(state)
}

/// The fields [`write_fields`] wrote into a directory, and their manifest.
pub struct SavedFields<'a> {
    /// The manifest, with each field's fingerprint under `fields`.
    pub manifest: Value,
    dir: &'a Path,
}

impl SavedFields<'_> {
    /// Field `name`, refused unless its manifest fingerprints it (a set torn between two
    /// writes).
    pub fn read(&self, name: &str) -> Result<Array2<f64>> {
        let path = self.dir.join(format!("{name}.npy"));
        let field: Array2<f64> =
            ndarray_npy::read_npy(&path).with_context(|| format!("reading {}", path.display()))?;
        if self.manifest["fields"][name].as_str() != Some(fingerprint(&field).as_str()) {
            bail!(
                "{} is not the field its manifest ({}) names: the state is torn (parts of two steps); \
                 start from another one",
                path.display(),
                self.dir.join(MANIFEST).display()
            );
        }
        Ok(field)
    }
}

/// Where [`write_fields`] left a whole set for `dir`: `dir`, or `<name>.new` when killed
/// between its renames; `None` if neither holds one.
pub fn saved(dir: &Path) -> Option<PathBuf> {
    let mut new = dir.file_name()?.to_os_string();
    new.push(".new");
    [dir.to_path_buf(), dir.with_file_name(new)]
        .into_iter()
        .find(|d| d.join(MANIFEST).exists())
}

/// The fields [`write_fields`] wrote into `dir`.
pub fn read_fields(dir: &Path) -> Result<SavedFields<'_>> {
    let manifest_path = dir.join(MANIFEST);
    let manifest: Value = serde_json::from_str(
        &std::fs::read_to_string(&manifest_path)
            .with_context(|| format!("reading {}", manifest_path.display()))?,
    )
    .with_context(|| format!("{}: not a state manifest", manifest_path.display()))?;
    Ok(SavedFields { manifest, dir })
}

/// `extra` (a JSON object) with the fields of `report` added: the summary's results.
pub fn results(extra: Value, report: &impl Serialize) -> Result<Value> {
    let (Value::Object(mut all), Value::Object(fields)) = (extra, serde_json::to_value(report)?) else {
        bail!("a summary's results are JSON objects");
    };
    all.extend(fields);
    Ok(Value::Object(all))
}

/// Runs `f` on the worker threads, so that the solvers' parallel passes do not each pay a
/// hand-off from the main thread (which dominates on small grids).
pub fn on_workers<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    rayon::scope(|_| f())
}
