//! A contact case by its keys: geometry, material, adhesion and solver settings, and what a
//! single solve prescribes or the path a sweep follows, from a TOML case file, the command
//! line's flags (feature `clap`: each key a `--flag`, its doc comment the help text) or the
//! Python package's keywords, layered in that order, and the library problem it builds.
//! Every key is in SI units, stated in brackets where it is defined.
// The doc comments of the keys are also the command's help text: units stand in brackets.
#![allow(rustdoc::broken_intra_doc_links)]

pub mod memory;

use anyhow::{Context, Result, bail};
use ljadhesion::{
    AdhesionLaw, DugdaleLaw, ExponentialLaw, LennardJones, LineLaw, NoAdhesion, PointLaw, SurfaceEnergyLaw,
    SurfaceLaw,
};
use ndarray::Array2;
use serde::{Deserialize, Serialize, de::DeserializeOwned};
use serde_json::Value;
use solver::Control;
use solver::geometry::SphereProfile;
use solver::{ContactOptions, ContactProblem, Method, Settings, Shape};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use surfgen::io::{self, ReadOptions, Surface};
use surfgen::{Amplitudes, Anisotropy, Generated, Grid, Normalization, Psd, SurfError, SurfaceSpec};

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "snake_case")]
pub enum DomainKind {
    /// The pattern repeats (rough surfaces): spectral kernel.
    Periodic,
    /// An isolated contact (spheres): Love's coefficients with zero padding.
    Free,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "snake_case")]
pub enum LawKind {
    /// No adhesion.
    None,
    /// Lennard-Jones averaged over the tilted cell (the paper's Eq. 11).
    Surface,
    /// Minus the gradient of the Lennard-Jones energy integrated over the tilted cells: Eq. 11's
    /// energy form, which the energy descent minimises.
    SurfaceEnergy,
    /// Lennard-Jones averaged along x (Medina & Dini 2014).
    Line,
    /// Lennard-Jones at the node.
    Point,
    /// -(w0/range) exp(-g/range), the contact-mechanics challenge's law.
    Exponential,
    /// -w0/range for g < range (Maugis-Dugdale).
    Dugdale,
}

/// A contact case: every flag is also a key of the TOML case file (`--config`), with the same
/// name in snake_case. Flags override the file.
#[derive(Debug, Default, Clone, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[serde(default, deny_unknown_fields)]
pub struct Case {
    /// Rough surface file (.npy + sidecar, .txt, .xyz, .gsf, .x3p, .sdf, .nc, .tmd, .mi, .nid,
    /// .sur, .mnt, .opd, .di/.spm, .ibw, .frt, .gwy, .h5, .datx; `roughcontact info FILE` shows what a file
    /// holds): heights, peaks towards the counterface. With --sphere-radius the roughness sits on the sphere.
    #[cfg_attr(feature = "clap", arg(long))]
    pub surface: Option<PathBuf>,
    /// Generate the roughness instead of reading it: RMS height Rq [m].
    #[cfg_attr(feature = "clap", arg(long, conflicts_with = "surface"))]
    pub rms_height: Option<f64>,
    /// Generate the roughness instead of reading it: RMS gradient [-].
    #[cfg_attr(feature = "clap", arg(long, conflicts_with_all = ["surface", "rms_height"]))]
    pub rms_gradient: Option<f64>,
    /// Generated roughness: Hurst exponent H [-] (default 0.8).
    #[cfg_attr(feature = "clap", arg(long))]
    pub hurst: Option<f64>,
    /// Generated roughness: roll-off wavelength [m] (default: a quarter of the box).
    #[cfg_attr(feature = "clap", arg(long))]
    pub rolloff_wavelength: Option<f64>,
    /// Generated roughness: short-wavelength cut-off [m] (default: four cells).
    #[cfg_attr(feature = "clap", arg(long))]
    pub cutoff_wavelength: Option<f64>,
    /// Generated roughness: random seed (default 1); a seed fixes the surface bit for bit.
    #[cfg_attr(feature = "clap", arg(long))]
    pub seed: Option<u64>,
    /// Box side [m]: for a bare surface file, a generated surface or a smooth sphere's grid.
    #[cfg_attr(feature = "clap", arg(long))]
    pub length: Option<f64>,
    /// Box size along y [m] (default: square cells).
    #[cfg_attr(feature = "clap", arg(long))]
    pub length_y: Option<f64>,
    /// Metres per unit in the surface file.
    #[cfg_attr(feature = "clap", arg(long))]
    pub unit: Option<f64>,
    /// The surface file's channel of heights, by name or index (default: the first channel
    /// of heights; `roughcontact info FILE` lists them).
    #[cfg_attr(feature = "clap", arg(long))]
    pub channel: Option<String>,
    /// Fill the points the instrument marks as not measured by harmonic interpolation
    /// (default: refuse such a file, counting them).
    #[cfg_attr(feature = "clap", arg(long, num_args = 0..=1, require_equals = true, default_missing_value = "true"))]
    pub fill_unmeasured: Option<bool>,
    /// The largest fraction of the points --fill-unmeasured fills, in [0, 1] (default 0.25:
    /// beyond it the filled surface is more interpolation than measurement; 1 fills any).
    #[cfg_attr(feature = "clap", arg(long))]
    pub max_unmeasured: Option<f64>,
    /// Radius R of a rigid sphere [m], centred on the grid.
    #[cfg_attr(feature = "clap", arg(long))]
    pub sphere_radius: Option<f64>,
    /// Amplitude A of a rigid wave A cos(2 pi x / L) [m] (half its peak-to-valley height),
    /// one wavelength across the box along x, crest centred: Westergaard's and Johnson's
    /// (1995) wavy contact (periodic; `roughcontact theory wavy` gives their curves). With
    /// roughness, the roughness sits on the wave.
    #[cfg_attr(feature = "clap", arg(long, conflicts_with = "sphere_radius"))]
    pub wave_amplitude: Option<f64>,
    /// Use the exact spherical profile instead of the paraboloid r^2/(2R).
    #[cfg_attr(feature = "clap", arg(long, num_args = 0..=1, require_equals = true, default_missing_value = "true"))]
    pub exact_sphere: Option<bool>,
    /// Grid points per side (default 256); must match a surface file.
    #[cfg_attr(feature = "clap", arg(long))]
    pub n: Option<usize>,
    /// Grid points along y, when not --n (a wave needs a few: its problem is one-dimensional).
    #[cfg_attr(feature = "clap", arg(long))]
    pub ny: Option<usize>,
    /// Periodic or free boundaries (default: periodic for a rough flat, free with a sphere).
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub domain: Option<DomainKind>,
    /// Composite modulus E* [Pa].
    #[cfg_attr(feature = "clap", arg(long))]
    pub modulus: Option<f64>,
    /// Adhesive law (default: surface when --work-of-adhesion is given, none otherwise).
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub law: Option<LawKind>,
    /// Work of adhesion w0 [J/m^2].
    #[cfg_attr(feature = "clap", arg(long))]
    pub work_of_adhesion: Option<f64>,
    /// Lennard-Jones equilibrium separation z0 [m] (surface, line, point laws).
    #[cfg_attr(feature = "clap", arg(long))]
    pub z0: Option<f64>,
    /// Range of the exponential or Dugdale law [m] (Dugdale default: 0.974 z0 if --z0 given).
    #[cfg_attr(feature = "clap", arg(long))]
    pub range: Option<f64>,
    /// Adhesive solver (`auto` by default: the tested choice for the law and the control).
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub solver: Option<Method>,
    /// Convergence tolerance: without adhesion the scale-free gap residual (default 1e-8, at
    /// least 1e-13); with adhesion, in units of the law's range [-] (default 1e-6, the paper's
    /// criterion), for dual-loop and accelerated the outer residual (a mean gap error: loads
    /// to ~2e-4 of the peak at the default, 1e-8 gives ~1e-6), for energy, newton and flow the
    /// worst cell's force imbalance times its compliance.
    #[cfg_attr(feature = "clap", arg(long))]
    pub tolerance: Option<f64>,
    /// Iteration limit: conjugate-gradient iterations without adhesion (default 10000); with
    /// it (default 20000) outer iterations, descent iterations (energy), Newton steps or flow
    /// steps (flow: thousands a solve on coarse rough grids, more at the smallest loads).
    #[cfg_attr(feature = "clap", arg(long))]
    pub max_iterations: Option<usize>,
    /// Output directory (default: run/solve for solve, run/sweep for sweep); one that holds
    /// another run is refused unless --overwrite (or, for a sweep, --resume).
    #[cfg_attr(feature = "clap", arg(long))]
    pub out: Option<PathBuf>,
}

/// The keys a struct of options can take in a case file: its fields' names.
fn keys<T: Default + Serialize>() -> Vec<String> {
    match serde_json::to_value(T::default()) {
        Ok(Value::Object(m)) => m.keys().cloned().collect(),
        _ => Vec::new(),
    }
}

/// The first non-finite number in `table` (arrays included), with its key.
fn non_finite(table: &toml::Table) -> Option<(&str, f64)> {
    fn bad(v: &toml::Value) -> Option<f64> {
        match v {
            toml::Value::Float(x) if !x.is_finite() => Some(*x),
            toml::Value::Array(a) => a.iter().find_map(bad),
            _ => None,
        }
    }
    table.iter().find_map(|(k, v)| bad(v).map(|x| (k.as_str(), x)))
}

/// Reads a TOML case file (or text) into two option structs, each key going to the struct that
/// has it (unknown keys are an error), then lays every flag given on the command line over it.
/// Values stay typed TOML values throughout, so nothing given is lost; a NaN or infinite number
/// anywhere is refused, naming its key.
pub fn layered<A, B>(text: Option<(&str, &str)>, a: &A, b: &B) -> Result<(A, B)>
where
    A: Default + Serialize + DeserializeOwned,
    B: Default + Serialize + DeserializeOwned,
{
    let file = match text {
        Some((name, text)) => {
            let table: toml::Table = toml::from_str(text).with_context(|| format!("parsing {name}"))?;
            Some((name, table))
        }
        None => None,
    };
    let mut flags = toml::Table::try_from(a)?;
    flags.extend(toml::Table::try_from(b)?);
    if let Some((key, x)) = non_finite(&flags) {
        bail!("--{} must be a finite number, got {x}", key.replace('_', "-"));
    }
    split(file, flags)
}

/// Reads a case given as one table of keys (the Python package's keywords, a study's run) into
/// two option structs, each key going to the struct that has it; `name` says where the keys came
/// from in messages. Unknown keys, values of the wrong type and non-finite numbers are refused,
/// naming the key.
pub fn from_table<A, B>(name: &str, table: toml::Table) -> Result<(A, B)>
where
    A: Default + Serialize + DeserializeOwned,
    B: Default + Serialize + DeserializeOwned,
{
    split(Some((name, table)), toml::Table::new())
}

/// `file`'s keys sorted into the two structs, with `flags` (already sorted by name) laid over.
fn split<A, B>(file: Option<(&str, toml::Table)>, flags: toml::Table) -> Result<(A, B)>
where
    A: Default + Serialize + DeserializeOwned,
    B: Default + Serialize + DeserializeOwned,
{
    let (ka, kb) = (keys::<A>(), keys::<B>());
    let (mut ta, mut tb) = (toml::Table::new(), toml::Table::new());
    let source = file.as_ref().map_or("the flags", |(name, _)| *name).to_string();
    if let Some((name, table)) = file {
        if let Some((key, x)) = non_finite(&table) {
            bail!("{name}: `{key}` must be a finite number, got {x}");
        }
        for (k, v) in table {
            if ka.contains(&k) {
                ta.insert(k, v);
            } else if kb.contains(&k) {
                tb.insert(k, v);
            } else {
                let mut all = ka.clone();
                all.extend(kb.clone());
                all.sort();
                bail!("{name}: unknown key `{k}`; the keys are {}", all.join(", "));
            }
        }
    }
    for (k, v) in flags {
        if ka.contains(&k) {
            ta.insert(k, v);
        } else {
            tb.insert(k, v);
        }
    }
    let a = typed(&source, ta)?;
    let b = typed(&source, tb)?;
    Ok((a, b))
}

/// `table` as the option struct `T`; a value of the wrong type is refused naming its key, the
/// value given and what the key takes, in words rather than serde's.
fn typed<T: DeserializeOwned>(source: &str, table: toml::Table) -> Result<T> {
    match table.clone().try_into() {
        Ok(t) => Ok(t),
        Err(whole) => {
            // The culprit: the first key that does not deserialise on its own.
            for (key, value) in table {
                let alone: toml::Table = [(key.clone(), value.clone())].into_iter().collect();
                if let Err(e) = alone.try_into::<T>() {
                    bail!(
                        "{source}: `{key}` must be {}, got {}",
                        expected(&e.to_string()),
                        given(&value)
                    );
                }
            }
            bail!("{source}: {}", whole.to_string().trim())
        }
    }
}

/// What a key takes, from serde's "expected ..." in `message`.
fn expected(message: &str) -> String {
    let wanted = message
        .split("expected ")
        .nth(1)
        .map(|w| w.lines().next().unwrap_or(w).trim())
        .unwrap_or("");
    let wanted = wanted.split(" in `").next().unwrap_or(wanted);
    match wanted {
        "usize" | "u64" | "u32" => "a whole number >= 0".into(),
        "f64" | "f32" => "a number".into(),
        "a boolean" | "bool" => "true or false".into(),
        "path string" => "a path (a string)".into(),
        "a string" => "a string".into(),
        "a sequence" => "a list".into(),
        w if w.starts_with("one of") => w.replace('`', "\""),
        "" => "another type".into(),
        w => w.to_string(),
    }
}

/// A value as the user wrote it, with its type.
fn given(value: &toml::Value) -> String {
    let kind = match value {
        toml::Value::String(_) => "a string",
        toml::Value::Integer(_) => "an integer",
        toml::Value::Float(_) => "a number with a fraction",
        toml::Value::Boolean(_) => "a boolean",
        toml::Value::Datetime(_) => "a date",
        toml::Value::Array(_) => "a list",
        toml::Value::Table(_) => "a table",
    };
    let text = value.to_string();
    let text = if text.len() > 60 {
        format!("{}...", &text[..text.floor_char_boundary(57)])
    } else {
        text
    };
    format!("{text} ({kind})")
}

/// A path a case file gave (`from_file`: not overridden by a flag) is relative to that file's
/// directory, as in any file that names others; a flag's is relative to the working directory.
pub fn beside(config: Option<&Path>, from_file: bool, path: &mut Option<PathBuf>) {
    if let (Some(config), true, Some(p)) = (config, from_file, path.as_mut())
        && p.is_relative()
        && let Some(dir) = config.parent()
    {
        *p = dir.join(&*p);
    }
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

/// A built case: the library's problem and the fingerprint of its roughness (read or
/// generated), if any.
pub struct Built {
    pub problem: ContactProblem,
    pub surface_hash: Option<String>,
}

impl Case {
    /// Whether the case has adhesion.
    pub fn adhesive(&self) -> bool {
        !matches!(self.law, None | Some(LawKind::None)) || self.work_of_adhesion.is_some()
    }

    /// Fills in the defaults, so that the summary and `--print-config` show the whole case;
    /// `out` is the command's own default output directory.
    pub fn fill_defaults(&mut self, out: &str) {
        let adhesive = self.adhesive();
        self.domain = self.domain.or(Some(if self.sphere_radius.is_some() {
            DomainKind::Free
        } else {
            DomainKind::Periodic
        }));
        if adhesive {
            self.law = self.law.or(Some(LawKind::Surface));
            self.solver = self.solver.or(Some(Method::Auto));
        } else {
            self.law = Some(LawKind::None);
        }
        self.tolerance = self.tolerance.or(Some(if adhesive {
            Settings::DEFAULT_TOLERANCE
        } else {
            ContactOptions::DEFAULT_TOLERANCE
        }));
        self.max_iterations = self.max_iterations.or(Some(if adhesive {
            Settings::DEFAULT_MAX_ITERATIONS
        } else {
            ContactOptions::DEFAULT_MAX_ITERATIONS
        }));
        if self.rms_height.is_some() || self.rms_gradient.is_some() {
            self.hurst = self.hurst.or(Some(0.8));
            self.seed = self.seed.or(Some(1));
        }
        self.out = self.out.clone().or_else(|| Some(PathBuf::from(out)));
    }

    /// Checks the settings that apply (the adhesive ones or the non-adhesive ones), so that a
    /// bad one is refused before the output directory is touched.
    pub fn validate_settings(&self, adhesive: bool) -> Result<()> {
        if adhesive {
            self.settings().validate()?;
        } else {
            self.contact_options().validate()?;
        }
        Ok(())
    }

    /// The non-adhesive solve's settings.
    pub fn contact_options(&self) -> ContactOptions {
        ContactOptions {
            tolerance: self.tolerance.unwrap_or(ContactOptions::DEFAULT_TOLERANCE),
            max_iterations: self
                .max_iterations
                .unwrap_or(ContactOptions::DEFAULT_MAX_ITERATIONS),
            ..ContactOptions::default()
        }
    }

    /// The adhesive solve's settings: `--solver auto` is the library's [`Method::Auto`].
    pub fn settings(&self) -> Settings {
        Settings {
            method: self.solver.unwrap_or_default(),
            tolerance: self.tolerance.unwrap_or(Settings::DEFAULT_TOLERANCE),
            max_iterations: self.max_iterations.unwrap_or(Settings::DEFAULT_MAX_ITERATIONS),
            ..Settings::default()
        }
    }

    fn law(&self) -> Result<Arc<dyn AdhesionLaw>> {
        let kind = self.law.unwrap_or(LawKind::None);
        if kind == LawKind::None {
            return Ok(Arc::new(NoAdhesion));
        }
        let w0 = self
            .work_of_adhesion
            .context("adhesion needs --work-of-adhesion w0 [J/m^2]")?;
        let lj = || -> Result<LennardJones> {
            if let Some(range) = self.range {
                bail!(
                    "--range {range:e} does not apply to the Lennard-Jones laws, whose range is \
                     --z0 (--range is the exponential and Dugdale laws')"
                );
            }
            let z0 = self
                .z0
                .context("the Lennard-Jones laws need --z0 [m], the equilibrium separation")?;
            Ok(LennardJones::new(w0, z0)?)
        };
        Ok(match kind {
            LawKind::None => unreachable!("handled above"),
            LawKind::Surface => Arc::new(SurfaceLaw(lj()?)),
            LawKind::SurfaceEnergy => Arc::new(SurfaceEnergyLaw(lj()?)),
            LawKind::Line => Arc::new(LineLaw(lj()?)),
            LawKind::Point => Arc::new(PointLaw(lj()?)),
            LawKind::Exponential => Arc::new(ExponentialLaw::new(
                w0,
                self.range.context("the exponential law needs --range rho [m]")?,
            )?),
            LawKind::Dugdale => match (self.range, self.z0) {
                (Some(_), Some(_)) => {
                    bail!("the Dugdale law takes --range h0 [m] or --z0 (the LJ-equivalent one), not both")
                }
                (Some(h0), None) => Arc::new(DugdaleLaw::new(w0, h0)?),
                (None, Some(_)) => Arc::new(DugdaleLaw::equivalent_to(&lj()?)),
                (None, None) => {
                    bail!("the Dugdale law needs --range h0 [m] (or --z0 for the LJ-equivalent one)")
                }
            },
        })
    }

    /// Refuses every key given that the case would not use: a key of a surface file without
    /// one, a generated surface's keys without a generated surface, a sphere's without a
    /// sphere, adhesion's keys without adhesion or with a law that has no use for them. The one
    /// place where keys that do not apply are refused, so that the record of a run is always
    /// what was solved.
    pub fn check_applicable(&self) -> Result<()> {
        let file = self.surface.is_some();
        let generated = self.rms_height.is_some() || self.rms_gradient.is_some();
        let law = self.law.unwrap_or(if self.adhesive() {
            LawKind::Surface
        } else {
            LawKind::None
        });
        let lennard_jones = matches!(
            law,
            LawKind::Surface | LawKind::SurfaceEnergy | LawKind::Line | LawKind::Point
        );
        let refused: [(&str, bool, &str); 14] = [
            (
                "rms_height",
                self.rms_height.is_some() && (file || self.rms_gradient.is_some()),
                "scales a generated surface; give it or --rms-gradient, and no --surface beside",
            ),
            (
                "rms_gradient",
                self.rms_gradient.is_some() && file,
                "scales a generated surface; give no --surface beside",
            ),
            (
                "max_unmeasured",
                self.max_unmeasured.is_some() && !file,
                "bounds the filled points of a surface file: give --surface",
            ),
            (
                "unit",
                self.unit.is_some() && !file,
                "is a surface file's unit: give --surface",
            ),
            (
                "channel",
                self.channel.is_some() && !file,
                "is a surface file's channel: give --surface",
            ),
            (
                "fill_unmeasured",
                self.fill_unmeasured.is_some() && !file,
                "fills a surface file's unmeasured points: give --surface",
            ),
            (
                "hurst",
                self.hurst.is_some() && !generated,
                "shapes a generated surface: give --rms-height or --rms-gradient",
            ),
            (
                "rolloff_wavelength",
                self.rolloff_wavelength.is_some() && !generated,
                "shapes a generated surface: give --rms-height or --rms-gradient",
            ),
            (
                "cutoff_wavelength",
                self.cutoff_wavelength.is_some() && !generated,
                "shapes a generated surface: give --rms-height or --rms-gradient",
            ),
            (
                "seed",
                self.seed.is_some() && !generated,
                "seeds a generated surface: give --rms-height or --rms-gradient",
            ),
            (
                "exact_sphere",
                self.exact_sphere.is_some() && self.sphere_radius.is_none(),
                "shapes a sphere: give --sphere-radius",
            ),
            (
                "work_of_adhesion",
                self.work_of_adhesion.is_some() && law == LawKind::None,
                "needs an adhesive law, but --law none",
            ),
            (
                "z0",
                self.z0.is_some() && !(lennard_jones || law == LawKind::Dugdale),
                "is the Lennard-Jones laws' (and Dugdale's LJ-equivalent) equilibrium separation; \
                 this case has no such law",
            ),
            (
                "solver",
                self.solver.is_some() && law == LawKind::None,
                "chooses the adhesive solver; without adhesion the conjugate gradients solve",
            ),
        ];
        if let Some((key, _, why)) = refused.iter().find(|(_, given, _)| *given) {
            bail!(
                "--{} does not apply to this case: it {why}",
                key.replace('_', "-")
            );
        }
        Ok(())
    }

    /// Builds the problem; call [`Case::fill_defaults`] first.
    pub fn build(&self) -> Result<Built> {
        self.build_on(None)
    }

    /// Builds the problem on `roughness` (a surface in memory) instead of the `surface` file;
    /// call [`Case::fill_defaults`] first.
    pub fn build_on(&self, roughness: Option<Surface>) -> Result<Built> {
        self.check_applicable()?;
        let e_star = self.modulus.context(
            "the composite modulus is required: --modulus E* [Pa] (or modulus = ... in the case file)",
        )?;
        if !(e_star.is_finite() && e_star > 0.0) {
            bail!("--modulus must be a finite E* > 0 Pa, got {e_star}");
        }
        let law = self.law()?;
        let periodic = self.domain.unwrap_or(DomainKind::Periodic) == DomainKind::Periodic;
        let check_memory = |nx: usize, ny: usize, lx: f64, ly: f64| {
            let domain = elastic::Domain {
                nx,
                ny,
                dx: lx / nx as f64,
                dy: ly / ny as f64,
                periodic,
            };
            // Auto as under approach control: the larger of its choices.
            let method = (law.work_of_adhesion() > 0.0).then(|| {
                self.settings()
                    .method
                    .resolve(law.as_ref(), solver::Control::Approach(0.0), &domain, e_star)
            });
            crate::memory::check(
                &format!("a {nx} x {ny} solve"),
                solver::memory_estimate(nx, ny, periodic, method),
            )
        };
        let mut builder = ContactProblem::builder()
            .modulus(e_star)
            .shared_law(law.clone())
            .periodic(periodic);
        let mut heights = None;
        let mut filled = None;
        let size;
        let roughness = match (roughness, &self.surface) {
            (Some(_), Some(path)) => bail!(
                "give the roughness once: a surface in memory or the file {}",
                path.display()
            ),
            (Some(s), None) => {
                for (key, given) in [
                    ("length", self.length.is_some()),
                    ("length_y", self.length_y.is_some()),
                    ("unit", self.unit.is_some()),
                    ("channel", self.channel.is_some()),
                    ("fill_unmeasured", self.fill_unmeasured.is_some()),
                    ("max_unmeasured", self.max_unmeasured.is_some()),
                ] {
                    if given {
                        bail!("`{key}` applies to a surface file; a surface in memory carries its own size");
                    }
                }
                Some(s)
            }
            (None, Some(path)) => {
                let options = ReadOptions {
                    length_x: self.length,
                    length_y: self.length_y,
                    unit: self.unit.unwrap_or(1.0),
                    periodic: true,
                    channel: None,
                    unmeasured: io::Unmeasured::filled_up_to(
                        self.fill_unmeasured == Some(true),
                        self.max_unmeasured,
                    )?,
                };
                let read = options
                    .with_channel(path, self.channel.as_deref())
                    .and_then(|options| io::read_noting(path, &options));
                let (surface, note) = read
                    .map_err(|e| naming("reading", path, e))
                    .context("--surface")?;
                filled = note;
                Some(surface)
            }
            (None, None) => None,
        };
        if let Some(s) = roughness {
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
            check_memory(s.grid.nx, s.grid.ny, s.grid.length_x, s.grid.length_y).with_context(|| {
                format!(
                    "the surface file (--surface) of {} x {} points",
                    s.grid.nx, s.grid.ny
                )
            })?;
            size = (s.grid.length_x, s.grid.length_y);
            heights = Some(s.heights);
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
            for (key, points) in [("n", n), ("ny", ny)] {
                if points < 2 {
                    bail!("--{key} must be at least 2 grid points, got {points}");
                }
            }
            if !(l > 0.0 && l <= surfgen::grid::MAX_LENGTH) {
                bail!("--length must be > 0 m and at most 1e100 m, got {l:?}");
            }
            let ly = self.length_y.unwrap_or(l * ny as f64 / n as f64);
            if !(ly > 0.0 && ly <= surfgen::grid::MAX_LENGTH) {
                bail!("--length-y must be > 0 m and at most 1e100 m, got {ly:?}");
            }
            let grid = Grid::new(n, ny, l, ly)?;
            check_memory(n, ny, l, ly).with_context(|| format!("--n {n}, --ny {ny}"))?;
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
            builder = builder.grid(n, ny, grid.length_x, grid.length_y);
            size = (grid.length_x, grid.length_y);
        }
        let surface_hash = heights.as_ref().map(fingerprint);
        if let Some(h) = heights {
            builder = builder.roughness(h, size.0, size.1);
        }
        builder = match (self.sphere_radius, self.wave_amplitude) {
            (Some(_), Some(_)) => bail!("give --sphere-radius or --wave-amplitude, not both"),
            (Some(radius), None) => builder.shape(Shape::Sphere {
                radius,
                profile: if self.exact_sphere.unwrap_or(false) {
                    SphereProfile::Exact
                } else {
                    SphereProfile::Paraboloid
                },
            }),
            (None, Some(amplitude)) => {
                if self.domain == Some(DomainKind::Free) {
                    bail!("a wave repeats: it needs the periodic domain (--domain periodic)");
                }
                builder.wave(amplitude)
            }
            (None, None) => builder,
        };
        let mut problem = builder.build()?;
        problem.warnings.extend(filled);
        Ok(Built {
            problem,
            surface_hash,
        })
    }
}

/// A surface file's error, with the file named once: the reader's own errors already name it.
pub fn naming(verb: &str, path: &Path, e: SurfError) -> anyhow::Error {
    match e {
        SurfError::Io { .. } | SurfError::Parse { .. } => e.into(),
        _ => anyhow::Error::from(e).context(format!("{verb} {}", path.display())),
    }
}

/// What a single solve prescribes (keys of the case file like the others).
#[derive(Debug, Default, Clone, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[serde(default, deny_unknown_fields)]
pub struct SolveControl {
    /// Load control: mean pressure over the box [Pa] (negative pulls, with adhesion).
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub mean_pressure: Option<f64>,
    /// Load control: total normal force [N] (negative pulls, with adhesion).
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub load: Option<f64>,
    /// Displacement control: approach from first touch [m], positive pushes together
    /// (negative holds the bodies apart, with adhesion).
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub approach: Option<f64>,
    /// Displacement control by the mean gap over the box [m] (periodic domains, where the
    /// mean displacement is zero: the approach is mean(initial gap) - mean gap).
    #[cfg_attr(feature = "clap", arg(long))]
    pub mean_gap: Option<f64>,
}

impl SolveControl {
    /// The library's control for `problem`: exactly one key must be given.
    pub fn control(&self, problem: &ContactProblem) -> Result<Control> {
        Ok(
            match (self.mean_pressure, self.load, self.approach, self.mean_gap) {
                (Some(p), None, None, None) => Control::MeanPressure(p),
                (None, Some(w), None, None) => Control::Force(w),
                (None, None, Some(d), None) => Control::Approach(d),
                (None, None, None, Some(g)) => {
                    if !problem.domain().periodic {
                        bail!(
                            "--mean-gap needs a periodic domain (on a free one the mean displacement is not zero)"
                        );
                    }
                    if !(g.is_finite() && g >= 0.0) {
                        bail!("--mean-gap must be finite and >= 0 m, got {g}");
                    }
                    Control::Approach(problem.initial_gap.mean().unwrap_or(0.0) - g)
                }
                _ => bail!(
                    "give exactly one of --mean-pressure [Pa], --load [N], --approach [m] or --mean-gap [m]"
                ),
            },
        )
    }
}

/// The path of a sweep (keys of the case file like the others).
#[derive(Debug, Default, Clone, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[serde(default, deny_unknown_fields)]
pub struct SweepPath {
    /// Approach at the start and the end of the cycle [m] (negative: bodies apart).
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub from: Option<f64>,
    /// Turning point of the cycle [m].
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub to: Option<f64>,
    /// Steps from --from to --to; the way back takes as many again (default 20).
    #[cfg_attr(feature = "clap", arg(long))]
    pub steps: Option<usize>,
    /// Explicit approaches [m], comma-separated, solved in this order.
    #[cfg_attr(feature = "clap", arg(long, value_delimiter = ',', allow_hyphen_values = true, conflicts_with_all = ["from", "to", "steps"]))]
    pub approaches: Option<Vec<f64>>,
    /// Explicit mean pressures [Pa] (load control), comma-separated, in this order.
    #[cfg_attr(feature = "clap", arg(long, value_delimiter = ',', allow_hyphen_values = true, conflicts_with_all = ["from", "to", "steps", "approaches"]))]
    pub mean_pressures: Option<Vec<f64>>,
    /// Explicit central gaps [m] (> 0), comma-separated: the approach follows, which traces the
    /// unstable middle of a sphere's S-shaped curve.
    #[cfg_attr(feature = "clap", arg(long, value_delimiter = ',', conflicts_with_all = ["from", "to", "steps", "approaches", "mean_pressures"]))]
    pub central_gaps: Option<Vec<f64>>,
    /// Largest change of approach or central gap between two solves [m]: a longer step is
    /// split into substeps that are solved (their iterations count in curve.csv) but not
    /// written, which keeps the sweep quasi-static [default: the adhesive law's range, z0 for
    /// Lennard-Jones; no splitting without adhesion]. Load steps are never split.
    #[cfg_attr(feature = "clap", arg(long))]
    pub max_step: Option<f64>,
    /// Start from a saved state instead of apart: a sweep's output directory (its last state),
    /// its `state/`, or one of its `states/step-NNNN` (with --save-states), on the same grid.
    /// To continue a cycle with another law, solver, tolerance or path.
    #[cfg_attr(feature = "clap", arg(long, value_name = "DIR"))]
    pub start_from: Option<PathBuf>,
    /// Find the pull-off force: the path goes in only (from --from to --to in --steps, or the
    /// --approaches), then unloads from its last state in steps of this size [m] until the
    /// load has come back from its minimum, and again around the minimum in finer steps.
    #[cfg_attr(feature = "clap", arg(long))]
    pub pull_off_step: Option<f64>,
    /// The lowest approach the pull-off search unloads to [m] (negative: bodies apart).
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub pull_off_floor: Option<f64>,
    /// Finer steps per coarse step around the lowest load of the pull-off search (1: none)
    /// [default: 5].
    #[cfg_attr(feature = "clap", arg(long))]
    pub pull_off_refinement: Option<usize>,
    /// The pull-off search stops once the load has come back above this fraction of its
    /// lowest, in (0, 1] [default: 0.5].
    #[cfg_attr(feature = "clap", arg(long))]
    pub pull_off_recovery: Option<f64>,
    /// Steps (counted from 0, comma-separated) whose fields are also kept in
    /// states/step-NNNN, as --save-states keeps every step's.
    #[cfg_attr(feature = "clap", arg(long, value_delimiter = ','))]
    pub keep_steps: Option<Vec<usize>>,
}

/// The memory a step of a sweep keeps until the end [bytes]: its control, its report and its
/// row of the summary (the report's residual history aside).
const STEP_BYTES: f64 = (std::mem::size_of::<Control>()
    + std::mem::size_of::<solver::SweepPoint>()
    + std::mem::size_of::<solver::CyclePoint>()) as f64;

impl SweepPath {
    /// Fills in the default number of steps of a cycle.
    pub fn fill_defaults(&mut self) {
        if self.approaches.is_none() && self.mean_pressures.is_none() && self.central_gaps.is_none() {
            self.steps = self.steps.or(Some(20));
        }
    }

    /// The controls of the path, in order: a cycle from `from` to `to` and back, or the
    /// explicit list given.
    pub fn controls(&self) -> Result<Vec<Control>> {
        let search = self.pull_off()?;
        if search.is_some() && (self.mean_pressures.is_some() || self.central_gaps.is_some()) {
            bail!(
                "the pull-off search follows an approach path: give --from/--to or --approaches, \
                 not --mean-pressures or --central-gaps"
            );
        }
        let controls: Vec<Control> = match (&self.approaches, &self.mean_pressures, &self.central_gaps) {
            (Some(a), None, None) => a.iter().map(|&v| Control::Approach(v)).collect(),
            (None, Some(p), None) => p.iter().map(|&v| Control::MeanPressure(v)).collect(),
            (None, None, Some(g)) => g.iter().map(|&v| Control::CentralGap(v)).collect(),
            (None, None, None) => {
                let (from, to) = match (self.from, self.to) {
                    (Some(f), Some(t)) => (f, t),
                    _ => bail!(
                        "give the path: --from A --to B [m] (--steps N), or --approaches, --mean-pressures or \
                         --central-gaps, or run a built-in case with --example"
                    ),
                };
                let steps = self.steps.unwrap_or(20);
                if steps == 0 {
                    bail!("--steps must be at least 1 (steps from --from to --to; as many back)");
                }
                memory::check(
                    &format!("a sweep of {} steps", 2 * steps as u64 + 1),
                    (2.0 * steps as f64 + 1.0) * STEP_BYTES,
                )?;
                let mut cycle = solver::approach_cycle(from, to, steps);
                if search.is_some() {
                    // The way in only: the search is the way out.
                    cycle.truncate(steps + 1);
                }
                cycle
            }
            _ => bail!("give one path only"),
        };
        if controls.is_empty() {
            bail!("the sweep path is empty");
        }
        if controls.iter().any(|c| {
            let (Control::Approach(v)
            | Control::MeanPressure(v)
            | Control::Force(v)
            | Control::CentralGap(v)) = *c;
            !v.is_finite()
        }) {
            bail!("the sweep path has a non-finite value");
        }
        // Without a pull-off search (whose steps are numbered on after the path's) a kept step
        // beyond the path would keep nothing.
        if let (None, Some(k)) = (
            search,
            self.keep_steps.iter().flatten().find(|&&k| k >= controls.len()),
        ) {
            bail!(
                "--keep-steps {k}: the path has {} steps, numbered 0 to {}",
                controls.len(),
                controls.len() - 1
            );
        }
        if let (Some(s), Some(Control::Approach(last))) = (search, controls.last())
            && s.floor >= *last
        {
            bail!(
                "--pull-off-floor ({:e} m) must be below the path's last approach ({last:e} m)",
                s.floor
            );
        }
        Ok(controls)
    }

    /// The pull-off search after the path, if asked for (`pull_off_step`), checked.
    pub fn pull_off(&self) -> Result<Option<solver::PullOffSearch>> {
        let Some(step) = self.pull_off_step else {
            if self.pull_off_floor.is_some()
                || self.pull_off_refinement.is_some()
                || self.pull_off_recovery.is_some()
            {
                bail!("the pull-off search's settings need --pull-off-step [m], which asks for it");
            }
            return Ok(None);
        };
        if !(step.is_finite() && step > 0.0) {
            bail!("--pull-off-step must be a positive length [m], got {step}");
        }
        let Some(floor) = self.pull_off_floor else {
            bail!("--pull-off-step needs --pull-off-floor, the lowest approach to unload to [m]");
        };
        if !floor.is_finite() {
            bail!("--pull-off-floor must be finite [m], got {floor}");
        }
        let refinement = self.pull_off_refinement.unwrap_or(5);
        if refinement == 0 {
            bail!("--pull-off-refinement must be at least 1 (1: no refinement)");
        }
        let recovery = self.pull_off_recovery.unwrap_or(0.5);
        if !(recovery > 0.0 && recovery <= 1.0) {
            bail!("--pull-off-recovery must be in (0, 1], got {recovery}");
        }
        Ok(Some(solver::PullOffSearch {
            step,
            floor,
            recovery: Some(recovery),
            refinement,
        }))
    }

    /// The largest step between two solves [m] on `problem` (`None`: no splitting), checked
    /// against `controls`.
    pub fn max_step(&self, problem: &ContactProblem, controls: &[Control]) -> Result<Option<f64>> {
        if let Some(h) = self.max_step
            && controls
                .iter()
                .all(|c| matches!(c, Control::MeanPressure(_) | Control::Force(_)))
        {
            bail!(
                "--max-step {h:e} does not apply to a path of loads: load steps are never split \
                 (it splits approach and central-gap steps)"
            );
        }
        let max_step = self.max_step.or(problem.adhesive().then(|| problem.law.range()));
        if let Some(h) = max_step
            && !(h.is_finite() && h > 0.0)
        {
            bail!("--max-step must be a positive length [m], got {h}");
        }
        solver::count_substeps(controls, max_step)?;
        Ok(max_step)
    }
}

/// A generated self-affine surface by its keys (`roughcontact generate`'s flags, the Python
/// package's `generate` keywords).
#[derive(Debug, Clone, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[serde(default, deny_unknown_fields)]
pub struct Generation {
    /// Grid points per side of a square grid [default: 1024]; or --nx and --ny.
    #[cfg_attr(feature = "clap", arg(long))]
    pub n: Option<usize>,
    /// Grid points along x.
    #[cfg_attr(feature = "clap", arg(long))]
    pub nx: Option<usize>,
    /// Grid points along y.
    #[cfg_attr(feature = "clap", arg(long))]
    pub ny: Option<usize>,
    /// Side of the square periodic box [m] [default: 1e-4]; or --length-x and --length-y.
    #[cfg_attr(feature = "clap", arg(long))]
    pub length: Option<f64>,
    /// Box size along x [m].
    #[cfg_attr(feature = "clap", arg(long))]
    pub length_x: Option<f64>,
    /// Box size along y [m].
    #[cfg_attr(feature = "clap", arg(long))]
    pub length_y: Option<f64>,
    /// Hurst exponent H in (0, 1) (fractal dimension 3 - H).
    #[cfg_attr(feature = "clap", arg(long, default_value_t = 0.8))]
    pub hurst: f64,
    /// Roll-off wavelength lambda_r [m]: the spectrum is flat at longer wavelengths.
    #[cfg_attr(feature = "clap", arg(long, default_value_t = 2e-5))]
    pub rolloff: f64,
    /// Short-wavelength cut-off lambda_s [m] (default: 4 grid spacings, the shortest that
    /// finite differences resolve to a few per cent).
    #[cfg_attr(feature = "clap", arg(long))]
    pub cutoff: Option<f64>,
    /// Long-wavelength cut-off lambda_L [m]: no roughness at longer wavelengths.
    #[cfg_attr(feature = "clap", arg(long))]
    pub long_cutoff: Option<f64>,
    /// Scale to this RMS height Rq [m].
    #[cfg_attr(feature = "clap", arg(long, group = "scale"))]
    pub rms_height: Option<f64>,
    /// Scale to this RMS gradient sqrt(<|grad h|^2>) [-] (the default, 1, when no scale is given).
    #[cfg_attr(feature = "clap", arg(long, group = "scale"))]
    pub rms_gradient: Option<f64>,
    /// Scale to this peak-to-valley height [m].
    #[cfg_attr(feature = "clap", arg(long, group = "scale"))]
    pub peak_to_valley: Option<f64>,
    /// Scale to this PSD plateau C0 [m^4] (Persson's convention: <h^2> = integral d^2q C(q)).
    #[cfg_attr(feature = "clap", arg(long, group = "scale"))]
    pub prefactor: Option<f64>,
    /// Random (Rayleigh) amplitudes, a Gaussian random field; default: exact amplitudes, random phases.
    #[cfg_attr(feature = "clap", arg(long))]
    pub rayleigh: bool,
    /// Anisotropy: correlation lengths along --angle are this many times those across it (1 = isotropic).
    #[cfg_attr(feature = "clap", arg(long, default_value_t = 1.0))]
    pub anisotropy: f64,
    /// Direction of the longer correlation, from the x axis [degrees].
    #[cfg_attr(feature = "clap", arg(long, default_value_t = 0.0))]
    pub angle: f64,
    /// Random seed: the same seed gives the same surface, bit for bit.
    #[cfg_attr(feature = "clap", arg(long, default_value_t = 0))]
    pub seed: u64,
}

impl Default for Generation {
    /// The command line's defaults.
    fn default() -> Self {
        Generation {
            n: None,
            nx: None,
            ny: None,
            length: None,
            length_x: None,
            length_y: None,
            hurst: 0.8,
            rolloff: 2e-5,
            cutoff: None,
            long_cutoff: None,
            rms_height: None,
            rms_gradient: None,
            peak_to_valley: None,
            prefactor: None,
            rayleigh: false,
            anisotropy: 1.0,
            angle: 0.0,
            seed: 0,
        }
    }
}

impl Generation {
    /// Grid points per side when neither `n` nor `nx`/`ny` is given.
    pub const DEFAULT_N: usize = 1024;
    /// The box's side [m] when neither `length` nor `length_x`/`length_y` is given.
    pub const DEFAULT_LENGTH: f64 = 1e-4;

    /// The generator's specification: at most one scale (RMS gradient 1 when none is given).
    pub fn spec(&self) -> Result<SurfaceSpec> {
        // A side given twice (`n` and `nx`) would drop one of them without a word.
        if self.n.is_some() && (self.nx.is_some() || self.ny.is_some()) {
            bail!("give --n (a square grid) or --nx and --ny, not both");
        }
        if self.length.is_some() && (self.length_x.is_some() || self.length_y.is_some()) {
            bail!("give --length (a square box) or --length-x and --length-y, not both");
        }
        let n = self.n.unwrap_or(Self::DEFAULT_N);
        let length = self.length.unwrap_or(Self::DEFAULT_LENGTH);
        let (nx, ny) = (self.nx.unwrap_or(n), self.ny.unwrap_or(n));
        let grid = Grid::new(
            nx,
            ny,
            self.length_x.unwrap_or(length),
            self.length_y.unwrap_or(length),
        )?;
        let scales = [
            self.rms_height,
            self.rms_gradient,
            self.peak_to_valley,
            self.prefactor,
        ];
        let normalization = match scales {
            [None, None, None, None] => Normalization::RmsGradient(1.0),
            [Some(v), None, None, None] => Normalization::RmsHeight(v),
            [None, Some(v), None, None] => Normalization::RmsGradient(v),
            [None, None, Some(v), None] => Normalization::PeakToValley(v),
            [None, None, None, Some(v)] => Normalization::Prefactor(v),
            _ => bail!(
                "give one scale: rms_height [m], rms_gradient [-], peak_to_valley [m] or prefactor [m^4]"
            ),
        };
        Ok(SurfaceSpec {
            grid,
            psd: Psd {
                hurst: self.hurst,
                rolloff_wavelength: self.rolloff,
                cutoff_wavelength: self.cutoff.unwrap_or(4.0 * grid.dx().max(grid.dy())),
                long_cutoff_wavelength: self.long_cutoff,
                anisotropy: Anisotropy {
                    ratio: self.anisotropy,
                    angle: self.angle.to_radians(),
                },
            },
            normalization,
            amplitudes: if self.rayleigh {
                Amplitudes::Rayleigh
            } else {
                Amplitudes::Exact
            },
            seed: self.seed,
        })
    }

    /// The surface, with the specification it was made from (after checking that the machine
    /// can hold it).
    pub fn generate(&self) -> Result<(SurfaceSpec, Generated)> {
        let spec = self.spec()?;
        let (nx, ny) = (spec.grid.nx, spec.grid.ny);
        memory::check(
            &format!("a {nx} x {ny} surface"),
            surfgen::generate::memory_estimate(nx, ny),
        )?;
        let cutoff = spec.psd.cutoff_wavelength;
        let generated = surfgen::generate(&spec).map_err(|e| match (self.cutoff, &e) {
            (None, SurfError::InvalidParameter { name, .. }) if *name == "cutoff_wavelength" => {
                anyhow::anyhow!(
                    "a {nx} x {ny} grid is too coarse for the default cut-off wavelength (4 grid spacings, \
                 {cutoff:e} m): no wavevector of the grid is in the spectrum's band; give more points (--n) \
                 or --cutoff and --rolloff [m]"
                )
            }
            _ => e.into(),
        })?;
        Ok((spec, generated))
    }
}
