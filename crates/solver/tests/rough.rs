//! Non-adhesive periodic rough contact: force balance, complementarity, the area-load slope.

use elastic::{Domain, Periodic};
use ndarray::Array2;
use solver::cg::solve;
use solver::geometry::flat_on_rough;
use solver::{ContactOptions, Control};
use surfgen::{Amplitudes, Grid, Normalization, Psd, SurfaceSpec, generate};

const E: f64 = 25e6;

/// H = 0.8, RMS gradient 1, roll-off at L/4 (or `rolloff` boxes), cut-off at `cutoff` cells.
fn surface_with(n: usize, seed: u64, rolloff: f64, cutoff: f64) -> (Array2<f64>, Domain) {
    let l = 1e-4;
    let grid = Grid::square(n, l).unwrap();
    let spec = SurfaceSpec {
        grid,
        psd: Psd::self_affine(0.8, l * rolloff, cutoff * grid.dx()),
        normalization: Normalization::RmsGradient(1.0),
        amplitudes: Amplitudes::Exact,
        seed,
    };
    let h = generate(&spec).unwrap().heights;
    (
        h,
        Domain {
            nx: n,
            ny: n,
            dx: grid.dx(),
            dy: grid.dy(),
            periodic: true,
        },
    )
}

fn surface(n: usize, seed: u64) -> (Array2<f64>, Domain) {
    surface_with(n, seed, 0.25, 4.0)
}

#[test]
fn force_balance_and_complementarity_hold() {
    let (h, dom) = surface(128, 1);
    let op = Periodic::new(dom, E).unwrap();
    let g0 = flat_on_rough(h.view()).unwrap();
    let p_mean = 0.02 * E;
    let opts = ContactOptions {
        tolerance: 1e-10,
        ..Default::default()
    };
    let (state, rep) = solve(
        &op,
        g0.view(),
        Control::MeanPressure(p_mean),
        &opts,
        None,
        &mut (),
    )
    .unwrap();
    assert!(rep.converged(), "{:?} {}", rep.termination, rep.residual);
    assert!((rep.mean_pressure / p_mean - 1.0).abs() < 1e-13, "force balance");
    // Complementarity: the gap recomputed from the displacement vanishes in contact and is
    // non-negative outside, to the tolerance times the roughness scale.
    let rms = (g0.iter().map(|g| g * g).sum::<f64>() / g0.len() as f64).sqrt();
    for ((p, g0), u) in state
        .pressure
        .iter()
        .zip(g0.iter())
        .zip(state.displacement.iter())
    {
        let g = g0 - rep.approach + u;
        assert!(*p >= 0.0);
        if *p > 0.0 {
            assert!(g.abs() < 1e-6 * rms, "gap {g:e} under pressure {p:e}");
        } else {
            assert!(g > -1e-6 * rms, "interpenetration {g:e}");
        }
    }
    // Displacement control at the found approach reproduces the load.
    let (_, again) = solve(
        &op,
        g0.view(),
        Control::Approach(rep.approach),
        &opts,
        None,
        &mut (),
    )
    .unwrap();
    assert!(again.converged());
    assert!(
        (again.mean_pressure / p_mean - 1.0).abs() < 1e-6,
        "{} vs {p_mean}",
        again.mean_pressure
    );
    assert!(
        rep.clusters > 5,
        "a rough contact has many clusters: {}",
        rep.clusters
    );
}

#[test]
fn warm_starts_converge_faster() {
    let (h, dom) = surface(128, 2);
    let op = Periodic::new(dom, E).unwrap();
    let g0 = flat_on_rough(h.view()).unwrap();
    let opts = ContactOptions::default();
    let (s1, cold) = solve(
        &op,
        g0.view(),
        Control::MeanPressure(0.02 * E),
        &opts,
        None,
        &mut (),
    )
    .unwrap();
    let (_, warm) = solve(
        &op,
        g0.view(),
        Control::MeanPressure(0.021 * E),
        &opts,
        Some(&s1),
        &mut (),
    )
    .unwrap();
    assert!(cold.converged() && warm.converged());
    assert!(
        warm.iterations < cold.iterations,
        "{} vs {}",
        warm.iterations,
        cold.iterations
    );
}

#[test]
fn small_load_area_slope_is_near_two() {
    // a_r = kappa p / (E* g_bar) at small load; boundary-element results give kappa ~ 2.
    // Single realisations scatter by +-10 % (a few large asperities dominate at small load),
    // so six are averaged. Cut-off at 8 cells, no roll-off, as in the speed comparisons.
    let n = 512;
    let mut kappas = Vec::new();
    for seed in 10..16 {
        let (h, dom) = surface_with(n, seed, 1.0, 8.0);
        let g_bar = surfgen::statistics(h.view(), &Grid::square(n, 1e-4).unwrap(), true, None).rms_gradient;
        let op = Periodic::new(dom, E).unwrap();
        let g0 = flat_on_rough(h.view()).unwrap();
        let reduced = 0.02;
        let (_, rep) = solve(
            &op,
            g0.view(),
            Control::MeanPressure(reduced * E * g_bar),
            &ContactOptions::default(),
            None,
            &mut (),
        )
        .unwrap();
        assert!(rep.converged());
        kappas.push(rep.contact_area_fraction / reduced);
    }
    let mean = kappas.iter().sum::<f64>() / kappas.len() as f64;
    println!("kappa by seed: {kappas:.3?}, mean {mean:.3}");
    assert!((1.8..=2.2).contains(&mean), "kappa = {mean}");
}

#[test]
fn results_do_not_depend_on_the_number_of_threads() {
    let (h, dom) = surface(96, 3);
    let g0 = flat_on_rough(h.view()).unwrap();
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                let op = Periodic::new(dom, E).unwrap();
                solve(
                    &op,
                    g0.view(),
                    Control::MeanPressure(0.03 * E),
                    &ContactOptions::default(),
                    None,
                    &mut (),
                )
                .unwrap()
            })
    };
    let (a, ra) = run(1);
    let (b, rb) = run(2);
    assert_eq!(ra.iterations, rb.iterations);
    assert_eq!(a.pressure, b.pressure);
}

#[test]
fn bad_input_is_refused_and_non_convergence_reported() {
    let (h, dom) = surface(32, 4);
    let op = Periodic::new(dom, E).unwrap();
    let g0 = flat_on_rough(h.view()).unwrap();
    let opts = ContactOptions::default();
    assert!(solve(&op, g0.view(), Control::MeanPressure(-1.0), &opts, None, &mut ()).is_err());
    assert!(solve(&op, g0.view(), Control::Approach(-1e-9), &opts, None, &mut ()).is_err());
    assert!(
        solve(
            &op,
            g0.view(),
            Control::MeanPressure(1e5),
            &ContactOptions {
                tolerance: 1e-16,
                ..opts
            },
            None,
            &mut ()
        )
        .is_err()
    );
    let mut bad = h.clone();
    bad[(3, 4)] = f64::NAN;
    assert!(flat_on_rough(bad.view()).is_err());
    let (_, rep) = solve(
        &op,
        g0.view(),
        Control::MeanPressure(1e5),
        &ContactOptions {
            max_iterations: 2,
            ..opts
        },
        None,
        &mut (),
    )
    .unwrap();
    assert!(!rep.converged() && rep.iterations == 2);
    let (state, rep) = solve(&op, g0.view(), Control::MeanPressure(0.0), &opts, None, &mut ()).unwrap();
    assert_eq!(rep.termination, solver::Termination::NoContact);
    assert!(state.pressure.iter().all(|&p| p == 0.0));
}
