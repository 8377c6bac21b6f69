//! Adhesive contact against an independent implementation: Tamaas 2.9 with its exponential
//! adhesion functional, on the same surface at the same mean gap (data/tamaas-adhesion-256,
//! see its README).

mod common;

use elastic::{Domain, Periodic};
use ljadhesion::ExponentialLaw;
use ndarray::Array2;
use solver::geometry::flat_on_rough;
use solver::{Control, Method, Settings, Start};
use std::path::Path;

fn load(name: &str) -> Array2<f64> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/tamaas-adhesion-256")
        .join(name);
    ndarray_npy::read_npy(&path).unwrap()
}

#[test]
fn exponential_adhesion_agrees_with_tamaas() {
    agrees_with_tamaas(Method::Accelerated);
}

#[test]
fn energy_descent_agrees_with_tamaas() {
    agrees_with_tamaas(Method::EnergyDescent);
}

fn agrees_with_tamaas(outer_loop: Method) {
    let h = load("surface.npy");
    let reference = load("tamaas_pressure.npy");
    let reference_gap = load("tamaas_gap.npy");
    let n = h.nrows();
    let domain = Domain {
        nx: n,
        ny: n,
        dx: 1.0 / n as f64,
        dy: 1.0 / n as f64,
        periodic: true,
    };
    let op = Periodic::new(domain, 1.0).unwrap();
    let g0 = flat_on_rough(h.view()).unwrap();
    // Tamaas prescribes the mean gap; on a periodic grid the mean displacement is zero, so
    // that is the approach mean(g0) - mean gap.
    let mean_gap = 0.08;
    let approach = g0.mean().unwrap() - mean_gap;
    let law = ExponentialLaw::new(1e-3, 2.0 / n as f64).unwrap();
    let options = Settings {
        tolerance: 1e-9,
        method: outer_loop,
        ..Settings::with_method(Method::Accelerated)
    };
    let (state, report) = rayon::ThreadPoolBuilder::new().build().unwrap().install(|| {
        common::problem(&op, &law, g0.view())
            .solve(Control::Approach(approach), &options, Start::Loading, &mut ())
            .unwrap()
    });
    assert!(report.converged());
    if outer_loop == Method::EnergyDescent {
        // One application for the direction and one for the trial gap per iteration, and one
        // for the preconditioner: no step cut. (Restoring the mean gap used to lift the whole
        // contact set off the wall by a round-off gap; the next direction pressed it back in
        // and 19 cuts followed here.)
        assert!(
            report.operator_calls <= 2 * common::inner(&report.iterations) + 2,
            "{} operator calls in {} iterations",
            report.operator_calls,
            common::inner(&report.iterations)
        );
    }
    println!(
        "outer {}, inner {}, {:.2} s; mean pressure {:.6e} (Tamaas {:.6e})",
        report.iterations.count(),
        common::inner(&report.iterations),
        report.wall_time_s,
        report.mean_pressure,
        reference.mean().unwrap()
    );
    assert!((state.contact.gap.mean().unwrap() / mean_gap - 1.0).abs() < 1e-9);
    let differ = state
        .contact
        .gap
        .iter()
        .zip(reference_gap.iter())
        .filter(|(a, b)| (**a == 0.0) != (**b == 0.0))
        .count();
    let in_contact = reference_gap.iter().filter(|g| **g == 0.0).count();
    println!("contact cells: {in_contact} (Tamaas), differing {differ}");
    assert_eq!(differ, 0, "{differ} of {in_contact} contact cells differ");
    let total = state.total_pressure();
    let pmax = reference.iter().fold(0.0f64, |m, p| m.max(p.abs()));
    let worst = total
        .iter()
        .zip(reference.iter())
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    println!("largest pressure difference {:.2e} of the maximum", worst / pmax);
    assert!((report.mean_pressure / reference.mean().unwrap() - 1.0).abs() < 1e-5);
    assert!(worst < 1e-5 * pmax);
}
