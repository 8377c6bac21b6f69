//! The mean mode of a periodic body that a uniform pressure displaces by a finite amount (a
//! layer on its base: [`elastic::Compliance::mean_compliance`] `C0` \[m/Pa\]).
//!
//! The methods solve with the mean displacement left out, as on the half-space: their approach
//! is measured from the mean surface. The approach from the rigid base is that plus the
//! layer's uniform compression, `delta = delta_mean + C0 p_mean`, and the surface displacement
//! gains `C0 p_mean`; here a solve's state and report are moved to that frame, a warm start
//! back to the methods', and a prescribed approach is met by a secant on the methods' own
//! (`delta_mean + C0 p_mean(delta_mean) = delta`, increasing along a stable branch).

use crate::error::Result;
use crate::report::Termination;
use crate::state::ContactState;

/// Secant steps before a prescribed approach is given up as not converged.
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

    /// Solves for the approach `delta` \[m\] from the base: `solve(delta_mean, last)` solves at
    /// the methods' approach `delta_mean`, warm from the last solution if any, and returns it
    /// with its mean pressure \[Pa\] and termination. The first guess takes `p_guess` \[Pa\];
    /// the secant stops within `tolerance` \[m\] of `delta`, or after [`MAX_STEPS`] with the
    /// last solution marked [`Termination::MaxIterations`]. Returns the solution (still in the
    /// methods' frame) and its mean pressure.
    pub(crate) fn approach<S>(
        &self,
        delta: f64,
        p_guess: f64,
        tolerance: f64,
        mut solve: impl FnMut(f64, Option<&S>) -> Result<(S, f64, Termination)>,
        mut mark: impl FnMut(&mut S, Termination),
    ) -> Result<(S, f64)> {
        let c0 = self.compliance;
        let miss = |x: f64, p: f64| x + c0 * p - delta;
        let mut x0 = delta - c0 * p_guess;
        let (mut s0, mut p0, t0) = solve(x0, None)?;
        if t0 != Termination::Converged && t0 != Termination::NoContact {
            return Ok((s0, p0));
        }
        let mut f0 = miss(x0, p0);
        if f0.abs() <= tolerance {
            return Ok((s0, p0));
        }
        // A fixed-point step first: exact when the mean pressure does not change.
        let mut x1 = delta - c0 * p0;
        for _ in 0..MAX_STEPS {
            let (s1, p1, t1) = solve(x1, Some(&s0))?;
            if t1 != Termination::Converged && t1 != Termination::NoContact {
                return Ok((s1, p1));
            }
            let f1 = miss(x1, p1);
            if f1.abs() <= tolerance {
                return Ok((s1, p1));
            }
            let next = if f1 != f0 {
                x1 - f1 * (x1 - x0) / (f1 - f0)
            } else {
                delta - c0 * p1
            };
            (x0, f0, s0, p0) = (x1, f1, s1, p1);
            x1 = next;
        }
        mark(&mut s0, Termination::MaxIterations);
        Ok((s0, p0))
    }
}
