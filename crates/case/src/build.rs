//! A case's problem: the keys that do not apply refused, the surface read or generated, the
//! geometry, material and law put together.

use crate::error::{Context, Error, Result, bail};
use crate::{Built, Case, Counterface, DomainKind, LawKind, LayerBase, fingerprint};
use solver::geometry::SphereProfile;
use solver::{ContactProblem, ProblemBuilder, Shape};
use std::path::Path;
use surfgen::io::{self, ReadOptions, Surface};
use surfgen::{Amplitudes, Grid, Normalization, Psd, SurfError, SurfaceSpec};

impl Case {
    /// Refuses every key given that the case would not use: a key of a surface file without
    /// one, a generated surface's keys without a generated surface, a sphere's without a
    /// sphere, adhesion's keys without adhesion or with a law that has no use for them. The one
    /// place where keys that do not apply are refused, so that the record of a run is always
    /// what was solved.
    pub fn check_applicable(&self) -> Result<()> {
        let file = self.surface.is_some();
        let generated = self.rms_height.is_some() || self.rms_gradient.is_some();
        let law = self.law.unwrap_or(if self.adhesive() {
            LawKind::Surface
        } else {
            LawKind::None
        });
        let coating = self.layer_base == Some(LayerBase::Elastic);
        let refused: [(&str, bool, &str); 19] = [
            (
                "rms_height",
                self.rms_height.is_some() && (file || self.rms_gradient.is_some()),
                "scales a generated surface; give it or --rms-gradient, and no --surface beside",
            ),
            (
                "rms_gradient",
                self.rms_gradient.is_some() && file,
                "scales a generated surface; give no --surface beside",
            ),
            (
                "max_unmeasured",
                self.max_unmeasured.is_some() && !file,
                "bounds the filled points of a surface file: give --surface",
            ),
            (
                "unit",
                self.unit.is_some() && !file,
                "is a surface file's unit: give --surface",
            ),
            (
                "channel",
                self.channel.is_some() && !file,
                "is a surface file's channel: give --surface",
            ),
            (
                "fill_unmeasured",
                self.fill_unmeasured.is_some() && !file,
                "fills a surface file's unmeasured points: give --surface",
            ),
            (
                "hurst",
                self.hurst.is_some() && !generated,
                "shapes a generated surface: give --rms-height or --rms-gradient",
            ),
            (
                "rolloff_wavelength",
                self.rolloff_wavelength.is_some() && !generated,
                "shapes a generated surface: give --rms-height or --rms-gradient",
            ),
            (
                "cutoff_wavelength",
                self.cutoff_wavelength.is_some() && !generated,
                "shapes a generated surface: give --rms-height or --rms-gradient",
            ),
            (
                "seed",
                self.seed.is_some() && !generated,
                "seeds a generated surface: give --rms-height or --rms-gradient",
            ),
            (
                "exact_sphere",
                self.exact_sphere.is_some() && self.sphere_radius.is_none(),
                "shapes a sphere: give --sphere-radius",
            ),
            (
                "work_of_adhesion",
                self.work_of_adhesion.is_some() && law == LawKind::None,
                "needs an adhesive law, but --law none",
            ),
            (
                "z0",
                self.z0.is_some() && !law.takes_z0(),
                "is the Lennard-Jones laws' (and Dugdale's LJ-equivalent) equilibrium separation; \
                 this case has no such law",
            ),
            (
                "poisson",
                self.poisson.is_some() && self.thickness.is_none() && !self.frictional(),
                "is a layer's Poisson's ratio (give --thickness) or the body's for a tangential \
                 path (give --friction-coefficient): a half-space under a normal load takes E* alone",
            ),
            (
                "counterface",
                self.counterface.is_some() && !self.frictional(),
                "sets how a tangential path couples to the normal contact: give \
                 --friction-coefficient or --shear-strength",
            ),
            (
                "layer_base",
                self.layer_base.is_some() && self.thickness.is_none(),
                "says how a layer meets its base: give --thickness",
            ),
            (
                "substrate_modulus",
                self.substrate_modulus.is_some() && !coating,
                "is a coating's substrate: give --layer-base elastic (and --thickness)",
            ),
            (
                "substrate_poisson",
                self.substrate_poisson.is_some() && !coating,
                "is a coating's substrate: give --layer-base elastic (and --thickness)",
            ),
            (
                "solver",
                self.solver.is_some() && law == LawKind::None,
                "chooses the adhesive solver; without adhesion the conjugate gradients solve",
            ),
        ];
        if let Some((key, _, why)) = refused.iter().find(|(_, given, _)| *given) {
            bail!(
                "--{} does not apply to this case: it {why}",
                key.replace('_', "-")
            );
        }
        Ok(())
    }

    /// Builds the problem; call [`Case::fill_defaults`] first.
    pub fn build(&self) -> Result<Built> {
        self.build_on(None)
    }

    /// Builds the problem on `roughness` (a surface in memory) instead of the `surface` file;
    /// call [`Case::fill_defaults`] first.
    pub fn build_on(&self, roughness: Option<Surface>) -> Result<Built> {
        self.check_applicable()?;
        let e_star = self.modulus.context(
            "the composite modulus is required: --modulus E* [Pa] (or modulus = ... in the case file)",
        )?;
        if !(e_star.is_finite() && e_star > 0.0) {
            bail!("--modulus must be a finite E* > 0 Pa, got {e_star}");
        }
        let law = self.law()?;
        let periodic = self.domain.unwrap_or(DomainKind::Periodic) == DomainKind::Periodic;
        let check_memory = |nx: usize, ny: usize, lx: f64, ly: f64| {
            let domain = elastic::Domain {
                nx,
                ny,
                dx: lx / nx as f64,
                dy: ly / ny as f64,
                periodic,
            };
            // Auto as under approach control: the larger of its choices.
            let method = (law.work_of_adhesion() > 0.0).then(|| {
                self.settings().method.resolve(
                    law.as_ref(),
                    solver::Control::Approach(0.0),
                    &domain,
                    domain.cell_compliance(e_star),
                    &solver::Interface {
                        hardness: self.hardness,
                        friction: None,
                    },
                )
            });
            crate::memory::check(
                &format!("a {nx} x {ny} solve"),
                solver::memory_estimate(nx, ny, periodic, method),
            )
        };
        let mut builder = ContactProblem::builder()
            .modulus(e_star)
            .shared_law(law.clone())
            .periodic(periodic);
        if self.frictional() {
            let friction = solver::Friction::new(
                self.friction_coefficient.unwrap_or(0.0),
                self.shear_strength.unwrap_or(0.0),
            )
            .map_err(|e| match e {
                solver::SolverError::InvalidParameter { name, value, reason } => {
                    Error::Key(format!("--{} {reason}, got {value}", name.replace('_', "-")))
                }
                other => Error::Key(other.to_string()),
            })?;
            let nu = self
                .poisson
                .context("friction needs the body's --poisson: its tangential compliance depends on it")?;
            builder = builder
                .friction(friction)
                .poisson(nu)
                .counterface(match self.counterface {
                    Some(Counterface::Rigid) => solver::Counterface::Rigid,
                    Some(Counterface::Similar) | None => solver::Counterface::Similar,
                });
        } else if let Some(nu) = self.poisson {
            builder = builder.poisson(nu);
        }
        if let Some(h) = self.hardness {
            if !(h.is_finite() && h > 0.0) {
                bail!("--hardness must be a finite H > 0 Pa (omit it for an elastic surface), got {h}");
            }
            builder = builder.hardness(h);
        }
        match (&self.maxwell_moduli, &self.maxwell_times) {
            (Some(moduli), Some(times)) => {
                // The solid's own checks, worded for the keys (the relaxed modulus is E*'s).
                elastic::Maxwell::new(e_star, moduli, times).map_err(|e| {
                    Error::Key(format!(
                        "--{} {}, got {}",
                        e.name.replace('_', "-"),
                        e.reason,
                        e.value
                    ))
                })?;
                builder = builder.maxwell(moduli, times);
            }
            (None, None) => {}
            (Some(_), None) => bail!("--maxwell-moduli needs the branches' --maxwell-times [s]"),
            (None, Some(_)) => bail!("--maxwell-times needs the branches' --maxwell-moduli [Pa]"),
        }
        if let Some(h) = self.thickness {
            let nu = self
                .poisson
                .context("--thickness needs the layer's --poisson: its response depends on it")?;
            let base = match self.layer_base.unwrap_or(LayerBase::Bonded) {
                LayerBase::Bonded => elastic::Base::Bonded,
                LayerBase::Frictionless => elastic::Base::Frictionless,
                LayerBase::Elastic => elastic::Base::Substrate {
                    e_star: self
                        .substrate_modulus
                        .context("--layer-base elastic needs the substrate's --substrate-modulus [Pa]")?,
                    poisson: self
                        .substrate_poisson
                        .context("--layer-base elastic needs the substrate's --substrate-poisson")?,
                },
            };
            let layer = elastic::Layer::new(h, nu, base).map_err(|e| {
                Error::Key(match e {
                    elastic::ElasticError::InvalidParameter { name, value, reason } => {
                        format!("--{} {reason}, got {value}", name.replace('_', "-"))
                    }
                    other => other.to_string(),
                })
            })?;
            builder = builder.layer(layer);
        }
        let (roughness, filled) = self.roughness(roughness)?;
        let (heights, size) = match roughness {
            Some(s) => {
                let expected = (
                    self.n.unwrap_or(s.grid.nx),
                    self.ny.or(self.n).unwrap_or(s.grid.ny),
                );
                if expected != (s.grid.nx, s.grid.ny) {
                    bail!(
                        "--n/--ny ask for {} x {} points, the surface file has {} x {}",
                        expected.0,
                        expected.1,
                        s.grid.nx,
                        s.grid.ny
                    );
                }
                check_memory(s.grid.nx, s.grid.ny, s.grid.length_x, s.grid.length_y).with_context(|| {
                    format!(
                        "the surface file (--surface) of {} x {} points",
                        s.grid.nx, s.grid.ny
                    )
                })?;
                (Some(s.heights), (s.grid.length_x, s.grid.length_y))
            }
            None => {
                let grid = self.grid()?;
                let (n, ny) = (grid.nx, grid.ny);
                check_memory(n, ny, grid.length_x, grid.length_y)
                    .with_context(|| format!("--n {n}, --ny {ny}"))?;
                builder = builder.grid(n, ny, grid.length_x, grid.length_y);
                (self.generated(grid)?, (grid.length_x, grid.length_y))
            }
        };
        let surface_hash = heights.as_ref().map(fingerprint);
        if let Some(h) = heights {
            builder = builder.roughness(h, size.0, size.1);
        }
        let mut problem = self.shaped(builder)?.build()?;
        problem.warnings.extend(filled);
        Ok(Built {
            problem,
            surface_hash,
        })
    }

    /// The roughness given: a surface in memory or the `surface` file's (read, with a note of
    /// the points filled), or none.
    fn roughness(&self, roughness: Option<Surface>) -> Result<(Option<Surface>, Option<String>)> {
        Ok(match (roughness, &self.surface) {
            (Some(_), Some(path)) => bail!(
                "give the roughness once: a surface in memory or the file {}",
                path.display()
            ),
            (Some(s), None) => {
                for (key, given) in [
                    ("length", self.length.is_some()),
                    ("length_y", self.length_y.is_some()),
                    ("unit", self.unit.is_some()),
                    ("channel", self.channel.is_some()),
                    ("fill_unmeasured", self.fill_unmeasured.is_some()),
                    ("max_unmeasured", self.max_unmeasured.is_some()),
                ] {
                    if given {
                        bail!("`{key}` applies to a surface file; a surface in memory carries its own size");
                    }
                }
                (Some(s), None)
            }
            (None, Some(path)) => {
                let options = ReadOptions {
                    length_x: self.length,
                    length_y: self.length_y,
                    unit: self.unit.unwrap_or(1.0),
                    periodic: true,
                    channel: None,
                    unmeasured: io::Unmeasured::filled_up_to(
                        self.fill_unmeasured == Some(true),
                        self.max_unmeasured,
                    )?,
                };
                let read = options
                    .with_channel(path, self.channel.as_deref())
                    .and_then(|options| io::read_noting(path, &options));
                let (surface, note) = read
                    .map_err(|e| naming("reading", path, e))
                    .context("--surface")?;
                (Some(surface), note)
            }
            (None, None) => (None, None),
        })
    }

    /// The roughness the case presses, read or generated, on its grid; `None` for a smooth
    /// body.
    pub fn rough_surface(&self) -> Result<Option<Surface>> {
        if let (Some(surface), _) = self.roughness(None)? {
            return Ok(Some(surface));
        }
        let grid = self.grid()?;
        match self.generated(grid)? {
            Some(heights) => Ok(Some(Surface::new(heights, grid, true)?)),
            None => Ok(None),
        }
    }

    /// The grid of a case without a surface file: `n` (and `ny`) points over `length` (and
    /// `length_y`).
    fn grid(&self) -> Result<Grid> {
        let generated = self.rms_height.is_some() || self.rms_gradient.is_some();
        if self.sphere_radius.is_none() && self.wave_amplitude.is_none() && !generated {
            bail!(
                "nothing to press: give --surface FILE, --rms-height/--rms-gradient (a generated \
                 surface) and/or --sphere-radius R or --wave-amplitude A [m]"
            );
        }
        let n = self.n.unwrap_or(256);
        let ny = self.ny.unwrap_or(n);
        let l = self
            .length
            .context("the grid needs its size: --length L [m] (and --n)")?;
        for (key, points) in [("n", n), ("ny", ny)] {
            if points < 2 {
                bail!("--{key} must be at least 2 grid points, got {points}");
            }
        }
        if !(l > 0.0 && l <= surfgen::grid::MAX_LENGTH) {
            bail!("--length must be > 0 m and at most 1e100 m, got {l:?}");
        }
        let ly = self.length_y.unwrap_or(l * ny as f64 / n as f64);
        if !(ly > 0.0 && ly <= surfgen::grid::MAX_LENGTH) {
            bail!("--length-y must be > 0 m and at most 1e100 m, got {ly:?}");
        }
        Ok(Grid::new(n, ny, l, ly)?)
    }

    /// The generated roughness on `grid`, if the case asks for one (`rms_height` or
    /// `rms_gradient`).
    fn generated(&self, grid: Grid) -> Result<Option<ndarray::Array2<f64>>> {
        let normalization = match (self.rms_height, self.rms_gradient) {
            (Some(rq), _) => Normalization::RmsHeight(rq),
            (None, Some(g)) => Normalization::RmsGradient(g),
            (None, None) => return Ok(None),
        };
        let spec = SurfaceSpec {
            grid,
            psd: Psd::self_affine(
                self.hurst.unwrap_or(0.8),
                self.rolloff_wavelength
                    .unwrap_or(grid.length_x.max(grid.length_y) / 4.0),
                self.cutoff_wavelength.unwrap_or(4.0 * grid.dx().max(grid.dy())),
            ),
            normalization,
            amplitudes: Amplitudes::Exact,
            seed: self.seed.unwrap_or(1),
        };
        Ok(Some(surfgen::generate(&spec)?.heights))
    }

    /// `builder` with the case's sphere or wave, if any.
    fn shaped(&self, builder: ProblemBuilder) -> Result<ProblemBuilder> {
        Ok(match (self.sphere_radius, self.wave_amplitude) {
            (Some(_), Some(_)) => bail!("give --sphere-radius or --wave-amplitude, not both"),
            (Some(radius), None) => builder.shape(Shape::Sphere {
                radius,
                profile: if self.exact_sphere.unwrap_or(false) {
                    SphereProfile::Exact
                } else {
                    SphereProfile::Paraboloid
                },
            }),
            (None, Some(amplitude)) => {
                if self.domain == Some(DomainKind::Free) {
                    bail!("a wave repeats: it needs the periodic domain (--domain periodic)");
                }
                builder.wave(amplitude)
            }
            (None, None) => builder,
        })
    }
}

/// A surface file's error, with the file named once: the reader's own errors already name it.
pub fn naming(verb: &str, path: &Path, e: SurfError) -> Error {
    match e {
        SurfError::Io { .. } | SurfError::Parse { .. } => e.into(),
        _ => Error::Context {
            context: format!("{verb} {}", path.display()),
            source: Box::new(e.into()),
        },
    }
}
