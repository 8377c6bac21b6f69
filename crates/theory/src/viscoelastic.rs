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

/// A generalized Maxwell solid.
#[derive(Clone, Debug, PartialEq)]
pub struct Maxwell {
    /// The relaxed (long-time) modulus `E_inf` \[Pa\].
    pub relaxed: f64,
    /// The branches `(E_k [Pa], tau_k [s])`.
    pub branches: Vec<(f64, f64)>,
}

/// A solid [`Maxwell::new`] refuses: the parameter by the name the front ends give it
/// (`modulus`, `maxwell_moduli`, `maxwell_times`), the value, and why.
#[derive(Clone, Debug, PartialEq)]
pub struct BadSolid {
    /// The parameter.
    pub name: &'static str,
    /// The value refused (a list's count for a list of the wrong length).
    pub value: f64,
    /// Why.
    pub reason: String,
}

impl std::fmt::Display for BadSolid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{} {}, got {}", self.name, self.reason, self.value)
    }
}

impl std::error::Error for BadSolid {}

impl Maxwell {
    /// The solid of relaxed modulus `relaxed` \[Pa\] and branches of `moduli` \[Pa\] relaxing in
    /// `times` \[s\]: all finite and > 0, the lists of one length.
    ///
    /// # Errors
    /// [`BadSolid`] naming the bad value.
    pub fn new(relaxed: f64, moduli: &[f64], times: &[f64]) -> Result<Maxwell, BadSolid> {
        if !(relaxed.is_finite() && relaxed > 0.0) {
            return Err(BadSolid {
                name: "modulus",
                value: relaxed,
                reason: "(the relaxed modulus) must be finite and > 0 Pa".into(),
            });
        }
        if moduli.len() != times.len() {
            return Err(BadSolid {
                name: "maxwell_times",
                value: times.len() as f64,
                reason: format!("must hold one time a branch modulus ({} given)", moduli.len()),
            });
        }
        for (name, list, unit) in [("maxwell_moduli", moduli, "Pa"), ("maxwell_times", times, "s")] {
            if let Some(&value) = list.iter().find(|v| !(v.is_finite() && **v > 0.0)) {
                return Err(BadSolid {
                    name,
                    value,
                    reason: format!("values must be finite and > 0 {unit}"),
                });
            }
        }
        Ok(Maxwell {
            relaxed,
            branches: moduli.iter().copied().zip(times.iter().copied()).collect(),
        })
    }

    /// The glassy (instantaneous) modulus `E_0 = E_inf + sum E_k` \[Pa\].
    pub fn glassy(&self) -> f64 {
        self.relaxed + self.branches.iter().map(|(e, _)| e).sum::<f64>()
    }

    /// The relaxation modulus `E(t)` \[Pa\] at `t >= 0` \[s\].
    pub fn relaxation(&self, t: f64) -> f64 {
        self.relaxed
            + self
                .branches
                .iter()
                .map(|&(e, tau)| e * (-t / tau).exp())
                .sum::<f64>()
    }

    /// `int_0^t E(u) du` \[Pa s\].
    fn relaxation_integral(&self, t: f64) -> f64 {
        self.relaxed * t
            + self
                .branches
                .iter()
                .map(|&(e, tau)| e * tau * -(-t / tau).exp_m1())
                .sum::<f64>()
    }

    /// The retardation spectrum: `(c_j [1/Pa], lambda_j [s])` with the creep compliance
    /// `J(t) = 1/E_inf - sum_j c_j exp(-t / lambda_j)`. In Laplace's variable `J` is
    /// `1 / (s Q(s))`, `Q(s) = E_inf + sum_k E_k s / (s + 1/tau_k)`; `Q` rises between its
    /// poles, so it has one root `-1/lambda_j` between each pair of consecutive `-1/tau_k`
    /// (and between the slowest and 0), found by bisection; `c_j = lambda_j / Q'(-1/lambda_j)`.
    pub fn retardation(&self) -> Vec<(f64, f64)> {
        let q = |s: f64| {
            self.relaxed
                + self
                    .branches
                    .iter()
                    .map(|&(e, tau)| e * s / (s + 1.0 / tau))
                    .sum::<f64>()
        };
        let dq = |s: f64| {
            self.branches
                .iter()
                .map(|&(e, tau)| e / tau / (s + 1.0 / tau).powi(2))
                .sum::<f64>()
        };
        let mut rates: Vec<f64> = self.branches.iter().map(|&(_, tau)| 1.0 / tau).collect();
        rates.sort_by(f64::total_cmp);
        rates.dedup();
        let mut out = Vec::with_capacity(rates.len());
        let mut above = 0.0;
        for &rate in &rates {
            // Q(-above) > 0 (or Q(0) = E_inf), Q -> -oo at -rate from above.
            let (mut hi, mut lo) = (-above, -rate);
            for _ in 0..200 {
                let mid = 0.5 * (hi + lo);
                if mid == hi || mid == lo {
                    break;
                }
                if q(mid) > 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            let s = 0.5 * (hi + lo);
            out.push((1.0 / (-s * dq(s)), -1.0 / s));
            above = rate;
        }
        out
    }

    /// The creep compliance `J(t)` \[1/Pa\] at `t >= 0` \[s\] (`1/E_0` at 0, `1/E_inf` at the end).
    pub fn creep(&self, t: f64) -> f64 {
        1.0 / self.relaxed
            - self
                .retardation()
                .iter()
                .map(|&(c, lambda)| c * (-t / lambda).exp())
                .sum::<f64>()
    }

    /// Lee & Radok's contact radius \[m\] at `t` \[s\] after a load `p0` \[N\] is put on the sphere
    /// at once: `a^3 = (3R/4) p0 J(t)`.
    pub fn creep_radius(&self, t: f64, r: f64, p0: f64) -> f64 {
        (0.75 * r * p0 * self.creep(t)).cbrt()
    }

    /// The sphere pressed in at the constant rate `rate` \[m/s\] until `t_max` \[s\] and drawn
    /// back at the same rate: contact radius \[m\] and load \[N\] at `t` \[s\]. Lee & Radok while
    /// the contact grows (`t <= t_max`), Ting after; zero once it has closed.
    pub fn triangle(&self, t: f64, r: f64, rate: f64, t_max: f64) -> (f64, f64) {
        let t1 = if t <= t_max {
            t
        } else {
            // int_{t1}^t E(t - s) delta'(s) ds = 0 with delta' = rate, then -rate after t_max:
            // Ehat(t - t1) = 2 Ehat(t - t_max), Ehat the relaxation integral (rising).
            let want = 2.0 * self.relaxation_integral(t - t_max);
            if self.relaxation_integral(t) <= want {
                return (0.0, 0.0);
            }
            let (mut lo, mut hi) = (0.0, t_max);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid == lo || mid == hi {
                    break;
                }
                if self.relaxation_integral(t - mid) > want {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            0.5 * (lo + hi)
        };
        // P = (4 / 3R) int_0^t1 E(t - s) d[(R rate s)^(3/2)] = 2 sqrt(R) rate^(3/2)
        // int_0^t1 E(t - s) sqrt(s) ds.
        let integral = self.relaxed * 2.0 / 3.0 * t1.powf(1.5)
            + self
                .branches
                .iter()
                .map(|&(e, tau)| e * (-(t - t1) / tau).exp() * tau.powf(1.5) * rooted(t1 / tau))
                .sum::<f64>();
        ((r * rate * t1).sqrt(), 2.0 * r.sqrt() * rate.powf(1.5) * integral)
    }
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
/// \[Pa\]: the two elastic limits of [`Maxwell::triangle`] (`E_inf` slow, `E_0` fast).
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
