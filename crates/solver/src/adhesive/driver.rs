//! What every adhesive method's iteration loop shares: the observer, the residual history, the
//! tolerance and the iteration limit, stall detection, and the outcome a solve ends with. A
//! method decides what a stall means for it (the dual loop changes its mixing, Newton gives up).

use super::Iterations;
use super::job::Outcome;
use crate::method::Settings;
use crate::report::Termination;
use std::time::Instant;

/// A residual is progress when it falls below this fraction of the best one so far.
const PROGRESS: f64 = 0.9;

pub(super) struct Driver<'a> {
    tolerance: f64,
    max_iterations: usize,
    observer: &'a mut dyn FnMut(usize, f64) -> bool,
    history: Vec<f64>,
    best: f64,
    improved_at: usize,
    started: Instant,
    /// How the solve ended: [`Termination::MaxIterations`] until something else is set.
    pub termination: Termination,
}

impl<'a> Driver<'a> {
    /// A solve that started at `started`, under `settings`' tolerance and iteration limit.
    pub fn new(
        settings: &Settings,
        observer: &'a mut dyn FnMut(usize, f64) -> bool,
        started: Instant,
    ) -> Self {
        Driver {
            tolerance: settings.tolerance,
            max_iterations: settings.max_iterations,
            observer,
            history: Vec::new(),
            best: f64::INFINITY,
            improved_at: 0,
            started,
            termination: Termination::MaxIterations,
        }
    }

    /// Records iteration `k`'s residual and shows it to the observer; whether to stop: the
    /// residual is below the tolerance and the method `accepts` the iterate (converged), the
    /// observer asks to stop (interrupted), or `k` is the iteration limit.
    pub fn stop(&mut self, k: usize, residual: f64, accepts: bool) -> bool {
        self.history.push(residual);
        if !(self.observer)(k, residual) {
            self.termination = Termination::Interrupted;
            return true;
        }
        if residual < self.tolerance && accepts {
            self.termination = Termination::Converged;
            return true;
        }
        k == self.max_iterations
    }

    /// Records the residual of another method's iteration `k` that the solve hands over to,
    /// and shows it to the observer; whether to go on.
    pub fn record(&mut self, k: usize, residual: f64) -> bool {
        self.history.push(residual);
        (self.observer)(k, residual)
    }

    /// The last residual recorded.
    pub fn last(&self) -> Option<f64> {
        self.history.last().copied()
    }

    /// The residual recorded before the last.
    pub fn previous(&self) -> Option<f64> {
        self.history.len().checked_sub(2).map(|i| self.history[i])
    }

    /// Iterations from the last progress to iteration `k`, whose residual is `residual`.
    pub fn since_progress(&mut self, k: usize, residual: f64) -> usize {
        if residual < PROGRESS * self.best {
            (self.best, self.improved_at) = (residual, k);
        }
        k - self.improved_at
    }

    /// Counts the iterations without progress from `k` again (after a change of strategy).
    pub fn restart_stall_count(&mut self, k: usize) {
        self.improved_at = k;
    }

    /// Counts one iteration fewer without progress (an iteration that moves towards a better
    /// state while its residual rises).
    pub fn defer_stall(&mut self) {
        self.improved_at += 1;
    }

    /// The outcome of the solve.
    pub fn finish(self, iterations: Iterations, operator_calls: usize) -> Outcome {
        Outcome {
            iterations,
            operator_calls,
            history: self.history,
            termination: self.termination,
            started: self.started,
        }
    }
}
