//! Load control under a hardness. Projecting onto the cap inside the load-controlled iteration
//! cycles: once most of the contact is held at the cap the elastic contact set no longer fixes
//! the load's multiplier, the approach (a sphere at eight times the load of first yield,
//! measured). Two outer loops meet the load instead:
//!
//! - An active set of the cells held at the cap (first): each round holds them at H and solves
//!   the elastic, preconditioned, load-controlled problem for the rest of the load on the other
//!   cells; cells whose pressure passes H join, held cells whose gap opens leave. The rounds
//!   start loose and tighten as the set settles (an inner tolerance the share of the contact
//!   that changed to the power 1.5), from the bearing set of nine tenths of the load.
//! - A search on the approach (where the active set cannot finish): the load grows
//!   monotonically with it, each trial an approach-controlled solve warm-started from the last,
//!   on the logarithm of the load by secants, bracketed and then refined by the Illinois
//!   variant of regula falsi, until the load is met or the bracket is narrower than the
//!   approach the solves resolve (their gap tolerance times the RMS initial gap).
//!
//! The choice and its measurements are in `docs/decisions.md`.

use super::{Scratch, gap_scale, solve_in};
use crate::error::{Result, invalid};
use crate::options::{ContactOptions, Control};
use crate::report::{ContactReport, Termination};
use crate::state::ContactState;
use ndarray::{Array2, ArrayView2, Zip};
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
    // The work of both loops is counted together, within one iteration limit.
    let mut search = Search {
        trials: 0,
        iterations: 0,
        calls: 0,
        history: Vec::new(),
        warm,
    };
    if let Some(report) = active_set(scratch, g0, cap, load, options, state, &mut search, observer)? {
        return Ok(ContactReport {
            wall_time_s: started.elapsed().as_secs_f64(),
            ..report
        });
    }
    let first_touch = g0.iter().copied().fold(f64::INFINITY, f64::min);
    let tolerance = options.tolerance * load;
    // The approach the solves resolve: their gap tolerance, relative to the RMS initial gap.
    let resolution = options.tolerance * gap_scale(g0);
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

/// Rounds of the active set before the search takes over.
const MAX_ROUNDS: usize = 40;

/// Rounds at the requested tolerance that still change the set before the search takes over.
const SETTLING_ROUNDS: usize = 6;

/// The share of the load a cold active set starts with on the bearing set: most of the answer
/// where the contact is mostly plastic, released in the first round where it is not.
const BEARING_SHARE: f64 = 0.9;

/// The inner tolerance of the first round.
const LOOSE: f64 = 1e-2;

/// A gap no displacement closes: it takes a held cell out of the elastic problem.
const OUT: f64 = 1e300;

/// Load control with the cells at the cap as an outer active set (the module's first loop).
/// None when it cannot finish: no settled set within [`MAX_ROUNDS`] (or [`SETTLING_ROUNDS`] at
/// the requested tolerance), a round whose elastic set empties, or no load left for one.
#[allow(clippy::too_many_arguments)]
fn active_set(
    scratch: &mut Scratch,
    g0: ArrayView2<f64>,
    cap: f64,
    load: f64,
    options: &ContactOptions,
    state: &mut ContactState,
    tally: &mut Search,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<Option<ContactReport>> {
    let warm = tally.warm;
    let op = scratch.op;
    let domain = *op.domain();
    let shape = domain.shape();
    let cell = domain.cell_area();
    // The gap scale the residuals are measured against: the problem's, not the held cells'.
    let scale = gap_scale(g0);
    let held_load = |held: &Array2<bool>| cap * cell * held.iter().filter(|&&h| h).count() as f64;
    // The start: a warm state's held cells and pressure while they leave load to the others,
    // else the bearing set's cells and the rest of the load spread evenly (the first round).
    let mut inner = ContactState::unloaded(shape);
    let warm_held = (warm && state.pressure.dim() == shape)
        .then(|| state.pressure.mapv(|p| p >= cap))
        .filter(|held| held_load(held) < BEARING_SHARE * load);
    let mut held = match warm_held {
        Some(held) => {
            Zip::from(&mut inner.pressure)
                .and(&state.pressure)
                .and(&held)
                .for_each(|e, &p, &h| *e = if h { 0.0 } else { p });
            held
        }
        None => {
            let depth = bearing_approach(g0, BEARING_SHARE * load / (cap * cell));
            g0.mapv(|g| g < depth)
        }
    };
    if state.pressure.dim() != shape {
        // The solution is assembled into the state's fields.
        *state = ContactState {
            permanent_set: state.permanent_set.take(),
            ..ContactState::unloaded(shape)
        };
    }
    let mut p_held = Array2::<f64>::zeros(shape);
    let mut u_held = Array2::<f64>::zeros(shape);
    let mut g_eff = Array2::<f64>::zeros(shape);
    let mut tolerance = options.tolerance.max(LOOSE);
    let mut last_changed = usize::MAX;
    let mut settling = 0;
    for _ in 0..MAX_ROUNDS {
        let rest = load - held_load(&held);
        if rest <= 0.0 {
            return Ok(None);
        }
        if inner.pressure.iter().all(|&p| p == 0.0) {
            // Every elastic cell joined (or a cold start): the rest spread over the others.
            let free = held.iter().filter(|&&h| !h).count().max(1) as f64;
            let spread = rest / (free * cell);
            Zip::from(&mut inner.pressure)
                .and(&held)
                .par_for_each(|p, &h| *p = if h { 0.0 } else { spread });
        }
        Zip::from(&mut p_held)
            .and(&held)
            .par_for_each(|p, &h| *p = if h { cap } else { 0.0 });
        op.apply(p_held.view(), u_held.view_mut(), &mut scratch.ws)?;
        tally.calls += 1;
        Zip::from(&mut g_eff)
            .and(g0)
            .and(&u_held)
            .and(&held)
            .par_for_each(|e, &g, &u, &h| *e = if h { OUT } else { g + u });
        let round = ContactOptions {
            max_iterations: options.max_iterations.saturating_sub(tally.iterations),
            tolerance,
            ..*options
        };
        let offset = tally.iterations;
        let report = super::solve_scaled(
            scratch,
            g_eff.view(),
            f64::INFINITY,
            Some(scale),
            Control::Force(rest),
            &round,
            &mut inner,
            true,
            &mut |i, r| observer(offset + i, r),
        )?;
        tally.iterations += report.iterations;
        tally.calls += report.operator_calls;
        tally.history.extend(&report.residual_history);
        let approach = report.approach;
        if !approach.is_finite() {
            // An elastic set of a cell or two that the step emptied: the search takes over.
            return Ok(None);
        }
        let mut changed = 0usize;
        if report.converged() {
            // A held cell leaves once its gap opens beyond what the round resolves; a cell
            // joins once its pressure passes H beyond the tolerance (it is clipped to H at the
            // end), so that a cell on the edge of both cannot flip from round to round.
            let opening = tolerance * scale;
            let limit = cap * (1.0 + options.tolerance);
            Zip::from(&mut held)
                .and(&mut inner.pressure)
                .and(&inner.displacement)
                .and(&u_held)
                .and(g0)
                .for_each(|h, p, &u, &uh, &g| {
                    let flip = if *h {
                        g + u + uh - approach > opening
                    } else {
                        *p > limit
                    };
                    if flip {
                        *h = !*h;
                        // A cell released starts at H, one that joins leaves the problem.
                        *p = if *h { 0.0 } else { cap };
                        changed += 1;
                    }
                });
        }
        if !report.converged() || (changed == 0 && tolerance <= options.tolerance) {
            assemble(state, (&inner, &p_held, &u_held), g0, cap, approach);
            let summary = super::report(op, &state.pressure, &state.displacement, &mut state.gap, approach);
            return Ok(Some(ContactReport {
                iterations: tally.iterations,
                residual: report.residual,
                residual_history: std::mem::take(&mut tally.history),
                termination: report.termination,
                operator_calls: tally.calls,
                ..summary
            }));
        }
        // The next round's tolerance: the share of the contact that changed to the power 1.5,
        // a hundred times tighter when the changes stop shrinking, the requested one once
        // nothing changes.
        let contact =
            inner.pressure.iter().filter(|&&p| p > 0.0).count() + held.iter().filter(|&&h| h).count();
        let share = changed as f64 / contact.max(1) as f64;
        let mut next = share.powf(1.5).min(tolerance);
        if changed >= last_changed {
            next = next.min(1e-2 * tolerance);
        }
        tolerance = next.max(options.tolerance);
        last_changed = changed;
        if tolerance <= options.tolerance {
            settling += 1;
            if settling > SETTLING_ROUNDS {
                // A few cells a round at full cost (an elastic set of a few cells): the
                // search takes over.
                return Ok(None);
            }
        }
    }
    Ok(None)
}

/// The whole solution into `state`: the pressures and displacements of the elastic cells
/// (`inner`) and of the held ones, the gap at `approach`.
fn assemble(
    state: &mut ContactState,
    (inner, p_held, u_held): (&ContactState, &Array2<f64>, &Array2<f64>),
    g0: ArrayView2<f64>,
    cap: f64,
    approach: f64,
) {
    Zip::from(&mut state.pressure)
        .and(&inner.pressure)
        .and(p_held)
        .par_for_each(|p, &e, &h| *p = e.min(cap) + h);
    Zip::from(&mut state.displacement)
        .and(&inner.displacement)
        .and(u_held)
        .par_for_each(|u, &e, &h| *u = e + h);
    Zip::from(&mut state.gap)
        .and(g0)
        .and(&state.displacement)
        .par_for_each(|gap, &g, &u| *gap = g + u - approach);
    state.approach = approach;
}
