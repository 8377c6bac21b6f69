//! Two-dimensional real convolution by FFT, fused and allocation-free.
//!
//! One application `out = K * in` runs three passes:
//! 1. real-to-complex FFTs of the input rows (zero-extended to the transform width `mx`),
//!    scattered into the *transposed half spectrum* (shape `(mx/2 + 1, my)`, row `kx` holding
//!    every `ky`), so that
//! 2. each `kx` row can be transformed along y, multiplied by the real kernel spectrum and
//!    transformed back while it sits in cache, and
//! 3. gathered back into rows for the complex-to-real FFTs of the output rows.
//!
//! This costs one forward and one inverse 2-D FFT and a single field-sized buffer (the
//! spectrum). Rows past the input's are zero (zero padding for linear convolution); only the
//! output's rows and columns are transformed back.

use ndarray::{Array2, ArrayView2, ArrayViewMut2, Axis};
use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};
use std::sync::{Arc, Mutex};

/// Rows moved together between row and transposed layouts.
const BLOCK: usize = 16;

/// Per-thread scratch: a block of half-spectrum rows, one real row and the FFT scratches.
struct Local {
    lines: Vec<Complex64>,
    real: Vec<f64>,
    scratch: Vec<Complex64>,
}

/// Caller-owned buffers for one [`Convolution`]: the spectrum and per-thread scratch.
pub struct ConvWorkspace {
    spectrum: Array2<Complex64>,
    locals: Vec<Mutex<Local>>,
}

impl ConvWorkspace {
    /// Bytes held by this workspace.
    pub fn bytes(&self) -> usize {
        let local = self.locals.first().map_or(0, |l| {
            let l = l.lock().expect("scratch lock");
            l.lines.len() * 16 + l.real.len() * 8 + l.scratch.len() * 16
        });
        self.spectrum.len() * 16 + local * self.locals.len()
    }
}

/// A planned convolution of `(ny_in, nx_in)` fields with a kernel of real spectrum on an
/// `(my, mx)` periodic transform grid, keeping the first `(ny_out, nx_out)` values.
#[derive(Clone)]
pub struct Convolution {
    mx: usize,
    my: usize,
    input: (usize, usize),
    output: (usize, usize),
    /// Real kernel spectrum, transposed half layout `(mx/2 + 1, my)`, already divided by `mx my`.
    kernel: Array2<f64>,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    col_forward: Arc<dyn Fft<f64>>,
    col_inverse: Arc<dyn Fft<f64>>,
}

/// A zero complex array from zeroed (lazily mapped) memory: `Array2::zeros` writes every
/// element of a complex array, which costs over a second at 8192 x 4097.
fn zeroed_complex(shape: (usize, usize)) -> Array2<Complex64> {
    let floats = vec![0.0f64; 2 * shape.0 * shape.1];
    let mut floats = std::mem::ManuallyDrop::new(floats);
    let (ptr, len, cap) = (floats.as_mut_ptr(), floats.len(), floats.capacity());
    // SAFETY: Complex64 is repr(C) { re: f64, im: f64 }: the same alignment as f64 and twice its
    // size, so the allocation of `cap` f64 holds exactly `cap / 2` complex values (cap is even
    // because vec! allocates exactly the even length asked for), and all-zero bits are 0 + 0i.
    debug_assert!(cap.is_multiple_of(2) && len == cap);
    let complex = unsafe { Vec::from_raw_parts(ptr as *mut Complex64, len / 2, cap / 2) };
    Array2::from_shape_vec(shape, complex).expect("length matches the shape")
}

/// Raw pointer to the spectrum for the scatter pass, whose tasks write disjoint columns.
#[derive(Clone, Copy)]
struct SpectrumPtr(*mut Complex64);
// SAFETY: only used to write disjoint elements from different threads (see `scatter`).
unsafe impl Send for SpectrumPtr {}
unsafe impl Sync for SpectrumPtr {}

impl SpectrumPtr {
    /// # Safety
    /// `i` must be in bounds, and no other thread may access element `i` meanwhile.
    unsafe fn write(self, i: usize, value: Complex64) {
        unsafe { *self.0.add(i) = value };
    }
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
        let mut real = RealFftPlanner::<f64>::new();
        let mut complex = FftPlanner::<f64>::new();
        Convolution {
            mx,
            my,
            input,
            output,
            kernel: Array2::zeros((0, 0)),
            r2c: real.plan_fft_forward(mx),
            c2r: real.plan_fft_inverse(mx),
            col_forward: complex.plan_fft_forward(my),
            col_inverse: complex.plan_fft_inverse(my),
        }
    }

    /// Sets the unscaled real kernel spectrum (transposed half layout `(mx/2 + 1, my)`).
    ///
    /// # Panics
    /// If its shape is not `(mx/2 + 1, my)`.
    pub fn set_kernel(&mut self, kernel: Array2<f64>) {
        assert_eq!(kernel.dim(), (self.mkx(), self.my), "kernel spectrum shape");
        self.kernel = kernel * (1.0 / (self.mx * self.my) as f64);
    }

    fn mkx(&self) -> usize {
        self.mx / 2 + 1
    }

    /// A workspace for this convolution (one per concurrent caller).
    pub fn make_workspace(&self) -> ConvWorkspace {
        let threads = rayon::current_num_threads().max(1);
        let scratch_len = self
            .r2c
            .get_scratch_len()
            .max(self.c2r.get_scratch_len())
            .max(self.col_forward.get_inplace_scratch_len())
            .max(self.col_inverse.get_inplace_scratch_len());
        ConvWorkspace {
            spectrum: zeroed_complex((self.mkx(), self.my)),
            locals: (0..threads)
                .map(|_| {
                    Mutex::new(Local {
                        lines: vec![Complex64::default(); BLOCK * self.mkx()],
                        real: vec![0.0; self.mx],
                        scratch: vec![Complex64::default(); scratch_len],
                    })
                })
                .collect(),
        }
    }

    /// The real kernel spectrum (transposed half layout), divided by `mx my`.
    pub fn kernel(&self) -> ArrayView2<'_, f64> {
        self.kernel.view()
    }

    /// `out = K * input`.
    ///
    /// # Panics
    /// If the shapes differ from the plan's, or `ws` was made by another convolution.
    pub fn apply(&self, input: ArrayView2<f64>, mut out: ArrayViewMut2<f64>, ws: &mut ConvWorkspace) {
        assert_eq!(input.dim(), self.input, "input shape");
        assert_eq!(out.dim(), self.output, "output shape");
        assert_eq!(ws.spectrum.dim(), (self.mkx(), self.my), "workspace shape");
        assert_eq!(self.kernel.dim(), (self.mkx(), self.my), "kernel not set");
        let locals = &ws.locals;
        let local = || {
            let i = rayon::current_thread_index().unwrap_or(0) % locals.len();
            locals[i].lock().expect("scratch lock")
        };
        let nx = self.input.1;
        let copy_row = |y: usize, real: &mut [f64]| {
            real[..nx].iter_mut().zip(input.row(y)).for_each(|(d, s)| *d = *s);
            real[nx..].iter_mut().for_each(|d| *d = 0.0);
        };
        self.scatter(self.input.0, copy_row, &mut ws.spectrum, &local);
        self.columns(&mut ws.spectrum, self.input.0, true, &local);
        self.gather(ws.spectrum.view(), out.view_mut(), &local);
    }

    /// The real part of the unscaled DFT of a full `(my, mx)` field given row by row
    /// (`row(y, out)` writes row `y`, `mx` values), in transposed half layout: the spectrum of
    /// an even kernel, which is real. The field itself is never stored.
    pub fn real_spectrum(
        &self,
        row: impl Fn(usize, &mut [f64]) + Sync,
        ws: &mut ConvWorkspace,
    ) -> Array2<f64> {
        let locals = &ws.locals;
        let local = || {
            let i = rayon::current_thread_index().unwrap_or(0) % locals.len();
            locals[i].lock().expect("scratch lock")
        };
        self.scatter(self.my, row, &mut ws.spectrum, &local);
        self.columns(&mut ws.spectrum, self.my, false, &local);
        ws.spectrum.mapv(|c| c.re)
    }

    /// Pass 1: row FFTs of the `ny` input rows (`row(y, out)` writes row `y`, zero-padded to
    /// `mx`) into the transposed spectrum.
    fn scatter<'a>(
        &self,
        ny: usize,
        row: impl Fn(usize, &mut [f64]) + Sync,
        spectrum: &mut Array2<Complex64>,
        local: &(impl Fn() -> std::sync::MutexGuard<'a, Local> + Sync),
    ) {
        let (mkx, my) = (self.mkx(), self.my);
        let ptr = SpectrumPtr(spectrum.as_mut_ptr());
        (0..ny.div_ceil(BLOCK)).into_par_iter().for_each(|block| {
            let mut guard = local();
            let Local { lines, real, scratch } = &mut *guard;
            let y0 = block * BLOCK;
            let rows = BLOCK.min(ny - y0);
            for r in 0..rows {
                row(y0 + r, real);
                let line = &mut lines[r * mkx..(r + 1) * mkx];
                self.r2c
                    .process_with_scratch(real, line, scratch)
                    .expect("sizes match the plan");
            }
            for kx in 0..mkx {
                for r in 0..rows {
                    // SAFETY: element (kx, y0 + r) of the (mkx, my) spectrum; blocks cover
                    // disjoint y ranges, so no two tasks write the same element, and nothing
                    // reads the spectrum during this pass.
                    unsafe { ptr.write(kx * my + y0 + r, lines[r * mkx + kx]) };
                }
            }
        });
    }

    /// Pass 2: along y, forward, times the kernel and inverse (unless `forward_only`), one `kx`
    /// row at a time; rows from `ny_in` on are zeroed first.
    fn columns<'a>(
        &self,
        spectrum: &mut Array2<Complex64>,
        ny_in: usize,
        convolve: bool,
        local: &(impl Fn() -> std::sync::MutexGuard<'a, Local> + Sync),
    ) {
        spectrum
            .axis_chunks_iter_mut(Axis(0), BLOCK)
            .into_par_iter()
            .enumerate()
            .for_each(|(block, mut rows)| {
                let mut guard = local();
                let scratch = &mut guard.scratch;
                for (r, mut row) in rows.outer_iter_mut().enumerate() {
                    let row = row.as_slice_mut().expect("standard layout");
                    row[ny_in..].iter_mut().for_each(|c| *c = Complex64::default());
                    self.col_forward.process_with_scratch(row, scratch);
                    if convolve {
                        let k = self.kernel.row(block * BLOCK + r);
                        row.iter_mut().zip(k.iter()).for_each(|(c, k)| *c *= *k);
                        self.col_inverse.process_with_scratch(row, scratch);
                    }
                }
            });
    }

    /// Pass 3: gather rows back and transform them to real output rows.
    fn gather<'a>(
        &self,
        spectrum: ArrayView2<Complex64>,
        mut out: ArrayViewMut2<f64>,
        local: &(impl Fn() -> std::sync::MutexGuard<'a, Local> + Sync),
    ) {
        let nx_out = self.output.1;
        let mkx = self.mkx();
        let nyquist = self.mx.is_multiple_of(2);
        out.axis_chunks_iter_mut(Axis(0), BLOCK)
            .into_par_iter()
            .enumerate()
            .for_each(|(block, mut rows)| {
                let mut guard = local();
                let Local { lines, real, scratch } = &mut *guard;
                let y0 = block * BLOCK;
                let n = rows.nrows();
                for kx in 0..mkx {
                    let col = &spectrum.row(kx);
                    let col = &col.as_slice().expect("standard layout")[y0..y0 + n];
                    for (r, c) in col.iter().enumerate() {
                        lines[r * mkx + kx] = *c;
                    }
                }
                for (r, mut o) in rows.outer_iter_mut().enumerate() {
                    let line = &mut lines[r * mkx..(r + 1) * mkx];
                    line[0].im = 0.0;
                    if nyquist {
                        line[mkx - 1].im = 0.0;
                    }
                    self.c2r
                        .process_with_scratch(line, real, scratch)
                        .expect("sizes match the plan and imaginary parts were cleared");
                    o.iter_mut().zip(&real[..nx_out]).for_each(|(d, s)| *d = *s);
                }
            });
    }
}
