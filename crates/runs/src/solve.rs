//! `solve`: one normal contact, with or without adhesion, from flags or a TOML case file.

use crate::run::{Reuse, RunDir, on_workers, results};
use crate::{note, say};
use anyhow::{Context, Result, bail};
use case::{Built, Case, SolveControl, beside, layered, to_toml};
use clap::Args;
use elastic::Domain;
use indicatif::{ProgressBar, ProgressStyle};
use ndarray::Array2;
use serde_json::json;
use solver::{Control, Observer, Start};
use std::path::{Path, PathBuf};
use std::time::Instant;

#[derive(Args, Debug)]
pub struct SolveArgs {
    #[command(flatten)]
    case: Case,
    #[command(flatten)]
    control: SolveControl,
    /// TOML case file; its keys are the flags' names in snake_case.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Print the resolved case as TOML and exit without solving.
    #[arg(long)]
    print_config: bool,
    /// Exit with status 0 even when the solve does not converge (the outputs say so).
    #[arg(long)]
    keep_going: bool,
    /// Replace the run already in --out (its case, summary, fields and plot; nothing else in
    /// the directory is touched).
    #[arg(long, conflicts_with = "resume")]
    overwrite: bool,
    /// Continue an interrupted tangential path in --out: the normal solve is run again, the
    /// finished tangential steps are kept, not redone.
    #[arg(long)]
    resume: bool,
    /// Do not draw the pressure map.
    #[arg(long)]
    no_png: bool,
}

pub fn solve(args: SolveArgs) -> Result<()> {
    let text = match &args.config {
        Some(path) => {
            Some(std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?)
        }
        None => None,
    };
    let name = args
        .config
        .as_ref()
        .map(|p| p.display().to_string())
        .unwrap_or_default();
    let (mut case, control) = layered(
        text.as_deref().map(|t| (name.as_str(), t)),
        &args.case,
        &args.control,
    )?;
    beside(
        args.config.as_deref(),
        args.case.surface.is_none(),
        &mut case.surface,
    );
    case.fill_defaults("run/solve");
    let resolved = to_toml(&case, &control)?;
    if args.print_config {
        say!("{resolved}");
        return Ok(());
    }
    let built = case.build()?;
    let problem = &built.problem;
    let tangential = control.tangential_path(case.frictional())?;
    if tangential.is_some() {
        problem.check_tangential()?;
    }
    let control = control.control(problem)?;
    for w in &problem.warnings {
        note!("warning: {w}");
    }
    case.validate_settings(problem.adhesive())?;
    if !problem.adhesive() {
        control.validate_without_adhesion()?;
    }
    let reuse = if args.resume {
        if tangential.is_none() {
            bail!("--resume continues an interrupted tangential path; this solve has none (it is run whole)");
        }
        Reuse::Resume(crate::run::Continued::TangentialPath)
    } else if args.overwrite {
        Reuse::Overwrite
    } else {
        Reuse::Refuse
    };
    let run = RunDir::open(&case.out.clone().expect("defaulted"), reuse)?;
    let out = run.path();
    if tangential.is_some() {
        // (A --resume where nothing was begun runs the path whole, as a sweep's does.)
        if args.resume
            && run
                .case()
                .is_some_and(|c| !crate::sweep::same_case(&c, &resolved))
        {
            bail!(
                "--resume: {} holds a different case; rerun without --resume (or with the same settings)",
                out.display()
            );
        }
        run.write_case(&resolved)?;
    }
    if problem.adhesive() {
        return solve_adhesive(&args, &case, control, tangential.as_deref(), &built, &run);
    }
    let options = case.contact_options();
    let mut progress = Progress::new();
    let (state, report) =
        on_workers(|| problem.solve_without_adhesion(control, &options, None, &mut progress))?;
    progress.finish();
    let edge = problem.edge_warning(&state.gap, &state.pressure);
    if let Some(w) = &edge {
        note!("warning: {w}");
    }
    let domain = problem.domain();
    run.write_field("pressure", &state.pressure)?;
    run.write_field("gap", &state.gap)?;
    run.write_field("displacement", &state.displacement)?;
    run.write_plastic(&state)?;
    let mut summary = results(
        json!({
            "units": {
                "load": "N", "mean_pressure": "Pa", "approach": "m", "max_pressure": "Pa",
                "elastic_energy": "J", "lengths": "m", "modulus": "Pa", "wall_time_s": "s",
                "permanent_set_volume": "m^3", "plastic_work": "J",
                "pressure.npy": "Pa", "gap.npy": "m", "displacement.npy": "m", "plastic.npy": "m"
            },
            "converged": report.converged(),
            "warnings": problem.warnings.iter().chain(&edge).collect::<Vec<_>>(),
        }),
        &report,
    )?;
    print_summary(out, &report, problem.interface.hardness.is_some())?;
    let sheared = shear(
        problem,
        || solver::Normal::without_adhesion(state.clone(), control, &options),
        tangential.as_deref(),
        (&run, args.resume),
        &mut summary,
    )?;
    run.write_summary(&case, &built, summary)?;
    if !args.no_png {
        pressure_map(
            out,
            &state.pressure,
            &domain,
            report.max_pressure,
            report.contact_area_fraction,
        )?;
    }
    finish(
        report.converged(),
        format!(
            "the solve did not converge: residual {:.3e} after {} iterations (tolerance {:.1e})",
            report.residual, report.iterations, options.tolerance
        ),
        args.keep_going,
        out,
    )?;
    finish(sheared, SHEAR_NOT_CONVERGED.into(), args.keep_going, out)
}

const SHEAR_NOT_CONVERGED: &str =
    "a step of the tangential path did not converge (tangential.csv says which)";

/// Runs the tangential path, if any, on the normal solution `normal` makes, adding its summary;
/// whether every step converged (true without a path).
fn shear<'a>(
    problem: &solver::ContactProblem,
    normal: impl FnOnce() -> solver::Normal<'a>,
    controls: Option<&[solver::TangentialControl]>,
    (run, resume): (&RunDir, bool),
    summary: &mut serde_json::Value,
) -> Result<bool> {
    let Some(controls) = controls else {
        return Ok(true);
    };
    let (tangential, converged) = crate::tangential::run(problem, normal(), controls, run, resume)?;
    if let serde_json::Value::Object(map) = summary {
        map.insert("tangential".into(), tangential);
    }
    Ok(converged)
}

/// Draws the contact pressure map.
pub fn pressure_map(out: &Path, pressure: &Array2<f64>, domain: &Domain, pmax: f64, area: f64) -> Result<()> {
    let pmax = pmax.max(f64::MIN_POSITIVE);
    let unit = if pmax >= 1e9 {
        (1e-9, "GPa")
    } else if pmax >= 1e6 {
        (1e-6, "MPa")
    } else {
        (1e-3, "kPa")
    };
    plot::field_map(
        &out.join("pressure.png"),
        pressure.view(),
        (
            0.0,
            0.0,
            domain.nx as f64 * domain.dx,
            domain.ny as f64 * domain.dy,
        ),
        &format!("contact pressure, area fraction {area:.4}"),
        "pressure",
        unit,
    )
}

/// Ends a run: an error (exit status 1) when it did not converge, unless told to keep going.
pub fn finish(converged: bool, msg: String, keep_going: bool, out: &Path) -> Result<()> {
    if converged {
        Ok(())
    } else if keep_going {
        note!("warning: {msg}; results written anyway");
        Ok(())
    } else {
        bail!(
            "{msg}; results are in {} (use --keep-going to accept them)",
            out.display()
        )
    }
}

/// Where a long solve stands: a spinner line on a terminal; without one (a log file), a
/// plain line once a minute.
struct Progress {
    bar: ProgressBar,
    quiet_since: Instant,
}

impl Progress {
    fn new() -> Progress {
        let bar = if crate::quiet() {
            ProgressBar::hidden()
        } else {
            ProgressBar::new_spinner()
        }
        .with_style(ProgressStyle::with_template("{spinner} {elapsed} {msg}").expect("valid template"));
        Progress {
            bar,
            quiet_since: Instant::now(),
        }
    }

    fn finish(&self) {
        self.bar.finish_and_clear();
    }
}

impl Observer for Progress {
    fn iteration(&mut self, _step: usize, iteration: usize, residual: f64) {
        if self.bar.is_hidden() {
            if self.quiet_since.elapsed().as_secs() >= 60 {
                crate::note_unchecked!("iteration {iteration}, residual {residual:.3e}");
                self.quiet_since = Instant::now();
            }
        } else if iteration.is_multiple_of(10) {
            self.bar
                .set_message(format!("iteration {iteration}, residual {residual:.3e}"));
            self.bar.tick();
        }
    }
}

fn solve_adhesive(
    args: &SolveArgs,
    case: &Case,
    control: Control,
    tangential: Option<&[solver::TangentialControl]>,
    built: &Built,
    run: &RunDir,
) -> Result<()> {
    let problem = &built.problem;
    let out = run.path();
    let settings = case.settings();
    let mut progress = Progress::new();
    let (state, report) = on_workers(|| problem.solve(control, &settings, Start::Loading, &mut progress))?;
    progress.finish();
    let edge = problem.edge_warning(&state.contact.gap, &state.contact.pressure);
    if let Some(w) = &edge {
        note!("warning: {w}");
    }
    let domain = problem.domain();
    run.write_adhesive_fields(&state)?;
    let mut summary = results(
        json!({
            "units": {
                "load": "N", "mean_pressure": "Pa", "approach": "m", "pressures": "Pa",
                "lengths": "m", "modulus": "Pa", "work_of_adhesion": "J/m^2", "wall_time_s": "s",
                "permanent_set_volume": "m^3", "plastic_work": "J",
                "pressure.npy": "Pa (total)", "compressive_pressure.npy": "Pa", "adhesive_pressure.npy": "Pa",
                "gap.npy": "m", "displacement.npy": "m", "plastic.npy": "m"
            },
            "law": problem.law.name(),
            "warnings": problem.warnings.iter().chain(&edge).collect::<Vec<_>>(),
            "converged": report.converged(),
        }),
        &report,
    )?;
    let sheared = shear(
        problem,
        || solver::Normal::adhesive(state.clone(), control, &settings),
        tangential,
        (run, args.resume),
        &mut summary,
    )?;
    run.write_summary(case, built, summary)?;
    if !args.no_png {
        pressure_map(
            out,
            &state.total_pressure(),
            &domain,
            report.max_pressure,
            report.contact_area_fraction,
        )?;
    }
    say!("load                     {:.6e} N", report.load);
    say!("mean pressure            {:.6e} Pa", report.mean_pressure);
    say!("approach                 {:.6e} m", report.approach);
    say!("contact area fraction    {:.6}", report.contact_area_fraction);
    say!("attractive area fraction {:.6}", report.attractive_area_fraction);
    say!("attached area fraction   {:.6}", report.attached_area_fraction);
    if problem.interface.hardness.is_some() {
        say_yield(&report.yielding, 25)?;
    }
    say!(
        "iterations               {} ({}), residual {:.2e}, {}",
        report.iterations,
        report.method,
        report.residual,
        report.termination
    );
    say!("wall time                {:.3} s", report.wall_time_s);
    say!("wrote {}/summary.json and the fields as .npy", out.display());
    finish(
        report.converged(),
        format!(
            "the adhesive solve did not converge: {}, residual {:.3e} after {} iterations ({}) \
             (tolerance {:.1e})",
            report.termination, report.residual, report.iterations, report.method, settings.tolerance
        ),
        args.keep_going,
        out,
    )?;
    finish(sheared, SHEAR_NOT_CONVERGED.into(), args.keep_going, out)
}

/// The lines on yielding, for a surface with a hardness.
fn say_yield(y: &solver::Yield, width: usize) -> Result<()> {
    say!("{:width$}{:.6}", "plastic area fraction", y.plastic_area_fraction);
    say!(
        "{:width$}{:.6e} m^3",
        "permanent set volume",
        y.permanent_set_volume
    );
    say!("{:width$}{:.6e} J", "plastic work", y.plastic_work);
    Ok(())
}

fn print_summary(out: &Path, r: &solver::ContactReport, hardness: bool) -> Result<()> {
    say!("load                   {:.6e} N", r.load);
    say!("mean pressure          {:.6e} Pa", r.mean_pressure);
    say!("approach               {:.6e} m", r.approach);
    say!("contact area fraction  {:.6}", r.contact_area_fraction);
    say!("contact clusters       {}", r.clusters);
    say!("max pressure           {:.6e} Pa", r.max_pressure);
    if hardness {
        say_yield(&r.yielding, 23)?;
    }
    say!(
        "iterations             {} ({} operator calls), residual {:.2e}, {}",
        r.iterations,
        r.operator_calls,
        r.residual,
        r.termination
    );
    say!("wall time              {:.3} s", r.wall_time_s);
    say!(
        "wrote {}/summary.json, pressure.npy, gap.npy, displacement.npy{}",
        out.display(),
        if hardness { ", plastic.npy" } else { "" }
    );
    Ok(())
}
