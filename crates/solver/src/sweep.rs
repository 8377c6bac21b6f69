//! Quasi-static sweeps with continuation: a list of controls (approaches, loads or central
//! gaps) solved in order, each step warm-started from the last, so that loading and unloading
//! follow their own branches; and what a sweep shows (pull-off, jumps, hysteresis).

use crate::adhesive::{AdhesiveState, Start};
use crate::error::{Result, SolverError, invalid};
use crate::method::Settings;
use crate::observer::{Branch, Observer, SweepPoint};
use crate::options::Control;
use crate::problem::ContactProblem;
use crate::report::Termination;

/// A sweep's path: the controls in order, and the time \[s\] each is reached at (a
/// viscoelastic body needs them, [`crate::time`]; an elastic one ignores them). A hold is a
/// repeated control at later times.
#[derive(Clone, Copy, Debug)]
pub struct Path<'a> {
    /// The controls.
    pub controls: &'a [Control],
    /// One time a control \[s\], never decreasing; `None`: no times.
    pub times: Option<&'a [f64]>,
}

impl<'a> Path<'a> {
    /// The controls reached at `times` \[s\].
    pub fn timed(controls: &'a [Control], times: &'a [f64]) -> Path<'a> {
        Path {
            controls,
            times: Some(times),
        }
    }

    /// Refuses times of another count than the controls', not finite, or going backwards.
    fn validate(&self) -> Result<()> {
        let Some(times) = self.times else {
            return Ok(());
        };
        if times.len() != self.controls.len() {
            return Err(invalid(
                "times",
                times.len() as f64,
                format!(
                    "must hold one time a step of the path ({} steps)",
                    self.controls.len()
                ),
            ));
        }
        if let Some(&t) = times.iter().find(|t| !t.is_finite()) {
            return Err(invalid("times", t, "must be finite [s]"));
        }
        if let Some(w) = times.windows(2).find(|w| w[1] < w[0]) {
            return Err(invalid(
                "times",
                w[1],
                format!("go backwards: the step before is at {:e} s", w[0]),
            ));
        }
        Ok(())
    }
}

impl<'a> From<&'a [Control]> for Path<'a> {
    fn from(controls: &'a [Control]) -> Self {
        Path {
            controls,
            times: None,
        }
    }
}

impl<'a> From<&'a Vec<Control>> for Path<'a> {
    fn from(controls: &'a Vec<Control>) -> Self {
        Path::from(controls.as_slice())
    }
}

impl<'a, const N: usize> From<&'a [Control; N]> for Path<'a> {
    fn from(controls: &'a [Control; N]) -> Self {
        Path::from(controls.as_slice())
    }
}

/// Times [`ContactProblem::sweep`] halves the substeps of a step that does not converge.
pub const RETRIES: usize = 3;

/// The approaches `from -> to` in `steps` equal steps and back again (`2 steps + 1` values) \[m\].
pub fn approach_cycle(from: f64, to: f64, steps: usize) -> Vec<Control> {
    let steps = steps.max(1);
    let at = |k: usize| from + (to - from) * k as f64 / steps as f64;
    (0..=steps)
        .chain((0..steps).rev())
        .map(|k| Control::Approach(at(k)))
        .collect()
}

fn value(c: Control) -> f64 {
    match c {
        Control::Approach(v) | Control::Force(v) | Control::MeanPressure(v) => v,
        // A smaller central gap brings the bodies together.
        Control::CentralGap(g) => -g,
    }
}

/// The branch of each step of `path`: loading while the control moves the bodies together
/// (the first step counts as loading), unloading while it moves them apart; a repeated value
/// keeps the previous branch.
pub fn branches(path: &[Control]) -> Vec<Branch> {
    let mut out = Vec::with_capacity(path.len());
    let mut current = Branch::Loading;
    for (k, c) in path.iter().enumerate() {
        if k > 0 {
            let (a, b) = (value(path[k - 1]), value(*c));
            if b > a {
                current = Branch::Loading;
            } else if b < a {
                current = Branch::Unloading;
            }
        }
        out.push(current);
    }
    out
}

impl ContactProblem {
    /// Solves every control of `path` in order, at its time if it has one (each warm-started
    /// from the previous step; the first from `start`, else from apart), telling `observer`
    /// every iteration and every step; its [`Observer::step`] returns `false` to stop early.
    /// Returns the solved points.
    ///
    /// A step of approach that does not converge is solved again from the state before it, in
    /// twice as many substeps, up to [`RETRIES`] times (down to an eighth): near a jump a long
    /// step can leave a ring of cells cycling in and out of contact for ever, which shorter steps,
    /// each warm-started closer to its answer, avoid. Central-gap steps are not retried: the ones
    /// that fail sit at the fold of a jump out, where finer substeps did not help
    /// (`docs/decisions.md`). The solves of a retry share one iteration limit
    /// ([`Settings::max_iterations`]), so a step costs at most `1 + RETRIES` limits. The failed
    /// attempts' iterations and time are counted in the step's report. A step that still does not
    /// converge (or a load or central-gap step) is reported (in its
    /// [`crate::AdhesiveReport::termination`]) and the sweep goes on from it.
    ///
    /// `max_step` \[m\] keeps the sweep quasi-static: a step of approach (or of central gap) longer
    /// than it is split into equal substeps no longer than it, each solved and warm-started in
    /// turn, and only the last is returned. Without it a long unloading step jumps across the
    /// attached states the surfaces would pass through and can land on a less attached branch.
    /// How fine is fine enough depends on the problem (`docs/decisions.md`). Load-controlled
    /// steps are never split.
    ///
    /// On a viscoelastic body every step needs a time; a substep's is interpolated linearly
    /// between its step's and the one before (the start state's history gives the first).
    ///
    /// # Errors
    /// As [`ContactProblem::solve`]; a `max_step` that is not positive and finite; times
    /// that do not match the path or go backwards, or none on a viscoelastic body.
    pub fn sweep<'a>(
        &self,
        path: impl Into<Path<'a>>,
        max_step: Option<f64>,
        settings: &Settings,
        start: Option<AdhesiveState>,
        observer: &mut dyn Observer,
    ) -> Result<Vec<SweepPoint>> {
        let problem = self;
        let Path {
            controls: path,
            times,
        } = path.into();
        Path {
            controls: path,
            times,
        }
        .validate()?;
        if self.solid.is_some() && times.is_none() {
            return Err(SolverError::Incomplete(
                "the time of each step [s] on a viscoelastic body (a step time or a list of times)",
            ));
        }
        let times = times.filter(|_| self.solid.is_some());
        let mut previous_time = start
            .as_ref()
            .and_then(|s| s.contact.history.as_ref())
            .map(|h| h.time);
        if let Some(h) = max_step
            && !(h.is_finite() && h > 0.0)
        {
            return Err(invalid(
                "max_step",
                h,
                "the largest sweep step must be positive and finite [m]",
            ));
        }
        // Where the start state stands, for splitting the first step too.
        let mut previous = match (&start, path.first()) {
            (Some(s), Some(Control::Approach(_))) => Some(Control::Approach(s.contact.approach)),
            (Some(s), Some(Control::CentralGap(_))) => {
                let (ny, nx) = s.contact.gap.dim();
                Some(Control::CentralGap(s.contact.gap[[ny / 2, nx / 2]]))
            }
            (Some(s), Some(c @ (Control::Force(_) | Control::MeanPressure(_)))) => {
                let sum = s.contact.pressure.sum() + s.adhesive_pressure.sum();
                Some(match c {
                    Control::Force(_) => Control::Force(sum * self.operator.domain().cell_area()),
                    _ => Control::MeanPressure(sum / s.contact.pressure.len() as f64),
                })
            }
            _ => None,
        };
        count_substeps(&[previous.as_slice(), path].concat(), max_step)?;
        // The first step's branch follows from where the start state stands (a resumed sweep).
        let branch = match previous {
            Some(p) => branches(&[&[p], path].concat())[1..].to_vec(),
            None => branches(path),
        };
        let mut state = start;
        let mut points = Vec::with_capacity(path.len());
        for (k, &control) in path.iter().enumerate() {
            let mut limit = max_step;
            let mut spent: Option<(crate::adhesive::Iterations, usize, f64)> = None;
            let mut retries = 0;
            let (next, mut report, between, unconverged_substeps) = loop {
                let between = substeps(previous, control, limit);
                let mut unconverged_substeps = 0;
                let mut current: Option<AdhesiveState> = None;
                // A retry's solves share one iteration limit, so that a step no substeps can save
                // costs at most `1 + RETRIES` limits.
                let mut budget = settings.max_iterations;
                let time = times.map(|t| t[k]);
                let mut solve = |sub: Control, at: Option<f64>, current: &Option<AdhesiveState>| {
                    let from = current
                        .as_ref()
                        .or(state.as_ref())
                        .map_or(Start::Loading, Start::Warm);
                    let limited = Settings {
                        max_iterations: budget,
                        ..*settings
                    };
                    let used = if retries == 0 { settings } else { &limited };
                    let solid = problem.solid.as_ref();
                    let (next, report) =
                        crate::time::solve(problem.parts(), solid, sub, at, used, from, &mut |i, r| {
                            crate::observer::heard(observer, k, i, r)
                        })?;
                    budget = budget.saturating_sub(report.iterations.count());
                    match &mut spent {
                        Some((iterations, calls, time)) => {
                            iterations.accumulate(&report.iterations);
                            *calls += report.operator_calls;
                            *time += report.wall_time_s;
                        }
                        None => spent = Some((report.iterations, report.operator_calls, report.wall_time_s)),
                    }
                    Ok::<_, SolverError>((next, report))
                };
                let parts = between.len() + 1;
                for (i, &sub) in between.iter().enumerate() {
                    // Substeps' times between the step's and the one before (at it, without one).
                    let at = time.map(|t| {
                        let t0 = previous_time.unwrap_or(t);
                        t0 + (t - t0) * (i + 1) as f64 / parts as f64
                    });
                    let (next, report) = solve(sub, at, &current)?;
                    unconverged_substeps += usize::from(!report.converged());
                    current = Some(next);
                }
                let (next, report) = solve(control, time, &current)?;
                // Halve the substeps of a step that did not converge, from the state before it.
                let length = previous.and_then(|p| retried_length(p, control)).unwrap_or(0.0);
                let interrupted = report.termination == Termination::Interrupted;
                if report.converged() || interrupted || retries == RETRIES || length <= 0.0 {
                    break (next, report, between, unconverged_substeps);
                }
                retries += 1;
                limit = Some(length / (2 * (between.len() + 1)) as f64);
            };
            if let Some((iterations, calls, time)) = spent {
                report.iterations = iterations;
                report.operator_calls = calls;
                report.wall_time_s = time;
            }
            let point = SweepPoint {
                control,
                time: times.map(|t| t[k]),
                branch: branch[k],
                report,
                substeps: between.len(),
                unconverged_substeps,
                retries,
            };
            let go_on =
                observer.step(k, &point, &next) && point.report.termination != Termination::Interrupted;
            points.push(point);
            state = Some(next);
            previous = Some(control);
            previous_time = times.map(|t| t[k]);
            if !go_on {
                break;
            }
        }
        Ok(points)
    }
}

/// The length of the step `previous -> next` \[m\] when both are approaches: the steps
/// [`ContactProblem::sweep`] retries.
fn retried_length(previous: Control, next: Control) -> Option<f64> {
    match (previous, next) {
        (Control::Approach(a), Control::Approach(b)) => Some((b - a).abs()),
        _ => None,
    }
}

/// The most substeps one step of a sweep may be split into (before retries, which split up to
/// `2^RETRIES` times finer): beyond it a `max_step` is a typing error, not a sweep that ends.
pub const MAX_SUBSTEPS: usize = 100_000;

/// A step as (start, end, the control of a value, the number of equal parts).
type Split = (f64, f64, fn(f64) -> Control, f64);

/// The step from `previous` to `next`, if it is one that [`substeps`] splits under `max_step`.
fn split(previous: Option<Control>, next: Control, max_step: Option<f64>) -> Option<Split> {
    let (previous, h) = (previous?, max_step.filter(|h| h.is_finite() && *h > 0.0)?);
    let (a, b, make): (f64, f64, fn(f64) -> Control) = match (previous, next) {
        (Control::Approach(a), Control::Approach(b)) => (a, b, Control::Approach),
        (Control::CentralGap(a), Control::CentralGap(b)) => (a, b, Control::CentralGap),
        _ => return None,
    };
    // A step of exactly `h` written in decimals (4e-9 to 3e-9 by 1e-9) can exceed it by an
    // ulp: that is no reason to solve it twice.
    let parts = ((b - a).abs() / h * (1.0 - 1e-9)).ceil().max(1.0);
    Some((a, b, make, parts))
}

/// The controls strictly between `previous` and `next` that split the step into equal parts
/// no longer than `max_step` \[m\] (none for load control, a change of kind, or no positive
/// limit): the substeps [`ContactProblem::sweep`] solves before `next`. At most
/// [`MAX_SUBSTEPS`] times `2^RETRIES` (a sweep refuses more than [`MAX_SUBSTEPS`] before its
/// retries: [`count_substeps`]).
pub fn substeps(previous: Option<Control>, next: Control, max_step: Option<f64>) -> Vec<Control> {
    let Some((a, b, make, parts)) = split(previous, next, max_step) else {
        return Vec::new();
    };
    // A bound on the allocation for direct callers; a sweep's retries stay within it.
    let parts = parts.min(((MAX_SUBSTEPS << RETRIES) + 1) as f64) as usize;
    (1..parts)
        .map(|i| make(a + (b - a) * i as f64 / parts as f64))
        .collect()
}

/// The substeps a sweep along `path` solves in all (see [`substeps`]), counted without making
/// them.
///
/// # Errors
/// A step that `max_step` would split into more than [`MAX_SUBSTEPS`].
pub fn count_substeps(path: &[Control], max_step: Option<f64>) -> Result<usize> {
    let mut total = 0;
    for w in path.windows(2) {
        let parts = split(Some(w[0]), w[1], max_step).map_or(1.0, |s| s.3);
        if parts - 1.0 > MAX_SUBSTEPS as f64 {
            return Err(invalid(
                "max_step",
                max_step.unwrap_or(f64::NAN),
                format!(
                    "splits a step of the path into {parts:.3e} substeps (at most {MAX_SUBSTEPS}): give a \
                     larger --max-step [m] (by default the adhesive law's range)"
                ),
            ));
        }
        total += parts as usize - 1;
    }
    Ok(total)
}

/// What a load-approach cycle shows. Loads in N, approaches in m.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct CycleSummary {
    /// The most negative load on the unloading branch \[N\] (the pull-off force under
    /// displacement control; reported as a negative number), if there is a tensile load on an
    /// unloading branch.
    pub pull_off_force: Option<f64>,
    /// The approach at which it occurred \[m\].
    pub pull_off_approach: Option<f64>,
    /// Whether that load is the last step's and the surfaces are still attached there: the
    /// pull-off then lies beyond the path (retract further).
    pub pull_off_at_path_end: bool,
    /// The first loading step attached after a step apart \[m\] (the jump into contact lies
    /// between it and the step before); attached means some cell within the law's range
    /// ([`CyclePoint::attached_area_fraction`]), so that an adhesive neck without compressive
    /// contact counts. Reported only when the branches differ in load (by more than 1e-4 of
    /// the largest load) at some approach solved on both (hysteresis): a contact that grows
    /// from a point and shrinks back to it the same way is no jump.
    pub jump_in_approach: Option<f64>,
    /// The first unloading step apart after an attached step \[m\] (same condition).
    pub jump_out_approach: Option<f64>,
    /// Energy lost in the cycle \[J\]: the work `sum W d(delta)` done on the bodies around the
    /// closed part of the path's first out-and-back (its first two monotone legs, over the
    /// approaches both cover; trapezoidal rule, linear at the ends), >= 0 for a dissipative
    /// cycle. `None` when the path never turns back. A leg's work beyond the other's range is
    /// no loss, and is left out (see [`closed_loop_work`]).
    pub hysteresis_energy: Option<f64>,
    /// Energy dissipated by yielding over the sweep \[J\]: the steps' plastic work, `H` times
    /// the permanent set's added volume (0 for an elastic surface).
    pub plastic_work: f64,
    /// Energy dissipated by a viscoelastic body's dashpots over the sweep \[J\] (0 when
    /// elastic; NaN when a step's is unknown).
    pub viscous_work: f64,
    /// On a path that starts and ends apart (no cell attached, or no load at all) at the same
    /// approach, the work `sum W d(delta)` done along all of it (trapezoidal rule) less the
    /// dashpots', yielding's and the elastic energy the body still stores at its end \[J\]:
    /// what the adhesive jumps lost. With
    /// [`CycleSummary::viscous_work`] it splits a viscoelastic body's hysteresis into viscous
    /// and adhesive. `None` on other paths, or when an energy is unknown.
    pub adhesive_work: Option<f64>,
    /// Whether every step converged (`converged` when serialised).
    #[serde(rename = "converged")]
    pub all_converged: bool,
}

/// What [`summarize`] needs of one step (so that a sweep read back from a file can be
/// summarised too). SI units.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct CyclePoint {
    /// Approach \[m\].
    pub approach: f64,
    /// Total load \[N\].
    pub load: f64,
    /// Fraction of cells in contact [-].
    pub contact_area_fraction: f64,
    /// Fraction of cells within the adhesive law's range, contact included [-].
    pub attached_area_fraction: f64,
    /// Direction of the step.
    pub branch: Branch,
    /// Whether the step converged.
    pub converged: bool,
    /// Energy dissipated by yielding in the step \[J\].
    pub plastic_work: f64,
    /// When the step was reached \[s\], on a path with times.
    pub time: Option<f64>,
    /// Elastic energy the body stores \[J\] (NaN when unknown: read from a curve written
    /// without it).
    pub elastic_energy: f64,
    /// Energy the body's dashpots dissipated over the step \[J\] (NaN when unknown).
    pub viscous_work: f64,
}

impl From<&SweepPoint> for CyclePoint {
    fn from(p: &SweepPoint) -> Self {
        CyclePoint {
            approach: p.report.approach,
            load: p.report.load,
            contact_area_fraction: p.report.contact_area_fraction,
            attached_area_fraction: p.report.attached_area_fraction,
            branch: p.branch,
            converged: p.report.converged(),
            plastic_work: p.report.yielding.plastic_work,
            time: p.time,
            elastic_energy: p.report.elastic_energy,
            viscous_work: p.report.viscous_work,
        }
    }
}

/// Summarises a sweep over approaches (see [`CycleSummary`]).
pub fn summarize(points: &[CyclePoint]) -> CycleSummary {
    let mut pull_off: Option<(f64, f64, usize)> = None;
    let (mut jump_in, mut jump_out) = (None, None);
    for (k, p) in points.iter().enumerate() {
        if p.branch == Branch::Unloading && pull_off.is_none_or(|(w, _, _)| p.load < w) {
            pull_off = Some((p.load, p.approach, k));
        }
        if k > 0 {
            let prev = &points[k - 1];
            let (was, is) = (prev.attached_area_fraction > 0.0, p.attached_area_fraction > 0.0);
            if p.branch == Branch::Loading && !was && is && jump_in.is_none() {
                jump_in = Some(p.approach);
            }
            if p.branch == Branch::Unloading && was && !is && jump_out.is_none() {
                jump_out = Some(p.approach);
            }
        }
    }
    let pull_off = pull_off.filter(|p| p.0 < 0.0);
    let scale = points.iter().map(|p| p.approach.abs()).fold(0.0, f64::max);
    let same = |a: f64, b: f64| (a - b).abs() <= 1e-9 * scale;
    let max_load = points.iter().map(|p| p.load.abs()).fold(0.0, f64::max);
    let hysteresis = points.iter().filter(|u| u.branch == Branch::Unloading).any(|u| {
        points.iter().any(|l| {
            l.branch == Branch::Loading
                && same(l.approach, u.approach)
                && (l.load - u.load).abs() > 1e-4 * max_load
        })
    });
    let at_end =
        pull_off.is_some_and(|(_, _, k)| k + 1 == points.len() && points[k].attached_area_fraction > 0.0);
    CycleSummary {
        pull_off_force: pull_off.map(|p| p.0),
        pull_off_approach: pull_off.map(|p| p.1),
        pull_off_at_path_end: at_end,
        jump_in_approach: jump_in.filter(|_| hysteresis),
        jump_out_approach: jump_out.filter(|_| hysteresis),
        hysteresis_energy: closed_loop_work(points),
        plastic_work: points.iter().map(|p| p.plastic_work).sum(),
        viscous_work: points.iter().map(|p| p.viscous_work).sum(),
        adhesive_work: adhesive_work(points),
        all_converged: points.iter().all(|p| p.converged),
    }
}

/// The work `sum W d(delta)` \[J\] around the closed part of the first out-and-back of
/// `points`: the first leg up to its first turn and the leg back, each over the approaches both
/// cover (a leg that goes further than the other contributes only inside the common range,
/// with the load interpolated linearly at its ends). `None` when the path does not turn.
pub fn closed_loop_work(points: &[CyclePoint]) -> Option<f64> {
    let a: Vec<f64> = points.iter().map(|p| p.approach).collect();
    // The direction of each step, steps of zero length skipped.
    let steps: Vec<(usize, f64)> = (1..a.len())
        .map(|k| (k, (a[k] - a[k - 1]).signum()))
        .filter(|(k, d)| *d != 0.0 && a[*k] != a[*k - 1])
        .collect();
    let first = steps.first()?.1;
    let turn = steps.iter().find(|(_, d)| *d != first)?.0 - 1;
    let end = steps
        .iter()
        .filter(|(k, _)| *k > turn)
        .find(|(_, d)| *d == first)
        .map_or(a.len() - 1, |(k, _)| k - 1);
    let near = |x: f64| (x - a[turn]).abs();
    let other_end = if near(a[0]) < near(a[end]) { a[0] } else { a[end] };
    let (lo, hi) = (other_end.min(a[turn]), other_end.max(a[turn]));
    Some(clipped_work(&points[..=turn], lo, hi) + clipped_work(&points[turn..=end], lo, hi))
}

/// See [`CycleSummary::adhesive_work`].
fn adhesive_work(points: &[CyclePoint]) -> Option<f64> {
    let (first, last) = (points.first()?, points.last()?);
    // Apart: no cell within the law's range, or (a law without attraction) no load at all.
    let apart =
        |p: &CyclePoint| p.attached_area_fraction == 0.0 || (p.contact_area_fraction == 0.0 && p.load == 0.0);
    // Back where it started, so that the law's energy (not known for every law) is the same.
    let scale = points.iter().map(|p| p.approach.abs()).fold(0.0, f64::max);
    let returned = (first.approach - last.approach).abs() <= 1e-9 * scale;
    if points.len() < 2 || !apart(first) || !apart(last) || !returned {
        return None;
    }
    let work: f64 = points
        .windows(2)
        .map(|w| 0.5 * (w[0].load + w[1].load) * (w[1].approach - w[0].approach))
        .sum();
    let lost: f64 = points[1..].iter().map(|p| p.viscous_work + p.plastic_work).sum();
    let rest = work - lost - (last.elastic_energy - first.elastic_energy);
    rest.is_finite().then_some(rest)
}

/// `sum W d(delta)` along `leg` over approaches in `[lo, hi]` only.
fn clipped_work(leg: &[CyclePoint], lo: f64, hi: f64) -> f64 {
    leg.windows(2)
        .map(|w| {
            let (p, q) = (w[0], w[1]);
            if p.approach == q.approach {
                return 0.0;
            }
            let load = |x: f64| p.load + (x - p.approach) / (q.approach - p.approach) * (q.load - p.load);
            let (x1, x2) = (p.approach.clamp(lo, hi), q.approach.clamp(lo, hi));
            0.5 * (load(x1) + load(x2)) * (x2 - x1)
        })
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn point(approach: f64, load: f64, contact: f64, attached: f64, branch: Branch) -> CyclePoint {
        CyclePoint {
            approach,
            load,
            contact_area_fraction: contact,
            attached_area_fraction: attached,
            branch,
            converged: true,
            plastic_work: 0.0,
            time: None,
            elastic_energy: 0.0,
            viscous_work: 0.0,
        }
    }

    #[test]
    fn an_adhesive_neck_without_contact_is_still_attached() {
        use Branch::{Loading, Unloading};
        let cycle = [
            point(-2.0, -0.1, 0.0, 0.0, Loading),
            point(-1.0, -0.2, 0.0, 0.0, Loading),
            point(0.0, -0.7, 0.01, 0.02, Loading),
            point(1.0, 0.5, 0.05, 0.06, Loading),
            point(0.0, -0.7, 0.01, 0.02, Unloading),
            point(-1.0, -0.8, 0.0, 0.01, Unloading),
            // A neck: no compressive contact, still attached and pulling hard.
            point(-2.0, -0.6, 0.0, 0.005, Unloading),
            point(-3.0, -0.05, 0.0, 0.0, Unloading),
        ];
        let s = summarize(&cycle);
        assert_eq!(s.jump_in_approach, Some(0.0));
        assert_eq!(s.jump_out_approach, Some(-3.0));
        assert_eq!(s.pull_off_force, Some(-0.8));
        assert_eq!(s.pull_off_approach, Some(-1.0));
        assert!(!s.pull_off_at_path_end);
        // Cut short while still attached and pulling harder: the pull-off lies beyond.
        let s = summarize(&cycle[..6]);
        assert_eq!(s.pull_off_force, Some(-0.8));
        assert!(s.pull_off_at_path_end);
    }

    #[test]
    fn the_hysteresis_is_the_work_around_the_closed_part_of_the_cycle_only() {
        use Branch::{Loading, Unloading};
        let at = |pairs: &[(f64, f64, Branch)]| -> Vec<CyclePoint> {
            pairs.iter().map(|&(a, w, b)| point(a, w, 0.0, 0.0, b)).collect()
        };
        // In at zero load, back through -1 N, and on past the start: the loop over [0, 2] holds
        // 0.5 + 1 J; the way back's last metre (1 J more), beyond where the cycle began, is no
        // loss.
        let cycle = at(&[
            (0.0, 0.0, Loading),
            (1.0, 0.0, Loading),
            (2.0, 0.0, Loading),
            (1.0, -1.0, Unloading),
            (0.0, -1.0, Unloading),
            (-1.0, -1.0, Unloading),
        ]);
        assert_eq!(summarize(&cycle).hysteresis_energy, Some(1.5));
        // The path, 0.07 -> 0.015 -> 0.075, with the same load both ways: no loss,
        // however far the way back overshoots, and within a step (linear ends).
        let there: Vec<(f64, f64, Branch)> = (0..=11)
            .map(|k| 0.07 - 0.005 * k as f64)
            .map(|a| (a, 1e-3 * (0.07 - a).powi(2), Loading))
            .collect();
        let back: Vec<(f64, f64, Branch)> = (1..=12)
            .map(|k| 0.015 + 0.005 * k as f64)
            .map(|a| (a, 1e-3 * (0.07 - a).powi(2), Unloading))
            .collect();
        let w = summarize(&at(&[there, back].concat())).hysteresis_energy.unwrap();
        assert!(w.abs() < 1e-15, "{w}");
        // A path that never turns holds no cycle.
        assert_eq!(summarize(&cycle[..3]).hysteresis_energy, None);
    }

    #[test]
    fn long_steps_split_into_equal_substeps_no_longer_than_the_limit() {
        use Control::{Approach, CentralGap, MeanPressure};
        let values = |v: Vec<Control>| -> Vec<f64> {
            v.into_iter()
                .map(|c| match c {
                    Approach(a) | CentralGap(a) => a,
                    _ => f64::NAN,
                })
                .collect()
        };
        // 1 -> 0 in steps of at most 0.3: four parts of 0.25, three intermediate controls.
        assert_eq!(
            values(substeps(Some(Approach(1.0)), Approach(0.0), Some(0.3))),
            [0.75, 0.5, 0.25]
        );
        assert_eq!(
            values(substeps(Some(CentralGap(0.0)), CentralGap(0.5), Some(0.25))),
            [0.25]
        );
        // Short steps, no previous control, no limit, a bad limit, load control or a change of
        // kind: nothing in between.
        assert!(substeps(Some(Approach(0.0)), Approach(0.2), Some(0.3)).is_empty());
        assert!(substeps(Some(Approach(4e-9)), Approach(3e-9), Some(1e-9)).is_empty());
        assert_eq!(
            substeps(Some(Approach(4e-9)), Approach(2e-9), Some(1e-9)).len(),
            1
        );
        assert!(substeps(Some(Approach(0.0)), Approach(0.0), Some(0.3)).is_empty());
        assert!(substeps(None, Approach(1.0), Some(0.3)).is_empty());
        assert!(substeps(Some(Approach(0.0)), Approach(1.0), None).is_empty());
        assert!(substeps(Some(Approach(0.0)), Approach(1.0), Some(0.0)).is_empty());
        assert!(substeps(Some(Approach(0.0)), Approach(1.0), Some(f64::NAN)).is_empty());
        assert!(substeps(Some(MeanPressure(0.0)), MeanPressure(1.0), Some(0.3)).is_empty());
        assert!(substeps(Some(CentralGap(1.0)), Approach(0.0), Some(0.3)).is_empty());
    }
}
