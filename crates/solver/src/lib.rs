//! # solver: normal contact of an elastic half-space with a rigid counterface
//!
//! Conventions, used by every crate of the workspace (docs/method.md section 1): SI units; arrays
//! of shape `(ny, nx)`; gap `g >= 0` \[m\]; pressure `p > 0` compressive \[Pa\] (adhesive
//! pressure `p_a <= 0`); approach `delta > 0` \[m\] pushes the bodies together, measured from
//! first touch of the undeformed surfaces; surface displacement `u` \[m\] positive away from
//! the counterface, so that `g = g0 - delta + u` with the initial gap `g0` of
//! [`geometry`] (minimum 0).
//!
//! A problem is a [`ContactProblem`]: the elastic operator on its grid ([`elastic::Periodic`]
//! or [`elastic::Free`]), the initial gap and the adhesive law, built from a geometry, a
//! surface, a material and a law by [`ProblemBuilder`]. [`ContactProblem::solve`] solves it
//! under a [`Control`] (mean pressure, force, approach or central gap) by a [`Method`] with
//! its [`Settings`], returning an [`AdhesiveState`] (fields, resumable as a warm start) and an
//! [`AdhesiveReport`]; [`ContactProblem::sweep`] follows a path of controls. An [`Observer`]
//! watches either. Without adhesion, [`cg::solve`] is the constrained conjugate-gradient solve.
//!
//! A rough sphere with the paper's surface law, swept in and out:
//!
//! ```
//! use ljadhesion::{LennardJones, SurfaceLaw};
//! use ndarray::Array2;
//! use solver::{ContactProblem, Settings, approach_cycle, summarize, CyclePoint};
//!
//! let (n, side, z0) = (32, 100e-9, 1e-9);
//! // A gentle roughness of 0.3 z0 (any heights \[m\] of shape (ny, nx) will do).
//! let heights = Array2::from_shape_fn((n, n), |(j, i)| {
//!     0.3 * z0 * ((i as f64 * 0.7).sin() * (j as f64 * 0.9).cos())
//! });
//! let problem = ContactProblem::builder()
//!     .roughness(heights, side, side)
//!     .sphere(1e-6)
//!     .modulus(1e9)
//!     .law(SurfaceLaw(LennardJones::new(0.02, z0)?))
//!     .build()?;
//! let path = approach_cycle(-3.0 * z0, 1.0 * z0, 4);
//! let points = problem.sweep(&path, Some(z0), &Settings::default(), None, &mut ())?;
//! let cycle = summarize(&points.iter().map(CyclePoint::from).collect::<Vec<_>>());
//! assert!(cycle.all_converged);
//! assert!(cycle.pull_off_force.unwrap() < 0.0);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod adhesive;
pub mod cg;
pub mod error;
mod fields;
pub mod friction;
pub mod geometry;
pub mod interface;
mod mean_mode;
pub mod method;
pub mod observer;
pub mod options;
pub mod problem;
pub mod pull_off;
pub mod report;
pub mod state;
mod sum;
pub mod sweep;
pub mod time;

pub use adhesive::{AdhesiveReport, AdhesiveState, Iterations, Start};
pub use error::{Result, SolverError};
pub use friction::{
    Counterface, Friction, Normal, NormalSolver, NormalState, Reached, ShearOptions, ShearReport, ShearState,
    TangentialControl, TangentialPath, TangentialProblem, TangentialSummary,
};
pub use interface::{Interface, Yield};
pub use method::{Method, Mixing, Settings};
pub use observer::{Branch, Observer, SweepPoint};
pub use options::{ContactOptions, Control};
pub use problem::{ContactProblem, ProblemBuilder, Shape, memory_estimate};
pub use pull_off::{PullOff, PullOffSearch};
pub use report::{ContactReport, Termination};
pub use state::ContactState;
pub use sweep::{
    CyclePoint, CycleSummary, MAX_SUBSTEPS, Path, RETRIES, approach_cycle, count_substeps, substeps,
    summarize,
};
pub use time::History;

/// The README's library example, run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeDoctests;

/// The guide's library page, run as a doctest.
#[cfg(doctest)]
#[doc = include_str!("../../../docs/howto/library.md")]
pub struct GuideLibraryDoctests;
