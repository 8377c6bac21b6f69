//! # ljadhesion: adhesive pressure on a boundary-element grid
//!
//! Maps a field of gaps `g >= 0` \[m\] to a field of adhesive pressures `p <= 0` \[Pa\] (negative
//! = attractive; the solver crate's conventions). The laws (docs/method.md sections 2 and 3, the
//! paper's Eqs. 5-12):
//!
//! | law | cell pressure |
//! |---|---|
//! | [`PointLaw`] | `p(z1)`, Lennard-Jones at the node |
//! | [`LineLaw`] | mean of `p` over `[z1, z2]` (node and +x neighbour; Medina & Dini 2014) |
//! | [`SurfaceLaw`] | that mean times the area factor `S` of the tilted cell (Eq. 11) |
//! | [`SurfaceEnergyLaw`] | minus the gradient of the Lennard-Jones energy over the tilted cells (Eq. 11's energy form) |
//! | [`ExponentialLaw`] | `-(w0/rho) exp(-g/rho)`, the contact-mechanics challenge's law |
//! | [`DugdaleLaw`] | `-w0/h0` for `g < h0` (Maugis-Dugdale) |
//!
//! with `z = g + z0` (Eq. 12), so that contact (`g = 0`) carries no adhesive pressure beyond
//! the Lennard-Jones equilibrium and only the attractive tail is used. Negative gaps are
//! treated as contact. Every cell depends only on known gaps, so fields are computed in
//! parallel; results do not depend on the number of threads at all.
//!
//! ```
//! use ljadhesion::{AdhesionLaw, Cells, LennardJones, PointLaw, SurfaceLaw};
//! use ndarray::Array2;
//! let lj = LennardJones::new(0.05, 2.071e-9)?;            // w0 [J/m^2], z0 \[m\]
//! let gap = Array2::from_elem((8, 8), 1e-9);              // flat, 1 nm
//! let cells = Cells { dx: 1e-8, dy: 1e-8, periodic: true };
//! let (mut a, mut b) = (Array2::zeros((8, 8)), Array2::zeros((8, 8)));
//! SurfaceLaw(lj).pressure_field(gap.view(), &cells, a.view_mut())?;
//! PointLaw(lj).pressure_field(gap.view(), &cells, b.view_mut())?;
//! assert_eq!(a, b);                                      // flat gaps: S = 1, mean = point value
//! # Ok::<(), ljadhesion::AdhesionError>(())
//! ```

pub mod error;
mod field;
pub mod laws;
pub mod lj;

pub use error::{AdhesionError, Result};
pub use laws::{DugdaleLaw, ExponentialLaw, LineLaw, NoAdhesion, PointLaw, SurfaceEnergyLaw, SurfaceLaw};
pub use lj::LennardJones;

use ndarray::{ArrayView2, ArrayViewMut2};

/// The grid cells a gap field lives on: spacings \[m\] and whether the field wraps around.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cells {
    /// Spacing along x (columns) \[m\].
    pub dx: f64,
    /// Spacing along y (rows) \[m\].
    pub dy: f64,
    /// Whether neighbours wrap around the edges (periodic domain) or are mirrored (free edges).
    pub periodic: bool,
}

/// An adhesive law on a grid: gap field in, adhesive pressure field out.
pub trait AdhesionLaw: Sync + Send {
    /// Writes the adhesive pressure \[Pa\] (<= 0 for the attractive laws) of every cell into
    /// `out`, given the gaps `gap` \[m\] (shape `(ny, nx)`, the same as `out`).
    ///
    /// # Errors
    /// [`AdhesionError::ShapeMismatch`] and [`AdhesionError::NonFiniteGap`]; `out` is then
    /// unspecified.
    fn pressure_field(&self, gap: ArrayView2<f64>, cells: &Cells, out: ArrayViewMut2<f64>) -> Result<()>;

    /// Writes the pressure \[Pa\] as [`AdhesionLaw::pressure_field`] does (bit for bit) into
    /// `pressure`, and into `own` and `next` its stiffness [Pa/m] when the cell's own column
    /// of nodes moves and when its +x neighbour's does, `-dp/dg` (the surface law's area
    /// factor also depends on the +y neighbour, which is in the cell's own column), for the
    /// laws whose cell mixes its gap with its neighbours' (line and surface), in closed form in
    /// one pass: their [`AdhesionLaw::stiffness_rows`] on every row. Returns `false`, with
    /// nothing written, for the other laws.
    ///
    /// # Errors
    /// As [`AdhesionLaw::pressure_field`].
    fn pressure_and_stiffness_field(
        &self,
        gap: ArrayView2<f64>,
        cells: &Cells,
        pressure: ArrayViewMut2<f64>,
        own: ArrayViewMut2<f64>,
        next: ArrayViewMut2<f64>,
    ) -> Result<bool> {
        let Some(rows) = self.stiffness_rows() else {
            return Ok(false);
        };
        field::rows3(gap, [pressure, own, next], |y, scratch, out| {
            rows.stiffness_row(gap, cells, y, scratch, out)
        })?;
        Ok(true)
    }

    /// The law's [`AdhesionLaw::pressure_and_stiffness_field`] one row at a time, if it has
    /// one (line and surface): for a solver's pass over the rows that uses each row of the
    /// three fields at once rather than storing them.
    fn stiffness_rows(&self) -> Option<&dyn StiffnessRows> {
        None
    }

    /// An upper bound of `|dp/dg|` [Pa/m], for choosing a stable relaxation.
    fn stiffness_bound(&self) -> f64;

    /// Work of adhesion w0 [J/m^2]: minus the integral of the law over the gap.
    fn work_of_adhesion(&self) -> f64;

    /// The law's length scale \[m\]: `z0` for Lennard-Jones, `rho` for the exponential law, `h0`
    /// for Dugdale. Gaps are resolved relative to it (solver tolerances, grid checks).
    fn range(&self) -> f64;

    /// The most attractive pressure the law gives on a flat gap field \[Pa\] (< 0): the
    /// Lennard-Jones peak `-16 w0 / (9 sqrt(3) z0)`, `-w0/rho`, `-w0/h0`.
    fn peak_pressure(&self) -> f64;

    /// Short name (`point`, `line`, `surface`, `exponential`, `dugdale`).
    fn name(&self) -> &'static str;

    /// The adhesive process-zone length `E* w0 / sigma0^2` \[m\] on a half-space of composite
    /// modulus `e_star` \[Pa\], `sigma0` the peak tension ([`AdhesionLaw::peak_pressure`]):
    /// a cell wider than it holds on or lets go whole.
    fn process_zone(&self, e_star: f64) -> f64 {
        let sigma0 = -self.peak_pressure();
        e_star * self.work_of_adhesion() / (sigma0 * sigma0)
    }

    /// The Lennard-Jones law behind this one, if any: the point, line and surface laws' own,
    /// the Dugdale law's it was made equivalent to. Its `z0` is the length of the Tabor
    /// parameter.
    fn lennard_jones(&self) -> Option<LennardJones> {
        None
    }

    /// The law as a [`LocalPotential`], if it is one: each cell's pressure depends on its own
    /// gap alone and derives from an interaction energy (the point, exponential and no-adhesion
    /// laws). Energy-minimising solvers need it; the line and surface laws, which mix a cell's
    /// gap with its neighbours' without an energy behind them, and the discontinuous Dugdale
    /// law, give `None`.
    fn local_potential(&self) -> Option<&dyn LocalPotential> {
        None
    }

    /// The potential of the local law this one becomes on flat gap fields, where a cell's
    /// neighbours share its gap: the point law for the line and surface laws, the law itself
    /// for those with a [`AdhesionLaw::local_potential`]. Solvers use its energy to predict a
    /// state far from the current one (across a jump), which the law itself then corrects.
    fn flat_potential(&self) -> Option<&dyn LocalPotential> {
        self.local_potential()
    }

    /// The law as a [`FieldPotential`], if it derives from an energy of the whole gap field
    /// that couples neighbouring cells ([`SurfaceEnergyLaw`]).
    fn field_potential(&self) -> Option<&dyn FieldPotential> {
        None
    }
}

/// A law's pressure and stiffness on one row of cells ([`AdhesionLaw::stiffness_rows`]): a
/// cell depends on its node and its +x and +y neighbours, so a row on its own row of gaps and
/// the next (wrapped or mirrored as [`Cells`] says).
pub trait StiffnessRows: Sync + Send {
    /// Writes row `y` of [`AdhesionLaw::pressure_and_stiffness_field`] (bit for bit) into
    /// `[pressure, own, next]`, each `gap.ncols()` long, with `scratch` as room for a row.
    /// `gap` must be in standard layout. A non-finite gap gives non-finite values, not an
    /// error: the caller checks.
    fn stiffness_row(
        &self,
        gap: ArrayView2<f64>,
        cells: &Cells,
        y: usize,
        scratch: &mut [f64],
        out: [&mut [f64]; 3],
    );
}

/// A law that derives from an interaction energy of the whole gap field, each cell's energy
/// depending on its own gap and its neighbours': the pressure at a node is minus the derivative
/// of the total energy by the node's gap, per cell area, so that energy-minimising solvers
/// apply, though no cell's pressure depends on its own gap alone.
pub trait FieldPotential: Sync + Send {
    /// Writes, for the gaps `gap` \[m\], each cell's interaction energy per area [J/m^2] (the
    /// field's energy per area is their mean) into `energy`, the law's pressure \[Pa\] (as
    /// [`AdhesionLaw::pressure_field`]) into `pressure`, and the diagonal of the second
    /// derivative of the energy by the gaps, per cell area [Pa/m], into `curvature`.
    ///
    /// # Errors
    /// As [`AdhesionLaw::pressure_field`].
    fn evaluate_field(
        &self,
        gap: ArrayView2<f64>,
        cells: &Cells,
        energy: ArrayViewMut2<f64>,
        pressure: ArrayViewMut2<f64>,
        curvature: ArrayViewMut2<f64>,
    ) -> Result<()>;
}

/// A law given by an interaction energy per area `V(g)` [J/m^2] of each cell's own gap `g >= 0`
/// \[m\]: `V(0) = -w0`, `V -> 0` far apart, pressure `p = -dV/dg` \[Pa\] (<= 0 attractive, the
/// [`AdhesionLaw::pressure_field`] of every cell). Negative gaps count as contact (`g = 0`).
pub trait LocalPotential: Sync + Send {
    /// `V(g)` [J/m^2].
    fn energy(&self, gap: f64) -> f64;
    /// `p(g) = -dV/dg` \[Pa\].
    fn pressure(&self, gap: f64) -> f64;
    /// `d^2V/dg^2 = -dp/dg` [Pa/m]: positive where the law stiffens the contact (the
    /// Lennard-Jones tail just outside contact), negative where it softens it.
    fn curvature(&self, gap: f64) -> f64;
    /// `(V, p, V'')` at once, for laws that share the work between them.
    fn evaluate(&self, gap: f64) -> (f64, f64, f64) {
        (self.energy(gap), self.pressure(gap), self.curvature(gap))
    }
}
