//! Time: a viscoelastic body ([`elastic::Maxwell`]) remembers its path, so each step of a
//! sweep has a time and the state carries the body's [`History`].
//!
//! A step of `dt` is one elastic solve (`docs/method.md` section 13): the body's compliance at
//! the step's effective modulus [`elastic::viscoelastic::Step::modulus`], and the initial gap
//! shifted by the branches' memory `s = -sum_k E_k (decay_k h_k - weight_k u_old) / E_eff`, so
//! that the new displacement is `u = C_eff p + s`. After it the branches' spring displacements
//! advance exactly for a `u` linear over the step. A state without a history is a body at
//! rest and undeformed just before the step (a first step is a jump: the glassy response).

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
    /// The displacement \[m\] on each branch's spring (shape `(ny, nx)` each, in the order of
    /// the solid's branches): the branch carries `E_k` times its stiffness applied to it.
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
    let (dt, u_old) = match (remembered, warm) {
        (Some(h), Some(w)) => (time - h.time, Some(&w.contact.displacement)),
        _ => (0.0, None),
    };
    let step = solid.step(dt);
    // The branches' memory as a shift of the initial gap.
    let mut shift = Array2::zeros(shape);
    for (k, &(e, _)) in solid.branches.iter().enumerate() {
        if let Some(h) = remembered {
            shift.scaled_add(-e * step.decay[k] / step.modulus, &h.branches[k]);
        }
        if let Some(u) = u_old {
            shift.scaled_add(e * step.weight[k] / step.modulus, u);
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
    let branches = solid
        .branches
        .iter()
        .enumerate()
        .map(|(k, _)| {
            let mut h = remembered.map_or_else(|| Array2::zeros(shape), |h| &h.branches[k] * step.decay[k]);
            let w = step.weight[k];
            match u_old {
                Some(u) => Zip::from(&mut h)
                    .and(&state.contact.displacement)
                    .and(u)
                    .for_each(|h, &new, &old| *h += w * (new - old)),
                None => h.scaled_add(w, &state.contact.displacement),
            }
            h
        })
        .collect();
    state.contact.history = Some(History { time, branches });
    Ok((state, report))
}
