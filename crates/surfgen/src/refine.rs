//! A periodic surface on a finer grid: the band-limited (trigonometric) interpolation through
//! its samples, for running one surface on several meshes. Exact for a surface whose spectrum
//! ends below the coarse grid's Nyquist wavevector (a generated surface with its cut-off at two
//! cells or more): the fine samples are then the same surface, only sampled more densely.

use crate::error::{Result, SurfError};
use crate::grid::check_finite;
use fft2::{Complex64, Fft2};
use ndarray::{Array2, ArrayView2};

/// The periodic surface through `heights` (shape `(ny, nx)`) sampled `factor` times as
/// densely along each axis, shape `(factor ny, factor nx)`: its spectrum padded with zeros
/// (a Nyquist coefficient split evenly between the two wavevectors it stands for), so that
/// every `factor`-th sample of the result is `heights` again.
///
/// # Errors
/// [`SurfError::InvalidParameter`] if `factor` is 0 or `heights` is empty,
/// [`SurfError::NonFinite`] if a height is not finite.
pub fn refine(heights: ArrayView2<f64>, factor: usize) -> Result<Array2<f64>> {
    let (ny, nx) = heights.dim();
    if factor == 0 {
        return Err(SurfError::invalid("refinement factor", 0.0, "must be at least 1"));
    }
    if nx == 0 || ny == 0 {
        return Err(SurfError::invalid(
            "surface size",
            0.0,
            "the surface has no points",
        ));
    }
    check_finite(heights)?;
    let coarse = Fft2::new(nx, ny);
    let spectrum = coarse.forward(heights.as_standard_layout().view());
    let (fine_nx, fine_ny) = (factor * nx, factor * ny);
    let fine = Fft2::new(fine_nx, fine_ny);
    // Transposed half layouts: row `kx`, column `ky` (from `ny/2 + 1` on, the negative ones).
    let mut padded = Array2::<Complex64>::zeros(fine.spectrum_shape());
    for kx in 0..coarse.nkx() {
        // A Nyquist column along x (even `nx`) stands for `+-nx/2`; the fine half spectrum holds
        // `+nx/2` only and its conjugate mirror supplies the other half.
        let x_share = if factor > 1 && 2 * kx == nx { 0.5 } else { 1.0 };
        for ky in 0..ny {
            let c = spectrum[(kx, ky)] * x_share;
            if factor > 1 && 2 * ky == ny {
                padded[(kx, ky)] += 0.5 * c;
                padded[(kx, fine_ny - ky)] += 0.5 * c;
            } else if 2 * ky < ny {
                padded[(kx, ky)] += c;
            } else {
                padded[(kx, fine_ny - (ny - ky))] += c;
            }
        }
    }
    let mut out = Array2::zeros((fine_ny, fine_nx));
    fine.inverse(&mut padded, out.view_mut(), 1.0 / (nx * ny) as f64);
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    /// A trigonometric polynomial whose wavevectors stay below the Nyquist of a 12 x 10 grid.
    fn band_limited(x: f64, y: f64) -> f64 {
        let t = 2.0 * PI;
        1.5 + (t * x).cos() - 0.7 * (t * (2.0 * x + 3.0 * y) + 0.4).sin()
            + 0.3 * (t * (4.0 * y - 5.0 * x)).cos()
    }

    #[test]
    fn a_band_limited_surface_is_interpolated_exactly() {
        let (nx, ny) = (12, 10);
        let coarse = Array2::from_shape_fn((ny, nx), |(j, i)| {
            band_limited(i as f64 / nx as f64, j as f64 / ny as f64)
        });
        for factor in [1, 2, 3] {
            let fine = refine(coarse.view(), factor).unwrap();
            assert_eq!(fine.dim(), (factor * ny, factor * nx));
            for ((j, i), &h) in fine.indexed_iter() {
                let exact = band_limited(i as f64 / (factor * nx) as f64, j as f64 / (factor * ny) as f64);
                assert!(
                    (h - exact).abs() < 1e-12,
                    "factor {factor} ({j}, {i}): {h} against {exact}"
                );
            }
        }
    }

    #[test]
    fn the_coarse_samples_come_back_with_nyquist_content_and_odd_sizes() {
        // Any field, even and odd sizes: every `factor`-th fine sample is the input again,
        // which needs the Nyquist coefficients split between their two wavevectors.
        for (nx, ny) in [(8, 6), (7, 9), (6, 5)] {
            let coarse = Array2::from_shape_fn((ny, nx), |(j, i)| {
                ((i * 7 + j * 13) % 11) as f64 - 5.0 + 0.1 * i as f64
            });
            let fine = refine(coarse.view(), 2).unwrap();
            for ((j, i), &h) in coarse.indexed_iter() {
                assert!(
                    (fine[(2 * j, 2 * i)] - h).abs() < 1e-12,
                    "({nx}, {ny}) at ({j}, {i})"
                );
            }
        }
    }

    #[test]
    fn bad_input_is_refused() {
        let flat = Array2::<f64>::zeros((4, 4));
        assert!(matches!(
            refine(flat.view(), 0),
            Err(SurfError::InvalidParameter { .. })
        ));
        let mut bad = flat.clone();
        bad[(1, 2)] = f64::NAN;
        assert!(matches!(
            refine(bad.view(), 2),
            Err(SurfError::NonFinite { row: 1, col: 2, .. })
        ));
    }
}
