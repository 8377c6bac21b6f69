//! The interface model: what bounds the tractions the wall and the law give, beyond the hard
//! wall itself: a hardness cap on the normal pressure (an elastic-perfectly-plastic surface,
//! Almqvist et al., Tribol. Int. 40, 2007), and friction bounding the shear of a tangential
//! path ([`crate::friction`]).
//!
//! Under the cap the compressive pressure `p_c` stays in `[0, H]`: three sets at a solution,
//! free (`p_c = 0`, gap > 0), elastic contact (`0 < p_c < H`, gap 0) and plastic (`p_c = H`,
//! where the surfaces would overlap). The overlap of a plastic cell, `-(g0 + u - delta)`, is its
//! new permanent set: the surface keeps it (added to the initial gap) for every later solve
//! started from that state, unloading included. Yielding dissipates `H` times the set's
//! volume.

use crate::error::{Result, SolverError, invalid};
use crate::state::ContactState;
use ljadhesion::{AdhesionLaw, Cells};
use ndarray::{Array2, ArrayView2, Zip};

/// The interface between the body and the counterface.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Interface {
    /// Penetration hardness `H` \[Pa\]: the compressive contact pressure never exceeds it.
    /// `None`: elastic.
    pub hardness: Option<f64>,
    /// Friction: how much shear a contact cell carries under a tangential path. `None`:
    /// frictionless (no tangential path).
    pub friction: Option<crate::friction::Friction>,
}

/// What yielding did in one solve.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct Yield {
    /// Fraction of cells held at the hardness [-].
    pub plastic_area_fraction: f64,
    /// Volume of the whole permanent set after the solve \[m^3\].
    pub permanent_set_volume: f64,
    /// Energy dissipated by yielding in this solve, `H` times the set's added volume \[J\].
    pub plastic_work: f64,
}

impl Interface {
    /// An elastic-perfectly-plastic surface of hardness `hardness` \[Pa\].
    ///
    /// # Errors
    /// A hardness that is not finite and positive.
    pub fn with_hardness(hardness: f64) -> Result<Interface> {
        let interface = Interface {
            hardness: Some(hardness),
            friction: None,
        };
        interface.validate()?;
        Ok(interface)
    }

    /// Refuses a hardness that is not finite and positive, and a bad friction law.
    pub fn validate(&self) -> Result<()> {
        if let Some(friction) = &self.friction {
            friction.validate()?;
        }
        match self.hardness {
            Some(h) if !(h.is_finite() && h > 0.0) => Err(invalid(
                "hardness",
                h,
                "must be a finite pressure > 0 Pa (omit it for an elastic surface)",
            )),
            _ => Ok(()),
        }
    }

    /// Refuses a hardness at or below the attraction `-p(0)` \[Pa\] that `law` gives surfaces
    /// in contact (the exponential's `w0 / rho`, Dugdale's `w0 / h0`; none for the
    /// Lennard-Jones laws, whose contact is their equilibrium): the wall holding a contact cell
    /// carries that pull as compressive pressure, so every contact would yield without bound.
    pub fn check_law(&self, law: &dyn AdhesionLaw) -> Result<()> {
        let Some(h) = self.hardness else {
            return Ok(());
        };
        let cells = Cells {
            dx: 1.0,
            dy: 1.0,
            periodic: true,
        };
        let mut at_contact = Array2::zeros((2, 2));
        law.pressure_field(Array2::zeros((2, 2)).view(), &cells, at_contact.view_mut())?;
        let pull = -at_contact[(0, 0)];
        if h <= pull {
            return Err(invalid(
                "hardness",
                h,
                format!(
                    "must exceed the `{}` law's attraction at contact, {pull:.4e} Pa: the wall \
                     holding a contact cell carries that pull, and every contact would yield \
                     without bound",
                    law.name()
                ),
            ));
        }
        Ok(())
    }

    /// The cap on the compressive pressure \[Pa\]: infinite when elastic.
    pub(crate) fn cap(&self) -> f64 {
        self.hardness.unwrap_or(f64::INFINITY)
    }
}

/// The initial gap a solve sees: `g0` plus the permanent set the surface has taken.
pub(crate) fn yielded_gap(g0: ArrayView2<f64>, set: Option<&Array2<f64>>) -> Result<Option<Array2<f64>>> {
    let Some(set) = set else {
        return Ok(None);
    };
    if set.dim() != g0.dim() {
        return Err(SolverError::ShapeMismatch {
            what: "warm-start permanent set",
            expected: g0.dim(),
            got: set.dim(),
        });
    }
    crate::error::finite("warm-start permanent set", set.view())?;
    Ok(Some(&g0 + set))
}

/// Settles a solved `state`: every cell held at the cap yields by its overlap
/// `-(g0 + u - delta)` (with `g0` the gap the solve saw, the previous set `before` included),
/// which joins the permanent set in `state`. The set is kept (zero where nothing yielded) once
/// a hardness is given, and carried unchanged without one. Returns what yielding did.
pub(crate) fn settle(
    interface: &Interface,
    g0: ArrayView2<f64>,
    before: Option<Array2<f64>>,
    state: &mut ContactState,
    cell_area: f64,
) -> Yield {
    let Some(h) = interface.hardness else {
        let volume = before.as_ref().map_or(0.0, |s| s.sum() * cell_area);
        state.permanent_set = before;
        return Yield {
            permanent_set_volume: volume,
            ..Yield::default()
        };
    };
    let mut set = before.unwrap_or_else(|| Array2::zeros(g0.dim()));
    let delta = state.approach;
    let (mut plastic, mut added) = (0usize, 0.0);
    Zip::from(&mut set)
        .and(&state.pressure)
        .and(g0)
        .and(&state.displacement)
        .for_each(|s, &p, &g0, &u| {
            if p >= h {
                plastic += 1;
                let overlap = (delta - g0 - u).max(0.0);
                *s += overlap;
                added += overlap;
            }
        });
    let n = set.len() as f64;
    let volume = set.sum() * cell_area;
    state.permanent_set = Some(set);
    Yield {
        plastic_area_fraction: plastic as f64 / n,
        permanent_set_volume: volume,
        plastic_work: h * added * cell_area,
    }
}
