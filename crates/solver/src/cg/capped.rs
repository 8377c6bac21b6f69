//! Load control under a hardness. Once most of the contact is held at the cap the elastic
//! contact set no longer fixes the load's multiplier, the approach (a sphere at eight times
//! the load of first yield left no cell between 0 and H and cycled, measured), so the load is
//! met by a search on the approach instead: the load grows monotonically with it, each trial
//! an approach-controlled solve warm-started from the last, bracketed and then refined by the
//! Illinois variant of regula falsi.

use super::{Scratch, solve_in};
use crate::error::Result;
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
    let first_touch = g0.iter().copied().fold(f64::INFINITY, f64::min);
    let tolerance = options.tolerance * load;
    let mut search = Search {
        trials: 0,
        iterations: 0,
        calls: 0,
        history: Vec::new(),
        warm,
    };
    // Below first touch nothing is carried.
    let mut lo = (first_touch, -load);
    let mut hi: Option<(f64, f64)> = None;
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
        if miss < 0.0 {
            lo = (trial, miss);
            if side == -1 {
                hi = hi.map(|(d, m)| (d, 0.5 * m));
            }
            side = -1;
        } else {
            hi = Some((trial, miss));
            if side == 1 {
                lo.1 *= 0.5;
            }
            side = 1;
        }
        trial = match hi {
            // Not bracketed yet: twice as deep from first touch.
            None => first_touch + 2.0 * (trial - first_touch).max(f64::MIN_POSITIVE),
            Some((d, m)) => {
                let next = lo.0 - lo.1 * (d - lo.0) / (m - lo.1);
                if next > lo.0 && next < d {
                    next
                } else {
                    0.5 * (lo.0 + d)
                }
            }
        };
        if hi.is_some_and(|(d, _)| (d - lo.0).abs() <= 1e-15 * d.abs()) {
            // The bracket is as narrow as the arithmetic allows: the load jumps across it.
            report.termination = Termination::MaxIterations;
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

/// The approach at which `cells` cells of the initial gap `g0` overlap.
fn bearing_approach(g0: ArrayView2<f64>, cells: f64) -> f64 {
    let mut gaps: Vec<f64> = g0.iter().copied().collect();
    let k = (cells.ceil() as usize).clamp(1, gaps.len()) - 1;
    let (_, kth, _) = gaps.select_nth_unstable_by(k, f64::total_cmp);
    *kth
}
