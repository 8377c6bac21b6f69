//! A sphere under a normal load `P` and a tangential load `Q` with Coulomb friction `mu`
//! (Cattaneo 1938, Mindlin 1949; Johnson 1985, section 7.2), and its fretting loop between
//! `+-Q*` (Mindlin & Deresiewicz 1953; Johnson 1985, section 7.5), for an elastic body of
//! shear modulus `G` and Poisson's ratio `nu` on a rigid one, in the decoupled theory (the
//! normal pressure is Hertz's whatever the shear).

/// The stick radius over the contact radius, `c / a = (1 - Q / (mu P))^(1/3)`, for
/// `0 <= Q / (mu P) = ratio <= 1`.
pub fn stick_ratio(ratio: f64) -> f64 {
    (1.0 - ratio).max(0.0).cbrt()
}

/// The tangential displacement \[m\] of the rigid body under a monotonically growing `Q`:
/// `3 mu P (2 - nu) / (16 G a) [1 - (1 - Q / (mu P))^(2/3)]`, with the contact radius `a`
/// \[m\], `mu_p = mu P` \[N\] and `q` = Q \[N\].
pub fn displacement(q: f64, mu_p: f64, shear_modulus: f64, poisson: f64, radius: f64) -> f64 {
    3.0 * mu_p * (2.0 - poisson) / (16.0 * shear_modulus * radius)
        * (1.0 - (1.0 - q / mu_p).max(0.0).powf(2.0 / 3.0))
}

/// The displacement \[m\] on the fretting loop between `-q_amp` and `+q_amp` \[N\] at the load
/// `q` \[N\], on the branch going down from `+q_amp` (`unloading`) or up from `-q_amp`
/// (Masing's rule: the virgin curve [`displacement`] doubled about the turning point).
pub fn loop_displacement(
    q: f64,
    q_amp: f64,
    unloading: bool,
    mu_p: f64,
    shear_modulus: f64,
    poisson: f64,
    radius: f64,
) -> f64 {
    let virgin = |q: f64| displacement(q, mu_p, shear_modulus, poisson, radius);
    let turn = virgin(q_amp);
    if unloading {
        turn - 2.0 * virgin((q_amp - q) / 2.0)
    } else {
        -turn + 2.0 * virgin((q + q_amp) / 2.0)
    }
}

/// The energy \[J\] the fretting loop between `+-q_amp` \[N\] dissipates per cycle:
/// `9 (mu P)^2 (2 - nu) / (10 G a) [1 - (1 - x)^(5/3) - (5 x / 6) (1 + (1 - x)^(2/3))]`,
/// `x = q_amp / (mu P)` (Johnson 1985, Eq. 7.59, a rigid counterface).
pub fn fretting_energy(q_amp: f64, mu_p: f64, shear_modulus: f64, poisson: f64, radius: f64) -> f64 {
    let x = (q_amp / mu_p).min(1.0);
    9.0 * mu_p * mu_p * (2.0 - poisson) / (10.0 * shear_modulus * radius)
        * (1.0 - (1.0 - x).powf(5.0 / 3.0) - 5.0 * x / 6.0 * (1.0 + (1.0 - x).powf(2.0 / 3.0)))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn anchors() {
        for (ratio, c) in [(0.25, 0.9086), (0.5, 0.7937), (0.875, 0.5)] {
            assert!((stick_ratio(ratio) - c).abs() < 1e-4);
        }
        // Full sliding: the displacement reaches 3 mu P (2 - nu) / (16 G a).
        assert!((displacement(2.0, 2.0, 1.0, 0.5, 1.0) - 3.0 * 2.0 * 1.5 / 16.0).abs() < 1e-15);
    }

    /// The loop's area, integrated from Masing's branches, is the closed form.
    #[test]
    fn fretting_energy_is_the_loop_area() {
        let (mu_p, g, nu, a, q_amp) = (1.0, 1.0, 0.3, 1.0, 0.6);
        let n = 20_000;
        let mut area = 0.0;
        for k in 0..n {
            let q = -q_amp + (k as f64 + 0.5) * 2.0 * q_amp / n as f64;
            let gap = loop_displacement(q, q_amp, true, mu_p, g, nu, a)
                - loop_displacement(q, q_amp, false, mu_p, g, nu, a);
            area += gap * 2.0 * q_amp / n as f64;
        }
        let exact = fretting_energy(q_amp, mu_p, g, nu, a);
        assert!((area - exact).abs() < 1e-8 * exact, "{area} {exact}");
    }
}
