//! JKR and DMT for a sphere of radius `r` \[m\], work of adhesion `w0` [J/m^2], modulus
//! `e_star` \[Pa\] (docs/method.md section 8.3).

use std::f64::consts::PI;

/// JKR load \[N\] at contact radius `a` \[m\]: `P = 4 E* a^3 / (3R) - sqrt(8 pi w0 E* a^3)`.
pub fn jkr_load(a: f64, r: f64, w0: f64, e_star: f64) -> f64 {
    4.0 * e_star * a.powi(3) / (3.0 * r) - (8.0 * PI * w0 * e_star * a.powi(3)).sqrt()
}

/// JKR approach \[m\] at contact radius `a` \[m\]: `delta = a^2/R - sqrt(2 pi w0 a / E*)`.
pub fn jkr_approach(a: f64, r: f64, w0: f64, e_star: f64) -> f64 {
    a * a / r - (2.0 * PI * w0 * a / e_star).sqrt()
}

/// JKR contact radius \[m\] at zero load: `a0 = (9 pi w0 R^2 / (2 E*))^(1/3)`, the root of
/// [`jkr_load`].
pub fn jkr_zero_load_radius(r: f64, w0: f64, e_star: f64) -> f64 {
    (9.0 * PI * w0 * r * r / (2.0 * e_star)).cbrt()
}

/// JKR pull-off force \[N\] under load control: `-1.5 pi R w0`.
pub fn jkr_pull_off_load_control(r: f64, w0: f64) -> f64 {
    -1.5 * PI * r * w0
}

/// JKR pull-off force \[N\] under displacement control (fixed grips): `-(5/6) pi R w0`.
pub fn jkr_pull_off_displacement_control(r: f64, w0: f64) -> f64 {
    -5.0 / 6.0 * PI * r * w0
}

/// DMT load \[N\] at contact radius `a` \[m\]: `P = 4 E* a^3/(3R) - 2 pi R w0`.
pub fn dmt_load(a: f64, r: f64, w0: f64, e_star: f64) -> f64 {
    4.0 * e_star * a.powi(3) / (3.0 * r) - 2.0 * PI * r * w0
}

/// DMT pull-off force \[N\] (both controls): `-2 pi R w0`.
pub fn dmt_pull_off(r: f64, w0: f64) -> f64 {
    -2.0 * PI * r * w0
}
