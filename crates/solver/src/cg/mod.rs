//! Constrained conjugate gradients for normal contact (Polonsky & Keer, Wear 231, 1999).
//!
//! Minimises the complementary energy `(1/2) <p, K p> + <p, g0 - delta>` over `p >= 0`: the
//! gap `g = g0 - delta + K p` vanishes where `p > 0` and is positive where `p = 0`. Under load
//! control the total force is imposed after every step and `delta` is the Lagrange multiplier
//! (the mean gap over the contact set); under displacement control `delta` is given. Each
//! iteration applies the elastic operator twice (to the pressure and to the search direction).
//!
//! Preconditioned ([`ContactOptions::preconditioned`], under load control): the search
//! direction is built from the gap residual on the contact set after the inverse of the
//! operator (its Fourier multiplier inverted, the stiffness `E* |q| / 2` on a periodic grid),
//! restricted to the contact set again and deflated of its mean there (Vollebregt's FFT
//! preconditioner). One more FFT convolution an iteration; the iteration count grows far more
//! slowly with the grid (`docs/performance.md`).
//!
//! Under a hardness `H` ([`Interface`]) the pressure is also bounded above, `p <= H`: the
//! directions live on the elastic contact set `0 < p < H`, cells at `H` are held there while
//! they overlap and released when their gap opens. The bound is a projection: no extra FFT an
//! iteration. Under load control the cells at H are an outer active set (`capped.rs`).

mod capped;

use crate::error::{Result, SolverError};
use crate::fields::{flat, flat_mut};
use crate::interface::{Interface, Yield};
use crate::mean_mode::MeanMode;
use crate::observer::Observer;
use crate::options::{ContactOptions, Control};
use crate::report::{ContactReport, Termination, count_clusters};
use crate::state::ContactState;
use elastic::Compliance;
use ndarray::{Array2, ArrayView2, Zip};
use rayon::prelude::*;
use std::time::Instant;

/// The preconditioned iteration, started cold, keeps its conjugate directions through a step
/// whose projection onto `p >= 0` changed it by at most this share (in the 2-norm).
const KEEP_DIRECTIONS: f64 = 0.3;

/// Solves the normal contact of the elastic half-space `op` with the initial gap `g0` \[m\]
/// (minimum 0, see [`crate::geometry`]) under `control`: [`solve_with`] an elastic surface.
///
/// # Errors
/// As [`solve_with`].
pub fn solve(
    op: &dyn Compliance,
    g0: ArrayView2<f64>,
    control: Control,
    options: &ContactOptions,
    warm: Option<&ContactState>,
    observer: &mut dyn Observer,
) -> Result<(ContactState, ContactReport)> {
    solve_with(op, g0, &Interface::default(), control, options, warm, observer)
}

/// Solves the normal contact of the half-space `op` with the initial gap `g0` \[m\] (minimum 0,
/// see [`crate::geometry`]) across `interface` under `control`, telling `observer` each
/// iteration's residual. `warm` (a previous state on the same grid) seeds the pressure and
/// brings its permanent set; otherwise the solve starts cold. Returns the new state (its
/// permanent set settled, [`crate::interface`]) and its report; a solve that reaches the
/// iteration limit returns its last iterate with [`Termination::MaxIterations`].
///
/// # Errors
/// Non-finite or negative-minimum `g0`, a field of the wrong shape, a negative load or
/// approach, a load beyond the hardness times the area, a tolerance below what f64
/// arithmetic can reach.
pub fn solve_with(
    op: &dyn Compliance,
    g0: ArrayView2<f64>,
    interface: &Interface,
    control: Control,
    options: &ContactOptions,
    warm: Option<&ContactState>,
    observer: &mut dyn Observer,
) -> Result<(ContactState, ContactReport)> {
    let Some(mean) = MeanMode::of(op) else {
        return solve_relative(op, g0, interface, control, options, warm, observer);
    };
    // An approach from the base: one bound-constrained solve with the mean mode included.
    if let Control::Approach(_) = control {
        let whole = crate::mean_mode::WithMean::new(op, mean);
        return solve_relative(&whole, g0, interface, control, options, warm, observer);
    }
    // A load: solved in the methods' frame (the approach from the mean surface), then moved
    // to the base's.
    let warm = warm.map(|w| {
        let mut w = w.clone();
        let p_mean = w.pressure.mean().unwrap_or(0.0);
        mean.shift(&mut w, p_mean, -1.0);
        w
    });
    let cells = g0.len() as f64 * op.domain().cell_area();
    let (mut state, mut report) =
        solve_relative(op, g0, interface, control, options, warm.as_ref(), observer)?;
    let p = report.mean_pressure;
    report.approach += mean.shift(&mut state, p, 1.0);
    report.elastic_energy += 0.5 * op.mean_compliance() * p * p * cells;
    Ok((state, report))
}

/// [`solve_with`] in the methods' frame: on a periodic body with a mean compliance, the
/// approach is measured from the mean surface ([`crate::mean_mode`]).
pub(crate) fn solve_relative(
    op: &dyn Compliance,
    g0: ArrayView2<f64>,
    interface: &Interface,
    control: Control,
    options: &ContactOptions,
    warm: Option<&ContactState>,
    observer: &mut dyn Observer,
) -> Result<(ContactState, ContactReport)> {
    let scratch = &mut Scratch::new(op);
    interface.validate()?;
    let mut state = match warm {
        Some(w) => w.clone(),
        None => ContactState::unloaded(op.domain().shape()),
    };
    let before = state.permanent_set.take();
    let yielded = crate::interface::yielded_gap(g0, before.as_ref())?;
    let g0 = yielded.as_ref().map_or(g0, |g| g.view());
    // On a periodic half-space the mean gap is the most an elastic surface can close.
    if let Control::Approach(delta) = control
        && op.domain().periodic
        && op.body() == elastic::Body::HalfSpace
        && interface.hardness.is_none()
        && delta >= g0.mean().unwrap_or(0.0)
    {
        return Err(crate::error::invalid(
            "approach",
            delta,
            "reaches the mean initial gap: a periodic surface is in full contact before that \
             (its mean pressure is then unbounded; prescribe a load instead)",
        ));
    }
    let mut report = solve_in(
        scratch,
        g0,
        interface.cap(),
        control,
        options,
        &mut state,
        warm.is_some(),
        &mut |i, r| crate::observer::heard(observer, 0, i, r),
    )?;
    report.yielding = crate::interface::settle(interface, g0, before, &mut state, op.domain().cell_area());
    crate::error::finite_result(
        &[
            ("pressure", &state.pressure),
            ("gap", &state.gap),
            ("displacement", &state.displacement),
        ],
        &[("load", report.load), ("approach", report.approach)],
    )?;
    Ok((state, report))
}

/// The operator and the buffers of the conjugate-gradient solver, owned by the caller so that
/// repeated solves on one grid (the adhesive inner loop) allocate nothing.
pub(crate) struct Scratch<'a> {
    pub(crate) op: &'a dyn Compliance,
    pub(crate) ws: elastic::Workspace,
    direction: Array2<f64>,
    response: Array2<f64>,
    /// Made by the first preconditioned solve.
    preconditioner: Option<Preconditioner>,
}

impl<'a> Scratch<'a> {
    /// Buffers for solves with `op`.
    pub(crate) fn new(op: &'a dyn Compliance) -> Self {
        let shape = op.domain().shape();
        Scratch {
            op,
            ws: op.make_workspace(),
            direction: Array2::zeros(shape),
            response: Array2::zeros(shape),
            preconditioner: None,
        }
    }

    /// The direction and its response on the operator's grid, and the preconditioner made
    /// once it is first `needed`.
    fn prepare(&mut self, needed: bool) {
        let shape = self.op.domain().shape();
        if needed && self.preconditioner.is_none() {
            self.preconditioner = Some(Preconditioner::new(self.op));
        }
        if self.direction.dim() != shape {
            self.direction = Array2::zeros(shape);
            self.response = Array2::zeros(shape);
        }
    }
}

/// The inverse of the operator by FFT, applied to the gap residual on the contact set.
struct Preconditioner {
    fft: fft2::Fft2,
    /// The inverted Fourier multiplier, divided by the transform grid's size.
    multiplier: Array2<f64>,
    ws: fft2::Workspace,
    /// The residual on the contact set (zero elsewhere) and its preconditioned image.
    masked: Array2<f64>,
    image: Array2<f64>,
}

impl Preconditioner {
    fn new(op: &dyn Compliance) -> Self {
        let domain = op.domain();
        // The transform grid: the field's own when periodic, padded twice when free.
        let (mx, my) = if domain.periodic {
            (domain.nx, domain.ny)
        } else {
            (2 * domain.nx, 2 * domain.ny)
        };
        let size = (mx * my) as f64;
        let compliance = op.fourier_compliance();
        // The mean (q = 0, no compliance on a periodic grid) gets the softest mode's stiffness.
        let softest = compliance.iter().fold(0.0f64, |m, &c| m.max(c));
        let multiplier = compliance.mapv(|c| 1.0 / (if c > 0.0 { c } else { softest } * size * size));
        let fft = fft2::Fft2::new(mx, my);
        let ws = fft.make_workspace();
        Preconditioner {
            fft,
            multiplier,
            ws,
            masked: Array2::zeros(domain.shape()),
            image: Array2::zeros(domain.shape()),
        }
    }
}

/// [`solve`] in place with the operator of `scratch` and the pressure bounded by `cap` \[Pa\]
/// (infinite: elastic): `state` is the warm start when `warm` is true (its pressure seeds the
/// solve) and receives the solution, its permanent set left as it was.
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_in(
    scratch: &mut Scratch,
    g0: ArrayView2<f64>,
    cap: f64,
    control: Control,
    options: &ContactOptions,
    state: &mut ContactState,
    warm: bool,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<ContactReport> {
    solve_scaled(scratch, g0, cap, None, control, options, state, warm, observer)
}

/// [`solve_in`] with the residual measured against the gap scale `scale` \[m\] when given
/// (else the RMS of `g0`).
#[allow(clippy::too_many_arguments)]
pub(crate) fn solve_scaled(
    scratch: &mut Scratch,
    g0: ArrayView2<f64>,
    cap: f64,
    scale: Option<f64>,
    control: Control,
    options: &ContactOptions,
    state: &mut ContactState,
    warm: bool,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<ContactReport> {
    let op = scratch.op;
    let started = Instant::now();
    let domain = *op.domain();
    let shape = domain.shape();
    let target_load = checked(&domain, g0, control, options)?;
    let cell = domain.cell_area();
    if let (Some(w), true) = (target_load, cap.is_finite()) {
        // The load's multiplier, the approach, is not fixed by the elastic contact set once
        // most cells are at the cap: the load is met by an outer loop whose rounds are elastic
        // (the preconditioner never sees a cap).
        return capped::solve_load(scratch, g0, cap, w, options, state, warm, observer);
    }
    let h_ref = scale.unwrap_or_else(|| gap_scale(g0));

    let (warm, mut approach) = start(state, shape, warm, control);
    let ContactState {
        pressure: p,
        gap,
        displacement: u,
        approach: state_approach,
        ..
    } = state;
    initial_pressure(p, g0, control, target_load, warm, op, cap);

    let g0 = g0.as_standard_layout();
    let g0s = flat(&g0);
    let nx = domain.nx;
    // Under approach control the mean of the pressure on the contact set has no elastic
    // stiffness on a periodic grid, which the operator's inverse cannot precondition: near full
    // contact the step it gives releases every cell (a wave at 40 of its 58 z0, measured).
    let preconditioned = options.preconditioned && target_load.is_some();
    scratch.prepare(preconditioned);
    let Scratch {
        ws,
        direction: t,
        response: r,
        preconditioner,
        ..
    } = scratch;
    let mut preconditioner = preconditioner.as_mut().filter(|_| preconditioned);
    let mut g_norm_old = 1.0;
    let mut conjugate = false;
    let nothing = p.iter().all(|&v| v == 0.0);
    let mut termination = if nothing {
        Termination::NoContact
    } else {
        Termination::MaxIterations
    };
    let mut tally = Tally::default();

    if nothing {
        released_everywhere(u, gap, g0.view(), approach);
    } else {
        loop {
            let fresh = tally.fresh_needed || tally.since_fresh >= 32;
            if fresh {
                tally.fresh_product(op, ws, p, u)?;
            }
            // Pass A: pending rescale, gap before the approach, contact count and gap sum.
            let s = std::mem::replace(&mut tally.pending, 1.0);
            let [in_contact, gap_sum] = rescale_and_gap(p, u, gap, g0s, nx, s, cap);
            if target_load.is_some() {
                approach = gap_sum / in_contact;
            }
            // Pass B: the approach, the residuals in and out of contact, and <g, t_old> on the
            // contact set for the step length.
            let [g2_contact, g2_out, g_t_old] = residuals(gap, p, t, approach, nx, cap);
            // The KKT residual: p >= 0 holds by construction, so zero gap where p > 0 and no
            // interpenetration where p = 0 are all that is left to check.
            let residual = ((g2_contact + g2_out) / in_contact.max(1.0)).sqrt() / h_ref;
            if residual < options.tolerance && !fresh {
                // Confirm on a fresh product before accepting.
                tally.fresh_needed = true;
                continue;
            }
            tally.history.push(residual);
            if !observer(tally.iterations, residual) {
                termination = Termination::Interrupted;
                break;
            }
            if residual < options.tolerance {
                termination = Termination::Converged;
                break;
            }
            if tally.iterations == options.max_iterations {
                break;
            }
            tally.iterations += 1;
            tally.since_fresh += 1;
            // The (preconditioned) residual the direction is built from, less `shift` (its mean on
            // the contact set under load control), and its product with the residual there.
            let (z, shift, gz): (&Array2<f64>, f64, f64) = match preconditioner.as_deref_mut() {
                None => (&*gap, 0.0, g2_contact),
                Some(pre) => {
                    let (shift, gz) = pre.apply(gap, p, in_contact);
                    (&pre.image, shift, gz)
                }
            };
            let beta = if conjugate && g_norm_old > 0.0 {
                gz / g_norm_old
            } else {
                0.0
            };
            g_norm_old = gz;
            let direction = Direction {
                z,
                shift,
                gz,
                beta,
                g_t_old,
            };
            let load_control = target_load.map(|_| in_contact);
            let [p_sum, changed, released, moved, bent] =
                along_direction(op, ws, (p, u, gap), (t, r), direction, load_control, cap)?;
            tally.calls += 1;
            // Polonsky & Keer restart the conjugate directions on every release. Preconditioned and
            // cold, a few edge cells then flip in and out each iteration and the search zig-zags,
            // so there the directions are kept while the projection changes little of the step; a
            // warm start is next to its solution, where restarts are cheaper than stale directions
            // (`docs/decisions.md`). Any change of the active set makes the updated u inexact.
            conjugate = if preconditioned && !warm {
                bent <= KEEP_DIRECTIONS * KEEP_DIRECTIONS * moved
            } else {
                released == 0.0
            };
            tally.fresh_needed |= changed > 0.0;
            if p_sum == 0.0 {
                termination = Termination::NoContact;
                released_everywhere(u, gap, g0.view(), approach);
                break;
            }
            if let Some(w) = target_load {
                tally.pending = w / (p_sum * cell);
            }
        }
    }
    let report = ContactReport {
        iterations: tally.iterations,
        residual: tally.history.last().copied().unwrap_or(0.0),
        residual_history: tally.history,
        termination,
        operator_calls: tally.calls,
        wall_time_s: started.elapsed().as_secs_f64(),
        ..report(op, p, u, gap, approach)
    };
    *state_approach = approach;
    Ok(report)
}

/// A solve's bookkeeping. `u = K p` is either fresh from the operator or updated in step as
/// `u - tau K t` (exact when no cell was clipped or released); `pending` is a load rescale of
/// both p and u not yet applied. A fresh product is taken every 32 iterations and before
/// accepting convergence, so round-off cannot accumulate.
struct Tally {
    history: Vec<f64>,
    calls: usize,
    iterations: usize,
    fresh_needed: bool,
    since_fresh: usize,
    pending: f64,
}

impl Tally {
    /// `u = K p` from the operator, the pending rescale applied to `p` first.
    fn fresh_product(
        &mut self,
        op: &dyn Compliance,
        ws: &mut elastic::Workspace,
        p: &mut Array2<f64>,
        u: &mut Array2<f64>,
    ) -> Result<()> {
        if self.pending != 1.0 {
            *p *= std::mem::replace(&mut self.pending, 1.0);
        }
        op.apply(p.view(), u.view_mut(), ws)?;
        self.calls += 1;
        self.since_fresh = 0;
        self.fresh_needed = false;
        Ok(())
    }
}

impl Default for Tally {
    fn default() -> Self {
        Tally {
            history: Vec::new(),
            calls: 0,
            iterations: 0,
            fresh_needed: true,
            since_fresh: 0,
            pending: 1.0,
        }
    }
}

/// What a conjugate direction is made of.
struct Direction<'a> {
    /// The (preconditioned) residual, less `shift`, its mean on the contact set under load
    /// control; `gz` its product with the residual there.
    z: &'a Array2<f64>,
    shift: f64,
    gz: f64,
    /// The weight of the last direction, and that direction's product with the residual.
    beta: f64,
    g_t_old: f64,
}

/// Passes C to F: the conjugate direction into `t`, its response `r = K t`, the step length
/// along it, and the step ([`step`], whose sums it returns). Under load control
/// (`load_control`: the cells in contact) the mean of `K t` only moves the approach.
fn along_direction(
    op: &dyn Compliance,
    ws: &mut elastic::Workspace,
    (p, u, gap): (&mut Array2<f64>, &mut Array2<f64>, &Array2<f64>),
    (t, r): (&mut Array2<f64>, &mut Array2<f64>),
    d: Direction,
    load_control: Option<f64>,
    cap: f64,
) -> Result<[f64; 5]> {
    let nx = p.ncols();
    // Pass C: conjugate direction on the contact set, and its sum there.
    let t_sum = direction(t, p, d.z, d.shift, d.beta, nx, cap);
    // Under load control the mean of K t over the contact set only moves the approach:
    // <K t - mean, t> = <K t, t - mean(t)>, so the mean of t is all that is needed.
    let t_mean = load_control.map_or(0.0, |in_contact| t_sum / in_contact);
    let gt = d.gz + d.beta * d.g_t_old;
    op.apply(t.view(), r.view_mut(), ws)?;
    // Pass D: curvature along t.
    let rt = crate::sum::rows3(p.view(), r.view(), t.view(), |p, r, t| {
        if p > 0.0 && p < cap { r * (t - t_mean) } else { 0.0 }
    });
    let tau = if rt > 0.0 {
        gt / rt
    } else {
        // No direction to give a step (every loaded cell at the cap, or a lone cell under load
        // control): interpenetrating cells enter at a lone cell's stiffness, or nothing would
        // ever move.
        1.0 / op.cell_compliance()
    };
    // Pass F: step, projection onto p >= 0, release of every interpenetrating cell at zero
    // pressure (free ones and those just clipped: releasing the clipped ones too saves about
    // a tenth of the iterations on rough surfaces), and the matching update of u while it
    // stays exact.
    Ok(step(p, u, gap, (t, r), tau, nx, cap))
}

/// Where a solve starts: `state` itself when `warm` and on the grid of `shape`, else
/// unloaded; returns whether it is warm and the approach it starts at.
fn start(state: &mut ContactState, shape: (usize, usize), warm: bool, control: Control) -> (bool, f64) {
    let warm = warm && state.pressure.dim() == shape && state.displacement.dim() == shape;
    if !warm {
        *state = ContactState::unloaded(shape);
    }
    let approach = match control {
        Control::Approach(d) => d,
        _ if warm => state.approach,
        _ => 0.0,
    };
    (warm, approach)
}

/// Checks the input of a solve on `domain`; returns the load the control prescribes \[N\] (none
/// under approach control).
fn checked(
    domain: &elastic::Domain,
    g0: ArrayView2<f64>,
    control: Control,
    options: &ContactOptions,
) -> Result<Option<f64>> {
    let shape = domain.shape();
    if g0.dim() != shape {
        return Err(SolverError::ShapeMismatch {
            what: "initial gap",
            expected: shape,
            got: g0.dim(),
        });
    }
    crate::error::finite("initial gap", g0)?;
    options.validate()?;
    let cell = domain.cell_area();
    let n = (domain.nx * domain.ny) as f64;
    control.validate_without_adhesion()?;
    let target_load = match control {
        Control::MeanPressure(p) => Some(p * n * cell),
        Control::Force(w) => Some(w),
        Control::Approach(_) | Control::CentralGap(_) => None,
    };
    Ok(target_load)
}

/// The scale of the gap residual: the RMS of `g0` about its mean \[m\] (at least the least
/// positive number).
fn gap_scale(g0: ArrayView2<f64>) -> f64 {
    let n = g0.len() as f64;
    let mean = g0.sum() / n;
    (g0.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / n)
        .sqrt()
        .max(f64::MIN_POSITIVE)
}

/// No contact: no displacement, the gap the undeformed one less the approach.
fn released_everywhere(u: &mut Array2<f64>, gap: &mut Array2<f64>, g0: ArrayView2<f64>, approach: f64) {
    u.fill(0.0);
    Zip::from(gap).and(g0).par_for_each(|g, &g0| *g = g0 - approach);
}

/// The pressure a solve starts from: a warm start's own if it has contact; else the
/// prescribed mean pressure everywhere, or under approach control the overlap times a cell's
/// stiffness; scaled to the prescribed load.
fn initial_pressure(
    p: &mut Array2<f64>,
    g0: ArrayView2<f64>,
    control: Control,
    target_load: Option<f64>,
    warm: bool,
    op: &dyn Compliance,
    cap: f64,
) {
    let domain = op.domain();
    let cell = domain.cell_area();
    let n = (domain.nx * domain.ny) as f64;
    match (warm, target_load, control) {
        (true, _, _) if p.iter().any(|&v| v > 0.0) => {}
        (_, Some(w), _) => p.fill(w / (n * cell)),
        (_, None, Control::Approach(d)) => {
            // Overlap times a cell's stiffness: any positive guess on the overlap will do, held
            // below a cap so that the first step has an elastic contact set to move.
            let k = op.e_star() / domain.dx.min(domain.dy);
            Zip::from(&mut *p)
                .and(&g0)
                .par_for_each(|p, &g| *p = ((d - g).max(0.0) * k).min(0.5 * cap));
        }
        _ => unreachable!("either a load or an approach is prescribed"),
    }
    if let Some(w) = target_load
        && w > 0.0
    {
        let total = p.sum() * cell;
        *p *= w / total;
    }
}

/// Pass A: the pending load rescale `s` of `p` and `u`, the gap before the approach, and the
/// count of cells in elastic contact (`0 < p < cap`) and the sum of their gaps.
fn rescale_and_gap(
    p: &mut Array2<f64>,
    u: &mut Array2<f64>,
    gap: &mut Array2<f64>,
    g0s: &[f64],
    nx: usize,
    s: f64,
    cap: f64,
) -> [f64; 2] {
    let sums: Vec<[f64; 2]> = flat_mut(p)
        .par_chunks_mut(nx)
        .zip(flat_mut(u).par_chunks_mut(nx))
        .zip(flat_mut(gap).par_chunks_mut(nx))
        .zip(g0s.par_chunks(nx))
        .map(|(((p, u), g), g0)| {
            let mut acc = [0.0; 2];
            for i in 0..p.len() {
                p[i] *= s;
                u[i] *= s;
                g[i] = g0[i] + u[i];
                if p[i] > 0.0 && p[i] < cap {
                    acc[0] += 1.0;
                    acc[1] += g[i];
                }
            }
            acc
        })
        .collect();
    sums.iter().fold([0.0; 2], |a, b| [a[0] + b[0], a[1] + b[1]])
}

/// Pass B: the approach taken off the gap; the squared residuals in and out of elastic
/// contact (interpenetration where free, an open gap where held at the cap), and `<g, t>` on
/// the elastic contact set.
fn residuals(
    gap: &mut Array2<f64>,
    p: &Array2<f64>,
    t: &Array2<f64>,
    approach: f64,
    nx: usize,
    cap: f64,
) -> [f64; 3] {
    let sums: Vec<[f64; 3]> = flat_mut(gap)
        .par_chunks_mut(nx)
        .zip(flat(p).par_chunks(nx))
        .zip(flat(t).par_chunks(nx))
        .map(|((g, p), t)| {
            let mut acc = [0.0; 3];
            for ((g, p), t) in g.iter_mut().zip(p).zip(t) {
                *g -= approach;
                if *p >= cap {
                    acc[1] += g.max(0.0).powi(2);
                } else if *p > 0.0 {
                    acc[0] += *g * *g;
                    acc[2] += *g * *t;
                } else {
                    acc[1] += g.min(0.0).powi(2);
                }
            }
            acc
        })
        .collect();
    sums.iter()
        .fold([0.0; 3], |a, b| [a[0] + b[0], a[1] + b[1], a[2] + b[2]])
}

impl Preconditioner {
    /// The residual `gap` on the contact set of `p` through the operator's inverse, into
    /// `image`; its mean there (`in_contact` cells) and its product with the residual, deflated
    /// of that mean (preconditioning is under load control only).
    fn apply(&mut self, gap: &Array2<f64>, p: &Array2<f64>, in_contact: f64) -> (f64, f64) {
        let nx = p.ncols();
        Zip::from(&mut self.masked)
            .and(gap)
            .and(p)
            .par_for_each(|m, &g, &p| *m = if p > 0.0 { g } else { 0.0 });
        self.fft.convolve(
            self.masked.view(),
            self.multiplier.view(),
            self.image.view_mut(),
            &mut self.ws,
        );
        let (ps, zs, gs) = (flat(p), flat(&self.image), flat(gap));
        let [z_sum, zg, g_sum] = crate::sum::ordered(p.nrows(), |j| {
            let mut acc = [0.0; 3];
            for k in j * nx..(j + 1) * nx {
                if ps[k] > 0.0 {
                    acc[0] += zs[k];
                    acc[1] += zs[k] * gs[k];
                    acc[2] += gs[k];
                }
            }
            acc
        });
        let z_mean = z_sum / in_contact;
        (z_mean, zg - z_mean * g_sum)
    }
}

/// Pass C: the conjugate direction `t <- z - shift + beta t` on the elastic contact set (zero
/// off it), and its sum.
fn direction(
    t: &mut Array2<f64>,
    p: &Array2<f64>,
    z: &Array2<f64>,
    shift: f64,
    beta: f64,
    nx: usize,
    cap: f64,
) -> f64 {
    let sums: Vec<f64> = flat_mut(t)
        .par_chunks_mut(nx)
        .zip(flat(p).par_chunks(nx))
        .zip(flat(z).par_chunks(nx))
        .map(|((t, p), z)| {
            let mut acc = 0.0;
            for ((t, p), z) in t.iter_mut().zip(p).zip(z) {
                *t = if *p > 0.0 && *p < cap {
                    z - shift + beta * *t
                } else {
                    0.0
                };
                acc += *t;
            }
            acc
        })
        .collect();
    sums.iter().sum::<f64>()
}

/// Pass F: the step `p - tau t` projected onto `0 <= p <= cap`, every interpenetrating cell at
/// zero pressure and every cell at the cap whose gap opened released, and `u` updated to match.
/// Returns the new load, the cells clipped or released, those released, and the squares of the
/// step and of what the projection changed in it.
fn step(
    p: &mut Array2<f64>,
    u: &mut Array2<f64>,
    gap: &Array2<f64>,
    (t, r): (&Array2<f64>, &Array2<f64>),
    tau: f64,
    nx: usize,
    cap: f64,
) -> [f64; 5] {
    let rows: Vec<[f64; 5]> = flat_mut(p)
        .par_chunks_mut(nx)
        .zip(flat_mut(u).par_chunks_mut(nx))
        .zip(flat(gap).par_chunks(nx))
        .zip(flat(t).par_chunks(nx))
        .zip(flat(r).par_chunks(nx))
        .map(|((((p, u), g), t), r)| {
            let mut acc = [0.0; 5];
            for i in 0..p.len() {
                let old = p[i];
                let step = old - tau * t[i];
                let mut new = step;
                let mut changed = false;
                if old > 0.0 && new < 0.0 {
                    new = 0.0;
                    changed = true;
                }
                if new == 0.0 {
                    new = if g[i] < 0.0 { (-tau * g[i]).min(cap) } else { 0.0 };
                    if new > 0.0 {
                        changed = true;
                        acc[2] += 1.0;
                    }
                } else if new >= cap {
                    // Held at the cap while it overlaps; back into elastic contact once open.
                    new = if old >= cap && g[i] > 0.0 {
                        (cap - tau * g[i]).max(0.0)
                    } else {
                        cap
                    };
                    if new != old {
                        changed = true;
                        acc[2] += f64::from(u8::from(old >= cap));
                    }
                }
                p[i] = new;
                u[i] -= tau * r[i];
                acc[0] += new;
                acc[1] += f64::from(u8::from(changed));
                acc[3] += (tau * t[i]).powi(2);
                acc[4] += (new - step).powi(2);
            }
            acc
        })
        .collect();
    rows.iter().fold([0.0; 5], |mut a, b| {
        a.iter_mut().zip(b).for_each(|(a, b)| *a += b);
        a
    })
}

/// What the solution `p`, `u` at `approach` says: load, contact, clusters, energy (the
/// iterations' counts are the caller's). The gap is set as the solution defines it: zero in
/// contact, non-negative elsewhere.
fn report(
    op: &dyn Compliance,
    p: &Array2<f64>,
    u: &Array2<f64>,
    gap: &mut Array2<f64>,
    approach: f64,
) -> ContactReport {
    Zip::from(&mut *gap)
        .and(p)
        .par_for_each(|g, &p| *g = if p > 0.0 { 0.0 } else { g.max(0.0) });
    let domain = op.domain();
    let cell = domain.cell_area();
    let n = (domain.nx * domain.ny) as f64;
    let load = p.sum() * cell;
    ContactReport {
        load,
        mean_pressure: load / (n * cell),
        approach,
        contact_area_fraction: p.iter().filter(|&&v| v > 0.0).count() as f64 / n,
        clusters: count_clusters(p.view(), domain.periodic),
        max_pressure: p.iter().cloned().fold(0.0, f64::max),
        elastic_energy: op.energy(p.view(), u.view()),
        yielding: Yield::default(),
        iterations: 0,
        residual: 0.0,
        residual_history: Vec::new(),
        termination: Termination::Converged,
        operator_calls: 0,
        wall_time_s: 0.0,
    }
}
