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

#[test]
fn a_flat_punch_creeps_with_the_creep_compliance_to_second_order_in_the_step() {
    // A punch's contact is its face at every time, so the grid's answer is the elastic one
    // times E_inf J(t) (the correspondence principle) and what remains is the time step's error.
    let solid = Maxwell::new(E_INF, &[9.0 * E_INF], &[1.0]).unwrap();
    let problem = punch(Some(solid.clone()));
    let load = 1e-3;
    let approach_at = |dt: f64, t: f64| {
        let steps = (t / dt).round() as usize;
        let times: Vec<f64> = (0..=steps).map(|k| k as f64 * dt).collect();
        let controls = vec![Control::Force(load); times.len()];
        sweep(&problem, &controls, &times).last().unwrap().1
    };
    let relaxed = approach_at(1e6, 1e6);
    let t = 4.0;
    let errors: Vec<f64> = [1.0, 0.5, 0.25]
        .iter()
        .map(|&dt| (approach_at(dt, t) / relaxed - E_INF * solid.creep(t)).abs())
        .collect();
    println!("errors at t = 4 s for steps of 1, 1/2, 1/4 s: {errors:?}");
    for w in errors.windows(2) {
        let order = (w[0] / w[1]).log2();
        assert!((order - 2.0).abs() < 0.15, "order {order}: {errors:?}");
    }
    assert!(errors[2] < 2e-3, "{errors:?}");
}

/// A periodic rough surface (64^2, seed 7) on the half-space or on a bonded layer of
/// thickness `layer` \[m\], viscoelastic with `branches` or elastic of modulus `e`.
fn rough(branches: Option<&[(f64, f64)]>, e: f64, layer: Option<f64>) -> ContactProblem {
    let grid = surfgen::Grid::square(64, 64e-6).unwrap();
    let spec = surfgen::SurfaceSpec {
        grid,
        psd: surfgen::Psd::self_affine(0.8, 16e-6, 4.0 * grid.dx()),
        normalization: surfgen::Normalization::RmsGradient(0.1),
        amplitudes: surfgen::Amplitudes::Exact,
        seed: 7,
    };
    let heights = surfgen::generate(&spec).unwrap().heights;
    let mut builder = ContactProblem::builder()
        .roughness(heights, 64e-6, 64e-6)
        .modulus(e);
    if let Some(h) = layer {
        builder = builder.layer(elastic::Layer::new(h, 0.45, elastic::Base::Bonded).unwrap());
    }
    if let Some(b) = branches {
        let (moduli, times): (Vec<f64>, Vec<f64>) = b.iter().copied().unzip();
        builder = builder.maxwell(&moduli, &times);
    }
    builder.build().unwrap()
}

#[test]
fn slow_and_fast_rough_contacts_are_the_relaxed_and_glassy_elastic_ones_on_any_body() {
    let branches = [(2.0 * E_INF, 0.1), (3.0 * E_INF, 1.0)];
    let glassy = 6.0 * E_INF;
    // Load control on the half-space, approach control on a layer (measured from its base).
    let loads: Vec<Control> = (1..=5).map(|k| Control::MeanPressure(2e4 * k as f64)).collect();
    for (layer, controls) in [(None, loads), (Some(8e-6), Vec::new())] {
        let controls = if controls.is_empty() {
            let top = rough(None, E_INF, layer).initial_gap.mean().unwrap();
            (1..=5).map(|k| Control::Approach(0.1 * top * k as f64)).collect()
        } else {
            controls
        };
        for (scale, e) in [(1e-6, glassy), (1e6, E_INF)] {
            let times: Vec<f64> = (0..controls.len()).map(|k| scale * k as f64).collect();
            let problem = rough(Some(&branches), E_INF, layer);
            let got = problem
                .sweep(Path::timed(&controls, &times), None, &settings(), None, &mut ())
                .unwrap();
            let want = rough(None, e, layer)
                .sweep(&controls, None, &settings(), None, &mut ())
                .unwrap();
            // The first step is a jump from rest (glassy on every path): the slow path relaxes after it.
            for (g, w) in got.iter().zip(&want).skip(usize::from(scale > 1.0)) {
                let (g, w) = (&g.report, &w.report);
                println!(
                    "layer {layer:?}, steps of {scale:e} s: load {:e} / {:e}, area {} / {}, {:?} {:?}",
                    g.load,
                    w.load,
                    g.contact_area_fraction,
                    w.contact_area_fraction,
                    g.termination,
                    w.termination
                );
                for (a, b) in [
                    (g.load, w.load),
                    (g.approach, w.approach),
                    (g.contact_area_fraction, w.contact_area_fraction),
                ] {
                    assert!((a / b - 1.0).abs() < 0.005, "{a} {b}");
                }
            }
        }
    }
}

#[test]
fn a_rough_contact_loaded_at_once_is_tamaas_first_viscoelastic_step() {
    // data/tamaas-viscoelastic-256 (see its README): E* = 1 relaxed, one branch of 9 relaxing
    // in 1 s, a mean pressure of 0.05 put on at time 0; Tamaas' backward Euler steps of 0.05 s.
    // Its first step is the jump (glassy, a twentieth of the branch relaxed): the same contact.
    // Later steps are not compared: Tamaas 2.9 does not relax to its own E under a held load.
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/tamaas-viscoelastic-256");
    let options = surfgen::io::ReadOptions {
        length_x: Some(1.0),
        ..Default::default()
    };
    let h = surfgen::io::read(&dir.join("surface.npy"), &options)
        .unwrap()
        .heights;
    let problem = ContactProblem::builder()
        .roughness(h, 1.0, 1.0)
        .modulus(1.0)
        .maxwell(&[9.0], &[1.0])
        .build()
        .unwrap();
    let text = std::fs::read_to_string(dir.join("tamaas_creep.csv")).unwrap();
    let first: Vec<f64> = text
        .lines()
        .nth(1)
        .unwrap()
        .split(',')
        .map(|x| x.parse().unwrap())
        .collect();
    let (t, tamaas) = (first[0], first[1]);
    let controls = [Control::MeanPressure(0.05); 2];
    let points = problem
        .sweep(
            Path::timed(&controls, &[0.0, t]),
            None,
            &settings(),
            None,
            &mut (),
        )
        .unwrap();
    let ours = points[1].report.contact_area_fraction;
    println!("contact area at {t} s: ours {ours:.6}, Tamaas {tamaas:.6}");
    assert!((ours / tamaas - 1.0).abs() < 2e-3, "{ours} {tamaas}");
}

#[test]
fn a_lennard_jones_sphere_pulls_off_as_the_relaxed_or_glassy_elastic_one_at_the_ends_of_the_rates() {
    // mu = 1 and 5 at E_inf (0.46 and 2.3 at E_0 = 10 E_inf); a cycle from apart to 1 z0 in
    // and back, in steps of z0 / 2.
    let (r, e, z0) = (1e-6_f64, 1e9, 1e-9_f64);
    let (n, side) = (64, 1.2e-7);
    for mu in [1.0, 5.0_f64] {
        let w = mu.powf(1.5) * e * z0.powf(1.5) / r.sqrt();
        let build = |branches: Option<(f64, f64)>, modulus: f64| {
            let mut b = ContactProblem::builder()
                .grid(n, n, side, side)
                .sphere(r)
                .modulus(modulus)
                .law(ljadhesion::SurfaceLaw(
                    ljadhesion::LennardJones::new(w, z0).unwrap(),
                ));
            if let Some((ek, tau)) = branches {
                b = b.maxwell(&[ek], &[tau]);
            }
            b.build().unwrap()
        };
        // Far enough out that the surfaces have come apart at the path's end.
        let apart = if mu > 2.0 { 16.0 } else { 3.0 };
        let path = solver::approach_cycle(-apart * z0, z0, 2 * (apart as usize + 1));
        let pull_off = |problem: &ContactProblem, times: Option<&[f64]>| {
            let points = problem
                .sweep(
                    Path {
                        controls: &path,
                        times,
                    },
                    Some(z0 / 2.0),
                    &settings(),
                    None,
                    &mut (),
                )
                .unwrap();
            assert!(points.iter().all(|p| p.report.converged()));
            assert_eq!(
                points.last().unwrap().report.attached_area_fraction,
                0.0,
                "still attached"
            );
            let cycle: Vec<solver::CyclePoint> = points.iter().map(solver::CyclePoint::from).collect();
            let summary = solver::summarize(&cycle);
            (
                -points.iter().map(|p| p.report.load).fold(0.0, f64::min),
                summary.adhesive_work.unwrap(),
                summary.viscous_work,
            )
        };
        let problem = build(Some((9.0 * e, 1.0)), e);
        for (step, modulus) in [(1e-9, 10.0 * e), (1e9, e)] {
            let times: Vec<f64> = (0..path.len()).map(|k| step * k as f64).collect();
            let (got, lost, viscous) = pull_off(&problem, Some(&times));
            let (want, lost_elastic, _) = pull_off(&build(None, modulus), None);
            println!(
                "mu {mu}, steps of {step:e} s: pull-off {got:e} N, elastic E* = {modulus:e}: {want:e} N; \
                 adhesive work {lost:e} J ({lost_elastic:e} J), viscous {viscous:e} J"
            );
            assert!((got / want - 1.0).abs() < 0.01, "{got} {want}");
            // The cycle's loss is the jumps' (the elastic one's; none without jumps), none of it
            // viscous: on the scale of the pull-off force times z0.
            let scale = want * z0;
            assert!(
                (lost - lost_elastic).abs() < 0.01 * scale,
                "{lost} {lost_elastic}"
            );
            assert!(viscous.abs() < 1e-3 * scale, "{viscous} {scale}");
        }
    }
}

#[test]
fn a_capped_sphere_paths_fast_and_slow_yield_as_the_glassy_and_relaxed_elastic_ones() {
    // A hardness of 0.02 E_inf, half Hertz's peak on the relaxed solid at the deepest step
    // (a contact 16 cells wide); in and out again in 12 steps.
    let (n, cell) = (64, 4e-6_f64);
    let hardness = 0.02 * E_INF;
    let delta = (16.0 * cell).powi(2) / R;
    let controls = solver::approach_cycle(0.0, delta, 6);
    let capped = |branches: Option<(f64, f64)>, e: f64| {
        let mut b = ContactProblem::builder()
            .grid(n, n, n as f64 * cell, n as f64 * cell)
            .sphere(R)
            .modulus(e)
            .hardness(hardness);
        if let Some((ek, tau)) = branches {
            b = b.maxwell(&[ek], &[tau]);
        }
        b.build().unwrap()
    };
    let problem = capped(Some((9.0 * E_INF, 1.0)), E_INF);
    for (scale, e) in [(1e-6, 10.0 * E_INF), (1e6, E_INF)] {
        let times: Vec<f64> = (0..controls.len()).map(|k| scale * (k + 1) as f64).collect();
        let got = problem
            .sweep(Path::timed(&controls, &times), None, &settings(), None, &mut ())
            .unwrap();
        let want = capped(None, e)
            .sweep(&controls, None, &settings(), None, &mut ())
            .unwrap();
        let (g, w) = (&got.last().unwrap().report, &want.last().unwrap().report);
        let deepest = |p: &[solver::SweepPoint]| p.iter().map(|p| p.report.load).fold(0.0, f64::max);
        println!(
            "steps of {scale:e} s: deepest load {:e} / {:e}, permanent set {:e} / {:e} m^3",
            deepest(&got),
            deepest(&want),
            g.yielding.permanent_set_volume,
            w.yielding.permanent_set_volume
        );
        assert!(w.yielding.permanent_set_volume > 0.0);
        assert!((deepest(&got) / deepest(&want) - 1.0).abs() < 0.005);
        assert!((g.yielding.permanent_set_volume / w.yielding.permanent_set_volume - 1.0).abs() < 0.005);
    }
}

/// A free-grid flat punch of radius 16 cells (64^2 cells of 1 um) on a half-space of relaxed
/// modulus `E_INF`, viscoelastic with `solid`: its face touches at approach 0, the rest stands
/// 0.1 mm off.
fn punch(solid: Option<Maxwell>) -> ContactProblem {
    let (n, cell) = (64, 1e-6_f64);
    let domain = elastic::Domain {
        nx: n,
        ny: n,
        dx: cell,
        dy: cell,
        periodic: false,
    };
    let centre = n as f64 / 2.0 - 0.5;
    let face = ndarray::Array2::from_shape_fn((n, n), |(j, i)| {
        let r = (i as f64 - centre).hypot(j as f64 - centre);
        if r < 16.0 { 0.0 } else { 1e-4 }
    });
    let op = elastic::Free::new(domain, E_INF).unwrap();
    let mut problem = ContactProblem::new(op, face, ljadhesion::NoAdhesion).unwrap();
    problem.solid = solid;
    problem
}

#[test]
fn a_punch_pressed_at_a_constant_rate_dissipates_and_stores_the_closed_form_energies() {
    // The punch's contact is its face throughout, so its displacement is linear in time
    // wherever the approach is, and each step is exact: per unit relaxed stiffness k, branch
    // k's spring stretches h_k = V tau_k (1 - exp(-t / tau_k)), its dashpot dissipates
    // (E_k / E_inf) k int h_k^2 / tau_k dt and the body stores
    // (k / 2) (delta^2 + sum_k (E_k / E_inf) h_k^2).
    let branches = [(9.0 * E_INF, 1.0), (5.0 * E_INF, 0.1)];
    let (moduli, taus): (Vec<f64>, Vec<f64>) = branches.iter().copied().unzip();
    let solid = Maxwell::new(E_INF, &moduli, &taus).unwrap();
    let (speed, dt, end) = (1e-8, 0.25, 3.0);
    let times: Vec<f64> = (0..=12).map(|k| k as f64 * dt).collect();
    let controls: Vec<Control> = times.iter().map(|t| Control::Approach(speed * t)).collect();
    let points = punch(Some(solid))
        .sweep(Path::timed(&controls, &times), None, &settings(), None, &mut ())
        .unwrap();
    let elastic = punch(None)
        .solve(
            Control::Approach(speed * end),
            &settings(),
            solver::Start::Loading,
            &mut (),
        )
        .unwrap()
        .1;
    let k = elastic.load / (speed * end);
    let (mut dissipated, mut stored) = (0.0, speed * end * speed * end);
    for &(e, tau) in &branches {
        let x = end / tau;
        let h = speed * tau * -(-x).exp_m1();
        dissipated += e / E_INF
            * speed
            * speed
            * tau
            * (end + 2.0 * tau * (-x).exp_m1() - 0.5 * tau * (-2.0 * x).exp_m1());
        stored += e / E_INF * h * h;
    }
    let (dissipated, stored) = (k * dissipated, 0.5 * k * stored);
    let viscous: f64 = points.iter().map(|p| p.report.viscous_work).sum();
    let last = &points.last().unwrap().report;
    println!(
        "viscous {viscous:e} J (closed form {dissipated:e}), stored {:e} J ({stored:e})",
        last.elastic_energy
    );
    assert!((viscous / dissipated - 1.0).abs() < 1e-6);
    assert!((last.elastic_energy / stored - 1.0).abs() < 1e-6);
}

#[test]
fn without_adhesion_a_cycle_loses_its_work_to_the_dashpots_alone() {
    // A free sphere and a periodic rough surface pressed in and drawn back apart at about one
    // relaxation time a cycle: the work done on them is the dashpots' plus what the body still
    // stores, and the adhesive rest is the trapezoidal rule's error, second order in the step.
    let branches = [(9.0 * E_INF, 1.0)];
    let sphere = sphere(64, 4e-5, &branches);
    let smooth_depth = 2e-7;
    let rough = rough(Some(&branches), E_INF, None);
    let rough_depth = 0.5 * rough.initial_gap.mean().unwrap();
    for (problem, depth) in [(sphere, smooth_depth), (rough, rough_depth)] {
        let mut rests = Vec::new();
        for steps in [10, 20] {
            let path = solver::approach_cycle(-0.1 * depth, depth, steps);
            let times: Vec<f64> = (0..path.len())
                .map(|k| k as f64 * 0.1 * 10.0 / steps as f64)
                .collect();
            let points = problem
                .sweep(Path::timed(&path, &times), None, &settings(), None, &mut ())
                .unwrap();
            let cycle: Vec<solver::CyclePoint> = points.iter().map(solver::CyclePoint::from).collect();
            let summary = solver::summarize(&cycle);
            let rest = summary.adhesive_work.unwrap();
            let stored = points.last().unwrap().report.elastic_energy;
            println!(
                "{} steps a leg: viscous {:e} J, still stored {stored:e} J, rest {rest:e} J",
                steps, summary.viscous_work
            );
            assert!(summary.viscous_work > 0.0);
            rests.push(rest.abs() / summary.viscous_work);
        }
        assert!(rests[0] / rests[1] > 3.5 && rests[1] < 5e-3, "{rests:?}");
    }
}
