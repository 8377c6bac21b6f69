//! The hardness cap: without adhesion the sphere's exact onset of yield, the bearing-area limit
//! and a load-unload-reload cycle whose external work is the plastic work; with adhesion every
//! method against another, and the pull-off of a yielded Lennard-Jones sphere.

use ljadhesion::{AdhesionLaw, LennardJones, PointLaw, SurfaceLaw};
use solver::{ContactOptions, ContactProblem, ContactState, Control, Interface, Method};
use surfgen::{Amplitudes, Grid, Normalization, Psd, SurfaceSpec, generate};

const E: f64 = 1e9;

/// A free-grid paraboloid of radius `r` \[m\] on `n`^2 cells `side` \[m\] across, hardness `h`.
fn sphere(n: usize, side: f64, r: f64, h: Option<f64>) -> ContactProblem {
    let mut builder = ContactProblem::builder()
        .grid(n, n, side, side)
        .sphere(r)
        .modulus(E);
    if let Some(h) = h {
        builder = builder.hardness(h);
    }
    builder.build().unwrap()
}

/// A periodic self-affine surface (Hurst 0.8, RMS gradient 0.1) on `n`^2 cells.
fn rough(n: usize, seed: u64, h: f64) -> ContactProblem {
    let l = 1e-4;
    let grid = Grid::square(n, l).unwrap();
    let spec = SurfaceSpec {
        grid,
        psd: Psd::self_affine(0.8, l / 4.0, 4.0 * grid.dx()),
        normalization: Normalization::RmsGradient(0.1),
        amplitudes: Amplitudes::Exact,
        seed,
    };
    let heights = generate(&spec).unwrap().heights;
    ContactProblem::builder()
        .roughness(heights, l, l)
        .modulus(E)
        .hardness(h)
        .build()
        .unwrap()
}

fn solve(
    problem: &ContactProblem,
    control: Control,
    warm: Option<&ContactState>,
) -> (ContactState, solver::ContactReport) {
    let options = ContactOptions {
        tolerance: 1e-10,
        ..ContactOptions::default()
    };
    let (state, report) = problem
        .solve_without_adhesion(control, &options, warm, &mut ())
        .unwrap();
    assert!(report.converged(), "{control:?}: {:?}", report.termination);
    (state, report)
}

#[test]
fn a_sphere_stays_hertzian_until_its_peak_reaches_the_hardness_then_caps_it() {
    // At H = 0.1 E*: P = pi^3 R^2 H^3 / (6 E*^2) = 5.168e-3 E* R^2, a = pi R H / (2 E*) = 0.1571 R.
    let (r, h) = (1e-6, 0.1 * E);
    let p_cap = std::f64::consts::PI.powi(3) * r * r * h.powi(3) / (6.0 * E * E);
    let a_cap = std::f64::consts::PI * r * h / (2.0 * E);
    assert!((p_cap / (E * r * r) - 5.168e-3).abs() < 1e-6);
    assert!((a_cap / r - 0.1571).abs() < 1e-4);
    let (n, side) = (128, 0.8 * r);
    let plastic = sphere(n, side, r, Some(h));
    let elastic = sphere(n, side, r, None);
    let cell = (side / n as f64).powi(2);

    // Below the onset: the same solution as the elastic one, Hertz's peak, nothing at H.
    let below = Control::Force(0.9 * p_cap);
    let (s, rep) = solve(&plastic, below, None);
    let (se, _) = solve(&elastic, below, None);
    let a = theory::hertz::radius_of_load(0.9 * p_cap, r, E);
    let p0 = 3.0 * 0.9 * p_cap / (2.0 * std::f64::consts::PI * a * a);
    assert_eq!(rep.yielding.plastic_area_fraction, 0.0);
    assert_eq!(rep.yielding.permanent_set_volume, 0.0);
    assert!(
        (rep.max_pressure / p0 - 1.0).abs() < 0.01,
        "{} vs {p0}",
        rep.max_pressure
    );
    let off = (&s.pressure - &se.pressure)
        .mapv(f64::abs)
        .fold(0.0f64, |m, &v| m.max(v));
    assert!(off < 1e-6 * h, "{off}");
    assert!(rep.max_pressure < h);

    // Above it: the peak is H to round-off, the area at least P / H, and the set's overlap
    // is where the pressure is H.
    for factor in [2.0, 8.0] {
        let load = factor * p_cap;
        let (s, rep) = solve(&plastic, Control::Force(load), None);
        assert_eq!(rep.max_pressure, h, "x{factor}");
        let area = rep.contact_area_fraction * (n * n) as f64 * cell;
        assert!(area >= load / h, "x{factor}: {area} < {}", load / h);
        assert!(rep.yielding.plastic_area_fraction > 0.0);
        let set = s.permanent_set.as_ref().unwrap();
        let yielded = ndarray::Zip::from(set)
            .and(&s.pressure)
            .fold(true, |ok, &d, &p| ok && (d == 0.0 || p == h));
        assert!(yielded, "a cell below H took permanent set");
        assert!(
            (rep.yielding.plastic_work - h * rep.yielding.permanent_set_volume).abs()
                <= 1e-12 * rep.yielding.plastic_work
        );
        // The load balance holds under the cap.
        assert!((rep.load / load - 1.0).abs() < 1e-9, "{} vs {load}", rep.load);
    }
}

#[test]
fn a_vanishing_hardness_gives_the_geometric_bearing_area() {
    let n = 256;
    let h = 1e-6 * E;
    let problem = rough(n, 7, h);
    let (s, rep) = solve(&problem, Control::MeanPressure(0.1 * h), None);
    // The bearing set of the same area: the cells of smallest initial gap.
    let in_contact = s.pressure.iter().filter(|&&p| p > 0.0).count();
    assert!((in_contact as f64 / (n * n) as f64 - rep.contact_area_fraction).abs() < 1e-12);
    let mut g0: Vec<f64> = problem.initial_gap.iter().copied().collect();
    g0.sort_by(f64::total_cmp);
    let level = g0[in_contact - 1];
    let differ = ndarray::Zip::from(&s.pressure)
        .and(&problem.initial_gap)
        .fold(0usize, |k, &p, &g| k + usize::from((p > 0.0) != (g <= level)));
    assert!(
        differ <= 25,
        "{differ} cells differ from the bearing set of {in_contact}"
    );
    // Almost all of it is held at H: the elastic deformation is negligible.
    assert!(rep.yielding.plastic_area_fraction > 0.9 * rep.contact_area_fraction);
}

#[test]
fn after_unloading_the_surface_keeps_its_set_reloading_is_elastic_and_the_cycle_work_is_the_plastic_work() {
    let n = 128;
    let h = 0.05 * E;
    let problem = rough(n, 3, h);
    let cell = problem.domain().cell_area();
    let area = cell * (n * n) as f64;
    // Load by approach steps to a mean pressure near 0.3 H, then unload to separation.
    let top = {
        let (s, _) = solve(&problem, Control::MeanPressure(0.3 * h), None);
        s.approach
    };
    let steps = 60;
    let path: Vec<f64> = (0..=steps)
        .map(|k| top * k as f64 / steps as f64)
        .chain((0..steps).rev().map(|k| top * k as f64 / steps as f64))
        .collect();
    let mut state: Option<ContactState> = None;
    let (mut work, mut plastic, mut last) = (0.0, 0.0, (0.0, 0.0));
    let mut loaded = None;
    for (k, &d) in path.iter().enumerate() {
        let (s, rep) = solve(&problem, Control::Approach(d), state.as_ref());
        // External work by the trapezoid rule: the load times the approach's step.
        if k > 0 {
            work += 0.5 * (rep.load + last.1) * (d - last.0);
        }
        last = (d, rep.load);
        plastic += rep.yielding.plastic_work;
        if k == steps {
            loaded = Some((s.clone(), rep.load));
        }
        state = Some(s);
    }
    let unloaded = state.unwrap();
    let set = unloaded.permanent_set.clone().unwrap();
    assert!(set.sum() > 0.0);
    // Separated: no pressure, no elastic displacement; the surface is its original shape less
    // the set, so the first touch is now deeper.
    assert!(unloaded.pressure.iter().all(|&p| p == 0.0));
    assert!(unloaded.displacement.iter().all(|&u| u == 0.0));
    let volume = set.sum() * cell;
    assert!((plastic - h * volume).abs() < 1e-9 * plastic);
    // The work around the cycle is dissipated by yielding alone (the trapezoid rule's error
    // over 60 steps a leg is well below a percent).
    assert!(
        (work / plastic - 1.0).abs() < 0.02,
        "cycle work {work:e} J, plastic {plastic:e} J"
    );

    // Reloading to the same load yields nothing more and finds the same contact set.
    let (loaded, load) = loaded.unwrap();
    let (s, rep) = solve(&problem, Control::Force(load), Some(&unloaded));
    assert!(
        rep.yielding.plastic_work < 1e-6 * plastic,
        "{:e}",
        rep.yielding.plastic_work
    );
    let differ = ndarray::Zip::from(&s.pressure)
        .and(&loaded.pressure)
        .fold(0usize, |k, &a, &b| k + usize::from((a > 0.0) != (b > 0.0)));
    assert!(differ <= 2, "{differ} cells differ");
    assert!(load / area < h);
}

#[test]
fn bad_hardness_and_loads_beyond_it_are_refused_by_name() {
    for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
        let err = ContactProblem::builder()
            .grid(16, 16, 1e-6, 1e-6)
            .sphere(1e-6)
            .modulus(E)
            .hardness(bad)
            .build()
            .unwrap_err();
        assert!(err.to_string().contains("hardness"), "{err}");
        assert!(Interface::with_hardness(bad).is_err());
    }
    let problem = rough(32, 1, 0.01 * E);
    let err = problem
        .solve_without_adhesion(
            Control::MeanPressure(0.02 * E),
            &ContactOptions::default(),
            None,
            &mut (),
        )
        .unwrap_err();
    assert!(
        err.to_string().contains("hardness times the nominal area"),
        "{err}"
    );
}

/// A Lennard-Jones sphere (Tabor parameter `mu`, R = 1000 z0, 64^2 cells of 4.7 z0) under
/// `law` made of the Lennard-Jones law, loaded from 3 z0 apart to the approach `deepest` \[m\]
/// and unloaded by `method` to its `tolerance`, with hardness `h` \[Pa\]: the pull-off \[N\] and
/// the plastic work \[J\] of the cycle.
fn sphere_cycle<L: AdhesionLaw + 'static>(
    law: fn(LennardJones) -> L,
    (method, tolerance): (Method, f64),
    h: Option<f64>,
    mu: f64,
    deepest: f64,
) -> (f64, f64) {
    let (r, z0): (f64, f64) = (1e-6, 1e-9);
    // mu^3 = R w0^2 / (E*^2 z0^3).
    let w0 = (mu.powi(3) * E * E * z0.powi(3) / r).sqrt();
    let mut builder = ContactProblem::builder()
        .grid(64, 64, 3e-7, 3e-7)
        .sphere(r)
        .modulus(E)
        .law(law(LennardJones::new(w0, z0).unwrap()));
    if let Some(h) = h {
        builder = builder.hardness(h);
    }
    let problem = builder.build().unwrap();
    let steps = ((deepest + 3.0 * z0) / (0.5 * z0)).round() as usize;
    let path = solver::approach_cycle(-3.0 * z0, deepest, steps);
    let mut settings = solver::Settings::with_method(method);
    settings.tolerance = tolerance;
    let points = problem
        .sweep(&path, Some(0.25 * z0), &settings, None, &mut ())
        .unwrap();
    let cycle: Vec<solver::CyclePoint> = points.iter().map(solver::CyclePoint::from).collect();
    let summary = solver::summarize(&cycle);
    assert!(summary.all_converged, "{method:?} {h:?} {mu} {deepest:e}");
    if h.is_none() {
        assert_eq!(summary.plastic_work, 0.0);
    }
    (-summary.pull_off_force.unwrap(), summary.plastic_work)
}

#[test]
fn every_adhesive_method_takes_a_hardness_and_they_agree() {
    use Method::{Accelerated, EnergyDescent, Flow, Newton};
    // Tabor parameter 1, yielding at 30 MPa (Hertz's peak at the deepest approach is 68 MPa,
    // the law's peak attraction 32 MPa): the gap methods against the accelerated loop, a
    // different algorithm (fixed point of the adhesive pressure around capped solves), on
    // the same cycle. The point law to 1e-8 of its range; the surface law to the default
    // 1e-6, where the methods' pull-offs spread by 1e-5.
    let h = Some(3e7);
    let point = |method| sphere_cycle(PointLaw, (method, 1e-8), h, 1.0, 6e-9);
    let surface = |method| sphere_cycle(SurfaceLaw, (method, 1e-6), h, 1.0, 6e-9);
    let (descent, by_loop) = (point(EnergyDescent), point(Accelerated));
    let reference = surface(Accelerated);
    assert!(reference.1 > 0.0);
    let mut pairs = vec![(descent, by_loop, 1e-6)];
    for method in [Flow, Newton] {
        pairs.push((surface(method), reference, 5e-5));
    }
    for (a, b, tolerance) in pairs {
        for (a, b) in [(a.0, b.0), (a.1, b.1)] {
            assert!((a / b - 1.0).abs() < tolerance, "{a:e} vs {b:e}");
        }
    }
}

#[test]
fn a_lennard_jones_sphere_pulls_off_harder_the_deeper_it_yielded_and_as_an_elastic_one_when_hard() {
    // Tabor parameter 5 (near JKR's limit), by the energy descent (`auto`'s choice).
    let cycle = |h, deepest| sphere_cycle(PointLaw, (Method::Auto, 1e-8), h, 5.0, deepest).0;
    let elastic = cycle(None, 6e-9);
    // A hardness far above every pressure reached: nothing yields, the same pull-off.
    let hard = cycle(Some(1e3 * E), 6e-9);
    assert!((hard / elastic - 1.0).abs() < 1e-6, "{hard:e} vs {elastic:e}");
    // At 30 MPa the flattened tip holds a larger contact, the more so the deeper it went.
    let shallow = cycle(Some(3e7), 3e-9);
    let deep = cycle(Some(3e7), 6e-9);
    assert!(shallow > 1.02 * elastic, "{shallow:e} vs {elastic:e}");
    assert!(deep > 1.05 * shallow, "{deep:e} vs {shallow:e}");
}

#[test]
fn a_hardness_below_the_laws_attraction_at_contact_is_refused() {
    // The exponential law pulls contact cells with w0 / rho = 1e7 Pa: a wall yielding at 5 MPa
    // could never hold them.
    let law = ljadhesion::ExponentialLaw::new(0.01, 1e-9).unwrap();
    let builder = || {
        ContactProblem::builder()
            .grid(16, 16, 1e-6, 1e-6)
            .sphere(1e-6)
            .modulus(E)
            .law(law)
    };
    let err = builder().hardness(5e6).build().unwrap_err();
    assert!(err.to_string().contains("hardness"), "{err}");
    assert!(err.to_string().contains("attraction at contact"), "{err}");
    assert!(builder().hardness(2e7).build().is_ok());
}

#[test]
fn with_a_vanishing_attraction_the_gap_methods_land_on_the_capped_contact() {
    // A rough surface in the mixed regime (RMS gradient 0.1, H = 0.1 E*), loaded to 0.15 H and
    // then 0.3 H, with a vanishing attraction: each gap method, started with every cell on the
    // wall, against the active set of the non-adhesive solver along the same path, an
    // independent algorithm (a projection of the pressure onto [0, H]).
    let h = 0.1 * E;
    let mut problem = rough(64, 3, h);
    let options = ContactOptions {
        tolerance: 1e-12,
        ..ContactOptions::default()
    };
    let loads = [0.15 * h, 0.3 * h];
    let mut reference: Vec<ContactState> = Vec::new();
    for &p in &loads {
        let (state, report) = problem
            .solve_without_adhesion(Control::MeanPressure(p), &options, reference.last(), &mut ())
            .unwrap();
        let plastic = report.yielding.plastic_area_fraction;
        assert!(plastic > 0.005 && plastic < report.contact_area_fraction - 0.01);
        reference.push(state);
    }
    problem.law = std::sync::Arc::new(ljadhesion::ExponentialLaw::new(1e-20, 1e-7).unwrap());
    // Not Newton: under a hardness it stalls when the plastic set changes this much in one
    // solve (151 steps at a residual of 2.3 from 0.15 H to 0.3 H; docs/solvers.md).
    for method in [Method::EnergyDescent, Method::Flow] {
        let mut settings = solver::Settings::with_method(method);
        settings.tolerance = 1e-9;
        let mut last: Option<solver::AdhesiveState> = None;
        for (&p, reference) in loads.iter().zip(&reference) {
            let control = Control::MeanPressure(p);
            let start = last
                .as_ref()
                .map_or(solver::Start::Unloading, solver::Start::Warm);
            let (state, got) = problem.solve(control, &settings, start, &mut ()).unwrap();
            assert!(
                got.converged(),
                "{method:?} at {p:e}: {:?} {:?} residual {:e}",
                got.termination,
                got.iterations,
                got.residual
            );
            let at_h = |p: &ndarray::Array2<f64>| p.mapv(|p| u8::from(p >= h));
            let touching = |p: &ndarray::Array2<f64>| p.mapv(|p| u8::from(p > 0.0));
            let differ = |a: ndarray::Array2<u8>, b: ndarray::Array2<u8>| {
                a.iter().zip(&b).filter(|(a, b)| a != b).count()
            };
            let (ours, theirs) = (&state.contact.pressure, &reference.pressure);
            let (c, y) = (
                differ(touching(ours), touching(theirs)),
                differ(at_h(ours), at_h(theirs)),
            );
            assert!(
                c <= 2 && y <= 2,
                "{method:?} at {p:e}: {c} contact and {y} plastic cells differ"
            );
            let set = |s: &ContactState| s.permanent_set.as_ref().unwrap().sum();
            let (a, b) = (set(&state.contact), set(reference));
            assert!(
                (a / b - 1.0).abs() < 1e-4,
                "{method:?} at {p:e}: set {a:e} against {b:e}"
            );
            let (a, b) = (state.contact.approach, reference.approach);
            assert!(
                (a / b - 1.0).abs() < 1e-6,
                "{method:?} at {p:e}: approach {a:e} against {b:e}"
            );
            last = Some(state);
        }
    }
}
