//! `cargo xtask study rate-pull-off` and `rate-retraction`: the pull-off of a Lennard-Jones
//! sphere on a standard linear solid against the rate it is pressed in and drawn back at,
//! between the relaxed and the glassy elastic spheres, and beside the effective-adhesion
//! theories.

use crate::sphere::{MODULUS, RADIUS, Z0};
use crate::study::work_of_adhesion;
use anyhow::{Context, Result};
use ljadhesion::{AdhesionLaw, LennardJones, SurfaceLaw};
use solver::{ContactProblem, Control, CyclePoint, Method, Path, Settings, summarize};
use std::f64::consts::PI;
use std::time::Instant;

/// E_0 / E_inf of the solid, its branch's relaxation time [s].
const GLASSY: f64 = 10.0;
const TAU: f64 = 1.0;

/// Pull-off over `pi R w0` against the speed (in z0 per relaxation time, from 1e-3 to 1e3) for
/// mu = 1 and 5 at the relaxed modulus (`MU`), the sphere pressed 1 z0 in from `FROM` z0 apart
/// (default 20) and drawn back to 20 z0 apart, in steps of `STEP` z0 (default 1/2) at one speed throughout, and the cycle's loss split
/// into the dashpots' and the adhesive jumps' (`solver::CycleSummary::adhesive_work`); the
/// grid 128^2 across 200 z0 at mu = 1 (the pull-off-mesh study's) and 256^2 across 512 z0 at
/// mu = 5 (the plastic-pull-off study's), wider than the relaxed contact.
pub fn rate_pull_off() -> Result<()> {
    let tabor: Vec<f64> = std::env::var("MU")
        .unwrap_or_else(|_| "1,5".into())
        .split(',')
        .map(|s| s.trim().parse())
        .collect::<Result<_, _>>()?;
    let h: f64 = std::env::var("STEP").unwrap_or_else(|_| "0.5".into()).parse()?;
    let from: f64 = std::env::var("FROM").unwrap_or_else(|_| "20".into()).parse()?;
    let settings = Settings::with_method(Method::Auto);
    println!("steps of {h} z0, from {from} z0 apart");
    println!(
        "| mu (E_inf) | speed (z0 / tau) | pull-off / (pi R w0) | viscous work / (pi R w0 z0) | adhesive work / (pi R w0 z0) | seconds |"
    );
    println!("|---|---|---|---|---|---|");
    for mu in tabor {
        let (n, side) = if mu > 2.0 {
            (256, 512.0 * Z0)
        } else {
            (128, 200.0 * Z0)
        };
        let w0 = work_of_adhesion(mu);
        let law = SurfaceLaw(LennardJones::new(w0, Z0)?);
        let (path, _) = press_and_draw_back(from, 20.0, h);
        let build = |modulus: f64, solid: bool| -> Result<ContactProblem> {
            let mut b = ContactProblem::builder()
                .grid(n, n, side, side)
                .sphere(RADIUS)
                .modulus(modulus)
                .law(law);
            if solid {
                b = b.maxwell(&[(GLASSY - 1.0) * MODULUS], &[TAU]);
            }
            Ok(b.build()?)
        };
        let pull_off =
            |problem: &ContactProblem, times: Option<&[f64]>| -> Result<(f64, bool, f64, f64, f64)> {
                let started = Instant::now();
                let path = Path {
                    controls: &path,
                    times,
                };
                let points = problem.sweep(path, Some(h * Z0), &settings, None, &mut ())?;
                let least = points.iter().map(|p| p.report.load).fold(0.0, f64::min);
                let converged = points.iter().all(|p| p.report.converged());
                let cycle: Vec<CyclePoint> = points.iter().map(CyclePoint::from).collect();
                let summary = summarize(&cycle);
                let energy = PI * RADIUS * w0 * Z0;
                Ok((
                    -least / (PI * RADIUS * w0),
                    converged,
                    summary.viscous_work / energy,
                    summary.adhesive_work.unwrap_or(f64::NAN) / energy,
                    started.elapsed().as_secs_f64(),
                ))
            };
        let row = |speed: String, (p, converged, viscous, adhesive, s): (f64, bool, f64, f64, f64)| {
            let flag = if converged { "" } else { " (not converged)" };
            println!("| {mu} | {speed} | {p:.4}{flag} | {viscous:.4} | {adhesive:.4} | {s:.0} |");
        };
        row("relaxed elastic".into(), pull_off(&build(MODULUS, false)?, None)?);
        let problem = build(MODULUS, true)?;
        for k in -3..=3 {
            let speed = 10f64.powi(k);
            let step = h * TAU / speed;
            let times: Vec<f64> = (0..path.len()).map(|i| i as f64 * step).collect();
            row(format!("{speed:e}"), pull_off(&problem, Some(&times))?);
        }
        row(
            "glassy elastic".into(),
            pull_off(&build(GLASSY * MODULUS, false)?, None)?,
        );
    }
    Ok(())
}

/// `cargo xtask study rate-retraction`: a Lennard-Jones sphere (`MU`, default 1; smooth, and
/// rough with `RQ` z0, default 1) pressed 1 z0 in slowly enough to stay relaxed, then drawn back
/// at one speed, 1e-3 to 1e2 z0 per relaxation time, in steps of `STEP` z0 (default 1/2);
/// beside it the sphere
/// whose receding edge follows Greenwood & Johnson's and Persson & Brener's effective adhesion
/// (`theory::rate_adhesion`) on the relaxed JKR contact. Writes the figure to `FIGURE`
/// (default `docs/figures/rate-retraction`, `.png` and `.svg`).
pub fn rate_retraction() -> Result<()> {
    use theory::rate_adhesion::{EdgeLaw, Model, retraction};
    let mu: f64 = std::env::var("MU").unwrap_or_else(|_| "1".into()).parse()?;
    let rq: f64 = std::env::var("RQ").unwrap_or_else(|_| "1".into()).parse()?;
    let h: f64 = std::env::var("STEP").unwrap_or_else(|_| "0.5".into()).parse()?;
    let figure = std::env::var("FIGURE").unwrap_or_else(|_| "docs/figures/rate-retraction".into());
    let settings = Settings::with_method(Method::Auto);
    let (n, side) = if mu > 2.0 {
        (256, 512.0 * Z0)
    } else {
        (128, 200.0 * Z0)
    };
    let w0 = work_of_adhesion(mu);
    let unit = PI * RADIUS * w0;
    let law = SurfaceLaw(LennardJones::new(w0, Z0)?);
    let (path, pressed) = if mu > 2.0 {
        press_and_draw_back(10.0, 40.0, h)
    } else {
        press_and_draw_back(3.0, 20.0, h)
    };
    let roughness = {
        let grid = surfgen::Grid::square(n, side)?;
        let spec = surfgen::SurfaceSpec {
            grid,
            psd: surfgen::Psd::self_affine(0.8, side / 2.0, 4.0 * side / n as f64),
            normalization: surfgen::Normalization::RmsHeight(rq * Z0),
            amplitudes: surfgen::Amplitudes::Exact,
            seed: 2027,
        };
        surfgen::generate(&spec)?.heights
    };
    let build = |rough: bool, solid: bool| -> Result<ContactProblem> {
        let mut b = ContactProblem::builder().sphere(RADIUS).modulus(MODULUS).law(law);
        b = if rough {
            b.roughness(roughness.clone(), side, side)
        } else {
            b.grid(n, n, side, side)
        };
        if solid {
            b = b.maxwell(&[(GLASSY - 1.0) * MODULUS], &[TAU]);
        }
        Ok(b.build()?)
    };
    // The least load drawn back, over pi R w0; whether every step converged.
    let pull_off = |problem: &ContactProblem, times: Option<&[f64]>| -> Result<(f64, bool)> {
        let path = Path {
            controls: &path,
            times,
        };
        let points = problem.sweep(path, Some(h * Z0), &settings, None, &mut ())?;
        let least = points[pressed..]
            .iter()
            .map(|p| p.report.load)
            .fold(0.0, f64::min);
        Ok((-least / unit, points.iter().all(|p| p.report.converged())))
    };
    let smooth_problem = build(false, true)?;
    let rough_problem = build(true, true)?;
    let solid = smooth_problem.solid.as_ref().context("the viscoelastic sphere")?;
    let models = [Model::GreenwoodJohnson, Model::PerssonBrener];
    let laws: Vec<EdgeLaw> = models
        .iter()
        .map(|&m| EdgeLaw::new(m, solid, w0, -law.peak_pressure()))
        .collect();
    let theory = |law: &EdgeLaw, speed: f64| -> f64 {
        retraction(law, MODULUS, RADIUS, w0, DEPTH * Z0, speed * Z0 / TAU, 4000)
            .map_or(f64::NAN, |r| -r.pull_off / unit)
    };
    let slow: Vec<f64> = laws.iter().map(|l| theory(l, 1e-9)).collect();
    println!(
        "mu = {mu} at E_inf, E0 = {GLASSY} E_inf, tau = {TAU} s; rough: Rq = {rq} z0; {n}^2 across {} z0; steps of {h} z0",
        side / Z0
    );
    println!(
        "| speed (z0 / tau) | smooth / (pi R w0) | gain | rough / (pi R w0) | gain | {} (gain) | {} (gain) | seconds |",
        models[0].name(),
        models[1].name()
    );
    println!("|---|---|---|---|---|---|---|---|");
    let flag = |c: bool| if c { "" } else { " (not converged)" };
    let (smooth0, c0) = pull_off(&build(false, false)?, None)?;
    let (rough0, r0) = pull_off(&build(true, false)?, None)?;
    println!(
        "| relaxed elastic | {smooth0:.4}{} | 1 | {rough0:.4}{} | 1 | {:.4} | {:.4} | |",
        flag(c0),
        flag(r0),
        slow[0],
        slow[1]
    );
    let mut curves: [Vec<(f64, f64, bool)>; 2] = [Vec::new(), Vec::new()];
    for k in -3..=2 {
        let speed = 10f64.powi(k);
        let started = Instant::now();
        // Loading steps a million relaxation times apart, then STEP z0 at the speed.
        let mut times = Vec::with_capacity(path.len());
        for i in 0..path.len() {
            let t = if i < pressed {
                i as f64 * 1e6 * TAU
            } else {
                (pressed - 1) as f64 * 1e6 * TAU + (i + 1 - pressed) as f64 * h * TAU / speed
            };
            times.push(t);
        }
        let (s, cs) = pull_off(&smooth_problem, Some(&times))?;
        let (r, cr) = pull_off(&rough_problem, Some(&times))?;
        curves[0].push((speed, s, cs));
        curves[1].push((speed, r, cr));
        let gains: Vec<String> = laws
            .iter()
            .zip(&slow)
            .map(|(l, s0)| {
                let p = theory(l, speed);
                format!("{p:.4} ({:.3})", p / s0)
            })
            .collect();
        println!(
            "| {speed:e} | {s:.4}{} | {:.3} | {r:.4}{} | {:.3} | {} | {} | {:.0} |",
            flag(cs),
            s / smooth0,
            flag(cr),
            r / rough0,
            gains[0],
            gains[1],
            started.elapsed().as_secs_f64()
        );
    }
    // The figure: gains over the relaxed elastic pull-off against speed.
    use plot::{Chart, Curve, Mark, PALETTE};
    let mut chart = Chart::new(
        format!("Drawn back from a relaxed contact, mu = {mu}, E0 = {GLASSY} E_inf"),
        "retraction speed [z0 / tau]",
        "pull-off / relaxed elastic pull-off",
    );
    chart.x_log = true;
    let fine: Vec<f64> = (0..=50)
        .map(|i| 10f64.powf(-3.0 + 5.0 * i as f64 / 50.0))
        .collect();
    for ((law, s0), (model, mark)) in laws
        .iter()
        .zip(&slow)
        .zip(models.iter().zip([Mark::Line, Mark::Dashed]))
    {
        let points = fine.iter().map(|&v| (v, theory(law, v) / s0)).collect();
        chart.curves.push(Curve::new(
            format!("{} (smooth)", model.name()),
            points,
            mark,
            PALETTE[0],
        ));
    }
    let gains = |c: &[(f64, f64, bool)], p0: f64| c.iter().map(|&(v, p, ok)| (v, p / p0, ok)).collect();
    chart.curves.push(Curve::solved(
        "smooth sphere",
        gains(&curves[0], smooth0),
        Mark::Dots,
        PALETTE[1],
    ));
    chart.curves.push(Curve::solved(
        format!("rough sphere (Rq = {rq} z0)"),
        gains(&curves[1], rough0),
        Mark::Triangles,
        PALETTE[2],
    ));
    crate::study::save_figure(&chart, &figure)
}

/// How far the sphere is pressed in \[z0\].
const DEPTH: f64 = 1.0;

/// Approaches from `from` z0 apart in to [`DEPTH`] and back out to `back` z0 apart, in steps
/// of `h` z0; with the number of steps pressing in.
fn press_and_draw_back(from: f64, back: f64, h: f64) -> (Vec<Control>, usize) {
    let mut path = Vec::new();
    let mut a = -from;
    while a < DEPTH {
        path.push(Control::Approach(a * Z0));
        a += h;
    }
    let pressed = path.len();
    while a >= -back {
        path.push(Control::Approach(a * Z0));
        a -= h;
    }
    (path, pressed)
}
