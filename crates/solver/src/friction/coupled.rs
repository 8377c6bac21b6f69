//! A tangential path on a body of Poisson's ratio below 1/2 pressed by a rigid counterface: the
//! shear moves the surface normally and the pressure moves it tangentially
//! ([`elastic::Shear::coupled_normal`]), so each step alternates the two solves until the
//! pressure settles: the tangential step at the latest pressure, with the pressure's own
//! tangential displacement since the path began added to the slip's reference, then the normal
//! contact again (same control, same method, warm) with the shear's normal displacement added
//! to the initial gap. A cell that enters the contact sticks where the surfaces then are.

use super::{Friction, ShearOptions, ShearReport, ShearState, TangentialControl, TangentialProblem};
use crate::adhesive::{AdhesiveState, Start};
use crate::error::Result;
use crate::report::Termination;
use crate::{ContactOptions, ContactProblem, ContactState, Control, Settings};
use elastic::{Shear, ShearWorkspace};
use ndarray::{Array2, Zip};
use std::sync::Arc;

/// What the counterface is made of: whether normal and tangential loads couple.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Counterface {
    /// The body's own material (`E*` the pair's composite modulus): the coupling cancels and a
    /// tangential path leaves the normal solution as it is (exact also for an incompressible
    /// body).
    #[default]
    Similar,
    /// Rigid: for `nu < 1/2` the shear and the pressure move the surface across each other's
    /// directions, and the normal contact changes under the shear.
    Rigid,
}

/// How the normal contact is solved again under the shear: as it was first solved.
#[derive(Clone, Copy)]
pub enum NormalSolver<'a> {
    /// The constrained conjugate gradients ([`ContactProblem::solve_without_adhesion`]).
    WithoutAdhesion(&'a ContactOptions),
    /// An adhesive method ([`ContactProblem::solve`]).
    Adhesive(&'a Settings),
}

/// A normal solution, of the conjugate gradients or of an adhesive method.
#[derive(Clone, Debug, PartialEq)]
pub enum NormalState {
    /// Without adhesion.
    WithoutAdhesion(ContactState),
    /// With the adhesive pressure.
    Adhesive(AdhesiveState),
}

impl NormalState {
    /// The compressive pressure, gap and displacement.
    pub fn contact(&self) -> &ContactState {
        match self {
            NormalState::WithoutAdhesion(c) => c,
            NormalState::Adhesive(a) => &a.contact,
        }
    }

    /// The normal load \[N\] on cells of `cell_area` \[m^2\], the adhesive pressure included.
    pub fn load(&self, cell_area: f64) -> f64 {
        cell_area
            * match self {
                NormalState::WithoutAdhesion(c) => c.pressure.sum(),
                NormalState::Adhesive(a) => a.total_pressure().sum(),
            }
    }

    /// Writes its load and approach into `report`.
    fn describe(&self, report: &mut ShearReport, cell_area: f64) {
        report.normal_load = self.load(cell_area);
        report.approach = self.contact().approach;
    }
}

/// The normal contact a tangential path starts from: its solution, the control that reached it
/// (held along the path) and how it was solved.
pub struct Normal<'a> {
    /// The solution.
    pub state: NormalState,
    /// Its control.
    pub control: Control,
    /// Its method.
    pub solver: NormalSolver<'a>,
}

/// A tangential path's end: the shear, each step's report, and the normal solution under the
/// last step's shear (the starting one when decoupled).
pub struct TangentialPath {
    /// The last step's shear and slip.
    pub shear: ShearState,
    /// One a step.
    pub reports: Vec<ShearReport>,
    /// The normal contact at the end.
    pub normal: NormalState,
}

impl ContactProblem {
    /// Follows the tangential `controls` from `normal`, unloaded, calling `step` after each (its
    /// index, state and report; `false` stops the path). Decoupled unless the counterface is
    /// rigid and the body's Poisson's ratio below 1/2 ([`Counterface`]). Under a force the
    /// contact cannot carry the path ends at that step (it slides away).
    ///
    /// # Errors
    /// As [`ContactProblem::tangential`] and [`TangentialProblem::solve`]; a normal state of
    /// the other kind than its solver's.
    pub fn tangential_path(
        &self,
        normal: Normal,
        controls: &[TangentialControl],
        options: &ShearOptions,
        step: &mut dyn FnMut(usize, &ShearState, &ShearReport) -> bool,
    ) -> Result<TangentialPath> {
        options.validate()?;
        let first = self.tangential(normal.state.contact())?;
        let start = ShearState::unloaded(self.domain().shape());
        let cell_area = self.domain().cell_area();
        if self.counterface == Counterface::Similar || !first.operator.coupled() {
            let mut step = |k: usize, s: &ShearState, r: &ShearReport| {
                let mut r = r.clone();
                normal.state.describe(&mut r, cell_area);
                step(k, s, &r)
            };
            let (shear, mut reports) = first.path(controls, start, options, &mut step)?;
            reports
                .iter_mut()
                .for_each(|r| normal.state.describe(r, cell_area));
            return Ok(TangentialPath {
                shear,
                reports,
                normal: normal.state,
            });
        }
        let (friction, _) = self.check_tangential()?;
        let coupled = Coupled {
            problem: self,
            operator: first.operator.clone(),
            friction,
            contact_gap: super::contact_gap(self.law.as_ref())?,
            reference: normal.state.contact().pressure.clone(),
            control: normal.control,
            solver: normal.solver,
        };
        let (mut shear, mut state, mut last) = (start, normal.state, first);
        let mut reports = Vec::with_capacity(controls.len());
        for (k, control) in controls.iter().enumerate() {
            let (next, mut report, next_state, solved_on) =
                coupled.step(*control, &shear, &last, &state, options)?;
            next_state.describe(&mut report, cell_area);
            let slid_away = report.gross_sliding && matches!(control, TangentialControl::Force(_));
            let go_on = step(k, &next, &report);
            reports.push(report);
            (shear, state, last) = (next, next_state, solved_on);
            if slid_away || !go_on {
                break;
            }
        }
        Ok(TangentialPath {
            shear,
            reports,
            normal: state,
        })
    }
}

/// The parts of a coupled path that stay along it.
struct Coupled<'a> {
    problem: &'a ContactProblem,
    operator: Arc<Shear>,
    friction: Friction,
    contact_gap: f64,
    /// The compressive pressure where the path began \[Pa\]: slip counts from there.
    reference: Array2<f64>,
    control: Control,
    solver: NormalSolver<'a>,
}

impl Coupled<'_> {
    /// One step from `previous` (solved on the contact of `last`) and the normal `state`; the
    /// new shear, its report, the normal state under it and the contact it was solved on.
    fn step(
        &self,
        control: TangentialControl,
        previous: &ShearState,
        last: &TangentialProblem,
        state: &NormalState,
        options: &ShearOptions,
    ) -> Result<(ShearState, ShearReport, NormalState, TangentialProblem)> {
        let shape = self.reference.dim();
        let mut ws = self.operator.make_workspace();
        // Where a cell out of the last step's contact sticks if it enters: the surfaces'
        // relative displacement D - u then.
        let mut base = self.pressure_displacement(&state.contact().pressure, &mut ws)?;
        let mut shear_u = [Array2::zeros(shape), Array2::zeros(shape)];
        let [ux, uy] = &mut shear_u;
        self.operator.apply(
            [previous.traction[0].view(), previous.traction[1].view()],
            [ux.view_mut(), uy.view_mut()],
            &mut ws,
        )?;
        let mut in_last = vec![false; shape.0 * shape.1];
        last.cells.iter().for_each(|&k| in_last[k] = true);
        for c in 0..2 {
            Zip::from(&mut base[c])
                .and(&shear_u[c])
                .and(&previous.slip[c])
                .and(ndarray::ArrayView2::from_shape(shape, &in_last).expect("grid shape"))
                .for_each(|b, &u, &s, &inside| {
                    *b = if inside {
                        s
                    } else {
                        previous.displacement[c] - u - *b
                    }
                });
        }
        let (mut current, mut tangential) = (state.clone(), None);
        let mut converged_normal = true;
        for round in 1..=options.max_coupling_iterations {
            let on = match tangential.take() {
                Some(t) => t,
                None => TangentialProblem::on(
                    self.operator.clone(),
                    self.friction,
                    current.contact(),
                    self.contact_gap,
                )?,
            };
            // The pressure's tangential displacement since the path began joins the slip's
            // reference: a sticking cell holds D - K q - offset.
            let offset = self.pressure_displacement(&current.contact().pressure, &mut ws)?;
            let mut reference = previous.clone();
            for c in 0..2 {
                reference.slip[c] = &base[c] + &offset[c];
            }
            let (mut shear, mut report) = on.solve(control, &reference, options)?;
            for (slip, offset) in shear.slip.iter_mut().zip(&offset) {
                for &k in &on.cells {
                    let (j, i) = (k / shape.1, k % shape.1);
                    slip[(j, i)] -= offset[(j, i)];
                }
            }
            let mut lift = Array2::zeros(shape);
            self.operator.coupled_normal(
                [shear.traction[0].view(), shear.traction[1].view()],
                lift.view_mut(),
                &mut ws,
            )?;
            let (next, converged) = self.normal(&lift + &self.problem.initial_gap, &current)?;
            converged_normal &= converged;
            let (before, after) = (&current.contact().pressure, &next.contact().pressure);
            let largest = after.iter().fold(0.0f64, |m, &p| m.max(p));
            let change = Zip::from(before)
                .and(after)
                .fold(0.0f64, |m, &a, &b| m.max((a - b).abs()));
            current = next;
            report.coupling_iterations = round;
            let settled = change <= options.coupling_tolerance * largest;
            if settled || round == options.max_coupling_iterations {
                if !(settled && converged_normal) {
                    report.termination = Termination::MaxIterations;
                }
                return Ok((shear, report, current, on));
            }
            tangential = Some(TangentialProblem::on(
                self.operator.clone(),
                self.friction,
                current.contact(),
                self.contact_gap,
            )?);
        }
        unreachable!("the loop returns at its last round")
    }

    /// The tangential displacement \[m\] the change of compressive pressure since the path
    /// began makes.
    fn pressure_displacement(
        &self,
        pressure: &Array2<f64>,
        ws: &mut ShearWorkspace,
    ) -> Result<[Array2<f64>; 2]> {
        let shape = pressure.dim();
        let mut u = [Array2::zeros(shape), Array2::zeros(shape)];
        let [ux, uy] = &mut u;
        let change = pressure - &self.reference;
        self.operator
            .coupled_tangential(change.view(), [ux.view_mut(), uy.view_mut()], ws)?;
        Ok(u)
    }

    /// The normal contact again with the initial gap `g0`, warm from `warm`; whether it
    /// converged.
    fn normal(&self, g0: Array2<f64>, warm: &NormalState) -> Result<(NormalState, bool)> {
        let problem = self.problem;
        match (self.solver, warm) {
            (NormalSolver::WithoutAdhesion(options), NormalState::WithoutAdhesion(w)) => {
                let (state, report) = crate::cg::solve_with(
                    problem.operator.as_ref(),
                    g0.view(),
                    &problem.interface,
                    self.control,
                    options,
                    Some(w),
                    &mut (),
                )?;
                Ok((NormalState::WithoutAdhesion(state), report.converged()))
            }
            (NormalSolver::Adhesive(settings), NormalState::Adhesive(w)) => {
                let mut parts = problem.parts();
                parts.g0 = g0.view();
                let (state, report) =
                    crate::adhesive::solve(parts, self.control, settings, Start::Warm(w), &mut |_, _| true)?;
                Ok((NormalState::Adhesive(state), report.converged()))
            }
            _ => Err(crate::error::SolverError::Unsupported(
                "a normal state of another kind than its solver's (adhesive or not)".into(),
            )),
        }
    }
}
