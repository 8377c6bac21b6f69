//! One application of each operator at 512^2, 2048^2 and 4096^2, beside a bare 2-D real FFT
//! round trip of the same size (realfft rows, rustfft columns over a blocked transpose, no
//! kernel), all measured in the same run.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use elastic::{Compliance, Domain, Free, Periodic};
use ndarray::{Array2, Axis};
use rayon::prelude::*;
use realfft::RealFftPlanner;
use rustfft::FftPlanner;
use rustfft::num_complex::Complex64;

/// Forward and inverse 2-D real FFT with plans made once: the floor an operator builds on.
struct RoundTrip {
    r2c: std::sync::Arc<dyn realfft::RealToComplex<f64>>,
    c2r: std::sync::Arc<dyn realfft::ComplexToReal<f64>>,
    fwd: std::sync::Arc<dyn rustfft::Fft<f64>>,
    inv: std::sync::Arc<dyn rustfft::Fft<f64>>,
    rows: Array2<Complex64>,
    cols: Array2<Complex64>,
}

impl RoundTrip {
    fn new(n: usize) -> Self {
        let mut rp = RealFftPlanner::new();
        let mut cp = FftPlanner::new();
        RoundTrip {
            r2c: rp.plan_fft_forward(n),
            c2r: rp.plan_fft_inverse(n),
            fwd: cp.plan_fft_forward(n),
            inv: cp.plan_fft_inverse(n),
            rows: Array2::zeros((n, n / 2 + 1)),
            cols: Array2::zeros((n / 2 + 1, n)),
        }
    }

    fn run(&mut self, field: &mut Array2<f64>) {
        let (r2c, c2r, fwd, inv) = (&self.r2c, &self.c2r, &self.fwd, &self.inv);
        self.rows
            .axis_iter_mut(Axis(0))
            .into_par_iter()
            .zip(field.axis_iter_mut(Axis(0)))
            .for_each(|(mut o, mut i)| {
                let mut s = r2c.make_scratch_vec();
                r2c.process_with_scratch(i.as_slice_mut().unwrap(), o.as_slice_mut().unwrap(), &mut s)
                    .unwrap();
            });
        transpose(&self.rows, &mut self.cols);
        self.cols
            .axis_chunks_iter_mut(Axis(0), 8)
            .into_par_iter()
            .for_each(|mut rows| {
                let mut s = vec![Complex64::default(); fwd.get_inplace_scratch_len()];
                for mut r in rows.outer_iter_mut() {
                    fwd.process_with_scratch(r.as_slice_mut().unwrap(), &mut s);
                    inv.process_with_scratch(r.as_slice_mut().unwrap(), &mut s);
                }
            });
        transpose(&self.cols, &mut self.rows);
        self.rows
            .axis_iter_mut(Axis(0))
            .into_par_iter()
            .zip(field.axis_iter_mut(Axis(0)))
            .for_each(|(mut i, mut o)| {
                let mut s = c2r.make_scratch_vec();
                let line = i.as_slice_mut().unwrap();
                line[0].im = 0.0;
                let last = line.len() - 1;
                line[last].im = 0.0;
                c2r.process_with_scratch(line, o.as_slice_mut().unwrap(), &mut s)
                    .unwrap();
            });
    }
}

fn transpose(src: &Array2<Complex64>, dst: &mut Array2<Complex64>) {
    const B: usize = 16;
    dst.axis_chunks_iter_mut(Axis(0), B)
        .into_par_iter()
        .enumerate()
        .for_each(|(b, mut out)| {
            let c0 = b * B;
            for r0 in (0..src.nrows()).step_by(B) {
                for (dc, mut orow) in out.outer_iter_mut().enumerate() {
                    for r in r0..(r0 + B).min(src.nrows()) {
                        orow[r] = src[(r, c0 + dc)];
                    }
                }
            }
        });
}

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("elastic");
    group.sample_size(10);
    for n in [512usize, 2048, 4096] {
        let p = Array2::from_shape_fn((n, n), |(j, i)| ((i * 7 + j * 3) % 17) as f64);
        let mut u = Array2::zeros((n, n));
        let mut field = p.clone();
        let mut rt = RoundTrip::new(n);
        group.bench_with_input(BenchmarkId::new("bare_round_trip", n), &n, |b, _| {
            b.iter(|| rt.run(&mut field))
        });
        drop(rt);
        let dom = Domain {
            nx: n,
            ny: n,
            dx: 1e-8,
            dy: 1e-8,
            periodic: true,
        };
        let op = Periodic::new(dom, 1e9).unwrap();
        let mut ws = op.make_workspace();
        group.bench_with_input(BenchmarkId::new("periodic", n), &n, |b, _| {
            b.iter(|| op.apply(p.view(), u.view_mut(), &mut ws).unwrap())
        });
        drop((op, ws));
        let op = Free::new(
            Domain {
                periodic: false,
                ..dom
            },
            1e9,
        )
        .unwrap();
        let mut ws = op.make_workspace();
        group.bench_with_input(BenchmarkId::new("free", n), &n, |b, _| {
            b.iter(|| op.apply(p.view(), u.view_mut(), &mut ws).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
