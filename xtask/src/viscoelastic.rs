//! `cargo xtask study rate-pull-off`: the pull-off of a Lennard-Jones sphere on a standard
//! linear solid against the rate it is pressed in and drawn back at, between the relaxed and
//! the glassy elastic spheres.

use crate::sphere::{MODULUS, RADIUS, Z0};
use anyhow::Result;
use ljadhesion::{LennardJones, SurfaceLaw};
use solver::{ContactProblem, Control, Method, Path, Settings};
use std::f64::consts::PI;
use std::time::Instant;

/// E_0 / E_inf of the solid, its branch's relaxation time [s].
const GLASSY: f64 = 10.0;
const TAU: f64 = 1.0;

/// Pull-off over `pi R w0` against the speed (in z0 per relaxation time, from 1e-3 to 1e3) for
/// mu = 1 and 5 at the relaxed modulus (`MU`), the sphere pressed 1 z0 in from 3 z0 apart
/// (10 z0 at mu = 5) and drawn back to 20 z0, in steps of z0 / 2 at one speed throughout; the
/// grid 128^2 across 200 z0 at mu = 1 (the pull-off-mesh study's) and 256^2 across 512 z0 at
/// mu = 5 (the plastic-pull-off study's), wider than the relaxed contact.
pub fn rate_pull_off() -> Result<()> {
    let tabor: Vec<f64> = std::env::var("MU")
        .unwrap_or_else(|_| "1,5".into())
        .split(',')
        .map(|s| s.trim().parse())
        .collect::<Result<_, _>>()?;
    let settings = Settings::with_method(Method::Auto);
    println!("| mu (E_inf) | speed (z0 / tau) | pull-off / (pi R w0) | seconds |");
    println!("|---|---|---|---|");
    for mu in tabor {
        let (n, side) = if mu > 2.0 {
            (256, 512.0 * Z0)
        } else {
            (128, 200.0 * Z0)
        };
        let w0 = (mu.powi(3) / (RADIUS / Z0)).sqrt() * MODULUS * Z0;
        let law = SurfaceLaw(LennardJones::new(w0, Z0)?);
        let depth = 1.0;
        let apart = if mu > 2.0 { 10.0 } else { 3.0 };
        let mut path: Vec<Control> = Vec::new();
        let mut a = -apart;
        while a < depth {
            path.push(Control::Approach(a * Z0));
            a += 0.5;
        }
        while a >= -20.0 {
            path.push(Control::Approach(a * Z0));
            a -= 0.5;
        }
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
        let pull_off = |problem: &ContactProblem, times: Option<&[f64]>| -> Result<(f64, bool, f64)> {
            let started = Instant::now();
            let path = Path {
                controls: &path,
                times,
            };
            let points = problem.sweep(path, Some(0.5 * Z0), &settings, None, &mut ())?;
            let least = points.iter().map(|p| p.report.load).fold(0.0, f64::min);
            let converged = points.iter().all(|p| p.report.converged());
            Ok((
                -least / (PI * RADIUS * w0),
                converged,
                started.elapsed().as_secs_f64(),
            ))
        };
        let row = |speed: String, (p, converged, s): (f64, bool, f64)| {
            let flag = if converged { "" } else { " (not converged)" };
            println!("| {mu} | {speed} | {p:.4}{flag} | {s:.0} |");
        };
        row("relaxed elastic".into(), pull_off(&build(MODULUS, false)?, None)?);
        let problem = build(MODULUS, true)?;
        for k in -3..=3 {
            let speed = 10f64.powi(k);
            let step = 0.5 * TAU / speed;
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
