//! # solver: normal contact of an elastic half-space with a rigid counterface
//!
//! Conventions, used by every crate of the workspace (method.md section 1): SI units; arrays
//! of shape `(ny, nx)`; gap `g >= 0` [m]; pressure `p > 0` compressive [Pa] (adhesive
//! pressure `p_a <= 0`); approach `delta > 0` [m] pushes the bodies together, measured from
//! first touch of the undeformed surfaces; surface displacement `u` [m] positive away from
//! the counterface, so that `g = g0 - delta + u` with the initial gap `g0` of
//! [`geometry`] (minimum 0).
//!
//! The problem is plain data: an elastic operator ([`elastic::Periodic`] or
//! [`elastic::Free`]), an initial gap field, a [`Control`] (mean pressure, force or approach)
//! and [`ContactOptions`]. [`solve`] returns a [`ContactState`] (fields, resumable as a warm
//! start) and a [`ContactReport`] (scalars, residual history, why it stopped).

pub mod adhesive;
pub mod cg;
pub mod error;
pub mod geometry;
pub mod options;
pub mod report;
pub mod state;
pub mod sweep;

pub use adhesive::{
    AdhesiveOptions, AdhesiveReport, AdhesiveState, OuterLoop, Start, solve_adhesive, solve_adhesive_observed,
};
pub use cg::{solve, solve_observed};
pub use error::{Result, SolverError};
pub use options::{ContactOptions, Control};
pub use report::{ContactReport, Termination};
pub use state::ContactState;
pub use sweep::{
    Branch, CyclePoint, CycleSummary, RETRIES, SweepPoint, approach_cycle, substeps, summarize, sweep,
    sweep_observed,
};
