//! The tangential (Cerruti) compliance against closed forms: single Fourier modes on periodic
//! grids, Johnson's uniform displacement under an elliptical shear on free grids, symmetry,
//! the two grids against each other on a local load; the normal-tangential coupling against
//! single modes, Hertz's pressure and reciprocity.

use elastic::{Domain, Shear};
use ndarray::Array2;
use std::f64::consts::PI;

const G: f64 = 1e9;

fn domain(n: usize, periodic: bool) -> Domain {
    Domain {
        nx: n,
        ny: n,
        dx: 1e-6,
        dy: 1e-6,
        periodic,
    }
}

fn apply(op: &Shear, tx: &Array2<f64>, ty: &Array2<f64>) -> (Array2<f64>, Array2<f64>) {
    let shape = tx.dim();
    let (mut ux, mut uy) = (Array2::zeros(shape), Array2::zeros(shape));
    let mut ws = op.make_workspace();
    op.apply([tx.view(), ty.view()], [ux.view_mut(), uy.view_mut()], &mut ws)
        .unwrap();
    (ux, uy)
}

/// A shear `cos(qx x + qy y)` along x displaces by `(1 - nu qx^2/q^2)/(G q)` along x and
/// `-nu qx qy / (G q^3)` along y, times the same cosine.
#[test]
fn periodic_modes_match_cerruti() {
    let (n, nu) = (64, 0.3);
    let d = domain(n, true);
    let op = Shear::new(d, G, nu).unwrap();
    let l = n as f64 * d.dx;
    for (mx, my) in [(3i32, 0i32), (0, 5), (4, 4), (2, -6)] {
        let (qx, qy) = (2.0 * PI * mx as f64 / l, 2.0 * PI * my as f64 / l);
        let q = qx.hypot(qy);
        let wave = Array2::from_shape_fn((n, n), |(j, i)| {
            (qx * i as f64 * d.dx + qy * j as f64 * d.dy).cos()
        });
        let (ux, uy) = apply(&op, &wave, &Array2::zeros((n, n)));
        let (cx, cy) = (
            (1.0 - nu * qx * qx / (q * q)) / (G * q),
            -nu * qx * qy / (G * q * q * q),
        );
        let scale = 1.0 / (G * q);
        for ((u, v), w) in ux.iter().zip(&uy).zip(&wave) {
            assert!((u - cx * w).abs() < 1e-12 * scale, "mode ({mx}, {my}) x");
            assert!((v - cy * w).abs() < 1e-12 * scale, "mode ({mx}, {my}) y");
        }
        // A shear along y gives the mirror image.
        let (vx, vy) = apply(&op, &Array2::zeros((n, n)), &wave);
        let cyy = (1.0 - nu * qy * qy / (q * q)) / (G * q);
        for ((u, v), w) in vx.iter().zip(&vy).zip(&wave) {
            assert!((u - cy * w).abs() < 1e-12 * scale && (v - cyy * w).abs() < 1e-12 * scale);
        }
    }
}

/// Johnson (1985, Eq. 3.95): the shear `q0 sqrt(1 - r^2/a^2)` along x on a circle of radius
/// `a` displaces the surface inside it by `u_x = pi q0 / (32 G a) [4 (2 - nu) a^2 - (4 - 3 nu)
/// x^2 - (4 - nu) y^2]`, `u_y = pi q0 nu x y / (16 G a)`.
#[test]
fn free_elliptical_shear_matches_johnson() {
    let (n, nu, radius) = (128, 0.3, 32.0);
    let d = domain(n, false);
    let op = Shear::new(d, G, nu).unwrap();
    let centre = n as f64 / 2.0 - 0.5;
    let q0 = 1e6;
    let a = radius * d.dx;
    let xy = |j: usize, i: usize| ((i as f64 - centre) * d.dx, (j as f64 - centre) * d.dy);
    let tx = Array2::from_shape_fn((n, n), |(j, i)| {
        let (x, y) = xy(j, i);
        q0 * (1.0 - (x * x + y * y) / (a * a)).max(0.0).sqrt()
    });
    let (ux, uy) = apply(&op, &tx, &Array2::zeros((n, n)));
    let scale = PI * q0 / (32.0 * G * a);
    let centre_value = scale * 4.0 * (2.0 - nu) * a * a;
    let (mut worst, mut worst_y): (f64, f64) = (0.0, 0.0);
    for j in 0..n {
        for i in 0..n {
            let (x, y) = xy(j, i);
            if x.hypot(y) < 0.8 * a {
                let exact_x =
                    scale * (4.0 * (2.0 - nu) * a * a - (4.0 - 3.0 * nu) * x * x - (4.0 - nu) * y * y);
                let exact_y = scale * 2.0 * nu * x * y;
                worst = worst.max((ux[(j, i)] - exact_x).abs() / centre_value);
                worst_y = worst_y.max((uy[(j, i)] - exact_y).abs() / centre_value);
            }
        }
    }
    assert!(
        worst < 2e-3 && worst_y < 2e-3,
        "worst errors {worst:e}, {worst_y:e} of the centre's"
    );
}

/// The operator is symmetric (reciprocity) on both grids, and its diagonal is the cell
/// compliance.
#[test]
fn reciprocity_and_diagonal() {
    for periodic in [true, false] {
        let n = 32;
        let op = Shear::new(domain(n, periodic), G, 0.25).unwrap();
        let field = |seed: u64| {
            Array2::from_shape_fn((n, n), |(j, i)| {
                let k = (j * n + i) as u64 * 2654435761 + seed;
                ((k % 1000) as f64 / 500.0) - 1.0
            })
        };
        let (a, b, c, e) = (field(1), field(7), field(13), field(29));
        let (u1, v1) = apply(&op, &a, &b);
        let (u2, v2) = apply(&op, &c, &e);
        let dot = |x: &Array2<f64>, y: &Array2<f64>| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>();
        let (left, right) = (dot(&c, &u1) + dot(&e, &v1), dot(&a, &u2) + dot(&b, &v2));
        assert!(
            (left - right).abs() < 1e-12 * left.abs().max(right.abs()),
            "{periodic}: {left} {right}"
        );
        if !periodic {
            let mut unit = Array2::zeros((n, n));
            unit[(n / 2, n / 3)] = 1.0;
            let (ux, _) = apply(&op, &unit, &Array2::zeros((n, n)));
            let (_, vy) = apply(&op, &Array2::zeros((n, n)), &unit);
            let [cx, cy] = op.cell_compliance();
            assert!((ux[(n / 2, n / 3)] - cx).abs() < 1e-12 * cx);
            assert!((vy[(n / 2, n / 3)] - cy).abs() < 1e-12 * cy);
        }
    }
}

/// A local shear on a large periodic grid displaces the cells near it as on a free grid, less
/// the periodic images' nearly uniform share: the coupling's sign and size agree.
#[test]
fn periodic_and_free_agree_near_a_local_load() {
    let (n, nu) = (256, 0.4);
    let (free, periodic) = (
        Shear::new(domain(n, false), G, nu).unwrap(),
        Shear::new(domain(n, true), G, nu).unwrap(),
    );
    let mut tx = Array2::zeros((n, n));
    for j in 126..130 {
        for i in 126..130 {
            tx[(j, i)] = 1e6;
        }
    }
    let ty = Array2::zeros((n, n));
    let (fx, fy) = apply(&free, &tx, &ty);
    let (px, py) = apply(&periodic, &tx, &ty);
    // The coupling is odd: positive ahead of the load on one diagonal, as Cerruti's x y / r^3.
    assert!(fy[(134, 134)] > 0.0 && fy[(134, 122)] < 0.0);
    let peak = fy.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let offset = fx[(128, 128)] - px[(128, 128)];
    // The periodic multiplier is the point kernel's, the free one the cell-integrated: they
    // differ next to the load, and agree a few cells away.
    let (mut worst_x, mut worst_y): (f64, f64) = (0.0, 0.0);
    for j in 112..144usize {
        for i in 112..144usize {
            if j.abs_diff(128).max(i.abs_diff(128)) >= 8 {
                worst_y = worst_y.max((fy[(j, i)] - py[(j, i)]).abs() / peak);
                worst_x = worst_x.max((fx[(j, i)] - px[(j, i)] - offset).abs() / fx[(128, 128)]);
            }
        }
    }
    // (The images a box away tilt u_x across the window by about 1 %: measured 1.2e-2 and
    // 2.0e-3 on this grid.)
    assert!(worst_x < 2e-2 && worst_y < 5e-3, "{worst_x:e} {worst_y:e}");
}

fn coupled_tangential(op: &Shear, p: &Array2<f64>) -> (Array2<f64>, Array2<f64>) {
    let shape = p.dim();
    let (mut ux, mut uy) = (Array2::zeros(shape), Array2::zeros(shape));
    let mut ws = op.make_workspace();
    op.coupled_tangential(p.view(), [ux.view_mut(), uy.view_mut()], &mut ws)
        .unwrap();
    (ux, uy)
}

fn coupled_normal(op: &Shear, tx: &Array2<f64>, ty: &Array2<f64>) -> Array2<f64> {
    let mut uz = Array2::zeros(tx.dim());
    let mut ws = op.make_workspace();
    op.coupled_normal([tx.view(), ty.view()], uz.view_mut(), &mut ws)
        .unwrap();
    uz
}

/// A pressure `cos(q . x)` moves the surface by `-(1 - 2 nu) q_c / (2 G q^2) sin(q . x)` along
/// each axis (inwards, towards its crests); a shear `cos(q . x)` along an axis moves it into
/// the body by `(1 - 2 nu) q_c / (2 G q^2) sin(q . x)`. Nothing at `nu = 1/2`.
#[test]
fn periodic_coupling_modes_match_the_closed_form() {
    let n = 64;
    let d = domain(n, true);
    let l = n as f64 * d.dx;
    for nu in [0.0, 0.3] {
        let op = Shear::new(d, G, nu).unwrap();
        assert!(op.coupled());
        for (mx, my) in [(3i32, 0i32), (0, 5), (4, 4), (2, -6)] {
            let (qx, qy) = (2.0 * PI * mx as f64 / l, 2.0 * PI * my as f64 / l);
            let q2 = qx * qx + qy * qy;
            let phase = |j: usize, i: usize| qx * i as f64 * d.dx + qy * j as f64 * d.dy;
            let wave = Array2::from_shape_fn((n, n), |(j, i)| phase(j, i).cos());
            let sine = Array2::from_shape_fn((n, n), |(j, i)| phase(j, i).sin());
            let c = (1.0 - 2.0 * nu) / (2.0 * G * q2);
            let tol = 1e-12 / (G * q2.sqrt());
            let (ux, uy) = coupled_tangential(&op, &wave);
            let uz_x = coupled_normal(&op, &wave, &Array2::zeros((n, n)));
            let uz_y = coupled_normal(&op, &Array2::zeros((n, n)), &wave);
            for k in 0..n * n {
                let (j, i) = (k / n, k % n);
                let s = sine[(j, i)];
                assert!(
                    (ux[(j, i)] + c * qx * s).abs() < tol,
                    "nu {nu} mode ({mx}, {my}) u_x"
                );
                assert!(
                    (uy[(j, i)] + c * qy * s).abs() < tol,
                    "nu {nu} mode ({mx}, {my}) u_y"
                );
                assert!(
                    (uz_x[(j, i)] - c * qx * s).abs() < tol,
                    "nu {nu} mode ({mx}, {my}) u_z"
                );
                assert!(
                    (uz_y[(j, i)] - c * qy * s).abs() < tol,
                    "nu {nu} mode ({mx}, {my}) u_z"
                );
            }
        }
    }
    let incompressible = Shear::new(d, G, 0.5).unwrap();
    assert!(!incompressible.coupled());
    let (ux, _) = coupled_tangential(&incompressible, &Array2::ones((n, n)));
    assert!(ux.iter().all(|&v| v == 0.0));
}

/// Johnson (1985, Eq. 3.41a): Hertz's pressure `p0 sqrt(1 - r^2/a^2)` moves the surface
/// radially by `-(1 - 2 nu) a^2 p0 / (6 G r) [1 - (1 - r^2/a^2)^(3/2)]` inside the circle and
/// `-(1 - 2 nu) a^2 p0 / (6 G r)` outside. The worst cell is at the circle's edge, where the
/// pressure's slope is infinite; its error converges with the grid.
#[test]
fn free_coupling_under_hertz_pressure_matches_johnson() {
    let worst = |n: usize| {
        let (nu, radius) = (0.3, n as f64 / 4.0);
        let d = domain(n, false);
        let op = Shear::new(d, G, nu).unwrap();
        let centre = n as f64 / 2.0 - 0.5;
        let (p0, a) = (1e6, radius * d.dx);
        let xy = |j: usize, i: usize| ((i as f64 - centre) * d.dx, (j as f64 - centre) * d.dy);
        let p = Array2::from_shape_fn((n, n), |(j, i)| {
            let (x, y) = xy(j, i);
            p0 * (1.0 - (x * x + y * y) / (a * a)).max(0.0).sqrt()
        });
        let (ux, uy) = coupled_tangential(&op, &p);
        let edge = (1.0 - 2.0 * nu) * a * p0 / (6.0 * G);
        let mut worst: f64 = 0.0;
        for j in 0..n {
            for i in 0..n {
                let (x, y) = xy(j, i);
                let r = x.hypot(y);
                let inner = (1.0 - r * r / (a * a)).max(0.0);
                let ur = -(1.0 - 2.0 * nu) * a * a * p0 / (6.0 * G * r) * (1.0 - inner.powf(1.5));
                worst = worst
                    .max((ux[(j, i)] - ur * x / r).abs() / edge)
                    .max((uy[(j, i)] - ur * y / r).abs() / edge);
            }
        }
        worst
    };
    // Measured: 6.3e-3 at 16 cells a radius, 2.6e-3 at 32, 9.0e-4 at 64.
    let (coarse, fine) = (worst(64), worst(128));
    assert!(
        fine < 3e-3 && fine < 0.5 * coarse,
        "worst errors {coarse:e}, {fine:e} of the edge's displacement"
    );
}

/// Betti's reciprocity across the coupling: the shear's work on the pressure's tangential
/// displacement equals the pressure's work on the shear's normal displacement, on both grids.
#[test]
fn coupling_is_reciprocal() {
    for periodic in [true, false] {
        let n = 32;
        let op = Shear::new(domain(n, periodic), G, 0.2).unwrap();
        let field = |seed: u64| {
            Array2::from_shape_fn((n, n), |(j, i)| {
                let k = (j * n + i) as u64 * 2654435761 + seed;
                ((k % 1000) as f64 / 500.0) - 1.0
            })
        };
        let (p, tx, ty) = (field(3), field(11), field(17));
        let (ux, uy) = coupled_tangential(&op, &p);
        let uz = coupled_normal(&op, &tx, &ty);
        let dot = |x: &Array2<f64>, y: &Array2<f64>| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
        let (left, right) = (dot(&tx, &ux) + dot(&ty, &uy), dot(&p, &uz));
        assert!(
            (left - right).abs() < 1e-12 * left.abs().max(right.abs()) && left.abs() > 0.0,
            "{periodic}: {left} {right}"
        );
    }
}

/// A layer on a rigid base: a uniform shear moves a bonded layer by `h / G` (and a
/// frictionless one is refused nothing: its mean is left out, as the half-space's); a layer
/// thicker than the box shears as the half-space; a bonded incompressible layer still couples,
/// reciprocally; a coating on its own material is the half-space; free grids are refused by
/// name.
#[test]
fn layers_shear_as_films_and_thick_ones_as_the_half_space() {
    use elastic::{Base, Body, Layer};
    let (n, nu, h) = (32, 0.3, 2e-6);
    let d = domain(n, true);
    let bonded = Shear::with_body(d, G, nu, Body::Layer(Layer::new(h, nu, Base::Bonded).unwrap())).unwrap();
    let uniform = Array2::from_elem((n, n), 1e6);
    let (ux, uy) = apply(&bonded, &uniform, &Array2::zeros((n, n)));
    assert!(
        ux.iter().all(|u| (u - 1e6 * h / G).abs() < 1e-12 * 1e6 * h / G)
            && uy.iter().all(|v| v.abs() < 1e-20)
    );
    let thick = Layer::new(1.0, nu, Base::Frictionless).unwrap();
    let (a, b) = (
        Shear::with_body(d, G, nu, Body::Layer(thick)).unwrap(),
        Shear::new(d, G, nu).unwrap(),
    );
    let field = |seed: u64| {
        Array2::from_shape_fn((n, n), |(j, i)| {
            let k = (j * n + i) as u64 * 2654435761 + seed;
            ((k % 1000) as f64 / 500.0) - 1.0
        })
    };
    let (tx, ty, p) = (field(5), field(9), field(21));
    let ((ax, ay), (bx, by)) = (apply(&a, &tx, &ty), apply(&b, &tx, &ty));
    let scale = bx.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    for (u, v) in ax.iter().chain(&ay).zip(bx.iter().chain(&by)) {
        assert!((u - v).abs() < 1e-12 * scale);
    }
    let incompressible =
        Shear::with_body(d, G, 0.5, Body::Layer(Layer::new(h, 0.5, Base::Bonded).unwrap())).unwrap();
    assert!(incompressible.coupled());
    let (ux, uy) = coupled_tangential(&incompressible, &p);
    let uz = coupled_normal(&incompressible, &tx, &ty);
    let dot = |x: &Array2<f64>, y: &Array2<f64>| x.iter().zip(y).map(|(a, b)| a * b).sum::<f64>();
    let (left, right) = (dot(&tx, &ux) + dot(&ty, &uy), dot(&p, &uz));
    assert!(
        (left - right).abs() < 1e-12 * left.abs() && left.abs() > 0.0,
        "{left} {right}"
    );
    let free = Shear::with_body(
        domain(n, false),
        G,
        nu,
        Body::Layer(Layer::new(h, nu, Base::Bonded).unwrap()),
    );
    assert!(free.is_err_and(|e| e.to_string().contains("periodic grids only")));
    // A coating on its own material is the half-space.
    let coating = Layer::new(
        h,
        nu,
        Base::Substrate {
            e_star: 2.0 * G / (1.0 - nu),
            poisson: nu,
        },
    )
    .unwrap();
    let same = Shear::with_body(d, G, nu, Body::Layer(coating)).unwrap();
    let ((cx, cy), (bx, by)) = (apply(&same, &tx, &ty), apply(&b, &tx, &ty));
    for (u, v) in cx.iter().chain(&cy).zip(bx.iter().chain(&by)) {
        assert!((u - v).abs() < 1e-12 * scale);
    }
}
