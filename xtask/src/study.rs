//! `cargo xtask study NAME`: studies that print the tables of `docs/validation.md` (mesh
//! refinement and the like). They assert nothing and take minutes to hours, so they are not
//! tests; each prints a Markdown table to stdout.

use crate::sphere::{MODULUS, RADIUS, Z0};
use anyhow::{Context, Result, bail};
use ljadhesion::{AdhesionLaw, LennardJones, LineLaw, PointLaw, SurfaceLaw};
use solver::{ContactProblem, Control, CyclePoint, Method, Settings, summarize};
use std::f64::consts::PI;
use std::time::Instant;

/// The studies, by name, with what each shows.
pub const STUDIES: [(&str, &str); 10] = [
    (
        "pull-off-mesh",
        "a sphere's pull-off at mu = 1 against the cell size, point, line, surface and surface-energy laws (minutes)",
    ),
    (
        "high-tabor-mesh",
        "a sphere's pull-off at mu = 10 against the cell size, point law (MESH=128,256,512; 512 takes ~40 min)",
    ),
    (
        "nested-start",
        "non-adhesive CG iterations from a cold start and from the solution of the grid twice as coarse, \
         recursively (SIZES=512,1024,2048; PRESSURE=0.04)",
    ),
    (
        "challenge-mesh",
        "the contact-mechanics challenge's load cycle, relative contact area against the cell size for the \
         surface, line, point and exponential laws (and `none`), one surface sampled on every grid, each run a \
         resumable sweep in target/challenge-mesh or DIR (SIZES=256,512,1024; LAWS=...; METHOD=auto; TOLERANCE=...; \
         REFINE=k; TABOR=mu, w0 set for it by the surface's RMS curvature as Fig. 10, else the challenge's 0.05 J/m^2; \
         FINEST=n, the grid the surface is made on, default the largest size, finer sizes interpolated; \
         CUT=n, the grid of whose cells four make the short cut-off, default the smallest size)",
    ),
    (
        "rough-sphere-mesh",
        "the pull-off of a rough sphere of Figs. 11-14 (mu = 5, Rq = 2 z0) against the cell size, point and \
         surface laws, one surface sampled on every grid (SIZES=90,135,270,540; LAWS=point,surface; SEEDS=1; \
         an hour or more)",
    ),
    (
        "plastic-rough",
        "elastic and plastic areas of a self-affine surface under a hardness against load, beside Persson's \
         elastoplastic theory, with the iterations against the elastic solve's (N=1024; minutes)",
    ),
    (
        "rate-pull-off",
        "the pull-off of a Lennard-Jones sphere (mu = 1 and 5) on a standard linear solid (E0 = 10 E_inf) \
         against the speed it is pressed in and drawn back at, 1e-3 to 1e3 z0 per relaxation time, beside the \
         relaxed and glassy elastic spheres, with the cycle's loss split into viscous and adhesive when the path \
         returns to its start (MU=1,5; STEP=0.5 z0; FROM=20 z0 apart; an hour)",
    ),
    (
        "rate-retraction",
        "a Lennard-Jones sphere, smooth and rough, on a standard linear solid (E0 = 10 E_inf), pressed in \
         relaxed and drawn back at 1e-3 to 1e2 z0 per relaxation time, beside Greenwood & Johnson's and Persson \
         & Brener's effective adhesion; writes the figure (MU=1; RQ=1 z0; STEP=0.5 z0; \
         FIGURE=docs/figures/rate-retraction; minutes at mu = 1, hours at 5)",
    ),
    (
        "friction-rough",
        "partial slip of a rough Lennard-Jones contact (Rq = 2 z0, w0 = 0.05 E* z0) at three depths under a growing \
         shear, Coulomb's mu = 0.3 alone and with a shear strength of 0.02 E*: static friction and stick area \
         against the shear; writes the figure (N=256; FIGURE=docs/figures/friction-rough; a minute)",
    ),
    (
        "plastic-pull-off",
        "the pull-off of a Lennard-Jones sphere (mu = 5) loaded past yield, against the depth and the hardness, \
         beside the elastic sphere's and Mesarovic & Johnson's flattened sphere (N=256; HALF=256 z0; \
         DEPTHS=5,10,20 z0; HARDNESS=0.025,0.05,0.1 E*; half an hour)",
    ),
];

/// Runs the study `name`.
pub fn run(name: &str) -> Result<()> {
    match name {
        "pull-off-mesh" => pull_off_mesh(),
        "high-tabor-mesh" => high_tabor_mesh(),
        "nested-start" => nested_start(),
        "challenge-mesh" => challenge_mesh(),
        "rough-sphere-mesh" => rough_sphere_mesh(),
        "plastic-rough" => crate::plastic::plastic_rough(),
        "plastic-pull-off" => crate::plastic::plastic_pull_off(),
        "rate-pull-off" => crate::viscoelastic::rate_pull_off(),
        "rate-retraction" => crate::viscoelastic::rate_retraction(),
        "friction-rough" => crate::friction::friction_rough(),
        _ => {
            let names: Vec<_> = STUDIES.iter().map(|(n, _)| *n).collect();
            bail!("unknown study `{name}`; the studies are {}", names.join(", "))
        }
    }
}

/// Writes `chart` to `figure` (a path without extension: `.png` and `.svg`), making its
/// directory.
pub(crate) fn save_figure(chart: &plot::Chart, figure: &str) -> Result<()> {
    let path = std::path::Path::new(figure);
    let dir = path.parent().unwrap_or(std::path::Path::new("."));
    std::fs::create_dir_all(dir)?;
    let stem = path.file_name().and_then(|s| s.to_str()).unwrap_or("figure");
    chart.save(dir, stem)
}

/// `w0` [J/m^2] of the smooth sphere (R, E*, z0 of [`crate::sphere`]) at Tabor parameter
/// `mu`: `mu^3 = R w0^2 / (E*^2 z0^3)`.
pub(crate) fn work_of_adhesion(mu: f64) -> f64 {
    (mu.powi(3) / (RADIUS / Z0)).sqrt() * MODULUS * Z0
}

/// The smooth sphere on a free grid of `n^2` cells spanning `2 half_width` z0, under `law`.
fn sphere(n: usize, half_width: f64, law: impl AdhesionLaw + 'static) -> Result<ContactProblem> {
    let side = 2.0 * half_width * Z0;
    Ok(ContactProblem::builder()
        .grid(n, n, side, side)
        .sphere(RADIUS)
        .modulus(MODULUS)
        .law(law)
        .build()?)
}

fn approaches(values: impl Iterator<Item = f64>) -> Vec<Control> {
    values.map(|a| Control::Approach(a * Z0)).collect()
}

/// Mesh refinement of the pull-off (mu = 1, R = 1000 z0, box 200 z0 wide) for the four
/// Lennard-Jones laws, by the accelerated loop.
fn pull_off_mesh() -> Result<()> {
    let (mu, half_width) = (1.0, 100.0);
    let w0 = work_of_adhesion(mu);
    let lj = LennardJones::new(w0, Z0)?;
    let g =
        theory::greenwood::Greenwood::new(mu, theory::greenwood::Mesh::default()).curve(5.0, 1.0, 0.01)?;
    println!("Greenwood's pull-off {:.4} (2 pi R w0)", g.pull_off_load_control);
    println!("| cells | cell / z0 | point | line | surface | surface-energy |");
    println!("|---|---|---|---|---|---|");
    let mut path = approaches((0..=3).map(|k| -3.0 + k as f64));
    path.extend(approaches((1..=12).map(|k| -0.25 * k as f64)));
    let settings = Settings::with_method(Method::Accelerated);
    for n in [16, 32, 64, 128, 256] {
        let mut row = format!("| {n} | {:.2} |", 2.0 * half_width / n as f64);
        for problem in [
            sphere(n, half_width, PointLaw(lj))?,
            sphere(n, half_width, LineLaw(lj))?,
            sphere(n, half_width, SurfaceLaw(lj))?,
            sphere(n, half_width, ljadhesion::SurfaceEnergyLaw(lj))?,
        ] {
            let points = problem.sweep(&path, None, &settings, None, &mut ())?;
            let s = summarize(&points.iter().map(CyclePoint::from).collect::<Vec<_>>());
            let pull_off = s.pull_off_force.unwrap_or(f64::NAN) / (2.0 * PI * RADIUS * w0);
            row += &format!(
                " {pull_off:.4}{} |",
                if s.all_converged { "" } else { " (not converged)" }
            );
        }
        println!("{row}");
    }
    Ok(())
}

/// Mesh refinement of the pull-off at mu = 10 (box 600 z0 wide), point law by the energy
/// descent; the grids from the environment variable `MESH` (default 128,256).
fn high_tabor_mesh() -> Result<()> {
    let mesh: Vec<usize> = list("MESH", "128,256")?;
    let w0 = work_of_adhesion(10.0);
    let lj = LennardJones::new(w0, Z0)?;
    let mut path = approaches((0..=24).map(|k| -2.0 + k as f64));
    path.extend(approaches((1..=30).map(|k| 22.0 - 1.5 * k as f64)));
    let settings = Settings::with_method(Method::EnergyDescent);
    println!("| cells | cell / z0 | pull-off / (pi R w0) | iterations per step | time |");
    println!("|---|---|---|---|---|");
    for n in mesh {
        let started = Instant::now();
        let points = sphere(n, 300.0, PointLaw(lj))?.sweep(&path, None, &settings, None, &mut ())?;
        let s = summarize(&points.iter().map(CyclePoint::from).collect::<Vec<_>>());
        let iterations =
            points.iter().map(|p| p.report.iterations.count()).sum::<usize>() / points.len().max(1);
        println!(
            "| {n} | {:.2} | {:.3} | {iterations} | {:.0} s |{}",
            600.0 / n as f64,
            -s.pull_off_force.unwrap_or(f64::NAN) / (PI * RADIUS * w0),
            started.elapsed().as_secs_f64(),
            if s.all_converged { "" } else { " not all converged" }
        );
    }
    Ok(())
}

/// The bench's surface (H = 0.8, RMS gradient 1, cut-off 8 cells, seed 2026, unit box, E* = 1)
/// solved at `p` E* cold, and from the solution on a grid twice as coarse (the initial gap
/// averaged over 2 x 2 cells, the pressure copied back to each cell), itself solved the same
/// way down to 128^2.
fn nested_start() -> Result<()> {
    use elastic::{Domain, Periodic};
    use ndarray::Array2;
    use solver::{ContactOptions, ContactState, cg};
    let sizes: Vec<usize> = list("SIZES", "512,1024,2048")?;
    let p: f64 = std::env::var("PRESSURE")
        .unwrap_or_else(|_| "0.04".into())
        .parse()?;
    let options = ContactOptions {
        tolerance: 5e-9,
        max_iterations: 100_000,
        preconditioned: false,
    };
    let op = |n: usize| {
        Periodic::new(
            Domain {
                nx: n,
                ny: n,
                dx: 1.0 / n as f64,
                dy: 1.0 / n as f64,
                periodic: true,
            },
            1.0,
        )
    };
    /// (cells per side, iterations, seconds) of each level, finest first.
    type Levels = Vec<(usize, usize, f64)>;
    // Solves on `g0`, from the coarser grid's solution while it is at least 128^2.
    fn nested(
        g0: &Array2<f64>,
        p: f64,
        options: &ContactOptions,
        op: &dyn Fn(usize) -> elastic::Result<Periodic>,
    ) -> Result<(ContactState, Levels)> {
        let n = g0.nrows();
        let mut levels = Vec::new();
        let warm = if n >= 256 {
            let coarse = Array2::from_shape_fn((n / 2, n / 2), |(j, i)| {
                (g0[(2 * j, 2 * i)]
                    + g0[(2 * j + 1, 2 * i)]
                    + g0[(2 * j, 2 * i + 1)]
                    + g0[(2 * j + 1, 2 * i + 1)])
                    / 4.0
            });
            let (state, below) = nested(&coarse, p, options, op)?;
            levels = below;
            let fine = Array2::from_shape_fn((n, n), |(j, i)| state.pressure[(j / 2, i / 2)]);
            Some(ContactState {
                pressure: fine,
                gap: Array2::zeros((n, n)),
                displacement: Array2::zeros((n, n)),
                approach: state.approach,
                ..ContactState::unloaded((n, n))
            })
        } else {
            None
        };
        let t = Instant::now();
        let (state, report) = cg::solve(
            &op(n)?,
            g0.view(),
            Control::MeanPressure(p),
            options,
            warm.as_ref(),
            &mut (),
        )?;
        levels.insert(0, (n, report.iterations, t.elapsed().as_secs_f64()));
        Ok((state, levels))
    }
    println!("p = {p} E*, tolerance {:e}", options.tolerance);
    println!(
        "| n | cold: iterations | cold: s | nested: iterations per level (finest first) | nested: s in all | same contact set | mean gap rel. diff |"
    );
    println!("|---|---|---|---|---|---|---|");
    for n in sizes {
        let g0 = bench_gap(n)?;
        let t = Instant::now();
        let (cold, report) = cg::solve(
            &op(n)?,
            g0.view(),
            Control::MeanPressure(p),
            &options,
            None,
            &mut (),
        )?;
        let cold_s = t.elapsed().as_secs_f64();
        let (warm, levels) = nested(&g0, p, &options, &op)?;
        let differ = cold
            .pressure
            .iter()
            .zip(warm.pressure.iter())
            .filter(|(a, b)| (**a > 0.0) != (**b > 0.0))
            .count();
        let mean = |s: &ContactState| s.gap.mean().unwrap_or(0.0);
        println!(
            "| {n} | {} | {cold_s:.2} | {} | {:.2} | {} | {:.1e} |",
            report.iterations,
            levels
                .iter()
                .map(|l| l.1.to_string())
                .collect::<Vec<_>>()
                .join(" / "),
            levels.iter().map(|l| l.2).sum::<f64>(),
            if differ == 0 {
                "yes".to_string()
            } else {
                format!("{differ} cells differ")
            },
            (mean(&cold) / mean(&warm) - 1.0).abs()
        );
    }
    Ok(())
}

/// The bench's initial gap on `n^2` cells of the unit box (see `roughcontact bench`).
fn bench_gap(n: usize) -> Result<ndarray::Array2<f64>> {
    let grid = surfgen::Grid::square(n, 1.0)?;
    let spec = surfgen::SurfaceSpec {
        grid,
        psd: surfgen::Psd::self_affine(0.8, 1.0, 8.0 / n as f64),
        normalization: surfgen::Normalization::RmsGradient(1.0),
        amplitudes: surfgen::Amplitudes::Exact,
        seed: 2026,
    };
    Ok(solver::geometry::flat_on_rough(
        surfgen::generate(&spec)?.heights.view(),
    )?)
}

/// The contact-mechanics challenge (L = 100 um, H = 0.8, roll-off 20 um, RMS gradient 1, seed
/// 1, E* = 25 MPa, w0 = 50 mJ/m^2, z0 = rho = 2.071 nm) under the loads p / (E* g_bar) =
/// 0.00125 ... 0.04 and back, on grids of `SIZES` cells a side. One surface for all of them:
/// made on the finest grid (or `FINEST`) with its short cut-off at four cells of the coarsest
/// (or `CUT`), and sampled at every k-th node for the coarser grids or interpolated through its
/// spectrum for finer ones (band-limited, so either way the samples are the same surface).
/// Prints the relative contact area of each law on each grid at each load.
fn challenge_mesh() -> Result<()> {
    let sizes: Vec<usize> = list("SIZES", "256,512,1024")?;
    let laws: Vec<String> = list("LAWS", "surface,line,point,exponential")?;
    // `FINEST=N`: the grid the surface is made on, if not the largest size run (so that a
    // law's rows share a surface with another law's on other grids).
    let largest = *sizes.iter().max().context("SIZES is empty")?;
    let finest: usize = match std::env::var("FINEST") {
        Ok(n) => n.parse()?,
        Err(_) => largest,
    };
    // `CUT=N`: the grid whose four cells make the short cut-off, if not the smallest size run
    // (so that a finer row can join the coarser rows' surface).
    let coarsest = match std::env::var("CUT") {
        Ok(n) => n.parse()?,
        Err(_) => *sizes.iter().min().context("SIZES is empty")?,
    };
    if 2 * finest < coarsest {
        bail!("the cut-off, four cells of {coarsest}, is finer than FINEST ({finest}) can carry");
    }
    if let Some(n) = sizes
        .iter()
        .find(|&&n| !finest.is_multiple_of(n) && !n.is_multiple_of(finest))
    {
        bail!("every size must divide FINEST ({finest}) or be a multiple of it; {n} is neither");
    }
    let (length, e_star, z0) = (1e-4, 25e6, 2.071e-9);
    let grid = surfgen::Grid::square(finest, length)?;
    let spec = surfgen::SurfaceSpec {
        grid,
        psd: surfgen::Psd::self_affine(0.8, 2e-5, 4.0 * length / coarsest as f64),
        normalization: surfgen::Normalization::RmsGradient(1.0),
        amplitudes: surfgen::Amplitudes::Exact,
        seed: 1,
    };
    let heights = surfgen::generate(&spec)?.heights;
    // `TABOR=mu`: the work of adhesion set, as Fig. 10 does, for the Tabor parameter mu on the
    // surface's local radius (its inverse RMS curvature); else the challenge's 0.05 J/m^2.
    let tabor: Option<f64> = std::env::var("TABOR").ok().map(|t| t.parse()).transpose()?;
    let w0 = match tabor {
        Some(mu) if mu.is_finite() && mu > 0.0 => {
            let radius = crate::gap_statistics(&heights, &grid).local_radius;
            crate::challenge::work_for_tabor(radius, mu)
        }
        Some(mu) => bail!("TABOR must be a Tabor parameter > 0, not {mu}"),
        None => 0.05,
    };
    eprintln!("work of adhesion {w0:.6e} J/m^2");
    let loads: [f64; 11] = [
        0.00125, 0.0025, 0.005, 0.01, 0.02, 0.04, 0.02, 0.01, 0.005, 0.0025, 0.00125,
    ];
    // `REFINE=k`: k - 1 loads between each two of the table's, geometrically spaced, to see
    // how much the unloading branch depends on the size of the load steps.
    let refine: usize = match std::env::var("REFINE") {
        Ok(k) => k.parse()?,
        Err(_) => 1,
    };
    if refine == 0 {
        bail!("REFINE must be at least 1 (the table's loads alone)");
    }
    let mut steps = vec![loads[0]];
    for w in loads.windows(2) {
        steps.extend((1..=refine).map(|k| w[0] * (w[1] / w[0]).powf(k as f64 / refine as f64)));
    }
    let pressures: Vec<toml::Value> = steps.iter().map(|&p| (p * e_star).into()).collect();
    let method = std::env::var("METHOD").unwrap_or_else(|_| "auto".into());
    let tolerance: Option<f64> = std::env::var("TOLERANCE").ok().map(|t| t.parse()).transpose()?;
    // Every setting that changes a run is in its name: a finished run is never redone, nor
    // taken for another's.
    let mut variant = format!("{method}_of{finest}_cut{coarsest}");
    if let Some(t) = tolerance {
        variant += &format!("_tol{t:e}");
    }
    if refine > 1 {
        variant += &format!("_refine{refine}");
    }
    if let Some(mu) = tabor {
        variant += &format!("_tabor{mu}");
    }
    // `DIR=path`: where the runs go, for a row longer than target/ lives.
    let dir =
        std::path::PathBuf::from(std::env::var("DIR").unwrap_or_else(|_| "target/challenge-mesh".into()));
    let surfaces = dir.join("surfaces");
    std::fs::create_dir_all(&surfaces)?;
    let mut sweeps = Vec::new();
    let mut rows = Vec::new();
    for law in &laws {
        let adhesion = match law.as_str() {
            "surface" | "line" | "point" | "surface-energy" => Some((law.as_str(), "z0")),
            "exponential" => Some(("exponential", "range")),
            "none" => None,
            other => bail!("unknown law `{other}` (surface, line, point, surface-energy, exponential, none)"),
        };
        for &n in &sizes {
            let path = surfaces.join(format!("n{n}_of{finest}_cut{coarsest}.npy"));
            if !path.exists() {
                let sampled = if n > finest {
                    surfgen::refine(heights.view(), n / finest)?
                } else {
                    let stride = finest / n;
                    heights.slice(ndarray::s![..;stride, ..;stride]).to_owned()
                };
                surfgen::io::write_npy(&sampled, &path)?;
            }
            let mut keys = toml::Table::new();
            let path = std::fs::canonicalize(&path)?.display().to_string();
            keys.insert("surface".into(), path.into());
            keys.insert("length".into(), length.into());
            keys.insert("modulus".into(), e_star.into());
            if let Some((law_key, range_key)) = adhesion {
                keys.insert("law".into(), law_key.into());
                keys.insert("work_of_adhesion".into(), w0.into());
                keys.insert(range_key.into(), z0.into());
                keys.insert("solver".into(), method.clone().into());
            }
            keys.insert("max_iterations".into(), 1_000_000i64.into());
            keys.insert("mean_pressures".into(), pressures.clone().into());
            if let Some(t) = tolerance {
                keys.insert("tolerance".into(), t.into());
            }
            sweeps.push(crate::series::Sweep {
                // One study a law: a study's runs set the same keys (`z0` or `range`).
                study: law.clone(),
                name: format!("n{n}_{variant}"),
                keys,
            });
            rows.push((law.clone(), n));
        }
    }
    let dirs = crate::series::run(&dir, &sweeps)?;
    print_areas(&rows, &dirs, &loads, refine, (length, e_star, w0, z0))?;
    eprintln!("runs in {} (resumable: the same command goes on)", dir.display());
    Ok(())
}

/// The challenge-mesh study's table: each run's contact area at each of `loads` (every
/// `refine`-th step), its cells in process zones, its solve time and whether it converged.
fn print_areas(
    rows: &[(String, usize)],
    dirs: &[std::path::PathBuf],
    loads: &[f64],
    refine: usize,
    (length, e_star, w0, z0): (f64, f64, f64, f64),
) -> Result<()> {
    println!(
        "| law | n | cell / process zone | {} | solve [s] | all converged |",
        loads
            .iter()
            .map(|p| format!("{p}"))
            .collect::<Vec<_>>()
            .join(" | ")
    );
    println!("|---|---|---|{}---|---|", "---|".repeat(loads.len()));
    let zone = ljadhesion::PointLaw(LennardJones::new(w0, z0)?).process_zone(e_star);
    for ((law, n), dir) in rows.iter().zip(dirs) {
        let curve = crate::series::Curve::read(dir)?;
        let areas: Vec<String> = curve
            .numbers("contact_area_fraction")?
            .iter()
            .step_by(refine)
            .map(|a| format!("{a:.5}"))
            .collect();
        let solve: f64 = curve.numbers("wall_time_s")?.iter().sum();
        let zones = if law == "none" {
            "-".to_string()
        } else {
            format!("{:.0}", length / *n as f64 / zone)
        };
        println!(
            "| {law} | {n} | {zones} | {} | {solve:.0} | {} |",
            areas.join(" | "),
            curve.converged()?.iter().all(|&c| c)
        );
    }
    Ok(())
}

/// A comma-separated list from the environment variable `name`, else `default`.
fn list<T: std::str::FromStr>(name: &str, default: &str) -> Result<Vec<T>>
where
    T::Err: std::error::Error + Send + Sync + 'static,
{
    let text = std::env::var(name).unwrap_or_else(|_| default.into());
    text.split(',')
        .map(|s| {
            s.trim()
                .parse::<T>()
                .map_err(|e| anyhow::anyhow!("{name}: `{s}`: {e}"))
        })
        .collect()
}

/// The rough sphere of Figs. 11-14 at mu = 5 and Rq = 2 z0 (the figures' box, spectrum and
/// pull-off search) on grids of several cell sizes, the same surface on each: generated on
/// the finest grid and sampled every `finest / n` nodes (the figures' short cut-off, 215 nm,
/// spans five cells of 90^2, so every grid keeps the spectrum). Does the surface law's cell
/// integral make the pull-off less dependent on the mesh than the point law, as the paper argues?
fn rough_sphere_mesh() -> Result<()> {
    use crate::rough_sphere::{Job, Plan, process_zone};
    use case::LawKind;
    let sizes: Vec<usize> = list("SIZES", "90,135,270,540")?;
    let laws: Vec<String> = list("LAWS", "point,surface")?;
    let seeds: Vec<u64> = list("SEEDS", "1")?;
    let finest = *sizes.iter().max().context("SIZES is empty")?;
    if let Some(n) = sizes.iter().find(|&&n| finest % n != 0) {
        bail!("every size must divide the finest ({finest}); {n} does not");
    }
    let (mu, rq) = (5, 2.0);
    let plan = Plan::new(false, LawKind::Point);
    let dir = std::path::PathBuf::from("target/rough-sphere-mesh");
    let surfaces = dir.join("surfaces");
    std::fs::create_dir_all(&surfaces)?;
    let mut jobs = Vec::new();
    let mut sweeps = Vec::new();
    for &seed in &seeds {
        let fine = Job {
            rq,
            cutoff: plan.cutoff(),
            seed,
            n: finest,
            ..Job::smooth(mu, finest, plan.length(), plan.tolerance, LawKind::Point)
        };
        let heights = fine.case().rough_surface()?.context("the job is rough")?.heights;
        for &n in &sizes {
            let stride = finest / n;
            // Named by the grid it was sampled from too: a finished run is never redone.
            let tag = format!("n{n}_of{finest}_seed{seed}");
            let path = surfaces.join(format!("{tag}.npy"));
            let sampled = heights.slice(ndarray::s![..;stride, ..;stride]).to_owned();
            surfgen::io::write_npy(&sampled, &path)?;
            for law in &laws {
                let law = match law.as_str() {
                    "point" => LawKind::Point,
                    "surface" => LawKind::Surface,
                    other => bail!("unknown law `{other}` (point, surface)"),
                };
                let job = Job { n, law, ..fine };
                let name = format!("{}_{tag}", law.name());
                sweeps.push(crate::series::Sweep {
                    study: "mesh".into(),
                    name,
                    keys: job.keys(Some(&std::fs::canonicalize(&path)?)),
                });
                jobs.push(job);
            }
        }
    }
    let dirs = crate::series::run(&dir, &sweeps)?;
    println!("| law | n | cell / process zone | pull-off / (pi R w0), by seed | wall [s] | all converged |");
    println!("|---|---|---|---|---|---|");
    for law in [LawKind::Point, LawKind::Surface] {
        for &n in &sizes {
            let found: Vec<_> = jobs
                .iter()
                .zip(&dirs)
                .filter(|(j, _)| j.law == law && j.n == n)
                .map(|(j, d)| j.outcome(d).map(|o| (o, j.force_unit())))
                .collect::<Result<_>>()?;
            if found.is_empty() {
                continue;
            }
            let pull_offs: Vec<String> = found
                .iter()
                .map(|(o, unit)| format!("{:.4}", o.pull_off / unit))
                .collect();
            println!(
                "| {} | {n} | {:.2} | {} | {:.0} | {} |",
                law.name(),
                plan.length() / n as f64 / process_zone(mu),
                pull_offs.join(", "),
                found.iter().map(|(o, _)| o.wall_time_s).sum::<f64>(),
                found.iter().all(|(o, _)| o.all_converged)
            );
        }
    }
    Ok(())
}
