//! The adhesive laws against their physics: conservation, extremes, limits, exact cell means.

use ljadhesion::*;
use ndarray::Array2;
use proptest::prelude::*;

const W0: f64 = 0.05;
const Z0: f64 = 2.071e-9;

fn lj() -> LennardJones {
    LennardJones::new(W0, Z0).unwrap()
}

/// 8-point Gauss-Legendre nodes and weights on [-1, 1].
const GL: [(f64, f64); 8] = [
    (-0.9602898564975363, 0.1012285362903763),
    (-0.7966664774136267, 0.2223810344533745),
    (-0.525532409916329, 0.3137066458778873),
    (-0.1834346424956498, 0.362683783378362),
    (0.1834346424956498, 0.362683783378362),
    (0.525532409916329, 0.3137066458778873),
    (0.7966664774136267, 0.2223810344533745),
    (0.9602898564975363, 0.1012285362903763),
];

/// Mean of `f` over [a, b] by composite Gauss-Legendre on `panels` geometric panels: never
/// divides a small difference, so it is a reference for the divided difference at any width.
fn quadrature_mean(f: impl Fn(f64) -> f64, a: f64, b: f64, panels: usize) -> f64 {
    if a == b {
        return f(a);
    }
    let (lo, hi) = (a.min(b), a.max(b));
    let ratio = (hi / lo).powf(1.0 / panels as f64);
    let mut sum = 0.0;
    let mut x0 = lo;
    for k in 0..panels {
        let x1 = if k + 1 == panels { hi } else { x0 * ratio };
        let (m, h) = (0.5 * (x0 + x1), 0.5 * (x1 - x0));
        sum += GL.iter().map(|(x, w)| w * h * f(m + h * x)).sum::<f64>();
        x0 = x1;
    }
    sum / (hi - lo)
}

#[test]
fn integral_of_the_lj_law_is_minus_w0() {
    // Over z in [z0, inf): substitute v = z0/z, panels in v on (0, 1].
    let law = lj();
    let integral = quadrature_mean(|v| law.pressure(Z0 / v) * Z0 / (v * v), 1e-12, 1.0, 64) * (1.0 - 1e-12);
    assert!((integral / -W0 - 1.0).abs() < 1e-10, "{integral}");
    // Phi is its antiderivative: Phi(z0) = w0, and the energy per area in contact is -w0.
    assert!((law.phi(Z0) / W0 - 1.0).abs() < 1e-15);
    assert!((law.energy_per_area(Z0) + W0).abs() < 1e-17);
    let (z1, z2) = (1.3 * Z0, 4.0 * Z0);
    let by_quadrature = quadrature_mean(|z| law.pressure(z), z1, z2, 32) * (z2 - z1);
    assert!((law.phi(z2) - law.phi(z1) - by_quadrature).abs() < 1e-12 * W0);
}

#[test]
fn the_other_laws_also_integrate_to_minus_w0() {
    let e = ExponentialLaw::new(W0, Z0).unwrap();
    let integral = quadrature_mean(|g| e.pressure(g), 0.0 + 1e-30, 60.0 * Z0, 200) * 60.0 * Z0;
    assert!((integral / -W0 - 1.0).abs() < 1e-10, "{integral}");
    let d = DugdaleLaw::equivalent_to(&lj());
    assert!((d.pressure(0.0) * d.range() / -W0 - 1.0).abs() < 1e-15);
    assert_eq!(d.pressure(d.range() * 1.000001), 0.0);
    // Maugis' equivalence: h0 = 0.974 z0 for the same peak stress.
    assert!((d.range() / Z0 - 0.974).abs() < 5e-4, "{}", d.range() / Z0);
}

/// Far from the wall the exponential law skips `exp`, whose result there is zero: the same
/// pressure, bit for bit, on both sides of where the skip begins.
#[test]
fn the_exponential_law_is_exact_where_it_underflows() {
    let e = ExponentialLaw::new(W0, Z0).unwrap();
    for k in 0..=20_000 {
        let g = Z0 * (700.0 + 100.0 * k as f64 / 20_000.0);
        let direct = -(W0 / Z0) * (-g / Z0).exp();
        assert_eq!(e.pressure(g).to_bits(), direct.to_bits(), "{}", g / Z0);
    }
}

#[test]
fn the_strongest_pull_is_at_the_sixth_root_of_three() {
    let law = lj();
    let z_star = 3f64.powf(1.0 / 6.0) * Z0;
    let expected = -16.0 * W0 / (9.0 * 3f64.sqrt() * Z0);
    assert!((law.pressure(z_star) / expected - 1.0).abs() < 1e-14);
    assert!((law.min_pressure() / expected - 1.0).abs() < 1e-15);
    assert!((law.min_pressure() / (W0 / Z0) + 1.0264).abs() < 1e-4);
    for k in 0..=10_000 {
        let z = Z0 * (1.0 + 3.0 * k as f64 / 10_000.0);
        assert!(law.pressure(z) >= expected * (1.0 + 1e-14));
    }
}

#[test]
fn stiffness_bounds_hold_and_are_reached() {
    let law = lj();
    let e = ExponentialLaw::new(W0, Z0).unwrap();
    let slope_max = |f: &dyn Fn(f64) -> f64| {
        (0..20_000)
            .map(|k| {
                let g = 10.0 * Z0 * k as f64 / 20_000.0;
                let h = 1e-5 * Z0;
                ((f(g + h) - f(g)) / h).abs()
            })
            .fold(0.0, f64::max)
    };
    let lj_max = slope_max(&|g| law.pressure(law.separation(g)));
    assert!(lj_max <= PointLaw(law).stiffness_bound() && lj_max > 0.99 * law.stiffness_bound());
    let e_max = slope_max(&|g| e.pressure(g));
    assert!(e_max <= e.stiffness_bound() && e_max > 0.99 * e.stiffness_bound());
}

#[test]
fn the_cell_mean_tends_to_the_point_value() {
    let law = lj();
    for z in [Z0, 1.2 * Z0, 3.0 * Z0] {
        assert_eq!(law.mean_pressure(z, z), law.pressure(z));
        let dp = (law.pressure(z * (1.0 + 1e-7)) - law.pressure(z * (1.0 - 1e-7))) / (2e-7 * z);
        for delta in [1e-3, 1e-6, 1e-9, 1e-12] {
            let d = delta * Z0;
            let mean = law.mean_pressure(z, z + d);
            // mean = p(z) + p'(z) d/2 + p''(z) d^2/6 + ..., and |p''| <= 208 w0/z0^3 on z >= z0,
            // so the remainder is below 35 (d/z0)^2 w0/z0: no loss of digits as d -> 0.
            let err = (mean - law.pressure(z) - 0.5 * dp * d).abs();
            assert!(
                err <= 1e-14 * W0 / Z0 + 35.0 * (d / Z0).powi(2) * W0 / Z0,
                "z={z} d={d}: {err}"
            );
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]
    #[test]
    fn the_divided_difference_matches_quadrature(g in 0.0..20.0f64, delta in prop_oneof![Just(0.0), 0.0..1e-9f64, 0.0..1e-3f64, 0.0..10.0f64]) {
        let law = lj();
        let (z1, z2) = (Z0 * (1.0 + g), Z0 * (1.0 + g + delta));
        let reference = quadrature_mean(|z| law.pressure(z), z1, z2, 48);
        let scale = quadrature_mean(|z| law.pressure(z).abs(), z1, z2, 48);
        let got = law.mean_pressure(z1, z2);
        prop_assert!((got - reference).abs() <= 1e-12 * scale, "g={g} delta={delta}: {got} vs {reference}");
        prop_assert!((law.mean_pressure(z2, z1) - got).abs() <= 1e-15 * scale);
    }

    #[test]
    fn the_surface_law_is_attractive_and_bounded(seed in 0u64..1000) {
        // A rough gap field from a cheap deterministic hash: gaps between 0 and 5 z0, some contact.
        let (ny, nx) = (12, 17);
        let mut state = seed.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
        let gap = Array2::from_shape_fn((ny, nx), |_| {
            state = state.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64 * 6.0 - 1.0).max(0.0) * Z0
        });
        let cells = Cells { dx: 0.5 * Z0, dy: 0.7 * Z0, periodic: seed % 2 == 0 };
        let mut out = Array2::zeros((ny, nx));
        SurfaceLaw(lj()).pressure_field(gap.view(), &cells, out.view_mut()).unwrap();
        let min = lj().min_pressure();
        for ((y, x), &p) in out.indexed_iter() {
            prop_assert!(p <= 0.0);
            let z1 = gap[(y, x)];
            let x2 = if x + 1 < nx { x + 1 } else if cells.periodic { 0 } else { nx - 2 };
            let y3 = if y + 1 < ny { y + 1 } else if cells.periodic { 0 } else { ny - 2 };
            let s = (1.0 + ((gap[(y, x2)] - z1) / cells.dx).powi(2) + ((gap[(y3, x)] - z1) / cells.dy).powi(2)).sqrt();
            prop_assert!(p >= s * min * (1.0 + 1e-14), "{p} below S p_min = {}", s * min);
        }
    }
}

#[test]
fn flat_gaps_give_the_point_law_exactly() {
    let cells = Cells {
        dx: 1e-9,
        dy: 1e-9,
        periodic: false,
    };
    for g in [0.0, 0.3e-9, 2.071e-9, 1e-8] {
        let gap = Array2::from_elem((5, 7), g);
        let mut fields = Vec::new();
        for law in [
            &PointLaw(lj()) as &dyn AdhesionLaw,
            &LineLaw(lj()),
            &SurfaceLaw(lj()),
        ] {
            let mut out = Array2::zeros((5, 7));
            law.pressure_field(gap.view(), &cells, out.view_mut()).unwrap();
            fields.push(out);
        }
        assert_eq!(fields[0], fields[1]);
        assert_eq!(fields[0], fields[2]);
        assert_eq!(fields[0][(0, 0)], lj().pressure(Z0 + g));
    }
}

#[test]
fn on_a_gap_ramp_the_surface_law_is_the_exact_cell_mean_times_the_area_factor() {
    let (ny, nx) = (6, 9);
    let (dx, dy) = (0.8 * Z0, 1.1 * Z0);
    let (alpha, beta) = (0.3, -0.2); // gap slopes along x and y
    let g0 = 3.0 * Z0;
    let gap = Array2::from_shape_fn((ny, nx), |(y, x)| {
        g0 + alpha * dx * x as f64 + beta * dy * y as f64
    });
    let law = lj();
    let cells = Cells {
        dx,
        dy,
        periodic: false,
    };
    let (mut surface, mut line) = (Array2::zeros((ny, nx)), Array2::zeros((ny, nx)));
    SurfaceLaw(law)
        .pressure_field(gap.view(), &cells, surface.view_mut())
        .unwrap();
    LineLaw(law)
        .pressure_field(gap.view(), &cells, line.view_mut())
        .unwrap();
    let s = (1.0 + alpha * alpha + beta * beta).sqrt();
    for y in 0..ny {
        for x in 0..nx {
            // Interior cells span [z, z + alpha dx]; the free last column mirrors to [z - alpha dx, z].
            let z1 = Z0 + gap[(y, x)];
            let z2 = if x + 1 < nx {
                z1 + alpha * dx
            } else {
                z1 - alpha * dx
            };
            let exact = (law.phi(z2) - law.phi(z1)) / (z2 - z1);
            assert!((line[(y, x)] / exact - 1.0).abs() < 1e-12, "({y},{x})");
            assert!((surface[(y, x)] / (s * exact) - 1.0).abs() < 1e-12, "({y},{x})");
        }
    }
}

#[test]
fn periodic_cells_wrap_around() {
    let gap = Array2::from_shape_fn((3, 4), |(y, x)| Z0 * (x + 2 * y) as f64);
    let cells = Cells {
        dx: Z0,
        dy: Z0,
        periodic: true,
    };
    let mut out = Array2::zeros((3, 4));
    LineLaw(lj())
        .pressure_field(gap.view(), &cells, out.view_mut())
        .unwrap();
    let expect = lj().mean_pressure(Z0 + gap[(1, 3)], Z0 + gap[(1, 0)]);
    assert_eq!(out[(1, 3)], expect);
}

#[test]
fn results_do_not_depend_on_the_number_of_threads() {
    let gap = Array2::from_shape_fn((257, 129), |(y, x)| {
        Z0 * (1.0 + ((x * 7 + y * 3) % 13) as f64 / 3.0)
    });
    let cells = Cells {
        dx: Z0,
        dy: Z0,
        periodic: true,
    };
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let (mut out, mut energy_form) = (Array2::zeros(gap.dim()), Array2::zeros(gap.dim()));
                SurfaceLaw(lj())
                    .pressure_field(gap.view(), &cells, out.view_mut())
                    .unwrap();
                SurfaceEnergyLaw(lj())
                    .pressure_field(gap.view(), &cells, energy_form.view_mut())
                    .unwrap();
                (out, energy_form)
            })
    };
    assert_eq!(run(1), run(2));
    assert_eq!(run(1), run(3));
}

#[test]
fn bad_input_is_refused() {
    assert!(LennardJones::new(0.0, Z0).is_err());
    assert!(LennardJones::new(W0, -1e-9).is_err());
    assert!(LennardJones::new(f64::NAN, Z0).is_err());
    assert!(ExponentialLaw::new(W0, 0.0).is_err());
    assert!(DugdaleLaw::new(-W0, Z0).is_err());
    let cells = Cells {
        dx: Z0,
        dy: Z0,
        periodic: true,
    };
    let mut gap = Array2::from_elem((4, 5), Z0);
    gap[(2, 3)] = f64::NAN;
    let laws: [&dyn AdhesionLaw; 5] = [
        &PointLaw(lj()),
        &LineLaw(lj()),
        &SurfaceLaw(lj()),
        &ExponentialLaw::new(W0, Z0).unwrap(),
        &DugdaleLaw::equivalent_to(&lj()),
    ];
    for law in laws {
        let mut out = Array2::zeros((4, 5));
        let err = law
            .pressure_field(gap.view(), &cells, out.view_mut())
            .unwrap_err();
        assert!(
            matches!(err, AdhesionError::NonFiniteGap { row: 2, col: 3, value } if value.is_nan()),
            "{}: {err}",
            law.name()
        );
        let mut wrong = Array2::zeros((5, 4));
        assert!(matches!(
            law.pressure_field(gap.view(), &cells, wrong.view_mut()),
            Err(AdhesionError::ShapeMismatch { .. })
        ));
    }
}

#[test]
fn local_potentials_are_consistent_with_their_laws() {
    let laws: Vec<Box<dyn AdhesionLaw>> = vec![
        Box::new(PointLaw(lj())),
        Box::new(ExponentialLaw::new(W0, Z0).unwrap()),
        Box::new(NoAdhesion),
    ];
    let cells = Cells {
        dx: 1e-8,
        dy: 1e-8,
        periodic: true,
    };
    for law in &laws {
        let v = law.local_potential().expect("a local law");
        assert_eq!(v.energy(0.0), -law.work_of_adhesion(), "{}", law.name());
        assert!(v.energy(1e3 * Z0).abs() < 2e-6 * W0); // the LJ tail: (4/3) w0 (z0/z)^2
        let gaps = Array2::from_shape_fn((1, 40), |(_, i)| 0.05 * Z0 * i as f64);
        let mut field = Array2::zeros(gaps.dim());
        law.pressure_field(gaps.view(), &cells, field.view_mut()).unwrap();
        for (&g, &p) in gaps.iter().zip(field.iter()) {
            assert_eq!(v.pressure(g), p, "{} at {g:e}", law.name());
            // Central differences, one-sided at contact (the hard wall).
            let h = 1e-5 * Z0;
            let (lo, hi) = if g == 0.0 { (0.0, 2.0 * h) } else { (g - h, g + h) };
            let mid = 0.5 * (lo + hi);
            let dv = (v.energy(hi) - v.energy(lo)) / (hi - lo);
            let dp = (v.pressure(hi) - v.pressure(lo)) / (hi - lo);
            let scale = law.peak_pressure().abs().max(1.0);
            assert!(
                (-dv - v.pressure(mid)).abs() < 1e-6 * scale,
                "{}: p at {g:e}",
                law.name()
            );
            let k = law.stiffness_bound().max(1.0);
            assert!(
                (-dp - v.curvature(mid)).abs() < 1e-5 * k,
                "{}: V'' at {g:e}",
                law.name()
            );
        }
    }
    // The line, surface and Dugdale laws have no local energy.
    assert!(LineLaw(lj()).local_potential().is_none());
    assert!(SurfaceLaw(lj()).local_potential().is_none());
    assert!(DugdaleLaw::equivalent_to(&lj()).local_potential().is_none());
}

#[test]
fn the_cell_mean_energy_is_the_quadrature_of_the_energy_and_its_derivatives_match() {
    let lj = lj();
    let z0 = Z0;
    for (z1, z2) in [
        (z0, 1.3 * z0),
        (1.2 * z0, 40.0 * z0),
        (3.0 * z0, 3.0 * z0 * (1.0 + 1e-9)),
        (7.0 * z0, 2.0 * z0),
    ] {
        let [m, m1, m2, m11, m22] = lj.mean_energy_v(z0 / z1, z0 / z2);
        let reference = quadrature_mean(|z| lj.energy_per_area(z), z1, z2, 64);
        assert!(
            (m - reference).abs() <= 1e-12 * W0,
            "{z1} {z2}: {m} vs {reference}"
        );
        // Derivatives by v, by central differences of the polynomial.
        let (v1, v2, h) = (z0 / z1, z0 / z2, 1e-5);
        let at = |a: f64, b: f64| lj.mean_energy_v(a, b)[0];
        let d1 = (at(v1 + h, v2) - at(v1 - h, v2)) / (2.0 * h);
        let d2 = (at(v1, v2 + h) - at(v1, v2 - h)) / (2.0 * h);
        let d11 = (at(v1 + h, v2) - 2.0 * m + at(v1 - h, v2)) / (h * h);
        let d22 = (at(v1, v2 + h) - 2.0 * m + at(v1, v2 - h)) / (h * h);
        for (exact, fd) in [(m1, d1), (m2, d2), (m11, d11), (m22, d22)] {
            assert!((exact - fd).abs() <= 1e-5 * W0 * 10.0, "{exact} vs {fd}");
        }
    }
}

/// A rough gap field of `ny` by `nx` cells, 0 to a few tens of z0, some cells closed.
fn rough_gap(ny: usize, nx: usize) -> Array2<f64> {
    Array2::from_shape_fn((ny, nx), |(y, x)| {
        let s = (0.7 * x as f64 + 1.3 * y as f64).sin() + (2.1 * x as f64 * y as f64).cos();
        (Z0 * (3.0 * s + 1.5 * s * s)).max(0.0)
    })
}

#[test]
fn the_surface_energy_law_is_minus_the_gradient_of_its_energy() {
    let law = SurfaceEnergyLaw(lj());
    let potential = law.field_potential().expect("a field potential");
    for periodic in [true, false] {
        let cells = Cells {
            dx: 3.0 * Z0,
            dy: 2.0 * Z0,
            periodic,
        };
        let gap = rough_gap(6, 7);
        let evaluate = |g: &Array2<f64>| {
            let (mut e, mut p, mut c) = (
                Array2::zeros(g.dim()),
                Array2::zeros(g.dim()),
                Array2::zeros(g.dim()),
            );
            potential
                .evaluate_field(g.view(), &cells, e.view_mut(), p.view_mut(), c.view_mut())
                .unwrap();
            (e.sum(), p, c)
        };
        let (e0, p, c) = evaluate(&gap);
        let mut from_law = Array2::zeros(gap.dim());
        law.pressure_field(gap.view(), &cells, from_law.view_mut())
            .unwrap();
        assert_eq!(from_law, p);
        let h = 1e-6 * Z0;
        for ((y, x), &g) in gap.indexed_iter() {
            if g < 2.0 * h {
                continue; // the wall: one-sided
            }
            let shifted = |d: f64| {
                let mut moved = gap.clone();
                moved[(y, x)] += d;
                evaluate(&moved).0
            };
            let (up, down) = (shifted(h), shifted(-h));
            let slope = (up - down) / (2.0 * h);
            let second = (up - 2.0 * e0 + down) / (h * h);
            let scale = 16.0 * W0 / (9.0 * 3f64.sqrt() * Z0);
            assert!(
                (p[(y, x)] + slope).abs() <= 1e-6 * scale,
                "periodic {periodic} ({y}, {x}): p {} vs -dE/dg {}",
                p[(y, x)],
                -slope
            );
            let stiffness = 16.0 * W0 / (Z0 * Z0);
            assert!(
                (c[(y, x)] - second).abs() <= 1e-3 * stiffness,
                "({y}, {x}): {} vs {second}",
                c[(y, x)]
            );
        }
    }
}

#[test]
fn the_surface_energy_law_on_flat_gaps_is_the_point_law() {
    for periodic in [true, false] {
        let cells = Cells {
            dx: 1e-8,
            dy: 1e-8,
            periodic,
        };
        for g in [0.0, 0.1 * Z0, 0.5 * Z0, 3.0 * Z0, 40.0 * Z0] {
            let gap = Array2::from_elem((4, 5), g);
            let (mut a, mut b) = (Array2::zeros((4, 5)), Array2::zeros((4, 5)));
            SurfaceEnergyLaw(lj())
                .pressure_field(gap.view(), &cells, a.view_mut())
                .unwrap();
            PointLaw(lj())
                .pressure_field(gap.view(), &cells, b.view_mut())
                .unwrap();
            for ((y, x), &a) in a.indexed_iter() {
                let b = b[(y, x)];
                // The mean is along x: a free domain's first column is the +x neighbour of no
                // cell (half its share), and its mirrored last column gives its share to the
                // second last.
                let share = match x {
                    _ if periodic => 1.0,
                    0 => 0.5,
                    3 => 1.5,
                    _ => 1.0,
                };
                assert!(
                    (a - share * b).abs() <= 1e-12 * b.abs().max(1e-3 * W0 / Z0),
                    "g {g} ({y}, {x}): {a} vs {b}"
                );
            }
        }
    }
}

/// The line and surface laws' closed-form stiffnesses are the slopes of their pressure fields
/// when a column of nodes moves (a cell's pressure depends on its own node, its +x neighbour
/// and, through the area factor, its +y neighbour): differences of the field, on rough gaps
/// from contact to far apart, periodic and free; the pressure is the field's bit for bit.
#[test]
fn the_closed_form_stiffnesses_are_the_slopes_of_the_pressure() {
    let (ny, nx) = (6, 7);
    let gap = rough_gap(ny, nx);
    let line = LineLaw(lj());
    let surface = SurfaceLaw(lj());
    let laws: [&dyn AdhesionLaw; 2] = [&line, &surface];
    for law in laws {
        for periodic in [true, false] {
            let cells = Cells {
                dx: 3e-9,
                dy: 4e-9,
                periodic,
            };
            let field = |g: &Array2<f64>| {
                let mut p = Array2::zeros((ny, nx));
                law.pressure_field(g.view(), &cells, p.view_mut()).unwrap();
                p
            };
            let (mut p, mut own, mut next) = (
                Array2::zeros((ny, nx)),
                Array2::zeros((ny, nx)),
                Array2::zeros((ny, nx)),
            );
            assert!(
                law.pressure_and_stiffness_field(
                    gap.view(),
                    &cells,
                    p.view_mut(),
                    own.view_mut(),
                    next.view_mut()
                )
                .unwrap()
            );
            assert_eq!(p, field(&gap));
            let h = 1e-8 * Z0;
            let scale = law.stiffness_bound();
            for x in 0..nx {
                // Forward differences (the law is clamped on the wall): column x moved
                // changes its own cells and those whose +x neighbour it is.
                let mut up = gap.clone();
                up.column_mut(x).mapv_inplace(|g| g + h);
                let pu = field(&up);
                let from = if x > 0 {
                    Some(x - 1)
                } else if periodic {
                    Some(nx - 1)
                } else {
                    None
                };
                for y in 0..ny {
                    let slope = |y: usize, c: usize| (p[(y, c)] - pu[(y, c)]) / h;
                    let expected = slope(y, x);
                    assert!(
                        (expected - own[(y, x)]).abs() < 1e-6 * scale,
                        "{} own ({y}, {x}): {} against {expected}",
                        law.name(),
                        own[(y, x)]
                    );
                    if let Some(c) = from.filter(|&c| c != x) {
                        let expected = slope(y, c);
                        assert!(
                            (expected - next[(y, c)]).abs() < 1e-6 * scale,
                            "{} next ({y}, {c}): {} against {expected}",
                            law.name(),
                            next[(y, c)]
                        );
                    }
                }
            }
        }
    }
    // Where a cell's two ends coincide, each slope of the mean is half the pressure's.
    let law = lj();
    for z in [1.0, 1.1, 1.2, 1.5, 3.0, 10.0].map(|r| r * Z0) {
        let v = Z0 / z;
        let (d1, d2) = law.mean_pressure_slopes_v(v, v);
        assert_eq!(d1, d2);
        assert!(
            (d1 + d2 + law.curvature(z)).abs() < 1e-12 * law.stiffness_bound(),
            "{z}"
        );
    }
    // The other laws have none.
    let mut a = Array2::zeros((ny, nx));
    let (mut b, mut c) = (a.clone(), a.clone());
    let cells = Cells {
        dx: 3e-9,
        dy: 4e-9,
        periodic: true,
    };
    assert!(
        !PointLaw(lj())
            .pressure_and_stiffness_field(gap.view(), &cells, a.view_mut(), b.view_mut(), c.view_mut())
            .unwrap()
    );
}
