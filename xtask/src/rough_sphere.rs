//! Rough spheres (Figs. 11-14): a rigid sphere R* = 100 um carrying a self-affine roughness,
//! pressed into an elastic flat (E* = 50 GPa) with a Lennard-Jones law (z0 = 0.3 nm) and
//! pulled off. The paper used its surface law; by default the point law stands in for it: on
//! the figures' grids (about a process zone a cell) the point law's pull-off is within 2-3 %
//! of its value on cells half as wide, the surface law's within 3-5 % and still several per
//! cent above the point law's there (its cell mean converges slowly on a rough contact's
//! steep edges), and the energy descent solves the point law 2.5 times faster than the flow
//! solves the surface law (`--rough-law surface` takes the paper's; docs/validation.md has
//! the measurements). Each figure draws the other law's points beside its own where their
//! runs have all finished ([`beside`]). The pull-off force is the most negative load of a
//! displacement-controlled unloading from a fixed preload
//! ([`solver::ContactProblem::pull_off`]).

use anyhow::{Context, Result};
use case::{Case, LawKind};
use std::f64::consts::PI;
use std::path::Path;

pub const RADIUS: f64 = 1e-4;
pub const MODULUS: f64 = 5e10;
pub const Z0: f64 = 0.3e-9;

/// The paper's works of adhesion [J/m^2] for its Tabor parameters 2, 5 and 7.
pub fn work_of_adhesion(mu: u32) -> f64 {
    match mu {
        2 => 0.075,
        5 => 0.29,
        7 => 0.48,
        _ => panic!("the paper's rough spheres have mu = 2, 5 or 7"),
    }
}

/// The exact Tabor parameter `(R w0^2 / (E*^2 z0^3))^(1/3)` of the paper's nominal `mu`.
pub fn tabor(mu: u32) -> f64 {
    theory::tabor_parameter(RADIUS, work_of_adhesion(mu), MODULUS, Z0)
}

/// The adhesive process-zone length \[m\] of the Lennard-Jones law at `mu`
/// ([`ljadhesion::AdhesionLaw::process_zone`]): the cell must not exceed it, or cells turn
/// bistable and the solution is neither mesh-converged nor, often, found.
pub fn process_zone(mu: u32) -> f64 {
    use ljadhesion::AdhesionLaw;
    ljadhesion::LennardJones::new(work_of_adhesion(mu), Z0)
        .map_or(f64::NAN, |lj| ljadhesion::PointLaw(lj).process_zone(MODULUS))
}

/// One rough sphere.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Job {
    /// Nominal Tabor parameter (2, 5, 7).
    pub mu: u32,
    /// RMS roughness \[z0\]; 0 for the smooth sphere.
    pub rq: f64,
    /// Short-wavelength cutoff \[m\].
    pub cutoff: f64,
    /// Hurst exponent of the roughness.
    pub hurst: f64,
    pub seed: u64,
    pub n: usize,
    /// Box side \[m\].
    pub length: f64,
    /// Outer tolerance (mean gap error \[z0\]).
    pub tolerance: f64,
    /// The point law (by the energy descent) or the surface law (by the flow).
    pub law: LawKind,
}

/// The roll-off wavelength [box sides]: half the box.
pub const ROLLOFF: f64 = 0.5;

/// The paper's Hurst exponent.
pub const HURST: f64 = 0.8;

#[derive(Clone, Debug)]
pub struct Outcome {
    /// Pull-off force \[N\] (positive: the tensile force needed).
    pub pull_off: f64,
    /// Measured RMS roughness \[m\], RMS gradient [-] of the roughness.
    pub rq: f64,
    pub rms_gradient: f64,
    /// Box side \[m\] and cutoff wavelength \[m\].
    pub length: f64,
    pub cutoff: f64,
    pub steps: usize,
    pub all_converged: bool,
    pub wall_time_s: f64,
}

impl Job {
    /// The smooth sphere of `mu` on an `n`^2 grid of side `length` \[m\].
    pub fn smooth(mu: u32, n: usize, length: f64, tolerance: f64, law: LawKind) -> Job {
        Job {
            mu,
            rq: 0.0,
            cutoff: 0.0,
            hurst: HURST,
            seed: 0,
            n,
            length,
            tolerance,
            law,
        }
    }

    pub fn w0(&self) -> f64 {
        work_of_adhesion(self.mu)
    }

    /// Preload approach \[z0\]: the smooth sphere's a0^2/(2R), plus three RMS roughnesses.
    pub fn preload(&self) -> f64 {
        jkr_radius(self.mu).powi(2) / (2.0 * RADIUS) / Z0 + 3.0 * self.rq
    }

    /// The pull-off scale pi R w0 \[N\].
    pub fn force_unit(&self) -> f64 {
        PI * RADIUS * self.w0()
    }

    pub fn case(&self) -> Case {
        let l = self.length;
        let mut c = Case {
            sphere_radius: Some(RADIUS),
            modulus: Some(MODULUS),
            law: Some(self.law),
            work_of_adhesion: Some(self.w0()),
            z0: Some(Z0),
            n: Some(self.n),
            length: Some(l),
            ..Case::default()
        };
        if self.rq > 0.0 {
            c.rms_height = Some(self.rq * Z0);
            c.hurst = Some(self.hurst);
            c.rolloff_wavelength = Some(ROLLOFF * l);
            c.cutoff_wavelength = Some(self.cutoff);
            c.seed = Some(self.seed);
        }
        c
    }

    /// The run's directory name in its study.
    fn name(&self) -> String {
        // The point law's runs keep the names they always had.
        let law = match self.law {
            LawKind::Point => String::new(),
            _ => format!("{}_", self.law.name()),
        };
        format!(
            "{law}mu{}_n{}_l{:.0}nm_rq{}_cutoff{:.0}nm_h{}_seed{}",
            self.mu,
            self.n,
            self.length * 1e9,
            self.rq,
            self.cutoff * 1e9,
            self.hurst,
            self.seed
        )
    }

    /// The run's case keys as a sweep of the command line's: in to the preload
    /// from two z0 apart in five steps, then the pull-off search: coarse unloading steps until
    /// the load has come back up from its minimum (or the sphere is far beyond the smooth
    /// sphere's pull-off distance), refined in fifths around it. The roughness is generated
    /// from the job's spectrum, or read from `surface` (heights \[m\] on the job's grid).
    pub fn keys(&self, surface: Option<&Path>) -> toml::Table {
        let top = self.preload();
        let scale = (PI * PI * self.w0().powi(2) * RADIUS / MODULUS.powi(2)).cbrt() / Z0;
        let mut keys = vec![
            ("sphere_radius", RADIUS.into()),
            ("modulus", MODULUS.into()),
            ("law", self.law.name().into()),
            ("solver", self.solver().into()),
            ("z0", Z0.into()),
            ("tolerance", self.tolerance.into()),
            ("max_iterations", 5000.into()),
            ("from", (-2.0 * Z0).into()),
            ("steps", 5.into()),
            // Unsplit steps, as the figures have always taken them.
            ("max_step", 1.0.into()),
            ("work_of_adhesion", self.w0().into()),
            ("n", (self.n as i64).into()),
            ("length", self.length.into()),
            ("to", (top * Z0).into()),
            ("pull_off_step", ((top / 8.0).max(0.5) * Z0).into()),
            (
                "pull_off_floor",
                (-(3.0 * scale + 3.0 * self.rq + 5.0) * Z0).into(),
            ),
        ];
        if let Some(path) = surface {
            keys.push(("surface", path.display().to_string().into()));
        } else if self.rq > 0.0 {
            let case = self.case();
            keys.extend([
                ("hurst", self.hurst.into()),
                ("rms_height", case.rms_height.expect("rough").into()),
                (
                    "rolloff_wavelength",
                    case.rolloff_wavelength.expect("rough").into(),
                ),
                ("cutoff_wavelength", case.cutoff_wavelength.expect("rough").into()),
                ("seed", (self.seed as i64).into()),
            ]);
        }
        keys.into_iter().map(|(k, v)| (k.to_string(), v)).collect()
    }

    /// The job as a run of the figures' studies (`OUT/studies/rough-spheres-rough` or
    /// `-smooth`).
    fn sweep(&self) -> crate::series::Sweep {
        crate::series::Sweep {
            study: format!("rough-spheres-{}", if self.rq > 0.0 { "rough" } else { "smooth" }),
            name: self.name(),
            keys: self.keys(None),
        }
    }

    /// The method: the energy descent for the laws with an energy, the flow for the surface
    /// law (which has none).
    fn solver(&self) -> &'static str {
        match self.law {
            LawKind::Surface | LawKind::Line => "flow",
            _ => "energy",
        }
    }

    /// What the run in `dir` found, from its summary.
    pub fn outcome(&self, dir: &Path) -> Result<Outcome> {
        let path = dir.join("summary.json");
        let text = std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
        let summary: serde_json::Value = serde_json::from_str(&text)?;
        let number = |k: &str| summary.get(k).and_then(serde_json::Value::as_f64);
        let (rms_gradient, rq) = if self.rq > 0.0 {
            let (g, _, rq, _) = crate::surface_statistics(&self.case())?;
            (g, rq)
        } else {
            (0.0, 0.0)
        };
        Ok(Outcome {
            // No tensile load on unloading: no pull-off force.
            pull_off: -number("pull_off_force").unwrap_or(0.0).min(0.0),
            rq,
            rms_gradient,
            length: self.length,
            cutoff: self.cutoff,
            steps: number("steps").context("the summary has no steps")? as usize,
            all_converged: summary.get("converged").and_then(serde_json::Value::as_bool) == Some(true),
            wall_time_s: number("wall_time_s").unwrap_or(0.0),
        })
    }
}

/// Mean and sample standard deviation.
pub fn mean_std(v: &[f64]) -> (f64, f64) {
    let n = v.len() as f64;
    let m = v.iter().sum::<f64>() / n;
    let s = if v.len() > 1 {
        (v.iter().map(|x| (x - m).powi(2)).sum::<f64>() / (n - 1.0)).sqrt()
    } else {
        0.0
    };
    (m, s)
}

/// The JKR contact radius at zero load of `mu`'s smooth sphere, (9 pi w0 R^2 / (2 E*))^(1/3)
/// \[m\]: sets the box.
pub fn jkr_radius(mu: u32) -> f64 {
    theory::jkr_dmt::jkr_zero_load_radius(RADIUS, work_of_adhesion(mu), MODULUS)
}

/// The smallest grid on a box of side `length` \[m\], from 32 cells on and with no prime
/// factor above 5 (cheap FFTs), whose cells are no larger than `mu`'s process zone.
pub fn needed_n(mu: u32, length: f64) -> usize {
    let needed = ((length / process_zone(mu)).ceil() as usize).max(32);
    (needed..)
        .find(|&n| {
            let mut m = n;
            for p in [2, 3, 5] {
                while m % p == 0 {
                    m /= p;
                }
            }
            m == 1
        })
        .expect("5-smooth numbers are unbounded")
}

/// The short cutoff \[cells of the coarsest grid\]: the roughness's shortest wavelength is
/// resolved on every Tabor parameter's grid.
pub const CUTOFF_CELLS: f64 = 4.0;

/// Settings shared by Figs. 11-14. Every Tabor parameter (set by the work of adhesion) sees
/// one roughness spectrum in physical units: one box ([`Plan::length`]), roll-off at half of
/// it, one cutoff ([`Plan::cutoff`]); only the grid, which must resolve each one's process
/// zone, differs.
pub struct Plan {
    /// Largest grid (cells per side); below it, the smallest FFT-friendly size whose cells
    /// resolve the process zone ([`Plan::n_for`]). Full mode: 512, which resolves mu = 2, 5
    /// and 7 (mu = 7 needs 450 cells a side); quick mode: 64, mu = 2 only.
    pub max_n: usize,
    pub seeds: Vec<u64>,
    /// RMS roughnesses \[z0\] of Figs. 11, 13, 14.
    pub rqs: Vec<f64>,
    /// Hurst exponents of Fig. 12 (at Rq = 2 z0): they set the RMS gradient.
    pub hursts: Vec<f64>,
    /// Outer tolerance \[z0\]: 1e-5 (the paper's 1e-6 stalls on some steps of these bistable
    /// problems and moves the pull-off by less than 1e-4 relative where both converge).
    pub tolerance: f64,
    /// The law (`Options::rough_law`).
    pub law: LawKind,
    /// The Tabor parameters of Figs. 11, 12 and 13-14: the paper's in full mode, mu = 2 only in
    /// quick mode. Those whose process zone `max_n` cannot resolve are not run
    /// ([`Plan::mus_run`]).
    pub mus: [Vec<u32>; 3],
}

pub fn plan(ctx: &crate::Context) -> Plan {
    Plan::new(ctx.quick(), ctx.options.rough_law)
}

impl Plan {
    /// The plan of quick mode (`quick`) or of full mode, with `law`.
    pub fn new(quick: bool, law: LawKind) -> Plan {
        Plan {
            max_n: if quick { 64 } else { 512 },
            seeds: if quick { vec![1, 2] } else { (1..=10).collect() },
            rqs: vec![0.0, 1.0, 2.0, 4.0, 8.0],
            hursts: if quick {
                vec![0.8, 0.5, 0.2]
            } else {
                vec![0.8, 0.6, 0.4, 0.2]
            },
            tolerance: 1e-5,
            law,
            mus: if quick {
                [vec![2], vec![2], vec![2]]
            } else {
                [vec![2, 5], vec![5, 7], vec![2, 5, 7]]
            },
        }
    }

    /// Figure `number`'s Tabor parameters (11 to 14).
    fn mus_of(&self, number: u32) -> &[u32] {
        &self.mus[match number {
            11 => 0,
            12 => 1,
            _ => 2,
        }]
    }

    /// Figure `number`'s Tabor parameters that are run: those whose cells resolve the process
    /// zone within `max_n`. Coarser cells trap the contact edge and overstate the pull-off by
    /// more than the trends the figures look for (smooth mu = 5: 1.85 pi R w0 on 128^2 cells of
    /// 1.7 zones, 1.545 on 256^2; mu = 7 on 256^2, 1.7 zones: 11-22 % above 384^2).
    pub fn mus_run(&self, number: u32) -> Vec<u32> {
        self.mus_of(number)
            .iter()
            .copied()
            .filter(|&mu| self.resolves(mu))
            .collect()
    }

    fn resolves(&self, mu: u32) -> bool {
        needed_n(mu, self.length()) <= self.max_n
    }

    /// The grid for `mu`: [`needed_n`] up to `max_n`.
    pub fn n_for(&self, mu: u32) -> usize {
        needed_n(mu, self.length()).min(self.max_n)
    }

    /// The plan's Tabor parameters, least sticky first.
    fn all_mus(&self) -> Vec<u32> {
        let mut all: Vec<u32> = self.mus.concat();
        all.sort_unstable();
        all.dedup();
        all
    }

    /// The box side \[m\]: 3.5 zero-load JKR radii of the stickiest Tabor parameter of the plan,
    /// whose contact is the widest; at the preload the undeformed gap at the box's edge is then
    /// more than ten z0 for every one.
    pub fn length(&self) -> f64 {
        3.5 * jkr_radius(*self.all_mus().last().expect("the plan has Tabor parameters"))
    }

    /// The short cutoff wavelength \[m\]: [`CUTOFF_CELLS`] cells of the coarsest grid, that of
    /// the least sticky Tabor parameter (the widest process zone).
    pub fn cutoff(&self) -> f64 {
        CUTOFF_CELLS * self.length() / self.n_for(self.all_mus()[0]) as f64
    }

    /// How well each of `mus` is resolved, for the reports.
    pub fn resolution(&self, mus: &[u32]) -> String {
        mus.iter()
            .map(|&mu| {
                let n = self.n_for(mu);
                let cell = self.length() / n as f64;
                format!(
                    "μ = {mu}: {n}² cells of {:.1} nm, {:.2} process zones (E* w0/σ0² = {:.1} nm)",
                    cell * 1e9,
                    cell / process_zone(mu),
                    process_zone(mu) * 1e9
                )
            })
            .collect::<Vec<_>>()
            .join("; ")
    }
}

/// What a point of a pull-off figure asks for: a Tabor parameter and a roughness, realised
/// over the plan's seeds.
#[derive(Clone, Copy, Debug)]
pub struct Spec {
    /// Nominal Tabor parameter (2, 5, 7).
    pub mu: u32,
    /// RMS roughness \[z0\]; 0 for the smooth sphere.
    pub rq: f64,
    /// Hurst exponent.
    pub hurst: f64,
}

impl Spec {
    /// Roughness `rq` \[z0\] of the paper's Hurst exponent (Figs. 11, 13, 14).
    pub fn new(mu: u32, rq: f64) -> Spec {
        Spec { mu, rq, hurst: HURST }
    }
}

/// The jobs of one point: one per seed (one only when smooth).
pub fn realisations(plan: &Plan, spec: Spec) -> Vec<Job> {
    let rough = spec.rq > 0.0;
    let seeds: &[u64] = if rough { &plan.seeds } else { &[0] };
    let smooth = Job::smooth(
        spec.mu,
        plan.n_for(spec.mu),
        plan.length(),
        plan.tolerance,
        plan.law,
    );
    seeds
        .iter()
        .map(|&seed| {
            if rough {
                Job {
                    rq: spec.rq,
                    cutoff: plan.cutoff(),
                    hurst: spec.hurst,
                    seed,
                    ..smooth
                }
            } else {
                smooth
            }
        })
        .collect()
}

/// A point of a pull-off figure: its jobs' outcomes.
pub struct Point {
    pub spec: Spec,
    pub outcomes: Vec<Outcome>,
    pub job: Job,
}

impl Point {
    /// Pull-off / (pi R w0): mean and standard deviation over the realisations.
    pub fn pull_off(&self) -> (f64, f64) {
        let v: Vec<f64> = self
            .outcomes
            .iter()
            .map(|o| o.pull_off / self.job.force_unit())
            .collect();
        mean_std(&v)
    }

    /// The standard error of the mean pull-off [pi R w0] over the realisations.
    pub fn standard_error(&self) -> f64 {
        self.pull_off().1 / (self.outcomes.len() as f64).sqrt()
    }

    pub fn mean(&self, f: impl Fn(&Outcome) -> f64) -> f64 {
        self.outcomes.iter().map(f).sum::<f64>() / self.outcomes.len() as f64
    }
}

/// The jobs of `wanted`'s realisations and of every point the figures being built ask for,
/// each once, and their sweeps.
pub fn sweeps(ctx: &crate::Context, wanted: &[Spec]) -> (Vec<Job>, Vec<crate::series::Sweep>) {
    let plan = plan(ctx);
    let mut jobs: Vec<Job> = Vec::new();
    for job in crate::rough_sphere_specs(ctx)
        .iter()
        .chain(wanted)
        .flat_map(|&s| realisations(&plan, s))
    {
        if !jobs.contains(&job) {
            jobs.push(job);
        }
    }
    let sweeps = jobs.iter().map(Job::sweep).collect();
    (jobs, sweeps)
}

/// The outcomes of `wanted`'s realisations. Every job of the figures being built runs in two
/// studies (`OUT/studies/rough-spheres-smooth` and `-rough`), the first time a figure asks;
/// later figures find their runs finished.
pub fn points(ctx: &crate::Context, wanted: &[Spec]) -> Result<Vec<Point>> {
    let plan = plan(ctx);
    let (jobs, sweeps) = sweeps(ctx, wanted);
    let dirs = crate::series::run(&ctx.options.out.join("studies"), &sweeps)?;
    let found: Vec<(Job, Outcome)> = jobs
        .iter()
        .zip(&dirs)
        .map(|(j, d)| Ok((*j, j.outcome(d)?)))
        .collect::<Result<_>>()?;
    let outcome = |job: &Job| {
        found
            .iter()
            .find(|(j, _)| j == job)
            .map(|(_, o)| o.clone())
            .expect("every job ran")
    };
    Ok(wanted
        .iter()
        .map(|&spec| {
            let jobs = realisations(&plan, spec);
            Point {
                spec,
                outcomes: jobs.iter().map(outcome).collect(),
                job: jobs[0],
            }
        })
        .collect())
}

/// The other law than the plan's: the surface law beside the point law, the point law beside
/// the surface law.
fn other(law: LawKind) -> LawKind {
    match law {
        LawKind::Point => LawKind::Surface,
        _ => LawKind::Point,
    }
}

/// The points of `specs` by the other law than the plan's whose realisations have all
/// finished in `OUT/studies` (left by an earlier build with that `--rough-law`, or by
/// `roughcontact study` by hand); none is run here, so a figure draws them beside its own
/// only once whole.
pub fn beside(ctx: &crate::Context, specs: &[Spec]) -> Result<Vec<Point>> {
    let plan = Plan::new(ctx.quick(), other(ctx.options.rough_law));
    let studies = ctx.options.out.join("studies");
    let mut points = Vec::new();
    for &spec in specs {
        let jobs = realisations(&plan, spec);
        let sweeps: Vec<_> = jobs.iter().map(Job::sweep).collect();
        let Some(dirs) = crate::series::finished(&studies, &sweeps)
            .into_iter()
            .collect::<Option<Vec<_>>>()
        else {
            continue;
        };
        let outcomes = jobs
            .iter()
            .zip(&dirs)
            .map(|(j, d)| j.outcome(d))
            .collect::<Result<_>>()?;
        points.push(Point {
            spec,
            outcomes,
            job: jobs[0],
        });
    }
    Ok(points)
}

/// The law and its method as the figures' legends and reports name them.
fn law_words(law: LawKind) -> &'static str {
    match law {
        LawKind::Point => "point law (by the energy descent)",
        _ => "surface law (Eq. 11, by the flow)",
    }
}

/// `", the <other law> N %"`: the other law's spread for a verdict, or nothing while its
/// points are not all finished.
pub fn other_words(ctx: &crate::Context, spread: Option<f64>) -> String {
    spread.map_or(String::new(), |s| {
        format!(
            ", the {} {:.0} %",
            law_words(other(ctx.options.rough_law)),
            100.0 * s
        )
    })
}

/// Where a falling curve `(x, y)` (sorted by x) first drops to `level`, by linear
/// interpolation.
pub fn crossing(curve: &[(f64, f64)], level: f64) -> Option<f64> {
    curve.windows(2).find_map(|w| {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        (y0 >= level && y1 < level).then(|| x0 + (level - y0) / (y1 - y0) * (x1 - x0))
    })
}

/// Whether `y` falls with `x`: each point at or below its predecessor within `slack` (the
/// scatter between realisations), and the last below the first.
pub fn falling(curve: &[(f64, f64)], slack: f64) -> bool {
    curve.windows(2).all(|w| w[1].1 <= w[0].1 + slack)
        && curve.last().map(|l| l.1) < curve.first().map(|f| f.1)
}

/// The points of Tabor parameter `mu` as `(x, y) = f(point)`, sorted by x.
pub fn curve_of(points: &[Point], mu: u32, f: impl Fn(&Point) -> (f64, f64)) -> Vec<(f64, f64)> {
    let mut c: Vec<(f64, f64)> = points.iter().filter(|p| p.spec.mu == mu).map(f).collect();
    c.sort_by(|a, b| a.0.total_cmp(&b.0));
    c
}

/// A Tabor parameter's curve `(x, mean pull-off / (pi R w0))`, sorted by x.
pub type MuCurve = (u32, Vec<(f64, f64)>);

/// What [`PullOffFigure::draw`] leaves for a figure's own verdict.
pub struct Drawn {
    pub report: crate::FigureReport,
    /// The plan's law's curves, one a Tabor parameter.
    pub curves: Vec<MuCurve>,
    /// The other law's [`largest_spread`], where the figure claims a collapse and the other
    /// law's points are all finished.
    pub other_spread: Option<f64>,
}

/// The common part of Figs. 11-14: per Tabor parameter a curve `x -> pull-off / (pi R w0)`
/// with error bars over the realisations, drawn and tabulated.
pub struct PullOffFigure<'a> {
    pub number: u32,
    pub title: &'a str,
    pub x_label: &'a str,
    pub x_name: &'a str,
    pub x_log: bool,
    pub legend: crate::plot::Legend,
    /// Whether the y axis makes room for the legend (where it would cover points).
    pub legend_room: bool,
    /// Whether the figure claims that its abscissa collapses the Tabor parameters' curves:
    /// then the other law's spread ([`largest_spread`]) is reported too, once it is whole.
    pub collapse: bool,
}

impl PullOffFigure<'_> {
    /// Draws `points` grouped by mu, at `x(point)`, with the other law's finished points
    /// beside them.
    pub fn draw(
        &self,
        ctx: &crate::Context,
        points: &[Point],
        x: impl Fn(&Point) -> f64,
        extra: Vec<crate::plot::Curve>,
    ) -> Result<Drawn> {
        use crate::plot::{Chart, Curve, Mark};
        let mut report = crate::FigureReport::new(self.number, self.title);
        let mut chart = Chart::new(self.title, self.x_label, "pull-off force F/(πRw0)");
        chart.x_log = self.x_log;
        chart.legend = self.legend;
        chart.legend_room = self.legend_room;
        chart.curves = extra;
        let mut mus: Vec<u32> = points.iter().map(|p| p.spec.mu).collect();
        mus.dedup();
        let mut curves = Vec::new();
        for &mu in &mus {
            // A point is converged when every realisation's sweep is.
            let mut pts: Vec<(f64, f64, f64, bool)> = points
                .iter()
                .filter(|p| p.spec.mu == mu)
                .map(|p| {
                    let all = p.outcomes.iter().all(|o| o.all_converged);
                    (x(p), p.pull_off().0, p.standard_error(), all)
                })
                .collect();
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let color = crate::tabor_colour(mu as f64);
            chart.curves.push(Curve::solved(
                format!(
                    "μ = {mu} (w0 = {} J/m²), {}: mean ± standard error",
                    work_of_adhesion(mu),
                    law_words(ctx.options.rough_law)
                ),
                pts.iter().map(|p| (p.0, p.1, p.3)).collect(),
                Mark::ErrorBars(pts.iter().map(|p| p.2).collect()),
                color,
            ));
            chart.curves.push(Curve::new(
                "",
                pts.iter().map(|p| (p.0, p.1)).collect(),
                Mark::Line,
                color,
            ));
            curves.push((mu, pts.iter().map(|p| (p.0, p.1)).collect()));
        }
        let plan = plan(ctx);
        let specs: Vec<Spec> = points.iter().map(|p| p.spec).collect();
        let beside = beside(ctx, &specs)?;
        let other = other(plan.law);
        let mut beside_curves = Vec::new();
        for &mu in &mus {
            let mut pts: Vec<(f64, f64, bool)> = beside
                .iter()
                .filter(|p| p.spec.mu == mu)
                .map(|p| (x(p), p.pull_off().0, p.outcomes.iter().all(|o| o.all_converged)))
                .collect();
            if pts.is_empty() {
                continue;
            }
            pts.sort_by(|a, b| a.0.total_cmp(&b.0));
            let color = crate::tabor_colour(mu as f64);
            chart.curves.push(Curve::solved(
                format!("μ = {mu}, {}: mean", law_words(other)),
                pts.clone(),
                Mark::Triangles,
                color,
            ));
            chart.curves.push(Curve::new(
                "",
                pts.iter().map(|p| (p.0, p.1)).collect(),
                Mark::Dashed,
                color,
            ));
            beside_curves.push(pts.iter().map(|p| (p.0, p.1)).collect::<Vec<_>>());
        }
        report.solver_seconds += points
            .iter()
            .flat_map(|p| &p.outcomes)
            .map(|o| o.wall_time_s)
            .sum::<f64>();
        report.save(&[chart], &ctx.options.out, &format!("fig{}", self.number))?;
        let mut other_spread = None;
        let stem = format!("fig{}", self.number);
        report.tables.extend(self.tables(&stem, &plan, points, &x));
        if !beside.is_empty() {
            let stem = format!("fig{}_{}_law", self.number, other.name());
            report
                .tables
                .extend(self.tables(&stem, &Plan::new(ctx.quick(), other), &beside, &x));
            report
                .agreement
                .push(Self::compared(points, &beside, plan.law, other));
            let whole = beside.len() == points.len() && beside_curves.len() > 1;
            other_spread = largest_spread(&beside_curves).filter(|_| self.collapse && whole);
            if let Some(spread) = other_spread {
                report.agreement.push(format!(
                    "Spread of the {} between the Tabor parameters (the same measure): {:.0} % at equal {}.",
                    law_words(other),
                    100.0 * spread,
                    self.x_label
                ));
            }
        }
        report.computed.extend(self.described(ctx, &plan, points, &mus));
        Ok(Drawn {
            report,
            curves,
            other_spread,
        })
    }

    /// What the figure computed, in words: the sphere, the law, the spectrum, the grids, what
    /// was not run and the pull-off search.
    fn described(&self, ctx: &crate::Context, plan: &Plan, points: &[Point], mus: &[u32]) -> Vec<String> {
        let mut computed = Vec::new();
        computed.push(format!(
        "Rigid sphere R* = 100 µm with self-affine roughness (H = 0.8 unless said otherwise, Rq as on the axis) on \
         a free grid, E* = 50 GPa, z0 = 0.3 nm, {}, tolerance {:e} z0; {} seeds per rough point (error bars: ± one \
         standard error of the mean; each realisation's pull-off in fig{}_realisations.csv).",
        match plan.law {
            LawKind::Point => "Lennard-Jones point law solved by the energy descent (on cells of a process zone \
                           within 2-3 % of its pull-off on cells half as wide, the paper's surface law 3-5 % \
                           from its own, and that by the flow, `--rough-law surface`, 2.5 times as long: \
                           docs/validation.md)",
            _ => "the paper's Lennard-Jones surface law (Eq. 11) solved by the flow",
        },
        plan.tolerance,
        plan.seeds.len(),
        self.number,
    ));
        computed.push(format!(
        "One roughness spectrum for every Tabor parameter (μ set by w0 alone): box {:.3} µm (3.5 zero-load JKR \
         radii of μ = {}), roll-off at half the box, short cutoff {:.1} nm ({CUTOFF_CELLS} cells of the coarsest \
         grid). Grids: {}.",
        plan.length() * 1e6,
        plan.all_mus().last().expect("the plan has Tabor parameters"),
        plan.cutoff() * 1e9,
        plan.resolution(mus)
    ));
        let skipped: Vec<String> = plan
            .mus_of(self.number)
            .iter()
            .filter(|mu| !mus.contains(mu))
            .map(|&mu| format!("μ = {mu} (needs {}² cells)", needed_n(mu, plan.length())))
            .collect();
        if !skipped.is_empty() {
            computed.push(format!(
            "Not run: {}, above this mode's cap of {}² cells; coarser cells trap the contact edge and overstate the pull-off by \
             more than the trends sought (μ = 7 on 256² cells, 1.7 process zones: 11-22 % above 384²).",
            skipped.join(", "),
            plan.max_n
        ));
        }
        if ctx.quick() {
            computed.push(
            "Quick mode: Tabor parameter 2 only (the paper's μ = 5 and 7 need minutes per run); full mode runs \
             the paper's values."
                .into(),
        );
        }
        computed.push(
        "Pull-off: displacement-controlled cycle, preloaded to the smooth sphere's a0²/(2R) plus 3 Rq, unloaded \
         in eighths of the preload until the load has risen back to half its minimum, then refined in \
         fifths of a step around the minimum; pull-off force = - the most negative load."
            .into(),
    );
        let failed: usize = points
            .iter()
            .flat_map(|p| &p.outcomes)
            .filter(|o| !o.all_converged)
            .count();
        if failed > 0 {
            computed.push(format!(
                "{failed} run(s) had a step that did not converge (see the CSV)."
            ));
        }
        computed
    }

    /// The tables `stem.csv` (a row a point) and `stem_realisations.csv` (a row a realisation)
    /// of `points`, realised by `plan`.
    fn tables(
        &self,
        stem: &str,
        plan: &Plan,
        points: &[Point],
        x: &impl Fn(&Point) -> f64,
    ) -> [crate::Table; 2] {
        let mut table = crate::Table::new(
            stem.to_string(),
            &[
                "mu",
                "rq_nominal_z0",
                "hurst",
                self.x_name,
                "pull_off_pi_r_w0",
                "std_pi_r_w0",
                "standard_error_pi_r_w0",
                "realisations",
                "all_converged",
            ],
        );
        let mut each = crate::Table::new(
            format!("{stem}_realisations"),
            &[
                "mu",
                "rq_nominal_z0",
                "hurst",
                "seed",
                self.x_name,
                "rq_measured_nm",
                "rms_gradient_measured",
                "pull_off_pi_r_w0",
                "converged",
            ],
        );
        for p in points {
            let (m, s) = p.pull_off();
            let (mu, rq, roughness) = (p.spec.mu as f64, p.spec.rq, p.spec.hurst);
            table.push(vec![
                mu,
                rq,
                roughness,
                x(p),
                m,
                s,
                p.standard_error(),
                p.outcomes.len() as f64,
                p.outcomes.iter().all(|o| o.all_converged) as u8 as f64,
            ]);
            for (job, o) in realisations(plan, p.spec).iter().zip(&p.outcomes) {
                each.push(vec![
                    mu,
                    rq,
                    roughness,
                    job.seed as f64,
                    x(p),
                    o.rq * 1e9,
                    o.rms_gradient,
                    o.pull_off / job.force_unit(),
                    o.all_converged as u8 as f64,
                ]);
            }
        }
        [table, each]
    }

    /// The report's line on the other law's points beside the figure's own: per Tabor
    /// parameter, how many are whole and their pull-off over the figure's law's, realisation
    /// by realisation (the same surfaces).
    fn compared(points: &[Point], beside: &[Point], own: LawKind, other: LawKind) -> String {
        let mut mus: Vec<u32> = points.iter().map(|p| p.spec.mu).collect();
        mus.dedup();
        let parts: Vec<String> = mus
            .iter()
            .map(|&mu| {
                let ratios: Vec<f64> = points
                    .iter()
                    .filter(|p| p.spec.mu == mu)
                    .filter_map(|p| {
                        let b = beside.iter().find(|b| {
                            b.spec.mu == mu && b.spec.rq == p.spec.rq && b.spec.hurst == p.spec.hurst
                        })?;
                        let pairs: Vec<f64> = p
                            .outcomes
                            .iter()
                            .zip(&b.outcomes)
                            .filter(|(a, _)| a.pull_off > 0.0)
                            .map(|(a, b)| b.pull_off / a.pull_off)
                            .collect();
                        (!pairs.is_empty()).then(|| mean_std(&pairs).0)
                    })
                    .collect();
                let wanted = points.iter().filter(|p| p.spec.mu == mu).count();
                if ratios.is_empty() {
                    format!("μ = {mu}: 0 of {wanted} points")
                } else {
                    let (lo, hi) = ratios
                        .iter()
                        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &r| {
                            (a.min(r), b.max(r))
                        });
                    match ratios.len() {
                        1 => format!("μ = {mu}: 1 of {wanted} points, {lo:.3}"),
                        k => format!("μ = {mu}: {k} of {wanted} points, {lo:.3} to {hi:.3}"),
                    }
                }
            })
            .collect();
        format!(
            "Beside it (triangles, dashed lines): the {} at every point whose realisations have all finished (not \
             run by this build; `--rough-law {}` runs them), on the same surfaces; its pull-off over the {} \
             law's, seed by seed, averaged a point: {}.",
            law_words(other),
            other.name(),
            own.name(),
            parts.join("; "),
        )
    }
}

/// How [`largest_spread`] measures the collapse of curves, for the reports.
pub const SPREAD: &str = "largest (max - min) / mean of the curves over the range of the abscissa they all cover, \
                          at 16 points evenly in its logarithm";

/// `curve`'s value at `x`, linear in `ln x` between its points (sorted by x, x > 0); `None`
/// outside them.
pub fn at_log(curve: &[(f64, f64)], x: f64) -> Option<f64> {
    curve.windows(2).find_map(|w| {
        let ((x0, y0), (x1, y1)) = (w[0], w[1]);
        (x0 > 0.0 && x0 <= x && x <= x1).then(|| {
            let t = if x1 > x0 {
                (x / x0).ln() / (x1 / x0).ln()
            } else {
                0.0
            };
            y0 + t * (y1 - y0)
        })
    })
}

/// The largest `(max - min) / mean` of the curves' values over the x range they all cover,
/// sampled at 16 points evenly in `ln x`; `None` when they share no range.
pub fn largest_spread(curves: &[Vec<(f64, f64)>]) -> Option<f64> {
    let positive = |c: &Vec<(f64, f64)>| c.iter().map(|p| p.0).filter(|&x| x > 0.0).collect::<Vec<_>>();
    let lo = curves
        .iter()
        .map(|c| positive(c).into_iter().fold(f64::INFINITY, f64::min))
        .fold(0.0, f64::max);
    let hi = curves
        .iter()
        .map(|c| positive(c).into_iter().fold(0.0, f64::max))
        .fold(f64::INFINITY, f64::min);
    if !(lo > 0.0 && hi > lo) {
        return None;
    }
    (0..16)
        .map(|k| {
            let x = lo * (hi / lo).powf(k as f64 / 15.0);
            let ys: Vec<f64> = curves.iter().filter_map(|c| at_log(c, x)).collect();
            let mean = ys.iter().sum::<f64>() / ys.len() as f64;
            let (min, max) = ys.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &y| {
                (a.min(y), b.max(y))
            });
            (max - min) / mean
        })
        .reduce(f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_papers_works_give_its_tabor_parameters() {
        for (mu, expected) in [(2, 2.0), (5, 5.0), (7, 7.0)] {
            assert!((tabor(mu) / expected - 1.0).abs() < 0.02, "{mu}: {}", tabor(mu));
        }
    }

    #[test]
    fn crossing_and_falling() {
        let c = [(0.0, 1.5), (1.0, 1.0), (2.0, 0.5)];
        assert_eq!(crossing(&c, 0.75), Some(1.5));
        assert_eq!(crossing(&c, 2.0), None);
        assert!(falling(&c, 0.0));
        assert!(!falling(&[(0.0, 1.0), (1.0, 1.1)], 0.05));
        // Small rises within the slack that add up to a rise are not a fall.
        assert!(!falling(&[(0.0, 1.0), (1.0, 1.01), (2.0, 1.02)], 0.02));
        assert_eq!(mean_std(&[1.0, 3.0]), (2.0, 2f64.sqrt()));
    }

    #[test]
    fn one_spectrum_on_grids_that_resolve_each_process_zone_up_to_the_cap() {
        let plan = Plan {
            max_n: 400,
            seeds: vec![1],
            rqs: vec![],
            hursts: vec![],
            tolerance: 1e-5,
            law: LawKind::Point,
            mus: [vec![2, 5], vec![5, 7], vec![2, 5, 7]],
        };
        // The box of the stickiest: mu = 7's contact is the widest.
        let l = plan.length();
        assert_eq!(l, 3.5 * jkr_radius(7));
        assert!(jkr_radius(7) > jkr_radius(5) && jkr_radius(5) > jkr_radius(2));
        for mu in [2, 5, 7] {
            let n = needed_n(mu, l);
            assert!(l / n as f64 <= process_zone(mu), "{mu}");
            // Every smaller size from 32 on that resolves it has a prime factor above 5.
            let five_smooth = |m: usize| {
                [2, 3, 5].iter().fold(m, |m, p| {
                    let mut m = m;
                    while m % p == 0 {
                        m /= p;
                    }
                    m
                }) == 1
            };
            assert!(
                (32..n).all(|m| l / m as f64 > process_zone(mu) || !five_smooth(m)),
                "{mu}: {n} is not the smallest"
            );
        }
        assert_eq!([needed_n(2, l), needed_n(5, l), needed_n(7, l)], [72, 270, 450]);
        assert_eq!(needed_n(2, 1e-9), 32);
        // mu = 7 needs more than the cap: not run, and the grids of the others as needed.
        assert_eq!(plan.n_for(5), 270);
        assert_eq!(plan.mus_run(12), vec![5]);
        assert_eq!(plan.mus_run(13), vec![2, 5]);
        // The cutoff is four cells of mu = 2's grid, the coarsest, on every grid.
        assert_eq!(plan.cutoff(), 4.0 * l / 72.0);
        let jobs = realisations(&plan, Spec::new(5, 2.0));
        assert!(
            jobs.iter()
                .all(|j| j.length == l && j.cutoff == plan.cutoff() && j.n == 270)
        );
    }

    #[test]
    fn the_surface_law_runs_by_the_flow_under_a_name_of_its_own() {
        let point = Job::smooth(5, 64, 1e-6, 1e-5, LawKind::Point);
        let surface = Job {
            law: LawKind::Surface,
            ..point
        };
        let keys = |j: &Job| (j.keys(None)["law"].clone(), j.keys(None)["solver"].clone());
        assert_eq!(keys(&point), ("point".into(), "energy".into()));
        assert_eq!(keys(&surface), ("surface".into(), "flow".into()));
        assert_ne!(point.name(), surface.name());
        assert_eq!(surface.case().law, Some(LawKind::Surface));
    }

    #[test]
    fn spread_at_equal_abscissa() {
        let a = vec![(1.0, 2.0), (4.0, 1.0)];
        // Linear in ln x: halfway in the logarithm at x = 2.
        assert!((at_log(&a, 2.0).unwrap() - 1.5).abs() < 1e-12);
        assert_eq!(at_log(&a, 8.0), None);
        // Identical curves do not spread; a curve twice as high spreads by 2/3 of the mean.
        assert_eq!(largest_spread(&[a.clone(), a.clone()]), Some(0.0));
        let b: Vec<(f64, f64)> = a.iter().map(|&(x, y)| (x, 2.0 * y)).collect();
        assert!((largest_spread(&[a.clone(), b]).unwrap() - 2.0 / 3.0).abs() < 1e-12);
        // Disjoint ranges share nothing.
        assert_eq!(largest_spread(&[a, vec![(5.0, 1.0), (6.0, 1.0)]]), None);
    }
}
