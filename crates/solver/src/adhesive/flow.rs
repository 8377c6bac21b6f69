//! Relaxation: adhesive contact under any law with a finite stiffness, the line and surface
//! laws included, as the stable state a surface comes to rest on when each cell is driven by
//! the force on it and damped, over the gap problem of `gap_problem` (the unknown,
//! constraints and force balance `r = S (g - g0) - p(g)` of the energy descent and Newton).
//!
//! The dynamics is FIRE's (Bitzek et al., Phys. Rev. Lett. 97, 2006; the constants of FIRE
//! 2.0, Guenole et al., Comput. Mater. Sci. 175, 2020): `M dv/dt = -r`, `dg/dt = v`, with the
//! velocity turned towards the force by a mixing that decays while the force does work and
//! zeroed, with the time step cut, when it stops doing work. The mass `M = S_ii + max(K_ii,
//! 0)` is the cell's own elastic stiffness and the stable part of the law's (`K = -dp/dg`,
//! just above the wall many times a cell's), so that every cell has about the same natural
//! period. For the line and surface laws, whose cell pressure is a mean over the gaps from
//! the node to its +x neighbour, the mass also couples each cell to that neighbour as the
//! law does (`Problem::precondition_rows`, solved along each row): with the diagonal alone,
//! the law's one-sided coupling, as stiff as a cell's own just above the wall, took twice the
//! steps. Each step is projected onto `g >= 0` (and the prescribed mean gap); a cell that
//! meets the wall stops there, and so does a cell that would move against the force on it.
//! Where the residual stops falling the longest step is cut ([`STALL`]). Only a stable state
//! is a state of rest: perturbed, the dynamics carries it back; a saddle or an unstable
//! branch repels it. This holds for laws without an energy too, which is why this is the
//! method for the paper's surface law (Eq. 11) on cells coarser than the process zone: there
//! every cell holds on or lets go alone, Eq. 11's forces are not the gradient of any energy,
//! and Newton and the loops circle between states (`docs/validation.md`), where the
//! relaxation settles.
//!
//! The damping is strong enough that the states reached are those of the overdamped flow
//! `M dg/dt = -r` from the same start, on the cases measured (`docs/decisions.md`), in a
//! fraction of its steps (a fifth on the challenge at 256^2): the inertia carries the long
//! wavelengths, which the overdamped flow moves slowly.
//!
//! Cost: one application of the stiffness and one evaluation of the law a step (three for laws
//! without a local potential, whose stiffness by a cell's own gap and by its neighbour's is
//! probed).

use super::driver::Driver;
use super::gap_problem::{Energy, Point, Problem, Setup, check_control, finish, setup};
use super::{AdhesiveMethod, AdhesiveReport, AdhesiveState, Iterations, Job};
use crate::error::{Result, SolverError};
use crate::report::Termination;
use ndarray::Array2;
use std::time::Instant;

/// The first time step, in units of a cell's period `sqrt(M / S_ii)` over `2 pi`.
const FIRST_STEP: f64 = 0.25;
/// The largest time step: below the limit `2 / sqrt(1.85)` of the stiffest elastic mode,
/// whose stiffness is about 1.85 times a cell's own on a periodic grid (the corner of the
/// Brillouin zone against the mean of `E* |q| / 2`), with a margin for the law's stiffness
/// rising within a step (`docs/decisions.md`).
const MAX_STEP: f64 = 1.0;
/// The largest time step after a stall: a cell stopped every step moves by `dt^2` times its
/// pull, which is stable while its stiffness is below `2 / dt^2` times its mass (8 here, 2 at
/// [`MAX_STEP`]).
const SAFE_STEP: f64 = 0.5;
/// The smallest time step.
const MIN_STEP: f64 = 0.005;
/// The mixing of the velocity towards the force after a stop, and its decay a step while the
/// force does work: strong damping, which keeps the overdamped flow's states.
const MIXING: f64 = 0.25;
const MIXING_DECAY: f64 = 0.99;
/// Steps the force must do work after a stop before the time step grows, and its growth and
/// cut.
const DELAY: usize = 20;
const GROWTH: f64 = 1.1;
const CUT: f64 = 0.5;
/// Steps without a 10 % fall of the best residual after which the largest time step is cut:
/// a few cells whose law stiffens faster than their mass tells chatter about their state
/// at a long step (the surface law at a Tabor parameter of 5, `docs/decisions.md`).
const STALL: usize = 500;

/// The relaxation of the module docs.
pub(super) struct Flow;

impl AdhesiveMethod for Flow {
    fn check(&self, job: &Job) -> Result<()> {
        energy(job).map(|_| ())
    }

    fn solve(
        &self,
        job: &Job,
        observer: &mut dyn FnMut(usize, f64) -> bool,
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
            "the relaxation (`flow`) needs a law with a finite stiffness, not `{}` (use `accelerated`)",
            law.name()
        )));
    }
    check_control(job, "the relaxation (`flow`)")?;
    Ok(Energy::of(law))
}

fn solve<'a>(
    job: &Job<'a>,
    energy: Energy<'a>,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<(AdhesiveState, AdhesiveReport)> {
    let started = Instant::now();
    let Job { law, settings, .. } = *job;
    let Setup {
        mut problem,
        mut x,
        delta,
        load,
    } = setup(job, energy)?;
    problem.couple_rows(&mut x)?;
    let unknown = x.gap.dim();
    let mut sums = problem.project_gradient(&mut x);
    // `M^-1 r` (the acceleration's opposite) and the velocity [m per time unit].
    let mut pull = Array2::zeros(unknown);
    let mut velocity = Array2::zeros(unknown);
    let mut trial = Point::new(Array2::zeros(unknown));
    let scale = job.residual_scale();
    let mut driver = Driver::new(settings, observer, started);
    let (mut dt, mut mixing, mut working) = (FIRST_STEP, MIXING, 0);
    let mut max_step = MAX_STEP;
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
        let force_weight = if problem.coupled() {
            problem.precondition_rows(&x, &mut pull)
        } else {
            problem.precondition(&x, &x.gradient, &mut pull)[0]
        };
        // Whether the velocity is zeroed before this step's update.
        let mut stopped = driver.since_progress(steps, sums.max * scale) > STALL;
        if stopped {
            // Cells chattering about a state the step is too long to settle in.
            max_step = (max_step * CUT).max(SAFE_STEP);
            dt = dt.min(max_step);
            driver.restart_stall_count(steps);
        }
        let moments = Moments::of(&problem, &x, &velocity, &pull);
        // The force's power on the velocity: stop when it turns against it.
        let power = if stopped { 0.0 } else { moments.power };
        if power > 0.0 {
            working += 1;
            if working > DELAY {
                dt = (dt * GROWTH).min(max_step);
                mixing *= MIXING_DECAY;
            }
        } else if power < 0.0 {
            working = 0;
            dt = (dt * CUT).max(MIN_STEP);
            mixing = MIXING;
            stopped = true;
        }
        // The velocity `v - dt M^-1 r`, turned towards the force keeping its kinetic energy
        // (mass-weighted).
        let (keep, turn) = if force_weight > 0.0 {
            let kinetic = moments.kinetic_after(dt, stopped);
            (1.0 - mixing, mixing * (kinetic / force_weight).sqrt())
        } else {
            (1.0, 0.0)
        };
        let pulls = crate::fields::flat(&pull);
        problem.move_cells(&x.gap, &mut velocity, dt, &mut trial.gap, |v, k, inside| {
            let a = pulls[k];
            let v = keep * (if stopped { 0.0 } else { v } - dt * a) - turn * a;
            // No cell of the block moves against the force on it: a cell that would climb
            // stops (inelastically, like one meeting the wall), so that inertia carries no
            // cell over a barrier of its own, and a cell falling into the law's well does not
            // bounce off its core, whose stiffness the mass of the step before does not know.
            if inside && v * a > 0.0 { 0.0 } else { v }
        });
        problem.evaluate(&mut trial)?;
        std::mem::swap(&mut x, &mut trial);
        sums = problem.project_gradient(&mut x);
    }
    let outcome = driver.finish(Iterations::Flow { steps }, problem.calls);
    Ok(finish(job, &problem, x, &sums, (delta, load), outcome))
}

/// The sums over the cells a step needs of the velocity `v` and the pull `a = M^-1 r`.
struct Moments {
    /// The force's power on the velocity, `-<r, v>`.
    power: f64,
    /// `sum m v^2`, `sum m v a` and `sum m a^2`.
    vv: f64,
    va: f64,
    aa: f64,
}

impl Moments {
    fn of(problem: &Problem, x: &Point, velocity: &Array2<f64>, pull: &Array2<f64>) -> Moments {
        use crate::fields::flat;
        let mx = problem.mx;
        let (rs, cs, vs, ps) = (flat(&x.gradient), flat(&x.curvature), flat(velocity), flat(pull));
        let [power, vv, va, aa] = crate::sum::ordered(problem.my, |j| {
            let mut sums = [0.0; 4];
            for i in 0..mx {
                let k = j * mx + i;
                let (m, v, a) = (problem.mass(cs, j, i, k), vs[k], ps[k]);
                sums[0] -= rs[k] * v;
                sums[1] += m * v * v;
                sums[2] += m * v * a;
                sums[3] += m * a * a;
            }
            sums
        });
        Moments { power, vv, va, aa }
    }

    /// `sum m (v - dt a)^2`, with `v = 0` if `stopped`.
    fn kinetic_after(&self, dt: f64, stopped: bool) -> f64 {
        let (vv, va) = if stopped { (0.0, 0.0) } else { (self.vv, self.va) };
        (vv - 2.0 * dt * va + dt * dt * self.aa).max(0.0)
    }
}
