//! Energy descent: adhesive contact under a local potential law as one bound-constrained
//! minimisation over the gap (or the displacement) of `gap`, with no outer loop (the
//! constrained nonlinear conjugate gradients of Bugnicourt et al., Tribol. Lett. 66:29, 2018,
//! which ContactMechanics/Adhesion also uses).
//!
//! Each iteration takes the conjugate direction of the projected gradient (Polak-Ribiere,
//! restarted when it is not a descent direction or a step was cut), preconditioned by the
//! diagonal of the curvature `S_ii + max(V'', 0)`: just above the wall the Lennard-Jones law
//! is 10-30 times stiffer than a cell, and those cells otherwise set the pace. Then it takes a
//! step from the exact curvature `S + V''` along it (only its positive part when the law makes
//! it negative) and projects onto the constraints; a step that would raise the energy is cut
//! to the minimiser of a parabola through the energies seen, so every iterate lowers the
//! energy. A descent method settles on stable states only: near a jump it stays on its branch
//! up to the fold, where a fixed-point iteration on the adhesive pressure can also land on the
//! unstable branch between.
//!
//! Under a hardness the wall is the kink of `gap`'s module docs (a cell may yield below it),
//! taken with the laws of a cell's own gap: a yielded cell of a field energy would pull on its
//! neighbours through an energy the kink's tangent does not continue.
//!
//! Two operator applications per iteration (the direction and the trial gap), against one per
//! inner iteration times many inner iterations per outer one in the dual loop.

use super::driver::Driver;
use super::gap::{Energy, Point, Setup, finish, on_wall, setup};
use super::job::{AdhesiveMethod, Job};
use super::{AdhesiveReport, AdhesiveState, Iterations};
use crate::error::{Result, SolverError};
use crate::fields::{flat, flat_mut};
use crate::report::Termination;
use ndarray::Array2;
use rayon::prelude::*;
use std::time::Instant;

/// Cuts of a step that would raise the energy before the solve gives up.
const MAX_CUTS: usize = 40;

/// The energy descent of the module docs.
pub(super) struct EnergyDescent;

impl AdhesiveMethod for EnergyDescent {
    fn check(&self, job: &Job) -> Result<()> {
        potential(job).map(|_| ())
    }

    fn solve(
        &self,
        job: &Job,
        observer: &mut dyn FnMut(usize, f64) -> bool,
    ) -> Result<(AdhesiveState, AdhesiveReport)> {
        solve(job, potential(job)?, observer)
    }

    fn peak_bytes(&self, cells: f64, periodic: bool) -> f64 {
        super::gap::peak_bytes(cells, periodic)
    }
}

/// The law's energy, if the descent can solve this problem; else why not.
fn potential<'a>(job: &Job<'a>) -> Result<Energy<'a>> {
    let law = job.law;
    let potential = match Energy::of(law) {
        Energy::None => {
            return Err(SolverError::Unsupported(format!(
                "energy descent needs a law with an energy (point, surface-energy, exponential), \
                 not `{}`",
                law.name()
            )));
        }
        Energy::Field(_) if job.interface.hardness.is_some() => {
            return Err(SolverError::Unsupported(format!(
                "energy descent takes a hardness with the laws of a cell's own gap (point, \
                 exponential, none), not `{}`, whose yielded cells would pull on their \
                 neighbours; use `newton`, `flow` or `accelerated`",
                law.name()
            )));
        }
        energy => energy,
    };
    super::gap::check_control(job, "energy descent")?;
    Ok(potential)
}

/// Solves under approach control or, periodic only, load control by the descent of the
/// module docs, with the law's `potential`.
pub(super) fn solve<'a>(
    job: &Job<'a>,
    potential: Energy<'a>,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<(AdhesiveState, AdhesiveReport)> {
    let started = Instant::now();
    let Job { law, settings, .. } = *job;
    let Setup {
        mut problem,
        mut x,
        delta,
        load,
    } = setup(job, potential)?;
    let unknown = x.gap.dim();
    let mut direction = Array2::zeros(unknown);
    let mut sums = problem.project_gradient(&mut x);
    let mut z = Array2::zeros(unknown);
    let [mut zr, _] = problem.precondition(&x, &direction, &mut z);
    direction.zip_mut_with(&z, |d, &z| *d = -z);
    let mut slope = -zr;
    let mut trial = Point::new(Array2::zeros(unknown));
    let mut s_direction = Array2::zeros(unknown);
    let (mx, my, nx, ny) = (problem.mx, problem.my, problem.nx, problem.ny);
    let yields = problem.cap.is_finite();

    let scale = job.residual_scale();
    let mut driver = Driver::new(settings, observer, started);
    let mut iterations = 0;
    loop {
        let residual = sums.max * scale;
        if driver.stop(iterations, residual, true) {
            break;
        }
        if load.is_some_and(|p| p < 0.0) && x.min_gap > 1e3 * law.range() {
            // Pulled by more than any attraction at these gaps can hold: flying apart.
            driver.termination = Termination::PulledOff;
            break;
        }
        iterations += 1;
        problem
            .stiffness
            .apply(direction.view(), s_direction.view_mut(), &mut problem.ws)?;
        problem.calls += 1;
        let (ds, ss, cs) = (flat(&direction), flat(&s_direction), flat(&x.curvature));
        let [elastic_curv, law_curv, law_pos] = crate::sum::ordered(my, |j| {
            let mut sums = [0.0; 3];
            for k in j * mx..(j + 1) * mx {
                let d2 = ds[k] * ds[k];
                sums[0] += ds[k] * ss[k];
                sums[1] += cs[k] * d2;
                sums[2] += cs[k].max(0.0) * d2;
            }
            sums
        });
        // The curvature of the energy along the direction; where the law makes it negative
        // (attraction stronger than elasticity), only its positive part, for a finite step.
        let curvature = if elastic_curv + law_curv > 0.0 {
            elastic_curv + law_curv
        } else {
            elastic_curv + law_pos
        };
        let mut step = if curvature > 0.0 {
            -slope / curvature
        } else {
            // No stiffness along the direction at all (a free rigid shift under load
            // control, in a concave part of the law): move by one range of the law.
            law.range() / direction.iter().fold(f64::MIN_POSITIVE, |m, d| m.max(d.abs()))
        };
        let energy = x.total_energy();
        let slack = 1e-13 * (x.energy.0 + x.energy.1.abs()) + f64::MIN_POSITIVE;
        let mut accepted = false;
        let mut cut = false;
        for _ in 0..MAX_CUTS {
            problem.step_and_project(&x.gap, &direction, step, &mut trial.gap, None);
            problem.evaluate(&mut trial)?;
            let rise = trial.total_energy() - energy;
            if rise <= slack {
                accepted = true;
                break;
            }
            // The energy rose (the contact set changed along the step, or the law's curvature
            // varied): the minimiser of the parabola through E(0), E'(0) and E(step), kept
            // within a tenth and a half of the step.
            let fitted = -slope * step * step / (2.0 * (rise - slope * step));
            step = fitted.clamp(0.1 * step, 0.5 * step);
            cut = true;
        }
        if !accepted {
            // No lower energy along a descent direction: the residual is round-off.
            break;
        }
        std::mem::swap(&mut x, &mut trial);
        let old_zr = zr;
        sums = problem.project_gradient(&mut x);
        let [new_zr, z_old] = problem.precondition(&x, &trial.gradient, &mut z);
        zr = new_zr;
        // Polak-Ribiere, reset to zero when negative, and steepest descent after a cut step.
        let beta = if cut || old_zr <= 0.0 {
            0.0
        } else {
            ((zr - z_old) / old_zr).max(0.0)
        };
        let parts: Vec<f64> = flat_mut(&mut direction)
            .par_chunks_mut(mx)
            .zip(flat(&x.gradient).par_chunks(mx))
            .zip(flat(&x.gap).par_chunks(mx))
            .zip(flat(&z).par_chunks(mx))
            .enumerate()
            .map(|(j, (((dr, rr), gr), zr))| {
                let mut slope = 0.0;
                for (i, (((d, &r), &g), &z)) in dr.iter_mut().zip(rr).zip(gr).zip(zr).enumerate() {
                    let next = -z + beta * *d;
                    // A cell on the wall moves only the way its own gradient sends it: under a
                    // hardness the conjugate part could otherwise carry it across the kink
                    // against it (orthant-wise descent's rule).
                    *d = if on_wall(j, i, g, nx, ny) && (r == 0.0 || (yields && next * r > 0.0)) {
                        0.0
                    } else {
                        next
                    };
                    slope += r * *d;
                }
                slope
            })
            .collect();
        slope = parts.iter().sum();
        if slope >= 0.0 {
            // Not a descent direction: steepest descent.
            direction.zip_mut_with(&z, |d, &z| *d = -z);
            slope = -zr;
        }
    }
    let outcome = driver.finish(Iterations::Descent { iterations }, problem.calls);
    Ok(finish(job, &problem, x, &sums, (delta, load), outcome))
}
