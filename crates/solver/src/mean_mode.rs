//! The mean mode of a periodic body that a uniform pressure displaces by a finite amount (a
//! layer on its base: [`elastic::Compliance::mean_compliance`] `C0` \[m/Pa\]).
//!
//! The methods solve with the mean displacement left out, as on the half-space: their approach
//! is measured from the mean surface. The approach from the rigid base is that plus the
//! layer's uniform compression, `delta = delta_mean + C0 p_mean`, and the surface displacement
//! gains `C0 p_mean`; here a solve's state and report are moved to that frame, a warm start
//! back to the methods'. A prescribed approach is, without adhesion, one solve with the mean
//! mode put back ([`WithMean`]: the constrained conjugate gradient needs no approach variable);
//! the adhesive methods meet it by a root search along their load-approach curve
//! ([`MeanMode::approach`]).

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
    /// `miss = x + C0 p - delta` vanishes, to within `tolerance` \[m\]. `solve(control, seed)`
    /// solves in the methods' frame, warm from the seed if any. Trials prescribe `x` below the
    /// mean gap (`bounds.0` \[m\]) and `p` at or past it (full contact, where `x` stops and the
    /// layer's compression takes up the rest). Load trials stay below `bounds.1` \[Pa\] (a
    /// hardness: no surface carries more), halfway to it from below where a step would pass
    /// it. The first trial is at `x = delta - C0 p_guess` (`p_guess` \[Pa\]: the warm
    /// start's); then the secant through the last two trials where it falls inside the
    /// bracket, else the chord between the two sides (Illinois' false position), else the
    /// fixed-point step (`x = delta - C0 p`, or `p = (delta - x) / C0`), which crosses the root
    /// on a rising curve. A trial that pulls off counts as too tensile. After [`MAX_STEPS`]
    /// trials the last is marked [`Termination::MaxIterations`]. The solution reports every
    /// trial's work ([`Solved::add_work`]).
    pub(crate) fn approach<S: Solved>(
        &self,
        delta: f64,
        p_guess: f64,
        (mean_gap, ceiling): (f64, f64),
        tolerance: f64,
        mut solve: impl FnMut(Control, Option<&S>) -> Result<S>,
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
        // The last trial: it carries the work of all before it, and seeds the next unless it
        // pulled off (then the next starts where the caller's did).
        let (mut last, mut seeds): (Option<S>, bool) = (None, false);
        let mut previous: Option<[f64; 3]> = None;
        let mut side = 0i32;
        for step in 1..=MAX_STEPS {
            let mut solution = solve(next, last.as_ref().filter(|_| seeds))?;
            if let Some(earlier) = &last {
                solution.add_work(earlier);
            }
            let trial = solution.trial();
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
                solution.mark(Termination::MaxIterations);
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
            seeds = trial.termination != Termination::PulledOff;
            last = Some(solution);
            // The secant through the last two trials, where it falls inside the bracket: on a
            // smooth curve it converges faster than the bracket's chord, which is kept to hold it.
            let secant = previous
                .filter(|[_, _, m]| m.is_finite() && miss.is_finite() && *m != miss)
                .map(|[xp, pp, mp]| {
                    let t = mp / (mp - miss);
                    (xp + t * (x - xp), pp + t * (p - pp))
                })
                .filter(|&(_, ps)| {
                    low.is_none_or(|[_, pl, _]| ps > pl) && high.is_none_or(|[_, ph, _]| ps < ph)
                });
            previous = Some([x, p, miss]);
            next = match (secant, low, high) {
                (Some((xs, ps)), _, _) => at(xs, ps),
                (None, Some([xl, pl, ml]), Some([xh, ph, mh])) if ml.is_finite() => {
                    let t = ml / (ml - mh);
                    at(xl + t * (xh - xl), pl + t * (ph - pl))
                }
                // Pulled off below: halfway in load.
                (None, Some([_, pl, _]), Some([_, ph, _])) => Control::MeanPressure(0.5 * (pl + ph)),
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

/// A periodic body's operator with its mean mode put back: `apply` adds `C0 p_mean` to every
/// displacement. The layer's approach from its base is then a bound-constrained problem of
/// its own, solved at once where the methods' frame needs a root search.
pub(crate) struct WithMean<'a> {
    op: &'a dyn elastic::Compliance,
    mean: MeanMode,
    /// The operator's multiplier with `C0 / (nx ny)` at `q = 0`.
    multiplier: ndarray::Array2<f64>,
}

impl<'a> WithMean<'a> {
    pub(crate) fn new(op: &'a dyn elastic::Compliance, mean: MeanMode) -> Self {
        let mut multiplier = op.fourier_compliance().to_owned();
        let d = op.domain();
        multiplier[(0, 0)] = mean.compliance / (d.nx * d.ny) as f64;
        WithMean { op, mean, multiplier }
    }
}

impl elastic::Compliance for WithMean<'_> {
    fn domain(&self) -> &elastic::Domain {
        self.op.domain()
    }

    fn e_star(&self) -> f64 {
        self.op.e_star()
    }

    fn body(&self) -> elastic::Body {
        self.op.body()
    }

    fn cell_compliance(&self) -> f64 {
        let d = self.op.domain();
        self.op.cell_compliance() + self.mean.compliance / (d.nx * d.ny) as f64
    }

    fn mean_compliance(&self) -> f64 {
        0.0
    }

    fn with_modulus(&self, _: f64) -> elastic::Result<Box<dyn elastic::Compliance>> {
        // A viscoelastic step scales the problem's operator before any solve wraps it.
        Err(elastic::ElasticError::Unsupported(
            "a borrowed operator with its mean mode is not rescaled",
        ))
    }

    fn make_workspace(&self) -> elastic::Workspace {
        self.op.make_workspace()
    }

    fn apply(
        &self,
        pressure: ndarray::ArrayView2<f64>,
        mut displacement: ndarray::ArrayViewMut2<f64>,
        ws: &mut elastic::Workspace,
    ) -> elastic::Result<()> {
        self.op.apply(pressure, displacement.view_mut(), ws)?;
        let shift = self.mean.compliance * pressure.mean().unwrap_or(0.0);
        displacement.par_mapv_inplace(|u| u + shift);
        Ok(())
    }

    fn fourier_compliance(&self) -> ndarray::ArrayView2<'_, f64> {
        self.multiplier.view()
    }
}

/// A solve as [`MeanMode::approach`] sees it: its [`Trial`], its termination to mark, and the
/// work of earlier trials to add to its own.
pub(crate) trait Solved {
    /// Where it landed.
    fn trial(&self) -> Trial;
    /// Marks why the search stopped.
    fn mark(&mut self, termination: Termination);
    /// Adds the iterations, operator calls, wall time and residual history (in front) of
    /// `earlier` to its own.
    fn add_work(&mut self, earlier: &Self);
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
