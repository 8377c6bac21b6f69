//! Newton-Krylov: adhesive contact under any law, the surface law included, as one nonlinear
//! complementarity problem over the gap, with no outer loop on the adhesive pressure.
//!
//! The unknown and its constraints are those of the energy descent (module `energy`): the gap
//! with its mean prescribed on a periodic domain, the padded displacement on a free one. The
//! equations are the cell force balance `r = S (g - g0) - p(g) = 0` where the gap is open and
//! `r >= 0` (the contact pressure) where it is closed; `p` is the law's pressure field, which
//! for the surface and line laws depends on a cell's neighbours and is the gradient of no
//! energy, so that no descent applies. Each iteration solves the linearised balance on the
//! cells not held by the wall, `(M / dt + S + K) d = -r` with `K = -dp/dg`, by restarted GMRES
//! (`K` applied as a directional difference of the whole field, exactly as the law is
//! evaluated), right-preconditioned by the stiffness's inverse where the law is softer than a
//! cell or by its diagonal where not (see `Linear::elastic`), and takes the step projected onto
//! `g >= 0`, halved while it raises the residual (pseudo-transient continuation, Kelley &
//! Keyes, SIAM J. Numer. Anal. 35, 1998). The mass `M = S + max(K_ii, 0)` is the stable part
//! of the stiffness, so that a pseudo-time step relaxes all wavelengths alike. The step `dt`
//! grows as the residual falls (switched evolution relaxation), so the iteration becomes
//! Newton's near a solution; far from one (a jump into or out of contact) steps of `dt` about
//! one follow the relaxation `M dg/dt = -r`, which settles on stable states.
//!
//! For the line and surface laws, a start from which Newton cannot get going (it falls back
//! on the smallest pseudo-time step) is first moved by descending the energy of the point law
//! (their law on flat gaps, [`ljadhesion::AdhesionLaw::flat_potential`]), which travels
//! across jumps, and Newton corrects that state.
//!
//! Convergence: the largest force imbalance of a cell times its compliance, over the law's
//! range (the energy descent's measure), below the tolerance.

mod krylov;

use super::driver::Driver;
use super::energy;
use super::gap::{self, GradientSums, Point, Problem, Setup, on_wall};
use super::job::{AdhesiveMethod, Job};
use super::{AdhesiveReport, AdhesiveState, Iterations, Start};
use crate::error::{Result, SolverError};
use crate::fields::{flat, flat_mut};
use crate::options::Control;
use crate::report::Termination;
use crate::sum::dot;
use krylov::{Gmres, LinearOperator};
use ndarray::{Array2, Zip, s};
use rayon::prelude::*;
use std::time::Instant;

/// Krylov vectors kept before GMRES restarts, at most.
const RESTART: usize = 30;
/// The most memory \[bytes\] the Krylov basis may take: on larger grids GMRES restarts
/// sooner (a constant, not the machine's memory, so that results do not depend on the machine).
const BASIS_BYTES: f64 = 4.0 * 1024.0 * 1024.0 * 1024.0;
/// Krylov vectors kept at least, however large the grid.
const MIN_RESTART: usize = 5;
/// Krylov iterations per Newton step at most.
const MAX_KRYLOV: usize = 300;
/// The first pseudo-time step, in units of each cell's relaxation time `1 / D`.
const FIRST_DT: f64 = 1e6;
/// The largest pseudo-time step (effectively Newton's).
const MAX_DT: f64 = 1e12;
/// The smallest pseudo-time step, in units of the relaxation time of the mass (the elastic
/// and the law's stable stiffness): each step then goes half way to the linearised solution
/// of the stable modes; a lower floor lets a snapping edge crawl (`docs/decisions.md`).
const MIN_DT: f64 = 1.0;
/// A step may raise the residual by this factor (the relaxation can have to climb out of a
/// well of the residual that holds no solution, past the fold of a branch); a larger rise
/// is retried with a tenth of the pseudo-time step, down to [`MIN_DT`], where it is taken.
const GROWTH: f64 = 4.0;
/// The largest move of a gap in one step, in ranges of the law.
const MAX_MOVE: f64 = 2.0;
/// Newton steps without a 10 % improvement of the best residual that count as a stall, when
/// the energy descent's prediction can take over.
const STALL: usize = 60;
/// The same when nothing can take over (Newton correcting that prediction): the relaxation
/// can take more than [`STALL`] steps of slowly rising residual to carry a cell of a contact
/// edge over its snap (`docs/decisions.md`).
const PATIENCE: usize = 150;
/// Consecutive steps raising the residual after which further rising steps do not count
/// towards a stall (a two-cycle never makes two).
const ESCAPE: usize = 5;
/// Halvings of a step that raises the residual before a new direction is sought.
const BACKTRACKS: usize = 3;
/// Each backtrack halves the step.
const BACKTRACK: f64 = 0.5;
/// The directional difference's step: the largest cell's move, in ranges of the law.
const DIFFERENCE: f64 = 1e-6;
/// Eisenstat-Walker forcing (their choice 2): `eta = GAMMA r_k^2 / r_{k-1}^2` kept within
/// `[ETA_MIN, ETA_MAX]`, so the Krylov solves are loose while the residual falls slowly.
const GAMMA: f64 = 0.9;
const ETA_MIN: f64 = 1e-4;
const ETA_MAX: f64 = 0.1;
/// The pseudo-time step's cut when no step along the direction lowers the residual enough.
const NO_STEP_CUT: f64 = 0.1;

/// The Krylov vectors GMRES keeps before it restarts on fields of `cells` values: [`RESTART`],
/// or fewer where their `restart + 1` fields would take more than [`BASIS_BYTES`].
fn restart_for(cells: usize) -> usize {
    let fields = (BASIS_BYTES / (8.0 * cells as f64)).floor() as usize;
    fields.saturating_sub(1).clamp(MIN_RESTART, RESTART)
}

/// Subtracts from `out` its mean over the moving cells (those where `mask > 0`), which
/// keeps their sum at zero where the mean gap is prescribed.
fn remove_moving_mean(out: &mut Array2<f64>, mask: &Array2<f64>) {
    let (sum, count) = out.iter().zip(mask).fold(
        (0.0, 0.0),
        |(s, c), (&o, &m)| if m > 0.0 { (s + o, c + 1.0) } else { (s, c) },
    );
    if count > 0.0 {
        let mean = sum / count;
        Zip::from(out).and(mask).par_for_each(|o, &m| {
            if m > 0.0 {
                *o -= mean;
            }
        });
    }
}

/// The linearised balance at one point: its preconditioner and the law's perturbation.
struct Linear {
    /// Whether the preconditioner is the elastic one, `W S^-1 W / (1 + 1/dt)` with
    /// `W = sqrt(S_ii / D)`, rather than the diagonal `1 / (D (1 + 1/dt))`, `D` being the
    /// diagonal `S_ii + max(-dp/dg, 0)`, chosen at each Newton step from the law's stiffness
    /// at the moving cells' gaps: where the law is nowhere stiffer than a cell, the work
    /// is the elastic solve, which the stiffness's inverse (one more FFT a Krylov iteration)
    /// does in far fewer iterations; where the law is stiffer, its stiff cells set the pace and
    /// the diagonal wins (measured in `docs/decisions.md`). For the line and surface laws the
    /// diagonal one also holds the law's stiffness by each cell's +x neighbour, solved along
    /// the rows ([`Problem::solve_rows`]).
    elastic: bool,
    /// The diagonal preconditioner on moving cells, 0 on held ones.
    inverse: Array2<f64>,
    /// The elastic preconditioner's weights `W` on moving cells, 0 on held ones, and a
    /// scratch field.
    weight: Array2<f64>,
    weighted: Array2<f64>,
    /// The law's stable stiffness over the pseudo-time step, `max(-dp/dg, 0) / dt`, on moving
    /// cells of the block.
    shift: Array2<f64>,
    /// The elastic stiffness's factor `1 + 1/dt`.
    elastic_factor: f64,
    /// The domain block's perturbed gap and the law's pressure there.
    perturbed: Array2<f64>,
    perturbed_law: Array2<f64>,
}

impl Linear {
    fn new(unknown: (usize, usize), block: (usize, usize)) -> Linear {
        let zeros = || Array2::zeros(unknown);
        Linear {
            elastic: false,
            inverse: zeros(),
            weight: zeros(),
            weighted: zeros(),
            shift: zeros(),
            elastic_factor: 1.0,
            perturbed: Array2::zeros(block),
            perturbed_law: Array2::zeros(block),
        }
    }

    /// Sets the preconditioner and the pseudo-time term at `x` (its gradient projected).
    fn prepare(&mut self, problem: &Problem, x: &Point, dt: f64) {
        self.elastic_factor = 1.0 + 1.0 / dt;
        let (mx, nx, ny, s0) = (problem.mx, problem.nx, problem.ny, problem.diagonal);
        let (gs, rs, cs) = (flat(&x.gap), flat(&x.gradient), flat(&x.curvature));
        flat_mut(&mut self.inverse)
            .par_chunks_mut(mx)
            .zip(flat_mut(&mut self.shift).par_chunks_mut(mx))
            .zip(flat_mut(&mut self.weight).par_chunks_mut(mx))
            .enumerate()
            .for_each(|(j, ((ir, sr), wr))| {
                for i in 0..mx {
                    let k = j * mx + i;
                    if on_wall(j, i, gs[k], nx, ny) && rs[k] == 0.0 {
                        (ir[i], sr[i], wr[i]) = (0.0, 0.0, 0.0);
                        continue;
                    }
                    let law = if j < ny && i < nx { cs[k].max(0.0) } else { 0.0 };
                    (ir[i], sr[i]) = (1.0 / ((s0 + law) * (1.0 + 1.0 / dt)), law / dt);
                    wr[i] = (s0 / (s0 + law)).sqrt();
                }
            });
        // The law's stiffest moving cell against a cell's elastic stiffness: `W` is at least
        // `sqrt(1/2)` everywhere exactly when the law is nowhere stiffer.
        self.elastic = self.weight.iter().all(|&w| w == 0.0 || w * w >= 0.5);
    }
}

/// The linearised balance at `x` as GMRES sees it.
struct Linearised<'a, 'p> {
    linear: &'a mut Linear,
    problem: &'a mut Problem<'p>,
    x: &'a Point,
}

impl LinearOperator for Linearised<'_, '_> {
    /// `out = A v`: the linearised balance `(M/dt + S + K) v` at `x` on the moving cells,
    /// zero on the held ones, less its mean over the moving cells where the mean gap is
    /// prescribed (the multiplier's change).
    fn apply(&mut self, v: &Array2<f64>, out: &mut Array2<f64>) -> Result<()> {
        let Linearised { linear, problem, x } = self;
        let problem = &mut **problem;
        problem
            .stiffness
            .apply(v.view(), out.view_mut(), &mut problem.ws)?;
        problem.calls += 1;
        if linear.elastic_factor != 1.0 {
            let factor = linear.elastic_factor;
            out.par_mapv_inplace(|o| o * factor);
        }
        let block = s![..problem.ny, ..problem.nx];
        let largest = v.slice(block).iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if largest > 0.0 {
            // A forward difference of the whole field: the law's neighbours move too.
            let h = DIFFERENCE * problem.law.range() / largest;
            Zip::from(&mut linear.perturbed)
                .and(x.gap.slice(block))
                .and(v.slice(block))
                .par_for_each(|p, &g, &v| *p = g + h * v);
            problem.law.pressure_field(
                linear.perturbed.view(),
                &problem.cells,
                linear.perturbed_law.view_mut(),
            )?;
            Zip::from(out.slice_mut(block))
                .and(&linear.perturbed_law)
                .and(x.law.slice(block))
                .par_for_each(|o, &hi, &lo| *o -= (hi - lo) / h);
        }
        let moving = &linear.inverse;
        Zip::from(&mut *out)
            .and(v)
            .and(&linear.shift)
            .and(moving)
            .par_for_each(|o, &v, &s, &m| *o = if m > 0.0 { *o + s * v } else { 0.0 });
        if problem.mean_gap.is_some() {
            remove_moving_mean(out, moving);
        }
        Ok(())
    }

    /// `out = M^-1 v`, with the mean that keeps the moving cells' sum at zero where the mean
    /// gap is prescribed (see [`Linear::elastic`]).
    fn precondition(&mut self, v: &Array2<f64>, out: &mut Array2<f64>) -> Result<()> {
        let Linearised { linear, problem, x } = self;
        let problem = &mut **problem;
        if linear.elastic {
            let factor = 1.0 / linear.elastic_factor;
            Zip::from(&mut linear.weighted)
                .and(v)
                .and(&linear.weight)
                .par_for_each(|t, &v, &w| *t = w * v);
            problem
                .stiffness
                .invert(linear.weighted.view(), out.view_mut(), &mut problem.ws)?;
            problem.calls += 1;
            Zip::from(&mut *out)
                .and(&linear.weight)
                .par_for_each(|o, &w| *o *= w * factor);
            if problem.mean_gap.is_some() {
                remove_moving_mean(out, &linear.weight);
            }
            return Ok(());
        }
        if problem.coupled() {
            let inverse = flat(&linear.inverse);
            problem.solve_rows(x, &|_, _, k| inverse[k], v, out);
            return Ok(());
        }
        let mu = if problem.mean_gap.is_some() {
            dot(&linear.inverse, v) / linear.inverse.sum().max(f64::MIN_POSITIVE)
        } else {
            0.0
        };
        Zip::from(out)
            .and(v)
            .and(&linear.inverse)
            .par_for_each(|o, &v, &m| *o = (v - mu) * m);
        Ok(())
    }
}

/// Newton-Krylov of the module docs.
pub(super) struct Newton;

impl AdhesiveMethod for Newton {
    fn check(&self, job: &Job) -> Result<()> {
        if !matches!(job.control, Control::Approach(_)) {
            return Err(SolverError::Unsupported(
                "the Newton solver takes the approach only (use `accelerated` for loads and central \
                 gaps)"
                    .into(),
            ));
        }
        if !job.law.stiffness_bound().is_finite() {
            return Err(SolverError::Unsupported(format!(
                "the Newton solver linearises the law, and `{}` jumps (use `accelerated`)",
                job.law.name()
            )));
        }
        Ok(())
    }

    fn solve(
        &self,
        job: &Job,
        observer: &mut dyn FnMut(usize, f64) -> bool,
    ) -> Result<(AdhesiveState, AdhesiveReport)> {
        solve(job, observer)
    }

    fn peak_bytes(&self, cells: f64, periodic: bool) -> f64 {
        // The unknown lives on the padded 2nx x 2ny grid of a free domain; the Krylov basis is
        // capped on large grids ([`restart_for`]).
        let unknown = if periodic { cells } else { 4.0 * cells };
        let fields = restart_for(unknown.min(usize::MAX as f64) as usize) + 1;
        let rest = if periodic { 392.0 } else { 1056.0 };
        rest * cells + 8.0 * fields as f64 * unknown
    }
}

/// Solves under approach control (periodic or free) with any law; see the module docs.
fn solve(job: &Job, observer: &mut dyn FnMut(usize, f64) -> bool) -> Result<(AdhesiveState, AdhesiveReport)> {
    let started = Instant::now();
    // A law without a local energy but with a field energy (surface-energy; not under a
    // hardness, which the descent takes with local energies only) or a flat one (line,
    // surface) can have its state predicted by descending that energy when Newton cannot get
    // going.
    let law = job.law;
    let field = law.field_potential().filter(|_| job.interface.hardness.is_none());
    let predictor = match (law.local_potential(), field) {
        (Some(_), _) => None,
        (None, Some(field)) => Some(gap::Energy::Field(field)),
        (None, None) => law.flat_potential().map(gap::Energy::Local),
    };
    let (state, report) = iterate(job, predictor.is_some(), observer)?;
    let Some(potential) = predictor.filter(|_| report.termination == Termination::MaxIterations) else {
        return Ok((state, report));
    };
    // No solution near the start (a jump into or out of contact): the descent of the flat
    // law's energy travels there, settling on a stable state, and Newton corrects it.
    let (predicted, descent) = energy::solve(job, potential, observer)?;
    let polish = Job {
        start: Start::Warm(&predicted),
        ..*job
    };
    let (state, mut polished) = iterate(&polish, false, observer)?;
    let (
        Iterations::Newton { steps, krylov, .. },
        Iterations::Newton {
            steps: more_steps,
            krylov: more_krylov,
            ..
        },
    ) = (report.iterations, polished.iterations)
    else {
        unreachable!("iterate reports Newton's counts")
    };
    polished.iterations = Iterations::Newton {
        steps: steps + more_steps,
        krylov: krylov + more_krylov,
        predictor: descent.iterations.count(),
    };
    polished.operator_calls += report.operator_calls + descent.operator_calls;
    let mut history = report.residual_history;
    history.extend(&polished.residual_history);
    polished.residual_history = history;
    polished.wall_time_s = started.elapsed().as_secs_f64();
    Ok((state, polished))
}

/// Newton as another method's polish: pseudo-transient, from its point `x` of `problem` at the
/// approach `delta`, for at most `max_steps`, telling `observer` its iterations. The flow hands
/// over so where it crawls: these implicit steps cross the soft mode a patch crawls along near
/// a fold in a few steps where the flow's explicit ones take thousands, and the small
/// pseudo-time steps far from a solution follow the same relaxation.
pub(in crate::adhesive) fn polish(
    job: &Job,
    problem: &mut Problem,
    x: &Point,
    delta: f64,
    max_steps: usize,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<(AdhesiveState, AdhesiveReport)> {
    let mut at = Point::new(x.gap.clone());
    problem.evaluate(&mut at)?;
    let sums = problem.project_gradient(&mut at);
    let start = gap::state(job, problem, at, &sums, (delta, None));
    let settings = crate::Settings {
        max_iterations: max_steps,
        ..*job.settings
    };
    let polish = Job {
        start: Start::Warm(&start),
        settings: &settings,
        ..*job
    };
    iterate(&polish, false, observer)
}

/// Newton from the start of `job`; with `give_up`, it stops (unconverged) as soon as it has to
/// fall back on the smallest pseudo-time step or a Krylov solve stops short of its forcing
/// term.
pub(super) fn iterate(
    job: &Job,
    give_up: bool,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<(AdhesiveState, AdhesiveReport)> {
    let started = Instant::now();
    let domain = *job.op.domain();
    let (law, settings) = (job.law, job.settings);
    let Setup {
        mut problem,
        mut x,
        delta,
        load,
    } = gap::setup(job, gap::Energy::None)?;
    // The line and surface laws: the preconditioner couples each cell to its +x neighbour as
    // their cell means do.
    problem.couple_rows(&mut x)?;
    let unknown = x.gap.dim();
    let mut sums: GradientSums = problem.project_gradient(&mut x);
    let mut norm = dot(&x.gradient, &x.gradient).sqrt();
    let mut trial = Point::new(Array2::zeros(unknown));
    let mut linear = Linear::new(unknown, domain.shape());
    let mut gmres = Gmres::new(unknown, restart_for(unknown.0 * unknown.1), MAX_KRYLOV);
    // The linearised balance's right-hand side `-r`.
    let mut rhs = Array2::zeros(unknown);
    let block = s![..problem.ny, ..problem.nx];
    let scale = job.residual_scale();
    let mut driver = Driver::new(settings, observer, started);
    let (mut steps, mut krylov) = (0, 0);
    let mut dt = FIRST_DT;
    let mut last_ratio = 1.0f64;
    let patience = if give_up { STALL } else { PATIENCE };
    // Consecutive steps that raised the residual.
    let mut rising = 0;
    loop {
        let residual = sums.max * scale;
        if driver.stop(steps, residual, true)
            || driver.since_progress(steps, residual) > patience
            || (give_up && dt <= MIN_DT)
        {
            break;
        }
        steps += 1;
        // Eisenstat-Walker forcing: solve loosely while the residual falls slowly.
        let eta = (GAMMA * last_ratio * last_ratio).clamp(ETA_MIN, ETA_MAX);
        linear.prepare(&problem, &x, dt);
        rhs.zip_mut_with(&x.gradient, |b, &r| *b = -r);
        let (iterations, solved) = gmres.solve(
            &mut Linearised {
                linear: &mut linear,
                problem: &mut problem,
                x: &x,
            },
            &rhs,
            eta,
        )?;
        krylov += iterations;
        // Nor has it where its linearisation cannot be solved: at a jump on a large grid the
        // first attempt would otherwise spend its steps in capped Krylov solves.
        if give_up && !solved {
            break;
        }
        let largest = gmres
            .solution
            .slice(block)
            .iter()
            .fold(0.0f64, |m, d| m.max(d.abs()));
        let full = (MAX_MOVE * law.range() / largest).min(1.0);
        // Backtrack along the direction while the residual rises (each try costs one
        // evaluation, against a Krylov solve for a new direction).
        let mut fraction = 1.0;
        let (mut trial_sums, mut trial_norm, mut first_norm) = (None, f64::NAN, f64::NAN);
        for cut in 0..=BACKTRACKS {
            problem.step_and_project(&x.gap, &gmres.solution, full * fraction, &mut trial.gap, None);
            problem.evaluate(&mut trial)?;
            let sums = problem.project_gradient(&mut trial);
            trial_norm = dot(&trial.gradient, &trial.gradient).sqrt();
            if cut == 0 {
                first_norm = trial_norm;
            }
            if trial_norm < norm {
                trial_sums = Some(sums);
                break;
            }
            if cut == BACKTRACKS {
                break;
            }
            fraction *= BACKTRACK;
        }
        let trial_sums = match trial_sums {
            Some(sums) => sums,
            // No decrease along the direction: take the full step if it is a small step of
            // the relaxation (or raises the residual only a little), else retry with a
            // smaller pseudo-time step.
            None if first_norm <= GROWTH * norm || dt <= MIN_DT => {
                fraction = 1.0;
                problem.step_and_project(&x.gap, &gmres.solution, full, &mut trial.gap, None);
                problem.evaluate(&mut trial)?;
                trial_norm = first_norm;
                problem.project_gradient(&mut trial)
            }
            None => {
                dt = (dt * NO_STEP_CUT).max(MIN_DT);
                continue;
            }
        };
        // A steady rise is the relaxation leaving an unstable equilibrium (where Newton had
        // nearly converged) for a stable one, not a stall: the residual can grow for a hundred
        // steps or more before the snap lands (`docs/decisions.md`, ESCAPE).
        rising = if trial_norm > norm { rising + 1 } else { 0 };
        if rising >= ESCAPE {
            driver.defer_stall();
        }
        last_ratio = (trial_norm / norm).min(1.0);
        // Switched evolution relaxation: the pseudo-time step grows as the residual falls,
        // and shrinks with a cut step. A whole step that lowers the residual at least doubles
        // it: after cuts near a snapping edge the residual falls by a few per cent a step, and
        // growing by that ratio alone leaves Newton crawling (`docs/decisions.md`).
        let ratio = (norm / trial_norm).clamp(0.1, 10.0);
        let growth = if fraction == 1.0 && ratio > 1.0 {
            ratio.max(2.0)
        } else {
            ratio
        };
        dt = (dt * fraction * growth).clamp(MIN_DT, MAX_DT);
        std::mem::swap(&mut x, &mut trial);
        (sums, norm) = (trial_sums, trial_norm);
    }
    let iterations = Iterations::Newton {
        steps,
        krylov,
        predictor: 0,
    };
    let outcome = driver.finish(iterations, problem.calls);
    Ok(gap::finish(job, &problem, x, &sums, (delta, load), outcome))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The basis is capped at [`BASIS_BYTES`] from the grid where 31 fields no longer fit: all 30
    /// vectors on a periodic 4096^2 grid, 7 on a free one (its padded 8192^2 unknown, where
    /// 31 fields took 16 GiB), never fewer than [`MIN_RESTART`].
    #[test]
    fn the_krylov_basis_is_capped() {
        let basis = |cells: usize| (restart_for(cells) + 1) as f64 * 8.0 * cells as f64;
        assert_eq!(restart_for(512 * 512), RESTART);
        assert_eq!(restart_for(4096 * 4096), RESTART);
        assert_eq!(restart_for(8192 * 8192), 7);
        assert!(basis(4096 * 4096) <= BASIS_BYTES && basis(8192 * 8192) <= BASIS_BYTES);
        assert_eq!(restart_for(1 << 32), MIN_RESTART);
    }
}
