//! A contact problem as one object: the elastic half-space on its grid, the rigid
//! counterface's initial gap, the adhesive law, and what the user should know before trusting
//! the result. Built from a geometry, a surface, a material and a law by [`ProblemBuilder`];
//! solved by [`ContactProblem::solve`] and [`ContactProblem::sweep`].

use crate::adhesive::{AdhesiveReport, AdhesiveState, Start};
use crate::error::{Result, SolverError, invalid};
use crate::geometry::{SphereProfile, flat_on_rough, sphere, wave};
use crate::interface::Interface;
use crate::method::{Method, Settings};
use crate::observer::Observer;
use crate::options::{ContactOptions, Control};
use crate::report::ContactReport;
use crate::state::ContactState;
use elastic::{Body, Compliance, Domain, Free, Layer, Periodic};
use ljadhesion::{AdhesionLaw, NoAdhesion};
use ndarray::Array2;
use std::sync::Arc;

/// The shape of the rigid counterface, on which any roughness sits.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub enum Shape {
    /// A flat: the roughness alone makes the gap.
    #[default]
    Flat,
    /// A sphere of radius `radius` \[m\] centred on the grid ([`crate::geometry::sphere`]).
    Sphere {
        /// Radius \[m\].
        radius: f64,
        /// Paraboloid or exact profile.
        profile: SphereProfile,
    },
    /// A wave `amplitude (1 - cos(2 pi x / L))`, one wavelength across the box along x
    /// ([`crate::geometry::wave`]); periodic domains only.
    Wave {
        /// Amplitude \[m\], half the peak-to-valley height.
        amplitude: f64,
    },
}

/// A normal contact problem: an elastic half-space (its operator knows the grid and the
/// composite modulus), the initial gap `g0` \[m\] to the rigid counterface (minimum 0, shape
/// `(ny, nx)`), an adhesive law ([`NoAdhesion`] for none), and warnings about the set-up.
#[derive(Clone)]
pub struct ContactProblem {
    /// The half-space's compliance on the grid: [`Periodic`] or [`Free`].
    pub operator: Arc<dyn Compliance>,
    /// The initial gap `g0` \[m\].
    pub initial_gap: Array2<f64>,
    /// The adhesive law.
    pub law: Arc<dyn AdhesionLaw>,
    /// The interface: elastic, or capped by a hardness.
    pub interface: Interface,
    /// A viscoelastic body: the generalized Maxwell solid whose relaxed modulus is the
    /// operator's E* ([`crate::time`]); its answers depend on the path, so it is swept along
    /// times. `None`: elastic.
    pub solid: Option<elastic::Maxwell>,
    /// The body's Poisson's ratio [-], which its tangential compliance needs (the normal one
    /// takes E* alone). `None`: not given.
    pub poisson: Option<f64>,
    /// What presses the body: whether its normal and tangential loads couple
    /// ([`crate::friction::Counterface`]).
    pub counterface: crate::friction::Counterface,
    /// Things the user should know before trusting the result: a grid too coarse for the law,
    /// attraction cut off at a free grid's edge.
    pub warnings: Vec<String>,
}

impl ContactProblem {
    /// A builder from geometry, surface, material and law.
    pub fn builder() -> ProblemBuilder {
        ProblemBuilder::default()
    }

    /// A problem from its parts, with the warnings computed as the builder does.
    ///
    /// # Errors
    /// An initial gap of another shape than the operator's grid.
    pub fn new(
        operator: impl Compliance + 'static,
        initial_gap: Array2<f64>,
        law: impl AdhesionLaw + 'static,
    ) -> Result<ContactProblem> {
        ContactProblem::from_shared(Arc::new(operator), initial_gap, Arc::new(law))
    }

    /// [`ContactProblem::new`] with shared parts.
    ///
    /// # Errors
    /// As [`ContactProblem::new`].
    pub fn from_shared(
        operator: Arc<dyn Compliance>,
        initial_gap: Array2<f64>,
        law: Arc<dyn AdhesionLaw>,
    ) -> Result<ContactProblem> {
        let expected = operator.domain().shape();
        if initial_gap.dim() != expected {
            return Err(SolverError::ShapeMismatch {
                what: "initial gap",
                expected,
                got: initial_gap.dim(),
            });
        }
        let mut problem = ContactProblem {
            operator,
            initial_gap,
            law,
            interface: Interface::default(),
            solid: None,
            poisson: None,
            counterface: Default::default(),
            warnings: Vec::new(),
        };
        problem.warnings = problem.check();
        Ok(problem)
    }

    /// The body, the law and the initial gap, as the adhesive methods take them.
    pub(crate) fn parts(&self) -> crate::adhesive::Parts<'_> {
        crate::adhesive::Parts {
            op: self.operator.as_ref(),
            law: self.law.as_ref(),
            interface: self.interface,
            g0: self.initial_gap.view(),
        }
    }

    /// The grid.
    pub fn domain(&self) -> Domain {
        *self.operator.domain()
    }

    /// The composite modulus E* \[Pa\].
    pub fn e_star(&self) -> f64 {
        self.operator.e_star()
    }

    /// Whether the law attracts at all.
    pub fn adhesive(&self) -> bool {
        self.law.work_of_adhesion() > 0.0
    }

    /// Solves the adhesive contact under `control` by the method of `settings`, from `start`:
    /// [`Control::Approach`] (any sign: negative is apart), [`Control::Force`] or
    /// [`Control::MeanPressure`] (any sign: negative pulls), or [`Control::CentralGap`] (the
    /// approach follows, which traces unstable branches). `observer` hears every iteration.
    ///
    /// # Errors
    /// Bad input, a method that cannot solve this law under this control (the message names
    /// one that can), non-finite gaps met by the law.
    pub fn solve(
        &self,
        control: Control,
        settings: &Settings,
        start: Start,
        observer: &mut dyn Observer,
    ) -> Result<(AdhesiveState, AdhesiveReport)> {
        self.elastic_only("a single solve")?;
        crate::adhesive::solve(self.parts(), control, settings, start, &mut |i, r| {
            crate::observer::heard(observer, 0, i, r)
        })
    }

    /// Solves the contact as if the law were switched off, by the constrained conjugate
    /// gradients of [`crate::cg`] (faster than an adhesive method with no adhesion), across the
    /// problem's interface.
    ///
    /// # Errors
    /// As [`crate::cg::solve_with`].
    pub fn solve_without_adhesion(
        &self,
        control: Control,
        options: &ContactOptions,
        warm: Option<&ContactState>,
        observer: &mut dyn Observer,
    ) -> Result<(ContactState, ContactReport)> {
        self.elastic_only("a single solve")?;
        crate::cg::solve_with(
            self.operator.as_ref(),
            self.initial_gap.view(),
            &self.interface,
            control,
            options,
            warm,
            observer,
        )
    }

    /// The tangential problem on the normal solution `normal` (its compressive pressure), under
    /// the interface's friction ([`crate::friction`]).
    ///
    /// # Errors
    /// No friction law or Poisson's ratio, a viscoelastic body or a layer on a free grid (their
    /// tangential compliances are not implemented), no cell in contact.
    pub fn tangential(&self, normal: &ContactState) -> Result<crate::friction::TangentialProblem> {
        let (friction, poisson) = self.check_tangential()?;
        let contact_gap = crate::friction::contact_gap(self.law.as_ref())?;
        crate::friction::TangentialProblem::new(
            self.operator.as_ref(),
            poisson,
            friction,
            normal,
            contact_gap,
        )
    }

    /// The friction law and Poisson's ratio a tangential path takes, or why the problem cannot
    /// take one (before any solve).
    ///
    /// # Errors
    /// As [`ContactProblem::tangential`], but for the contact.
    pub fn check_tangential(&self) -> Result<(crate::friction::Friction, f64)> {
        let friction = self.interface.friction.ok_or(SolverError::Incomplete(
            "a friction law for a tangential path: a friction coefficient or a shear strength",
        ))?;
        let poisson = self.poisson.ok_or(SolverError::Incomplete(
            "the body's Poisson's ratio for a tangential path: its tangential compliance depends on it",
        ))?;
        if self.solid.is_some() {
            return Err(SolverError::Unsupported(
                "tangential loading of a viscoelastic body is not implemented: its shear \
                 relaxes along the path"
                    .into(),
            ));
        }
        elastic::Shear::supports(self.operator.body(), self.operator.domain().periodic)?;
        Ok((friction, poisson))
    }

    /// Refuses `what` on a viscoelastic body, whose answer depends on the path: it is swept
    /// along times ([`ContactProblem::sweep`]).
    pub(crate) fn elastic_only(&self, what: &str) -> Result<()> {
        match self.solid {
            Some(_) => Err(SolverError::Unsupported(format!(
                "{what} on a viscoelastic body: its answer depends on the load history; sweep a \
                 path with a time for each step (a hold is a repeated value)"
            ))),
            None => Ok(()),
        }
    }

    /// On a free grid, a warning when a solution's contact (compressive pressure > 0) or, with
    /// adhesion, its attached zone (gaps within the law's range) reaches the grid's border: the
    /// half-space carries no pressure beyond the grid, so the box is too small and the loads
    /// are off. `None` on periodic grids and inside the border.
    pub fn edge_warning(&self, gap: &Array2<f64>, compressive_pressure: &Array2<f64>) -> Option<String> {
        let domain = self.domain();
        if domain.periodic {
            return None;
        }
        let (ny, nx) = gap.dim();
        let range = if self.adhesive() { self.law.range() } else { 0.0 };
        let reached =
            ndarray::Zip::indexed(gap)
                .and(compressive_pressure)
                .fold(0usize, |n, (j, i), &g, &p| {
                    let border = j == 0 || i == 0 || j == ny - 1 || i == nx - 1;
                    n + usize::from(border && (p > 0.0 || g < range))
                });
        (reached > 0).then(|| {
            format!(
                "the contact{} reaches the edge of the free grid ({reached} border cells): the \
                 half-space carries no pressure beyond the grid, so the loads are off; enlarge \
                 the box (--length)",
                if range > 0.0 { " or the attached zone" } else { "" }
            )
        })
    }

    /// The warnings of this set-up (see [`ContactProblem::warnings`]).
    fn check(&self) -> Vec<String> {
        let mut warnings = Vec::new();
        if !self.adhesive() {
            return warnings;
        }
        let law = self.law.as_ref();
        let domain = self.domain();
        warnings.extend(resolution_warnings(&domain, self.e_star(), law));
        if domain.periodic {
            return warnings;
        }
        // The attraction beyond the grid is lost: the smallest gap on the border says how much.
        // The law's energy there, -V(g), is the share of w0 its tail holds beyond that gap; on a
        // sphere (gap r^2/(2R) outside) the force the tail would add, 2 pi R V(g), is that
        // share of 2 pi R w0 (undeformed).
        let g0 = &self.initial_gap;
        let (ny, nx) = g0.dim();
        let border = g0
            .indexed_iter()
            .filter(|((j, i), _)| *j == 0 || *i == 0 || *j == ny - 1 || *i == nx - 1)
            .map(|(_, g)| *g)
            .fold(f64::INFINITY, f64::min);
        let share = law
            .flat_potential()
            .map(|v| -v.energy(border) / law.work_of_adhesion());
        if border < 10.0 * law.range() && share.is_none_or(|s| s > 1e-3) {
            let held = share.map_or(String::new(), |s| {
                format!(
                    " (the law holds {:.1} % of w0 beyond that gap: on a sphere, about that share \
                     of 2 pi R w0 is missing from the loads)",
                    100.0 * s
                )
            });
            warnings.push(format!(
                "the undeformed gap at the grid's edge is only {:.2} times the adhesive range: \
                 the attraction beyond the grid is cut off{held}; enlarge the box (gap >= 10 ranges)",
                border / law.range()
            ));
        }
        warnings
    }
}

/// Roughly the peak memory \[bytes\] a solve on an `nx` x `ny` grid takes with `method`
/// (`None`: without adhesion; `Auto` counts as Newton, the largest): the bytes a cell measured
/// at 256^2-1024^2 (`docs/performance.md`), Newton's Krylov basis apart (it is capped on large
/// grids), plus a fixed 16 MiB. For refusing a grid the machine cannot hold before anything is
/// allocated; not a bound.
pub fn memory_estimate(nx: usize, ny: usize, periodic: bool, method: Option<Method>) -> f64 {
    // Counted in f64: a grid too large to hold is to be refused, not to overflow the count.
    let cells = nx as f64 * ny as f64;
    let bytes = match method {
        None => 128.0 * cells,
        Some(method) => crate::adhesive::peak_bytes(method, cells, periodic),
    };
    bytes + 16.0 * 1024.0 * 1024.0
}

impl std::fmt::Debug for ContactProblem {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ContactProblem")
            .field("domain", &self.domain())
            .field("e_star", &self.e_star())
            .field("law", &self.law.name())
            .field("warnings", &self.warnings)
            .finish_non_exhaustive()
    }
}

/// Warnings about a grid too coarse for the law: the cohesive (process-zone) length
/// `E* w0 / sigma0^2` must span at least one cell, or the adhesive zone at a contact edge
/// falls inside one cell. Each message says how fine the grid should be.
fn resolution_warnings(domain: &Domain, e_star: f64, law: &dyn AdhesionLaw) -> Vec<String> {
    let process_zone = law.process_zone(e_star);
    let cell = domain.dx.max(domain.dy);
    let mut warnings = Vec::new();
    if cell > process_zone {
        warnings.push(format!(
            "the cell size {cell:.3e} m exceeds the adhesive process-zone length E* w0 / sigma0^2 = \
             {process_zone:.3e} m: the attractive zone at contact edges is not resolved; use a cell \
             of at most {process_zone:.3e} m ({} cells across this domain) for mesh-converged \
             adhesion",
            (domain.nx as f64 * domain.dx / process_zone).ceil()
        ));
    }
    warnings
}

/// Builds a [`ContactProblem`] from a geometry, a surface, a material and a law:
///
/// ```
/// use ljadhesion::{LennardJones, SurfaceLaw};
/// use solver::ContactProblem;
///
/// let law = SurfaceLaw(LennardJones::new(0.05, 1e-9)?);
/// let problem = ContactProblem::builder()
///     .grid(64, 64, 2e-7, 2e-7)
///     .sphere(1e-6)
///     .modulus(1e9)
///     .law(law)
///     .build()?;
/// assert!(!problem.domain().periodic);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Default)]
pub struct ProblemBuilder {
    modulus: Option<f64>,
    grid: Option<(usize, usize, f64, f64)>,
    roughness: Option<Array2<f64>>,
    shape: Shape,
    periodic: Option<bool>,
    law: Option<Arc<dyn AdhesionLaw>>,
    interface: Interface,
    body: Body,
    maxwell: Option<(Vec<f64>, Vec<f64>)>,
    poisson: Option<f64>,
    counterface: crate::friction::Counterface,
}

impl ProblemBuilder {
    /// The composite modulus E* \[Pa\] (required): with a [`ProblemBuilder::layer`], the
    /// layer's plane-strain modulus `E / (1 - nu^2)`.
    pub fn modulus(mut self, e_star: f64) -> Self {
        self.modulus = Some(e_star);
        self
    }

    /// A grid of `nx` by `ny` cells spanning `length_x` by `length_y` \[m\]; with roughness, its
    /// shape must match the heights'.
    pub fn grid(mut self, nx: usize, ny: usize, length_x: f64, length_y: f64) -> Self {
        self.grid = Some((nx, ny, length_x, length_y));
        self
    }

    /// Roughness heights \[m\] of shape `(ny, nx)` (peaks towards the half-space) spanning
    /// `length_x` by `length_y` \[m\]: they set the grid.
    pub fn roughness(mut self, heights: Array2<f64>, length_x: f64, length_y: f64) -> Self {
        let (ny, nx) = heights.dim();
        self.grid = Some((nx, ny, length_x, length_y));
        self.roughness = Some(heights);
        self
    }

    /// The counterface's shape (a flat by default).
    pub fn shape(mut self, shape: Shape) -> Self {
        self.shape = shape;
        self
    }

    /// A paraboloidal sphere of radius `radius` \[m\].
    pub fn sphere(self, radius: f64) -> Self {
        self.shape(Shape::Sphere {
            radius,
            profile: SphereProfile::Paraboloid,
        })
    }

    /// A wave of amplitude `amplitude` \[m\].
    pub fn wave(self, amplitude: f64) -> Self {
        self.shape(Shape::Wave { amplitude })
    }

    /// Periodic (the pattern repeats) or free (an isolated contact) boundaries; by default
    /// free for a sphere, periodic otherwise.
    pub fn periodic(mut self, periodic: bool) -> Self {
        self.periodic = Some(periodic);
        self
    }

    /// The adhesive law (none by default).
    pub fn law(mut self, law: impl AdhesionLaw + 'static) -> Self {
        self.law = Some(Arc::new(law));
        self
    }

    /// A hardness `H` \[Pa\]: the surface yields where the compressive pressure would exceed
    /// it ([`crate::interface`]); elastic by default.
    pub fn hardness(mut self, hardness: f64) -> Self {
        self.interface.hardness = Some(hardness);
        self
    }

    /// Friction for tangential paths ([`crate::friction`]); frictionless by default.
    pub fn friction(mut self, friction: crate::friction::Friction) -> Self {
        self.interface.friction = Some(friction);
        self
    }

    /// The body's Poisson's ratio `nu` [-] in (-1, 0.5], for its tangential compliance (a
    /// layer's is the layer's own).
    pub fn poisson(mut self, poisson: f64) -> Self {
        self.poisson = Some(poisson);
        self
    }

    /// What presses the body ([`crate::friction::Counterface`]); of its own material by
    /// default (the decoupled tangential problem).
    pub fn counterface(mut self, counterface: crate::friction::Counterface) -> Self {
        self.counterface = counterface;
        self
    }

    /// A viscoelastic body: branches of `moduli` \[Pa\] relaxing in `times` \[s\] beside the
    /// relaxed modulus ([`ProblemBuilder::modulus`]), a generalized Maxwell solid
    /// ([`crate::time`]); elastic by default.
    pub fn maxwell(mut self, moduli: &[f64], times: &[f64]) -> Self {
        self.maxwell = Some((moduli.to_vec(), times.to_vec()));
        self
    }

    /// An elastic layer of finite thickness on a rigid base for the body ([`elastic::Layer`]);
    /// a half-space by default. On periodic grids the approach is then measured from the base
    /// (`crate::mean_mode`).
    pub fn layer(mut self, layer: Layer) -> Self {
        self.body = Body::Layer(layer);
        self
    }

    /// [`ProblemBuilder::law`] for a shared law.
    pub fn shared_law(mut self, law: Arc<dyn AdhesionLaw>) -> Self {
        self.law = Some(law);
        self
    }

    /// The problem.
    ///
    /// # Errors
    /// A missing modulus or grid, nothing to press (a flat with no roughness), heights whose
    /// shape differs from the grid's, a wave on a free domain, a hardness that is not finite
    /// and positive or not above the law's attraction at contact, and the geometry's and the
    /// operators' own checks.
    pub fn build(self) -> Result<ContactProblem> {
        let e_star = self
            .modulus
            .ok_or(SolverError::Incomplete("the composite modulus E* [Pa]"))?;
        if !(e_star.is_finite() && e_star > 0.0) {
            return Err(invalid("modulus", e_star, "must be a finite E* > 0 Pa"));
        }
        let (nx, ny, lx, ly) = self.grid.ok_or(SolverError::Incomplete(
            "the grid: its cells and size, or roughness heights with their size [m]",
        ))?;
        for (name, l) in [("length_x", lx), ("length_y", ly)] {
            if !(l.is_finite() && l > 0.0) {
                return Err(invalid(name, l, "must be a finite length > 0 m"));
            }
        }
        if let Some(h) = &self.roughness
            && h.dim() != (ny, nx)
        {
            return Err(SolverError::ShapeMismatch {
                what: "roughness heights",
                expected: (ny, nx),
                got: h.dim(),
            });
        }
        let periodic = self
            .periodic
            .unwrap_or(!matches!(self.shape, Shape::Sphere { .. }));
        let domain = Domain {
            nx,
            ny,
            dx: lx / nx as f64,
            dy: ly / ny as f64,
            periodic,
        };
        let roughness = self.roughness.as_ref().map(|h| h.view());
        let initial_gap = match self.shape {
            Shape::Flat => flat_on_rough(roughness.ok_or(SolverError::Incomplete(
                "something to press: roughness, a sphere or a wave",
            ))?)?,
            Shape::Sphere { radius, profile } => sphere(&domain, radius, profile, roughness)?,
            Shape::Wave { amplitude } => {
                if !periodic {
                    return Err(SolverError::Unsupported(
                        "a wave repeats: it needs the periodic domain".into(),
                    ));
                }
                wave(&domain, amplitude, roughness)?
            }
        };
        let operator: Arc<dyn Compliance> = if periodic {
            Arc::new(Periodic::with_body(domain, e_star, self.body)?)
        } else {
            Arc::new(Free::with_body(domain, e_star, self.body)?)
        };
        self.interface.validate()?;
        let law = self.law.unwrap_or_else(|| Arc::new(NoAdhesion));
        self.interface.check_law(law.as_ref())?;
        let solid = match &self.maxwell {
            Some((moduli, times)) => {
                let solid = elastic::Maxwell::new(e_star, moduli, times).map_err(|e| {
                    SolverError::InvalidParameter {
                        name: e.name,
                        value: e.value,
                        reason: e.reason,
                    }
                })?;
                crate::time::check(&solid, operator.as_ref())?;
                Some(solid)
            }
            None => None,
        };
        if let Some(nu) = self.poisson
            && !(nu > -1.0 && nu <= 0.5)
        {
            return Err(invalid("poisson", nu, "must lie in (-1, 0.5]"));
        }
        let mut problem = ContactProblem::from_shared(operator, initial_gap, law)?;
        problem.interface = self.interface;
        problem.solid = solid;
        problem.poisson = self.poisson;
        problem.counterface = self.counterface;
        Ok(problem)
    }
}
