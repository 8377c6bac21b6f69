//! Tangential loading of a normal contact: partial slip under Coulomb's law with Derjaguin's
//! adhesive term, `|q| <= tau0 + mu p_c` on the cells in contact, no shear elsewhere
//! (docs/method.md section 14). A cell is in contact where the wall presses it (`p_c > 0`)
//! or, with adhesion, where its gap is within that of the law's strongest attraction (the
//! edge of contact of Greenwood, 1997: `0.2 z0` for Lennard-Jones, 0 for the exponential and
//! Dugdale laws); there the tensile ring at a contact's edge carries the shear strength.
//!
//! The rigid body moves tangentially by `D` \[m\] (a vector in the plane); the body's surface by
//! `u = K q` ([`elastic::Shear`]). The slip `s = D - u` is what the contact remembers: a cell
//! sticks (`s` unchanged from the last step) while its shear is inside the disc of radius
//! `g = tau0 + mu p_c`, and slips along its shear when on it. A step is then the convex problem
//! `min 1/2 q.Kq - q.(D - s_prev)` over shears inside their discs (its optimality conditions
//! are exactly these), under a prescribed `D` or, with `D` its multiplier, a prescribed total
//! force `Q = sum q dA` \[N\]. It is solved by conjugate gradients over the free cells and
//! along the slipping cells' rims (the rim's curvature in the step), every iterate projected
//! back onto the discs: a tangential form of Polonsky & Keer's method (1999).
//!
//! Against a counterface of the body's own material the problem is the decoupled one: the
//! normal pressure is the normal solution's, whatever the shear. Against a rigid one, a
//! half-space of Poisson's ratio below 1/2, or a layer, couples the two ([`coupled`]).

use crate::error::{Result, SolverError, invalid};
use crate::report::Termination;
use crate::state::ContactState;
use elastic::{Compliance, Shear};
use ljadhesion::{AdhesionLaw, Cells};
use ndarray::Array2;
use std::sync::Arc;
use std::time::Instant;

pub mod coupled;
pub use coupled::{Counterface, Normal, NormalSolver, NormalState, Reached, TangentialPath};

/// Coulomb friction with Derjaguin's adhesive term: a contact cell carries a shear up to
/// `shear_strength + coefficient p_c` \[Pa\].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Friction {
    /// Coulomb's friction coefficient `mu` [-], `>= 0`.
    pub coefficient: f64,
    /// Shear strength `tau0` \[Pa\] of a contact cell at no pressure (adhesive friction), `>= 0`.
    pub shear_strength: f64,
}

impl Friction {
    /// A friction law, checked.
    ///
    /// # Errors
    /// A coefficient or shear strength that is negative or not finite, or both zero (a
    /// frictionless contact carries no shear).
    pub fn new(coefficient: f64, shear_strength: f64) -> Result<Friction> {
        let friction = Friction {
            coefficient,
            shear_strength,
        };
        friction.validate()?;
        Ok(friction)
    }

    /// Refuses a negative or non-finite coefficient or shear strength, or a law that carries
    /// no shear.
    pub fn validate(&self) -> Result<()> {
        if !(self.coefficient.is_finite() && self.coefficient >= 0.0) {
            return Err(invalid(
                "friction_coefficient",
                self.coefficient,
                "must be a finite number >= 0",
            ));
        }
        if !(self.shear_strength.is_finite() && self.shear_strength >= 0.0) {
            return Err(invalid(
                "shear_strength",
                self.shear_strength,
                "must be a finite shear stress >= 0 Pa",
            ));
        }
        if self.coefficient == 0.0 && self.shear_strength == 0.0 {
            return Err(invalid(
                "friction_coefficient",
                0.0,
                "with no shear strength the contact is frictionless and carries no tangential \
                 load: give a coefficient or a shear strength > 0",
            ));
        }
        Ok(())
    }

    /// The largest shear \[Pa\] a cell of compressive pressure `p_c` \[Pa\] carries, in contact
    /// or not.
    pub fn bound(&self, p_c: f64, in_contact: bool) -> f64 {
        if in_contact {
            self.shear_strength + self.coefficient * p_c
        } else {
            0.0
        }
    }
}

/// What a tangential step prescribes, as a vector `[x, y]` in the plane of the grid.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TangentialControl {
    /// The total shear force on the body \[N\].
    Force([f64; 2]),
    /// The rigid body's tangential displacement \[m\], from where the normal load left it (on
    /// periodic grids relative to the body's mean surface, which a mean shear moves without
    /// bound).
    Displacement([f64; 2]),
}

/// The tangential state of a contact: fields of the grid's shape `(ny, nx)`.
#[derive(Clone, Debug, PartialEq)]
pub struct ShearState {
    /// Shear traction on the body `[q_x, q_y]` \[Pa\].
    pub traction: [Array2<f64>; 2],
    /// The surfaces' relative tangential displacement since the path began, `[s_x, s_y]` \[m\]:
    /// the rigid body's displacement less the surface's, `D - u`. On the cells in contact, the
    /// slip; a cell that enters the contact sticks at its value.
    pub slip: [Array2<f64>; 2],
    /// The rigid body's tangential displacement \[m\].
    pub displacement: [f64; 2],
    /// The total shear force \[N\].
    pub force: [f64; 2],
}

impl ShearState {
    /// No shear and no slip: where a tangential path begins.
    pub fn unloaded(shape: (usize, usize)) -> ShearState {
        ShearState {
            traction: [Array2::zeros(shape), Array2::zeros(shape)],
            slip: [Array2::zeros(shape), Array2::zeros(shape)],
            displacement: [0.0; 2],
            force: [0.0; 2],
        }
    }
}

/// The gap \[m\] of `law`'s strongest attraction on a flat field, the smallest where there are
/// several (Dugdale's plateau): a cell at most this far apart is in contact for friction. Zero
/// without adhesion.
///
/// # Errors
/// The law's own refusal of a gap field.
pub fn contact_gap(law: &dyn AdhesionLaw) -> Result<f64> {
    if law.work_of_adhesion() <= 0.0 {
        return Ok(0.0);
    }
    let cells = Cells {
        dx: 1.0,
        dy: 1.0,
        periodic: true,
    };
    let mut out = Array2::zeros((2, 2));
    let mut pressure = |g: f64| -> Result<f64> {
        law.pressure_field(Array2::from_elem((2, 2), g).view(), &cells, out.view_mut())?;
        Ok(out[(0, 0)])
    };
    let (samples, reach) = (2000, 5.0 * law.range());
    let values = (0..=samples)
        .map(|k| pressure(reach * k as f64 / samples as f64))
        .collect::<Result<Vec<f64>>>()?;
    let lowest = values.iter().copied().fold(f64::INFINITY, f64::min);
    let first = values
        .iter()
        .position(|&p| p <= lowest * (1.0 - 1e-9))
        .unwrap_or(0);
    if first == 0 {
        return Ok(0.0);
    }
    // The minimum lies within a sample of `first`: a golden-section search there.
    let step = reach / samples as f64;
    let (mut lo, mut hi) = (step * (first - 1) as f64, step * (first + 1).min(samples) as f64);
    let ratio = (5f64.sqrt() - 1.0) / 2.0;
    for _ in 0..60 {
        let (a, b) = (hi - ratio * (hi - lo), lo + ratio * (hi - lo));
        if pressure(a)? <= pressure(b)? {
            hi = b;
        } else {
            lo = a;
        }
    }
    Ok(0.5 * (lo + hi))
}

/// A tangential solve's settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShearOptions {
    /// Tolerance on the worst cell's error in its slip (a sticking cell's slip, a slipping
    /// cell's slip across its shear), over the slip a cell's own largest shear makes (its
    /// bound times its compliance) [-].
    pub tolerance: f64,
    /// Iteration limit.
    pub max_iterations: usize,
    /// Under the coupling, the rounds of normal and tangential solves stop when the largest
    /// change of the compressive pressure over a round is at most this fraction of its
    /// largest value [-].
    pub coupling_tolerance: f64,
    /// The most rounds a coupled step takes.
    pub max_coupling_iterations: usize,
}

impl ShearOptions {
    /// The default tolerance.
    pub const DEFAULT_TOLERANCE: f64 = 1e-8;
    /// The default iteration limit.
    pub const DEFAULT_MAX_ITERATIONS: usize = 10_000;
    /// The default coupling tolerance.
    pub const DEFAULT_COUPLING_TOLERANCE: f64 = 1e-6;

    /// Refuses a tolerance that is not finite and positive, or no iterations.
    pub fn validate(&self) -> Result<()> {
        if !(self.tolerance.is_finite() && self.tolerance > 0.0) {
            return Err(invalid("tolerance", self.tolerance, "must be finite and > 0"));
        }
        if !(self.coupling_tolerance.is_finite() && self.coupling_tolerance > 0.0) {
            return Err(invalid(
                "coupling_tolerance",
                self.coupling_tolerance,
                "must be finite and > 0",
            ));
        }
        if self.max_iterations == 0 || self.max_coupling_iterations == 0 {
            return Err(invalid("max_iterations", 0.0, "must be at least 1"));
        }
        Ok(())
    }
}

impl Default for ShearOptions {
    fn default() -> Self {
        ShearOptions {
            tolerance: ShearOptions::DEFAULT_TOLERANCE,
            max_iterations: ShearOptions::DEFAULT_MAX_ITERATIONS,
            coupling_tolerance: ShearOptions::DEFAULT_COUPLING_TOLERANCE,
            max_coupling_iterations: 50,
        }
    }
}

/// What a tangential step reports. SI units.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ShearReport {
    /// Total shear force `[Q_x, Q_y]` \[N\].
    pub force: [f64; 2],
    /// The rigid body's tangential displacement `[D_x, D_y]` \[m\] (NaN under a force the
    /// contact cannot carry).
    pub displacement: [f64; 2],
    /// The most shear force the contact carries, `sum (tau0 + mu p_c) dA` \[N\]: the static
    /// friction force of a decoupled contact.
    pub capacity: f64,
    /// Fraction of the grid's cells in contact and sticking [-].
    pub stick_area_fraction: f64,
    /// Fraction of the grid's cells in contact and slipping [-].
    pub slip_area_fraction: f64,
    /// Energy friction dissipated over the step, `sum q . (s - s_prev) dA` with `q` averaged
    /// over the step \[J\].
    pub frictional_work: f64,
    /// Elastic energy of the shear, `(1/2) sum q . u dA` \[J\].
    pub elastic_energy: f64,
    /// Every cell in contact slips: the contact slides as a whole.
    pub gross_sliding: bool,
    /// Rounds of the normal and tangential solves under the coupling (0 when decoupled).
    pub coupling_iterations: usize,
    /// The normal load \[N\] under the shear (compressive, adhesive pressure included): the
    /// normal solution's when decoupled, and under load control.
    pub normal_load: f64,
    /// The normal approach \[m\] under the shear: the normal solution's when decoupled, and
    /// under approach control.
    pub approach: f64,
    /// Iterations run (of the last round's tangential solve when coupled).
    pub iterations: usize,
    /// Final residual ([`ShearOptions::tolerance`]).
    pub residual: f64,
    /// Why it stopped.
    pub termination: Termination,
    /// Wall time \[s\].
    pub wall_time_s: f64,
}

/// The tangential problem on one normal solution: the shear compliance, and each contact
/// cell's bound.
pub struct TangentialProblem {
    operator: Arc<Shear>,
    /// Flat indices of the cells in contact, and their bounds \[Pa\].
    cells: Vec<usize>,
    bound: Vec<f64>,
    shape: (usize, usize),
    cell_area: f64,
}

impl TangentialProblem {
    /// The tangential problem of the body of `normal`'s operator, of Poisson's ratio `poisson`,
    /// on the normal solution `state` (its compressive pressure and gap), under `friction`, with
    /// the cells whose gap is at most `contact_gap` \[m\] in contact besides those pressed
    /// ([`contact_gap`] of the law).
    ///
    /// # Errors
    /// A bad friction law or Poisson's ratio, a body whose tangential compliance is not
    /// implemented, fields of another shape, no cell in contact.
    pub fn new(
        normal: &dyn Compliance,
        poisson: f64,
        friction: Friction,
        state: &ContactState,
        contact_gap: f64,
    ) -> Result<Self> {
        friction.validate()?;
        let operator = Arc::new(Shear::of(normal, poisson)?);
        TangentialProblem::on(operator, friction, state, contact_gap)
    }

    /// [`TangentialProblem::new`] with the shear compliance made.
    fn on(operator: Arc<Shear>, friction: Friction, state: &ContactState, contact_gap: f64) -> Result<Self> {
        let domain = *operator.domain();
        let shape = domain.shape();
        for (what, field) in [("normal pressure", &state.pressure), ("normal gap", &state.gap)] {
            if field.dim() != shape {
                return Err(SolverError::ShapeMismatch {
                    what,
                    expected: shape,
                    got: field.dim(),
                });
            }
            crate::error::finite(what, field.view())?;
        }
        let (mut cells, mut bound) = (Vec::new(), Vec::new());
        for (k, (&p, &g)) in state.pressure.iter().zip(&state.gap).enumerate() {
            let b = friction.bound(p.max(0.0), p > 0.0 || g <= contact_gap);
            if b > 0.0 {
                cells.push(k);
                bound.push(b);
            }
        }
        if cells.is_empty() {
            return Err(SolverError::Unsupported(
                "a tangential load needs a normal contact: the normal solution has no cell in \
                 compressive contact (press the bodies together first)"
                    .into(),
            ));
        }
        Ok(TangentialProblem {
            operator,
            cells,
            bound,
            shape,
            cell_area: domain.cell_area(),
        })
    }

    /// The shear compliance.
    pub fn operator(&self) -> &Shear {
        &self.operator
    }

    /// The most shear force the contact carries \[N\].
    pub fn capacity(&self) -> f64 {
        self.bound.iter().sum::<f64>() * self.cell_area
    }

    /// The cells in contact as a fraction of the grid [-].
    pub fn contact_area_fraction(&self) -> f64 {
        self.cells.len() as f64 / (self.shape.0 * self.shape.1) as f64
    }

    /// Solves one step of a tangential path from `previous` (its slip is the history).
    ///
    /// # Errors
    /// A state of another shape, bad options, a non-finite control.
    pub fn solve(
        &self,
        control: TangentialControl,
        previous: &ShearState,
        options: &ShearOptions,
    ) -> Result<(ShearState, ShearReport)> {
        self.solve_from(control, previous, None, options)
    }

    /// [`TangentialProblem::solve`] with the iteration started from the shear `warm` \[Pa\]
    /// rather than the previous step's (a coupled step's last round).
    fn solve_from(
        &self,
        control: TangentialControl,
        previous: &ShearState,
        warm: Option<&[Array2<f64>; 2]>,
        options: &ShearOptions,
    ) -> Result<(ShearState, ShearReport)> {
        options.validate()?;
        let started = Instant::now();
        for field in previous
            .traction
            .iter()
            .chain(&previous.slip)
            .chain(warm.into_iter().flatten())
        {
            if field.dim() != self.shape {
                return Err(SolverError::ShapeMismatch {
                    what: "previous tangential state",
                    expected: self.shape,
                    got: field.dim(),
                });
            }
        }
        let (TangentialControl::Force(v) | TangentialControl::Displacement(v)) = control;
        if !(v[0].is_finite() && v[1].is_finite()) {
            return Err(invalid("tangential control", v[0] + v[1], "must be finite"));
        }
        let capacity = self.capacity();
        let cell = self.operator.cell_compliance();
        let self_compliance = cell[0].max(cell[1]);
        let scale = self.bound.iter().fold(0.0f64, |m, &g| m.max(g)) * self_compliance;
        let s_prev = self.on_cells(&previous.slip);
        let tau_prev = self.on_cells(&previous.traction);
        let mut tau = match warm {
            Some(warm) => {
                let mut tau = self.on_cells(warm);
                self.project(&mut tau);
                tau
            }
            None => tau_prev.clone(),
        };
        let target = match control {
            TangentialControl::Force(q) => Some(q),
            TangentialControl::Displacement(_) => None,
        };
        let mut ws = self.operator.make_workspace();
        let mut fields = Fields::new(self.shape);
        if let Some(q) = target {
            let magnitude = norm(q);
            if magnitude >= capacity {
                // More than the contact carries: every cell slides along the force.
                for (t, g) in tau.iter_mut().zip(&self.bound) {
                    *t = times(g / magnitude, q);
                }
                let mut report = self.report(&tau, &tau_prev, None, [f64::NAN; 2]);
                report.gross_sliding = true;
                report.elastic_energy = fields.energy(&self.operator, &self.cells, &tau, &mut ws)?;
                let state = self.state(&tau, previous, &s_prev, None, None, [f64::NAN; 2]);
                report.wall_time_s = started.elapsed().as_secs_f64();
                return Ok((state, report));
            }
            // The change of force spread in proportion to the bounds, then made exact.
            let change = sub(q, self.force(&tau));
            for (t, g) in tau.iter_mut().zip(&self.bound) {
                *t = add(*t, times(g / capacity, change));
            }
            self.project(&mut tau);
            self.fix_force(&mut tau, q);
        }
        let n = self.cells.len();
        let (mut w, mut r, mut t, mut kt, mut gradient) = (
            vec![[0.0; 2]; n],
            vec![[0.0; 2]; n],
            vec![[0.0; 2]; n],
            vec![[0.0; 2]; n],
            vec![[0.0; 2]; n],
        );
        let mut curvature = vec![0.0; n];
        let mut free = vec![false; n];
        let (mut g_old, mut residual, mut iterations) = (0.0f64, f64::INFINITY, 0);
        let mut d = match control {
            TangentialControl::Displacement(d) => d,
            TangentialControl::Force(_) => previous.displacement,
        };
        let mut termination = Termination::MaxIterations;
        while iterations < options.max_iterations {
            // The surface's displacement plus the slip before: sticking cells hold it at D.
            fields.apply(&self.operator, &self.cells, &tau, &mut w, &mut ws)?;
            w.iter_mut().zip(&s_prev).for_each(|(w, s)| *w = add(*w, *s));
            // D under force control: the mean over the cells inside their discs, then over the
            // free cells (those released from their rims join them).
            for pass in 0..2 {
                if target.is_some() {
                    let (mut sum, mut count) = ([0.0; 2], 0usize);
                    for (i, wi) in w.iter().enumerate() {
                        if (pass == 0 && !self.on_rim(i, tau[i])) || (pass == 1 && free[i]) {
                            sum = add(sum, *wi);
                            count += 1;
                        }
                    }
                    if count > 0 {
                        d = times(1.0 / count as f64, sum);
                    }
                }
                for (i, (ri, wi)) in r.iter_mut().zip(&w).enumerate() {
                    *ri = sub(*wi, d);
                    // A cell on its rim stays there while it slips outwards (-r along q).
                    free[i] = !self.on_rim(i, tau[i]) || dot(*ri, tau[i]) > 0.0;
                }
            }
            // The gradient on the set each cell may move in: a free cell's whole slip, a
            // slipping cell's slip across its shear (it moves along its disc's rim), with the
            // rim's curvature `|slip| / g` that the step must respect there.
            for i in 0..n {
                (gradient[i], curvature[i]) = if free[i] {
                    (r[i], 0.0)
                } else {
                    let along = dot(r[i], tau[i]) / norm(tau[i]);
                    (across(r[i], tau[i]), (-along).max(0.0) / self.bound[i])
                };
            }
            residual = gradient.iter().fold(0.0f64, |m, g| m.max(norm(*g))) / scale;
            if residual <= options.tolerance {
                termination = Termination::Converged;
                break;
            }
            iterations += 1;
            // A conjugate direction, preconditioned by each cell's own stiffness (its
            // compliance, plus the rim's curvature on a slipping cell); a slipping cell's stays
            // along its rim, and under a force the free cells take the direction's sum out (so
            // that the step keeps the force, and D drops out of it).
            let mut g_new = 0.0;
            for ((g, k), ri) in gradient.iter_mut().zip(&curvature).zip(&r) {
                *g = times(self_compliance / (self_compliance + k), *g);
                g_new += dot(*ri, *g);
            }
            // Restarted only where the direction would not descend: restarting whenever a cell
            // joins the free set (as Polonsky and Keer do) restarts at nearly every iteration
            // of a large rough contact and costs a fifth more iterations.
            let descends = r.iter().zip(&t).map(|(r, t)| dot(*r, *t)).sum::<f64>() > 0.0;
            let beta = if descends && g_old > 0.0 {
                g_new / g_old
            } else {
                0.0
            };
            for i in 0..n {
                t[i] = add(gradient[i], times(beta, t[i]));
                if !free[i] {
                    t[i] = across(t[i], tau[i]);
                }
            }
            if target.is_some() {
                let count = free.iter().filter(|&&f| f).count();
                if count > 0 {
                    let mean = times(1.0 / count as f64, t.iter().fold([0.0; 2], |s, t| add(s, *t)));
                    t.iter_mut()
                        .zip(&free)
                        .filter(|(_, f)| **f)
                        .for_each(|(t, _)| *t = sub(*t, mean));
                }
            }
            fields.apply(&self.operator, &self.cells, &t, &mut kt, &mut ws)?;
            let (mut num, mut den) = (0.0, 0.0);
            for i in 0..n {
                num += dot(r[i], t[i]);
                den += dot(t[i], kt[i]) + curvature[i] * dot(t[i], t[i]);
            }
            if den > 0.0 {
                let alpha = num / den;
                tau.iter_mut()
                    .zip(&t)
                    .for_each(|(v, t)| *v = sub(*v, times(alpha, *t)));
            }
            self.project(&mut tau);
            if let Some(q) = target {
                self.fix_force(&mut tau, q);
            }
            g_old = g_new;
        }
        let mut report = self.report(&tau, &tau_prev, Some((&r, &free)), d);
        report.gross_sliding = free.iter().all(|f| !f);
        report.iterations = iterations;
        report.residual = residual;
        report.termination = termination;
        report.elastic_energy = fields.energy(&self.operator, &self.cells, &tau, &mut ws)?;
        let state = self.state(
            &tau,
            previous,
            &s_prev,
            Some((&r, &free)),
            Some(&fields.displacement),
            d,
        );
        report.wall_time_s = started.elapsed().as_secs_f64();
        Ok((state, report))
    }

    /// A pair of fields' values on the contact cells.
    fn on_cells(&self, fields: &[Array2<f64>; 2]) -> Vec<[f64; 2]> {
        self.cells
            .iter()
            .map(|&k| {
                let (j, i) = (k / self.shape.1, k % self.shape.1);
                [fields[0][(j, i)], fields[1][(j, i)]]
            })
            .collect()
    }

    /// Whether cell `i`'s shear `q` is on its disc's rim.
    fn on_rim(&self, i: usize, q: [f64; 2]) -> bool {
        norm(q) >= self.bound[i] * (1.0 - 1e-12)
    }

    /// Every shear brought back inside its disc.
    fn project(&self, tau: &mut [[f64; 2]]) {
        for (t, &g) in tau.iter_mut().zip(&self.bound) {
            let m = norm(*t);
            if m > g {
                *t = times(g / m, *t);
            }
        }
    }

    /// The total shear force \[N\].
    fn force(&self, tau: &[[f64; 2]]) -> [f64; 2] {
        times(self.cell_area, tau.iter().fold([0.0; 2], |s, t| add(s, *t)))
    }

    /// Makes the total shear force `q` \[N\] exact by a uniform shear added to the cells inside
    /// their discs, projecting again, until it holds or no cell is left inside.
    fn fix_force(&self, tau: &mut [[f64; 2]], q: [f64; 2]) {
        for _ in 0..50 {
            let error = sub(q, self.force(tau));
            if norm(error) <= 1e-13 * self.capacity() {
                return;
            }
            let inside = (0..tau.len()).filter(|&i| !self.on_rim(i, tau[i])).count();
            if inside == 0 {
                return;
            }
            let per = times(1.0 / (inside as f64 * self.cell_area), error);
            for (i, g) in self.bound.iter().enumerate() {
                if !self.on_rim(i, tau[i]) {
                    let moved = add(tau[i], per);
                    let m = norm(moved);
                    tau[i] = if m > *g { times(g / m, moved) } else { moved };
                }
            }
        }
    }

    /// The step's scalars (the solver's counts are filled in by the caller); `slip` gives each
    /// cell's `r = -(slip increment)` and whether it is free (without it every cell slides).
    fn report(
        &self,
        tau: &[[f64; 2]],
        tau_prev: &[[f64; 2]],
        slip: Option<(&[[f64; 2]], &[bool])>,
        d: [f64; 2],
    ) -> ShearReport {
        let n = self.cells.len();
        let total = (self.shape.0 * self.shape.1) as f64;
        let (mut work, mut slipping) = (0.0, n);
        if let Some((r, free)) = slip {
            slipping = 0;
            for i in (0..n).filter(|&i| !free[i]) {
                slipping += 1;
                // The slip increment is -r; the shear averaged over the step.
                work -= 0.5 * dot(add(tau[i], tau_prev[i]), r[i]);
            }
        }
        ShearReport {
            force: self.force(tau),
            displacement: d,
            capacity: self.capacity(),
            stick_area_fraction: (n - slipping) as f64 / total,
            slip_area_fraction: slipping as f64 / total,
            frictional_work: work * self.cell_area,
            elastic_energy: 0.0,
            gross_sliding: false,
            coupling_iterations: 0,
            normal_load: 0.0,
            approach: 0.0,
            iterations: 0,
            residual: 0.0,
            termination: Termination::Converged,
            wall_time_s: 0.0,
        }
    }

    /// The state after the step: the shear, and the slip grown by each slipping cell's
    /// increment (sticking cells keep theirs); out of contact `D - u` from the surface's
    /// displacement `u` (unchanged from `previous` without it: gross sliding under a force).
    fn state(
        &self,
        tau: &[[f64; 2]],
        previous: &ShearState,
        s_prev: &[[f64; 2]],
        slip: Option<(&[[f64; 2]], &[bool])>,
        u: Option<&[Array2<f64>; 2]>,
        d: [f64; 2],
    ) -> ShearState {
        let slip_of = |c: usize| match u {
            Some(u) => u[c].mapv(|u| d[c] - u),
            None => previous.slip[c].clone(),
        };
        let mut state = ShearState {
            traction: [Array2::zeros(self.shape), Array2::zeros(self.shape)],
            slip: [slip_of(0), slip_of(1)],
            displacement: d,
            force: self.force(tau),
        };
        for (i, &k) in self.cells.iter().enumerate() {
            let (j, x) = (k / self.shape.1, k % self.shape.1);
            let increment = match slip {
                Some((r, free)) if !free[i] => times(-1.0, r[i]),
                _ => [0.0; 2],
            };
            for c in 0..2 {
                state.traction[c][(j, x)] = tau[i][c];
                state.slip[c][(j, x)] = s_prev[i][c] + increment[c];
            }
        }
        state
    }
}

fn add(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

fn times(s: f64, a: [f64; 2]) -> [f64; 2] {
    [s * a[0], s * a[1]]
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn norm(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}

/// `a` less its part along `q`.
fn across(a: [f64; 2], q: [f64; 2]) -> [f64; 2] {
    sub(a, times(dot(a, q) / dot(q, q), q))
}

/// Full-grid buffers for applying the shear compliance to values on the contact cells.
struct Fields {
    traction: [Array2<f64>; 2],
    displacement: [Array2<f64>; 2],
}

impl Fields {
    fn new(shape: (usize, usize)) -> Fields {
        Fields {
            traction: [Array2::zeros(shape), Array2::zeros(shape)],
            displacement: [Array2::zeros(shape), Array2::zeros(shape)],
        }
    }

    /// The full fields of `values` on the contact `cells` (zero elsewhere) and their
    /// displacements.
    fn load(
        &mut self,
        op: &Shear,
        cells: &[usize],
        values: &[[f64; 2]],
        ws: &mut elastic::ShearWorkspace,
    ) -> Result<()> {
        let [tx, ty] = &mut self.traction;
        let (sx, sy) = (
            tx.as_slice_mut().expect("standard layout"),
            ty.as_slice_mut().expect("standard layout"),
        );
        for (&k, v) in cells.iter().zip(values) {
            (sx[k], sy[k]) = (v[0], v[1]);
        }
        let [ux, uy] = &mut self.displacement;
        op.apply([tx.view(), ty.view()], [ux.view_mut(), uy.view_mut()], ws)?;
        Ok(())
    }

    /// `out = K values` on the contact `cells`.
    fn apply(
        &mut self,
        op: &Shear,
        cells: &[usize],
        values: &[[f64; 2]],
        out: &mut [[f64; 2]],
        ws: &mut elastic::ShearWorkspace,
    ) -> Result<()> {
        self.load(op, cells, values, ws)?;
        let [ux, uy] = &self.displacement;
        let (dx, dy) = (
            ux.as_slice().expect("standard layout"),
            uy.as_slice().expect("standard layout"),
        );
        for (&k, o) in cells.iter().zip(out.iter_mut()) {
            *o = [dx[k], dy[k]];
        }
        Ok(())
    }

    /// The elastic energy \[J\] of the shear `values` on the contact `cells`.
    fn energy(
        &mut self,
        op: &Shear,
        cells: &[usize],
        values: &[[f64; 2]],
        ws: &mut elastic::ShearWorkspace,
    ) -> Result<f64> {
        self.load(op, cells, values, ws)?;
        let ([tx, ty], [ux, uy]) = (&self.traction, &self.displacement);
        Ok(op.energy([tx.view(), ty.view()], [ux.view(), uy.view()]))
    }
}

/// What a tangential path did, from its steps' reports.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct TangentialSummary {
    /// The static friction force \[N\]: the shear force at which the stick zone vanishes, the
    /// contact's capacity `sum (tau0 + mu p_c) dA` in the decoupled problem.
    pub static_friction: f64,
    /// Whether the path reached it (some step slid as a whole).
    pub gross_sliding: bool,
    /// Energy friction dissipated over the path, the steps' sum \[J\].
    pub frictional_work: f64,
    /// The work the shear force did on the rigid body, `sum Q . dD` over the steps (trapezoidal)
    /// \[J\]: over a closed fretting cycle, the energy it dissipates.
    pub work: f64,
    /// Whether every step converged.
    pub all_converged: bool,
    /// The cells that carry shear, as a fraction of the grid [-].
    pub contact_area_fraction: f64,
}

impl TangentialSummary {
    /// The summary of `reports`, the steps of a path that began unloaded.
    pub fn of(reports: &[ShearReport]) -> TangentialSummary {
        let mut work = 0.0;
        let mut before = ([0.0; 2], [0.0; 2]);
        for r in reports {
            if r.displacement.iter().all(|v| v.is_finite()) {
                for c in 0..2 {
                    work += 0.5 * (r.force[c] + before.0[c]) * (r.displacement[c] - before.1[c]);
                }
                before = (r.force, r.displacement);
            }
        }
        TangentialSummary {
            static_friction: reports.first().map_or(0.0, |r| r.capacity),
            gross_sliding: reports.iter().any(|r| r.gross_sliding),
            frictional_work: reports.iter().map(|r| r.frictional_work).sum(),
            work,
            all_converged: reports.iter().all(|r| r.termination == Termination::Converged),
            contact_area_fraction: reports
                .first()
                .map_or(0.0, |r| r.stick_area_fraction + r.slip_area_fraction),
        }
    }
}

impl TangentialProblem {
    /// Follows the `controls` from `start`, each step from the last one's state, calling
    /// `step` after each with its index and report (return `false` to stop). Under a force the
    /// contact cannot carry the path ends at that step (it slides away).
    ///
    /// # Errors
    /// As [`TangentialProblem::solve`].
    pub fn path(
        &self,
        controls: &[TangentialControl],
        start: ShearState,
        options: &ShearOptions,
        step: &mut dyn FnMut(usize, &ShearState, &ShearReport) -> bool,
    ) -> Result<(ShearState, Vec<ShearReport>)> {
        follow(controls, start, |c, s| self.solve(c, &s, options), step)
    }
}

/// Follows `controls` from `start`, each step by `solve` from the last state, calling `step`
/// after each; a path ends early where `step` says so or under a force the contact cannot carry.
fn follow<S>(
    controls: &[TangentialControl],
    start: S,
    mut solve: impl FnMut(TangentialControl, S) -> Result<(S, ShearReport)>,
    step: &mut dyn FnMut(usize, &S, &ShearReport) -> bool,
) -> Result<(S, Vec<ShearReport>)> {
    let mut state = start;
    let mut reports = Vec::with_capacity(controls.len());
    for (k, &control) in controls.iter().enumerate() {
        let (next, report) = solve(control, state)?;
        let slid_away = report.gross_sliding && matches!(control, TangentialControl::Force(_));
        let go_on = step(k, &next, &report);
        reports.push(report);
        state = next;
        if slid_away || !go_on {
            break;
        }
    }
    Ok((state, reports))
}
