//! A viscoelastic body swept in time against Lee & Radok's and Ting's sphere, and its elastic
//! limits: the creep of a standard linear solid under a step load, constant-rate loading and
//! unloading, very slow and very fast paths, the order of the time integration.

use solver::{ContactProblem, Control, Method, Path, Settings};
use theory::viscoelastic::{Maxwell, creep_radius, creep_time, triangle};

const R: f64 = 1e-3;
const E_INF: f64 = 1e6;

/// A free-grid sphere on `n`^2 cells across `side` \[m\] with branches `(E_k, tau_k)`.
fn sphere(n: usize, side: f64, branches: &[(f64, f64)]) -> ContactProblem {
    let (moduli, times): (Vec<f64>, Vec<f64>) = branches.iter().copied().unzip();
    ContactProblem::builder()
        .grid(n, n, side, side)
        .sphere(R)
        .modulus(E_INF)
        .maxwell(&moduli, &times)
        .build()
        .unwrap()
}

fn settings() -> Settings {
    Settings {
        method: Method::Auto,
        tolerance: 1e-9,
        ..Settings::default()
    }
}

/// Loads \[N\], approaches \[m\] and contact radii from the area \[m\] of a sweep.
fn sweep(problem: &ContactProblem, controls: &[Control], times: &[f64]) -> Vec<(f64, f64, f64)> {
    let cell = problem.domain().cell_area();
    let cells = (problem.domain().nx * problem.domain().ny) as f64;
    let points = problem
        .sweep(Path::timed(controls, times), None, &settings(), None, &mut ())
        .unwrap();
    points
        .iter()
        .map(|p| {
            assert!(p.report.converged(), "{:?}", p.report.termination);
            let area = p.report.contact_area_fraction * cells * cell;
            (
                p.report.load,
                p.report.approach,
                (area / std::f64::consts::PI).sqrt(),
            )
        })
        .collect()
}

#[test]
fn a_standard_linear_solid_creeps_under_a_step_load_as_lee_and_radok_say() {
    // E0 / E_inf = 10; the glassy Hertz radius 12 cells, the relaxed one 26.
    let tau = 1.0;
    let solid = Maxwell::new(E_INF, &[9.0 * E_INF], &[tau]).unwrap();
    let tc = creep_time(&solid).unwrap();
    let (n, cell) = (128, 2e-6_f64);
    let a0 = 12.0 * cell;
    let load = 4.0 * solid.glassy() * a0.powi(3) / (3.0 * R);
    let problem = sphere(n, n as f64 * cell, &[(9.0 * E_INF, tau)]);
    // Steps of tau / 4 over five creep times, then longer ones to the relaxed end.
    let mut times: Vec<f64> = (0..=200).map(|k| 0.25 * tau * k as f64).collect();
    times.extend((1..=10).map(|k| 50.0 * tau + 100.0 * tau * k as f64));
    let controls = vec![Control::Force(load); times.len()];
    let got = sweep(&problem, &controls, &times);
    // The radius of the approach, a^2 = R delta (the Hertzian shape holds while the contact
    // grows), and the one of the area (within a cell).
    let radius = |k: usize| (R * got[k].1).sqrt();
    for (k, &t) in times.iter().enumerate() {
        let want = creep_radius(&solid, t, R, load);
        assert!(
            (radius(k) / want - 1.0).abs() < 0.01,
            "t {t}: {} against {want}",
            radius(k)
        );
        assert!(
            (got[k].2 - want).abs() < cell,
            "t {t}: area radius {} against {want}",
            got[k].2
        );
    }
    let (first, last) = (radius(0), radius(times.len() - 1));
    let at_tc = radius(40);
    assert_eq!(times[40], tc);
    println!(
        "a(inf)/a(0+) {:.5} (10^(1/3) = 2.15443), a(tc)/a(inf) {:.5} (0.8746)",
        last / first,
        at_tc / last
    );
    assert!((last / first / 10f64.cbrt() - 1.0).abs() < 0.01);
    assert!((at_tc / last / 0.8746 - 1.0).abs() < 0.01);
}

#[test]
fn constant_rate_indentation_and_unloading_follow_lee_radok_and_ting() {
    let branches = [(4.0 * E_INF, 0.1), (5.0 * E_INF, 1.0)];
    let (moduli, taus): (Vec<f64>, Vec<f64>) = branches.iter().copied().unzip();
    let solid = Maxwell::new(E_INF, &moduli, &taus).unwrap();
    let (n, cell) = (128, 2e-6_f64);
    let problem = sphere(n, n as f64 * cell, &branches);
    // In to a contact radius of 24 cells in 2 s and out at the same rate.
    let t_max = 2.0;
    let rate = (24.0 * cell).powi(2) / R / t_max;
    let steps = 200;
    let times: Vec<f64> = (0..=2 * steps).map(|k| t_max * k as f64 / steps as f64).collect();
    let controls: Vec<Control> = times
        .iter()
        .map(|&t| Control::Approach(rate * if t <= t_max { t } else { 2.0 * t_max - t }))
        .collect();
    let got = sweep(&problem, &controls, &times);
    let peak = triangle(&solid, t_max, R, rate, t_max).1;
    let (mut worst_in, mut worst_out) = (0.0f64, 0.0f64);
    for (k, &t) in times.iter().enumerate() {
        let (_, want) = triangle(&solid, t, R, rate, t_max);
        // Loads well above the grid's resolution: a contact of 8 cells and more.
        if want < 0.1 * peak {
            continue;
        }
        let error = (got[k].0 / want - 1.0).abs();
        if t <= t_max {
            worst_in = worst_in.max(error);
        } else {
            worst_out = worst_out.max(error);
        }
    }
    println!("loading within {worst_in:.2e}, unloading within {worst_out:.2e}");
    assert!(worst_in < 0.01, "{worst_in}");
    assert!(worst_out < 0.02, "{worst_out}");
}

#[test]
fn very_slow_and_very_fast_paths_are_the_relaxed_and_glassy_elastic_answers() {
    let branches = [(2.0 * E_INF, 0.1), (3.0 * E_INF, 1.0)];
    let glassy = 6.0 * E_INF;
    let (n, cell) = (64, 4e-6_f64);
    let problem = sphere(n, n as f64 * cell, &branches);
    let delta = (12.0 * cell).powi(2) / R;
    let controls: Vec<Control> = (0..=10)
        .map(|k| Control::Approach(delta * k as f64 / 10.0))
        .collect();
    let elastic = |e: f64| {
        let problem = ContactProblem::builder()
            .grid(n, n, n as f64 * cell, n as f64 * cell)
            .sphere(R)
            .modulus(e)
            .build()
            .unwrap();
        let points = problem
            .sweep(&controls, None, &settings(), None, &mut ())
            .unwrap();
        points.last().unwrap().report.load
    };
    for (scale, e) in [(1e-6, glassy), (1e6, E_INF)] {
        let times: Vec<f64> = (0..=10).map(|k| scale * k as f64).collect();
        let got = sweep(&problem, &controls, &times).last().unwrap().0;
        let want = elastic(e);
        println!("steps of {scale:e} s: {got:e} N, elastic {want:e} N");
        assert!((got / want - 1.0).abs() < 0.005, "{got} {want}");
    }
}
