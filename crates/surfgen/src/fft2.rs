//! Two-dimensional real FFTs, planned once and run in parallel.
//!
//! The spectrum of an `(ny, nx)` real field is kept as the *transposed half spectrum*: an array
//! of shape `(nx/2 + 1, ny)` whose row `kx` holds the coefficients of all `ky` for that `kx`.
//! Keeping it transposed lets both passes run over contiguous rows and saves a full-size
//! transpose buffer. The forward transform is unscaled; the inverse divides by nothing either
//! (callers fold `1/N` into the `scale` they pass).

use ndarray::{Array2, ArrayView2, ArrayViewMut2, Axis};
use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};
use std::sync::Arc;

/// Rows handled together when moving between row-major and transposed layouts: enough to
/// use whole cache lines of the strided side, few enough to stay in L1/L2.
const BLOCK: usize = 16;

/// Plans for the 2-D real transforms of one grid shape.
pub struct Fft2 {
    nx: usize,
    ny: usize,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    col_forward: Arc<dyn Fft<f64>>,
    col_inverse: Arc<dyn Fft<f64>>,
}

impl Fft2 {
    /// Plans the transforms of `(ny, nx)` fields.
    pub fn new(nx: usize, ny: usize) -> Self {
        let mut real = RealFftPlanner::<f64>::new();
        let mut complex = FftPlanner::<f64>::new();
        Fft2 {
            nx,
            ny,
            r2c: real.plan_fft_forward(nx),
            c2r: real.plan_fft_inverse(nx),
            col_forward: complex.plan_fft_forward(ny),
            col_inverse: complex.plan_fft_inverse(ny),
        }
    }

    /// Number of stored `kx` columns, `nx/2 + 1`.
    pub fn nkx(&self) -> usize {
        self.nx / 2 + 1
    }

    /// Shape `(nx/2 + 1, ny)` of the transposed half spectrum.
    pub fn spectrum_shape(&self) -> (usize, usize) {
        (self.nkx(), self.ny)
    }

    /// Unscaled forward transform of `field` (shape `(ny, nx)`) into a new transposed half spectrum.
    ///
    /// # Panics
    /// If `field` does not have shape `(ny, nx)`.
    pub fn forward(&self, field: ArrayView2<f64>) -> Array2<Complex64> {
        assert_eq!(field.dim(), (self.ny, self.nx), "field shape");
        let nkx = self.nkx();
        let mut rows = Array2::<Complex64>::zeros((self.ny, nkx));
        rows.axis_chunks_iter_mut(Axis(0), BLOCK)
            .into_par_iter()
            .zip(field.axis_chunks_iter(Axis(0), BLOCK).into_par_iter())
            .for_each(|(mut out, inp)| {
                let mut line = self.r2c.make_input_vec();
                let mut scratch = self.r2c.make_scratch_vec();
                for (mut o, i) in out.outer_iter_mut().zip(inp.outer_iter()) {
                    line.iter_mut().zip(i.iter()).for_each(|(l, v)| *l = *v);
                    self.r2c
                        .process_with_scratch(
                            &mut line,
                            o.as_slice_mut().expect("standard layout"),
                            &mut scratch,
                        )
                        .expect("buffer sizes match the plan");
                }
            });
        let mut spectrum = Array2::<Complex64>::zeros(self.spectrum_shape());
        transpose_into(rows.view(), spectrum.view_mut(), 1.0);
        drop(rows);
        self.columns(&mut spectrum, &self.col_forward);
        spectrum
    }

    /// Inverse transform of a transposed half spectrum into `field` (shape `(ny, nx)`), each
    /// value multiplied by `scale`. Consumes `spectrum` as scratch (its content is destroyed).
    /// Imaginary parts that a real field cannot have (the `kx = 0` and Nyquist columns of a
    /// non-Hermitian input) are dropped.
    ///
    /// # Panics
    /// If the shapes do not match the plan.
    pub fn inverse(&self, spectrum: &mut Array2<Complex64>, mut field: ArrayViewMut2<f64>, scale: f64) {
        assert_eq!(spectrum.dim(), self.spectrum_shape(), "spectrum shape");
        assert_eq!(field.dim(), (self.ny, self.nx), "field shape");
        self.columns(spectrum, &self.col_inverse);
        let spectrum = spectrum.view();
        let nkx = self.nkx();
        let nyquist = self.nx.is_multiple_of(2);
        field
            .axis_chunks_iter_mut(Axis(0), BLOCK)
            .into_par_iter()
            .enumerate()
            .for_each(|(block, mut out)| {
                let y0 = block * BLOCK;
                let rows = out.nrows();
                let mut lines = Array2::<Complex64>::zeros((rows, nkx));
                transpose_into(
                    spectrum.slice(ndarray::s![.., y0..y0 + rows]),
                    lines.view_mut(),
                    scale,
                );
                let mut scratch = self.c2r.make_scratch_vec();
                for (mut line, mut o) in lines.outer_iter_mut().zip(out.outer_iter_mut()) {
                    let line = line.as_slice_mut().expect("standard layout");
                    line[0].im = 0.0;
                    if nyquist {
                        line[nkx - 1].im = 0.0;
                    }
                    self.c2r
                        .process_with_scratch(line, o.as_slice_mut().expect("standard layout"), &mut scratch)
                        .expect("buffer sizes match the plan and imaginary parts were cleared");
                }
            });
    }

    /// In-place complex FFT of every row of `spectrum` (the `ky` direction).
    fn columns(&self, spectrum: &mut Array2<Complex64>, fft: &Arc<dyn Fft<f64>>) {
        spectrum
            .axis_chunks_iter_mut(Axis(0), BLOCK)
            .into_par_iter()
            .for_each(|mut rows| {
                let mut scratch = vec![Complex64::default(); fft.get_inplace_scratch_len()];
                for mut row in rows.outer_iter_mut() {
                    fft.process_with_scratch(row.as_slice_mut().expect("standard layout"), &mut scratch);
                }
            });
    }
}

/// `dst = scale * src^T`, blocked for cache use; `dst` must have the transposed shape of `src`.
fn transpose_into(src: ArrayView2<Complex64>, mut dst: ArrayViewMut2<Complex64>, scale: f64) {
    debug_assert_eq!(dst.dim(), (src.ncols(), src.nrows()));
    dst.axis_chunks_iter_mut(Axis(0), BLOCK)
        .into_par_iter()
        .enumerate()
        .for_each(|(block, mut out)| {
            let c0 = block * BLOCK;
            for r0 in (0..src.nrows()).step_by(BLOCK) {
                let r1 = (r0 + BLOCK).min(src.nrows());
                for (dc, mut orow) in out.outer_iter_mut().enumerate() {
                    for r in r0..r1 {
                        orow[r] = src[(r, c0 + dc)] * scale;
                    }
                }
            }
        });
}

#[cfg(test)]
mod tests {
    use super::*;

    fn naive_dft(field: ArrayView2<f64>, kx: usize, ky: usize) -> Complex64 {
        let (ny, nx) = field.dim();
        let mut acc = Complex64::default();
        for ((y, x), v) in field.indexed_iter() {
            let ph =
                -2.0 * std::f64::consts::PI * ((kx * x) as f64 / nx as f64 + (ky * y) as f64 / ny as f64);
            acc += Complex64::from_polar(*v, ph);
        }
        acc
    }

    #[test]
    fn forward_matches_naive_dft_and_inverse_undoes_it() {
        for (nx, ny) in [(8, 6), (7, 9), (33, 20)] {
            let field = Array2::from_shape_fn((ny, nx), |(y, x)| {
                ((x * 7 + y * 13) % 11) as f64 - 5.0 + 0.1 * x as f64
            });
            let fft = Fft2::new(nx, ny);
            let mut spec = fft.forward(field.view());
            for kx in 0..fft.nkx() {
                for ky in 0..ny {
                    let d = spec[(kx, ky)] - naive_dft(field.view(), kx, ky);
                    assert!(d.norm() < 1e-10, "({nx},{ny}) k=({kx},{ky}) off by {d}");
                }
            }
            let mut back = Array2::zeros((ny, nx));
            fft.inverse(&mut spec, back.view_mut(), 1.0 / (nx * ny) as f64);
            for (a, b) in back.iter().zip(field.iter()) {
                assert!((a - b).abs() < 1e-12);
            }
        }
    }
}
