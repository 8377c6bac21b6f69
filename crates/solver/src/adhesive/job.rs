//! What every method is given and gives back: the checked job, the trait a method implements,
//! and the state and report a finished solve assembles.

use super::{AdhesiveReport, AdhesiveState, Iterations, Start};
use crate::error::Result;
use crate::interface::Interface;
use crate::method::{Method, Settings};
use crate::options::Control;
use crate::report::{Termination, count_clusters};
use crate::state::ContactState;
use elastic::{Compliance, Domain};
use ljadhesion::{AdhesionLaw, Cells};
use ndarray::{Array2, ArrayView2, Zip};
use std::time::Instant;

/// The law's view of a grid: the one conversion from the elastic grid to the law's cells.
pub(crate) fn cells(domain: &Domain) -> Cells {
    Cells {
        dx: domain.dx,
        dy: domain.dy,
        periodic: domain.periodic,
    }
}

/// One solve's input, checked: the problem's parts, the control, the settings, the resolved
/// method and the start. A method that cannot take the interface refuses it in its `check`.
#[derive(Clone, Copy)]
pub(crate) struct Job<'a> {
    pub op: &'a dyn Compliance,
    pub law: &'a dyn AdhesionLaw,
    pub interface: Interface,
    /// The initial gap, the start's permanent set included.
    pub g0: ArrayView2<'a, f64>,
    pub control: Control,
    pub settings: &'a Settings,
    pub method: Method,
    pub start: Start<'a>,
}

impl Job<'_> {
    /// The residuals' scale: a cell's compliance over the law's range [1/Pa].
    pub fn residual_scale(&self) -> f64 {
        self.op.cell_compliance() / self.law.range()
    }
}

/// An adhesive method: a file or folder implementing this, and its entry in the table of
/// methods (`method.rs`: the variant of [`Method`], its name, its implementation).
pub(crate) trait AdhesiveMethod {
    /// Refuses, with the reason and a method that can, a problem this method cannot solve.
    fn check(&self, job: &Job) -> Result<()>;

    /// Solves `job`, calling `observer(iteration, residual)` after every iteration.
    fn solve(
        &self,
        job: &Job,
        observer: &mut dyn FnMut(usize, f64) -> bool,
    ) -> Result<(AdhesiveState, AdhesiveReport)>;

    /// Roughly the peak memory \[bytes\] a solve takes on a grid of `cells` cells, periodic or
    /// free, without the process's fixed part: the bytes a cell measured at 256^2-1024^2
    /// (`docs/performance.md`). For refusing a grid before anything is allocated; not a bound.
    fn peak_bytes(&self, cells: f64, periodic: bool) -> f64;
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
    let (mut max_p, mut min_p, mut stored) = (f64::NEG_INFINITY, f64::INFINITY, 0.0);
    Zip::from(&contact.pressure)
        .and(&p_a)
        .and(&contact.displacement)
        .for_each(|&c, &a, &u| {
            max_p = max_p.max(c + a);
            min_p = min_p.min(c + a);
            stored += (c + a) * u;
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
        yielding: crate::interface::Yield::default(),
        elastic_energy: 0.5 * stored * cell,
        viscous_work: 0.0,
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
