//! Non-adhesive sphere on a free grid against Hertz.

use elastic::{Domain, Free};
use solver::cg::solve;
use solver::geometry::{SphereProfile, sphere};
use solver::{ContactOptions, Control};
use std::f64::consts::PI;

const E: f64 = 1e9;
const R: f64 = 1e-4;

struct Errors {
    approach: f64,
    radius_cells: f64,
    max_pressure: f64,
    load_at_approach: f64,
}

/// Solves at the Hertz load whose contact spans `diameter` cells.
fn hertz(diameter: usize) -> Errors {
    let a = 1e-6;
    let d = 2.0 * a / diameter as f64;
    let n = diameter * 3 / 2;
    let dom = Domain {
        nx: n,
        ny: n,
        dx: d,
        dy: d,
        periodic: false,
    };
    let op = Free::new(dom, E).unwrap();
    let g0 = sphere(&dom, R, SphereProfile::Paraboloid, None).unwrap();
    let w = 4.0 * E * a.powi(3) / (3.0 * R);
    let opts = ContactOptions {
        tolerance: 1e-10,
        ..Default::default()
    };
    let (_, rep) = solve(&op, g0.view(), Control::Force(w), &opts, None, &mut ()).unwrap();
    assert!(
        rep.converged(),
        "{:?} after {} iterations",
        rep.termination,
        rep.iterations
    );
    assert!((rep.load / w - 1.0).abs() < 1e-12, "force balance");
    let radius = (rep.contact_area_fraction * (n * n) as f64 * d * d / PI).sqrt();
    let p0 = 3.0 * w / (2.0 * PI * a * a);
    // Displacement control at the Hertz approach gives the Hertz load back.
    let (_, by_approach) = solve(&op, g0.view(), Control::Approach(a * a / R), &opts, None, &mut ()).unwrap();
    assert!(by_approach.converged());
    Errors {
        approach: rep.approach / (a * a / R) - 1.0,
        radius_cells: (radius - a) / d,
        max_pressure: rep.max_pressure / p0 - 1.0,
        load_at_approach: by_approach.load / w - 1.0,
    }
}

#[test]
fn hertz_contact_on_a_free_grid_converges_under_refinement() {
    println!(
        "diameter [cells] | approach error | radius error [cells] | max pressure error | load error at Hertz approach"
    );
    let mut last = None;
    for diameter in [24, 48, 96] {
        let e = hertz(diameter);
        println!(
            "{diameter:>16} | {:>14.2e} | {:>20.2} | {:>18.2e} | {:.2e}",
            e.approach, e.radius_cells, e.max_pressure, e.load_at_approach
        );
        if let Some(prev) = last {
            let prev: Errors = prev;
            assert!(
                e.approach.abs() < prev.approach.abs(),
                "approach error must shrink"
            );
            assert!(
                e.load_at_approach.abs() < prev.load_at_approach.abs(),
                "load error must shrink"
            );
        }
        if diameter == 96 {
            assert!(e.approach.abs() < 0.005, "approach {:e}", e.approach);
            assert!(e.load_at_approach.abs() < 0.005, "load {:e}", e.load_at_approach);
            assert!(e.radius_cells.abs() <= 1.0, "radius {} cells", e.radius_cells);
            assert!(e.max_pressure.abs() < 0.01, "max pressure {:e}", e.max_pressure);
        }
        last = Some(e);
    }
}
