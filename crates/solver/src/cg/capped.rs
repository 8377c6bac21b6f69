//! Load control under a hardness. Once most of the contact is held at the cap the elastic
//! contact set no longer fixes the load's multiplier, the approach (a sphere at eight times
//! the load of first yield left no cell between 0 and H and cycled, measured), so the load is
//! met by a search on the approach instead: the load grows monotonically with it, each trial
//! an approach-controlled solve warm-started from the last, on the logarithm of the load by
//! secants, bracketed and then refined by the Illinois variant of regula falsi, until the load
//! is met or the bracket is narrower than the approach the solves resolve (their gap tolerance
//! times the RMS initial gap).

use super::{Scratch, solve_in};
use crate::error::{Result, invalid};
use crate::options::{ContactOptions, Control};
use crate::report::{ContactReport, Termination};
use crate::state::ContactState;
use ndarray::ArrayView2;
use std::time::Instant;

/// Trials allowed to bracket and to refine the approach.
const MAX_TRIALS: usize = 200;

/// Solves for the load `load` \[N\] with the pressure capped at `cap` \[Pa\] (see
/// [`super::solve_in`]): the load is met to `options.tolerance` of itself, and the iterations,
/// operator calls and residuals of every trial are counted in the report.
#[allow(clippy::too_many_arguments)]
pub(super) fn solve_load(
    scratch: &mut Scratch,
    g0: ArrayView2<f64>,
    cap: f64,
    load: f64,
    options: &ContactOptions,
    state: &mut ContactState,
    warm: bool,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<ContactReport> {
    let started = Instant::now();
    let domain = *scratch.op.domain();
    let cell = domain.cell_area();
    // The dual loops ask for the load plus the attraction's: a law whose attraction in contact
    // exceeds the hardness outpulls it.
    let area = cell * (domain.nx * domain.ny) as f64;
    if load > cap * area {
        return Err(invalid(
            "load",
            load,
            format!(
                "exceeds the hardness times the nominal area, {:.4e} N: a plastic surface cannot \
                 carry it (with adhesion, the compressive load that balances the attraction: a \
                 law whose attraction in contact exceeds the hardness outpulls it)",
                cap * area
            ),
        ));
    }
    let first_touch = g0.iter().copied().fold(f64::INFINITY, f64::min);
    let tolerance = options.tolerance * load;
    // The approach the solves resolve: their gap tolerance, relative to the RMS initial gap.
    let n = g0.len() as f64;
    let mean = g0.sum() / n;
    let resolution = options.tolerance * (g0.iter().map(|g| (g - mean).powi(2)).sum::<f64>() / n).sqrt();
    let mut search = Search {
        trials: 0,
        iterations: 0,
        calls: 0,
        history: Vec::new(),
        warm,
    };
    // The search is on the logarithm of the load, nearly linear in the approach on rough
    // surfaces (exponential at small loads): `(approach, ln(P / load))`, -inf without contact.
    // Below first touch nothing is carried.
    let mut lo = (first_touch, f64::NEG_INFINITY);
    let mut hi: Option<(f64, f64)> = None;
    let mut last: Option<(f64, f64)> = None;
    // A first trial: the warm state's approach, or the bearing area's for this load (the
    // approach at which the cells overlapping would carry it all at the cap).
    let mut trial = if warm && state.approach > first_touch {
        state.approach
    } else {
        bearing_approach(g0, load / (cap * cell))
    };
    let mut report;
    let mut side = 0i8;
    loop {
        report = search.trial(scratch, g0, cap, trial, options, state, observer)?;
        let miss = report.load - load;
        let done = miss.abs() <= tolerance || !report.converged();
        if done || search.trials_left() == 0 {
            report.termination = match report.termination {
                Termination::NoContact if load == 0.0 => Termination::NoContact,
                Termination::Converged | Termination::NoContact if miss.abs() <= tolerance => {
                    Termination::Converged
                }
                Termination::Interrupted => Termination::Interrupted,
                _ => Termination::MaxIterations,
            };
            break;
        }
        let point = (trial, (report.load / load).ln());
        // Illinois: an end kept twice in a row has its miss halved.
        if miss < 0.0 {
            lo = point;
            if side == -1 {
                hi = hi.map(|(d, m)| (d, 0.5 * m));
            }
            side = -1;
        } else {
            hi = Some(point);
            if side == 1 && lo.1.is_finite() {
                lo.1 *= 0.5;
            }
            side = 1;
        }
        trial = next_trial(lo, hi, last, point, first_touch);
        last = Some(point).filter(|p| p.1.is_finite());
        if hi.is_some_and(|(d, _)| d - lo.0 <= resolution) {
            // The bracket is narrower than the approach the solves resolve: the load is as
            // close as they can tell.
            break;
        }
    }
    Ok(ContactReport {
        iterations: search.iterations,
        residual_history: search.history,
        operator_calls: search.calls,
        wall_time_s: started.elapsed().as_secs_f64(),
        ..report
    })
}

/// The trials' tally.
struct Search {
    trials: usize,
    iterations: usize,
    calls: usize,
    history: Vec<f64>,
    warm: bool,
}

impl Search {
    fn trials_left(&self) -> usize {
        MAX_TRIALS.saturating_sub(self.trials)
    }

    /// An approach-controlled solve at `approach`, from the last trial's state, within what is
    /// left of the iteration limit.
    #[allow(clippy::too_many_arguments)]
    fn trial(
        &mut self,
        scratch: &mut Scratch,
        g0: ArrayView2<f64>,
        cap: f64,
        approach: f64,
        options: &ContactOptions,
        state: &mut ContactState,
        observer: &mut dyn FnMut(usize, f64) -> bool,
    ) -> Result<ContactReport> {
        let left = ContactOptions {
            max_iterations: options.max_iterations.saturating_sub(self.iterations),
            ..*options
        };
        let offset = self.iterations;
        let report = solve_in(
            scratch,
            g0,
            cap,
            Control::Approach(approach),
            &left,
            state,
            self.warm,
            &mut |i, r| observer(offset + i, r),
        )?;
        self.warm = true;
        self.trials += 1;
        self.iterations += report.iterations;
        self.calls += report.operator_calls;
        self.history.extend(&report.residual_history);
        Ok(report)
    }
}

/// The next approach to try, from the bracket `lo` (load short) and `hi` (load beyond; none
/// yet) and the last two trials `last` and `point`, each `(approach, ln(P / load))`: the
/// regula falsi inside a bracket whose ends both carry load, else the secant through the last
/// two trials where it falls inside the bracket, else its middle, or twice as deep from first
/// touch while nothing is beyond.
fn next_trial(
    lo: (f64, f64),
    hi: Option<(f64, f64)>,
    last: Option<(f64, f64)>,
    point: (f64, f64),
    first_touch: f64,
) -> f64 {
    let inside = |d: f64| d > lo.0 && hi.is_none_or(|(h, _)| d < h);
    let secant = |(a, fa): (f64, f64), (b, fb): (f64, f64)| a - fa * (b - a) / (fb - fa);
    if let Some(h) = hi
        && lo.1.is_finite()
    {
        let d = secant(lo, h);
        if inside(d) {
            return d;
        }
    }
    if let Some(prev) = last
        && point.1.is_finite()
        && point.1 != prev.1
    {
        let d = secant(prev, point);
        // Beyond the bracket's top, at most four times as deep from first touch.
        if inside(d) && d - first_touch <= 4.0 * (point.0.max(prev.0) - first_touch) {
            return d;
        }
    }
    match hi {
        Some((h, _)) => 0.5 * (lo.0 + h),
        None => first_touch + 2.0 * (point.0 - first_touch).max(f64::MIN_POSITIVE),
    }
}

/// The approach at which `cells` cells of the initial gap `g0` overlap.
fn bearing_approach(g0: ArrayView2<f64>, cells: f64) -> f64 {
    let mut gaps: Vec<f64> = g0.iter().copied().collect();
    let k = (cells.ceil() as usize).clamp(1, gaps.len()) - 1;
    let (_, kth, _) = gaps.select_nth_unstable_by(k, f64::total_cmp);
    *kth
}
