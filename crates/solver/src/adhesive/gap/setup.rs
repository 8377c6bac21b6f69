//! The gap problem set up from a solve's job at its first admissible point (cold or warm), and
//! the state and report made from its solution.

use super::{Energy, GradientSums, Point, Problem, Stiffness};
use crate::adhesive::job::{Job, Outcome, assemble, cells};
use crate::adhesive::{AdhesiveReport, AdhesiveState, Start};
use crate::error::{Result, SolverError, invalid};
use crate::options::Control;
use crate::state::ContactState;
use elastic::{FreeStiffness, PeriodicStiffness};
use ndarray::{Array2, Zip, s};

/// Refuses, for the solver `name`, the controls the gap problem does not take: loads and
/// central gaps on free domains, central gaps anywhere.
pub(in crate::adhesive) fn check_control(job: &Job, name: &str) -> Result<()> {
    if !job.op.domain().periodic && !matches!(job.control, Control::Approach(_)) {
        return Err(SolverError::Unsupported(format!(
            "{name} on a free domain takes the approach only (use `accelerated` for loads and \
             central gaps)"
        )));
    }
    if let Control::CentralGap(g) = job.control {
        return Err(invalid(
            "central_gap",
            g,
            format!("{name} takes the approach (or mean gap), the load or the mean pressure"),
        ));
    }
    Ok(())
}

/// A problem over the gap, set up from a solve's arguments, at its first admissible point.
pub(in crate::adhesive) struct Setup<'a> {
    pub(in crate::adhesive) problem: Problem<'a>,
    /// The first admissible point, evaluated (its gradient not yet projected).
    pub(in crate::adhesive) x: Point,
    /// The approach \[m\] (approach control; else 0).
    pub(in crate::adhesive) delta: f64,
    /// The mean pressure \[Pa\] (load control; else `None`).
    pub(in crate::adhesive) load: Option<f64>,
}

/// Sets up the problem over the gap (or the padded displacement, free) under approach control
/// (`Control::Approach`) or, periodic only, load control (`Control::Force`,
/// `Control::MeanPressure`), with the law's `energy` if it has one; see the module docs.
pub(in crate::adhesive) fn setup<'a>(job: &Job<'a>, energy: Energy<'a>) -> Result<Setup<'a>> {
    let (op, law, g0, settings) = (job.op, job.law, job.g0, job.settings);
    let (control, start) = (job.control, job.start);
    let domain = *op.domain();
    let shape = domain.shape();
    let (ny, nx) = shape;
    let n = (nx * ny) as f64;
    let cells = cells(&domain);
    let (delta, load) = match control {
        Control::Approach(d) => (d, None),
        Control::MeanPressure(p) => (0.0, Some(p)),
        Control::Force(w) => (0.0, Some(w / (n * domain.cell_area()))),
        Control::CentralGap(_) => unreachable!("refused by the caller"),
    };
    let mean_gap = g0.mean().unwrap_or(0.0) - delta;
    if domain.periodic && load.is_none() && mean_gap <= 0.0 {
        return Err(invalid(
            "approach",
            delta,
            "reaches the mean initial gap: a periodic surface is in full contact before that",
        ));
    }
    // The problem on `stiffness` over the unknown whose undeformed value is `base` (the gap, or
    // free, the padded displacement's base), its mean gap or load prescribed or not. The
    // cells' energies of a field energy are kept; a probe's buffers are made when first needed.
    let problem = |stiffness, ws, base: Array2<f64>, (mean_gap, load)| {
        let energies = if matches!(energy, Energy::Field(_)) {
            shape
        } else {
            (0, 0)
        };
        let (my, mx) = base.dim();
        Problem {
            ws,
            stiffness,
            energy,
            law,
            cells,
            domain,
            probe: (Array2::zeros(energies), Array2::zeros((0, 0))),
            closed: Array2::zeros((0, 0)),
            couple: false,
            base,
            mx,
            my,
            nx,
            ny,
            mean_gap,
            load,
            cap: job.interface.cap(),
            calls: 0,
            diagonal: 0.0,
            split: None,
        }
    };
    let (mut problem, first, hold) = if domain.periodic {
        let stiffness = PeriodicStiffness::of(op)?;
        let first = match start {
            // A first step from the rigid overlap (or, under load control, where the rigid
            // shift has no elastic stiffness, from a point contact) would snap far more of
            // the surface in than a quasi-static approach does: start from the non-adhesive
            // contact at the same compressive load or approach instead.
            Start::Loading => {
                let non_adhesive = |control| {
                    let interface = &job.interface;
                    let options = &settings.contact;
                    crate::cg::solve_relative(op, g0, interface, control, options, None, &mut ())
                        .map(|(s, _)| signed_gap(s))
                };
                match load {
                    Some(p) if p > 0.0 => non_adhesive(Control::MeanPressure(p))?,
                    None if delta > 0.0 => non_adhesive(Control::Approach(delta))?,
                    _ => g0.mapv(|g| (g - delta).max(0.0)),
                }
            }
            Start::Unloading => Array2::zeros(shape),
            Start::Warm(s) => s.contact.gap.clone(),
        };
        let ws = stiffness.make_workspace();
        let problem = problem(
            Stiffness::Periodic(stiffness),
            ws,
            g0.to_owned(),
            (load.is_none().then_some(mean_gap), load),
        );
        // A warm start keeps its attached cells (gap within the law's range) in place and
        // moves only the rest: a uniform shift would tear the attached rim off at once (or
        // press cells into attraction on loading), and the descent would settle in that
        // state's basin rather than follow the branch; from the held guess the descent itself
        // decides what peels off.
        let hold = matches!(start, Start::Warm(_)).then(|| law.range());
        (problem, first, hold)
    } else {
        let stiffness = FreeStiffness::of(op)?;
        let padded = stiffness.padded_shape();
        let mut ws = stiffness.make_workspace();
        let mut base = Array2::zeros(padded);
        base.slice_mut(s![..ny, ..nx]).assign(&g0.mapv(|g| g - delta));
        // The first guess: the base (no displacement) from scratch; a warm start keeps the old
        // displacement, with its attached cells held at their old gaps (as on periodic grids).
        let mut first = Array2::zeros(padded);
        match start {
            Start::Loading => first.assign(&base.mapv(|b| b.max(0.0))),
            Start::Unloading => {}
            Start::Warm(s) => {
                let total = &s.contact.pressure + &s.adhesive_pressure;
                stiffness.displacement(total.view(), first.view_mut(), &mut ws)?;
                first += &base;
                let range = law.range();
                Zip::from(first.slice_mut(s![..ny, ..nx]))
                    .and(&s.contact.gap)
                    .for_each(|f, &old| {
                        if old <= range {
                            *f = old;
                        }
                    });
            }
        }
        let problem = problem(Stiffness::Free(stiffness), ws, base, (None, None));
        (problem, first, None)
    };
    let unknown = first.dim();
    {
        // The stiffness is a convolution: its diagonal is the response to a unit impulse.
        let mut impulse = Array2::zeros(unknown);
        impulse[(0, 0)] = 1.0;
        let mut response = Array2::zeros(unknown);
        problem
            .stiffness
            .apply(impulse.view(), response.view_mut(), &mut problem.ws)?;
        problem.diagonal = response[(0, 0)];
        problem.calls += 1;
    }
    let mut x = Point::new(Array2::zeros(unknown));
    problem.step_and_project(&first, &first, 0.0, &mut x.gap, hold);
    drop(first);
    problem.evaluate(&mut x)?;
    Ok(Setup {
        problem,
        x,
        delta,
        load,
    })
}

/// The gap of a non-adhesive state less its permanent set: negative where the surface yielded
/// in that solve (the gap of the unknown, [`super`]'s module docs).
fn signed_gap(state: ContactState) -> Array2<f64> {
    match state.permanent_set {
        Some(set) => state.gap - set,
        None => state.gap,
    }
}

/// The state and report at the solution `x`, whose gradient `sums` describe (see [`setup`]
/// for `delta` and `load`); `outcome`'s operator calls are replaced by the problem's count.
pub(in crate::adhesive) fn finish(
    job: &Job,
    problem: &Problem,
    x: Point,
    sums: &GradientSums,
    at: (f64, Option<f64>),
    mut outcome: Outcome,
) -> (AdhesiveState, AdhesiveReport) {
    let AdhesiveState {
        contact,
        adhesive_pressure,
    } = state(job, problem, x, sums, at);
    outcome.operator_calls = problem.calls;
    assemble(job, contact, adhesive_pressure, outcome)
}

/// The state at the point `x`, whose gradient `sums` describe (see [`setup`] for `delta` and
/// `load`): the start another method takes from this one.
pub(in crate::adhesive) fn state(
    job: &Job,
    problem: &Problem,
    x: Point,
    sums: &GradientSums,
    (delta, load): (f64, Option<f64>),
) -> AdhesiveState {
    let g0 = job.g0;
    let domain = problem.domain;
    let shape = domain.shape();
    let (ny, nx) = shape;
    // The mean pressure: prescribed, or minus the multiplier of the mean gap (free: none).
    let mean_pressure = load.unwrap_or(-sums.lambda);
    let block = s![..ny, ..nx];
    let (gap, elastic, law_pressure) = if domain.periodic {
        (x.gap, x.elastic, x.law)
    } else {
        let take = |a: &Array2<f64>| a.slice(block).to_owned();
        (take(&x.gap), take(&x.elastic), take(&x.law))
    };
    // Contact pressure where the gap is closed: the gradient's elastic and adhesive part plus
    // the mean pressure, at most the hardness (held at it where the surface yielded).
    let cap = problem.cap;
    let mut pressure = Array2::zeros(shape);
    Zip::from(&mut pressure)
        .and(&gap)
        .and(&elastic)
        .and(&law_pressure)
        .par_for_each(|p, &g, &e, &l| {
            *p = if g < 0.0 {
                cap
            } else if g == 0.0 {
                (e - l + mean_pressure).clamp(0.0, cap)
            } else {
                0.0
            }
        });
    // Periodic: the mean displacement is zero. Free: the base is `g0 - delta`.
    let mut displacement = &gap - &problem.base.slice(block);
    if domain.periodic {
        let mean = displacement.mean().unwrap_or(0.0);
        displacement.mapv_inplace(|u| u - mean);
    }
    let approach = match load {
        None => delta,
        Some(_) => g0.mean().unwrap_or(0.0) - gap.mean().unwrap_or(0.0),
    };
    // A yielded cell's gap is closed: its overlap joins the permanent set when the solve
    // settles ([`crate::interface::settle`]).
    let mut gap = gap;
    gap.mapv_inplace(|g| g.max(0.0));
    let contact = ContactState {
        pressure,
        gap,
        displacement,
        approach,
        permanent_set: None,
        history: None,
    };
    AdhesiveState {
        contact,
        adhesive_pressure: law_pressure,
    }
}
