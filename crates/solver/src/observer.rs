//! Who watches a solve or a sweep, and what a sweep shows them at each step.

use crate::adhesive::report::AdhesiveReport;
use crate::adhesive::state::AdhesiveState;
use crate::options::Control;

/// Watches a solve or a sweep. Both methods do nothing by default; `()` watches nothing.
///
/// ```
/// use solver::{AdhesiveState, Observer, SweepPoint};
///
/// /// Prints each finished step of a sweep, and stops it once the bodies pull apart.
/// struct Log;
///
/// impl Observer for Log {
///     fn step(&mut self, k: usize, point: &SweepPoint, _: &AdhesiveState) -> bool {
///         println!("step {k}: load {:e} N", point.report.load);
///         point.report.attached_area_fraction > 0.0 || k == 0
///     }
/// }
/// ```
pub trait Observer {
    /// After every iteration of a solve: the sweep step it belongs to (0 for a single solve),
    /// the method's iteration count within the solve, and its residual.
    fn iteration(&mut self, _step: usize, _iteration: usize, _residual: f64) {}

    /// Asked after every iteration: `true` stops the solve where it stands, reported as
    /// [`crate::Termination::Interrupted`], and a sweep after that step (a user's Ctrl-C).
    fn interrupted(&mut self) -> bool {
        false
    }

    /// After every step of a sweep, with its point and state; `false` stops the sweep.
    fn step(&mut self, _index: usize, _point: &SweepPoint, _state: &AdhesiveState) -> bool {
        true
    }
}

impl Observer for () {}

/// Shows `observer` an iteration of sweep step `step`; whether the solve goes on.
pub(crate) fn heard(observer: &mut dyn Observer, step: usize, iteration: usize, residual: f64) -> bool {
    observer.iteration(step, iteration, residual);
    !observer.interrupted()
}

/// The direction of a sweep step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Branch {
    /// Bodies moving together (approach or load increasing, central gap decreasing).
    Loading,
    /// Bodies moving apart.
    Unloading,
}

impl Branch {
    /// `loading` or `unloading`.
    pub fn name(self) -> &'static str {
        match self {
            Branch::Loading => "loading",
            Branch::Unloading => "unloading",
        }
    }
}

/// One solved step of a sweep.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct SweepPoint {
    /// The control of this step.
    pub control: Control,
    /// The time it was reached at \[s\], on a path with times.
    pub time: Option<f64>,
    /// Its direction.
    pub branch: Branch,
    /// The solve's report. When the step was split (see [`crate::ContactProblem::sweep`]), its iteration counts and
    /// wall time include the substeps'.
    pub report: AdhesiveReport,
    /// Intermediate solves taken before this control (0 when the step was not split), in the
    /// last attempt.
    pub substeps: usize,
    /// How many of those intermediate solves missed their tolerance.
    pub unconverged_substeps: usize,
    /// Times the step was solved again in finer substeps because it did not converge (see
    /// [`crate::ContactProblem::sweep`]); 0 when the first attempt converged.
    pub retries: usize,
}
