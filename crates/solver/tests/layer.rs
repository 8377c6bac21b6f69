//! A sphere pressed into an elastic layer on a rigid base, against the thin-layer corrections
//! of Hertz (Dimitriadis et al. 2002; the Winkler limit), and a periodic layer's approach
//! measured from its base.

use elastic::{Base, Layer};
use solver::{ContactOptions, ContactProblem, Control};
use theory::layer as theory_layer;

const R: f64 = 1e-3;
const E_STAR: f64 = 1e6;

/// The load \[N\] of a free-grid sphere pressed `delta` \[m\] into `layer` (none: the
/// half-space), on `n`^2 cells across `side` \[m\].
fn load(layer: Option<Layer>, delta: f64, n: usize, side: f64) -> f64 {
    let mut builder = ContactProblem::builder()
        .grid(n, n, side, side)
        .sphere(R)
        .modulus(E_STAR);
    if let Some(layer) = layer {
        builder = builder.layer(layer);
    }
    let problem = builder.build().unwrap();
    let options = ContactOptions {
        tolerance: 1e-10,
        ..ContactOptions::default()
    };
    let (_, report) = problem
        .solve_without_adhesion(Control::Approach(delta), &options, None, &mut ())
        .unwrap();
    assert!(report.converged(), "{report:?}");
    report.load
}

fn base_of(base: Base) -> theory_layer::Base {
    match base {
        Base::Bonded => theory_layer::Base::Bonded,
        Base::Frictionless => theory_layer::Base::Frictionless,
        Base::Substrate { .. } => unreachable!("rigid bases only"),
    }
}

/// The exact (quadrature) sphere on `layer` of modulus `e_star` \[Pa\].
fn exact(layer: Layer, e_star: f64) -> theory_layer::LayerContact<impl Fn(f64) -> f64> {
    let h = layer.thickness;
    theory_layer::LayerContact::new(h, e_star, move |x| layer.compliance_ratio(x / h, e_star))
}

#[test]
fn a_sphere_on_a_layer_is_the_exact_solution_and_tends_to_hertz_at_dimitriadis_rate() {
    // Hertz radius a = sqrt(R delta) of 24 cells; chi = a / h. The grid's own error is taken
    // out by dividing by the half-space's load on the same grid (the ratios move by 2e-4 from
    // 24 to 48 cells).
    let (n, a) = (128, 1e-4);
    let (side, delta) = (n as f64 * a / 24.0, a * a / R);
    let hertz = load(None, delta, n, side);
    let hertz_exact = theory::hertz::load_of_approach(delta, R, E_STAR);
    for (nu, base) in [
        (0.49, Base::Bonded),
        (0.3, Base::Bonded),
        (0.3, Base::Frictionless),
    ] {
        let (alpha0, _) = theory_layer::dimitriadis_coefficients(nu, base_of(base));
        let first = -2.0 * alpha0 / std::f64::consts::PI;
        for chi in [0.05, 0.1, 0.25, 0.5] {
            let layer = Layer::new(a / chi, nu, base).unwrap();
            let got = load(Some(layer), delta, n, side) / hertz;
            let want = exact(layer, E_STAR).hertz(delta, R).load / hertz_exact;
            let fit =
                theory_layer::dimitriadis_load(delta, R, a / chi, E_STAR, nu, base_of(base)) / hertz_exact;
            println!("{base:?} nu {nu} chi {chi}: {got:.5}, exact {want:.5}, Dimitriadis {fit:.5}");
            assert!(
                (got / want - 1.0).abs() < 5e-4,
                "{base:?} nu {nu} chi {chi}: {got} {want}"
            );
            if chi == 0.05 {
                // The first-order rate, the second-order term taken out.
                let rate = (got - 1.0 - first * first * chi * chi) / (first * chi);
                assert!((rate - 1.0).abs() < 0.02, "{base:?} nu {nu}: rate {rate}");
            }
        }
    }
}

#[test]
fn a_sphere_on_a_coating_is_the_exact_solution() {
    // As above, on coatings over substrates ten times softer and stiffer than themselves.
    let (n, a) = (128, 1e-4);
    let (side, delta) = (n as f64 * a / 24.0, a * a / R);
    let hertz = load(None, delta, n, side);
    let hertz_exact = theory::hertz::load_of_approach(delta, R, E_STAR);
    for (e_sub, nu_sub) in [(0.1 * E_STAR, 0.45), (10.0 * E_STAR, 0.3)] {
        for chi in [0.25, 1.0] {
            let base = Base::Substrate {
                e_star: e_sub,
                poisson: nu_sub,
            };
            let layer = Layer::new(a / chi, 0.3, base).unwrap();
            let got = load(Some(layer), delta, n, side) / hertz;
            let want = exact(layer, E_STAR).hertz(delta, R).load / hertz_exact;
            println!("substrate {e_sub:e} Pa, chi {chi}: {got:.5}, exact {want:.5}");
            assert!((got / want - 1.0).abs() < 1e-3, "{e_sub} {chi}: {got} {want}");
        }
    }
}

#[test]
fn a_thin_compressible_layer_is_winklers_bed() {
    // a = sqrt(2 R delta) = 20 h, resolved by 24 cells; the load against pi M R delta^2 / h.
    let (n, nu) = (128, 0.3);
    for ratio in [5.0, 10.0, 20.0] {
        let a = 1e-4;
        let (h, delta) = (a / ratio, a * a / (2.0 * R));
        let side = n as f64 * a / 24.0;
        let got = load(Some(Layer::new(h, nu, Base::Bonded).unwrap()), delta, n, side);
        let want = theory_layer::winkler_load(delta, R, h, E_STAR, nu);
        println!("a/h {ratio}: {:.4}", got / want);
        if ratio >= 20.0 {
            assert!((got / want - 1.0).abs() < 0.02, "a/h {ratio}: {got} {want}");
        }
    }
}

#[test]
fn a_wave_flattened_on_a_periodic_layer_sinks_it_by_its_uniform_compression() {
    // A wave A (1 - cos q x) pressed flat on a layer: the mode q needs A / C(q) of pressure
    // amplitude, the mean pressure compresses the layer by C0 p_mean, so from the base the
    // approach is the mean gap + C0 p_mean. Both controls, without adhesion and through an adhesive
    // method with no law.
    let (n, side, amplitude) = (64, 64e-6, 0.2e-6);
    let q = 2.0 * std::f64::consts::PI / side;
    for base in [Base::Bonded, Base::Frictionless] {
        let layer = Layer::new(10e-6, 0.3, base).unwrap();
        let problem = ContactProblem::builder()
            .grid(n, n, side, side)
            .wave(amplitude)
            .modulus(E_STAR)
            .layer(layer)
            .build()
            .unwrap();
        let p_mean = 1.5 * amplitude / layer.compliance(q, E_STAR);
        // From first touch: the sampled wave's mean gap (its crest falls between cells).
        let mean_gap = problem.initial_gap.mean().unwrap();
        let delta = mean_gap + layer.compliance(0.0, E_STAR) * p_mean;
        let options = ContactOptions {
            tolerance: 1e-10,
            ..ContactOptions::default()
        };
        let (_, loaded) = problem
            .solve_without_adhesion(Control::MeanPressure(p_mean), &options, None, &mut ())
            .unwrap();
        assert_eq!(loaded.contact_area_fraction, 1.0);
        assert!(
            (loaded.approach / delta - 1.0).abs() < 1e-9,
            "{base:?}: {} {delta}",
            loaded.approach
        );
        let (_, pressed) = problem
            .solve_without_adhesion(Control::Approach(delta), &options, None, &mut ())
            .unwrap();
        assert!(pressed.converged());
        assert!(
            (pressed.mean_pressure / p_mean - 1.0).abs() < 1e-8,
            "{base:?}: {} {p_mean}",
            pressed.mean_pressure
        );
        let settings = solver::Settings::default();
        for control in [Control::MeanPressure(p_mean), Control::Approach(delta)] {
            let (_, report) = problem
                .solve(control, &settings, solver::Start::Loading, &mut ())
                .unwrap();
            assert!(report.converged(), "{base:?} {control:?}: {report:?}");
            assert!(
                (report.approach / delta - 1.0).abs() < 1e-6,
                "{base:?} {control:?}: {}",
                report.approach
            );
            assert!(
                (report.mean_pressure / p_mean - 1.0).abs() < 1e-6,
                "{base:?} {control:?}: {}",
                report.mean_pressure
            );
        }
    }
}

/// The pull-off force \[N\] of a Lennard-Jones sphere (surface law, Tabor parameter `mu`,
/// R = 1 um, E* = 1 GPa, z0 = 1 nm) on `layer` (none: the half-space), from a cycle to 4 z0
/// deep on a 64^2 free grid, and the JKR contact radius at pull-off \[m\].
fn pull_off(layer: Option<Layer>, mu: f64) -> (f64, f64) {
    use ljadhesion::{LennardJones, SurfaceLaw};
    let (r, z0, e): (f64, f64, f64) = (1e-6, 1e-9, 1e9);
    let w0 = (mu.powi(3) * e * e * z0.powi(3) / r).sqrt();
    let mut builder = ContactProblem::builder()
        .grid(64, 64, 3e-7, 3e-7)
        .sphere(r)
        .modulus(e)
        .law(SurfaceLaw(LennardJones::new(w0, z0).unwrap()));
    if let Some(layer) = layer {
        builder = builder.layer(layer);
    }
    let problem = builder.build().unwrap();
    let path = solver::approach_cycle(-3.0 * z0, 4.0 * z0, 14);
    let points = problem
        .sweep(
            &path,
            Some(0.25 * z0),
            &solver::Settings::default(),
            None,
            &mut (),
        )
        .unwrap();
    let cycle: Vec<solver::CyclePoint> = points.iter().map(solver::CyclePoint::from).collect();
    let summary = solver::summarize(&cycle);
    assert!(summary.all_converged, "{layer:?}");
    let a_jkr = (9.0 * std::f64::consts::PI * w0 * r * r / (8.0 * e)).cbrt();
    (-summary.pull_off_force.unwrap(), a_jkr)
}

#[test]
fn a_layer_pulls_off_as_jkr_on_the_layer() {
    // Tabor parameter 5: near JKR. A bonded layer a hundred contact radii thick pulls off as
    // the half-space (within 1 %); on one a contact radius thick the pull-off grows as JKR's
    // on the same layer does (the exact Griffith balance, theory::layer::LayerContact).
    let (half, a) = pull_off(None, 5.0);
    let (r, e, w0) = (1e-6, 1e9, theory::work_of_adhesion_of_tabor(5.0, 1e-6, 1e9, 1e-9));
    for (thickness, tolerance) in [(100.0 * a, 0.01), (a, 0.02)] {
        let layer = Layer::new(thickness, 0.3, Base::Bonded).unwrap();
        let (got, _) = pull_off(Some(layer), 5.0);
        let jkr = exact(layer, e).pull_off(r, w0).load / (-1.5 * std::f64::consts::PI * r * w0);
        println!(
            "h = {:.0} a: pull-off {:.4} of the half-space's, JKR on the layer {jkr:.4}",
            thickness / a,
            got / half
        );
        assert!((got / half / jkr - 1.0).abs() < tolerance, "{got} {half} {jkr}");
    }
}

#[test]
fn past_the_mean_gap_a_periodic_half_space_refuses_the_approach_and_a_layer_takes_it() {
    // Full contact closes the mean gap: beyond it only the layer's compression moves.
    let (n, side, amplitude) = (32, 32e-6, 0.2e-6);
    let build = |layer: Option<Layer>| {
        let mut b = ContactProblem::builder()
            .grid(n, n, side, side)
            .wave(amplitude)
            .modulus(E_STAR);
        if let Some(layer) = layer {
            b = b.layer(layer);
        }
        b.build().unwrap()
    };
    let delta = 1.5 * build(None).initial_gap.mean().unwrap();
    let options = ContactOptions::default();
    let e = build(None)
        .solve_without_adhesion(Control::Approach(delta), &options, None, &mut ())
        .unwrap_err();
    assert!(
        e.to_string().contains("approach") && e.to_string().contains("mean initial gap"),
        "{e}"
    );
    let layer = Layer::new(10e-6, 0.3, Base::Bonded).unwrap();
    let problem = build(Some(layer));
    let (_, pressed) = problem
        .solve_without_adhesion(Control::Approach(delta), &options, None, &mut ())
        .unwrap();
    assert!(pressed.converged());
    // The same state under the load it found.
    let (_, loaded) = problem
        .solve_without_adhesion(
            Control::MeanPressure(pressed.mean_pressure),
            &options,
            None,
            &mut (),
        )
        .unwrap();
    assert!(
        (loaded.approach / delta - 1.0).abs() < 1e-6,
        "{} {delta}",
        loaded.approach
    );
    assert_eq!(loaded.contact_area_fraction, pressed.contact_area_fraction);
}

#[test]
fn a_layer_yields_under_a_hardness_the_same_under_either_control() {
    // A rough periodic layer under a hardness, loaded to 0.3 H, then pressed cold to the
    // approach that load reached: every trial of the approach's root search starts from the
    // caller's (here no) permanent set, so the same contact, cells at H and set come out.
    let (n, side) = (64, 64e-6);
    let heights = ndarray::Array2::from_shape_fn((n, n), |(j, i)| {
        let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
        0.3e-6
            * ((2.0 * std::f64::consts::PI * (3.0 * x + y)).sin()
                + 0.5 * (2.0 * std::f64::consts::PI * (5.0 * y - 2.0 * x)).cos())
    });
    let hardness = 0.05 * E_STAR;
    let problem = ContactProblem::builder()
        .roughness(heights, side, side)
        .modulus(E_STAR)
        .layer(Layer::new(8e-6, 0.3, Base::Bonded).unwrap())
        .hardness(hardness)
        .build()
        .unwrap();
    let options = ContactOptions {
        tolerance: 1e-10,
        ..ContactOptions::default()
    };
    let (loaded_state, loaded) = problem
        .solve_without_adhesion(Control::MeanPressure(0.3 * hardness), &options, None, &mut ())
        .unwrap();
    assert!(loaded.converged() && loaded.yielding.plastic_area_fraction > 0.0);
    let (pressed_state, pressed) = problem
        .solve_without_adhesion(Control::Approach(loaded.approach), &options, None, &mut ())
        .unwrap();
    assert!(pressed.converged());
    assert!(
        (pressed.mean_pressure / loaded.mean_pressure - 1.0).abs() < 1e-6,
        "{} {}",
        pressed.mean_pressure,
        loaded.mean_pressure
    );
    assert_eq!(pressed.contact_area_fraction, loaded.contact_area_fraction);
    assert_eq!(
        pressed.yielding.plastic_area_fraction,
        loaded.yielding.plastic_area_fraction
    );
    let (a, b) = (
        pressed_state.permanent_set.unwrap(),
        loaded_state.permanent_set.unwrap(),
    );
    let worst = (&a - &b).iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(worst < 1e-6 * b.iter().fold(0.0f64, |m, v| m.max(*v)), "{worst}");
}
