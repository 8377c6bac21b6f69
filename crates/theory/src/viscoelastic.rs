//! A rigid sphere of radius `r` \[m\] on a viscoelastic half-space without adhesion: a
//! generalized Maxwell solid (Prony series) of plane-strain relaxation modulus
//! `E(t) = E_inf + sum_k E_k exp(-t / tau_k)` \[Pa\] (a constant Poisson's ratio, so that
//! `E* = E / (1 - nu^2)` relaxes alike), times in s.
//!
//! While the contact grows, Lee & Radok (1960): the elastic solution with the modulus turned
//! into a hereditary integral, `P(t) = (4 / 3R) int_0^t E(t - s) d[a^3(s)]` at
//! `a^2 = R delta`, or under a prescribed load `a^3(t) = (3R/4) int_0^t J(t - s) dP(s)`, `J` the
//! creep compliance. While it recedes, Ting (1966): the contact radius is the one at the
//! earlier time `t1 <= t` for which `int_{t1}^t E(t - s) d[delta(s)] = 0`, and the load is
//! Lee & Radok's integral stopped at `t1`.

pub use elastic::viscoelastic::{BadSolid, Maxwell};

/// Lee & Radok's contact radius \[m\] at `t` \[s\] after a load `p0` \[N\] is put on the sphere
/// at once: `a^3 = (3R/4) p0 J(t)`.
pub fn creep_radius(solid: &Maxwell, t: f64, r: f64, p0: f64) -> f64 {
    (0.75 * r * p0 * solid.creep(t)).cbrt()
}

/// The sphere pressed in at the constant rate `rate` \[m/s\] until `t_max` \[s\] and drawn
/// back at the same rate: contact radius \[m\] and load \[N\] at `t` \[s\]. Lee & Radok while
/// the contact grows (`t <= t_max`), Ting after; zero once it has closed.
pub fn triangle(solid: &Maxwell, t: f64, r: f64, rate: f64, t_max: f64) -> (f64, f64) {
    let t1 = if t <= t_max {
        t
    } else {
        // int_{t1}^t E(t - s) delta'(s) ds = 0 with delta' = rate, then -rate after t_max:
        // Ehat(t - t1) = 2 Ehat(t - t_max), Ehat the relaxation integral (rising).
        let want = 2.0 * solid.relaxation_integral(t - t_max);
        if solid.relaxation_integral(t) <= want {
            return (0.0, 0.0);
        }
        let (mut lo, mut hi) = (0.0, t_max);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if mid == lo || mid == hi {
                break;
            }
            if solid.relaxation_integral(t - mid) > want {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        0.5 * (lo + hi)
    };
    // P = (4 / 3R) int_0^t1 E(t - s) d[(R rate s)^(3/2)] = 2 sqrt(R) rate^(3/2)
    // int_0^t1 E(t - s) sqrt(s) ds.
    let integral = solid.relaxed * 2.0 / 3.0 * t1.powf(1.5)
        + solid
            .branches
            .iter()
            .map(|&(e, tau)| e * (-(t - t1) / tau).exp() * tau.powf(1.5) * rooted(t1 / tau))
            .sum::<f64>();
    ((r * rate * t1).sqrt(), 2.0 * r.sqrt() * rate.powf(1.5) * integral)
}

/// `K(x) = int_0^x exp(-(x - w)) sqrt(w) dw = sqrt(x) - D(sqrt(x))`, `D` Dawson's function:
/// by its series of positive terms `exp(-x) sum_n x^(n + 3/2) / (n! (n + 3/2))` up to
/// `x = 200`, beyond by `D(y) ~ 1/(2y) + 1/(4y^3) + 3/(8y^5) + 15/(16y^7) + 105/(32y^9)`
/// (its next term below 1e-12 there).
fn rooted(x: f64) -> f64 {
    if x <= 0.0 {
        return 0.0;
    }
    if x > 200.0 {
        let y = x.sqrt();
        let dawson = (0..5)
            .scan(0.5 / y, |term, n| {
                let now = *term;
                *term *= (2 * n + 1) as f64 / (2.0 * y * y);
                Some(now)
            })
            .sum::<f64>();
        return y - dawson;
    }
    // Terms x^(n+3/2)/(n! (n+3/2)), by the ratio of consecutive ones.
    let (mut power, mut sum, mut n) = (x.powf(1.5), 0.0, 0.0);
    loop {
        let term = power / (n + 1.5);
        sum += term;
        if term < 1e-17 * sum && n > x {
            break;
        }
        n += 1.0;
        power *= x / n;
    }
    (-x).exp() * sum
}

/// Hertz's load \[N\] of a sphere of radius `r` \[m\] at approach `delta` \[m\] on modulus `e`
/// \[Pa\]: the two elastic limits of [`triangle`] (`E_inf` slow, `E_0` fast).
pub fn hertz_limit(delta: f64, r: f64, e: f64) -> f64 {
    4.0 / 3.0 * e * r.sqrt() * delta.max(0.0).powf(1.5)
}

/// The creep time `tau E_0 / E_inf` \[s\] of a standard linear solid (one branch).
pub fn creep_time(solid: &Maxwell) -> Option<f64> {
    match solid.branches.as_slice() {
        [(_, tau)] => Some(tau * solid.glassy() / solid.relaxed),
        _ => None,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rooted_is_continuous_where_the_series_hands_over() {
        let (below, above) = (rooted(200.0 - 1e-9), rooted(200.0 + 1e-9));
        assert!((below - above).abs() < 1e-11 * below, "{below} {above}");
        // Small x: (2/3) x^(3/2).
        assert!((rooted(1e-8) / (2.0 / 3.0 * 1e-12) - 1.0).abs() < 1e-7);
    }
}
