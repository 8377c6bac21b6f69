//! A rigid wave on a periodic half-space: Westergaard's non-adhesive solution and Johnson's
//! (1995) JKR solution (`theory::wavy`) at a high Tabor parameter, on grids that resolve the
//! adhesive process zone many times over (a wavelength of thousands of cells costs little in
//! one dimension).

mod common;

use elastic::{Compliance, Domain, Periodic};
use ljadhesion::{LennardJones, PointLaw, SurfaceLaw};
use ndarray::Array2;
use solver::cg::solve;
use solver::geometry::wave;
use solver::{
    AdhesiveReport, Branch, ContactOptions, Control, CyclePoint, Method, Settings, SweepPoint, summarize,
};
use std::f64::consts::PI;
use theory::wavy::Wave;

const Z0: f64 = 1e-9;
const E: f64 = 1e9;
const W0: f64 = 0.1 * E * Z0;

/// A wave with Johnson's parameter `alpha` whose crests have Tabor parameter `mu`, with
/// `w0 = E* z0 / 10` (the process zone `E* w0 / sigma0^2` is then 9.5 z0, and the gap's
/// slope at the contact edge about 0.1: a half-space's small slopes), one wavelength across
/// `n` cells (two rows: the problem is one-dimensional).
fn wave_case(mu: f64, alpha: f64, n: usize) -> (Periodic, Array2<f64>, Wave) {
    let w0 = W0;
    // mu^3 = R w0^2 / (E*^2 z0^3), alpha^2 = 2 lambda w0 / (pi^2 E* Delta^2), R = lambda^2 / (4 pi^2 Delta)
    let r = mu.powi(3) * Z0.powi(3) * E * E / (w0 * w0);
    let wavelength = (32.0 * PI * PI * r * r * w0 / (E * alpha * alpha)).cbrt();
    let amplitude = wavelength.powi(2) / (4.0 * PI * PI * r);
    let theory = Wave {
        amplitude,
        wavelength,
        e_star: E,
        work_of_adhesion: w0,
    };
    assert!((theory.johnson_alpha() / alpha - 1.0).abs() < 1e-12);
    assert!((theory::tabor_parameter(theory.crest_radius(), w0, E, Z0) / mu - 1.0).abs() < 1e-12);
    let dx = wavelength / n as f64;
    let domain = Domain {
        nx: n,
        ny: 2,
        dx,
        dy: dx,
        periodic: true,
    };
    let g0 = wave(&domain, amplitude, None).unwrap();
    (Periodic::new(domain, E).unwrap(), g0, theory)
}

#[test]
fn a_pressed_wave_is_westergaards() {
    let (op, g0, theory) = wave_case(10.0, 0.3, 4096);
    let p_star = theory.full_contact_pressure();
    // From a narrow strip to near-complete contact (the amplitude is 58 z0).
    for approach in [5.0, 20.0, 40.0, 50.0, 56.0] {
        let (_, report) = solve(
            &op,
            g0.view(),
            Control::Approach(approach * Z0),
            &ContactOptions::default(),
            None,
            &mut (),
        )
        .unwrap();
        let a = 0.5 * report.contact_area_fraction * theory.wavelength;
        // Counting cells puts the edge within half a cell: dp/da * dx / 2 bounds the error.
        let slope = PI * p_star / theory.wavelength * (2.0 * PI * a / theory.wavelength).sin();
        let tol = slope * op.domain().dx;
        let expected = theory.westergaard_pressure(a);
        println!(
            "approach {approach} z0: p/p* {:.5}, Westergaard {:.5}",
            report.mean_pressure / p_star,
            expected / p_star
        );
        assert!(
            (report.mean_pressure - expected).abs() < tol,
            "{} vs {expected}",
            report.mean_pressure
        );
    }
}

/// The Lennard-Jones law a cycle uses, each with its solver.
#[derive(Clone, Copy, Debug)]
enum Law {
    /// The point law, by energy descent.
    Point,
    /// The paper's surface law, by Newton.
    Surface,
}

/// A cycle of the wave: approach from `bottom` [z0] (apart) to `top` [z0] and back in steps of
/// one `z0`.
fn wave_cycle(op: &Periodic, g0: &Array2<f64>, law: Law, top: i32, bottom: i32) -> Vec<SweepPoint> {
    let lj = LennardJones::new(W0, Z0).unwrap();
    let (point, surface) = (PointLaw(lj), SurfaceLaw(lj));
    let (problem, method) = match law {
        Law::Point => (common::problem(op, &point, g0.view()), Method::EnergyDescent),
        Law::Surface => (common::problem(op, &surface, g0.view()), Method::Newton),
    };
    let mut path: Vec<Control> = (bottom..=top).map(|k| Control::Approach(k as f64 * Z0)).collect();
    path.extend((bottom..top).rev().map(|k| Control::Approach(k as f64 * Z0)));
    let options = Settings::with_method(method);
    problem.sweep(&path, None, &options, None, &mut ()).unwrap()
}

/// How a wave's cycle compares with Johnson's JKR solution.
struct Agreement {
    /// Largest `|p - p_JKR(a)|` over `p*` on the loading and the unloading branch, beyond what
    /// counting attached cells explains (each edge placed within a cell).
    worst: [f64; 2],
    /// The most tensile mean pressure while unloading over Johnson's pull-off pressure.
    pull_off_ratio: f64,
}

/// How far a solve's mean pressure lies from Johnson's at its attached half-width, beyond what
/// placing each edge within a cell `dx` [m] explains, in units of `p*`; `None` when detached.
fn jkr_excess(theory: &Wave, dx: f64, r: &AdhesiveReport) -> Option<f64> {
    (r.attached_area_fraction > 0.0).then(|| {
        let a = 0.5 * r.attached_area_fraction * theory.wavelength;
        let quantum = (theory.jkr_pressure(a + dx) - theory.jkr_pressure(a)).abs();
        ((r.mean_pressure - theory.jkr_pressure(a)).abs() - quantum) / theory.full_contact_pressure()
    })
}

/// Runs the wave at Tabor parameter `mu` on `n` cells (Johnson's alpha = 0.3: adhesive but not
/// sticky, the contact does not snap shut) from `bottom` to `top` [z0] and back, and checks
/// what holds at any resolution: every step converges, the wall contact lies inside the
/// attached strip, the strip outlives the load's minimum under approach control, and the cycle
/// loses energy.
fn johnson_agreement(law: Law, mu: f64, n: usize, top: i32, bottom: i32) -> Agreement {
    let (op, g0, theory) = wave_case(mu, 0.3, n);
    let points = wave_cycle(&op, &g0, law, top, bottom);
    let p_star = theory.full_contact_pressure();
    let dx = op.domain().dx;
    let mut worst = [0.0f64; 2];
    for p in &points {
        let r = &p.report;
        assert!(r.converged(), "mu = {mu}, approach {} z0", r.approach / Z0);
        // JKR's contact edge is the crack tip: the attached cells (gap under z0) reach out to
        // the peak tension, while those on the wall (p_c > 0) are only the compressive part of
        // the contact (at mu = 10 about 3/4 of it at zero load, none once the load is tensile
        // enough).
        assert!(r.contact_area_fraction <= r.attached_area_fraction);
        if let Some(excess) = jkr_excess(&theory, dx, r) {
            let b = usize::from(p.branch == Branch::Unloading);
            worst[b] = worst[b].max(excess);
        }
    }
    let (pull_off, a_min) = theory.jkr_pull_off();
    let tensile = points
        .iter()
        .filter(|p| p.branch == Branch::Unloading)
        .map(|p| p.report.mean_pressure)
        .fold(f64::INFINITY, f64::min);
    let last_attached = points
        .iter()
        .rfind(|p| p.branch == Branch::Unloading && p.report.attached_area_fraction > 0.0)
        .unwrap();
    assert!(0.5 * last_attached.report.attached_area_fraction * theory.wavelength < a_min);
    let summary = summarize(&points.iter().map(CyclePoint::from).collect::<Vec<_>>());
    assert!(summary.jump_out_approach.is_some() && summary.hysteresis_energy.is_some_and(|w| w > 0.0));
    println!(
        "{law:?} law, mu = {mu}, {n} cells ({:.1} per process zone): within {:.2e} (loading) and {:.2e} \
         (unloading) p* + a cell's worth of Johnson's; pull-off {:.5} p*, Johnson {:.5} p*",
        n as f64 / (theory.wavelength / (0.95 * Z0 * E * Z0 / W0)),
        worst[0],
        worst[1],
        tensile / p_star,
        pull_off / p_star
    );
    Agreement {
        worst,
        pull_off_ratio: tensile / pull_off,
    }
}

#[test]
fn a_high_tabor_wave_follows_johnsons_jkr_solution() {
    // mu = 3 with 7 cells per process zone: within 7e-4 p* on both branches, pull-off 0.7 %.
    let a = johnson_agreement(Law::Point, 3.0, 1024, 12, -10);
    assert!(a.worst[0] < 1e-3 && a.worst[1] < 1e-3, "{:?}", a.worst);
    assert!((a.pull_off_ratio - 1.0).abs() < 0.01, "{}", a.pull_off_ratio);
    // mu = 10 with 2.6 cells per process zone: the lattice holds the advancing edge back (the
    // loading branch 2.0e-3 p* off, unloading 1.1e-3, pull-off 0.8 %); both fall to 4.9e-4 and
    // 0.07 % on 8192 cells (`wave_mesh_study`), so the bounds here are the grid's, not the
    // law's.
    let a = johnson_agreement(Law::Point, 10.0, 4096, 36, -26);
    assert!(a.worst[0] < 2.5e-3 && a.worst[1] < 1.5e-3, "{:?}", a.worst);
    assert!((a.pull_off_ratio - 1.0).abs() < 0.015, "{}", a.pull_off_ratio);
}

#[test]
#[ignore = "long: the mu = 10 wave converging from 2048 to 8192 cells (docs/validation.md)"]
fn wave_mesh_study() {
    let mut previous: Option<Agreement> = None;
    for n in [2048, 4096, 8192] {
        let a = johnson_agreement(Law::Point, 10.0, n, 36, -26);
        if let Some(p) = previous {
            assert!(
                a.worst[0] < p.worst[0] && (a.pull_off_ratio - 1.0).abs() < (p.pull_off_ratio - 1.0).abs()
            );
        }
        previous = Some(a);
    }
}

#[test]
fn the_surface_law_converges_on_a_high_tabor_wave() {
    // The paper's surface law where it is 30 times stiffer than a cell at the wall (mu = 10,
    // 4096 cells): the jump in at -6 z0, two steps on and back, each a lattice-trapped crack
    // front carrying about 13 cells per edge over their snap (Newton: ~330 steps a solve; with
    // the pseudo-time step grown only by the residual's ratio and 60 steps of patience, 2 of
    // these 7 steps ended unconverged after more than 6000 Newton steps each).
    let (op, g0, theory) = wave_case(10.0, 0.3, 4096);
    let points = wave_cycle(&op, &g0, Law::Surface, -4, -7);
    for p in &points {
        let r = &p.report;
        assert!(r.converged(), "approach {} z0", r.approach / Z0);
        if r.approach > -6.5 * Z0 {
            // Attached, and on Johnson's curve as closely as along the whole cycle (the study
            // below).
            let excess = jkr_excess(&theory, op.domain().dx, r).expect("attached");
            assert!(excess < 5e-3, "approach {} z0: {excess}", r.approach / Z0);
        }
    }
}

#[test]
#[ignore = "long: the paper's surface law on the mu = 10 wave, 124 Newton solves (17 minutes; docs/validation.md)"]
fn the_surface_law_on_a_high_tabor_wave_follows_johnsons_jkr_solution() {
    // Measured: within 4.9e-3 (loading) and 4.7e-3 (unloading) p*, pull-off 2.4 % above
    // Johnson's. The point law on the same grid: 2.0e-3, 1.1e-3 and 0.8 %: the surface law's
    // area factor adds attraction where the gap slopes at the crack tip.
    let a = johnson_agreement(Law::Surface, 10.0, 4096, 36, -26);
    assert!(a.worst[0] < 5e-3 && a.worst[1] < 5e-3, "{:?}", a.worst);
    assert!((a.pull_off_ratio - 1.0).abs() < 0.03, "{}", a.pull_off_ratio);
}
