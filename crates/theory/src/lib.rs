//! # theory: reference models for adhesive and rough contact
//!
//! Plain numbers in, numbers out; no dependency on the rest of the workspace. SI units unless
//! a function says it works in the dimensionless units of its model. Sign conventions: load
//! `P > 0` compressive, approach `delta > 0` pushing the bodies together (docs/method.md
//! sections 6 and 8).

pub mod flattened;
pub mod greenwood;
pub mod hertz;
pub mod jkr_dmt;
pub mod layer;
pub mod maugis;
pub mod mindlin;
pub mod rate_adhesion;
pub mod rough;
pub mod viscoelastic;
pub mod wavy;

/// Tabor parameter `mu = (R w0^2 / (E*^2 z0^3))^(1/3)` of a sphere of radius `r` \[m\] with
/// work of adhesion `w0` [J/m^2] and range `z0` \[m\] on a half-space of modulus `e_star` \[Pa\].
pub fn tabor_parameter(r: f64, w0: f64, e_star: f64, z0: f64) -> f64 {
    (r * w0 * w0 / (e_star * e_star * z0.powi(3))).cbrt()
}

/// The work of adhesion [J/m^2] that gives a sphere of radius `r` \[m\] the Tabor parameter
/// `mu` ([`tabor_parameter`] solved for `w0`), with range `z0` \[m\] on a half-space of
/// modulus `e_star` \[Pa\].
pub fn work_of_adhesion_of_tabor(mu: f64, r: f64, e_star: f64, z0: f64) -> f64 {
    (mu.powi(3) * z0.powi(3) * e_star * e_star / r).sqrt()
}

/// Maugis' parameter equivalent to a Lennard-Jones law of Tabor parameter `mu`: the Dugdale
/// law with the same work of adhesion and peak stress gives `lambda = 1.157 mu`
/// (docs/method.md section 8.3).
pub fn maugis_parameter_of_tabor(mu: f64) -> f64 {
    // lambda = 2 sigma0 (R / (pi w0 K^2))^(1/3), sigma0 = 16 w0 / (9 sqrt 3 z0), K = 4 E*/3.
    let sigma0_factor = 16.0 / (9.0 * 3f64.sqrt());
    2.0 * sigma0_factor * (9.0 / (16.0 * std::f64::consts::PI)).cbrt() * mu
}
