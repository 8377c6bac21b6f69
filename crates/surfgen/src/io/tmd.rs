//! TrueMap / TrueSurf binary data (`.tmd`): the magic `Binary TrueMap Data File v2.0\r\n\0`, a
//! comment ended by `\r\n\0`, then little-endian `width` and `height` (u32: points along x and
//! y), the box's sides and offsets (f32, millimetres), and `width * height` f32 heights
//! [mm], x varying fastest.

use super::{Measurement, Number, ReadOptions, header};
use crate::error::{Result, SurfError};
use crate::grid::Grid;
use ndarray::Array2;
use std::path::Path;

const MAGIC: &[u8] = b"Binary TrueMap Data File v2.0\r\n\0";
const END: &[u8] = b"\r\n\0";

pub(super) fn read(path: &Path, options: &ReadOptions) -> Result<Measurement> {
    let bytes = std::fs::read(path).map_err(|e| SurfError::io(path, e))?;
    let bad = |m: String| SurfError::parse(path, None, m);
    let rest = bytes
        .strip_prefix(MAGIC)
        .ok_or_else(|| bad("not a TrueMap file (no 'Binary TrueMap Data File v2.0')".into()))?;
    let comment = rest
        .windows(END.len())
        .position(|w| w == END)
        .ok_or_else(|| bad("the comment is not ended".into()))?;
    let rest = &rest[comment + END.len()..];
    let field = |k: usize| -> Result<[u8; 4]> {
        rest.get(4 * k..4 * k + 4)
            .map(|b| b.try_into().expect("4 bytes"))
            .ok_or_else(|| bad("the header ends early".into()))
    };
    let (nx, ny) = (
        u32::from_le_bytes(field(0)?) as usize,
        u32::from_le_bytes(field(1)?) as usize,
    );
    let (lx, ly) = (
        header(
            path,
            "x length",
            f32::from_le_bytes(field(2)?) as f64,
            Number::Size,
        )?,
        header(
            path,
            "y length",
            f32::from_le_bytes(field(3)?) as f64,
            Number::Size,
        )?,
    );
    let data = &rest[24.min(rest.len())..];
    let n = nx
        .checked_mul(ny)
        .filter(|&n| n >= 1 && n <= data.len() / 4)
        .ok_or_else(|| {
            bad(format!(
                "{nx} x {ny} heights need {} bytes, the file holds {}",
                4 * nx as u128 * ny as u128,
                data.len()
            ))
        })?;
    if data.len() != 4 * n {
        return Err(bad(format!(
            "{nx} x {ny} heights need {} bytes, found {}",
            4 * n,
            data.len()
        )));
    }
    let mm = 1e-3 * options.unit;
    let heights: Vec<f64> = data
        .chunks_exact(4)
        .map(|c| f32::from_le_bytes(c.try_into().expect("4 bytes")) as f64 * mm)
        .collect();
    let grid = Grid::new(nx, ny, lx * mm, ly * mm).map_err(|e| bad(e.to_string()))?;
    Measurement::new(
        Array2::from_shape_vec((ny, nx), heights).expect("counted"),
        grid,
        options.periodic,
    )
}
