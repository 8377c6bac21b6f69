//! The half-space operators against exact solutions.

use elastic::love::rectangle_displacement;
use elastic::{
    Compliance, Domain, ElasticError, Free, FreeStiffness, Material, Periodic, PeriodicStiffness,
    composite_modulus,
};
use ndarray::Array2;
use proptest::prelude::*;
use std::f64::consts::PI;

const E: f64 = 25e6;

fn domain(nx: usize, ny: usize, d: f64, periodic: bool) -> Domain {
    Domain {
        nx,
        ny,
        dx: d,
        dy: 1.3 * d,
        periodic,
    }
}

fn apply(op: &dyn Compliance, p: &Array2<f64>) -> Array2<f64> {
    let mut u = Array2::zeros(p.dim());
    op.apply(p.view(), u.view_mut(), &mut op.make_workspace())
        .unwrap();
    u
}

#[test]
fn a_sinusoidal_pressure_gives_the_exact_amplitude() {
    let (nx, ny, d) = (48, 40, 1e-6);
    let dom = domain(nx, ny, d, true);
    let op = Periodic::new(dom, E).unwrap();
    let (lx, ly) = (nx as f64 * d, ny as f64 * dom.dy);
    for (kx, ky) in [(1, 0), (0, 3), (5, 7), (24, 0), (7, 20)] {
        let (qx, qy) = (2.0 * PI * kx as f64 / lx, 2.0 * PI * ky as f64 / ly);
        let phase = |j: usize, i: usize| qx * i as f64 * d + qy * j as f64 * dom.dy;
        let p0 = 1e5;
        let p = Array2::from_shape_fn((ny, nx), |(j, i)| p0 * phase(j, i).cos());
        let u = apply(&op, &p);
        let amp = 2.0 * p0 / (E * qx.hypot(qy));
        for ((j, i), v) in u.indexed_iter() {
            assert!((v - amp * phase(j, i).cos()).abs() < 1e-12 * amp, "k=({kx},{ky})");
        }
    }
    // A uniform pressure displaces nothing: the mean displacement is zero by convention.
    let u = apply(&op, &Array2::from_elem((ny, nx), 1e5));
    let scale = 2.0 * 1e5 / (E * 2.0 * PI / lx.max(ly));
    assert!(u.iter().all(|v| v.abs() < 1e-13 * scale));
}

#[test]
fn love_closed_form_checks() {
    let u = rectangle_displacement(0.0, 0.0, 1.0, 1.0, 1.0, 1.0);
    assert!((u - 2.2444).abs() < 1e-4);
    // Far away: the point load 4ab p / (pi E* r).
    let r = 1e3;
    let far = rectangle_displacement(r * 0.6, r * 0.8, 1.0, 2.0, 1.0, 1.0);
    assert!((far / (8.0 / (PI * r)) - 1.0).abs() < 1e-5);
    // Corner of a square: half the centre value of a square twice the size, by symmetry.
    let corner = rectangle_displacement(1.0, 1.0, 1.0, 1.0, 1.0, 1.0);
    let big = rectangle_displacement(0.0, 0.0, 2.0, 2.0, 1.0, 1.0);
    assert!((corner - big / 4.0).abs() < 1e-14);
    // On an edge line the limits are taken, not NaN.
    assert!(rectangle_displacement(1.0, 0.0, 1.0, 1.0, 1.0, 1.0).is_finite());
    assert!(rectangle_displacement(3.0, 1.0, 1.0, 1.0, 1.0, 1.0).is_finite());
}

/// The cell integral of `1/(pi E* |r - s|)` by 8-point Gauss-Legendre on 4 x 4 panels: no
/// cancellation, so a reference at any distance of at least a few cells.
fn influence_by_quadrature(x: f64, y: f64, a: f64, b: f64) -> f64 {
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
    let panels = 4;
    let (hx, hy) = (a / panels as f64, b / panels as f64);
    let mut sum = 0.0;
    for pi in 0..panels {
        for pj in 0..panels {
            let (cx, cy) = (-a + (2 * pi + 1) as f64 * hx, -b + (2 * pj + 1) as f64 * hy);
            for (u, wu) in GL {
                for (v, wv) in GL {
                    sum += wu * wv * hx * hy / (x - cx - hx * u).hypot(y - cy - hy * v);
                }
            }
        }
    }
    sum / (PI * E)
}

#[test]
fn the_far_field_expansion_joins_the_closed_form() {
    use elastic::love::cell_influence;
    let (a, b) = (0.5e-6, 0.65e-6);
    // Closed form near the cell, expansion beyond 64 half-sides (~40 cells here): both hold
    // to a few 1e-12 on either side of the switch and far beyond it, where the closed form
    // alone would lose digits to cancellation.
    for (i, j) in [
        (4.0, 1.0),
        (20.0, 7.0),
        (38.0, 5.0),
        (41.0, 3.0),
        (30.0, 60.0),
        (300.0, 100.0),
        (2000.0, 4000.0),
    ] {
        let (x, y) = (i * 2.0 * a, j * 2.0 * b);
        let reference = influence_by_quadrature(x, y, a, b);
        let got = cell_influence(x, y, a, b, E);
        assert!(
            ((got - reference) / reference).abs() < 5e-12,
            "({i},{j}): {got:e} vs {reference:e}"
        );
    }
    let far = rectangle_displacement(4000e-6, 8000e-6, a, b, 1.0, E);
    let reference = influence_by_quadrature(4000e-6, 8000e-6, a, b);
    assert!(
        ((far - reference) / reference).abs() > 1e-11,
        "the closed form alone degrades far away"
    );
}

#[test]
fn a_uniformly_loaded_patch_matches_love_everywhere() {
    let (nx, ny, d) = (40, 36, 1e-6);
    let dom = domain(nx, ny, d, false);
    let op = Free::new(dom, E).unwrap();
    // Cells 10..20 in x and 8..14 in y carry p0.
    let p0 = 2e5;
    let p = Array2::from_shape_fn((ny, nx), |(j, i)| {
        if (10..20).contains(&i) && (8..14).contains(&j) {
            p0
        } else {
            0.0
        }
    });
    let u = apply(&op, &p);
    let (cx, cy) = (15.0 * d, 11.0 * dom.dy); // patch centre (cell centres at index * spacing)
    let (a, b) = (5.0 * d, 3.0 * dom.dy);
    let umax = rectangle_displacement(0.0, 0.0, a, b, p0, E);
    for (j, i) in [(11, 15), (8, 10), (13, 19), (0, 0), (35, 39), (11, 25)] {
        // Centre, a corner cell, the opposite corner cell, far corners, outside on the axis.
        let exact = rectangle_displacement(
            i as f64 * d - cx + 0.5 * d,
            j as f64 * dom.dy - cy + 0.5 * dom.dy,
            a,
            b,
            p0,
            E,
        );
        assert!(
            (u[(j, i)] - exact).abs() < 1e-12 * umax,
            "({j},{i}): {} vs {exact}",
            u[(j, i)]
        );
    }
}

/// Largest error of u inside a Hertz contact of `cells` cells across, relative to u(0).
fn hertz_error(cells: usize) -> (f64, f64) {
    let n = cells + cells / 4 * 2;
    let radius = 1e-4;
    let a = 1e-6; // contact radius
    let d = 2.0 * a / cells as f64;
    let dom = Domain {
        nx: n,
        ny: n,
        dx: d,
        dy: d,
        periodic: false,
    };
    let op = Free::new(dom, E).unwrap();
    let p0 = 2.0 * E * a / (PI * radius);
    let c = (n as f64 - 1.0) / 2.0;
    let r = |j: usize, i: usize| ((i as f64 - c) * d).hypot((j as f64 - c) * d);
    let p = Array2::from_shape_fn((n, n), |(j, i)| {
        p0 * (1.0 - (r(j, i) / a).powi(2)).max(0.0).sqrt()
    });
    let u = apply(&op, &p);
    let delta = a * a / radius;
    let mut worst: f64 = 0.0;
    for ((j, i), v) in u.indexed_iter() {
        let rr = r(j, i);
        if rr < a {
            worst = worst.max((v - (delta - rr * rr / (2.0 * radius))).abs() / delta);
        }
    }
    let centre = u[(n / 2, n / 2)];
    (worst, centre)
}

#[test]
fn hertz_pressure_gives_the_hertz_displacement() {
    let (coarse, _) = hertz_error(50);
    let (fine, _) = hertz_error(100);
    println!("Hertz displacement error: 50 cells across {coarse:.2e}, 100 cells {fine:.2e}");
    assert!(fine < 0.005, "{fine}");
    assert!(
        fine < 0.75 * coarse,
        "refinement must reduce the error: {coarse} -> {fine}"
    );
}

#[test]
fn free_and_periodic_agree_for_a_small_patch_in_a_large_box() {
    let (n, d) = (128, 1e-6);
    let p = Array2::from_shape_fn((n, n), |(j, i)| {
        if (62..66).contains(&i) && (62..66).contains(&j) {
            1e5
        } else {
            0.0
        }
    });
    let uf = apply(&Free::new(domain(n, n, d, false), E).unwrap(), &p);
    let up = apply(&Periodic::new(domain(n, n, d, true), E).unwrap(), &p);
    // Away from the patch both are its far field; the periodic images add a nearly uniform
    // offset, so differences between points agree. (On the patch itself the two
    // discretisations differ by ~1 %: the spectral kernel treats the pressure as band-limited,
    // Love's coefficients as constant over each cell.)
    let reference = uf[(64, 70)];
    for (j, i) in [(64, 80), (90, 64), (70, 76), (30, 40)] {
        let (df, dp) = (reference - uf[(j, i)], up[(64, 70)] - up[(j, i)]);
        assert!((df - dp).abs() < 0.01 * df.abs(), "({j},{i}): {df:e} vs {dp:e}");
    }
}

fn random_field(ny: usize, nx: usize, seed: u64) -> Array2<f64> {
    let mut s = seed.wrapping_mul(0x9E3779B97F4A7C15) | 1;
    Array2::from_shape_fn((ny, nx), |_| {
        s ^= s << 13;
        s ^= s >> 7;
        s ^= s << 17;
        (s >> 11) as f64 / (1u64 << 53) as f64 - 0.3
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(24))]
    #[test]
    fn operators_are_symmetric_and_positive(seed in 1u64..10_000, periodic in any::<bool>()) {
        let dom = domain(20, 14, 1e-6, periodic);
        let op: Box<dyn Compliance> = if periodic { Box::new(Periodic::new(dom, E).unwrap()) } else { Box::new(Free::new(dom, E).unwrap()) };
        let (p1, p2) = (random_field(14, 20, seed), random_field(14, 20, seed + 7919));
        let (u1, u2) = (apply(op.as_ref(), &p1), apply(op.as_ref(), &p2));
        let dot = |a: &Array2<f64>, b: &Array2<f64>| a.iter().zip(b.iter()).map(|(x, y)| x * y).sum::<f64>();
        let (a, b) = (dot(&p1, &u2), dot(&p2, &u1));
        prop_assert!((a - b).abs() <= 1e-12 * dot(&p1, &u1).abs().max(dot(&p2, &u2).abs()));
        prop_assert!(dot(&p1, &u1) > 0.0);
        prop_assert!(op.energy(p1.view(), u1.view()) > 0.0);
    }
}

#[test]
fn the_periodic_stiffness_inverts_the_compliance_on_zero_mean_fields() {
    let dom = domain(48, 40, 1e-6, true);
    let (op, stiff) = (
        Periodic::new(dom, E).unwrap(),
        PeriodicStiffness::new(dom, E).unwrap(),
    );
    let mut p = random_field(40, 48, 7);
    let mean = p.mean().unwrap();
    p -= mean;
    let u = apply(&op, &p);
    let mut back = Array2::zeros(p.dim());
    stiff
        .apply(u.view(), back.view_mut(), &mut stiff.make_workspace())
        .unwrap();
    let scale = p.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = (&back - &p).iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(
        err < 1e-12 * scale,
        "stiffness(compliance(p)) - p = {err:e} of {scale:e}"
    );
    // A uniform displacement is a rigid shift: no pressure (beyond round-off of the
    // pressure scale E* u / dx).
    stiff
        .apply(
            Array2::from_elem(p.dim(), 1e-6).view(),
            back.view_mut(),
            &mut stiff.make_workspace(),
        )
        .unwrap();
    assert!(back.iter().all(|v| v.abs() < 1e-12 * E * 1e-6 / 1e-6));
    // `invert` is the compliance on zero-mean fields, whatever the pressure's mean.
    let mut inverted = Array2::zeros(p.dim());
    let shifted = &p + 2.0;
    stiff
        .invert(shifted.view(), inverted.view_mut(), &mut stiff.make_workspace())
        .unwrap();
    let u_scale = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = (&inverted - &u).iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(
        err < 1e-12 * u_scale,
        "invert(p + c) - compliance(p) = {err:e} of {u_scale:e}"
    );
}

#[test]
fn the_free_stiffness_inverts_the_padded_compliance_whose_first_block_is_the_free_one() {
    let dom = domain(24, 20, 1e-6, false);
    let (op, stiff) = (Free::new(dom, E).unwrap(), FreeStiffness::new(dom, E).unwrap());
    assert_eq!(stiff.padded_shape(), (40, 48));
    let mut ws = stiff.make_workspace();
    let p = random_field(20, 24, 3);
    let mut padded = Array2::zeros((40, 48));
    stiff.displacement(p.view(), padded.view_mut(), &mut ws).unwrap();
    // The first block is the free displacement; the padding moves too (a free surface).
    let u = apply(&op, &p);
    let block = padded.slice(ndarray::s![..20, ..24]);
    let scale = u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = (&block - &u).iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(err < 1e-12 * scale, "first block - free = {err:e} of {scale:e}");
    assert!(
        padded
            .slice(ndarray::s![20.., ..])
            .iter()
            .any(|v| v.abs() > 1e-3 * scale)
    );
    // The stiffness gives the pressure back, with none in the padding.
    let mut back = Array2::zeros((40, 48));
    stiff.apply(padded.view(), back.view_mut(), &mut ws).unwrap();
    let p_scale = p.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = Array2::from_shape_fn((40, 48), |(j, i)| {
        let want = if j < 20 && i < 24 { p[(j, i)] } else { 0.0 };
        (back[(j, i)] - want).abs()
    })
    .iter()
    .fold(0.0f64, |m, &v| m.max(v));
    assert!(
        err < 1e-10 * p_scale,
        "stiffness(displacement(p)) - p = {err:e} of {p_scale:e}"
    );
    // Positive definite: a rigid shift of the padded grid is held by a positive pressure.
    stiff
        .apply(Array2::from_elem((40, 48), 1e-9).view(), back.view_mut(), &mut ws)
        .unwrap();
    assert!(back.iter().all(|&v| v > 0.0));
    // `invert` is the stiffness's inverse on the whole padded grid, padding included.
    let q = random_field(40, 48, 4);
    let mut u = Array2::zeros((40, 48));
    stiff.invert(q.view(), u.view_mut(), &mut ws).unwrap();
    stiff.apply(u.view(), back.view_mut(), &mut ws).unwrap();
    let q_scale = q.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = (&back - &q).iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(
        err < 1e-10 * q_scale,
        "stiffness(invert(q)) - q = {err:e} of {q_scale:e}"
    );
    // On a pressure confined to the first block it is `displacement`.
    let mut confined = Array2::zeros((40, 48));
    confined.slice_mut(ndarray::s![..20, ..24]).assign(&p);
    stiff.invert(confined.view(), u.view_mut(), &mut ws).unwrap();
    let scale = padded.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = (&u - &padded).iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(
        err < 1e-12 * scale,
        "invert - displacement = {err:e} of {scale:e}"
    );
}

#[test]
fn results_do_not_depend_on_the_number_of_threads() {
    let p = random_field(70, 90, 5);
    for periodic in [true, false] {
        let run = |threads: usize| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap()
                .install(|| {
                    let dom = domain(90, 70, 1e-6, periodic);
                    let op: Box<dyn Compliance> = if periodic {
                        Box::new(Periodic::new(dom, E).unwrap())
                    } else {
                        Box::new(Free::new(dom, E).unwrap())
                    };
                    apply(op.as_ref(), &p)
                })
        };
        let one = run(1);
        assert_eq!(one, run(2));
        assert_eq!(one, run(3));
    }
}

#[test]
fn a_periodic_workspace_is_about_one_field() {
    let n = 256;
    let op = Periodic::new(domain(n, n, 1e-6, true), E).unwrap();
    let field = n * n * 8;
    let bytes = op.make_workspace().bytes();
    assert!(
        bytes <= 3 * field,
        "{bytes} bytes of workspace for a {field}-byte field"
    );
    assert!(bytes <= field * 11 / 10 + rayon::current_num_threads() * (16 * (n / 2 + 1) * 16 + 3 * n * 16));
}

#[test]
fn a_workspace_is_reused_without_changing_results() {
    let dom = domain(33, 17, 1e-6, false);
    let op = Free::new(dom, E).unwrap();
    let mut ws = op.make_workspace();
    let (p1, p2) = (random_field(17, 33, 1), random_field(17, 33, 2));
    let mut u = Array2::zeros((17, 33));
    op.apply(p1.view(), u.view_mut(), &mut ws).unwrap();
    let first = u.clone();
    op.apply(p2.view(), u.view_mut(), &mut ws).unwrap();
    op.apply(p1.view(), u.view_mut(), &mut ws).unwrap();
    assert_eq!(u, first);
}

#[test]
fn bad_input_is_refused() {
    assert!(Material::new(-1.0, 0.3).is_err());
    assert!(Material::new(1e9, 0.6).is_err());
    assert!(Material::new(1e9, -1.0).is_err());
    assert!(Material::new(f64::NAN, 0.3).is_err());
    let rubber = Material::new(10e6, 0.5).unwrap();
    assert!((composite_modulus(&rubber, &Material::RIGID).unwrap() - 10e6 / 0.75).abs() < 1e-6);
    assert!(composite_modulus(&Material::RIGID, &Material::RIGID).is_err());
    assert!(Periodic::new(domain(8, 8, 1e-6, true), 0.0).is_err());
    assert!(Free::new(domain(8, 8, -1e-6, false), E).is_err());
    let op = Periodic::new(domain(8, 6, 1e-6, true), E).unwrap();
    let mut ws = op.make_workspace();
    let mut u = Array2::zeros((8, 6));
    let err = op
        .apply(Array2::zeros((6, 8)).view(), u.view_mut(), &mut ws)
        .unwrap_err();
    assert!(
        matches!(
            err,
            ElasticError::ShapeMismatch {
                what: "displacement",
                ..
            }
        ),
        "{err}"
    );
}
