//! `cargo xtask study plastic-rough`: elastic and plastic contact areas of a self-affine surface
//! under a hardness, against load, beside Persson's elastoplastic theory, with the iterations
//! each solve took beside the elastic solve at the same load.

use anyhow::{Context, Result};
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

/// `cargo xtask study plastic-pull-off`: a Lennard-Jones sphere (point law, mu = 5, R = 1000
/// z0) on a free grid of `N` (default 256) cells `HALF` (default 256) z0 either side, loaded to
/// each depth of `DEPTHS` (z0, default 5,10,20) past yield at each hardness of `HARDNESS` (E*,
/// default 0.025,0.05,0.1) and unloaded; its pull-off beside the elastic sphere's on the same
/// grid and beside Mesarovic & Johnson's flattened sphere in the JKR limit
/// ([`theory::flattened`]), taken flattened to the radius of the plastic zone and to the
/// contact radius at the deepest point.
pub fn plastic_pull_off() -> Result<()> {
    use crate::sphere::{MODULUS, RADIUS, Z0};
    use ljadhesion::{LennardJones, PointLaw};
    use solver::{ContactProblem, CyclePoint, Method, Settings, summarize};
    use std::f64::consts::PI;
    let n: usize = std::env::var("N").unwrap_or_else(|_| "256".into()).parse()?;
    let half: f64 = std::env::var("HALF").unwrap_or_else(|_| "256".into()).parse()?;
    let list = |name: &str, default: &str| -> Result<Vec<f64>> {
        let text = std::env::var(name).unwrap_or_else(|_| default.into());
        Ok(text
            .split(',')
            .map(|s| s.trim().parse())
            .collect::<Result<_, _>>()?)
    };
    let hardnesses = list("HARDNESS", "0.025,0.05,0.1")?;
    let depths = list("DEPTHS", "5,10,20")?;
    let mu: f64 = 5.0;
    let w0 = crate::study::work_of_adhesion(mu);
    let law = PointLaw(LennardJones::new(w0, Z0)?);
    let side = 2.0 * half * Z0;
    let cell_area = (side / n as f64).powi(2);
    let jkr = 1.5 * PI * RADIUS * w0;
    let settings = Settings::with_method(Method::EnergyDescent);
    // Loaded in steps of z0 from 3 z0 apart and unloaded to 30 z0 apart, in steps of z0.
    let cycle = |depth: f64| -> Vec<Control> {
        let down = (0..).map(|k| -3.0 + k as f64).take_while(|&a| a < depth);
        let up = (0..).map(|k| depth - k as f64).take_while(|&a| a >= -30.0);
        down.chain(up).map(|a| Control::Approach(a * Z0)).collect()
    };
    // Pull-off [N] (positive), plastic and contact radius at the deepest point [m], mean
    // iterations a step, all converged, seconds.
    let run = |hardness: Option<f64>, depth: f64| -> Result<(f64, f64, f64, usize, bool, f64)> {
        let mut builder = ContactProblem::builder()
            .grid(n, n, side, side)
            .sphere(RADIUS)
            .modulus(MODULUS)
            .law(law);
        if let Some(h) = hardness {
            builder = builder.hardness(h * MODULUS);
        }
        let started = Instant::now();
        let points = builder
            .build()?
            .sweep(&cycle(depth), Some(0.5 * Z0), &settings, None, &mut ())?;
        let deepest = points
            .iter()
            .max_by(|a, b| a.report.approach.total_cmp(&b.report.approach))
            .context("an empty sweep")?;
        let radius = |fraction: f64| (fraction * (n * n) as f64 * cell_area / PI).sqrt();
        let plastic = radius(deepest.report.yielding.plastic_area_fraction);
        let contact = radius(deepest.report.contact_area_fraction);
        let iterations = points.iter().map(|p| p.report.iterations.count()).sum::<usize>() / points.len();
        let s = summarize(&points.iter().map(CyclePoint::from).collect::<Vec<_>>());
        let pull_off = -s.pull_off_force.unwrap_or(f64::NAN);
        Ok((
            pull_off,
            plastic,
            contact,
            iterations,
            s.all_converged,
            started.elapsed().as_secs_f64(),
        ))
    };
    println!(
        "mu = {mu}, R = {:.0} z0, {n}^2 cells of {:.2} z0, point law; JKR's pull-off 1.5 pi R w0 = {jkr:.4e} N",
        RADIUS / Z0,
        side / n as f64 / Z0
    );
    println!(
        "| H / E* | depth / z0 | plastic radius / z0 | contact radius / z0 | pull-off / JKR | M-J at plastic radius | M-J at contact radius | iterations a step | s |"
    );
    println!("|---|---|---|---|---|---|---|---|---|");
    for &depth in &depths {
        let (elastic, _, contact, iterations, converged, s) = run(None, depth)?;
        println!(
            "| elastic | {depth} | 0 | {:.1} | {:.4} | 1 | 1 | {iterations}{} | {s:.0} |",
            contact / Z0,
            elastic / jkr,
            if converged { "" } else { " not all converged" }
        );
        for &h in &hardnesses {
            let (pull_off, plastic, contact, iterations, converged, s) = run(Some(h), depth)?;
            let theory = |a_max: f64| {
                let flattened = theory::flattened::Flattened {
                    r: RADIUS,
                    e_star: MODULUS,
                    hardness: h * MODULUS,
                    a_max,
                };
                -flattened.pull_off(w0) / jkr
            };
            println!(
                "| {h} | {depth} | {:.1} | {:.1} | {:.4} | {:.4} | {:.4} | {iterations}{} | {s:.0} |",
                plastic / Z0,
                contact / Z0,
                pull_off / jkr,
                theory(plastic),
                theory(contact),
                if converged { "" } else { " not all converged" }
            );
        }
    }
    Ok(())
}
