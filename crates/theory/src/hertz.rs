//! Hertz: a rigid sphere of radius `r` \[m\] on an elastic half-space of modulus `e_star` \[Pa\].

use std::f64::consts::PI;

/// Load \[N\] at contact radius `a` \[m\]: `P = 4 E* a^3 / (3R)`.
pub fn load_of_radius(a: f64, r: f64, e_star: f64) -> f64 {
    4.0 * e_star * a.powi(3) / (3.0 * r)
}

/// Contact radius \[m\] under load `p` \[N\]: `a = (3 P R / (4 E*))^(1/3)`.
pub fn radius_of_load(p: f64, r: f64, e_star: f64) -> f64 {
    (3.0 * p * r / (4.0 * e_star)).cbrt()
}

/// Approach \[m\] at contact radius `a` \[m\]: `delta = a^2 / R`.
pub fn approach_of_radius(a: f64, r: f64) -> f64 {
    a * a / r
}

/// Load \[N\] at approach `delta` \[m\]: `P = (4/3) E* R^(1/2) delta^(3/2)`.
pub fn load_of_approach(delta: f64, r: f64, e_star: f64) -> f64 {
    4.0 / 3.0 * e_star * r.sqrt() * delta.max(0.0).powf(1.5)
}

/// Pressure \[Pa\] at distance `rho` \[m\] from the centre: `p0 sqrt(1 - rho^2/a^2)`,
/// `p0 = 2 E* a / (pi R)`.
pub fn pressure(rho: f64, a: f64, r: f64, e_star: f64) -> f64 {
    let p0 = 2.0 * e_star * a / (PI * r);
    p0 * (1.0 - (rho / a).powi(2)).max(0.0).sqrt()
}
