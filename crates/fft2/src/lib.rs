//! Two-dimensional real FFTs of row-major `(my, mx)` fields, planned once, run in parallel,
//! with results that do not depend on the number of threads (every value is computed by one
//! task in a fixed order).
//!
//! The spectrum is kept as the *transposed half spectrum*: an array of shape `(mx/2 + 1, my)`
//! whose row `kx` holds the coefficients of every `ky` for that `kx`. Both passes then run
//! over contiguous rows, and a filter along y (a convolution's multiplier) is applied while a
//! row sits in cache. A transform costs one field-sized complex buffer, the
//! [`Workspace`]'s spectrum, and no transpose buffer: rows are scattered into it and gathered
//! out of it in blocks.
//!
//! Transforms are unscaled: the inverse of the forward transform is `mx my` times the input
//! unless the caller folds `1/(mx my)` into a `scale` or a multiplier.
//!
//! ```
//! use fft2::Fft2;
//! use ndarray::Array2;
//!
//! let field = Array2::from_shape_fn((6, 8), |(y, x)| (x * y) as f64);
//! let fft = Fft2::new(8, 6);
//! let mut spectrum = fft.forward(field.view());
//! assert_eq!(spectrum.dim(), (5, 6));
//! let mut back = Array2::zeros((6, 8));
//! fft.inverse(&mut spectrum, back.view_mut(), 1.0 / 48.0);
//! assert!(back.iter().zip(&field).all(|(a, b)| (a - b).abs() < 1e-12));
//! ```

use ndarray::{Array2, ArrayView2, ArrayViewMut2, Axis};
use rayon::prelude::*;
use realfft::{ComplexToReal, RealFftPlanner, RealToComplex};
pub use rustfft::num_complex::Complex64;
use rustfft::{Fft, FftPlanner};
use std::sync::{Arc, Mutex, MutexGuard};

/// Rows moved together between the row and transposed layouts: enough to use whole cache
/// lines on the strided side, few enough to stay in L1/L2.
const BLOCK: usize = 16;

/// Plans for the 2-D real transforms of one `(my, mx)` grid. Cloning shares the plans.
#[derive(Clone)]
pub struct Fft2 {
    mx: usize,
    my: usize,
    r2c: Arc<dyn RealToComplex<f64>>,
    c2r: Arc<dyn ComplexToReal<f64>>,
    col_forward: Arc<dyn Fft<f64>>,
    col_inverse: Arc<dyn Fft<f64>>,
}

/// Per-thread scratch: a block of half-spectrum rows, one real row and the FFT scratches.
struct Local {
    lines: Vec<Complex64>,
    real: Vec<f64>,
    scratch: Vec<Complex64>,
}

/// Per-thread scratch for one plan, handed out by rayon thread index.
struct Scratch(Vec<Mutex<Local>>);

impl Scratch {
    fn local(&self) -> MutexGuard<'_, Local> {
        let i = rayon::current_thread_index().unwrap_or(0) % self.0.len();
        self.0[i].lock().expect("scratch lock")
    }
}

/// Caller-owned buffers for the transforms of one [`Fft2`]: the spectrum and per-thread
/// scratch. One per concurrent caller; reusing it makes repeated transforms allocation-free.
pub struct Workspace {
    spectrum: Array2<Complex64>,
    scratch: Scratch,
}

impl Workspace {
    /// Bytes held by this workspace.
    pub fn bytes(&self) -> usize {
        let local = self.scratch.0.first().map_or(0, |l| {
            let l = l.lock().expect("scratch lock");
            l.lines.len() * 16 + l.real.len() * 8 + l.scratch.len() * 16
        });
        self.spectrum.len() * 16 + local * self.scratch.0.len()
    }

    /// The transposed half spectrum left by the last forward transform.
    pub fn spectrum(&self) -> ArrayView2<'_, Complex64> {
        self.spectrum.view()
    }

    /// The same spectrum, to be changed in place before [`Fft2::inverse_into`] (a multiplier
    /// that mixes the spectra of several fields).
    pub fn spectrum_mut(&mut self) -> ArrayViewMut2<'_, Complex64> {
        self.spectrum.view_mut()
    }
}

/// What the pass along y does to each `kx` row of the spectrum.
enum AlongY<'a> {
    Forward,
    Inverse,
    /// Forward, times the real multiplier's row, inverse: a convolution.
    Filter(ArrayView2<'a, f64>),
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

/// Raw pointer to the spectrum for the scatter pass, whose tasks write disjoint elements.
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

impl Fft2 {
    /// Plans the transforms of `(my, mx)` fields.
    pub fn new(mx: usize, my: usize) -> Self {
        let mut real = RealFftPlanner::<f64>::new();
        let mut complex = FftPlanner::<f64>::new();
        Fft2 {
            mx,
            my,
            r2c: real.plan_fft_forward(mx),
            c2r: real.plan_fft_inverse(mx),
            col_forward: complex.plan_fft_forward(my),
            col_inverse: complex.plan_fft_inverse(my),
        }
    }

    /// Shape `(my, mx)` of the fields.
    pub fn shape(&self) -> (usize, usize) {
        (self.my, self.mx)
    }

    /// Number of stored `kx` rows, `mx/2 + 1`.
    pub fn nkx(&self) -> usize {
        self.mx / 2 + 1
    }

    /// Shape `(mx/2 + 1, my)` of the transposed half spectrum.
    pub fn spectrum_shape(&self) -> (usize, usize) {
        (self.nkx(), self.my)
    }

    fn make_scratch(&self) -> Scratch {
        let threads = rayon::current_num_threads().max(1);
        let scratch_len = self
            .r2c
            .get_scratch_len()
            .max(self.c2r.get_scratch_len())
            .max(self.col_forward.get_inplace_scratch_len())
            .max(self.col_inverse.get_inplace_scratch_len());
        Scratch(
            (0..threads)
                .map(|_| {
                    Mutex::new(Local {
                        lines: vec![Complex64::default(); BLOCK * self.nkx()],
                        real: vec![0.0; self.mx],
                        scratch: vec![Complex64::default(); scratch_len],
                    })
                })
                .collect(),
        )
    }

    /// Buffers for this plan's transforms (one per concurrent caller).
    pub fn make_workspace(&self) -> Workspace {
        Workspace {
            spectrum: zeroed_complex(self.spectrum_shape()),
            scratch: self.make_scratch(),
        }
    }

    /// Unscaled forward transform of `field` (any shape up to `(my, mx)`, zero-padded to it)
    /// into the workspace's spectrum ([`Workspace::spectrum`]).
    ///
    /// # Panics
    /// If `field` is larger than `(my, mx)` or `ws` was made by a plan of another shape.
    pub fn forward_into(&self, field: ArrayView2<f64>, ws: &mut Workspace) {
        self.check_workspace(ws);
        let (ny, nx) = field.dim();
        assert!(ny <= self.my && nx <= self.mx, "field larger than the plan");
        self.scatter(ny, padded_row(field), &mut ws.spectrum, &ws.scratch);
        self.along_y(&mut ws.spectrum, ny, AlongY::Forward, &ws.scratch);
    }

    /// Unscaled forward transform of a `(my, mx)` field into a new transposed half spectrum.
    ///
    /// # Panics
    /// If `field` does not have shape `(my, mx)`.
    pub fn forward(&self, field: ArrayView2<f64>) -> Array2<Complex64> {
        assert_eq!(field.dim(), self.shape(), "field shape");
        let mut ws = self.make_workspace();
        self.forward_into(field, &mut ws);
        ws.spectrum
    }

    /// The real part of the unscaled forward transform of a `(my, mx)` field given row by row
    /// (`row(y, out)` writes row `y`, `mx` values): the spectrum of an even kernel, which is
    /// real. The field itself is never stored.
    pub fn real_spectrum(&self, row: impl Fn(usize, &mut [f64]) + Sync, ws: &mut Workspace) -> Array2<f64> {
        self.rows_forward(row, ws);
        ws.spectrum.mapv(|c| c.re)
    }

    /// The imaginary part of the same transform: the spectrum of a kernel odd along one axis
    /// and even along the other, which is imaginary.
    pub fn imaginary_spectrum(
        &self,
        row: impl Fn(usize, &mut [f64]) + Sync,
        ws: &mut Workspace,
    ) -> Array2<f64> {
        self.rows_forward(row, ws);
        ws.spectrum.mapv(|c| c.im)
    }

    fn rows_forward(&self, row: impl Fn(usize, &mut [f64]) + Sync, ws: &mut Workspace) {
        self.check_workspace(ws);
        self.scatter(self.my, row, &mut ws.spectrum, &ws.scratch);
        self.along_y(&mut ws.spectrum, self.my, AlongY::Forward, &ws.scratch);
    }

    /// Inverse transform of a transposed half spectrum into `field` (shape `(my, mx)`), each
    /// value multiplied by `scale`. Consumes `spectrum` as scratch (its content is destroyed).
    /// Imaginary parts that a real field cannot have (the `kx = 0` and Nyquist rows of a
    /// non-Hermitian input) are dropped.
    ///
    /// # Panics
    /// If the shapes do not match the plan.
    pub fn inverse(&self, spectrum: &mut Array2<Complex64>, field: ArrayViewMut2<f64>, scale: f64) {
        assert_eq!(spectrum.dim(), self.spectrum_shape(), "spectrum shape");
        assert_eq!(field.dim(), self.shape(), "field shape");
        let scratch = self.make_scratch();
        self.along_y(spectrum, self.my, AlongY::Inverse, &scratch);
        self.gather(spectrum.view(), field, scale, &scratch);
    }

    /// Inverse transform of the workspace's own spectrum into `out` (its first `out.dim()`
    /// values of the `(my, mx)` field), each value multiplied by `scale`; the spectrum is
    /// consumed as scratch. With [`Workspace::spectrum_mut`], for multipliers that mix fields.
    ///
    /// # Panics
    /// If `out` exceeds the plan's shape or `ws` was made by a plan of another shape.
    pub fn inverse_into(&self, ws: &mut Workspace, out: ArrayViewMut2<f64>, scale: f64) {
        self.check_workspace(ws);
        assert!(
            out.nrows() <= self.my && out.ncols() <= self.mx,
            "output larger than the plan"
        );
        self.along_y(&mut ws.spectrum, self.my, AlongY::Inverse, &ws.scratch);
        self.gather(ws.spectrum.view(), out, scale, &ws.scratch);
    }

    /// Circular convolution `out = K * input` on the `(my, mx)` grid, where `multiplier` is the
    /// real spectrum of `K` (transposed half layout, already divided by `mx my`). `input` may
    /// be smaller than the grid (zero-padded: a linear convolution when the padding is wide
    /// enough); `out` receives the first `out.dim()` values.
    ///
    /// # Panics
    /// If a shape exceeds the plan's or `ws` was made by a plan of another shape.
    pub fn convolve(
        &self,
        input: ArrayView2<f64>,
        multiplier: ArrayView2<f64>,
        out: ArrayViewMut2<f64>,
        ws: &mut Workspace,
    ) {
        let (ny, nx) = input.dim();
        assert!(ny <= self.my && nx <= self.mx, "input larger than the plan");
        self.convolve_rows(ny, padded_row(input), multiplier, out, ws);
    }

    /// [`Fft2::convolve`] of an input given row by row: `row(y, out)` writes row `y` (`mx`
    /// values, zero-padded by the caller) of the first `ny` rows; the rest are zero. For an
    /// input that is a function of fields the caller holds, which then needs no field of its
    /// own (a field-sized write and read fewer).
    ///
    /// # Panics
    /// If `ny` or `out` exceeds the plan's shape or `ws` was made by a plan of another shape.
    pub fn convolve_rows(
        &self,
        ny: usize,
        row: impl Fn(usize, &mut [f64]) + Sync,
        multiplier: ArrayView2<f64>,
        out: ArrayViewMut2<f64>,
        ws: &mut Workspace,
    ) {
        self.check_workspace(ws);
        assert_eq!(multiplier.dim(), self.spectrum_shape(), "multiplier shape");
        assert!(ny <= self.my, "input larger than the plan");
        assert!(
            out.nrows() <= self.my && out.ncols() <= self.mx,
            "output larger than the plan"
        );
        self.scatter(ny, row, &mut ws.spectrum, &ws.scratch);
        self.along_y(&mut ws.spectrum, ny, AlongY::Filter(multiplier), &ws.scratch);
        self.gather(ws.spectrum.view(), out, 1.0, &ws.scratch);
    }

    fn check_workspace(&self, ws: &Workspace) {
        assert_eq!(
            ws.spectrum.dim(),
            self.spectrum_shape(),
            "workspace of another plan"
        );
    }

    /// Pass 1: row FFTs of the `ny` input rows (`row(y, out)` writes row `y`, `mx` values)
    /// into the transposed spectrum.
    fn scatter(
        &self,
        ny: usize,
        row: impl Fn(usize, &mut [f64]) + Sync,
        spectrum: &mut Array2<Complex64>,
        scratch: &Scratch,
    ) {
        let (mkx, my) = (self.nkx(), self.my);
        let ptr = SpectrumPtr(spectrum.as_mut_ptr());
        (0..ny.div_ceil(BLOCK)).into_par_iter().for_each(|block| {
            let mut guard = scratch.local();
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

    /// Pass 2: along y, one `kx` row at a time; entries from `ny_in` on (rows never
    /// scattered) are zeroed first.
    fn along_y(&self, spectrum: &mut Array2<Complex64>, ny_in: usize, what: AlongY, scratch: &Scratch) {
        spectrum
            .axis_chunks_iter_mut(Axis(0), BLOCK)
            .into_par_iter()
            .enumerate()
            .for_each(|(block, mut rows)| {
                let mut guard = scratch.local();
                let scratch = &mut guard.scratch;
                for (r, mut row) in rows.outer_iter_mut().enumerate() {
                    let row = row.as_slice_mut().expect("owned arrays are standard layout");
                    row[ny_in..].iter_mut().for_each(|c| *c = Complex64::default());
                    match &what {
                        AlongY::Forward => self.col_forward.process_with_scratch(row, scratch),
                        AlongY::Inverse => self.col_inverse.process_with_scratch(row, scratch),
                        AlongY::Filter(multiplier) => {
                            self.col_forward.process_with_scratch(row, scratch);
                            let k = multiplier.row(block * BLOCK + r);
                            row.iter_mut().zip(k.iter()).for_each(|(c, k)| *c *= *k);
                            self.col_inverse.process_with_scratch(row, scratch);
                        }
                    }
                }
            });
    }

    /// Pass 3: gather rows back, times `scale`, and transform them to the real rows of `out`
    /// (its first `out.ncols()` values).
    fn gather(
        &self,
        spectrum: ArrayView2<Complex64>,
        mut out: ArrayViewMut2<f64>,
        scale: f64,
        scratch: &Scratch,
    ) {
        let nx_out = out.ncols();
        let mkx = self.nkx();
        let nyquist = self.mx.is_multiple_of(2);
        out.axis_chunks_iter_mut(Axis(0), BLOCK)
            .into_par_iter()
            .enumerate()
            .for_each(|(block, mut rows)| {
                let mut guard = scratch.local();
                let Local { lines, real, scratch } = &mut *guard;
                let y0 = block * BLOCK;
                let n = rows.nrows();
                for kx in 0..mkx {
                    let col = spectrum.row(kx);
                    let col = &col.as_slice().expect("owned arrays are standard layout")[y0..y0 + n];
                    for (r, c) in col.iter().enumerate() {
                        lines[r * mkx + kx] = *c * scale;
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

/// Row `y` of `field`, zero-padded to the length of `out`.
fn padded_row(field: ArrayView2<'_, f64>) -> impl Fn(usize, &mut [f64]) + Sync + '_ {
    let nx = field.ncols();
    move |y, out| {
        out[..nx].iter_mut().zip(field.row(y)).for_each(|(d, s)| *d = *s);
        out[nx..].iter_mut().for_each(|d| *d = 0.0);
    }
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

    fn field(ny: usize, nx: usize) -> Array2<f64> {
        Array2::from_shape_fn((ny, nx), |(y, x)| {
            ((x * 7 + y * 13) % 11) as f64 - 5.0 + 0.1 * x as f64
        })
    }

    #[test]
    fn forward_matches_naive_dft_and_inverse_undoes_it() {
        // Odd and even lengths, and more rows than one block.
        for (nx, ny) in [(8, 6), (7, 9), (33, 20)] {
            let field = field(ny, nx);
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

    #[test]
    fn zero_padded_convolution_matches_direct_linear_convolution() {
        // K(dx, dy) = 1 / (1 + dx^2 + 2 dy^2), even, on a grid padded twice: the circular
        // convolution of the padded input is the linear one on the kept block.
        let (nx, ny) = (5, 19);
        let (mx, my) = (2 * nx, 2 * ny);
        let kernel = |dx: isize, dy: isize| 1.0 / (1.0 + (dx * dx) as f64 + 2.0 * (dy * dy) as f64);
        let wrap = |k: usize, m: usize| {
            if k <= m / 2 {
                k as isize
            } else {
                k as isize - m as isize
            }
        };
        let fft = Fft2::new(mx, my);
        let mut ws = fft.make_workspace();
        let spectrum = fft.real_spectrum(
            |y, out| {
                out.iter_mut()
                    .enumerate()
                    .for_each(|(x, o)| *o = kernel(wrap(x, mx), wrap(y, my)))
            },
            &mut ws,
        );
        let multiplier = spectrum / (mx * my) as f64;
        let input = field(ny, nx);
        let mut out = Array2::zeros((ny, nx));
        fft.convolve(input.view(), multiplier.view(), out.view_mut(), &mut ws);
        for ((y, x), got) in out.indexed_iter() {
            let direct: f64 = input
                .indexed_iter()
                .map(|((j, i), p)| p * kernel(x as isize - i as isize, y as isize - j as isize))
                .sum();
            assert!(
                (got - direct).abs() < 1e-12 * direct.abs().max(1.0),
                "({y},{x}): {got} vs {direct}"
            );
        }
    }

    #[test]
    fn results_do_not_depend_on_the_thread_count() {
        let (nx, ny) = (64, 48);
        let input = field(ny, nx);
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let fft = Fft2::new(nx, ny);
                let mut spec = fft.forward(input.view());
                let mut back = Array2::zeros((ny, nx));
                fft.inverse(&mut spec, back.view_mut(), 0.5);
                back
            })
        };
        assert_eq!(run(1), run(3));
    }
}
