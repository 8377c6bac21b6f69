//! A layer on a rigid base against an independent implementation: ContactMechanics'
//! finite-thickness periodic half-space on the same rough surface at two thicknesses and two
//! loads (data/contactmechanics-layer-256, see its README).

use elastic::{Base, Layer};
use ndarray::Array2;
use solver::{ContactOptions, ContactProblem, Control};
use std::path::{Path, PathBuf};

fn data(dir: &str, name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../data")
        .join(dir)
        .join(name)
}

#[test]
fn contact_areas_on_a_layer_match_contactmechanics() {
    let h: Array2<f64> = ndarray_npy::read_npy(data("contactmechanics-plastic-256", "surface.npy")).unwrap();
    let rows: Vec<serde_json::Value> = serde_json::from_str(
        &std::fs::read_to_string(data("contactmechanics-layer-256", "cm_layer.json")).unwrap(),
    )
    .unwrap();
    assert_eq!(rows.len(), 4);
    let options = ContactOptions {
        tolerance: 1e-10,
        ..ContactOptions::default()
    };
    for row in rows {
        let number = |key: &str| row[key].as_f64().unwrap();
        let (thickness, nu, young) = (number("thickness"), number("poisson"), number("young"));
        let mean_pressure = number("mean_pressure");
        let problem = ContactProblem::builder()
            .roughness(h.clone(), 1.0, 1.0)
            .modulus(young / (1.0 - nu * nu))
            .layer(Layer::new(thickness, nu, Base::Bonded).unwrap())
            .build()
            .unwrap();
        let (state, report) = problem
            .solve_without_adhesion(Control::MeanPressure(mean_pressure), &options, None, &mut ())
            .unwrap();
        assert!(
            report.converged(),
            "h {thickness} p {mean_pressure}: {:?}",
            report.termination
        );
        let ours = state.pressure.iter().filter(|&&p| p > 0.0).count() as f64;
        let theirs = number("contact_cells");
        eprintln!(
            "h {thickness} p {mean_pressure:.4e}: {ours} vs {theirs} contact cells ({:+.3} %), {} iterations",
            100.0 * (ours / theirs - 1.0),
            report.iterations
        );
        assert!(
            (ours / theirs - 1.0).abs() < 0.005,
            "h {thickness} p {mean_pressure}: {ours} vs {theirs}"
        );
    }
}

#[test]
fn a_coating_on_its_own_material_is_the_half_space_and_on_a_rigid_one_the_bonded_layer() {
    // The same surface and loads: a coating on a substrate of its own material finds the
    // half-space's contact, one on a substrate a million times stiffer the bonded layer's.
    let h: Array2<f64> = ndarray_npy::read_npy(data("contactmechanics-plastic-256", "surface.npy")).unwrap();
    let (e_star, nu, thickness) = (1e9 / 0.91, 0.3, 1.0 / 16.0);
    let solve = |base: Option<Base>, share: f64| {
        let mut builder = ContactProblem::builder()
            .roughness(h.clone(), 1.0, 1.0)
            .modulus(e_star);
        if let Some(base) = base {
            builder = builder.layer(Layer::new(thickness, nu, base).unwrap());
        }
        let problem = builder.build().unwrap();
        let options = ContactOptions {
            tolerance: 1e-10,
            ..ContactOptions::default()
        };
        let (state, report) = problem
            .solve_without_adhesion(Control::MeanPressure(share * e_star), &options, None, &mut ())
            .unwrap();
        assert!(report.converged());
        state.pressure
    };
    let cells = |p: &Array2<f64>| p.iter().filter(|&&v| v > 0.0).count();
    for share in [0.005, 0.02] {
        let same = solve(Some(Base::Substrate { e_star, poisson: nu }), share);
        let half = solve(None, share);
        let worst = (&same - &half).iter().fold(0.0f64, |m, v| m.max(v.abs()));
        let peak = half.iter().fold(0.0f64, |m, v| m.max(*v));
        // Both solved to the tolerance 1e-10 of the gap residual.
        assert!(worst < 1e-7 * peak, "{worst} of {peak}");
        assert_eq!(cells(&same), cells(&half));
        let stiff = solve(
            Some(Base::Substrate {
                e_star: 1e6 * e_star,
                poisson: 0.2,
            }),
            share,
        );
        let bonded = solve(Some(Base::Bonded), share);
        assert_eq!(cells(&stiff), cells(&bonded), "p {share} E*");
    }
}
