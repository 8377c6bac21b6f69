//! The viscoelastic sphere's closed forms against their anchors and limits: Lee & Radok's
//! creep of a standard linear solid, the creep compliance against the relaxation modulus,
//! constant-rate indentation between the relaxed and glassy Hertz, Ting's unloading.

use theory::viscoelastic::{Maxwell, creep_time, hertz_limit};

#[test]
fn a_standard_linear_solid_creeps_as_lee_and_radok_say() {
    // E0 / E_inf = 10 under a step load.
    let solid = Maxwell::new(1e6, &[9e6], &[1.0]).unwrap();
    let tc = creep_time(&solid).unwrap();
    assert!((tc - 10.0).abs() < 1e-12);
    let a = |t: f64| theory::viscoelastic::creep_radius(&solid, t, 1e-3, 1e-2);
    let (start, end) = (a(0.0), a(1e6 * tc));
    assert!((end / start - 10f64.cbrt()).abs() < 1e-12, "{}", end / start);
    assert!((a(tc) / end - 0.8746).abs() < 5e-5, "{}", a(tc) / end);
    // The glassy Hertz radius at once.
    let hertz = (0.75 * 1e-3 * 1e-2 / solid.glassy()).cbrt();
    assert!((start / hertz - 1.0).abs() < 1e-12);
}

#[test]
fn the_creep_compliance_inverts_the_relaxation_modulus() {
    // int_0^t E(t - s) J'(s) ds + E(t) J(0) = 1 for every t, three branches.
    let solid = Maxwell::new(2e5, &[1e6, 3e5, 5e6], &[0.01, 1.0, 30.0]).unwrap();
    assert!((solid.creep(0.0) * solid.glassy() - 1.0).abs() < 1e-12);
    assert!((solid.creep(1e9) * solid.relaxed - 1.0).abs() < 1e-12);
    // J' from the spectrum, the integral by Simpson's rule.
    let spectrum = solid.retardation();
    let slope = |s: f64| -> f64 { spectrum.iter().map(|&(c, l)| c / l * (-s / l).exp()).sum() };
    for t in [0.003, 0.1, 2.0, 50.0] {
        let n = 200_000;
        let h = t / n as f64;
        let sum: f64 = (0..=n)
            .map(|k| {
                let s = k as f64 * h;
                let w = if k == 0 || k == n {
                    1.0
                } else if k % 2 == 1 {
                    4.0
                } else {
                    2.0
                };
                w * solid.relaxation(t - s) * slope(s)
            })
            .sum();
        let total = sum * h / 3.0 + solid.relaxation(t) * solid.creep(0.0);
        assert!((total - 1.0).abs() < 1e-9, "t {t}: {total}");
    }
}

#[test]
fn constant_rate_indentation_runs_from_the_glassy_to_the_relaxed_hertz() {
    let solid = Maxwell::new(1e6, &[4e6, 5e6], &[0.1, 10.0]).unwrap();
    let (r, rate) = (1e-3, 1e-6);
    // Fast: 1e-4 of the quickest time; slow: 1e5 times the slowest (the corrections are of
    // order t / tau and tau / t).
    for (t, modulus) in [(1e-5, solid.glassy()), (1e6, solid.relaxed)] {
        let (a, p) = theory::viscoelastic::triangle(&solid, t, r, rate, 2.0 * t);
        let delta = rate * t;
        assert!((a / (r * delta).sqrt() - 1.0).abs() < 1e-12);
        let want = hertz_limit(delta, r, modulus);
        assert!((p / want - 1.0).abs() < 1e-4, "t {t}: {p} {want}");
    }
    // In between: the hereditary integral against a direct quadrature.
    let t = 3.0;
    let (_, p) = theory::viscoelastic::triangle(&solid, t, r, rate, 2.0 * t);
    let n = 400_000;
    let h = t.sqrt() / n as f64;
    // s = u^2: int_0^t E(t - s) sqrt(s) ds = int_0^sqrt(t) E(t - u^2) 2 u^2 du.
    let sum: f64 = (0..=n)
        .map(|k| {
            let u = k as f64 * h;
            let w = if k == 0 || k == n { 0.5 } else { 1.0 };
            w * solid.relaxation(t - u * u) * 2.0 * u * u
        })
        .sum();
    let want = 2.0 * r.sqrt() * rate.powf(1.5) * sum * h;
    assert!((p / want - 1.0).abs() < 1e-8, "{p} {want}");
}

#[test]
fn tings_unloading_is_elastic_in_either_limit_and_opens_before_the_approach_returns() {
    let (r, rate, t_max) = (1e-3, 1e-6, 1.0);
    for solid in [
        Maxwell::new(1e6, &[9e6], &[1e-6]).unwrap(),
        Maxwell::new(1e6, &[9e6], &[1e6]).unwrap(),
    ] {
        let modulus = if solid.branches[0].1 < 1.0 {
            solid.relaxed
        } else {
            solid.glassy()
        };
        // The corrections are of order (E_k / E_inf) tau / (t - t_max) and (t / tau): 1e-4
        // at t = 1.9 on the fast-relaxing solid, 1e-5 on the slow one.
        for t in [1.2, 1.5, 1.9] {
            let (a, p) = theory::viscoelastic::triangle(&solid, t, r, rate, t_max);
            let delta = rate * (2.0 * t_max - t);
            assert!((a / (r * delta).sqrt() - 1.0).abs() < 1e-4, "t {t}: {a}");
            assert!(
                (p / hertz_limit(delta, r, modulus) - 1.0).abs() < 2e-4,
                "t {t}: {p}"
            );
        }
    }
    // A standard linear solid with tau comparable to the cycle: the load falls to zero while
    // the approach is still positive (the surface lags behind the sphere), and the radius
    // shrinks continuously from its largest.
    let solid = Maxwell::new(1e6, &[9e6], &[0.3]).unwrap();
    let (a_top, p_top) = theory::viscoelastic::triangle(&solid, t_max, r, rate, t_max);
    let (a_next, p_next) = theory::viscoelastic::triangle(&solid, t_max + 1e-9, r, rate, t_max);
    assert!((a_next / a_top - 1.0).abs() < 1e-6 && (p_next / p_top - 1.0).abs() < 1e-5);
    let (a_late, p_late) = theory::viscoelastic::triangle(&solid, 1.9, r, rate, t_max);
    assert_eq!((a_late, p_late), (0.0, 0.0));
}

#[test]
fn bad_solids_are_refused_by_name() {
    let refused = |relaxed: f64, moduli: &[f64], times: &[f64]| {
        Maxwell::new(relaxed, moduli, times).unwrap_err().to_string()
    };
    assert_eq!(
        refused(-1.0, &[], &[]),
        "modulus (the relaxed modulus) must be finite and > 0 Pa, got -1"
    );
    assert_eq!(
        refused(1.0, &[1.0], &[]),
        "maxwell_times must hold one time a branch modulus (1 given), got 0"
    );
    assert_eq!(
        refused(1.0, &[1.0], &[-2.0]),
        "maxwell_times values must be finite and > 0 s, got -2"
    );
    assert!(refused(1.0, &[f64::NAN], &[2.0]).starts_with("maxwell_moduli values"));
}
