//! The regular grid a surface lives on.

use crate::error::{Result, SurfError};
use ndarray::ArrayView2;
use serde::{Deserialize, Serialize};

/// A regular `nx` by `ny` grid covering `length_x` by `length_y` metres.
///
/// Arrays on it have shape `(ny, nx)` (row index = y). On a periodic grid the spacing is
/// `length / n` and the point `n` coincides with point `0`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Grid {
    /// Number of points along x (columns).
    pub nx: usize,
    /// Number of points along y (rows).
    pub ny: usize,
    /// Lateral size along x \[m\].
    pub length_x: f64,
    /// Lateral size along y \[m\].
    pub length_y: f64,
}

impl Grid {
    /// A grid, checked: at least 2 points per side, finite positive lengths.
    pub fn new(nx: usize, ny: usize, length_x: f64, length_y: f64) -> Result<Self> {
        for (name, n) in [("nx", nx), ("ny", ny)] {
            if n < 2 {
                return Err(SurfError::invalid(name, n as f64, "need at least 2 points"));
            }
        }
        for (name, l) in [("length_x", length_x), ("length_y", length_y)] {
            if !(l > 0.0 && l <= MAX_LENGTH) {
                return Err(SurfError::invalid(
                    name,
                    l,
                    "a lateral size must be > 0 m and at most 1e100 m",
                ));
            }
        }
        Ok(Grid {
            nx,
            ny,
            length_x,
            length_y,
        })
    }

    /// A square grid of `n` by `n` points and side `length` \[m\].
    pub fn square(n: usize, length: f64) -> Result<Self> {
        Self::new(n, n, length, length)
    }

    /// Spacing along x \[m\].
    pub fn dx(&self) -> f64 {
        self.length_x / self.nx as f64
    }

    /// Spacing along y \[m\].
    pub fn dy(&self) -> f64 {
        self.length_y / self.ny as f64
    }

    /// Number of points.
    pub fn len(&self) -> usize {
        self.nx * self.ny
    }

    /// Always false: a grid has at least 4 points.
    pub fn is_empty(&self) -> bool {
        false
    }

    /// Nominal area `length_x * length_y` [m^2].
    pub fn area(&self) -> f64 {
        self.length_x * self.length_y
    }

    /// Array shape `(ny, nx)`.
    pub fn shape(&self) -> (usize, usize) {
        (self.ny, self.nx)
    }

    /// Checks that `heights` has this grid's shape and only finite values.
    pub fn check(&self, heights: ArrayView2<f64>) -> Result<()> {
        if heights.dim() != self.shape() {
            return Err(SurfError::ShapeMismatch {
                expected: self.shape(),
                got: heights.dim(),
            });
        }
        check_finite(heights)
    }

    /// Wavevector component [rad/m] of DFT index `k` along an axis of `n` points and length `l`,
    /// with indices above `n/2` meaning negative wavevectors.
    pub(crate) fn wavevector(k: usize, n: usize, l: f64) -> f64 {
        let signed = if k <= n / 2 { k as f64 } else { k as f64 - n as f64 };
        2.0 * std::f64::consts::PI * signed / l
    }
}

/// The largest height or lateral size \[m\] a surface may have: far beyond any surface, and
/// small enough that the sums of squares and products made of it (statistics, spectra, a
/// solver's energies) stay finite in double precision.
pub const MAX_LENGTH: f64 = 1e100;

/// Returns the first height that is NaN, infinite or beyond [`MAX_LENGTH`] as an error.
pub fn check_finite(heights: ArrayView2<f64>) -> Result<()> {
    match heights
        .indexed_iter()
        .find(|(_, v)| !v.is_finite() || v.abs() > MAX_LENGTH)
    {
        Some(((row, col), &value)) => Err(SurfError::NonFinite { row, col, value }),
        None => Ok(()),
    }
}
