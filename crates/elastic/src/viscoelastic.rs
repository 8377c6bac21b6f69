//! A generalized Maxwell solid (Prony series): the plane-strain relaxation modulus
//! `E(t) = E_inf + sum_k E_k exp(-t / tau_k)` \[Pa\], times in s, with a constant Poisson's
//! ratio so that every compliance of a body scales with `1 / E(t)` alike. Its creep compliance,
//! and the step that integrates its branches in time for a displacement linear over the step.

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
    pub fn relaxation_integral(&self, t: f64) -> f64 {
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

    /// The step of `dt >= 0` \[s\] for a displacement `u` linear over it ([`Step`]).
    pub fn step(&self, dt: f64) -> Step {
        let (decay, weight): (Vec<f64>, Vec<f64>) = self
            .branches
            .iter()
            .map(|&(_, tau)| {
                let x = dt / tau;
                // (1 - exp(-x)) / x, 1 at x = 0 (a jump: the glassy response).
                let w = if x > 0.0 { -(-x).exp_m1() / x } else { 1.0 };
                ((-x).exp(), w)
            })
            .unzip();
        let modulus = self.relaxed
            + self
                .branches
                .iter()
                .zip(&weight)
                .map(|(&(e, _), w)| e * w)
                .sum::<f64>();
        Step {
            modulus,
            decay,
            weight,
        }
    }
}

/// One time step of a [`Maxwell`] solid's surface. Branch `k` holds a displacement `h_k` \[m\]
/// on its spring (its dashpot takes the rest of `u`): `dh_k/dt + h_k / tau_k = du/dt`, so that the
/// surface carries `S (E_inf u + sum_k E_k h_k)`, `S` the body's stiffness at unit modulus. For
/// `u` linear over a step of `dt` the update is exact,
/// `h_k <- decay_k h_k + weight_k (u_new - u_old)`, `decay_k = exp(-dt / tau_k)`,
/// `weight_k = (1 - decay_k) tau_k / dt`, which makes the scheme second order for a smooth `u`
/// and stable for any `dt`; the new displacement is then the elastic one of modulus
/// [`Step::modulus`] under the pressure, less the branches' memory
/// `sum_k E_k (decay_k h_k - weight_k u_old) / modulus`.
#[derive(Clone, Debug, PartialEq)]
pub struct Step {
    /// The step's effective modulus `E_inf + sum_k E_k weight_k` \[Pa\]: `E_0` for a jump,
    /// `E_inf` for a step much longer than every `tau_k`.
    pub modulus: f64,
    /// `exp(-dt / tau_k)` a branch [-].
    pub decay: Vec<f64>,
    /// `(1 - exp(-dt / tau_k)) tau_k / dt` a branch [-] (1 for `dt = 0`).
    pub weight: Vec<f64>,
}
