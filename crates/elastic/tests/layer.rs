//! A layer's operators against its compliance: the free grid's real-space coefficients against
//! its 2-D transform, the periodic operator against its modes, a thin layer against Winkler.

use elastic::love::cell_influence;
use elastic::{Base, Body, Compliance, Domain, Free, FreeStiffness, Layer, Periodic, PeriodicStiffness};
use ndarray::Array2;
use std::f64::consts::PI;

const E_STAR: f64 = 1e9;

/// A free square grid of `n`^2 cells `d` \[m\] wide.
fn free_square(n: usize, d: f64) -> Domain {
    Domain {
        nx: n,
        ny: n,
        dx: d,
        dy: d,
        periodic: false,
    }
}

fn apply(op: &dyn Compliance, p: &Array2<f64>) -> Array2<f64> {
    let mut u = Array2::zeros(p.dim());
    op.apply(p.view(), u.view_mut(), &mut op.make_workspace())
        .unwrap();
    u
}

/// The displacement \[m\] at `(x, y)` \[m\] under unit pressure on the cell `|x'| <= a`,
/// `|y'| <= b` of `layer`, less the half-space's, by the inverse Fourier transform of the
/// compliances' difference times the cell's transform, `4ab sinc(qx a) sinc(qy b)`, in polar
/// coordinates: `(1 / 4 pi^2) int dq (2 / E*) (R(q) - 1) int dtheta S(q) cos(q.r)`. `R - 1`
/// decays as `exp(-2 q h)`: cut at `q h = 30`; panels shorter than a quarter period and than
/// `1 / 2h`.
fn correction_by_transform(layer: &Layer, x: f64, y: f64, a: f64, b: f64) -> f64 {
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
    let sinc = |v: f64| if v == 0.0 { 1.0 } else { v.sin() / v };
    let reach = x.abs() + y.abs() + a + b;
    let top = 30.0 / layer.thickness;
    let panels = (top / (0.5 * PI / reach).min(0.5 / layer.thickness)).ceil() as usize;
    let width = top / panels as f64;
    let angles = 4 * ((top * reach) as usize + 64);
    let mut sum = 0.0;
    for k in 0..panels {
        for &(t, w) in &GL {
            let q = (k as f64 + 0.5 + 0.5 * t) * width;
            let ring: f64 = (0..angles)
                .map(|m| {
                    let theta = 2.0 * PI * m as f64 / angles as f64;
                    let (qx, qy) = (q * theta.cos(), q * theta.sin());
                    4.0 * a * b * sinc(qx * a) * sinc(qy * b) * (qx * x + qy * y).cos()
                })
                .sum::<f64>()
                * 2.0
                * PI
                / angles as f64;
            sum += 0.5 * width * w * 2.0 / E_STAR * (layer.compliance_ratio(q, E_STAR) - 1.0) * ring;
        }
    }
    sum / (4.0 * PI * PI)
}

#[test]
fn the_free_layers_coefficients_are_the_transform_of_its_compliance() {
    // A unit impulse on one cell of a free grid: the displacement at other cells is Love's
    // coefficient plus the layer's correction, here from the 2-D transform (the operator
    // uses the Hankel transform and a cell quadrature), on layers half a cell to 8 cells thick.
    let (n, dx, dy) = (48, 1e-6, 1.3e-6);
    let domain = Domain {
        nx: n,
        ny: n,
        dx,
        dy,
        periodic: false,
    };
    let source = (20, 20);
    let mut p = Array2::zeros((n, n));
    p[source] = 1.0;
    // Coatings: on substrates ten times softer and stiffer, the thin ones' cell (20, 45) past
    // 40 thicknesses, in the tail.
    let soft = Base::Substrate {
        e_star: 0.1 * E_STAR,
        poisson: 0.45,
    };
    let stiff = Base::Substrate {
        e_star: 10.0 * E_STAR,
        poisson: 0.3,
    };
    for (h, nu, base) in [
        (0.5, 0.3, Base::Bonded),
        (2.0, 0.3, Base::Bonded),
        (8.0, 0.3, Base::Bonded),
        (2.0, 0.5, Base::Bonded),
        (2.0, 0.0, Base::Frictionless),
        (2.0, 0.3, soft),
        (0.5, 0.3, soft),
        (0.5, 0.45, stiff),
    ] {
        let layer = Layer::new(h * dx, nu, base).unwrap();
        let free = Free::with_body(domain, E_STAR, Body::Layer(layer)).unwrap();
        let u = apply(&free, &p);
        let scale = u[source];
        for (j, i) in [
            (20, 20),
            (20, 21),
            (21, 20),
            (23, 22),
            (26, 17),
            (20, 32),
            (20, 45),
        ] {
            let (x, y) = ((i as f64 - 20.0) * dx, (j as f64 - 20.0) * dy);
            let want = cell_influence(x, y, 0.5 * dx, 0.5 * dy, E_STAR)
                + correction_by_transform(&layer, x, y, 0.5 * dx, 0.5 * dy);
            // A coating's tail beyond 40 thicknesses is fitted (a 1/s^5 term left out): 4e-7
            // on the substrate ten times softer; its table within them 6e-8.
            let within = match base {
                Base::Substrate { .. } => 5e-7,
                _ => 1e-8,
            };
            assert!(
                (u[(j, i)] - want).abs() < within * scale,
                "h {h} cells, nu {nu}, {base:?}, cell ({j}, {i}): {:e} {want:e}",
                u[(j, i)]
            );
        }
        // Far beyond 40 thicknesses a layer on a rigid base has no influence.
        if h < 1.0 && !matches!(base, Base::Substrate { .. }) {
            assert!(u[(20, 45)].abs() < 1e-12 * scale, "{:e}", u[(20, 45)]);
        }
        // The padded stiffness exists (its spectrum is positive).
        FreeStiffness::with_body(domain, E_STAR, Body::Layer(layer)).unwrap();
    }
}

#[test]
fn a_free_coating_on_its_own_material_is_the_half_space_and_a_thin_one_its_substrate() {
    let (n, d) = (32, 1e-6);
    let domain = free_square(n, d);
    let mut p = Array2::zeros((n, n));
    for j in 8..24 {
        for i in 10..20 {
            p[(j, i)] = 1e6 * (1.0 + 0.1 * (i * j) as f64);
        }
    }
    let half = apply(&Free::new(domain, E_STAR).unwrap(), &p);
    let peak = half.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let own = Layer::new(
        2.0 * d,
        0.3,
        Base::Substrate {
            e_star: E_STAR,
            poisson: 0.3,
        },
    )
    .unwrap();
    let u = apply(&Free::with_body(domain, E_STAR, Body::Layer(own)).unwrap(), &p);
    let worst = (&u - &half).iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(worst < 1e-12 * peak, "{worst:e} {peak:e}");
    // A coating a thousandth of a cell thick on a substrate ten times softer: the substrate's
    // half-space plus the coating's own compression, of order h / dx.
    let thin = Layer::new(
        1e-3 * d,
        0.3,
        Base::Substrate {
            e_star: 0.1 * E_STAR,
            poisson: 0.45,
        },
    )
    .unwrap();
    let u = apply(&Free::with_body(domain, E_STAR, Body::Layer(thin)).unwrap(), &p);
    let substrate = apply(&Free::new(domain, 0.1 * E_STAR).unwrap(), &p);
    // The compression: the constant term of the compliance at q -> 0, 2 R'(0) h / E*.
    let h = thin.thickness;
    let slope = (thin.compliance_ratio(1e-5 / h, E_STAR) - 10.0) / 1e-5;
    let own = (&u - &substrate) / (&p.mapv(|v| v.max(1.0)) * (2.0 * slope * h / E_STAR));
    for (j, i) in [(8, 10), (15, 15), (23, 19)] {
        assert!((own[(j, i)] - 1.0).abs() < 1e-2, "({j}, {i}): {}", own[(j, i)]);
    }
}

#[test]
fn the_periodic_layer_scales_each_mode_and_leaves_the_mean_to_its_compliance() {
    let (nx, ny, d) = (48, 40, 1e-6);
    let domain = Domain {
        nx,
        ny,
        dx: d,
        dy: d,
        periodic: true,
    };
    let layer = Layer::new(3e-6, 0.3, Base::Bonded).unwrap();
    let op = Periodic::with_body(domain, E_STAR, Body::Layer(layer)).unwrap();
    let stiffness = PeriodicStiffness::with_body(domain, E_STAR, Body::Layer(layer)).unwrap();
    let (lx, ly) = (nx as f64 * d, ny as f64 * d);
    for (kx, ky) in [(1, 0), (0, 3), (5, 7), (24, 0)] {
        let (qx, qy) = (2.0 * PI * kx as f64 / lx, 2.0 * PI * ky as f64 / ly);
        let phase = |j: usize, i: usize| qx * i as f64 * d + qy * j as f64 * d;
        let p = Array2::from_shape_fn((ny, nx), |(j, i)| 1e5 * phase(j, i).cos());
        let u = apply(&op, &p);
        let amp = 1e5 * layer.compliance(qx.hypot(qy), E_STAR);
        for ((j, i), v) in u.indexed_iter() {
            assert!((v - amp * phase(j, i).cos()).abs() < 1e-12 * amp, "k=({kx},{ky})");
        }
        let mut back = Array2::zeros((ny, nx));
        stiffness
            .apply(u.view(), back.view_mut(), &mut stiffness.make_workspace())
            .unwrap();
        assert!((&back - &p).iter().all(|v| v.abs() < 1e-9 * 1e5), "k=({kx},{ky})");
    }
    // A cell's own compliance is the operator's diagonal, the mean mode's share included.
    let mut impulse = Array2::zeros((ny, nx));
    impulse[(0, 0)] = 1.0;
    let diagonal = apply(&op, &impulse)[(0, 0)] + op.mean_compliance() / (nx * ny) as f64;
    assert!(
        (op.cell_compliance() / diagonal - 1.0).abs() < 1e-12,
        "{} {diagonal}",
        op.cell_compliance()
    );
    assert_eq!(op.mean_compliance(), layer.compliance(0.0, E_STAR));
    assert!(op.mean_compliance() > 0.0);
    let half_space = Periodic::new(domain, E_STAR).unwrap();
    assert_eq!(half_space.mean_compliance(), 0.0);
    let free = Free::with_body(
        Domain {
            periodic: false,
            ..domain
        },
        E_STAR,
        Body::Layer(layer),
    )
    .unwrap();
    assert_eq!(free.mean_compliance(), 0.0);
}

#[test]
fn a_thin_layer_under_a_wide_load_is_winklers_foundation() {
    // A uniform square load 40 cells wide on a layer a tenth of a cell thick: inside, the
    // surface sinks by h / M times the pressure, as a bed of springs; outside, not at all.
    let (n, d, h, nu) = (64, 1e-6, 1e-7, 0.3);
    let layer = Layer::new(h, nu, Base::Bonded).unwrap();
    let domain = free_square(n, d);
    let free = Free::with_body(domain, E_STAR, Body::Layer(layer)).unwrap();
    let p = Array2::from_shape_fn((n, n), |(j, i)| {
        if (12..52).contains(&j) && (12..52).contains(&i) {
            1e6
        } else {
            0.0
        }
    });
    let u = apply(&free, &p);
    let winkler = 1e6 * layer.compliance(0.0, E_STAR);
    // Love's coefficients and the layer's correction are each ~20 times the sum here.
    assert!(
        (u[(32, 32)] / winkler - 1.0).abs() < 1e-7,
        "{} {winkler}",
        u[(32, 32)]
    );
    assert!(u[(32, 5)].abs() < 1e-9 * winkler, "{}", u[(32, 5)]);
}

#[test]
fn a_layer_far_thinner_than_a_cell_is_winklers_bed_cell_by_cell() {
    // A hundredth of a cell thick: each cell sinks by h / M under its own pressure alone.
    let (n, d) = (16, 1e-6);
    let domain = free_square(n, d);
    let mut p = Array2::zeros((n, n));
    p[(8, 8)] = 1e6;
    let layer = Layer::new(d / 100.0, 0.3, Base::Bonded).unwrap();
    let u = apply(&Free::with_body(domain, E_STAR, Body::Layer(layer)).unwrap(), &p);
    let own = 1e6 * layer.compliance(0.0, E_STAR);
    assert!((u[(8, 8)] / own - 1.0).abs() < 1e-12, "{} {own}", u[(8, 8)]);
    assert!(
        u.indexed_iter()
            .all(|((j, i), v)| (j, i) == (8, 8) || v.abs() < 1e-12 * own)
    );
}

#[test]
fn a_body_at_another_modulus_is_the_operator_built_there() {
    // Rescaled operators (a viscoelastic step's) against ones built at the new modulus:
    // the half-space, a bonded layer and a coating (its substrate scaled alike), both grids.
    let p = Array2::from_shape_fn((16, 16), |(j, i)| ((i * 7 + j * 3) % 5) as f64 * 1e5);
    let coating = |substrate: f64| {
        Body::Layer(
            Layer::new(
                2e-6,
                0.3,
                Base::Substrate {
                    e_star: substrate,
                    poisson: 0.25,
                },
            )
            .unwrap(),
        )
    };
    let layer = Body::Layer(Layer::new(2e-6, 0.45, Base::Bonded).unwrap());
    // Each body at E* = 1 GPa and as built at 2.5 GPa.
    let bodies = [
        (Body::HalfSpace, Body::HalfSpace),
        (layer, layer),
        (coating(4e9), coating(1e10)),
    ];
    for periodic in [true, false] {
        let domain = Domain {
            periodic,
            ..free_square(16, 1e-6)
        };
        for (body, at_new_modulus) in bodies {
            let build = |e: f64, body: Body| -> Box<dyn Compliance> {
                if periodic {
                    Box::new(Periodic::with_body(domain, e, body).unwrap())
                } else {
                    Box::new(Free::with_body(domain, e, body).unwrap())
                }
            };
            let scaled = build(1e9, body).with_modulus(2.5e9).unwrap();
            let fresh = build(2.5e9, at_new_modulus);
            let (a, b) = (apply(scaled.as_ref(), &p), apply(fresh.as_ref(), &p));
            let worst = (&a - &b).iter().fold(0.0f64, |m, d| m.max(d.abs()));
            let top = b.iter().fold(0.0f64, |m, d| m.max(d.abs()));
            assert!(
                worst <= 1e-12 * top,
                "{body:?} periodic {periodic}: {worst} of {top}"
            );
            assert_eq!(scaled.e_star(), 2.5e9);
            assert!((scaled.cell_compliance() / fresh.cell_compliance() - 1.0).abs() < 1e-12);
            assert!(
                (scaled.mean_compliance() - fresh.mean_compliance()).abs()
                    <= 1e-12 * fresh.mean_compliance().abs()
            );
        }
    }
}
