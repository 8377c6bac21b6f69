//! Random periodic self-affine surfaces (docs/method.md section 5, the paper's Eq. 13).
//!
//! Each Fourier coefficient gets the amplitude `sqrt(C(q))` (exactly, or times a Rayleigh
//! variate) and a uniformly random phase; the coefficients of `kx = 0` and of the Nyquist
//! column are mirrored so that the surface is real, and `C(0) = 0` makes its mean zero.
//!
//! Reproducibility: the random numbers of the column `kx` come from stream `kx` of a ChaCha8
//! generator seeded with the `seed`, one draw per coefficient in `ky` order, so a seed fixes the
//! surface bit for bit on every platform and for every number of threads.

use crate::error::{Result, SurfError};
use crate::grid::Grid;
use crate::psd::Psd;
use crate::stats::Analysis;
use fft2::Complex64;
use fft2::Fft2;
use ndarray::{Array2, Axis};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// How the random coefficients' magnitudes are drawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Amplitudes {
    /// `|h_q| = sqrt(C(q))` exactly: every realisation has the target spectrum, only phases vary.
    #[default]
    Exact,
    /// `|h_q| = sqrt(C(q)) * r`, `r` Rayleigh distributed with `<r^2> = 1`: a Gaussian random field.
    Rayleigh,
}

/// What sets the surface's scale.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Normalization {
    /// Root-mean-square height Rq \[m\].
    RmsHeight(f64),
    /// Root-mean-square gradient `sqrt(<|grad h|^2>)` [-], computed spectrally.
    RmsGradient(f64),
    /// Peak-to-valley height `max - min` \[m\].
    PeakToValley(f64),
    /// The plateau `C0` of the spectrum [m^4] (see [`crate::psd`] for the convention).
    Prefactor(f64),
}

/// Everything that defines a generated surface.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct SurfaceSpec {
    pub grid: Grid,
    pub psd: Psd,
    pub normalization: Normalization,
    pub amplitudes: Amplitudes,
    /// Seed of the random phases (and amplitudes).
    pub seed: u64,
}

/// A generated surface with what was learnt while making it.
#[derive(Clone, Debug)]
pub struct Generated {
    /// Heights \[m\], shape `(ny, nx)`, zero mean.
    pub heights: Array2<f64>,
    /// Spectral moments and radial PSD (10 bins per decade) of the final surface, exact,
    /// from its own spectrum.
    pub analysis: Analysis,
    /// The plateau `C0` of the realised spectrum [m^4].
    pub prefactor: f64,
    /// Legal but suspicious parameter choices (see [`Psd::validate`]).
    pub warnings: Vec<String>,
}

/// A uniform variate in `[0, 1)` from the top 53 bits of a `u64`: portable and exact.
fn unit(bits: u64) -> f64 {
    (bits >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
}

/// Roughly the peak memory \[bytes\] [`generate`] takes on an `nx` x `ny` grid (the heights,
/// the half spectrum and the FFT's scratch: about 32 bytes a point, measured at 2048^2, plus a
/// fixed 16 MiB): for refusing a grid the machine cannot hold before anything is allocated.
pub fn memory_estimate(nx: usize, ny: usize) -> f64 {
    32.0 * nx as f64 * ny as f64 + 16.0 * 1024.0 * 1024.0
}

/// Generates the surface described by `spec`.
///
/// ```
/// use surfgen::{generate, Amplitudes, Grid, Normalization, Psd, SurfaceSpec};
/// let spec = SurfaceSpec {
///     grid: Grid::square(64, 1e-4)?,
///     psd: Psd::self_affine(0.8, 2e-5, 5e-6),
///     normalization: Normalization::RmsHeight(1e-6),
///     amplitudes: Amplitudes::Exact,
///     seed: 7,
/// };
/// let surface = generate(&spec)?;
/// let rq = (surface.heights.mapv(|h| h * h).mean().unwrap()).sqrt();
/// assert!((rq / 1e-6 - 1.0).abs() < 1e-12);
/// # Ok::<(), surfgen::SurfError>(())
/// ```
pub fn generate(spec: &SurfaceSpec) -> Result<Generated> {
    let grid = spec.grid;
    let warnings = spec.psd.validate(&grid)?;
    let target = match spec.normalization {
        Normalization::RmsHeight(v) => ("rms_height", v),
        Normalization::RmsGradient(v) => ("rms_gradient", v),
        Normalization::PeakToValley(v) => ("peak_to_valley", v),
        Normalization::Prefactor(v) => ("prefactor", v),
    };
    // A prefactor [m^4] is a height squared times an area: its bound is the square's.
    let largest = if target.0 == "prefactor" {
        crate::grid::MAX_LENGTH * crate::grid::MAX_LENGTH
    } else {
        crate::grid::MAX_LENGTH
    };
    if !(target.1 > 0.0 && target.1 <= largest) {
        return Err(SurfError::invalid(
            target.0,
            target.1,
            format!("must be > 0 and at most {largest:e} (SI units)"),
        ));
    }
    let fft = Fft2::new(grid.nx, grid.ny);
    let mut spectrum = fill_spectrum(fft.spectrum_shape(), spec);
    let unscaled = Analysis::from_spectrum(spectrum.view(), &grid, 10);
    if unscaled.moments.m0 == 0.0 {
        return Err(SurfError::invalid(
            "cutoff_wavelength",
            spec.psd.cutoff_wavelength,
            "no wavevector of the grid falls inside the spectrum's band",
        ));
    }
    // Coefficients are drawn with unit plateau; `factor` scales them (and so the heights).
    let n = grid.len() as f64;
    let plateau_scale = n * 2.0 * PI / grid.area().sqrt(); // |H_k| per sqrt(C) [1/m]
    let factor = match spec.normalization {
        Normalization::RmsHeight(rq) => rq / unscaled.moments.rms_height(),
        Normalization::RmsGradient(g) => g / unscaled.moments.rms_gradient(),
        Normalization::Prefactor(c0) => c0.sqrt() * plateau_scale,
        Normalization::PeakToValley(_) => 1.0,
    };
    let mut heights = Array2::<f64>::zeros(grid.shape());
    fft.inverse(&mut spectrum, heights.view_mut(), factor / n);
    let mut factor = factor;
    if let Normalization::PeakToValley(pv) = spec.normalization {
        let (lo, hi) = heights
            .par_iter()
            .fold(
                || (f64::INFINITY, f64::NEG_INFINITY),
                |(lo, hi), &h| (lo.min(h), hi.max(h)),
            )
            .reduce(
                || (f64::INFINITY, f64::NEG_INFINITY),
                |a, b| (a.0.min(b.0), a.1.max(b.1)),
            );
        let s = pv / (hi - lo);
        heights.par_mapv_inplace(|h| h * s);
        factor *= s;
    }
    Ok(Generated {
        heights,
        analysis: unscaled.scaled(factor),
        prefactor: (factor / plateau_scale).powi(2),
        warnings,
    })
}

/// The unit-plateau random coefficients as a transposed half spectrum of `shape`.
fn fill_spectrum(shape: (usize, usize), spec: &SurfaceSpec) -> Array2<Complex64> {
    // Every coefficient is written below, so the (large) array is not zeroed first.
    let mut spectrum = Array2::<Complex64>::uninit(shape);
    let grid = spec.grid;
    let (nx, ny) = (grid.nx, grid.ny);
    let base = ChaCha8Rng::seed_from_u64(spec.seed);
    let shape_at = spec.psd.shape_fn();
    let qy: Vec<f64> = (0..ny)
        .map(|ky| Grid::wavevector(ky, ny, grid.length_y))
        .collect();
    spectrum
        .axis_iter_mut(Axis(0))
        .into_par_iter()
        .enumerate()
        .for_each(|(kx, mut column)| {
            let mut rng = base.clone();
            rng.set_stream(kx as u64);
            let qx = Grid::wavevector(kx, nx, grid.length_x);
            for (ky, c) in column.iter_mut().enumerate() {
                let c = c.write(Complex64::default());
                let phase = 2.0 * PI * unit(rand::Rng::next_u64(&mut rng));
                let rayleigh = match spec.amplitudes {
                    Amplitudes::Exact => 1.0,
                    Amplitudes::Rayleigh => (-(1.0 - unit(rand::Rng::next_u64(&mut rng))).ln()).sqrt(),
                };
                let shape = shape_at(qx, qy[ky]);
                *c = if shape > 0.0 {
                    Complex64::from_polar(shape.sqrt() * rayleigh, phase)
                } else {
                    Complex64::default()
                };
            }
            // Columns that are their own mirror image (kx = 0 and, for even nx, the Nyquist
            // column) must satisfy H(-ky) = conj(H(ky)) for the surface to be real.
            if kx == 0 || (nx.is_multiple_of(2) && kx == nx / 2) {
                let col = column.as_slice_mut().expect("standard layout");
                // SAFETY: every element of the column was written in the loop above.
                let col =
                    unsafe { &mut *(col as *mut [std::mem::MaybeUninit<Complex64>] as *mut [Complex64]) };
                for ky in ny / 2 + 1..ny {
                    col[ky] = col[ny - ky].conj();
                }
                col[0] = Complex64::new(col[0].norm() * col[0].re.signum(), 0.0);
                if ny.is_multiple_of(2) {
                    let c = col[ny / 2];
                    col[ny / 2] = Complex64::new(c.norm() * c.re.signum(), 0.0);
                }
            }
        });
    // SAFETY: each column was fully written by the loop above.
    unsafe { spectrum.assume_init() }
}
