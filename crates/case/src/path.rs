//! What a solve prescribes and the path a sweep follows, by their keys.

use crate::error::{Result, bail};
use crate::memory;
use serde::{Deserialize, Serialize};
use solver::{ContactProblem, Control};
use std::path::PathBuf;

/// What a single solve prescribes (keys of the case file like the others).
#[derive(Debug, Default, Clone, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[serde(default, deny_unknown_fields)]
pub struct SolveControl {
    /// Load control: mean pressure over the box [Pa] (negative pulls, with adhesion).
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub mean_pressure: Option<f64>,
    /// Load control: total normal force [N] (negative pulls, with adhesion).
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub load: Option<f64>,
    /// Displacement control: approach from first touch [m], positive pushes together
    /// (negative holds the bodies apart, with adhesion).
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub approach: Option<f64>,
    /// Displacement control by the mean gap over the box [m] (periodic domains, where the
    /// mean displacement is zero: the approach is mean(initial gap) - mean gap).
    #[cfg_attr(feature = "clap", arg(long))]
    pub mean_gap: Option<f64>,
    /// A tangential path after the normal solve: the shear forces [N] along
    /// --tangential-angle, comma-separated, each step from the last (negative: the other way;
    /// a reversal makes a fretting loop). Needs --friction-coefficient or --shear-strength.
    #[cfg_attr(
        feature = "clap",
        arg(long, value_delimiter = ',', allow_hyphen_values = true)
    )]
    pub tangential_loads: Option<Vec<f64>>,
    /// A tangential path after the normal solve: the rigid body's tangential displacements [m]
    /// along --tangential-angle, comma-separated (on periodic grids relative to the body's
    /// mean surface).
    #[cfg_attr(
        feature = "clap",
        arg(
            long,
            value_delimiter = ',',
            allow_hyphen_values = true,
            conflicts_with = "tangential_loads"
        )
    )]
    pub tangential_displacements: Option<Vec<f64>>,
    /// The direction of the tangential path from the x axis towards y [rad] (default 0).
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub tangential_angle: Option<f64>,
}

impl SolveControl {
    /// The tangential path's controls, if one is given, for a case with friction
    /// (`frictional`) or without: friction without a path, or a path without friction, is
    /// refused.
    pub fn tangential_path(&self, frictional: bool) -> Result<Option<Vec<solver::TangentialControl>>> {
        let path = self.tangential()?;
        match (frictional, &path) {
            (true, None) => bail!(
                "--friction-coefficient and --shear-strength bound a tangential path's shear: give \
                 --tangential-loads [N] or --tangential-displacements [m]"
            ),
            (false, Some(_)) => bail!(
                "a tangential path needs friction: --friction-coefficient [-] and/or \
                 --shear-strength [Pa], and the body's --poisson"
            ),
            _ => Ok(path),
        }
    }

    /// The tangential path's controls, if one is given.
    fn tangential(&self) -> Result<Option<Vec<solver::TangentialControl>>> {
        use solver::TangentialControl::{Displacement, Force};
        let angle = self.tangential_angle.unwrap_or(0.0);
        if !angle.is_finite() {
            bail!("--tangential-angle must be a finite angle [rad], got {angle}");
        }
        let (c, s) = (angle.cos(), angle.sin());
        let (values, force) = match (&self.tangential_loads, &self.tangential_displacements) {
            (Some(v), None) => (v, true),
            (None, Some(v)) => (v, false),
            (None, None) => {
                if self.tangential_angle.is_some() {
                    bail!(
                        "--tangential-angle orients a tangential path: give --tangential-loads [N] or --tangential-displacements [m]"
                    );
                }
                return Ok(None);
            }
            (Some(_), Some(_)) => {
                bail!("give one of --tangential-loads [N] and --tangential-displacements [m]")
            }
        };
        if values.is_empty() {
            bail!("the tangential path has no step");
        }
        if let Some(v) = values.iter().find(|v| !v.is_finite()) {
            bail!("the tangential path's values must be finite, got {v}");
        }
        let make = |v: [f64; 2]| if force { Force(v) } else { Displacement(v) };
        Ok(Some(values.iter().map(|v| make([v * c, v * s])).collect()))
    }

    /// The library's control for `problem`: exactly one key must be given.
    pub fn control(&self, problem: &ContactProblem) -> Result<Control> {
        Ok(
            match (self.mean_pressure, self.load, self.approach, self.mean_gap) {
                (Some(p), None, None, None) => Control::MeanPressure(p),
                (None, Some(w), None, None) => Control::Force(w),
                (None, None, Some(d), None) => Control::Approach(d),
                (None, None, None, Some(g)) => {
                    if !problem.domain().periodic {
                        bail!(
                            "--mean-gap needs a periodic domain (on a free one the mean displacement is not zero)"
                        );
                    }
                    if !(g.is_finite() && g >= 0.0) {
                        bail!("--mean-gap must be finite and >= 0 m, got {g}");
                    }
                    Control::Approach(problem.initial_gap.mean().unwrap_or(0.0) - g)
                }
                _ => bail!(
                    "give exactly one of --mean-pressure [Pa], --load [N], --approach [m] or --mean-gap [m]"
                ),
            },
        )
    }
}

/// The path of a sweep (keys of the case file like the others).
#[derive(Debug, Default, Clone, Serialize, Deserialize)]
#[cfg_attr(feature = "clap", derive(clap::Args))]
#[serde(default, deny_unknown_fields)]
pub struct SweepPath {
    /// Approach at the start and the end of the cycle [m] (negative: bodies apart).
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub from: Option<f64>,
    /// Turning point of the cycle [m].
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub to: Option<f64>,
    /// Steps from --from to --to; the way back takes as many again (default 20).
    #[cfg_attr(feature = "clap", arg(long))]
    pub steps: Option<usize>,
    /// Explicit approaches [m], comma-separated, solved in this order.
    #[cfg_attr(feature = "clap", arg(long, value_delimiter = ',', allow_hyphen_values = true, conflicts_with_all = ["from", "to", "steps"]))]
    pub approaches: Option<Vec<f64>>,
    /// Explicit mean pressures [Pa] (load control), comma-separated, in this order.
    #[cfg_attr(feature = "clap", arg(long, value_delimiter = ',', allow_hyphen_values = true, conflicts_with_all = ["from", "to", "steps", "approaches"]))]
    pub mean_pressures: Option<Vec<f64>>,
    /// Explicit central gaps [m] (> 0), comma-separated: the approach follows, which traces the
    /// unstable middle of a sphere's S-shaped curve.
    #[cfg_attr(feature = "clap", arg(long, value_delimiter = ',', conflicts_with_all = ["from", "to", "steps", "approaches", "mean_pressures"]))]
    pub central_gaps: Option<Vec<f64>>,
    /// Largest change of approach or central gap between two solves [m]: a longer step is
    /// split into substeps that are solved (their iterations count in curve.csv) but not
    /// written, which keeps the sweep quasi-static [default: the adhesive law's range, z0 for
    /// Lennard-Jones; no splitting without adhesion]. Load steps are never split.
    #[cfg_attr(feature = "clap", arg(long))]
    pub max_step: Option<f64>,
    /// Start from a saved state instead of apart: a sweep's output directory (its last state),
    /// its `state/`, or one of its `states/step-NNNN` (with --save-states), on the same grid.
    /// To continue a cycle with another law, solver, tolerance or path.
    #[cfg_attr(feature = "clap", arg(long, value_name = "DIR"))]
    pub start_from: Option<PathBuf>,
    /// Find the pull-off force: the path goes in only (from --from to --to in --steps, or the
    /// --approaches), then unloads from its last state in steps of this size [m] until the
    /// load has come back from its minimum, and again around the minimum in finer steps.
    #[cfg_attr(feature = "clap", arg(long))]
    pub pull_off_step: Option<f64>,
    /// The lowest approach the pull-off search unloads to [m] (negative: bodies apart).
    #[cfg_attr(feature = "clap", arg(long, allow_hyphen_values = true))]
    pub pull_off_floor: Option<f64>,
    /// Finer steps per coarse step around the lowest load of the pull-off search (1: none)
    /// [default: 5].
    #[cfg_attr(feature = "clap", arg(long))]
    pub pull_off_refinement: Option<usize>,
    /// The pull-off search stops once the load has come back above this fraction of its
    /// lowest, in (0, 1] [default: 0.5].
    #[cfg_attr(feature = "clap", arg(long))]
    pub pull_off_recovery: Option<f64>,
    /// How long each step of the path lasts [s] on a viscoelastic body: step k is reached at
    /// k times it (a pull-off search's steps last as long, its finer ones in proportion).
    #[cfg_attr(feature = "clap", arg(long))]
    pub step_time: Option<f64>,
    /// The time each step of the path is reached at [s] on a viscoelastic body, comma-separated,
    /// never decreasing (a hold: a repeated approach or load at later times).
    #[cfg_attr(
        feature = "clap",
        arg(long, value_delimiter = ',', conflicts_with = "step_time")
    )]
    pub times: Option<Vec<f64>>,
    /// Steps (counted from 0, comma-separated) whose fields are also kept in
    /// states/step-NNNN, as --save-states keeps every step's.
    #[cfg_attr(feature = "clap", arg(long, value_delimiter = ','))]
    pub keep_steps: Option<Vec<usize>>,
}

/// The memory a step of a sweep keeps until the end [bytes]: its control, its report and its
/// row of the summary (the report's residual history aside).
const STEP_BYTES: f64 = (std::mem::size_of::<Control>()
    + std::mem::size_of::<solver::SweepPoint>()
    + std::mem::size_of::<solver::CyclePoint>()) as f64;

impl SweepPath {
    /// Fills in the default number of steps of a cycle.
    pub fn fill_defaults(&mut self) {
        if self.approaches.is_none() && self.mean_pressures.is_none() && self.central_gaps.is_none() {
            self.steps = self.steps.or(Some(20));
        }
    }

    /// The controls of the path, in order: a cycle from `from` to `to` and back, or the
    /// explicit list given.
    pub fn controls(&self) -> Result<Vec<Control>> {
        let search = self.pull_off()?;
        if search.is_some() && (self.mean_pressures.is_some() || self.central_gaps.is_some()) {
            bail!(
                "the pull-off search follows an approach path: give --from/--to or --approaches, \
                 not --mean-pressures or --central-gaps"
            );
        }
        let controls: Vec<Control> = match (&self.approaches, &self.mean_pressures, &self.central_gaps) {
            (Some(a), None, None) => a.iter().map(|&v| Control::Approach(v)).collect(),
            (None, Some(p), None) => p.iter().map(|&v| Control::MeanPressure(v)).collect(),
            (None, None, Some(g)) => g.iter().map(|&v| Control::CentralGap(v)).collect(),
            (None, None, None) => {
                let (from, to) = match (self.from, self.to) {
                    (Some(f), Some(t)) => (f, t),
                    _ => bail!(
                        "give the path: --from A --to B [m] (--steps N), or --approaches, --mean-pressures or \
                         --central-gaps, or run a built-in case with --example"
                    ),
                };
                let steps = self.steps.unwrap_or(20);
                if steps == 0 {
                    bail!("--steps must be at least 1 (steps from --from to --to; as many back)");
                }
                memory::check(
                    &format!("a sweep of {} steps", 2 * steps as u64 + 1),
                    (2.0 * steps as f64 + 1.0) * STEP_BYTES,
                )?;
                let mut cycle = solver::approach_cycle(from, to, steps);
                if search.is_some() {
                    // The way in only: the search is the way out.
                    cycle.truncate(steps + 1);
                }
                cycle
            }
            _ => bail!("give one path only"),
        };
        if controls.is_empty() {
            bail!("the sweep path is empty");
        }
        if controls.iter().any(|c| {
            let (Control::Approach(v)
            | Control::MeanPressure(v)
            | Control::Force(v)
            | Control::CentralGap(v)) = *c;
            !v.is_finite()
        }) {
            bail!("the sweep path has a non-finite value");
        }
        // Without a pull-off search (whose steps are numbered on after the path's) a kept step
        // beyond the path would keep nothing.
        if let (None, Some(k)) = (
            search,
            self.keep_steps.iter().flatten().find(|&&k| k >= controls.len()),
        ) {
            bail!(
                "--keep-steps {k}: the path has {} steps, numbered 0 to {}",
                controls.len(),
                controls.len() - 1
            );
        }
        if let (Some(s), Some(Control::Approach(last))) = (search, controls.last())
            && s.floor >= *last
        {
            bail!(
                "--pull-off-floor ({:e} m) must be below the path's last approach ({last:e} m)",
                s.floor
            );
        }
        Ok(controls)
    }

    /// The times of the `steps` steps of the path on `problem` [s]: none on an elastic body
    /// (which refuses them: they would change nothing), required on a viscoelastic one.
    pub fn times(&self, problem: &ContactProblem, steps: usize) -> Result<Option<Vec<f64>>> {
        let given = if self.step_time.is_some() {
            "--step-time"
        } else {
            "--times"
        };
        if problem.solid.is_none() {
            if self.step_time.is_some() || self.times.is_some() {
                bail!(
                    "{given} times a viscoelastic body's steps, and this body is elastic (give \
                 --maxwell-moduli [Pa] and --maxwell-times [s])"
                );
            }
            return Ok(None);
        }
        let times = match (self.step_time, &self.times) {
            (Some(dt), None) => {
                if !(dt.is_finite() && dt > 0.0) {
                    bail!("--step-time must be a finite duration > 0 s, got {dt}");
                }
                (0..steps).map(|k| k as f64 * dt).collect()
            }
            (None, Some(t)) => {
                if t.len() != steps {
                    bail!(
                        "--times gives {} times for a path of {steps} steps: give one a step",
                        t.len()
                    );
                }
                if let Some(w) = t.windows(2).find(|w| w[1] < w[0]) {
                    bail!("--times go backwards: {:e} s after {:e} s", w[1], w[0]);
                }
                t.clone()
            }
            _ => bail!(
                "a viscoelastic body (--maxwell-moduli) remembers its path: give each step a time, \
                 --step-time S or --times T,T,... [s]"
            ),
        };
        Ok(Some(times))
    }

    /// The pull-off search after the path, if asked for (`pull_off_step`), checked.
    pub fn pull_off(&self) -> Result<Option<solver::PullOffSearch>> {
        let Some(step) = self.pull_off_step else {
            if self.pull_off_floor.is_some()
                || self.pull_off_refinement.is_some()
                || self.pull_off_recovery.is_some()
            {
                bail!("the pull-off search's settings need --pull-off-step [m], which asks for it");
            }
            return Ok(None);
        };
        if !(step.is_finite() && step > 0.0) {
            bail!("--pull-off-step must be a positive length [m], got {step}");
        }
        let Some(floor) = self.pull_off_floor else {
            bail!("--pull-off-step needs --pull-off-floor, the lowest approach to unload to [m]");
        };
        if !floor.is_finite() {
            bail!("--pull-off-floor must be finite [m], got {floor}");
        }
        let refinement = self.pull_off_refinement.unwrap_or(5);
        if refinement == 0 {
            bail!("--pull-off-refinement must be at least 1 (1: no refinement)");
        }
        let recovery = self.pull_off_recovery.unwrap_or(0.5);
        if !(recovery > 0.0 && recovery <= 1.0) {
            bail!("--pull-off-recovery must be in (0, 1], got {recovery}");
        }
        if self.times.is_some() {
            bail!(
                "the pull-off search's steps on a viscoelastic body last --step-time each: give \
                 --step-time [s] rather than --times"
            );
        }
        Ok(Some(solver::PullOffSearch {
            step,
            floor,
            recovery: Some(recovery),
            refinement,
            rate: self.step_time.map(|dt| step / dt),
        }))
    }

    /// The largest step between two solves [m] on `problem` (`None`: no splitting), checked
    /// against `controls`.
    pub fn max_step(&self, problem: &ContactProblem, controls: &[Control]) -> Result<Option<f64>> {
        if let Some(h) = self.max_step
            && controls
                .iter()
                .all(|c| matches!(c, Control::MeanPressure(_) | Control::Force(_)))
        {
            bail!(
                "--max-step {h:e} does not apply to a path of loads: load steps are never split \
                 (it splits approach and central-gap steps)"
            );
        }
        let max_step = self.max_step.or(problem.adhesive().then(|| problem.law.range()));
        if let Some(h) = max_step
            && !(h.is_finite() && h > 0.0)
        {
            bail!("--max-step must be a positive length [m], got {h}");
        }
        solver::count_substeps(controls, max_step)?;
        Ok(max_step)
    }
}
