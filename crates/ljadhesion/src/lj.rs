//! The Lennard-Jones 9-3 law between parallel half-spaces (docs/method.md section 2, Eqs. 5-6, 12).
//!
//! `p(z) = (8 w0 / (3 z0)) [ (z0/z)^9 - (z0/z)^3 ]` \[Pa\], positive = repulsive, at atomic
//! separation `z = g + z0` for a continuum gap `g >= 0`. Its antiderivative
//! `Phi(z) = (w0 / (3 z0)) (4 z0^3 / z^2 - z0^9 / z^8)` (`Phi' = p`, `Phi(z0) = w0`,
//! `Phi(inf) = 0`) gives `integral_{z0}^{inf} p dz = -w0` and the interaction energy per
//! area `-Phi(z)`, which is `-w0` in contact.

use crate::error::{Result, positive};

/// The Lennard-Jones 9-3 law with work of adhesion `w0` [J/m^2] and equilibrium separation
/// `z0` \[m\].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LennardJones {
    w0: f64,
    z0: f64,
}

impl LennardJones {
    /// The law, checked: `w0 > 0`, `z0 > 0`, both finite.
    pub fn new(w0: f64, z0: f64) -> Result<Self> {
        Ok(LennardJones {
            w0: positive("work_of_adhesion", w0)?,
            z0: positive("z0", z0)?,
        })
    }

    /// Work of adhesion w0 [J/m^2].
    pub fn work_of_adhesion(&self) -> f64 {
        self.w0
    }

    /// Equilibrium separation z0 \[m\].
    pub fn z0(&self) -> f64 {
        self.z0
    }

    /// Atomic separation `z = g + z0` \[m\] of a continuum gap `g` \[m\], clamped to `z >= z0`
    /// (a NaN gap stays NaN, so that it is reported rather than taken for contact).
    pub fn separation(&self, gap: f64) -> f64 {
        if gap < 0.0 { self.z0 } else { gap + self.z0 }
    }

    /// Pressure `p(z)` \[Pa\] at atomic separation `z` \[m\] (positive = repulsive).
    ///
    /// ```
    /// let lj = ljadhesion::LennardJones::new(0.05, 2e-9)?;
    /// assert_eq!(lj.pressure(2e-9), 0.0);
    /// let z_min = 3f64.powf(1.0 / 6.0) * 2e-9; // where the pull is strongest
    /// assert!((lj.pressure(z_min) / lj.min_pressure() - 1.0).abs() < 1e-14);
    /// # Ok::<(), ljadhesion::AdhesionError>(())
    /// ```
    pub fn pressure(&self, z: f64) -> f64 {
        // The cell mean over a zero-width interval, so that a flat gap field gives the point
        // law to the last bit.
        let v = self.z0 / z;
        self.mean_pressure_v(v, v)
    }

    /// `Phi(z)` [J/m^2], the antiderivative of [`LennardJones::pressure`] vanishing at infinity.
    pub fn phi(&self, z: f64) -> f64 {
        let v = self.z0 / z;
        let v2 = v * v;
        let v8 = v2 * v2 * v2 * v2;
        self.w0 / 3.0 * (4.0 * v2 - v8)
    }

    /// Interaction energy per area `-Phi(z)` [J/m^2]: `-w0` at `z = z0`, 0 far apart.
    pub fn energy_per_area(&self, z: f64) -> f64 {
        -self.phi(z)
    }

    /// `-dp/dz` [Pa/m] at atomic separation `z` \[m\]:
    /// `(8 w0 / (z0 z)) (3 (z0/z)^9 - (z0/z)^3)`, `16 w0 / z0^2` at `z = z0`, zero at the peak
    /// pull, negative beyond.
    pub fn curvature(&self, z: f64) -> f64 {
        let v = self.z0 / z;
        let v3 = v * v * v;
        8.0 * self.w0 / (self.z0 * z) * (3.0 * v3 * v3 * v3 - v3)
    }

    /// The most negative pressure, `-16 w0 / (9 sqrt(3) z0)` \[Pa\], reached at `z = 3^(1/6) z0`.
    pub fn min_pressure(&self) -> f64 {
        -16.0 * self.w0 / (9.0 * 3f64.sqrt() * self.z0)
    }

    /// Mean of `p` over the separations between `z1` and `z2` \[m\] (either order), i.e. the
    /// divided difference `(Phi(z2) - Phi(z1)) / (z2 - z1)`, and `p(z1)` when they coincide.
    ///
    /// Written with `v = z0/z` as
    /// `(w0 / (3 z0)) v1 v2 (v1 + v2) [ (v1^2 + v2^2)(v1^4 + v2^4) - 4 ]`, which follows from
    /// `(a^-k - b^-k)/(a - b)` being a sum of positive terms: no difference of nearly equal
    /// numbers is formed, so the result is accurate to a few ulps of the integrand's scale for
    /// every interval, 0 included (the naive quotient loses every digit as `z2 -> z1`).
    pub fn mean_pressure(&self, z1: f64, z2: f64) -> f64 {
        self.mean_pressure_v(self.z0 / z1, self.z0 / z2)
    }

    /// [`LennardJones::mean_pressure`] in terms of `v = z0 / z` at both ends.
    #[inline]
    pub fn mean_pressure_v(&self, v1: f64, v2: f64) -> f64 {
        let (a, b) = (v1 * v1, v2 * v2);
        self.w0 / (3.0 * self.z0) * v1 * v2 * (v1 + v2) * ((a + b) * (a * a + b * b) - 4.0)
    }

    /// The slopes of [`LennardJones::mean_pressure_v`] by the separations at its two ends,
    /// `(dM/dz1, dM/dz2)` [Pa/m], in terms of `v = z0 / z`: polynomials like the mean itself
    /// (`dv/dz = -v^2 / z0`), so free of cancellation for every interval; where the ends
    /// coincide each is half the slope of the pressure.
    #[inline]
    pub fn mean_pressure_slopes_v(&self, v1: f64, v2: f64) -> (f64, f64) {
        let (a, b) = (v1 * v1, v2 * v2);
        let q = (a + b) * (a * a + b * b) - 4.0;
        let r = 2.0 * (v1 + v2) * (a * a + b * b);
        let c = -self.w0 / (3.0 * self.z0 * self.z0);
        // d/dv1 of v1 v2 (v1 + v2) q, with dq/dv1 = 2 v1 (a^2 + b^2 + 2 a (a + b)).
        let d1 = v2 * ((2.0 * v1 + v2) * q + a * (r + 4.0 * a * (a + b) * (v1 + v2)));
        let d2 = v1 * ((2.0 * v2 + v1) * q + b * (r + 4.0 * b * (a + b) * (v1 + v2)));
        (c * a * d1, c * b * d2)
    }

    /// Mean of the interaction energy per area `-Phi` over the separations between `z1` and
    /// `z2`, in terms of `v = z0 / z` at both ends, with its partial derivatives by `v1` and
    /// `v2`: `[M, dM/dv1, dM/dv2, d2M/dv1^2, d2M/dv2^2]`.
    ///
    /// With `Psi(z) = (w0 z0 / 3) (4 v - v^7 / 7)` (`Psi' = -Phi`),
    /// `M = (Psi(z2) - Psi(z1)) / (z2 - z1) = (w0 / 3) [ -4 v1 v2 + (1/7) sum_{k=0..6} v1^(7-k) v2^(1+k) ]`:
    /// a polynomial, free of cancellation for every interval, and `-Phi(z1)` when they coincide.
    pub fn mean_energy_v(&self, v1: f64, v2: f64) -> [f64; 5] {
        let mut a = [1.0; 8];
        let mut b = [1.0; 8];
        for i in 1..8 {
            a[i] = a[i - 1] * v1;
            b[i] = b[i - 1] * v2;
        }
        let (mut m, mut m1, mut m2, mut m11, mut m22) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for k in 0..7 {
            let kf = k as f64;
            m += a[7 - k] * b[1 + k];
            m1 += (7.0 - kf) * a[6 - k] * b[1 + k];
            m2 += (1.0 + kf) * a[7 - k] * b[k];
            if k < 6 {
                m11 += (7.0 - kf) * (6.0 - kf) * a[5 - k] * b[1 + k];
            }
            if k > 0 {
                m22 += (1.0 + kf) * kf * a[7 - k] * b[k - 1];
            }
        }
        let c = self.w0 / 3.0;
        [
            c * (m / 7.0 - 4.0 * v1 * v2),
            c * (m1 / 7.0 - 4.0 * v2),
            c * (m2 / 7.0 - 4.0 * v1),
            c * m11 / 7.0,
            c * m22 / 7.0,
        ]
    }

    /// Largest `|dp/dg|` over the attractive tail `g >= 0`: `16 w0 / z0^2` [Pa/m], at contact.
    /// It also bounds the slope of [`LennardJones::mean_pressure`] in either end.
    pub fn stiffness_bound(&self) -> f64 {
        16.0 * self.w0 / (self.z0 * self.z0)
    }
}
