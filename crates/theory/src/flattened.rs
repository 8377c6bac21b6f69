//! A sphere flattened by a hardness, unloaded with JKR adhesion: the fully plastic loading of
//! Mesarovic & Johnson (J. Mech. Phys. Solids 48, 2000) in the JKR limit, for a rigid sphere of
//! radius `r` \[m\] on an elastic-perfectly-plastic half-space of modulus `e_star` \[Pa\] and
//! hardness `hardness` \[Pa\] (docs/method.md section 11).
//!
//! Loaded to the contact radius `a_max` \[m\] at the uniform pressure H (the load
//! `pi a_max^2 H`), the half-space keeps the permanent set that makes its unloaded surface the
//! loaded one: the sphere's gap `r^2 / 2R` becomes `f(r) = delta_max - u_H(r)` inside `a_max`,
//! with `u_H` the displacement of the uniform pressure (Johnson, Contact Mechanics eq. 3.39) and
//! `delta_max = a_max^2 / 2R + u_H(a_max)`. Unloading is elastic: at contact radius `a` the
//! load is Sneddon's `P1(a) = 2 E* int_0^a f'(s) s^2 / sqrt(a^2 - s^2) ds` less JKR's
//! `sqrt(8 pi w0 E* a^3)`, and the pull-off is its minimum.

use crate::greenwood::{elliptic_ke, elliptic_ke_complementary};
use std::f64::consts::PI;

/// The flattened sphere: radius \[m\], modulus \[Pa\], hardness \[Pa\], the contact radius of
/// the load it was flattened at \[m\] (zero: never loaded past the first touch).
#[derive(Clone, Copy, Debug)]
pub struct Flattened {
    pub r: f64,
    pub e_star: f64,
    pub hardness: f64,
    pub a_max: f64,
}

impl Flattened {
    /// The load \[N\] that flattened it: `pi a_max^2 H`.
    pub fn max_load(&self) -> f64 {
        PI * self.a_max * self.a_max * self.hardness
    }

    /// The displacement \[m\] of the uniform pressure H on the disc of radius `a_max` at radius
    /// `s` \[m\] inside it: `4 H a_max E(s / a_max) / (pi E*)`.
    fn u_h(&self, s: f64) -> f64 {
        4.0 * self.hardness * self.a_max / (PI * self.e_star) * elliptic_ke(s / self.a_max).1
    }

    /// The permanent set \[m\] at radius `s` \[m\]: `delta_max - u_H(s) - s^2 / 2R` inside
    /// `a_max`, zero outside.
    pub fn set(&self, s: f64) -> f64 {
        if s >= self.a_max {
            return 0.0;
        }
        // u_H(a_max) with E(1) = 1.
        let delta_max =
            self.a_max * self.a_max / (2.0 * self.r) + 4.0 * self.hardness * self.a_max / (PI * self.e_star);
        delta_max - self.u_h(s) - s * s / (2.0 * self.r)
    }

    /// The slope `f'(s)` of the unloaded gap at `s = a sin(t)` \[m\]: `-u_H'(s)` inside
    /// `a_max`, `s / R` outside. `to_edge` is `asin(a_max / a) - t` when `a >= a_max`, which
    /// gives `1 - (s / a_max)^2` to full precision where the slope's logarithm diverges.
    fn slope(&self, a: f64, t: f64, to_edge: Option<f64>) -> f64 {
        let s = a * t.sin();
        // Short of the edge by `to_edge` (s itself may round onto a_max there).
        if to_edge.is_none_or(|d| d <= 0.0) && s >= self.a_max {
            return s / self.r;
        }
        let k = s / self.a_max;
        if k == 0.0 {
            return 0.0;
        }
        // 1 - k^2 = (a / a_max)^2 (sin^2(edge) - sin^2(t)) = (a / a_max)^2 sin(edge - t) sin(edge + t).
        let kp = match to_edge {
            Some(d) => a / self.a_max * (d.sin() * (2.0 * t + d).sin()).max(0.0).sqrt(),
            None => ((1.0 - k) * (1.0 + k)).sqrt(),
        };
        let (kk, ee) = elliptic_ke_complementary(k, kp);
        4.0 * self.hardness / (PI * self.e_star) * (kk - ee) / k
    }

    /// Sneddon's load \[N\] at contact radius `a` \[m\] without adhesion.
    pub fn elastic_load(&self, a: f64) -> f64 {
        // s = a sin(t): P1 = 2 E* a^2 int_0^{pi/2} f'(a sin t) sin^2 t dt, split where the
        // slope's logarithmic singularity sits (s = a_max).
        let integral = if a >= self.a_max {
            // Up to the edge, 1 - k^2 from the distance to it; at a = a_max the edge is pi/2.
            let edge = (self.a_max / a).asin();
            let inside = tanh_sinh(
                &|t, _, to_b| self.slope(a, t, Some(to_b)) * t.sin().powi(2),
                0.0,
                edge,
            );
            inside
                + tanh_sinh(
                    &|t, _, _| self.slope(a, t, None) * t.sin().powi(2),
                    edge,
                    0.5 * PI,
                )
        } else {
            tanh_sinh(&|t, _, _| self.slope(a, t, None) * t.sin().powi(2), 0.0, 0.5 * PI)
        };
        2.0 * self.e_star * a * a * integral
    }

    /// The JKR load \[N\] at contact radius `a` \[m\] with work of adhesion `w0` [J/m^2].
    pub fn jkr_load(&self, a: f64, w0: f64) -> f64 {
        self.elastic_load(a) - (8.0 * PI * w0 * self.e_star * a.powi(3)).sqrt()
    }

    /// The pull-off force \[N\] under load control, negative (as
    /// [`crate::jkr_dmt::jkr_pull_off_load_control`]): the least JKR load over the contact
    /// radii up to the larger of `a_max` and twice the sphere's own radius at pull-off.
    pub fn pull_off(&self, w0: f64) -> f64 {
        let sphere = (9.0 * PI * w0 * self.r * self.r / (8.0 * self.e_star)).cbrt();
        let top = self.a_max.max(2.0 * sphere);
        // A scan, then golden sections around the least point.
        let count = 400;
        let load = |a: f64| self.jkr_load(a, w0);
        let (mut best, mut at) = (f64::INFINITY, 0);
        for i in 1..=count {
            let p = load(top * i as f64 / count as f64);
            if p < best {
                (best, at) = (p, i);
            }
        }
        let step = top / count as f64;
        let (mut lo, mut hi) = ((at as f64 - 1.0) * step, ((at + 1).min(count) as f64) * step);
        let golden = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..80 {
            let (x1, x2) = (hi - golden * (hi - lo), lo + golden * (hi - lo));
            if load(x1) < load(x2) {
                hi = x2;
            } else {
                lo = x1;
            }
        }
        load(0.5 * (lo + hi)).min(best)
    }
}

/// The integral of `f(x, x - a, b - x)` over `[a, b]` by tanh-sinh quadrature: endpoint
/// singularities such as logarithms converge as fast as smooth integrands, given the
/// distances to the ends to full precision.
fn tanh_sinh(f: &dyn Fn(f64, f64, f64) -> f64, a: f64, b: f64) -> f64 {
    let half = 0.5 * (b - a);
    let h = 1.0 / 64.0;
    let mut sum = 0.0;
    for i in -384i32..=384 {
        let t = f64::from(i) * h;
        let u = 0.5 * PI * t.sinh();
        let weight = 0.5 * PI * t.cosh() / u.cosh().powi(2);
        // 1 -+ tanh(u) without cancellation.
        let (to_a, to_b) = if u >= 0.0 {
            let e = 2.0 / ((2.0 * u).exp() + 1.0);
            (half * (2.0 - e), half * e)
        } else {
            let e = 2.0 / ((-2.0 * u).exp() + 1.0);
            (half * e, half * (2.0 - e))
        };
        if weight < 1e-300 || to_a <= 0.0 || to_b <= 0.0 {
            continue;
        }
        sum += weight * f(a + to_a, to_a, to_b);
    }
    sum * h * half
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::jkr_dmt::jkr_pull_off_load_control;

    fn sphere(a_max: f64) -> Flattened {
        Flattened {
            r: 1e-6,
            e_star: 1e9,
            hardness: 1e8,
            a_max,
        }
    }

    #[test]
    fn the_flattened_profile_carries_its_load_at_its_radius_and_a_sphere_is_hertzian() {
        // The uniform pressure H over a_max is the elastic solution of the profile it left.
        let f = sphere(4e-7);
        assert!(
            (f.elastic_load(f.a_max) / f.max_load() - 1.0).abs() < 1e-9,
            "{}",
            f.elastic_load(f.a_max) / f.max_load()
        );
        // Never flattened: Hertz.
        let s = sphere(0.0);
        let a: f64 = 1e-7;
        let hertz = 4.0 * s.e_star * a.powi(3) / (3.0 * s.r);
        assert!((s.elastic_load(a) / hertz - 1.0).abs() < 1e-12);
    }

    #[test]
    fn the_set_vanishes_at_the_edge_and_is_deepest_at_the_centre() {
        let f = sphere(4e-7);
        let mut last = f.set(0.0);
        assert!(f.set(f.a_max * (1.0 - 1e-9)).abs() < 1e-6 * last);
        assert!(last > 0.0);
        for i in 1..100 {
            let s = f.set(f.a_max * f64::from(i) / 100.0);
            assert!(s < last && s >= 0.0, "{i}: {s:e} after {last:e}");
            last = s;
        }
    }

    #[test]
    fn the_pull_off_is_jkr_unflattened_and_grows_with_the_flattening() {
        let w0 = 0.05;
        let expected = jkr_pull_off_load_control(1e-6, w0);
        assert!((sphere(0.0).pull_off(w0) / expected - 1.0).abs() < 1e-9);
        let mut last = expected;
        for a_max in [2e-7, 3e-7, 4e-7, 6e-7] {
            let p = sphere(a_max).pull_off(w0);
            assert!(p < last, "{a_max:e}: {p:e} after {last:e}");
            last = p;
        }
    }
}
