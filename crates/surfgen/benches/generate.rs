//! Generation of a self-affine surface (the contact-mechanics challenge's spectrum, short
//! cut-off at 4 grid spacings) at 1024^2 and 4096^2, with its spectral analysis.

use criterion::{BenchmarkId, Criterion, criterion_group, criterion_main};
use surfgen::{Amplitudes, Grid, Normalization, Psd, SurfaceSpec, generate};

fn bench(c: &mut Criterion) {
    let mut group = c.benchmark_group("generate");
    group.sample_size(10);
    for n in [1024usize, 4096] {
        let grid = Grid::square(n, 1e-4).unwrap();
        let spec = SurfaceSpec {
            grid,
            psd: Psd::self_affine(0.8, 2e-5, 4.0 * grid.dx()),
            normalization: Normalization::RmsGradient(1.0),
            amplitudes: Amplitudes::Exact,
            seed: 1,
        };
        group.bench_with_input(BenchmarkId::from_parameter(n), &spec, |b, spec| {
            b.iter(|| generate(spec).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
