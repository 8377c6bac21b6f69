//! Two-dimensional real convolution by FFT on the shared [`fft2`] engine: one forward and one
//! inverse 2-D FFT per application, the multiplier applied while each `kx` row of the
//! spectrum sits in cache, and no allocation (the caller's workspace holds the spectrum).

use fft2::Fft2;
pub use fft2::Workspace as ConvWorkspace;
use ndarray::{Array2, ArrayView2, ArrayViewMut2};

/// A planned convolution of `(ny_in, nx_in)` fields with a kernel of real spectrum on an
/// `(my, mx)` periodic transform grid, keeping the first `(ny_out, nx_out)` values. Rows and
/// columns past the input's are zero (zero padding for a linear convolution).
#[derive(Clone)]
pub struct Convolution {
    fft: Fft2,
    input: (usize, usize),
    output: (usize, usize),
    /// Real kernel spectrum, transposed half layout `(mx/2 + 1, my)`, already divided by `mx my`.
    kernel: Array2<f64>,
}

impl Convolution {
    /// Plans the transforms. `kernel` is the unscaled real spectrum of the kernel in transposed
    /// half layout `(mx/2 + 1, my)`.
    ///
    /// # Panics
    /// If shapes are inconsistent (input or output larger than the transform grid).
    pub fn new(
        mx: usize,
        my: usize,
        kernel: Array2<f64>,
        input: (usize, usize),
        output: (usize, usize),
    ) -> Self {
        let mut conv = Self::without_kernel(mx, my, input, output);
        conv.set_kernel(kernel);
        conv
    }

    /// The plans alone, for computing a kernel's spectrum with [`Convolution::real_spectrum`]
    /// before [`Convolution::set_kernel`]; [`Convolution::apply`] panics until then.
    pub fn without_kernel(mx: usize, my: usize, input: (usize, usize), output: (usize, usize)) -> Self {
        assert!(input.0 <= my && input.1 <= mx && output.0 <= my && output.1 <= mx);
        Convolution {
            fft: Fft2::new(mx, my),
            input,
            output,
            kernel: Array2::zeros((0, 0)),
        }
    }

    /// Sets the unscaled real kernel spectrum (transposed half layout `(mx/2 + 1, my)`).
    ///
    /// # Panics
    /// If its shape is not `(mx/2 + 1, my)`.
    pub fn set_kernel(&mut self, kernel: Array2<f64>) {
        assert_eq!(kernel.dim(), self.fft.spectrum_shape(), "kernel spectrum shape");
        let (my, mx) = self.fft.shape();
        self.kernel = kernel * (1.0 / (mx * my) as f64);
    }

    /// Multiplies the kernel by `factor` (a change of modulus).
    pub fn scale_kernel(&mut self, factor: f64) {
        self.kernel *= factor;
    }

    /// A workspace for this convolution (one per concurrent caller).
    pub fn make_workspace(&self) -> ConvWorkspace {
        self.fft.make_workspace()
    }

    /// The real kernel spectrum (transposed half layout), divided by `mx my`.
    pub fn kernel(&self) -> ArrayView2<'_, f64> {
        self.kernel.view()
    }

    /// `out = K * input`.
    ///
    /// # Panics
    /// If the shapes differ from the plan's, or `ws` was made by another convolution.
    pub fn apply(&self, input: ArrayView2<f64>, out: ArrayViewMut2<f64>, ws: &mut ConvWorkspace) {
        assert_eq!(input.dim(), self.input, "input shape");
        let copy = |y: usize, row: &mut [f64]| row.iter_mut().zip(input.row(y)).for_each(|(d, s)| *d = *s);
        self.apply_rows(copy, out, ws);
    }

    /// `out = K * input` with the input given row by row: `row(y, out)` writes row `y` of
    /// it (`nx_in` values), so that an input computed from other fields needs no field of its
    /// own.
    ///
    /// # Panics
    /// If `out`'s shape differs from the plan's, or `ws` was made by another convolution.
    pub fn apply_rows(
        &self,
        row: impl Fn(usize, &mut [f64]) + Sync,
        out: ArrayViewMut2<f64>,
        ws: &mut ConvWorkspace,
    ) {
        assert_eq!(out.dim(), self.output, "output shape");
        assert_eq!(self.kernel.dim(), self.fft.spectrum_shape(), "kernel not set");
        let (ny, nx) = self.input;
        let padded = |y: usize, out: &mut [f64]| {
            row(y, &mut out[..nx]);
            out[nx..].iter_mut().for_each(|v| *v = 0.0);
        };
        self.fft.convolve_rows(ny, padded, self.kernel.view(), out, ws);
    }

    /// The real part of the unscaled DFT of a full `(my, mx)` field given row by row
    /// (`row(y, out)` writes row `y`, `mx` values): the spectrum of an even kernel.
    pub fn real_spectrum(
        &self,
        row: impl Fn(usize, &mut [f64]) + Sync,
        ws: &mut ConvWorkspace,
    ) -> Array2<f64> {
        self.fft.real_spectrum(row, ws)
    }
}
