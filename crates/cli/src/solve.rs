//! `solve`: one non-adhesive normal contact, from flags or a TOML case file.

use crate::plot;
use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use elastic::{Compliance, Domain, Free, Periodic};
use ndarray::Array2;
use serde::{Deserialize, Serialize};
use serde_json::json;
use solver::geometry::{SphereProfile, flat_on_rough, sphere};
use solver::{ContactOptions, Control};
use std::path::{Path, PathBuf};
use std::time::Instant;
use surfgen::io::{self, ReadOptions};

#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DomainKind {
    /// The pattern repeats (rough surfaces): spectral kernel.
    Periodic,
    /// An isolated contact (spheres): Love's coefficients with zero padding.
    Free,
}

/// A contact case: every flag is also a key of the TOML case file (`--config`), with the same
/// name in snake_case. Flags override the file.
#[derive(Args, Debug, Default, Clone, Serialize, Deserialize)]
#[serde(default, deny_unknown_fields)]
pub struct Case {
    /// Rough surface file (.npy + sidecar, .txt, .xyz, .gsf): heights [m], peaks towards the
    /// counterface. With --sphere-radius the roughness sits on the sphere.
    #[arg(long)]
    pub surface: Option<PathBuf>,
    /// Box side [m]: for a bare surface file, or the grid of a smooth sphere.
    #[arg(long)]
    pub length: Option<f64>,
    /// Box size along y [m] (default: square cells).
    #[arg(long)]
    pub length_y: Option<f64>,
    /// Metres per unit in the surface file.
    #[arg(long)]
    pub unit: Option<f64>,
    /// Radius R of a rigid sphere [m], centred on the grid.
    #[arg(long)]
    pub sphere_radius: Option<f64>,
    /// Use the exact spherical profile instead of the paraboloid r^2/(2R).
    #[arg(long, num_args = 0..=1, default_missing_value = "true")]
    pub exact_sphere: Option<bool>,
    /// Grid points per side of a smooth sphere's grid (default 256); must match a surface file.
    #[arg(long)]
    pub n: Option<usize>,
    /// Periodic or free boundaries (default: periodic for a rough flat, free with a sphere).
    #[arg(long, value_enum)]
    pub domain: Option<DomainKind>,
    /// Composite modulus E* [Pa].
    #[arg(long)]
    pub modulus: Option<f64>,
    /// Load control: mean pressure over the box [Pa].
    #[arg(long)]
    pub mean_pressure: Option<f64>,
    /// Load control: total normal force [N].
    #[arg(long)]
    pub load: Option<f64>,
    /// Displacement control: approach from first touch [m], positive pushes together.
    #[arg(long)]
    pub approach: Option<f64>,
    /// Convergence tolerance on the scale-free residual (default 1e-8; at least 1e-13).
    #[arg(long)]
    pub tolerance: Option<f64>,
    /// Iteration limit (default 10000).
    #[arg(long)]
    pub max_iterations: Option<usize>,
    /// Output directory (default: run).
    #[arg(long)]
    pub out: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct SolveArgs {
    #[command(flatten)]
    case: Case,
    /// TOML case file; its keys are the flags' names in snake_case.
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// Print the resolved case as TOML and exit without solving.
    #[arg(long)]
    print_config: bool,
    /// Exit with status 0 even when the solve does not converge (the outputs say so).
    #[arg(long)]
    keep_going: bool,
    /// Do not draw the pressure map.
    #[arg(long)]
    no_png: bool,
}

/// The case from the file, with every flag given on the command line laid over it.
fn resolve(args: &SolveArgs) -> Result<Case> {
    let mut merged = match &args.config {
        Some(path) => {
            let text =
                std::fs::read_to_string(path).with_context(|| format!("reading {}", path.display()))?;
            let case: Case = toml::from_str(&text).with_context(|| format!("parsing {}", path.display()))?;
            serde_json::to_value(case)?
        }
        None => json!({}),
    };
    if let (Some(base), serde_json::Value::Object(flags)) =
        (merged.as_object_mut(), serde_json::to_value(&args.case)?)
    {
        for (k, v) in flags {
            if !v.is_null() {
                base.insert(k, v);
            }
        }
    }
    Ok(serde_json::from_value(merged)?)
}

/// FNV-1a over the heights' bits: a stable fingerprint of the input surface.
fn fingerprint(h: &Array2<f64>) -> String {
    let mut hash: u64 = 0xcbf29ce484222325;
    for v in h.iter() {
        for b in v.to_le_bytes() {
            hash ^= b as u64;
            hash = hash.wrapping_mul(0x100000001b3);
        }
    }
    format!("fnv1a64:{hash:016x}")
}

pub fn solve(args: SolveArgs) -> Result<()> {
    let mut case = resolve(&args)?;
    // Defaults made explicit, so that the summary and --print-config show the whole case.
    case.domain = case.domain.or(Some(if case.sphere_radius.is_some() {
        DomainKind::Free
    } else {
        DomainKind::Periodic
    }));
    case.tolerance = case.tolerance.or(Some(1e-8));
    case.max_iterations = case.max_iterations.or(Some(10_000));
    case.out = case.out.or_else(|| Some(PathBuf::from("run")));
    if args.print_config {
        println!("{}", toml::to_string(&case)?.trim_end());
        return Ok(());
    }
    let e_star = case.modulus.context(
        "the composite modulus is required: --modulus E* [Pa] (or modulus = ... in the case file)",
    )?;
    let control = match (case.mean_pressure, case.load, case.approach) {
        (Some(p), None, None) => Control::MeanPressure(p),
        (None, Some(w), None) => Control::Force(w),
        (None, None, Some(d)) => Control::Approach(d),
        _ => bail!("give exactly one of --mean-pressure [Pa], --load [N] or --approach [m]"),
    };
    let surface = match &case.surface {
        Some(path) => {
            let options = ReadOptions {
                length_x: case.length,
                length_y: case.length_y,
                unit: case.unit.unwrap_or(1.0),
                periodic: true,
            };
            let s = io::read(path, &options).with_context(|| format!("reading {}", path.display()))?;
            if let Some(n) = case.n
                && (s.grid.nx != n || s.grid.ny != n)
            {
                bail!(
                    "--n {n} does not match the surface file's {} x {} grid",
                    s.grid.nx,
                    s.grid.ny
                );
            }
            Some(s)
        }
        None => None,
    };
    let kind = case.domain.expect("defaulted above");
    let domain = match &surface {
        Some(s) => Domain {
            nx: s.grid.nx,
            ny: s.grid.ny,
            dx: s.grid.dx(),
            dy: s.grid.dy(),
            periodic: kind == DomainKind::Periodic,
        },
        None => {
            if case.sphere_radius.is_none() {
                bail!("nothing to press: give --surface FILE and/or --sphere-radius R [m]");
            }
            let n = case.n.unwrap_or(256);
            let l = case
                .length
                .context("a smooth sphere needs its grid: --length L [m] (and --n)")?;
            let ly = case.length_y.unwrap_or(l);
            Domain {
                nx: n,
                ny: n,
                dx: l / n as f64,
                dy: ly / n as f64,
                periodic: kind == DomainKind::Periodic,
            }
        }
    };
    let g0 = match case.sphere_radius {
        Some(r) => {
            let profile = if case.exact_sphere.unwrap_or(false) {
                SphereProfile::Exact
            } else {
                SphereProfile::Paraboloid
            };
            sphere(&domain, r, profile, surface.as_ref().map(|s| s.heights.view()))?
        }
        None => flat_on_rough(surface.as_ref().expect("checked above").heights.view())?,
    };
    let options = ContactOptions {
        tolerance: case.tolerance.expect("defaulted above"),
        max_iterations: case.max_iterations.expect("defaulted above"),
    };
    let op: Box<dyn Compliance> = match kind {
        DomainKind::Periodic => Box::new(Periodic::new(domain, e_star)?),
        DomainKind::Free => Box::new(Free::new(domain, e_star)?),
    };
    let mut last = Instant::now();
    let mut progress = |it: usize, residual: f64| {
        if last.elapsed().as_secs_f64() > 1.0 {
            eprint!("\riteration {it:>6}  residual {residual:.3e}");
            last = Instant::now();
        }
    };
    let (state, report) =
        solver::solve_observed(op.as_ref(), g0.view(), control, &options, None, &mut progress)?;
    eprint!("\r{:60}\r", "");

    let out = case.out.clone().expect("defaulted above");
    std::fs::create_dir_all(&out).with_context(|| format!("creating {}", out.display()))?;
    for (name, field) in [
        ("pressure", &state.pressure),
        ("gap", &state.gap),
        ("displacement", &state.displacement),
    ] {
        io::write_npy(field, &out.join(format!("{name}.npy")))?;
    }
    let summary = json!({
        "version": env!("CARGO_PKG_VERSION"),
        "case": case,
        "units": {
            "load": "N", "mean_pressure": "Pa", "approach": "m", "max_pressure": "Pa",
            "elastic_energy": "J", "lengths": "m", "modulus": "Pa", "wall_time_s": "s",
            "pressure.npy": "Pa", "gap.npy": "m", "displacement.npy": "m"
        },
        "surface_hash": surface.as_ref().map(|s| fingerprint(&s.heights)),
        "grid": { "nx": domain.nx, "ny": domain.ny, "dx": domain.dx, "dy": domain.dy, "periodic": domain.periodic },
        "load": report.load,
        "mean_pressure": report.mean_pressure,
        "approach": report.approach,
        "contact_area_fraction": report.contact_area_fraction,
        "contact_clusters": report.clusters,
        "max_pressure": report.max_pressure,
        "elastic_energy": report.elastic_energy,
        "iterations": report.iterations,
        "operator_calls": report.operator_calls,
        "converged": report.converged(),
        "termination": format!("{:?}", report.termination),
        "residual": report.residual,
        "residual_history": report.residual_history,
        "wall_time_s": report.wall_time_s,
    });
    std::fs::write(
        out.join("summary.json"),
        serde_json::to_string_pretty(&summary)? + "\n",
    )?;
    if !args.no_png {
        let pmax = report.max_pressure.max(f64::MIN_POSITIVE);
        let unit = if pmax >= 1e9 {
            (1e-9, "GPa")
        } else if pmax >= 1e6 {
            (1e-6, "MPa")
        } else {
            (1e-3, "kPa")
        };
        plot::field_map(
            &out.join("pressure.png"),
            state.pressure.view(),
            (domain.nx as f64 * domain.dx, domain.ny as f64 * domain.dy),
            &format!(
                "contact pressure, area fraction {:.4}",
                report.contact_area_fraction
            ),
            "pressure",
            unit,
        )?;
    }
    print_summary(&out, &report);
    if !report.converged() {
        let msg = format!(
            "the solve did not converge: residual {:.3e} after {} iterations (tolerance {:.1e})",
            report.residual, report.iterations, options.tolerance
        );
        if args.keep_going {
            eprintln!("warning: {msg}; results written anyway");
        } else {
            bail!(
                "{msg}; results are in {} (use --keep-going to accept them)",
                out.display()
            );
        }
    }
    Ok(())
}

fn print_summary(out: &Path, r: &solver::ContactReport) {
    println!("load                   {:.6e} N", r.load);
    println!("mean pressure          {:.6e} Pa", r.mean_pressure);
    println!("approach               {:.6e} m", r.approach);
    println!("contact area fraction  {:.6}", r.contact_area_fraction);
    println!("contact clusters       {}", r.clusters);
    println!("max pressure           {:.6e} Pa", r.max_pressure);
    println!(
        "iterations             {} ({} operator calls), residual {:.2e}, {:?}",
        r.iterations, r.operator_calls, r.residual, r.termination
    );
    println!("wall time              {:.3} s", r.wall_time_s);
    println!(
        "wrote {}/summary.json, pressure.npy, gap.npy, displacement.npy",
        out.display()
    );
}
