//! The exact sphere-on-a-layer solution against its limits: the half-space (Hertz, JKR),
//! Dimitriadis' small-chi series and Winkler's thin bed.

use elastic::{Base, Layer};
use std::f64::consts::PI;
use theory::layer::{self as tl, LayerContact};

const R: f64 = 1e-3;
const E: f64 = 1e6;

fn on(h: f64, nu: f64, base: Base) -> LayerContact<impl Fn(f64) -> f64> {
    let layer = Layer::new(h, nu, base).unwrap();
    LayerContact::new(h, E, move |x| layer.compliance_ratio(x / h, E))
}

#[test]
fn on_a_half_space_it_is_hertz_and_jkr() {
    let body = LayerContact::new(1e-4, E, |_| 1.0);
    let (a, w) = (1e-4, 0.05);
    let s = body.sphere(a, R, w);
    let (p, d) = (
        theory::jkr_dmt::jkr_load(a, R, w, E),
        theory::jkr_dmt::jkr_approach(a, R, w, E),
    );
    assert!((s.load / p - 1.0).abs() < 1e-12, "{s:?} {p}");
    assert!((s.approach / d - 1.0).abs() < 1e-12, "{s:?} {d}");
    let h = body.hertz(1e-5, R);
    let want = theory::hertz::load_of_approach(1e-5, R, E);
    assert!((h.load / want - 1.0).abs() < 1e-12, "{h:?} {want}");
    let off = body.pull_off(R, w);
    assert!((-off.load / (1.5 * PI * R * w) - 1.0).abs() < 1e-10, "{off:?}");
    assert!((body.punch_stiffness(a) / (2.0 * E * a) - 1.0).abs() < 1e-12);
}

#[test]
fn at_small_chi_it_is_dimitriadis_series() {
    for (nu, base, b) in [
        (0.49, Base::Bonded, tl::Base::Bonded),
        (0.3, Base::Bonded, tl::Base::Bonded),
        (0.3, Base::Frictionless, tl::Base::Frictionless),
    ] {
        for chi in [0.02, 0.05, 0.1] {
            let (a, delta) = (1e-4, 1e-8 / R);
            let _ = a;
            let h = (R * delta).sqrt() / chi;
            let got = on(h, nu, base).hertz(delta, R).load;
            let want = tl::dimitriadis_load(delta, R, h, E, nu, b);
            println!("{base:?} nu {nu} chi {chi}: {:.6} of Dimitriadis", got / want);
            assert!((got / want - 1.0).abs() < 2e-3, "{base:?} {nu} {chi}");
        }
    }
}

#[test]
fn a_thin_compressible_layer_is_winklers_bed() {
    // Contact radius a = sqrt(2 R delta) = 20 h.
    let nu = 0.3;
    let a = 1e-4;
    let (h, delta) = (a / 20.0, a * a / (2.0 * R));
    let body = on(h, nu, Base::Bonded);
    let got = body.hertz(delta, R).load;
    let want = tl::winkler_load(delta, R, h, E, nu);
    assert!((got / want - 1.0).abs() < 0.01, "{got} {want}");
    let stiffness = body.punch_stiffness(a);
    let bed = PI * a * a * tl::p_wave_modulus(E, nu) / h;
    assert!((stiffness / bed - 1.0).abs() < 0.15, "{stiffness} {bed}");
}

#[test]
fn past_its_reach_it_gives_no_number() {
    let h = 1e-6;
    let body = on(h, 0.45, Base::Bonded);
    assert!(body.sphere(0.99 * tl::REACH * h, R, 0.0).load.is_finite());
    assert!(body.sphere(1.01 * tl::REACH * h, R, 0.0).load.is_nan());
    assert!(body.punch_stiffness(1.01 * tl::REACH * h).is_nan());
    // A pull-off whose least load lies past the reach: a film 1e-4 of JKR's radius.
    let (w, e_film) = (0.05, E);
    let a_jkr = (9.0 * PI * w * R * R / (8.0 * e_film)).cbrt();
    let thin = on(a_jkr / 1e4, 0.3, Base::Bonded).pull_off(R, w);
    assert!(thin.load.is_nan(), "{thin:?}");
}
