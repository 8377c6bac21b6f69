//! Agreement with an independent implementation: Tamaas 2.9 on the same surface and load
//! (data/tamaas-512, see its README).

use elastic::{Domain, Periodic};
use ndarray::Array2;
use solver::geometry::flat_on_rough;
use solver::{ContactOptions, Control, solve};
use std::path::Path;
use surfgen::io::{ReadOptions, read};

fn load(name: &str) -> Array2<f64> {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data/tamaas-512")
        .join(name);
    read(
        &path,
        &ReadOptions {
            length_x: Some(1.0),
            ..Default::default()
        },
    )
    .unwrap()
    .heights
}

#[test]
fn same_contact_set_as_tamaas_pixel_for_pixel() {
    let h = load("surface.npy");
    let reference = load("tamaas_pressure.npy");
    let n = h.nrows();
    let dom = Domain {
        nx: n,
        ny: n,
        dx: 1.0 / n as f64,
        dy: 1.0 / n as f64,
        periodic: true,
    };
    let op = Periodic::new(dom, 1.0).unwrap();
    let g0 = flat_on_rough(h.view()).unwrap();
    let opts = ContactOptions {
        tolerance: 1e-10,
        ..Default::default()
    };
    let (state, rep) = solve(&op, g0.view(), Control::MeanPressure(0.04), &opts, None).unwrap();
    assert!(rep.converged());
    let differ = state
        .pressure
        .iter()
        .zip(reference.iter())
        .filter(|(a, b)| (**a > 0.0) != (**b > 0.0))
        .count();
    assert_eq!(differ, 0, "cells in contact in one solution only");
    let pmax = reference.iter().cloned().fold(0.0, f64::max);
    let worst = state
        .pressure
        .iter()
        .zip(reference.iter())
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(
        worst < 1e-6 * pmax,
        "largest pressure difference {:e} of the maximum",
        worst / pmax
    );
}
