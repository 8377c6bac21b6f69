//! `cargo xtask figures`: Figures 5-14 of Ghanbarzadeh, Faraji & Neville (2020) rebuilt from
//! nothing, as PNG + SVG with their data as CSV, and `FIGURES.md` saying what was computed and
//! how well each figure agrees with its reference (docs/method.md section 7).
//!
//! Each figure is a module (`fig05` ... `fig14`) that asks for its runs, draws itself and
//! reports. The runs are shared physics (`sphere`, `challenge`, `rough_sphere`): the spheres'
//! cached on disk by their inputs ([`cache`]) and run in parallel with a progress bar
//! ([`Context::run`]), the challenge's and the rough spheres' run as studies of the command
//! line in `OUT/studies/` ([`series`]), resumable and runnable across machines.
//! Quick mode uses small grids (a few minutes, run by the test suite); full mode the largest
//! this machine affords, stated in each figure's report.

pub mod cache;
pub mod challenge;
pub mod fig05;
pub mod fig06;
pub mod fig07;
pub mod fig08;
pub mod fig09;
pub mod fig10;
pub mod fig11;
pub mod fig12;
pub mod fig13;
pub mod fig14;
pub mod friction;
pub use plot;
pub mod plastic;
pub mod report;
pub mod rough_sphere;

/// The colour of Tabor parameter `mu` (the paper's 0.1-7), the same in every figure.
pub fn tabor_colour(mu: f64) -> plotters::style::RGBColor {
    use plot::PALETTE;
    use plotters::style::RGBColor;
    const COLOURS: [(f64, RGBColor); 8] = [
        (0.1, RGBColor(23, 190, 207)),
        (0.2, RGBColor(188, 189, 34)),
        (0.3, RGBColor(227, 119, 194)),
        (1.0, PALETTE[4]),
        (2.0, PALETTE[0]),
        (3.0, PALETTE[1]),
        (5.0, PALETTE[5]),
        (7.0, PALETTE[2]),
    ];
    COLOURS
        .iter()
        .min_by(|a, b| (a.0 - mu).abs().total_cmp(&(b.0 - mu).abs()))
        .expect("colours")
        .1
}
pub mod series;
pub mod sphere;
pub mod study;
pub mod viscoelastic;

use anyhow::{Context as _, Result, bail};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rayon::prelude::*;
use std::path::PathBuf;
use std::time::Instant;

pub use report::{FigureReport, Table};

/// A sweep observer handing every step's state to a closure.
pub struct States<'a>(pub &'a mut dyn FnMut(usize, &solver::AdhesiveState));

impl solver::Observer for States<'_> {
    fn step(&mut self, k: usize, _: &solver::SweepPoint, state: &solver::AdhesiveState) -> bool {
        (self.0)(k, state);
        true
    }
}

/// What to build and where.
#[derive(Clone, Debug)]
pub struct Options {
    /// Small grids and few points: a few minutes.
    pub quick: bool,
    /// Figure numbers to build (all of 5-14 when empty).
    pub only: Vec<u32>,
    /// Output directory (figures, CSV, FIGURES.md, the run cache in `cache/`, the studies in
    /// `studies/`).
    pub out: PathBuf,
    /// The contact-mechanics challenge's own topography, if the user has it (Figs. 8-9).
    pub challenge_surface: Option<PathBuf>,
    /// Recompute every run instead of reading the cache and the studies' finished runs.
    pub fresh: bool,
    /// Show progress bars.
    pub progress: bool,
    /// The rough spheres' law (Figs. 11-14): the point law (the default, by the energy
    /// descent) or the paper's surface law (by the flow, 2.5 times the time).
    pub rough_law: case::LawKind,
    /// The adhesive law of the challenge's figures (Figs. 8-10): the paper's surface law (by
    /// the flow) or the challenge's exponential law.
    pub challenge_law: case::LawKind,
}

pub const ALL: [u32; 10] = [5, 6, 7, 8, 9, 10, 11, 12, 13, 14];

/// What every figure module gets: the options and the cache.
pub struct Context {
    pub options: Options,
    pub cache: cache::Cache,
}

impl Context {
    pub fn quick(&self) -> bool {
        self.options.quick
    }

    /// Whether figure `n` is among those being built (`--only`, all when empty).
    pub fn builds(&self, n: u32) -> bool {
        self.options.only.is_empty() || self.options.only.contains(&n)
    }

    /// `quick` in quick mode, `full` otherwise.
    pub fn pick<T>(&self, quick: T, full: T) -> T {
        if self.options.quick { quick } else { full }
    }

    /// Runs independent `jobs` in parallel (each through the cache under `kind`), with a
    /// progress bar named `what`; results in the order of `jobs`.
    pub fn run<J, R>(
        &self,
        what: &str,
        kind: &str,
        jobs: &[J],
        f: impl Fn(&J) -> Result<R> + Sync,
    ) -> Result<Vec<R>>
    where
        J: serde::Serialize + Sync,
        R: serde::Serialize + serde::de::DeserializeOwned + Send,
    {
        let bar = if self.options.progress {
            ProgressBar::new(jobs.len() as u64)
        } else {
            ProgressBar::with_draw_target(Some(jobs.len() as u64), ProgressDrawTarget::hidden())
        };
        bar.set_style(
            ProgressStyle::with_template("{prefix:>12} [{bar:30}] {pos}/{len} runs, {elapsed}")
                .expect("valid template")
                .progress_chars("=> "),
        );
        bar.set_prefix(what.to_string());
        let out = jobs
            .par_iter()
            .map(|job| {
                let r = self.cache.get_or(kind, job, || f(job));
                bar.inc(1);
                r
            })
            .collect::<Result<Vec<R>>>();
        bar.finish_and_clear();
        out
    }
}

/// The figures asked for, checked, and their context: the output directory made, the cache
/// opened, the studies cleared when `fresh`.
fn context(options: Options) -> Result<(Vec<u32>, Context)> {
    let only = if options.only.is_empty() {
        ALL.to_vec()
    } else {
        options.only.clone()
    };
    if let Some(bad) = only.iter().find(|n| !ALL.contains(n)) {
        bail!("there is no figure {bad}: the paper's figures with results are 5 to 14");
    }
    std::fs::create_dir_all(&options.out).with_context(|| format!("creating {}", options.out.display()))?;
    let cache = cache::Cache::new(options.out.join("cache"), options.fresh)?;
    let studies = options.out.join("studies");
    if options.fresh && studies.exists() {
        std::fs::remove_dir_all(&studies).with_context(|| format!("removing {}", studies.display()))?;
    }
    Ok((only, Context { options, cache }))
}

/// Every challenge run the figures being built ask for (Figs. 8-10 among `--only`): the
/// challenge's studies run them together, whichever figure asks first.
pub fn challenge_runs(ctx: &Context) -> Result<Vec<challenge::Run>> {
    let mut all = Vec::new();
    if ctx.builds(8) || ctx.builds(9) {
        all.extend(fig08::runs(ctx));
    }
    if ctx.builds(10) {
        all.extend(fig10::runs(ctx)?.0);
    }
    Ok(all)
}

/// Every rough-sphere point the figures being built ask for (Figs. 11-14 among `--only`),
/// run together in the same way.
pub fn rough_sphere_specs(ctx: &Context) -> Vec<rough_sphere::Spec> {
    let mut all = Vec::new();
    if ctx.builds(11) {
        all.extend(fig11::wanted(ctx));
    }
    if ctx.builds(12) {
        all.extend(fig12::wanted(ctx));
    }
    if ctx.builds(13) || ctx.builds(14) {
        all.extend(fig13::wanted(ctx));
    }
    all
}

/// Writes the study files of the requested figures' rough-sphere and challenge series into
/// `options.out/studies` without running them; returns each file, its directory and its runs.
pub fn write_studies(options: Options) -> Result<Vec<(PathBuf, PathBuf, usize)>> {
    let (_, ctx) = context(options)?;
    let mut sweeps = rough_sphere::sweeps(&ctx, &[]).1;
    sweeps.extend(challenge::sweeps(&ctx, &[])?);
    series::write(&ctx.options.out.join("studies"), &sweeps)
}

/// Builds the requested figures into `options.out` and writes `FIGURES.md` there.
pub fn figures(options: Options) -> Result<Vec<FigureReport>> {
    let (only, ctx) = context(options)?;
    let mut reports = Vec::new();
    for n in only {
        let start = Instant::now();
        let mut r = match n {
            5 => fig05::run(&ctx),
            6 => fig06::run(&ctx),
            7 => fig07::run(&ctx),
            8 => fig08::run(&ctx),
            9 => fig09::run(&ctx),
            10 => fig10::run(&ctx),
            11 => fig11::run(&ctx),
            12 => fig12::run(&ctx),
            13 => fig13::run(&ctx),
            14 => fig14::run(&ctx),
            _ => unreachable!("checked above"),
        }
        .with_context(|| format!("figure {n}"))?;
        r.seconds = start.elapsed().as_secs_f64();
        r.mode = if ctx.quick() { "quick" } else { "full" }.into();
        r.write(&ctx.options.out)?;
        if ctx.options.progress {
            eprintln!("figure {n:>2}: {} ({:.0} s)", r.title, r.seconds);
        }
        reports.push(r);
    }
    report::write_markdown(&ctx.options)?;
    Ok(reports)
}

/// Statistics of the roughness behind `case` (its heights alone, periodic): RMS gradient
/// [-], local radius (inverse RMS curvature) \[m\], Rq \[m\], cell \[m\].
pub fn surface_statistics(case: &case::Case) -> Result<(f64, f64, f64, f64)> {
    let surface = case.rough_surface()?.context("the case has no roughness")?;
    let s = gap_statistics(&surface.heights, &surface.grid);
    Ok((
        s.rms_gradient,
        s.local_radius,
        s.heights.rms_height,
        surface.grid.dx(),
    ))
}

/// The library's problem of `case`, its defaults filled as the command line fills them.
pub fn problem(case: &case::Case) -> Result<solver::ContactProblem> {
    let mut case = case.clone();
    case.fill_defaults("");
    Ok(case.build()?.problem)
}

/// The statistics of the gap a flat leaves on periodic `heights`, as the problem sees it
/// (`max(H) - H`).
pub fn gap_statistics(heights: &ndarray::Array2<f64>, grid: &surfgen::Grid) -> surfgen::Statistics {
    let top = heights.fold(f64::NEG_INFINITY, |m, &v| m.max(v));
    let g0 = heights.mapv(|v| top - v);
    surfgen::statistics(g0.view(), grid, true, None)
}
