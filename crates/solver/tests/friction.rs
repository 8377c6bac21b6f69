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
            state = next;
        }
        // At the capacity the contact slides as a whole.
        let (_, report) = tangential
            .solve(TangentialControl::Force([mu_p, 0.0]), &state, &options())
            .unwrap();
        assert!(report.gross_sliding && report.stick_area_fraction == 0.0);
    }
}

/// Mindlin and Deresiewicz: a shear force cycled between +-Q* traces Masing's loop, and the
/// energy one cycle dissipates (the work of the force, and friction's own sum over the cells)
/// is their closed form within 2 %.
#[test]
fn fretting_loop_dissipates_mindlin_deresiewicz() {
    let (problem, normal, load, a) = hertz_contact(128, 24.0);
    let nu = 0.3;
    let g = E_STAR * (1.0 - nu) / 2.0;
    let tangential =
        TangentialProblem::new(problem.operator.as_ref(), nu, Friction::new(MU, 0.0).unwrap(), &normal).unwrap();
    let mu_p = MU * load;
    let amplitude = 0.6 * mu_p;
    let steps = 16;
    let leg = |from: f64, to: f64| (1..=steps).map(move |k| from + (to - from) * k as f64 / steps as f64);
    let controls: Vec<_> = leg(0.0, amplitude)
        .chain(leg(amplitude, -amplitude))
        .chain(leg(-amplitude, amplitude))
        .map(|q| TangentialControl::Force([q, 0.0]))
        .collect();
    let (_, reports) = tangential
        .path(&controls, ShearState::unloaded((128, 128)), &options(), &mut |_, _, _| true)
        .unwrap();
    assert_eq!(reports.len(), 3 * steps);
    let cycle = &reports[steps - 1..];
    let summary = solver::TangentialSummary::of(&reports);
    assert!(summary.all_converged && !summary.gross_sliding);
    // The closed cycle: from +Q* down and back (measured: 0.9 % under the closed form at 16
    // steps a leg, friction's sum within 2e-5 of the loop's area).
    let mut work = 0.0;
    for w in cycle.windows(2) {
        work += 0.5 * (w[0].force[0] + w[1].force[0]) * (w[1].displacement[0] - w[0].displacement[0]);
    }
    let friction: f64 = cycle[1..].iter().map(|r| r.frictional_work).sum();
    let exact = theory::mindlin::fretting_energy(amplitude, mu_p, g, nu, a);
    assert!((work - exact).abs() < 2e-2 * exact, "loop area {work:e} vs {exact:e}");
    assert!((friction - exact).abs() < 2e-2 * exact, "friction's work {friction:e} vs {exact:e}");
    // The branches follow Masing's rule.
    for r in &cycle[1..=steps] {
        let q = r.force[0];
        let exact = theory::mindlin::loop_displacement(q, amplitude, true, mu_p, g, nu, a);
        let scale = theory::mindlin::displacement(amplitude, mu_p, g, nu, a);
        assert!((r.displacement[0] - exact).abs() < 1e-2 * scale, "Q {q:e}: {:e} vs {exact:e}", r.displacement[0]);
    }
}

/// A prescribed displacement gives back the force that prescribed it, and the same state.
#[test]
fn displacement_control_matches_force_control() {
    let (problem, normal, load, _) = hertz_contact(96, 16.0);
    let tangential =
        TangentialProblem::new(problem.operator.as_ref(), 0.4, Friction::new(MU, 0.0).unwrap(), &normal).unwrap();
    let start = ShearState::unloaded((96, 96));
    // Along a diagonal, to exercise the coupling.
    let q = 0.5 * MU * load / 2f64.sqrt();
    let (by_force, rf) = tangential
        .solve(TangentialControl::Force([q, q]), &start, &options())
        .unwrap();
    let (by_displacement, rd) = tangential
        .solve(TangentialControl::Displacement(rf.displacement), &start, &options())
        .unwrap();
    assert!(rd.termination == solver::report::Termination::Converged);
    for c in 0..2 {
        assert!((rd.force[c] - q).abs() < 1e-6 * q, "{:?} vs {q}", rd.force);
        let peak = by_force.traction[c].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = (&by_force.traction[c] - &by_displacement.traction[c]).iter().fold(0.0f64, |m, v| m.max(v.abs()));
        assert!(diff < 1e-5 * peak, "traction {c}: {diff:e} of {peak:e}");
    }
    assert!((rf.stick_area_fraction - rd.stick_area_fraction).abs() < 1e-9);
}
