//! Which adhesive method solves a problem, and how hard it tries.
//!
//! The five methods (`docs/solvers.md` says which one when) share one entry point,
//! [`crate::ContactProblem::solve`], one set of [`Settings`] and one report. [`Method::Auto`]
//! is resolved here, from the law and the control, so the library and the command line pick
//! the same method for the same problem.

use crate::error::{Result, invalid};
use crate::interface::Interface;
use crate::options::{ContactOptions, Control};
use elastic::Domain;
use ljadhesion::AdhesionLaw;

/// The adhesive methods, one entry each: the variant of [`Method`] with its doc, its name on
/// the command line and in case files, and its implementation (a type in `adhesive/` that
/// implements `AdhesiveMethod`). `$then` is the macro that expands the table: [`Method`] here,
/// the dispatch in `adhesive`. Adding a method is its folder (declared by its `mod` line in
/// `adhesive`) and one entry.
macro_rules! adhesive_methods {
    ($then:ident) => {
        $then! {
            /// The tested choice for the law, the control and the grid: the energy descent,
            /// Newton or the flow where one of them is, else the accelerated loop
            /// (`Method::resolve`).
            #[default]
            Auto = "auto" => dual_loop::DualLoop { accelerated: true },
            /// The paper's relaxation of the adhesive pressure, `p_a <- p_a + beta (law(g) - p_a)`,
            /// around non-adhesive inner solves (the paper's Fig. 4).
            DualLoop = "dual-loop" => dual_loop::DualLoop { accelerated: false },
            /// The dual loop with Anderson mixing of the adhesive pressure: the same fixed point in
            /// fewer outer iterations. Any law and control.
            Accelerated = "accelerated" => dual_loop::DualLoop { accelerated: true },
            /// No outer loop: constrained conjugate gradients on the total energy, for laws with an
            /// energy (point, surface-energy, exponential), under approach control, or load control on
            /// periodic domains.
            EnergyDescent = "energy" => energy::EnergyDescent,
            /// No outer loop: Newton-Krylov on the cells' force balance with pseudo-transient
            /// continuation, for any law but Dugdale's (the surface law included), under approach
            /// control.
            Newton = "newton" => newton::Newton,
            /// No outer loop: a damped relaxation of the cells under the force on them (FIRE) in
            /// explicit projected steps until it rests, for any law with a finite stiffness (the line
            /// and surface laws included), under approach control, or load control on periodic
            /// domains. It settles on stable states where no other method converges (the surface law
            /// on cells far coarser than the process zone), in many cheap iterations.
            Flow = "flow" => flow::Flow,
        }
    };
}
pub(crate) use adhesive_methods;

/// [`Method`], [`Method::ALL`] and [`Method::name`] from the table (the implementations are
/// the dispatch's).
macro_rules! define_methods {
    ($($(#[$meta:meta])* $variant:ident = $name:literal => $implementation:expr,)*) => {
        /// An adhesive solution method, named on the command line and in case files by
        /// [`Method::name`]; `Auto` is the default.
        #[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
        #[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
        pub enum Method {
            $(
                $(#[$meta])*
                #[cfg_attr(feature = "clap", value(name = $name))]
                $variant,
            )*
        }

        impl Method {
            /// Every method, `Auto` first.
            pub const ALL: &'static [Method] = &[$(Method::$variant),*];

            /// The method's name as the command line takes it.
            pub fn name(self) -> &'static str {
                match self {
                    $(Method::$variant => $name,)*
                }
            }
        }
    };
}
adhesive_methods!(define_methods);

impl Method {
    /// The ratio of the law's stiffness bound to a cell's own elastic stiffness above which
    /// [`Method::resolve`] takes the flow rather than Newton under approach control
    /// (`docs/decisions.md`: the two take the same time near 5-8).
    pub const FLOW_ABOVE: f64 = 8.0;

    /// The method for `law` under `control` on `domain`, whose cells have the compliance
    /// `cell_compliance` \[m/Pa\] ([`elastic::Compliance::cell_compliance`]), across
    /// `interface`: itself, or for [`Method::Auto`] the energy descent for the laws with an
    /// energy (local, or of the field without a hardness, which the
    /// descent does not take with it); for the other laws with a flat potential (the line
    /// and surface laws, and the surface-energy law under a hardness) under approach control
    /// Newton where the law's stiffness bound is at most [`Method::FLOW_ABOVE`] times a cell's
    /// own elastic stiffness, else the flow (on coarser cells, where each cell holds on or lets
    /// go alone, Newton circles between states); the flow for them under load control on periodic domains; the
    /// accelerated loop elsewhere (central-gap control, Dugdale's law, no adhesion, loads on
    /// free domains). Near a fold the accelerated loop leaves a branch early, where the methods
    /// that relax from the last state hold on; under load control on coarse cells it circles
    /// with the line and surface laws, where the flow settles (`docs/solvers.md`).
    pub fn resolve(
        self,
        law: &dyn AdhesionLaw,
        control: Control,
        domain: &Domain,
        cell_compliance: f64,
        interface: &Interface,
    ) -> Method {
        if self != Method::Auto {
            return self;
        }
        let approach = matches!(control, Control::Approach(_));
        let load = matches!(control, Control::Force(_) | Control::MeanPressure(_));
        let adhesive = law.work_of_adhesion() > 0.0;
        // Under a hardness the descent takes only the laws of a cell's own gap.
        let field = law.field_potential().is_some() && interface.hardness.is_none();
        let energy = law.local_potential().is_some() || field;
        let averaged = !energy && law.flat_potential().is_some() && law.stiffness_bound().is_finite();
        let periodic = domain.periodic;
        let coarse = law.stiffness_bound() * cell_compliance > Method::FLOW_ABOVE;
        if approach && adhesive && energy {
            Method::EnergyDescent
        } else if approach && adhesive && averaged {
            if coarse { Method::Flow } else { Method::Newton }
        } else if load && periodic && adhesive && averaged {
            Method::Flow
        } else {
            Method::Accelerated
        }
    }
}

impl std::fmt::Display for Method {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Serialised by its name ([`Method::name`]).
impl serde::Serialize for Method {
    fn serialize<S: serde::Serializer>(&self, serializer: S) -> std::result::Result<S::Ok, S::Error> {
        serializer.serialize_str(self.name())
    }
}

/// Read by its name ([`Method::name`]).
impl<'de> serde::Deserialize<'de> for Method {
    fn deserialize<D: serde::Deserializer<'de>>(deserializer: D) -> std::result::Result<Self, D::Error> {
        let name = <std::borrow::Cow<'de, str>>::deserialize(deserializer)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

impl std::str::FromStr for Method {
    type Err = String;

    fn from_str(s: &str) -> std::result::Result<Self, String> {
        Method::ALL
            .iter()
            .copied()
            .find(|m| m.name() == s)
            .ok_or_else(|| {
                let names: Vec<_> = Method::ALL.iter().map(|m| m.name()).collect();
                format!("unknown method `{s}`; the methods are {}", names.join(", "))
            })
    }
}

/// How an adhesive solve runs: the method, its tolerance and limit, and the settings that
/// only some methods read (each says which).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Settings {
    /// The method ([`Method::Auto`] by default).
    pub method: Method,
    /// Tolerance on the method's residual, in units of the law's range [-]: the dual loops'
    /// mean gap error of the pending adhesive correction, the descent's and Newton's largest
    /// force imbalance of a cell times its compliance (`docs/solvers.md`). The paper's 1e-6.
    pub tolerance: f64,
    /// Limit on the method's own iterations: outer iterations of the dual loops, descent
    /// iterations, Newton steps.
    pub max_iterations: usize,
    /// The dual loops only: relaxation and mixing.
    pub mixing: Mixing,
    /// The non-adhesive solves inside a method: the dual loops' inner solves and the cold
    /// start of the gap methods (energy descent, flow, Newton) on a periodic grid under a
    /// compressive load or an approach.
    pub contact: ContactOptions,
}

/// The dual loop's and the accelerated loop's own settings.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mixing {
    /// Global relaxation factor `beta` in (0, 1] (`None`: 1). Each cell's step is further
    /// scaled by `1 / (1 + k c)`, with `k` the law's attractive stiffness at the cell's gap and
    /// `c` the cell's compliance; `beta` shrinks when the residual grows or stalls and regrows
    /// slowly while it falls.
    pub relaxation: Option<f64>,
    /// Iterates kept by the accelerated loop's Anderson mixing.
    pub history: usize,
}

impl Settings {
    /// The paper's tolerance, 1e-6 of the law's range.
    pub const DEFAULT_TOLERANCE: f64 = 1e-6;
    /// The default limit on the method's iterations.
    pub const DEFAULT_MAX_ITERATIONS: usize = 20_000;

    /// The default settings with `method`.
    pub fn with_method(method: Method) -> Settings {
        Settings {
            method,
            ..Settings::default()
        }
    }

    /// Refuses a tolerance outside (0, 0.1] and a relaxation outside (0, 1].
    pub fn validate(&self) -> Result<()> {
        if !(self.tolerance > 0.0 && self.tolerance <= 0.1) {
            return Err(invalid(
                "tolerance",
                self.tolerance,
                "must be > 0 and at most 0.1 (of the law's range): a looser one accepts gaps off \
                 by a sizeable part of the range the law acts over",
            ));
        }
        if let Some(b) = self.mixing.relaxation
            && !(b > 0.0 && b <= 1.0)
        {
            return Err(invalid("relaxation", b, "must be in (0, 1]"));
        }
        Ok(())
    }
}

impl Default for Settings {
    fn default() -> Self {
        Settings {
            method: Method::Auto,
            tolerance: Settings::DEFAULT_TOLERANCE,
            max_iterations: Settings::DEFAULT_MAX_ITERATIONS,
            mixing: Mixing {
                relaxation: None,
                history: 8,
            },
            contact: ContactOptions {
                tolerance: 1e-10,
                ..ContactOptions::default()
            },
        }
    }
}
