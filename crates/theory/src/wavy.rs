//! A rigid one-dimensional wave `h(x) = amplitude cos(2 pi x / wavelength)` pressed onto an
//! elastic half-space (plane strain, modulus `e_star` \[Pa\]): Westergaard's non-adhesive
//! solution and Johnson's (1995) JKR solution with work of adhesion `w0` [J/m^2].
//!
//! Each crest makes a contact strip of half-width `a` \[m\] per wavelength; the mean pressure
//! `p` \[Pa\] (compressive > 0) is the load per wavelength over the wavelength. With
//! `psi = pi a / wavelength`, `p* = pi E* amplitude / wavelength` (the mean pressure that
//! flattens the wave) and Johnson's parameter `alpha = sqrt(2 wavelength w0 / (pi^2 E* amplitude^2))`:
//!
//! - Westergaard: `p = p* sin^2 psi`;
//! - JKR: `p = p* (sin^2 psi - alpha sqrt(tan psi))`, the periodic flat-punch (Westergaard
//!   crack) correction `-sqrt(2 E* w0 tan(psi) / wavelength)` whose stress-intensity factor at
//!   the strip's edge, `|p_F| sqrt(wavelength / tan psi)`, releases `K^2/(2 E*) = w0`.
//!
//! For a narrow strip (`a << wavelength`) these are Hertz's and JKR's cylinder of radius
//! `R = wavelength^2 / (4 pi^2 amplitude)` (the crest's curvature radius), load per length
//! `pi E* a^2 / (4R) - sqrt(2 pi E* w0 a)`. Beyond the maximum of the JKR curve the gaps close:
//! the contact snaps to complete.

use std::f64::consts::PI;

/// A wave in contact, in SI units.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Wave {
    /// Amplitude `Delta` \[m\] (half the peak-to-valley height).
    pub amplitude: f64,
    /// Wavelength `lambda` \[m\].
    pub wavelength: f64,
    /// Contact modulus `E*` \[Pa\].
    pub e_star: f64,
    /// Work of adhesion `w0` [J/m^2] (0 for Westergaard's problem).
    pub work_of_adhesion: f64,
}

impl Wave {
    /// The mean pressure of complete contact `p* = pi E* Delta / lambda` \[Pa\].
    pub fn full_contact_pressure(&self) -> f64 {
        PI * self.e_star * self.amplitude / self.wavelength
    }

    /// Johnson's adhesion parameter `alpha = sqrt(2 lambda w0 / (pi^2 E* Delta^2))` [-].
    pub fn johnson_alpha(&self) -> f64 {
        (2.0 * self.wavelength * self.work_of_adhesion / (PI * PI * self.e_star * self.amplitude.powi(2)))
            .sqrt()
    }

    /// The crests' curvature radius `R = lambda^2 / (4 pi^2 Delta)` \[m\].
    pub fn crest_radius(&self) -> f64 {
        self.wavelength.powi(2) / (4.0 * PI * PI * self.amplitude)
    }

    /// Westergaard's mean pressure \[Pa\] at contact half-width `a` \[m\], `0 <= a <= lambda/2`.
    pub fn westergaard_pressure(&self, a: f64) -> f64 {
        self.full_contact_pressure() * (PI * a / self.wavelength).sin().powi(2)
    }

    /// Johnson's JKR mean pressure \[Pa\] at contact half-width `a` \[m\], `0 <= a < lambda/2`.
    pub fn jkr_pressure(&self, a: f64) -> f64 {
        let psi = PI * a / self.wavelength;
        self.full_contact_pressure() * (psi.sin().powi(2) - self.johnson_alpha() * psi.tan().sqrt())
    }

    /// The JKR curve's minimum on the strip's branch (below the snap to complete contact):
    /// the pull-off mean pressure under load control \[Pa\] (< 0 for `w0 > 0`) and the
    /// half-width \[m\] where it is reached.
    pub fn jkr_pull_off(&self) -> (f64, f64) {
        let (_, a_max) = self.jkr_snap_to_full_contact();
        self.jkr_extremum(|p| -p, PI * a_max / self.wavelength)
    }

    /// The JKR curve's maximum, past which the contact snaps to complete under load control:
    /// the mean pressure \[Pa\] and the half-width \[m\]. (For `alpha` above about 0.57 the
    /// maximum is negative: the wave sticks fully once it touches.)
    pub fn jkr_snap_to_full_contact(&self) -> (f64, f64) {
        self.jkr_extremum(|p| p, 0.5 * PI)
    }

    /// Where `objective(p(a))` is largest for `psi` in `(0, psi_max)`: the best point of a fine
    /// grid, refined by golden sections between its neighbours.
    fn jkr_extremum(&self, objective: impl Fn(f64) -> f64, psi_max: f64) -> (f64, f64) {
        let f = |psi: f64| objective(self.jkr_pressure(psi * self.wavelength / PI));
        let n = 4000;
        let step = psi_max / n as f64;
        let best = (1..n)
            .max_by(|&i, &j| f(i as f64 * step).total_cmp(&f(j as f64 * step)))
            .unwrap_or(1);
        let (mut lo, mut hi) = ((best - 1) as f64 * step, (best + 1) as f64 * step);
        let g = (5f64.sqrt() - 1.0) / 2.0;
        for _ in 0..200 {
            let (x1, x2) = (hi - g * (hi - lo), lo + g * (hi - lo));
            if f(x1) > f(x2) {
                hi = x2;
            } else {
                lo = x1;
            }
        }
        let psi = 0.5 * (lo + hi);
        let a = psi * self.wavelength / PI;
        (self.jkr_pressure(a), a)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wave(w0: f64) -> Wave {
        Wave {
            amplitude: 2e-8,
            wavelength: 1e-5,
            e_star: 1e9,
            work_of_adhesion: w0,
        }
    }

    #[test]
    fn a_narrow_strip_is_the_cylinder_of_the_crest_radius() {
        let w = wave(0.05);
        let r = w.crest_radius();
        for a in [1e-9, 1e-8, 3e-8] {
            let hertz = PI * w.e_star * a * a / (4.0 * r);
            let jkr = hertz - (2.0 * PI * w.e_star * w.work_of_adhesion * a).sqrt();
            // Per wavelength: load per length = p lambda. The relative error is O((a/lambda)^2).
            let tol = 1e-12 + 2.0 * (PI * a / w.wavelength).powi(2);
            assert!((w.westergaard_pressure(a) * w.wavelength / hertz - 1.0).abs() < tol);
            assert!((w.jkr_pressure(a) * w.wavelength / jkr - 1.0).abs() < tol);
        }
    }

    #[test]
    fn without_adhesion_jkr_is_westergaard_and_complete_contact_needs_p_star() {
        let w = wave(0.0);
        assert_eq!(w.johnson_alpha(), 0.0);
        for a in [1e-7, 2e-6, 4.9e-6] {
            assert_eq!(w.jkr_pressure(a), w.westergaard_pressure(a));
        }
        assert!((w.westergaard_pressure(0.5 * w.wavelength) / w.full_contact_pressure() - 1.0).abs() < 1e-15);
    }

    #[test]
    fn the_pull_off_and_the_snap_are_the_curves_stationary_points() {
        let w = wave(0.02);
        let alpha = w.johnson_alpha();
        assert!(alpha > 0.1 && alpha < 0.5, "{alpha}");
        let p_star = w.full_contact_pressure();
        for (p, a) in [w.jkr_pull_off(), w.jkr_snap_to_full_contact()] {
            // dp/dpsi = p* (sin 2 psi - alpha sec^2 psi / (2 sqrt(tan psi))) = 0
            let psi = PI * a / w.wavelength;
            let slope = (2.0 * psi).sin() - alpha / (psi.cos().powi(2) * 2.0 * psi.tan().sqrt());
            assert!(slope.abs() < 1e-6, "{slope}");
            assert!((w.jkr_pressure(a) - p).abs() <= 1e-15 * p_star);
        }
        let (pull_off, a_min) = w.jkr_pull_off();
        let (snap, a_max) = w.jkr_snap_to_full_contact();
        assert!(pull_off < 0.0 && snap > 0.0 && a_min < a_max);
        // For small alpha the minimum sits at psi = (alpha/4)^(2/3) with -3 (alpha/4)^(4/3) p*
        // (the cylinder's pull-off); at alpha ~ 0.3 the wave's curvature corrects it by a few %.
        let cylinder = -3.0 * (alpha / 4.0).powf(4.0 / 3.0) * p_star;
        assert!(
            (pull_off / cylinder - 1.0).abs() < 0.05,
            "{pull_off} vs {cylinder}"
        );
    }
}
