//! The tangential surface compliance of an isotropic elastic half-space (Cerruti's problem):
//! shear tractions `(q_x, q_y)` \[Pa\] uniform over each cell to the tangential surface
//! displacements `(u_x, u_y)` \[m\], both in the direction the traction acts on the body
//! (docs/method.md section 14).
//!
//! A point force `Q_x` on the surface of a half-space of shear modulus `G` and Poisson's
//! ratio `nu` displaces it by (Johnson 1985, Eq. 3.86)
//! `u_x = Q_x / (2 pi G) [(1 - nu) / r + nu x^2 / r^3]`, `u_y = Q_x / (2 pi G) nu x y / r^3`,
//! and by the same in `y` for `Q_y`; in Fourier space the multipliers are
//! `(1 - nu qx^2/q^2) / (G q)`, `(1 - nu qy^2/q^2) / (G q)` and `-nu qx qy / (G q^3)`.
//!
//! Unless `nu = 1/2`, normal and tangential loads are coupled (Johnson 1985, Eqs. 3.19 and
//! 3.86): the shear moves the surface into the body by `u_z = (1 - 2 nu)/(4 pi G) Q_x x / r^2`,
//! and a compressive point load `P` moves it inwards, `u_x = -(1 - 2 nu)/(4 pi G) P x / r^2`;
//! in Fourier space the multiplier `-i (1 - 2 nu) qx / (2 G q^2)` and its negative
//! ([`Shear::coupled_normal`], [`Shear::coupled_tangential`]). Between bodies of like materials
//! the coupling cancels; against a rigid counterface it does not.
//!
//! As the normal operators: [`Shear`] is periodic (the mean mode, which a uniform shear moves
//! without bound, is left out: displacements are measured from the mean surface) or free
//! (exact cell integrals of the point kernel, applied by DC-FFT on a zero-padded grid).

use crate::error::{ElasticError, Result};
use crate::layer::ShearFactors;
use crate::love::cell_influence;
use crate::material::check_poisson;
use crate::operators::wavevector;
use crate::{Body, Compliance, Domain};
use fft2::{Complex64, Fft2, Workspace as FftWorkspace};
use ndarray::{Array2, ArrayView2, ArrayViewMut2, Zip};
use rayon::prelude::*;
use std::f64::consts::PI;

/// The tangential compliance of a half-space on a grid (periodic or free).
#[derive(Clone)]
pub struct Shear {
    domain: Domain,
    shear_modulus: f64,
    poisson: f64,
    fft: Fft2,
    /// The multipliers `xx`, `yy`, `xy` on the transform grid (transposed half layout), divided
    /// by the grid's number of points.
    kernels: [Array2<f64>; 3],
    /// The diagonal: a cell's displacement along x and along y under a unit traction on itself
    /// along the same axis \[m/Pa\].
    cell: [f64; 2],
    /// The coupling's multipliers `m_x`, `m_y` (layout of `kernels`; `None` at `nu = 1/2`):
    /// `u_z = i (m_x q_x + m_y q_y)` and `u_c = -i m_c p` in Fourier space.
    coupling: Option<[Array2<f64>; 2]>,
}

/// Buffers for [`Shear::apply`]: one per concurrent caller.
pub struct ShearWorkspace([FftWorkspace; 2]);

impl Shear {
    /// The half-space of shear modulus `shear_modulus` \[Pa\] and Poisson's ratio `poisson` on
    /// `domain`. Plans and kernels are made once here.
    ///
    /// # Errors
    /// A bad domain, a shear modulus that is not finite and positive, a Poisson's ratio
    /// outside `(-1, 0.5]`.
    pub fn new(domain: Domain, shear_modulus: f64, poisson: f64) -> Result<Self> {
        Shear::with_body(domain, shear_modulus, poisson, Body::HalfSpace)
    }

    /// The tangential compliance of `body` of shear modulus `shear_modulus` \[Pa\] and Poisson's
    /// ratio `poisson` on `domain`: the half-space on either grid, a layer on periodic grids.
    ///
    /// # Errors
    /// As [`Shear::new`]; [`ElasticError::Unsupported`] for a layer on a free grid, whose
    /// tangential kernels are not derived.
    pub fn with_body(domain: Domain, shear_modulus: f64, poisson: f64, body: Body) -> Result<Self> {
        Shear::supports(body, domain.periodic)?;
        if !(shear_modulus.is_finite() && shear_modulus > 0.0) {
            return Err(ElasticError::InvalidParameter {
                name: "shear_modulus",
                value: shear_modulus,
                reason: "must be finite and > 0 Pa",
            });
        }
        check_poisson("poisson_ratio", poisson)?;
        domain.validate()?;
        let (a, b) = (domain.dx / 2.0, domain.dy / 2.0);
        let scale = 1.0 / (2.0 * PI * shear_modulus);
        let cell = [
            scale
                * ((1.0 - poisson) * cell_integral(Kernel::One, 0.0, 0.0, a, b)
                    + poisson * cell_integral(Kernel::Xx, 0.0, 0.0, a, b)),
            scale
                * ((1.0 - poisson) * cell_integral(Kernel::One, 0.0, 0.0, a, b)
                    + poisson * cell_integral(Kernel::Yy, 0.0, 0.0, a, b)),
        ];
        let factors = |q: f64| match body {
            Body::HalfSpace => ShearFactors {
                along: 1.0,
                across: 1.0,
                coupling: -(1.0 - 2.0 * poisson) / 2.0,
            },
            Body::Layer(layer) => layer.shear_factors(q, 2.0 * shear_modulus / (1.0 - poisson)),
        };
        let (fft, kernels) = if domain.periodic {
            let mean = match body {
                Body::HalfSpace => None,
                Body::Layer(layer) => layer.mean_shear_compliance(shear_modulus),
            };
            periodic_kernels(&domain, shear_modulus, poisson, &factors, mean)
        } else {
            free_kernels(&domain, scale, poisson)
        };
        // The half-space's coupling vanishes at nu = 1/2; a layer's, held by its base, does not.
        let coupling = (poisson < 0.5 || body != Body::HalfSpace).then(|| {
            if domain.periodic {
                periodic_coupling(&domain, shear_modulus, &factors)
            } else {
                free_coupling(&domain, &fft, shear_modulus, poisson)
            }
        });
        let mut shear = Shear {
            domain,
            shear_modulus,
            poisson,
            fft,
            kernels,
            cell,
            coupling,
        };
        if body != Body::HalfSpace {
            // A layer's diagonal: the periodic operator's own, from a unit traction.
            let shape = domain.shape();
            let mut unit = Array2::zeros(shape);
            unit[(0, 0)] = 1.0;
            let (zero, mut ux, mut uy) = (Array2::zeros(shape), Array2::zeros(shape), Array2::zeros(shape));
            let mut ws = shear.make_workspace();
            shear.apply(
                [unit.view(), zero.view()],
                [ux.view_mut(), uy.view_mut()],
                &mut ws,
            )?;
            shear.cell[0] = ux[(0, 0)];
            shear.apply(
                [zero.view(), unit.view()],
                [ux.view_mut(), uy.view_mut()],
                &mut ws,
            )?;
            shear.cell[1] = uy[(0, 0)];
        }
        Ok(shear)
    }

    /// Refuses a body whose tangential compliance is not derived on this kind of grid.
    ///
    /// # Errors
    /// [`ElasticError::Unsupported`] for a layer on a free grid.
    pub fn supports(body: Body, periodic: bool) -> Result<()> {
        match body {
            Body::HalfSpace => Ok(()),
            Body::Layer(_) if !periodic => Err(ElasticError::Unsupported(
                "a layer's tangential compliance is implemented on periodic grids only: a \
                 tangential path on a free grid takes the half-space",
            )),
            Body::Layer(_) => Ok(()),
        }
    }

    /// The tangential compliance of the body whose normal operator is `normal` (of
    /// plane-strain modulus `E*`) and whose Poisson's ratio is `poisson` (a layer's own),
    /// against a rigid counterface: `G = E* (1 - nu) / 2`.
    ///
    /// # Errors
    /// As [`Shear::with_body`]; a Poisson's ratio other than a layer's own.
    pub fn of(normal: &dyn Compliance, poisson: f64) -> Result<Self> {
        check_poisson("poisson_ratio", poisson)?;
        let body = normal.body();
        if let Body::Layer(layer) = body
            && layer.poisson != poisson
        {
            return Err(ElasticError::InvalidParameter {
                name: "poisson_ratio",
                value: poisson,
                reason: "must be the layer's own",
            });
        }
        Shear::with_body(
            *normal.domain(),
            normal.e_star() * (1.0 - poisson) / 2.0,
            poisson,
            body,
        )
    }

    /// The grid.
    pub fn domain(&self) -> &Domain {
        &self.domain
    }

    /// Shear modulus G \[Pa\].
    pub fn shear_modulus(&self) -> f64 {
        self.shear_modulus
    }

    /// Poisson's ratio [-].
    pub fn poisson(&self) -> f64 {
        self.poisson
    }

    /// A cell's displacement along x and along y under a unit traction \[Pa\] on itself along
    /// the same axis \[m/Pa\].
    pub fn cell_compliance(&self) -> [f64; 2] {
        self.cell
    }

    /// Buffers for [`Shear::apply`].
    pub fn make_workspace(&self) -> ShearWorkspace {
        ShearWorkspace([self.fft.make_workspace(), self.fft.make_workspace()])
    }

    /// Writes the tangential displacements \[m\] `(u_x, u_y)` under the shear tractions
    /// `(q_x, q_y)` \[Pa\]: two forward and two inverse transforms.
    ///
    /// # Errors
    /// [`ElasticError::ShapeMismatch`] if a field is not `(ny, nx)`.
    pub fn apply(
        &self,
        traction: [ArrayView2<f64>; 2],
        displacement: [ArrayViewMut2<f64>; 2],
        ws: &mut ShearWorkspace,
    ) -> Result<()> {
        self.check_shapes(&[
            ("traction x", traction[0].dim()),
            ("traction y", traction[1].dim()),
            ("displacement x", displacement[0].dim()),
            ("displacement y", displacement[1].dim()),
        ])?;
        let [wx, wy] = &mut ws.0;
        self.fft.forward_into(traction[0], wx);
        self.fft.forward_into(traction[1], wy);
        let [kxx, kyy, kxy] = &self.kernels;
        Zip::from(wx.spectrum_mut())
            .and(wy.spectrum_mut())
            .and(kxx)
            .and(kyy)
            .and(kxy)
            .par_for_each(|x, y, &xx, &yy, &xy| {
                let (tx, ty): (Complex64, Complex64) = (*x, *y);
                *x = tx * xx + ty * xy;
                *y = tx * xy + ty * yy;
            });
        let [ux, uy] = displacement;
        self.fft.inverse_into(wx, ux, 1.0);
        self.fft.inverse_into(wy, uy, 1.0);
        Ok(())
    }

    /// Whether pressure and shear are coupled (a half-space's for `nu < 1/2`, a layer's always).
    pub fn coupled(&self) -> bool {
        self.coupling.is_some()
    }

    /// Writes the normal displacement \[m\] (into the body, as a compressive pressure's) under the
    /// shear tractions `(q_x, q_y)` \[Pa\]; zero at `nu = 1/2`. On periodic grids relative to
    /// its mean.
    ///
    /// # Errors
    /// [`ElasticError::ShapeMismatch`] if a field is not `(ny, nx)`.
    pub fn coupled_normal(
        &self,
        traction: [ArrayView2<f64>; 2],
        mut normal: ArrayViewMut2<f64>,
        ws: &mut ShearWorkspace,
    ) -> Result<()> {
        self.check_shapes(&[
            ("traction x", traction[0].dim()),
            ("traction y", traction[1].dim()),
            ("normal displacement", normal.dim()),
        ])?;
        let Some([mx, my]) = &self.coupling else {
            normal.fill(0.0);
            return Ok(());
        };
        let [wx, wy] = &mut ws.0;
        self.fft.forward_into(traction[0], wx);
        self.fft.forward_into(traction[1], wy);
        Zip::from(wx.spectrum_mut())
            .and(wy.spectrum())
            .and(mx)
            .and(my)
            .par_for_each(|x, &y, &a, &b| *x = Complex64::i() * (*x * a + y * b));
        self.fft.inverse_into(wx, normal, 1.0);
        Ok(())
    }

    /// Writes the tangential displacements \[m\] `(u_x, u_y)` under the compressive pressure
    /// \[Pa\] (inwards, towards where it presses); zero at `nu = 1/2`. On periodic grids relative
    /// to their means.
    ///
    /// # Errors
    /// [`ElasticError::ShapeMismatch`] if a field is not `(ny, nx)`.
    pub fn coupled_tangential(
        &self,
        pressure: ArrayView2<f64>,
        displacement: [ArrayViewMut2<f64>; 2],
        ws: &mut ShearWorkspace,
    ) -> Result<()> {
        self.check_shapes(&[
            ("pressure", pressure.dim()),
            ("displacement x", displacement[0].dim()),
            ("displacement y", displacement[1].dim()),
        ])?;
        let [mut ux, mut uy] = displacement;
        let Some([mx, my]) = &self.coupling else {
            ux.fill(0.0);
            uy.fill(0.0);
            return Ok(());
        };
        let [wx, wy] = &mut ws.0;
        self.fft.forward_into(pressure, wx);
        Zip::from(wx.spectrum_mut())
            .and(wy.spectrum_mut())
            .and(mx)
            .and(my)
            .par_for_each(|x, y, &a, &b| {
                let p = -Complex64::i() * *x;
                (*x, *y) = (p * a, p * b);
            });
        self.fft.inverse_into(wx, ux, 1.0);
        self.fft.inverse_into(wy, uy, 1.0);
        Ok(())
    }

    fn check_shapes(&self, fields: &[(&'static str, (usize, usize))]) -> Result<()> {
        let shape = self.domain.shape();
        match fields.iter().find(|(_, got)| *got != shape) {
            Some(&(what, got)) => Err(ElasticError::ShapeMismatch {
                what,
                expected: shape,
                got,
            }),
            None => Ok(()),
        }
    }

    /// Elastic energy `(1/2) sum q . u dx dy` \[J\] stored by `traction`, given its displacement.
    pub fn energy(&self, traction: [ArrayView2<f64>; 2], displacement: [ArrayView2<f64>; 2]) -> f64 {
        let mut sum = 0.0;
        for (q, u) in traction.iter().zip(&displacement) {
            Zip::from(q).and(u).for_each(|q, u| sum += q * u);
        }
        0.5 * sum * self.domain.cell_area()
    }
}

/// The point kernels integrated over a cell: `1/r`, `x^2/r^3`, `y^2/r^3` and `x y/r^3`; the
/// coupling's `x/r^2` and `y/r^2`.
#[derive(Clone, Copy)]
enum Kernel {
    One,
    Xx,
    Yy,
    Xy,
    X,
    Y,
}

/// `x ln(y + r)`, vanishing with `x`, and evaluated without cancellation for `y <= 0` (as in
/// Love's solution).
fn x_log(x: f64, y: f64) -> f64 {
    if x == 0.0 {
        return 0.0;
    }
    let r = x.hypot(y);
    x * if y > 0.0 {
        (y + r).ln()
    } else {
        (x * x / (r - y)).ln()
    }
}

/// `x atan(y/x) + (y/2) ln(x^2 + y^2)`, whose mixed derivative is `x / (x^2 + y^2)`; its limits
/// on the axes.
fn x_atan(x: f64, y: f64) -> f64 {
    let r2 = x * x + y * y;
    let along = if x == 0.0 { 0.0 } else { x * (y / x).atan() };
    let log = if y == 0.0 { 0.0 } else { 0.5 * y * r2.ln() };
    along + log
}

/// Distance in half-sides beyond which [`cell_integral`] integrates by Gauss quadrature: the
/// closed forms subtract terms of order `r` to get `a b / r`, the 3-point rule errs by about
/// `(a / r)^6`; both are near 1e-11 here.
const FAR: f64 = 64.0;

/// `int int f(x - x', y - y') dx' dy'` over the cell `|x'| <= a`, `|y'| <= b` \[m\]: the closed
/// forms `F(s, t)` with `d^2 F / ds dt = f` summed over the corners near the cell, Gauss
/// quadrature far from it.
fn cell_integral(kernel: Kernel, x: f64, y: f64, a: f64, b: f64) -> f64 {
    if let Kernel::One = kernel {
        // Love's `p / (pi E*)` times this integral.
        return PI * cell_influence(x, y, a, b, 1.0);
    }
    if x * x + y * y >= (FAR * a.max(b)).powi(2) {
        const NODES: [f64; 3] = [-0.774_596_669_241_483_4, 0.0, 0.774_596_669_241_483_4];
        const WEIGHTS: [f64; 3] = [5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0];
        let mut sum = 0.0;
        for (u, wu) in NODES.iter().zip(WEIGHTS) {
            for (v, wv) in NODES.iter().zip(WEIGHTS) {
                let (s, t) = (x - u * a, y - v * b);
                let r = s.hypot(t);
                let f = match kernel {
                    Kernel::Xx => s * s / r,
                    Kernel::Yy => t * t / r,
                    Kernel::X => s,
                    Kernel::Y => t,
                    _ => s * t / r,
                } / (r * r);
                sum += wu * wv * f;
            }
        }
        return sum * a * b;
    }
    let corner = |s: f64, t: f64| match kernel {
        Kernel::Xx => x_log(t, s),
        Kernel::Yy => x_log(s, t),
        Kernel::X => x_atan(s, t),
        Kernel::Y => x_atan(t, s),
        _ => -s.hypot(t),
    };
    corner(x + a, y + b) - corner(x + a, y - b) - corner(x - a, y + b) + corner(x - a, y - b)
}

/// The periodic multipliers of a body of `factors` ([`ShearFactors`]): along the wave
/// `(1 - nu) r_LL / (G q)`, across it `r_TT / (G q)`, so `xx = (C_LL qx^2 + C_TT qy^2) / q^2`
/// and `xy = (C_LL - C_TT) qx qy / q^2`; the mean mode `mean` \[m/Pa\] (a bonded layer's) or
/// left out.
fn periodic_kernels(
    domain: &Domain,
    g: f64,
    nu: f64,
    factors: &dyn Fn(f64) -> ShearFactors,
    mean: Option<f64>,
) -> (Fft2, [Array2<f64>; 3]) {
    let Domain { nx, ny, dx, dy, .. } = *domain;
    let (lx, ly) = (nx as f64 * dx, ny as f64 * dy);
    let scale = 1.0 / (nx * ny) as f64;
    let make = |which: usize| {
        Array2::from_shape_fn((nx / 2 + 1, ny), |(kx, ky)| {
            let (qx, qy) = (wavevector(kx, nx, lx), wavevector(ky, ny, ly));
            let q = qx.hypot(qy);
            if q == 0.0 {
                return if which < 2 {
                    scale * mean.unwrap_or(0.0)
                } else {
                    0.0
                };
            }
            let f = factors(q);
            let (along, across) = ((1.0 - nu) * f.along, f.across);
            let c = scale / (g * q * q * q);
            match which {
                0 => c * (along * qx * qx + across * qy * qy),
                1 => c * (along * qy * qy + across * qx * qx),
                // At a Nyquist index `+q` and `-q` are one mode: the odd coupling averages out.
                _ if 2 * kx == nx || 2 * ky == ny => 0.0,
                _ => c * (along - across) * qx * qy,
            }
        })
    };
    (Fft2::new(nx, ny), [make(0), make(1), make(2)])
}

fn free_kernels(domain: &Domain, scale: f64, nu: f64) -> (Fft2, [Array2<f64>; 3]) {
    let Domain { nx, ny, dx, dy, .. } = *domain;
    let (a, b) = (dx / 2.0, dy / 2.0);
    let (mx, my) = (2 * nx, 2 * ny);
    let fft = Fft2::new(mx, my);
    // Offsets 0..=n along each axis; the padded grid's wrap folds the rest back by symmetry
    // (even for xx and yy, odd in both for xy, which vanishes at the padding's Nyquist offset n).
    let quadrant = |kernel: Kernel| -> Vec<f64> {
        (0..(ny + 1) * (nx + 1))
            .into_par_iter()
            .map(|k| {
                let (j, i) = (k / (nx + 1), k % (nx + 1));
                cell_integral(kernel, i as f64 * dx, j as f64 * dy, a, b)
            })
            .collect()
    };
    let (one, xx, yy, xy) = (
        quadrant(Kernel::One),
        quadrant(Kernel::Xx),
        quadrant(Kernel::Yy),
        quadrant(Kernel::Xy),
    );
    let fold = |k: usize, n: usize| if k <= n { (k, 1.0) } else { (2 * n - k, -1.0) };
    let mut ws = fft.make_workspace();
    let spectrum = |value: &(dyn Fn(usize) -> f64 + Sync), odd: bool, ws: &mut FftWorkspace| {
        let row = |j: usize, out: &mut [f64]| {
            let (jj, sy) = fold(j, ny);
            out.iter_mut().enumerate().for_each(|(i, o)| {
                let (ii, sx) = fold(i, nx);
                *o = if !odd {
                    value(jj * (nx + 1) + ii)
                } else if ii == nx || jj == ny {
                    0.0
                } else {
                    sx * sy * value(jj * (nx + 1) + ii)
                };
            });
        };
        fft.real_spectrum(row, ws).mapv(|k| k * scale / (mx * my) as f64)
    };
    let kxx = spectrum(&|k| (1.0 - nu) * one[k] + nu * xx[k], false, &mut ws);
    let kyy = spectrum(&|k| (1.0 - nu) * one[k] + nu * yy[k], false, &mut ws);
    let kxy = spectrum(&|k| nu * xy[k], true, &mut ws);
    (fft, [kxx, kyy, kxy])
}

/// The coupling's multipliers on a periodic grid: `m_x = c_zL qx / (G q^2)` (the half-space's
/// `-(1 - 2 nu) qx / (2 G q^2)`), zero at the mean and, along its own axis, at the Nyquist
/// index (where `+q` and `-q` are one mode and the odd kernel averages out).
fn periodic_coupling(domain: &Domain, g: f64, factors: &dyn Fn(f64) -> ShearFactors) -> [Array2<f64>; 2] {
    let Domain { nx, ny, dx, dy, .. } = *domain;
    let (lx, ly) = (nx as f64 * dx, ny as f64 * dy);
    let c = 1.0 / (g * (nx * ny) as f64);
    let make = |along_x: bool| {
        Array2::from_shape_fn((nx / 2 + 1, ny), |(kx, ky)| {
            let (qx, qy) = (wavevector(kx, nx, lx), wavevector(ky, ny, ly));
            let q2 = qx * qx + qy * qy;
            let nyquist = if along_x { 2 * kx == nx } else { 2 * ky == ny };
            if q2 == 0.0 || nyquist {
                0.0
            } else {
                c * factors(q2.sqrt()).coupling * if along_x { qx } else { qy } / q2
            }
        })
    };
    [make(true), make(false)]
}

/// The coupling's multipliers on a free grid: the imaginary spectra of the cell integrals of
/// `(1 - 2 nu)/(4 pi G) x / r^2` and `... y / r^2`, odd along their own axis.
fn free_coupling(domain: &Domain, fft: &Fft2, g: f64, nu: f64) -> [Array2<f64>; 2] {
    let Domain { nx, ny, dx, dy, .. } = *domain;
    let (a, b) = (dx / 2.0, dy / 2.0);
    let (mx, my) = fft.shape();
    let scale = (1.0 - 2.0 * nu) / (4.0 * PI * g) / (mx * my) as f64;
    let fold = |k: usize, n: usize| if k <= n { (k, 1.0) } else { (2 * n - k, -1.0) };
    let mut ws = fft.make_workspace();
    let mut make = |kernel: Kernel, along_x: bool| {
        let values: Vec<f64> = (0..(ny + 1) * (nx + 1))
            .into_par_iter()
            .map(|k| {
                let (j, i) = (k / (nx + 1), k % (nx + 1));
                cell_integral(kernel, i as f64 * dx, j as f64 * dy, a, b)
            })
            .collect();
        let row = |j: usize, out: &mut [f64]| {
            let (jj, sy) = fold(j, ny);
            out.iter_mut().enumerate().for_each(|(i, o)| {
                let (ii, sx) = fold(i, nx);
                let (nyquist, sign) = if along_x { (ii == nx, sx) } else { (jj == ny, sy) };
                *o = if nyquist {
                    0.0
                } else {
                    sign * values[jj * (nx + 1) + ii]
                };
            });
        };
        fft.imaginary_spectrum(row, &mut ws).mapv(|m| m * scale)
    };
    [make(Kernel::X, true), make(Kernel::Y, false)]
}
