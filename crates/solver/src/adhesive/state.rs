//! The fields of an adhesive solution, and where a solve starts from.

use crate::state::ContactState;
use ndarray::Array2;

/// Where a solve starts.
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
    /// Compressive pressure `p_c >= 0` \[Pa\] in `pressure`, the gap \[m\] (zero in contact), the
    /// total surface displacement `K (p_c + p_a)` \[m\] and the approach \[m\].
    pub contact: ContactState,
    /// Adhesive pressure `p_a <= 0` \[Pa\].
    pub adhesive_pressure: Array2<f64>,
}

impl AdhesiveState {
    pub(super) fn is_standard_layout(&self) -> bool {
        let c = &self.contact;
        [&c.pressure, &c.gap, &c.displacement, &self.adhesive_pressure]
            .iter()
            .all(|a| a.is_standard_layout())
    }

    pub(super) fn to_standard_layout(&self) -> AdhesiveState {
        let standard = |a: &Array2<f64>| a.as_standard_layout().into_owned();
        AdhesiveState {
            contact: ContactState {
                pressure: standard(&self.contact.pressure),
                gap: standard(&self.contact.gap),
                displacement: standard(&self.contact.displacement),
                approach: self.contact.approach,
                permanent_set: self.contact.permanent_set.as_ref().map(standard),
                history: self.contact.history.as_ref().map(|h| crate::time::History {
                    time: h.time,
                    branches: h.branches.iter().map(standard).collect(),
                }),
            },
            adhesive_pressure: standard(&self.adhesive_pressure),
        }
    }

    /// The total pressure `p_c + p_a` \[Pa\].
    pub fn total_pressure(&self) -> Array2<f64> {
        &self.contact.pressure + &self.adhesive_pressure
    }
}
