//! The power spectral density of a self-affine surface (docs/method.md section 5, the paper's Eq. 13).
//!
//! Convention (Persson's): a periodic surface `h(x) = sum_q h_q exp(i q.x)` over the nominal
//! area `A` has the 2-D isotropic spectrum `C(q) = A / (2 pi)^2 <|h_q|^2>` [m^4], so that
//! `<h^2> = (2 pi)^2 / A * sum_q C(q)` (the discrete form of `integral d^2q C(q)`).

use crate::error::{Result, SurfError};
use crate::grid::Grid;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// Stretch and rotation of the spectrum, for anisotropic surfaces.
///
/// The spectrum is evaluated at the effective wavevector
/// `q_eff = sqrt((ratio * q_a)^2 + q_b^2)`, where `q_a` is the component of `q` along the unit
/// vector at `angle` from the x axis and `q_b` the one across it. A `ratio` above 1 makes every
/// correlation length along that direction `ratio` times longer (ridges run along it); all
/// cut-off wavelengths of [`Psd`] are those across it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Anisotropy {
    /// Ratio of correlation lengths along and across the principal direction (> 0, 1 = isotropic).
    pub ratio: f64,
    /// Angle of the principal direction from the x axis \[rad\].
    pub angle: f64,
}

impl Default for Anisotropy {
    fn default() -> Self {
        Anisotropy {
            ratio: 1.0,
            angle: 0.0,
        }
    }
}

/// The shape of the self-affine spectrum of Eq. 13, with unit plateau:
///
/// `C(q)/C0 = 1` for `q_L <= q < q_r`, `(q/q_r)^(-2(1+H))` for `q_r <= q <= q_s`, `0` otherwise
/// (always 0 at `q = 0`), with `q_r = 2 pi / rolloff_wavelength`, `q_s = 2 pi / cutoff_wavelength`
/// and `q_L = 2 pi / long_cutoff_wavelength` (0 when absent).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Psd {
    /// Hurst exponent H, in (0, 1); the fractal dimension is 3 - H.
    pub hurst: f64,
    /// Roll-off wavelength lambda_r \[m\]: the spectrum is flat at longer wavelengths.
    pub rolloff_wavelength: f64,
    /// Short-wavelength cut-off lambda_s \[m\]: no roughness at shorter wavelengths.
    pub cutoff_wavelength: f64,
    /// Optional long-wavelength cut-off lambda_L \[m\]: no roughness at longer wavelengths.
    pub long_cutoff_wavelength: Option<f64>,
    /// Stretch and rotation of the spectrum (isotropic by default).
    #[serde(default)]
    pub anisotropy: Anisotropy,
}

impl Psd {
    /// An isotropic spectrum without long-wavelength cut-off.
    pub fn self_affine(hurst: f64, rolloff_wavelength: f64, cutoff_wavelength: f64) -> Self {
        Psd {
            hurst,
            rolloff_wavelength,
            cutoff_wavelength,
            long_cutoff_wavelength: None,
            anisotropy: Anisotropy::default(),
        }
    }

    /// Roll-off wavevector q_r [rad/m].
    pub fn q_rolloff(&self) -> f64 {
        2.0 * PI / self.rolloff_wavelength
    }

    /// Short-wavelength cut-off wavevector q_s [rad/m].
    pub fn q_cutoff(&self) -> f64 {
        2.0 * PI / self.cutoff_wavelength
    }

    /// Long-wavelength cut-off wavevector q_L [rad/m] (0 when absent).
    pub fn q_long_cutoff(&self) -> f64 {
        self.long_cutoff_wavelength.map_or(0.0, |l| 2.0 * PI / l)
    }

    /// `C(q)/C0` at the wavevector `(qx, qy)` [rad/m].
    pub fn shape(&self, qx: f64, qy: f64) -> f64 {
        self.shape_fn()(qx, qy)
    }

    /// [`Psd::shape`] with the rotation worked out once, for evaluation on a whole grid.
    pub fn shape_fn(&self) -> impl Fn(f64, f64) -> f64 + Sync + '_ {
        let Anisotropy { ratio, angle } = self.anisotropy;
        let (s, c) = angle.sin_cos();
        move |qx, qy| {
            let qa = qx * c + qy * s;
            let qb = -qx * s + qy * c;
            self.shape_radial(((ratio * qa).powi(2) + qb * qb).sqrt())
        }
    }

    /// `C(q)/C0` at the (effective) wavevector magnitude `q` [rad/m].
    pub fn shape_radial(&self, q: f64) -> f64 {
        let qr = self.q_rolloff();
        if q <= 0.0 || q < self.q_long_cutoff() || q > self.q_cutoff() {
            0.0
        } else if q < qr {
            1.0
        } else {
            (q / qr).powf(-2.0 * (1.0 + self.hurst))
        }
    }

    /// Checks the parameters against each other and the grid. Returns warnings for choices that
    /// are legal but probably not meant (a roll-off longer than the box), and an error for
    /// those that give garbage (H outside (0, 1), a cut-off below two grid spacings, ...).
    pub fn validate(&self, grid: &Grid) -> Result<Vec<String>> {
        let mut warnings = Vec::new();
        if !(self.hurst > 0.0 && self.hurst < 1.0) {
            return Err(SurfError::invalid(
                "hurst",
                self.hurst,
                "the Hurst exponent must lie in (0, 1)",
            ));
        }
        for (name, v) in [
            ("rolloff_wavelength", self.rolloff_wavelength),
            ("cutoff_wavelength", self.cutoff_wavelength),
            (
                "long_cutoff_wavelength",
                self.long_cutoff_wavelength.unwrap_or(1.0),
            ),
            ("anisotropy.ratio", self.anisotropy.ratio),
        ] {
            if !(v.is_finite() && v > 0.0) {
                return Err(SurfError::invalid(name, v, "must be finite and > 0"));
            }
        }
        if !self.anisotropy.angle.is_finite() {
            return Err(SurfError::invalid(
                "anisotropy.angle",
                self.anisotropy.angle,
                "must be finite",
            ));
        }
        if self.cutoff_wavelength >= self.rolloff_wavelength {
            return Err(SurfError::invalid(
                "cutoff_wavelength",
                self.cutoff_wavelength,
                format!(
                    "the short-wavelength cut-off must be shorter than the roll-off wavelength {} m",
                    self.rolloff_wavelength
                ),
            ));
        }
        if let Some(long) = self.long_cutoff_wavelength
            && long <= self.rolloff_wavelength
        {
            return Err(SurfError::invalid(
                "long_cutoff_wavelength",
                long,
                format!(
                    "must be longer than the roll-off wavelength {} m",
                    self.rolloff_wavelength
                ),
            ));
        }
        let spacing = grid.dx().max(grid.dy());
        if self.cutoff_wavelength < 2.0 * spacing * (1.0 - 1e-12) {
            return Err(SurfError::invalid(
                "cutoff_wavelength",
                self.cutoff_wavelength,
                format!(
                    "shorter than two grid spacings ({} m): the grid cannot represent it; refine the grid to at least {} points per side or lengthen the cut-off",
                    2.0 * spacing,
                    (2.0 * grid.length_x.max(grid.length_y) / self.cutoff_wavelength).ceil()
                ),
            ));
        }
        let box_len = grid.length_x.min(grid.length_y);
        if self.rolloff_wavelength > box_len * (1.0 + 1e-12) {
            warnings.push(format!(
                "roll-off wavelength {} m is longer than the box ({} m): the surface has no flat part of the spectrum",
                self.rolloff_wavelength, box_len
            ));
        }
        if let Some(long) = self.long_cutoff_wavelength
            && long > box_len * (1.0 + 1e-12)
        {
            warnings.push(format!(
                "long-wavelength cut-off {long} m is longer than the box ({box_len} m) and has no effect"
            ));
        }
        if self.cutoff_wavelength < 4.0 * spacing {
            warnings.push(format!(
                "short cut-off {} m is below four grid spacings: the shortest waves are sampled by fewer than 4 points, so finite-difference slopes and curvatures underestimate the spectral ones",
                self.cutoff_wavelength
            ));
        }
        Ok(warnings)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn shape_follows_eq13() {
        let psd = Psd::self_affine(0.8, 2e-5, 1e-7);
        let qr = psd.q_rolloff();
        assert_eq!(psd.shape_radial(0.0), 0.0);
        assert_eq!(psd.shape_radial(0.5 * qr), 1.0);
        assert!((psd.shape_radial(2.0 * qr) - 2f64.powf(-3.6)).abs() < 1e-15);
        assert_eq!(psd.shape_radial(1.01 * psd.q_cutoff()), 0.0);
    }

    #[test]
    fn anisotropy_stretches_along_its_direction() {
        let mut psd = Psd::self_affine(0.5, 1e-5, 1e-7);
        psd.anisotropy = Anisotropy {
            ratio: 4.0,
            angle: 0.0,
        };
        let q = 4.0 * psd.q_rolloff();
        // Along x the spectrum is that of q * ratio; across it the nominal one.
        assert_eq!(psd.shape(q, 0.0), psd.shape_radial(4.0 * q));
        assert_eq!(psd.shape(0.0, q), psd.shape_radial(q));
        psd.anisotropy.angle = std::f64::consts::FRAC_PI_2;
        assert!((psd.shape(0.0, q) - psd.shape_radial(4.0 * q)).abs() < 1e-12 * psd.shape_radial(4.0 * q));
    }

    #[test]
    fn validation_rejects_nonsense() {
        let grid = Grid::square(256, 1e-4).unwrap();
        assert!(Psd::self_affine(1.2, 2e-5, 1e-6).validate(&grid).is_err());
        assert!(Psd::self_affine(0.0, 2e-5, 1e-6).validate(&grid).is_err());
        assert!(Psd::self_affine(0.8, 1e-6, 2e-5).validate(&grid).is_err());
        // 0.5 um is below two spacings of 0.39 um.
        assert!(Psd::self_affine(0.8, 2e-5, 5e-7).validate(&grid).is_err());
        assert!(
            Psd::self_affine(0.8, 2e-5, 2e-6)
                .validate(&grid)
                .unwrap()
                .is_empty()
        );
        assert_eq!(
            Psd::self_affine(0.8, 2e-4, 2e-6).validate(&grid).unwrap().len(),
            1
        );
    }
}
