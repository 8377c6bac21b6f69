//! Adhesive contact by the dual-loop method (method.md section 4; the paper's Fig. 4).
//!
//! The pressure is split into a compressive part `p_c >= 0` (the contact constraint) and an
//! adhesive part `p_a <= 0` (the law). With `p_a` held fixed, the gap is
//! `g = g0 - delta + K p_a + K p_c`: a non-adhesive contact problem for `p_c` with the initial
//! gap `g0 + K p_a`, solved by the constrained conjugate gradients of [`crate::cg`] (the
//! inner loop, warm-started from the previous outer iteration). The outer loop relaxes `p_a`
//! towards the law evaluated on the new gaps, `p_a <- p_a + beta (law(g) - p_a)`
//! ([`OuterLoop::DualLoop`], the paper's scheme), or mixes the last few iterates
//! ([`OuterLoop::Accelerated`], Anderson mixing), which reaches the same fixed point in far
//! fewer outer iterations. Laws with a local potential (point, exponential) can also be solved
//! with no outer loop at all, by descending the total energy ([`OuterLoop::EnergyDescent`],
//! module `energy`), under approach control, or load control on periodic domains; any law
//! but Dugdale's, the surface law included, by Newton-Krylov on the force balance
//! ([`OuterLoop::Newton`], module `newton`), under approach control.
//!
//! Convergence (the paper's criterion, made scale-free): the mean over the grid of
//! `|law(g) - p_a|` times the compliance of one cell (the displacement of a cell under unit
//! pressure on itself), over the law's range, is below [`AdhesiveOptions::tolerance`]
//! (default 1e-6): the mean gap error that the pending adhesive correction would cause locally
//! is below `1e-6 z0`.

mod anderson;
mod energy;
mod newton;

use crate::cg::{Scratch, solve_in};
use crate::error::{Result, SolverError, invalid};
use crate::options::{ContactOptions, Control};
use crate::report::{Termination, count_clusters};
use crate::state::ContactState;
use anderson::Anderson;
use elastic::{Compliance, Domain};
use ljadhesion::{AdhesionLaw, Cells, LocalPotential};
use ndarray::{Array2, ArrayView2, Zip};
use std::time::Instant;

/// The inner solve's gap error as a fraction of the outer residual. 0.1 was enough while the
/// inner solver also bounded its relative pressure change (which stopped it late); on its KKT
/// residual alone, 0.1 let jumps into and out of contact stall the outer loop (two steps of
/// `jkr-sphere` unconverged after 20000 outer iterations); 0.01 converges them all, in fewer
/// outer and inner iterations overall.
const INNER_FACTOR: f64 = 0.01;

/// Outer iterations without a 10 % improvement of the best residual that count as a stall.
const STALL: usize = 60;

/// How the outer loop updates the adhesive pressure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum OuterLoop {
    /// The paper's relaxation `p_a <- p_a + beta (law(g) - p_a)`, with an adaptive `beta`.
    DualLoop,
    /// Anderson mixing of the last [`AdhesiveOptions::history`] iterates (the default).
    Accelerated,
    /// No outer loop: constrained conjugate gradients on the total energy over the gap, for
    /// laws with a [`ljadhesion::LocalPotential`], under approach control, or load control on
    /// periodic domains. Its iterations are reported as inner iterations (no outer ones); the tolerance applies
    /// to the largest force imbalance of a cell times the cell's compliance, over the law's
    /// range (the module docs' measure, taken at its worst cell instead of on average).
    EnergyDescent,
    /// No outer loop either, for any law but Dugdale's (the surface law included):
    /// Newton-Krylov on the cells' force balance over the gap, globalised by pseudo-transient
    /// continuation (module `newton`), under approach control. Newton steps are reported as
    /// outer iterations, Krylov iterations as inner ones; the tolerance is the energy descent's
    /// worst-cell measure.
    Newton,
}

/// Settings of the adhesive solver, independent of the problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdhesiveOptions {
    /// The outer update.
    pub outer_loop: OuterLoop,
    /// Outer tolerance on the scale-free residual (module docs); the paper's 1e-6 by default.
    pub tolerance: f64,
    /// Outer iteration limit.
    pub max_outer_iterations: usize,
    /// Global relaxation factor `beta` in (0, 1] (`None`: 1). Each cell's step is further
    /// scaled by `1 / (1 + k c)`, with `k` the law's attractive stiffness at the cell's gap and
    /// `c` the cell's compliance. `beta` shrinks when the residual grows or stalls and regrows
    /// slowly while it falls.
    pub relaxation: Option<f64>,
    /// Iterates kept by Anderson mixing.
    pub history: usize,
    /// The inner (non-adhesive) solver's settings.
    pub inner: ContactOptions,
}

impl Default for AdhesiveOptions {
    fn default() -> Self {
        AdhesiveOptions {
            outer_loop: OuterLoop::Accelerated,
            tolerance: 1e-6,
            max_outer_iterations: 20_000,
            relaxation: None,
            history: 8,
            inner: ContactOptions {
                tolerance: 1e-10,
                max_iterations: 10_000,
            },
        }
    }
}

/// Where the outer loop starts.
#[derive(Clone, Copy, Debug)]
pub enum Start<'a> {
    /// No adhesive pressure: the bodies come together (the paper's loading start).
    Loading,
    /// The law's peak attraction everywhere: the bodies come apart from contact (the paper's
    /// unloading start).
    Unloading,
    /// A previous solution on the same grid (continuation along a sweep).
    Warm(&'a AdhesiveState),
}

/// The fields of an adhesive contact: all of shape `(ny, nx)`.
#[derive(Clone, Debug, PartialEq)]
pub struct AdhesiveState {
    /// Compressive pressure `p_c >= 0` [Pa] in `pressure`, the gap [m] (zero in contact), the
    /// total surface displacement `K (p_c + p_a)` [m] and the approach [m].
    pub contact: ContactState,
    /// Adhesive pressure `p_a <= 0` [Pa].
    pub adhesive_pressure: Array2<f64>,
}

impl AdhesiveState {
    /// The total pressure `p_c + p_a` [Pa].
    pub fn total_pressure(&self) -> Array2<f64> {
        &self.contact.pressure + &self.adhesive_pressure
    }
}

/// Scalars of an adhesive solution and the history of its solve. SI units; loads positive
/// compressive.
#[derive(Clone, Debug, PartialEq)]
pub struct AdhesiveReport {
    /// Total normal force `sum (p_c + p_a) dA` [N].
    pub load: f64,
    /// Load over the nominal area [Pa].
    pub mean_pressure: f64,
    /// The compressive part of the load [N] (>= 0).
    pub compressive_load: f64,
    /// The adhesive part of the load [N] (<= 0).
    pub adhesive_load: f64,
    /// Approach from first touch of the undeformed surfaces [m].
    pub approach: f64,
    /// Gap at the centre cell `(ny/2, nx/2)` [m].
    pub central_gap: f64,
    /// Fraction of cells in contact (`p_c > 0`) [-].
    pub contact_area_fraction: f64,
    /// Fraction of cells out of contact with a net attraction (`p_c = 0`, `p_a < 0`) [-].
    pub attractive_area_fraction: f64,
    /// Fraction of cells attached: gap below the law's range (`z0` for Lennard-Jones), contact
    /// included [-]. Unlike the contact area it stays nonzero while an adhesive neck without
    /// compressive contact holds the bodies together.
    pub attached_area_fraction: f64,
    /// Number of contact clusters.
    pub clusters: usize,
    /// Largest total pressure [Pa].
    pub max_pressure: f64,
    /// Most negative total pressure [Pa].
    pub min_pressure: f64,
    /// Outer iterations run.
    pub outer_iterations: usize,
    /// Inner (conjugate-gradient) iterations, summed over the outer ones.
    pub inner_iterations: usize,
    /// Calls to the elastic operator.
    pub operator_calls: usize,
    /// Final outer residual (module docs).
    pub residual: f64,
    /// The outer residual after every outer iteration.
    pub residual_history: Vec<f64>,
    /// The relaxation factor at the end.
    pub relaxation: f64,
    /// Why it stopped.
    pub termination: Termination,
    /// Wall time [s].
    pub wall_time_s: f64,
}

impl AdhesiveReport {
    /// Whether the solve met its tolerance.
    pub fn converged(&self) -> bool {
        self.termination == Termination::Converged
    }
}

/// The displacement [m] of one cell under unit pressure [Pa] on itself: the cell's compliance.
pub fn cell_compliance(domain: &Domain, e_star: f64) -> f64 {
    elastic::love::cell_influence(0.0, 0.0, domain.dx / 2.0, domain.dy / 2.0, e_star)
}

/// Warnings about a grid too coarse for the law: the cohesive (process-zone) length
/// `E* w0 / sigma0^2` must span at least one cell, or the adhesive zone at a contact edge
/// falls inside one cell. Each message says how fine the grid should be.
pub fn resolution_warnings(domain: &Domain, e_star: f64, law: &dyn AdhesionLaw) -> Vec<String> {
    let sigma = -law.peak_pressure();
    let process_zone = e_star * law.work_of_adhesion() / (sigma * sigma);
    let cell = domain.dx.max(domain.dy);
    let mut warnings = Vec::new();
    if cell > process_zone {
        warnings.push(format!(
            "the cell size {cell:.3e} m exceeds the adhesive process-zone length E* w0 / sigma0^2 = \
             {process_zone:.3e} m: the attractive zone at contact edges is not resolved; use a cell \
             of at most {process_zone:.3e} m ({} cells across this domain) for mesh-converged \
             adhesion",
            (domain.nx as f64 * domain.dx / process_zone).ceil()
        ));
    }
    warnings
}

/// Solves the adhesive contact of the half-space `op` with the initial gap `g0` [m] under the
/// adhesive `law` and `control`: [`Control::Approach`] (any sign: negative is apart),
/// [`Control::Force`] or [`Control::MeanPressure`] (any sign: negative pulls), or
/// [`Control::CentralGap`] (the approach follows, which traces unstable branches).
///
/// # Errors
/// Bad input (as [`crate::solve`]), a non-positive tolerance or relaxation factor, and
/// non-finite gaps met by the law.
pub fn solve_adhesive(
    op: &dyn Compliance,
    law: &dyn AdhesionLaw,
    g0: ArrayView2<f64>,
    control: Control,
    options: &AdhesiveOptions,
    start: Start,
) -> Result<(AdhesiveState, AdhesiveReport)> {
    solve_adhesive_observed(op, law, g0, control, options, start, &mut |_, _| {})
}

/// [`solve_adhesive`], calling `observer(outer_iteration, residual)` after every outer
/// iteration.
pub fn solve_adhesive_observed(
    op: &dyn Compliance,
    law: &dyn AdhesionLaw,
    g0: ArrayView2<f64>,
    control: Control,
    options: &AdhesiveOptions,
    start: Start,
    observer: &mut dyn FnMut(usize, f64),
) -> Result<(AdhesiveState, AdhesiveReport)> {
    let started = Instant::now();
    let domain = *op.domain();
    let shape = domain.shape();
    if g0.dim() != shape {
        return Err(SolverError::ShapeMismatch {
            what: "initial gap",
            expected: shape,
            got: g0.dim(),
        });
    }
    if !(options.tolerance > 0.0 && options.tolerance.is_finite()) {
        return Err(invalid("tolerance", options.tolerance, "must be finite and > 0"));
    }
    if let Some(b) = options.relaxation
        && !(b > 0.0 && b <= 1.0)
    {
        return Err(invalid("relaxation", b, "must be in (0, 1]"));
    }
    let value = match control {
        Control::Approach(v) | Control::Force(v) | Control::MeanPressure(v) | Control::CentralGap(v) => v,
    };
    if !value.is_finite() {
        return Err(invalid("control", value, "must be finite"));
    }
    if let Control::CentralGap(g) = control
        && g <= 0.0
    {
        return Err(invalid(
            "central_gap",
            g,
            "must be > 0 m: in contact the central gap does not fix the approach",
        ));
    }
    if options.outer_loop == OuterLoop::EnergyDescent {
        let potential = energy_descent_law(&domain, law, control)?;
        return energy::solve(op, law, potential, g0, control, options, start, observer);
    }
    if options.outer_loop == OuterLoop::Newton {
        if !matches!(control, Control::Approach(_)) {
            return Err(SolverError::Unsupported(
                "the Newton solver takes the approach only (use `accelerated` for loads and central \
                 gaps)"
                    .into(),
            ));
        }
        if !law.stiffness_bound().is_finite() {
            return Err(SolverError::Unsupported(format!(
                "the Newton solver linearises the law, and `{}` jumps (use `accelerated`)",
                law.name()
            )));
        }
        return newton::solve(op, law, g0, control, options, start, observer);
    }
    let cell = domain.cell_area();
    let n = (domain.nx * domain.ny) as f64;
    let cells = Cells {
        dx: domain.dx,
        dy: domain.dy,
        periodic: domain.periodic,
    };
    let centre = (domain.ny / 2, domain.nx / 2);
    let scale = cell_compliance(&domain, op.e_star()) / law.range();

    let (mut p_a, mut contact, mut warm) = match start {
        Start::Loading => (Array2::zeros(shape), ContactState::unloaded(shape), false),
        Start::Unloading => (
            Array2::from_elem(shape, law.peak_pressure()),
            ContactState::unloaded(shape),
            false,
        ),
        Start::Warm(s) => {
            if s.adhesive_pressure.dim() != shape {
                return Err(SolverError::ShapeMismatch {
                    what: "warm-start adhesive pressure",
                    expected: shape,
                    got: s.adhesive_pressure.dim(),
                });
            }
            (s.adhesive_pressure.clone(), s.contact.clone(), true)
        }
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
    let mut shifted = Array2::<f64>::zeros(shape);
    let mut law_shifted = Array2::<f64>::zeros(shape);
    let mut cell_beta = Array2::<f64>::zeros(shape);
    let c_cell = cell_compliance(&domain, op.e_star());
    let probe = 1e-3 * law.range();
    let mut beta = options.relaxation.unwrap_or(1.0);
    let beta_max = 1.0;
    let beta_min = 0.05 * beta;
    let mut mixer = Anderson::new(match options.outer_loop {
        OuterLoop::DualLoop | OuterLoop::EnergyDescent | OuterLoop::Newton => 0,
        OuterLoop::Accelerated => options.history,
    });
    let mut history: Vec<f64> = Vec::new();
    let (mut calls, mut inner_iterations, mut outer) = (0, 0, 0);
    let mut termination = Termination::MaxIterations;
    let mut falling = 0;
    // Stall detection: the best residual so far and when it last improved by 10 %.
    let (mut best, mut improved_at, mut stalls) = (f64::INFINITY, 0, 0);
    let mut approach = 0.0;
    loop {
        op.apply(p_a.view(), u_a.view_mut(), &mut scratch.ws)?;
        calls += 1;
        let adhesive_load = p_a.sum() * cell;
        let (inner_control, shift) = match control {
            Control::Approach(d) => (Control::Approach(0.0), d),
            Control::CentralGap(gc) => (
                Control::Approach(0.0),
                g0[centre] + u_a[centre] + u_c[centre] - gc,
            ),
            Control::Force(w) | Control::MeanPressure(w) => {
                let w = if let Control::MeanPressure(p) = control {
                    p * n * cell
                } else {
                    w
                };
                let compressive = w - adhesive_load;
                if compressive <= 0.0 {
                    // No contact can carry a load this tensile against this attraction.
                    termination = Termination::PulledOff;
                    break;
                }
                (Control::Force(compressive), 0.0)
            }
        };
        Zip::from(&mut g_eff)
            .and(&g0)
            .and(&u_a)
            .par_for_each(|g, &g0, &u| *g = g0 + u - shift);
        // Inexact inner solves: the inner gap error need only be well below the outer one.
        let inner_options = match history.last() {
            Some(&r) => {
                let mean = g_eff.mean().unwrap_or(0.0);
                let rms = (g_eff.iter().map(|g| (g - mean).powi(2)).sum::<f64>() / n).sqrt();
                let wanted = INNER_FACTOR * r.min(1.0) * law.range() / rms.max(f64::MIN_POSITIVE);
                ContactOptions {
                    tolerance: wanted.clamp(options.inner.tolerance, 1e-4),
                    ..options.inner
                }
            }
            None => options.inner,
        };
        let report = solve_in(
            op,
            g_eff.view(),
            inner_control,
            &inner_options,
            &mut contact,
            warm,
            &mut scratch,
            &mut |_, _| {},
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
        history.push(residual);
        observer(outer, residual);
        if residual < options.tolerance
            && inner_ok
            && inner_options.tolerance <= options.inner.tolerance * 1e3
        {
            termination = Termination::Converged;
            break;
        }
        if outer == options.max_outer_iterations {
            break;
        }
        outer += 1;
        // Adapt the relaxation: halve it (and forget the mixing history) when the residual
        // grows, regrow it slowly while the residual falls.
        // A jump into or out of contact makes the residual grow for a while by itself, so the
        // factor has a floor.
        if residual < 0.9 * best {
            best = residual;
            improved_at = outer;
        }
        if outer - improved_at > STALL {
            // Cycling between nearly equal states (a few cells at a contact edge, near a
            // jump): Anderson mixing can orbit there for ever. Drop it for the damped plain
            // relaxation, whose small steps settle on one state, with a lower floor.
            stalls += 1;
            improved_at = outer;
            mixer = Anderson::new(0);
            beta = (beta * 0.5).max(beta_min * 0.02);
            falling = 0;
        } else if history.len() >= 2 && residual > history[history.len() - 2] {
            if residual > 2.0 * history[history.len() - 2] || options.outer_loop == OuterLoop::DualLoop {
                beta = (beta * 0.7).max(if stalls > 0 { beta_min * 0.02 } else { beta_min });
                mixer.reset();
            }
            falling = 0;
        } else {
            falling += 1;
            if falling >= 5 {
                beta = (beta * 1.2).min(beta_max);
                falling = 0;
            }
        }
        // A diagonal preconditioner: each cell relaxed by 1 / (1 + k c), with k its own
        // attractive stiffness (from a probe of the law at slightly larger gaps) and c the
        // cell's compliance, so that stiff cells at contact edges do not hold back the others.
        Zip::from(&mut shifted)
            .and(&contact.gap)
            .par_for_each(|s, &g| *s = g + probe);
        law.pressure_field(shifted.view(), &cells, law_shifted.view_mut())?;
        Zip::from(&mut cell_beta)
            .and(&law_shifted)
            .and(&law_p)
            .par_for_each(|b, &hi, &lo| {
                let stiffness = ((lo - hi) / probe).max(0.0);
                *b = beta / (1.0 + stiffness * c_cell);
            });
        mixer.step(&mut p_a, residual_field.view(), cell_beta.view());
        // Attractive laws only: an extrapolated step must not push.
        p_a.par_mapv_inplace(|p| p.min(0.0));
    }

    // The total displacement and the reported fields.
    let mut displacement = u_a;
    displacement += &u_c;
    contact.displacement = displacement;
    contact.approach = approach;
    Ok(assemble(
        &domain,
        law,
        contact,
        p_a,
        (outer, inner_iterations, calls),
        history,
        beta,
        termination,
        started,
    ))
}

/// The law's local potential, if the energy descent can solve this problem; else why not.
fn energy_descent_law<'a>(
    domain: &Domain,
    law: &'a dyn AdhesionLaw,
    control: Control,
) -> Result<&'a dyn LocalPotential> {
    let Some(potential) = law.local_potential() else {
        return Err(SolverError::Unsupported(format!(
            "energy descent needs a law with a local potential (point, exponential), not `{}`",
            law.name()
        )));
    };
    if !domain.periodic && !matches!(control, Control::Approach(_)) {
        return Err(SolverError::Unsupported(
            "energy descent on a free domain takes the approach only (use `accelerated` for loads \
             and central gaps)"
                .into(),
        ));
    }
    if let Control::CentralGap(g) = control {
        return Err(invalid(
            "central_gap",
            g,
            "energy descent takes the approach (or mean gap), the load or the mean pressure",
        ));
    }
    Ok(potential)
}

/// The state and report of a finished solve: `contact` with its gap, compressive pressure,
/// displacement and approach set, and the adhesive pressure `p_a`.
#[allow(clippy::too_many_arguments)]
fn assemble(
    domain: &Domain,
    law: &dyn AdhesionLaw,
    contact: ContactState,
    p_a: Array2<f64>,
    (outer, inner_iterations, calls): (usize, usize, usize),
    history: Vec<f64>,
    relaxation: f64,
    termination: Termination,
    started: Instant,
) -> (AdhesiveState, AdhesiveReport) {
    let cell = domain.cell_area();
    let n = (domain.nx * domain.ny) as f64;
    let centre = (domain.ny / 2, domain.nx / 2);
    let compressive_load = contact.pressure.sum() * cell;
    let adhesive_load = p_a.sum() * cell;
    let load = compressive_load + adhesive_load;
    let in_contact = contact.pressure.iter().filter(|&&p| p > 0.0).count();
    let attractive = Zip::from(&contact.pressure)
        .and(&p_a)
        .fold(0usize, |acc, &c, &a| acc + usize::from(c == 0.0 && a < 0.0));
    let range = law.range();
    let attached = contact.gap.iter().filter(|&&g| g < range).count();
    let (mut max_p, mut min_p) = (f64::NEG_INFINITY, f64::INFINITY);
    Zip::from(&contact.pressure).and(&p_a).for_each(|&c, &a| {
        max_p = max_p.max(c + a);
        min_p = min_p.min(c + a);
    });
    let report = AdhesiveReport {
        load,
        mean_pressure: load / (n * cell),
        compressive_load,
        adhesive_load,
        approach: contact.approach,
        central_gap: contact.gap[centre],
        contact_area_fraction: in_contact as f64 / n,
        attractive_area_fraction: attractive as f64 / n,
        attached_area_fraction: attached as f64 / n,
        clusters: count_clusters(contact.pressure.view(), domain.periodic),
        max_pressure: max_p,
        min_pressure: min_p,
        outer_iterations: outer,
        inner_iterations,
        operator_calls: calls,
        residual: history.last().copied().unwrap_or(f64::NAN),
        residual_history: history,
        relaxation,
        termination,
        wall_time_s: started.elapsed().as_secs_f64(),
    };
    let state = AdhesiveState {
        contact,
        adhesive_pressure: p_a,
    };
    (state, report)
}
