//! The two operators of a body: periodic (spectral) and free (influence coefficients +
//! DC-FFT).

use crate::body::Body;
use crate::convolution::{ConvWorkspace, Convolution};
use crate::error::{ElasticError, Result};
use crate::material::check_modulus;
use crate::{Compliance, Domain};
use ndarray::{Array2, ArrayView2, ArrayViewMut2};
use rayon::prelude::*;
use std::f64::consts::PI;

/// Buffers owned by the caller of [`Compliance::apply`]: one per concurrent caller.
pub struct Workspace(ConvWorkspace);

impl Workspace {
    /// Bytes held (the spectrum plus per-thread scratch).
    pub fn bytes(&self) -> usize {
        self.0.bytes()
    }
}

fn check(what: &'static str, expected: (usize, usize), got: (usize, usize)) -> Result<()> {
    if expected == got {
        Ok(())
    } else {
        Err(ElasticError::ShapeMismatch { what, expected, got })
    }
}

/// Wavevector [rad/m] of DFT index `k` on an axis of `n` points spanning `l` metres.
pub(crate) fn wavevector(k: usize, n: usize, l: f64) -> f64 {
    let signed = if k <= n / 2 { k as f64 } else { k as f64 - n as f64 };
    2.0 * PI * signed / l
}

/// The periodic body: `u(q) = 2 p(q) R(q) / (E* |q|)` for `q != 0`, `R` the body's factor
/// ([`Body::compliance_ratio`], 1 for the half-space); the mean displacement is left out
/// (`q = 0` carries the load, which a periodic half-space cannot displace by a finite amount,
/// and a layer displaces by [`Compliance::mean_compliance`] times the mean pressure), so `u` is
/// the displacement relative to its mean.
#[derive(Clone)]
pub struct Periodic {
    domain: Domain,
    e_star: f64,
    body: Body,
    cell: f64,
    conv: Convolution,
}

impl Periodic {
    /// The half-space on `domain` (its `periodic` flag must be set) for composite modulus
    /// `e_star` \[Pa\]. Plans are made once here.
    pub fn new(domain: Domain, e_star: f64) -> Result<Self> {
        Periodic::with_body(domain, e_star, Body::HalfSpace)
    }

    /// The operator of `body` (of plane-strain modulus `e_star` \[Pa\]) on `domain`.
    pub fn with_body(domain: Domain, e_star: f64, body: Body) -> Result<Self> {
        let e_star = check_modulus(e_star)?;
        domain.validate()?;
        let Domain { nx, ny, .. } = domain;
        let kernel = periodic_multiplier(&domain, |q| {
            if q == 0.0 {
                0.0
            } else {
                2.0 / (e_star * q) * body.compliance_ratio(q, e_star)
            }
        });
        // The circulant's diagonal, the mean of the multiplier over the grid, mean mode included
        // (the half-space keeps Love's self-coefficient). The half layout holds the columns
        // kx = 1 .. (nx - 1) / 2 for their mirror images too.
        let cell = match body {
            Body::HalfSpace => domain.cell_compliance(e_star),
            Body::Layer(_) => {
                let total: f64 = kernel
                    .outer_iter()
                    .enumerate()
                    .map(|(kx, row)| {
                        let copies = if kx > 0 && 2 * kx < nx { 2.0 } else { 1.0 };
                        copies * row.sum()
                    })
                    .sum();
                (total + body.mean_compliance(e_star).unwrap_or(0.0)) / (nx * ny) as f64
            }
        };
        Ok(Periodic {
            domain: Domain {
                periodic: true,
                ..domain
            },
            e_star,
            body,
            cell,
            conv: Convolution::new(nx, ny, kernel, (ny, nx), (ny, nx)),
        })
    }
}

/// `f(|q|)` on the periodic transform grid of `domain` (transposed half layout).
fn periodic_multiplier(domain: &Domain, f: impl Fn(f64) -> f64) -> Array2<f64> {
    let Domain { nx, ny, dx, dy, .. } = *domain;
    let (lx, ly) = (nx as f64 * dx, ny as f64 * dy);
    Array2::from_shape_fn((nx / 2 + 1, ny), |(kx, ky)| {
        f(wavevector(kx, nx, lx).hypot(wavevector(ky, ny, ly)))
    })
}

/// The periodic body's stiffness: the inverse of [`Periodic`] on fields of zero mean,
/// `p(q) = E* |q| u(q) / (2 R(q))` for `q != 0`; the mean of `u` is ignored and the pressure comes out
/// with zero mean (the mean pressure is the load, which the displacement's fluctuations do not
/// fix). For solvers whose unknown is the displacement or the gap rather than the pressure.
pub struct PeriodicStiffness {
    domain: Domain,
    conv: Convolution,
    /// Its inverse on fields of zero mean: [`Periodic`]'s multiplier, zero at `q = 0`.
    inverse: Convolution,
}

impl PeriodicStiffness {
    /// The half-space's on the periodic `domain` for composite modulus `e_star` \[Pa\].
    pub fn new(domain: Domain, e_star: f64) -> Result<Self> {
        PeriodicStiffness::with_body(domain, e_star, Body::HalfSpace)
    }

    /// The stiffness of `body` (of plane-strain modulus `e_star` \[Pa\]) on `domain`.
    pub fn with_body(domain: Domain, e_star: f64, body: Body) -> Result<Self> {
        PeriodicStiffness::of(&Periodic::with_body(domain, e_star, body)?)
    }

    /// The inverse of the periodic operator `op` on fields of zero mean, from its multiplier
    /// (nothing of the body recomputed).
    ///
    /// # Errors
    /// [`ElasticError::Unsupported`] if `op` is not periodic.
    pub fn of(op: &dyn Compliance) -> Result<Self> {
        let domain = *op.domain();
        if !domain.periodic {
            return Err(ElasticError::Unsupported(
                "a periodic stiffness inverts a periodic operator",
            ));
        }
        let Domain { nx, ny, .. } = domain;
        // The operator's multiplier is stored divided by `nx ny`; the mean mode is left out.
        let scale = (nx * ny) as f64;
        let mut inverse = op.fourier_compliance().mapv(|k| k * scale);
        inverse[(0, 0)] = 0.0;
        let kernel = inverse.mapv(|k| if k > 0.0 { 1.0 / k } else { 0.0 });
        Ok(PeriodicStiffness {
            domain,
            conv: Convolution::new(nx, ny, kernel, (ny, nx), (ny, nx)),
            inverse: Convolution::new(nx, ny, inverse, (ny, nx), (ny, nx)),
        })
    }

    /// Buffers for [`PeriodicStiffness::apply`]; make one per concurrent caller.
    pub fn make_workspace(&self) -> Workspace {
        Workspace(self.conv.make_workspace())
    }

    /// Writes the pressure \[Pa\] (zero mean) that holds the surface at `displacement` \[m\].
    ///
    /// # Errors
    /// [`ElasticError::ShapeMismatch`] if a field is not `(ny, nx)`.
    pub fn apply(
        &self,
        displacement: ArrayView2<f64>,
        pressure: ArrayViewMut2<f64>,
        ws: &mut Workspace,
    ) -> Result<()> {
        let shape = self.domain.shape();
        check("displacement", shape, displacement.dim())?;
        check("pressure", shape, pressure.dim())?;
        self.conv.apply(displacement, pressure, &mut ws.0);
        Ok(())
    }

    /// [`PeriodicStiffness::apply`] with the displacement given row by row: `displacement(y, row)`
    /// writes its row `y`, so that a displacement computed from other fields needs no field of
    /// its own.
    ///
    /// # Errors
    /// [`ElasticError::ShapeMismatch`] if `pressure` is not `(ny, nx)`.
    pub fn apply_rows(
        &self,
        displacement: impl Fn(usize, &mut [f64]) + Sync,
        pressure: ArrayViewMut2<f64>,
        ws: &mut Workspace,
    ) -> Result<()> {
        check("pressure", self.domain.shape(), pressure.dim())?;
        self.conv.apply_rows(displacement, pressure, &mut ws.0);
        Ok(())
    }

    /// Writes the displacement \[m\] (zero mean) under `pressure` \[Pa\], whose mean is ignored:
    /// the inverse of [`PeriodicStiffness::apply`] on fields of zero mean (for preconditioning
    /// solvers over the displacement).
    ///
    /// # Errors
    /// [`ElasticError::ShapeMismatch`] if a field is not `(ny, nx)`.
    pub fn invert(
        &self,
        pressure: ArrayView2<f64>,
        displacement: ArrayViewMut2<f64>,
        ws: &mut Workspace,
    ) -> Result<()> {
        let shape = self.domain.shape();
        check("pressure", shape, pressure.dim())?;
        check("displacement", shape, displacement.dim())?;
        self.inverse.apply(pressure, displacement, &mut ws.0);
        Ok(())
    }
}

/// The free (non-periodic) body: exact influence coefficients of uniform pressure on each
/// rectangular cell (Love 1929 for the half-space, plus a layer's correction), applied as a
/// linear convolution by FFT on a zero-padded `2nx` by `2ny` grid (DC-FFT). The displacement is
/// the true one (zero at infinity).
#[derive(Clone)]
pub struct Free {
    domain: Domain,
    e_star: f64,
    body: Body,
    cell: f64,
    conv: Convolution,
}

impl Free {
    /// The half-space on `domain` for composite modulus `e_star` \[Pa\]. Computes the influence
    /// coefficients and their spectrum once (the most expensive step: about 1.3 s at 4096^2).
    pub fn new(domain: Domain, e_star: f64) -> Result<Self> {
        Free::with_body(domain, e_star, Body::HalfSpace)
    }

    /// The operator of `body` (of plane-strain modulus `e_star` \[Pa\]) on `domain`. A layer's
    /// coefficients cost more than Love's where the layer is thicker than a cell (64 points a
    /// cell within 40 thicknesses: `docs/performance.md`).
    pub fn with_body(domain: Domain, e_star: f64, body: Body) -> Result<Self> {
        let e_star = check_modulus(e_star)?;
        domain.validate()?;
        let (conv, cell) = free_convolution(&domain, e_star, body)?;
        Ok(Free {
            domain: Domain {
                periodic: false,
                ..domain
            },
            e_star,
            body,
            cell,
            conv,
        })
    }
}

/// The DC-FFT convolution of the free `body` from `(ny, nx)` pressures to `(ny, nx)`
/// displacements, and its self-coefficient \[m/Pa\].
fn free_convolution(domain: &Domain, e_star: f64, body: Body) -> Result<(Convolution, f64)> {
    let Domain { nx, ny, dx, dy, .. } = *domain;
    let influence = body.influence(dx, dy, e_star);
    let (mx, my) = (2 * nx, 2 * ny);
    // Influence of cell (0, 0) on the cell at offset (i, j): even in both, so compute a
    // quadrant and wrap. Offset n (the padding's Nyquist) never reaches a kept output; it
    // takes the value at +n so that the kernel stays even and its spectrum real.
    let quadrant: Vec<f64> = (0..(ny + 1) * (nx + 1))
        .into_par_iter()
        .map(|k| {
            let (j, i) = (k / (nx + 1), k % (nx + 1));
            influence.at(i as f64 * dx, j as f64 * dy)
        })
        .collect();
    let fold = |k: usize, n: usize| if k <= n { k } else { 2 * n - k };
    let wrapped_row = |j: usize, out: &mut [f64]| {
        let q = &quadrant[fold(j, ny) * (nx + 1)..][..nx + 1];
        out.iter_mut().enumerate().for_each(|(i, o)| *o = q[fold(i, nx)]);
    };
    let mut conv = Convolution::without_kernel(mx, my, (ny, nx), (ny, nx));
    let kernel = conv.real_spectrum(wrapped_row, &mut conv.make_workspace());
    let diagonal = quadrant[0];
    drop(quadrant);
    conv.set_kernel(kernel);
    Ok((conv, diagonal))
}

/// The free body's stiffness on its padded grid, for solvers whose unknown is the
/// displacement: the inverse of the `2nx` by `2ny` circulant compliance whose first `(ny, nx)`
/// block is [`Free`]. A displacement `U` \[m\] of the whole padded grid is held by the pressure
/// `S U` \[Pa\] on the whole padded grid; where `S U` vanishes outside the first block, `U`'s
/// first block is exactly the free displacement under `S U`'s first block (the padding
/// keeps the periodic images from reaching it), so minimising over `U` with no pressure
/// allowed in the padding solves the free problem. Fields have shape `(2ny, 2nx)`; the
/// spectrum of the wrapped Love kernel is positive (checked), with a condition number of
/// about `4 n`.
pub struct FreeStiffness {
    domain: Domain,
    e_star: f64,
    stiffness: Convolution,
    compliance: Convolution,
    /// The circulant compliance from padded fields to padded fields.
    padded_compliance: Convolution,
}

impl FreeStiffness {
    /// The half-space's for the free `domain` and composite modulus `e_star` \[Pa\].
    ///
    /// # Errors
    /// A bad domain or modulus, or a kernel spectrum that is not positive (not seen on any
    /// grid: the wrapped kernel of Love's coefficients is positive definite).
    pub fn new(domain: Domain, e_star: f64) -> Result<Self> {
        FreeStiffness::with_body(domain, e_star, Body::HalfSpace)
    }

    /// The stiffness of `body` (of plane-strain modulus `e_star` \[Pa\]) on the free `domain`.
    ///
    /// # Errors
    /// As [`FreeStiffness::new`].
    pub fn with_body(domain: Domain, e_star: f64, body: Body) -> Result<Self> {
        FreeStiffness::of(&Free::with_body(domain, e_star, body)?)
    }

    /// The inverse of the free operator `op`'s padded circulant, from its multiplier (no
    /// influence coefficient recomputed).
    ///
    /// # Errors
    /// As [`FreeStiffness::new`]; [`ElasticError::Unsupported`] if `op` is periodic.
    pub fn of(op: &dyn Compliance) -> Result<Self> {
        let domain = *op.domain();
        if domain.periodic {
            return Err(ElasticError::Unsupported(
                "a free stiffness inverts a free operator",
            ));
        }
        let padded = (2 * domain.ny, 2 * domain.nx);
        // The compliance's multiplier is stored divided by `mx my`; the stiffness's unscaled one
        // is its reciprocal.
        let kernel = op.fourier_compliance();
        if let Some(&smallest) = kernel.iter().find(|&&k| k.is_nan() || k <= 0.0) {
            return Err(ElasticError::InvalidParameter {
                name: "compliance eigenvalue",
                value: smallest,
                reason: "the padded free kernel is not positive definite on this grid",
            });
        }
        let scale = (padded.0 * padded.1) as f64;
        let plan = |input| Convolution::without_kernel(padded.1, padded.0, input, padded);
        let (mut stiffness, mut compliance, mut padded_compliance) =
            (plan(padded), plan((domain.ny, domain.nx)), plan(padded));
        stiffness.set_kernel(kernel.mapv(|k| 1.0 / (k * scale)));
        let unscaled = kernel.mapv(|k| k * scale);
        compliance.set_kernel(unscaled.clone());
        padded_compliance.set_kernel(unscaled);
        Ok(FreeStiffness {
            domain,
            e_star: op.e_star(),
            stiffness,
            compliance,
            padded_compliance,
        })
    }

    /// The free domain, whose fields are the first `(ny, nx)` block of the padded ones.
    pub fn domain(&self) -> &Domain {
        &self.domain
    }

    /// Composite modulus E* \[Pa\].
    pub fn e_star(&self) -> f64 {
        self.e_star
    }

    /// Shape `(2ny, 2nx)` of the padded fields.
    pub fn padded_shape(&self) -> (usize, usize) {
        (2 * self.domain.ny, 2 * self.domain.nx)
    }

    /// Buffers for [`FreeStiffness::apply`] and [`FreeStiffness::displacement`].
    pub fn make_workspace(&self) -> Workspace {
        Workspace(self.stiffness.make_workspace())
    }

    /// Writes the padded pressure \[Pa\] that holds the padded surface at `displacement` \[m\].
    ///
    /// # Errors
    /// [`ElasticError::ShapeMismatch`] if a field is not `(2ny, 2nx)`.
    pub fn apply(
        &self,
        displacement: ArrayView2<f64>,
        pressure: ArrayViewMut2<f64>,
        ws: &mut Workspace,
    ) -> Result<()> {
        let shape = self.padded_shape();
        check("displacement", shape, displacement.dim())?;
        check("pressure", shape, pressure.dim())?;
        self.stiffness.apply(displacement, pressure, &mut ws.0);
        Ok(())
    }

    /// [`FreeStiffness::apply`] with the displacement given row by row: `displacement(y, row)`
    /// writes its row `y`, so that a displacement computed from other fields needs no field of
    /// its own.
    ///
    /// # Errors
    /// [`ElasticError::ShapeMismatch`] if `pressure` is not `(2ny, 2nx)`.
    pub fn apply_rows(
        &self,
        displacement: impl Fn(usize, &mut [f64]) + Sync,
        pressure: ArrayViewMut2<f64>,
        ws: &mut Workspace,
    ) -> Result<()> {
        check("pressure", self.padded_shape(), pressure.dim())?;
        self.stiffness.apply_rows(displacement, pressure, &mut ws.0);
        Ok(())
    }

    /// Writes the padded displacement \[m\] under the padded `pressure` \[Pa\]: the circulant
    /// compliance, the exact inverse of [`FreeStiffness::apply`] on the padded grid (for
    /// preconditioning solvers over the displacement).
    ///
    /// # Errors
    /// [`ElasticError::ShapeMismatch`] if a field is not `(2ny, 2nx)`.
    pub fn invert(
        &self,
        pressure: ArrayView2<f64>,
        displacement: ArrayViewMut2<f64>,
        ws: &mut Workspace,
    ) -> Result<()> {
        let shape = self.padded_shape();
        check("pressure", shape, pressure.dim())?;
        check("displacement", shape, displacement.dim())?;
        self.padded_compliance.apply(pressure, displacement, &mut ws.0);
        Ok(())
    }

    /// Writes the padded displacement \[m\] under `pressure` \[Pa\] on the `(ny, nx)` domain (none
    /// in the padding): the inverse of [`FreeStiffness::apply`], whose first block is [`Free`]'s
    /// displacement. For starting a minimisation from a known pressure.
    ///
    /// # Errors
    /// [`ElasticError::ShapeMismatch`] if a field has the wrong shape.
    pub fn displacement(
        &self,
        pressure: ArrayView2<f64>,
        displacement: ArrayViewMut2<f64>,
        ws: &mut Workspace,
    ) -> Result<()> {
        check("pressure", self.domain.shape(), pressure.dim())?;
        check("displacement", self.padded_shape(), displacement.dim())?;
        self.compliance.apply(pressure, displacement, &mut ws.0);
        Ok(())
    }
}

macro_rules! impl_compliance {
    ($t:ty) => {
        impl Compliance for $t {
            fn domain(&self) -> &Domain {
                &self.domain
            }
            fn e_star(&self) -> f64 {
                self.e_star
            }
            fn body(&self) -> Body {
                self.body
            }
            fn cell_compliance(&self) -> f64 {
                self.cell
            }
            fn with_modulus(&self, e_star: f64) -> Result<Box<dyn Compliance>> {
                let e_star = check_modulus(e_star)?;
                let factor = self.e_star / e_star;
                let mut scaled = self.clone();
                scaled.conv.scale_kernel(factor);
                scaled.cell *= factor;
                scaled.e_star = e_star;
                scaled.body = self.body.with_modulus_scaled(1.0 / factor);
                Ok(Box::new(scaled))
            }
            fn make_workspace(&self) -> Workspace {
                Workspace(self.conv.make_workspace())
            }
            fn apply(
                &self,
                pressure: ArrayView2<f64>,
                displacement: ArrayViewMut2<f64>,
                ws: &mut Workspace,
            ) -> Result<()> {
                let shape = self.domain.shape();
                check("pressure", shape, pressure.dim())?;
                check("displacement", shape, displacement.dim())?;
                self.conv.apply(pressure, displacement, &mut ws.0);
                Ok(())
            }
            fn fourier_compliance(&self) -> ArrayView2<'_, f64> {
                self.conv.kernel()
            }
        }
    };
}

impl_compliance!(Periodic);
impl_compliance!(Free);
