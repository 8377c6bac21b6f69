//! The mean mode of a periodic body that a uniform pressure displaces by a finite amount (a
//! layer on its base: [`elastic::Compliance::mean_compliance`] `C0` \[m/Pa\]).
//!
//! The methods solve with the mean displacement left out, as on the half-space: their approach
//! is measured from the mean surface. The approach from the rigid base is that plus the
//! layer's uniform compression, `delta = delta_mean + C0 p_mean`, and the surface displacement
//! gains `C0 p_mean`; here a solve's state and report are moved to that frame, a warm start
//! back to the methods', and a prescribed approach is met by a root search along the methods'
//! load-approach curve ([`MeanMode::approach`]).

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

    /// Solves for the approach `delta` \[m\] from the base: finds the point `(x, p)` of the
    /// methods' curve (approach from the mean surface `x` \[m\], mean pressure `p` \[Pa\]) where
    /// `miss = x + C0 p - delta` vanishes, to within `tolerance` \[m\]. `solve(control, last)`
    /// solves in the methods' frame, warm from the last trial if any, and returns the solution
    /// and its [`Trial`]. Trials prescribe `x` (which follows unstable branches) below the mean
    /// gap `mean_gap` \[m\], `p` at or past it (full contact, where `x` stops and the layer's
    /// compression takes up the rest). The first is at `x = delta - C0 p_guess` (`p_guess`
    /// \[Pa\]: the warm start's); then the fixed-point step (`x = delta - C0 p`, or
    /// `p = (delta - x) / C0`), which crosses the root on a rising curve; then the chord
    /// between the two sides (Illinois' false position). After [`MAX_STEPS`] trials the last
    /// solution is marked [`Termination::MaxIterations`] by `mark`. A trial that pulls off
    /// counts as too tensile; load trials stay below `ceiling` \[Pa\] (a hardness: no surface
    /// carries more), halfway to it from the side below where a step would pass it.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn approach<S>(
        &self,
        delta: f64,
        p_guess: f64,
        mean_gap: f64,
        tolerance: f64,
        ceiling: f64,
        mut solve: impl FnMut(Control, Option<&S>) -> Result<(S, Trial)>,
        mut mark: impl FnMut(&mut S, Termination),
    ) -> Result<S> {
        let c0 = self.compliance;
        // Below the mean gap an approach is well posed; at it, only a load.
        let closes = |x: f64| x >= mean_gap - 1e-9 * mean_gap.abs();
        let at = |x: f64, p: f64| {
            if closes(x) {
                Control::MeanPressure(p)
            } else {
                Control::Approach(x)
            }
        };
        let mut next = at(
            delta - c0 * p_guess,
            ((delta - mean_gap) / c0).max(p_guess).min(0.5 * ceiling),
        );
        // The two sides: (x, p, miss); the miss of a side that stays is halved (Illinois).
        let (mut low, mut high): (Option<[f64; 3]>, Option<[f64; 3]>) = (None, None);
        let mut last: Option<S> = None;
        let mut side = 0i32;
        for step in 1..=MAX_STEPS {
            let (mut solution, trial) = solve(next, last.as_ref())?;
            let (x, p) = (trial.approach, trial.mean_pressure);
            let miss = match trial.termination {
                Termination::PulledOff => f64::NEG_INFINITY,
                Termination::Converged | Termination::NoContact => x + c0 * p - delta,
                _ => return Ok(solution),
            };
            if miss.abs() <= tolerance {
                return Ok(solution);
            }
            if step == MAX_STEPS {
                mark(&mut solution, Termination::MaxIterations);
                return Ok(solution);
            }
            if miss < 0.0 {
                if let Some(h) = high.as_mut().filter(|_| side < 0) {
                    h[2] *= 0.5;
                }
                side = side.min(0) - 1;
                low = Some([x, p, miss]);
            } else {
                if let Some(l) = low.as_mut().filter(|_| side > 0) {
                    l[2] *= 0.5;
                }
                side = side.max(0) + 1;
                high = Some([x, p, miss]);
            }
            if trial.termination != Termination::PulledOff {
                last = Some(solution);
            }
            next = match (low, high) {
                (Some([xl, pl, ml]), Some([xh, ph, mh])) if ml.is_finite() => {
                    let t = ml / (ml - mh);
                    at(xl + t * (xh - xl), pl + t * (ph - pl))
                }
                // Pulled off below: halfway in load.
                (Some([_, pl, _]), Some([_, ph, _])) => Control::MeanPressure(0.5 * (pl + ph)),
                _ if miss.is_finite() => at(delta - c0 * p, (delta - x) / c0),
                // Pulled off with nothing above: half as tensile.
                _ => Control::MeanPressure(0.5 * p),
            };
            if let Control::MeanPressure(q) = next
                && q >= ceiling
            {
                let below = low.map_or(0.0, |[_, pl, _]| pl.max(0.0));
                next = Control::MeanPressure(0.5 * (below + ceiling));
            }
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
