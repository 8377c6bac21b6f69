//! Agreement with an independent implementation of tangential contact: Tamaas 2.9's
//! `PolonskyKeerTan` on the same surface, load and friction (data/tamaas-tangential-256, see
//! its README).

use ndarray::Array2;
use solver::{
    ContactOptions, ContactProblem, Control, Friction, ShearOptions, ShearState, TangentialControl,
};
use std::path::{Path, PathBuf};
use surfgen::io::{ReadOptions, read};

const MU: f64 = 0.3;
const MEAN_PRESSURE: f64 = 0.05;

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../data/tamaas-tangential-256")
}

fn load(name: &str) -> Array2<f64> {
    read(
        &dir().join(name),
        &ReadOptions {
            length_x: Some(1.0),
            ..Default::default()
        },
    )
    .unwrap()
    .heights
}

/// Tamaas's stick cells at each ratio, from its results.
fn tamaas_stick() -> Vec<(f64, usize)> {
    std::fs::read_to_string(dir().join("tamaas_results.jsonl"))
        .unwrap()
        .lines()
        .map(|line| {
            let v: serde_json::Value = serde_json::from_str(line).unwrap();
            (
                v["ratio"].as_f64().unwrap(),
                v["stick"].as_u64().unwrap() as usize,
            )
        })
        .collect()
}

#[test]
fn same_stick_zone_and_shear_as_tamaas() {
    let h = load("surface.npy");
    let n = h.nrows();
    let problem = ContactProblem::builder()
        .roughness(h, 1.0, 1.0)
        .modulus(4.0 / 3.0)
        .poisson(0.5)
        .friction(Friction::new(MU, 0.0).unwrap())
        .build()
        .unwrap();
    let (normal, _) = problem
        .solve_without_adhesion(
            Control::MeanPressure(MEAN_PRESSURE),
            &ContactOptions::default(),
            None,
            &mut (),
        )
        .unwrap();
    let tangential = problem.tangential(&normal).unwrap();
    // The static friction is mu times the load.
    assert!((tangential.capacity() - MU * MEAN_PRESSURE).abs() < 1e-12);
    let expected = tamaas_stick();
    assert_eq!(expected.len(), 4);
    for (ratio, tamaas) in expected {
        let q = ratio * MU * MEAN_PRESSURE;
        let (state, report) = tangential
            .solve(
                TangentialControl::Force([q, 0.0]),
                &ShearState::unloaded((n, n)),
                &ShearOptions::default(),
            )
            .unwrap();
        assert!(report.termination == solver::report::Termination::Converged);
        let stick = (report.stick_area_fraction * (n * n) as f64).round() as usize;
        assert!(
            stick.abs_diff(tamaas) as f64 <= 0.01 * tamaas as f64,
            "Q/muP {ratio}: {stick} stick cells, Tamaas {tamaas}"
        );
        if dir().join(format!("tamaas_shear_x_{ratio}.npy")).exists() {
            let largest = state.traction[0].iter().fold(0.0f64, |m, v| m.max(v.abs()));
            for (c, axis) in ["x", "y"].iter().enumerate() {
                let reference = load(&format!("tamaas_shear_{axis}_{ratio}.npy"));
                let worst = (&state.traction[c] - &reference)
                    .iter()
                    .fold(0.0f64, |m, v| m.max(v.abs()));
                assert!(
                    worst < 3e-3 * largest,
                    "Q/muP {ratio}, shear {axis}: {:e} of the largest",
                    worst / largest
                );
            }
        }
    }
}
