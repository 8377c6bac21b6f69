//! What is prescribed and how hard to try.

/// The control of a normal contact problem.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Control {
    /// Mean pressure over the whole grid \[Pa\] (load control).
    MeanPressure(f64),
    /// Total normal force \[N\] (load control).
    Force(f64),
    /// Approach `delta` \[m\] from first touch, positive pushing the bodies together
    /// (displacement control).
    Approach(f64),
    /// Gap at the centre cell `(ny/2, nx/2)` \[m\], > 0; the approach follows. Adhesive solver
    /// only: it traces the unstable middle of an S-shaped load-approach curve (Greenwood 1997).
    CentralGap(f64),
}

impl Control {
    /// Refuses what a contact without adhesion cannot take: a tensile or non-finite load, a
    /// negative approach, a prescribed central gap (the adhesive solver's).
    pub fn validate_without_adhesion(&self) -> crate::Result<()> {
        use crate::error::invalid;
        match *self {
            Control::MeanPressure(v) | Control::Force(v) if !(v.is_finite() && v >= 0.0) => {
                let name = if matches!(self, Control::Force(_)) {
                    "load"
                } else {
                    "mean_pressure"
                };
                Err(invalid(name, v, "a compressive load must be finite and >= 0"))
            }
            Control::Approach(d) if !(d.is_finite() && d >= 0.0) => Err(invalid(
                "approach",
                d,
                "must be finite and >= 0 m (positive pushes the bodies together)",
            )),
            Control::CentralGap(g) => Err(invalid(
                "central_gap",
                g,
                "prescribing the central gap needs adhesion (use the adhesive solver)",
            )),
            _ => Ok(()),
        }
    }
}

/// Solver settings, independent of the problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactOptions {
    /// Convergence tolerance on the scale-free residual (see [`crate::ContactReport::residual`]).
    pub tolerance: f64,
    /// Iteration limit; reaching it ends the solve with [`crate::Termination::MaxIterations`].
    pub max_iterations: usize,
    /// Precondition the search directions by the inverse of the elastic operator restricted
    /// to the contact set (see [`crate::cg`]): fewer iterations that grow more slowly with the
    /// grid, one more FFT convolution each. Under load control only (approach control is
    /// always plain: see [`crate::cg`]). On by default: the faster at every grid measured,
    /// 128^2 to 4096^2, and in the adhesive loops' inner solves (`docs/performance.md`); off,
    /// the iteration is Polonsky and Keer's (as Tamaas's `PolonskyKeerRey`).
    pub preconditioned: bool,
}

impl ContactOptions {
    /// The default tolerance on the scale-free gap residual.
    pub const DEFAULT_TOLERANCE: f64 = 1e-8;
    /// The default iteration limit.
    pub const DEFAULT_MAX_ITERATIONS: usize = 10_000;

    /// Refuses a tolerance outside [1e-13, 0.1]: what f64 arithmetic resolves, and a gap
    /// residual (relative to the RMS height) loose enough to stop before the contact means
    /// anything.
    pub fn validate(&self) -> crate::Result<()> {
        if !(self.tolerance >= 1e-13 && self.tolerance <= 0.1) {
            return Err(crate::error::invalid(
                "tolerance",
                self.tolerance,
                "must be between 1e-13 (what f64 arithmetic resolves) and 0.1 (the gap residual is \
                 relative to the surface's RMS height: a looser one stops before the contact means \
                 anything)",
            ));
        }
        Ok(())
    }
}

impl Default for ContactOptions {
    fn default() -> Self {
        ContactOptions {
            tolerance: ContactOptions::DEFAULT_TOLERANCE,
            max_iterations: ContactOptions::DEFAULT_MAX_ITERATIONS,
            preconditioned: true,
        }
    }
}
