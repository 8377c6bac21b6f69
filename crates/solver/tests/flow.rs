//! The damped relaxation (`Method::Flow`) on smooth spheres with the paper's surface law:
//! against Newton through whole approach cycles at Tabor parameters 1, 3 and 5, and at 5 on
//! cells so coarse that the contact edge's cells are bistable, against itself in smaller steps.

mod common;

use common::*;
use solver::{Method, Settings};
use std::f64::consts::PI;

#[test]
fn the_flow_follows_newton_through_surface_law_sphere_cycles() {
    pool().install(|| {
        // R = 1000 z0 on a box 125 z0 across, cells of 2 z0; of 1 z0 at mu = 5, so that a cell
        // is 0.37 process zones and Newton's states do not depend on its step (on 2 z0 cells
        // they do, below).
        for (mu, n) in [(1.0, 64), (3.0, 64), (5.0, 128)] {
            let (op, g0, law, w0) = sphere_case(mu, n, 62.5);
            let path = approaches([-3.0, -2.0, -1.0, 0.0, 1.0, 0.0, -1.0, -2.0, -3.0].into_iter());
            let unit = PI * R * w0;
            let run = |method| {
                let settings = Settings {
                    tolerance: 1e-8,
                    max_iterations: 200_000,
                    ..Settings::with_method(method)
                };
                checked_sweep(&op, &law, &g0, &path, &settings)
            };
            let (newton, _) = run(Method::Newton);
            let (flow, worst) = run(Method::Flow);
            println!("mu = {mu}: flow's equations met to {worst:e} of the range");
            print_cycle(&flow, unit);
            assert!(worst < 1e-5, "mu = {mu}: {worst}");
            for (n, f) in newton.iter().zip(&flow) {
                assert!(n.report.converged() && f.report.converged(), "mu = {mu}");
                let difference = (n.report.load - f.report.load).abs() / unit;
                println!(
                    "  a/z0 {:5.1}: load difference {difference:.1e} pi R w0, areas {:.4} / {:.4}",
                    n.report.approach / Z0,
                    n.report.contact_area_fraction,
                    f.report.contact_area_fraction
                );
                assert!(
                    difference < 1e-5,
                    "mu = {mu} at {}: {difference}",
                    n.report.approach
                );
                assert_eq!(n.report.contact_area_fraction, f.report.contact_area_fraction);
            }
        }
    });
}

#[test]
fn at_a_high_tabor_parameter_the_flow_lands_where_it_would_in_smaller_steps() {
    // mu = 5 on cells of 0.73 process zones: at -1 z0 on loading, Newton ends 1.9e-4 pi R w0
    // less tensile in one step and 2.2e-4 in substeps of 0.05 z0 (three stable states of the
    // edge's bistable cells, docs/validation.md); the flow's state does not depend on the step.
    pool().install(|| {
        let (op, g0, law, w0) = sphere_case(5.0, 64, 62.5);
        let path = approaches([-3.0, -2.0, -1.0, 0.0, -1.0, -2.0, -3.0].into_iter());
        let settings = Settings {
            tolerance: 1e-8,
            max_iterations: 200_000,
            ..Settings::with_method(Method::Flow)
        };
        let problem = problem(&op, &law, g0.view());
        let [whole, split] =
            [None, Some(0.25 * Z0)].map(|h| problem.sweep(&path, h, &settings, None, &mut ()).unwrap());
        print_cycle(&whole, PI * R * w0);
        for (a, b) in whole.iter().zip(&split) {
            assert!(a.report.converged() && b.report.converged());
            assert!((a.report.load - b.report.load).abs() < 1e-7 * PI * R * w0);
            assert_eq!(a.report.contact_area_fraction, b.report.contact_area_fraction);
        }
    });
}

#[test]
fn the_flow_on_coarse_rough_cells_does_not_depend_on_the_number_of_threads() {
    use ljadhesion::{LennardJones, SurfaceLaw};
    use solver::{Control, Start};
    let (op, g0, e_star) = coarse_challenge();
    let law = SurfaceLaw(LennardJones::new(0.05, 2.071e-9).unwrap());
    let problem = problem(&op, &law, g0.view());
    let settings = Settings {
        max_iterations: 200_000,
        ..Settings::with_method(Method::Flow)
    };
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| {
                problem
                    .solve(
                        Control::MeanPressure(0.005 * e_star),
                        &settings,
                        Start::Loading,
                        &mut (),
                    )
                    .unwrap()
            })
    };
    let (a, ra) = run(1);
    let (b, rb) = run(3);
    assert!(ra.converged());
    assert_eq!(ra.iterations, rb.iterations);
    assert_eq!(a, b);
}

/// A law of the user's that couples a cell to its +x neighbour but gives no stiffness in
/// closed form: the surface law's pressure alone, so that the flow probes its stiffness.
#[derive(Clone)]
struct Probed(ljadhesion::SurfaceLaw);

impl ljadhesion::AdhesionLaw for Probed {
    fn pressure_field(
        &self,
        gap: ndarray::ArrayView2<f64>,
        cells: &ljadhesion::Cells,
        out: ndarray::ArrayViewMut2<f64>,
    ) -> ljadhesion::Result<()> {
        self.0.pressure_field(gap, cells, out)
    }
    fn stiffness_bound(&self) -> f64 {
        self.0.stiffness_bound()
    }
    fn work_of_adhesion(&self) -> f64 {
        self.0.work_of_adhesion()
    }
    fn range(&self) -> f64 {
        self.0.range()
    }
    fn peak_pressure(&self) -> f64 {
        self.0.peak_pressure()
    }
    fn name(&self) -> &'static str {
        "probed surface"
    }
}

#[test]
fn a_probed_stiffness_and_the_closed_form_reach_the_same_states() {
    // The mass only sets the flow's path; on a smooth sphere at mu = 3 (one stable state a
    // step) both reach the same loads and contact areas.
    pool().install(|| {
        let (op, g0, law, w0) = sphere_case(3.0, 64, 62.5);
        let path = approaches([-2.0, 0.0, 1.0, -1.0, -3.0].into_iter());
        let settings = Settings {
            tolerance: 1e-8,
            max_iterations: 200_000,
            ..Settings::with_method(Method::Flow)
        };
        let (closed, _) = checked_sweep(&op, &law, &g0, &path, &settings);
        let (probed, worst) = checked_sweep(&op, &Probed(law), &g0, &path, &settings);
        assert!(worst < 1e-5, "{worst}");
        for (a, b) in closed.iter().zip(&probed) {
            assert!(a.report.converged() && b.report.converged());
            let difference = (a.report.load - b.report.load).abs() / (PI * R * w0);
            println!(
                "a/z0 {:5.1}: load difference {difference:.1e} pi R w0, steps {} / {}",
                a.report.approach / Z0,
                a.report.iterations.count(),
                b.report.iterations.count()
            );
            assert!(difference < 1e-6, "{difference}");
            assert_eq!(a.report.contact_area_fraction, b.report.contact_area_fraction);
        }
    });
}
