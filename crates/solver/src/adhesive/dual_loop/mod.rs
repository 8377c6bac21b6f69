//! The dual loop (the paper's Fig. 4) and its accelerated form.
//!
//! With the adhesive pressure `p_a` held fixed, the gap is `g = g0 - delta + K p_a + K p_c`:
//! a non-adhesive contact problem for `p_c` with the initial gap `g0 + K p_a`, solved by the
//! constrained conjugate gradients of [`crate::cg`] (the inner loop, warm-started from the
//! previous outer iteration). The outer loop relaxes `p_a` towards the law evaluated on the
//! new gaps, `p_a <- p_a + beta (law(g) - p_a)` ([`crate::Method::DualLoop`], the paper's scheme), or
//! mixes the last few iterates ([`crate::Method::Accelerated`], Anderson mixing), which reaches the
//! same fixed point in far fewer outer iterations.
//!
//! Convergence (the paper's criterion, made scale-free): the mean over the grid of
//! `|law(g) - p_a|` times the compliance of one cell, over the law's range, is below the
//! tolerance: the mean gap error that the pending adhesive correction would cause locally.

mod anderson;

use super::driver::Driver;
use super::job::{AdhesiveMethod, Job, assemble, cells};
use super::{AdhesiveReport, AdhesiveState, Iterations, Start};
use crate::cg::{Scratch, solve_in};
use crate::error::Result;
use crate::method::Settings;
use crate::options::{ContactOptions, Control};
use crate::report::Termination;
use crate::state::ContactState;
use anderson::Anderson;
use ljadhesion::{AdhesionLaw, Cells};
use ndarray::{Array2, Zip};
use std::time::Instant;

/// The inner solve's gap error as a fraction of the outer residual: looser lets jumps into
/// and out of contact stall the outer loop (`docs/decisions.md`).
const INNER_FACTOR: f64 = 0.01;

/// Outer iterations without a 10 % improvement of the best residual that count as a stall.
const STALL: usize = 60;

/// The relaxation factor `beta`: its floor as a share of the starting one, and that floor's
/// share once the loop has stalled (a jump makes the residual grow for a while by itself, so
/// the factor needs a floor; a stalled loop needs a lower one to settle).
const FLOOR: f64 = 0.05;
const STALLED_FLOOR: f64 = 0.02;
/// `beta`'s cut at a stall and when the residual grows (by more than [`JUMP`] times, or at
/// all in the plain loop), and its growth after [`FALLING`] falling iterations in a row.
const STALL_CUT: f64 = 0.5;
const CUT: f64 = 0.7;
const JUMP: f64 = 2.0;
const GROWTH: f64 = 1.2;
const FALLING: usize = 5;
/// The probe of a cell's attractive stiffness, in ranges of the law.
const PROBE: f64 = 1e-3;
/// The loosest inner tolerance, and how far above the requested one the last inner solve may
/// be while the outer loop is taken as converged.
const INNER_LOOSEST: f64 = 1e-4;
const INNER_SLACK: f64 = 1e3;

/// The dual loop; `accelerated` mixes the iterates.
pub(super) struct DualLoop {
    pub accelerated: bool,
}

impl AdhesiveMethod for DualLoop {
    fn check(&self, _job: &Job) -> Result<()> {
        // Any law under any control, any interface (the cap bounds the inner solves).
        Ok(())
    }

    fn solve(
        &self,
        job: &Job,
        observer: &mut dyn FnMut(usize, f64) -> bool,
    ) -> Result<(AdhesiveState, AdhesiveReport)> {
        solve(job, self.accelerated, observer)
    }

    fn peak_bytes(&self, cells: f64, _periodic: bool) -> f64 {
        384.0 * cells
    }
}

fn solve(
    job: &Job,
    accelerated: bool,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<(AdhesiveState, AdhesiveReport)> {
    let (op, law, g0, settings) = (job.op, job.law, job.g0, job.settings);
    let (control, start) = (job.control, job.start);
    let started = Instant::now();
    let domain = *op.domain();
    let shape = domain.shape();
    let cell = domain.cell_area();
    let n = (domain.nx * domain.ny) as f64;
    let cells = cells(&domain);
    let centre = (domain.ny / 2, domain.nx / 2);
    let scale = job.residual_scale();

    let (mut p_a, mut contact, mut warm) = match start {
        Start::Loading => (Array2::zeros(shape), ContactState::unloaded(shape), false),
        Start::Unloading => (
            Array2::from_elem(shape, law.peak_pressure()),
            ContactState::unloaded(shape),
            false,
        ),
        Start::Warm(s) => (s.adhesive_pressure.clone(), s.contact.clone(), true),
    };
    // The elastic response of the compressive pressure, for the central-gap control.
    // One operator workspace, shared by the outer products and the inner solves.
    let mut scratch = Scratch::new(op);
    let mut u_c = Array2::zeros(shape);
    if warm {
        op.apply(contact.pressure.view(), u_c.view_mut(), &mut scratch.ws)?;
    }
    let mut u_a = Array2::<f64>::zeros(shape);
    let mut g_eff = Array2::<f64>::zeros(shape);
    let mut law_p = Array2::<f64>::zeros(shape);
    let mut residual_field = Array2::<f64>::zeros(shape);
    let mut cell_beta = CellRelaxation::new(shape, op.cell_compliance(), law.range());
    let mut relaxation = Relaxation::new(settings.mixing.relaxation.unwrap_or(1.0));
    let mut mixer = Anderson::new(if accelerated { settings.mixing.history } else { 0 });
    let (mut calls, mut inner_iterations, mut outer) = (0, 0, 0);
    let mut driver = Driver::new(settings, observer, started);
    let mut approach = 0.0;
    loop {
        op.apply(p_a.view(), u_a.view_mut(), &mut scratch.ws)?;
        calls += 1;
        let adhesive_load = p_a.sum() * cell;
        let Some((inner_control, shift)) = inner_control(
            control,
            g0[centre] + u_a[centre] + u_c[centre],
            adhesive_load,
            n * cell,
        ) else {
            // No contact can carry a load this tensile against this attraction.
            driver.termination = Termination::PulledOff;
            break;
        };
        Zip::from(&mut g_eff)
            .and(&g0)
            .and(&u_a)
            .par_for_each(|g, &g0, &u| *g = g0 + u - shift);
        let inner_options = inner_options(driver.last(), &g_eff, settings, law.range());
        let report = solve_in(
            &mut scratch,
            g_eff.view(),
            job.interface.cap(),
            inner_control,
            &inner_options,
            &mut contact,
            warm,
            &mut |_, _| true,
        )?;
        warm = true;
        calls += report.operator_calls;
        inner_iterations += report.iterations;
        approach = match inner_control {
            Control::Force(_) => report.approach,
            _ => shift,
        };
        u_c.assign(&contact.displacement);
        law.pressure_field(contact.gap.view(), &cells, law_p.view_mut())?;
        Zip::from(&mut residual_field)
            .and(&law_p)
            .and(&p_a)
            .par_for_each(|r, &l, &p| *r = l - p);
        let residual = residual_field.iter().map(|r| r.abs()).sum::<f64>() / n * scale;
        let inner_ok = report.converged();
        if driver.stop(
            outer,
            residual,
            inner_ok && inner_options.tolerance <= settings.contact.tolerance * INNER_SLACK,
        ) {
            break;
        }
        outer += 1;
        relaxation.adapt(&mut driver, &mut mixer, outer, residual, accelerated);
        cell_beta.update(law, &cells, (&contact.gap, &law_p), relaxation.beta)?;
        mixer.step(&mut p_a, residual_field.view(), cell_beta.beta.view());
        // Attractive laws only: an extrapolated step must not push.
        p_a.par_mapv_inplace(|p| p.min(0.0));
    }

    // The total displacement and the reported fields.
    let mut displacement = u_a;
    displacement += &u_c;
    contact.displacement = displacement;
    contact.approach = approach;
    let iterations = Iterations::Loop {
        outer,
        inner: inner_iterations,
        relaxation: relaxation.beta,
    };
    Ok(assemble(job, contact, p_a, driver.finish(iterations, calls)))
}

/// The inner solve's control and the approach shift of the outer gap, under `control`: the
/// approach itself; a central gap's, from the centre's undeformed gap plus its displacement
/// `centre_gap`; under load control the compressive load left after the adhesive one
/// (`None` when it is not positive: nothing can carry the load). `area` is the box's [m^2].
fn inner_control(control: Control, centre_gap: f64, adhesive_load: f64, area: f64) -> Option<(Control, f64)> {
    match control {
        Control::Approach(d) => Some((Control::Approach(0.0), d)),
        Control::CentralGap(gc) => Some((Control::Approach(0.0), centre_gap - gc)),
        Control::Force(w) | Control::MeanPressure(w) => {
            let w = if let Control::MeanPressure(p) = control {
                p * area
            } else {
                w
            };
            let compressive = w - adhesive_load;
            (compressive > 0.0).then_some((Control::Force(compressive), 0.0))
        }
    }
}

/// Inexact inner solves: the inner gap error need only be well below the outer one (`last`,
/// in units of the law's `range`), relative to the RMS of the effective gap `g_eff`.
fn inner_options(last: Option<f64>, g_eff: &Array2<f64>, settings: &Settings, range: f64) -> ContactOptions {
    match last {
        Some(r) => {
            let n = g_eff.len() as f64;
            let mean = g_eff.mean().unwrap_or(0.0);
            let rms = (g_eff.iter().map(|g| (g - mean).powi(2)).sum::<f64>() / n).sqrt();
            let wanted = INNER_FACTOR * r.min(1.0) * range / rms.max(f64::MIN_POSITIVE);
            ContactOptions {
                tolerance: wanted.clamp(settings.contact.tolerance, INNER_LOOSEST),
                ..settings.contact
            }
        }
        None => settings.contact,
    }
}

/// A diagonal preconditioner: each cell relaxed by `beta / (1 + k c)`, with `k` its own
/// attractive stiffness (from a probe of the law at gaps larger by `probe`) and `c` the cell's
/// compliance, so that stiff cells at contact edges do not hold back the others. Its fields
/// are kept between the outer iterations.
struct CellRelaxation {
    /// Each cell's relaxation factor.
    beta: Array2<f64>,
    shifted: Array2<f64>,
    law_shifted: Array2<f64>,
    c_cell: f64,
    probe: f64,
}

impl CellRelaxation {
    fn new(shape: (usize, usize), c_cell: f64, range: f64) -> Self {
        CellRelaxation {
            beta: Array2::zeros(shape),
            shifted: Array2::zeros(shape),
            law_shifted: Array2::zeros(shape),
            c_cell,
            probe: PROBE * range,
        }
    }

    /// The factors at the gaps `gap`, where the law gives `law_p`, for the relaxation `beta`.
    fn update(
        &mut self,
        law: &dyn AdhesionLaw,
        cells: &Cells,
        (gap, law_p): (&Array2<f64>, &Array2<f64>),
        beta: f64,
    ) -> Result<()> {
        let (probe, c_cell) = (self.probe, self.c_cell);
        Zip::from(&mut self.shifted)
            .and(gap)
            .par_for_each(|s, &g| *s = g + probe);
        law.pressure_field(self.shifted.view(), cells, self.law_shifted.view_mut())?;
        Zip::from(&mut self.beta)
            .and(&self.law_shifted)
            .and(law_p)
            .par_for_each(|b, &hi, &lo| {
                let stiffness = ((lo - hi) / probe).max(0.0);
                *b = beta / (1.0 + stiffness * c_cell);
            });
        Ok(())
    }
}

/// The relaxation factor and its adaptation: halved (and the mixing history forgotten) when
/// the residual grows, regrown slowly while it falls. A jump into or out of contact makes the
/// residual grow for a while by itself, so the factor has a floor.
struct Relaxation {
    beta: f64,
    floor: f64,
    /// Outer iterations the residual has fallen in a row.
    falling: usize,
    stalls: usize,
}

impl Relaxation {
    const MAX: f64 = 1.0;

    fn new(beta: f64) -> Self {
        Relaxation {
            beta,
            floor: FLOOR * beta,
            falling: 0,
            stalls: 0,
        }
    }

    fn adapt(
        &mut self,
        driver: &mut Driver,
        mixer: &mut Anderson,
        outer: usize,
        residual: f64,
        accelerated: bool,
    ) {
        if driver.since_progress(outer, residual) > STALL {
            // Cycling between nearly equal states (a few cells at a contact edge, near a
            // jump): Anderson mixing can orbit there for ever. Drop it for the damped plain
            // relaxation, whose small steps settle on one state, with a lower floor.
            self.stalls += 1;
            driver.restart_stall_count(outer);
            *mixer = Anderson::new(0);
            self.beta = (self.beta * STALL_CUT).max(self.floor * STALLED_FLOOR);
            self.falling = 0;
        } else if let Some(previous) = driver.previous()
            && residual > previous
        {
            if residual > JUMP * previous || !accelerated {
                self.beta = (self.beta * CUT).max(if self.stalls > 0 {
                    self.floor * STALLED_FLOOR
                } else {
                    self.floor
                });
                mixer.reset();
            }
            self.falling = 0;
        } else {
            self.falling += 1;
            if self.falling >= FALLING {
                self.beta = (self.beta * GROWTH).min(Self::MAX);
                self.falling = 0;
            }
        }
    }
}
