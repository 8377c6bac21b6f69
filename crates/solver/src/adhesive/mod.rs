//! Adhesive contact: what the five methods share (`docs/method.md` section 4 for the physics,
//! `docs/solvers.md` for the methods).
//!
//! The pressure is split into a compressive part `p_c >= 0` (the contact constraint) and an
//! adhesive part `p_a <= 0` (the law). Every method implements the trait `AdhesiveMethod` in a file
//! of its own: the dual loops (`dual_loop`), the energy descent (`energy`), Newton
//! (`newton`) and the damped relaxation (`flow`), the last three over the gap problem of
//! `gap`; Newton's linear solves
//! are the GMRES of `krylov`. `solve` checks the input,
//! resolves [`Method::Auto`], asks the method whether it can solve the problem, and runs it.

mod anderson;
mod driver;
mod dual_loop;
mod energy;
mod flow;
mod gap;
mod krylov;
mod newton;
pub(crate) use newton::restart_for;

use crate::error::{Result, SolverError, invalid};
use crate::method::{Method, Settings};
use crate::options::Control;
use crate::problem::ContactProblem;
use crate::report::{Termination, count_clusters};
use crate::state::ContactState;
use elastic::{Compliance, Domain};
use ljadhesion::{AdhesionLaw, Cells};
use ndarray::{Array2, ArrayView2, Zip};
use std::time::Instant;

/// Where a solve starts.
#[derive(Clone, Copy, Debug)]
pub enum Start<'a> {
    /// No adhesive pressure: the bodies come together (the paper's loading start).
    Loading,
    /// The law's peak attraction everywhere: the bodies come apart from contact (the paper's
    /// unloading start).
    Unloading,
    /// A previous solution on the same grid (continuation along a sweep).
    Warm(&'a AdhesiveState),
}

/// The fields of an adhesive contact: all of shape `(ny, nx)`.
#[derive(Clone, Debug, PartialEq)]
pub struct AdhesiveState {
    /// Compressive pressure `p_c >= 0` \[Pa\] in `pressure`, the gap \[m\] (zero in contact), the
    /// total surface displacement `K (p_c + p_a)` \[m\] and the approach \[m\].
    pub contact: ContactState,
    /// Adhesive pressure `p_a <= 0` \[Pa\].
    pub adhesive_pressure: Array2<f64>,
}

impl AdhesiveState {
    fn is_standard_layout(&self) -> bool {
        let c = &self.contact;
        [&c.pressure, &c.gap, &c.displacement, &self.adhesive_pressure]
            .iter()
            .all(|a| a.is_standard_layout())
    }

    fn to_standard_layout(&self) -> AdhesiveState {
        let standard = |a: &Array2<f64>| a.as_standard_layout().into_owned();
        AdhesiveState {
            contact: ContactState {
                pressure: standard(&self.contact.pressure),
                gap: standard(&self.contact.gap),
                displacement: standard(&self.contact.displacement),
                approach: self.contact.approach,
            },
            adhesive_pressure: standard(&self.adhesive_pressure),
        }
    }

    /// The total pressure `p_c + p_a` \[Pa\].
    pub fn total_pressure(&self) -> Array2<f64> {
        &self.contact.pressure + &self.adhesive_pressure
    }
}

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
    /// The iterations the limit [`Settings::max_iterations`] bounds: outer iterations,
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
    /// The method that solved it ([`Method::Auto`] resolved).
    pub method: Method,
    /// What the method counted.
    pub iterations: Iterations,
    /// Calls to the elastic operator.
    pub operator_calls: usize,
    /// Final residual, in units of the law's range ([`Settings::tolerance`]).
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

/// The displacement \[m\] of one cell under unit pressure \[Pa\] on itself: the cell's compliance.
pub fn cell_compliance(domain: &Domain, e_star: f64) -> f64 {
    elastic::love::cell_influence(0.0, 0.0, domain.dx / 2.0, domain.dy / 2.0, e_star)
}

/// The law's view of a grid: the one conversion from the elastic grid to the law's cells.
pub(crate) fn cells(domain: &Domain) -> Cells {
    Cells {
        dx: domain.dx,
        dy: domain.dy,
        periodic: domain.periodic,
    }
}

/// One solve's input, checked: the problem's parts, the control, the settings, the resolved
/// method and the start.
#[derive(Clone, Copy)]
pub(crate) struct Job<'a> {
    pub op: &'a dyn Compliance,
    pub law: &'a dyn AdhesionLaw,
    pub g0: ArrayView2<'a, f64>,
    pub control: Control,
    pub settings: &'a Settings,
    pub method: Method,
    pub start: Start<'a>,
}

impl Job<'_> {
    /// The residuals' scale: a cell's compliance over the law's range [1/Pa].
    pub fn residual_scale(&self) -> f64 {
        cell_compliance(self.op.domain(), self.op.e_star()) / self.law.range()
    }
}

/// An adhesive method. A new method is a file implementing this, and a line in
/// [`implementation`].
pub(crate) trait AdhesiveMethod {
    /// Refuses, with the reason and a method that can, a problem this method cannot solve.
    fn check(&self, job: &Job) -> Result<()>;

    /// Solves `job`, calling `observer(iteration, residual)` after every iteration.
    fn solve(
        &self,
        job: &Job,
        observer: &mut dyn FnMut(usize, f64) -> bool,
    ) -> Result<(AdhesiveState, AdhesiveReport)>;
}

fn implementation(method: Method) -> &'static dyn AdhesiveMethod {
    match method {
        Method::DualLoop => &dual_loop::DualLoop { accelerated: false },
        Method::Auto | Method::Accelerated => &dual_loop::DualLoop { accelerated: true },
        Method::EnergyDescent => &energy::EnergyDescent,
        Method::Newton => &newton::Newton,
        Method::Flow => &flow::Flow,
    }
}

/// Solves `problem` under `control` (see [`ContactProblem::solve`]).
pub(crate) fn solve(
    problem: &ContactProblem,
    control: Control,
    settings: &Settings,
    start: Start,
    observer: &mut dyn FnMut(usize, f64) -> bool,
) -> Result<(AdhesiveState, AdhesiveReport)> {
    let op = problem.operator.as_ref();
    let shape = op.domain().shape();
    // The methods work on contiguous rows: any other layout is copied into one here.
    let g0 = problem.initial_gap.as_standard_layout();
    let g0 = g0.view();
    if g0.dim() != shape {
        return Err(SolverError::ShapeMismatch {
            what: "initial gap",
            expected: shape,
            got: g0.dim(),
        });
    }
    settings.validate()?;
    let value = match control {
        Control::Approach(v) | Control::Force(v) | Control::MeanPressure(v) | Control::CentralGap(v) => v,
    };
    if !value.is_finite() {
        return Err(invalid("control", value, "must be finite"));
    }
    if let Control::CentralGap(g) = control
        && g <= 0.0
    {
        return Err(invalid(
            "central_gap",
            g,
            "must be > 0 m: in contact the central gap does not fix the approach",
        ));
    }
    if let Start::Warm(s) = start {
        for (what, got) in [
            ("warm-start adhesive pressure", s.adhesive_pressure.dim()),
            ("warm-start gap", s.contact.gap.dim()),
        ] {
            if got != shape {
                return Err(SolverError::ShapeMismatch {
                    what,
                    expected: shape,
                    got,
                });
            }
        }
    }
    let standard;
    let start = match start {
        Start::Warm(s) if !s.is_standard_layout() => {
            standard = s.to_standard_layout();
            Start::Warm(&standard)
        }
        other => other,
    };
    let law = problem.law.as_ref();
    let method = settings.method.resolve(law, control, op.domain(), op.e_star());
    let job = Job {
        op,
        law,
        g0,
        control,
        settings,
        method,
        start,
    };
    let imp = implementation(method);
    imp.check(&job)?;
    let (state, report) = imp.solve(&job, observer)?;
    crate::error::finite_result(
        &[
            ("compressive pressure", &state.contact.pressure),
            ("adhesive pressure", &state.adhesive_pressure),
            ("gap", &state.contact.gap),
            ("displacement", &state.contact.displacement),
        ],
        &[("load", report.load), ("approach", report.approach)],
    )?;
    Ok((state, report))
}

/// How a method's solve ended: its counts, residuals and termination.
pub(crate) struct Outcome {
    pub iterations: Iterations,
    pub operator_calls: usize,
    pub history: Vec<f64>,
    pub termination: Termination,
    pub started: Instant,
}

/// The state and report of a finished solve: `contact` with its gap, compressive pressure,
/// displacement and approach set, and the adhesive pressure `p_a`.
pub(crate) fn assemble(
    job: &Job,
    contact: ContactState,
    p_a: Array2<f64>,
    outcome: Outcome,
) -> (AdhesiveState, AdhesiveReport) {
    let domain = job.op.domain();
    let cell = domain.cell_area();
    let n = (domain.nx * domain.ny) as f64;
    let centre = (domain.ny / 2, domain.nx / 2);
    let compressive_load = contact.pressure.sum() * cell;
    let adhesive_load = p_a.sum() * cell;
    let load = compressive_load + adhesive_load;
    let in_contact = contact.pressure.iter().filter(|&&p| p > 0.0).count();
    let attractive = Zip::from(&contact.pressure)
        .and(&p_a)
        .fold(0usize, |acc, &c, &a| acc + usize::from(c == 0.0 && a < 0.0));
    let range = job.law.range();
    let attached = contact.gap.iter().filter(|&&g| g < range).count();
    let (mut max_p, mut min_p) = (f64::NEG_INFINITY, f64::INFINITY);
    Zip::from(&contact.pressure).and(&p_a).for_each(|&c, &a| {
        max_p = max_p.max(c + a);
        min_p = min_p.min(c + a);
    });
    let report = AdhesiveReport {
        load,
        mean_pressure: load / (n * cell),
        compressive_load,
        adhesive_load,
        approach: contact.approach,
        central_gap: contact.gap[centre],
        contact_area_fraction: in_contact as f64 / n,
        attractive_area_fraction: attractive as f64 / n,
        attached_area_fraction: attached as f64 / n,
        clusters: count_clusters(contact.pressure.view(), domain.periodic),
        max_pressure: max_p,
        min_pressure: min_p,
        method: job.method,
        iterations: outcome.iterations,
        operator_calls: outcome.operator_calls,
        residual: outcome.history.last().copied().unwrap_or(f64::NAN),
        residual_history: outcome.history,
        termination: outcome.termination,
        wall_time_s: outcome.started.elapsed().as_secs_f64(),
    };
    let state = AdhesiveState {
        contact,
        adhesive_pressure: p_a,
    };
    (state, report)
}
