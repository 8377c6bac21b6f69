//! # elastic: surface operators of an elastic body
//!
//! The normal surface displacement `u` \[m\] of an elastic half-space of composite modulus `E*`
//! \[Pa\] under a normal pressure `p` \[Pa\] (positive = compressive, pushing the surface in, so
//! `u > 0` under a compressive load) that is uniform over each cell of a regular grid
//! (docs/method.md section 1, the paper's Eqs. 1-2):
//!
//! - [`Periodic`]: the spectral kernel `u(q) = 2 p(q) / (E* |q|)`, mean displacement zero;
//! - [`Free`]: Love's exact influence coefficients for rectangular cells, applied as a linear
//!   convolution on a zero-padded grid (DC-FFT); the displacement vanishes at infinity.
//!
//! Both take a [`Body`] other than the half-space: a [`Layer`] of finite thickness on a rigid
//! base, bonded or frictionless, or on an elastic substrate, whose compliance by wavenumber is
//! the half-space's times a factor of `q h` (on free grids, Love's coefficients plus the
//! layer's correction in real space).
//!
//! Both operators are [`Compliance`] operators ([`PeriodicStiffness`] inverts the periodic one,
//! [`FreeStiffness`] the free one on its padded grid):
//! planned once, then applied many times to caller-owned buffers with a caller-owned
//! [`Workspace`] (no field-sized allocation per application), in parallel, with results that do not depend on the number of threads at all.
//! Arrays have shape `(ny, nx)`.
//!
//! ```
//! use elastic::{Compliance, Domain, Periodic};
//! use ndarray::Array2;
//! let domain = Domain { nx: 64, ny: 64, dx: 1e-6, dy: 1e-6, periodic: true };
//! let op = Periodic::new(domain, 1e9)?;
//! let mut ws = op.make_workspace();
//! // p = p0 cos(q x) gives u = 2 p0 cos(q x) / (E* q).
//! let q = 2.0 * std::f64::consts::PI * 4.0 / 64e-6;
//! let p = Array2::from_shape_fn((64, 64), |(_, i)| 1e6 * (q * i as f64 * 1e-6).cos());
//! let mut u = Array2::zeros((64, 64));
//! op.apply(p.view(), u.view_mut(), &mut ws)?;
//! assert!((u[(0, 0)] - 2.0 * 1e6 / (1e9 * q)).abs() < 1e-12 * u[(0, 0)]);
//! # Ok::<(), elastic::ElasticError>(())
//! ```

mod body;
mod convolution;
pub mod error;
pub mod layer;
pub mod love;
pub mod material;
mod operators;
pub mod shear;
pub mod viscoelastic;

pub use body::Body;
pub use error::{ElasticError, Result};
pub use layer::{Base, Layer, ShearFactors};
pub use material::{Material, composite_modulus};
pub use operators::{Free, FreeStiffness, Periodic, PeriodicStiffness, Workspace};
pub use shear::{Shear, ShearWorkspace};
pub use viscoelastic::Maxwell;

use ndarray::{ArrayView2, ArrayViewMut2, Zip};

/// The grid of cells an operator acts on.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Domain {
    /// Cells along x (columns).
    pub nx: usize,
    /// Cells along y (rows).
    pub ny: usize,
    /// Cell size along x \[m\].
    pub dx: f64,
    /// Cell size along y \[m\].
    pub dy: f64,
    /// Periodic (the pattern repeats every `nx dx` by `ny dy`) or free (isolated).
    pub periodic: bool,
}

impl Domain {
    /// Shape `(ny, nx)` of the fields.
    pub fn shape(&self) -> (usize, usize) {
        (self.ny, self.nx)
    }

    /// Area of one cell [m^2].
    pub fn cell_area(&self) -> f64 {
        self.dx * self.dy
    }

    /// The displacement \[m\] of one cell under unit pressure \[Pa\] on itself, on a half-space
    /// of composite modulus `e_star` \[Pa\]: the cell's compliance [m/Pa].
    pub fn cell_compliance(&self, e_star: f64) -> f64 {
        love::cell_influence(0.0, 0.0, self.dx / 2.0, self.dy / 2.0, e_star)
    }

    fn validate(&self) -> Result<()> {
        for (name, n) in [("nx", self.nx), ("ny", self.ny)] {
            if n < 2 {
                return Err(ElasticError::InvalidParameter {
                    name,
                    value: n as f64,
                    reason: "need at least 2 cells",
                });
            }
        }
        for (name, d) in [("dx", self.dx), ("dy", self.dy)] {
            if !(d.is_finite() && d > 0.0) {
                return Err(ElasticError::InvalidParameter {
                    name,
                    value: d,
                    reason: "cell size must be finite and > 0 m",
                });
            }
        }
        Ok(())
    }
}

/// A linear elastic surface operator: displacement = compliance applied to pressure.
pub trait Compliance: Sync + Send {
    /// The grid it acts on.
    fn domain(&self) -> &Domain;

    /// Composite modulus E* \[Pa\] (a layer's plane-strain modulus).
    fn e_star(&self) -> f64;

    /// The body whose compliance this is.
    fn body(&self) -> Body;

    /// The displacement \[m\] of a cell under unit pressure \[Pa\] on itself: the operator's
    /// diagonal (Love's self-coefficient, [`Domain::cell_compliance`], for the half-space).
    fn cell_compliance(&self) -> f64;

    /// The compliance \[m/Pa\] of the mean mode that [`Compliance::apply`] leaves out: a mean
    /// pressure `p` also displaces the whole surface by this times `p`. Zero on free grids
    /// (nothing is left out) and for the periodic half-space (the mode has no finite
    /// compliance: displacements and approaches are measured from the mean surface).
    fn mean_compliance(&self) -> f64 {
        if self.domain().periodic {
            self.body().mean_compliance(self.e_star()).unwrap_or(0.0)
        } else {
            0.0
        }
    }

    /// The same body on the same grid with every modulus scaled so that its plane-strain
    /// modulus is `e_star` \[Pa\] (a coating's substrate scaled alike): the compliance times
    /// `self.e_star() / e_star`, nothing recomputed but the kernel's scale. A viscoelastic
    /// step's effective body.
    ///
    /// # Errors
    /// A modulus that is not finite and positive.
    fn with_modulus(&self, e_star: f64) -> Result<Box<dyn Compliance>>;

    /// Buffers for [`Compliance::apply`]; make one per concurrent caller and reuse it.
    fn make_workspace(&self) -> Workspace;

    /// Writes the displacement \[m\] caused by `pressure` \[Pa\] into `displacement`.
    ///
    /// # Errors
    /// [`ElasticError::ShapeMismatch`] if a field is not `(ny, nx)`.
    ///
    /// # Panics
    /// If `ws` was made by another operator.
    fn apply(
        &self,
        pressure: ArrayView2<f64>,
        displacement: ArrayViewMut2<f64>,
        ws: &mut Workspace,
    ) -> Result<()>;

    /// The operator's real Fourier multiplier on its transform grid (transposed half layout
    /// `(mx/2 + 1, my)`, with `(mx, my) = (nx, ny)` periodic and `(2nx, 2ny)` free), divided by
    /// `mx my` [m/Pa]: for preconditioners.
    fn fourier_compliance(&self) -> ArrayView2<'_, f64>;

    /// Elastic energy `(1/2) sum p u dx dy` \[J\] stored by `pressure`, given its displacement.
    fn energy(&self, pressure: ArrayView2<f64>, displacement: ArrayView2<f64>) -> f64 {
        let mut sum = 0.0;
        Zip::from(pressure)
            .and(displacement)
            .for_each(|p, u| sum += p * u);
        0.5 * sum * self.domain().cell_area()
    }
}
