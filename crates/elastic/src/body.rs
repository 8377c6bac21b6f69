//! What lies under the surface: the body whose compliance the operators apply.
//!
//! A body is its surface compliance by wavenumber, `2 / (E* q)` times a factor of `q` alone
//! ([`Body::compliance_ratio`]), and, on free grids, the same in real space cell by cell. A new
//! body is a variant here and its two forms.

use crate::layer::{Base, Layer, RealSpace};
use crate::love::cell_influence;

/// The elastic body under the surface, of plane-strain modulus `E*` (the operators').
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Body {
    /// An elastic half-space (the paper's body).
    #[default]
    HalfSpace,
    /// A layer of finite thickness on a rigid base ([`Layer`]).
    Layer(Layer),
}

impl Body {
    /// The body's compliance at wavenumber `q` \[1/m\] over the half-space's `2 / (E* q)` of
    /// plane-strain modulus `e_star` \[Pa\] [-].
    pub fn compliance_ratio(&self, q: f64, e_star: f64) -> f64 {
        match self {
            Body::HalfSpace => 1.0,
            Body::Layer(layer) => layer.compliance_ratio(q, e_star),
        }
    }

    /// The compliance \[m/Pa\] of the mean mode (a uniform pressure), for plane-strain modulus
    /// `e_star` \[Pa\]: `None` for the half-space, which a uniform pressure displaces without
    /// bound (periodic displacements are then measured from the mean surface).
    pub fn mean_compliance(&self, e_star: f64) -> Option<f64> {
        match self {
            Body::HalfSpace => None,
            Body::Layer(layer) => layer.mean_compliance(e_star),
        }
    }

    /// The body with every modulus times `ratio` (a coating's substrate's: the layer's own is
    /// the operator's).
    pub(crate) fn with_modulus_scaled(self, ratio: f64) -> Body {
        match self {
            Body::Layer(Layer {
                base: Base::Substrate { e_star, poisson },
                thickness,
                poisson: nu,
            }) => Body::Layer(Layer {
                thickness,
                poisson: nu,
                base: Base::Substrate {
                    e_star: e_star * ratio,
                    poisson,
                },
            }),
            other => other,
        }
    }

    /// The influence coefficients of cells `dx` by `dy` \[m\] for plane-strain modulus `e_star`
    /// \[Pa\]: tables made once here.
    pub(crate) fn influence(&self, dx: f64, dy: f64, e_star: f64) -> Influence {
        Influence {
            half: (0.5 * dx, 0.5 * dy),
            e_star,
            layer: match self {
                Body::HalfSpace => None,
                Body::Layer(layer) => Some(layer.real_space(e_star)),
            },
        }
    }
}

/// The displacement of a cell's centre under unit pressure on another cell.
pub(crate) struct Influence {
    half: (f64, f64),
    e_star: f64,
    layer: Option<RealSpace>,
}

impl Influence {
    /// The displacement \[m\] at offset `(x, y)` \[m\] from the loaded cell's centre under unit
    /// pressure \[Pa\] on it: Love's half-space coefficient, plus the layer's correction.
    pub(crate) fn at(&self, x: f64, y: f64) -> f64 {
        let (a, b) = self.half;
        let love = cell_influence(x, y, a, b, self.e_star);
        match &self.layer {
            None => love,
            Some(layer) => layer.coefficient(x, y, a, b, self.e_star, love),
        }
    }
}
