//! Plain-text formats: a height matrix, and `x y h` triples.

use super::{Measurement, Profile, ReadOptions, Surface, Topography, length_unit};
use crate::error::{Result, SurfError};
use crate::grid::Grid;
use ndarray::Array2;
use std::fmt::Write as _;
use std::fs::File;
use std::io::{BufRead, BufReader, BufWriter, Write};
use std::path::Path;

fn lines(path: &Path) -> Result<impl Iterator<Item = Result<(usize, String)>> + '_> {
    let file = File::open(path).map_err(|e| SurfError::io(path, e))?;
    Ok(BufReader::new(file)
        .lines()
        .enumerate()
        .map(move |(i, l)| l.map(|l| (i + 1, l)).map_err(|e| SurfError::io(path, e))))
}

fn number(path: &Path, line: usize, token: &str) -> Result<f64> {
    let v: f64 = token
        .parse()
        .map_err(|_| SurfError::parse(path, Some(line), format!("cannot read '{token}' as a number")))?;
    if !v.is_finite() {
        return Err(SurfError::parse(
            path,
            Some(line),
            format!("non-finite value '{token}'"),
        ));
    }
    Ok(v)
}

/// Parses `key=value` pairs of our header comment.
fn header_value(line: &str, key: &str) -> Option<String> {
    line.split_whitespace()
        .find_map(|t| t.strip_prefix(key).and_then(|r| r.strip_prefix('=')))
        .map(str::to_string)
}

pub(super) fn read_matrix(path: &Path, options: &ReadOptions) -> Result<Topography> {
    let mut rows: Vec<f64> = Vec::new();
    let (mut nx, mut ny) = (0usize, 0usize);
    let mut opts = *options;
    // Gwyddion's text export says `# Width: 10.00 µm`, `# Height: ...`, `# Value units: m`.
    let mut z_unit = 1.0;
    for item in lines(path)? {
        let (no, line) = item?;
        let t = line.trim();
        if let Some(comment) = t.strip_prefix('#') {
            let quantity = |v: &str| -> Result<f64> {
                let (x, unit) = v.trim().split_once(' ').unwrap_or((v.trim(), "m"));
                let factor = length_unit(unit).ok_or_else(|| {
                    SurfError::parse(path, Some(no), format!("unknown length unit '{unit}'"))
                })?;
                Ok(number(path, no, x)? * factor)
            };
            let c = comment.trim();
            if let Some(v) = c.strip_prefix("Width:") {
                opts.length_x = Some(quantity(v)?);
            } else if let Some(v) = c.strip_prefix("Height:") {
                opts.length_y = Some(quantity(v)?);
            } else if let Some(v) = c.strip_prefix("Value units:") {
                z_unit = length_unit(v).ok_or_else(|| {
                    SurfError::parse(path, Some(no), format!("unknown height unit '{}'", v.trim()))
                })?;
            }
            if let Some(v) = header_value(comment, "length_x") {
                opts.length_x = Some(number(path, no, &v)? / options.unit);
            }
            if let Some(v) = header_value(comment, "length_y") {
                opts.length_y = Some(number(path, no, &v)? / options.unit);
            }
            if let Some(v) = header_value(comment, "periodic") {
                opts.periodic = v == "true";
            }
            continue;
        }
        if t.is_empty() {
            continue;
        }
        let before = rows.len();
        for token in t
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty())
        {
            // NaN marks an unmeasured point, as Gwyddion's export writes it.
            let nan = token.eq_ignore_ascii_case("nan");
            rows.push(if nan { f64::NAN } else { number(path, no, token)? });
        }
        let count = rows.len() - before;
        if ny == 0 {
            nx = count;
        } else if count != nx {
            return Err(SurfError::parse(
                path,
                Some(no),
                format!("ragged rows: {count} values where the first row has {nx}"),
            ));
        }
        ny += 1;
    }
    let scale = z_unit * options.unit;
    if (ny == 1 || nx == 1) && rows.len() >= 2 {
        // One row or one column: a line scan.
        return Ok(Topography::Profile(Profile {
            heights: rows.into_iter().map(|h| h * scale).collect(),
            length: opts.length_x.map(|l| l * options.unit),
            channel: 0,
        }));
    }
    if ny < 2 || nx < 2 {
        return Err(SurfError::parse(
            path,
            None,
            format!("need at least 2 heights, found {ny} rows of {nx}"),
        ));
    }
    let grid = opts.grid_for(path, ny, nx)?;
    let grid = Grid::new(nx, ny, grid.length_x * options.unit, grid.length_y * options.unit)?;
    let heights = Array2::from_shape_vec((ny, nx), rows).expect("counted") * scale;
    Ok(Topography::Surface(Measurement::new(
        heights,
        grid,
        opts.periodic,
    )?))
}

pub(super) fn write_matrix(surface: &Surface, path: &Path) -> Result<()> {
    let file = File::create(path).map_err(|e| SurfError::io(path, e))?;
    let mut w = BufWriter::with_capacity(1 << 20, file);
    let g = surface.grid;
    let mut buf = format!(
        "# roughcontact surface (heights in m, one row of x per line): nx={} ny={} length_x={:e} length_y={:e} periodic={}\n",
        g.nx, g.ny, g.length_x, g.length_y, surface.periodic
    );
    for row in surface.heights.rows() {
        for (i, h) in row.iter().enumerate() {
            if i > 0 {
                buf.push(' ');
            }
            write!(buf, "{h:e}").expect("write to string");
        }
        buf.push('\n');
        w.write_all(buf.as_bytes()).map_err(|e| SurfError::io(path, e))?;
        buf.clear();
    }
    w.flush().map_err(|e| SurfError::io(path, e))
}

pub(super) fn read_xyh(path: &Path, options: &ReadOptions) -> Result<Measurement> {
    let mut heights: Vec<f64> = Vec::new();
    let mut first_x: Vec<f64> = Vec::new();
    let mut row_y: Vec<f64> = Vec::new();
    let mut in_row = 0usize;
    let close_row = |in_row: &mut usize, no: usize, first_x: &Vec<f64>, rows: usize| -> Result<()> {
        if *in_row > 0 && rows > 1 && *in_row != first_x.len() {
            return Err(SurfError::parse(
                path,
                Some(no),
                format!(
                    "ragged rows: row {rows} has {} points where the first has {}",
                    *in_row,
                    first_x.len()
                ),
            ));
        }
        *in_row = 0;
        Ok(())
    };
    let mut last = 0;
    for item in lines(path)? {
        let (no, line) = item?;
        last = no;
        let t = line.trim();
        if t.starts_with('#') {
            continue;
        }
        if t.is_empty() {
            close_row(&mut in_row, no, &first_x, row_y.len())?;
            continue;
        }
        let vals = t
            .split(|c: char| c.is_whitespace() || c == ',')
            .filter(|s| !s.is_empty())
            .map(|tok| number(path, no, tok))
            .collect::<Result<Vec<f64>>>()?;
        let [x, y, h] = vals[..] else {
            return Err(SurfError::parse(
                path,
                Some(no),
                format!("expected 'x y h', found {} values", vals.len()),
            ));
        };
        if in_row == 0 {
            row_y.push(y);
        } else if y != row_y[row_y.len() - 1] {
            return Err(SurfError::parse(
                path,
                Some(no),
                format!("y = {y} changes within a row (rows must be separated by a blank line)"),
            ));
        }
        if row_y.len() == 1 {
            first_x.push(x);
        } else if in_row >= first_x.len() || x != first_x[in_row] {
            return Err(SurfError::parse(
                path,
                Some(no),
                format!("x = {x} does not match the first row's x values"),
            ));
        }
        in_row += 1;
        heights.push(h);
    }
    close_row(&mut in_row, last + 1, &first_x, row_y.len())?;
    let (nx, ny) = (first_x.len(), row_y.len());
    if nx < 2 || ny < 2 {
        return Err(SurfError::parse(
            path,
            None,
            format!("need at least 2 x 2 points, found {ny} rows of {nx}"),
        ));
    }
    // The coordinates must be a uniform grid (to 1e-6 of a spacing, what decimal files keep):
    // an average spacing would silently move every point.
    for (axis, c) in [("x", &first_x), ("y", &row_y)] {
        let step = (c[c.len() - 1] - c[0]) / (c.len() - 1) as f64;
        if let Some(k) = (1..c.len()).find(|&k| ((c[k] - c[k - 1]) - step).abs() > 1e-6 * step.abs()) {
            return Err(SurfError::parse(
                path,
                None,
                format!(
                    "the {axis} spacing is not uniform: {axis} = {} to {} differs from the mean spacing {step:e}",
                    c[k - 1],
                    c[k]
                ),
            ));
        }
    }
    // A periodic grid of n points spans n spacings.
    let lx = (first_x[nx - 1] - first_x[0]) / (nx - 1) as f64 * nx as f64;
    let ly = (row_y[ny - 1] - row_y[0]) / (ny - 1) as f64 * ny as f64;
    let grid = Grid::new(nx, ny, lx.abs() * options.unit, ly.abs() * options.unit)
        .map_err(|e| SurfError::parse(path, None, format!("coordinates do not span a grid: {e}")))?;
    let heights = Array2::from_shape_vec((ny, nx), heights).expect("counted") * options.unit;
    Measurement::new(heights, grid, options.periodic)
}

pub(super) fn write_xyh(surface: &Surface, path: &Path) -> Result<()> {
    let file = File::create(path).map_err(|e| SurfError::io(path, e))?;
    let mut w = BufWriter::with_capacity(1 << 20, file);
    let (dx, dy) = (surface.grid.dx(), surface.grid.dy());
    let mut buf = String::new();
    for (j, row) in surface.heights.rows().into_iter().enumerate() {
        if j > 0 {
            buf.push('\n');
        }
        let y = j as f64 * dy;
        for (i, h) in row.iter().enumerate() {
            writeln!(buf, "{:e} {y:e} {h:e}", i as f64 * dx).expect("write to string");
        }
        w.write_all(buf.as_bytes()).map_err(|e| SurfError::io(path, e))?;
        buf.clear();
    }
    w.flush().map_err(|e| SurfError::io(path, e))
}
