//! Wyko / Veeco Vision (`.opd`): after a 2-byte version, a directory of 24-byte entries (a
//! name of 16 bytes, a type i16, a length i32, an attribute u16), the first of which is the
//! directory itself; the blocks follow in the entries' order. `Raw` (a 2-D array: columns,
//! rows and the bytes a value as i16, then the values column by column, each column from the
//! image's top) holds the heights in waves: a height is `raw * Wavelength [nm] / Mult`;
//! `Pixel_size` [mm] and `Aspect` give the spacings. NaN and values of 1e10 and above mark
//! unmeasured points.

use super::{Measurement, Number, ReadOptions};
use crate::error::{Result, SurfError};
use crate::grid::Grid;
use ndarray::Array2;
use std::path::Path;

const ENTRY: usize = 24;

pub(super) fn read(path: &Path, options: &ReadOptions) -> Result<Measurement> {
    let bytes = std::fs::read(path).map_err(|e| SurfError::io(path, e))?;
    let bad = |m: String| SurfError::parse(path, None, m);
    let entry = |k: usize| -> Option<(String, i16, usize)> {
        let e = bytes.get(2 + k * ENTRY..2 + (k + 1) * ENTRY)?;
        let name = String::from_utf8_lossy(&e[..16])
            .trim_end_matches(['\0', ' '])
            .to_string();
        let kind = i16::from_le_bytes([e[16], e[17]]);
        let length = i32::from_le_bytes([e[18], e[19], e[20], e[21]]);
        Some((name, kind, usize::try_from(length).ok()?))
    };
    let directory = match entry(0) {
        Some((name, _, length)) if name == "Directory" && length <= bytes.len() => length,
        _ => return Err(bad("not a Wyko OPD file (no directory)".into())),
    };
    // Each block's (type, start, length), in the directory's order.
    let mut blocks = Vec::new();
    let mut at = 2usize;
    for k in 0..directory / ENTRY {
        let Some((name, kind, length)) = entry(k) else {
            break;
        };
        if length > 0 {
            blocks.push((name, kind, at, length));
            at = at.saturating_add(length);
        }
    }
    let block = |names: &[&str]| blocks.iter().find(|b| names.contains(&b.0.as_str()));
    let body = |b: &(String, i16, usize, usize)| -> Result<&[u8]> {
        bytes
            .get(b.2..b.2.saturating_add(b.3))
            .ok_or_else(|| bad(format!("block {} ends beyond the file", b.0)))
    };
    let float = |name: &str| -> Result<Option<f64>> {
        match block(&[name]) {
            Some(b) => {
                let v = body(b)?;
                let v: [u8; 4] = v
                    .get(..4)
                    .and_then(|v| v.try_into().ok())
                    .ok_or_else(|| bad(format!("block {name} is short")))?;
                Ok(Some(f32::from_le_bytes(v) as f64).filter(|x| x.is_finite()))
            }
            None => Ok(None),
        }
    };
    let raw = block(&["Raw", "RAW_DATA", "RAW DATA"]).ok_or_else(|| bad("no Raw block of heights".into()))?;
    let data = body(raw)?;
    if raw.1 != 3 || data.len() < 6 {
        return Err(bad("the Raw block is not a 2-D array".into()));
    }
    let header = |k: usize| i16::from_le_bytes([data[2 * k], data[2 * k + 1]]);
    let (nx, ny, size) = (header(0).max(0) as usize, header(1).max(0) as usize, header(2));
    let n = nx
        .checked_mul(ny)
        .filter(|&n| n >= 1)
        .ok_or_else(|| bad(format!("{nx} x {ny} points")))?;
    let values: Vec<f64> = match size {
        4 if data.len() >= 6 + 4 * n => data[6..6 + 4 * n]
            .chunks_exact(4)
            .map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64)
            .collect(),
        2 if data.len() >= 6 + 2 * n => data[6..6 + 2 * n]
            .chunks_exact(2)
            .map(|c| i16::from_le_bytes([c[0], c[1]]) as f64)
            .collect(),
        4 | 2 => return Err(bad(format!("{nx} x {ny} values do not fit in the Raw block"))),
        s => {
            return Err(bad(format!(
                "{s} bytes a value in the Raw block (2 or 4 are read)"
            )));
        }
    };
    let wavelength = float("Wavelength")?.ok_or_else(|| bad("no Wavelength block".into()))?;
    let mult = match block(&["Mult"]) {
        Some(b) => body(b)?
            .get(..2)
            .map_or(1.0, |m| i16::from_le_bytes([m[0], m[1]]).max(1) as f64),
        None => 1.0,
    };
    let pixel = float("Pixel_size")?.ok_or_else(|| bad("no Pixel_size block".into()))?;
    let aspect = float("Aspect")?.unwrap_or(1.0);
    super::header(path, "Wavelength", wavelength, Number::Size)?;
    super::header(path, "Pixel_size", pixel, Number::Size)?;
    super::header(path, "Aspect", aspect, Number::Size)?;
    let scale = wavelength * 1e-9 / mult * options.unit;
    // Stored column by column (x slowest), each from the top: ours is (y, x) from y = 0.
    // Unmeasured points hold NaN or a huge value.
    let heights = Array2::from_shape_fn((ny, nx), |(j, i)| match values[i * ny + (ny - 1 - j)] {
        v if v.abs() < 1e10 => v * scale,
        _ => f64::NAN,
    });
    let mm = 1e-3 * options.unit;
    let grid = Grid::new(nx, ny, nx as f64 * pixel * mm, ny as f64 * pixel * aspect * mm)
        .map_err(|e| bad(e.to_string()))?;
    Measurement::new(heights, grid, options.periodic)
}
