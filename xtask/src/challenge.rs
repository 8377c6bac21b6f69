//! The contact-mechanics challenge (Müser et al. 2017; Figs. 8-10): a periodic self-affine
//! surface pressed by increasing mean pressures, with and without adhesion, each load
//! warm-started from the last. Relative contact area against the reduced pressure
//! p/(E* g_bar), and the gap along the mid cross-section.

use anyhow::{Context as _, Result, bail};
use case::{Case, LawKind};
use std::path::{Path, PathBuf};

/// The challenge's box \[m\], modulus \[Pa\], and adhesion (work [J/m^2], and the range \[m\]:
/// the exponential law's rho and Lennard-Jones' z0 alike).
pub const LENGTH: f64 = 1e-4;
pub const MODULUS: f64 = 25e6;
pub const WORK: f64 = 0.05;
pub const RANGE: f64 = 2.071e-9;
/// The adhesive runs' limit on a load's iterations.
const MAX_STEPS: usize = 200_000;

/// The challenge surface from its specification (or the user's file) on an `n^2` grid with
/// RMS gradient `g_bar`; the short cutoff is the specification's 0.1 um or four cells,
/// whichever is longer (a coarser grid cannot carry shorter waves).
pub fn case(n: usize, g_bar: f64, surface: Option<&PathBuf>) -> Case {
    let mut c = Case {
        modulus: Some(MODULUS),
        length: Some(LENGTH),
        ..Case::default()
    };
    match surface {
        Some(path) => c.surface = Some(path.clone()),
        None => {
            c.rms_gradient = Some(g_bar);
            c.hurst = Some(0.8);
            c.rolloff_wavelength = Some(2e-5);
            c.cutoff_wavelength = Some(cutoff(n));
            c.seed = Some(1);
            c.n = Some(n);
        }
    }
    c
}

/// The short-wavelength cutoff used on an `n^2` grid \[m\].
pub fn cutoff(n: usize) -> f64 {
    (1e-7f64).max(4.0 * LENGTH / n as f64)
}

/// A loading sequence on one surface.
#[derive(Clone, Debug)]
pub struct Run {
    pub case: Case,
    /// Reduced pressures p/(E* g_bar), increasing.
    pub reduced: Vec<f64>,
    /// Reduced pressures of the unloading branch that follows, decreasing, each warm-started
    /// from the last (adhesive runs only: without adhesion the solution is unique).
    pub unloading: Vec<f64>,
    /// Reduced pressure at which to keep the gap along the mid cross-section.
    pub profile_at: Option<f64>,
}

#[derive(Clone, Debug)]
pub struct LoadPoint {
    pub reduced: f64,
    pub mean_pressure: f64,
    pub contact_area_fraction: f64,
    /// Mean gap \[m\].
    pub mean_gap: f64,
    pub converged: bool,
    pub iterations: usize,
    pub wall_time_s: f64,
}

#[derive(Clone, Debug)]
pub struct Outcome {
    pub points: Vec<LoadPoint>,
    /// The unloading branch (empty unless asked for).
    pub unloading: Vec<LoadPoint>,
    /// Gap \[m\] along the mid cross-section x = L/2 (column nx/2), against y.
    pub profile: Vec<f64>,
    /// Measured RMS gradient and local radius (inverse RMS curvature) \[m\] of the surface.
    pub rms_gradient: f64,
    pub local_radius: f64,
    pub rms_height: f64,
    pub cell: f64,
    pub warnings: Vec<String>,
}

impl Run {
    /// The run's sweep of its study: its loads as mean pressures \[Pa\] (the reduced ones times
    /// E* and the surface's measured RMS gradient `g`), loading then unloading, the step of
    /// the profile kept.
    fn sweep(&self, g: f64) -> Result<crate::series::Sweep> {
        let mut keys = toml::Table::try_from(&self.case)?;
        let loads: Vec<toml::Value> = self
            .reduced
            .iter()
            .chain(&self.unloading)
            .map(|r| (r * MODULUS * g).into())
            .collect();
        keys.insert("mean_pressures".into(), loads.into());
        // Every run sets the key, so that a study's runs set the same keys.
        let kept: Vec<toml::Value> = self
            .profile_step()
            .map(|k| (k as i64).into())
            .into_iter()
            .collect();
        keys.insert("keep_steps".into(), kept.into());
        let adhesive = self.case.law.is_some();
        if adhesive {
            // The flow's first load from a cold start takes more than the default 20000 steps
            // at 1024^2 (docs/validation.md).
            keys.insert("max_iterations".into(), (MAX_STEPS as i64).into());
        }
        let file = self.case.surface.is_some();
        let n = self.case.n.map_or("file".into(), |n| n.to_string());
        // The exponential law's runs keep their names from before the law was a choice.
        let name = match (self.case.law, self.case.work_of_adhesion) {
            (Some(LawKind::Exponential), Some(w0)) => format!("n{n}_g{g:.6}_w0{w0:.6e}"),
            (Some(law), Some(w0)) => format!("{}_n{n}_g{g:.6}_w0{w0:.6e}", law.name()),
            _ => format!("n{n}_g{g:.6}"),
        };
        Ok(crate::series::Sweep {
            study: format!(
                "challenge-{}{}",
                if file { "file-" } else { "" },
                if adhesive { "adhesive" } else { "plain" }
            ),
            name,
            keys,
        })
    }

    /// The loading step whose gap gives the profile.
    fn profile_step(&self) -> Option<usize> {
        self.profile_at
            .and_then(|p| self.reduced.iter().position(|&r| r == p))
    }

    /// What the sweep in `dir` found, from its curve (and the kept step's gap).
    fn outcome(&self, dir: &Path, stats: (f64, f64, f64, f64)) -> Result<Outcome> {
        let (_, local_radius, rms_height, cell) = stats;
        let p = crate::problem(&self.case)?;
        let mean_g0 = p.initial_gap.mean().unwrap_or(0.0);
        let curve = crate::series::Curve::read(dir)?;
        let reduced: Vec<f64> = self.reduced.iter().chain(&self.unloading).copied().collect();
        if curve.len() != reduced.len() {
            bail!(
                "{} holds {} loads, not {}",
                dir.display(),
                curve.len(),
                reduced.len()
            );
        }
        let (approach, pressure, area) = (
            curve.numbers("approach")?,
            curve.numbers("mean_pressure")?,
            curve.numbers("contact_area_fraction")?,
        );
        let (converged, iterations, time) = (
            curve.converged()?,
            curve.numbers("iterations")?,
            curve.numbers("wall_time_s")?,
        );
        let mut points: Vec<LoadPoint> = reduced
            .into_iter()
            .enumerate()
            .map(|(k, reduced)| LoadPoint {
                reduced,
                mean_pressure: pressure[k],
                contact_area_fraction: area[k],
                // Periodic: the mean displacement is zero.
                mean_gap: mean_g0 - approach[k],
                converged: converged[k],
                iterations: iterations[k] as usize,
                wall_time_s: time[k],
            })
            .collect();
        let unloading = points.split_off(self.reduced.len());
        let profile = match self.profile_step() {
            Some(k) => profile(dir, k)?,
            None => Vec::new(),
        };
        Ok(Outcome {
            points,
            unloading,
            profile,
            rms_gradient: stats.0,
            local_radius,
            rms_height,
            cell,
            warnings: p.warnings,
        })
    }
}

/// The sweeps of `runs` and of every run of the figures being built, each once: a run asked
/// for twice (Figs. 8 and 10 share the plain one in quick mode) keeps the steps either keeps.
pub fn sweeps(ctx: &crate::Context, runs: &[Run]) -> Result<Vec<crate::series::Sweep>> {
    let mut sweeps: Vec<crate::series::Sweep> = Vec::new();
    for run in crate::challenge_runs(ctx)?.iter().chain(runs) {
        let (g, ..) = crate::surface_statistics(&run.case)?;
        let sweep = run.sweep(g)?;
        match sweeps
            .iter_mut()
            .find(|s| s.study == sweep.study && s.name == sweep.name)
        {
            Some(same) => {
                let steps = |s: &crate::series::Sweep| match s.keys.get("keep_steps") {
                    Some(toml::Value::Array(a)) => a.clone(),
                    _ => unreachable!("every sweep keeps its steps' list"),
                };
                let mut kept = steps(same);
                for k in steps(&sweep) {
                    if !kept.contains(&k) {
                        kept.push(k);
                    }
                }
                let mut keys = sweep.keys.clone();
                keys.insert("keep_steps".into(), kept.clone().into());
                same.keys.insert("keep_steps".into(), kept.into());
                if keys != same.keys {
                    bail!("two challenge runs named {} differ", sweep.name);
                }
            }
            None => sweeps.push(sweep),
        }
    }
    Ok(sweeps)
}

/// Runs the challenge's `runs` as studies of sweeps (`OUT/studies/challenge-*`, with every
/// other challenge run of the figures being built; see [`crate::series`]), each load
/// warm-started from the last.
pub fn outcomes(ctx: &crate::Context, runs: &[Run]) -> Result<Vec<Outcome>> {
    let sweeps = sweeps(ctx, runs)?;
    let dirs = crate::series::run(&ctx.options.out.join("studies"), &sweeps)?;
    runs.iter()
        .map(|r| {
            let stats = crate::surface_statistics(&r.case)?;
            let own = r.sweep(stats.0)?;
            let (_, dir) = sweeps
                .iter()
                .zip(&dirs)
                .find(|(s, _)| s.study == own.study && s.name == own.name)
                .context("every run was swept")?;
            r.outcome(dir, stats)
        })
        .collect()
}

/// The challenge case with adhesion by `law` of work `w0` [J/m^2] and range [`RANGE`].
pub fn adhesive(mut case: Case, w0: f64, law: LawKind) -> Case {
    case.law = Some(law);
    case.work_of_adhesion = Some(w0);
    if law.takes_z0() {
        case.z0 = Some(RANGE);
    } else {
        case.range = Some(RANGE);
    }
    case
}

/// The law in a legend.
pub fn label(law: LawKind) -> &'static str {
    match law {
        LawKind::Exponential => "challenge's exponential law",
        LawKind::Surface => "LJ surface law",
        LawKind::Point => "LJ point law",
        other => other.name(),
    }
}

/// The law in a sentence of FIGURES.md.
pub fn describe(law: LawKind) -> &'static str {
    match law {
        LawKind::Exponential => {
            "the challenge's own law, σ(g) = -(w0/ρ) exp(-g/ρ), ρ = 2.071 nm, with a hard wall (the paper \
             used its Lennard-Jones surface law: `--challenge-law surface`)"
        }
        LawKind::Surface => {
            "the paper's Lennard-Jones surface law (Eq. 11, each cell the mean of the law over its gaps), \
             z0 = 2.071 nm, solved by the flow"
        }
        LawKind::Point => "Lennard-Jones at the nodes (the point law), z0 = 2.071 nm, with a hard wall at z0",
        other => other.name(),
    }
}

/// The adhesive process-zone length \[m\] of `law` with work `w0` and range [`RANGE`]
/// ([`ljadhesion::AdhesionLaw::process_zone`]).
pub fn process_zone(w0: f64, law: LawKind) -> f64 {
    adhesive(Case::default(), w0, law)
        .law()
        .map_or(f64::NAN, |l| l.process_zone(MODULUS))
}

/// The Tabor parameter `(R w0^2 / (E*^2 rho^3))^(1/3)` (Müser's Tabor-like parameter for the
/// exponential law; Tabor's with z0 for Lennard-Jones), with the local radius `R` \[m\].
pub fn tabor(local_radius: f64, w0: f64) -> f64 {
    theory::tabor_parameter(local_radius, w0, MODULUS, RANGE)
}

/// The work of adhesion [J/m^2] that gives Tabor parameter `mu` at local radius `R` \[m\].
pub fn work_for_tabor(local_radius: f64, mu: f64) -> f64 {
    theory::work_of_adhesion_of_tabor(mu, local_radius, MODULUS, RANGE)
}

/// The gap (m) along the middle column of the sweep in `dir` at step `k`: read from the kept
/// state once and stored beside the run as `profile.csv`, which the repository keeps (the
/// states it does not).
fn profile(dir: &Path, k: usize) -> Result<Vec<f64>> {
    let kept = dir.join("profile.csv");
    if let Ok(text) = std::fs::read_to_string(&kept) {
        return text
            .lines()
            .skip(1)
            .map(|l| {
                l.parse::<f64>()
                    .with_context(|| format!("reading {}: {l:?}", kept.display()))
            })
            .collect();
    }
    let file = dir.join("states").join(format!("step-{k:04}")).join("gap.npy");
    let gap: ndarray::Array2<f64> =
        ndarray_npy::read_npy(&file).with_context(|| format!("reading {}", file.display()))?;
    let (ny, nx) = gap.dim();
    let column: Vec<f64> = (0..ny).map(|j| gap[(j, nx / 2)]).collect();
    let text: String = std::iter::once("gap_m".to_string())
        .chain(column.iter().map(|g| format!("{g:e}")))
        .map(|l| l + "\n")
        .collect();
    std::fs::write(&kept, text).with_context(|| format!("writing {}", kept.display()))?;
    Ok(column)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_profile_is_kept_beside_the_run_bit_for_bit() {
        let dir = std::env::temp_dir().join(format!("xtask-profile-{}", std::process::id()));
        let step = dir.join("states").join("step-0002");
        std::fs::create_dir_all(&step).unwrap();
        let gap = ndarray::Array2::from_shape_fn((5, 4), |(j, i)| (j as f64 + 0.1 * i as f64) / 3.0 * 1e-9);
        ndarray_npy::write_npy(step.join("gap.npy"), &gap).unwrap();
        let read = profile(&dir, 2).unwrap();
        assert_eq!(read, gap.column(2).to_vec());
        std::fs::remove_dir_all(dir.join("states")).unwrap();
        assert_eq!(profile(&dir, 2).unwrap(), read);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
