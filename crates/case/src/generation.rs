//! A generated self-affine surface by its keys.

use crate::error::{Result, bail};
use crate::memory;
use serde::{Deserialize, Serialize};
use surfgen::{Amplitudes, Anisotropy, Generated, Grid, Normalization, Psd, SurfError, SurfaceSpec};

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
                crate::Error::Key(format!(
                    "a {nx} x {ny} grid is too coarse for the default cut-off wavelength (4 grid spacings, \
                 {cutoff:e} m): no wavevector of the grid is in the spectrum's band; give more points (--n) \
                 or --cutoff and --rolloff [m]"
                ))
            }
            _ => e.into(),
        })?;
        Ok((spec, generated))
    }
}
