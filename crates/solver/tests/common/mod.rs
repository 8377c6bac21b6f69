//! What the solver's tests share: a problem from parts they keep using, and observers.
#![allow(dead_code)]

use elastic::{Compliance, Domain, Free, Periodic};
use ljadhesion::{AdhesionLaw, Cells, ExponentialLaw, LennardJones, PointLaw, SurfaceLaw};
use ndarray::Array2;
use solver::geometry::{SphereProfile, flat_on_rough, sphere};
use solver::{AdhesiveState, Control, Iterations, Method, Settings, SweepPoint, approach_cycle};
use surfgen::{Amplitudes, Grid, Normalization, Psd, SurfaceSpec, generate};

use ndarray::ArrayView2;
use solver::{ContactProblem, Observer};

pub const Z0: f64 = 1e-9;
pub const E: f64 = 1e9;
pub const R: f64 = 1e-6;

/// The problem of these parts (cloned: the tests go on using them).
pub fn problem<O, L>(op: &O, law: &L, g0: ArrayView2<f64>) -> ContactProblem
where
    O: Compliance + Clone + 'static,
    L: AdhesionLaw + Clone + 'static,
{
    ContactProblem::new(op.clone(), g0.to_owned(), law.clone()).unwrap()
}

/// Calls `f(index, point, state)` after every step of a sweep; `false` stops it.
pub struct Steps<F>(F);

pub fn steps<F: FnMut(usize, &SweepPoint, &AdhesiveState) -> bool>(f: F) -> Steps<F> {
    Steps(f)
}

impl<F: FnMut(usize, &SweepPoint, &AdhesiveState) -> bool> Observer for Steps<F> {
    fn step(&mut self, index: usize, point: &SweepPoint, state: &AdhesiveState) -> bool {
        (self.0)(index, point, state)
    }
}

/// The work a method did below its own iterations: inner or Krylov iterations, or the
/// descent's iterations.
pub fn inner(iterations: &Iterations) -> usize {
    iterations.inner().unwrap_or(iterations.count())
}

/// A rigid sphere (R = 1000 z0) on a free grid of `n^2` cells spanning `2 half_width` z0, with
/// the surface law at Tabor parameter `mu`; returns the operator, g0, the law and w0.
pub fn sphere_case(mu: f64, n: usize, half_width: f64) -> (Free, Array2<f64>, SurfaceLaw, f64) {
    // mu^3 = R w0^2 / (E*^2 z0^3)
    let w0 = (mu.powi(3) / (R / Z0)).sqrt() * E * Z0;
    let dx = 2.0 * half_width * Z0 / n as f64;
    let domain = Domain {
        nx: n,
        ny: n,
        dx,
        dy: dx,
        periodic: false,
    };
    let op = Free::new(domain, E).unwrap();
    let g0 = sphere(&domain, R, SphereProfile::Paraboloid, None).unwrap();
    let law = SurfaceLaw(LennardJones::new(w0, Z0).unwrap());
    assert!((theory::tabor_parameter(R, w0, E, Z0) / mu - 1.0).abs() < 1e-12);
    (op, g0, law, w0)
}

pub fn approaches(values: impl Iterator<Item = f64>) -> Vec<Control> {
    values.map(|a| Control::Approach(a * Z0)).collect()
}

pub fn pool() -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new().build().unwrap()
}

pub fn rough(n: usize) -> (Periodic, Array2<f64>) {
    let l = 1e-5;
    let grid = Grid::square(n, l).unwrap();
    flat_on_periodic(
        SurfaceSpec {
            grid,
            psd: Psd::self_affine(0.8, l / 4.0, 4.0 * grid.dx()),
            normalization: Normalization::RmsHeight(2e-8),
            amplitudes: Amplitudes::Exact,
            seed: 7,
        },
        1e8,
    )
}

/// A rigid flat on the periodic surface `spec` generates, over an elastic half-space of
/// modulus `e_star` [Pa]: the operator and the undeformed gap.
pub fn flat_on_periodic(spec: SurfaceSpec, e_star: f64) -> (Periodic, Array2<f64>) {
    let h = generate(&spec).unwrap().heights;
    let domain = Domain {
        nx: spec.grid.nx,
        ny: spec.grid.ny,
        dx: spec.grid.dx(),
        dy: spec.grid.dy(),
        periodic: true,
    };
    (
        Periodic::new(domain, e_star).unwrap(),
        flat_on_rough(h.view()).unwrap(),
    )
}

/// The contact-mechanics challenge's surface and material (H = 0.8, roll-off L/5, RMS gradient
/// 1, E* = 25 MPa) on 64^2 cells of 390 nm, the challenge's own cells at 256^2 (190 Lennard-Jones
/// process zones at w0 = 50 mJ/m^2, z0 = 2.071 nm): the operator, g0 and E* \[Pa\].
pub fn coarse_challenge() -> (Periodic, Array2<f64>, f64) {
    let l = 2.5e-5;
    let grid = Grid::square(64, l).unwrap();
    let e_star = 25e6;
    let (op, g0) = flat_on_periodic(
        SurfaceSpec {
            grid,
            psd: Psd::self_affine(0.8, l / 5.0, 4.0 * grid.dx()),
            normalization: Normalization::RmsGradient(1.0),
            amplitudes: Amplitudes::Exact,
            seed: 1,
        },
        e_star,
    );
    (op, g0, e_star)
}

/// The largest deviation of an adhesive solution from its equations, in units of the law's
/// range: gaps against `g0 - delta + K (p_c + p_a)` (zero in contact), the adhesive pressure
/// against the law times the cell compliance; and whether complementarity holds.
pub fn equilibrium_error(
    op: &dyn Compliance,
    law: &dyn AdhesionLaw,
    g0: &Array2<f64>,
    state: &AdhesiveState,
) -> f64 {
    let domain = *op.domain();
    let mut u = Array2::zeros(g0.dim());
    op.apply(
        state.total_pressure().view(),
        u.view_mut(),
        &mut op.make_workspace(),
    )
    .unwrap();
    let mut law_p = Array2::zeros(g0.dim());
    let cells = Cells {
        dx: domain.dx,
        dy: domain.dy,
        periodic: domain.periodic,
    };
    law.pressure_field(state.contact.gap.view(), &cells, law_p.view_mut())
        .unwrap();
    let c = domain.cell_compliance(op.e_star());
    let mut worst = 0.0f64;
    for (k, (&p, &g)) in state.contact.pressure.iter().zip(&state.contact.gap).enumerate() {
        assert!(p >= 0.0 && g >= 0.0 && (p == 0.0 || g == 0.0));
        let free_gap = g0.as_slice().unwrap()[k] - state.contact.approach + u.as_slice().unwrap()[k];
        let expected = if p > 0.0 { 0.0 } else { free_gap };
        worst = worst.max((expected - g).abs());
        let pa = state.adhesive_pressure.as_slice().unwrap()[k];
        worst = worst.max((pa - law_p.as_slice().unwrap()[k]).abs() * c);
    }
    worst / law.range()
}

/// The rough 64^2 surface under an exponential law of range 1 nm (against an RMS height of
/// 20 nm: asperities snap into contact and stick on the way back), cycled by energy descent
/// from a mean gap of 80 nm (the highest peak 10 ranges away) to 15 nm and back in `steps`
/// steps each way, split into substeps no longer than `max_step`.
pub fn rough_energy_cycle(
    steps: usize,
    max_step: Option<f64>,
    tolerance: f64,
) -> (Vec<Control>, Vec<SweepPoint>) {
    let (op, g0) = rough(64);
    let law = ExponentialLaw::new(5e-3, 1e-9).unwrap();
    let mean = g0.mean().unwrap();
    let path = approach_cycle(mean - 8e-8, mean - 1.5e-8, steps);
    let options = Settings {
        method: Method::EnergyDescent,
        tolerance,
        ..Settings::with_method(Method::Accelerated)
    };
    let points = problem(&op, &law, g0.view())
        .sweep(&path, max_step, &options, None, &mut ())
        .unwrap();
    (path, points)
}

/// A sweep and the largest error of its states in their equations (in ranges).
pub fn checked_sweep<O: Compliance + Clone + 'static, L: AdhesionLaw + Clone + 'static>(
    op: &O,
    law: &L,
    g0: &Array2<f64>,
    path: &[Control],
    options: &Settings,
) -> (Vec<SweepPoint>, f64) {
    let mut worst = 0.0f64;
    let points = problem(op, law, g0.view())
        .sweep(
            path,
            None,
            options,
            None,
            &mut steps(|_, _, state| {
                worst = worst.max(equilibrium_error(op, law, g0, state));
                true
            }),
        )
        .unwrap();
    (points, worst)
}

/// A cycle of the sphere at mu = 10, point law, by the energy descent on a free grid: the
/// points, w0 and the largest error in the equations (in ranges).
pub fn high_tabor_cycle(n: usize, half_width: f64, path: &[Control]) -> (Vec<SweepPoint>, f64, f64) {
    let (op, g0, law, w0) = sphere_case(10.0, n, half_width);
    let point = PointLaw(law.0);
    let options = Settings {
        method: Method::EnergyDescent,
        ..Settings::with_method(Method::Accelerated)
    };
    let (points, worst) = checked_sweep(&op, &point, &g0, path, &options);
    (points, w0, worst)
}

/// The contact-mechanics challenge's surface as `xtask`'s Figs. 8-9 build it (L = 100 um,
/// H = 0.8, roll-off 20 um, cutoff four cells, RMS gradient 1, seed 1) on `n^2` cells, with its
/// modulus (25 MPa) and exponential adhesion (50 mJ/m^2, 2.071 nm).
pub fn challenge(n: usize) -> (Periodic, Array2<f64>, ExponentialLaw) {
    let grid = Grid::square(n, 1e-4).unwrap();
    let (op, g0) = flat_on_periodic(
        SurfaceSpec {
            grid,
            psd: Psd::self_affine(0.8, 2e-5, (1e-7f64).max(4.0 * grid.dx())),
            normalization: Normalization::RmsGradient(1.0),
            amplitudes: Amplitudes::Exact,
            seed: 1,
        },
        25e6,
    );
    (op, g0, ExponentialLaw::new(0.05, 2.071e-9).unwrap())
}

/// The cycle of `path` by the accelerated loop, and what it shows.
pub fn accelerated_cycle<O, L>(
    op: &O,
    law: &L,
    g0: &Array2<f64>,
    path: &[Control],
) -> (Vec<SweepPoint>, solver::CycleSummary)
where
    O: Compliance + Clone + 'static,
    L: AdhesionLaw + Clone + 'static,
{
    let points = problem(op, law, g0.view())
        .sweep(
            path,
            None,
            &Settings::with_method(Method::Accelerated),
            None,
            &mut (),
        )
        .unwrap();
    let summary = solver::summarize(&points.iter().map(solver::CyclePoint::from).collect::<Vec<_>>());
    (points, summary)
}

/// Two methods' sweeps of one path agree: every step converged, loads within `tolerance`
/// times `load_unit` [N], the same contact area.
pub fn assert_same_cycle(a: &[SweepPoint], b: &[SweepPoint], load_unit: f64, tolerance: f64) {
    assert_eq!(a.len(), b.len());
    for (a, b) in a.iter().zip(b) {
        let (ra, rb) = (&a.report, &b.report);
        println!(
            "a/z0 {:5.2}: load {:9.6} ({}, {:?}) against {:9.6} ({}, {:?}); area {:.4}",
            ra.approach / Z0,
            ra.load / load_unit,
            ra.method,
            ra.iterations,
            rb.load / load_unit,
            rb.method,
            rb.iterations,
            ra.contact_area_fraction
        );
        assert!(ra.converged() && rb.converged());
        assert!((ra.load - rb.load).abs() < tolerance * load_unit);
        assert_eq!(ra.contact_area_fraction, rb.contact_area_fraction);
    }
}

/// Prints a sweep, a line a step, loads in units of `load_unit` [N].
pub fn print_cycle(points: &[SweepPoint], load_unit: f64) {
    for p in points {
        let r = &p.report;
        println!(
            "{:9} a/z0 {:6.2} load {:9.6} area {:.4} {:?}",
            p.branch.name(),
            r.approach / Z0,
            r.load / load_unit,
            r.contact_area_fraction,
            r.iterations
        );
    }
}
