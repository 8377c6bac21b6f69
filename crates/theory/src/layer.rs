//! A rigid sphere of radius `r` \[m\] on an elastic layer of thickness `h` \[m\] on a rigid
//! base, the layer of plane-strain modulus `e_star = E / (1 - nu^2)` \[Pa\] and Poisson's ratio
//! `nu`: the corrections of Hertz that users apply by hand.

use std::f64::consts::PI;

/// How the layer meets its rigid base.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Base {
    /// Bonded (no slip).
    Bonded,
    /// Free to slide (frictionless).
    Frictionless,
}

/// Dimitriadis et al. (Biophys. J. 82, 2002) load \[N\] at approach `delta` \[m\]: Hertz's load
/// times a polynomial in `chi = sqrt(R delta) / h`,
/// `1 - (2 a0/pi) chi + (4 a0^2/pi^2) chi^2 - (8/pi^3)(a0^3 + 4 pi^2 b0/15) chi^3
/// + (16 a0/pi^4)(a0^3 + 3 pi^2 b0/5) chi^4`, with, bonded,
/// `a0 = -(1.2876 - 1.4678 nu + 1.3442 nu^2)/(1 - nu)`,
/// `b0 = (0.6387 - 1.0277 nu + 1.5164 nu^2)/(1 - nu)`, and sliding
/// `a0 = -0.347 (3 - 2 nu)/(1 - nu)`, `b0 = 0.056 (5 - 2 nu)/(1 - nu)`. A fit for
/// `chi <~ 0.5`-1; at `nu = 0.5` bonded the `chi^4` coefficient is -0.0974 (often quoted +).
pub fn dimitriadis_load(delta: f64, r: f64, h: f64, e_star: f64, nu: f64, base: Base) -> f64 {
    let chi = (r * delta.max(0.0)).sqrt() / h;
    let (a0, b0) = dimitriadis_coefficients(nu, base);
    let poly = 1.0 - 2.0 * a0 / PI * chi + 4.0 * a0 * a0 / (PI * PI) * chi * chi
        - 8.0 / PI.powi(3) * (a0.powi(3) + 4.0 * PI * PI * b0 / 15.0) * chi.powi(3)
        + 16.0 * a0 / PI.powi(4) * (a0.powi(3) + 3.0 * PI * PI * b0 / 5.0) * chi.powi(4);
    crate::hertz::load_of_approach(delta, r, e_star) * poly
}

/// Dimitriadis' `(alpha0, beta0)` for Poisson's ratio `nu` on `base`.
pub fn dimitriadis_coefficients(nu: f64, base: Base) -> (f64, f64) {
    match base {
        Base::Bonded => (
            -(1.2876 - 1.4678 * nu + 1.3442 * nu * nu) / (1.0 - nu),
            (0.6387 - 1.0277 * nu + 1.5164 * nu * nu) / (1.0 - nu),
        ),
        Base::Frictionless => (
            -0.347 * (3.0 - 2.0 * nu) / (1.0 - nu),
            0.056 * (5.0 - 2.0 * nu) / (1.0 - nu),
        ),
    }
}

/// The P-wave (confined) modulus \[Pa\] of the layer, `M = E (1 - nu) / ((1 + nu)(1 - 2 nu))
/// = E* (1 - nu)^2 / (1 - 2 nu)`: infinite when incompressible.
pub fn p_wave_modulus(e_star: f64, nu: f64) -> f64 {
    e_star * (1.0 - nu).powi(2) / (1.0 - 2.0 * nu)
}

/// The thin compressible bonded layer's load \[N\] at approach `delta` \[m\] (the Winkler
/// limit, contact radius much larger than `h`): each point sinks as a spring of stiffness
/// `M / h`, so `a^2 = 2 R delta` and `P = pi M R delta^2 / h`.
pub fn winkler_load(delta: f64, r: f64, h: f64, e_star: f64, nu: f64) -> f64 {
    PI * p_wave_modulus(e_star, nu) * r * delta.max(0.0).powi(2) / h
}

/// The Winkler limit's contact radius \[m\] at approach `delta` \[m\]: `sqrt(2 R delta)`.
pub fn winkler_radius(delta: f64, r: f64) -> f64 {
    (2.0 * r * delta.max(0.0)).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_incompressible_bonded_polynomial_is_the_quoted_one_with_its_sign() {
        let (a0, b0) = dimitriadis_coefficients(0.5, Base::Bonded);
        let c = [
            -2.0 * a0 / PI,
            4.0 * a0 * a0 / (PI * PI),
            -8.0 / PI.powi(3) * (a0.powi(3) + 4.0 * PI * PI * b0 / 15.0),
            16.0 * a0 / PI.powi(4) * (a0.powi(3) + 3.0 * PI * PI * b0 / 5.0),
        ];
        for (got, want) in c.iter().zip([1.133, 1.283, 0.769, -0.0974]) {
            assert!((got - want).abs() < 1.5e-3, "{c:?}");
        }
        // chi -> 0: Hertz.
        let hertz = crate::hertz::load_of_approach(1e-9, 1e-3, 1e6);
        let thick = dimitriadis_load(1e-9, 1e-3, 1e3, 1e6, 0.3, Base::Bonded);
        assert!((thick / hertz - 1.0).abs() < 1e-6);
    }
}
