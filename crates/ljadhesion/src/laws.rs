//! The adhesive laws: Lennard-Jones at the node (`point`), averaged along x (`line`) and over
//! the tilted cell (`surface`, the paper's Eq. 11), and the exponential and Dugdale laws.

use crate::error::{Result, positive};
use crate::field;
use crate::lj::LennardJones;
use crate::{AdhesionLaw, Cells, FieldPotential, LocalPotential, StiffnessRows};
use ndarray::{Array2, ArrayView2, ArrayViewMut2};

/// The trait methods the three Lennard-Jones laws take from their [`LennardJones`].
macro_rules! lennard_jones_scales {
    ($name:literal) => {
        fn stiffness_bound(&self) -> f64 {
            self.0.stiffness_bound()
        }
        fn work_of_adhesion(&self) -> f64 {
            self.0.work_of_adhesion()
        }
        fn range(&self) -> f64 {
            self.0.z0()
        }
        fn peak_pressure(&self) -> f64 {
            self.0.min_pressure()
        }
        fn name(&self) -> &'static str {
            $name
        }
        fn lennard_jones(&self) -> Option<LennardJones> {
            Some(self.0)
        }
    };
}

/// `dz/dg`: 1 where the gap is open, 0 in contact (the separation is clamped there at z0).
fn open(gap: f64) -> f64 {
    if gap >= 0.0 { 1.0 } else { 0.0 }
}

/// The naive law: `p_i = p(z1)`, the Lennard-Jones pressure at the cell's node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PointLaw(pub LennardJones);

/// The line-integral law (Medina & Dini 2014): the mean of the Lennard-Jones pressure over the
/// separations between the cell's node and its +x neighbour,
/// `p_i = (Phi(z2) - Phi(z1)) / (z2 - z1)`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct LineLaw(pub LennardJones);

/// The surface-integral law (the paper's Eq. 11): the line law times the area factor of the
/// tilted cell, `p_i = S (Phi(z2) - Phi(z1)) / (z2 - z1)` with
/// `S = sqrt(1 + ((z2 - z1)/a_x)^2 + ((z3 - z1)/a_y)^2)`; node 3 is the +y neighbour.
/// On a flat gap field `S = 1` and it equals [`PointLaw`] exactly. Like the line law it is
/// one-sided: the mean is over the gaps from the node to its +x neighbour, so the value
/// belongs half a cell off the node, and on a problem symmetric about the node (a sphere) the
/// field leans towards +x and +y where the gap varies steeply within a cell.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceLaw(pub LennardJones);

/// The surface law's energy form: the Lennard-Jones interaction energy integrated over each
/// tilted cell, `E_i = A S M` with `M = (Psi(z2) - Psi(z1)) / (z2 - z1)` the mean of the energy
/// per area `-Phi` over the separations from the node to its +x neighbour and `S` the area
/// factor of [`SurfaceLaw`]. The pressure at a node is minus the derivative of the total
/// energy by its gap, per cell area: it gathers the node's share of the three cells it
/// belongs to (its own, the -x and the -y neighbour's), where Eq. 11 gives a cell's whole mean
/// to its node. So it derives from an energy ([`AdhesionLaw::field_potential`]) and the energy
/// descent applies. On a flat gap field it equals [`PointLaw`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SurfaceEnergyLaw(pub LennardJones);

impl AdhesionLaw for PointLaw {
    fn pressure_field(&self, gap: ArrayView2<f64>, _cells: &Cells, out: ArrayViewMut2<f64>) -> Result<()> {
        let lj = self.0;
        field::nodal(gap, out, |g| lj.pressure(lj.separation(g)))
    }
    lennard_jones_scales!("point");
    fn local_potential(&self) -> Option<&dyn LocalPotential> {
        Some(self)
    }
}

/// The point law's potential, for the laws that average it over a cell.
macro_rules! flat_point_potential {
    ($law:ty) => {
        /// The point law's potential: this law on flat gap fields ([`AdhesionLaw::flat_potential`]).
        impl LocalPotential for $law {
            fn energy(&self, gap: f64) -> f64 {
                PointLaw(self.0).energy(gap)
            }
            fn pressure(&self, gap: f64) -> f64 {
                PointLaw(self.0).pressure(gap)
            }
            fn curvature(&self, gap: f64) -> f64 {
                PointLaw(self.0).curvature(gap)
            }
        }
    };
}
flat_point_potential!(LineLaw);
flat_point_potential!(SurfaceLaw);
flat_point_potential!(SurfaceEnergyLaw);

/// `V(g) = -Phi(g + z0)`: `-w0` in contact, convex up to the peak pull at `z = 3^(1/6) z0`.
impl LocalPotential for PointLaw {
    fn energy(&self, gap: f64) -> f64 {
        self.0.energy_per_area(self.0.separation(gap))
    }
    fn pressure(&self, gap: f64) -> f64 {
        self.0.pressure(self.0.separation(gap))
    }
    fn curvature(&self, gap: f64) -> f64 {
        self.0.curvature(self.0.separation(gap))
    }
}

impl AdhesionLaw for LineLaw {
    fn pressure_field(&self, gap: ArrayView2<f64>, cells: &Cells, out: ArrayViewMut2<f64>) -> Result<()> {
        let lj = self.0;
        let z0 = lj.z0();
        field::neighbours(
            gap,
            cells,
            out,
            |g| z0 / lj.separation(g),
            |_, _, _, v1, v2| lj.mean_pressure_v(v1, v2),
        )
    }
    fn stiffness_rows(&self) -> Option<&dyn StiffnessRows> {
        Some(self)
    }
    lennard_jones_scales!("line");
    fn flat_potential(&self) -> Option<&dyn LocalPotential> {
        Some(self)
    }
}

/// Eq. 11 on one cell: the slopes `sx`, `sy` of the tilted cell from its node's separation to
/// its +x and +y neighbours', its area factor `S`, and the mean Lennard-Jones pressure over
/// the separations from the node to its +x neighbour; the cell's pressure is `S` times the
/// mean. The pressure field and its stiffness rows both take it from here, so that they agree
/// bit for bit.
struct TiltedCell {
    sx: f64,
    sy: f64,
    area: f64,
    mean: f64,
}

impl TiltedCell {
    /// The cell of gaps `[g1, g2, g3]` (node, +x, +y) \[m\], `(v1, v2)` the node's and the +x
    /// neighbour's `z0 / z`, on cells of inverse spacings `(ix, iy)` \[1/m\].
    fn of(lj: &LennardJones, (ix, iy): (f64, f64), [g1, g2, g3]: [f64; 3], (v1, v2): (f64, f64)) -> Self {
        let (sx, sy, area) = tilt(
            (ix, iy),
            [lj.separation(g1), lj.separation(g2), lj.separation(g3)],
        );
        TiltedCell {
            sx,
            sy,
            area,
            mean: lj.mean_pressure_v(v1, v2),
        }
    }
}

/// The slopes `sx`, `sy` of a cell whose node, +x and +y neighbours sit at separations
/// `[z1, z2, z3]` \[m\], on cells of inverse spacings `(ix, iy)` \[1/m\], and its area factor
/// `S = sqrt(1 + sx^2 + sy^2)` (Eq. 11).
fn tilt((ix, iy): (f64, f64), [z1, z2, z3]: [f64; 3]) -> (f64, f64, f64) {
    let (sx, sy) = ((z2 - z1) * ix, (z3 - z1) * iy);
    (sx, sy, (1.0 + sx * sx + sy * sy).sqrt())
}

impl AdhesionLaw for SurfaceLaw {
    fn pressure_field(&self, gap: ArrayView2<f64>, cells: &Cells, out: ArrayViewMut2<f64>) -> Result<()> {
        let lj = self.0;
        let z0 = lj.z0();
        let (ix, iy) = (1.0 / cells.dx, 1.0 / cells.dy);
        field::neighbours(
            gap,
            cells,
            out,
            |g| z0 / lj.separation(g),
            |g1, g2, g3, v1, v2| {
                let c = TiltedCell::of(&lj, (ix, iy), [g1, g2, g3], (v1, v2));
                c.area * c.mean
            },
        )
    }
    fn stiffness_rows(&self) -> Option<&dyn StiffnessRows> {
        Some(self)
    }
    // The stiffness bound is that of the mean pressure; the area factor `S` multiplies it
    // where the gap is steep.
    lennard_jones_scales!("surface");
    fn flat_potential(&self) -> Option<&dyn LocalPotential> {
        Some(self)
    }
}

impl StiffnessRows for LineLaw {
    fn stiffness_row(
        &self,
        gap: ArrayView2<f64>,
        cells: &Cells,
        y: usize,
        scratch: &mut [f64],
        out: [&mut [f64]; 3],
    ) {
        let lj = self.0;
        let z0 = lj.z0();
        field::neighbours3_row(
            gap,
            cells,
            y,
            scratch,
            out,
            |g| z0 / lj.separation(g),
            |g1, g2, _, v1, v2| {
                let (d1, d2) = lj.mean_pressure_slopes_v(v1, v2);
                [lj.mean_pressure_v(v1, v2), -open(g1) * d1, -open(g2) * d2]
            },
        );
    }
}

impl StiffnessRows for SurfaceLaw {
    fn stiffness_row(
        &self,
        gap: ArrayView2<f64>,
        cells: &Cells,
        y: usize,
        scratch: &mut [f64],
        out: [&mut [f64]; 3],
    ) {
        let lj = self.0;
        let z0 = lj.z0();
        let (ix, iy) = (1.0 / cells.dx, 1.0 / cells.dy);
        field::neighbours3_row(
            gap,
            cells,
            y,
            scratch,
            out,
            |g| z0 / lj.separation(g),
            |g1, g2, g3, v1, v2| {
                let TiltedCell { sx, sy, area, mean } = TiltedCell::of(&lj, (ix, iy), [g1, g2, g3], (v1, v2));
                let (d1, d2) = lj.mean_pressure_slopes_v(v1, v2);
                // The area factor's slopes by z1, z2 and z3, -(sx ix + sy iy) / S, sx ix / S and
                // sy iy / S, times the mean (one division a cell: they were most of its time).
                let m = mean / area;
                let (a1, a2, a3) = (-(sx * ix + sy * iy) * m, sx * ix * m, sy * iy * m);
                [
                    area * mean,
                    -open(g1) * (area * d1 + a1) - open(g3) * a3,
                    -open(g2) * (area * d2 + a2),
                ]
            },
        );
    }
}

impl AdhesionLaw for SurfaceEnergyLaw {
    fn pressure_field(&self, gap: ArrayView2<f64>, cells: &Cells, out: ArrayViewMut2<f64>) -> Result<()> {
        let shape = gap.dim();
        let (mut energy, mut curvature) = (Array2::zeros(shape), Array2::zeros(shape));
        self.evaluate_field(gap, cells, energy.view_mut(), out, curvature.view_mut())
    }
    lennard_jones_scales!("surface-energy");
    fn flat_potential(&self) -> Option<&dyn LocalPotential> {
        Some(self)
    }
    fn field_potential(&self) -> Option<&dyn FieldPotential> {
        Some(self)
    }
}

impl FieldPotential for SurfaceEnergyLaw {
    fn evaluate_field(
        &self,
        gap: ArrayView2<f64>,
        cells: &Cells,
        energy: ArrayViewMut2<f64>,
        pressure: ArrayViewMut2<f64>,
        curvature: ArrayViewMut2<f64>,
    ) -> Result<()> {
        let lj = self.0;
        let z0 = lj.z0();
        let (ix, iy) = (1.0 / cells.dx, 1.0 / cells.dy);
        field::cell_energies(gap, cells, energy, pressure, curvature, |g1, g2, g3| {
            let (z1, z2, z3) = (lj.separation(g1), lj.separation(g2), lj.separation(g3));
            let (v1, v2) = (z0 / z1, z0 / z2);
            let [m, m1, m2, m11, m22] = lj.mean_energy_v(v1, v2);
            // By the separations: dv/dz = -v^2 / z0.
            let (mz1, mz2) = (-v1 * v1 / z0 * m1, -v2 * v2 / z0 * m2);
            let mzz1 = v1 * v1 / (z0 * z0) * (2.0 * v1 * m1 + v1 * v1 * m11);
            let mzz2 = v2 * v2 / (z0 * z0) * (2.0 * v2 * m2 + v2 * v2 * m22);
            let (sx, sy, area) = tilt((ix, iy), [z1, z2, z3]);
            let (a1, a2, a3) = (-(sx * ix + sy * iy) / area, sx * ix / area, sy * iy / area);
            let a11 = ((ix * ix + iy * iy) - a1 * a1) / area;
            let a22 = (ix * ix - a2 * a2) / area;
            let a33 = (iy * iy - a3 * a3) / area;
            (
                area * m,
                [area * mz1 + m * a1, area * mz2 + m * a2, m * a3],
                [
                    area * mzz1 + 2.0 * a1 * mz1 + m * a11,
                    area * mzz2 + 2.0 * a2 * mz2 + m * a22,
                    m * a33,
                ],
            )
        })
    }
}

/// The exponential law of the contact-mechanics challenge, with a hard wall:
/// `sigma(g) = -(w0 / rho) exp(-g / rho)` \[Pa\] for `g >= 0` (negative gaps count as contact),
/// at the node. Its integral over `g >= 0` is `-w0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ExponentialLaw {
    w0: f64,
    rho: f64,
}

impl ExponentialLaw {
    /// Work of adhesion `w0` [J/m^2] and range `rho` \[m\], both > 0.
    pub fn new(w0: f64, rho: f64) -> Result<Self> {
        Ok(ExponentialLaw {
            w0: positive("work_of_adhesion", w0)?,
            rho: positive("range", rho)?,
        })
    }

    /// `sigma(g)` \[Pa\].
    pub fn pressure(&self, gap: f64) -> f64 {
        let g = if gap < 0.0 { 0.0 } else { gap }; // NaN stays NaN
        if g > UNDERFLOW * self.rho {
            // What `exp` returns there, without libm's slow path near underflow.
            return -0.0;
        }
        -(self.w0 / self.rho) * (-g / self.rho).exp()
    }
}

/// Ranges beyond which `exp(-g / rho)` underflows to zero (`ln 2^-1075` = -745.13).
const UNDERFLOW: f64 = 745.2;

impl AdhesionLaw for ExponentialLaw {
    fn pressure_field(&self, gap: ArrayView2<f64>, _cells: &Cells, out: ArrayViewMut2<f64>) -> Result<()> {
        field::nodal(gap, out, |g| self.pressure(g))
    }
    /// `w0 / rho^2`, at contact.
    fn stiffness_bound(&self) -> f64 {
        self.w0 / (self.rho * self.rho)
    }
    fn work_of_adhesion(&self) -> f64 {
        self.w0
    }
    fn range(&self) -> f64 {
        self.rho
    }
    fn peak_pressure(&self) -> f64 {
        -self.w0 / self.rho
    }
    fn name(&self) -> &'static str {
        "exponential"
    }
    fn local_potential(&self) -> Option<&dyn LocalPotential> {
        Some(self)
    }
}

/// `V(g) = -w0 exp(-g / rho)`: concave everywhere.
impl LocalPotential for ExponentialLaw {
    fn energy(&self, gap: f64) -> f64 {
        -self.w0 * (-gap.max(0.0) / self.rho).exp()
    }
    fn pressure(&self, gap: f64) -> f64 {
        ExponentialLaw::pressure(self, gap)
    }
    fn curvature(&self, gap: f64) -> f64 {
        ExponentialLaw::pressure(self, gap) / self.rho
    }
    fn evaluate(&self, gap: f64) -> (f64, f64, f64) {
        let p = ExponentialLaw::pressure(self, gap);
        (p * self.rho, p, p / self.rho)
    }
}

/// The Dugdale (Maugis) law: a constant pull `sigma0 = w0 / h0` for `0 <= g < h0` and none
/// beyond, at the node. With `h0 = 0.974 z0` and `sigma0` the Lennard-Jones peak it is the
/// Dugdale model equivalent to the Lennard-Jones law (docs/method.md section 8.3).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct DugdaleLaw {
    w0: f64,
    range: f64,
    /// The Lennard-Jones law it was made equivalent to ([`DugdaleLaw::equivalent_to`]).
    lj: Option<LennardJones>,
}

impl DugdaleLaw {
    /// Work of adhesion `w0` [J/m^2] and range `h0` \[m\], both > 0.
    pub fn new(w0: f64, range: f64) -> Result<Self> {
        Ok(DugdaleLaw {
            w0: positive("work_of_adhesion", w0)?,
            range: positive("range", range)?,
            lj: None,
        })
    }

    /// The Dugdale law with the same work of adhesion and peak stress as `lj`.
    pub fn equivalent_to(lj: &LennardJones) -> Self {
        let w0 = lj.work_of_adhesion();
        DugdaleLaw {
            w0,
            range: w0 / -lj.min_pressure(),
            lj: Some(*lj),
        }
    }

    /// `sigma(g)` \[Pa\].
    pub fn pressure(&self, gap: f64) -> f64 {
        if gap < self.range {
            -self.w0 / self.range
        } else {
            0.0
        }
    }
}

impl AdhesionLaw for DugdaleLaw {
    fn pressure_field(&self, gap: ArrayView2<f64>, _cells: &Cells, out: ArrayViewMut2<f64>) -> Result<()> {
        field::nodal(gap, out, |g| {
            // NaN must stay NaN so that it is reported.
            if g.is_nan() { g } else { self.pressure(g) }
        })
    }
    /// Infinite: the law jumps from `-sigma0` to 0 at `g = h0`; solvers must not rely on a
    /// stiffness to relax it.
    fn stiffness_bound(&self) -> f64 {
        f64::INFINITY
    }
    fn work_of_adhesion(&self) -> f64 {
        self.w0
    }
    fn range(&self) -> f64 {
        self.range
    }
    fn peak_pressure(&self) -> f64 {
        -self.w0 / self.range
    }
    fn name(&self) -> &'static str {
        "dugdale"
    }
    fn lennard_jones(&self) -> Option<LennardJones> {
        self.lj
    }
}

/// No adhesion at all: zero pressure at every gap. With it the adhesive solver reduces to the
/// non-adhesive one, so that sweeps run the same way with and without adhesion.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct NoAdhesion;

impl AdhesionLaw for NoAdhesion {
    fn pressure_field(&self, gap: ArrayView2<f64>, _cells: &Cells, out: ArrayViewMut2<f64>) -> Result<()> {
        field::nodal(gap, out, |g| if g.is_nan() { g } else { 0.0 })
    }
    fn stiffness_bound(&self) -> f64 {
        0.0
    }
    fn work_of_adhesion(&self) -> f64 {
        0.0
    }
    /// 1 m: a scale for the solver's residual, which stays 0.
    fn range(&self) -> f64 {
        1.0
    }
    fn peak_pressure(&self) -> f64 {
        0.0
    }
    fn name(&self) -> &'static str {
        "none"
    }
    fn local_potential(&self) -> Option<&dyn LocalPotential> {
        Some(self)
    }
}

impl LocalPotential for NoAdhesion {
    fn energy(&self, _gap: f64) -> f64 {
        0.0
    }
    fn pressure(&self, _gap: f64) -> f64 {
        0.0
    }
    fn curvature(&self, _gap: f64) -> f64 {
        0.0
    }
}
