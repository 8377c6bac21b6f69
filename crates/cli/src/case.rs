//! The contact case shared by `solve` and `sweep`: geometry, material, adhesion and solver
//! settings, from flags and/or a TOML case file, and the problem it builds.

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use elastic::{Compliance, Domain, Free, Periodic};
use ljadhesion::{
    AdhesionLaw, DugdaleLaw, ExponentialLaw, LennardJones, LineLaw, NoAdhesion, PointLaw, SurfaceLaw,
};
use ndarray::Array2;
use serde::{Deserialize, Serialize, de::DeserializeOwned};
use serde_json::{Map, Value};
use solver::adhesive::OuterLoop;
use solver::geometry::{SphereProfile, flat_on_rough, sphere, wave};
use solver::{AdhesiveOptions, ContactOptions, Control};
use std::path::{Path, PathBuf};
use surfgen::io::{self, ReadOptions};
use surfgen::{Amplitudes, Grid, Normalization, Psd, SurfaceSpec};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DomainKind {
    /// The pattern repeats (rough surfaces): spectral kernel.
    Periodic,
    /// An isolated contact (spheres): Love's coefficients with zero padding.
    Free,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum LawKind {
    /// No adhesion.
    None,
    /// Lennard-Jones averaged over the tilted cell (the paper's Eq. 11).
    Surface,
    /// Lennard-Jones averaged along x (Medina & Dini 2014).
    Line,
    /// Lennard-Jones at the node.
    Point,
    /// -(w0/range) exp(-g/range), the contact-mechanics challenge's law.
    Exponential,
    /// -w0/range for g < range (Maugis-Dugdale).
    Dugdale,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum OuterKind {
    /// `energy` for the point and exponential laws, `newton` for the line and surface laws
    /// (approach or mean-gap control, both), `accelerated` elsewhere.
    Auto,
    /// The paper's relaxation of the adhesive pressure.
    DualLoop,
    /// Anderson mixing of the adhesive pressure (fewer outer iterations, same solution).
    Accelerated,
    /// No outer loop: conjugate gradients on the total energy (point or exponential law;
    /// approach or mean-gap control, or load control on periodic domains; fastest there).
    Energy,
    /// No outer loop, any law but Dugdale's (surface included): Newton-Krylov on the cells'
    /// force balance (approach or mean-gap control).
    Newton,
}

/// The solver's name, as `--solver` takes it.
pub fn solver_name(outer_loop: OuterLoop) -> &'static str {
    match outer_loop {
        OuterLoop::DualLoop => "dual-loop",
        OuterLoop::Accelerated => "accelerated",
        OuterLoop::EnergyDescent => "energy",
        OuterLoop::Newton => "newton",
    }
}

/// A contact case: every flag is also a key of the TOML case file (`--config`), with the same
/// name in snake_case. Flags override the file.
#[derive(Args, Debug, Default, Clone, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Case {
    /// Rough surface file (.npy + sidecar, .txt, .xyz, .gsf): heights [m], peaks towards the
    /// counterface. With --sphere-radius the roughness sits on the sphere.
    #[arg(long)]
    pub surface: Option<PathBuf>,
    /// Generate the roughness instead of reading it: RMS height Rq [m].
    #[arg(long, conflicts_with = "surface")]
    pub rms_height: Option<f64>,
    /// Generate the roughness instead of reading it: RMS gradient [-].
    #[arg(long, conflicts_with_all = ["surface", "rms_height"])]
    pub rms_gradient: Option<f64>,
    /// Generated roughness: Hurst exponent H [-] (default 0.8).
    #[arg(long)]
    pub hurst: Option<f64>,
    /// Generated roughness: roll-off wavelength [m] (default: a quarter of the box).
    #[arg(long)]
    pub rolloff_wavelength: Option<f64>,
    /// Generated roughness: short-wavelength cut-off [m] (default: four cells).
    #[arg(long)]
    pub cutoff_wavelength: Option<f64>,
    /// Generated roughness: random seed (default 1); a seed fixes the surface bit for bit.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Box side [m]: for a bare surface file, a generated surface or a smooth sphere's grid.
    #[arg(long)]
    pub length: Option<f64>,
    /// Box size along y [m] (default: square cells).
    #[arg(long)]
    pub length_y: Option<f64>,
    /// Metres per unit in the surface file.
    #[arg(long)]
    pub unit: Option<f64>,
    /// Radius R of a rigid sphere [m], centred on the grid.
    #[arg(long)]
    pub sphere_radius: Option<f64>,
    /// Amplitude A of a rigid wave A cos(2 pi x / L) [m] (half its peak-to-valley height),
    /// one wavelength across the box along x, crest centred: Westergaard's and Johnson's
    /// (1995) wavy contact (periodic; `roughcontact theory wavy` gives their curves). With
    /// roughness, the roughness sits on the wave.
    #[arg(long, conflicts_with = "sphere_radius")]
    pub wave_amplitude: Option<f64>,
    /// Use the exact spherical profile instead of the paraboloid r^2/(2R).
    #[arg(long, num_args = 0..=1, default_missing_value = "true")]
    pub exact_sphere: Option<bool>,
    /// Grid points per side (default 256); must match a surface file.
    #[arg(long)]
    pub n: Option<usize>,
    /// Grid points along y, when not --n (a wave needs a few: its problem is one-dimensional).
    #[arg(long)]
    pub ny: Option<usize>,
    /// Periodic or free boundaries (default: periodic for a rough flat, free with a sphere).
    #[arg(long, value_enum)]
    pub domain: Option<DomainKind>,
    /// Composite modulus E* [Pa].
    #[arg(long)]
    pub modulus: Option<f64>,
    /// Adhesive law (default: surface when --work-of-adhesion is given, none otherwise).
    #[arg(long, value_enum)]
    pub law: Option<LawKind>,
    /// Work of adhesion w0 [J/m^2].
    #[arg(long)]
    pub work_of_adhesion: Option<f64>,
    /// Lennard-Jones equilibrium separation z0 [m] (surface, line, point laws).
    #[arg(long)]
    pub z0: Option<f64>,
    /// Range of the exponential or Dugdale law [m] (Dugdale default: 0.974 z0 if --z0 given).
    #[arg(long)]
    pub range: Option<f64>,
    /// Adhesive solver: auto (the default: energy or newton where they are the tested choice,
    /// else accelerated), dual-loop, accelerated, energy or newton.
    #[arg(long, value_enum)]
    pub solver: Option<OuterKind>,
    /// Convergence tolerance: without adhesion the scale-free gap residual (default 1e-8, at
    /// least 1e-13); with adhesion, in units of the law's range [-] (default 1e-6, the paper's
    /// criterion), for dual-loop and accelerated the outer residual (a mean gap error), for
    /// energy and newton the worst cell's force imbalance times its compliance.
    #[arg(long)]
    pub tolerance: Option<f64>,
    /// Iteration limit: conjugate-gradient iterations without adhesion (default 10000); with
    /// it (default 20000) outer iterations, descent iterations (energy) or Newton steps.
    #[arg(long)]
    pub max_iterations: Option<usize>,
    /// Output directory (default: run).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

/// The keys a struct of options can take in a case file: its fields' names.
fn keys<T: Default + Serialize>() -> Vec<String> {
    match serde_json::to_value(T::default()) {
        Ok(Value::Object(m)) => m.keys().cloned().collect(),
        _ => Vec::new(),
    }
}

/// Reads a TOML case file (or text) into two option structs, each key going to the struct that
/// has it (unknown keys are an error), then lays every flag given on the command line over it.
pub fn layered<A, B>(text: Option<(&str, &str)>, a: &A, b: &B) -> Result<(A, B)>
where
    A: Default + Serialize + DeserializeOwned,
    B: Default + Serialize + DeserializeOwned,
{
    let (mut ma, mut mb) = (Map::new(), Map::new());
    if let Some((name, text)) = text {
        let table: toml::Table = toml::from_str(text).with_context(|| format!("parsing {name}"))?;
        let (ka, kb) = (keys::<A>(), keys::<B>());
        for (k, v) in table {
            let v = serde_json::to_value(v)?;
            if ka.contains(&k) {
                ma.insert(k, v);
            } else if kb.contains(&k) {
                mb.insert(k, v);
            } else {
                let mut all = ka.clone();
                all.extend(kb.clone());
                all.sort();
                bail!("{name}: unknown key `{k}`; the keys are {}", all.join(", "));
            }
        }
    }
    let overlay = |m: &mut Map<String, Value>, flags: Value| {
        if let Value::Object(flags) = flags {
            for (k, v) in flags {
                if !v.is_null() {
                    m.insert(k, v);
                }
            }
        }
    };
    overlay(&mut ma, serde_json::to_value(a)?);
    overlay(&mut mb, serde_json::to_value(b)?);
    Ok((
        serde_json::from_value(Value::Object(ma))?,
        serde_json::from_value(Value::Object(mb))?,
    ))
}

/// Both option structs as one TOML case (for `--print-config`).
pub fn to_toml<A: Serialize, B: Serialize>(a: &A, b: &B) -> Result<String> {
    let mut table: toml::Table = toml::Table::try_from(a)?;
    table.extend(toml::Table::try_from(b)?);
    Ok(toml::to_string(&table)?.trim_end().to_string())
}

/// FNV-1a over the heights' bits: a stable fingerprint of the input surface.
pub fn fingerprint(h: &Array2<f64>) -> String {
    let mut hash: u64 = 0xcbf29ce484222325;
    for v in h.iter() {
        for b in v.to_le_bytes() {
            hash ^= b as u64;
            hash = hash.wrapping_mul(0x100000001b3);
        }
    }
    format!("fnv1a64:{hash:016x}")
}

/// A built problem: grid, operator, initial gap, adhesive law and solver settings.
pub struct Problem {
    pub domain: Domain,
    pub op: Box<dyn Compliance>,
    pub g0: Array2<f64>,
    pub law: Box<dyn AdhesionLaw>,
    pub e_star: f64,
    /// Fingerprint of the roughness (read or generated), if any.
    pub surface_hash: Option<String>,
    /// Things the user should know before trusting the result.
    pub warnings: Vec<String>,
}

impl Problem {
    pub fn adhesive(&self) -> bool {
        self.law.name() != "none"
    }
}

impl Case {
    /// Whether the case has adhesion.
    pub fn adhesive(&self) -> bool {
        !matches!(self.law, None | Some(LawKind::None)) || self.work_of_adhesion.is_some()
    }

    /// Fills in the defaults, so that the summary and `--print-config` show the whole case.
    pub fn fill_defaults(&mut self) {
        let adhesive = self.adhesive();
        self.domain = self.domain.or(Some(if self.sphere_radius.is_some() {
            DomainKind::Free
        } else {
            DomainKind::Periodic
        }));
        if adhesive {
            self.law = self.law.or(Some(LawKind::Surface));
            self.solver = self.solver.or(Some(OuterKind::Auto));
        } else {
            self.law = Some(LawKind::None);
        }
        self.tolerance = self.tolerance.or(Some(if adhesive { 1e-6 } else { 1e-8 }));
        self.max_iterations = self
            .max_iterations
            .or(Some(if adhesive { 20_000 } else { 10_000 }));
        if self.rms_height.is_some() || self.rms_gradient.is_some() {
            self.hurst = self.hurst.or(Some(0.8));
            self.seed = self.seed.or(Some(1));
        }
        self.out = self.out.clone().or_else(|| Some(PathBuf::from("run")));
    }

    pub fn contact_options(&self) -> ContactOptions {
        ContactOptions {
            tolerance: self.tolerance.unwrap_or(1e-8),
            max_iterations: self.max_iterations.unwrap_or(10_000),
        }
    }

    /// The adhesive solver's settings for solves under controls like `control`.
    ///
    /// Under approach control `auto` takes a solver with no outer loop: the energy descent
    /// for the laws that have an energy, Newton for the line and surface laws. The accelerated
    /// loop is left for the rest (load and central-gap control, Dugdale's law) because near a
    /// fold it leaves a branch early: unloading, its mixed iterates settle on the unstable
    /// middle of the S and detach before the state does (sphere, μ = 2, 128²: at -3.12 z0,
    /// the fold at -3.39 z0; `jkr-sphere` (μ = 3) in steps of z0/8: -4.38 z0, the fold at -5.0
    /// z0; `wavy-jkr`: -5 z0 against -7 z0, the pull-off 2 % short of Johnson's, where
    /// Newton's is 0.2 % over it), where Newton, which relaxes from the last state, holds on.
    /// The loop is faster only where no cell is near a snap (`rough-sphere`: 6 s against 9 s,
    /// the same cycle within 1e-5 of the pull-off); on soft laws its residual, the law's
    /// mismatch cell by cell, also stops it short on long wavelengths (`dmt-sphere`: loads up
    /// to 0.5 % off and a spurious jump in and out at the default tolerance).
    pub fn adhesive_options(&self, control: Control) -> AdhesiveOptions {
        let approach = matches!(control, Control::Approach(_));
        let energy_applies = matches!(self.law, Some(LawKind::Point | LawKind::Exponential)) && approach;
        let newton_applies = matches!(self.law, Some(LawKind::Line | LawKind::Surface)) && approach;
        AdhesiveOptions {
            outer_loop: match self.solver {
                Some(OuterKind::DualLoop) => OuterLoop::DualLoop,
                Some(OuterKind::Energy) => OuterLoop::EnergyDescent,
                Some(OuterKind::Accelerated) => OuterLoop::Accelerated,
                Some(OuterKind::Newton) => OuterLoop::Newton,
                None | Some(OuterKind::Auto) if energy_applies => OuterLoop::EnergyDescent,
                None | Some(OuterKind::Auto) if newton_applies => OuterLoop::Newton,
                None | Some(OuterKind::Auto) => OuterLoop::Accelerated,
            },
            tolerance: self.tolerance.unwrap_or(1e-6),
            max_outer_iterations: self.max_iterations.unwrap_or(20_000),
            ..AdhesiveOptions::default()
        }
    }

    fn law(&self) -> Result<Box<dyn AdhesionLaw>> {
        let kind = self.law.unwrap_or(LawKind::None);
        if kind == LawKind::None {
            return Ok(Box::new(NoAdhesion));
        }
        let w0 = self
            .work_of_adhesion
            .context("adhesion needs --work-of-adhesion w0 [J/m^2]")?;
        let lj = || -> Result<LennardJones> {
            let z0 = self
                .z0
                .context("the Lennard-Jones laws need --z0 [m], the equilibrium separation")?;
            Ok(LennardJones::new(w0, z0)?)
        };
        Ok(match kind {
            LawKind::None => unreachable!("handled above"),
            LawKind::Surface => Box::new(SurfaceLaw(lj()?)),
            LawKind::Line => Box::new(LineLaw(lj()?)),
            LawKind::Point => Box::new(PointLaw(lj()?)),
            LawKind::Exponential => Box::new(ExponentialLaw::new(
                w0,
                self.range.context("the exponential law needs --range rho [m]")?,
            )?),
            LawKind::Dugdale => match (self.range, self.z0) {
                (Some(h0), _) => Box::new(DugdaleLaw::new(w0, h0)?),
                (None, Some(_)) => Box::new(DugdaleLaw::equivalent_to(&lj()?)),
                (None, None) => {
                    bail!("the Dugdale law needs --range h0 [m] (or --z0 for the LJ-equivalent one)")
                }
            },
        })
    }

    /// Builds the problem; call [`Case::fill_defaults`] first.
    pub fn build(&self) -> Result<Problem> {
        let e_star = self.modulus.context(
            "the composite modulus is required: --modulus E* [Pa] (or modulus = ... in the case file)",
        )?;
        if !(e_star.is_finite() && e_star > 0.0) {
            bail!("--modulus must be a finite E* > 0 Pa, got {e_star}");
        }
        let law = self.law()?;
        let kind = self.domain.unwrap_or(DomainKind::Periodic);
        let periodic = kind == DomainKind::Periodic;
        let mut heights = None;
        let domain = if let Some(path) = &self.surface {
            let options = ReadOptions {
                length_x: self.length,
                length_y: self.length_y,
                unit: self.unit.unwrap_or(1.0),
                periodic: true,
            };
            let s = io::read(path, &options).with_context(|| format!("reading {}", path.display()))?;
            let expected = (
                self.n.unwrap_or(s.grid.nx),
                self.ny.or(self.n).unwrap_or(s.grid.ny),
            );
            if expected != (s.grid.nx, s.grid.ny) {
                bail!(
                    "--n/--ny ask for {} x {} points, the surface file has {} x {}",
                    expected.0,
                    expected.1,
                    s.grid.nx,
                    s.grid.ny
                );
            }
            let d = Domain {
                nx: s.grid.nx,
                ny: s.grid.ny,
                dx: s.grid.dx(),
                dy: s.grid.dy(),
                periodic,
            };
            heights = Some(s.heights);
            d
        } else {
            let generated = self.rms_height.is_some() || self.rms_gradient.is_some();
            if self.sphere_radius.is_none() && self.wave_amplitude.is_none() && !generated {
                bail!(
                    "nothing to press: give --surface FILE, --rms-height/--rms-gradient (a generated \
                     surface) and/or --sphere-radius R or --wave-amplitude A [m]"
                );
            }
            let n = self.n.unwrap_or(256);
            let ny = self.ny.unwrap_or(n);
            let l = self
                .length
                .context("the grid needs its size: --length L [m] (and --n)")?;
            let ly = self.length_y.unwrap_or(l * ny as f64 / n as f64);
            let grid = Grid::new(n, ny, l, ly)?;
            if generated {
                let spec = SurfaceSpec {
                    grid,
                    psd: Psd::self_affine(
                        self.hurst.unwrap_or(0.8),
                        self.rolloff_wavelength.unwrap_or(l.max(ly) / 4.0),
                        self.cutoff_wavelength.unwrap_or(4.0 * grid.dx().max(grid.dy())),
                    ),
                    normalization: match (self.rms_height, self.rms_gradient) {
                        (Some(rq), _) => Normalization::RmsHeight(rq),
                        (None, Some(g)) => Normalization::RmsGradient(g),
                        _ => unreachable!("generated"),
                    },
                    amplitudes: Amplitudes::Exact,
                    seed: self.seed.unwrap_or(1),
                };
                heights = Some(surfgen::generate(&spec)?.heights);
            }
            Domain {
                nx: n,
                ny,
                dx: grid.dx(),
                dy: grid.dy(),
                periodic,
            }
        };
        let roughness = heights.as_ref().map(|h| h.view());
        let g0 = match (self.sphere_radius, self.wave_amplitude) {
            (Some(_), Some(_)) => bail!("give a sphere or a wave, not both"),
            (Some(r), None) => {
                let profile = if self.exact_sphere.unwrap_or(false) {
                    SphereProfile::Exact
                } else {
                    SphereProfile::Paraboloid
                };
                sphere(&domain, r, profile, roughness)?
            }
            (None, Some(amplitude)) => {
                if !periodic {
                    bail!("a wave repeats: it needs the periodic domain (--domain periodic)");
                }
                wave(&domain, amplitude, roughness)?
            }
            (None, None) => flat_on_rough(roughness.expect("checked above"))?,
        };
        let op: Box<dyn Compliance> = match kind {
            DomainKind::Periodic => Box::new(Periodic::new(domain, e_star)?),
            DomainKind::Free => Box::new(Free::new(domain, e_star)?),
        };
        let mut warnings = Vec::new();
        if law.name() != "none" {
            warnings.extend(solver::adhesive::resolution_warnings(
                &domain,
                e_star,
                law.as_ref(),
            ));
            if !domain.periodic {
                // The attraction beyond the grid is lost: the smallest gap on the border says how
                // much. The law's energy there, -V(g), is the share of w0 its tail holds beyond
                // that gap, and on a sphere (gap r^2/(2R) outside) the force the tail would add,
                // 2 pi R V(g), is that share of 2 pi R w0 (undeformed; `jkr-sphere`, edge at
                // 4.9 z0: 3.8 % estimated, 2.9 % measured at its pull-off, 2.5 z0 apart).
                let (ny, nx) = g0.dim();
                let border = g0
                    .indexed_iter()
                    .filter(|((j, i), _)| *j == 0 || *i == 0 || *j == ny - 1 || *i == nx - 1)
                    .map(|(_, g)| *g)
                    .fold(f64::INFINITY, f64::min);
                let share = law
                    .flat_potential()
                    .map(|v| -v.energy(border) / law.work_of_adhesion());
                if border < 10.0 * law.range() && share.is_none_or(|s| s > 1e-3) {
                    let held = share.map_or(String::new(), |s| {
                        format!(
                            " (the law holds {:.1} % of w0 beyond that gap: on a sphere, about that share \
                             of 2 pi R w0 is missing from the loads)",
                            100.0 * s
                        )
                    });
                    warnings.push(format!(
                        "the undeformed gap at the grid's edge is only {:.2} times the adhesive range: \
                         the attraction beyond the grid is cut off{held}; enlarge the box (gap >= 10 ranges)",
                        border / law.range()
                    ));
                }
            }
        }
        Ok(Problem {
            domain,
            op,
            g0,
            law,
            e_star,
            surface_hash: heights.as_ref().map(fingerprint),
            warnings,
        })
    }
}

/// Writes `summary.json` into `out`: the version, the resolved case, the surface's
/// fingerprint and the grid, then the run's own `results` (a JSON object).
pub fn write_summary(out: &Path, case: &impl Serialize, problem: &Problem, results: Value) -> Result<()> {
    let d = problem.domain;
    let mut summary = serde_json::json!({
        "version": env!("CARGO_PKG_VERSION"),
        "case": case,
        "surface_hash": problem.surface_hash,
        "grid": { "nx": d.nx, "ny": d.ny, "dx": d.dx, "dy": d.dy, "periodic": d.periodic },
    });
    if let (Value::Object(all), Value::Object(results)) = (&mut summary, results) {
        all.extend(results);
    }
    std::fs::write(
        out.join("summary.json"),
        serde_json::to_string_pretty(&summary)? + "\n",
    )?;
    Ok(())
}

/// Writes a field as `.npy` into `dir`.
pub fn write_field(dir: &Path, name: &str, field: &Array2<f64>) -> Result<()> {
    io::write_npy(field, &dir.join(format!("{name}.npy")))?;
    Ok(())
}

/// Runs `f` on the worker threads, so that the solvers' parallel passes do not each pay a
/// hand-off from the main thread (which dominates on small grids).
pub fn on_workers<R: Send>(f: impl FnOnce() -> R + Send) -> R {
    rayon::scope(|_| f())
}
