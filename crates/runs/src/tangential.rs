//! A tangential path after a normal solve: a row of `tangential.csv` as each step finishes, the
//! last step's shear and slip as fields, its summary into `summary.json`. After every step the
//! path's state (shear, slip, the rows so far and, when coupled, the normal contact under the
//! shear) is saved in `tangential_state/`, so that `solve --resume` goes on from there.

use crate::run::{RunDir, on_workers, read_fields, saved as saved_dir, write_fields};
use crate::{note, say};
use anyhow::{Context, Result, bail};
use ndarray::Array2;
use serde_json::{Value, json};
use solver::report::Termination;
use solver::{
    AdhesiveState, ContactProblem, ContactState, Normal, NormalState, Reached, ShearOptions, ShearReport,
    ShearState, TangentialControl, TangentialPath, TangentialSummary,
};
use std::io::Write;

/// The columns of `tangential.csv`.
pub const HEADER: &str = "step,force_x,force_y,displacement_x,displacement_y,capacity,\
stick_area_fraction,slip_area_fraction,frictional_work,elastic_energy,gross_sliding,normal_load,\
approach,coupling_iterations,iterations,residual,converged,wall_time_s";

/// The directory of the path's saved state.
pub const STATE: &str = "tangential_state";

/// Runs `controls` on the `normal` solution of `problem`, writing into `run`, from the saved
/// state of an interrupted path when `resume`; returns the summary's `tangential` object and
/// whether every step converged.
pub fn run(
    problem: &ContactProblem,
    normal: Normal,
    controls: &[TangentialControl],
    run: &RunDir,
    resume: bool,
) -> Result<(Value, bool)> {
    let options = ShearOptions::default();
    let total = controls.len();
    let out = run.path();
    let (mut rows, reached) = match saved_dir(&out.join(STATE)).filter(|_| resume) {
        Some(dir) => saved(&dir, &normal.state)?,
        None => (Vec::new(), None),
    };
    if rows.len() > total {
        bail!(
            "--resume: {} holds {} tangential steps, more than this path's {total}",
            out.join(STATE).display(),
            rows.len()
        );
    }
    let csv_path = out.join("tangential.csv");
    crate::output::text(
        &csv_path,
        &format!(
            "{HEADER}\n{}",
            rows.iter().map(|r| format!("{r}\n")).collect::<String>()
        ),
    )?;
    let mut reports = rows.iter().map(|r| parse(r)).collect::<Result<Vec<_>>>()?;
    let done = reports.len();
    let ended = reports.last().is_some_and(|r: &ShearReport| {
        r.gross_sliding && matches!(controls[done - 1], TangentialControl::Force(_))
    });
    if done > 0 {
        note!("resuming the tangential path after {done} of {total} steps");
    }
    let coupled = problem.counterface == solver::Counterface::Rigid;
    let mut csv = std::fs::OpenOptions::new()
        .append(true)
        .open(&csv_path)
        .with_context(|| format!("opening {}", csv_path.display()))?;
    let mut failure = None;
    let path = if ended || done == total {
        let Reached { shear, normal: under } = reached.context("a resumed path without its state")?;
        TangentialPath {
            shear,
            reports: Vec::new(),
            normal: under,
        }
    } else {
        on_workers(|| {
            problem.tangential_path(
                normal,
                reached,
                &controls[done..],
                &options,
                &mut |k, shear, under, r| {
                    let k = done + k;
                    crate::note_unchecked!(
                        "tangential step {}/{total}: force ({:.4e}, {:.4e}) N, stick area fraction {:.4}{}",
                        k + 1,
                        r.force[0],
                        r.force[1],
                        r.stick_area_fraction,
                        if r.gross_sliding { ", sliding" } else { "" }
                    );
                    rows.push(row(k, r));
                    // The state first, then its row: a path killed between the two finds the row
                    // in the state's manifest.
                    let saved = save(&out.join(STATE), &rows, shear, coupled.then_some(under))
                        .and_then(|()| Ok(writeln!(csv, "{}", rows[k]).and_then(|()| csv.flush())?));
                    if let Err(e) = saved {
                        failure = Some(e);
                        return false;
                    }
                    true
                },
            )
        })?
    };
    if let Some(e) = failure {
        return Err(e);
    }
    reports.extend(path.reports);
    let state = path.shear;
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
                "tangential.csv": "force N, displacement m, capacity N, work and energy J, normal load N, approach m"
            }),
        );
    }
    Ok((value, summary.all_converged))
}

/// Step `k`'s row of `tangential.csv`: every number in its shortest exact form, so that a
/// resumed path reads back the reports it wrote.
fn row(k: usize, r: &ShearReport) -> String {
    format!(
        "{k},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{:e},{},{:e},{:e},{},{},{:e},{},{:.3}",
        r.force[0],
        r.force[1],
        r.displacement[0],
        r.displacement[1],
        r.capacity,
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
        r.termination == Termination::Converged,
        r.wall_time_s
    )
}

/// The report a row of `tangential.csv` holds.
fn parse(line: &str) -> Result<ShearReport> {
    let cells: Vec<&str> = line.split(',').collect();
    if cells.len() != HEADER.split(',').count() {
        bail!("a tangential.csv row of {} columns: {line}", cells.len());
    }
    let f = |k: usize| -> Result<f64> { cells[k].parse().with_context(|| format!("column {k} of {line}")) };
    let n = |k: usize| -> Result<usize> { cells[k].parse().with_context(|| format!("column {k} of {line}")) };
    let b = |k: usize| -> Result<bool> { cells[k].parse().with_context(|| format!("column {k} of {line}")) };
    Ok(ShearReport {
        force: [f(1)?, f(2)?],
        displacement: [f(3)?, f(4)?],
        capacity: f(5)?,
        stick_area_fraction: f(6)?,
        slip_area_fraction: f(7)?,
        frictional_work: f(8)?,
        elastic_energy: f(9)?,
        gross_sliding: b(10)?,
        normal_load: f(11)?,
        approach: f(12)?,
        coupling_iterations: n(13)?,
        iterations: n(14)?,
        residual: f(15)?,
        termination: if b(16)? {
            Termination::Converged
        } else {
            Termination::MaxIterations
        },
        wall_time_s: f(17)?,
    })
}

/// Saves the path's state after its last row: the shear and slip, and the normal contact under
/// them when it moves with them.
fn save(
    dir: &std::path::Path,
    rows: &[String],
    shear: &ShearState,
    under: Option<&NormalState>,
) -> Result<()> {
    let mut fields = vec![
        ("shear_x".to_string(), &shear.traction[0]),
        ("shear_y".to_string(), &shear.traction[1]),
        ("slip_x".to_string(), &shear.slip[0]),
        ("slip_y".to_string(), &shear.slip[1]),
    ];
    let mut manifest = json!({ "rows": rows });
    if let Some(under) = under {
        let contact = under.contact();
        fields.extend([
            ("normal_pressure".to_string(), &contact.pressure),
            ("normal_gap".to_string(), &contact.gap),
            ("normal_displacement".to_string(), &contact.displacement),
        ]);
        fields.extend(
            contact
                .permanent_set
                .as_ref()
                .map(|s| ("normal_plastic".to_string(), s)),
        );
        if let NormalState::Adhesive(a) = under {
            fields.push(("normal_adhesive_pressure".to_string(), &a.adhesive_pressure));
        }
        manifest["normal_approach"] = contact.approach.into();
    }
    write_fields(dir, &fields, manifest)
}

/// The rows and state an interrupted path saved in `dir`; `normal` is the path's starting
/// normal solution (the normal contact of a decoupled path, and the kind of a coupled one's).
fn saved(dir: &std::path::Path, normal: &NormalState) -> Result<(Vec<String>, Option<Reached>)> {
    let saved = read_fields(dir)?;
    let (manifest, read) = (&saved.manifest, |name: &str| saved.read(name));
    let rows: Vec<String> = manifest["rows"]
        .as_array()
        .context("a tangential state without its rows")?
        .iter()
        .map(|r| r.as_str().map(str::to_string).context("a row that is not text"))
        .collect::<Result<_>>()?;
    let Some(last) = rows.last() else {
        return Ok((rows, None));
    };
    let last = parse(last)?;
    let shear = ShearState {
        traction: [read("shear_x")?, read("shear_y")?],
        slip: [read("slip_x")?, read("slip_y")?],
        displacement: last.displacement,
        force: last.force,
    };
    let under = match manifest["normal_approach"].as_f64() {
        None => normal.clone(),
        Some(approach) => {
            let plastic = |name: &str| -> Result<Option<Array2<f64>>> {
                match manifest["fields"].get(name) {
                    Some(_) => Ok(Some(read(name)?)),
                    None => Ok(None),
                }
            };
            let contact = ContactState {
                pressure: read("normal_pressure")?,
                gap: read("normal_gap")?,
                displacement: read("normal_displacement")?,
                approach,
                permanent_set: plastic("normal_plastic")?,
                history: None,
            };
            match normal {
                NormalState::WithoutAdhesion(_) => NormalState::WithoutAdhesion(contact),
                NormalState::Adhesive(_) => NormalState::Adhesive(AdhesiveState {
                    contact,
                    adhesive_pressure: read("normal_adhesive_pressure")?,
                }),
            }
        }
    };
    Ok((rows, Some(Reached { shear, normal: under })))
}
