//! The fields of a contact solution, resumable for continuation.

use ndarray::Array2;

/// The state of a normal contact: all fields have the grid's shape `(ny, nx)`.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactState {
    /// Contact pressure \[Pa\], `>= 0` (compressive).
    pub pressure: Array2<f64>,
    /// Gap \[m\], `>= 0`; zero where in contact.
    pub gap: Array2<f64>,
    /// Normal surface displacement of the half-space \[m\] (positive away from the counterface).
    pub displacement: Array2<f64>,
    /// Approach \[m\] from first touch (positive = pushed together).
    pub approach: f64,
    /// Permanent set \[m\] (`>= 0`): how far the surface has yielded under a hardness
    /// ([`crate::Interface`]), added to the initial gap of every solve started from this
    /// state. `None` for a surface that never had a hardness.
    pub permanent_set: Option<Array2<f64>>,
    /// What a viscoelastic body remembers of its path ([`crate::time`]): the time and the
    /// branches' fields. `None` for an elastic body.
    pub history: Option<crate::time::History>,
}

impl ContactState {
    /// A state with no load, for a cold start.
    pub fn unloaded(shape: (usize, usize)) -> Self {
        ContactState {
            pressure: Array2::zeros(shape),
            gap: Array2::zeros(shape),
            displacement: Array2::zeros(shape),
            approach: 0.0,
            permanent_set: None,
            history: None,
        }
    }
}
