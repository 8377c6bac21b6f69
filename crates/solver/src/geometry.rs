//! The undeformed separation between the counterface and the elastic half-space.
//!
//! Every geometry is reduced to one field, the initial gap `g0` \[m\], shifted so that its
//! minimum is 0: the bodies touch first where `g0 = 0`, and the gap under an approach
//! `delta` \[m\] (positive = pushing together) with surface displacement `u` is
//! `g = g0 - delta + u` (docs/method.md section 1).

use crate::error::{Result, SolverError, invalid};
use elastic::Domain;
use ndarray::{Array2, ArrayView2};

/// The shape of a rigid sphere's profile.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SphereProfile {
    /// `h(r) = r^2 / (2R)`, the Hertzian approximation (the default).
    Paraboloid,
    /// `h(r) = R - sqrt(R^2 - r^2)`; cells beyond `r = R` are refused.
    Exact,
}

fn shift_to_zero(mut g0: Array2<f64>) -> Array2<f64> {
    let min = g0.iter().cloned().fold(f64::INFINITY, f64::min);
    g0.mapv_inplace(|v| v - min);
    g0
}

/// A rigid flat against a rough surface of `heights` \[m\] (peaks towards the flat):
/// `g0 = max(H) - H`.
pub fn flat_on_rough(heights: ArrayView2<f64>) -> Result<Array2<f64>> {
    crate::error::finite("height", heights)?;
    Ok(shift_to_zero(heights.mapv(|h| -h)))
}

/// A rigid sphere of radius `radius` \[m\] centred on the grid (optionally carrying the
/// roughness `heights` \[m\], peaks towards the half-space): `g0 = h(r) - H`, shifted to
/// first touch.
pub fn sphere(
    domain: &Domain,
    radius: f64,
    profile: SphereProfile,
    heights: Option<ArrayView2<f64>>,
) -> Result<Array2<f64>> {
    if !(radius.is_finite() && radius > 0.0) {
        return Err(invalid("sphere_radius", radius, "must be finite and > 0 m"));
    }
    let (cx, cy) = ((domain.nx as f64 - 1.0) / 2.0, (domain.ny as f64 - 1.0) / 2.0);
    let mut g0 = Array2::zeros(domain.shape());
    for ((j, i), g) in g0.indexed_iter_mut() {
        let r2 = ((i as f64 - cx) * domain.dx).powi(2) + ((j as f64 - cy) * domain.dy).powi(2);
        *g = match profile {
            SphereProfile::Paraboloid => r2 / (2.0 * radius),
            SphereProfile::Exact => {
                if r2 >= radius * radius {
                    return Err(invalid(
                        "sphere_radius",
                        radius,
                        "the grid reaches beyond the sphere's equator",
                    ));
                }
                radius - (radius * radius - r2).sqrt()
            }
        };
    }
    with_roughness(g0, heights)
}

/// `g0 - heights` (the roughness carried by a curved counterface), shifted to first touch.
fn with_roughness(mut g0: Array2<f64>, heights: Option<ArrayView2<f64>>) -> Result<Array2<f64>> {
    if let Some(h) = heights {
        if h.dim() != g0.dim() {
            return Err(SolverError::ShapeMismatch {
                what: "heights",
                expected: g0.dim(),
                got: h.dim(),
            });
        }
        crate::error::finite("height", h)?;
        g0 -= &h;
    }
    Ok(shift_to_zero(g0))
}

/// A rigid one-dimensional wave of amplitude `amplitude` \[m\] (half its peak-to-valley
/// height) and one wavelength across the domain's x side, crest centred on the grid
/// (optionally carrying the roughness `heights` \[m\], peaks towards the half-space):
/// `g0 = amplitude (1 - cos(2 pi (x - x_c) / length_x)) - H`, shifted to first touch. On a
/// periodic domain the smooth wave is the Westergaard / Johnson (1995) problem of a wavy
/// surface (`theory::wavy`).
pub fn wave(domain: &Domain, amplitude: f64, heights: Option<ArrayView2<f64>>) -> Result<Array2<f64>> {
    if !(amplitude.is_finite() && amplitude > 0.0) {
        return Err(invalid("wave_amplitude", amplitude, "must be finite and > 0 m"));
    }
    let centre = (domain.nx as f64 - 1.0) / 2.0;
    let mut g0 = Array2::zeros(domain.shape());
    for ((_, i), g) in g0.indexed_iter_mut() {
        let phase = 2.0 * std::f64::consts::PI * (i as f64 - centre) / domain.nx as f64;
        *g = amplitude * (1.0 - phase.cos());
    }
    with_roughness(g0, heights)
}
