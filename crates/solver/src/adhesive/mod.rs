//! Adhesive contact: what the five methods share (`docs/method.md` section 4 for the physics,
//! `docs/solvers.md` for the methods).
//!
//! The pressure is split into a compressive part `p_c >= 0` (the contact constraint) and an
//! adhesive part `p_a <= 0` (the law). The rooms:
//!
//! - `state`, `report`: what a solve gives (public), `job`: what a method is given, the trait
//!   `AdhesiveMethod` it implements and the report it assembles; `driver`: the iteration loop's
//!   limits, stalls and observer, shared by every method.
//! - the methods, a file or folder each: the dual loops (`dual_loop`, with its Anderson
//!   mixing), the energy descent (`energy`), Newton (`newton`, with its GMRES) and the damped
//!   relaxation (`flow`, with its far field). The last three work on the gap problem of `gap`
//!   (the system, its stiffness, the row-coupled preconditioner, the set-up); they compose
//!   through small calls: Newton's `polish` finishes the flow's crawl, the energy descent
//!   predicts Newton's start.
//! - here: the dispatch. `solve` checks the input, resolves [`Method::Auto`], asks the
//!   method whether it can solve the problem, and runs it.

mod driver;
mod dual_loop;
mod energy;
mod flow;
mod gap;
mod job;
mod newton;
pub(crate) mod report;
pub(crate) mod state;

pub use report::{AdhesiveReport, Iterations};
pub use state::{AdhesiveState, Start};

use crate::error::{Result, SolverError, invalid};
use crate::interface::Interface;
use crate::mean_mode::{MeanMode, Solved, Trial};
use crate::method::{Method, Settings};
use crate::options::Control;
use elastic::Compliance;
use job::{AdhesiveMethod, Job};
use ljadhesion::AdhesionLaw;
use ndarray::ArrayView2;

/// The implementation of each method, from the table of methods (`Auto` is resolved before
/// the dispatch; as a fallback it is the accelerated loop).
macro_rules! dispatch {
    ($($(#[$meta:meta])* $variant:ident = $name:literal => $implementation:expr,)*) => {
        fn implementation(method: Method) -> &'static dyn AdhesiveMethod {
            match method {
                $(Method::$variant => &$implementation,)*
            }
        }
    };
}
crate::method::adhesive_methods!(dispatch);

/// Roughly the peak memory \[bytes\] a solve by `method` takes on a grid of `cells` cells
/// ([`AdhesiveMethod::peak_bytes`]); `Auto` counts as the largest, Newton.
pub(crate) fn peak_bytes(method: Method, cells: f64, periodic: bool) -> f64 {
    let method = if method == Method::Auto {
        Method::Newton
    } else {
        method
    };
    implementation(method).peak_bytes(cells, periodic)
}

/// The body, the law and the initial gap of a problem ([`crate::ContactProblem`]).
#[derive(Clone, Copy)]
pub(crate) struct Parts<'a> {
    pub op: &'a dyn Compliance,
    pub law: &'a dyn AdhesionLaw,
    pub interface: Interface,
    pub g0: ArrayView2<'a, f64>,
}

/// Solves the problem of `parts` under `control` (see [`crate::ContactProblem::solve`]).
pub(crate) fn solve(
    parts: Parts,
    control: Control,
    settings: &Settings,
    start: Start,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<(AdhesiveState, AdhesiveReport)> {
    let Some(mean) = MeanMode::of(parts.op) else {
        return solve_relative(parts, control, settings, start, observer);
    };
    // The methods' frame: the approach from the mean surface (crate::mean_mode).
    let mean_of = |s: &AdhesiveState| s.total_pressure().mean().unwrap_or(0.0);
    let warm = match start {
        Start::Warm(w) => {
            let mut w = w.clone();
            let p_mean = mean_of(&w);
            mean.shift(&mut w.contact, p_mean, -1.0);
            Some(w)
        }
        _ => None,
    };
    let start = warm.as_ref().map_or(start, Start::Warm);
    let area = parts.op.domain().cell_area() * parts.g0.len() as f64;
    let to_base = |(mut state, mut report): (AdhesiveState, AdhesiveReport)| {
        let p = report.mean_pressure;
        report.approach += mean.shift(&mut state.contact, p, 1.0);
        report.elastic_energy += 0.5 * parts.op.mean_compliance() * p * p * area;
        (state, report)
    };
    let Control::Approach(delta) = control else {
        return solve_relative(parts, control, settings, start, observer).map(to_base);
    };
    // Each trial starts from the caller's permanent set, seeded by the last trial's fields.
    let before = warm.as_ref().and_then(|w| w.contact.permanent_set.clone());
    let guess = warm.as_ref().map_or(0.0, mean_of);
    let bounds = (
        parts.g0.mean().unwrap_or(0.0),
        parts.interface.hardness.unwrap_or(f64::INFINITY),
    );
    // The approach's tolerance: relative to the law's range, or without adhesion (whose range
    // means nothing) to the mean initial gap.
    let length = if parts.law.work_of_adhesion() > 0.0 || bounds.0 <= 0.0 {
        parts.law.range()
    } else {
        bounds.0
    };
    // Approach trials below the mean gap: they follow the branches loads cannot.
    let solution = mean.approach(
        delta,
        guess,
        bounds,
        settings.tolerance * length,
        |control, last: Option<&(AdhesiveState, AdhesiveReport)>| {
            let seed = last.map(|(s, _)| {
                let mut s = s.clone();
                s.contact.permanent_set = before.clone();
                s
            });
            let from = seed.as_ref().map_or(start, Start::Warm);
            solve_relative(parts, control, settings, from, observer)
        },
    )?;
    Ok(to_base(solution))
}

/// [`solve`] in the methods' frame: on a periodic body with a mean compliance, the approach
/// is measured from the mean surface ([`crate::mean_mode`]).
fn solve_relative(
    parts: Parts,
    control: Control,
    settings: &Settings,
    start: Start,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<(AdhesiveState, AdhesiveReport)> {
    let Parts {
        op,
        law,
        interface,
        g0,
    } = parts;
    interface.validate()?;
    interface.check_law(law)?;
    let shape = op.domain().shape();
    // The methods work on contiguous rows: any other layout is copied into one here.
    let g0 = g0.as_standard_layout();
    let g0 = g0.view();
    if g0.dim() != shape {
        return Err(SolverError::ShapeMismatch {
            what: "initial gap",
            expected: shape,
            got: g0.dim(),
        });
    }
    settings.validate()?;
    let value = match control {
        Control::Approach(v) | Control::Force(v) | Control::MeanPressure(v) | Control::CentralGap(v) => v,
    };
    if !value.is_finite() {
        return Err(invalid("control", value, "must be finite"));
    }
    if let Control::CentralGap(g) = control
        && g <= 0.0
    {
        return Err(invalid(
            "central_gap",
            g,
            "must be > 0 m: in contact the central gap does not fix the approach",
        ));
    }
    if let Start::Warm(s) = start {
        for (what, got) in [
            ("warm-start adhesive pressure", s.adhesive_pressure.dim()),
            ("warm-start gap", s.contact.gap.dim()),
        ] {
            if got != shape {
                return Err(SolverError::ShapeMismatch {
                    what,
                    expected: shape,
                    got,
                });
            }
        }
    }
    let standard;
    let start = match start {
        Start::Warm(s) if !s.is_standard_layout() => {
            standard = s.to_standard_layout();
            Start::Warm(&standard)
        }
        other => other,
    };
    // The surface as the start left it: its permanent set joins the initial gap.
    let before = match start {
        Start::Warm(s) => s.contact.permanent_set.clone(),
        _ => None,
    };
    let yielded = crate::interface::yielded_gap(g0, before.as_ref())?;
    let g0 = yielded.as_ref().map_or(g0, |g| g.view());
    let method = settings
        .method
        .resolve(law, control, op.domain(), op.cell_compliance(), &interface);
    let job = Job {
        op,
        law,
        interface,
        g0,
        control,
        settings,
        method,
        start,
    };
    let imp = implementation(method);
    imp.check(&job)?;
    crate::error::finite("initial gap", g0)?;
    let (mut state, mut report) = imp.solve(&job, observer)?;
    report.yielding = crate::interface::settle(
        &interface,
        g0,
        before,
        &mut state.contact,
        op.domain().cell_area(),
    );
    crate::error::finite_result(
        &[
            ("compressive pressure", &state.contact.pressure),
            ("adhesive pressure", &state.adhesive_pressure),
            ("gap", &state.contact.gap),
            ("displacement", &state.contact.displacement),
        ],
        &[("load", report.load), ("approach", report.approach)],
    )?;
    Ok((state, report))
}

impl Solved for (AdhesiveState, AdhesiveReport) {
    fn trial(&self) -> Trial {
        Trial {
            approach: self.1.approach,
            mean_pressure: self.1.mean_pressure,
            termination: self.1.termination,
        }
    }

    fn mark(&mut self, termination: crate::report::Termination) {
        self.1.termination = termination;
    }

    fn add_work(&mut self, earlier: &Self) {
        let (report, earlier) = (&mut self.1, &earlier.1);
        let mut iterations = earlier.iterations;
        iterations.accumulate(&report.iterations);
        report.iterations = iterations;
        report.operator_calls += earlier.operator_calls;
        report.wall_time_s += earlier.wall_time_s;
        report.residual_history = [earlier.residual_history.as_slice(), &report.residual_history].concat();
    }
}
