//! The figures' cases: what the command line's case file would say, as plain data that keys
//! the cache, built into the library's [`ContactProblem`] by its builder.

use anyhow::{Context, Result};
use ljadhesion::{AdhesionLaw, ExponentialLaw, LennardJones, NoAdhesion, PointLaw, SurfaceLaw};
use ndarray::Array2;
use serde::{Deserialize, Serialize};
use solver::ContactProblem;
use std::path::PathBuf;
use std::sync::Arc;
use surfgen::io::{self, ReadOptions};
use surfgen::{Amplitudes, Grid, Normalization, Psd, SurfaceSpec};

/// The adhesive laws the figures use.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Law {
    /// Lennard-Jones averaged over the tilted cell (the paper's Eq. 11).
    Surface,
    /// Lennard-Jones at the node.
    Point,
    /// The contact-mechanics challenge's exponential law.
    Exponential,
}

impl Law {
    /// The law's name on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Law::Point => "point",
            Law::Surface => "surface",
            Law::Exponential => "exponential",
        }
    }
}

/// A case, in the command line's terms and units (SI).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct Case {
    /// A topography file instead of a generated surface.
    pub surface: Option<PathBuf>,
    /// Generated roughness, normalised by its RMS height \[m\] or RMS gradient [-].
    pub rms_height: Option<f64>,
    pub rms_gradient: Option<f64>,
    /// Generated roughness: Hurst exponent [-], roll-off and cut-off wavelengths \[m\], seed.
    pub hurst: Option<f64>,
    pub rolloff_wavelength: Option<f64>,
    pub cutoff_wavelength: Option<f64>,
    pub seed: Option<u64>,
    /// Cells per side, box side \[m\].
    pub n: Option<usize>,
    pub length: Option<f64>,
    /// A rigid sphere's radius \[m\]: a free domain, else periodic.
    pub sphere_radius: Option<f64>,
    /// E* \[Pa\].
    pub modulus: f64,
    /// The law, its work w0 [J/m^2], z0 \[m\] (Lennard-Jones) and range \[m\] (exponential).
    pub law: Option<Law>,
    pub work_of_adhesion: Option<f64>,
    pub z0: Option<f64>,
    pub range: Option<f64>,
}

impl Case {
    /// The roughness heights \[m\] with the box's sides \[m\], if the case has roughness.
    pub fn heights(&self) -> Result<Option<(Array2<f64>, f64, f64)>> {
        if let Some(path) = &self.surface {
            let options = ReadOptions {
                length_x: self.length,
                ..Default::default()
            };
            let s = io::read(path, &options).with_context(|| format!("reading {}", path.display()))?;
            return Ok(Some((s.heights, s.grid.length_x, s.grid.length_y)));
        }
        let normalization = match (self.rms_height, self.rms_gradient) {
            (Some(rq), _) => Normalization::RmsHeight(rq),
            (None, Some(g)) => Normalization::RmsGradient(g),
            (None, None) => return Ok(None),
        };
        let (n, l) = self.grid()?;
        let grid = Grid::new(n, n, l, l)?;
        let spec = SurfaceSpec {
            grid,
            psd: Psd::self_affine(
                self.hurst.unwrap_or(0.8),
                self.rolloff_wavelength.unwrap_or(l / 4.0),
                self.cutoff_wavelength.unwrap_or(4.0 * grid.dx()),
            ),
            normalization,
            amplitudes: Amplitudes::Exact,
            seed: self.seed.unwrap_or(1),
        };
        Ok(Some((surfgen::generate(&spec)?.heights, l, l)))
    }

    fn grid(&self) -> Result<(usize, f64)> {
        Ok((
            self.n.unwrap_or(256),
            self.length.context("a generated grid needs its length")?,
        ))
    }

    /// The adhesive law (none without one).
    pub fn law(&self) -> Result<Arc<dyn AdhesionLaw>> {
        let Some(kind) = self.law else {
            return Ok(Arc::new(NoAdhesion));
        };
        let w0 = self.work_of_adhesion.context("adhesion needs its work")?;
        let lj = || -> Result<LennardJones> { Ok(LennardJones::new(w0, self.z0.context("z0")?)?) };
        Ok(match kind {
            Law::Surface => Arc::new(SurfaceLaw(lj()?)),
            Law::Point => Arc::new(PointLaw(lj()?)),
            Law::Exponential => Arc::new(ExponentialLaw::new(w0, self.range.context("range")?)?),
        })
    }

    /// The problem.
    pub fn build(&self) -> Result<ContactProblem> {
        let mut builder = ContactProblem::builder()
            .modulus(self.modulus)
            .shared_law(self.law()?);
        builder = match self.heights()? {
            Some((h, lx, ly)) => builder.roughness(h, lx, ly),
            None => {
                let (n, l) = self.grid()?;
                builder.grid(n, n, l, l)
            }
        };
        if let Some(r) = self.sphere_radius {
            builder = builder.sphere(r);
        }
        Ok(builder.build()?)
    }
}
