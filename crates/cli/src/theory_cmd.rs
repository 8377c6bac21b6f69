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
}

pub fn theory(a: TheoryArgs) -> Result<()> {
    if a.points < 2 {
        bail!("--points must be at least 2");
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
    };
    if !(lambda.is_finite() && lambda > 0.0) {
        bail!("the Maugis parameter must be finite and > 0, got {lambda}");
    }
    let model = MaugisDugdale::new(lambda);
    let mut out: Box<dyn Write> = match &a.output {
        Some(p) => Box::new(std::fs::File::create(p)?),
        None => Box::new(std::io::stdout().lock()),
    };
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
    for p in model.curve_to_radius(a.points, a.max_radius) {
        writeln!(out, "{:e},{:e},{:e},{:e}", p.m, p.radius, p.load, p.approach)?;
    }
    Ok(())
}
