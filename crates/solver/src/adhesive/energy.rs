//! Energy descent: periodic adhesive contact under a local potential law as one
//! bound-constrained minimisation over the gap, with no outer loop (the constrained nonlinear
//! conjugate gradients of Bugnicourt et al., Tribol. Lett. 66:29, 2018, which
//! ContactMechanics/Adhesion also uses).
//!
//! With the approach `delta` given on a periodic domain the mean displacement is zero, so the
//! mean gap is fixed, `mean(g) = mean(g0) - delta`, and the total energy per area is
//! `E(g) = (1/2) <g - g0, S (g - g0)> / N + mean(V(g))` over `g >= 0` with that mean, `S` the
//! periodic stiffness ([`elastic::PeriodicStiffness`]) and `V` the law's interaction energy.
//! Its gradient `r = S (g - g0) - p(g)` [Pa] balances the mean-pressure multiplier where
//! `g > 0` and is the contact pressure where `g = 0`. Under load control (mean pressure
//! `p_m` given) the mean gap is free and the load's potential `p_m mean(g)` joins `E`.
//!
//! Each iteration takes the conjugate direction of the projected gradient (Polak-Ribiere,
//! restarted when it is not a descent direction or a step was cut), a step from the exact
//! curvature `S + V''` along it (only its positive part when the law makes it negative), and
//! projects onto the constraints; a step that would raise the energy is cut to the minimiser
//! of a parabola through the energies seen, so every iterate lowers the energy. A descent
//! method settles on stable states only: near a jump it stays on its branch up to the fold,
//! where a fixed-point iteration on the adhesive pressure can also land on the unstable
//! branch between.
//!
//! Two operator applications per iteration (the direction and the trial gap), against one per
//! inner iteration times many inner iterations per outer one in the dual loop.

use super::{AdhesiveOptions, AdhesiveReport, AdhesiveState, Start, assemble};
use crate::error::{Result, SolverError, invalid};
use crate::options::Control;
use crate::report::Termination;
use crate::state::ContactState;
use elastic::{Compliance, PeriodicStiffness};
use ljadhesion::{AdhesionLaw, LocalPotential};
use ndarray::{Array2, ArrayView2, Zip};
use rayon::prelude::*;
use std::time::Instant;

/// Cuts of a step that would raise the energy before the solve gives up.
const MAX_CUTS: usize = 40;

/// Sums of `K` quantities computed row by row in parallel and added in row order: the result
/// does not depend on the number of threads.
fn row_sums<const K: usize>(ny: usize, row: impl Fn(usize) -> [f64; K] + Sync) -> [f64; K] {
    let parts: Vec<[f64; K]> = (0..ny).into_par_iter().map(&row).collect();
    parts.iter().fold([0.0; K], |mut acc, p| {
        acc.iter_mut().zip(p).for_each(|(a, b)| *a += b);
        acc
    })
}

/// One admissible gap and what the solver needs of it.
struct Point {
    gap: Array2<f64>,
    /// `S (g - g0)` [Pa].
    elastic: Array2<f64>,
    /// `p(g)` [Pa].
    law: Array2<f64>,
    /// `V''(g)` [Pa/m].
    curvature: Array2<f64>,
    /// The gradient `S (g - g0) - p(g)` [Pa], then projected ([`Problem::project_gradient`]).
    gradient: Array2<f64>,
    /// Elastic energy, and interaction energy plus the load's potential `p_mean mean(g)`, per
    /// area [J/m^2].
    energy: (f64, f64),
    /// The gradient's sum over the cells off the wall, and their number.
    free: (f64, f64),
    /// The smallest gap [m].
    min_gap: f64,
}

impl Point {
    fn new(gap: Array2<f64>) -> Point {
        let shape = gap.dim();
        Point {
            gap,
            elastic: Array2::zeros(shape),
            law: Array2::zeros(shape),
            curvature: Array2::zeros(shape),
            gradient: Array2::zeros(shape),
            energy: (0.0, 0.0),
            free: (0.0, 0.0),
            min_gap: 0.0,
        }
    }

    fn total_energy(&self) -> f64 {
        self.energy.0 + self.energy.1
    }
}

/// Sums of a projected gradient `rho` (against the previous one, `old`).
struct GradientSums {
    /// The mean-pressure multiplier [Pa].
    lambda: f64,
    /// `max |rho|` [Pa].
    max: f64,
    /// `<rho, rho>` and `<rho, old>` [Pa^2].
    squared: f64,
    against_old: f64,
}

struct Problem<'a> {
    stiffness: PeriodicStiffness,
    ws: elastic::Workspace,
    potential: &'a dyn LocalPotential,
    g0: ArrayView2<'a, f64>,
    nx: usize,
    ny: usize,
    /// The prescribed mean gap [m] (approach control).
    mean_gap: f64,
    /// The prescribed mean pressure [Pa] (load control: the mean gap is free).
    load: Option<f64>,
    scratch: Array2<f64>,
    calls: usize,
}

impl Problem<'_> {
    /// Writes `max(from + step d + c, 0)` into `gap`, with the shift `c` that restores the mean
    /// gap: the Euclidean projection of the step onto the constraints. `c` comes from Newton
    /// on the convex, piecewise-linear mean (exact after finitely many steps). Also leaves
    /// `gap - g0` in the scratch field, for [`Problem::evaluate`]. With `hold`, cells of `from`
    /// with a gap at most `hold` [m] stay where they are and only the others shift (a warm
    /// start's first guess).
    fn step_and_project(
        &mut self,
        from: &Array2<f64>,
        d: &Array2<f64>,
        step: f64,
        gap: &mut Array2<f64>,
        hold: Option<f64>,
    ) {
        let (nx, n) = (self.nx, (self.nx * self.ny) as f64);
        let (fs, ds) = (from.as_slice().expect("layout"), d.as_slice().expect("layout"));
        // Holding every cell would leave nothing to restore the mean gap with.
        let hold = hold.filter(|&h| fs.iter().any(|&f| f > h));
        let held = |f: f64| hold.is_some_and(|h| f <= h);
        let mut c = 0.0;
        for _ in 0..if self.load.is_some() { 0 } else { 100 } {
            let [sum, free] = row_sums(self.ny, |j| {
                let (f, d) = (&fs[j * nx..][..nx], &ds[j * nx..][..nx]);
                f.iter().zip(d).fold([0.0, 0.0], |[s, k], (&f, &d)| {
                    let v = f + step * d + c;
                    if held(f) {
                        [s + f, k]
                    } else if v > 0.0 {
                        [s + v, k + 1.0]
                    } else {
                        [s, k]
                    }
                })
            });
            if free == 0.0 {
                // Everything below the wall: lift the highest cell to the mean gap.
                let top = fs
                    .iter()
                    .zip(ds)
                    .fold(f64::NEG_INFINITY, |m, (&f, &d)| m.max(f + step * d));
                c = self.mean_gap - top;
                continue;
            }
            let excess = sum / n - self.mean_gap;
            if excess.abs() <= 1e-15 * self.mean_gap {
                break;
            }
            c -= excess * n / free;
        }
        Zip::from(gap)
            .and(&mut self.scratch)
            .and(from)
            .and(d)
            .and(&self.g0)
            .par_for_each(|g, u, &f, &d, &g0| {
                *g = if held(f) { f } else { (f + step * d + c).max(0.0) };
                *u = *g - g0;
            });
    }

    /// Fills `at`'s fields, energy and raw gradient from its admissible gap, just made by
    /// [`Problem::step_and_project`].
    fn evaluate(&mut self, at: &mut Point) -> Result<()> {
        let nx = self.nx;
        self.stiffness
            .apply(self.scratch.view(), at.elastic.view_mut(), &mut self.ws)?;
        self.calls += 1;
        let potential = self.potential;
        let load = self.load.unwrap_or(0.0);
        let gs = at.gap.as_slice().expect("layout");
        let ds = self.scratch.as_slice().expect("layout");
        let es = at.elastic.as_slice().expect("layout");
        let sums: Vec<[f64; 6]> = at
            .law
            .as_slice_mut()
            .expect("layout")
            .par_chunks_mut(nx)
            .zip(at.curvature.as_slice_mut().expect("layout").par_chunks_mut(nx))
            .zip(at.gradient.as_slice_mut().expect("layout").par_chunks_mut(nx))
            .enumerate()
            .map(|(j, ((lr, cr), rr))| {
                // Elastic energy, interaction energy and the load's potential, free gradient
                // and count, non-finite gaps, smallest gap.
                let mut sums = [0.0, 0.0, 0.0, 0.0, 0.0, f64::INFINITY];
                for i in 0..nx {
                    let k = j * nx + i;
                    let g = gs[k];
                    let (v, p, c) = potential.evaluate(g);
                    (lr[i], cr[i]) = (p, c);
                    rr[i] = es[k] - p + load;
                    sums[0] += ds[k] * es[k];
                    sums[1] += v + load * g;
                    sums[5] = sums[5].min(g);
                    if g > 0.0 {
                        sums[2] += rr[i];
                        sums[3] += 1.0;
                    }
                    if !g.is_finite() {
                        sums[4] += 1.0;
                    }
                }
                sums
            })
            .collect();
        let t = sums
            .iter()
            .fold([0.0, 0.0, 0.0, 0.0, 0.0, f64::INFINITY], |mut a, b| {
                a.iter_mut().take(5).zip(b).for_each(|(a, b)| *a += b);
                a[5] = a[5].min(b[5]);
                a
            });
        if t[4] > 0.0 {
            let k = gs.iter().position(|g| !g.is_finite()).unwrap_or(0);
            return Err(SolverError::NonFinite {
                what: "gap",
                row: k / nx,
                col: k % nx,
                value: gs[k],
            });
        }
        let n = (self.nx * self.ny) as f64;
        at.energy = (0.5 * t[0] / n, t[1] / n);
        at.free = (t[2], t[3]);
        at.min_gap = t[5];
        Ok(())
    }

    /// Projects `at`'s raw gradient in place: less the mean-pressure multiplier (its mean over
    /// the cells off the wall), zero where a cell on the wall is pushed into it (that is its
    /// contact pressure), and with zero mean over the cells that move, so that the mean gap
    /// stays. Returns its sums against `old`.
    fn project_gradient(&self, at: &mut Point, old: &Array2<f64>) -> GradientSums {
        let nx = self.nx;
        let lambda = if self.load.is_none() && at.free.1 > 0.0 {
            at.free.0 / at.free.1
        } else {
            0.0
        };
        let gs = at.gap.as_slice().expect("layout");
        let [sum, moving] = {
            let rs = at.gradient.as_slice_mut().expect("layout");
            let parts: Vec<[f64; 2]> = rs
                .par_chunks_mut(nx)
                .enumerate()
                .map(|(j, row)| {
                    let mut sums = [0.0; 2];
                    for (r, &g) in row.iter_mut().zip(&gs[j * nx..][..nx]) {
                        let v = *r - lambda;
                        *r = if g <= 0.0 && v >= 0.0 { 0.0 } else { v };
                        if *r != 0.0 {
                            sums[0] += *r;
                            sums[1] += 1.0;
                        }
                    }
                    sums
                })
                .collect();
            parts.iter().fold([0.0; 2], |a, b| [a[0] + b[0], a[1] + b[1]])
        };
        let shift = if self.load.is_none() && moving > 0.0 {
            sum / moving
        } else {
            0.0
        };
        let os = old.as_slice().expect("layout");
        let parts: Vec<[f64; 3]> = at
            .gradient
            .as_slice_mut()
            .expect("layout")
            .par_chunks_mut(nx)
            .enumerate()
            .map(|(j, row)| {
                let mut sums = [0.0f64; 3];
                for (r, &o) in row.iter_mut().zip(&os[j * nx..][..nx]) {
                    if *r != 0.0 {
                        *r -= shift;
                    }
                    sums[0] = sums[0].max(r.abs());
                    sums[1] += *r * *r;
                    sums[2] += *r * o;
                }
                sums
            })
            .collect();
        let [max, squared, against_old] = parts
            .iter()
            .fold([0.0f64; 3], |a, b| [a[0].max(b[0]), a[1] + b[1], a[2] + b[2]]);
        GradientSums {
            lambda,
            max,
            squared,
            against_old,
        }
    }
}

/// Solves under approach control (`Control::Approach`) or load control (`Control::Force`,
/// `Control::MeanPressure`) on the periodic operator `op`; see the module docs.
#[allow(clippy::too_many_arguments)]
pub(super) fn solve(
    op: &dyn Compliance,
    law: &dyn AdhesionLaw,
    potential: &dyn LocalPotential,
    g0: ArrayView2<f64>,
    control: Control,
    options: &AdhesiveOptions,
    start: Start,
    observer: &mut dyn FnMut(usize, f64),
) -> Result<(AdhesiveState, AdhesiveReport)> {
    let started = Instant::now();
    let domain = *op.domain();
    let shape = domain.shape();
    let (ny, nx) = shape;
    if let Some(((row, col), &value)) = g0.indexed_iter().find(|(_, v)| !v.is_finite()) {
        return Err(SolverError::NonFinite {
            what: "initial gap",
            row,
            col,
            value,
        });
    }
    let n = (nx * ny) as f64;
    let (delta, load) = match control {
        Control::Approach(d) => (d, None),
        Control::MeanPressure(p) => (0.0, Some(p)),
        Control::Force(w) => (0.0, Some(w / (n * domain.cell_area()))),
        Control::CentralGap(_) => unreachable!("refused by the caller"),
    };
    let mean_gap = g0.mean().unwrap_or(0.0) - delta;
    if load.is_none() && mean_gap <= 0.0 {
        return Err(invalid(
            "approach",
            delta,
            "reaches the mean initial gap: a periodic surface is in full contact before that",
        ));
    }
    let stiffness = PeriodicStiffness::new(domain, op.e_star())?;
    let mut problem = Problem {
        ws: stiffness.make_workspace(),
        stiffness,
        potential,
        g0,
        nx,
        ny,
        mean_gap,
        load,
        scratch: Array2::zeros(shape),
        calls: 0,
    };
    let first = match start {
        // Under load control the rigid shift has no elastic stiffness, and a first step from
        // a point contact would snap far more of the surface in than a quasi-static approach
        // does: start from the non-adhesive contact at the same (compressive) load instead.
        Start::Loading => match load {
            Some(p) if p > 0.0 => {
                crate::cg::solve(op, g0, Control::MeanPressure(p), &options.inner, None)?
                    .0
                    .gap
            }
            _ => g0.mapv(|g| g - delta),
        },
        Start::Unloading => Array2::zeros(shape),
        Start::Warm(s) => {
            if s.contact.gap.dim() != shape {
                return Err(SolverError::ShapeMismatch {
                    what: "warm-start gap",
                    expected: shape,
                    got: s.contact.gap.dim(),
                });
            }
            s.contact.gap.clone()
        }
    };
    let mut x = Point::new(Array2::zeros(shape));
    // A warm start keeps its attached cells (gap within the law's range) in place and moves
    // only the rest: a uniform shift would tear the attached rim off at once (or press cells
    // into attraction on loading), and the descent would settle in that state's basin rather
    // than follow the branch; from the held guess the descent itself decides what peels off.
    let hold = matches!(start, Start::Warm(_)).then(|| law.range());
    problem.step_and_project(&first, &first, 0.0, &mut x.gap, hold);
    drop(first);
    problem.evaluate(&mut x)?;
    let mut direction = Array2::zeros(shape);
    let mut sums = problem.project_gradient(&mut x, &direction);
    direction.zip_mut_with(&x.gradient, |d, &r| *d = -r);
    let mut slope = -sums.squared;
    let mut trial = Point::new(Array2::zeros(shape));
    let mut s_direction = Array2::zeros(shape);

    let scale = super::cell_compliance(&domain, op.e_star()) / law.range();
    let mut history = Vec::new();
    let mut termination = Termination::MaxIterations;
    let mut iterations = 0;
    loop {
        let residual = sums.max * scale;
        history.push(residual);
        observer(iterations, residual);
        if residual < options.tolerance {
            termination = Termination::Converged;
            break;
        }
        if iterations == options.max_outer_iterations {
            break;
        }
        if load.is_some_and(|p| p < 0.0) && x.min_gap > 1e3 * law.range() {
            // Pulled by more than any attraction at these gaps can hold: flying apart.
            termination = Termination::PulledOff;
            break;
        }
        iterations += 1;
        problem
            .stiffness
            .apply(direction.view(), s_direction.view_mut(), &mut problem.ws)?;
        problem.calls += 1;
        let (ds, ss, cs) = (
            direction.as_slice().expect("layout"),
            s_direction.as_slice().expect("layout"),
            x.curvature.as_slice().expect("layout"),
        );
        let [elastic_curv, law_curv, law_pos] = row_sums(ny, |j| {
            let mut sums = [0.0; 3];
            for k in j * nx..(j + 1) * nx {
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
        let old_squared = sums.squared;
        sums = problem.project_gradient(&mut x, &trial.gradient);
        // Polak-Ribiere, reset to zero when negative, and steepest descent after a cut step.
        let beta = if cut || old_squared <= 0.0 {
            0.0
        } else {
            ((sums.squared - sums.against_old) / old_squared).max(0.0)
        };
        let parts: Vec<f64> = direction
            .as_slice_mut()
            .expect("layout")
            .par_chunks_mut(nx)
            .zip(x.gradient.as_slice().expect("layout").par_chunks(nx))
            .zip(x.gap.as_slice().expect("layout").par_chunks(nx))
            .map(|((dr, rr), gr)| {
                let mut slope = 0.0;
                for ((d, &r), &g) in dr.iter_mut().zip(rr).zip(gr) {
                    *d = if g <= 0.0 && r == 0.0 { 0.0 } else { -r + beta * *d };
                    slope += r * *d;
                }
                slope
            })
            .collect();
        slope = parts.iter().sum();
        if slope >= 0.0 {
            // Not a descent direction: steepest descent.
            direction.zip_mut_with(&x.gradient, |d, &r| *d = -r);
            slope = -sums.squared;
        }
    }
    // The mean pressure: prescribed, or minus the multiplier of the mean gap.
    let mean_pressure = load.unwrap_or(-sums.lambda);

    // Contact pressure where the gap is closed: the gradient's elastic and adhesive part plus
    // the mean pressure.
    let mut pressure = Array2::zeros(shape);
    Zip::from(&mut pressure)
        .and(&x.gap)
        .and(&x.elastic)
        .and(&x.law)
        .par_for_each(|p, &g, &e, &l| {
            *p = if g <= 0.0 {
                (e - l + mean_pressure).max(0.0)
            } else {
                0.0
            }
        });
    let mut displacement = &x.gap - &g0;
    let mean = displacement.mean().unwrap_or(0.0);
    displacement.mapv_inplace(|u| u - mean);
    // On a periodic domain the mean displacement is zero.
    let approach = match load {
        None => delta,
        Some(_) => g0.mean().unwrap_or(0.0) - x.gap.mean().unwrap_or(0.0),
    };
    let contact = ContactState {
        pressure,
        gap: x.gap,
        displacement,
        approach,
    };
    Ok(assemble(
        &domain,
        law,
        contact,
        x.law,
        (0, iterations, problem.calls),
        history,
        1.0,
        termination,
        started,
    ))
}
