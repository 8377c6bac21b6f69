//! Digital Surf / MountainsMap (`.sur`): a 512-byte little-endian header at fixed offsets
//! (signature `DIGITAL SURF`, the object type, bits a point, the smallest and largest stored
//! values, points along x and y, the spacings and the height step as f32 in the units their
//! names give, the sizes of a comment and a private zone, the height offset), then the points
//! as i16 or i32, x varying fastest, after the comment and private zones. A height is
//! `raw * dz + z offset`; points below the smallest value are unmeasured where the file says it
//! marks them.

use super::{Measurement, Number, ReadOptions, header, length_unit};
use crate::error::{Result, SurfError};
use crate::grid::Grid;
use ndarray::Array2;
use std::path::Path;

const HEADER: usize = 512;

pub(super) fn read(path: &Path, options: &ReadOptions) -> Result<Measurement> {
    let bytes = std::fs::read(path).map_err(|e| SurfError::io(path, e))?;
    let bad = |m: String| SurfError::parse(path, None, m);
    if bytes.len() < HEADER || !bytes.starts_with(b"DIGITAL SURF") {
        return Err(bad(
            "not a Digital Surf file (no 512-byte header starting DIGITAL SURF)".into(),
        ));
    }
    let i16_at = |o: usize| i16::from_le_bytes([bytes[o], bytes[o + 1]]);
    let i32_at = |o: usize| i32::from_le_bytes(bytes[o..o + 4].try_into().expect("4 bytes"));
    let f32_at = |o: usize| f32::from_le_bytes(bytes[o..o + 4].try_into().expect("4 bytes")) as f64;
    let text_at = |o: usize| {
        String::from_utf8_lossy(&bytes[o..o + 16])
            .trim_matches(|c: char| c == '\0' || c == ' ')
            .to_string()
    };
    if i16_at(12) != 0 {
        return Err(bad(
            "a Macintosh-ordered (big-endian) file: only PC files are read".into(),
        ));
    }
    if i16_at(18) != 2 {
        return Err(bad(format!(
            "object type {}: only surfaces (type 2) are read",
            i16_at(18)
        )));
    }
    let bits = i16_at(98);
    let size = match bits {
        16 => 2,
        32 => 4,
        b => return Err(bad(format!("{b} bits a point (16 or 32 are read)"))),
    };
    let (zmin, nx, ny) = (i32_at(100), i32_at(108), i32_at(112));
    let (dx, dy, dz) = (
        header(path, "x spacing", f32_at(120).abs(), Number::Size)?,
        header(path, "y spacing", f32_at(124).abs(), Number::Size)?,
        header(path, "height step dz", f32_at(128), Number::Scale)?,
    );
    let unit = |o: usize| -> Result<f64> {
        let name = text_at(o);
        length_unit(&name).ok_or_else(|| bad(format!("unknown length unit '{name}'")))
    };
    let (ux, uy, uz) = (unit(180)?, unit(196)?, unit(212)?);
    let skip = i16_at(334).max(0) as usize + i16_at(336).max(0) as usize;
    let z_offset = super::offset(path, "height offset", f32_at(474), "height step dz", dz)?;
    let (nx, ny) = (usize::try_from(nx).unwrap_or(0), usize::try_from(ny).unwrap_or(0));
    let start = HEADER + skip;
    let n = nx
        .checked_mul(ny)
        .filter(|&n| n >= 1 && start + n * size <= bytes.len())
        .ok_or_else(|| {
            bad(format!(
                "{nx} x {ny} points of {bits} bits do not fit in a file of {} bytes",
                bytes.len()
            ))
        })?;
    let raw: Vec<i32> = bytes[start..start + n * size]
        .chunks_exact(size)
        .map(|c| {
            if size == 2 {
                i16::from_le_bytes([c[0], c[1]]) as i32
            } else {
                i32::from_le_bytes(c.try_into().expect("4 bytes"))
            }
        })
        .collect();
    // With a non-zero flag at byte 86, values below the smallest stored one are unmeasured.
    let marks = i16_at(86) != 0;
    let scale = uz * options.unit;
    let heights: Vec<f64> = raw
        .into_iter()
        .map(|v| {
            if marks && v < zmin {
                f64::NAN
            } else {
                (v as f64 * dz + z_offset) * scale
            }
        })
        .collect();
    let grid = Grid::new(
        nx,
        ny,
        nx as f64 * dx * ux * options.unit,
        ny as f64 * dy * uy * options.unit,
    )
    .map_err(|e| bad(e.to_string()))?;
    Measurement::new(
        Array2::from_shape_vec((ny, nx), heights).expect("counted"),
        grid,
        options.periodic,
    )
}
