//! Tangential loading against closed forms: Cattaneo and Mindlin's partial slip of a sphere
//! and Mindlin and Deresiewicz' fretting loop (decoupled theory), gross sliding at the
//! contact's capacity.

use solver::{
    ContactOptions, ContactProblem, ContactState, Control, Friction, ShearOptions, ShearState, TangentialControl,
    TangentialProblem,
};
use std::f64::consts::PI;

const E_STAR: f64 = 1e9;
const RADIUS: f64 = 1e-3;
const MU: f64 = 0.3;
const DX: f64 = 1e-6;

/// A sphere pressed on a free grid of `n` cells to a Hertz contact `cells` cells in radius:
/// the normal state, the load \[N\] and the contact radius \[m\].
fn hertz_contact(n: usize, cells: f64) -> (ContactProblem, ContactState, f64, f64) {
    let problem = ContactProblem::builder()
        .grid(n, n, n as f64 * DX, n as f64 * DX)
        .sphere(RADIUS)
        .modulus(E_STAR)
        .build()
        .unwrap();
    let a = cells * DX;
    let load = 4.0 * E_STAR * a.powi(3) / (3.0 * RADIUS);
    let options = ContactOptions {
        tolerance: 1e-12,
        ..ContactOptions::default()
    };
    let (state, _) = problem
        .solve_without_adhesion(Control::Force(load), &options, None, &mut ())
        .unwrap();
    (problem, state, load, a)
}

fn options() -> ShearOptions {
    ShearOptions::default()
}

/// Cattaneo-Mindlin: the stick zone shrinks as `c / a = (1 - Q / mu P)^(1/3)` (within a cell,
/// 48 cells across the contact) and the body moves by `3 mu P (2 - nu) / (16 G a) [1 - (1 -
/// Q / mu P)^(2/3)]` (within 1 %), for an incompressible and a compressible body.
#[test]
fn cattaneo_mindlin_partial_slip() {
    let (problem, normal, load, a) = hertz_contact(128, 24.0);
    for nu in [0.5, 0.3] {
        let tangential =
            TangentialProblem::new(problem.operator.as_ref(), nu, Friction::new(MU, 0.0).unwrap(), &normal).unwrap();
        let g = E_STAR * (1.0 - nu) / 2.0;
        let mu_p = MU * load;
        // The grid's contact carries mu times its load.
        assert!((tangential.capacity() - mu_p).abs() < 1e-9 * mu_p);
        let mut state = ShearState::unloaded((128, 128));
        for ratio in [0.1, 0.25, 0.5, 0.75, 0.875, 0.95] {
            let (next, report) = tangential
                .solve(TangentialControl::Force([ratio * mu_p, 0.0]), &state, &options())
                .unwrap();
            assert!(report.termination == solver::report::Termination::Converged, "{ratio}: {report:?}");
            let c = (report.stick_area_fraction * (128.0 * 128.0) * DX * DX / PI).sqrt();
            let c_exact = theory::mindlin::stick_ratio(ratio) * a;
            assert!((c - c_exact).abs() < DX, "nu {nu}, Q/muP {ratio}: c {c:e} exact {c_exact:e}");
            let d_exact = theory::mindlin::displacement(ratio * mu_p, mu_p, g, nu, a);
            let d = report.displacement[0];
            assert!((d - d_exact).abs() < 1e-2 * d_exact, "nu {nu}, Q/muP {ratio}: {d:e} vs {d_exact:e}");
            assert!(report.displacement[1].abs() < 1e-6 * d && report.force[1].abs() < 1e-9 * mu_p);
            println!("nu {nu} ratio {ratio}: c/a {:.4} ({:.4}) d/d_exact {:.5} iterations {}", c / a, c_exact / a, d / d_exact, report.iterations);
            state = next;
        }
        // At the capacity the contact slides as a whole.
        let (_, report) = tangential
            .solve(TangentialControl::Force([mu_p, 0.0]), &state, &options())
            .unwrap();
        assert!(report.gross_sliding && report.stick_area_fraction == 0.0);
    }
}
