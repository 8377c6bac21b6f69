//! Pictures: height maps with a colour bar, and log-log curves. One style for all.
//!
//! Machines here have no system fonts, so the DejaVu Sans font shipped in `assets/fonts` is
//! compiled in and registered before the first text is drawn.

use anyhow::{Context, Result, anyhow};
use ndarray::ArrayView2;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use std::path::Path;
use std::sync::Once;

static FONT: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");

/// Registers the bundled font (once); call before drawing any text.
pub fn ensure_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        if register_font("sans-serif", FontStyle::Normal, FONT).is_err() {
            panic!("the bundled font is not a valid TrueType file");
        }
    });
}

/// A value's display unit: the SI prefix that makes `|v|` readable, and its factor.
pub fn length_unit(v: f64) -> (f64, &'static str) {
    let v = v.abs();
    if v >= 1e-3 {
        (1e3, "mm")
    } else if v >= 1e-6 {
        (1e6, "µm")
    } else if v >= 1e-9 {
        (1e9, "nm")
    } else {
        (1e12, "pm")
    }
}

/// Viridis, interpolated between nine anchors; `t` in [0, 1].
pub fn viridis(t: f64) -> RGBColor {
    const A: [(u8, u8, u8); 9] = [
        (68, 1, 84),
        (71, 44, 122),
        (59, 81, 139),
        (44, 113, 142),
        (33, 144, 141),
        (39, 173, 129),
        (92, 200, 99),
        (170, 220, 50),
        (253, 231, 37),
    ];
    let x = t.clamp(0.0, 1.0) * 8.0;
    let i = (x.floor() as usize).min(7);
    let f = x - i as f64;
    let mix = |a: u8, b: u8| (a as f64 + f * (b as f64 - a as f64)).round() as u8;
    RGBColor(
        mix(A[i].0, A[i + 1].0),
        mix(A[i].1, A[i + 1].1),
        mix(A[i].2, A[i + 1].2),
    )
}

fn err<E: std::fmt::Debug>(path: &Path) -> impl Fn(E) -> anyhow::Error + '_ {
    move |e| anyhow!("drawing {}: {e:?}", path.display())
}

/// Draws a field on an `lx` by `ly` [m] box as a colour map with a colour bar; `value_label`
/// names the quantity and `value_unit` is `(factor, unit)` for the colour-bar axis.
pub fn field_map(
    path: &Path,
    field: ArrayView2<f64>,
    (lx, ly): (f64, f64),
    title: &str,
    value_label: &str,
    (vf, vu): (f64, &str),
) -> Result<()> {
    ensure_font();
    let (ny, nx) = field.dim();
    let (lf, lu) = length_unit(lx.max(ly));
    let side = 640u32;
    let (w, h) = if lx >= ly {
        (side, ((side as f64 * ly / lx) as u32).max(120))
    } else {
        (((side as f64 * lx / ly) as u32).max(120), side)
    };
    let root = BitMapBackend::new(path, (w + 230, h + 90)).into_drawing_area();
    root.fill(&WHITE).map_err(err(path))?;
    let (main, bar) = root.split_horizontally(w + 110);
    let (lo, hi) = field
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let span = if hi > lo { hi - lo } else { 1.0 };
    let mut chart = ChartBuilder::on(&main)
        .caption(title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(0.0..lx * lf, 0.0..ly * lf)
        .map_err(err(path))?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(format!("x ({lu})"))
        .y_desc(format!("y ({lu})"))
        .label_style(("sans-serif", 13))
        .draw()
        .map_err(err(path))?;
    let area = chart.plotting_area();
    let (px, py) = area.get_pixel_range();
    let (pw, ph) = ((px.end - px.start).max(1), (py.end - py.start).max(1));
    for j in 0..ph {
        // Row 0 of the picture is the top, i.e. the largest y.
        let iy = (((ph - 1 - j) as f64 + 0.5) / ph as f64 * ny as f64) as usize;
        for i in 0..pw {
            let ix = ((i as f64 + 0.5) / pw as f64 * nx as f64) as usize;
            let v = field[(iy.min(ny - 1), ix.min(nx - 1))];
            main.draw_pixel((px.start + i, py.start + j), &viridis((v - lo) / span))
                .map_err(err(path))?;
        }
    }
    colour_bar(&bar, (lo, span), value_label, (vf, vu))
        .with_context(|| format!("drawing {}", path.display()))?;
    root.present()
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

/// The colour bar of a map whose values run from `lo` to `lo + span`, on `area`: viridis,
/// labelled `value_label (vu)` with the values times `vf`. One bar for every map drawn.
pub fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, plotters::coord::Shift>,
    (lo, span): (f64, f64),
    value_label: &str,
    (vf, vu): (f64, &str),
) -> Result<()> {
    let mut cb = ChartBuilder::on(area)
        .margin_top(45)
        .margin_bottom(65)
        .margin_right(10)
        .y_label_area_size(80)
        .build_cartesian_2d(0.0..1.0, lo * vf..(lo + span) * vf)
        .map_err(|e| anyhow!("{e:?}"))?;
    cb.configure_mesh()
        .disable_mesh()
        .disable_x_axis()
        .y_desc(format!("{value_label} ({vu})"))
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .draw()
        .map_err(|e| anyhow!("{e:?}"))?;
    let steps = 128;
    cb.draw_series((0..steps).map(|k| {
        let a = lo + span * k as f64 / steps as f64;
        let b = lo + span * (k + 1) as f64 / steps as f64;
        Rectangle::new(
            [(0.0, a * vf), (1.0, b * vf)],
            viridis((k as f64 + 0.5) / steps as f64).filled(),
        )
    }))
    .map_err(|e| anyhow!("{e:?}"))?;
    Ok(())
}

/// A named curve for [`loglog`] and [`lines`]: points and whether to draw them as markers or a line.
pub struct Series<'a> {
    pub label: &'a str,
    pub points: Vec<(f64, f64)>,
    pub markers: bool,
    pub color: RGBColor,
}

/// A log-log plot of several series (non-positive points are skipped).
pub fn loglog(path: &Path, title: &str, x_label: &str, y_label: &str, series: &[Series]) -> Result<()> {
    ensure_font();
    let pos = |s: &Series| -> Vec<(f64, f64)> {
        s.points
            .iter()
            .copied()
            .filter(|(x, y)| *x > 0.0 && *y > 0.0 && x.is_finite() && y.is_finite())
            .collect()
    };
    let all: Vec<(f64, f64)> = series.iter().flat_map(pos).collect();
    if all.is_empty() {
        anyhow::bail!("nothing positive to plot in {}", path.display());
    }
    let (x0, x1, y0, y1) = all.iter().fold(
        (f64::INFINITY, 0.0f64, f64::INFINITY, 0.0f64),
        |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
    );
    // plotters draws no ticks on log axes far from 1 (e.g. a PSD near 1e-30 m^4), so such
    // axes are plotted in units of a power of ten named in the label.
    let rescale = |hi: f64, label: &str| -> (f64, String) {
        let k = hi.log10().floor() as i32;
        if k.abs() > 6 {
            (10f64.powi(-k), format!("{label} ×1e{k}"))
        } else {
            (1.0, label.to_string())
        }
    };
    let (fx, x_label) = rescale(x1, x_label);
    let (fy, y_label) = rescale(y1, y_label);
    let (x0, x1, y0, y1) = (x0 * fx, x1 * fx, y0 * fy, y1 * fy);
    let pos = |s: &Series| -> Vec<(f64, f64)> { pos(s).into_iter().map(|(x, y)| (x * fx, y * fy)).collect() };
    let root = BitMapBackend::new(path, (800, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(err(path))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d((x0 / 1.2..x1 * 1.2).log_scale(), (y0 / 2.0..y1 * 2.0).log_scale())
        .map_err(err(path))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .label_style(("sans-serif", 14))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .draw()
        .map_err(err(path))?;
    draw_series(&mut chart, series.iter().map(|s| (s, pos(s))), path)?;
    root.present()
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}

/// Draws each series (as markers or a line) with its legend entry.
fn draw_series<'a, 'b: 'a, 's, X, Y>(
    chart: &mut ChartContext<'a, BitMapBackend<'b>, Cartesian2d<X, Y>>,
    series: impl Iterator<Item = (&'s Series<'s>, Vec<(f64, f64)>)>,
    path: &Path,
) -> Result<()>
where
    X: Ranged<ValueType = f64>,
    Y: Ranged<ValueType = f64>,
{
    for (s, points) in series {
        let c = s.color;
        if s.markers {
            chart
                .draw_series(points.into_iter().map(|p| Circle::new(p, 3, c.filled())))
                .map_err(err(path))?
                .label(s.label)
                .legend(move |(x, y)| Circle::new((x + 10, y), 3, c.filled()));
        } else {
            chart
                .draw_series(LineSeries::new(points, c.stroke_width(2)))
                .map_err(err(path))?
                .label(s.label)
                .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], c.stroke_width(2)));
        }
    }
    chart
        .configure_series_labels()
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font(("sans-serif", 14))
        .draw()
        .map_err(err(path))?;
    Ok(())
}

/// A plot of several series on linear axes (non-finite points are skipped).
pub fn lines(path: &Path, title: &str, x_label: &str, y_label: &str, series: &[Series]) -> Result<()> {
    ensure_font();
    let finite = |s: &Series| -> Vec<(f64, f64)> {
        s.points
            .iter()
            .copied()
            .filter(|(x, y)| x.is_finite() && y.is_finite())
            .collect()
    };
    let all: Vec<(f64, f64)> = series.iter().flat_map(finite).collect();
    if all.is_empty() {
        anyhow::bail!("nothing to plot in {}", path.display());
    }
    let (x0, x1, y0, y1) = all.iter().fold(
        (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY),
        |(a, b, c, d), &(x, y)| (a.min(x), b.max(x), c.min(y), d.max(y)),
    );
    let pad = |lo: f64, hi: f64| {
        let d = (hi - lo)
            .abs()
            .max(hi.abs().max(lo.abs()) * 1e-6)
            .max(f64::MIN_POSITIVE);
        (lo - 0.05 * d, hi + 0.05 * d)
    };
    let ((x0, x1), (y0, y1)) = (pad(x0, x1), pad(y0, y1));
    let root = BitMapBackend::new(path, (800, 600)).into_drawing_area();
    root.fill(&WHITE).map_err(err(path))?;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(45)
        .y_label_area_size(75)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(err(path))?;
    chart
        .configure_mesh()
        .x_desc(x_label)
        .y_desc(y_label)
        .label_style(("sans-serif", 14))
        .draw()
        .map_err(err(path))?;
    draw_series(&mut chart, series.iter().map(|s| (s, finite(s))), path)?;
    root.present()
        .with_context(|| format!("writing {}", path.display()))?;
    Ok(())
}
