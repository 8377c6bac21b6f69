//! Time: a viscoelastic body ([`elastic::Maxwell`]) remembers its path, so each step of a
//! sweep has a time and the state carries the body's [`History`].
//!
//! A step of `dt` is one elastic solve (`docs/method.md` section 13): the body's compliance at
//! the step's effective modulus [`elastic::viscoelastic::Step::modulus`], and the initial gap
//! shifted by the branches' memory `s = -sum_k E_k (decay_k h_k - weight_k u_old) / E_eff`, so
//! that the new displacement is `u = C_eff p + s`. After it the branches advance exactly for a
//! `u` linear over the step, and so does the energy their dashpots dissipate. A state without a
//! history is a body at rest and undeformed just before the step (a first step is a jump: the
//! glassy response).
//!
//! The memory is each branch's stress `sigma_k = E_k S h_k` (`S` the stiffness at unit
//! modulus, `h_k` the spring's displacement): one field a branch, `h_k = C sigma_k / E_k`
//! recovered by one application of the compliance `C` a step, and `S u` needs none, since the
//! surface carries `p = E_inf S u + sum_k sigma_k`.

use crate::adhesive::{self, AdhesiveReport, AdhesiveState, Parts, Start};
use crate::error::{Result, SolverError, invalid};
use crate::method::Settings;
use crate::options::Control;
use elastic::{Body, Compliance, Maxwell};
use ndarray::{Array2, Zip};

/// What a viscoelastic body remembers after a step.
#[derive(Clone, Debug, PartialEq)]
pub struct History {
    /// When the state was reached \[s\].
    pub time: f64,
    /// The stress \[Pa\] each branch carries (shape `(ny, nx)` each, in the order of the
    /// solid's branches): `E_k` times the body's stiffness at unit modulus applied to the
    /// displacement on its spring.
    pub branches: Vec<Array2<f64>>,
}

/// Refuses a solid the problem's body cannot take: a relaxed modulus other than the
/// operator's, or a coating (its substrate would relax alike).
pub(crate) fn check(solid: &Maxwell, op: &dyn Compliance) -> Result<()> {
    let e = op.e_star();
    if (solid.relaxed - e).abs() > 1e-12 * e {
        return Err(invalid(
            "modulus",
            solid.relaxed,
            format!("the solid's relaxed modulus must be the body's E*, {e:e} Pa"),
        ));
    }
    if let Body::Layer(layer) = op.body()
        && matches!(layer.base, elastic::Base::Substrate { .. })
    {
        return Err(SolverError::Unsupported(
            "a viscoelastic coating: the substrate would relax with it (one relaxation function \
             scales the whole body); use a layer on a rigid base, or an elastic coating"
                .into(),
        ));
    }
    Ok(())
}

/// Solves the step to `control` at `time` \[s\] from `start` (see the module docs); an elastic
/// body (`solid` `None`) ignores the time.
pub(crate) fn solve(
    parts: Parts,
    solid: Option<&Maxwell>,
    control: Control,
    time: Option<f64>,
    settings: &Settings,
    start: Start,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<(AdhesiveState, AdhesiveReport)> {
    let Some(solid) = solid else {
        return adhesive::solve(parts, control, settings, start, observer);
    };
    check(solid, parts.op)?;
    let time = time.ok_or(SolverError::Incomplete(
        "the time of each step [s] on a viscoelastic body (a step time or a list of times)",
    ))?;
    if !time.is_finite() {
        return Err(invalid("times", time, "must be finite [s]"));
    }
    let shape = parts.op.domain().shape();
    let warm = match start {
        Start::Warm(s) => Some(s),
        _ => None,
    };
    let remembered = warm.and_then(|w| w.contact.history.as_ref());
    if let Some(h) = remembered {
        if time < h.time {
            return Err(invalid(
                "times",
                time,
                format!("go backwards: the state was reached at {:e} s", h.time),
            ));
        }
        if h.branches.len() != solid.branches.len() || h.branches.iter().any(|b| b.dim() != shape) {
            return Err(SolverError::Unsupported(format!(
                "the start state's history holds {} branch fields, the solid has {} branches on \
                 a {shape:?} grid",
                h.branches.len(),
                solid.branches.len()
            )));
        }
    }
    let (dt, old) = match (remembered, warm) {
        (Some(h), Some(w)) => (time - h.time, Some((h, w))),
        _ => (0.0, None),
    };
    let step = solid.step(dt);
    let relaxed = solid.relaxed;
    // The springs' displacements h_k = C sigma_k / E_k (the operator is at E_inf; with the
    // mean mode that it leaves out, a layer's uniform compression) and S u_old.
    let mut springs: Vec<Array2<f64>> = Vec::with_capacity(solid.branches.len());
    let mut stiff_old = Array2::zeros(shape);
    if let Some((h, w)) = old {
        let mut ws = parts.op.make_workspace();
        for (k, &(e, _)) in solid.branches.iter().enumerate() {
            let mut spring = Array2::zeros(shape);
            parts.op.apply(h.branches[k].view(), spring.view_mut(), &mut ws)?;
            spring += parts.op.mean_compliance() * h.branches[k].mean().unwrap_or(0.0);
            spring *= relaxed / e;
            springs.push(spring);
        }
        stiff_old = w.total_pressure();
        for sigma in &h.branches {
            stiff_old -= sigma;
        }
        stiff_old /= relaxed;
    }
    // The branches' memory as a shift of the initial gap.
    let mut shift = Array2::zeros(shape);
    if let Some((_, w)) = old {
        for (k, &(e, _)) in solid.branches.iter().enumerate() {
            shift.scaled_add(-e * step.decay[k] / step.modulus, &springs[k]);
            shift.scaled_add(e * step.weight[k] / step.modulus, &w.contact.displacement);
        }
    }
    let mut g0 = &parts.g0 + &shift;
    // The solvers measure the approach from first touch: re-zero the gap and shift back.
    let lowest = g0.iter().copied().fold(f64::INFINITY, f64::min);
    g0 -= lowest;
    let op = parts.op.with_modulus(step.modulus)?;
    let moved = match control {
        Control::Approach(delta) => Control::Approach(delta - lowest),
        other => other,
    };
    // The start in the step's frame (its history is the shift's, not the solve's).
    let seed = warm.map(|w| {
        let c = &w.contact;
        AdhesiveState {
            contact: crate::state::ContactState {
                pressure: c.pressure.clone(),
                gap: c.gap.clone(),
                displacement: &c.displacement - &shift,
                approach: c.approach - lowest,
                permanent_set: c.permanent_set.clone(),
                history: None,
            },
            adhesive_pressure: w.adhesive_pressure.clone(),
        }
    });
    let from = seed.as_ref().map_or(start, Start::Warm);
    let stepped = Parts {
        op: op.as_ref(),
        g0: g0.view(),
        ..parts
    };
    let (mut state, mut report) = adhesive::solve(stepped, moved, settings, from, observer)?;
    state.contact.displacement += &shift;
    state.contact.approach += lowest;
    report.approach += lowest;
    // S u_new from p_new = E_eff S u_new + sum_k (decay_k sigma_k - weight_k E_k S u_old).
    let mut stiff = state.total_pressure();
    if let Some((h, _)) = old {
        for (k, &(e, _)) in solid.branches.iter().enumerate() {
            stiff.scaled_add(-step.decay[k], &h.branches[k]);
            stiff.scaled_add(step.weight[k] * e, &stiff_old);
        }
    }
    stiff /= step.modulus;
    let u_new = &state.contact.displacement;
    let du = match old {
        Some((_, w)) => u_new - &w.contact.displacement,
        None => u_new.clone(),
    };
    let dr = &stiff - &stiff_old;
    let dot = |a: &Array2<f64>, b: &Array2<f64>| Zip::from(a).and(b).fold(0.0, |s, &x, &y| s + x * y);
    let cell = parts.op.domain().cell_area();
    let mut viscous = 0.0;
    let mut stored = relaxed * dot(u_new, &stiff);
    let mut branches = Vec::with_capacity(solid.branches.len());
    for (k, &(e, tau)) in solid.branches.iter().enumerate() {
        let (d, w, x) = (step.decay[k], step.weight[k], dt / tau);
        let mut sigma = dr.clone() * (w * e);
        let mut spring = du.clone() * w;
        if let Some((h, _)) = old {
            sigma.scaled_add(d, &h.branches[k]);
            spring.scaled_add(d, &springs[k]);
            if x > 0.0 {
                // The dashpot's power (E_k / tau_k) <h, S h> integrated over the step for the
                // exact h(t) = q h_old + (1 - q) tau du/dt, q = exp(-t / tau).
                let g = if x < 1e-3 {
                    x / 3.0 - x * x / 4.0
                } else {
                    (x + 2.0 * (-x).exp_m1() - 0.5 * (-2.0 * x).exp_m1()) / (x * x)
                };
                viscous += -0.5 * (-2.0 * x).exp_m1() * dot(&springs[k], &h.branches[k])
                    + e * (-x).exp_m1().powi(2) / x * dot(&springs[k], &dr)
                    + e * g * dot(&du, &dr);
            }
        }
        stored += dot(&spring, &sigma);
        branches.push(sigma);
    }
    report.viscous_work = viscous * cell;
    report.elastic_energy = 0.5 * stored * cell;
    state.contact.history = Some(History { time, branches });
    Ok((state, report))
}
