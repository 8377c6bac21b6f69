//! The flow against itself: its accelerations and handover change none of its states.

use super::*;

/// The flow without its far field, with its shift alone, and with both accelerations.
const PLAIN: Course = Course {
    far_field: false,
    relax: false,
    ..Course::STANDARD
};
const SHIFT: Course = Course {
    relax: false,
    ..Course::STANDARD
};
use crate::{ContactProblem, Control, Method, Settings, Start};
use ljadhesion::{LennardJones, SurfaceLaw};

/// The far field's shift and relaxation under load control, and its relaxation under
/// approach control (the mean gap prescribed), land the flow in the states it reaches
/// without them, in a fraction of the steps: the contact-mechanics challenge's surface on
/// cells 190 process zones wide (each cell holds on or lets go alone), loaded from a cold
/// start and then unloaded, each load from the state before; then the same at the
/// approaches the loads reached.
#[test]
fn the_far_field_keeps_the_flows_states() {
    let (n, e_star) = (64, 25e6);
    let (problem, lj) = challenge(n);
    let settings = Settings {
        max_iterations: 200_000,
        ..Settings::with_method(Method::Flow)
    };
    let run = |course: Course, path: &[Control]| {
        let mut states: Vec<(AdhesiveState, AdhesiveReport)> = Vec::new();
        for &control in path {
            let job = Job {
                op: problem.operator.as_ref(),
                law: problem.law.as_ref(),
                interface: Default::default(),
                g0: problem.initial_gap.view(),
                control,
                settings: &settings,
                method: Method::Flow,
                start: states.last().map_or(Start::Loading, |(s, _)| Start::Warm(s)),
            };
            let solved = solve(&job, energy(&job).unwrap(), &mut |_, _| true, course);
            states.push(solved.unwrap());
        }
        states
    };
    // `gain`: the fewest times fewer applications of the stiffness the far field must take.
    let compare = |course: Course,
                   faster: &[(AdhesiveState, AdhesiveReport)],
                   plain: &[(AdhesiveState, AdhesiveReport)],
                   gain: f64| {
        let count = |states: &[(AdhesiveState, AdhesiveReport)]| {
            let steps = states.iter().map(|(_, r)| r.iterations.count()).sum::<usize>();
            let applications = states.iter().map(|(_, r)| r.operator_calls).sum::<usize>();
            (steps, applications)
        };
        for ((a, ra), (b, rb)) in faster.iter().zip(plain) {
            assert!(ra.converged() && rb.converged());
            let (ga, gb) = (&a.contact.gap, &b.contact.gap);
            let switched = ga
                .iter()
                .zip(gb)
                .filter(|(x, y)| (**x <= 0.0) != (**y <= 0.0))
                .count();
            let moved = ga.iter().zip(gb).fold(0.0f64, |m, (x, y)| m.max((x - y).abs()));
            println!(
                "{course:?} {:.4e} Pa, {:.4e} m: areas {:.5} / {:.5}, {switched} cells switched, gaps within {:.1e} z0, steps {} / {}",
                ra.mean_pressure,
                ra.approach,
                ra.contact_area_fraction,
                rb.contact_area_fraction,
                moved / lj.z0(),
                ra.iterations.count(),
                rb.iterations.count()
            );
            // The same contact set; the gaps as near as the tolerance leaves the soft
            // mode, whose stiffness is only the contacts'.
            assert_eq!(switched, 0);
            assert!(moved < 1e-3 * lj.z0());
        }
        let ((steps, applications), (plain_steps, plain_applications)) = (count(faster), count(plain));
        println!(
            "{course:?}: {steps} steps, {applications} applications against {plain_steps}, {plain_applications}"
        );
        assert!(
            gain * (applications as f64) < plain_applications as f64,
            "{course:?}: {applications} / {plain_applications}"
        );
    };
    let loads = [0.00125, 0.0025, 0.005, 0.0025, 0.00125].map(|p| Control::MeanPressure(p * e_star));
    let plain = run(PLAIN, &loads);
    // 1471 against 6549 steps when the shift was written.
    for course in [SHIFT, Course::STANDARD] {
        compare(course, &run(course, &loads), &plain, 3.0);
    }
    // Under approach control the plain flow is quick on a grid this small (765 applications
    // against 570 when the relaxation was written; at 512^2 it takes four times the steps:
    // docs/decisions.md).
    let approaches: Vec<Control> = plain.iter().map(|(_, r)| Control::Approach(r.approach)).collect();
    compare(
        Course::STANDARD,
        &run(Course::STANDARD, &approaches),
        &run(PLAIN, &approaches),
        1.2,
    );
}

/// Newton from the flow's point lands on the state the flow settles on: a rough sphere
/// with the surface law on cells 1.25 ranges wide, stepped out of contact, the flow alone
/// against the flow handing over as soon as its residual is below a hundred tolerances
/// (where it crawls, a residual that long stopped falling).
#[test]
fn newton_takes_over_from_the_flow_at_the_flows_state() {
    let (n, side, z0) = (48, 60e-9, 1e-9);
    let heights = Array2::from_shape_fn((n, n), |(j, i)| {
        0.4 * z0 * ((i as f64 * 0.7).sin() * (j as f64 * 0.9).cos() + (i as f64 * 0.3 + j as f64 * 0.4).cos())
    });
    let problem = ContactProblem::builder()
        .roughness(heights, side, side)
        .sphere(1e-6)
        .modulus(1e9)
        .law(SurfaceLaw(LennardJones::new(0.05, z0).unwrap()))
        .build()
        .unwrap();
    let settings = Settings {
        tolerance: 1e-8,
        max_iterations: 100_000,
        ..Settings::with_method(Method::Flow)
    };
    let solve_at = |delta: f64, start: Start, hand_over_below: Option<f64>| {
        let job = Job {
            op: problem.operator.as_ref(),
            law: problem.law.as_ref(),
            interface: Default::default(),
            g0: problem.initial_gap.view(),
            control: Control::Approach(delta),
            settings: &settings,
            method: Method::Flow,
            start,
        };
        solve(
            &job,
            energy(&job).unwrap(),
            &mut |_, _| true,
            Course {
                hand_over_below,
                ..Course::STANDARD
            },
        )
        .unwrap()
    };
    let (loaded, _) = solve_at(1.0 * z0, Start::Loading, None);
    for delta in [0.0, -0.5 * z0] {
        let (flow, flow_report) = solve_at(delta, Start::Warm(&loaded), None);
        let (handed, report) = solve_at(delta, Start::Warm(&loaded), Some(1e-6));
        assert!(flow_report.converged() && report.converged());
        let Iterations::Flow { steps, newton } = report.iterations else {
            panic!("the flow reports its own counts: {:?}", report.iterations)
        };
        assert!(newton > 0 && report.method == Method::Flow);
        assert_eq!(report.residual_history.len(), steps + newton + 1);
        let moved = (&handed.contact.gap - &flow.contact.gap)
            .iter()
            .fold(0.0f64, |m, d| m.max(d.abs()));
        println!(
            "approach {:.2} z0: loads {:.6e} / {:.6e} N, gaps within {:.1e} z0; {steps} + {newton} against {} steps",
            delta / z0,
            report.load,
            flow_report.load,
            moved / z0,
            flow_report.iterations.count()
        );
        assert!(moved < 1e-5 * z0);
        assert!((report.load - flow_report.load).abs() < 1e-6 * flow_report.load.abs());
    }
}

/// The far field's update made in the evaluation's pass over the rows, the law's fields
/// unstored, gives what the evaluation and then the update over the stored fields give, to
/// the last bit: the pull, the held cells, the gradient and the step's sums; and the law's
/// fields stored afterwards are those the evaluation stores.
#[test]
fn the_update_in_the_evaluations_pass_is_the_update_after_it() {
    let (n, length) = (24, 2.4e-7);
    let lj = LennardJones::new(0.05, 2.071e-9).unwrap();
    let heights = Array2::from_shape_fn((n, n), |(j, i)| {
        3e-9 * ((i as f64 * 0.7).sin() * (j as f64 * 0.9).cos() + (i as f64 * 0.3 + j as f64 * 0.5).cos())
    });
    on_coupled_problem(heights, length, 2e4, |mut problem, _| {
        // Gaps from the wall to ten ranges, a few cells on it; some velocity.
        let gap = Array2::from_shape_fn((n, n), |(j, i)| {
            (((i * 7 + j * 13) % 23) as f64 / 2.2 - 0.5).max(0.0) * lj.z0()
        });
        let velocity = Array2::from_shape_fn((n, n), |(j, i)| 1e-11 * ((i + 2 * j) % 5) as f64 - 2e-11);
        let (mut apart, mut together) = (Point::new(gap.clone()), Point::new(gap));
        let (mut far_apart, mut far_together) = (FarField::new((n, n)), FarField::new((n, n)));
        let (mut pull_apart, mut pull_together) = (Array2::zeros((n, n)), Array2::zeros((n, n)));
        problem.evaluate(&mut apart).unwrap();
        let (w1, m1) = far_apart
            .update(&mut problem, &apart, &velocity, &mut pull_apart)
            .unwrap();
        let (w2, m2) = far_together
            .evaluate_and_update(&mut problem, &mut together, &velocity, &mut pull_together)
            .unwrap();
        assert!(far_apart.held.iter().any(|&h| h == 0) && far_apart.held.iter().any(|&h| h == 1));
        assert_eq!(pull_apart, pull_together);
        assert_eq!(far_apart.held, far_together.held);
        assert_eq!(apart.gradient, together.gradient);
        assert_eq!(
            (far_apart.step, far_apart.mean),
            (far_together.step, far_together.mean)
        );
        assert_eq!(
            (w1, m1.power, m1.vv, m1.va, m1.aa),
            (w2, m2.power, m2.vv, m2.va, m2.aa)
        );
        problem.store_law(&mut together).unwrap();
        assert_eq!(
            (&apart.law, &apart.curvature, &apart.coupling),
            (&together.law, &together.curvature, &together.coupling)
        );
    });
}

/// The elastic force's split into a near part and a kept far part
/// ([`Problem::split_elastic`]) gives the transform's force where the far part was made,
/// and away from there the transform's force for a uniform move (which costs none on a
/// periodic grid) and, for one cell's move, the transform's response on that cell and its
/// eight neighbours and none farther than two cells.
#[test]
fn the_split_elastic_force_is_the_transforms_where_it_should_be() {
    let (n, length) = (24, 2.4e-7);
    let heights = Array2::from_shape_fn((n, n), |(j, i)| {
        3e-9 * ((i as f64 * 0.7).sin() * (j as f64 * 0.9).cos() + (i as f64 * 0.3 + j as f64 * 0.5).cos())
    });
    on_coupled_problem(heights, length, 2e4, |mut problem, x| {
        let elastic = |problem: &mut Problem, gap: &Array2<f64>, near: bool| {
            assert_eq!(problem.near_only(near), near);
            let mut at = Point::new(gap.clone());
            problem.evaluate(&mut at).unwrap();
            at.elastic
        };
        problem.split_elastic().unwrap();
        assert!(!problem.near_only(true), "no far part before a transform");
        let gap = x.gap.mapv(|g| g + 1e-9);
        let transformed = elastic(&mut problem, &gap, false);
        let scale = transformed.iter().fold(0.0f64, |m, e| m.max(e.abs()));
        let off = |a: &Array2<f64>, b: &Array2<f64>| {
            a.iter().zip(b).fold(0.0f64, |m, (x, y)| m.max((x - y).abs())) / scale
        };
        assert!(off(&elastic(&mut problem, &gap, true), &transformed) < 1e-12);
        let shifted = gap.mapv(|g| g + 2e-9);
        assert!(off(&elastic(&mut problem, &shifted, true), &transformed) < 1e-12);
        let (c, by) = (10, 1e-9);
        let mut moved = gap.clone();
        moved[(c, c)] += by;
        let near = elastic(&mut problem, &moved, true) - &transformed;
        let exact = elastic(&mut problem, &moved, false) - &transformed;
        let own = exact[(c, c)];
        assert!(own > 0.0);
        for (((j, i), &a), &b) in near.indexed_iter().zip(&exact) {
            let apart = j.abs_diff(c).max(i.abs_diff(c));
            if apart <= 1 {
                assert!(
                    (a - b).abs() <= 1e-9 * own + 1e-12 * scale,
                    "({j}, {i}): {a:e} against {b:e}"
                );
            } else if apart > 2 {
                assert!(a.abs() <= 1e-12 * scale, "({j}, {i}): {a:e}");
            }
        }
    });
}

/// The coupled mass keeps the force weight `<r, M^-1 r>` positive where a cell just above
/// the wall (the law 200 times as stiff as the cell, and as stiff by its +x neighbour's
/// gap) sits beside a soft one: clamped to the cell's own diagonal alone, the coupling made
/// the mass's symmetric part indefinite, and a residual along its negative direction gave a
/// negative weight, on which the flow stopped every step.
#[test]
fn the_coupled_mass_keeps_the_force_weight_positive() {
    let (n, length) = (16, 1e-6);
    on_coupled_problem(Array2::zeros((n, n)), length, 1e3, |problem, mut x| {
        assert!(problem.coupled());
        let cell = problem.diagonal;
        // Stiff cells at even columns, coupled to their soft +x neighbours; the residual is
        // `P z` for the direction `z = (-0.45, 1)` of each pair, along which the symmetric part
        // of the mass clamped to the own diagonal alone is negative.
        let (stiff, coupling) = (200.0 * cell, 0.9 * 201.0 * cell);
        x.curvature = Array2::from_shape_fn((n, n), |(_, i)| if i % 2 == 0 { stiff } else { 0.0 });
        x.coupling = Array2::from_shape_fn((n, n), |(_, i)| if i % 2 == 0 { coupling } else { 0.0 });
        x.gradient = Array2::from_shape_fn((n, n), |(_, i)| {
            if i % 2 == 0 {
                (201.0 * -0.45 + 0.9 * 201.0) * cell
            } else {
                cell
            }
        });
        let mut pull = Array2::zeros((n, n));
        let weight = problem.precondition_rows(&x, &mut pull);
        assert!(weight > 0.0, "force weight {weight:e}");
    });
}

/// The far field's relaxation, preconditioned by the compliance, solves its linear model of
/// the soft cells' balance in a few iterations: the challenge's surface at 256^2 (cells 48
/// process zones wide) at rest under the flow, its soft cells then displaced by a long wave
/// a tenth of a range high, under load control and under a prescribed mean gap (whose sum
/// it keeps).
#[test]
fn the_far_fields_relaxation_solves_its_linear_model_in_a_few_iterations() {
    let (n, e_star) = (256, 25e6);
    let (contact, lj) = challenge(n);
    let settings = Settings {
        max_iterations: 200_000,
        ..Settings::with_method(Method::Flow)
    };
    let load = Control::MeanPressure(0.005 * e_star);
    let job = |control| Job {
        op: contact.operator.as_ref(),
        law: contact.law.as_ref(),
        interface: Default::default(),
        g0: contact.initial_gap.view(),
        control,
        settings: &settings,
        method: Method::Flow,
        start: Start::Loading,
    };
    let (rest, report) = Flow.solve(&job(load), &mut |_, _| true).unwrap();
    assert!(report.converged());
    let wave = Array2::from_shape_fn((n, n), |(j, i)| {
        let (x, y) = (i as f64 / n as f64, j as f64 / n as f64);
        0.1 * lj.z0() * (std::f64::consts::TAU * x).sin() * (std::f64::consts::TAU * (x + y)).cos()
    });
    // Of zero sum over the cells it moves, which keeps the prescribed mean gap.
    let soft = rest.contact.gap.mapv(|g| g > SOFT_CLEARANCE * 2.0 * lj.z0());
    let mean = Zip::from(&wave)
        .and(&soft)
        .fold(0.0, |m, &w, &s| if s { m + w } else { m })
        / soft.iter().filter(|&&s| s).count() as f64;
    let wave = wave - mean;
    for control in [load, Control::Approach(report.approach)] {
        let j = job(control);
        let Setup {
            mut problem, mut x, ..
        } = setup(&j, energy(&j).unwrap()).unwrap();
        problem.couple_rows(&mut x).unwrap();
        Zip::from(&mut x.gap)
            .and(&rest.contact.gap)
            .and(&wave)
            .and(&soft)
            .for_each(|g, &at, &w, &s| *g = if s { at + w } else { at });
        problem.evaluate(&mut x).unwrap();
        problem.project_gradient(&mut x);
        let mut far = FarField::new((n, n));
        match control {
            Control::MeanPressure(_) => {
                let (velocity, mut pull) = (Array2::zeros((n, n)), Array2::zeros((n, n)));
                far.update(&mut problem, &x, &velocity, &mut pull).unwrap();
            }
            _ => far.mark(&problem, &x),
        }
        let calls = problem.calls;
        let mut trial = Point::new(x.gap.clone());
        far.relax(&mut problem, &x, &mut trial).unwrap();
        let applications = problem.calls - calls;
        // The soft cells' number and the sum of their move.
        let (mut moved, mut count) = (0.0, 0);
        Zip::from(&trial.gap)
            .and(&x.gap)
            .and(&far.held)
            .for_each(|&g, &g1, &h| {
                if h == 0 {
                    moved += g - g1;
                    count += 1;
                }
            });
        // The soft cells' force in the relaxation's linear model, `r + (S + max(K, 0)) d` for
        // the move `d`, against the force before it, in the compliance's norm (the energy
        // norm of the move's error).
        let d = &trial.gap - &x.gap;
        let mut force = Array2::zeros((n, n));
        problem
            .stiffness
            .apply(d.view(), force.view_mut(), &mut problem.ws)
            .unwrap();
        Zip::from(&mut force)
            .and(&x.gradient)
            .and(&d)
            .and(&x.curvature)
            .and(&far.held)
            .for_each(|f, &r, &d, &c, &h| *f = if h == 0 { *f + r + c.max(0.0) * d } else { 0.0 });
        let before = x.gradient.clone() * far.held.mapv(|h| f64::from(u8::from(h == 0)));
        let norm = |problem: &mut Problem, r: &Array2<f64>| {
            let mut u = Array2::zeros((n, n));
            problem
                .stiffness
                .invert(r.view(), u.view_mut(), &mut problem.ws)
                .unwrap();
            (r * &u).sum().sqrt()
        };
        let left = norm(&mut problem, &force) / norm(&mut problem, &before);
        println!(
            "{control:?}: {count} soft cells, {applications} applications, force down to {left:.2e}, sum of the move {:.2e} z0",
            moved / lj.z0()
        );
        assert!(count > n * n / 2, "{count} soft cells");
        // Two applications an iteration and one first: ten iterations at most, where the
        // diagonal took its thirty.
        assert!(applications <= 21, "{applications} applications");
        assert!(left < 0.02, "the force down to {left:.2e} only");
        if let Control::Approach(_) = control {
            assert!(
                moved.abs() < 1e-9 * count as f64 * lj.z0(),
                "{:e} z0",
                moved / lj.z0()
            );
        }
    }
}

/// The contact-mechanics challenge's surface family on `n^2` cells of a 25 um box (H = 0.8,
/// roll-off a fifth of the box, cut-off four cells, RMS gradient 1, seed 1), periodic,
/// E* = 25 MPa, with the surface law (w0 = 50 mJ/m^2, z0 = 2.071 nm): cells 190 process
/// zones wide at 64^2.
fn challenge(n: usize) -> (ContactProblem, LennardJones) {
    let length = 2.5e-5;
    let grid = surfgen::Grid::square(n, length).unwrap();
    let spec = surfgen::SurfaceSpec {
        grid,
        psd: surfgen::Psd::self_affine(0.8, length / 5.0, 4.0 * grid.dx()),
        normalization: surfgen::Normalization::RmsGradient(1.0),
        amplitudes: surfgen::Amplitudes::Exact,
        seed: 1,
    };
    let lj = LennardJones::new(0.05, 2.071e-9).unwrap();
    let problem = ContactProblem::builder()
        .roughness(surfgen::generate(&spec).unwrap().heights, length, length)
        .periodic(true)
        .modulus(25e6)
        .law(SurfaceLaw(lj))
        .build()
        .unwrap();
    (problem, lj)
}

/// The held set's `held^T S held` followed through a few cells changing, by the kernel
/// between them, is the one a transform of the new held set gives, to rounding.
#[test]
fn the_held_sets_stiffness_follows_its_changes() {
    let (n, length, z0) = (48, 4.8e-7, 2.071e-9);
    let heights = Array2::from_shape_fn((n, n), |(j, i)| {
        3e-9 * ((i as f64 * 0.7).sin() * (j as f64 * 0.9).cos() + (i as f64 * 0.3 + j as f64 * 0.5).cos())
    });
    on_coupled_problem(heights, length, 2e4, |mut problem, _| {
        let mut gap = Array2::from_shape_fn((n, n), |(j, i)| {
            (((i * 7 + j * 13) % 23) as f64 / 2.2 - 0.5).max(0.0) * z0
        });
        let (velocity, mut pull) = (Array2::zeros((n, n)), Array2::zeros((n, n)));
        let mut far = FarField::new((n, n));
        let mut at = Point::new(gap.clone());
        problem.evaluate(&mut at).unwrap();
        far.update(&mut problem, &at, &velocity, &mut pull).unwrap();
        for round in 0..3 {
            // One soft cell onto the wall, one held cell far off it.
            let pick = |flag: u8| {
                far.held
                    .indexed_iter()
                    .filter(|&(_, &h)| h == flag)
                    .nth(7 * round + 3)
                    .unwrap()
                    .0
            };
            let (soft, held) = (pick(0), pick(1));
            gap[soft] = 0.0;
            gap[held] = 20.0 * z0;
            let mut at = Point::new(gap.clone());
            problem.evaluate(&mut at).unwrap();
            let transforms = problem.calls;
            far.update(&mut problem, &at, &velocity, &mut pull).unwrap();
            assert_eq!((far.held[soft], far.held[held]), (1, 0));
            // Followed, not transformed.
            assert_eq!(problem.calls, transforms);
            let mut fresh = FarField::new((n, n));
            fresh.update(&mut problem, &at, &velocity, &mut pull).unwrap();
            assert_eq!(far.held, fresh.held);
            let error = (far.elastic - fresh.elastic).abs() / fresh.elastic.abs();
            assert!(error < 1e-13, "round {round}: relative error {error:e}");
        }
        assert!(far.changes.as_ref().is_some_and(|c| c.len() >= 6));
    });
}

/// Hands `test` the gap problem of the surface law (w0 = 50 mJ/m^2, z0 = 2.071 nm) on the
/// periodic `heights` of side `length` \[m\], E* = 25 MPa, under the mean pressure `load`
/// \[Pa\], coupled by rows, with its first point.
fn on_coupled_problem(heights: Array2<f64>, length: f64, load: f64, test: impl FnOnce(Problem, Point)) {
    let problem = ContactProblem::builder()
        .roughness(heights, length, length)
        .periodic(true)
        .modulus(25e6)
        .law(SurfaceLaw(LennardJones::new(0.05, 2.071e-9).unwrap()))
        .build()
        .unwrap();
    let settings = Settings::with_method(Method::Flow);
    let job = Job {
        op: problem.operator.as_ref(),
        law: problem.law.as_ref(),
        interface: Default::default(),
        g0: problem.initial_gap.view(),
        control: Control::MeanPressure(load),
        settings: &settings,
        method: Method::Flow,
        start: Start::Loading,
    };
    let Setup {
        mut problem, mut x, ..
    } = setup(&job, energy(&job).unwrap()).unwrap();
    problem.couple_rows(&mut x).unwrap();
    test(problem, x);
}
