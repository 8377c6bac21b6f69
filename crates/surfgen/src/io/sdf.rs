//! ISO 25178-71 Surface Data File (`.sdf`): a magic line `aISO-1.0` (text data) or `bISO-1.0`
//! (binary data), a header of `Key = value` lines ended by a line `*`, then `NumPoints` heights
//! a profile along x for `NumProfiles` profiles (y), as text separated by white space or as
//! little-endian binary of `DataType` (5: i16, 6: i32, 7: f64), then optionally `*` and a
//! trailer. Heights are the stored numbers times `Zscale` [m]; `Xscale` and `Yscale` are the
//! spacings [m], so the box is `NumPoints * Xscale` by `NumProfiles * Yscale`.

use super::{Measurement, Number, ReadOptions, Surface};
use crate::error::{Result, SurfError};
use crate::grid::Grid;
use ndarray::Array2;
use std::path::Path;

/// Reads a text (`a`) or binary (`b`) SDF file.
pub(super) fn read(path: &Path, options: &ReadOptions) -> Result<Measurement> {
    let bytes = std::fs::read(path).map_err(|e| SurfError::io(path, e))?;
    let bad = |line: Option<usize>, m: String| SurfError::parse(path, line, m);
    let binary = match bytes.get(..8) {
        Some(b"aISO-1.0") => false,
        Some(b"bISO-1.0") => true,
        _ => {
            return Err(bad(
                Some(1),
                "not an ISO 25178-71 SDF file: the first line is not aISO-1.0 or bISO-1.0".into(),
            ));
        }
    };
    // The header: lines up to the one that is `*`.
    let mut at = 0;
    let mut header = Vec::new();
    let mut ended = false;
    for (i, line) in bytes.split(|&b| b == b'\n').enumerate() {
        at += line.len() + 1;
        let line =
            std::str::from_utf8(line).map_err(|_| bad(Some(i + 1), "the header is not text".into()))?;
        let line = line.trim();
        if i == 0 {
            continue;
        }
        if line == "*" {
            ended = true;
            break;
        }
        if line.is_empty() {
            continue;
        }
        let Some((k, v)) = line.split_once('=') else {
            return Err(bad(
                Some(i + 1),
                format!("expected 'Key = value', found '{line}'"),
            ));
        };
        header.push((i + 1, k.trim().to_string(), v.trim().to_string()));
    }
    if !ended {
        return Err(bad(None, "the header is not ended by a line '*'".into()));
    }
    let get = |key: &str| header.iter().find(|(_, k, _)| k == key);
    let number = |key: &str| -> Result<f64> {
        let (line, _, v) = get(key).ok_or_else(|| bad(None, format!("the header lacks {key}")))?;
        v.parse::<f64>()
            .ok()
            .filter(|x| x.is_finite())
            .ok_or_else(|| bad(Some(*line), format!("cannot read {key} '{v}'")))
    };
    let count = |key: &str| -> Result<usize> {
        let x = number(key)?;
        if x >= 1.0 && x.fract() == 0.0 && x < 1e9 {
            Ok(x as usize)
        } else {
            Err(bad(
                get(key).map(|h| h.0),
                format!("{key} must be a positive whole number, got {x}"),
            ))
        }
    };
    let (nx, ny) = (count("NumPoints")?, count("NumProfiles")?);
    let (sx, sy, sz) = (
        super::header(path, "Xscale", number("Xscale")?, Number::Size)?,
        super::header(path, "Yscale", number("Yscale")?, Number::Size)?,
        super::header(path, "Zscale", number("Zscale")?, Number::Scale)?,
    );
    if get("Compression").is_some_and(|(_, _, v)| v != "0") {
        return Err(bad(
            None,
            "compressed SDF data is not supported (Compression must be 0)".into(),
        ));
    }
    let n = nx.checked_mul(ny).filter(|&n| n <= bytes.len()).ok_or_else(|| {
        bad(
            None,
            format!("{nx} x {ny} points cannot fit in a file of {} bytes", bytes.len()),
        )
    })?;
    let rest = &bytes[at.min(bytes.len())..];
    let values: Vec<f64> = if binary {
        let (size, kind) = match number("DataType")? as i64 {
            5 => (2, 5),
            6 => (4, 6),
            7 => (8, 7),
            t => {
                return Err(bad(
                    None,
                    format!("unknown binary DataType {t} (5: i16, 6: i32, 7: f64)"),
                ));
            }
        };
        if rest.len() < n * size {
            return Err(bad(
                None,
                format!(
                    "{nx} x {ny} points need {} data bytes, found {}",
                    n * size,
                    rest.len()
                ),
            ));
        }
        rest[..n * size]
            .chunks_exact(size)
            .map(|c| match kind {
                5 => i16::from_le_bytes([c[0], c[1]]) as f64,
                6 => i32::from_le_bytes([c[0], c[1], c[2], c[3]]) as f64,
                _ => f64::from_le_bytes(c.try_into().expect("8 bytes")),
            })
            .collect()
    } else {
        let text = std::str::from_utf8(rest).map_err(|_| bad(None, "the data are not text".into()))?;
        let data = text.split("\n*").next().unwrap_or("");
        let mut values = Vec::with_capacity(n);
        for word in data.split_whitespace() {
            if values.len() == n {
                return Err(bad(
                    None,
                    format!("more than the {nx} x {ny} points the header declares"),
                ));
            }
            values.push(
                word.parse::<f64>()
                    .map_err(|_| bad(None, format!("cannot read the height '{word}'")))?,
            );
        }
        if values.len() != n {
            return Err(bad(
                None,
                format!("{nx} x {ny} points declared, {} found", values.len()),
            ));
        }
        values
    };
    let unit = options.unit;
    let grid = Grid::new(nx, ny, nx as f64 * sx * unit, ny as f64 * sy * unit)
        .map_err(|e| bad(None, e.to_string()))?;
    let heights = Array2::from_shape_vec((ny, nx), values.into_iter().map(|v| v * sz * unit).collect())
        .expect("counted");
    Measurement::new(heights, grid, options.periodic)
}

/// Writes a text SDF file: heights in metres (`Zscale = 1`) with the digits that read back to
/// the same numbers.
pub(super) fn write(surface: &Surface, path: &Path) -> Result<()> {
    let g = surface.grid;
    let mut out = format!(
        "aISO-1.0\nManufacID = roughcontact\nCreateDate = 000000000000\nModDate = 000000000000\n\
         NumPoints = {}\nNumProfiles = {}\nXscale = {:e}\nYscale = {:e}\nZscale = 1.0E0\n\
         Zresolution = -1\nCompression = 0\nDataType = 7\nCheckType = 0\n*\n",
        g.nx,
        g.ny,
        g.dx(),
        g.dy()
    );
    for row in surface.heights.rows() {
        let line: Vec<String> = row.iter().map(|h| format!("{h:e}")).collect();
        out += &line.join(" ");
        out.push('\n');
    }
    out += "*\n";
    std::fs::write(path, out).map_err(|e| SurfError::io(path, e))
}
