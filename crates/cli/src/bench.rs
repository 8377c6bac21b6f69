//! `bench`: the same self-affine contact problem at increasing sizes.

use anyhow::{Result, bail};
use clap::Args;
use elastic::{Domain, Periodic};
use serde_json::json;
use solver::geometry::flat_on_rough;
use solver::{ContactOptions, Control, Interface};
use std::path::PathBuf;
use std::time::Instant;
use surfgen::{Amplitudes, Grid, Normalization, Psd, SurfaceSpec};

#[derive(Args, Debug)]
pub struct BenchArgs {
    /// Grid sizes (points per side), solved in this order.
    #[arg(long, value_delimiter = ',', default_value = "256,512,1024,2048,4096")]
    sizes: Vec<usize>,
    /// Mean pressure in units of E* [-].
    #[arg(long, default_value_t = 0.04)]
    pressure: f64,
    /// Hardness in units of E* [-]: the pressure cap of an elastic-perfectly-plastic surface
    /// (absent: elastic). The check then also counts the cells at H that differ.
    #[arg(long, value_name = "H")]
    hardness: Option<f64>,
    /// Convergence tolerance of the timed solve.
    #[arg(long, default_value_t = 1e-8)]
    tolerance: f64,
    /// Iteration limit of the timed solve (a limited run still measures memory and the time
    /// per iteration).
    #[arg(long, default_value_t = 10_000)]
    max_iterations: usize,
    /// Also solve to 1e-12 and report how far the timed solve is from it (contact cells that
    /// differ, relative difference of the mean gap).
    #[arg(long)]
    check: bool,
    /// Which conjugate gradients to time: plain (Polonsky-Keer), preconditioned (by the
    /// inverse operator on the contact set) or both, one after the other at each size.
    #[arg(long, value_enum, default_value_t = BenchSolver::Both)]
    solver: BenchSolver,
    /// Write the table as JSON to this file too.
    #[arg(long, value_name = "FILE")]
    json: Option<PathBuf>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq, clap::ValueEnum)]
enum BenchSolver {
    Plain,
    Preconditioned,
    Both,
}

/// Peak resident memory of this process so far [bytes] (Linux), `None` elsewhere.
fn peak_rss() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: u64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb * 1024)
}

pub fn bench(a: BenchArgs) -> Result<()> {
    if a.sizes.iter().any(|&n| n < 8) {
        bail!("--sizes are points per side, each at least 8 (the surface's cut-off is 8 cells)");
    }
    if !(a.pressure.is_finite() && a.pressure > 0.0) {
        bail!(
            "--pressure must be a finite mean pressure > 0 in units of E*, got {}",
            a.pressure
        );
    }
    let interface = match a.hardness {
        None => Interface::default(),
        Some(h) if h.is_finite() && h > a.pressure => Interface::with_hardness(h)?,
        Some(h) => bail!(
            "--hardness must be a finite H in units of E* above the mean pressure {} (a plastic \
             surface carries at most H over the whole area), got {h}",
            a.pressure
        ),
    };
    // Every size is checked before the first is solved: one the machine cannot hold is refused
    // with its estimate, not found out after the others have run.
    for &n in &a.sizes {
        case::memory::check(
            &format!("a {n} x {n} bench"),
            solver::memory_estimate(n, n, true, None) + surfgen::generate::memory_estimate(n, n),
        )?;
    }
    crate::outln!(
        "Self-affine surface, Hurst 0.8, RMS gradient 1, short cut-off 8 cells, no roll-off; E* = 1, p = {} E*{}, tolerance {:e}, {} threads",
        a.pressure,
        a.hardness.map_or(String::new(), |h| format!(", hardness {h} E*")),
        a.tolerance,
        rayon::current_num_threads()
    );
    let solvers: &[bool] = match a.solver {
        BenchSolver::Plain => &[false],
        BenchSolver::Preconditioned => &[true],
        BenchSolver::Both => &[false, true],
    };
    crate::outln!(
        "{:>6} {:>15} {:>7} {:>10} {:>10} {:>12} {:>10}{}",
        "n",
        "solver",
        "iters",
        "op calls",
        "time [s]",
        "peak [MB]",
        "area",
        match (a.check, a.hardness.is_some()) {
            (false, _) => "",
            (true, false) => "  contact diff  mean-gap rel. diff",
            (true, true) => "  contact diff  mean-gap rel. diff  at-H diff",
        }
    );
    let mut rows = Vec::new();
    for &n in &a.sizes {
        let grid = Grid::square(n, 1.0)?;
        let spec = SurfaceSpec {
            grid,
            psd: Psd::self_affine(0.8, 1.0, 8.0 / n as f64),
            normalization: Normalization::RmsGradient(1.0),
            amplitudes: Amplitudes::Exact,
            seed: 2026,
        };
        let h = surfgen::generate(&spec)?.heights;
        let g0 = flat_on_rough(h.view())?;
        drop(h);
        let dom = Domain {
            nx: n,
            ny: n,
            dx: 1.0 / n as f64,
            dy: 1.0 / n as f64,
            periodic: true,
        };
        let op = Periodic::new(dom, 1.0)?;
        for &preconditioned in solvers {
            rows.push(time_one(&a, n, &op, g0.view(), &interface, preconditioned)?);
        }
    }
    if let Some(path) = a.json {
        std::fs::write(&path, serde_json::to_string_pretty(&rows)? + "\n")?;
    }
    Ok(())
}

/// Solves the bench's problem on `op` with one solver and prints its row.
fn time_one(
    a: &BenchArgs,
    n: usize,
    op: &Periodic,
    g0: ndarray::ArrayView2<f64>,
    interface: &Interface,
    preconditioned: bool,
) -> Result<serde_json::Value> {
    let opts = ContactOptions {
        tolerance: a.tolerance,
        max_iterations: a.max_iterations,
        preconditioned,
    };
    let solver = if preconditioned { "preconditioned" } else { "plain" };
    let t = Instant::now();
    let control = Control::MeanPressure(a.pressure);
    let (state, rep) = solver::cg::solve_with(op, g0, interface, control, &opts, None, &mut ())?;
    let time = t.elapsed().as_secs_f64();
    let peak = peak_rss().map(|b| b as f64 / 1e6);
    let mut row = json!({
        "n": n, "solver": solver, "iterations": rep.iterations, "operator_calls": rep.operator_calls, "wall_time_s": time,
        "peak_rss_mb": peak, "contact_area_fraction": rep.contact_area_fraction, "converged": rep.converged(),
        "hardness": a.hardness, "plastic_area_fraction": rep.yielding.plastic_area_fraction,
    });
    let mut extra = String::new();
    if a.check {
        let tight = ContactOptions {
            tolerance: 1e-12,
            ..Default::default()
        };
        // From the timed solve's pressure, without the set it settled (the reference yields
        // from the same undeformed surface).
        let warm = solver::ContactState {
            permanent_set: None,
            ..state.clone()
        };
        let (reference, _) =
            solver::cg::solve_with(op, g0, interface, control, &tight, Some(&warm), &mut ())?;
        let differ = state
            .pressure
            .iter()
            .zip(reference.pressure.iter())
            .filter(|(x, y)| (**x > 0.0) != (**y > 0.0))
            .count();
        let mean_gap = |s: &solver::ContactState| s.gap.mean().unwrap_or(0.0);
        let gap_diff = (mean_gap(&state) / mean_gap(&reference) - 1.0).abs();
        extra = format!("  {differ:>12}  {gap_diff:>18.2e}");
        row["contact_cells_differing"] = json!(differ);
        row["mean_gap_relative_difference"] = json!(gap_diff);
        if let Some(h) = a.hardness {
            let at_h = state
                .pressure
                .iter()
                .zip(reference.pressure.iter())
                .filter(|(x, y)| (**x >= h) != (**y >= h))
                .count();
            extra += &format!("  {at_h:>9}");
            row["cells_at_hardness_differing"] = json!(at_h);
        }
    }
    crate::outln!(
        "{n:>6} {solver:>15} {:>7} {:>10} {time:>10.3} {:>12} {:>10.5}{extra}",
        rep.iterations,
        rep.operator_calls,
        peak.map_or("n/a".into(), |p| format!("{p:.0}")),
        rep.contact_area_fraction
    );
    Ok(row)
}
