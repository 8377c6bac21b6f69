//! The pull-off force under displacement control: unload in coarse steps until the load has
//! passed its minimum, then solve again between the minimum's neighbours in finer steps (the
//! pull-off of a DMT-like or rough contact sits in a sharp corner of the load curve).

use crate::adhesive::AdhesiveState;
use crate::error::{Result, invalid};
use crate::method::Settings;
use crate::observer::Observer;
use crate::observer::SweepPoint;
use crate::options::Control;
use crate::problem::ContactProblem;

/// How [`ContactProblem::pull_off`] unloads.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct PullOffSearch {
    /// The coarse unloading step \[m\], positive.
    pub step: f64,
    /// The lowest approach the coarse unloading reaches \[m\] (the last step lands on it to
    /// round-off).
    pub floor: f64,
    /// Stop the coarse unloading once the load has come back above this fraction (in (0, 1])
    /// of the most negative load so far: the minimum has been passed. `None` unloads to the
    /// floor.
    pub recovery: Option<f64>,
    /// Fine steps per coarse step around the coarse minimum (1: no refinement).
    pub refinement: usize,
    /// The unloading speed \[m/s\] on a viscoelastic body (each step lasts its length over
    /// it); an elastic body ignores it.
    pub rate: Option<f64>,
}

/// What [`ContactProblem::pull_off`] found.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct PullOff {
    /// Minus the most negative load on any step, coarse or fine \[N\]; 0 when none is tensile.
    pub force: f64,
    /// The approach of that step \[m\].
    pub approach: f64,
    /// The coarse unloading steps, in order.
    pub coarse: Vec<SweepPoint>,
    /// The fine steps strictly between the coarse minimum's neighbours, in order.
    pub refined: Vec<SweepPoint>,
}

impl PullOffSearch {
    /// The steps a search from approach `from` \[m\] solves at most: its coarse steps to the
    /// floor and its fine ones.
    pub fn most_steps(&self, from: f64) -> usize {
        self.coarse_steps(from) + 2 * self.refinement.max(1) - 1
    }

    fn coarse_steps(&self, from: f64) -> usize {
        ((from - self.floor) / self.step).round().max(1.0) as usize
    }

    fn check(&self, from: f64) -> Result<()> {
        if !(self.step.is_finite() && self.step > 0.0) {
            return Err(invalid(
                "step",
                self.step,
                "the unloading step must be positive and finite [m]",
            ));
        }
        if !(self.floor.is_finite() && self.floor < from) {
            return Err(invalid(
                "floor",
                self.floor,
                "the lowest approach must be finite and below the start's [m]",
            ));
        }
        if let Some(r) = self.recovery
            && !(r > 0.0 && r <= 1.0)
        {
            return Err(invalid(
                "recovery",
                r,
                "the recovered fraction of the minimum load must be in (0, 1]",
            ));
        }
        if let Some(v) = self.rate
            && !(v.is_finite() && v > 0.0)
        {
            return Err(invalid(
                "rate",
                v,
                "the unloading speed must be finite and > 0 m/s",
            ));
        }
        if self.refinement == 0 {
            return Err(invalid(
                "refinement",
                0.0,
                "at least one fine step per coarse step",
            ));
        }
        Ok(())
    }
}

/// Follows the coarse unloading: the lowest load, the state before it, and when to stop.
struct Tracker<'a> {
    inner: &'a mut dyn Observer,
    recovery: Option<f64>,
    lowest: Option<(usize, f64)>,
    last: AdhesiveState,
    before_lowest: Option<AdhesiveState>,
}

impl Observer for Tracker<'_> {
    fn iteration(&mut self, step: usize, iteration: usize, residual: f64) {
        self.inner.iteration(step, iteration, residual);
    }

    fn interrupted(&mut self) -> bool {
        self.inner.interrupted()
    }

    fn step(&mut self, k: usize, point: &SweepPoint, state: &AdhesiveState) -> bool {
        let go_on = self.inner.step(k, point, state);
        let load = point.report.load;
        let previous = std::mem::replace(&mut self.last, state.clone());
        if self.lowest.is_none_or(|(_, min)| load < min) {
            self.lowest = Some((k, load));
            self.before_lowest = Some(previous);
        }
        let min = self.lowest.map_or(0.0, |(_, min)| min);
        let recovered = self.recovery.is_some_and(|r| min < 0.0 && load > r * min);
        go_on && !recovered
    }
}

impl ContactProblem {
    /// Unloads from `start` (an attached state) by approach steps of `search.step` towards
    /// `search.floor` (a sweep: see [`ContactProblem::sweep`] for its retries), stopping early
    /// once the load has recovered (`search.recovery`); then sweeps again from the step before
    /// the lowest load to the step after it in `search.refinement` times finer steps. The
    /// observer sees the coarse sweep's steps, then the fine sweep's (numbered from 0 again);
    /// `false` from it ends the coarse unloading.
    ///
    /// # Errors
    /// As [`ContactProblem::sweep`]; a search whose step is not positive, whose floor is not
    /// below the start's approach, whose recovery is outside (0, 1] or whose refinement is 0.
    pub fn pull_off(
        &self,
        search: &PullOffSearch,
        settings: &Settings,
        start: AdhesiveState,
        observer: &mut dyn Observer,
    ) -> Result<PullOff> {
        let from = start.contact.approach;
        search.check(from)?;
        let steps = search.coarse_steps(from);
        let path: Vec<Control> = (1..=steps)
            .map(|k| Control::Approach(from - k as f64 * search.step))
            .collect();
        let mut tracker = Tracker {
            inner: &mut *observer,
            recovery: search.recovery,
            lowest: None,
            last: start.clone(),
            before_lowest: None,
        };
        // On a viscoelastic body each step takes its length over the unloading speed.
        let clock = match (&self.solid, search.rate) {
            (Some(_), Some(rate)) => Some((rate, start.contact.history.as_ref().map_or(0.0, |h| h.time))),
            (Some(_), None) => {
                return Err(crate::error::SolverError::Incomplete(
                    "the unloading speed [m/s] of a pull-off search on a viscoelastic body",
                ));
            }
            (None, _) => None,
        };
        let timed = |path: &[Control], from: f64, t0: f64| -> Option<Vec<f64>> {
            clock.map(|(rate, _)| {
                path.iter()
                    .map(|c| match c {
                        Control::Approach(a) => t0 + (from - a).abs() / rate,
                        _ => t0,
                    })
                    .collect()
            })
        };
        let times = timed(&path, from, clock.map_or(0.0, |c| c.1));
        let coarse = self.sweep(
            crate::sweep::Path {
                controls: &path,
                times: times.as_deref(),
            },
            None,
            settings,
            Some(start),
            &mut tracker,
        )?;
        let (lowest, before) = (tracker.lowest, tracker.before_lowest);
        let mut refined = Vec::new();
        if let (Some((k, _)), Some(before), true) = (lowest, before, search.refinement > 1) {
            let a = if k == 0 {
                from
            } else {
                coarse[k - 1].report.approach
            };
            let b = coarse
                .get(k + 1)
                .map_or(a - 2.0 * search.step, |p| p.report.approach);
            let parts = 2 * search.refinement;
            let fine: Vec<Control> = (1..parts)
                .map(|j| Control::Approach(a + (b - a) * j as f64 / parts as f64))
                .collect();
            let t0 = before.contact.history.as_ref().map_or(0.0, |h| h.time);
            let times = timed(&fine, a, t0);
            let path = crate::sweep::Path {
                controls: &fine,
                times: times.as_deref(),
            };
            refined = self.sweep(path, None, settings, Some(before), observer)?;
        }
        let (force, approach) = coarse
            .iter()
            .chain(&refined)
            .map(|p| (p.report.load, p.report.approach))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .map_or((0.0, from), |(load, approach)| (-load.min(0.0), approach));
        Ok(PullOff {
            force,
            approach,
            coarse,
            refined,
        })
    }
}
