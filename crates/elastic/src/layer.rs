//! An elastic layer of finite thickness on a rigid base or an elastic substrate: its surface
//! compliance by wavenumber.
//!
//! A layer of thickness `h` \[m\], Poisson's ratio `nu` and plane-strain modulus
//! `E* = E / (1 - nu^2)` on a rigid base, loaded by a normal pressure on its frictionless top,
//! answers a mode of wavenumber `q` \[1/m\] with the displacement `C(q) p(q)`, the half-space's
//! `2 / (E* q)` times a factor of `x = q h` alone:
//!
//! - base bonded (Carbone & Mangialardi, J. Mech. Phys. Solids 56, 2008, the form
//!   ContactMechanics uses): `[(3 - 4 nu) sinh 2x - 2x] / [(3 - 4 nu) cosh 2x + 2x^2 + 5 - 12 nu
//!   + 8 nu^2]`;
//! - base frictionless (the layer slides on it): `(cosh 2x - 1) / (sinh 2x + 2x)`.
//!
//! Both tend to 1 as `x -> oo` (the half-space) and give a finite mean mode: `h / M` bonded, with
//! `M = E* (1 - nu)^2 / (1 - 2 nu)` the P-wave modulus (0 when incompressible: no volume to
//! lose), `h / E*` frictionless (every mode is a plane wave, in plane strain along its crests).
//! Evaluated without overflow at any `x`, and without cancellation as `x -> 0`. On an elastic
//! substrate (a coating) the factor is solved a wavenumber from Navier's equations
//! ([`Base::Substrate`]; docs/method.md section 12).

use crate::error::{ElasticError, Result};
use std::f64::consts::PI;

/// What the layer lies on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Base {
    /// A rigid base, bonded: no displacement at the base.
    Bonded,
    /// A rigid base, frictionless: no normal displacement and no shear traction at the base.
    Frictionless,
    /// An elastic half-space of another material, bonded (a coating on a substrate): its
    /// plane-strain modulus \[Pa\] and Poisson's ratio, which must lie in (-1, 0.5).
    Substrate {
        /// Plane-strain modulus `E / (1 - nu^2)` of the substrate \[Pa\].
        e_star: f64,
        /// Poisson's ratio of the substrate [-].
        poisson: f64,
    },
}

/// An elastic layer on a rigid base (module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layer {
    /// Thickness \[m\].
    pub thickness: f64,
    /// Poisson's ratio of the layer [-].
    pub poisson: f64,
    /// How it meets its base.
    pub base: Base,
}

/// Below this `x = q h` the factors' small-`x` forms are taken, above it their forms scaled by
/// `2 exp(-2x)`; both are exact, the choice only keeps round-off small.
const SMALL: f64 = 0.5;

impl Layer {
    /// A layer, checked: finite thickness > 0 m, `-1 < poisson <= 0.5`.
    ///
    /// # Errors
    /// [`ElasticError::InvalidParameter`] naming `thickness` or `poisson`.
    pub fn new(thickness: f64, poisson: f64, base: Base) -> Result<Layer> {
        if !(thickness.is_finite() && thickness > 0.0) {
            return Err(ElasticError::InvalidParameter {
                name: "thickness",
                value: thickness,
                reason: "must be a finite layer thickness > 0 m",
            });
        }
        crate::material::check_poisson("poisson", poisson)?;
        if let Base::Substrate {
            e_star,
            poisson: substrate,
        } = base
        {
            if !(e_star.is_finite() && e_star > 0.0) {
                return Err(ElasticError::InvalidParameter {
                    name: "substrate_modulus",
                    value: e_star,
                    reason: "must be a finite plane-strain modulus > 0 Pa",
                });
            }
            crate::material::check_poisson("substrate_poisson", substrate)?;
            // The coating's solution is written with Lame's lambda, infinite at nu = 1/2.
            for (name, nu) in [("poisson", poisson), ("substrate_poisson", substrate)] {
                if nu >= 0.5 {
                    return Err(ElasticError::InvalidParameter {
                        name,
                        value: nu,
                        reason: "must be below 0.5 for a coating on a substrate (the \
                                 incompressible limit is taken on a rigid base only)",
                    });
                }
            }
        }
        Ok(Layer {
            thickness,
            poisson,
            base,
        })
    }

    /// The layer's compliance at wavenumber `q` \[1/m\] over the half-space's of its own
    /// plane-strain modulus `e_star` \[Pa\], `C(q) E* q / 2` [-]: 1 for `q h -> oo`; on a rigid
    /// base in `(0, 1]`, on a substrate tending to `E* / E*_substrate` as `q h -> 0`.
    pub fn compliance_ratio(&self, q: f64, e_star: f64) -> f64 {
        let x = q * self.thickness;
        let nu = self.poisson;
        match self.base {
            Base::Substrate {
                e_star: substrate,
                poisson,
            } => coating_ratio(x, (e_star, nu), (substrate, poisson)),
            Base::Bonded => {
                let a = 3.0 - 4.0 * nu;
                let c = 5.0 - 12.0 * nu + 8.0 * nu * nu;
                if x < SMALL {
                    // (3 - 4nu) sinh 2x - 2x = (3 - 4nu) (sinh 2x - 2x) + (2 - 4nu) 2x: no
                    // cancellation, also at nu = 1/2, where only the cubic term is left.
                    let numerator = a * sinh_less_linear(2.0 * x) + (2.0 - 4.0 * nu) * 2.0 * x;
                    numerator / (a * (2.0 * x).cosh() + 2.0 * x * x + c)
                } else {
                    let (e2, e4) = ((-2.0 * x).exp(), (-4.0 * x).exp());
                    let numerator = a * (1.0 - e4) - 4.0 * x * e2;
                    numerator / (a * (1.0 + e4) + 2.0 * e2 * (2.0 * x * x + c))
                }
            }
            Base::Frictionless => {
                if x < SMALL {
                    // cosh 2x - 1 = 2 sinh^2 x.
                    let s = x.sinh();
                    2.0 * s * s / ((2.0 * x).sinh() + 2.0 * x)
                } else {
                    let e2 = (-2.0 * x).exp();
                    (1.0 - e2) * (1.0 - e2) / (1.0 - e2 * e2 + 4.0 * x * e2)
                }
            }
        }
    }

    /// The displacement \[m\] of the mode of wavenumber `q` \[1/m\] under unit pressure \[Pa\], on
    /// a layer of plane-strain modulus `e_star` \[Pa\]: `2 / (E* q)` times
    /// [`Layer::compliance_ratio`], and at `q = 0` its limit (module docs).
    pub fn compliance(&self, q: f64, e_star: f64) -> f64 {
        if q == 0.0 {
            return self.mean_compliance(e_star).unwrap_or(f64::INFINITY);
        }
        2.0 / (e_star * q) * self.compliance_ratio(q, e_star)
    }

    /// The compliance \[m/Pa\] of the mean mode of a layer of plane-strain modulus `e_star`
    /// \[Pa\]: `h / M` bonded, `h / E*` frictionless; `None` on a substrate, a half-space that
    /// a uniform pressure displaces without bound.
    pub fn mean_compliance(&self, e_star: f64) -> Option<f64> {
        let nu = self.poisson;
        match self.base {
            Base::Bonded => Some(self.thickness * (1.0 - 2.0 * nu) / (e_star * (1.0 - nu) * (1.0 - nu))),
            Base::Frictionless => Some(self.thickness / e_star),
            Base::Substrate { .. } => None,
        }
    }

    /// The tangential factors at wavenumber `q` \[1/m\] (`q > 0`) of a layer of shear modulus
    /// `G`: along the wave (plane strain) `C_LL = (1 - nu) r_LL / (G q)`, across it (antiplane)
    /// `C_TT = r_TT / (G q)`, and the coupling `C_zL = i c_zL / (G q)` (the normal displacement
    /// under a shear along the wave; the half-space's `r = 1`, `c_zL = -(1 - 2 nu)/2`). From
    /// Navier's equations through the layer (docs/method.md section 14); on a substrate by
    /// the coating's six conditions (as its normal factor) and, across the wave, in closed form.
    pub fn shear_factors(&self, q: f64, e_star: f64) -> ShearFactors {
        let x = q * self.thickness;
        let nu = self.poisson;
        let a = 3.0 - 4.0 * nu;
        match self.base {
            Base::Substrate {
                e_star: substrate,
                poisson,
            } => {
                let (w0, u0) = coating_surface(x, (e_star, nu), (substrate, poisson), (0.0, 1.0));
                // Shear moduli over the layer's, G = E* (1 - nu) / 2; G1 = (1 - nu1) / 2 in the
                // units of coating_surface.
                let ratio = substrate * (1.0 - poisson) / (e_star * (1.0 - nu));
                let t = x.tanh();
                ShearFactors {
                    along: u0 / 2.0,
                    across: (1.0 + ratio * t) / (t + ratio),
                    coupling: -w0 * (1.0 - nu) / 2.0,
                }
            }
            Base::Bonded => {
                let c = 5.0 - 12.0 * nu + 8.0 * nu * nu;
                if x < SMALL {
                    let denominator = a * (2.0 * x).cosh() + 2.0 * x * x + c;
                    let s = x.sinh();
                    ShearFactors {
                        along: (a * sinh_less_linear(2.0 * x) + (a + 1.0) * 2.0 * x) / denominator,
                        across: x.tanh(),
                        coupling: (x * x - (1.0 - 2.0 * nu) * a * s * s) / denominator,
                    }
                } else {
                    let (e2, e4) = ((-2.0 * x).exp(), (-4.0 * x).exp());
                    let denominator = a * (1.0 + e4) + 2.0 * e2 * (2.0 * x * x + c);
                    ShearFactors {
                        along: (a * (1.0 - e4) + 4.0 * x * e2) / denominator,
                        across: x.tanh(),
                        coupling: (4.0 * x * x * e2 - (1.0 - 2.0 * nu) * a * (1.0 - e2) * (1.0 - e2))
                            / (2.0 * denominator),
                    }
                }
            }
            Base::Frictionless => {
                if x < SMALL {
                    let (c, s2) = (x.cosh(), (2.0 * x).sinh());
                    ShearFactors {
                        along: 2.0 * c * c / (s2 + 2.0 * x),
                        across: 1.0 / x.tanh(),
                        coupling: (2.0 * x - (1.0 - 2.0 * nu) * s2) / (2.0 * (2.0 * x + s2)),
                    }
                } else {
                    let (e2, e4) = ((-2.0 * x).exp(), (-4.0 * x).exp());
                    let denominator = 1.0 - e4 + 4.0 * x * e2;
                    ShearFactors {
                        along: (1.0 + e2) * (1.0 + e2) / denominator,
                        across: 1.0 / x.tanh(),
                        coupling: (4.0 * x * e2 - (1.0 - 2.0 * nu) * (1.0 - e4)) / (2.0 * denominator),
                    }
                }
            }
        }
    }

    /// The tangential compliance \[m/Pa\] of a uniform shear on a layer of shear modulus `g`
    /// \[Pa\]: `h / G` bonded; `None` on a frictionless base (the layer slides) or a substrate
    /// (a half-space, displaced without bound).
    pub fn mean_shear_compliance(&self, g: f64) -> Option<f64> {
        match self.base {
            Base::Bonded => Some(self.thickness / g),
            _ => None,
        }
    }

    /// The layer's influence in real space (tabulated once: about 3 million Bessel functions).
    pub(crate) fn real_space(&self, e_star: f64) -> RealSpace {
        RealSpace::new(self, e_star)
    }
}

/// A layer's tangential compliance at one wavenumber over the half-space's
/// ([`Layer::shear_factors`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ShearFactors {
    /// `r_LL`, along the wave.
    pub along: f64,
    /// `r_TT`, across it.
    pub across: f64,
    /// `c_zL`, the coupling.
    pub coupling: f64,
}

/// 8-point Gauss-Legendre nodes and weights on `[-1, 1]`.
const GAUSS: [(f64, f64); 8] = [
    (-0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
    (-0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (-0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (-0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_5),
    (0.960_289_856_497_536_3, 0.101_228_536_290_376_3),
];

/// Beyond this distance over the thickness the layer's correction is its tail
/// ([`RealSpace`]): on a rigid base nothing (the influence decays exponentially, below
/// `1e-14 / (pi E* h)` there for every base and `nu` in `[0, 0.5]`), under a coating the
/// substrate's half-space and algebraic terms.
const CUT: f64 = 40.0;

/// Cells wider than this many thicknesses see the layer as Winkler's bed ([`RealSpace::thin`]).
const THIN: f64 = 64.0;

/// Spacing of the tabulated correction in distance over thickness: cubic interpolation on it is
/// good to about 1e-9 of the correction.
const TABLE_STEP: f64 = 0.02;

/// The layer's point influence in real space less the half-space's, for the free grid's
/// influence coefficients. By the Hankel transform, a point force `P` displaces the surface at
/// distance `r` by `P G(r)` with `G(r) = [1/r + F(r/h)/h] / (pi E*)`, where
/// `F(s) = int_0^oo (R(t) - 1) J0(s t) dt` and `R` is [`Layer::compliance_ratio`] at `q = t/h`.
/// `F` is smooth; it is tabulated once by Gauss-Legendre quadrature (`R - 1` decays as
/// `exp(-2t)`, cut at `t = 30`; panels shorter than half a period of `J0`) up to [`CUT`]
/// thicknesses. Beyond, `F` is its tail. With `rho = R(0)`, `F -> (rho - 1)/s`; on a rigid base
/// `rho = 0` and `R` is odd in `t`, so `F + 1/s` dies exponentially and the whole influence
/// vanishes. A coating keeps its substrate's `1/r` (`rho = E*/E*_substrate`) and algebraic
/// terms from `R`'s even powers (`t^2` gives `-1/s^3`, `t^4` `9/s^5`): the tail is
/// `(rho - 1)/s + A/s^3 + B/s^5`, `A` and `B` through `F` at [`CUT`] and 1.5 [`CUT`].
#[derive(Clone, Debug)]
pub(crate) struct RealSpace {
    thickness: f64,
    /// `rho - 1`.
    far: f64,
    /// The tail's `A` and `B` ([`RealSpace::beyond`]).
    tail: [f64; 2],
    /// The local compliance \[m/Pa\] of wide cells, `2 rho1 h / E*`: on a rigid base the mean
    /// mode's, Winkler's bed.
    local: f64,
    /// `F` at `s = k TABLE_STEP`, `k = 0..`, one point past [`CUT`] on either side for the
    /// interpolation.
    table: Vec<f64>,
}

impl RealSpace {
    fn new(layer: &Layer, e_star: f64) -> RealSpace {
        use rayon::prelude::*;
        let points = (CUT / TABLE_STEP) as usize + 3;
        let table = (0..points)
            .into_par_iter()
            .map(|k| hankel(layer, e_star, k as f64 * TABLE_STEP))
            .collect();
        let h = layer.thickness;
        let (far, tail, local) = match layer.base {
            Base::Substrate { e_star: e_sub, .. } => {
                let rho = e_star / e_sub;
                // The tail's two terms after the substrate's 1/s, through F at CUT and 1.5 CUT.
                let (s1, s2) = (CUT, 1.5 * CUT);
                let (f1, f2) = (
                    hankel(layer, e_star, s1) - (rho - 1.0) / s1,
                    hankel(layer, e_star, s2) - (rho - 1.0) / s2,
                );
                let b = (f1 * s1.powi(3) - f2 * s2.powi(3)) / (s1.powi(-2) - s2.powi(-2));
                let a = f1 * s1.powi(3) - b / (s1 * s1);
                // R's slope at t = 0, Richardson's from t = 1e-4 and 2e-4.
                let slope = |t: f64| (layer.compliance_ratio(t / h, e_star) - rho) / t;
                let rho1 = 2.0 * slope(1e-4) - slope(2e-4);
                (rho - 1.0, [a, b], 2.0 * rho1 * h / e_star)
            }
            _ => (-1.0, [0.0; 2], layer.mean_compliance(e_star).unwrap_or(0.0)),
        };
        RealSpace {
            thickness: h,
            far,
            tail,
            local,
            table,
        }
    }

    /// The displacement \[m\] at offset `(x, y)` \[m\] from the centre of the loaded cell of
    /// half-sides `a`, `b` under unit pressure \[Pa\] on it, given the half-space's
    /// (`love`, [`crate::love::cell_influence`] at `e_star` \[Pa\]).
    ///
    /// On cells wider than [`THIN`] thicknesses the layer's influence dies within a fraction of
    /// a cell: the far field (nothing on a rigid base, the substrate's half-space under a
    /// coating) plus the local compliance on the loaded cell itself (the quadrature would take
    /// `(8 THIN)^2` points a cell; the terms left out are `exp(-THIN/2)`-small on a rigid base,
    /// of order `h / dx` of the coating's own correction).
    /// Beyond [`CUT`] thicknesses, the tail alone.
    pub(crate) fn coefficient(&self, x: f64, y: f64, a: f64, b: f64, e_star: f64, love: f64) -> f64 {
        let h = self.thickness;
        let far = (1.0 + self.far) * love;
        if 2.0 * a.max(b) > THIN * h {
            return if x.abs() < a && y.abs() < b {
                far + self.local
            } else {
                far
            };
        }
        // The nearest point of the cell.
        let near = (x.abs() - a).max(0.0).hypot((y.abs() - b).max(0.0));
        if near > CUT * h {
            return if self.tail == [0.0; 2] {
                far
            } else {
                far + self.cell_integral(x, y, a, b, e_star, |s| self.beyond(s) - self.far / s)
            };
        }
        love + self.cell_integral(x, y, a, b, e_star, |s| self.correction(s))
    }

    /// `int F(r/h) dA / (pi E* h)` over the cell, `F` given.
    fn cell_integral(&self, x: f64, y: f64, a: f64, b: f64, e_star: f64, f: impl Fn(f64) -> f64) -> f64 {
        let h = self.thickness;
        // Panels no wider than the thickness, 8 points each way: `F` varies on the scale `h`.
        let panels = |half: f64| ((2.0 * half / h).ceil() as usize).max(1);
        let (px, py) = (panels(a), panels(b));
        let (wx, wy) = (2.0 * a / px as f64, 2.0 * b / py as f64);
        let mut sum = 0.0;
        for j in 0..py {
            let ym = -b + (j as f64 + 0.5) * wy;
            for &(v, wv) in &GAUSS {
                let dy = y - (ym + 0.5 * wy * v);
                for i in 0..px {
                    let xm = -a + (i as f64 + 0.5) * wx;
                    for &(u, wu) in &GAUSS {
                        let s = (x - (xm + 0.5 * wx * u)).hypot(dy) / h;
                        sum += wu * wv * f(s);
                    }
                }
            }
        }
        sum * 0.25 * wx * wy / (PI * e_star * h)
    }

    /// `F(s)`'s tail, `(rho - 1)/s + A/s^3 + B/s^5`.
    fn beyond(&self, s: f64) -> f64 {
        let [a, b] = self.tail;
        self.far / s + a / s.powi(3) + b / s.powi(5)
    }

    /// `F(s)`: inside [`CUT`] by cubic interpolation in the table, beyond it the tail.
    fn correction(&self, s: f64) -> f64 {
        if s >= CUT {
            return self.beyond(s);
        }
        let at = s / TABLE_STEP;
        // Four points k-1..k+2 around `at`; the table's evenness about 0 (F is even in s)
        // supplies the point before the first.
        let k = (at.floor() as usize).min(self.table.len() - 3);
        let t = at - k as f64;
        let f = |i: isize| self.table[i.unsigned_abs()];
        let k = k as isize;
        let (a, b, c, d) = (f(k - 1), f(k), f(k + 1), f(k + 2));
        // Lagrange's cubic through the four.
        let (tm, tp, t2) = (t - 1.0, t + 1.0, t - 2.0);
        (-t * tm * t2 * a + 3.0 * tp * tm * t2 * b - 3.0 * tp * t * t2 * c + tp * t * tm * d) / 6.0
    }
}

/// `F(s) = int_0^30 (R(t) - 1) J0(s t) dt` ([`RealSpace`]) by composite Gauss-Legendre.
fn hankel(layer: &Layer, e_star: f64, s: f64) -> f64 {
    let width = if s > 0.0 { (PI / s).min(0.5) } else { 0.5 };
    let panels = (30.0 / width).ceil() as usize;
    let width = 30.0 / panels as f64;
    (0..panels)
        .map(|i| {
            let middle = (i as f64 + 0.5) * width;
            GAUSS
                .iter()
                .map(|&(x, w)| {
                    let t = middle + 0.5 * width * x;
                    w * (layer.compliance_ratio(t / layer.thickness, e_star) - 1.0) * libm::j0(s * t)
                })
                .sum::<f64>()
                * 0.5
                * width
        })
        .sum()
}

/// A coating's compliance ratio at `x = q h`: the layer `(E*, nu)` bonded to the substrate
/// `(E*, nu)`, both below `nu = 1/2`. Navier's equations for a mode `e^{iqx}` (displacements
/// `i U(z)`, `W(z)`, `z` down, lengths in units of `1/q`) are solved by
/// `W = (c + d z) e^{-z}`, `U = (-c + k d - d z) e^{-z}` and
/// `W = (c + d z) e^{z}`, `U = (c + k d + d z) e^{z}`, `k = 3 - 4 nu`: in the layer the decaying
/// family from the top and the growing one anchored at the interface (both bounded), in the
/// substrate the decaying one from the interface. Six conditions fix the six constants: under
/// unit pressure no shear on top, and at the interface `W`, `U`, `s_zz` and `s_xz` continuous,
/// with `s_zz = (l + 2m) W' - l U` and `s_xz = m (U' + W)` (times `q`). The ratio is
/// `W(0) E* / 2` with the moduli in units of the layer's `E*`.
fn coating_ratio(x: f64, layer: (f64, f64), substrate: (f64, f64)) -> f64 {
    coating_surface(x, layer, substrate, (1.0, 0.0)).0 / 2.0
}

/// [`coating_ratio`]'s surface displacement `(W(0), U(0))` under a pressure `p` and a shear
/// `t` (the traction `i t e^{iqx}` along x: `s_xz(0) = -t`), in units of `1 / (E* q)`.
fn coating_surface(x: f64, (e1, nu1): (f64, f64), (e2, nu2): (f64, f64), (p, t): (f64, f64)) -> (f64, f64) {
    // Lame's constants from E* and nu: E = E* (1 - nu^2), mu = E* (1 - nu) / 2.
    let lame = |e_star: f64, nu: f64| {
        let mu = e_star * (1.0 - nu) / 2.0;
        (2.0 * mu * nu / (1.0 - 2.0 * nu), mu, 3.0 - 4.0 * nu)
    };
    let (l1, m1, k1) = lame(1.0, nu1);
    let (l2, m2, k2) = lame(e2 / e1, nu2);
    // Each family's (W, U, W', U') at a point `z` of its own coordinate, per unit c and d.
    let decaying = |k: f64, z: f64| {
        let e = (-z).exp();
        [
            [e, z * e],
            [-e, (k - z) * e],
            [-e, (1.0 - z) * e],
            [e, (z - 1.0 - k) * e],
        ]
    };
    let growing = |k: f64, z: f64| {
        let e = z.exp();
        [
            [e, z * e],
            [e, (k + z) * e],
            [e, (1.0 + z) * e],
            [e, (1.0 + k + z) * e],
        ]
    };
    // Rows: the four quantities (W, U, s_zz, s_xz) of a state at a point for the columns.
    let quantities = |f: [[f64; 2]; 4], (l, m): (f64, f64)| {
        let [w, u, dw, du] = f;
        let mut out = [[0.0; 2]; 4];
        for c in 0..2 {
            out[0][c] = w[c];
            out[1][c] = u[c];
            out[2][c] = (l + 2.0 * m) * dw[c] - l * u[c];
            out[3][c] = m * (du[c] + w[c]);
        }
        out
    };
    let top = (
        quantities(decaying(k1, 0.0), (l1, m1)),
        quantities(growing(k1, -x), (l1, m1)),
    );
    let interface = (
        quantities(decaying(k1, x), (l1, m1)),
        quantities(growing(k1, 0.0), (l1, m1)),
        quantities(decaying(k2, 0.0), (l2, m2)),
    );
    // Unknowns (c1, d1, c2, d2, c3, d3); the right-hand side last.
    let mut a = [[0.0; 7]; 6];
    for c in 0..2 {
        a[0][c] = top.0[2][c];
        a[0][2 + c] = top.1[2][c];
        a[1][c] = top.0[3][c];
        a[1][2 + c] = top.1[3][c];
        for q in 0..4 {
            a[2 + q][c] = interface.0[q][c];
            a[2 + q][2 + c] = interface.1[q][c];
            a[2 + q][4 + c] = -interface.2[q][c];
        }
    }
    a[0][6] = -p;
    a[1][6] = -t;
    let y = eliminate(a);
    // W(0) = c1 + (c2 + d2 (-x)) e^{-x}, in units of 1 / (E* q); the half-space's is 2.
    let w0 = y[0] + top.1[0][0] * y[2] + top.1[0][1] * y[3];
    let u0 = top.0[1][0] * y[0] + top.0[1][1] * y[1] + top.1[1][0] * y[2] + top.1[1][1] * y[3];
    (w0, u0)
}

/// Gaussian elimination with partial pivoting of an `N` x `N` system, its right-hand side the
/// last of the `M = N + 1` columns.
fn eliminate<const N: usize, const M: usize>(mut a: [[f64; M]; N]) -> [f64; N] {
    debug_assert_eq!(M, N + 1);
    for c in 0..N {
        let p = (c..N).fold(c, |p, i| if a[i][c].abs() > a[p][c].abs() { i } else { p });
        a.swap(c, p);
        let pivot = a[c];
        for row in a.iter_mut().skip(c + 1) {
            let f = row[c] / pivot[c];
            row.iter_mut().zip(&pivot).skip(c).for_each(|(v, p)| *v -= f * p);
        }
    }
    let mut y = [0.0; N];
    for c in (0..N).rev() {
        y[c] = (a[c][N] - (c + 1..N).map(|k| a[c][k] * y[k]).sum::<f64>()) / a[c][c];
    }
    y
}

/// `sinh y - y` for `0 <= y < 1`, by its series (no cancellation as `y -> 0`).
fn sinh_less_linear(y: f64) -> f64 {
    let y2 = y * y;
    let (mut term, mut sum, mut k) = (y * y2 / 6.0, 0.0, 3.0);
    while term > 1e-17 * sum || sum == 0.0 {
        sum += term;
        term *= y2 / ((k + 1.0) * (k + 2.0));
        k += 2.0;
        if term == 0.0 {
            break;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    const E_STAR: f64 = 1e9;

    fn layer(nu: f64, base: Base) -> Layer {
        Layer::new(1e-6, nu, base).unwrap()
    }

    /// The factors as the literature writes them, for moderate `x` only.
    fn closed_form(l: &Layer, q: f64) -> f64 {
        let (x, nu) = (q * l.thickness, l.poisson);
        match l.base {
            Base::Bonded => {
                let a = 3.0 - 4.0 * nu;
                (a * (2.0 * x).sinh() - 2.0 * x)
                    / (a * (2.0 * x).cosh() + 2.0 * x * x + 5.0 - 12.0 * nu + 8.0 * nu * nu)
            }
            Base::Frictionless => ((2.0 * x).cosh() - 1.0) / ((2.0 * x).sinh() + 2.0 * x),
            Base::Substrate { .. } => unreachable!("rigid bases only"),
        }
    }

    #[test]
    fn a_coatings_tail_continues_its_tabulated_influence() {
        // Substrates 100 times stiffer to 100 times softer: the tail against the quadrature
        // out to 200 thicknesses, in units of the influence at the load's centre F(0).
        for (e_sub, within) in [
            (1e11, 1e-12),
            (1e10, 1e-10),
            (3e8, 1e-7),
            (1e8, 1e-6),
            (1e7, 1e-4),
        ] {
            let l = layer(
                0.3,
                Base::Substrate {
                    e_star: e_sub,
                    poisson: 0.45,
                },
            );
            let rs = RealSpace::new(&l, E_STAR);
            for s in [50.0, 80.0, 120.0, 200.0] {
                let err = (hankel(&l, E_STAR, s) - rs.beyond(s)).abs() / rs.table[0].abs();
                assert!(err < within, "substrate {e_sub} Pa, s {s}: {err:e}");
            }
        }
    }

    #[test]
    fn the_factors_are_the_closed_forms_to_round_off_on_either_side_of_the_switch() {
        for base in [Base::Bonded, Base::Frictionless] {
            for nu in [-0.5, 0.0, 0.3, 0.49, 0.5] {
                let l = layer(nu, base);
                for x in [0.01, 0.1, 0.3, 0.499, 0.5, 0.501, 1.0, 2.0, 5.0, 10.0] {
                    let q = x / l.thickness;
                    let (got, want) = (l.compliance_ratio(q, E_STAR), closed_form(&l, q));
                    // The closed form itself loses digits to cancellation at small x.
                    let tolerance = if x < 0.1 { 1e-10 } else { 1e-13 };
                    assert!(
                        (got / want - 1.0).abs() < tolerance,
                        "{base:?} nu {nu} x {x}: {got} {want}"
                    );
                }
            }
        }
    }

    /// The surface displacement \[m\] under unit pressure of a plane-strain layer of thickness 1
    /// and Young's modulus 1 at wavenumber `q`, from Navier's equations integrated through its
    /// depth (RK4) with its four boundary conditions: no shear and the pressure on top, no
    /// normal displacement at the base and no shear (frictionless) or no slip (bonded) there.
    fn navier(q: f64, nu: f64, base: Base) -> f64 {
        navier_surface(q, nu, base, (1.0, 0.0)).1
    }

    /// [`navier`]'s surface displacement `(U, W)` (`u_x = i U e^{iqx}`, `u_z = W e^{iqx}`)
    /// under a pressure `p` and a shear `t` (the traction `i t e^{iqx}` along x on the surface).
    fn navier_surface(q: f64, nu: f64, base: Base, (p, t): (f64, f64)) -> (f64, f64) {
        let mu = 1.0 / (2.0 * (1.0 + nu));
        let lambda = nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        // Y = (U, U', W, W') with u_x = i U e^{iqx}, u_z = W e^{iqx}, z down into the layer.
        let f = |y: [f64; 4]| {
            let [u, du, w, dw] = y;
            let ddu = ((lambda + 2.0 * mu) * q * q * u - (lambda + mu) * q * dw) / mu;
            let ddw = (mu * q * q * w + (lambda + mu) * q * du) / (lambda + 2.0 * mu);
            [du, ddu, dw, ddw]
        };
        let n = 2000;
        let dz = 1.0 / n as f64;
        // Y(1) for each unit start: the columns of the fundamental matrix.
        let at_base: Vec<[f64; 4]> = (0..4)
            .map(|k| {
                let mut y = [0.0; 4];
                y[k] = 1.0;
                let add = |y: [f64; 4], k: [f64; 4], h: f64| std::array::from_fn(|i| y[i] + h * k[i]);
                for _ in 0..n {
                    let k1 = f(y);
                    let k2 = f(add(y, k1, dz / 2.0));
                    let k3 = f(add(y, k2, dz / 2.0));
                    let k4 = f(add(y, k3, dz));
                    y = std::array::from_fn(|i| {
                        y[i] + dz / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i])
                    });
                }
                y
            })
            .collect();
        let row = |i: usize| [at_base[0][i], at_base[1][i], at_base[2][i], at_base[3][i]];
        // sigma_zz(0) = lambda (-q U + W') + 2 mu W' = -p, mu (U' + q W) = -t,
        // W(1) = 0, and U'(1) = 0 (frictionless) or U(1) = 0 (bonded).
        let a = [
            [-lambda * q, 0.0, 0.0, lambda + 2.0 * mu, -p],
            [0.0, mu, mu * q, 0.0, -t],
            [row(2)[0], row(2)[1], row(2)[2], row(2)[3], 0.0],
            match base {
                Base::Frictionless => [row(1)[0], row(1)[1], row(1)[2], row(1)[3], 0.0],
                Base::Bonded => [row(0)[0], row(0)[1], row(0)[2], row(0)[3], 0.0],
                Base::Substrate { .. } => unreachable!("rigid bases only"),
            },
        ];
        // The pressure pushes the surface into the layer, W(0) > 0.
        let y = eliminate(a);
        (y[0], y[2])
    }

    /// Along the wave, a shear's tangential and normal displacements are Navier's: the factors
    /// `r_LL` and `c_zL` of [`Layer::shear_factors`] on either side of the switch, and Betti's
    /// reciprocity between the shear's normal displacement and the pressure's tangential one.
    #[test]
    fn the_shear_factors_solve_navier_s_equations_through_the_layer() {
        for base in [Base::Bonded, Base::Frictionless] {
            for nu in [0.0, 0.25, 0.3, 0.45] {
                let l = Layer::new(1.0, nu, base).unwrap();
                let g = 1.0 / (2.0 * (1.0 + nu));
                for q in [0.1, 0.3, 0.5, 1.0, 2.0] {
                    let f = l.shear_factors(q, 1.0 / (1.0 - nu * nu));
                    let (u, w) = navier_surface(q, nu, base, (0.0, 1.0));
                    let along = u * g * q / (1.0 - nu);
                    let coupling = -w * g * q;
                    assert!(
                        (f.along / along - 1.0).abs() < 1e-9,
                        "{base:?} nu {nu} q {q}: {f:?} {along}"
                    );
                    assert!(
                        (f.coupling - coupling).abs() < 1e-9 * f.coupling.abs().max(1e-3),
                        "{base:?} nu {nu} q {q}: {f:?} {coupling}"
                    );
                    // The pressure's tangential displacement: C_Lz = i U_p / p and C_zL = W / (i t),
                    // and Betti's C_Lz = -C_zL is U_p = W.
                    let (u_p, _) = navier_surface(q, nu, base, (1.0, 0.0));
                    assert!(
                        (u_p - w).abs() < 1e-9 * w.abs().max(1e-6),
                        "{base:?} nu {nu} q {q}"
                    );
                }
            }
        }
    }

    /// A coating on its own material shears as the half-space; on a substrate 1e9 times
    /// stiffer, as the bonded layer (across the wave too).
    #[test]
    fn a_coating_shears_as_the_half_space_or_the_bonded_layer() {
        for nu in [0.0, 0.3, 0.45] {
            let coating = |e_star: f64| Layer::new(1.0, nu, Base::Substrate { e_star, poisson: nu }).unwrap();
            let bonded = Layer::new(1.0, nu, Base::Bonded).unwrap();
            for x in [0.05, 0.5, 2.0, 20.0] {
                let same = coating(1.0).shear_factors(x, 1.0);
                assert!(
                    (same.along - 1.0).abs() < 1e-12 && (same.across - 1.0).abs() < 1e-12,
                    "{same:?}"
                );
                assert!(
                    (same.coupling + (1.0 - 2.0 * nu) / 2.0).abs() < 1e-12,
                    "nu {nu} x {x}: {same:?}"
                );
                let (hard, want) = (coating(1e9).shear_factors(x, 1.0), bonded.shear_factors(x, 1.0));
                for (got, want) in [
                    (hard.along, want.along),
                    (hard.across, want.across),
                    (hard.coupling, want.coupling),
                ] {
                    assert!(
                        (got - want).abs() < 1e-5 * want.abs().max(1e-3),
                        "nu {nu} x {x}: {hard:?} {want:?}"
                    );
                }
            }
        }
    }

    /// Thin layers: bonded, simple shear (`h / G` along and across the wave); on a frictionless
    /// base, a membrane (along: `(1 - nu) / (2 G q^2 h)`, the in-plane stiffness `E h / (1 -
    /// nu^2)`; across: `1 / (G q^2 h)`). Thick ones: the half-space, without overflow.
    #[test]
    fn thin_layers_shear_as_a_film_and_thick_ones_as_the_half_space() {
        let nu = 0.3;
        let x = 1e-3;
        let at = |base: Base, x: f64| {
            let l = layer(nu, base);
            l.shear_factors(x / l.thickness, E_STAR)
        };
        let bonded = at(Base::Bonded, x);
        // C q G = (1 - nu) r_LL = x and r_TT = x at leading order.
        assert!(((1.0 - nu) * bonded.along / x - 1.0).abs() < 1e-5 && (bonded.across / x - 1.0).abs() < 1e-6);
        let frictionless = at(Base::Frictionless, x);
        assert!(
            (frictionless.along * 2.0 * x - 1.0).abs() < 1e-5,
            "{frictionless:?}"
        );
        assert!((frictionless.across * x - 1.0).abs() < 1e-6);
        for base in [Base::Bonded, Base::Frictionless] {
            for x in [40.0, 400.0, 4e5] {
                let f = at(base, x);
                assert!((f.along - 1.0).abs() < 1e-15 && (f.across - 1.0).abs() < 1e-15);
                assert!(
                    (f.coupling + (1.0 - 2.0 * nu) / 2.0).abs() < 1e-15,
                    "{base:?} {x}: {f:?}"
                );
            }
        }
    }

    #[test]
    fn the_factors_solve_navier_s_equations_through_the_layer() {
        for base in [Base::Bonded, Base::Frictionless] {
            for nu in [0.0, 0.3, 0.45] {
                let l = Layer::new(1.0, nu, base).unwrap();
                for q in [0.1, 0.5, 1.0, 2.0] {
                    let e_star = 1.0 / (1.0 - nu * nu);
                    let (got, want) = (l.compliance(q, e_star), navier(q, nu, base));
                    assert!(
                        (got / want - 1.0).abs() < 1e-10,
                        "{base:?} nu {nu} q {q}: {got} {want}"
                    );
                }
            }
        }
    }

    #[test]
    fn a_thick_layer_is_the_half_space_and_nothing_overflows() {
        for base in [Base::Bonded, Base::Frictionless] {
            for nu in [0.0, 0.3, 0.5] {
                let l = layer(nu, base);
                for x in [40.0, 400.0, 4e5] {
                    let r = l.compliance_ratio(x / l.thickness, E_STAR);
                    assert!((r - 1.0).abs() < 1e-15, "{base:?} nu {nu} x {x}: {r}");
                }
            }
        }
    }

    #[test]
    fn the_mean_mode_is_the_thin_layers_compliance_and_the_limit_of_the_modes() {
        // Bonded: h / M, M = E* (1 - nu)^2 / (1 - 2 nu); frictionless: h / E*.
        let h = 1e-6;
        let bonded = layer(0.3, Base::Bonded);
        let m = E_STAR * 0.7 * 0.7 / 0.4;
        assert!((bonded.compliance(0.0, E_STAR) / (h / m) - 1.0).abs() < 1e-15);
        let frictionless = layer(0.3, Base::Frictionless);
        assert!((frictionless.compliance(0.0, E_STAR) / (h / E_STAR) - 1.0).abs() < 1e-15);
        for l in [bonded, frictionless] {
            let at_zero = l.compliance(0.0, E_STAR);
            let small = l.compliance(1e-7 / h, E_STAR);
            assert!((small / at_zero - 1.0).abs() < 1e-6, "{l:?}: {small} {at_zero}");
        }
        // Incompressible and bonded: no mean mode, and C -> 4 q^2 h^3 / (3 E*) (2 x^3 / 3 of
        // the half-space's).
        let incompressible = layer(0.5, Base::Bonded);
        assert_eq!(incompressible.compliance(0.0, E_STAR), 0.0);
        let x = 1e-3;
        let r = incompressible.compliance_ratio(x / h, E_STAR);
        assert!((r / (2.0 * x * x * x / 3.0) - 1.0).abs() < 1e-5, "{r}");
    }

    #[test]
    fn the_layer_is_stiffer_than_the_half_space_the_more_the_longer_the_wave() {
        for base in [Base::Bonded, Base::Frictionless] {
            let l = layer(0.3, base);
            let mut last = 0.0;
            for k in 1..200 {
                let r = l.compliance_ratio(k as f64 * 0.05 / l.thickness, E_STAR);
                assert!(r > last && r <= 1.0, "{base:?} x {}: {r}", k as f64 * 0.05);
                last = r;
            }
        }
    }

    #[test]
    fn a_coating_on_its_own_material_is_the_half_space_and_on_a_rigid_one_the_bonded_layer() {
        for nu in [0.0, 0.3, 0.45] {
            let same = layer(
                nu,
                Base::Substrate {
                    e_star: E_STAR,
                    poisson: nu,
                },
            );
            let stiff = layer(
                nu,
                Base::Substrate {
                    e_star: 1e6 * E_STAR,
                    poisson: 0.2,
                },
            );
            let bonded = layer(nu, Base::Bonded);
            for x in [1e-3, 0.01, 0.1, 0.5, 1.0, 3.0, 10.0, 30.0, 400.0] {
                let q = x / same.thickness;
                let r = same.compliance_ratio(q, E_STAR);
                assert!((r - 1.0).abs() < 1e-13, "nu {nu} x {x}: {r}");
                // A substrate a million times stiffer gives way by ~1e-6 of the layer.
                let (got, want) = (
                    stiff.compliance_ratio(q, E_STAR),
                    bonded.compliance_ratio(q, E_STAR),
                );
                assert!(
                    (got / want - 1.0).abs() < 2e-5 / (x * x).min(1.0),
                    "nu {nu} x {x}: {got} {want}"
                );
            }
        }
        // Long waves see the substrate, short ones the coating.
        let soft = layer(
            0.3,
            Base::Substrate {
                e_star: 0.1 * E_STAR,
                poisson: 0.4,
            },
        );
        assert!((soft.compliance_ratio(1e-6 / soft.thickness, E_STAR) / 10.0 - 1.0).abs() < 1e-4);
        assert!((soft.compliance_ratio(40.0 / soft.thickness, E_STAR) - 1.0).abs() < 1e-12);
        assert_eq!(soft.mean_compliance(E_STAR), None);
    }

    #[test]
    fn bad_layers_are_refused_by_name() {
        for h in [0.0, -1e-6, f64::NAN, f64::INFINITY] {
            let e = Layer::new(h, 0.3, Base::Bonded).unwrap_err();
            assert!(e.to_string().contains("thickness"), "{e}");
        }
        for nu in [-1.0, 0.51, f64::NAN] {
            let e = Layer::new(1e-6, nu, Base::Frictionless).unwrap_err();
            assert!(e.to_string().contains("poisson"), "{e}");
        }
        for e_star in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            let e = Layer::new(1e-6, 0.3, Base::Substrate { e_star, poisson: 0.3 }).unwrap_err();
            assert!(e.to_string().contains("substrate_modulus"), "{e}");
        }
        let e = Layer::new(
            1e-6,
            0.3,
            Base::Substrate {
                e_star: 1e9,
                poisson: 0.5,
            },
        )
        .unwrap_err();
        assert!(
            e.to_string().contains("substrate_poisson") && e.to_string().contains("0.5"),
            "{e}"
        );
        let e = Layer::new(
            1e-6,
            0.5,
            Base::Substrate {
                e_star: 1e9,
                poisson: 0.3,
            },
        )
        .unwrap_err();
        assert!(e.to_string().contains("poisson"), "{e}");
    }
}
