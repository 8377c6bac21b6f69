//! # surfgen: self-affine rough surfaces and their statistics
//!
//! Periodic, zero-mean random surfaces with the power spectrum of the paper's Eq. 13
//! (docs/method.md section 5): flat below the roll-off wavevector `q_r`, the power law
//! `(q/q_r)^(-2(1+H))` up to the short cut-off `q_s`, zero outside (and below an optional
//! long-wavelength cut-off), optionally anisotropic. A `u64` seed fixes a surface bit for bit
//! on every platform and for every number of threads.
//!
//! Conventions: SI units throughout (heights and lengths in m, wavevectors in rad/m, the PSD
//! in m^4 as defined in [`psd`]); arrays have shape `(ny, nx)`; the forward DFT is unscaled.
//!
//! ```
//! use surfgen::{generate, statistics, Amplitudes, Grid, Normalization, Psd, SurfaceSpec};
//! let spec = SurfaceSpec {
//!     grid: Grid::square(128, 1e-4)?,                  // 128^2 points over 0.1 mm
//!     psd: Psd::self_affine(0.8, 2e-5, 4e-6),          // H, roll-off, cut-off \[m\]
//!     normalization: Normalization::RmsGradient(1.0),
//!     amplitudes: Amplitudes::Exact,
//!     seed: 1,
//! };
//! let surface = generate(&spec)?;
//! let stats = statistics(surface.heights.view(), &spec.grid, true, None);
//! assert!((stats.rms_gradient - 1.0).abs() < 1e-12);
//! # Ok::<(), surfgen::SurfError>(())
//! ```

/// The 2-D real FFT engine whose transposed half spectra [`stats`] reads.
pub use fft2;

pub mod error;
pub mod generate;
pub mod grid;
pub mod io;
pub mod psd;
pub mod refine;
pub mod stats;

pub use error::{Result, SurfError};
pub use generate::{Amplitudes, Generated, Normalization, SurfaceSpec, generate};
pub use grid::Grid;
pub use io::{Metadata, ReadOptions, Surface};
pub use psd::{Anisotropy, Psd};
pub use refine::refine;
pub use stats::{
    Analysis, Curvatures, HeightStats, HurstFit, RadialPsd, SpectralMoments, Statistics, bearing_area_curve,
    statistics,
};
