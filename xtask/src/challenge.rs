//! The contact-mechanics challenge (Müser et al. 2017; Figs. 8-10): a periodic self-affine
//! surface pressed by increasing mean pressures, with and without adhesion, each load
//! warm-started from the last. Relative contact area against the reduced pressure
//! p/(E* g_bar), and the gap along the mid cross-section.

use crate::case::{Case, Law};
use anyhow::{Context as _, Result};
use serde::{Deserialize, Serialize};
use solver::{AdhesiveState, ContactOptions, ContactState, Control, Settings, Start};
use std::path::PathBuf;

/// The challenge's box \[m\], modulus \[Pa\], and adhesion (work [J/m^2], exponential range \[m\]).
pub const LENGTH: f64 = 1e-4;
pub const MODULUS: f64 = 25e6;
pub const WORK: f64 = 0.05;
pub const RANGE: f64 = 2.071e-9;

/// The challenge surface from its specification (or the user's file) on an `n^2` grid with
/// RMS gradient `g_bar`; the short cutoff is the specification's 0.1 um or four cells,
/// whichever is longer (a coarser grid cannot carry shorter waves).
pub fn case(n: usize, g_bar: f64, surface: Option<&PathBuf>) -> Case {
    let mut c = Case {
        modulus: MODULUS,
        length: Some(LENGTH),
        ..Case::default()
    };
    match surface {
        Some(path) => c.surface = Some(path.clone()),
        None => {
            c.rms_gradient = Some(g_bar);
            c.hurst = Some(0.8);
            c.rolloff_wavelength = Some(2e-5);
            c.cutoff_wavelength = Some(cutoff(n));
            c.seed = Some(1);
            c.n = Some(n);
        }
    }
    c
}

/// The short-wavelength cutoff used on an `n^2` grid \[m\].
pub fn cutoff(n: usize) -> f64 {
    (1e-7f64).max(4.0 * LENGTH / n as f64)
}

/// A loading sequence on one surface.
#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Run {
    pub case: Case,
    /// Reduced pressures p/(E* g_bar), increasing.
    pub reduced: Vec<f64>,
    /// Reduced pressures of the unloading branch that follows, decreasing, each warm-started
    /// from the last (adhesive runs only: without adhesion the solution is unique).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub unloading: Vec<f64>,
    /// Reduced pressure at which to keep the gap along the mid cross-section.
    pub profile_at: Option<f64>,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct LoadPoint {
    pub reduced: f64,
    pub mean_pressure: f64,
    pub contact_area_fraction: f64,
    /// Mean gap \[m\].
    pub mean_gap: f64,
    pub converged: bool,
    pub iterations: usize,
    pub wall_time_s: f64,
}

#[derive(Clone, Debug, Serialize, Deserialize)]
pub struct Outcome {
    pub points: Vec<LoadPoint>,
    /// The unloading branch (empty unless asked for).
    #[serde(default)]
    pub unloading: Vec<LoadPoint>,
    /// Gap \[m\] along the mid cross-section x = L/2 (column nx/2), against y.
    pub profile: Vec<f64>,
    /// Measured RMS gradient and local radius (inverse RMS curvature) \[m\] of the surface.
    pub rms_gradient: f64,
    pub local_radius: f64,
    pub rms_height: f64,
    pub cell: f64,
    pub warnings: Vec<String>,
}

impl Run {
    /// Solves every load in turn; with `log`, one line per finished load on stderr (a 1024^2
    /// adhesive run takes an hour).
    pub fn solve(&self, log: bool) -> Result<Outcome> {
        let (rms_gradient, local_radius, rms_height, cell) = crate::surface_statistics(&self.case)?;
        let p = self.case.build()?;
        let (ny, nx) = p.initial_gap.dim();
        let mut points = Vec::new();
        let mut profile = Vec::new();
        let mut keep = |reduced: f64, gap: &ndarray::Array2<f64>| {
            if self.profile_at == Some(reduced) {
                profile = (0..ny).map(|j| gap[(j, nx / 2)]).collect();
            }
        };
        let mean = |a: &ndarray::Array2<f64>| a.iter().sum::<f64>() / a.len() as f64;
        let mut unloading = Vec::new();
        if p.adhesive() {
            let settings = Settings::default();
            let mut state: Option<AdhesiveState> = None;
            for (loading, loads) in [(true, &self.reduced), (false, &self.unloading)] {
                for &r in loads {
                    let control = Control::MeanPressure(r * p.e_star() * rms_gradient);
                    let start = match &state {
                        Some(s) => Start::Warm(s),
                        None => Start::Loading,
                    };
                    let (s, rep) = p
                        .solve(control, &settings, start, &mut ())
                        .with_context(|| format!("p/(E* g) = {r}"))?;
                    // The profile is the loading branch's.
                    if loading {
                        keep(r, &s.contact.gap);
                    }
                    if log {
                        eprintln!(
                            "challenge {nx}^2 adhesive, {} p/(E* g) = {r}: contact {:.4}, {:?}, {:.0} s, {:?}",
                            if loading { "loading" } else { "unloading" },
                            rep.contact_area_fraction,
                            rep.iterations,
                            rep.wall_time_s,
                            rep.termination
                        );
                    }
                    let branch = if loading { &mut points } else { &mut unloading };
                    branch.push(LoadPoint {
                        reduced: r,
                        mean_pressure: rep.mean_pressure,
                        contact_area_fraction: rep.contact_area_fraction,
                        mean_gap: mean(&s.contact.gap),
                        converged: rep.converged(),
                        iterations: rep.iterations.count(),
                        wall_time_s: rep.wall_time_s,
                    });
                    state = Some(s);
                }
            }
        } else {
            let options = ContactOptions::default();
            let mut state: Option<ContactState> = None;
            for &r in &self.reduced {
                let control = Control::MeanPressure(r * p.e_star() * rms_gradient);
                let (s, rep) = p
                    .solve_without_adhesion(control, &options, state.as_ref(), &mut ())
                    .with_context(|| format!("p/(E* g) = {r}"))?;
                keep(r, &s.gap);
                points.push(LoadPoint {
                    reduced: r,
                    mean_pressure: rep.mean_pressure,
                    contact_area_fraction: rep.contact_area_fraction,
                    mean_gap: mean(&s.gap),
                    converged: rep.converged(),
                    iterations: rep.iterations,
                    wall_time_s: rep.wall_time_s,
                });
                state = Some(s);
            }
        }
        Ok(Outcome {
            points,
            unloading,
            profile,
            rms_gradient,
            local_radius,
            rms_height,
            cell,
            warnings: p.warnings,
        })
    }
}

/// The challenge case with its exponential adhesion of work `w0` [J/m^2].
pub fn adhesive(mut case: Case, w0: f64) -> Case {
    case.law = Some(Law::Exponential);
    case.work_of_adhesion = Some(w0);
    case.range = Some(RANGE);
    case
}

/// The adhesive process-zone length `E* w0 / sigma0^2` \[m\] of the exponential law of work `w0`
/// (peak stress `sigma0 = w0 / rho`).
pub fn process_zone(w0: f64) -> f64 {
    MODULUS * RANGE * RANGE / w0
}

/// Müser's Tabor-like parameter of the exponential law, `(R w0^2 / (E*^2 rho^3))^(1/3)`, with
/// the local radius `R` \[m\].
pub fn tabor(local_radius: f64, w0: f64) -> f64 {
    (local_radius * w0 * w0 / (MODULUS * MODULUS * RANGE.powi(3))).cbrt()
}

/// The work of adhesion [J/m^2] that gives Tabor parameter `mu` at local radius `R` \[m\].
pub fn work_for_tabor(local_radius: f64, mu: f64) -> f64 {
    (mu.powi(3) * MODULUS * MODULUS * RANGE.powi(3) / local_radius).sqrt()
}
