//! A tangential path on a body pressed by a rigid counterface (a half-space of Poisson's ratio
//! below 1/2, or a layer, which its base holds): the shear moves the surface normally and the
//! pressure moves it tangentially
//! ([`elastic::Shear::coupled_normal`]), so each step alternates the two solves until the
//! pressure settles: the tangential step at the latest pressure, with the pressure's own
//! tangential displacement since the path began added to the slip's reference, then the normal
//! contact again (same control, same method, warm) with the shear's normal displacement added
//! to the initial gap. A cell that enters the contact sticks where the surfaces then are (the
//! state's slip is their relative displacement everywhere).

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
    /// Rigid: the shear and the pressure move the surface across each other's directions (a
    /// half-space's for `nu < 1/2`, a layer's at any `nu`), and the normal contact changes under
    /// the shear.
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

impl<'a> Normal<'a> {
    /// A solution of the conjugate gradients under `control` with `options`.
    pub fn without_adhesion(state: ContactState, control: Control, options: &'a ContactOptions) -> Self {
        Normal {
            state: NormalState::WithoutAdhesion(state),
            control,
            solver: NormalSolver::WithoutAdhesion(options),
        }
    }

    /// A solution of an adhesive method under `control` with `settings`.
    pub fn adhesive(state: AdhesiveState, control: Control, settings: &'a Settings) -> Self {
        Normal {
            state: NormalState::Adhesive(state),
            control,
            solver: NormalSolver::Adhesive(settings),
        }
    }
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

/// Where an interrupted path stood: its last step's shear and the normal contact under it.
pub struct Reached {
    /// The shear and slip.
    pub shear: ShearState,
    /// The normal contact (the starting one when decoupled).
    pub normal: NormalState,
}

impl ContactProblem {
    /// Follows the tangential `controls` from `normal`, unloaded, or from where an interrupted
    /// path on it stood (`reached`; `controls` are then the steps left), calling `step` after
    /// each (its index among `controls`, its shear, the normal contact under it and its report;
    /// `false` stops the path). Decoupled unless the counterface is rigid and the body couples
    /// ([`Counterface`], [`elastic::Shear::coupled`]). Under a force the contact cannot carry
    /// the path ends at that step (it slides away).
    ///
    /// # Errors
    /// As [`ContactProblem::tangential`] and [`TangentialProblem::solve`]; a normal state of
    /// the other kind than its solver's.
    pub fn tangential_path(
        &self,
        normal: Normal,
        reached: Option<Reached>,
        controls: &[TangentialControl],
        options: &ShearOptions,
        step: &mut dyn FnMut(usize, &ShearState, &NormalState, &ShearReport) -> bool,
    ) -> Result<TangentialPath> {
        options.validate()?;
        let first = self.tangential(normal.state.contact())?;
        let cell_area = self.domain().cell_area();
        let coupled = (self.counterface == Counterface::Rigid && first.operator.coupled())
            .then(|| -> Result<Coupled> {
                Ok(Coupled {
                    problem: self,
                    operator: first.operator.clone(),
                    friction: self.check_tangential()?.0,
                    contact_gap: super::contact_gap(self.law.as_ref())?,
                    reference: normal.state.contact().pressure.clone(),
                    control: normal.control,
                    solver: normal.solver,
                })
            })
            .transpose()?;
        let (shear, state) = match reached {
            Some(Reached { shear, normal: under }) => {
                for field in shear
                    .traction
                    .iter()
                    .chain(&shear.slip)
                    .chain([&under.contact().pressure])
                {
                    if field.dim() != first.shape {
                        return Err(crate::error::SolverError::ShapeMismatch {
                            what: "the path's reached state",
                            expected: first.shape,
                            got: field.dim(),
                        });
                    }
                }
                (shear, if coupled.is_some() { under } else { normal.state })
            }
            None => (ShearState::unloaded(first.shape), normal.state),
        };
        let ((shear, normal), reports) = super::follow(
            controls,
            (shear, state),
            |control, (shear, under)| {
                let (next, mut report, under) = match &coupled {
                    Some(coupled) => coupled.step(control, &shear, &under, options)?,
                    None => {
                        let (next, report) = first.solve(control, &shear, options)?;
                        (next, report, under)
                    }
                };
                under.describe(&mut report, cell_area);
                Ok(((next, under), report))
            },
            &mut |k, (shear, under), report| step(k, shear, under, report),
        )?;
        Ok(TangentialPath {
            shear,
            reports,
            normal,
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
    /// One step from `previous` and the normal `state` under it: the new shear, its report and
    /// the normal state under it.
    fn step(
        &self,
        control: TangentialControl,
        previous: &ShearState,
        state: &NormalState,
        options: &ShearOptions,
    ) -> Result<(ShearState, ShearReport, NormalState)> {
        let started = std::time::Instant::now();
        let shape = self.reference.dim();
        let mut ws = self.operator.make_workspace();
        let (mut current, mut converged_normal) = (state.clone(), true);
        let mut last: Option<ShearState> = None;
        for round in 1..=options.max_coupling_iterations {
            let on = TangentialProblem::on(
                self.operator.clone(),
                self.friction,
                current.contact(),
                self.contact_gap,
            )?;
            // The pressure's tangential displacement since the path began joins the slip's
            // reference: a sticking cell holds D - K q - offset.
            let offset = self.pressure_displacement(&current.contact().pressure, &mut ws)?;
            let mut reference = previous.clone();
            for (slip, offset) in reference.slip.iter_mut().zip(&offset) {
                *slip += offset;
            }
            // Each round after the first starts from the last one's shear.
            let warm = last.as_ref().map(|s| &s.traction);
            let (mut shear, mut report) = on.solve_from(control, &reference, warm, options)?;
            for (slip, offset) in shear.slip.iter_mut().zip(&offset) {
                *slip -= offset;
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
            report.wall_time_s = started.elapsed().as_secs_f64();
            let settled = change <= options.coupling_tolerance * largest;
            if settled || round == options.max_coupling_iterations {
                if !(settled && converged_normal) {
                    report.termination = Termination::MaxIterations;
                }
                return Ok((shear, report, current));
            }
            last = Some(shear);
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
