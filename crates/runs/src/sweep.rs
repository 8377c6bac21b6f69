//! `sweep`: a quasi-static approach-retraction cycle (or any list of approaches, mean
//! pressures or central gaps) with continuation, written step by step and resumable.

use crate::run::{CurveWriter, Reuse, RunDir, on_workers, read_state, results};
use crate::solve::finish;
use crate::{note, say};
use anyhow::{Context, Result, bail};
use case::{Case, SweepPath, beside, layered, to_toml};
use clap::{Args, ValueEnum};
use indicatif::{ProgressBar, ProgressStyle};
use plot::{Chart, Curve, Mark, PALETTE};
use serde_json::json;
use solver::{
    AdhesiveState, Branch, Control, CyclePoint, CycleSummary, Observer, SweepPoint, Termination, summarize,
};
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Built-in cases, runnable with no input files (their TOML is in `cases/`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Example {
    /// Rigid sphere on an elastic flat without adhesion (Hertz), ~1 s.
    Hertz,
    /// Sphere with the Lennard-Jones surface law at Tabor parameter 3 (JKR side), ~20 s.
    JkrSphere,
    /// Sphere at Tabor parameter 0.1 (DMT side), ~2 s.
    DmtSphere,
    /// Rough sphere (Rq = z0) at Tabor parameter 2, ~15 s.
    RoughSphere,
    /// The contact-mechanics challenge at 256^2 with its exponential adhesion, load-controlled, ~9 s.
    ChallengeSmall,
    /// Rigid wave at Johnson's alpha 0.3, crests at Tabor parameter 3 (Johnson 1995), ~2 s.
    WavyJkr,
}

impl Example {
    fn toml(self) -> (&'static str, &'static str) {
        match self {
            Example::Hertz => ("hertz", include_str!("../cases/hertz.toml")),
            Example::JkrSphere => ("jkr-sphere", include_str!("../cases/jkr-sphere.toml")),
            Example::DmtSphere => ("dmt-sphere", include_str!("../cases/dmt-sphere.toml")),
            Example::RoughSphere => ("rough-sphere", include_str!("../cases/rough-sphere.toml")),
            Example::ChallengeSmall => ("challenge-small", include_str!("../cases/challenge-small.toml")),
            Example::WavyJkr => ("wavy-jkr", include_str!("../cases/wavy-jkr.toml")),
        }
    }
}

#[derive(Args, Debug)]
pub struct SweepArgs {
    #[command(flatten)]
    case: Case,
    #[command(flatten)]
    path: SweepPath,
    /// TOML case file; its keys are the flags' names in snake_case.
    #[arg(long, value_name = "FILE", conflicts_with = "example")]
    config: Option<PathBuf>,
    /// Run a built-in case (flags still override its settings).
    #[arg(long, value_enum)]
    example: Option<Example>,
    /// Continue an interrupted sweep in --out: finished steps are kept, not redone.
    #[arg(long)]
    resume: bool,
    /// Replace the run already in --out (its case, curve, states, fields and plots; nothing
    /// else in the directory is touched).
    #[arg(long, conflicts_with = "resume")]
    overwrite: bool,
    /// Also keep every step's fields (gap, compressive and adhesive pressure [Pa],
    /// displacement [m], .npy) in --out/states/step-NNNN, not only the last one in --out/state.
    #[arg(long)]
    save_states: bool,
    /// Print the resolved case as TOML and exit without solving.
    #[arg(long)]
    print_config: bool,
    /// Exit with status 0 even when a step does not converge (curve.csv says which).
    #[arg(long)]
    keep_going: bool,
    /// Do not draw the load-approach plot.
    #[arg(long)]
    no_png: bool,
}

pub fn sweep(args: SweepArgs) -> Result<()> {
    let (case, path, resolved) = resolved_case(&args)?;
    if args.print_config {
        say!("{resolved}");
        return Ok(());
    }
    let controls = path.controls()?;
    let search = path.pull_off()?;
    let built = case.build()?;
    let problem = &built.problem;
    for w in &problem.warnings {
        note!("warning: {w}");
    }
    // Read and check a --start-from state before anything is written, so that a wrong one leaves
    // the output directory as it was.
    let saved = match &path.start_from {
        Some(dir) => Some((dir, start_from(dir, problem)?)),
        None => None,
    };
    let max_step = path.max_step(problem, &controls)?;
    let times = path.times(problem, controls.len())?;
    case.validate_settings(problem.adhesive())?;
    let settings = case.settings();
    let reuse = match (args.resume, args.overwrite) {
        (true, _) => Reuse::Resume(crate::run::Continued::Sweep),
        (false, true) => Reuse::Overwrite,
        (false, false) => Reuse::Refuse,
    };
    let run = RunDir::open(&case.out.clone().expect("defaulted"), reuse)?;
    let out = run.path();
    let (mut rows, mut start) = if args.resume && run.has_curve() {
        resumed(&run, &resolved, &controls, search.is_some())?
    } else {
        run.write_case(&resolved)?;
        run.start_curve()?;
        (Vec::new(), None)
    };
    // A sweep from a saved state (also one resumed before its first step finished).
    if let (None, Some((dir, state))) = (&start, saved) {
        note!(
            "starting from {} (approach {:e} m)",
            dir.display(),
            state.contact.approach
        );
        start = Some(state);
    }
    let done = rows.len().min(controls.len());

    let split = solver::count_substeps(&controls[done.saturating_sub(1)..], max_step)?;
    if split > 0 {
        note!(
            "note: {split} substeps are solved between the path's steps (none longer than {:.3e} m, \
             to stay quasi-static); a larger --max-step is faster but may jump between branches",
            max_step.unwrap_or(f64::NAN)
        );
    }
    // The path's last approach, where a pull-off search starts.
    let last = match controls.last() {
        Some(&Control::Approach(a)) => a,
        _ => f64::NAN,
    };
    let total = controls.len() + search.map_or(0, |s| s.most_steps(last));
    let bar = progress_bar(total, done);
    let started = Instant::now();
    let keep = (path.keep_steps.iter().flatten().copied())
        .chain(search.map(|_| controls.len() - 1))
        .collect();
    let mut writer = StepWriter::new(&run, (done, total), args.save_states, keep, &bar, problem)?;
    let mut points = if done < controls.len() {
        let rest = solver::Path {
            controls: &controls[done..],
            times: times.as_ref().map(|t| &t[done..]),
        };
        on_workers(|| problem.sweep(rest, max_step, &settings, start, &mut writer))?
    } else {
        Vec::new()
    };
    if let Some(search) = &search
        && writer.error.is_none()
        && done + points.len() == controls.len()
        && points
            .iter()
            .all(|p| p.report.termination != Termination::Interrupted)
    {
        let from = run.resume_state(controls.len() - 1, last)?;
        let pull = on_workers(|| problem.pull_off(search, &settings, from, &mut writer))?;
        points.extend(pull.coarse);
        points.extend(pull.refined);
    }
    bar.finish_and_clear();
    if let Some(e) = writer.error {
        return Err(e.context("writing the sweep's results"));
    }
    rows.extend(points.iter().map(CyclePoint::from));
    let cycle = rows;
    let summary = summarize(&cycle);
    let mut warnings: Vec<String> = problem.warnings.iter().chain(&writer.edge).cloned().collect();
    if summary.pull_off_at_path_end {
        let w = "the most tensile load is the path's last step, still attached: the pull-off lies \
                 beyond the path (retract further: a more negative --to, or --pull-off-step)"
            .to_string();
        note!("warning: {w}");
        warnings.push(w);
    }
    let theory = Theory::of(&case, problem, &summary);

    let domain = problem.domain();
    let range = problem.law.range();
    let json = json!({
        "path": path,
        "units": {
            "pull_off_force": "N", "pull_off_approach": "m", "jump_in_approach": "m",
            "jump_out_approach": "m", "hysteresis_energy": "J", "plastic_work": "J",
            "viscous_work": "J", "adhesive_work": "J", "lengths": "m",
            "pressures": "Pa", "plastic.npy": "m (the permanent set after the last step)",
            "curve.csv": "approach m, load N, mean_pressure Pa, central_gap m, wall_time_s s, \
                          permanent_set_volume m^3, plastic_work J, time s, elastic_energy J, \
                          viscous_work J"
        },
        "law": problem.law.name(),
        "method": problem
            .adhesive()
            .then(|| {
                settings
                    .method
                    .resolve(problem.law.as_ref(), controls[0], &domain, problem.operator.cell_compliance(), &problem.interface)
                    .name()
            }),
        "adhesive_range": problem.adhesive().then_some(range),
        "adhesive_range_per_cell": problem.adhesive().then_some(range / domain.dx.max(domain.dy)),
        "tabor_parameter": theory.tabor,
        "wave": theory.johnson(),
        "max_step": max_step,
        "warnings": warnings,
        "steps": cycle.len(),
        "wall_time_s": started.elapsed().as_secs_f64(),
    });
    run.write_summary(&case, &built, results(json, &summary)?)?;
    if !args.no_png && cycle.len() > 1 {
        plot_cycle(&out.join("load_approach.png"), &cycle, &summary)?;
    }
    print_cycle(&cycle, &summary, &theory, &case, &built, controls[0])?;
    say!("wrote {}/curve.csv, summary.json", out.display());
    let failed = cycle.iter().filter(|p| !p.converged).count();
    finish(
        summary.all_converged,
        format!(
            "{failed} of {} steps did not converge (see curve.csv)",
            cycle.len()
        ),
        args.keep_going,
        out,
    )
}

/// The case and path of `args` (a file, a built-in example, flags), defaults filled, with
/// their resolved TOML.
fn resolved_case(args: &SweepArgs) -> Result<(Case, SweepPath, String)> {
    let (name, text) = match (&args.config, args.example) {
        (Some(path), _) => (
            path.display().to_string(),
            Some(std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?),
        ),
        (None, Some(e)) => {
            let (n, t) = e.toml();
            (format!("example {n}"), Some(t.to_string()))
        }
        (None, None) => (String::new(), None),
    };
    let (mut case, mut path) = layered(
        text.as_deref().map(|t| (name.as_str(), t)),
        &args.case,
        &args.path,
    )?;
    beside(
        args.config.as_deref(),
        args.case.surface.is_none(),
        &mut case.surface,
    );
    beside(
        args.config.as_deref(),
        args.path.start_from.is_none(),
        &mut path.start_from,
    );
    case.refuse_friction()?;
    case.fill_defaults("run/sweep");
    path.fill_defaults();
    let resolved = to_toml(&case, &path)?;
    Ok((case, path, resolved))
}

/// The saved state in `dir` (`--start-from`), checked against the problem's grid.
fn start_from(dir: &Path, problem: &solver::ContactProblem) -> Result<AdhesiveState> {
    let state = read_state(dir)?;
    let shape = problem.initial_gap.dim();
    if state.contact.gap.dim() != shape {
        bail!(
            "--start-from: {} holds a {:?} grid, this case has {shape:?}",
            dir.display(),
            state.contact.gap.dim()
        );
    }
    Ok(state)
}

/// A resumed sweep: the same case (wherever the directory is now), its finished rows and the
/// last state. A pull-off search that had begun (`search`) is redone from the path's last
/// state.
fn resumed(
    run: &RunDir,
    resolved: &str,
    controls: &[Control],
    search: bool,
) -> Result<(Vec<CyclePoint>, Option<AdhesiveState>)> {
    let out = run.path();
    if !same_case(&run.case().unwrap_or_default(), resolved) {
        bail!(
            "--resume: {} holds a different case; rerun without --resume (or with the same settings)",
            out.display()
        );
    }
    let mut rows = run.read_curve()?;
    if search && rows.len() > controls.len() {
        rows.truncate(controls.len());
        run.truncate_curve(rows.len())?;
    }
    check_rows(&rows, controls).with_context(|| {
        format!(
            "--resume: {}/curve.csv does not belong to this path",
            out.display()
        )
    })?;
    let start = match rows.last() {
        Some(last) => Some(run.resume_state(rows.len() - 1, last.approach)?),
        None => None,
    };
    note!("resuming after {} of {} steps", rows.len(), controls.len());
    Ok((rows, start))
}

/// The sweep's progress bar at `done` of `total` steps (hidden when quiet).
fn progress_bar(total: usize, done: usize) -> ProgressBar {
    let bar = if crate::quiet() {
        ProgressBar::hidden()
    } else {
        ProgressBar::new(total as u64)
    }
    .with_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} steps, {elapsed} elapsed, ~{eta} left  {msg}")
            .expect("valid template"),
    );
    bar.set_position(done as u64);
    bar
}

/// What theory says beside a cycle: the Tabor parameter of a sphere or a wave's crests with a
/// Lennard-Jones law (the problem's), and for an adhesive wave Johnson's (1995) solution.
struct Theory {
    tabor: Option<f64>,
    wave: Option<theory::wavy::Wave>,
    /// The cycle's pull-off as the mean pressure over the box [Pa].
    pull_off_pressure: Option<f64>,
    /// The law's work of adhesion [J/m^2] (zero without adhesion).
    work_of_adhesion: f64,
}

impl Theory {
    fn of(case: &Case, problem: &solver::ContactProblem, summary: &CycleSummary) -> Theory {
        let domain = problem.domain();
        let work_of_adhesion = problem.law.work_of_adhesion();
        // A wave's crests are its spheres: Johnson's parameter and JKR pull-off come with it.
        let wave = case.wave_amplitude.map(|amplitude| theory::wavy::Wave {
            amplitude,
            wavelength: domain.nx as f64 * domain.dx,
            e_star: problem.e_star(),
            work_of_adhesion,
        });
        let radius = case.sphere_radius.or(wave.map(|w| w.crest_radius()));
        let tabor = match (radius, problem.law.lennard_jones()) {
            (Some(r), Some(lj)) => Some(theory::tabor_parameter(
                r,
                work_of_adhesion,
                problem.e_star(),
                lj.z0(),
            )),
            _ => None,
        };
        Theory {
            tabor,
            // Johnson's wave is on a half-space.
            wave: wave.filter(|_| problem.adhesive() && case.thickness.is_none()),
            pull_off_pressure: summary
                .pull_off_force
                .map(|f| f / (domain.cell_area() * (domain.nx * domain.ny) as f64)),
            work_of_adhesion,
        }
    }

    /// Johnson's numbers for `summary.json`.
    fn johnson(&self) -> Option<serde_json::Value> {
        self.wave.map(|w| {
            json!({
                "johnson_parameter": w.johnson_alpha(),
                "crest_radius": w.crest_radius(),
                "full_contact_pressure": w.full_contact_pressure(),
                "jkr_pull_off_mean_pressure": w.jkr_pull_off().0,
                "pull_off_mean_pressure": self.pull_off_pressure,
            })
        })
    }
}

/// The cycle's results on standard output, beside the theory that applies: a sphere's
/// pull-off against Maugis-Dugdale, a smooth sphere without adhesion against Hertz, a wave
/// against Johnson; under load control the contact area a step.
fn print_cycle(
    cycle: &[CyclePoint],
    summary: &CycleSummary,
    theory: &Theory,
    case: &Case,
    built: &case::Built,
    first: Control,
) -> Result<()> {
    let problem = &built.problem;
    say!("steps                 {}", cycle.len());
    if let Some(w) = summary.pull_off_force {
        say!(
            "pull-off force        {w:.6e} N at approach {:.4e} m",
            summary.pull_off_approach.unwrap_or(f64::NAN)
        );
        // A sphere's pull-off in its natural unit, beside Maugis-Dugdale's at its Tabor parameter.
        if let (Some(r), true, None) = (case.sphere_radius, theory.work_of_adhesion > 0.0, theory.wave) {
            let unit = std::f64::consts::PI * r * theory.work_of_adhesion;
            let mut line = format!("                      = {:.4} pi R w0", w / unit);
            if let Some(mu) = theory.tabor {
                let md = theory::maugis::MaugisDugdale::new(theory::maugis_parameter_of_tabor(mu));
                let on = match (case.thickness.is_some(), problem.solid.is_some()) {
                    (true, _) => ", half-space",
                    (false, true) => ", relaxed",
                    _ => "",
                };
                line += &format!(
                    " (Maugis-Dugdale's least load at lambda = 1.157 mu{on}: {:.4}",
                    md.pull_off_load_control()
                );
                // A viscoelastic body: also the glassy sphere's, mu scaling as E*^(-2/3).
                if let Some(solid) = &problem.solid {
                    let glassy = mu * (solid.relaxed / solid.glassy()).powf(2.0 / 3.0);
                    let md = theory::maugis::MaugisDugdale::new(theory::maugis_parameter_of_tabor(glassy));
                    line += &format!("; glassy, mu {glassy:.3}: {:.4}", md.pull_off_load_control());
                }
                line += ")";
            }
            if let elastic::Body::Layer(layer) = problem.operator.body() {
                let a = (9.0 * std::f64::consts::PI * theory.work_of_adhesion * r * r
                    / (8.0 * problem.e_star()))
                .cbrt();
                if a <= theory::layer::REACH * layer.thickness {
                    let jkr = exact_on(layer, problem.e_star()).pull_off(r, theory.work_of_adhesion);
                    line += &format!("; JKR's on the layer, smooth: {:.4}", jkr.load / unit);
                }
            }
            say!("{line}");
        }
    }
    // A smooth sphere without adhesion: the deepest step against Hertz.
    if let (Some(r), false, None, None) = (
        case.sphere_radius,
        problem.adhesive(),
        built.surface_hash.as_ref(),
        case.wave_amplitude,
    ) && let Some(deep) = cycle.iter().max_by(|a, b| a.approach.total_cmp(&b.approach))
        && deep.approach > 0.0
    {
        // On a layer, the exact frictionless sphere (theory::layer::LayerContact).
        let chi = |layer: &elastic::Layer| (r * deep.approach).sqrt() / layer.thickness;
        // (Not a number where the contact is wider than the solution's reach.)
        let reference = match problem.operator.body() {
            elastic::Body::Layer(layer) if chi(&layer) <= theory::layer::REACH => Some((
                format!("the exact sphere on the layer (chi = {:.3})", chi(&layer)),
                exact_on(layer, problem.e_star()).hertz(deep.approach, r).load,
            ))
            .filter(|(_, load)| load.is_finite()),
            elastic::Body::Layer(_) => None,
            elastic::Body::HalfSpace => Some((
                "Hertz".to_string(),
                theory::hertz::load_of_approach(deep.approach, r, problem.e_star()),
            )),
        };
        if let Some((name, reference)) = reference {
            say!(
                "{name} at the deepest approach ({:.4e} m): {reference:.6e} N; solved {:.6e} N ({:+.2} %)",
                deep.approach,
                deep.load,
                100.0 * (deep.load / reference - 1.0)
            );
        }
    }
    // Under load control the contact area is the result: a line a step.
    if matches!(first, Control::MeanPressure(_)) {
        let domain = problem.domain();
        say!("mean pressure [Pa]  contact area  attached area  branch");
        let area = domain.cell_area() * (domain.nx * domain.ny) as f64;
        for p in cycle {
            say!(
                "{:>18.4e}  {:>12.6}  {:>13.6}  {}",
                p.load / area,
                p.contact_area_fraction,
                p.attached_area_fraction,
                p.branch.name()
            );
        }
    }
    if let Some(a) = summary.jump_in_approach {
        say!("jump in at approach   {a:.4e} m");
    }
    if let Some(a) = summary.jump_out_approach {
        say!("jump out at approach  {a:.4e} m");
    }
    if let Some(w) = summary.hysteresis_energy {
        say!("hysteresis energy     {w:.6e} J (lost around the closed part of the cycle)");
    }
    if problem.interface.hardness.is_some() {
        say!(
            "plastic work          {:.6e} J (dissipated by yielding; the permanent set in plastic.npy)",
            summary.plastic_work
        );
    }
    if problem.solid.is_some() {
        say!(
            "viscous work          {:.6e} J (dissipated by the dashpots)",
            summary.viscous_work
        );
        if let Some(w) = summary.adhesive_work {
            say!("adhesive work         {w:.6e} J (lost in the jumps, from apart to apart)");
        }
    }
    if let Some(mu) = theory.tabor {
        say!("Tabor parameter       {mu:.4}");
    }
    if let (Some(w), Some(p)) = (theory.wave, theory.pull_off_pressure) {
        say!(
            "pull-off pressure     {p:.6e} Pa; Johnson's JKR wave (alpha {:.4}): {:.6e} Pa",
            w.johnson_alpha(),
            w.jkr_pull_off().0
        );
    }
    Ok(())
}

/// A rigid sphere on `layer` of modulus `e_star` \[Pa\], solved exactly.
fn exact_on(layer: elastic::Layer, e_star: f64) -> theory::layer::LayerContact<impl Fn(f64) -> f64> {
    let h = layer.thickness;
    theory::layer::LayerContact::new(h, e_star, move |x| layer.compliance_ratio(x / h, e_star))
}

/// Whether two resolved cases (TOML) are the same apart from their output directory, which
/// may be spelt differently or moved between a sweep and its resumption.
pub(crate) fn same_case(a: &str, b: &str) -> bool {
    matches!((without_out(a), without_out(b)), (Some(a), Some(b)) if a == b)
}

/// A case (TOML) without its output directory; `None` if it does not parse.
pub(crate) fn without_out(case: &str) -> Option<toml::Table> {
    toml::from_str::<toml::Table>(case).ok().map(|mut t| {
        t.remove("out");
        t
    })
}

/// The finished rows of a sweep being resumed must be a start of its path: no more rows than
/// steps, and under approach control each at its step's approach.
fn check_rows(rows: &[CyclePoint], controls: &[Control]) -> Result<()> {
    if rows.len() > controls.len() {
        bail!(
            "it holds {} rows, the path has {} steps",
            rows.len(),
            controls.len()
        );
    }
    for (k, (row, control)) in rows.iter().zip(controls).enumerate() {
        if let Control::Approach(a) = *control
            && row.approach != a
        {
            bail!(
                "step {k} is at approach {:e} m, the path has {a:e} m",
                row.approach
            );
        }
    }
    Ok(())
}

/// The load-approach chart: each branch a line through its steps (loading solid with dots,
/// unloading dashed with triangles, so that neither hides the other; unconverged steps
/// hollow), the pull-off and the jumps ringed.
fn plot_cycle(path: &Path, cycle: &[CyclePoint], summary: &CycleSummary) -> Result<()> {
    let (lf, lu) = plot::length_unit(cycle.iter().map(|p| p.approach.abs()).fold(0.0, f64::max));
    let max_load = cycle.iter().map(|p| p.load.abs()).fold(0.0, f64::max);
    let (ff, fu) = force_unit(max_load);
    let branch = |b: Branch| -> Vec<(f64, f64, bool)> {
        cycle
            .iter()
            .filter(|p| p.branch == b)
            .map(|p| (p.approach * lf, p.load * ff, p.converged))
            .collect()
    };
    let line = |points: &[(f64, f64, bool)]| points.iter().map(|p| (p.0, p.1)).collect();
    // The step of `branch` at `approach`, scaled.
    let at = |b: Branch, approach: Option<f64>| -> Vec<(f64, f64)> {
        cycle
            .iter()
            .filter(|p| p.branch == b && Some(p.approach) == approach)
            .map(|p| (p.approach * lf, p.load * ff))
            .take(1)
            .collect()
    };
    let mut chart = Chart::new(
        "load against approach",
        format!("approach [{lu}]"),
        format!("load [{fu}]"),
    );
    let (loading, unloading) = (branch(Branch::Loading), branch(Branch::Unloading));
    chart.curves = vec![
        Curve::new("", line(&loading), Mark::Line, PALETTE[0]),
        Curve::new("", line(&unloading), Mark::Dashed, PALETTE[3]),
    ];
    let times: Option<Vec<f64>> = cycle.iter().map(|p| p.time).collect();
    match times.filter(|t| t.last() > t.first()) {
        // A path in time: its steps coloured by when they were reached, in five bands.
        Some(t) => {
            let (first, last) = (t[0], t[t.len() - 1]);
            const BANDS: usize = 5;
            let band = |time: f64| (((time - first) / (last - first) * BANDS as f64) as usize).min(BANDS - 1);
            for b in 0..BANDS {
                let (from, to) = (
                    first + (last - first) * b as f64 / BANDS as f64,
                    first + (last - first) * (b + 1) as f64 / BANDS as f64,
                );
                let points: Vec<(f64, f64, bool)> = cycle
                    .iter()
                    .zip(&t)
                    .filter(|(_, time)| band(**time) == b)
                    .map(|(p, _)| (p.approach * lf, p.load * ff, p.converged))
                    .collect();
                let label = format!("t {from:.2e} - {to:.2e} s");
                let color = plot::viridis(b as f64 / (BANDS - 1) as f64);
                chart.curves.push(Curve::solved(label, points, Mark::Dots, color));
            }
        }
        None => {
            chart
                .curves
                .push(Curve::solved("loading", loading, Mark::Dots, PALETTE[0]));
            chart
                .curves
                .push(Curve::solved("unloading", unloading, Mark::Triangles, PALETTE[3]));
        }
    }
    let pull_off: Vec<(f64, f64)> = summary
        .pull_off_force
        .zip(summary.pull_off_approach)
        .map(|(w, a)| (a * lf, w * ff))
        .into_iter()
        .collect();
    let jumps: Vec<(f64, f64)> = at(Branch::Loading, summary.jump_in_approach)
        .into_iter()
        .chain(at(Branch::Unloading, summary.jump_out_approach))
        .collect();
    for (label, points, color) in [("pull-off", pull_off, PALETTE[1]), ("jumps", jumps, PALETTE[2])] {
        if !points.is_empty() {
            chart.curves.push(Curve::new(label, points, Mark::Rings, color));
        }
    }
    chart.save_png(path)
}

fn force_unit(v: f64) -> (f64, &'static str) {
    if v >= 1.0 {
        (1.0, "N")
    } else if v >= 1e-3 {
        (1e3, "mN")
    } else if v >= 1e-6 {
        (1e6, "µN")
    } else if v >= 1e-9 {
        (1e9, "nN")
    } else {
        (1e12, "pN")
    }
}

/// How often a sweep inside a study writes where its running step stands.
const PROGRESS_EVERY: std::time::Duration = std::time::Duration::from_secs(10);

/// Writes each finished step (its row of curve.csv, its state) and shows where the sweep
/// stands; a write that fails stops the sweep and is kept in `error`.
struct StepWriter<'a> {
    run: &'a RunDir,
    /// Steps finished (before this run too, when resumed), and the steps in all.
    done: usize,
    steps: usize,
    save_states: bool,
    /// Steps whose states are kept whatever `save_states` says: those asked for, and the
    /// pull-off search's start.
    keep: Vec<usize>,
    curve: CurveWriter,
    bar: &'a ProgressBar,
    /// The last finished step, shown beside the running solve's iteration and residual.
    last: String,
    quiet_since: Instant,
    /// When the running step's progress was last written for a study ([`PROGRESS_EVERY`]).
    progress_since: Instant,
    error: Option<anyhow::Error>,
    problem: &'a solver::ContactProblem,
    /// The first step whose contact reached a free grid's edge, as a warning.
    edge: Option<String>,
}

impl<'a> StepWriter<'a> {
    /// A writer into `run` of the steps after `done` of `total`, keeping the fields of every
    /// step (`save_states`) or of those in `keep`.
    fn new(
        run: &'a RunDir,
        (done, total): (usize, usize),
        save_states: bool,
        keep: Vec<usize>,
        bar: &'a ProgressBar,
        problem: &'a solver::ContactProblem,
    ) -> Result<Self> {
        Ok(StepWriter {
            run,
            done,
            steps: total,
            save_states,
            keep,
            curve: run.curve_writer()?,
            bar,
            last: String::new(),
            quiet_since: Instant::now(),
            progress_since: Instant::now(),
            error: None,
            problem,
            edge: None,
        })
    }
}

impl Observer for StepWriter<'_> {
    fn iteration(&mut self, _: usize, iteration: usize, residual: f64) {
        // Without a terminal, where the running solve stands once a minute.
        if self.bar.is_hidden() && self.quiet_since.elapsed().as_secs() >= 60 {
            crate::note_unchecked!(
                "step {}/{}: iteration {iteration}, residual {residual:.2e}",
                self.done + 1,
                self.steps
            );
            self.quiet_since = Instant::now();
        }
        // Inside a study (quiet), where the running step stands goes to the run's directory.
        if crate::quiet() && self.progress_since.elapsed() >= PROGRESS_EVERY {
            self.run.write_progress(Some(&format!(
                "step {}/{}: iteration {iteration}, residual {residual:.2e}",
                self.done + 1,
                self.steps
            )));
            self.progress_since = Instant::now();
        }
        if iteration.is_multiple_of(10) {
            self.bar.set_message(format!(
                "iteration {iteration}, residual {residual:.2e}  {}",
                self.last
            ));
        }
    }

    fn step(&mut self, _: usize, p: &SweepPoint, state: &AdhesiveState) -> bool {
        let r = &p.report;
        let k = self.done;
        self.done += 1;
        if self.edge.is_none()
            && let Some(w) = self
                .problem
                .edge_warning(&state.contact.gap, &state.contact.pressure)
        {
            let w = format!("from step {k} on, {w}");
            self.bar.suspend(|| crate::note_unchecked!("warning: {w}"));
            self.edge = Some(w);
        }
        self.run.write_progress(None);
        let saved = self
            .run
            .save_state(k, state, self.save_states || self.keep.contains(&k))
            .and_then(|_| self.run.write_plastic(&state.contact))
            .and_then(|_| self.curve.append(k, p));
        let message = format!("last: approach {:.4e} m, load {:.4e} N", r.approach, r.load);
        if self.bar.is_hidden() {
            // No terminal (a background run, a log file): a plain line a step instead.
            crate::note_unchecked!(
                "step {}/{}: approach {:.4e} m, load {:.4e} N, {}, {:.1} s",
                k + 1,
                self.steps,
                r.approach,
                r.load,
                if r.converged() {
                    "converged"
                } else {
                    "NOT converged"
                },
                r.wall_time_s
            );
        }
        self.bar.set_message(message.clone());
        self.last = message;
        self.bar.inc(1);
        match saved {
            Ok(()) => true,
            Err(e) => {
                self.error = Some(e);
                false
            }
        }
    }
}
