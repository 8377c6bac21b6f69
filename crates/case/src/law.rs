//! The adhesive laws a case can name, and each law made from the case's keys.

use crate::Case;
use crate::error::{Context, Result, bail};
use ljadhesion::{
    AdhesionLaw, DugdaleLaw, ExponentialLaw, LennardJones, LineLaw, NoAdhesion, PointLaw, SurfaceEnergyLaw,
    SurfaceLaw,
};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// The laws, one entry each: the variant of [`LawKind`] with its doc (the help text), its name
/// in case files (on the command line the same in kebab-case), whether the law takes `z0`, and
/// how it is made from the keys. Adding a law is its type in `ljadhesion` and one entry here.
macro_rules! laws {
    ($($(#[doc = $doc:literal])* $variant:ident = $name:literal (z0: $z0:literal) => $make:expr,)*) => {
        /// An adhesive law by its name in case files and on the command line.
        #[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
        #[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
        pub enum LawKind {
            $($(#[doc = $doc])* #[serde(rename = $name)] $variant,)*
        }

        impl LawKind {
            /// Every law, in the table's order.
            pub const ALL: &'static [LawKind] = &[$(LawKind::$variant),*];

            /// The law's name in case files.
            pub fn name(self) -> &'static str {
                match self {
                    $(LawKind::$variant => $name,)*
                }
            }

            /// Whether the law takes the key `z0` (the Lennard-Jones laws' equilibrium separation).
            pub fn takes_z0(self) -> bool {
                match self {
                    $(LawKind::$variant => $z0,)*
                }
            }

            /// The law from the case's keys.
            fn make(self, keys: &LawKeys) -> Result<Arc<dyn AdhesionLaw>> {
                match self {
                    $(LawKind::$variant => {
                        let make: fn(&LawKeys) -> Result<Arc<dyn AdhesionLaw>> = $make;
                        make(keys)
                    })*
                }
            }
        }
    };
}

laws! {
    /// No adhesion.
    None = "none" (z0: false) => |_| Ok(Arc::new(NoAdhesion)),
    /// Lennard-Jones averaged over the tilted cell (the paper's Eq. 11).
    Surface = "surface" (z0: true) => |k| Ok(Arc::new(SurfaceLaw(k.lennard_jones()?))),
    /// Minus the gradient of the Lennard-Jones energy integrated over the tilted cells: Eq. 11's
    /// energy form, which the energy descent minimises.
    SurfaceEnergy = "surface_energy" (z0: true) => |k| Ok(Arc::new(SurfaceEnergyLaw(k.lennard_jones()?))),
    /// Lennard-Jones averaged along x (Medina & Dini 2014).
    Line = "line" (z0: true) => |k| Ok(Arc::new(LineLaw(k.lennard_jones()?))),
    /// Lennard-Jones at the node.
    Point = "point" (z0: true) => |k| Ok(Arc::new(PointLaw(k.lennard_jones()?))),
    /// -(w0/range) exp(-g/range), the contact-mechanics challenge's law.
    Exponential = "exponential" (z0: false) => |k| Ok(Arc::new(ExponentialLaw::new(
        k.work_of_adhesion()?,
        k.range.context("the exponential law needs --range rho [m]")?,
    )?)),
    /// -w0/range for g < range (Maugis-Dugdale).
    Dugdale = "dugdale" (z0: true) => |k| k.dugdale(),
}

/// The keys a law is made from.
struct LawKeys {
    work_of_adhesion: Option<f64>,
    z0: Option<f64>,
    range: Option<f64>,
}

impl LawKeys {
    fn work_of_adhesion(&self) -> Result<f64> {
        self.work_of_adhesion
            .context("adhesion needs --work-of-adhesion w0 [J/m^2]")
    }

    /// The Lennard-Jones law of `w0` and `z0`; its range is `z0`, so `range` is refused.
    fn lennard_jones(&self) -> Result<LennardJones> {
        let w0 = self.work_of_adhesion()?;
        if let Some(range) = self.range {
            bail!(
                "--range {range:e} does not apply to the Lennard-Jones laws, whose range is \
                 --z0 (--range is the exponential and Dugdale laws')"
            );
        }
        let z0 = self
            .z0
            .context("the Lennard-Jones laws need --z0 [m], the equilibrium separation")?;
        Ok(LennardJones::new(w0, z0)?)
    }

    /// Dugdale's law of range `range`, or the one equivalent to the Lennard-Jones law of `z0`.
    fn dugdale(&self) -> Result<Arc<dyn AdhesionLaw>> {
        let w0 = self.work_of_adhesion()?;
        Ok(match (self.range, self.z0) {
            (Some(_), Some(_)) => {
                bail!("the Dugdale law takes --range h0 [m] or --z0 (the LJ-equivalent one), not both")
            }
            (Some(h0), None) => Arc::new(DugdaleLaw::new(w0, h0)?),
            (None, Some(_)) => Arc::new(DugdaleLaw::equivalent_to(&self.lennard_jones()?)),
            (None, None) => {
                bail!("the Dugdale law needs --range h0 [m] (or --z0 for the LJ-equivalent one)")
            }
        })
    }
}

impl Case {
    /// The case's adhesive law (none without one).
    pub fn law(&self) -> Result<Arc<dyn AdhesionLaw>> {
        self.law.unwrap_or(LawKind::None).make(&LawKeys {
            work_of_adhesion: self.work_of_adhesion,
            z0: self.z0,
            range: self.range,
        })
    }
}
