//! Gwyddion Simple Field (`.gsf`): a text header of `Key = value` lines after the magic line
//! `Gwyddion Simple Field 1.0`, NUL-padded to a multiple of 4 bytes (1 to 4 NULs), then
//! `XRes * YRes` little-endian f32 heights, row by row.

use super::{Measurement, Number, ReadOptions, Surface, length_unit};
use crate::error::{Result, SurfError};
use crate::grid::Grid;
use ndarray::Array2;
use std::path::Path;

const MAGIC: &str = "Gwyddion Simple Field 1.0\n";

pub(super) fn read(path: &Path, options: &ReadOptions) -> Result<Measurement> {
    let bytes = std::fs::read(path).map_err(|e| SurfError::io(path, e))?;
    if !bytes.starts_with(MAGIC.as_bytes()) {
        return Err(SurfError::parse(
            path,
            Some(1),
            "missing the line 'Gwyddion Simple Field 1.0'",
        ));
    }
    let end = bytes
        .iter()
        .position(|&b| b == 0)
        .ok_or_else(|| SurfError::parse(path, None, "header is not terminated by NUL padding"))?;
    let header = std::str::from_utf8(&bytes[..end])
        .map_err(|_| SurfError::parse(path, None, "header is not UTF-8"))?;
    let (mut xres, mut yres, mut xreal, mut yreal) = (None, None, None, None);
    let (mut xy_unit, mut z_unit) = (1.0, 1.0);
    for (i, line) in header.lines().enumerate().skip(1) {
        let Some((key, value)) = line.split_once('=') else {
            if line.trim().is_empty() {
                continue;
            }
            return Err(SurfError::parse(
                path,
                Some(i + 1),
                format!("expected 'Key = value', found '{line}'"),
            ));
        };
        let value = value.trim();
        let bad = |what: &str| SurfError::parse(path, Some(i + 1), format!("cannot read {what} '{value}'"));
        match key.trim() {
            "XRes" => xres = Some(value.parse::<usize>().map_err(|_| bad("XRes"))?),
            "YRes" => yres = Some(value.parse::<usize>().map_err(|_| bad("YRes"))?),
            "XReal" => xreal = Some(value.parse::<f64>().map_err(|_| bad("XReal"))?),
            "YReal" => yreal = Some(value.parse::<f64>().map_err(|_| bad("YReal"))?),
            "XYUnits" => xy_unit = length_unit(value).ok_or_else(|| bad("XYUnits"))?,
            "ZUnits" => z_unit = length_unit(value).ok_or_else(|| bad("ZUnits"))?,
            _ => {}
        }
    }
    let (Some(nx), Some(ny)) = (xres, yres) else {
        return Err(SurfError::parse(path, None, "header lacks XRes or YRes"));
    };
    let data_start = (end / 4 + 1) * 4;
    let expected = nx * ny * 4;
    let got = bytes.len().saturating_sub(data_start);
    if got != expected {
        return Err(SurfError::parse(
            path,
            None,
            format!("{nx} x {ny} heights need {expected} data bytes, found {got}"),
        ));
    }
    if bytes[end..data_start].iter().any(|&b| b != 0) {
        return Err(SurfError::parse(path, None, "header padding is not all NUL"));
    }
    let heights: Vec<f64> = bytes[data_start..]
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64 * z_unit * options.unit)
        .collect();
    let lx = super::header(path, "XReal", xreal.unwrap_or(nx as f64), Number::Size)? * xy_unit * options.unit;
    let ly = super::header(path, "YReal", yreal.unwrap_or(ny as f64), Number::Size)? * xy_unit * options.unit;
    let grid = Grid::new(nx, ny, lx, ly).map_err(|e| SurfError::parse(path, None, e.to_string()))?;
    Measurement::new(
        Array2::from_shape_vec((ny, nx), heights).expect("counted"),
        grid,
        options.periodic,
    )
}

pub(super) fn write(surface: &Surface, path: &Path) -> Result<()> {
    let g = surface.grid;
    let mut out = format!(
        "{MAGIC}XRes = {}\nYRes = {}\nXReal = {:e}\nYReal = {:e}\nXYUnits = m\nZUnits = m\nTitle = roughcontact surface\n",
        g.nx, g.ny, g.length_x, g.length_y
    )
    .into_bytes();
    let pad = 4 - out.len() % 4;
    out.extend(std::iter::repeat_n(0u8, pad));
    out.reserve(g.len() * 4);
    for &h in surface.heights.iter() {
        out.extend_from_slice(&(h as f32).to_le_bytes());
    }
    std::fs::write(path, out).map_err(|e| SurfError::io(path, e))
}
