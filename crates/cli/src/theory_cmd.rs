//! `theory`: reference curves as CSV, and their characteristic numbers.

use anyhow::{Result, bail};
use clap::{Args, Subcommand};
use serde_json::json;
use std::io::Write;
use std::path::PathBuf;
use theory::maugis::MaugisDugdale;

#[derive(Args, Debug)]
pub struct TheoryArgs {
    #[command(subcommand)]
    model: Model,
    /// Write the curve to this CSV file instead of standard output.
    #[arg(short, long, global = true)]
    output: Option<PathBuf>,
    /// Print the model's characteristic numbers instead of the curve.
    #[arg(long, global = true)]
    summary: bool,
    /// With --summary: as JSON (snake_case keys).
    #[arg(long, global = true)]
    json: bool,
    /// Points on the curve.
    #[arg(long, global = true, default_value_t = 200)]
    points: usize,
    /// Largest dimensionless contact radius A on the curve (the compressive end).
    #[arg(long, global = true, default_value_t = 3.0)]
    max_radius: f64,
    /// Also draw the curve (load against approach) as a PNG.
    #[arg(long, global = true, value_name = "FILE")]
    plot: Option<PathBuf>,
}

#[derive(Subcommand, Debug)]
enum Model {
    /// Maugis-Dugdale sphere: A = a/(pi w0 R^2/K)^(1/3), P = load/(pi w0 R),
    /// D = approach/(pi^2 w0^2 R/K^2)^(1/3), K = 4E*/3.
    Maugis {
        /// Maugis' parameter lambda (> 0); or give --tabor.
        #[arg(long)]
        lambda: Option<f64>,
        /// Tabor parameter mu of a Lennard-Jones law: lambda = 1.157 mu.
        #[arg(long)]
        tabor: Option<f64>,
    },
    /// JKR sphere in Maugis' units (the lambda -> infinity limit).
    Jkr,
    /// DMT sphere in Maugis' units (the lambda -> 0 limit).
    Dmt,
    /// Greenwood (1997): sphere with the full Lennard-Jones 9-3 law on an axisymmetric grid,
    /// traced by its central separation (S-curves whole). Load W/(2 pi R w0), approach
    /// alpha/z0 (zero when the undeformed apex is at z0), radii in sqrt(R z0).
    Greenwood {
        /// Tabor parameter mu = (R w0^2 / (E*^2 z0^3))^(1/3) (> 0).
        #[arg(long)]
        tabor: f64,
        /// Trace until the approach alpha/z0 exceeds this.
        #[arg(long, default_value_t = 3.0, allow_hyphen_values = true)]
        max_approach: f64,
        /// Central separation h(0)/z0 to start from (far apart).
        #[arg(long, default_value_t = 5.0)]
        from: f64,
        /// Largest change of approach (or load) between points [-].
        #[arg(long, default_value_t = 0.02)]
        resolution: f64,
        /// Ring width in units of sqrt(R z0) (default 0.02: pull-off converged to 1e-4).
        #[arg(long, default_value_t = 0.02)]
        ring_width: f64,
    },
}

fn greenwood(
    a: &TheoryArgs,
    mu: f64,
    max_approach: f64,
    from: f64,
    resolution: f64,
    ring_width: f64,
) -> Result<()> {
    use theory::greenwood::{Greenwood, Mesh};
    if !(mu.is_finite() && mu > 0.0) {
        bail!("--tabor must be finite and > 0, got {mu}");
    }
    if !(from > 1.0 && resolution > 0.0 && ring_width > 0.0 && ring_width < 1.0 && max_approach.is_finite()) {
        bail!("need --from > 1, --resolution > 0, 0 < --ring-width < 1 and a finite --max-approach");
    }
    let mesh = Mesh {
        spacing: ring_width,
        ..Mesh::default()
    };
    let c = Greenwood::new(mu, mesh).curve(from, max_approach, resolution)?;
    let mut out = open(a)?;
    let jump = |k: Option<usize>| k.map(|k| c.points[k].approach);
    if a.summary {
        if a.json {
            let v = json!({
                "model": "greenwood", "tabor_parameter": mu,
                "units": "pull-off forces in 2 pi R w0, approaches in z0 (zero: undeformed apex at z0)",
                "pull_off_load_control": c.pull_off_load_control,
                "pull_off_displacement_control": c.pull_off_displacement_control,
                "jump_in_approach": jump(c.jump_in), "jump_out_approach": jump(c.jump_out),
                "points": c.points.len(),
            });
            writeln!(out, "{}", serde_json::to_string_pretty(&v)?)?;
        } else {
            writeln!(out, "Greenwood (Lennard-Jones sphere), mu = {mu}")?;
            writeln!(
                out,
                "pull-off under load control          {:.6} 2 pi R w0",
                c.pull_off_load_control
            )?;
            writeln!(
                out,
                "pull-off under displacement control  {:.6} 2 pi R w0",
                c.pull_off_displacement_control
            )?;
            if let (Some(i), Some(o)) = (jump(c.jump_in), jump(c.jump_out)) {
                writeln!(out, "jump in at approach                  {i:.4} z0")?;
                writeln!(out, "jump out at approach                 {o:.4} z0")?;
            }
        }
        return Ok(());
    }
    writeln!(out, "central_separation,approach,load,contact_radius")?;
    for p in &c.points {
        writeln!(
            out,
            "{:e},{:e},{:e},{:e}",
            p.central_separation, p.approach, p.load, p.contact_radius
        )?;
    }
    if let Some(path) = &a.plot {
        let pts = c.points.iter().map(|p| (p.approach, p.load)).collect();
        draw(
            path,
            &format!("Lennard-Jones sphere (Greenwood), mu = {mu}"),
            "approach alpha/z0",
            "load W/(2 pi R w0)",
            pts,
        )?;
    }
    Ok(())
}

fn open(a: &TheoryArgs) -> Result<Box<dyn Write>> {
    Ok(match &a.output {
        Some(p) => Box::new(std::fs::File::create(p)?),
        None => Box::new(std::io::stdout().lock()),
    })
}

fn draw(path: &std::path::Path, title: &str, x: &str, y: &str, points: Vec<(f64, f64)>) -> Result<()> {
    crate::plot::lines(
        path,
        title,
        x,
        y,
        &[crate::plot::Series {
            label: "theory",
            points,
            markers: false,
            color: plotters::style::RGBColor(31, 119, 180),
        }],
    )
}

pub fn theory(a: TheoryArgs) -> Result<()> {
    if a.points < 2 {
        bail!("--points must be at least 2");
    }
    if let Model::Greenwood {
        tabor,
        max_approach,
        from,
        resolution,
        ring_width,
    } = a.model
    {
        return greenwood(&a, tabor, max_approach, from, resolution, ring_width);
    }
    let (lambda, tabor) = match a.model {
        Model::Maugis {
            lambda: Some(l),
            tabor: None,
        } => (l, None),
        Model::Maugis {
            lambda: None,
            tabor: Some(mu),
        } => (theory::maugis_parameter_of_tabor(mu), Some(mu)),
        Model::Maugis { .. } => bail!("give exactly one of --lambda or --tabor"),
        Model::Jkr => (1e7, None),
        Model::Dmt => (1e-7, None),
        Model::Greenwood { .. } => unreachable!("handled above"),
    };
    if !(lambda.is_finite() && lambda > 0.0) {
        bail!("the Maugis parameter must be finite and > 0, got {lambda}");
    }
    let model = MaugisDugdale::new(lambda);
    let mut out = open(&a)?;
    if a.summary {
        let (lc, dc) = (
            model.pull_off_load_control(),
            model.pull_off_displacement_control(),
        );
        if a.json {
            let v = json!({
                "model": "maugis_dugdale", "lambda": lambda, "tabor_parameter": tabor,
                "units": "pull-off forces in pi R w0",
                "pull_off_load_control": lc, "pull_off_displacement_control": dc,
            });
            writeln!(out, "{}", serde_json::to_string_pretty(&v)?)?;
        } else {
            writeln!(out, "Maugis-Dugdale, lambda = {lambda:.6}")?;
            writeln!(out, "pull-off under load control          {lc:.6} pi R w0")?;
            writeln!(out, "pull-off under displacement control  {dc:.6} pi R w0")?;
        }
        return Ok(());
    }
    writeln!(out, "m,contact_radius_A,load_P,approach_D")?;
    if !(a.max_radius.is_finite() && a.max_radius > 0.0) {
        bail!("--max-radius must be finite and > 0");
    }
    let curve = model.curve_to_radius(a.points, a.max_radius);
    for p in &curve {
        writeln!(out, "{:e},{:e},{:e},{:e}", p.m, p.radius, p.load, p.approach)?;
    }
    if let Some(path) = &a.plot {
        let pts = curve.iter().map(|p| (p.approach, p.load)).collect();
        draw(
            path,
            &format!("Maugis-Dugdale, lambda = {lambda:.4}"),
            "approach D",
            "load P = W/(pi R w0)",
            pts,
        )?;
    }
    Ok(())
}
