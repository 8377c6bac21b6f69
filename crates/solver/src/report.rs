//! What a solve reports besides its fields.

use ndarray::ArrayView2;

/// Why a solve stopped.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
pub enum Termination {
    /// The residual fell below the tolerance.
    Converged,
    /// The iteration limit was reached first: the fields are the last iterate.
    MaxIterations,
    /// Nothing to solve: zero load or no overlap at the prescribed approach.
    NoContact,
    /// Adhesive load control: the attraction alone exceeds the prescribed (tensile) load, so no
    /// equilibrium in contact exists (the surfaces have pulled off). The fields are the last
    /// iterate.
    PulledOff,
    /// The observer asked the solve to stop (a user's Ctrl-C): the fields are the last iterate.
    Interrupted,
}

impl std::fmt::Display for Termination {
    /// In words, for people: "converged", "stopped at the iteration limit", ...
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Termination::Converged => "converged",
            Termination::MaxIterations => "stopped at the iteration limit (not converged)",
            Termination::NoContact => "no contact (nothing to solve)",
            Termination::PulledOff => "pulled off (no equilibrium in contact at this load)",
            Termination::Interrupted => "interrupted (not converged)",
        })
    }
}

/// Scalars of a contact solution and the history of the solve. SI units.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct ContactReport {
    /// Total normal force \[N\] (positive = compressive).
    pub load: f64,
    /// Load over the nominal area \[Pa\].
    pub mean_pressure: f64,
    /// Approach from first touch \[m\].
    pub approach: f64,
    /// Fraction of cells with positive pressure [-].
    pub contact_area_fraction: f64,
    /// Number of contact clusters (4-connected, wrapping around on periodic grids).
    pub clusters: usize,
    /// Largest pressure \[Pa\].
    pub max_pressure: f64,
    /// Elastic energy `(1/2) sum p u dA` \[J\].
    pub elastic_energy: f64,
    /// What yielding did under a hardness (zeros when elastic).
    #[serde(flatten)]
    pub yielding: crate::interface::Yield,
    /// Iterations run.
    pub iterations: usize,
    /// Final residual: the RMS gap on the contact set (plus the RMS interpenetration outside
    /// it) over the RMS of the initial gap, free of units and of the problem's scale. It is
    /// the whole optimality (KKT) residual, as `p >= 0` holds at every iterate; at 1e-8 the
    /// mean gap is within about 1e-9 of a tightly converged solve (`roughcontact bench
    /// --check`).
    pub residual: f64,
    /// The residual after every iteration.
    pub residual_history: Vec<f64>,
    /// Why it stopped.
    pub termination: Termination,
    /// Calls to the elastic operator.
    pub operator_calls: usize,
    /// Wall time of the solve \[s\].
    pub wall_time_s: f64,
}

impl ContactReport {
    /// Whether the solve met its tolerance (or had nothing to solve).
    pub fn converged(&self) -> bool {
        matches!(self.termination, Termination::Converged | Termination::NoContact)
    }
}

/// Number of 4-connected clusters of cells with positive pressure.
pub fn count_clusters(pressure: ArrayView2<f64>, periodic: bool) -> usize {
    let (ny, nx) = pressure.dim();
    let mut label = vec![false; nx * ny];
    let mut stack = Vec::new();
    let mut clusters = 0;
    for start in 0..nx * ny {
        if label[start] || pressure[(start / nx, start % nx)] <= 0.0 {
            continue;
        }
        clusters += 1;
        label[start] = true;
        stack.push(start);
        while let Some(k) = stack.pop() {
            let (y, x) = (k / nx, k % nx);
            let mut visit = |yy: Option<usize>, xx: Option<usize>| {
                if let (Some(yy), Some(xx)) = (yy, xx) {
                    let n = yy * nx + xx;
                    if !label[n] && pressure[(yy, xx)] > 0.0 {
                        label[n] = true;
                        stack.push(n);
                    }
                }
            };
            let step = |i: usize, n: usize, up: bool| -> Option<usize> {
                match (up, periodic) {
                    (true, _) if i + 1 < n => Some(i + 1),
                    (true, true) => Some(0),
                    (false, _) if i > 0 => Some(i - 1),
                    (false, true) => Some(n - 1),
                    _ => None,
                }
            };
            visit(Some(y), step(x, nx, true));
            visit(Some(y), step(x, nx, false));
            visit(step(y, ny, true), Some(x));
            visit(step(y, ny, false), Some(x));
        }
    }
    clusters
}
