//! Every picture the command line and the figures draw, in one style: a [`Chart`] of curves
//! (lines, dashed lines, markers, markers with error bars) on linear or logarithmic axes, and
//! a colour map of a field ([`field_map`], [`map`]) with its colour bar. A point whose solve
//! did not converge ([`Curve::solved`]) is drawn as a hollow circle, whatever its curve's mark,
//! and the legend then says what hollow means; no other mark is hollow but the large rings.
//!
//! Machines without system fonts draw text too: the DejaVu Sans font in `fonts/` is compiled in and registered before the first text is drawn.

use anyhow::{Context, Result, anyhow};
use ndarray::ArrayView2;
use plotters::coord::Shift;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};
use std::path::Path;
use std::sync::Once;

static FONT: &[u8] = include_bytes!("../fonts/DejaVuSans.ttf");

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

/// Tableau's ten colours: distinguishable, also in grey print.
pub const PALETTE: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
];
pub const GREY: RGBColor = RGBColor(110, 110, 110);

/// `c` mixed with white: `t = 0` is `c`, `t = 1` white.
pub fn lighter(c: RGBColor, t: f64) -> RGBColor {
    let m = |v: u8| (v as f64 + t * (255.0 - v as f64)).round() as u8;
    RGBColor(m(c.0), m(c.1), m(c.2))
}

/// How a curve is drawn.
#[derive(Clone, Debug)]
pub enum Mark {
    Line,
    Dashed,
    /// Filled triangles.
    Triangles,
    /// Filled dots.
    Dots,
    /// Large open circles: single points singled out (a pull-off, a jump).
    Rings,
    /// Filled dots with vertical error bars of these half-widths (one per point).
    ErrorBars(Vec<f64>),
}

/// A labelled curve.
#[derive(Clone, Debug)]
pub struct Curve {
    pub label: String,
    pub points: Vec<(f64, f64)>,
    pub mark: Mark,
    pub color: RGBColor,
    /// Whether the solve behind each point converged; empty for curves that are not solver
    /// output (references, theory).
    pub converged: Vec<bool>,
}

impl Curve {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, mark: Mark, color: RGBColor) -> Self {
        Curve {
            label: label.into(),
            points,
            mark,
            color,
            converged: Vec::new(),
        }
    }

    /// A curve of solver output: each point with whether its solve converged. The unconverged
    /// ones are drawn hollow.
    pub fn solved(
        label: impl Into<String>,
        points: Vec<(f64, f64, bool)>,
        mark: Mark,
        color: RGBColor,
    ) -> Self {
        let converged = points.iter().map(|p| p.2).collect();
        Curve {
            converged,
            ..Curve::new(
                label,
                points.into_iter().map(|p| (p.0, p.1)).collect(),
                mark,
                color,
            )
        }
    }

    /// The points whose solve did not converge.
    pub fn unconverged(&self) -> usize {
        self.converged.iter().filter(|&&c| !c).count()
    }

    fn converged_at(&self, k: usize) -> bool {
        self.converged.get(k).copied().unwrap_or(true)
    }
}

/// The radius of the hollow circle of an unconverged point [px].
const HOLLOW: i32 = 5;

/// Where the legend sits.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Legend {
    UpperLeft,
    UpperRight,
    LowerLeft,
    LowerRight,
}

/// A chart: axes (labels with units or the paper's dimensionless groups) and curves.
#[derive(Clone, Debug)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub x_log: bool,
    pub y_log: bool,
    pub curves: Vec<Curve>,
    /// Axis ranges; by default the data's, padded.
    pub x_range: Option<(f64, f64)>,
    pub y_range: Option<(f64, f64)>,
    pub legend: Legend,
    /// Whether the data's y range (linear axes) widens on the legend's side so that the legend,
    /// as wide as long labels make it, covers no point.
    pub legend_room: bool,
}

impl Default for Chart {
    fn default() -> Self {
        Chart {
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            x_log: false,
            y_log: false,
            curves: Vec::new(),
            x_range: None,
            y_range: None,
            legend: Legend::UpperLeft,
            legend_room: false,
        }
    }
}

/// Writes `charts` side by side as `dir/stem.png` and `dir/stem.svg`.
pub fn save_panels(charts: &[Chart], dir: &Path, stem: &str) -> Result<()> {
    ensure_font();
    let size = (SIZE.0 * charts.len() as u32 * 5 / 6 + SIZE.0 / 6, SIZE.1);
    let png = dir.join(format!("{stem}.png"));
    surfgen::io::atomically(&png, |p| {
        panels(charts, BitMapBackend::new(p, size).into_drawing_area())
            .with_context(|| format!("drawing {}", png.display()))
    })?;
    let svg = dir.join(format!("{stem}.svg"));
    surfgen::io::atomically(&svg, |p| {
        panels(charts, SVGBackend::new(p, size).into_drawing_area())
            .with_context(|| format!("drawing {}", svg.display()))
    })
}

fn panels<DB: DrawingBackend>(charts: &[Chart], root: DrawingArea<DB, Shift>) -> Result<()> {
    for (chart, area) in charts.iter().zip(root.split_evenly((1, charts.len()))) {
        chart.render(&area)?;
    }
    root.present().map_err(draw_err)?;
    Ok(())
}

const SIZE: (u32, u32) = (900, 640);
/// Points of a line above which it is drawn a pixel wide: about the plot's width in pixels.
const DENSE: usize = 800;

fn draw_err<E: std::fmt::Debug>(e: E) -> anyhow::Error {
    anyhow!("drawing: {e:?}")
}

impl Chart {
    pub fn new(title: impl Into<String>, x_label: impl Into<String>, y_label: impl Into<String>) -> Self {
        Chart {
            title: title.into(),
            x_label: x_label.into(),
            y_label: y_label.into(),
            ..Chart::default()
        }
    }

    /// Writes `dir/stem.png` and `dir/stem.svg`.
    pub fn save(&self, dir: &Path, stem: &str) -> Result<()> {
        save_panels(std::slice::from_ref(self), dir, stem)
    }

    /// Writes the PNG `path`.
    pub fn save_png(&self, path: &Path) -> Result<()> {
        ensure_font();
        surfgen::io::atomically(path, |p| {
            panels(
                std::slice::from_ref(self),
                BitMapBackend::new(p, SIZE).into_drawing_area(),
            )
            .with_context(|| format!("drawing {}", path.display()))
        })
    }

    /// plotters draws no ticks on a log axis far from 1 (a PSD near 1e-30 m^4), so such an axis
    /// is drawn in units of a power of ten named in its label: the chart to draw instead, if any.
    fn rescaled(&self) -> Option<Chart> {
        let largest = |f: fn((f64, f64)) -> f64| {
            self.curves
                .iter()
                .flat_map(|c| c.points.iter().copied())
                .filter(|&p| self.usable(p))
                .map(f)
                .fold(0.0, f64::max)
        };
        let power = |log: bool, hi: f64| {
            let k = if log && hi > 0.0 {
                hi.log10().floor() as i32
            } else {
                0
            };
            if k.abs() > 6 { k } else { 0 }
        };
        let (kx, ky) = (
            power(self.x_log, largest(|p| p.0)),
            power(self.y_log, largest(|p| p.1)),
        );
        if (kx, ky) == (0, 0) {
            return None;
        }
        let (fx, fy) = (10f64.powi(-kx), 10f64.powi(-ky));
        let label = |l: &str, k: i32| {
            if k == 0 {
                l.to_string()
            } else {
                format!("{l} ×1e{k}")
            }
        };
        let mut c = self.clone();
        for curve in &mut c.curves {
            curve.points.iter_mut().for_each(|p| *p = (p.0 * fx, p.1 * fy));
            if let Mark::ErrorBars(e) = &mut curve.mark {
                e.iter_mut().for_each(|e| *e *= fy);
            }
        }
        c.x_range = self.x_range.map(|(a, b)| (a * fx, b * fx));
        c.y_range = self.y_range.map(|(a, b)| (a * fy, b * fy));
        c.x_label = label(&self.x_label, kx);
        c.y_label = label(&self.y_label, ky);
        Some(c)
    }

    /// Whether a point can be drawn: finite, positive on log axes, and inside given ranges
    /// (a line leaving the range simply stops there).
    fn usable(&self, (x, y): (f64, f64)) -> bool {
        let inside = |v: f64, r: Option<(f64, f64)>| r.is_none_or(|(lo, hi)| v >= lo && v <= hi);
        x.is_finite()
            && y.is_finite()
            && (!self.x_log || x > 0.0)
            && (!self.y_log || y > 0.0)
            && inside(x, self.x_range)
            && inside(y, self.y_range)
    }

    /// The axis ranges: given, or the data's (error bars included) with a margin.
    fn ranges(&self) -> Result<((f64, f64), (f64, f64))> {
        let mut xs = (f64::INFINITY, f64::NEG_INFINITY);
        let mut ys = xs;
        for c in &self.curves {
            for (k, &p) in c.points.iter().enumerate() {
                if !self.usable(p) {
                    continue;
                }
                let e = match &c.mark {
                    Mark::ErrorBars(e) => e.get(k).copied().unwrap_or(0.0),
                    _ => 0.0,
                };
                xs = (xs.0.min(p.0), xs.1.max(p.0));
                ys = (ys.0.min(p.1 - e), ys.1.max(p.1 + e));
            }
        }
        if !xs.0.is_finite() {
            anyhow::bail!("nothing to plot in '{}'", self.title);
        }
        let pad = |(lo, hi): (f64, f64), log: bool| {
            if log {
                let f = if hi > lo { (hi / lo).powf(0.05) } else { 2.0 };
                (lo / f, hi * f)
            } else {
                let d = if hi > lo { hi - lo } else { hi.abs().max(1e-300) };
                (lo - 0.05 * d, hi + 0.05 * d)
            }
        };
        let mut y = pad(ys, self.y_log);
        if self.legend_room && !self.y_log {
            let entries = self.curves.iter().filter(|c| !c.label.is_empty()).count()
                + usize::from(self.curves.iter().any(|c| c.unconverged() > 0));
            // The legend's share of the plot's height: 19 px a line and a frame, of about 480 px.
            let share = ((entries as f64 * 19.0 + 16.0) / 480.0).min(0.6);
            let room = (y.1 - y.0) * share / (1.0 - share);
            match self.legend {
                Legend::UpperLeft | Legend::UpperRight => y.1 += room,
                Legend::LowerLeft | Legend::LowerRight => y.0 -= room,
            }
        }
        Ok((
            self.x_range.unwrap_or_else(|| pad(xs, self.x_log)),
            self.y_range.unwrap_or(y),
        ))
    }

    fn render<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
        if let Some(chart) = self.rescaled() {
            return chart.render(root);
        }
        root.fill(&WHITE).map_err(draw_err)?;
        let ((x0, x1), (y0, y1)) = self.ranges()?;
        let mut builder = ChartBuilder::on(root);
        builder
            .caption(&self.title, ("sans-serif", 22))
            .margin(18)
            .x_label_area_size(50)
            .y_label_area_size(80);
        match (self.x_log, self.y_log) {
            (false, false) => {
                let mut c = builder.build_cartesian_2d(x0..x1, y0..y1).map_err(draw_err)?;
                self.body(&mut c)?;
            }
            (true, false) => {
                let mut c = builder
                    .build_cartesian_2d((x0..x1).log_scale(), y0..y1)
                    .map_err(draw_err)?;
                self.body(&mut c)?;
            }
            (false, true) => {
                let mut c = builder
                    .build_cartesian_2d(x0..x1, (y0..y1).log_scale())
                    .map_err(draw_err)?;
                self.body(&mut c)?;
            }
            (true, true) => {
                let mut c = builder
                    .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
                    .map_err(draw_err)?;
                self.body(&mut c)?;
            }
        }
        Ok(())
    }

    fn body<'a, DB, X, Y>(&self, chart: &mut ChartContext<'a, DB, Cartesian2d<X, Y>>) -> Result<()>
    where
        DB: DrawingBackend + 'a,
        X: Ranged<ValueType = f64> + ValueFormatter<f64>,
        Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
    {
        let fmt = |v: &f64| {
            let a = v.abs();
            if a < 1e-12 {
                "0".to_string()
            } else if !(1e-3..1e4).contains(&a) {
                format!("{v:.0e}")
            } else {
                format!("{}", (v * 1e6).round() / 1e6)
            }
        };
        chart
            .configure_mesh()
            .light_line_style(RGBColor(235, 235, 235))
            .x_desc(&self.x_label)
            .y_desc(&self.y_label)
            .x_label_formatter(&fmt)
            .y_label_formatter(&fmt)
            .label_style(("sans-serif", 16))
            .axis_desc_style(("sans-serif", 18))
            .draw()
            .map_err(draw_err)?;
        for c in &self.curves {
            let color = c.color;
            let usable: Vec<(usize, (f64, f64))> = c
                .points
                .iter()
                .copied()
                .enumerate()
                .filter(|&(_, p)| self.usable(p))
                .collect();
            let all: Vec<(f64, f64)> = usable.iter().map(|&(_, p)| p).collect();
            // Markers only where the solve converged; lines run through every point.
            let marked = || {
                usable
                    .iter()
                    .filter(|&&(k, _)| c.converged_at(k))
                    .map(|&(_, p)| p)
            };
            // A line of more points than pixels across is drawn a pixel wide: plotters joins
            // wide segments with mitres, which spike far off the plot where a dense line turns back.
            let width = if all.len() > DENSE { 1 } else { 2 };
            let anno = match &c.mark {
                Mark::Line => chart
                    .draw_series(LineSeries::new(all, color.stroke_width(width)))
                    .map_err(draw_err)?,
                Mark::Dashed => chart
                    .draw_series(DashedLineSeries::new(all, 8, 5, color.stroke_width(2)))
                    .map_err(draw_err)?,
                Mark::Triangles => chart
                    .draw_series(marked().map(|p| TriangleMarker::new(p, 6, color.filled())))
                    .map_err(draw_err)?,
                Mark::Dots => chart
                    .draw_series(marked().map(|p| Circle::new(p, 4, color.filled())))
                    .map_err(draw_err)?,
                Mark::Rings => chart
                    .draw_series(marked().map(|p| Circle::new(p, 9, color.stroke_width(2))))
                    .map_err(draw_err)?,
                Mark::ErrorBars(half) => {
                    let bars: Vec<((f64, f64), f64)> = usable
                        .iter()
                        .filter_map(|&(k, p)| half.get(k).map(|&e| (p, e)))
                        .collect();
                    chart
                        .draw_series(bars.iter().map(|&((x, y), e)| {
                            ErrorBar::new_vertical(x, y - e, y, y + e, color.stroke_width(2), 8)
                        }))
                        .map_err(draw_err)?;
                    chart
                        .draw_series(marked().map(|p| Circle::new(p, 4, color.filled())))
                        .map_err(draw_err)?
                }
            };
            if !c.label.is_empty() {
                let mark = c.mark.clone();
                anno.label(c.label.clone()).legend(move |(x, y)| match mark {
                    Mark::Line => {
                        PathElement::new(vec![(x, y), (x + 22, y)], color.stroke_width(width)).into_dyn()
                    }
                    // Two dashes, as the curve draws them (8 px on, 5 off).
                    Mark::Dashed => plotters::element::DashedPathElement::new(
                        vec![(x, y), (x + 21, y)],
                        8,
                        5,
                        color.stroke_width(2),
                    )
                    .into_dyn(),
                    Mark::Triangles => TriangleMarker::new((x + 11, y), 6, color.filled()).into_dyn(),
                    Mark::Rings => Circle::new((x + 11, y), 7, color.stroke_width(2)).into_dyn(),
                    _ => Circle::new((x + 11, y), 4, color.filled()).into_dyn(),
                });
            }
            let hollow = usable.iter().filter(|&&(k, _)| !c.converged_at(k));
            chart
                .draw_series(hollow.flat_map(|&(_, p)| {
                    [
                        Circle::new(p, HOLLOW, WHITE.filled()),
                        Circle::new(p, HOLLOW, color.stroke_width(2)),
                    ]
                }))
                .map_err(draw_err)?;
        }
        if self.curves.iter().any(|c| c.unconverged() > 0) {
            chart
                .draw_series(std::iter::empty::<Circle<(f64, f64), i32>>())
                .map_err(draw_err)?
                .label("hollow: not converged")
                .legend(|(x, y)| Circle::new((x + 11, y), HOLLOW, GREY.stroke_width(2)));
        }
        chart
            .configure_series_labels()
            .position(match self.legend {
                Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
                Legend::UpperRight => SeriesLabelPosition::UpperRight,
                Legend::LowerLeft => SeriesLabelPosition::LowerLeft,
                Legend::LowerRight => SeriesLabelPosition::LowerRight,
            })
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font(("sans-serif", 15))
            .draw()
            .map_err(draw_err)?;
        Ok(())
    }
}

/// The picture size of a map of an `lx` by `ly` box: a 640-pixel long side, plus margins for
/// the axes and the colour bar.
fn map_size((lx, ly): (f64, f64)) -> (u32, u32) {
    let side = 640.0;
    let (w, h) = if lx >= ly {
        (side, (side * ly / lx).max(120.0))
    } else {
        ((side * lx / ly).max(120.0), side)
    };
    (w as u32 + 230, h as u32 + 90)
}

/// Writes a field over the box `[x0, x0 + lx] x [y0, y0 + ly]` \[m\] as a colour map with a
/// colour bar to the PNG `path`; `value_label` names the quantity and `(vf, vu)` scales its
/// values for the colour bar's axis.
pub fn field_map(
    path: &Path,
    field: ArrayView2<f64>,
    (x0, y0, lx, ly): (f64, f64, f64, f64),
    title: &str,
    value_label: &str,
    (vf, vu): (f64, &str),
) -> Result<()> {
    ensure_font();
    if let Some(((row, col), v)) = field.indexed_iter().find(|(_, v)| !v.is_finite()) {
        anyhow::bail!("{title}: the field holds {v} at row {row}, column {col}; a map of it is not drawn");
    }
    surfgen::io::atomically(path, |p| {
        let root = BitMapBackend::new(p, map_size((lx, ly))).into_drawing_area();
        draw_map(root, field, (x0, y0, lx, ly), title, value_label, (vf, vu))
            .with_context(|| format!("drawing {}", path.display()))
    })
}

/// The same as [`field_map`] as `dir/stem.png` and `dir/stem.svg`.
pub fn map(
    dir: &Path,
    stem: &str,
    field: ArrayView2<f64>,
    extent: (f64, f64, f64, f64),
    title: &str,
    value_label: &str,
    unit: (f64, &str),
) -> Result<()> {
    field_map(
        &dir.join(format!("{stem}.png")),
        field,
        extent,
        title,
        value_label,
        unit,
    )?;
    let svg = dir.join(format!("{stem}.svg"));
    surfgen::io::atomically(&svg, |p| {
        let root = SVGBackend::new(p, map_size((extent.2, extent.3))).into_drawing_area();
        draw_map(root, field, extent, title, value_label, unit)
            .with_context(|| format!("drawing {}", svg.display()))
    })
}

/// One rectangle per cell where cells are at least a pixel wide (so that an SVG stays exact);
/// finer fields are sampled at each pixel's centre.
fn draw_map<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    field: ArrayView2<f64>,
    (x0, y0, lx, ly): (f64, f64, f64, f64),
    title: &str,
    value_label: &str,
    (vf, vu): (f64, &str),
) -> Result<()> {
    root.fill(&WHITE).map_err(draw_err)?;
    let (ny, nx) = field.dim();
    let (lf, lu) = length_unit(lx.max(ly));
    let (width, _) = root.dim_in_pixel();
    let (main, bar) = root.split_horizontally(width - 120);
    let (lo, hi) = field
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let span = if hi > lo { hi - lo } else { 1.0 };
    let (x0, y0, x1, y1) = (x0 * lf, y0 * lf, (x0 + lx) * lf, (y0 + ly) * lf);
    let mut chart = ChartBuilder::on(&main)
        .caption(title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(x0..x1, y0..y1)
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(format!("x ({lu})"))
        .y_desc(format!("y ({lu})"))
        .label_style(("sans-serif", 13))
        .draw()
        .map_err(draw_err)?;
    let (px, py) = chart.plotting_area().get_pixel_range();
    let (pw, ph) = (
        (px.end - px.start).max(1) as usize,
        (py.end - py.start).max(1) as usize,
    );
    // Cells per picture column and row, at least one: each drawn rectangle covers (sx, sy) cells.
    let (sx, sy) = (nx.div_ceil(pw), ny.div_ceil(ph));
    let (dx, dy) = ((x1 - x0) / nx as f64, (y1 - y0) / ny as f64);
    let colour = |v: f64| viridis((v - lo) / span).filled();
    chart
        .draw_series((0..ny).step_by(sy).flat_map(|j| {
            (0..nx).step_by(sx).map(move |i| {
                // The value at the rectangle's centre cell.
                let v = field[((j + sy / 2).min(ny - 1), (i + sx / 2).min(nx - 1))];
                let (x, y) = (x0 + i as f64 * dx, y0 + j as f64 * dy);
                Rectangle::new([(x, y), (x + sx as f64 * dx, y + sy as f64 * dy)], colour(v))
            })
        }))
        .map_err(draw_err)?;
    colour_bar(&bar, (lo, span), value_label, (vf, vu))?;
    root.present().map_err(draw_err)?;
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
