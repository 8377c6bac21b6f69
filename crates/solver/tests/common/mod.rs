//! What the solver's tests share: a problem from parts they keep using, and observers.
#![allow(dead_code)]

use elastic::Compliance;
use ljadhesion::AdhesionLaw;
use ndarray::ArrayView2;
use solver::{AdhesiveState, ContactProblem, Iterations, Observer, SweepPoint};

/// The problem of these parts (cloned: the tests go on using them).
pub fn problem<O, L>(op: &O, law: &L, g0: ArrayView2<f64>) -> ContactProblem
where
    O: Compliance + Clone + 'static,
    L: AdhesionLaw + Clone + 'static,
{
    ContactProblem::new(op.clone(), g0.to_owned(), law.clone()).unwrap()
}

/// Calls `f(index, point, state)` after every step of a sweep; `false` stops it.
pub struct Steps<F>(F);

pub fn steps<F: FnMut(usize, &SweepPoint, &AdhesiveState) -> bool>(f: F) -> Steps<F> {
    Steps(f)
}

impl<F: FnMut(usize, &SweepPoint, &AdhesiveState) -> bool> Observer for Steps<F> {
    fn step(&mut self, index: usize, point: &SweepPoint, state: &AdhesiveState) -> bool {
        (self.0)(index, point, state)
    }
}

/// The work a method did below its own iterations: inner or Krylov iterations, or the
/// descent's iterations.
pub fn inner(iterations: &Iterations) -> usize {
    iterations.inner().unwrap_or(iterations.count())
}
