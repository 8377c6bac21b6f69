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

use crate::error::{Result, SolverError};
use crate::fields::{flat, flat_mut};
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

/// Solves the normal contact of the half-space `op` with the initial gap `g0` \[m\] (minimum 0,
/// see [`crate::geometry`]) under `control`, telling `observer` each iteration's residual.
/// `warm` (a previous state on the same grid) seeds the pressure; otherwise the solve starts
/// cold. Returns the new state and its report; a solve that reaches the iteration limit
/// returns its last iterate with [`Termination::MaxIterations`].
///
/// # Errors
/// Non-finite or negative-minimum `g0`, a field of the wrong shape, a negative load or
/// approach, a tolerance below what f64 arithmetic can reach.
pub fn solve(
    op: &dyn Compliance,
    g0: ArrayView2<f64>,
    control: Control,
    options: &ContactOptions,
    warm: Option<&ContactState>,
    observer: &mut dyn Observer,
) -> Result<(ContactState, ContactReport)> {
    let mut state = match warm {
        Some(w) => w.clone(),
        None => ContactState::unloaded(op.domain().shape()),
    };
    let mut scratch = Scratch::new(op);
    let report = solve_in(
        &mut scratch,
        g0,
        control,
        options,
        &mut state,
        warm.is_some(),
        &mut |i, r| crate::observer::heard(observer, 0, i, r),
    )?;
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

/// [`solve`] in place with the operator of `scratch`: `state` is the warm start when `warm`
/// is true (its pressure seeds the solve) and receives the solution.
pub(crate) fn solve_in(
    scratch: &mut Scratch,
    g0: ArrayView2<f64>,
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
        Control::MeanPressure(p) => Some(("mean_pressure", p, p * n * cell)),
        Control::Force(w) => Some(("load", w, w)),
        Control::Approach(_) | Control::CentralGap(_) => None,
    };
    let g0_mean = g0.mean().unwrap_or(0.0);
    let h_ref = (g0.iter().map(|v| (v - g0_mean).powi(2)).sum::<f64>() / n)
        .sqrt()
        .max(f64::MIN_POSITIVE);

    let warm = warm && state.pressure.dim() == shape && state.displacement.dim() == shape;
    if !warm {
        *state = ContactState::unloaded(shape);
    }
    let ContactState {
        pressure: p,
        gap,
        displacement: u,
        approach: state_approach,
    } = state;
    let mut approach = match control {
        Control::Approach(d) => d,
        _ if warm => *state_approach,
        _ => 0.0,
    };
    match (warm, target_load, control) {
        (true, _, _) if p.iter().any(|&v| v > 0.0) => {}
        (_, Some((.., w)), _) => p.fill(w / (n * cell)),
        (_, None, Control::Approach(d)) => {
            // Overlap times a cell's stiffness: any positive guess on the overlap will do.
            let k = op.e_star() / domain.dx.min(domain.dy);
            Zip::from(&mut *p)
                .and(&g0)
                .par_for_each(|p, &g| *p = (d - g).max(0.0) * k);
        }
        _ => unreachable!("either a load or an approach is prescribed"),
    }
    if let Some((.., w)) = target_load
        && w > 0.0
    {
        let total = p.sum() * cell;
        *p *= w / total;
    }

    let g0 = g0.as_standard_layout();
    let g0s = flat(&g0);
    let nx = domain.nx;
    // Under approach control the mean of the pressure on the contact set has no elastic
    // stiffness on a periodic grid, which the operator's inverse cannot precondition: near full
    // contact the step it gives releases every cell (a wave at 40 of its 58 z0, measured).
    let preconditioned = options.preconditioned && target_load.is_some();
    if preconditioned && scratch.preconditioner.is_none() {
        scratch.preconditioner = Some(Preconditioner::new(op));
    }
    let Scratch {
        ws,
        direction: t,
        response: r,
        preconditioner,
        ..
    } = scratch;
    let mut preconditioner = preconditioner.as_mut().filter(|_| preconditioned);
    if t.dim() != shape {
        *t = Array2::zeros(shape);
        *r = Array2::zeros(shape);
    }
    let mut history = Vec::new();
    let mut calls = 0;
    let mut g_norm_old = 1.0;
    let mut conjugate = false;
    let mut termination = Termination::MaxIterations;
    let mut iterations = 0;
    // `u = K p` is either fresh from the operator or updated in step as `u - tau K t`
    // (exact when no cell was clipped or released); `pending` is a load rescale of both p and
    // u not yet applied. A fresh product is taken every 32 iterations and before accepting
    // convergence, so round-off cannot accumulate.
    let mut fresh_needed = true;
    let mut since_fresh = 0;
    let mut pending = 1.0;

    let nothing = p.iter().all(|&v| v == 0.0);
    if nothing {
        termination = Termination::NoContact;
    }
    loop {
        if nothing {
            break;
        }
        let fresh = fresh_needed || since_fresh >= 32;
        if fresh {
            if pending != 1.0 {
                *p *= pending;
                pending = 1.0;
            }
            op.apply(p.view(), u.view_mut(), ws)?;
            calls += 1;
            since_fresh = 0;
            fresh_needed = false;
        }
        // Pass A: pending rescale, gap before the approach, contact count and gap sum.
        let s = std::mem::replace(&mut pending, 1.0);
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
                    if p[i] > 0.0 {
                        acc[0] += 1.0;
                        acc[1] += g[i];
                    }
                }
                acc
            })
            .collect();
        let [in_contact, gap_sum] = sums.iter().fold([0.0; 2], |a, b| [a[0] + b[0], a[1] + b[1]]);
        if target_load.is_some() {
            approach = gap_sum / in_contact;
        }
        // Pass B: the approach, the residuals in and out of contact, and <g, t_old> on the
        // contact set for the step length.
        let sums: Vec<[f64; 3]> = flat_mut(gap)
            .par_chunks_mut(nx)
            .zip(flat(p).par_chunks(nx))
            .zip(flat(t).par_chunks(nx))
            .map(|((g, p), t)| {
                let mut acc = [0.0; 3];
                for ((g, p), t) in g.iter_mut().zip(p).zip(t) {
                    *g -= approach;
                    if *p > 0.0 {
                        acc[0] += *g * *g;
                        acc[2] += *g * *t;
                    } else {
                        acc[1] += g.min(0.0).powi(2);
                    }
                }
                acc
            })
            .collect();
        let [g2_contact, g2_out, g_t_old] = sums
            .iter()
            .fold([0.0; 3], |a, b| [a[0] + b[0], a[1] + b[1], a[2] + b[2]]);
        let gap_residual = ((g2_contact + g2_out) / in_contact.max(1.0)).sqrt() / h_ref;
        // The KKT residual: p >= 0 holds by construction, so zero gap where p > 0 and no
        // interpenetration where p = 0 are all that is left to check.
        let residual = gap_residual;
        if residual < options.tolerance && !fresh {
            // Confirm on a fresh product before accepting.
            fresh_needed = true;
            continue;
        }
        history.push(residual);
        if !observer(iterations, residual) {
            termination = Termination::Interrupted;
            break;
        }
        if residual < options.tolerance {
            termination = Termination::Converged;
            break;
        }
        if iterations == options.max_iterations {
            break;
        }
        iterations += 1;
        since_fresh += 1;
        // The (preconditioned) residual the direction is built from, less `shift` (its mean on
        // the contact set under load control), and its product with the residual there.
        let (z, shift, gz): (&Array2<f64>, f64, f64) = match preconditioner.as_deref_mut() {
            None => (&*gap, 0.0, g2_contact),
            Some(pre) => {
                Zip::from(&mut pre.masked)
                    .and(&*gap)
                    .and(&*p)
                    .par_for_each(|m, &g, &p| *m = if p > 0.0 { g } else { 0.0 });
                pre.fft.convolve(
                    pre.masked.view(),
                    pre.multiplier.view(),
                    pre.image.view_mut(),
                    &mut pre.ws,
                );
                let (ps, zs, gs) = (flat(p), flat(&pre.image), flat(gap));
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
                // Deflated of its mean: preconditioning is under load control only.
                let z_mean = z_sum / in_contact;
                (&pre.image, z_mean, zg - z_mean * g_sum)
            }
        };
        // Pass C: conjugate direction on the contact set, and its sum there.
        let beta = if conjugate { gz / g_norm_old } else { 0.0 };
        g_norm_old = gz;
        let sums: Vec<f64> = flat_mut(t)
            .par_chunks_mut(nx)
            .zip(flat(p).par_chunks(nx))
            .zip(flat(z).par_chunks(nx))
            .map(|((t, p), z)| {
                let mut acc = 0.0;
                for ((t, p), z) in t.iter_mut().zip(p).zip(z) {
                    *t = if *p > 0.0 { z - shift + beta * *t } else { 0.0 };
                    acc += *t;
                }
                acc
            })
            .collect();
        // Under load control the mean of K t over the contact set only moves the approach:
        // <K t - mean, t> = <K t, t - mean(t)>, so the mean of t is all that is needed.
        let t_mean = if target_load.is_some() {
            sums.iter().sum::<f64>() / in_contact
        } else {
            0.0
        };
        let gt = gz + beta * g_t_old;
        op.apply(t.view(), r.view_mut(), ws)?;
        calls += 1;
        // Pass D: curvature along t.
        let rt = crate::sum::rows3(p.view(), r.view(), t.view(), |p, r, t| {
            if p > 0.0 { r * (t - t_mean) } else { 0.0 }
        });
        let tau = if rt > 0.0 { gt / rt } else { 0.0 };
        // Pass F: step, projection onto p >= 0, release of every interpenetrating cell at zero
        // pressure (free ones and those just clipped: releasing the clipped ones too saves about
        // a tenth of the iterations on rough surfaces), and the matching update of u while it
        // stays exact.
        let rows: Vec<[f64; 5]> = flat_mut(p)
            .par_chunks_mut(nx)
            .zip(flat_mut(u).par_chunks_mut(nx))
            .zip(flat(gap).par_chunks(nx))
            .zip(flat(t).par_chunks(nx))
            .zip(flat(r).par_chunks(nx))
            .map(|((((p, u), g), t), r)| {
                // The new load, the cells clipped or released, those released, and the squares
                // of the step and of what the projection changed in it.
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
                        new = if g[i] < 0.0 { -tau * g[i] } else { 0.0 };
                        if new > 0.0 {
                            changed = true;
                            acc[2] += 1.0;
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
        let [p_sum, changed, released, moved, bent] = rows.iter().fold([0.0; 5], |mut a, b| {
            a.iter_mut().zip(b).for_each(|(a, b)| *a += b);
            a
        });
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
        fresh_needed |= changed > 0.0;
        if p_sum == 0.0 {
            termination = Termination::NoContact;
            u.fill(0.0);
            Zip::from(&mut *gap)
                .and(&g0)
                .par_for_each(|g, &g0| *g = g0 - approach);
            break;
        }
        if let Some((.., w)) = target_load {
            pending = w / (p_sum * cell);
        }
    }
    if nothing {
        u.fill(0.0);
        Zip::from(&mut *gap)
            .and(&g0)
            .par_for_each(|g, &g0| *g = g0 - approach);
    }
    // Report the gap as the solution defines it: zero in contact, non-negative elsewhere.
    Zip::from(&mut *gap)
        .and(&*p)
        .par_for_each(|g, &p| *g = if p > 0.0 { 0.0 } else { g.max(0.0) });
    let load = p.sum() * cell;
    let contact = p.iter().filter(|&&v| v > 0.0).count() as f64 / n;
    let report = ContactReport {
        load,
        mean_pressure: load / (n * cell),
        approach,
        contact_area_fraction: contact,
        clusters: count_clusters(p.view(), domain.periodic),
        max_pressure: p.iter().cloned().fold(0.0, f64::max),
        elastic_energy: op.energy(p.view(), u.view()),
        iterations,
        residual: history.last().copied().unwrap_or(0.0),
        residual_history: history,
        termination,
        operator_calls: calls,
        wall_time_s: started.elapsed().as_secs_f64(),
    };
    *state_approach = approach;
    Ok(report)
}
