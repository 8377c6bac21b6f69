//! Elastic constants and the composite modulus (docs/method.md section 1).

use crate::error::{ElasticError, Result};

/// An isotropic elastic material: Young's modulus `e` \[Pa\] and Poisson's ratio `nu` [-].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Material {
    pub e: f64,
    pub nu: f64,
}

impl Material {
    /// A material, checked: `e > 0` and finite, `-1 < nu <= 0.5`.
    pub fn new(e: f64, nu: f64) -> Result<Self> {
        if !(e.is_finite() && e > 0.0) {
            return Err(ElasticError::InvalidParameter {
                name: "young_modulus",
                value: e,
                reason: "must be finite and > 0 Pa",
            });
        }
        check_poisson("poisson_ratio", nu)?;
        Ok(Material { e, nu })
    }

    /// A rigid body (infinite modulus): it adds nothing to the composite compliance.
    pub const RIGID: Material = Material {
        e: f64::INFINITY,
        nu: 0.0,
    };

    /// Plane-strain compliance `(1 - nu^2) / E` [1/Pa].
    fn compliance(&self) -> f64 {
        if self.e.is_infinite() {
            0.0
        } else {
            (1.0 - self.nu * self.nu) / self.e
        }
    }
}

/// Composite (contact) modulus `E* = 1 / ((1 - nu1^2)/E1 + (1 - nu2^2)/E2)` \[Pa\] of two bodies
/// ([`Material::RIGID`] for a rigid one).
///
/// ```
/// use elastic::{composite_modulus, Material};
/// let steel = Material::new(210e9, 0.3)?;
/// let e_star = composite_modulus(&steel, &Material::RIGID)?;
/// assert!((e_star - 210e9 / 0.91).abs() < 1e-3);
/// # Ok::<(), elastic::ElasticError>(())
/// ```
pub fn composite_modulus(a: &Material, b: &Material) -> Result<f64> {
    for m in [a, b] {
        if *m != Material::RIGID {
            Material::new(m.e, m.nu)?;
        }
    }
    let c = a.compliance() + b.compliance();
    if c <= 0.0 {
        return Err(ElasticError::InvalidParameter {
            name: "composite_modulus",
            value: f64::INFINITY,
            reason: "both bodies are rigid",
        });
    }
    Ok(1.0 / c)
}

pub(crate) fn check_modulus(e_star: f64) -> Result<f64> {
    if e_star.is_finite() && e_star > 0.0 {
        Ok(e_star)
    } else {
        Err(ElasticError::InvalidParameter {
            name: "e_star",
            value: e_star,
            reason: "the composite modulus must be finite and > 0 Pa",
        })
    }
}

/// Refuses a Poisson's ratio `nu` outside `(-1, 0.5]`, naming it `name`.
pub(crate) fn check_poisson(name: &'static str, nu: f64) -> Result<()> {
    if nu > -1.0 && nu <= 0.5 {
        Ok(())
    } else {
        Err(ElasticError::InvalidParameter {
            name,
            value: nu,
            reason: "must lie in (-1, 0.5]",
        })
    }
}
