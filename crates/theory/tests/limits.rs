//! Reference models against their limits and each other.

use theory::jkr_dmt::*;
use theory::maugis::MaugisDugdale;
use theory::rough::*;
use theory::*;

#[test]
fn maugis_dugdale_tends_to_dmt_and_jkr() {
    let dmt = MaugisDugdale::new(1e-4);
    assert!(
        (dmt.pull_off_load_control() + 2.0).abs() < 1e-3,
        "{}",
        dmt.pull_off_load_control()
    );
    let jkr = MaugisDugdale::new(1e4);
    assert!(
        (jkr.pull_off_load_control() + 1.5).abs() < 1e-3,
        "{}",
        jkr.pull_off_load_control()
    );
    assert!(
        (jkr.pull_off_displacement_control() + 5.0 / 6.0).abs() < 1e-3,
        "{}",
        jkr.pull_off_displacement_control()
    );
    // Monotone transition in between.
    let mut last = -2.0;
    for l in [0.1, 0.3, 1.0, 3.0, 10.0] {
        let p = MaugisDugdale::new(l).pull_off_load_control();
        assert!(p > last && p < -1.5, "lambda {l}: {p}");
        last = p;
    }
}

#[test]
fn the_limits_are_approached_at_the_expected_rate() {
    for (l, target) in [(1e-6, -2.0), (1e-7, -2.0), (1e6, -1.5), (1e7, -1.5)] {
        let p = MaugisDugdale::new(l).pull_off_load_control();
        println!("lambda {l:e}: pull-off {p:.9}");
        assert!((p - target).abs() < 1e-6, "lambda {l}: {p}");
    }
    let fixed_grips = MaugisDugdale::new(1e7).pull_off_displacement_control();
    assert!((fixed_grips + 5.0 / 6.0).abs() < 1e-6, "{fixed_grips}");
    // DMT's side has no fold: separation is continuous, under fixed grips as under load.
    let dmt = MaugisDugdale::new(1e-7);
    assert!(!dmt.has_fold());
    assert_eq!(dmt.pull_off_displacement_control(), dmt.pull_off_load_control());
}

#[test]
fn the_displacement_control_fold_appears_near_lambda_0_94() {
    // Below the fold's appearance the approach falls until the contact vanishes; above, it
    // turns first, at a load well above the load-control pull-off.
    for (l, fold) in [
        (0.3, false),
        (0.9, false),
        (0.93, false),
        (0.95, true),
        (1.0, true),
        (5.0, true),
    ] {
        let m = MaugisDugdale::new(l);
        assert_eq!(m.has_fold(), fold, "lambda {l}");
        let (lc, dc) = (m.pull_off_load_control(), m.pull_off_displacement_control());
        if fold {
            assert!(dc > lc + 0.5, "lambda {l}: {dc} vs {lc}");
        } else {
            assert_eq!(dc, lc, "lambda {l}");
        }
    }
}

#[test]
fn hertz_jkr_and_dmt_relations() {
    let (r, w0, e) = (1e-4, 0.05, 1e9);
    let a = 1e-6;
    assert!(
        (theory::hertz::radius_of_load(theory::hertz::load_of_radius(a, r, e), r, e) / a - 1.0).abs() < 1e-14
    );
    let d = theory::hertz::approach_of_radius(a, r);
    assert!(
        (theory::hertz::load_of_approach(d, r, e) / theory::hertz::load_of_radius(a, r, e) - 1.0).abs()
            < 1e-14
    );
    // JKR load minimum over a is -1.5 pi R w0.
    let min = (1..200000)
        .map(|k| jkr_load(k as f64 * 1e-11, r, w0, e))
        .fold(f64::INFINITY, f64::min);
    assert!(
        (min / jkr_pull_off_load_control(r, w0) - 1.0).abs() < 1e-6,
        "{min}"
    );
    assert!((dmt_pull_off(r, w0) / (-2.0 * std::f64::consts::PI * r * w0) - 1.0).abs() < 1e-15);
    assert!((dmt_load(0.0, r, w0, e) - dmt_pull_off(r, w0)).abs() < 1e-20);
    // The zero-load radius is the root of the JKR load (whose scale is pi R w0).
    let a0 = jkr_zero_load_radius(r, w0, e);
    assert!(jkr_load(a0, r, w0, e).abs() < 1e-12 * std::f64::consts::PI * r * w0);
    assert!(jkr_load(0.99 * a0, r, w0, e) < 0.0 && jkr_load(1.01 * a0, r, w0, e) > 0.0);
}

#[test]
fn tabor_to_maugis_is_1_157() {
    assert!(
        (maugis_parameter_of_tabor(1.0) - 1.157).abs() < 1e-3,
        "{}",
        maugis_parameter_of_tabor(1.0)
    );
    // The paper's Fig. 11 materials: R = 100 um, E* = 50 GPa, z0 = 0.3 nm, w0 = 0.075 J/m^2: mu ~ 2.
    let mu = tabor_parameter(1e-4, 0.075, 50e9, 0.3e-9);
    assert!((mu - 2.0).abs() < 0.1, "{mu}");
}

#[test]
fn rough_contact_areas() {
    // Persson's slope sqrt(8/pi), Müser's slope k, both saturating at 1.
    let eps = 1e-6;
    assert!((persson_area(eps) / eps - (8.0 / std::f64::consts::PI).sqrt()).abs() < 1e-6);
    assert!((muser_area(eps, 2.0) / eps - 2.0).abs() < 1e-6);
    assert!((muser_area(1e-3, 2.0) / 1e-3 - 2.0).abs() < 1e-5);
    assert!((muser_area(100.0, 2.0) - 1.0).abs() < 1e-4);
    assert!((persson_area(100.0) - 1.0).abs() < 1e-15);
    let mut last = 0.0;
    for k in 1..400 {
        let a = muser_area(k as f64 * 0.01, 2.0);
        assert!(a > last && a <= 1.0);
        last = a;
    }
    assert!((erf(0.5) - 0.5204998778130465).abs() < 1e-15);
    assert!((erf(3.0) - 0.9999779095030014).abs() < 1e-15);
    assert!(ciavarella_sticky(1e-9, 50e9, 1e-5, 0.1));
}

#[test]
fn self_affine_moments_and_persson_tosatti() {
    use theory::rough::{SelfAffineSpectrum, persson_tosatti_work};
    let s = SelfAffineSpectrum {
        hurst: 0.8,
        q_long: 2.0 * std::f64::consts::PI / 1e-4,
        q_rolloff: 2.0 * std::f64::consts::PI / 2e-5,
        q_short: 2.0 * std::f64::consts::PI / 1e-7,
        rms_height: 1e-6,
    };
    assert!((s.moment(0.0) / 1e-12 - 1.0).abs() < 1e-12);
    // Against a midpoint quadrature on a logarithmic grid.
    let c = |q: f64| {
        if q < s.q_rolloff {
            1.0
        } else {
            (q / s.q_rolloff).powf(-2.0 * (1.0 + s.hurst))
        }
    };
    let quad = |n: f64| {
        let steps = 200_000;
        let (a, b) = (s.q_long.ln(), s.q_short.ln());
        let h = (b - a) / steps as f64;
        (0..steps)
            .map(|k| {
                let q = (a + (k as f64 + 0.5) * h).exp();
                2.0 * std::f64::consts::PI * q.powf(n + 2.0) * c(q) * h
            })
            .sum::<f64>()
    };
    for n in [1.0, 2.0] {
        let expected = 1e-12 * quad(n) / quad(0.0);
        assert!((s.moment(n) / expected - 1.0).abs() < 1e-6, "n = {n}");
    }
    // The elastic term grows like Rq^2: a smooth surface sticks, a rough one does not.
    let g = s.moment(2.0).sqrt();
    let w = persson_tosatti_work(0.05, 25e6, s.moment(1.0), g);
    assert!(w < 0.0, "Rq = 1 um on E* = 25 MPa is not sticky: {w}");
    let smooth = SelfAffineSpectrum {
        rms_height: 1e-9,
        ..s
    };
    let w = persson_tosatti_work(0.05, 25e6, smooth.moment(1.0), smooth.moment(2.0).sqrt());
    assert!(w > 0.0 && w < 0.05 * 1.01);
}

#[test]
fn persson_elastoplastic_tends_to_the_elastic_theory_and_to_the_bearing_area() {
    // A hardness far above every pressure reached: the elastic theory, nothing plastic.
    for x in [0.01, 0.1, 0.5, 1.0] {
        let (elastic, plastic) = persson_elastoplastic(x, 1e3);
        assert!(
            (elastic - persson_area(x)).abs() < 1e-12,
            "{x}: {elastic} vs {}",
            persson_area(x)
        );
        assert!(plastic < 1e-12, "{x}: {plastic}");
    }
    // A vanishing hardness: the bearing area p / H, all of it plastic.
    let (elastic, plastic) = persson_elastoplastic(5e-4, 1e-3);
    assert!(
        elastic < 1e-12 && (plastic - 0.5).abs() < 1e-12,
        "{elastic} {plastic}"
    );
    // Between: both areas grow with the load, the load is carried, and at p = H all is plastic.
    let h = 0.5;
    let mut last = (0.0, 0.0);
    for k in 1..50 {
        let x = h * k as f64 / 50.0;
        let (e, p) = persson_elastoplastic(x, h);
        assert!(p >= last.1 && e + p <= 1.0 + 1e-12, "{x}: {e} {p}");
        // The elastic contact carries less than H a cell.
        assert!(x - p * h <= e * h + 1e-12, "{x}: {e} {p}");
        last = (e, p);
    }
    assert_eq!(persson_elastoplastic(h, h), (0.0, 1.0));
}
