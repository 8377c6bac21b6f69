//! One plotting style for every figure: a [`Chart`] of curves (lines, dashed lines, markers,
//! markers with error bars) on linear or logarithmic axes, and a colour [`map`], each written
//! as PNG and SVG, in the command line's plotting module's font and colours (shared as source).

use crate::plot::{colour_bar, ensure_font, length_unit, viridis};
use anyhow::{Context, Result, anyhow};
use ndarray::ArrayView2;
use plotters::coord::Shift;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::prelude::*;
use std::path::Path;

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
    /// Open circles.
    Circles,
    /// Filled dots.
    Dots,
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
}

impl Curve {
    pub fn new(label: impl Into<String>, points: Vec<(f64, f64)>, mark: Mark, color: RGBColor) -> Self {
        Curve {
            label: label.into(),
            points,
            mark,
            color,
        }
    }
}

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
        }
    }
}

/// Writes `charts` side by side as `dir/stem.png` and `dir/stem.svg`.
pub fn save_panels(charts: &[Chart], dir: &Path, stem: &str) -> Result<()> {
    ensure_font();
    let size = (SIZE.0 * charts.len() as u32 * 5 / 6 + SIZE.0 / 6, SIZE.1);
    let png = dir.join(format!("{stem}.png"));
    panels(charts, BitMapBackend::new(&png, size).into_drawing_area())
        .with_context(|| format!("drawing {}", png.display()))?;
    let svg = dir.join(format!("{stem}.svg"));
    panels(charts, SVGBackend::new(&svg, size).into_drawing_area())
        .with_context(|| format!("drawing {}", svg.display()))
}

fn panels<DB: DrawingBackend>(charts: &[Chart], root: DrawingArea<DB, Shift>) -> Result<()> {
    for (chart, area) in charts.iter().zip(root.split_evenly((1, charts.len()))) {
        chart.render(&area)?;
    }
    root.present().map_err(draw_err)?;
    Ok(())
}

const SIZE: (u32, u32) = (900, 640);

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
        Ok((
            self.x_range.unwrap_or_else(|| pad(xs, self.x_log)),
            self.y_range.unwrap_or_else(|| pad(ys, self.y_log)),
        ))
    }

    fn render<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()> {
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
            let points: Vec<(f64, f64)> = c.points.iter().copied().filter(|&p| self.usable(p)).collect();
            let anno = match &c.mark {
                Mark::Line => chart
                    .draw_series(LineSeries::new(points, color.stroke_width(2)))
                    .map_err(draw_err)?,
                Mark::Dashed => chart
                    .draw_series(DashedLineSeries::new(points, 8, 5, color.stroke_width(2)))
                    .map_err(draw_err)?,
                Mark::Circles => chart
                    .draw_series(
                        points
                            .into_iter()
                            .map(|p| Circle::new(p, 4, color.stroke_width(2))),
                    )
                    .map_err(draw_err)?,
                Mark::Dots => chart
                    .draw_series(points.into_iter().map(|p| Circle::new(p, 4, color.filled())))
                    .map_err(draw_err)?,
                Mark::ErrorBars(half) => {
                    let bars: Vec<((f64, f64), f64)> = c
                        .points
                        .iter()
                        .zip(half)
                        .filter(|(p, _)| self.usable(**p))
                        .map(|(p, e)| (*p, *e))
                        .collect();
                    chart
                        .draw_series(bars.iter().map(|&((x, y), e)| {
                            ErrorBar::new_vertical(x, y - e, y, y + e, color.stroke_width(2), 8)
                        }))
                        .map_err(draw_err)?;
                    chart
                        .draw_series(bars.iter().map(|&(p, _)| Circle::new(p, 4, color.filled())))
                        .map_err(draw_err)?
                }
            };
            if c.label.is_empty() {
                continue;
            }
            let mark = c.mark.clone();
            anno.label(c.label.clone()).legend(move |(x, y)| match mark {
                Mark::Line => PathElement::new(vec![(x, y), (x + 22, y)], color.stroke_width(2)).into_dyn(),
                // Two dashes, as the curve draws them (8 px on, 5 off).
                Mark::Dashed => plotters::element::DashedPathElement::new(
                    vec![(x, y), (x + 21, y)],
                    8,
                    5,
                    color.stroke_width(2),
                )
                .into_dyn(),
                Mark::Circles => Circle::new((x + 11, y), 4, color.stroke_width(2)).into_dyn(),
                _ => Circle::new((x + 11, y), 4, color.filled()).into_dyn(),
            });
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

/// A field on an `lx` by `ly` \[m\] box as a colour map (one rectangle per cell, so that the SVG
/// stays exact) with a colour bar; `(vf, vu)` scales the values for the colour-bar axis.
pub fn map(
    dir: &Path,
    stem: &str,
    field: ArrayView2<f64>,
    (lx, ly): (f64, f64),
    title: &str,
    value_label: &str,
    (vf, vu): (f64, &str),
) -> Result<()> {
    ensure_font();
    let png = dir.join(format!("{stem}.png"));
    draw_map(
        BitMapBackend::new(&png, (860, 700)).into_drawing_area(),
        field,
        (lx, ly),
        title,
        value_label,
        (vf, vu),
    )
    .with_context(|| format!("drawing {}", png.display()))?;
    let svg = dir.join(format!("{stem}.svg"));
    draw_map(
        SVGBackend::new(&svg, (860, 700)).into_drawing_area(),
        field,
        (lx, ly),
        title,
        value_label,
        (vf, vu),
    )
    .with_context(|| format!("drawing {}", svg.display()))
}

fn draw_map<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    field: ArrayView2<f64>,
    (lx, ly): (f64, f64),
    title: &str,
    value_label: &str,
    (vf, vu): (f64, &str),
) -> Result<()> {
    root.fill(&WHITE).map_err(draw_err)?;
    let (ny, nx) = field.dim();
    let (lf, lu) = length_unit(lx.max(ly));
    let (main, bar) = root.split_horizontally(700);
    let (lo, hi) = field
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let span = if hi > lo { hi - lo } else { 1.0 };
    let mut chart = ChartBuilder::on(&main)
        .caption(title, ("sans-serif", 20))
        .margin(15)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d(-lx * lf / 2.0..lx * lf / 2.0, -ly * lf / 2.0..ly * lf / 2.0)
        .map_err(draw_err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(format!("x ({lu})"))
        .y_desc(format!("y ({lu})"))
        .label_style(("sans-serif", 15))
        .axis_desc_style(("sans-serif", 17))
        .draw()
        .map_err(draw_err)?;
    let (dx, dy) = (lx * lf / nx as f64, ly * lf / ny as f64);
    chart
        .draw_series(field.indexed_iter().map(|((j, i), &v)| {
            let x = -lx * lf / 2.0 + i as f64 * dx;
            let y = -ly * lf / 2.0 + j as f64 * dy;
            Rectangle::new([(x, y), (x + dx, y + dy)], viridis((v - lo) / span).filled())
        }))
        .map_err(draw_err)?;
    colour_bar(&bar, (lo, span), value_label, (vf, vu))?;
    root.present().map_err(draw_err)?;
    Ok(())
}
