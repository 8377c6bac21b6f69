//! The preconditioned conjugate gradients against the plain ones: the same solution (contact
//! set, load, pressures) in fewer iterations, whose number grows more slowly than the square
//! root of the number of cells.

use elastic::{Compliance, Domain, Free, Periodic};
use ndarray::Array2;
use solver::cg::solve;
use solver::geometry::{SphereProfile, flat_on_rough, sphere};
use solver::{ContactOptions, ContactReport, ContactState, Control};
use surfgen::{Amplitudes, Grid, Normalization, Psd, SurfaceSpec, generate};

/// The bench's surface (`roughcontact bench`): H = 0.8, RMS gradient 1, cut-off 8 cells, on the
/// unit box with E* = 1.
fn bench_case(n: usize) -> (Periodic, Array2<f64>) {
    let grid = Grid::square(n, 1.0).unwrap();
    let spec = SurfaceSpec {
        grid,
        psd: Psd::self_affine(0.8, 1.0, 8.0 / n as f64),
        normalization: Normalization::RmsGradient(1.0),
        amplitudes: Amplitudes::Exact,
        seed: 2026,
    };
    let g0 = flat_on_rough(generate(&spec).unwrap().heights.view()).unwrap();
    let domain = Domain {
        nx: n,
        ny: n,
        dx: 1.0 / n as f64,
        dy: 1.0 / n as f64,
        periodic: true,
    };
    (Periodic::new(domain, 1.0).unwrap(), g0)
}

fn both(
    op: &dyn Compliance,
    g0: &Array2<f64>,
    control: Control,
    tolerance: f64,
) -> [(ContactState, ContactReport); 2] {
    [false, true].map(|preconditioned| {
        let options = ContactOptions {
            tolerance,
            preconditioned,
            ..ContactOptions::default()
        };
        let (state, report) = solve(op, g0.view(), control, &options, None, &mut ()).unwrap();
        assert!(
            report.converged(),
            "{control:?}, preconditioned {preconditioned}: {:?}",
            report.termination
        );
        (state, report)
    })
}

#[test]
fn the_preconditioned_solve_is_the_plain_one_in_fewer_iterations() {
    // A Hertzian sphere on a free grid (contact 48 cells across) and rough periodic contact,
    // each under load and under displacement control (where the option leaves the iteration
    // plain: the same iterations).
    let (e, r, a) = (1e9, 1e-4, 1e-6);
    let d = 2.0 * a / 48.0;
    let domain = Domain {
        nx: 72,
        ny: 72,
        dx: d,
        dy: d,
        periodic: false,
    };
    let free = Free::new(domain, e).unwrap();
    let ball = sphere(&domain, r, SphereProfile::Paraboloid, None).unwrap();
    let hertz_load = 4.0 * e * a.powi(3) / (3.0 * r);
    let (rough_op, rough_g0) = bench_case(256);
    let cases: [(&str, &dyn Compliance, &Array2<f64>, Control); 4] = [
        ("Hertz, load", &free, &ball, Control::Force(hertz_load)),
        ("Hertz, approach", &free, &ball, Control::Approach(a * a / r)),
        ("rough, load", &rough_op, &rough_g0, Control::MeanPressure(0.04)),
        ("rough, approach", &rough_op, &rough_g0, Control::Approach(0.02)),
    ];
    for (name, op, g0, control) in cases {
        let [(plain, p), (pre, q)] = both(op, g0, control, 1e-10);
        let differ = plain
            .pressure
            .iter()
            .zip(&pre.pressure)
            .filter(|(a, b)| (**a > 0.0) != (**b > 0.0))
            .count();
        let largest = plain.pressure.iter().fold(0.0f64, |m, v| m.max(*v));
        let deviation = (&plain.pressure - &pre.pressure)
            .iter()
            .fold(0.0f64, |m, v| m.max(v.abs()))
            / largest;
        println!(
            "{name}: iterations {} plain, {} preconditioned; loads {:.9e} / {:.9e}; contact cells differing {differ}; \
             largest pressure difference {deviation:.1e} of the peak",
            p.iterations, q.iterations, p.load, q.load
        );
        assert_eq!(differ, 0, "{name}");
        assert!((p.load / q.load - 1.0).abs() < 1e-8, "{name}");
        assert!(deviation < 1e-6, "{name}: {deviation:e}");
        if matches!(control, Control::Approach(_)) {
            assert_eq!(q.iterations, p.iterations, "{name}");
        } else {
            assert!(q.iterations < p.iterations, "{name}");
        }
    }
}

#[test]
fn preconditioned_iterations_grow_more_slowly_than_the_square_root_of_the_cells() {
    // The bench's surface at p = 0.04 E* on 128^2 and 512^2 cells (16 times as many): the
    // exponent of the iteration count against the number of cells.
    let exponent = |preconditioned: bool| {
        let iterations = [128, 512].map(|n| {
            let (op, g0) = bench_case(n);
            let options = ContactOptions {
                tolerance: 5e-9,
                preconditioned,
                ..ContactOptions::default()
            };
            let (_, report) = solve(
                &op,
                g0.view(),
                Control::MeanPressure(0.04),
                &options,
                None,
                &mut (),
            )
            .unwrap();
            assert!(report.converged());
            report.iterations as f64
        });
        println!("preconditioned {preconditioned}: iterations {iterations:?}");
        (iterations[1] / iterations[0]).ln() / 16f64.ln()
    };
    let (plain, pre) = (exponent(false), exponent(true));
    println!("exponents: plain {plain:.3}, preconditioned {pre:.3}");
    assert!(pre < 0.5 && pre < plain, "{pre} against {plain}");
}
