//! The effective adhesion of a receding edge on a viscoelastic solid against direct
//! quadratures of the models' integrals, their limits, and the retracting sphere against JKR.

use std::f64::consts::PI;
use theory::rate_adhesion::{EdgeLaw, Maxwell, Model, retraction};

const E: f64 = 1e9;
const Z0: f64 = 1e-9;
const R: f64 = 1e-6;

fn solid() -> Maxwell {
    // Two branches, E0 = 10 E_inf.
    Maxwell::new(E, &[3e9, 6e9], &[0.1, 2.0]).unwrap()
}

/// w0 of Tabor parameter 3, and the Lennard-Jones peak stress.
fn adhesion() -> (f64, f64) {
    let w0 = (27.0 * Z0.powi(3) * E * E / R).sqrt();
    (w0, 16.0 * w0 / (9.0 * 3f64.sqrt() * Z0))
}

#[test]
fn slow_edges_need_w0_and_fast_ones_e0_over_e_inf_times_it() {
    let (w0, sigma0) = adhesion();
    for model in [Model::GreenwoodJohnson, Model::PerssonBrener] {
        let law = EdgeLaw::new(model, &solid(), w0, sigma0);
        assert!((law.limit - 10.0).abs() < 1e-12);
        let slow = law.ratio(1e-20);
        let fast = law.ratio(1e6);
        assert!(slow > 1.0 && slow - 1.0 < 1e-6, "{model:?}: {slow}");
        assert!((fast / 10.0 - 1.0).abs() < 1e-3, "{model:?}: {fast}");
        // Rising, and the speed its inverse.
        let mut last = 1.0;
        for k in -12..=3 {
            let v = 10f64.powi(k);
            let r = law.ratio(v);
            assert!(r >= last, "{model:?} at {v}: {r} after {last}");
            last = r;
            if r > 1.0 + 1e-9 && r < 9.99 {
                let back = law.speed(r).unwrap();
                assert!((back / v - 1.0).abs() < 1e-6, "{model:?}: {back} for {v}");
            }
        }
        assert_eq!(law.speed(1.0), Some(0.0));
        assert_eq!(law.speed(10.0), None);
    }
}

#[test]
fn persson_brener_against_its_integral_over_frequency() {
    // The ratio at v solves 1/ratio = 1 - (2/pi) E_inf int_0^{2 pi v / a} |Im 1/E(w)|
    // sqrt(1 - (w a / 2 pi v)^2) dw / w with a = E_inf G / (pi sigma0^2): evaluate the integral
    // with the complex modulus directly (midpoint rule in w = W sin(theta)).
    let (w0, sigma0) = adhesion();
    let solid = solid();
    let law = EdgeLaw::new(Model::PerssonBrener, &solid, w0, sigma0);
    for v in [1e-10, 1e-8, 1e-7, 1e-6] {
        let ratio = law.ratio(v);
        let a = E * ratio * w0 / (PI * sigma0 * sigma0);
        let top = 2.0 * PI * v / a;
        let loss = |w: f64| {
            // 1/E(w) for E(w) = E_inf + sum E_k i w tau / (1 + i w tau).
            let (mut re, mut im) = (E, 0.0);
            for &(e, tau) in &solid.branches {
                let x = w * tau;
                re += e * x * x / (1.0 + x * x);
                im += e * x / (1.0 + x * x);
            }
            im / (re * re + im * im)
        };
        let n = 200_000;
        let mut sum = 0.0;
        for i in 0..n {
            // w = top sin(theta): sqrt(1 - (w/top)^2) dw / w = cos^2(theta) / sin(theta) d theta.
            let theta = (i as f64 + 0.5) / n as f64 * PI / 2.0;
            let (s, c) = theta.sin_cos();
            sum += loss(top * s) * c * c / s;
        }
        let integral = sum * PI / 2.0 / n as f64;
        let direct = 1.0 / (1.0 - 2.0 / PI * E * integral);
        assert!(
            (direct / ratio - 1.0).abs() < 1e-5,
            "v {v}: {direct} against {ratio}"
        );
    }
}

#[test]
fn greenwood_johnson_against_the_averaged_creep_compliance() {
    // w0 / G = E_inf int_0^1 J(T (1 - xi)) artanh(sqrt xi) d xi, T = pi E_inf G / (4 sigma0^2 v):
    // midpoint rule in xi = 1 - u^2 (the weight's log at xi = 1 becomes u log u).
    let (w0, sigma0) = adhesion();
    let solid = solid();
    let law = EdgeLaw::new(Model::GreenwoodJohnson, &solid, w0, sigma0);
    for v in [1e-10, 1e-9, 1e-8, 1e-7] {
        let ratio = law.ratio(v);
        let transit = PI * E * ratio * w0 / (4.0 * sigma0 * sigma0) / v;
        let n = 400_000;
        let mut sum = 0.0;
        for i in 0..n {
            let u = (i as f64 + 0.5) / n as f64;
            let xi: f64 = 1.0 - u * u;
            sum += solid.creep(transit * u * u) * xi.sqrt().atanh() * 2.0 * u;
        }
        let direct = 1.0 / (E * sum / n as f64);
        assert!(
            (direct / ratio - 1.0).abs() < 2e-5,
            "v {v}: {direct} against {ratio}"
        );
    }
}

#[test]
fn a_sphere_drawn_back_slowly_pulls_off_as_jkr() {
    let (w0, sigma0) = adhesion();
    let jkr = -1.5 * PI * R * w0;
    // No branches: the edge holds until G = w0 and follows JKR's equilibrium.
    let elastic = Maxwell::new(E, &[], &[]).unwrap();
    let law = EdgeLaw::new(Model::GreenwoodJohnson, &elastic, w0, sigma0);
    let p = retraction(&law, E, R, w0, Z0, 1e-9, 4000).unwrap();
    assert!((p.pull_off / jkr - 1.0).abs() < 1e-4, "{:?}", p);
    // JKR's pull-off radius (9 pi w0 R^2 / (8 E*))^(1/3), approach -a^2/(3R).
    let a = (9.0 * PI * w0 * R * R / (8.0 * E)).cbrt();
    assert!((p.radius / a - 1.0).abs() < 1e-2, "{} against {a}", p.radius);
    for model in [Model::GreenwoodJohnson, Model::PerssonBrener] {
        let law = EdgeLaw::new(model, &solid(), w0, sigma0);
        let slow = retraction(&law, E, R, w0, Z0, 1e-18, 4000).unwrap();
        assert!((slow.pull_off / jkr - 1.0).abs() < 1e-3, "{model:?}: {slow:?}");
        // Faster pulls harder, up to the fast edge's E0 / E_inf times JKR's work.
        let mut last = slow.pull_off;
        for v in [1e-11, 1e-10, 1e-9, 1e-8, 1e-7] {
            let p = retraction(&law, E, R, w0, Z0, v, 4000).unwrap().pull_off;
            assert!(p < last, "{model:?} at {v}: {p} after {last}");
            last = p;
            let coarse = retraction(&law, E, R, w0, Z0, v, 2000).unwrap().pull_off;
            assert!(
                (coarse / p - 1.0).abs() < 2e-3,
                "{model:?} at {v}: {coarse} against {p}"
            );
        }
    }
    assert!(retraction(&law, E, R, w0, -1.0, 1e-9, 100).is_none());
}
