//! The hardness cap against an independent implementation: ContactMechanics' penetration-hardness
//! system on the same periodic surface at two hardnesses and three loads each
//! (data/contactmechanics-plastic-256, see its README).

use elastic::{Domain, Periodic};
use ndarray::Array2;
use solver::geometry::flat_on_rough;
use solver::{ContactOptions, Control, Interface};
use std::path::{Path, PathBuf};

fn data(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/contactmechanics-plastic-256")
        .join(name)
}

#[test]
fn contact_and_plastic_areas_match_contactmechanics() {
    let h: Array2<f64> = ndarray_npy::read_npy(data("surface.npy")).unwrap();
    let n = h.nrows();
    let cells = (n * n) as f64;
    let domain = Domain {
        nx: n,
        ny: n,
        dx: 1.0 / n as f64,
        dy: 1.0 / n as f64,
        periodic: true,
    };
    let op = Periodic::new(domain, 1.0).unwrap();
    let g0 = flat_on_rough(h.view()).unwrap();
    let options = ContactOptions {
        tolerance: 1e-10,
        ..ContactOptions::default()
    };
    for (hardness, pressures) in [(0.03, [0.003, 0.01, 0.02]), (0.1, [0.01, 0.03, 0.05])] {
        let interface = Interface::with_hardness(hardness).unwrap();
        for mean_pressure in pressures {
            let (state, report) = solver::cg::solve_with(
                &op,
                g0.view(),
                &interface,
                Control::MeanPressure(mean_pressure),
                &options,
                None,
                &mut (),
            )
            .unwrap();
            assert!(
                report.converged(),
                "H {hardness} p {mean_pressure}: {:?}",
                report.termination
            );
            let theirs: Array2<f64> =
                ndarray_npy::read_npy(data(&format!("cm_pressure_H{hardness}_p{mean_pressure}.npy")))
                    .unwrap();
            let area = |p: &Array2<f64>| p.iter().filter(|&&v| v > 0.0).count() as f64;
            let at_h = |p: &Array2<f64>| p.iter().filter(|&&v| v >= hardness * (1.0 - 1e-9)).count() as f64;
            let (a, b) = (area(&state.pressure), area(&theirs));
            let (pa, pb) = (at_h(&state.pressure), at_h(&theirs));
            eprintln!(
                "H {hardness} p {mean_pressure}: area {} vs {} ({:+.3} %), at H {pa} vs {pb}, {} iterations",
                a / cells,
                b / cells,
                100.0 * (a / b - 1.0),
                report.iterations
            );
            assert!(
                (a / b - 1.0).abs() < 0.005,
                "H {hardness} p {mean_pressure}: area {a} vs {b}"
            );
            assert!(
                (pa - pb).abs() <= (0.01 * pb).max(3.0),
                "H {hardness} p {mean_pressure}: cells at H {pa} vs {pb}"
            );
            assert_eq!(report.yielding.plastic_area_fraction, pa / cells);
        }
    }
}
