//! `cargo xtask study plastic-rough`: elastic and plastic contact areas of a self-affine surface
//! under a hardness, against load, beside Persson's elastoplastic theory, with the iterations
//! each solve took beside the elastic solve at the same load.

use anyhow::Result;
use elastic::{Domain, Periodic};
use solver::{ContactOptions, Control, Interface, cg};
use std::time::Instant;

/// One surface (Hurst 0.8, no roll-off, cut-off at 8 cells, seed 2026, unit box, E* = 1) on
/// `N` (default 1024) cells a side, at RMS gradients 1 and 0.1 with H = 0.1 E* (reduced hardness
/// H / (E* g_bar) = 0.1 and 1), loads up to 0.9 H.
pub fn plastic_rough() -> Result<()> {
    let n: usize = std::env::var("N").unwrap_or_else(|_| "1024".into()).parse()?;
    let hardness = 0.1;
    let domain = Domain {
        nx: n,
        ny: n,
        dx: 1.0 / n as f64,
        dy: 1.0 / n as f64,
        periodic: true,
    };
    let op = Periodic::new(domain, 1.0)?;
    let options = ContactOptions::default();
    let interface = Interface::with_hardness(hardness)?;
    let cells = (n * n) as f64;
    println!("{n}^2, H = {hardness} E*, tolerance {:e}", options.tolerance);
    println!(
        "| g_bar | H / (E* g_bar) | p / H | elastic area | Persson | plastic area | Persson | iterations (elastic solve) | s (elastic) |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for rms_gradient in [1.0, 0.1] {
        let grid = surfgen::Grid::square(n, 1.0)?;
        let spec = surfgen::SurfaceSpec {
            grid,
            psd: surfgen::Psd::self_affine(0.8, 1.0, 8.0 / n as f64),
            normalization: surfgen::Normalization::RmsGradient(rms_gradient),
            amplitudes: surfgen::Amplitudes::Exact,
            seed: 2026,
        };
        let g0 = solver::geometry::flat_on_rough(surfgen::generate(&spec)?.heights.view())?;
        let reduced_hardness = hardness / rms_gradient;
        for share in [0.02, 0.05, 0.1, 0.2, 0.4, 0.6, 0.8, 0.9] {
            let p = share * hardness;
            let control = Control::MeanPressure(p);
            let t = Instant::now();
            let (state, report) =
                cg::solve_with(&op, g0.view(), &interface, control, &options, None, &mut ())?;
            let capped_s = t.elapsed().as_secs_f64();
            let t = Instant::now();
            let (_, elastic) = cg::solve(&op, g0.view(), control, &options, None, &mut ())?;
            let elastic_s = t.elapsed().as_secs_f64();
            let plastic = report.yielding.plastic_area_fraction;
            let in_contact = state.pressure.iter().filter(|&&v| v > 0.0).count() as f64 / cells;
            let (theory_el, theory_pl) =
                theory::rough::persson_elastoplastic(p / rms_gradient, reduced_hardness);
            println!(
                "| {rms_gradient} | {reduced_hardness} | {share} | {:.5} | {theory_el:.5} | {plastic:.5} | {theory_pl:.5} | {}{} ({}) | {capped_s:.2} ({elastic_s:.2}) |",
                in_contact - plastic,
                report.iterations,
                if report.converged() { "" } else { " NOT CONVERGED" },
                elastic.iterations,
            );
        }
    }
    Ok(())
}
