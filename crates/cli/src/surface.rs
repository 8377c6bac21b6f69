//! `generate`, `stats` and `psd`: making and measuring surfaces.

use crate::plot::{self, Chart, Curve, Mark, PALETTE};
use anyhow::{Context, Result, bail};
use case::Generation;
use clap::Args;
use serde::Serialize;
use std::io::Write;
use std::path::{Path, PathBuf};
use surfgen::io::{self, ReadOptions};
use surfgen::{Analysis, Metadata, Statistics, Surface};

#[derive(Args, Debug)]
pub struct GenerateArgs {
    #[command(flatten)]
    surface: Generation,
    /// Output surface file: .npy (with .json sidecar), .txt, .xyz, .gsf, .x3p, .sdf or .nc.
    #[arg(short, long, default_value = "surface.npy")]
    output: PathBuf,
    /// Do not draw the PNG height map.
    #[arg(long)]
    no_png: bool,
    /// Print the statistics as JSON instead of a table.
    #[arg(long)]
    json: bool,
}

/// Where a surface comes from, for commands that read one.
#[derive(Args, Debug)]
pub struct SurfaceFile {
    /// Surface file: .npy (+ .json sidecar), .txt/.dat/.asc/.csv, .xyz/.xyh, .gsf, .x3p, .sdf,
    /// .nc, .tmd, .mi, .nid, .sur, .mnt, .opd, .di/.spm, .ibw, .frt, .gwy, .h5 or .datx (heights and sizes
    /// converted to metres from the file's units).
    pub file: PathBuf,
    /// Box size along x [m], for files that do not carry it (bare .npy, plain matrix).
    #[arg(long)]
    length: Option<f64>,
    /// Box size along y [m] (default: square cells).
    #[arg(long)]
    length_y: Option<f64>,
    /// Metres per file unit, for lengths and heights (e.g. 1e-4 for files in units of 0.1 mm).
    #[arg(long, default_value_t = 1.0)]
    unit: f64,
    /// Treat a file without metadata as non-periodic (finite differences then skip the edges).
    #[arg(long)]
    not_periodic: bool,
    /// The channel of heights to read, by name or index (default: the first channel of
    /// heights; `roughcontact info FILE` lists them).
    #[arg(long)]
    channel: Option<String>,
    /// Fill the points the instrument marks as not measured by harmonic interpolation
    /// (default: refuse such a file, counting them).
    #[arg(long)]
    fill_unmeasured: bool,
    /// The largest fraction of the points --fill-unmeasured fills, in [0, 1] (default 0.25:
    /// beyond it the filled surface is more interpolation than measurement; 1 fills any).
    #[arg(long, value_name = "FRACTION")]
    max_unmeasured: Option<f64>,
}

impl SurfaceFile {
    /// The reading options the flags give, the channel resolved to its index.
    pub fn options(&self) -> Result<ReadOptions> {
        let options = ReadOptions {
            length_x: self.length,
            length_y: self.length_y,
            unit: self.unit,
            periodic: !self.not_periodic,
            channel: None,
            unmeasured: io::Unmeasured::filled_up_to(self.fill_unmeasured, self.max_unmeasured)
                .map_err(|e| anyhow::anyhow!(e).context("--max-unmeasured"))?,
        };
        Ok(options
            .with_channel(&self.file, self.channel.as_deref())
            .map_err(|e| case::naming("reading", &self.file, e))?)
    }

    /// The surface, and a warning on standard error when points were filled.
    fn read(&self) -> Result<Surface> {
        let (surface, filled) = io::read_noting(&self.file, &self.options()?)
            .map_err(|e| case::naming("reading", &self.file, e))?;
        if let Some(note) = filled {
            crate::errln!("warning: {note}");
        }
        Ok(surface)
    }
}

#[derive(Args, Debug)]
pub struct InfoArgs {
    #[command(flatten)]
    surface: SurfaceFile,
    /// Print JSON instead of a table.
    #[arg(long)]
    json: bool,
}

/// What `info` finds in a file: its channels, and the surface it reads as.
#[derive(Serialize)]
struct Info {
    file: PathBuf,
    channels: Vec<io::Channel>,
    /// The channel read as the surface (the default, or --channel), or why none can be.
    reads_as: std::result::Result<Reading, String>,
}

#[derive(Serialize)]
struct Reading {
    channel: usize,
    /// `surface` or `line scan`.
    kind: &'static str,
    nx: usize,
    ny: usize,
    length_x_m: Option<f64>,
    length_y_m: Option<f64>,
    unmeasured_points: usize,
    /// The measured points' statistics; `None` (null) where no point is measured.
    mean_height_m: Option<f64>,
    rms_height_m: Option<f64>,
    min_height_m: Option<f64>,
    max_height_m: Option<f64>,
}

impl Reading {
    fn of(t: io::Topography) -> Self {
        let (channel, kind, nx, ny, lx, ly, heights) = match t {
            io::Topography::Surface(m) => (
                m.channel,
                "surface",
                m.grid.nx,
                m.grid.ny,
                Some(m.grid.length_x),
                Some(m.grid.length_y),
                m.heights.into_iter().collect::<Vec<_>>(),
            ),
            io::Topography::Profile(p) => (
                p.channel,
                "line scan",
                p.heights.len(),
                1,
                p.length,
                None,
                p.heights,
            ),
        };
        let measured: Vec<f64> = heights.iter().copied().filter(|h| !h.is_nan()).collect();
        let some = !measured.is_empty();
        let n = measured.len().max(1) as f64;
        let mean = measured.iter().sum::<f64>() / n;
        Reading {
            channel,
            kind,
            nx,
            ny,
            length_x_m: lx,
            length_y_m: ly,
            unmeasured_points: heights.len() - measured.len(),
            mean_height_m: some.then_some(mean),
            rms_height_m: some.then(|| (measured.iter().map(|h| (h - mean).powi(2)).sum::<f64>() / n).sqrt()),
            min_height_m: some.then(|| measured.iter().copied().fold(f64::INFINITY, f64::min)),
            max_height_m: some.then(|| measured.iter().copied().fold(f64::NEG_INFINITY, f64::max)),
        }
    }
}

/// A lateral size for a table: both sides, one (a line), or none.
fn size_text(x: Option<f64>, y: Option<f64>) -> String {
    match (x, y) {
        (Some(x), Some(y)) => format!("{x:.4e} x {y:.4e}"),
        (Some(x), None) => format!("{x:.4e} (a line)"),
        _ => "not in the file".into(),
    }
}

/// `roughcontact info`: a file's channels, grid, size and units, and its unmeasured points.
pub fn info(a: InfoArgs) -> Result<()> {
    let path = &a.surface.file;
    let options = a.surface.options()?;
    let channels = io::channels(path, &options).map_err(|e| case::naming("reading", path, e))?;
    let reads_as = io::read_topography(path, &options)
        .map(Reading::of)
        .map_err(|e| e.to_string());
    let info = Info {
        file: path.clone(),
        channels,
        reads_as,
    };
    // A file whose channel does not read is listed, then refused (status 1), naming why.
    let refused = |e: &String| anyhow::anyhow!("{}: the channel does not read: {e}", path.display());
    if a.json {
        crate::outln!("{}", serde_json::to_string_pretty(&info)?);
        return info.reads_as.as_ref().map(|_| ()).map_err(refused);
    }
    crate::outln!("{}", path.display());
    crate::outln!(
        "  channel  name                         points        size [m]                 unit  heights"
    );
    for (i, c) in info.channels.iter().enumerate() {
        let points = format!("{} x {}", c.nx, c.ny);
        crate::outln!(
            "  {i:>7}  {:<28} {points:<13} {:<24} {:<5} {}",
            c.name,
            size_text(c.length_x, c.length_y),
            c.unit,
            if c.height { "yes" } else { "no" }
        );
    }
    match &info.reads_as {
        Ok(r) => {
            crate::outln!(
                "reads as channel {}: a {} of {} x {} points, {} m",
                r.channel,
                r.kind,
                r.nx,
                r.ny,
                size_text(r.length_x_m, r.length_y_m)
            );
            match (r.mean_height_m, r.rms_height_m, r.min_height_m, r.max_height_m) {
                (Some(mean), Some(rms), Some(min), Some(max)) => crate::outln!(
                    "  heights [m] of the measured points: mean {mean:.4e}, RMS {rms:.4e}, min {min:.4e}, max {max:.4e}"
                ),
                _ => crate::outln!("  no point is measured"),
            }
            if r.ny == 1 {
                crate::outln!("  a contact calculation needs a surface: this line scan is refused");
            }
            if r.unmeasured_points > 0 {
                crate::outln!(
                    "  {} of {} points not measured: a contact calculation refuses the file unless \
                     --fill-unmeasured fills them",
                    r.unmeasured_points,
                    r.nx * r.ny
                );
            } else {
                crate::outln!("  every point measured");
            }
        }
        Err(e) => return Err(refused(e)),
    }
    Ok(())
}

#[derive(Args, Debug)]
pub struct StatsArgs {
    #[command(flatten)]
    surface: SurfaceFile,
    /// Print JSON (snake_case keys, SI units) instead of a table.
    #[arg(long)]
    json: bool,
    /// Hurst fit range: smallest and largest wavevector [rad/m] (default: past the roll-off to
    /// before the cut-off, found from the spectrum).
    #[arg(long, num_args = 2, value_names = ["Q_MIN", "Q_MAX"])]
    fit_range: Option<Vec<f64>>,
    /// Also write the bearing-area (material ratio) curve as CSV: height [m], ratio [-].
    #[arg(long, value_name = "FILE")]
    bearing: Option<PathBuf>,
}

#[derive(Args, Debug)]
pub struct PsdArgs {
    #[command(flatten)]
    surface: SurfaceFile,
    /// Output CSV (default: <file stem>_psd.csv); the plot goes beside it as .png.
    #[arg(short, long)]
    output: Option<PathBuf>,
    /// Logarithmic bins per decade of wavevector.
    #[arg(long, default_value_t = 10)]
    bins_per_decade: usize,
    /// Do not draw the log-log plot.
    #[arg(long)]
    no_png: bool,
}

/// The statistics report: grid and statistics side by side, SI units.
#[derive(Serialize)]
struct Report<'a> {
    nx: usize,
    ny: usize,
    length_x: f64,
    length_y: f64,
    periodic: bool,
    #[serde(flatten)]
    statistics: &'a Statistics,
}

fn print_report(surface: &Surface, statistics: &Statistics, json: bool) -> Result<()> {
    let mut out = std::io::stdout().lock();
    if json {
        let report = Report {
            nx: surface.grid.nx,
            ny: surface.grid.ny,
            length_x: surface.grid.length_x,
            length_y: surface.grid.length_y,
            periodic: surface.periodic,
            statistics,
        };
        writeln!(out, "{}", serde_json::to_string_pretty(&report)?)?;
        return Ok(());
    }
    let g = surface.grid;
    let s = statistics;
    let h = &s.heights;
    let rows: Vec<(&str, String, &str)> = vec![
        ("grid", format!("{} x {}", g.nx, g.ny), "points"),
        ("box", format!("{:.6e} x {:.6e}", g.length_x, g.length_y), "m"),
        ("spacing", format!("{:.6e} x {:.6e}", g.dx(), g.dy()), "m"),
        ("periodic", surface.periodic.to_string(), ""),
        ("mean height", format!("{:.6e}", h.mean), "m"),
        ("RMS height Rq", format!("{:.6e}", h.rms_height), "m"),
        ("min / max", format!("{:.6e} / {:.6e}", h.min, h.max), "m"),
        ("peak-to-valley", format!("{:.6e}", h.peak_to_valley), "m"),
        ("skewness", format!("{:.4}", h.skewness), "-"),
        ("kurtosis", format!("{:.4}", h.kurtosis), "- (3 for Gaussian)"),
        ("RMS gradient (spectral)", format!("{:.6}", s.rms_gradient), "-"),
        (
            "RMS gradient (finite diff.)",
            format!("{:.6}", s.rms_gradient_fd),
            "-",
        ),
        ("RMS mean curvature", format!("{:.6e}", s.curvature.mean), "1/m"),
        ("RMS Laplacian", format!("{:.6e}", s.curvature.laplacian), "1/m"),
        ("RMS d2h/dx2", format!("{:.6e}", s.curvature.profile_x), "1/m"),
        (
            "  same, finite diff.",
            format!(
                "{:.6e} / {:.6e} / {:.6e}",
                s.curvature_fd.mean, s.curvature_fd.laplacian, s.curvature_fd.profile_x
            ),
            "1/m",
        ),
        ("local radius 1/curvature", format!("{:.6e}", s.local_radius), "m"),
        (
            "Hurst exponent (fit)",
            match (s.hurst_fit, s.hurst_fit_range) {
                (Some(hf), Some([a, b])) => format!("{hf:.4} over q = {a:.3e} .. {b:.3e} rad/m"),
                _ => "n/a (too few spectral bins)".into(),
            },
            "-",
        ),
    ];
    for (name, value, unit) in rows {
        writeln!(out, "{name:<28} {value}  {unit}")?;
    }
    Ok(())
}

fn draw_height_map(path: &Path, surface: &Surface, title: &str) -> Result<()> {
    let pv = surface.heights.iter().fold(0.0f64, |a, &h| a.max(h.abs()));
    plot::field_map(
        path,
        surface.heights.view(),
        (0.0, 0.0, surface.grid.length_x, surface.grid.length_y),
        title,
        "height",
        plot::length_unit(pv),
    )
}

pub fn generate(a: GenerateArgs) -> Result<()> {
    let (spec, generated) = a.surface.generate()?;
    let (grid, nx, ny) = (spec.grid, spec.grid.nx, spec.grid.ny);
    for w in &generated.warnings {
        crate::errln!("warning: {w}");
    }
    let surface = Surface::new(generated.heights, grid, true)?;
    // The heights go to disk while the statistics and the picture are computed.
    let mut metadata = Metadata {
        spec: Some(spec),
        prefactor: Some(generated.prefactor),
        ..Metadata::of(&surface)
    };
    let (written, statistics) = rayon::join(
        || io::write(&surface, &a.output, None).map_err(|e| case::naming("writing", &a.output, e)),
        || -> Result<Statistics> {
            let statistics =
                surfgen::stats::statistics_with(surface.heights.view(), &generated.analysis, true, None);
            if !a.no_png {
                let png = a.output.with_extension("png");
                let title = format!(
                    "H = {}, seed {}, {} x {}",
                    a.surface.hurst, a.surface.seed, nx, ny
                );
                draw_height_map(&png, &surface, &title)?;
            }
            Ok(statistics)
        },
    );
    written?;
    let statistics = statistics?;
    metadata.statistics = Some(statistics.clone());
    io::write_metadata(&a.output, &metadata)?;
    print_report(&surface, &statistics, a.json)?;
    if !a.json {
        crate::errln!(
            "wrote {} (+ .json sidecar{})",
            a.output.display(),
            if a.no_png { "" } else { ", .png map" }
        );
    }
    Ok(())
}

pub fn stats(a: StatsArgs) -> Result<()> {
    let surface = a.surface.read()?;
    let fit_range = match a.fit_range.as_deref() {
        Some([lo, hi]) if *lo > 0.0 && hi > lo => Some((*lo, *hi)),
        Some(r) => bail!("--fit-range needs 0 < Q_MIN < Q_MAX [rad/m], got {r:?}"),
        None => None,
    };
    let statistics = surfgen::statistics(surface.heights.view(), &surface.grid, surface.periodic, fit_range);
    if let Some(path) = &a.bearing {
        let mut csv = String::from("height_m,material_ratio\n");
        for (z, r) in surfgen::bearing_area_curve(surface.heights.view(), 201) {
            csv += &format!("{z:e},{r:e}\n");
        }
        std::fs::write(path, csv).with_context(|| format!("writing {}", path.display()))?;
    }
    print_report(&surface, &statistics, a.json)
}

pub fn psd(a: PsdArgs) -> Result<()> {
    if a.bins_per_decade == 0 {
        bail!("--bins-per-decade must be at least 1");
    }
    let surface = a.surface.read()?;
    let analysis = Analysis::new(surface.heights.view(), &surface.grid, a.bins_per_decade);
    let r = &analysis.radial_psd;
    let output = a.output.unwrap_or_else(|| {
        let stem = a
            .surface
            .file
            .file_stem()
            .and_then(|s| s.to_str())
            .unwrap_or("surface");
        a.surface.file.with_file_name(format!("{stem}_psd.csv"))
    });
    let mut csv = String::from("q_rad_per_m,psd_m4,std_err_m4,count\n");
    for i in 0..r.q.len() {
        csv += &format!("{:e},{:e},{:e},{}\n", r.q[i], r.psd[i], r.std_err[i], r.count[i]);
    }
    std::fs::write(&output, csv).with_context(|| format!("writing {}", output.display()))?;
    let fit = r.default_fit_range().and_then(|(lo, hi)| r.fit_hurst(lo, hi));
    if !a.no_png {
        // Bins past a cut-off hold only round-off (~1e-30 of the peak): leave them out of the plot.
        let peak = r.psd.iter().cloned().fold(0.0, f64::max);
        let mut chart = Chart::new("Radially averaged PSD", "q (rad/m)", "C(q) (m^4)");
        chart.x_log = true;
        chart.y_log = true;
        chart.curves.push(Curve::new(
            "radial average",
            r.q.iter()
                .copied()
                .zip(r.psd.iter().copied())
                .filter(|(_, c)| *c > 1e-20 * peak)
                .collect(),
            Mark::Dots,
            PALETTE[0],
        ));
        if let Some(f) = fit {
            chart.curves.push(Curve::new(
                format!("fit, H = {:.3}", f.hurst),
                vec![(f.q_min, f.psd_at(f.q_min)), (f.q_max, f.psd_at(f.q_max))],
                Mark::Line,
                PALETTE[3],
            ));
        }
        chart.save_png(&output.with_extension("png"))?;
    }
    match fit {
        Some(f) => crate::outln!(
            "wrote {} ({} bins); fitted Hurst exponent {:.4} over q = {:.3e} .. {:.3e} rad/m",
            output.display(),
            r.q.len(),
            f.hurst,
            f.q_min,
            f.q_max
        ),
        None => crate::outln!("wrote {} ({} bins)", output.display(), r.q.len()),
    }
    Ok(())
}
