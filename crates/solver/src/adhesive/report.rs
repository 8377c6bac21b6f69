//! What an adhesive solve reports: its scalars, and what its method counted.

use crate::method::Method;
use crate::report::Termination;

/// What a method counted, in its own terms (serialised with its `kind`: `loop`, `descent`,
/// `newton`).
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum Iterations {
    /// The dual loop and the accelerated loop.
    Loop {
        /// Outer iterations (adhesive-pressure updates).
        outer: usize,
        /// Conjugate-gradient iterations of the inner solves, summed.
        inner: usize,
        /// The relaxation factor at the end.
        relaxation: f64,
    },
    /// The energy descent.
    Descent {
        /// Descent iterations.
        iterations: usize,
    },
    /// The damped relaxation.
    Flow {
        /// Explicit steps.
        steps: usize,
        /// Newton steps after the flow crawled near a fold and handed its point to Newton
        /// (under approach control; 0 if it did not).
        newton: usize,
    },
    /// Newton.
    Newton {
        /// Newton steps.
        steps: usize,
        /// Krylov (GMRES) iterations, summed.
        krylov: usize,
        /// Iterations of the point law's energy descent that predicted the state, where
        /// Newton from the start could not get going.
        predictor: usize,
    },
}

impl Iterations {
    /// The iterations the limit [`crate::Settings::max_iterations`] bounds: outer iterations,
    /// descent iterations or Newton steps.
    pub fn count(&self) -> usize {
        match *self {
            Iterations::Loop { outer, .. } => outer,
            Iterations::Descent { iterations } => iterations,
            Iterations::Flow { steps, .. } => steps,
            Iterations::Newton { steps, .. } => steps,
        }
    }

    /// The iterations of the solver inside a step: conjugate gradients of the dual loops,
    /// Krylov iterations of Newton, the Newton steps a flow handed over to (if any); the
    /// descent has none.
    pub fn inner(&self) -> Option<usize> {
        match *self {
            Iterations::Loop { inner, .. } => Some(inner),
            Iterations::Descent { .. } => None,
            Iterations::Flow { newton, .. } => (newton > 0).then_some(newton),
            Iterations::Newton { krylov, .. } => Some(krylov),
        }
    }

    /// Adds the counts of `other`, a solve by the same method (a sweep's substeps); the last
    /// relaxation factor is kept.
    pub fn accumulate(&mut self, other: &Iterations) {
        match (self, other) {
            (
                Iterations::Loop {
                    outer,
                    inner,
                    relaxation,
                },
                Iterations::Loop {
                    outer: o,
                    inner: i,
                    relaxation: r,
                },
            ) => {
                *outer += o;
                *inner += i;
                *relaxation = *r;
            }
            (Iterations::Descent { iterations }, Iterations::Descent { iterations: i }) => *iterations += i,
            (Iterations::Flow { steps, newton }, Iterations::Flow { steps: s, newton: n }) => {
                *steps += s;
                *newton += n;
            }
            (
                Iterations::Newton {
                    steps,
                    krylov,
                    predictor,
                },
                Iterations::Newton {
                    steps: s,
                    krylov: k,
                    predictor: p,
                },
            ) => {
                *steps += s;
                *krylov += k;
                *predictor += p;
            }
            (this, other) => *this = *other,
        }
    }
}

/// The counts in words: "12 outer, 345 inner".
impl std::fmt::Display for Iterations {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            Iterations::Loop { outer, inner, .. } => write!(f, "{outer} outer, {inner} inner"),
            Iterations::Descent { iterations } => write!(f, "{iterations} descent"),
            Iterations::Flow { steps, newton: 0 } => write!(f, "{steps} flow steps"),
            Iterations::Flow { steps, newton } => write!(f, "{steps} flow steps, then {newton} Newton steps"),
            Iterations::Newton {
                steps,
                krylov,
                predictor,
            } => write!(f, "{steps} Newton steps, {krylov} Krylov, {predictor} predictor"),
        }
    }
}

/// Scalars of an adhesive solution and the history of its solve. SI units; loads positive
/// compressive.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct AdhesiveReport {
    /// Total normal force `sum (p_c + p_a) dA` \[N\].
    pub load: f64,
    /// Load over the nominal area \[Pa\].
    pub mean_pressure: f64,
    /// The compressive part of the load \[N\] (>= 0).
    pub compressive_load: f64,
    /// The adhesive part of the load \[N\] (<= 0).
    pub adhesive_load: f64,
    /// Approach from first touch of the undeformed surfaces \[m\].
    pub approach: f64,
    /// Gap at the centre cell `(ny/2, nx/2)` \[m\].
    pub central_gap: f64,
    /// Fraction of cells in contact (`p_c > 0`) [-].
    pub contact_area_fraction: f64,
    /// Fraction of cells out of contact with a net attraction (`p_c = 0`, `p_a < 0`) [-].
    pub attractive_area_fraction: f64,
    /// Fraction of cells attached: gap below the law's range (`z0` for Lennard-Jones), contact
    /// included [-]. Unlike the contact area it stays nonzero while an adhesive neck without
    /// compressive contact holds the bodies together.
    pub attached_area_fraction: f64,
    /// Number of contact clusters.
    pub clusters: usize,
    /// Largest total pressure \[Pa\].
    pub max_pressure: f64,
    /// Most negative total pressure \[Pa\].
    pub min_pressure: f64,
    /// What yielding did under a hardness (zeros when elastic).
    #[serde(flatten)]
    pub yielding: crate::interface::Yield,
    /// Elastic energy the body stores \[J\]: `(1/2) sum (p_c + p_a) u dA` for an elastic body,
    /// its springs' energy for a viscoelastic one ([`crate::time`]).
    pub elastic_energy: f64,
    /// Energy the body's dashpots dissipated over the step that reached this state \[J\] (0
    /// when elastic).
    pub viscous_work: f64,
    /// The method that solved it ([`Method::Auto`] resolved).
    pub method: Method,
    /// What the method counted.
    pub iterations: Iterations,
    /// Calls to the elastic operator.
    pub operator_calls: usize,
    /// Final residual, in units of the law's range ([`crate::Settings::tolerance`]).
    pub residual: f64,
    /// The residual after every iteration.
    pub residual_history: Vec<f64>,
    /// Why it stopped.
    pub termination: Termination,
    /// Wall time \[s\].
    pub wall_time_s: f64,
}

impl AdhesiveReport {
    /// Whether the solve met its tolerance.
    pub fn converged(&self) -> bool {
        self.termination == Termination::Converged
    }
}
