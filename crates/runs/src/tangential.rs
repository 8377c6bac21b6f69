//! A tangential path after a normal solve: its steps into `tangential.csv`, the last step's
//! shear and slip as fields, its summary into `summary.json`.

use crate::run::{RunDir, on_workers};
use crate::{note, say};
use anyhow::Result;
use serde_json::{Value, json};
use solver::{ContactProblem, Normal, ShearOptions, TangentialControl, TangentialPath, TangentialSummary};

/// The columns of `tangential.csv`.
pub const HEADER: &str = "step,force_x,force_y,displacement_x,displacement_y,stick_area_fraction,\
slip_area_fraction,frictional_work,elastic_energy,gross_sliding,normal_load,approach,\
coupling_iterations,iterations,residual,converged,wall_time_s";

/// Runs `controls` on the `normal` solution of `problem`, writing into `run`; returns the
/// summary's `tangential` object and whether every step converged.
pub fn run(
    problem: &ContactProblem,
    normal: Normal,
    controls: &[TangentialControl],
    run: &RunDir,
) -> Result<(Value, bool)> {
    let options = ShearOptions::default();
    let total = controls.len();
    let TangentialPath {
        shear: state,
        reports,
        ..
    } = on_workers(|| {
        problem.tangential_path(normal, controls, &options, &mut |k, _, r| {
            crate::note_unchecked!(
                "tangential step {}/{total}: force ({:.4e}, {:.4e}) N, stick area fraction {:.4}{}",
                k + 1,
                r.force[0],
                r.force[1],
                r.stick_area_fraction,
                if r.gross_sliding { ", sliding" } else { "" }
            );
            true
        })
    })?;
    let mut csv = format!("{HEADER}\n");
    for (k, r) in reports.iter().enumerate() {
        csv += &format!(
            "{k},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{:e},{:e},{},{},{:e},{},{:.3}\n",
            r.force[0],
            r.force[1],
            r.displacement[0],
            r.displacement[1],
            r.stick_area_fraction,
            r.slip_area_fraction,
            r.frictional_work,
            r.elastic_energy,
            r.gross_sliding,
            r.normal_load,
            r.approach,
            r.coupling_iterations,
            r.iterations,
            r.residual,
            r.termination == solver::report::Termination::Converged,
            r.wall_time_s
        );
    }
    crate::output::text(&run.path().join("tangential.csv"), &csv)?;
    for (name, field) in [
        ("shear_x", &state.traction[0]),
        ("shear_y", &state.traction[1]),
        ("slip_x", &state.slip[0]),
        ("slip_y", &state.slip[1]),
    ] {
        run.write_field(name, field)?;
    }
    let summary = TangentialSummary::of(&reports);
    if reports.len() < total {
        note!(
            "the tangential path ended at step {} of {total}: the force exceeds the most the contact carries, {:.4e} N (it slides)",
            reports.len(),
            summary.static_friction
        );
    }
    say!("static friction force    {:.6e} N", summary.static_friction);
    say!(
        "friction's work          {:.6e} J over {} tangential steps",
        summary.frictional_work,
        reports.len()
    );
    if let Some(last) = reports.last() {
        say!("last stick area fraction {:.6}", last.stick_area_fraction);
    }
    let mut value = serde_json::to_value(&summary)?;
    if let Value::Object(map) = &mut value {
        map.insert("steps".into(), json!(reports.len()));
        map.insert(
            "units".into(),
            json!({
                "static_friction": "N", "frictional_work": "J", "work": "J",
                "shear_x.npy": "Pa", "shear_y.npy": "Pa", "slip_x.npy": "m", "slip_y.npy": "m",
                "tangential.csv": "force N, displacement m, work and energy J"
            }),
        );
    }
    Ok((value, summary.all_converged))
}
