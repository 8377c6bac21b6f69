//! The mean mode of a periodic body that a uniform pressure displaces by a finite amount (a
//! layer on its base: [`elastic::Compliance::mean_compliance`] `C0` \[m/Pa\]).
//!
//! The methods solve with the mean displacement left out, as on the half-space: their approach
//! is measured from the mean surface. The approach from the rigid base is that plus the
//! layer's uniform compression, `delta = delta_mean + C0 p_mean`, and the surface displacement
//! gains `C0 p_mean`; here a solve's state and report are moved to that frame, a warm start
//! back to the methods', and a prescribed approach is met by a root search over the mean
//! pressure with the methods under load control, which stay well posed in full contact (where
//! the methods' approach stops moving and the layer's compression takes up the rest).

use crate::error::Result;
use crate::options::Control;
use crate::report::Termination;
use crate::state::ContactState;

/// Trial solves before a prescribed approach is given up as not converged.
const MAX_STEPS: usize = 40;

/// A periodic body's mean mode.
#[derive(Clone, Copy, Debug)]
pub(crate) struct MeanMode {
    /// `C0` \[m/Pa\], > 0.
    compliance: f64,
}

impl MeanMode {
    /// The mean mode of `op`, `None` where nothing is left out (free grids, the half-space).
    pub(crate) fn of(op: &dyn elastic::Compliance) -> Option<MeanMode> {
        let compliance = op.mean_compliance();
        (compliance > 0.0).then_some(MeanMode { compliance })
    }

    /// Moves `state` at mean pressure `p_mean` \[Pa\] from the methods' frame to the base's
    /// (`sign` 1) or back (`sign` -1); returns the approach's shift \[m\].
    pub(crate) fn shift(&self, state: &mut ContactState, p_mean: f64, sign: f64) -> f64 {
        let shift = sign * self.compliance * p_mean;
        state.approach += shift;
        state.displacement += shift;
        shift
    }

    /// Solves for the approach `delta` \[m\] from the base. `solve(control, last)` solves in
    /// the methods' frame, warm from the last trial if any, and returns the solution and its
    /// [`Trial`]. The mean pressure is sought (the methods' approach rises with it, so
    /// `miss(p) = delta_mean(p) + C0 p - delta` rises too): from `p_guess` \[Pa\] (else the
    /// full-contact bound `(delta - mean_gap) / C0`, or zero), then the fixed-point step
    /// `p = (delta - delta_mean(p)) / C0`, which crosses the root, then false position
    /// (Illinois) in the bracket, to within `tolerance` \[m\]; after [`MAX_STEPS`] the last
    /// solution is marked [`Termination::MaxIterations`] by `mark`. A trial that pulls off counts
    /// as too tensile. With no contact at zero load and `delta <= 0`, the answer is the
    /// approach-controlled solve at `delta` (no mean pressure, no shift).
    pub(crate) fn approach<S>(
        &self,
        delta: f64,
        p_guess: Option<f64>,
        mean_gap: f64,
        tolerance: f64,
        mut solve: impl FnMut(Control, Option<&S>) -> Result<(S, Trial)>,
        mut mark: impl FnMut(&mut S, Termination),
    ) -> Result<S> {
        let c0 = self.compliance;
        let mut p = p_guess.unwrap_or(((delta - mean_gap) / c0).max(0.0));
        // The bracket: (p, miss) below and above the root.
        let (mut low, mut high): (Option<(f64, f64)>, Option<(f64, f64)>) = (None, None);
        let mut last: Option<S> = None;
        let mut stale = 0;
        for step in 1..=MAX_STEPS {
            let (mut solution, trial) = solve(Control::MeanPressure(p), last.as_ref())?;
            let miss = match trial.termination {
                Termination::PulledOff => f64::NEG_INFINITY,
                Termination::Converged | Termination::NoContact => {
                    trial.approach + c0 * trial.mean_pressure - delta
                }
                _ => return Ok(solution),
            };
            if trial.termination == Termination::NoContact && p == 0.0 && delta <= 0.0 {
                return solve(Control::Approach(delta), None).map(|(s, _)| s);
            }
            if miss.abs() <= tolerance {
                return Ok(solution);
            }
            if step == MAX_STEPS {
                mark(&mut solution, Termination::MaxIterations);
                return Ok(solution);
            }
            let fixed_point = (delta - trial.approach) / c0;
            if miss < 0.0 {
                // Illinois: halve the other end's weight when the same end moves twice.
                if let Some(h) = high.as_mut().filter(|_| stale < 0) {
                    h.1 *= 0.5;
                }
                stale = stale.min(0) - 1;
                low = Some((p, miss));
            } else {
                if let Some(l) = low.as_mut().filter(|_| stale > 0) {
                    l.1 *= 0.5;
                }
                stale = stale.max(0) + 1;
                high = Some((p, miss));
            }
            if trial.termination != Termination::PulledOff {
                last = Some(solution);
            }
            p = match (low, high) {
                (Some((a, fa)), Some((b, fb))) if fa.is_finite() => a - fa * (b - a) / (fb - fa),
                (Some((a, _)), Some((b, _))) => 0.5 * (a + b),
                _ if miss.is_finite() => fixed_point,
                // Pulled off with nothing above: half as tensile.
                _ => 0.5 * p,
            };
        }
        unreachable!("the last step returns")
    }
}

/// What [`MeanMode::approach`] needs of a trial solve, in the methods' frame.
pub(crate) struct Trial {
    /// Approach from the mean surface \[m\].
    pub(crate) approach: f64,
    /// Mean pressure \[Pa\].
    pub(crate) mean_pressure: f64,
    /// Why it stopped.
    pub(crate) termination: Termination,
}
