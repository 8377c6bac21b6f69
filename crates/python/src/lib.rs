//! `roughcontact._native`: the engine behind the Python package `roughcontact`. The public
//! API, its docstrings and its argument checking live in `python/roughcontact`; this module
//! only translates numpy arrays and keyword dictionaries into the library's objects (through
//! the `case` crate, as the command line does) and runs them with the GIL released.

use anyhow::Context as _;
use case::{Case, Generation, SolveControl, SweepPath};
use ndarray::Array2;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray2};
use pyo3::exceptions::{PyFileNotFoundError, PyOSError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};
use solver::{AdhesiveState, ContactProblem, Observer, Start, SweepPoint, Termination};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use surfgen::io::{self, ReadOptions, Surface};
use surfgen::{Grid, Metadata};

/// An error of the library as a Python exception: a missing file as `FileNotFoundError`,
/// another failure to read or write as `OSError`, everything else (bad input) as `ValueError`;
/// the message is the library's, causes joined by colons.
fn py_error(e: anyhow::Error) -> PyErr {
    // The causes joined by colons, each once (a reader's error already quotes its cause).
    let mut message = String::new();
    for cause in e.chain() {
        let text = cause.to_string();
        if !message.contains(&text) {
            if !message.is_empty() {
                message.push_str(": ");
            }
            message.push_str(&text);
        }
    }
    // One line of plain words: serde's and toml's messages end in a line break or span
    // several with a source excerpt.
    let message = keywords(message.trim());
    for cause in e.chain() {
        let io = cause.downcast_ref::<std::io::Error>().or_else(|| {
            match cause.downcast_ref::<surfgen::SurfError>() {
                Some(surfgen::SurfError::Io { source, .. }) => Some(source),
                _ => None,
            }
        });
        if let Some(io) = io {
            return match io.kind() {
                std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(message),
                _ => PyOSError::new_err(message),
            };
        }
    }
    PyValueError::new_err(message)
}

/// The library's messages name the command line's flags; here they name the keywords
/// (`--mean-pressure` becomes `mean_pressure`).
fn keywords(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(i) = rest.find("--") {
        out.push_str(&rest[..i]);
        let after = &rest[i + 2..];
        let end = after
            .find(|c: char| !(c.is_ascii_alphanumeric() || c == '-'))
            .unwrap_or(after.len());
        if end > 0 && after.starts_with(|c: char| c.is_ascii_lowercase()) {
            out.push_str(&after[..end].replace('-', "_"));
        } else {
            out.push_str("--");
            out.push_str(&after[..end]);
        }
        rest = &after[end..];
    }
    out.push_str(rest);
    out
}

/// A TOML case file's keys as JSON, for `roughcontact.from_toml`.
#[pyfunction]
fn read_toml(path: PathBuf) -> PyResult<String> {
    let text = std::fs::read_to_string(&path)
        .with_context(|| format!("reading {}", path.display()))
        .py()?;
    let table: toml::Table = toml::from_str(&text)
        .with_context(|| format!("parsing {}", path.display()))
        .py()?;
    serde_json::to_string(&table).py()
}

trait OrPy<T> {
    fn py(self) -> PyResult<T>;
}

impl<T, E: Into<anyhow::Error>> OrPy<T> for Result<T, E> {
    fn py(self) -> PyResult<T> {
        self.map_err(|e| py_error(e.into()))
    }
}

/// A Python value as a TOML value of a case key: bool, int, float, str (paths as str) and
/// lists of them.
fn toml_value(key: &str, v: &Bound<'_, PyAny>) -> PyResult<toml::Value> {
    if v.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(v.extract()?));
    }
    if v.is_instance_of::<PyInt>() {
        return Ok(toml::Value::Integer(v.extract().map_err(|_| {
            PyValueError::new_err(format!("`{key}`: the integer is out of range"))
        })?));
    }
    if v.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(v.extract()?));
    }
    if v.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(v.extract()?));
    }
    if v.is_instance_of::<PyList>() || v.is_instance_of::<PyTuple>() {
        let items: Vec<Bound<'_, PyAny>> = v.extract()?;
        return items
            .iter()
            .map(|item| toml_value(key, item))
            .collect::<PyResult<Vec<_>>>()
            .map(toml::Value::Array);
    }
    Err(PyValueError::new_err(format!(
        "`{key}`: a {} is not a value a case key takes (numbers, strings, paths, booleans, lists)",
        v.get_type().name()?
    )))
}

/// A keyword dictionary (values already plain Python: the package converts numpy scalars,
/// arrays and paths) as a TOML table; `None` values are left out (not given).
fn table(keys: &Bound<'_, PyDict>) -> PyResult<toml::Table> {
    let mut table = toml::Table::new();
    for (k, v) in keys.iter() {
        let k: String = k.extract()?;
        if !v.is_none() {
            let value = toml_value(&k, &v)?;
            table.insert(k, value);
        }
    }
    Ok(table)
}

/// A surface from a numpy array (any layout: read through its strides) and its sides [m].
fn surface(
    heights: PyReadonlyArray2<'_, f64>,
    length_x: f64,
    length_y: f64,
    periodic: bool,
) -> PyResult<Surface> {
    let h = heights.as_array().to_owned();
    let (ny, nx) = h.dim();
    let grid = Grid::new(nx, ny, length_x, length_y).py()?;
    Surface::new(h, grid, periodic).py()
}

/// A result's named fields, for a dict on the Python side.
type Fields<'py> = Vec<(String, Bound<'py, PyArray2<f64>>)>;

fn array<'py>(py: Python<'py>, a: Array2<f64>) -> Bound<'py, PyArray2<f64>> {
    a.into_pyarray(py)
}

/// Cancels a running solve from another thread (the package's Ctrl-C).
#[pyclass(frozen)]
struct Cancel(Arc<AtomicBool>);

#[pymethods]
impl Cancel {
    #[new]
    fn new() -> Self {
        Cancel(Arc::new(AtomicBool::new(false)))
    }

    /// Asks the solve to stop where it stands.
    fn set(&self) {
        self.0.store(true, Ordering::SeqCst);
    }
}

/// Hands the solver's progress to a Python callable and its stop to [`Cancel`]; an exception
/// raised by the callable stops the solve and is raised again when it returns.
struct Progress {
    callback: Option<Py<PyAny>>,
    cancel: Arc<AtomicBool>,
    error: Option<PyErr>,
}

impl Progress {
    fn new(callback: Option<Py<PyAny>>, cancel: &Cancel) -> Self {
        Progress {
            callback,
            cancel: cancel.0.clone(),
            error: None,
        }
    }

    fn call(&mut self, make: impl FnOnce(Python<'_>) -> PyResult<Bound<'_, PyDict>>) {
        let Some(callback) = &self.callback else {
            return;
        };
        if self.error.is_some() {
            return;
        }
        let result = Python::attach(|py| -> PyResult<()> {
            callback.call1(py, (make(py)?,))?;
            Ok(())
        });
        if let Err(e) = result {
            self.error = Some(e);
            self.cancel.store(true, Ordering::SeqCst);
        }
    }

    /// The solve's outcome, or the callable's exception.
    fn finish<T>(self, outcome: anyhow::Result<T>) -> PyResult<T> {
        match self.error {
            Some(e) => Err(e),
            None => outcome.py(),
        }
    }
}

impl Observer for Progress {
    fn iteration(&mut self, step: usize, iteration: usize, residual: f64) {
        self.call(|py| {
            let d = PyDict::new(py);
            d.set_item("step", step)?;
            d.set_item("iteration", iteration)?;
            d.set_item("residual", residual)?;
            Ok(d)
        });
    }

    fn interrupted(&mut self) -> bool {
        self.cancel.load(Ordering::SeqCst)
    }

    fn step(&mut self, index: usize, point: &SweepPoint, _state: &AdhesiveState) -> bool {
        self.call(|py| {
            let d = PyDict::new(py);
            d.set_item("step", index)?;
            d.set_item("done", true)?;
            d.set_item("approach", point.report.approach)?;
            d.set_item("load", point.report.load)?;
            d.set_item("converged", point.report.converged())?;
            Ok(d)
        });
        !self.cancel.load(Ordering::SeqCst)
    }
}

/// Runs `f` on `threads` threads of a pool of its own (`None`: the shared pool, on its worker
/// threads as the command line does).
fn on_pool<R: Send>(threads: Option<usize>, f: impl FnOnce() -> R + Send) -> anyhow::Result<R> {
    Ok(match threads {
        Some(n) => {
            case::memory::check_threads("threads", n)?;
            rayon::ThreadPoolBuilder::new().num_threads(n).build()?.install(f)
        }
        None => rayon::scope(|_| f()),
    })
}

/// A case from its keys (and the roughness given as an array instead of a `surface` file):
/// the filled-in case, the problem and the case's second struct.
fn built<B>(
    name: &str,
    keys: &Bound<'_, PyDict>,
    roughness: Option<(PyReadonlyArray2<'_, f64>, f64, f64)>,
) -> PyResult<(Case, B, case::Built)>
where
    B: Default + serde::Serialize + serde::de::DeserializeOwned,
{
    let (mut case, second): (Case, B) = case::from_table(name, table(keys)?).py()?;
    if case.out.is_some() {
        return Err(PyValueError::new_err(
            "`out` is the command line's output directory; the Python package returns its results",
        ));
    }
    let roughness = roughness
        .map(|(h, lx, ly)| surface(h, lx, ly, true))
        .transpose()?;
    case.fill_defaults("");
    case.out = None;
    let built = case.build_on(roughness).py()?;
    Ok((case, second, built))
}

/// Solves one contact. Returns the summary as JSON and the fields.
#[pyfunction]
#[pyo3(signature = (keys, roughness, threads, progress, cancel))]
fn solve<'py>(
    py: Python<'py>,
    keys: &Bound<'py, PyDict>,
    roughness: Option<(PyReadonlyArray2<'py, f64>, f64, f64)>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    cancel: &Cancel,
) -> PyResult<(String, Fields<'py>)> {
    let (case, control, built): (Case, SolveControl, _) = built("the keywords", keys, roughness)?;
    let problem = &built.problem;
    let tangential = control.tangential_path(case.frictional()).py()?;
    if tangential.is_some() {
        problem.check_tangential().py()?;
    }
    let control = control.control(problem).py()?;
    case.validate_settings(problem.adhesive()).py()?;
    if !problem.adhesive() {
        control.validate_without_adhesion().py()?;
    }
    let mut observer = Progress::new(progress, cancel);
    let cancel_flag = cancel.0.clone();
    let adhesive = problem.adhesive();
    let outcome = py.detach(|| {
        on_pool(threads, || -> anyhow::Result<_> {
            Ok(if adhesive {
                let settings = case.settings();
                let (state, report) = problem.solve(control, &settings, Start::Loading, &mut observer)?;
                let edge = problem.edge_warning(&state.contact.gap, &state.contact.pressure);
                let head = (report.converged(), report.termination);
                let mut summary = summary(problem, head, &report, edge)?;
                let sheared = shear(
                    problem,
                    || solver::Normal::adhesive(state.clone(), control, &settings),
                    tangential.as_deref(),
                    &mut summary,
                    &cancel_flag,
                )?;
                let mut fields = adhesive_fields(state);
                fields.extend(sheared);
                (summary, fields)
            } else {
                let options = case.contact_options();
                let (state, report) =
                    problem.solve_without_adhesion(control, &options, None, &mut observer)?;
                let edge = problem.edge_warning(&state.gap, &state.pressure);
                let head = (report.converged(), report.termination);
                let mut summary = summary(problem, head, &report, edge)?;
                let sheared = shear(
                    problem,
                    || solver::Normal::without_adhesion(state.clone(), control, &options),
                    tangential.as_deref(),
                    &mut summary,
                    &cancel_flag,
                )?;
                let mut fields = vec![
                    ("pressure", state.pressure),
                    ("gap", state.gap),
                    ("displacement", state.displacement),
                ];
                fields.extend(state.permanent_set.map(|s| ("plastic", s)));
                fields.extend(sheared);
                (summary, fields)
            })
        })
        .and_then(|r| r)
    });
    let (mut summary, fields) = observer.finish(outcome)?;
    summary["case"] = serde_json::to_value(&case).py()?;
    summary["surface_hash"] = serde_json::to_value(&built.surface_hash).py()?;
    let fields = fields
        .into_iter()
        .map(|(name, a)| (name.to_string(), array(py, a)))
        .collect();
    Ok((summary.to_string(), fields))
}

/// Runs the tangential path, if any, on the normal solution `normal` makes: adds the summary's
/// `tangential` (the path's summary and its steps' reports) and returns the last step's shear
/// and slip.
fn shear<'a>(
    problem: &ContactProblem,
    normal: impl FnOnce() -> solver::Normal<'a>,
    controls: Option<&[solver::TangentialControl]>,
    summary: &mut serde_json::Value,
    cancel: &AtomicBool,
) -> anyhow::Result<Vec<(&'static str, Array2<f64>)>> {
    let Some(controls) = controls else {
        return Ok(Vec::new());
    };
    let solver::TangentialPath {
        shear: state,
        reports,
        ..
    } = problem.tangential_path(
        normal(),
        None,
        controls,
        &solver::ShearOptions::default(),
        &mut |_, _, _, _| !cancel.load(Ordering::SeqCst),
    )?;
    let mut value = serde_json::to_value(solver::TangentialSummary::of(&reports))?;
    value["steps"] = serde_json::to_value(&reports)?;
    summary["tangential"] = value;
    let [shear_x, shear_y] = state.traction;
    let [slip_x, slip_y] = state.slip;
    Ok(vec![
        ("shear_x", shear_x),
        ("shear_y", shear_y),
        ("slip_x", slip_x),
        ("slip_y", slip_y),
    ])
}

/// A solve's summary: the law, whether and how it ended, the report, and the problem's
/// warnings with the edge warning of the state reached.
fn summary(
    problem: &ContactProblem,
    (converged, termination): (bool, Termination),
    report: &impl serde::Serialize,
    edge: Option<String>,
) -> anyhow::Result<serde_json::Value> {
    let warnings: Vec<String> = problem.warnings.iter().cloned().chain(edge).collect();
    Ok(serde_json::json!({
        "law": problem.law.name(),
        "converged": converged,
        "termination": termination.to_string(),
        "report": serde_json::to_value(report)?,
        "warnings": warnings,
    }))
}

/// An adhesive state's fields, named as the command line's files.
fn adhesive_fields(state: AdhesiveState) -> Vec<(&'static str, Array2<f64>)> {
    let mut fields = vec![
        ("pressure", state.total_pressure()),
        ("compressive_pressure", state.contact.pressure),
        ("adhesive_pressure", state.adhesive_pressure),
        ("gap", state.contact.gap),
        ("displacement", state.contact.displacement),
    ];
    fields.extend(state.contact.permanent_set.map(|s| ("plastic", s)));
    fields
}

/// Follows a sweep's path. Returns the summary and the steps as JSON, and the last state's
/// fields.
#[pyfunction]
#[pyo3(signature = (keys, roughness, threads, progress, cancel))]
fn sweep<'py>(
    py: Python<'py>,
    keys: &Bound<'py, PyDict>,
    roughness: Option<(PyReadonlyArray2<'py, f64>, f64, f64)>,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
    cancel: &Cancel,
) -> PyResult<(String, Fields<'py>)> {
    let (case, mut path, built): (Case, SweepPath, _) = built("the keywords", keys, roughness)?;
    case.refuse_friction().py()?;
    if path.start_from.is_some() {
        return Err(PyValueError::new_err(
            "`start_from` reads a command-line run directory; give the path from apart instead",
        ));
    }
    if path.keep_steps.is_some() {
        return Err(PyValueError::new_err(
            "`keep_steps` keeps step directories of a command-line run; here the last state's \
             fields come back, and `progress` sees every step",
        ));
    }
    path.fill_defaults();
    let search = path.pull_off().py()?;
    let problem = &built.problem;
    let controls = path.controls().py()?;
    let max_step = path.max_step(problem, &controls).py()?;
    let times = path.times(problem, controls.len()).py()?;
    case.validate_settings(problem.adhesive()).py()?;
    let settings = case.settings();
    let mut observer = Progress::new(progress, cancel);
    /// Keeps the last state of the sweep for the caller, and numbers the steps on through the
    /// pull-off search.
    struct Last<'a> {
        inner: &'a mut Progress,
        state: Option<AdhesiveState>,
        done: usize,
    }
    impl Observer for Last<'_> {
        fn iteration(&mut self, step: usize, iteration: usize, residual: f64) {
            self.inner.iteration(step, iteration, residual);
        }
        fn interrupted(&mut self) -> bool {
            self.inner.interrupted()
        }
        fn step(&mut self, _: usize, point: &SweepPoint, state: &AdhesiveState) -> bool {
            self.state = Some(state.clone());
            self.done += 1;
            self.inner.step(self.done - 1, point, state)
        }
    }
    let mut last = Last {
        inner: &mut observer,
        state: None,
        done: 0,
    };
    let outcome = py.detach(|| {
        on_pool(threads, || {
            let mut points = problem
                .sweep(
                    solver::Path {
                        controls: &controls,
                        times: times.as_deref(),
                    },
                    max_step,
                    &settings,
                    None,
                    &mut last,
                )
                .context("sweeping")?;
            // The pull-off search from the path's last state, when asked for and reached.
            if let (Some(search), Some(from)) = (&search, last.state.clone())
                && points.len() == controls.len()
                && !last.inner.interrupted()
            {
                let pull = problem
                    .pull_off(search, &settings, from, &mut last)
                    .context("searching for the pull-off")?;
                points.extend(pull.coarse);
                points.extend(pull.refined);
            }
            Ok(points)
        })
        .and_then(|r| r)
    });
    let state = last.state.take();
    let points = observer.finish(outcome)?;
    let cycle: Vec<solver::CyclePoint> = points.iter().map(solver::CyclePoint::from).collect();
    let method = problem.adhesive().then(|| {
        settings
            .method
            .resolve(
                problem.law.as_ref(),
                controls[0],
                &problem.domain(),
                problem.operator.cell_compliance(),
                &problem.interface,
            )
            .name()
    });
    let summary = serde_json::json!({
        "law": problem.law.name(),
        "method": method,
        "max_step": max_step,
        "cycle": solver::summarize(&cycle),
        "steps": points,
        "converged": points.iter().map(|p| p.report.converged()).collect::<Vec<_>>(),
        "termination": points.iter().map(|p| p.report.termination.to_string()).collect::<Vec<_>>(),
        "iterations": points.iter().map(|p| p.report.iterations.count()).collect::<Vec<_>>(),
        "warnings": problem.warnings,
        "case": case,
        "path": path,
        "surface_hash": built.surface_hash,
    });
    let fields = state
        .map(adhesive_fields)
        .unwrap_or_default()
        .into_iter()
        .map(|(name, a)| (name.to_string(), array(py, a)))
        .collect();
    Ok((summary.to_string(), fields))
}

/// The second struct of a case that has only one.
#[derive(Default, serde::Serialize, serde::Deserialize)]
#[serde(deny_unknown_fields)]
struct NoKeys {}

/// Generates a surface from its keys: heights [m] (ny, nx), sides [m], the specification and
/// the generator's warnings as JSON.
#[pyfunction]
fn generate<'py>(
    py: Python<'py>,
    keys: &Bound<'py, PyDict>,
) -> PyResult<(Bound<'py, PyArray2<f64>>, f64, f64, String)> {
    let (generation, NoKeys {}): (Generation, _) = case::from_table("the keywords", table(keys)?).py()?;
    let (spec, generated) = py.detach(|| generation.generate()).py()?;
    let info = serde_json::json!({
        "spec": spec,
        "prefactor": generated.prefactor,
        "warnings": generated.warnings,
    });
    Ok((
        array(py, generated.heights),
        spec.grid.length_x,
        spec.grid.length_y,
        info.to_string(),
    ))
}

/// The reading options of the keywords, the channel resolved to its index.
#[allow(clippy::too_many_arguments)]
fn read_options(
    path: &Path,
    length: Option<f64>,
    length_y: Option<f64>,
    unit: f64,
    periodic: bool,
    channel: Option<String>,
    fill_unmeasured: bool,
    max_unmeasured: Option<f64>,
) -> PyResult<ReadOptions> {
    let options = ReadOptions {
        length_x: length,
        length_y,
        unit,
        periodic,
        channel: None,
        unmeasured: io::Unmeasured::filled_up_to(fill_unmeasured, max_unmeasured).py()?,
    };
    options
        .with_channel(path, channel.as_deref())
        .map_err(|e| case::naming("reading", path, e))
        .py()
}

/// A surface read for Python: heights [m] (ny, nx), sides [m], whether it is periodic, and a
/// note of the points filled, if any.
type ReadSurface<'py> = (Bound<'py, PyArray2<f64>>, f64, f64, bool, Option<String>);

/// Reads a surface file: heights [m] (ny, nx), sides [m], whether it is periodic, and a note
/// of the points filled, if any.
#[pyfunction]
#[pyo3(signature = (path, length, length_y, unit, periodic, channel, fill_unmeasured, max_unmeasured))]
#[allow(clippy::too_many_arguments)]
fn read(
    py: Python<'_>,
    path: PathBuf,
    length: Option<f64>,
    length_y: Option<f64>,
    unit: f64,
    periodic: bool,
    channel: Option<String>,
    fill_unmeasured: bool,
    max_unmeasured: Option<f64>,
) -> PyResult<ReadSurface<'_>> {
    let options = read_options(
        &path,
        length,
        length_y,
        unit,
        periodic,
        channel,
        fill_unmeasured,
        max_unmeasured,
    )?;
    let (s, note) = py
        .detach(|| io::read_noting(&path, &options).map_err(|e| case::naming("reading", &path, e)))
        .py()?;
    Ok((
        array(py, s.heights),
        s.grid.length_x,
        s.grid.length_y,
        s.periodic,
        note,
    ))
}

/// A file's channels as JSON: name, points, sizes [m], unit, whether they are heights.
#[pyfunction]
#[pyo3(signature = (path, length, length_y, unit))]
fn channels(path: PathBuf, length: Option<f64>, length_y: Option<f64>, unit: f64) -> PyResult<String> {
    let options = read_options(&path, length, length_y, unit, true, None, false, None)?;
    let channels = io::channels(&path, &options)
        .map_err(|e| case::naming("reading", &path, e))
        .py()?;
    Ok(serde_json::to_string(&channels).expect("channels serialise"))
}

/// Writes a surface file in the format of the path's extension (`.npy` with its sidecar).
#[pyfunction]
fn write(
    py: Python<'_>,
    path: PathBuf,
    heights: PyReadonlyArray2<'_, f64>,
    length_x: f64,
    length_y: f64,
    periodic: bool,
) -> PyResult<()> {
    let s = surface(heights, length_x, length_y, periodic)?;
    py.detach(|| -> anyhow::Result<()> {
        io::write(&s, &path, None).map_err(|e| case::naming("writing", &path, e))?;
        if path.extension().is_some_and(|e| e == "npy") {
            io::write_metadata(&path, &Metadata::of(&s))?;
        }
        Ok(())
    })
    .py()
}

/// The surface's statistics as JSON (`roughcontact stats --json`).
#[pyfunction]
fn statistics(
    py: Python<'_>,
    heights: PyReadonlyArray2<'_, f64>,
    length_x: f64,
    length_y: f64,
    periodic: bool,
) -> PyResult<String> {
    let s = surface(heights, length_x, length_y, periodic)?;
    let statistics = py.detach(|| surfgen::statistics(s.heights.view(), &s.grid, s.periodic, None));
    serde_json::to_string(&statistics).py()
}

/// The radially averaged PSD as JSON (q [rad/m], psd [m^4], std_err, count).
#[pyfunction]
fn psd(
    py: Python<'_>,
    heights: PyReadonlyArray2<'_, f64>,
    length_x: f64,
    length_y: f64,
    bins_per_decade: usize,
) -> PyResult<String> {
    if bins_per_decade == 0 {
        return Err(PyValueError::new_err("bins_per_decade must be at least 1"));
    }
    let s = surface(heights, length_x, length_y, true)?;
    let radial = py.detach(|| surfgen::Analysis::new(s.heights.view(), &s.grid, bins_per_decade).radial_psd);
    serde_json::to_string(&radial).py()
}

mod reference;

#[pymodule]
fn _native(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<Cancel>()?;
    m.add_function(wrap_pyfunction!(solve, m)?)?;
    m.add_function(wrap_pyfunction!(sweep, m)?)?;
    m.add_function(wrap_pyfunction!(generate, m)?)?;
    m.add_function(wrap_pyfunction!(read, m)?)?;
    m.add_function(wrap_pyfunction!(channels, m)?)?;
    m.add_function(wrap_pyfunction!(write, m)?)?;
    m.add_function(wrap_pyfunction!(statistics, m)?)?;
    m.add_function(wrap_pyfunction!(psd, m)?)?;
    m.add_function(wrap_pyfunction!(read_toml, m)?)?;
    reference::register(m)?;
    m.add("VERSION", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}
