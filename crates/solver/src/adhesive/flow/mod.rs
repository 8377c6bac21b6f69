//! Relaxation: adhesive contact under any law with a finite stiffness, the line and surface
//! laws included, as the stable state a surface comes to rest on when each cell is driven by
//! the force on it and damped, over the gap problem of `gap` (the unknown,
//! constraints and force balance `r = S (g - g0) - p(g)` of the energy descent and Newton).
//!
//! The dynamics is FIRE's (Bitzek et al., Phys. Rev. Lett. 97, 2006; the constants of FIRE 2.0,
//! Guenole et al., Comput. Mater. Sci. 175, 2020, but for a milder restart on coarse cells): `M
//! dv/dt = -r`, `dg/dt = v`, with the velocity turned towards the force by a mixing that decays
//! while the force does work and zeroed, with the time step cut, when it stops doing work. The mass
//! `M = S_ii + max(K_ii, 0)` is the cell's own elastic stiffness and the stable part of the law's
//! (`K = -dp/dg`, just above the wall many times a cell's), so that every cell has about the same
//! natural period. For the line and surface laws, whose cell pressure is a mean over the gaps from
//! the node to its +x neighbour, the mass also couples each cell to that neighbour as the law does
//! (`Problem::precondition_rows`, solved along each row): with the diagonal alone, the law's
//! one-sided coupling, as stiff as a cell's own just above the wall, took twice the steps. Each
//! step is projected onto `g >= 0` (and the prescribed mean gap); a cell that meets the wall stops
//! there, and so does a cell that would move against the force on it. Where the residual stops
//! falling ([`STALL`]), the velocity is zeroed. Only a stable state is a state of rest:
//! perturbed, the dynamics carries it back; a saddle or an unstable branch repels it. This
//! holds for laws without an energy too, which is why this is the method for the paper's
//! surface law (Eq. 11) on cells coarser than the process zone: there every cell holds on or
//! lets go alone, Eq. 11's forces are not the gradient of any energy, and Newton and the loops
//! circle between states (`docs/validation.md`), where the relaxation settles.
//!
//! The damping is strong enough that the states reached are those of the overdamped flow
//! `M dg/dt = -r` from the same start, on the cases measured (`docs/decisions.md`), in a
//! fraction of its steps (a fifth on the challenge at 256^2): the inertia carries the long
//! wavelengths, which the overdamped flow moves slowly.
//!
//! Near a fold a patch of cells can crawl for thousands of steps past the ghost of a state
//! that has just vanished (its soft mode nearly unstiffened, FIRE's restarts keeping it from
//! gathering speed). Under approach control, once the flow stalls a second time, it hands its
//! point to Newton ([`newton::polish`]), whose implicit steps cross such a mode in a few: on the
//! rough spheres of Figs. 11-14 it lands on the state the flow reaches when let run
//! (`docs/decisions.md`). If Newton does not converge, the flow goes on.
//!
//! Under load control the mean gap is free, and the free surface far from the wall is the
//! slowest part of all: its shift as a whole and its long wavelengths, which the flow alone
//! moves for thousands of steps after the contact set has settled. The cells far from the
//! wall leave their shift to a step of its own and, every few dozen steps, their whole field
//! to conjugate gradients with the other cells held, preconditioned by the compliance
//! ([`FarField`]): light loads take a tenth of the steps, the challenge at 1024^2 less than
//! half; the loading areas agree with the plain flow's within 1 %, the unloading branch's as
//! closely as it agrees with itself under smaller load steps (`docs/decisions.md`). Under
//! approach control on a periodic grid the mean gap is prescribed, so the far field is not
//! shifted, but its field is relaxed keeping its mean: the challenge at 512^2 takes a quarter
//! of the steps, in the same states.
//!
//! Cost: one application of the stiffness and one evaluation of the law a step (the line and
//! surface laws with their stiffness by a cell's own gap and by its neighbour's in closed form;
//! a law of the user's without it is probed, two more evaluations), and with the far field up
//! to [`RELAX_ITERATIONS`] iterations of two transforms each (the stiffness and the
//! compliance; about ten iterations) every [`RELAX_EVERY`] steps. Under load control with the
//! line or surface law on a periodic grid, while the residual is large, the stiffness's
//! transforms are made only every [`SPLIT_EVERY`]-th step: in between, the elastic force is
//! its near part from the stiffness's own 5 x 5 stencil plus its far part kept from the last
//! transform (multiple time stepping; the states are those of the flow without it, within the
//! spread of its own paths, `docs/decisions.md`).

use super::driver::Driver;
use super::gap::{Energy, Point, Problem, Row, Setup, check_control, finish, setup};
use super::job::{AdhesiveMethod, Job};
use super::{AdhesiveReport, AdhesiveState, Iterations, newton};
use crate::error::{Result, SolverError};
use crate::report::Termination;
use ndarray::{Array2, Zip};
use std::time::Instant;

mod far_field;
#[cfg(test)]
mod tests;

use far_field::{FarField, Moments};

/// The first time step, in units of a cell's period `sqrt(M / S_ii)` over `2 pi`.
const FIRST_STEP: f64 = 0.25;
/// The largest time step: below the limit `2 / sqrt(1.85)` of the stiffest elastic mode,
/// whose stiffness is about 1.85 times a cell's own on a periodic grid (the corner of the
/// Brillouin zone against the mean of `E* |q| / 2`), with a margin for the law's stiffness
/// rising within a step (`docs/decisions.md`).
const MAX_STEP: f64 = 1.0;
/// The smallest time step.
const MIN_STEP: f64 = 0.005;
/// The mixing of the velocity towards the force after a stop, and its decay a step while the
/// force does work: strong damping, which keeps the overdamped flow's states.
const MIXING: f64 = 0.25;
const MIXING_DECAY: f64 = 0.99;
/// Steps the force must do work after a stop before the time step grows, its growth, and its
/// cut at a stop: FIRE 2.0's (20 steps, 0.5), and milder ([`SNAPPING`]) where the cells are so
/// coarse that a stop is most often a cell snapping on or off, not a step too long
/// (`docs/decisions.md`).
const DELAY: usize = 20;
const GROWTH: f64 = 1.1;
const CUT: f64 = 0.5;
const SNAPPING_DELAY: usize = 5;
const SNAPPING_CUT: f64 = 0.9;
/// The law's largest stiffness over a cell's own elastic stiffness above which the milder
/// restart is taken: between the rough sphere of `data/bench/rough-sphere-mu5.toml` (15,
/// slower with it) and the challenge at 512^2 and 1024^2 (1635 and 817, faster).
const SNAPPING: f64 = 100.0;
/// Steps without a 10 % fall of the best residual after which the velocity is zeroed; under
/// approach control the second stall hands over to Newton ([`HANDOVER_STEPS`]). Cutting the
/// largest time step at a stall made crawls and peels about twice as slow on the rough
/// spheres and over four times on the 4096^2 challenge's last load (`docs/decisions.md`).
const STALL: usize = 500;
/// Under approach control, the Newton steps the flow hands a crawl to at most: after a second
/// stall, a patch passing the ghost of a vanished state near a fold (`docs/decisions.md`).
const HANDOVER_STEPS: usize = 300;
/// Under load control, the share of its Newton step the rigid shift of the soft cells takes a
/// step, times the time step squared (the flow's own scaling, so the two cannot fight), and
/// the clearance, in ranges of the law, that keeps cells near the wall out of the soft set
/// (`docs/decisions.md`).
const SHIFT_SHARE: f64 = 0.3;
const SOFT_CLEARANCE: f64 = 5.0;
/// Under load control, the steps between two solves of the soft cells' balance
/// ([`FarField::relax`]), the conjugate-gradient iterations a solve takes at most (it takes
/// about ten), and the fall of its residual's norm (preconditioned) at which it stops
/// (`docs/decisions.md`).
const RELAX_EVERY: usize = 50;
const RELAX_ITERATIONS: usize = 30;
const RELAX_TOLERANCE: f64 = 1e-2;
/// Under load control on a periodic grid with the line or surface law, the elastic force's far
/// part is transformed every `SPLIT_EVERY`-th step and kept in between, its near part made
/// every step ([`Problem::split_elastic`]), while the residual is above `SPLIT_ABOVE` times
/// the tolerance; below it every step transforms, and a state is at rest only by a
/// transform's force (`docs/decisions.md`).
const SPLIT_EVERY: usize = 6;
const SPLIT_ABOVE: f64 = 100.0;
/// Cells a step's changes of the held set may cost in lookups of the stiffness's kernel
/// before [`FarField::settle`] transforms the held set again instead: one lookup a
/// `LOOKUP_SHARE`-th of the grid's cells, about a transform pair's time at 4096^2
/// (`docs/decisions.md`).
const LOOKUP_SHARE: usize = 32;
/// The changed cells a row records for that update, at most.
const ROW_RECORD: usize = 64;

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
        solve(job, energy(job)?, observer, Course::STANDARD)
    }

    fn peak_bytes(&self, cells: f64, periodic: bool) -> f64 {
        super::gap::peak_bytes(cells, periodic)
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

/// How the flow runs: the method runs [`Course::STANDARD`]; the tests take its accelerations
/// and its handover apart to hold each against the plain flow.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Course {
    /// Whether the far field is taken apart ([`FarField`]): shifted as a whole under load
    /// control.
    far_field: bool,
    /// Whether the far field is also relaxed every [`RELAX_EVERY`] steps, and the elastic force
    /// split into its near and far parts ([`Problem::split_elastic`]).
    relax: bool,
    /// Under approach control, the residual (in ranges) below which the flow hands its point to
    /// Newton ([`newton::polish`]); `None`: when it crawls, at a second stall ([`STALL`]).
    hand_over_below: Option<f64>,
}

impl Course {
    const STANDARD: Course = Course {
        far_field: true,
        relax: true,
        hand_over_below: None,
    };
}

/// The relaxation of `job`, run as `course` says.
fn solve<'a>(
    job: &Job<'a>,
    energy: Energy<'a>,
    observer: &mut dyn FnMut(usize, f64) -> bool,
    course: Course,
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
    let (delay, cut) = if law.stiffness_bound() > SNAPPING * problem.diagonal {
        (SNAPPING_DELAY, SNAPPING_CUT)
    } else {
        (DELAY, CUT)
    };
    let (mut steps, mut stalls, mut newton_steps) = (0, 0, None);
    // Under a prescribed mean gap (periodic approach control) the far field is relaxed but
    // not shifted: its mean is held.
    let mut far_field = (load.is_some() || problem.mean_gap.is_some())
        .then(|| FarField::new(unknown))
        .filter(|_| course.far_field);
    let shifted = far_field.is_some() && load.is_some();
    if shifted && course.relax && problem.coupled() && problem.periodic_at_least(5) {
        problem.split_elastic()?;
    }
    // Whether `x` was evaluated by the split's near part alone, and the residual below which
    // every evaluation transforms.
    let mut x_near = false;
    let transform_below = SPLIT_ABOVE * settings.tolerance;
    // The far field's update at `x`, where made with its evaluation.
    let mut next = None;
    loop {
        if x_near && sums.max * scale <= transform_below {
            problem.near_only(false);
            x_near = false;
            if let Some(far_field) = far_field.as_mut() {
                next = Some(far_field.evaluate_and_update(&mut problem, &mut x, &velocity, &mut pull)?);
            }
            sums = problem.project_gradient(&mut x);
        }
        if driver.stop(steps, sums.max * scale, true) {
            break;
        }
        if load.is_some_and(|p| p < 0.0) && x.min_gap > 1e3 * law.range() {
            // Pulled by more than any attraction at these gaps can hold: flying apart.
            driver.termination = Termination::PulledOff;
            break;
        }
        steps += 1;
        let (force_weight, moments) = match &mut far_field {
            Some(far_field) if shifted => match next.take() {
                Some(update) => update,
                None => far_field.update(&mut problem, &x, &velocity, &mut pull)?,
            },
            _ => {
                let force_weight = if problem.coupled() {
                    problem.precondition_rows(&x, &mut pull)
                } else {
                    problem.precondition(&x, &x.gradient, &mut pull)[0]
                };
                (force_weight, Moments::of(&problem, &x, &velocity, &pull))
            }
        };
        // Whether the velocity is zeroed before this step's update.
        let mut stopped = driver.since_progress(steps, sums.max * scale) > STALL;
        stalls += usize::from(stopped);
        let crawling = match course.hand_over_below {
            None => stopped && stalls >= 2,
            Some(residual) => sums.max * scale < residual,
        };
        if crawling && load.is_none() && newton_steps.is_none() {
            // Newton failing in any way (a non-finite linearisation too) leaves the flow to go on.
            let handed = newton::polish(
                job,
                &mut problem,
                &x,
                delta,
                HANDOVER_STEPS,
                &mut |k, residual| driver.record(steps + k, residual),
            )
            .ok();
            newton_steps = Some(handed.as_ref().map_or(0, |(_, r)| r.iterations.count()));
            if let Some((state, mut report)) = handed
                && (report.converged() || report.termination == Termination::Interrupted)
            {
                let newton = report.iterations.count();
                report.iterations = Iterations::Flow { steps, newton };
                report.operator_calls += problem.calls;
                report.residual_history = driver.finish(report.iterations, 0).history;
                report.wall_time_s = started.elapsed().as_secs_f64();
                return Ok((state, report));
            }
        }
        if stopped {
            driver.restart_stall_count(steps);
        }
        // The force's power on the velocity: stop when it turns against it.
        let power = if stopped { 0.0 } else { moments.power };
        if power > 0.0 {
            working += 1;
            if working > delay {
                dt = (dt * GROWTH).min(MAX_STEP);
                mixing *= MIXING_DECAY;
            }
        } else if power < 0.0 {
            working = 0;
            dt = (dt * cut).max(MIN_STEP);
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
        // The far field's rigid shift rides on the move, its pull's mean on the soft cells
        // taken out on the way ([`FarField`]).
        let shifting = far_field.as_ref().filter(|_| shifted);
        let shift = shifting.map(|f| (&f.held, SHIFT_SHARE * dt * dt * f.step));
        let (held, mean) = shifting.map_or((None, 0.0), |f| (Some(crate::fields::flat(&f.held)), f.mean));
        problem.move_cells(
            &x.gap,
            &mut velocity,
            dt,
            &mut trial.gap,
            shift,
            |v, k, inside| {
                let a = if held.is_some_and(|h| h[k] == 0) {
                    pulls[k] - mean
                } else {
                    pulls[k]
                };
                let v = keep * (if stopped { 0.0 } else { v } - dt * a) - turn * a;
                // No cell of the block moves against the force on it: a cell that would climb
                // stops (inelastically, like one meeting the wall), so that inertia carries no
                // cell over a barrier of its own, and a cell falling into the law's well does not
                // bounce off its core, whose stiffness the mass of the step before does not know.
                if inside && v * a > 0.0 { 0.0 } else { v }
            },
        );
        let relaxing = course.far_field && course.relax && steps % RELAX_EVERY == 0;
        x_near = problem.near_only(steps % SPLIT_EVERY != 0 && sums.max * scale > transform_below);
        // The next step's far-field pass rides on this evaluation, unless a relaxation comes
        // between them.
        match far_field.as_mut().filter(|_| shifted && !relaxing) {
            Some(far_field) => {
                next = Some(far_field.evaluate_and_update(&mut problem, &mut trial, &velocity, &mut pull)?)
            }
            None => problem.evaluate(&mut trial)?,
        }
        std::mem::swap(&mut x, &mut trial);
        sums = problem.project_gradient(&mut x);
        if let Some(far_field) = far_field.as_mut().filter(|_| relaxing) {
            if !shifted {
                far_field.mark(&problem, &x);
            }
            far_field.relax(&mut problem, &x, &mut trial)?;
            x_near = problem.near_only(false);
            // The soft cells arrive at rest.
            Zip::from(&mut velocity)
                .and(&far_field.held)
                .par_for_each(|v, &h| {
                    if h == 0 {
                        *v = 0.0
                    }
                });
            if shifted {
                next = Some(far_field.evaluate_and_update(&mut problem, &mut trial, &velocity, &mut pull)?);
            } else {
                problem.evaluate(&mut trial)?;
            }
            std::mem::swap(&mut x, &mut trial);
            sums = problem.project_gradient(&mut x);
        }
    }
    if x_near {
        problem.near_only(false);
        problem.evaluate(&mut x)?;
        sums = problem.project_gradient(&mut x);
    }
    problem.store_law(&mut x)?;
    let newton = newton_steps.unwrap_or(0);
    let outcome = driver.finish(Iterations::Flow { steps, newton }, problem.calls);
    Ok(finish(job, &problem, x, &sums, (delta, load), outcome))
}
