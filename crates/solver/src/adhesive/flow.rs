//! Overdamped flow: adhesive contact under any law with a finite stiffness, the line and
//! surface laws included, as the state the surface relaxes to when each cell moves at a speed
//! proportional to the force on it, `M dg/dt = -r`, over the gap problem of `gap_problem` (the
//! unknown, constraints and force balance `r = S (g - g0) - p(g)` of the energy descent and
//! Newton), integrated by explicit projected steps.
//!
//! The mobility is `1 / M` with `M = S_ii + max(K_ii, 0)`, the cell's own elastic stiffness
//! and the stable part of the law's (`K = -dp/dg`, just above the wall many times a cell's):
//! each step moves a cell by [`STEP`] times the displacement that would balance it were its
//! neighbours held, then projects onto `g >= 0` (and the prescribed mean gap). A state the flow
//! comes to rest on is stable: perturbed, it flows back; a saddle or an unstable branch repels
//! it. This holds for laws without an energy too, which is why the flow is the method for the
//! paper's surface law (Eq. 11) on cells coarser than the process zone: there every cell holds
//! on or lets go alone, Eq. 11's forces are not the gradient of any energy, and Newton and the
//! loops circle between states (`docs/validation.md`), where the flow settles.
//!
//! Cost: one application of the stiffness and one evaluation of the law an iteration (two for
//! laws without a local potential, whose stiffness is probed); many iterations, since the
//! explicit step moves long wavelengths slowly (`docs/solvers.md`).

use super::driver::Driver;
use super::gap_problem::{Energy, Point, Setup, check_control, finish, setup};
use super::{AdhesiveMethod, AdhesiveReport, AdhesiveState, Iterations, Job};
use crate::error::{Result, SolverError};
use crate::report::Termination;
use ndarray::Array2;
use std::time::Instant;

/// The explicit step, in units of a cell's relaxation `1 / M`: below the stability limit of
/// the stiffest elastic mode, whose stiffness is about 1.85 times a cell's own on a periodic
/// grid (the corner of the Brillouin zone against the mean of `E* |q| / 2`).
const STEP: f64 = 0.5;

/// The overdamped flow of the module docs.
pub(super) struct Flow;

impl AdhesiveMethod for Flow {
    fn check(&self, job: &Job) -> Result<()> {
        energy(job).map(|_| ())
    }

    fn solve(
        &self,
        job: &Job,
        observer: &mut dyn FnMut(usize, f64),
    ) -> Result<(AdhesiveState, AdhesiveReport)> {
        solve(job, energy(job)?, observer)
    }
}

/// What the law gives the gap problem (its energy where it has one, which saves probing its
/// stiffness), if the flow can solve this problem; else why not.
fn energy<'a>(job: &Job<'a>) -> Result<Energy<'a>> {
    let law = job.law;
    if !law.stiffness_bound().is_finite() {
        return Err(SolverError::Unsupported(format!(
            "the overdamped flow needs a law with a finite stiffness, not `{}` (use `accelerated`)",
            law.name()
        )));
    }
    check_control(job, "the overdamped flow")?;
    Ok(Energy::of(law))
}

fn solve<'a>(
    job: &Job<'a>,
    energy: Energy<'a>,
    observer: &mut dyn FnMut(usize, f64),
) -> Result<(AdhesiveState, AdhesiveReport)> {
    let started = Instant::now();
    let Job { law, settings, .. } = *job;
    let Setup {
        mut problem,
        mut x,
        delta,
        load,
    } = setup(job, energy)?;
    let unknown = x.gap.dim();
    let mut sums = problem.project_gradient(&mut x);
    let mut velocity = Array2::zeros(unknown);
    let mut trial = Point::new(Array2::zeros(unknown));
    let scale = job.residual_scale();
    let mut driver = Driver::new(settings, observer, started);
    let mut steps = 0;
    loop {
        if driver.stop(steps, sums.max * scale, true) {
            break;
        }
        if load.is_some_and(|p| p < 0.0) && x.min_gap > 1e3 * law.range() {
            // Pulled by more than any attraction at these gaps can hold: flying apart.
            driver.termination = Termination::PulledOff;
            break;
        }
        steps += 1;
        problem.precondition(&x, &x.gradient, &mut velocity);
        problem.step_and_project(&x.gap, &velocity, -STEP, &mut trial.gap, None);
        problem.evaluate(&mut trial)?;
        std::mem::swap(&mut x, &mut trial);
        sums = problem.project_gradient(&mut x);
    }
    let outcome = driver.finish(Iterations::Flow { steps }, problem.calls);
    Ok(finish(job, &problem, x, &sums, (delta, load), outcome))
}
