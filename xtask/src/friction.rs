//! `cargo xtask study friction-rough`: partial slip of a rough adhesive contact, with and
//! without a shear strength.

use anyhow::Result;
use ljadhesion::{LennardJones, SurfaceLaw};
use plot::{Chart, Curve, Mark, PALETTE};
use solver::{
    AdhesiveState, ContactProblem, Control, Friction, Settings, ShearOptions, ShearState, Start,
    TangentialControl,
};

/// The units: E* \[Pa\], z0 \[m\]; the work of adhesion `0.05 E* z0`, Coulomb's `mu`.
const E_STAR: f64 = 1e9;
const Z0: f64 = 1e-9;
const W0: f64 = 0.05 * E_STAR * Z0;
const MU: f64 = 0.3;

/// A periodic self-affine surface (N^2, default 256, across 512 z0; Rq = 2 z0, H = 0.8) with a
/// Lennard-Jones surface law (w0 = 0.05 E* z0), pressed in by approach from apart to three
/// depths; on each state a shear grows along x to 0.95 of the static friction, with Coulomb's
/// mu = 0.3 alone and with a shear strength `tau0` of 0.02 E* beside it. Prints the normal
/// state, the static friction and the stick fraction against Q over the static friction;
/// writes the figure to `FIGURE` (default `docs/figures/friction-rough`).
pub fn friction_rough() -> Result<()> {
    let n: usize = std::env::var("N").unwrap_or_else(|_| "256".into()).parse()?;
    let figure = std::env::var("FIGURE").unwrap_or_else(|_| "docs/figures/friction-rough".into());
    let side = 512.0 * Z0;
    let spec = surfgen::SurfaceSpec {
        grid: surfgen::Grid::square(n, side)?,
        psd: surfgen::Psd::self_affine(0.8, side / 4.0, 4.0 * side / n as f64),
        normalization: surfgen::Normalization::RmsHeight(2.0 * Z0),
        amplitudes: surfgen::Amplitudes::Exact,
        seed: 2028,
    };
    let heights = surfgen::generate(&spec)?.heights;
    let tau0 = 0.02 * E_STAR;
    let build = |shear_strength: f64| -> Result<ContactProblem> {
        Ok(ContactProblem::builder()
            .roughness(heights.clone(), side, side)
            .modulus(E_STAR)
            .poisson(0.5)
            .friction(Friction::new(MU, shear_strength)?)
            .law(SurfaceLaw(LennardJones::new(W0, Z0)?))
            .build()?)
    };
    let problems = [build(0.0)?, build(tau0)?];
    let settings = Settings::default();
    // Pressed in by approach (from the highest peak's touch) in steps of z0/2.
    let depths = [1.0, 2.0, 4.0];
    let mut states: Vec<(f64, AdhesiveState, solver::AdhesiveReport)> = Vec::new();
    let mut last: Option<AdhesiveState> = None;
    let mut a = -1.0;
    while a <= depths[depths.len() - 1] + 1e-9 {
        let start = last.as_ref().map_or(Start::Loading, Start::Warm);
        let (state, report) = problems[0].solve(Control::Approach(a * Z0), &settings, start, &mut ())?;
        if depths.iter().any(|d| (d - a).abs() < 1e-9) {
            states.push((a, state.clone(), report));
        }
        last = Some(state);
        a += 0.5;
    }
    let mut chart = Chart::new(
        format!("partial slip of a rough adhesive contact ({n}^2, Rq = 2 z0, w0 = 0.05 E* z0)"),
        "Q / static friction",
        "stick area / contact area",
    );
    println!(
        "| approach (z0) | load / (E* A) | contact fraction | tau0 / E* | static friction / (E* A) | share of tau0 A | stick/contact at Q/Qs = 0.25, 0.5, 0.75, 0.95 | iterations a step |"
    );
    println!("|---|---|---|---|---|---|---|---|");
    let ratios = [0.05, 0.1, 0.25, 0.5, 0.75, 0.9, 0.95];
    for (k, (depth, normal, report)) in states.iter().enumerate() {
        for (j, problem) in problems.iter().enumerate() {
            let tangential = problem.tangential(&normal.contact)?;
            let capacity = tangential.capacity();
            let contact = tangential.contact_area_fraction();
            let controls: Vec<_> = ratios
                .iter()
                .map(|r| TangentialControl::Force([r * capacity, 0.0]))
                .collect();
            let (_, reports) = tangential.path(
                &controls,
                ShearState::unloaded((n, n)),
                &ShearOptions::default(),
                &mut |_, _, _| true,
            )?;
            let points: Vec<(f64, f64, bool)> = ratios
                .iter()
                .zip(&reports)
                .map(|(r, rep)| {
                    let converged = rep.termination == solver::report::Termination::Converged;
                    (*r, rep.stick_area_fraction / contact, converged)
                })
                .collect();
            let pick = |r: f64| {
                points
                    .iter()
                    .find(|p| (p.0 - r).abs() < 1e-12)
                    .map_or(f64::NAN, |p| p.1)
            };
            let strength = if j == 0 { 0.0 } else { tau0 };
            let area = side * side;
            println!(
                "| {depth} | {:.3e} | {:.4} | {} | {:.3e} | {:.2} | {:.3}, {:.3}, {:.3}, {:.3} | {:.0} |",
                report.load / (E_STAR * area),
                contact,
                strength / E_STAR,
                capacity / (E_STAR * area),
                strength * contact * area / capacity,
                pick(0.25),
                pick(0.5),
                pick(0.75),
                pick(0.95),
                reports.iter().map(|r| r.iterations as f64).sum::<f64>() / reports.len() as f64
            );
            chart.curves.push(Curve::solved(
                format!(
                    "{depth} z0 in, {}",
                    if j == 0 { "mu only" } else { "mu and tau0" }
                ),
                points,
                if j == 0 { Mark::Line } else { Mark::Dashed },
                PALETTE[k % PALETTE.len()],
            ));
        }
    }
    crate::study::save_figure(&chart, &figure)
}
