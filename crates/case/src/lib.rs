//! A contact case by its keys: geometry, material, adhesion and solver settings, and what a
//! single solve prescribes or the path a sweep follows, from a TOML case file, the command
//! line's flags (feature `clap`: each key a `--flag`, its doc comment the help text) or the
//! Python package's keywords, layered in that order, and the library problem it builds.
//! Every key is in SI units, stated in brackets where it is defined.
// The doc comments of the keys are also the command's help text: units stand in brackets.
#![allow(rustdoc::broken_intra_doc_links)]

mod build;
pub mod error;
mod generation;
mod keys;
mod law;
pub mod memory;
mod path;

pub use build::naming;
pub use error::{Error, Result};
pub use generation::Generation;
pub use keys::{beside, fingerprint, from_table, layered, to_toml};
pub use law::LawKind;
pub use path::{SolveControl, SweepPath};

use serde::{Deserialize, Serialize};
use solver::{ContactOptions, ContactProblem, Method, Settings};
use std::path::PathBuf;

#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "snake_case")]
pub enum DomainKind {
    /// The pattern repeats (rough surfaces): spectral kernel.
    Periodic,
    /// An isolated contact (spheres): Love's coefficients with zero padding.
    Free,
}

/// How a layer meets its rigid base.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "snake_case")]
pub enum LayerBase {
    /// Bonded: no slip at the base.
    Bonded,
    /// Frictionless: the layer slides on the base.
    Frictionless,
    /// An elastic substrate (a coating), bonded: give --substrate-modulus and
    /// --substrate-poisson.
    Elastic,
}

/// What presses the body, for a tangential path.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
#[serde(rename_all = "snake_case")]
pub enum Counterface {
    /// Of the body's material (--modulus the pair's E*): normal and tangential loads do not
    /// couple, the pressure stays the normal solution's.
    Similar,
    /// Rigid: the shear changes the pressure and the pressure the slip (on a half-space for
    /// --poisson below 0.5; a layer, held by its base, also at 0.5); each step iterates the
    /// two solves.
    Rigid,
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
    /// Composite modulus E* [Pa]; with --thickness, the layer's plane-strain modulus
    /// E / (1 - nu^2).
    #[cfg_attr(feature = "clap", arg(long))]
    pub modulus: Option<f64>,
    /// Thickness h [m] of an elastic layer on a rigid base, in place of the half-space (a film
    /// or coating; needs --poisson). On periodic grids the approach is then measured from the
    /// base.
    #[cfg_attr(feature = "clap", arg(long))]
    pub thickness: Option<f64>,
    /// Poisson's ratio nu [-], in (-1, 0.5] (0.5: incompressible): a layer's, or the body's
    /// for a tangential path (its shear modulus is then E* (1 - nu) / 2, against a rigid
    /// counterface).
    #[cfg_attr(feature = "clap", arg(long))]
    pub poisson: Option<f64>,
    /// What the layer lies on: a rigid base, bonded or frictionless, or an elastic substrate
    /// (default bonded).
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub layer_base: Option<LayerBase>,
    /// The substrate's plane-strain modulus E / (1 - nu^2) under a coating [Pa] (with
    /// --layer-base elastic).
    #[cfg_attr(feature = "clap", arg(long))]
    pub substrate_modulus: Option<f64>,
    /// The substrate's Poisson's ratio under a coating [-], in (-1, 0.5) (with --layer-base
    /// elastic).
    #[cfg_attr(feature = "clap", arg(long))]
    pub substrate_poisson: Option<f64>,
    /// Penetration hardness H [Pa] of an elastic-perfectly-plastic surface: the compressive
    /// contact pressure never exceeds it, and where it would the surface yields and keeps the
    /// overlap as permanent set (default: elastic).
    #[cfg_attr(feature = "clap", arg(long))]
    pub hardness: Option<f64>,
    /// Coulomb's friction coefficient mu [-] (>= 0) of a tangential path: a contact cell carries
    /// a shear up to --shear-strength + mu times its pressure. Needs --poisson.
    #[cfg_attr(feature = "clap", arg(long))]
    pub friction_coefficient: Option<f64>,
    /// Shear strength tau0 [Pa] (>= 0) of a contact cell at no pressure, for a tangential path
    /// (Derjaguin's adhesive friction; default 0).
    #[cfg_attr(feature = "clap", arg(long))]
    pub shear_strength: Option<f64>,
    /// What presses the body along a tangential path (default similar: the decoupled problem).
    #[cfg_attr(feature = "clap", arg(long, value_enum))]
    pub counterface: Option<Counterface>,
    /// A viscoelastic body (generalized Maxwell solid): the moduli E_k [Pa] of its branches,
    /// comma-separated, beside the relaxed --modulus; the glassy modulus is their sum with it.
    /// Needs --maxwell-times, and times for a sweep's steps (--step-time or `times`).
    #[cfg_attr(feature = "clap", arg(long, value_delimiter = ','))]
    pub maxwell_moduli: Option<Vec<f64>>,
    /// The relaxation times tau_k [s] of the branches, comma-separated, one a --maxwell-moduli.
    #[cfg_attr(feature = "clap", arg(long, value_delimiter = ','))]
    pub maxwell_times: Option<Vec<f64>>,
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

    /// Whether the case has friction (a tangential path's interface).
    pub fn frictional(&self) -> bool {
        self.friction_coefficient.is_some() || self.shear_strength.is_some()
    }

    /// Refuses friction where no tangential path can follow (a sweep): the path follows a
    /// single normal solve.
    pub fn refuse_friction(&self) -> Result<()> {
        if self.frictional() {
            return Err(Error::Key(
                "--friction-coefficient, --shear-strength and --counterface set a tangential path, \
                 which follows a single normal solve: `roughcontact solve ... --tangential-loads` (a sweep has \
                 none)"
                    .into(),
            ));
        }
        Ok(())
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
}
