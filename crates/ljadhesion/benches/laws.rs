//! Each law on a 4096^2 gap field, beside the floor: reading three gap arrays and writing one.

use criterion::{Criterion, criterion_group, criterion_main};
use ljadhesion::*;
use ndarray::{Array2, Zip};

fn bench(c: &mut Criterion) {
    let n = 4096;
    let z0 = 0.3e-9;
    let gap = Array2::from_shape_fn((n, n), |(y, x)| z0 * (((x * 31 + y * 17) % 101) as f64 / 20.0));
    let (g2, g3) = (gap.clone() * 1.01, gap.clone() * 0.99);
    let cells = Cells {
        dx: 1e-9,
        dy: 1e-9,
        periodic: true,
    };
    let lj = LennardJones::new(0.075, z0).unwrap();
    let mut out = Array2::<f64>::zeros((n, n));
    let mut group = c.benchmark_group("law_4096");
    group.sample_size(20);
    group.bench_function("floor_read3_write1", |b| {
        b.iter(|| {
            Zip::from(&mut out)
                .and(&gap)
                .and(&g2)
                .and(&g3)
                .par_for_each(|o, &a, &b, &c| *o = a + b + c)
        })
    });
    let laws: [(&str, Box<dyn AdhesionLaw>); 5] = [
        ("point", Box::new(PointLaw(lj))),
        ("line", Box::new(LineLaw(lj))),
        ("surface", Box::new(SurfaceLaw(lj))),
        ("exponential", Box::new(ExponentialLaw::new(0.075, z0).unwrap())),
        ("dugdale", Box::new(DugdaleLaw::equivalent_to(&lj))),
    ];
    for (name, law) in laws {
        group.bench_function(name, |b| {
            b.iter(|| law.pressure_field(gap.view(), &cells, out.view_mut()).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
